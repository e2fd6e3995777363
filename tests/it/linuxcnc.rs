//! LinuxCNC acceptance: LinuxCNC's own interpreter must accept every G-code
//! program that `post` and `gen` write for `data/`, and produce the motions the CL file asked for.
//!
//! The interpreter is `rs274` from Debian's `linuxcnc-uspace` (`.ci/run` installs it). Invocation:
//!
//! ```text
//! rs274 -g PROGRAM.ngc < /dev/null
//! ```
//!
//! `-g` is batch mode: without it rs274 shows a menu and reads choices from standard input (so
//! stdin is closed anyway). No tool table (`-t`), parameter file (`-v`) or INI file (`-i`) is
//! needed: the defaults give axes X Y Z A B C in mm. It prints one canonical machining call per
//! line on standard output, e.g. `   13 N..... STRAIGHT_TRAVERSE(0.0000, 400.0000, 100.0000,
//! 0.0000, 0.0000, 0.0000)` (X Y Z A B C, 4 decimals; `N30` instead of `N.....` for numbered
//! blocks), errors on standard error (the message and the offending block), and exits with 1 on
//! an error; besides that its standard error holds only `executing`.
//!
//! The test compares rs274's STRAIGHT_TRAVERSE, STRAIGHT_FEED (with the SET_FEED_RATE in force),
//! ARC_FEED (end, centre, direction, Z, C, feed), DWELL and START_SPINDLE_CLOCKWISE /
//! COUNTERCLOCKWISE (our M3 pick / M4 place) with the motions the CL file asks for, worked out
//! here from the CL statements: RAPID for the next motion only, modal FEDRAT with MMPM/IPM and
//! UNITS/INCHES, CIRCLE + GOTO arcs counter-clockwise about the CIRCLE's axis.
//!
//! When rs274 is missing the test prints why and passes, except under `CI=true`, where it fails.

use std::path::Path;
use std::process::{Command, Stdio};

use biscara::cl::{ClReader, FeedUnit, Statement, Units};

use crate::programming::{data_files, stem};
use crate::util::{biscara, temp_dir};

/// One motion or event, as rs274 reports it or as the CL file asks for it: mm, degrees, mm/min.
#[derive(Debug, Clone, PartialEq)]
enum Canon {
    Traverse([f64; 4]),
    Feed([f64; 4], f64),
    /// End `[x, y, z, c]`, centre `[x, y]`, +1 counter-clockwise / −1 clockwise, feed.
    Arc([f64; 4], [f64; 2], i32, f64),
    Dwell(f64),
    Pick,
    Place,
}

/// Tolerances: 3 decimals in the G-code (½e-3) plus inch conversion; feeds have 1 decimal.
fn close(a: &Canon, b: &Canon) -> bool {
    let near = |a: &[f64], b: &[f64], tol: f64| a.iter().zip(b).all(|(a, b)| (a - b).abs() <= tol);
    match (a, b) {
        (Canon::Traverse(p), Canon::Traverse(q)) => near(p, q, 1.1e-3),
        (Canon::Feed(p, f), Canon::Feed(q, g)) => near(p, q, 1.1e-3) && (f - g).abs() <= 0.051,
        (Canon::Arc(p, c, r, f), Canon::Arc(q, d, s, g)) => {
            near(p, q, 1.1e-3) && near(c, d, 2.1e-3) && r == s && (f - g).abs() <= 0.051
        }
        (Canon::Dwell(s), Canon::Dwell(t)) => (s - t).abs() <= 1e-3,
        (Canon::Pick, Canon::Pick) | (Canon::Place, Canon::Place) => true,
        _ => false,
    }
}

/// The motions a CL file asks for.
fn expected_motions(cl: &str) -> Vec<Canon> {
    let mut motions = Vec::new();
    let (mut scale, mut feed, mut rapid) = (1.0, 0.0, false);
    let mut position = [0.0_f64; 4];
    let mut circle = None;
    for record in ClReader::new(cl.as_bytes()) {
        let record = record.expect("the CL file reads");
        match record.statement {
            Statement::Units(Units::Inches) => scale = 25.4,
            Statement::Units(_) => scale = 1.0,
            Statement::Rapid => rapid = true,
            Statement::Feed(f) => {
                feed = f.value
                    * match f.unit {
                        Some(FeedUnit::Mmpm) => 1.0,
                        Some(FeedUnit::Ipm) => 25.4,
                        None => scale,
                    }
            }
            Statement::Circle(c) => circle = Some(c),
            Statement::Goto(goto) => {
                let end =
                    [goto.x * scale, goto.y * scale, goto.z * scale, goto.c.unwrap_or(position[3])];
                motions.push(match circle.take() {
                    Some(c) => Canon::Arc(
                        end,
                        [c.center[0] * scale, c.center[1] * scale],
                        if c.axis[2] > 0.0 { 1 } else { -1 },
                        feed,
                    ),
                    None if std::mem::take(&mut rapid) => Canon::Traverse(end),
                    None => Canon::Feed(end, feed),
                });
                position = end;
            }
            Statement::Delay(seconds) => motions.push(Canon::Dwell(seconds)),
            Statement::Pick => motions.push(Canon::Pick),
            Statement::Place => motions.push(Canon::Place),
            _ => {}
        }
    }
    motions
}

/// The numbers between the parentheses of a canonical call.
fn arguments(call: &str) -> Vec<f64> {
    let inside = call.split_once('(').and_then(|(_, rest)| rest.rsplit_once(')')).map(|(a, _)| a);
    inside
        .unwrap_or_default()
        .split(',')
        .map(|word| word.trim().parse().unwrap_or_else(|_| panic!("a number in {call}")))
        .collect()
}

/// The motions in rs274's canonical output.
fn canonical_motions(output: &str) -> Vec<Canon> {
    let mut motions = Vec::new();
    let mut feed = 0.0;
    for line in output.lines() {
        // "   13 N..... NAME(args)": skip the counter and the block number.
        let mut words = line.split_whitespace();
        let (Some(_), Some(_)) = (words.next(), words.next()) else { continue };
        let call = words.collect::<Vec<_>>().join(" ");
        let name = call.split('(').next().unwrap_or_default();
        match name {
            "SET_FEED_RATE" => feed = arguments(&call)[0],
            "STRAIGHT_TRAVERSE" | "STRAIGHT_FEED" => {
                let v = arguments(&call);
                let end = [v[0], v[1], v[2], v[5]];
                motions.push(if name == "STRAIGHT_TRAVERSE" {
                    Canon::Traverse(end)
                } else {
                    Canon::Feed(end, feed)
                });
            }
            "ARC_FEED" => {
                // first_end, second_end, first_axis, second_axis, rotation, axis_end, a, b, c
                let v = arguments(&call);
                motions.push(Canon::Arc([v[0], v[1], v[5], v[8]], [v[2], v[3]], v[4] as i32, feed));
            }
            "DWELL" => motions.push(Canon::Dwell(arguments(&call)[0])),
            "START_SPINDLE_CLOCKWISE" => motions.push(Canon::Pick),
            "START_SPINDLE_COUNTERCLOCKWISE" => motions.push(Canon::Place),
            _ => {}
        }
    }
    motions
}

/// Runs rs274 on `program`; `None` when rs274 is not installed.
///
/// rs274 creates, truncates and maps `$HOME/.tool.mmap` (its tool table), so two runs sharing a
/// HOME can kill each other with SIGBUS; each run here gets the program's own folder as HOME.
fn rs274(program: &Path) -> Option<std::process::Output> {
    let folder = program.parent().expect("folder");
    let spawned = Command::new("rs274")
        .arg("-g")
        .arg(program)
        .current_dir(folder)
        .env("HOME", folder)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn();
    match spawned {
        Ok(child) => Some(child.wait_with_output().expect("wait for rs274")),
        Err(err) if err.kind() == std::io::ErrorKind::NotFound => None,
        Err(err) => panic!("cannot run rs274: {err}"),
    }
}

/// rs274 accepts `program` and its motions are those of `cl`. Returns false when rs274 is
/// missing.
#[track_caller]
fn check_with_rs274(program: &Path, cl: &str) -> bool {
    let Some(output) = rs274(program) else { return false };
    let stdout = String::from_utf8_lossy(&output.stdout);
    let stderr = String::from_utf8_lossy(&output.stderr);
    let gcode = std::fs::read_to_string(program).expect("program");
    let report = format!(
        "rs274 -g {}\nexit: {}\n--- stderr ---\n{stderr}\n--- program ---\n{gcode}",
        program.display(),
        output.status
    );
    assert!(output.status.success(), "rs274 rejected the program\n{report}");
    let complaints: Vec<&str> = stderr
        .lines()
        .filter(|line| !line.trim().is_empty() && line.trim() != "executing")
        .collect();
    assert!(complaints.is_empty(), "rs274 complained: {complaints:?}\n{report}");
    assert!(stdout.contains("PROGRAM_END()"), "rs274 did not reach M2\n{report}");
    let actual = canonical_motions(&stdout);
    let expected = expected_motions(cl);
    assert!(!expected.is_empty());
    assert_eq!(actual.len(), expected.len(), "motion count\n{actual:#?}\n{expected:#?}\n{report}");
    for (index, (got, want)) in actual.iter().zip(&expected).enumerate() {
        assert!(
            close(got, want),
            "motion {index}: rs274 {got:?}, the CL asks for {want:?}\n{report}"
        );
    }
    true
}

fn skip_or_fail() {
    crate::util::skip_or_fail(
        "LinuxCNC acceptance",
        "rs274",
        " (apt-get install --no-install-recommends linuxcnc-uspace)",
    );
}

#[test]
fn linuxcnc_accepts_every_generated_program_with_the_cl_motions() {
    let dir = temp_dir("linuxcnc");
    let mut checked = 0;
    for job in data_files("jobs", "txt") {
        let name = stem(&job);
        let job = job.to_str().expect("path");
        for (suffix, extra) in [("", None), (".numbered", Some("--line-numbers"))] {
            let program = format!("{name}{suffix}.ngc");
            let cl = format!("{name}{suffix}.cl");
            let mut args = vec!["gen", job, "-o", &program, "--clf", &cl];
            args.extend(extra);
            biscara(&dir, &args).success();
            let cl_text = std::fs::read_to_string(dir.join(&cl)).expect("CL");
            if !check_with_rs274(&dir.join(&program), &cl_text) {
                return skip_or_fail();
            }
            checked += 1;
        }
    }
    for cl in data_files("cl", "cl") {
        let name = stem(&cl);
        let cl_text = std::fs::read_to_string(&cl).expect("CL");
        for (suffix, extra) in [("", None), (".numbered", Some("--line-numbers"))] {
            let program = format!("{name}{suffix}.ngc");
            let mut args = vec!["post", cl.to_str().expect("path"), "-o", &program];
            args.extend(extra);
            biscara(&dir, &args).success();
            if !check_with_rs274(&dir.join(&program), &cl_text) {
                return skip_or_fail();
            }
            checked += 1;
        }
    }
    assert!(checked >= 6, "every example in data/ checked");
}

#[test]
fn the_canonical_output_parser_reads_rs274_lines() {
    let output = "   15 N..... SET_FEED_RATE(3000.0000)\n   16 N40    STRAIGHT_FEED(150.0000, \
                  320.0000, 10.0000, 0.0000, 0.0000, 30.0000)\n   22 N..... ARC_FEED(160.0000, \
                  330.0000, 160.0000, 320.0000, -1, 60.0000, 0.0000, 0.0000, 30.0000)\n   \
                  19 N..... DWELL(0.3000)\n   18 N..... START_SPINDLE_CLOCKWISE(0)\n";
    assert_eq!(
        canonical_motions(output),
        vec![
            Canon::Feed([150.0, 320.0, 10.0, 30.0], 3000.0),
            Canon::Arc([160.0, 330.0, 60.0, 30.0], [160.0, 320.0], -1, 3000.0),
            Canon::Dwell(0.3),
            Canon::Pick,
        ]
    );
}
