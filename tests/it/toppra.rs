//! toppra (PyPI) as an independent reference for `--profile optimal` (issue 16): the programs of
//! `data/programs/` and the demo job, on the default and the weak-motor robot, timed by `biscara
//! joints --profile optimal` and, move by move, by `tests/toppra/compare.py`. Our duration must be
//! at most 1.03 × toppra's, plus one time step per move (we round every move up to whole steps).
//!
//! The moves go to toppra as joints sampled by IK along each move (every 0.25 mm of path,
//! 0.25° of C and 1° of turning, at least 50 samples), with the path coordinate (mm) and C
//! (degrees) as two more "joints" carrying the feed or rapid speed, the path acceleration and
//! C's limits (SPEC §1.3, §6), from the robot file: nothing of our planner is used.
//!
//! Needs `python3` with the `toppra` package (`.ci/run` installs it from PyPI). When either is
//! missing the test prints why and passes, except under `CI=true`, where it fails.

use std::io::Write as _;
use std::path::Path;
use std::process::Command;

use biscara::interpolate::Segment;
use biscara::kinematics::{Kinematics, Pose, Robot, Theta3Unwrapper};
use biscara::motion::{MotionKind, read_jsonl};

use crate::util::{biscara, repo_root, temp_dir};

/// Time step of the trajectories compared, s.
const DT: f64 = 0.001;
/// Our duration may exceed toppra's by this factor (issue 16), plus a step per move.
const FACTOR: f64 = 1.03;

/// Whether `python3 -c "import toppra"` works.
fn toppra_available() -> bool {
    Command::new("python3")
        .args(["-c", "import toppra"])
        .output()
        .is_ok_and(|output| output.status.success())
}

fn skip_or_fail(what: &str) {
    let in_ci = std::env::var("CI").is_ok_and(|value| value == "true");
    assert!(!in_ci, "{what} is missing, and CI=true requires it (pip install toppra)");
    #[allow(clippy::print_stderr)]
    {
        eprintln!("SKIPPED: toppra comparison: {what} not found (pip install toppra)");
    }
}

/// The duration of a joint CSV: its last row's time.
fn duration_of(csv: &Path) -> f64 {
    let text = std::fs::read_to_string(csv).expect("joint CSV");
    let last = text.lines().last().expect("rows");
    last.split(',').next().and_then(|t| t.parse().ok()).expect("time")
}

/// Writes the moves of the inter-file `jsonl` for compare.py into `out`; returns the number of
/// moves and the seconds of dwells (rounded up to whole steps, as the interpolator holds them).
fn write_moves(jsonl: &Path, robot: &Robot, out: &Path) -> (usize, f64) {
    let model = Kinematics::new(robot).expect("robot");
    let reader = std::io::BufReader::new(std::fs::File::open(jsonl).expect("inter-file"));
    let mut file = std::fs::File::create(out).expect("moves file");
    let mut pose = model.home().to_degrees();
    let mut theta3 = Theta3Unwrapper::new();
    let (mut moves, mut holds) = (0, 0.0);
    let [t1, t2, t3, d4] = robot.joint_max_velocity.to_array();
    let [a1, a2, a3, a4] = robot.joint_max_acceleration.to_array();
    let motion_limits = robot.motion;
    for motion in read_jsonl(reader) {
        let motion = motion.expect("motion");
        let (segment, feed) = match motion.kind {
            MotionKind::Rapid { end } => (Segment::line(pose, end), None),
            MotionKind::Linear { end, feed } => (Segment::line(pose, end), Some(feed.mm_per_min)),
            MotionKind::Arc { end, center, plane, clockwise, turns, feed } => {
                (Segment::arc(pose, end, center, plane, clockwise, turns), Some(feed.mm_per_min))
            }
            MotionKind::Dwell { seconds } => {
                holds += (seconds / DT * (1.0 - 1e-9)).ceil() * DT;
                continue;
            }
            _ => continue,
        };
        pose = segment.end();
        let (length, rotation) = (segment.length(), segment.rotation().abs());
        if length < 1e-12 && rotation < 1e-12 {
            continue;
        }
        moves += 1;
        // Columns: θ1, θ2, θ3 (rad), d4 (mm), then the path (mm) and C (degrees) when they move.
        let mut vlim = vec![t1.to_radians(), t2.to_radians(), t3.to_radians(), d4];
        let mut alim = vec![a1.to_radians(), a2.to_radians(), a3.to_radians(), a4];
        let path_speed = match feed {
            Some(mm_per_min) if length >= 1e-12 => mm_per_min / 60.0,
            _ => motion_limits.rapid_velocity,
        };
        let rotation_speed = match feed {
            // LinuxCNC: a move with no XYZ length runs its feed in degrees/min of C.
            Some(per_min) if length < 1e-12 => (per_min / 60.0).min(motion_limits.rapid_rotation),
            _ => motion_limits.rapid_rotation,
        };
        if length >= 1e-12 {
            vlim.push(path_speed);
            alim.push(motion_limits.acceleration);
        }
        if rotation >= 1e-12 {
            vlim.push(rotation_speed);
            alim.push(motion_limits.rotation_acceleration);
        }
        let samples = (length / 0.25 + rotation / 0.25 + segment.turning()).ceil().max(50.0);
        let samples = samples as usize;
        let (mut ss, mut qs) = (Vec::new(), Vec::new());
        for k in 0..=samples {
            let s = k as f64 / samples as f64;
            let [x, y, z, c] = segment.point(s);
            let mut solution = model.inverse(&Pose::from_degrees(x, y, z, c)).expect("IK");
            theta3.apply(&mut solution);
            let mut row = solution.joints.to_array().to_vec();
            if length >= 1e-12 {
                row.push(s * length);
            }
            if rotation >= 1e-12 {
                row.push(c);
            }
            ss.push(s);
            qs.push(row);
        }
        let record = serde_json::json!({
            "line": motion.line, "s": ss, "q": qs, "vlim": vlim, "alim": alim,
        });
        writeln!(file, "{record}").expect("write move");
    }
    (moves, holds)
}

#[test]
fn optimal_is_within_3_percent_of_toppra() {
    if !toppra_available() {
        skip_or_fail("python3 with the toppra package");
        return;
    }
    let dir = temp_dir("toppra");
    let root = repo_root();
    biscara(&dir, &["demo", "demo"]).success();
    let programs = [
        ("data/programs/arcs_and_offsets.ngc", None),
        ("data/programs/engraving_arcs.ngc", Some("-75,300,20,0")),
        ("data/programs/pick_place_inch.ngc", None),
        ("demo job.ngc", None),
    ];
    let script = root.join("tests/toppra/compare.py");
    let mut report = String::new();
    for robot_name in ["default", "weak-motors"] {
        let robot_file = root.join(format!("data/robots/{robot_name}.json"));
        let robot_path = robot_file.to_str().expect("path");
        let robot =
            Robot::from_json(&std::fs::read_to_string(&robot_file).expect("robot")).expect("robot");
        for (program, origin) in programs {
            let source = if program.starts_with("demo ") {
                dir.join("demo/job.ngc")
            } else {
                root.join(program)
            };
            let source = source.to_str().expect("path");
            let mut interpret = vec!["--robot", robot_path, "interpret", source, "-o", "p.jsonl"];
            if let Some(origin) = origin {
                interpret.extend(["--origin", origin]);
            }
            biscara(&dir, &interpret).success();
            let mut durations = Vec::new();
            for profile in ["trapezoid", "optimal"] {
                let args = [
                    "--robot",
                    robot_path,
                    "joints",
                    "--profile",
                    profile,
                    "p.jsonl",
                    "-o",
                    "q.csv",
                ];
                biscara(&dir, &args).success();
                durations.push(duration_of(&dir.join("q.csv")));
            }
            let (moves, holds) =
                write_moves(&dir.join("p.jsonl"), &robot, &dir.join("moves.jsonl"));
            let output = Command::new("python3")
                .arg(&script)
                .arg(dir.join("moves.jsonl"))
                .output()
                .expect("run python3");
            let stdout = String::from_utf8_lossy(&output.stdout);
            assert!(
                output.status.success(),
                "compare.py failed ({})\n{stdout}\n{}",
                output.status,
                String::from_utf8_lossy(&output.stderr)
            );
            let toppra: f64 = stdout
                .lines()
                .find_map(|line| line.strip_prefix("total "))
                .and_then(|total| total.parse().ok())
                .expect("total");
            let toppra = toppra + holds;
            let (trapezoid, optimal) = (durations[0], durations[1]);
            report.push_str(&format!(
                "{robot_name:12} {program:38} trapezoid {trapezoid:8.3} s  optimal {optimal:8.3} s  \
                 toppra {toppra:8.3} s  optimal/toppra {:.4}\n",
                optimal / toppra
            ));
            assert!(
                optimal <= FACTOR * toppra + moves as f64 * DT,
                "{program} on {robot_name}: optimal {optimal} s > {FACTOR} × toppra {toppra} s \
                 + {moves} steps"
            );
        }
    }
    #[allow(clippy::print_stderr)]
    {
        eprintln!("toppra comparison (dt {DT} s):\n{report}");
    }
}
