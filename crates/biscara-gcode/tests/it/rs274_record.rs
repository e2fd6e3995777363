//! LinuxCNC's `rs274` results for the conformance programs (`tests/conformance/*.ngc`):
//! recorded beside each program (`NAME.rs274`: the motions derived from the canonical calls
//! rs274 printed, as inter-file lines, or its error message and the motions before it), and the
//! judgement of our interpreter against such a result. This module is shared by two test
//! crates: this package's, which compares with the records on every `cargo test` (no rs274
//! needed), and the `biscara` package's, which runs rs274 itself and re-records (`#[path]`).

#![allow(dead_code)] // each including crate uses a part

use std::fs::File;
use std::io::BufReader;
use std::path::{Path, PathBuf};

use biscara_files::FileSystem;
use biscara_gcode::{Config, GcodeError, IniFile, Interpreter, ToolTable, interpret_seekable};
use biscara_motion::{Motion, MotionKind};

/// The conformance programs, from the repository's root.
pub const CASES: &str = "crates/biscara-gcode/tests/conformance";

/// What rs274 made of a program.
#[derive(Debug, Clone, PartialEq)]
pub enum Outcome {
    /// The motions, absolute mm and degrees (line numbers are 0: rs274 does not print them).
    Motions(Vec<Motion>),
    /// rs274 refused the program: its message (first line of the error) and the motions it
    /// made before.
    Error {
        /// The message.
        message: String,
        /// The motions before the error.
        before: Vec<Motion>,
    },
}

/// The tool table beside `program` (`NAME.tbl` for `NAME.ngc`, else the `test.tbl` of its
/// folder, as LinuxCNC's interpreter tests have it), read as `interpret` reads it.
pub fn own_table(program: &Path) -> Option<ToolTable> {
    let own = program.with_extension("tbl");
    let folder = program.parent().map(|folder| folder.join("test.tbl"));
    let path = std::iter::once(own).chain(folder).find(|path| path.exists())?;
    Some(ToolTable::read(&FileSystem, &path).expect("read the program's tool table"))
}

/// The INI file rs274 is given (`-i`) for `program`: `NAME.ini` beside `NAME.ngc`, else the
/// `test.ini` of its folder, as LinuxCNC's interpreter tests have it.
pub fn own_ini(program: &Path) -> Option<std::path::PathBuf> {
    let own = program.with_extension("ini");
    let folder = program.parent().map(|folder| folder.join("test.ini"));
    std::iter::once(own).chain(folder).find(|path| path.exists())
}

/// The configuration rs274 is matched with: the defaults but rs274's path control mode (G64 with
/// no tolerance, where `interpret` starts in exact stop), and the program's own tool table
/// (`NAME.tbl`) and INI file (`NAME.ini`) when it has them.
pub fn config(path: &Path) -> Config {
    let ini = own_ini(path).map(|ini| IniFile::read(&FileSystem, &ini).expect("read the INI file"));
    Config {
        tool_table: own_table(path).map(std::sync::Arc::new),
        ini: ini.map(std::sync::Arc::new),
        blend: Some(0.0),
        ..Config::default()
    }
}

/// The interpreter on the file `path`, started like rs274 (at 0,0,0,0 with G28/G30 at 0), with
/// file subroutines beside it (rs274 runs in the program's folder and finds them there).
pub fn interpreter(path: &Path) -> Interpreter<BufReader<File>> {
    let file = File::open(path).unwrap_or_else(|err| panic!("{}: {err}", path.display()));
    interpret_seekable(BufReader::new(file), &config(path))
        .with_subroutines(Some(path.to_path_buf()), Vec::new())
        .with_environment(std::sync::Arc::new(FileSystem))
}

/// Our motions for `path`.
pub fn ours(path: &Path) -> Result<Vec<Motion>, GcodeError> {
    interpreter(path).collect()
}

/// Our motions for `path` before the first error, and the outcome.
pub fn ours_with_partial(path: &Path) -> (Vec<Motion>, Result<Vec<Motion>, GcodeError>) {
    let mut motions = Vec::new();
    for result in interpreter(path) {
        match result {
            Ok(motion) => motions.push(motion),
            Err(err) => return (motions, Err(err)),
        }
    }
    (motions.clone(), Ok(motions))
}

/// Our motions without the events of codes rs274 has no motion for (M19, M62–M68, M100–M199):
/// its canon prints them as calls the comparison does not read.
pub fn without_codes(ours: &[Motion]) -> Vec<Motion> {
    ours.iter().filter(|m| !matches!(m.kind, MotionKind::Code { .. })).copied().collect()
}

/// The first difference between our motions and rs274's, if any.
pub fn compare(ours: &[Motion], theirs: &[Motion], inches: bool) -> Result<(), String> {
    let ours = &without_codes(ours)[..];
    let unit = if inches { 25.4 } else { 1.0 };
    // Each printed number is rounded to 1e-4 of the unit (±5e-5), and an absolute position
    // sums up to four: the position and the G92 offset, both turned by a rotation (±7.1e-5
    // each), the origin and the tool offset (±5e-5 each): at most 2.42e-4.
    let length_tolerance = 2.45e-4 * unit + 1e-9;
    let close = |a: f64, b: f64, tolerance: f64| (a - b).abs() <= tolerance + 1e-12 * b.abs();
    let close_all = |a: &[f64], b: &[f64], tolerance: f64| {
        a.iter().zip(b).all(|(x, y)| close(*x, *y, tolerance))
    };
    let end_ok = |a: [f64; 4], b: [f64; 4]| {
        close_all(&a[..3], &b[..3], length_tolerance) && close(a[3], b[3], 1.5e-4)
    };
    // A straight move to where the tool already is moves nothing, and rs274 makes some that we
    // do not: it holds lengths in inches, so a Z it computes as 2 + 12.74 − 12.74 can come out
    // a hair below a canned cycle's R plane of 2, and it rapids "up" to it. Both sides drop them.
    let moving = |motions: &[Motion]| -> Vec<Motion> {
        let mut at: Option<[f64; 4]> = None;
        let mut kept = Vec::with_capacity(motions.len());
        for motion in motions {
            let end = motion.kind.end();
            let straight =
                matches!(motion.kind, MotionKind::Rapid { .. } | MotionKind::Linear { .. });
            if straight
                && let (Some(from), Some(to)) = (at, end)
                && end_ok(from, to)
            {
                continue;
            }
            at = end.or(at);
            kept.push(*motion);
        }
        kept
    };
    let (ours, theirs) = (&moving(ours)[..], &moving(theirs)[..]);
    for (index, (our, their)) in ours.iter().zip(theirs).enumerate() {
        let differ = || {
            Err(format!(
                "motion {} (our line {}) differs:\n  ours:  {:?} blend {:?}\n  rs274: {:?} blend {:?}",
                index + 1,
                our.line,
                our.kind,
                our.blend,
                their.kind,
                their.blend
            ))
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
        // rs274 prints the tolerance to 1e-6 of the unit.
        let blend_ok = match (our.blend, their.blend) {
            (Some(a), Some(b)) => close(a, b, 0.6e-6 * unit + 1e-12),
            (a, b) => a == b,
        };
        if !same || !blend_ok {
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

pub fn uses_inches(path: &Path) -> bool {
    std::fs::read(path).is_ok_and(|bytes| {
        let text = String::from_utf8_lossy(&bytes).to_ascii_uppercase();
        text.contains("G20")
    })
}

/// Whether rs274's `message` refuses a user M code (M100–M199) it has no program for.
pub fn user_m_code(message: &str) -> bool {
    message
        .strip_prefix("Unknown m code used: M")
        .and_then(|number| number.trim().parse::<u32>().ok())
        .is_some_and(|number| (100..=199).contains(&number))
}

/// rs274's outcome with its spline calls expanded as ours are (`expand`: rs274's NURBS and
/// spline output is compared with our straight pieces), as it is recorded.
pub fn expand(
    case: &Path,
    theirs: Outcome,
    expand: impl Fn(&[Motion], &[Motion]) -> Vec<Motion>,
) -> Outcome {
    match (ours(case), theirs) {
        (Ok(ours), Outcome::Motions(theirs)) => {
            Outcome::Motions(expand(&without_codes(&ours), &theirs))
        }
        (_, theirs) => theirs,
    }
}

/// Our interpreter on the conformance program `case` against rs274's outcome (expanded):
/// `None` when they agree as the program's name prefix asks — `error_*` refused by both, with
/// LinuxCNC's message contained in ours unless its first line reads `; message differs: WHY`;
/// `unsupported_*` refused by us as not supported; `user_m_*` a user M-code event where rs274
/// lacks its program; `axis_*` refused for an A/B/U/V/W word; any other the same motions.
pub fn judge_case(case: &Path, theirs: &Outcome) -> Option<String> {
    let name = case.file_name().and_then(|n| n.to_str()).unwrap_or_default().to_owned();
    let text = std::fs::read_to_string(case).expect("read case");
    let ours = ours(case);
    if name.starts_with("error_") {
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
            Err(GcodeError::NotSupported { .. } | GcodeError::CannotRun { .. }) => None,
            other => Some(format!("not refused as unsupported: {other:?}")),
        }
    } else if name.starts_with("user_m_") {
        match (&ours, &theirs) {
            (Ok(motions), Outcome::Error { message, .. }) if user_m_code(message) => motions
                .iter()
                .any(|m| matches!(m.kind, MotionKind::Code { .. }))
                .then_some(())
                .map_or(Some("no code event".to_owned()), |()| None),
            _ => Some(format!("ours: {ours:?}\nrs274: {theirs:?}")),
        }
    } else if name.starts_with("axis_") {
        match ours {
            Err(GcodeError::ForeignAxis { .. }) => None,
            other => Some(format!("A/B/U/V/W not refused: {other:?}")),
        }
    } else {
        match (ours, theirs) {
            (Ok(ours), Outcome::Motions(theirs)) => {
                compare(&without_codes(&ours), theirs, uses_inches(case)).err()
            }
            (ours, theirs) => Some(format!("ours: {ours:?}\nrs274: {theirs:?}")),
        }
    }
}

/// The first line of a record of motions.
const MOTIONS_HEADER: &str = "# rs274 motions";
/// The first line of a record of an error, before its message.
const ERROR_HEADER: &str = "# rs274 error: ";

/// Where the result of `case` is recorded: `NAME.rs274` beside `NAME.ngc`.
pub fn record_path(case: &Path) -> PathBuf {
    case.with_extension("rs274")
}

/// What stands in a record for the folder of the conformance programs: rs274's messages name
/// the program's absolute path, and a record must not depend on where the repository lies.
const FOLDER: &str = "$CONFORMANCE";

/// The record of an outcome of a program in `dir`: a header line, then the motions as inter-file
/// lines.
pub fn record_text(outcome: &Outcome, dir: &Path) -> String {
    let (header, motions) = match outcome {
        Outcome::Motions(motions) => (MOTIONS_HEADER.to_owned(), motions),
        Outcome::Error { message, before } => {
            let message = message.replace(&dir.display().to_string(), FOLDER);
            (format!("{ERROR_HEADER}{message}"), before)
        }
    };
    let mut out = format!("{header}\n").into_bytes();
    // rs274's spline and tilted-arc calls are expanded with our own moves (`expand`) when we
    // run the program; where we refuse it they stay markers with NaN numbers, which no
    // judgement reads (only rs274's refusal or message is judged then): not recorded.
    let recorded = |motion: &&Motion| {
        motion.kind.end().is_none_or(|end| end.iter().all(|value| value.is_finite()))
            && motion.extrude.is_none_or(f64::is_finite)
    };
    for motion in motions.iter().filter(recorded) {
        biscara_motion::write_jsonl(&mut out, motion).expect("write to memory");
    }
    String::from_utf8(out).expect("inter-file lines are text")
}

/// A record of a program in `dir` read back.
pub fn read_record(text: &str, dir: &Path) -> Result<Outcome, String> {
    let (header, rest) = text.split_once('\n').unwrap_or((text, ""));
    let mut motions = biscara_motion::read_jsonl(rest.as_bytes())
        .collect::<Result<Vec<_>, _>>()
        .map_err(|err| err.to_string())?;
    // rs274 prints no line numbers (the reader numbers lines without one).
    for motion in &mut motions {
        motion.line = 0;
    }
    if header == MOTIONS_HEADER {
        Ok(Outcome::Motions(motions))
    } else if let Some(message) = header.strip_prefix(ERROR_HEADER) {
        let message = message.replace(FOLDER, &dir.display().to_string());
        Ok(Outcome::Error { message, before: motions })
    } else {
        Err(format!("not a record: {header}"))
    }
}

/// Every conformance program under `dir`, sorted.
pub fn cases(dir: &Path) -> Vec<PathBuf> {
    let mut cases: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap_or_else(|err| panic!("{}: {err}", dir.display()))
        .filter_map(|entry| entry.ok().map(|entry| entry.path()))
        .filter(|path| path.extension().is_some_and(|extension| extension == "ngc"))
        .collect();
    cases.sort();
    cases
}
