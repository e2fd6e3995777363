//! Real programs in their firmware's dialect (docs/gcode.md, issue 14): every program of
//! `../shared/realworld` (beside the clone; never copied into the project) goes through
//! `biscara interpret` with no flag. Each must be read as the dialect this table names (the
//! note on stderr says which `auto` chose), exit 0, and its moves and dwells must be what the
//! source firmware would do: end points, arc centres (I J K form), dwell seconds in the
//! dialect's unit and extrusion per move are compared, motion by motion, with [`Reader`], a
//! small reader of the plain subset of G-code these programs use, written from the firmware
//! documentation and independent of the interpreter. The four expected refusals must fail with
//! a clear `FILE:LINE:COL` error. A LinuxCNC program with O-words and expressions, which that
//! reader does not evaluate, is compared with LinuxCNC's own `rs274` instead.
//!
//! Every program that is read then goes through `check --fit`, which must be clean or find only
//! the problems [`CHECK`] names.
//!
//! When `../shared/realworld` is missing the test says so and passes, except under `CI=true`.

use std::path::PathBuf;

use biscara::kinematics::{Kinematics, Robot};
use biscara::motion::{Motion, MotionKind, read_jsonl};

use crate::util::{biscara, repo_root, skip_or_fail, temp_dir};

/// What a program must do.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Expect {
    /// Read as this dialect (its name on the command line), exit 0, moves as [`Reader`] says.
    Read(&'static str),
    /// Read as LinuxCNC G-code, exit 0, moves as LinuxCNC's `rs274` makes them (a program with
    /// O-words, parameters and expressions, which [`Reader`] does not evaluate).
    ReadAsRs274,
    /// Refused with a `FILE:LINE:COL` error containing one of these texts.
    Refused(&'static [&'static str]),
}

/// Every program of the folder, with what it must do.
const PROGRAMS: &[(&str, Expect)] = &[
    ("laser/fabtotum-laser-cardboard.gcode", Expect::Read("marlin")),
    ("laser/inkscape-lasertools-qr.gcode", Expect::Read("linuxcnc")),
    ("laser/lasergrbl-vector-snowflake.nc", Expect::Read("grbl")),
    ("laser/laserweb4-lasercut-crlf.gcode", Expect::Read("grbl")),
    ("mill/cambam-2008-smile-inch.nc", Expect::Read("linuxcnc")),
    ("mill/cambam-birthday.nc", Expect::Read("linuxcnc")),
    ("mill/dxf2gcode-b02-erin7.ngc", Expect::Read("linuxcnc")),
    ("mill/estlcam10-spool.nc", Expect::Read("mach3")),
    ("mill/fengrave-140-text.ngc", Expect::Read("linuxcnc")),
    ("mill/freecad-grbl-ecscentric-cut.nc", Expect::Read("grbl")),
    ("mill/fusion-grbl-clamp-base.nc", Expect::Read("linuxcnc")),
    ("mill/fusion-linuxcnc-inch-hema-p030.ngc", Expect::Read("linuxcnc")),
    // G41 with a P word (Mach3's compensation radius) says Mach3.
    ("mill/fusion-mach3-eccentric-g41p.tap", Expect::Read("mach3")),
    // Nothing in it tells the dialects apart but `.tap`, Mach3's own extension.
    ("mill/fusion-mach3-heatsink-bottom.tap", Expect::Read("mach3")),
    ("mill/gcodetools-puzzle03.gcode", Expect::Read("linuxcnc")),
    ("mill/jscut-jsdc-engrave.gcode", Expect::Read("grbl")),
    ("mill/openvoronoi-ttt-vcarve.ngc", Expect::Read("linuxcnc")),
    ("mill/partkam-plate.nc", Expect::Read("linuxcnc")),
    ("mill/pycam-tiny-cat-outline.ngc", Expect::Read("linuxcnc")),
    ("mill/solidworkscam-motor-offset-g41d.tap", Expect::Read("mach3")),
    ("mill/supercam-girl-inch.gcode", Expect::Read("linuxcnc")),
    ("mill/viaconstructor-all.ngc", Expect::Read("linuxcnc")),
    ("other/camotics-tpl-cds.gcode", Expect::Read("linuxcnc")),
    ("other/flatcam-inferred-bcnc-sample.gcode", Expect::Read("grbl")),
    ("other/gcode-exporter-pcb-reprap.gcode", Expect::Read("marlin")),
    ("other/gmax-4axis-rotation-a.ngc", Expect::Refused(&["A axis word"])),
    // Its subroutine files are not shipped with it: rs274 refuses it with the same message.
    (
        "other/handwritten-linuxcnc-external-subs.ngc",
        Expect::Refused(&["EOF in file:", "seeking o-word: o<drill_man> from line: 71"]),
    ),
    (
        "other/handwritten-linuxcnc-spool-owords-b.nc",
        Expect::Refused(&["B axis word", "O-word is not supported yet"]),
    ),
    ("other/millmasterpro-mastercam-hdr-g70.nc", Expect::Refused(&["Bad character '/' used"])),
    // O-word subroutines, expressions and probing (G38.2, run as rs274 simulates it) for the
    // autolevel.
    ("other/pcb2gcode-autolevel-linuxcnc-back.ngc", Expect::ReadAsRs274),
    ("plotter/estlcam10-crown-plotter.gcode", Expect::Read("grbl")),
    ("plotter/gcodeplot-3rect.gcode", Expect::Read("marlin")),
    ("plotter/rotrics-studio-dexarm-quote.gcode", Expect::Read("marlin")),
    ("plotter/svg2gcode-smooth-curves-arcs.gcode", Expect::Read("grbl")),
    ("printer/cura-4.10-hex.gcode", Expect::Read("marlin")),
    ("printer/cura-griffin-ultimaker.gcode", Expect::Read("marlin")),
    ("printer/cura-legacy-fabtotum-keychain.gcode", Expect::Read("marlin")),
    ("printer/cura-reprap-m566.gcode", Expect::Read("marlin")),
    ("printer/kisslicer-1.6.3.gcode", Expect::Read("marlin")),
    ("printer/miraclegrue-makerbot-20mmbox.gcode", Expect::Read("marlin")),
    ("printer/prusaslicer-273-mini-qoi-thumb.gcode", Expect::Read("marlin")),
    ("printer/skeinforge-makerbot-20mmbox.gcode", Expect::Read("marlin")),
    ("printer/slic3r-120-sample.gcode", Expect::Read("marlin")),
];

pub(crate) fn realworld() -> Option<PathBuf> {
    // Beside the clone (CI), or beside the folder of worktrees.
    for relative in ["../shared/realworld", "../../shared/realworld"] {
        let folder = repo_root().join(relative);
        if folder.join("SOURCES.tsv").is_file() {
            return Some(folder);
        }
    }
    skip_or_fail("real-world programs", "../shared/realworld", " (beside the clone)");
    None
}

#[test]
fn every_real_program_is_read_as_its_firmware_reads_it() {
    let Some(folder) = realworld() else { return };
    let mut listed: Vec<&str> = PROGRAMS.iter().map(|(name, _)| *name).collect();
    listed.sort_unstable();
    let mut present = Vec::new();
    for group in std::fs::read_dir(&folder).expect("realworld folder") {
        let group = group.expect("entry").path();
        if !group.is_dir() {
            continue;
        }
        for file in std::fs::read_dir(&group).expect("group folder") {
            let file = file.expect("entry").path();
            let relative = file.strip_prefix(&folder).expect("inside").to_string_lossy();
            present.push(relative.replace('\\', "/"));
        }
    }
    present.sort_unstable();
    assert_eq!(present, listed, "the table must name every program of the folder");

    let home = Kinematics::new(&Robot::default()).expect("default robot").home().to_degrees();
    let dir = temp_dir("realworld");
    let mut failures = Vec::new();
    let mut accepted = 0;
    let mut compared = 0;
    for &(name, expect) in PROGRAMS {
        let path = folder.join(name);
        let program = path.to_string_lossy().into_owned();
        let run = biscara(&dir, &["interpret", &program]);
        match expect {
            Expect::Read(dialect) => {
                if run.code != 0 {
                    failures.push(format!("{name}: refused\n{}", run.stderr));
                    continue;
                }
                accepted += 1;
                let chosen = format!("read as {dialect} G-code");
                // LinuxCNC without evidence is the silent default.
                let silent = dialect == "linuxcnc" && !run.stderr.contains("read as");
                if !run.stderr.contains(&chosen) && !silent {
                    failures.push(format!("{name}: not {chosen}\n{}", run.stderr));
                    continue;
                }
                let ours: Vec<Motion> = read_jsonl(run.stdout.as_bytes())
                    .collect::<Result<_, _>>()
                    .unwrap_or_else(|err| panic!("{name}: our own inter-file: {err}"));
                let text = std::fs::read(&path).expect("read program");
                let expected = Reader::new(dialect, home, &text).read();
                if expected.is_empty() {
                    failures.push(format!("{name}: the reader found no move to compare"));
                }
                compared += expected.len();
                if let Err(message) = compare(&ours, &expected) {
                    failures.push(format!("{name} ({dialect}): {message}"));
                }
            }
            Expect::ReadAsRs274 => {
                if run.code != 0 {
                    failures.push(format!("{name}: refused\n{}", run.stderr));
                    continue;
                }
                accepted += 1;
                if run.stderr.contains("read as") && !run.stderr.contains("read as linuxcnc") {
                    failures.push(format!("{name}: not read as linuxcnc\n{}", run.stderr));
                    continue;
                }
                if !crate::rs274::available("every_real_program_is_read_as_its_firmware_reads_it") {
                    continue;
                }
                match crate::conformance::check(&path, &dir) {
                    Ok(crate::conformance::Verdict::Match) => compared += 1,
                    Ok(verdict) => failures.push(format!("{name}: {verdict:?}, not a match")),
                    Err(message) => failures.push(format!("{name} (rs274): {message}")),
                }
            }
            Expect::Refused(texts) => {
                let located = format!("biscara: error: {program}:");
                let rest = run.stderr.strip_prefix(&located).unwrap_or("");
                let line_col: Vec<&str> = rest.splitn(3, ':').take(2).collect();
                let numbered = line_col.len() == 2
                    && line_col
                        .iter()
                        .all(|n| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()));
                if run.code != 1 || !numbered || !texts.iter().any(|t| run.stderr.contains(t)) {
                    failures
                        .push(format!("{name}: want a FILE:LINE:COL error with {texts:?}\n{run}"));
                }
            }
        }
    }
    #[allow(clippy::print_stderr)]
    {
        eprintln!(
            "real-world programs accepted: {accepted} of {}; {compared} moves and dwells compared",
            PROGRAMS.len()
        );
    }
    assert!(
        failures.is_empty(),
        "{} programs misbehaved:\n{}",
        failures.len(),
        failures.join("\n\n")
    );
}

/// What `check --fit` finds in a program that is read, where it is not clean: the kinds of
/// problem (`check --json`'s `kind`), each with why.
const CHECK: &[(&str, CheckFinds)] = &[
    // Its LinuxCNC post switches the laser on at S1 ("set power to 0") and keeps it on through
    // the G0 moves between paths: S1 is low, not 0, and LinuxCNC has no laser mode.
    ("laser/inkscape-lasertools-qr.gcode", CheckFinds::Problems(&["tool"])),
    // 54 x 488 mm: longer than the workspace's largest rectangle either way.
    ("other/camotics-tpl-cds.gcode", CheckFinds::DoesNotFit),
];

/// What `check --fit` finds where it is not clean.
#[derive(Debug, Clone, Copy)]
enum CheckFinds {
    /// Problems of these kinds only.
    Problems(&'static [&'static str]),
    /// `--fit` finds no place for the program.
    DoesNotFit,
}

/// `check --fit` on every program that is read: clean (exit 0, no problem), or what [`CHECK`]
/// names. Its Z range is centred in the robot's stroke when it lies outside it (what `--fit`
/// does). Samples are 20 ms apart rather than 1 ms, to keep this debug-build test short.
#[test]
fn every_real_program_read_passes_check_fit() {
    let Some(folder) = realworld() else { return };
    let dir = temp_dir("realworld-check");
    let read: Vec<&str> = PROGRAMS
        .iter()
        .filter(|(_, expect)| !matches!(expect, Expect::Refused(_)))
        .map(|(name, _)| *name)
        .collect();
    let threads = std::thread::available_parallelism().map_or(2, |n| n.get().min(4));
    let failures: Vec<String> = std::thread::scope(|scope| {
        let workers: Vec<_> = (0..threads)
            .map(|worker| {
                let (read, folder, dir) = (&read, &folder, &dir);
                scope.spawn(move || {
                    let mut failures = Vec::new();
                    for name in read.iter().skip(worker).step_by(threads) {
                        if let Err(message) = check_fit(&folder.join(name), dir, name) {
                            failures.push(format!("{name}: {message}"));
                        }
                    }
                    failures
                })
            })
            .collect();
        workers.into_iter().flat_map(|worker| worker.join().expect("worker")).collect()
    });
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

/// `check PROGRAM --fit --json` as [`CHECK`] expects it for `name`.
fn check_fit(path: &std::path::Path, dir: &std::path::Path, name: &str) -> Result<(), String> {
    let program = path.to_string_lossy();
    let run = biscara(dir, &["check", &program, "--fit", "--json", "--dt", "0.02"]);
    let expected = CHECK.iter().find(|(file, _)| *file == name).map(|(_, finds)| *finds);
    if let Some(CheckFinds::DoesNotFit) = expected {
        return match run.code == 1 && run.stderr.contains("does not fit") {
            true => Ok(()),
            false => Err(format!("want \"does not fit\"\n{run}")),
        };
    }
    let report: serde_json::Value = serde_json::from_str(&run.stdout)
        .map_err(|err| format!("no JSON report ({err})\n{run}"))?;
    let kinds: Vec<&str> = report["problems"]
        .as_array()
        .ok_or_else(|| format!("no problems array\n{run}"))?
        .iter()
        .filter_map(|problem| problem["kind"].as_str())
        .collect();
    match expected {
        None if run.code == 0 && kinds.is_empty() => Ok(()),
        Some(CheckFinds::Problems(allowed))
            if run.code == 1
                && !kinds.is_empty()
                && kinds.iter().all(|kind| allowed.contains(kind)) =>
        {
            Ok(())
        }
        _ => Err(format!("expected {expected:?}, found problems {kinds:?}\n{run}")),
    }
}

/// A move or dwell as the firmware makes it: what [`compare`] checks.
#[derive(Debug, Clone, PartialEq)]
enum Step {
    Rapid {
        end: [f64; 4],
        extrude: Option<f64>,
    },
    Linear {
        end: [f64; 4],
        extrude: Option<f64>,
    },
    /// `center` is `None` for the R form (only the end point is checked).
    Arc {
        end: [f64; 4],
        center: Option<[f64; 2]>,
        clockwise: bool,
    },
    Dwell {
        seconds: f64,
    },
    /// A move under Mach3's G41/G42 P (cutter compensation by `radius`): the tool's end lies
    /// beside the programmed `end`, at least the radius from it and at most √2 times (a corner
    /// of up to 90° with the next move), at the programmed Z.
    Compensated {
        end: [f64; 4],
        radius: f64,
    },
}

fn ours_as_steps(ours: &[Motion]) -> Vec<Step> {
    ours.iter()
        .filter_map(|motion| match motion.kind {
            MotionKind::Rapid { end } => Some(Step::Rapid { end, extrude: motion.extrude }),
            MotionKind::Linear { end, .. } => Some(Step::Linear { end, extrude: motion.extrude }),
            MotionKind::Arc { end, center, clockwise, .. } => {
                Some(Step::Arc { end, center: Some(center), clockwise })
            }
            MotionKind::Dwell { seconds } => Some(Step::Dwell { seconds }),
            _ => None,
        })
        .collect()
}

fn compare(ours: &[Motion], expected: &[(usize, Step)]) -> Result<(), String> {
    let steps = ours_as_steps(ours);
    let lines: Vec<usize> = ours
        .iter()
        .filter(|m| m.kind.end().is_some() || matches!(m.kind, MotionKind::Dwell { .. }))
        .map(|m| m.line)
        .collect();
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-6 * (1.0 + b.abs());
    let close_all = |a: &[f64], b: &[f64]| a.iter().zip(b).all(|(x, y)| close(*x, *y));
    let close_option = |a: Option<f64>, b: Option<f64>| match (a, b) {
        (Some(a), Some(b)) => close(a, b),
        (None, None) => true,
        _ => false,
    };
    for (index, (line, step)) in expected.iter().enumerate() {
        let Some(our) = steps.get(index) else {
            return Err(format!(
                "{} moves and dwells, the firmware makes {}",
                steps.len(),
                expected.len()
            ));
        };
        let same = match (our, step) {
            (Step::Rapid { end: a, extrude: x }, Step::Rapid { end: b, extrude: y })
            | (Step::Linear { end: a, extrude: x }, Step::Linear { end: b, extrude: y }) => {
                close_all(a, b) && close_option(*x, *y)
            }
            (
                Step::Arc { end: a, center: c, clockwise: w },
                Step::Arc { end: b, center: d, clockwise: v },
            ) => {
                close_all(a, b)
                    && w == v
                    && match (c, d) {
                        (Some(c), Some(d)) => close_all(c, d),
                        _ => true,
                    }
            }
            (Step::Dwell { seconds: a }, Step::Dwell { seconds: b }) => close(*a, *b),
            (
                Step::Linear { end: a, .. } | Step::Arc { end: a, .. },
                Step::Compensated { end: b, radius },
            ) => {
                let beside = (a[0] - b[0]).hypot(a[1] - b[1]);
                close(a[2], b[2]) && beside >= radius - 1e-6 && beside <= radius * 2f64.sqrt()
            }
            _ => false,
        };
        if !same || lines[index] != *line {
            return Err(format!(
                "step {} differs:\n  ours (line {}): {our:?}\n  firmware (line {line}): {step:?}",
                index + 1,
                lines[index]
            ));
        }
    }
    if steps.len() != expected.len() {
        return Err(format!(
            "{} moves and dwells, the firmware makes {}",
            steps.len(),
            expected.len()
        ));
    }
    Ok(())
}

/// A reader of the plain G-code these programs use, as their firmware documents it: words,
/// comments, G0–G3 (I J K offsets or R), G4, G17–G19, G20/G21, G28, G90/G91, G92 (with E),
/// M82/M83, `#n = value` parameters; per dialect: Marlin's one command per line, its G0 (a G1)
/// and its G4 and G28, Grbl's `$` lines, Mach3's nested comments, program numbers and G41/G42 P
/// (checked as [`Step::Compensated`]). Positions in mm.
struct Reader<'a> {
    dialect: &'static str,
    home: [f64; 4],
    text: &'a [u8],
    /// Machine position (mm, degrees), without offsets.
    position: [f64; 4],
    /// G92 offsets (mm, degrees): program coordinate = position − offset.
    offset: [f64; 4],
    inches: bool,
    relative: bool,
    plane: usize,
    motion: Option<u32>,
    e: f64,
    e_relative: bool,
    params: std::collections::HashMap<u32, f64>,
    /// Mach3's cutter compensation radius (mm) while G41/G42 P is in force.
    compensation: Option<f64>,
}

impl<'a> Reader<'a> {
    fn new(dialect: &'static str, home: [f64; 4], text: &'a [u8]) -> Reader<'a> {
        Reader {
            dialect,
            home,
            text,
            position: home,
            offset: [0.0; 4],
            inches: false,
            relative: false,
            plane: 17,
            motion: None,
            e: 0.0,
            e_relative: false,
            params: std::collections::HashMap::new(),
            compensation: None,
        }
    }

    fn unit(&self, axis: usize) -> f64 {
        if axis < 3 && self.inches { 25.4 } else { 1.0 }
    }

    /// The line without comments (nested parentheses in Marlin and Mach3).
    fn strip(&self, line: &str) -> String {
        let nested = matches!(self.dialect, "marlin" | "mach3");
        let mut out = String::new();
        let mut depth = 0;
        for c in line.chars() {
            match c {
                '(' if depth == 0 || nested => depth += 1,
                ')' if depth > 0 => depth -= 1,
                ';' if depth == 0 => break,
                _ if depth > 0 => {}
                _ => out.push(c),
            }
        }
        out
    }

    /// Words: a letter, then a number or `#n`, spaces anywhere.
    fn words(&self, code: &str) -> Vec<(char, f64)> {
        let squeezed: Vec<char> =
            code.chars().filter(|c| !c.is_whitespace()).map(|c| c.to_ascii_uppercase()).collect();
        let mut words = Vec::new();
        let mut at = 0;
        while at < squeezed.len() {
            let letter = squeezed[at];
            at += 1;
            let start = at;
            if squeezed.get(at) == Some(&'#') {
                at += 1;
                while squeezed.get(at).is_some_and(char::is_ascii_digit) {
                    at += 1;
                }
                let index: u32 =
                    squeezed[start + 1..at].iter().collect::<String>().parse().expect("#n");
                words.push((letter, self.params.get(&index).copied().unwrap_or(0.0)));
                continue;
            }
            while squeezed
                .get(at)
                .is_some_and(|c| c.is_ascii_digit() || matches!(c, '.' | '-' | '+'))
            {
                at += 1;
            }
            let number: String = squeezed[start..at].iter().collect();
            match number.parse::<f64>() {
                Ok(value) => words.push((letter, value)),
                // Marlin's `G28 X`: a letter alone names an axis.
                Err(_) if number.is_empty() => words.push((letter, f64::NAN)),
                Err(_) => {}
            }
        }
        words
    }

    fn read(mut self) -> Vec<(usize, Step)> {
        let text = String::from_utf8_lossy(self.text).into_owned();
        let mut steps = Vec::new();
        for (index, line) in text.lines().enumerate() {
            let number = index + 1;
            let code = self.strip(line);
            let trimmed = code.trim();
            if trimmed.is_empty() || trimmed == "%" {
                continue;
            }
            if self.dialect == "grbl" && trimmed.starts_with('$') {
                continue;
            }
            if let Some((name, value)) = trimmed.split_once('=') {
                let name = name.trim();
                if let Some(index) = name.strip_prefix('#') {
                    let index: u32 = index.trim().parse().expect("#n =");
                    self.params.insert(index, value.trim().parse().expect("#n = number"));
                    continue;
                }
            }
            let mut words = self.words(trimmed);
            if self.dialect == "mach3" && words.len() == 1 && words[0].0 == 'O' {
                continue;
            }
            if self.dialect == "marlin" {
                if words.iter().any(|(letter, _)| *letter == 'A') {
                    // MakerBot's flavour: A is the extruder.
                    for word in &mut words {
                        if word.0 == 'A' {
                            word.0 = 'E';
                        }
                    }
                }
                // One command per line: the first G, M or T; a line without one is skipped.
                let words_no_n: Vec<(char, f64)> =
                    words.iter().copied().filter(|(letter, _)| *letter != 'N').collect();
                match words_no_n.first() {
                    Some(('G' | 'M' | 'T', _)) => {}
                    _ => continue,
                }
                let first = words_no_n[0];
                words = std::iter::once(first)
                    .chain(words_no_n[1..].iter().copied().filter(|(l, _)| !matches!(l, 'G' | 'M')))
                    .collect();
            }
            let before = steps.len();
            self.block(number, &words, &mut steps);
            if let Some(radius) = self.compensation {
                for (_, step) in &mut steps[before..] {
                    if let Step::Linear { end, .. } | Step::Arc { end, .. } = *step {
                        *step = Step::Compensated { end, radius };
                    }
                }
            }
        }
        steps
    }

    fn block(&mut self, line: usize, words: &[(char, f64)], steps: &mut Vec<(usize, Step)>) {
        let marlin = self.dialect == "marlin";
        let word = |letter: char| words.iter().find(|(l, _)| *l == letter).map(|(_, v)| *v);
        let g: Vec<u32> = words
            .iter()
            .filter(|(l, _)| *l == 'G')
            .map(|(_, v)| (v * 10.0).round() as u32)
            .collect();
        let m: Vec<u32> = words.iter().filter(|(l, _)| *l == 'M').map(|(_, v)| *v as u32).collect();
        if marlin && m.iter().any(|&code| code == 82 || code == 83) {
            self.e_relative = m.contains(&83);
            return;
        }
        if marlin && !m.is_empty() {
            return;
        }
        for &code in &g {
            match code {
                // Mach3's G41/G42 P: the compensation radius (Mach3 only; G40 ends it).
                410 | 420 if self.dialect == "mach3" => {
                    self.compensation = word('P').map(|radius| radius * self.unit(0));
                }
                400 => self.compensation = None,
                170 | 180 | 190 => self.plane = code as usize / 10,
                200 => self.inches = true,
                210 => self.inches = false,
                900 | 910 => {
                    self.relative = code == 910;
                    if marlin {
                        self.e_relative = self.relative;
                    }
                }
                _ => {}
            }
        }
        let axes = ['X', 'Y', 'Z', 'C'];
        let given: Vec<Option<f64>> = axes.iter().map(|&letter| word(letter)).collect();
        let target = |this: &Self| -> [f64; 4] {
            std::array::from_fn(|axis| match given[axis] {
                None => this.position[axis],
                Some(v) if this.relative => this.position[axis] + v * this.unit(axis),
                Some(v) => v * this.unit(axis) + this.offset[axis],
            })
        };
        if g.contains(&40) {
            let seconds = if marlin {
                word('S').or(word('P').map(|ms| ms / 1000.0)).unwrap_or(0.0)
            } else {
                word('P').expect("G4 P")
            };
            steps.push((line, Step::Dwell { seconds }));
            return;
        }
        if g.contains(&920) {
            for (axis, value) in given.iter().enumerate() {
                if let Some(v) = value {
                    self.offset[axis] = self.position[axis] - v * self.unit(axis);
                }
            }
            if let Some(e) = word('E') {
                self.e = e * self.unit(0);
            }
            return;
        }
        if g.contains(&280) {
            let named = given.iter().any(Option::is_some);
            if !marlin {
                let through = target(self);
                steps.push((line, Step::Rapid { end: through, extrude: None }));
                self.position = through;
            }
            let mut end = self.position;
            for axis in 0..4 {
                if !named
                    || given[axis].is_some()
                    || (marlin && words.iter().any(|(l, _)| *l == axes[axis]))
                {
                    end[axis] = self.home[axis];
                }
            }
            steps.push((line, Step::Rapid { end, extrude: None }));
            self.position = end;
            return;
        }
        let motion_code = g.iter().copied().find(|code| matches!(code, 0 | 10 | 20 | 30));
        if let Some(code) = motion_code {
            self.motion = Some(code);
        }
        let axis_words = given.iter().any(Option::is_some);
        // Marlin moves only for axis or E words (`G1 F1500` sets the feed rate).
        let moves = if marlin {
            motion_code.is_some() && (axis_words || word('E').is_some())
        } else {
            motion_code.is_some() || axis_words
        };
        let Some(motion) = self.motion.filter(|_| moves) else { return };
        let end = target(self);
        let extrude = if (motion_code.is_some() || given.iter().any(Option::is_some)) && marlin {
            word('E').map(|e| {
                let value = e * self.unit(0);
                let delta = if self.e_relative { value } else { value - self.e };
                self.e += delta;
                delta
            })
        } else {
            None
        };
        let step = match motion {
            // Marlin's G0 is its G1 (G0_G1: the same move, at the feed rate in force).
            0 if marlin => Step::Linear { end, extrude },
            0 => Step::Rapid { end, extrude },
            10 => Step::Linear { end, extrude },
            _ => {
                let (first, second) = match self.plane {
                    17 => (0, 1),
                    18 => (2, 0),
                    _ => (1, 2),
                };
                let offsets = [word('I'), word('J'), word('K')];
                let center = if word('R').is_some() {
                    None
                } else {
                    let offset = |axis: usize| offsets[axis].unwrap_or(0.0) * self.unit(axis);
                    Some([
                        self.position[first] + offset(first),
                        self.position[second] + offset(second),
                    ])
                };
                Step::Arc { end, center, clockwise: motion == 20 }
            }
        };
        steps.push((line, step));
        self.position = end;
    }
}

#[test]
fn the_reader_knows_the_firmware_rules_it_checks() {
    let home = [0.0, 400.0, 100.0, 0.0];
    let marlin = Reader::new(
        "marlin",
        home,
        b"M83\nG1 X10 E2 F100\nG4 P500\nG4 S2\nG28 X\nG91 G0 Z5\nM104 S200\nG92 E0\n",
    )
    .read();
    assert_eq!(
        marlin,
        [
            (2, Step::Linear { end: [10.0, 400.0, 100.0, 0.0], extrude: Some(2.0) }),
            (3, Step::Dwell { seconds: 0.5 }),
            (4, Step::Dwell { seconds: 2.0 }),
            (5, Step::Rapid { end: [0.0, 400.0, 100.0, 0.0], extrude: None }),
        ]
    );
    let grbl =
        Reader::new("grbl", home, b"$H\nG20 G1 X1 F10\nG21 X10\nG2 X20 Y400 I5 J0 K3\nG4 P1.5\n")
            .read();
    assert_eq!(
        grbl,
        [
            (2, Step::Linear { end: [25.4, 400.0, 100.0, 0.0], extrude: None }),
            (3, Step::Linear { end: [10.0, 400.0, 100.0, 0.0], extrude: None }),
            (
                4,
                Step::Arc {
                    end: [20.0, 400.0, 100.0, 0.0],
                    center: Some([15.0, 400.0]),
                    clockwise: true
                }
            ),
            (5, Step::Dwell { seconds: 1.5 }),
        ]
    );
}
