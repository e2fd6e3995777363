//! Property tests: no input makes the CL reader or the postprocessor panic, every error names a
//! line of the input, and every program written is complete with blocks LinuxCNC can read.

use biscara_post::{PostOptions, post};
use proptest::prelude::*;

/// Text that looks like CL data: known and unknown words, numbers of every kind, separators,
/// continuations and comments, in random order.
fn cl_like() -> impl Strategy<Value = String> {
    let word = prop::sample::select(vec![
        "GOTO", "goto", "RAPID", "FEDRAT", "CIRCLE", "DELAY", "PICK", "PLACE", "PPRINT", "PARTNO",
        "UNITS", "END", "FINI", "SPINDL", "COOLNT", "TLAXIS", "CYCLE", "MMPM", "IPM", "INCHES",
        "MM", "/", ",", " , ", "$", "$$", "\n", "\n", "\n", "(", ")", "NaN", "inf", "-inf",
        "1e999", "1e300", "-0", "0", "1", "-1", "25.4", ".5", "1.", "0,0,1", "0,0,-1",
    ]);
    let number = any::<f64>().prop_map(|value| value.to_string());
    prop::collection::vec(prop_oneof![3 => word.prop_map(str::to_owned), 1 => number], 0..80)
        .prop_map(|parts| parts.concat())
}

/// A valid CL program: statements in any order after a FEDRAT, ending with END and FINI.
fn valid_program() -> impl Strategy<Value = String> {
    let coordinate = || -1000.0..1000.0f64;
    let statement = prop_oneof![
        Just("RAPID".to_owned()),
        (coordinate(), coordinate(), coordinate())
            .prop_map(|(x, y, z)| format!("GOTO/{x},{y},{z}")),
        (coordinate(), coordinate(), coordinate(), -720.0..720.0f64)
            .prop_map(|(x, y, z, c)| format!("goto / {x} , {y} , {z} , {c}")),
        (coordinate(), coordinate(), coordinate())
            .prop_map(|(x, y, z)| format!("GOTO/{x},{y},$\n {z},0,0,1")),
        (0.1..1e4f64).prop_map(|f| format!("FEDRAT / {f}, MMPM")),
        (0.1..100.0f64).prop_map(|f| format!("FEDRAT/IPM,{f}")),
        (0.0..10.0f64).prop_map(|s| format!("DELAY/{s}")),
        Just("PICK".to_owned()),
        Just("PLACE".to_owned()),
        "[a-zA-Z0-9 ,.()/]{0,30}".prop_map(|text| format!("PPRINT/{text}")),
        Just("SPINDL/ON".to_owned()),
        Just("UNITS/INCHES".to_owned()),
        Just("UNITS/MM".to_owned()),
        Just("$$ a comment".to_owned()),
    ];
    prop::collection::vec(statement, 0..40)
        .prop_map(|statements| format!("FEDRAT/100\n{}\nEND\nFINI\n", statements.join("\n")))
}

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
