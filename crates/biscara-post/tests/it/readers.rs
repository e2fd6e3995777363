//! Property tests: no input makes the CL reader or the postprocessor panic, every error names a
//! line of the input, and every program written is complete with blocks LinuxCNC can read.

use biscara_post::{PostOptions, post};
use proptest::prelude::*;

use crate::strategies::{cl_like, valid_program};

fn lines_in(bytes: &[u8]) -> usize {
    bytes.iter().filter(|&&byte| byte == b'\n').count() + 1
}

fn check_no_panic(bytes: &[u8]) -> Result<(), TestCaseError> {
    let mut out = Vec::new();
    for line_numbers in [false, true] {
        match post(bytes, &mut out, PostOptions { line_numbers }) {
            Ok(_) => {
                let gcode = String::from_utf8(out.clone()).expect("G-code is text");
                // LinuxCNC refuses blocks longer than 255 characters.
                let longest = gcode.lines().map(str::len).max().unwrap_or(0);
                prop_assert!(longest <= 255, "{gcode}");
                prop_assert!(gcode.starts_with('%') && gcode.ends_with("M2\n%\n"), "{gcode}");
            }
            Err(err) => {
                let line = err.line().expect("reading a slice cannot fail to write");
                prop_assert!((1..=lines_in(bytes)).contains(&line), "{err} for {bytes:?}");
                let prefix = format!("{line}: ");
                prop_assert!(err.to_string().starts_with(&prefix), "{err}");
            }
        }
        out.clear();
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn arbitrary_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..400)) {
        check_no_panic(&bytes)?;
    }

    #[test]
    fn arbitrary_text_never_panics(text in "\\PC{0,200}") {
        check_no_panic(text.as_bytes())?;
    }

    #[test]
    fn valid_programs_always_post(text in valid_program()) {
        let mut out = Vec::new();
        let result = post(text.as_bytes(), &mut out, PostOptions::default());
        prop_assert!(result.is_ok(), "{result:?} for\n{text}");
        check_no_panic(text.as_bytes())?;
    }

    #[test]
    fn cl_like_text_never_panics(text in cl_like()) {
        check_no_panic(text.as_bytes())?;
    }
}
