//! Property tests: no input makes the CL reader or the postprocessor panic, and every error
//! names a line of the input.

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

fn lines_in(bytes: &[u8]) -> usize {
    bytes.iter().filter(|&&byte| byte == b'\n').count() + 1
}

fn check_no_panic(bytes: &[u8]) -> Result<(), TestCaseError> {
    let mut out = Vec::new();
    for line_numbers in [false, true] {
        match post(bytes, &mut out, PostOptions { line_numbers }) {
            Ok(_) => {}
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
    fn cl_like_text_never_panics(text in cl_like()) {
        check_no_panic(text.as_bytes())?;
    }
}
