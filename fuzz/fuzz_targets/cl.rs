//! The CL reader and postprocessor on arbitrary bytes: they may refuse them, never panic.
#![no_main]

use biscara::post::{PostOptions, post};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = post(data, &mut std::io::sink(), PostOptions { line_numbers: data.len() % 2 == 0 });
});
