//! Hermetic conformance with LinuxCNC: every program of `tests/conformance/` against the result
//! LinuxCNC's `rs274` gave for it, recorded beside it (`NAME.rs274`), on every `cargo test` —
//! rs274 need not be installed. The `biscara` package's conformance test runs rs274 itself and
//! re-records (a stale record fails it under CI=true).

use std::path::Path;

use crate::rs274_record::{cases, config, judge_case, read_record, record_path};

/// Whether `case` needs LinuxCNC's Python plug-ins: its INI file has a `[PYTHON]` section.
fn needs_python(case: &Path) -> bool {
    config(case).ini.is_some_and(|ini| ini.has_section("PYTHON"))
}

/// In a build without the Python plug-ins (the cargo feature `python` off), what a program that
/// needs them gives: an error, the refusal of its Python line, or, for a call of a Python
/// subroutine, no subroutine of that name (as LinuxCNC without the plug-ins); `None` when so.
#[cfg(not(feature = "python"))]
fn without_python(case: &Path) -> Option<String> {
    match crate::rs274_record::ours(case) {
        Err(err) => {
            let message = err.to_string();
            let refused = message.contains("leaves out (the cargo feature `python`");
            (!refused && !message.contains("seeking o-word"))
                .then(|| format!("not refused as Python: {message}"))
        }
        Ok(_) => Some("runs without the Python plug-ins".to_owned()),
    }
}

#[test]
fn every_conformance_program_matches_its_recorded_rs274_result() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/conformance");
    let cases = cases(&dir);
    let (mut failures, mut missing) = (Vec::new(), Vec::new());
    let mut python = 0;
    for case in &cases {
        let name = case.file_name().and_then(|n| n.to_str()).unwrap_or_default();
        if needs_python(case) {
            python += 1;
            // Built without the plug-ins, a Python program is refused instead of compared.
            #[cfg(not(feature = "python"))]
            {
                if let Some(problem) = without_python(case) {
                    failures.push(format!("{name}: {problem}"));
                }
                continue;
            }
        }
        let Ok(text) = std::fs::read_to_string(record_path(case)) else {
            missing.push(name.to_owned());
            continue;
        };
        let theirs = read_record(&text, &dir).unwrap_or_else(|err| panic!("{name}: {err}"));
        if let Some(problem) = judge_case(case, &theirs) {
            failures.push(format!("{name}: {problem}"));
        }
    }
    assert!(missing.is_empty(), "{} programs have no recorded result: {missing:?}", missing.len());
    assert!(cases.len() >= 500, "only {} recorded programs", cases.len());
    assert!(python > 0, "no program needs the Python plug-ins");
    assert!(
        failures.is_empty(),
        "{} of {} programs differ from rs274's recorded result:\n{}",
        failures.len(),
        cases.len(),
        failures.join("\n")
    );
}

/// The records read back as they were written, and a record that is not one is an error.
#[test]
fn records_round_trip() {
    use crate::rs274_record::{Outcome, record_text};
    use biscara_motion::{Motion, MotionKind};
    let dir = Path::new("/some/where/tests/conformance");
    let motion = |end: [f64; 4]| Motion {
        line: 0,
        kind: MotionKind::Rapid { end },
        extrude: None,
        blend: None,
        naive_cam: None,
    };
    for outcome in [
        Outcome::Motions(vec![motion([1.0, 2.5, -3.0, 0.1]), motion([0.0; 4])]),
        Outcome::Error { message: "Bad number format".to_owned(), before: vec![motion([1.0; 4])] },
        Outcome::Motions(Vec::new()),
    ] {
        assert_eq!(read_record(&record_text(&outcome, dir), dir), Ok(outcome));
    }
    assert!(read_record("G0 X1\n", dir).is_err());
    // A message naming the program's folder is recorded without it, and read back with it.
    let message = format!("EOF in file:{}/a.ngc seeking o-word", dir.display());
    let outcome = Outcome::Error { message, before: Vec::new() };
    let text = record_text(&outcome, dir);
    assert!(text.starts_with("# rs274 error: EOF in file:$CONFORMANCE/a.ngc"), "{text}");
    assert_eq!(read_record(&text, dir), Ok(outcome));
}
