//! The G-code interpreter on arbitrary bytes: it may refuse them, never panic or hang (a loop
//! without motion stops at its bound; one that moves is read for 100 000 motions).
#![no_main]

use biscara::gcode::{Config, interpret};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let config =
        Config { home: [0.0, 460.0, 100.0, 0.0], max_idle_jumps: 1000, ..Config::default() };
    for motion in interpret(data, &config).take(100_000) {
        if motion.is_err() {
            break;
        }
    }
});
