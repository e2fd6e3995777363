//! The G-code interpreter on arbitrary bytes: it may refuse them, never panic or hang.
#![no_main]

use biscara::gcode::{Config, interpret};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let config = Config { home: [0.0, 460.0, 100.0, 0.0], ..Config::default() };
    for motion in interpret(data, &config) {
        if motion.is_err() {
            break;
        }
    }
});
