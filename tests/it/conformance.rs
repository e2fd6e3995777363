//! Conformance with LinuxCNC: `interpret` and LinuxCNC's `rs274` run on the same programs and
//! compared motion by motion — kind, end point, feed, arc centre, plane, direction and turns,
//! dwell — to rs274's printed precision (4 decimals of the program's unit).
//!
//! (a) `tests/conformance/*.ngc`: a small program per feature. `error_*` programs must be
//!     refused by both, with LinuxCNC's message contained in ours unless the program's first
//!     line reads `; message differs: WHY`; `unsupported_*` must be refused by us as "not
//!     supported yet"; `axis_*` (A B U V W words) must be refused by us.
//! (b) every `*.ngc` under `data/`.
//! (c) LinuxCNC's own example programs (from the linuxcnc packages): counted as matching,
//!     refused as not supported, refused by rs274 itself, or differing; none may differ.

use std::fs::File;
use std::io::BufReader;
use std::path::{Path, PathBuf};

use biscara::gcode::{Config, GcodeError, interpret};
use biscara::motion::{Motion, MotionKind};

use crate::rs274::{self, Outcome};
use crate::util::{repo_root, temp_dir};

/// Our motions for `path`, started like rs274: at 0,0,0,0 with G28/G30 at 0.
fn ours(path: &Path) -> Result<Vec<Motion>, GcodeError> {
    let file = File::open(path).unwrap_or_else(|err| panic!("{}: {err}", path.display()));
    interpret(BufReader::new(file), &Config::default()).collect()
}

/// The first difference between our motions and rs274's, if any.
fn compare(ours: &[Motion], theirs: &[Motion], inches: bool) -> Result<(), String> {
    let unit = if inches { 25.4 } else { 1.0 };
    // Each printed number is rounded to 1e-4 of the unit; an absolute position sums up to three.
    let length_tolerance = 1.5e-4 * unit + 1e-9;
    let close = |a: f64, b: f64, tolerance: f64| (a - b).abs() <= tolerance + 1e-12 * b.abs();
    let close_all = |a: &[f64], b: &[f64], tolerance: f64| {
        a.iter().zip(b).all(|(x, y)| close(*x, *y, tolerance))
    };
    for (index, (our, their)) in ours.iter().zip(theirs).enumerate() {
        let differ = || {
            Err(format!(
                "motion {} (our line {}) differs:\n  ours:  {:?}\n  rs274: {:?}",
                index + 1,
                our.line,
                our.kind,
                their.kind
            ))
        };
        let end_ok = |a: [f64; 4], b: [f64; 4]| {
            close_all(&a[..3], &b[..3], length_tolerance) && close(a[3], b[3], 1.5e-4)
        };
        let feed_ok = |a: f64, b: f64| close(a, b, 0.6e-4 * unit + 1e-9 * b.abs());
        let same = match (our.kind, their.kind) {
            (MotionKind::Rapid { end: a }, MotionKind::Rapid { end: b }) => end_ok(a, b),
            (MotionKind::Linear { end: a, feed: f }, MotionKind::Linear { end: b, feed: g }) => {
                end_ok(a, b) && feed_ok(f.mm_per_min, g.mm_per_min)
            }
            (
                MotionKind::Arc { end: a, center: c, plane: p, clockwise: w, turns: t, feed: f },
                MotionKind::Arc { end: b, center: d, plane: q, clockwise: x, turns: u, feed: g },
            ) => {
                end_ok(a, b)
                    && close_all(&c, &d, length_tolerance)
                    && p == q
                    && w == x
                    && t == u
                    && feed_ok(f.mm_per_min, g.mm_per_min)
            }
            (MotionKind::Dwell { seconds: a }, MotionKind::Dwell { seconds: b }) => {
                close(a, b, 0.6e-4)
            }
            (a, b) => a == b,
        };
        if !same {
            return differ();
        }
    }
    if ours.len() != theirs.len() {
        return Err(format!(
            "{} motions here, {} from rs274; first extra: {:?}",
            ours.len(),
            theirs.len(),
            ours.get(theirs.len()).map(|m| m.kind).or(theirs.get(ours.len()).map(|m| m.kind))
        ));
    }
    Ok(())
}

fn uses_inches(path: &Path) -> bool {
    std::fs::read(path).is_ok_and(|bytes| {
        let text = String::from_utf8_lossy(&bytes).to_ascii_uppercase();
        text.contains("G20")
    })
}

/// How one program fared.
#[derive(Debug, PartialEq, Eq, Clone, Copy)]
enum Verdict {
    Match,
    NotSupported,
    ForeignAxis,
    BothRefuse,
}

/// Runs both on `path`: `Ok(verdict)` or the difference.
fn check(path: &Path, dir: &Path) -> Result<Verdict, String> {
    let theirs = rs274::run(path, dir);
    let ours = ours(path);
    match (ours, theirs) {
        (Ok(ours), Outcome::Motions(theirs)) => {
            compare(&ours, &theirs, uses_inches(path)).map(|()| Verdict::Match)
        }
        (Err(GcodeError::NotSupported { .. }), _) => Ok(Verdict::NotSupported),
        (Err(GcodeError::ForeignAxis { .. }), _) => Ok(Verdict::ForeignAxis),
        (Err(err), Outcome::Error { .. }) => {
            let _ = err;
            Ok(Verdict::BothRefuse)
        }
        (Ok(_), Outcome::Error { message, .. }) => {
            Err(format!("rs274 refuses ({message}), we accept"))
        }
        (Err(err), Outcome::Motions(_)) => Err(format!("we refuse ({err}), rs274 accepts")),
    }
}

fn files_under(dir: &Path, extensions: &[&str], into: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else { return };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() {
            files_under(&path, extensions, into);
        } else if path
            .extension()
            .and_then(|e| e.to_str())
            .is_some_and(|e| extensions.contains(&e.to_ascii_lowercase().as_str()))
        {
            into.push(path);
        }
    }
}

#[test]
fn hand_written_cases_conform() {
    if !rs274::available("hand_written_cases_conform") {
        return;
    }
    let dir = temp_dir("conformance-cases");
    let mut cases = Vec::new();
    files_under(&repo_root().join("tests/conformance"), &["ngc"], &mut cases);
    cases.sort();
    assert!(cases.len() >= 60, "only {} conformance cases", cases.len());
    let mut failures = Vec::new();
    for case in &cases {
        let name = case.file_name().and_then(|n| n.to_str()).expect("name").to_owned();
        let text = std::fs::read_to_string(case).expect("read case");
        let ours = ours(case);
        let theirs = rs274::run(case, &dir);
        let problem = if name.starts_with("error_") {
            match (&ours, &theirs) {
                (Err(err), Outcome::Error { message, .. }) => {
                    let differs =
                        text.lines().next().is_some_and(|l| l.starts_with("; message differs:"));
                    if !differs && !err.to_string().contains(message.as_str()) {
                        Some(format!("messages differ:\n  ours:  {err}\n  rs274: {message}"))
                    } else {
                        None
                    }
                }
                (Ok(_), _) => Some("we accept it".to_owned()),
                (Err(err), Outcome::Motions(_)) => Some(format!("rs274 accepts it; we: {err}")),
            }
        } else if name.starts_with("unsupported_") {
            match ours {
                Err(GcodeError::NotSupported { .. }) => None,
                other => Some(format!("not refused as unsupported: {other:?}")),
            }
        } else if name.starts_with("axis_") {
            match ours {
                Err(GcodeError::ForeignAxis { .. }) => None,
                other => Some(format!("A/B/U/V/W not refused: {other:?}")),
            }
        } else {
            match (ours, theirs) {
                (Ok(ours), Outcome::Motions(theirs)) => {
                    compare(&ours, &theirs, uses_inches(case)).err()
                }
                (ours, theirs) => Some(format!("ours: {ours:?}\nrs274: {theirs:?}")),
            }
        };
        if let Some(problem) = problem {
            failures.push(format!("{name}: {problem}"));
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {} cases fail:\n{}",
        failures.len(),
        cases.len(),
        failures.join("\n")
    );
}

#[test]
fn programs_in_data_conform() {
    if !rs274::available("programs_in_data_conform") {
        return;
    }
    let dir = temp_dir("conformance-data");
    let mut programs = Vec::new();
    files_under(&repo_root().join("data"), &["ngc", "nc"], &mut programs);
    programs.sort();
    assert!(!programs.is_empty(), "no G-code programs in data/");
    for program in &programs {
        match check(program, &dir) {
            Ok(Verdict::Match) => {}
            other => panic!("{}: {other:?}", program.display()),
        }
    }
}

/// LinuxCNC's example programs: where the packages put them.
const EXAMPLE_FOLDERS: [&str; 3] =
    ["/usr/share/linuxcnc/ncfiles", "/usr/share/doc/linuxcnc/examples", "/usr/share/axis/images"];

#[test]
fn linuxcnc_examples_match_or_are_refused() {
    if !rs274::available("linuxcnc_examples_match_or_are_refused") {
        return;
    }
    let dir = temp_dir("conformance-examples");
    let mut programs = Vec::new();
    for folder in EXAMPLE_FOLDERS {
        files_under(Path::new(folder), &["ngc", "nc"], &mut programs);
    }
    programs.sort();
    // The packages ship many copies of the same programs: count each text once.
    let mut seen = std::collections::HashSet::new();
    let files = programs.len();
    programs.retain(|path| seen.insert(std::fs::read(path).unwrap_or_default()));
    let mut counts = [0usize; 4];
    let mut differ = Vec::new();
    let mut matched = Vec::new();
    for program in &programs {
        match check(program, &dir) {
            Ok(verdict) => {
                counts[verdict as usize] += 1;
                if verdict == Verdict::Match {
                    matched.push(program.display().to_string());
                }
            }
            Err(problem) => differ.push(format!("{}: {problem}", program.display())),
        }
    }
    #[allow(clippy::print_stderr)]
    {
        eprintln!(
            "LinuxCNC examples: {} distinct programs ({files} files): {} match, {} refused as \
             not supported yet (O-words, canned cycles, …), {} refused for A/B/U/V/W axis words, \
             {} refused by rs274 itself and by us, {} differ",
            programs.len(),
            counts[Verdict::Match as usize],
            counts[Verdict::NotSupported as usize],
            counts[Verdict::ForeignAxis as usize],
            counts[Verdict::BothRefuse as usize],
            differ.len()
        );
        eprintln!("matching: {}", matched.join(", "));
    }
    assert!(!programs.is_empty(), "no example programs found in {EXAMPLE_FOLDERS:?}");
    assert!(differ.is_empty(), "{} examples differ:\n{}", differ.len(), differ.join("\n"));
}
