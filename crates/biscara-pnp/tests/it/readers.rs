//! Property tests: no input makes the points reader or the CL generator panic, every error names
//! a line of the input, and a program is written only for a valid job.

use biscara_kinematics::Kinematics;
use biscara_pnp::{PointsReader, write_cl};
use proptest::prelude::*;

use crate::strategies::points_like;

fn check_no_panic(model: &Kinematics, bytes: &[u8]) -> Result<(), TestCaseError> {
    let lines = bytes.iter().filter(|&&byte| byte == b'\n').count() + 1;
    for record in PointsReader::new(bytes) {
        if let Err(err) = record {
            prop_assert!((1..=lines).contains(&err.line), "{err}");
        }
    }
    let mut out = Vec::new();
    match write_cl(bytes, model, &mut out) {
        Ok(()) => {
            let text = String::from_utf8(out).expect("CL is text");
            prop_assert!(
                text.starts_with("PARTNO/PICK AND PLACE\n") && text.ends_with("END\nFINI\n")
            );
        }
        Err(err) => {
            let line = err.line().expect("writing to a Vec cannot fail");
            prop_assert!((1..=lines).contains(&line), "{err}");
            let prefix = format!("{line}: ");
            prop_assert!(err.to_string().starts_with(&prefix), "{err}");
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1000))]

    #[test]
    fn arbitrary_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..400)) {
        check_no_panic(&Kinematics::default(), &bytes)?;
    }

    #[test]
    fn arbitrary_text_never_panics(text in "\\PC{0,200}") {
        check_no_panic(&Kinematics::default(), text.as_bytes())?;
    }

    #[test]
    fn points_like_text_never_panics(text in points_like()) {
        check_no_panic(&Kinematics::default(), text.as_bytes())?;
    }

    /// Any pick/place pair in a reachable box gives a program with one PICK and one PLACE.
    #[test]
    fn reachable_pairs_always_give_a_program(
        pick in (-150.0..150.0f64, 280.0..380.0f64, 0.0..40.0f64, -90.0..90.0f64),
        place in (-150.0..150.0f64, 280.0..380.0f64, 0.0..40.0f64, -90.0..90.0f64),
    ) {
        let text = format!(
            "pick {} {} {} {}\nplace {} {} {} {}\n",
            pick.0, pick.1, pick.2, pick.3, place.0, place.1, place.2, place.3
        );
        let mut out = Vec::new();
        write_cl(text.as_bytes(), &Kinematics::default(), &mut out).map_err(|err| {
            TestCaseError::fail(format!("{err} for {text}"))
        })?;
        let cl = String::from_utf8(out).expect("text");
        prop_assert_eq!(cl.matches("\nPICK\n").count(), 1);
        prop_assert_eq!(cl.matches("\nPLACE\n").count(), 1);
    }
}
