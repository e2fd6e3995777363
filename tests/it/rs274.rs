//! LinuxCNC's standalone interpreter `rs274` (Debian's `linuxcnc-uspace`), run on a G-code file
//! and its canonical-machining output read back as motions in absolute millimetres — the
//! reference that `interpret` is compared with.
//!
//! Invocation: `HOME=DIR rs274 -t DIR/tools.tbl -g PROGRAM OUTPUT < /dev/null` (`-g`: batch, no
//! prompts; a HOME of its own because rs274 maps `$HOME/.tool.mmap`; a tool table holding tools
//! 0–999, because `interpret` has no tool table — T words have no effect (docs/gcode.md) — and the
//! standalone's default table refuses `T5`). It writes one
//! canonical command a line (`STRAIGHT_FEED(x, y, z, a, b, c)`, `ARC_FEED(…)`, …) to OUTPUT,
//! positions in program units relative to the active offsets, 4 decimals; errors go to stderr
//! (the message, then the offending line) with exit code 1. rs274 starts at 0,0,0 with the G28
//! and G30 positions at 0.

use std::path::Path;
use std::process::{Command, Stdio};
use std::sync::Mutex;

use biscara::motion::{Feed, Motion, MotionKind, Plane};

/// Where `rs274` is looked for.
pub const RS274: &str = "/usr/bin/rs274";

/// Whether `rs274` is installed. When it is not, a test prints why it skips — and fails under
/// `CI=true`, where `.ci/run` installs it.
pub fn available(test: &str) -> bool {
    if Path::new(RS274).exists() {
        return true;
    }
    let ci = std::env::var("CI").is_ok_and(|value| value == "true");
    assert!(!ci, "{test}: {RS274} is missing under CI=true (apt-get install linuxcnc-uspace)");
    #[allow(clippy::print_stderr)]
    {
        eprintln!("{test}: skipped: {RS274} not installed (apt-get install linuxcnc-uspace)");
    }
    false
}

/// What rs274 made of a program.
pub use crate::record::{Outcome, own_ini, own_table};

pub fn run(program: &Path, dir: &Path) -> Outcome {
    static LOCK: Mutex<()> = Mutex::new(());
    let _guard = LOCK.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
    let output = dir.join("rs274.out");
    let mut tools = dir.join("tools.tbl");
    if let Some(table) = own_table(program) {
        // The program's own table (mm), in the standalone's machine units (inches).
        tools = dir.join("own-tools.tbl");
        let text: String = table
            .entries()
            .iter()
            .map(|e| {
                let inch = |mm: f64| mm / 25.4;
                format!(
                    "T{} P{} X{:.12} Y{:.12} Z{:.12} C{:.12} D{:.12} I{} J{} Q{}\n",
                    e.tool,
                    e.pocket,
                    inch(e.offset[0]),
                    inch(e.offset[1]),
                    inch(e.offset[2]),
                    e.offset[3],
                    inch(e.diameter),
                    e.front_angle,
                    e.back_angle,
                    e.orientation
                )
            })
            .collect();
        std::fs::write(&tools, text).expect("write the tool table");
    } else if !tools.exists() {
        let table: String = (1..1000).map(|tool| format!("T{tool} P{tool} Z0 D0\n")).collect();
        std::fs::write(&tools, table).expect("write the tool table");
    }
    let ini = own_ini(program);
    let mut attempt = 0;
    let run = loop {
        let _ = std::fs::remove_file(&output);
        let mut command = Command::new(RS274);
        if let Some(ini) = &ini {
            command.arg("-i").arg(ini);
        }
        let child = command
            .arg("-t")
            .arg(&tools)
            .arg("-g")
            .arg(program)
            .arg(&output)
            // File subroutines are found in the current folder.
            .current_dir(program.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(dir))
            .env("HOME", dir)
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .expect("run rs274");
        let Some(run) = bounded(child, &output) else {
            let _ = std::fs::remove_file(&output);
            return Outcome::Error {
                message: format!(
                    "rs274 ran away (more than {RUNAWAY_SECONDS} s or {} MiB of output)",
                    RUNAWAY_BYTES >> 20
                ),
                before: Vec::new(),
            };
        };
        attempt += 1;
        if run.status.code().is_some() {
            break run;
        }
        assert!(attempt < 200, "rs274 keeps dying on {}: {}", program.display(), run.status);
        std::thread::sleep(std::time::Duration::from_millis(50));
    };
    let canon = std::fs::read_to_string(&output).unwrap_or_default();
    let motions = parse(&canon);
    if run.status.success() {
        return Outcome::Motions(motions);
    }
    let stderr = String::from_utf8_lossy(&run.stderr);
    let message = stderr
        .lines()
        .find(|line| !line.trim().is_empty() && line.trim() != "executing")
        .map(str::to_owned)
        .unwrap_or_else(|| format!("(no message; {}; stderr {stderr:?})", run.status));
    Outcome::Error { message, before: motions }
}

/// How long rs274 may run, and how much it may write, before it is stopped as running away (an
/// endless loop, such as LinuxCNC's own test `g71-endless-loop` makes this rs274 do).
const RUNAWAY_SECONDS: u64 = 30;
const RUNAWAY_BYTES: u64 = 256 << 20;

/// Waits for `child`, reading its standard error; `None` (the child killed) when it runs past
/// [`RUNAWAY_SECONDS`] or its `output` grows past [`RUNAWAY_BYTES`].
fn bounded(mut child: std::process::Child, output: &Path) -> Option<std::process::Output> {
    use std::io::Read;
    let mut stderr = child.stderr.take().expect("piped stderr");
    // Read on another thread, so that a chatty rs274 never blocks on a full pipe.
    let reader = std::thread::spawn(move || {
        let mut text = Vec::new();
        let _ = stderr.read_to_end(&mut text);
        text
    });
    let start = std::time::Instant::now();
    let mut pause = std::time::Duration::from_micros(200);
    let status = loop {
        if let Some(status) = child.try_wait().expect("wait for rs274") {
            break status;
        }
        let size = std::fs::metadata(output).map_or(0, |meta| meta.len());
        if start.elapsed().as_secs() >= RUNAWAY_SECONDS || size > RUNAWAY_BYTES {
            let _ = child.kill();
            let _ = child.wait();
            let _ = reader.join();
            return None;
        }
        std::thread::sleep(pause);
        pause = (pause * 2).min(std::time::Duration::from_millis(20));
    };
    let stderr = reader.join().unwrap_or_default();
    Some(std::process::Output { status, stdout: Vec::new(), stderr })
}

/// The arguments of `NAME(a, b, …)` as numbers (non-numbers skipped).
fn numbers(arguments: &str) -> Vec<f64> {
    arguments.split([',', ' ']).filter_map(|part| part.trim().parse::<f64>().ok()).collect()
}

/// Reads rs274's canonical commands into motions, applying the offsets and units as LinuxCNC's
/// canon does (offsets and feeds converted to mm when they are set).
pub fn parse(canon: &str) -> Vec<Motion> {
    let mut motions = Vec::new();
    let mut factor = 1.0;
    let mut g5x = [0.0; 4];
    let mut g92 = [0.0; 4];
    let mut tlo = [0.0; 4];
    let mut plane = Plane::Xy;
    // SET_XY_ROTATION: the system's rotation about Z, degrees (canon: rot(p + g92) + g5x + tlo).
    let mut rotation = 0.0_f64;
    let mut feed = 0.0;
    // Where rs274's canon (`saicanon.cc`) is, x y z c in program units: it follows the moves,
    // the G5x and G92 offsets and the units, not the tool length offset (the start of a
    // probe's backoff).
    let mut canon_at = [0.0_f64; 4];
    // rs274's canon starts in CANON_CONTINUOUS with no tolerance (LinuxCNC's G64 by default);
    // canned cycles restore it after their exact-path moves.
    let mut blend = Some(0.0);
    let lines: Vec<&str> = canon
        .lines()
        .map(|line| {
            // `   12 N..... CALL(…)` or `   12 N30    CALL(…)`
            let rest = line.trim_start();
            let rest = rest.split_once(' ').map_or(rest, |(_, rest)| rest).trim_start();
            let rest = rest.split_once(' ').map_or(rest, |(_, rest)| rest);
            rest.trim()
        })
        .collect();
    let push = |motions: &mut Vec<Motion>, kind: MotionKind, blend: Option<f64>| {
        let blend = kind.end().and(blend);
        motions.push(Motion { blend, ..Motion::new(0, kind) });
    };
    for (index, line) in lines.iter().enumerate() {
        let (name, arguments) = match line.find('(') {
            Some(open) => (&line[..open], line[open + 1..].trim_end_matches(')')),
            None => (*line, ""),
        };
        let values = numbers(arguments);
        let turn = |x: f64, y: f64| -> [f64; 2] {
            let t = rotation.to_radians();
            [x * t.cos() - y * t.sin(), x * t.sin() + y * t.cos()]
        };
        let pose = |v: &[f64]| -> [f64; 4] {
            let [x, y] = turn(v[0] * factor + g92[0], v[1] * factor + g92[1]);
            [
                x + g5x[0] + tlo[0],
                y + g5x[1] + tlo[1],
                v[2] * factor + g5x[2] + g92[2] + tlo[2],
                v[5] + g5x[3] + g92[3] + tlo[3],
            ]
        };
        match name {
            "USE_LENGTH_UNITS" => {
                let old = factor;
                factor = if arguments.contains("INCHES") { 25.4 } else { 1.0 };
                for value in &mut canon_at[..3] {
                    *value *= old / factor;
                }
            }
            "SET_G5X_OFFSET" => {
                let new = [values[1] * factor, values[2] * factor, values[3] * factor, values[6]];
                shift_canon(&mut canon_at, g5x, new, factor);
                g5x = new;
            }
            "USE_TOOL_LENGTH_OFFSET" => {
                tlo = [values[0] * factor, values[1] * factor, values[2] * factor, values[5]];
            }
            "SET_XY_ROTATION" => rotation = values[0],
            "SET_G92_OFFSET" => {
                let new = [values[0] * factor, values[1] * factor, values[2] * factor, values[5]];
                shift_canon(&mut canon_at, g92, new, factor);
                g92 = new;
            }
            "SELECT_PLANE" => {
                plane = if arguments.ends_with("XZ") {
                    Plane::Xz
                } else if arguments.ends_with("YZ") {
                    Plane::Yz
                } else {
                    Plane::Xy
                };
            }
            "SET_FEED_RATE" => feed = values[0] * factor,
            // `(CANON_CONTINUOUS, tolerance)` under G64, `(CANON_EXACT_PATH)` under G61,
            // `(CANON_EXACT_STOP)` under G61.1.
            "SET_MOTION_CONTROL_MODE" => {
                blend = arguments
                    .starts_with("CANON_CONTINUOUS")
                    .then(|| values.first().copied().unwrap_or(0.0) * factor);
            }
            "STRAIGHT_TRAVERSE" => {
                canon_at = [values[0], values[1], values[2], values[5]];
                push(&mut motions, MotionKind::Rapid { end: pose(&values) }, blend)
            }
            "STRAIGHT_FEED" => {
                canon_at = [values[0], values[1], values[2], values[5]];
                push(
                    &mut motions,
                    MotionKind::Linear {
                        end: pose(&values),
                        feed: Feed { mm_per_min: feed, inverse_time: false },
                    },
                    blend,
                );
            }
            "ARC_FEED" => {
                // first_end, second_end, first_centre, second_centre, rotation, axis_end, a, b, c
                let [first, second, normal] = plane.axes();
                let mut program = [0.0; 6];
                program[first] = values[0];
                program[second] = values[1];
                program[normal] = values[5];
                program[5] = values[8];
                canon_at = [program[0], program[1], program[2], program[5]];
                let end = pose(&program);
                if rotation != 0.0 && plane != Plane::Xy {
                    // In a tilted plane (LinuxCNC's canon turns the arc's basis vectors): our
                    // straight moves stand for it, its end is checked (see `expand_splines`).
                    let feed = Feed { mm_per_min: feed, inverse_time: false };
                    let kind = MotionKind::Linear { end, feed };
                    let blend = kind.end().and(blend);
                    let tilted = Motion { blend, extrude: Some(f64::NAN), ..Motion::new(0, kind) };
                    motions.push(tilted);
                    continue;
                }
                // The centre is turned as the points are.
                let mut point = [0.0; 6];
                point[first] = values[2];
                point[second] = values[3];
                let centre = pose(&point);
                let center = [centre[first], centre[second]];
                let rotation = values[4];
                push(
                    &mut motions,
                    MotionKind::Arc {
                        end,
                        center,
                        plane,
                        clockwise: rotation < 0.0,
                        turns: rotation.abs() as u32,
                        feed: Feed { mm_per_min: feed, inverse_time: false },
                    },
                    blend,
                );
            }
            // A G5/G5.1 spline: rs274's canon prints the number of control points, not where the
            // curve goes. A linear move with an end that is not a number stands for it; see
            // `expand_splines`.
            "NURBS_FEED" => push(
                &mut motions,
                MotionKind::Linear {
                    end: [f64::NAN; 4],
                    feed: Feed { mm_per_min: feed, inverse_time: false },
                },
                blend,
            ),
            // rs274's canon (`saicanon.cc`) goes to the probe's end point, where no probe
            // trips, and stands 0.254 mm (0.01 inch) back from it along the move: our two
            // straight moves.
            "STRAIGHT_PROBE" => {
                let feed = Feed { mm_per_min: feed, inverse_time: false };
                push(&mut motions, MotionKind::Linear { end: pose(&values), feed }, blend);
                let distance =
                    (0..3).map(|axis| (canon_at[axis] - values[axis]).powi(2)).sum::<f64>();
                let mut stop = values.clone();
                if distance != 0.0 {
                    let (distance, backoff) = (distance.sqrt(), 0.254 / factor);
                    for axis in 0..3 {
                        stop[axis] += backoff * (canon_at[axis] - values[axis]) / distance;
                    }
                    push(&mut motions, MotionKind::Linear { end: pose(&stop), feed }, blend);
                }
                canon_at = [stop[0], stop[1], stop[2], stop[5]];
            }
            "DWELL" => push(&mut motions, MotionKind::Dwell { seconds: values[0] }, None),
            "START_SPINDLE_CLOCKWISE" => push(&mut motions, MotionKind::Pick, None),
            "START_SPINDLE_COUNTERCLOCKWISE" => push(&mut motions, MotionKind::Place, None),
            "STOP_SPINDLE_TURNING" => {
                // M2/M30 reset the spindle (then SET_SPINDLE_MODE): not a programmed M5.
                let reset =
                    lines.get(index + 1).is_some_and(|next| next.starts_with("SET_SPINDLE_MODE"));
                if !reset {
                    push(&mut motions, MotionKind::GripperOff, None);
                }
            }
            "PROGRAM_STOP" | "OPTIONAL_PROGRAM_STOP" => push(&mut motions, MotionKind::Pause, None),
            "PROGRAM_END" => {
                push(&mut motions, MotionKind::End, None);
                break;
            }
            _ => {}
        }
    }
    motions
}

/// rs274's canon when an offset (mm, degrees) changes from `old` to `new`: the same point,
/// in the new coordinates (`canon_at` in program units: `factor` mm each).
fn shift_canon(canon_at: &mut [f64; 4], old: [f64; 4], new: [f64; 4], factor: f64) {
    for axis in 0..4 {
        let unit = if axis == 3 { 1.0 } else { factor };
        canon_at[axis] += (old[axis] - new[axis]) / unit;
    }
}

/// Whether `motion` stands for one of rs274's `NURBS_FEED`s (see [`parse`]).
pub fn is_spline(motion: &Motion) -> bool {
    matches!(motion.kind, MotionKind::Linear { end, .. } if end[0].is_nan())
}

/// Whether `motion` stands for one of rs274's arcs in a tilted plane (an XZ or YZ arc of a
/// rotated system, see [`parse`]): its end is known, its points are not compared.
fn is_tilted_arc(motion: &Motion) -> bool {
    motion.extrude.is_some_and(f64::is_nan)
}

/// rs274's motions with each spline (`NURBS_FEED`) replaced by the straight moves `ours` made
/// of it: the moves of one line that stand where the spline stands in the sequence, with
/// rs274's feed and blend. Their ends are ours (rs274 does not print the curve's points); where
/// the curve ends is checked by the motions after it, which start there (a program ends with
/// moves that show the position). A spline with no straight move of ours in its place is left
/// as it is, and so differs. An arc in a tilted plane is replaced the same way, but its last
/// move keeps rs274's end, so that where it ends is compared too (that its points lie on the
/// tilted arc is `biscara-gcode`'s test).
pub fn expand_splines(ours: &[Motion], theirs: &[Motion]) -> Vec<Motion> {
    let mut expanded = Vec::with_capacity(theirs.len());
    let mut at = 0;
    for motion in theirs {
        let ours_here = ours.get(at);
        let curve = is_spline(motion) || is_tilted_arc(motion);
        match (curve, motion.kind, ours_here) {
            (true, MotionKind::Linear { feed, end: their_end }, Some(first))
                if matches!(first.kind, MotionKind::Linear { .. }) =>
            {
                let line = first.line;
                while let Some(our) = ours.get(at)
                    && our.line == line
                    && let MotionKind::Linear { end, .. } = our.kind
                {
                    let last = ours.get(at + 1).is_none_or(|next| next.line != line);
                    let end = if last && is_tilted_arc(motion) { their_end } else { end };
                    let kind = MotionKind::Linear { end, feed };
                    expanded.push(Motion { kind, extrude: None, ..*motion });
                    at += 1;
                }
            }
            _ => {
                expanded.push(*motion);
                at += 1;
            }
        }
    }
    expanded
}
