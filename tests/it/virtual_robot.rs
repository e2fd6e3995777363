//! `biscara check`, `workspace`, `plot` and `--fit`: the virtual robot from the command line.

use serde_json::Value;

use crate::golden::check_golden;
use crate::util::{Run, biscara, repo_root, temp_dir};

/// The default robot's home pose.
const HOME_Y: f64 = 460.798724079689;

fn json(run: &Run) -> Value {
    serde_json::from_str(&run.stdout).unwrap_or_else(|err| panic!("not JSON: {err}\n{run}"))
}

fn problems<'a>(report: &'a Value, kind: &str) -> Vec<&'a Value> {
    report["problems"]
        .as_array()
        .expect("problems")
        .iter()
        .filter(|problem| problem["kind"] == kind)
        .collect()
}

/// Rows of a path CSV: `[t, x, y, z, c]`.
fn path_rows(text: &str) -> Vec<Vec<f64>> {
    text.lines()
        .skip(1)
        .map(|line| line.split(',').map(|f| f.parse().expect("number")).collect())
        .collect()
}

/// Writes `program` as `job.jsonl` (and any other files) into a fresh folder.
fn setup(name: &str, files: &[(&str, &str)]) -> std::path::PathBuf {
    let dir = temp_dir(name);
    for (file, text) in files {
        std::fs::write(dir.join(file), text).expect("write test file");
    }
    dir
}

/// The path CSV of `job.jsonl` with the same options, to find times independently of check.
fn path_of(dir: &std::path::Path, extra: &[&str]) -> Vec<Vec<f64>> {
    let mut args = vec!["interpolate", "job.jsonl"];
    args.extend_from_slice(extra);
    path_rows(&biscara(dir, &args).success().stdout)
}

#[track_caller]
fn assert_time(problem: &Value, expected: f64) {
    let t = problem["t_s"].as_f64().expect("t_s");
    assert!((t - expected).abs() < 1e-9, "expected t = {expected}, got {problem:#}");
}

const BOX_PROGRAM: &str = r#"{"line":1,"kind":"rapid","end":[0.0,400.0,50.0,0.0]}
{"line":2,"kind":"linear","end":[100.0,400.0,50.0,0.0],"feed":3000.0}
{"line":3,"kind":"linear","end":[100.0,300.0,50.0,0.0],"feed":3000.0}
{"line":4,"kind":"end"}
"#;

#[test]
fn a_box_in_the_path_is_a_scene_collision_at_its_line_and_time() {
    // The gripper (radius 20, z 50..90) moves along y = 400 on line 2; the box's face is at x = 60.
    let scene = r#"{"boxes": [{"name": "fixture", "min": [60, 380, 0], "max": [80, 420, 60]}]}"#;
    let dir = setup("check-scene", &[("job.jsonl", BOX_PROGRAM), ("cell.json", scene)]);
    let run = biscara(&dir, &["check", "job.jsonl", "--scene", "cell.json", "--json"]);
    run.expect_code(1).stderr_has("the check found 1 problem");
    let report = json(&run);
    assert_eq!(report["ok"], false);
    let hits = problems(&report, "scene_collision");
    assert_eq!(hits.len(), 1, "{report:#}");
    let hit = hits[0];
    assert_eq!(hit["line"], 2, "{hit:#}");
    assert_eq!(hit["subject"], "gripper in fixture");
    // Expected: the first sample of line 2 closer than 20 mm to the face, from the path CSV.
    let path = path_of(&dir, &[]);
    let first = path.iter().find(|row| row[1] > 40.0 + 1e-9 && row[2] == 400.0).expect("row");
    assert_time(hit, first[0]);
    // It lasts until the gripper is 20 mm past the far face (x = 100, where line 2 ends).
    let last = path.iter().rev().find(|row| row[1] < 100.0 - 1e-9 && row[2] == 400.0).expect("row");
    assert!((hit["t_end_s"].as_f64().unwrap() - last[0]).abs() < 1e-9, "{hit:#}");
    assert_eq!(hit["line_end"], 2);
    assert!(hit["samples"].as_u64().unwrap() > 1000, "{hit:#}");
    // Text output names FILE:LINE.
    let text = biscara(&dir, &["check", "job.jsonl", "--scene", "cell.json"]);
    text.expect_code(1);
    assert!(text.stdout.contains("job.jsonl:2: scene_collision (gripper in fixture)"), "{text}");
}

#[test]
fn distal_links_folded_onto_each_other_are_a_self_collision() {
    // Elbows-in working mode "-+": near the top of the workspace the elbows meet and the distal
    // links fold onto each other. Line 2 drives the platform from y = 380 up to y = 460 (on the
    // way it passes poses beyond a type-2 singularity, reported as unreachable, then comes back
    // into the robot's assembly mode with the elbows less than a link width apart).
    let robot = r#"{"working_mode": "-+"}"#;
    let program = r#"{"line":1,"kind":"rapid","end":[-20.0,380.0,50.0,0.0]}
{"line":2,"kind":"linear","end":[-20.0,460.0,50.0,0.0],"feed":1200.0}
{"line":3,"kind":"end"}
"#;
    let dir = setup("check-self", &[("job.jsonl", program), ("robot.json", robot)]);
    let run = biscara(&dir, &["--robot", "robot.json", "check", "job.jsonl", "--json"]);
    run.expect_code(1);
    let report = json(&run);
    let folded: Vec<_> = problems(&report, "self_collision")
        .into_iter()
        .filter(|p| p["subject"] == "distal link 1 and distal link 2")
        .collect();
    // The start (home: in this mode the elbows nearly meet there) and line 2.
    assert_eq!(folded.len(), 2, "{report:#}");
    assert_eq!(folded[0]["line"], 0, "{report:#}");
    let on_line_2 = folded[1];
    assert_eq!(on_line_2["line"], 2, "{on_line_2:#}");
    assert!(on_line_2["message"].as_str().unwrap().contains("fold onto each other"));
    // Independently: the elbows by IK of the path rows, first row of line 2 under 30 mm.
    let model = biscara::kinematics::Kinematics::new(
        &biscara::kinematics::Robot::from_json(robot).unwrap(),
    )
    .unwrap();
    let path = path_of(&dir, &["--robot", "robot.json"]);
    // Line 2 starts where line 1 ends, at (−20, 380).
    let start_of_line_2 =
        path.iter().position(|row| row[1] == -20.0 && row[2] == 380.0).expect("line 2");
    let first = path[start_of_line_2..]
        .iter()
        .find(|row| {
            let pose = biscara::kinematics::Pose::from_degrees(row[1], row[2], row[3], row[4]);
            // Between the two the pose is beyond a type-2 singularity (no body to test).
            let solution = model.inverse(&pose).expect("both chains reach");
            let elbows = solution.configuration.elbows;
            model.check_assembly(&solution).is_ok() && (elbows[0] - elbows[1]).norm() < 30.0
        })
        .expect("the elbows meet on line 2");
    assert_time(on_line_2, first[0]);
}

#[test]
fn joint_limit_velocity_and_acceleration_violations_at_their_lines() {
    // Line 2 lifts the tool above z = 100: d4 = 100 − z < 0. (From z = 50.01, so that no sample
    // lands on z = 100 itself, where rounding decides the side: at 20 mm/s a sample every
    // 0.02 mm.)
    let lift = r#"{"line":1,"kind":"rapid","end":[0.0,400.0,50.01,0.0]}
{"line":2,"kind":"linear","end":[0.0,400.0,120.0,0.0],"feed":1200.0}
{"line":3,"kind":"end"}
"#;
    let dir = setup("check-limits", &[("job.jsonl", lift)]);
    let report = json(biscara(&dir, &["check", "job.jsonl", "--json"]).expect_code(1));
    let limits = problems(&report, "joint_limit");
    assert_eq!(limits.len(), 1, "{report:#}");
    assert_eq!((limits[0]["line"].clone(), limits[0]["subject"].clone()), (2.into(), "d4".into()));
    let path = path_of(&dir, &[]);
    let first = path.iter().find(|row| row[3] > 100.0 + 1e-9).expect("above 100");
    assert_time(limits[0], first[0]);
    assert_eq!(report["problems"].as_array().unwrap().len(), 1, "{report:#}");

    // Line 2 sweeps x at 2 m/s with the paper's constant profile (no joint slow-down):
    // θ1 and θ2 exceed 360 °/s there, and only there.
    let sweep = r#"{"line":1,"kind":"rapid","end":[-100.0,350.0,50.0,0.0]}
{"line":2,"kind":"linear","end":[100.0,350.0,50.0,0.0],"feed":120000.0}
{"line":3,"kind":"end"}
"#;
    let dir = setup("check-velocity", &[("job.jsonl", sweep)]);
    let run = biscara(&dir, &["check", "job.jsonl", "--json", "--profile", "constant"]);
    let report = json(run.expect_code(1));
    let fast = problems(&report, "velocity_limit");
    assert!(!fast.is_empty(), "{report:#}");
    for problem in &fast {
        assert_eq!(problem["line"], 2, "{problem:#}");
        assert!(problem["subject"] == "theta1" || problem["subject"] == "theta2");
    }
    // The same program with the default (optimal) profile is slowed to the limits: clean.
    let run = biscara(&dir, &["check", "job.jsonl", "--json"]);
    assert_eq!(json(&run)["ok"], true, "{run}");

    // Line 2 turns C at the home pose: θ3 accelerates at rotation_acceleration (7200 °/s²),
    // above this robot's 1000 °/s².
    let turn = format!(
        r#"{{"line":1,"kind":"dwell","seconds":0.1}}
{{"line":2,"kind":"linear","end":[0.0,{HOME_Y},100.0,90.0],"feed":6000.0}}
{{"line":3,"kind":"end"}}
"#
    );
    let robot = r#"{"joint_max_acceleration": {"theta1": 7200, "theta2": 7200, "theta3": 1000, "d4": 10000}}"#;
    let dir = setup("check-acceleration", &[("job.jsonl", &turn), ("robot.json", robot)]);
    // The default (optimal) profile keeps θ3 within its 1000 °/s²; the trapezoid does not.
    let run = biscara(&dir, &["--robot", "robot.json", "check", "job.jsonl", "--json"]);
    assert_eq!(json(&run)["ok"], true, "{run}");
    let run = biscara(
        &dir,
        &["--robot", "robot.json", "check", "job.jsonl", "--json", "--profile", "trapezoid"],
    );
    let report = json(run.expect_code(1));
    let hard = problems(&report, "acceleration_limit");
    assert!(!hard.is_empty(), "{report:#}");
    for problem in &hard {
        assert_eq!(
            (problem["line"].clone(), problem["subject"].clone()),
            (2.into(), "theta3".into())
        );
    }
    assert_eq!(hard.len(), report["problems"].as_array().unwrap().len(), "{report:#}");
    // Grouped: the acceleration phase and the deceleration phase, not one entry per sample.
    assert_eq!(hard.len(), 2, "{report:#}");
    let peak = &report["summary"]["peak_acceleration"]["theta3"];
    assert!((peak["value"].as_f64().unwrap() - 7200.0).abs() < 1.0, "{peak:#}");
    assert_eq!(peak["line"], 2);
}

#[test]
fn the_demo_job_is_clean() {
    let dir = temp_dir("check-clean");
    let job = repo_root().join("data/jobs/pick_place.txt");
    let generated = biscara(&dir, &["gen", job.to_str().expect("path"), "-o", "job.ngc"]);
    generated.success();
    let run = biscara(&dir, &["check", "job.ngc", "--json"]);
    run.success();
    let report = json(&run);
    assert_eq!(report["ok"], true);
    assert_eq!(report["problems"].as_array().map(Vec::len), Some(0));
    let summary = &report["summary"];
    assert!(summary["duration_s"].as_f64().unwrap() > 1.0, "{summary:#}");
    assert!(summary["path_length_mm"].as_f64().unwrap() > 100.0, "{summary:#}");
    for joint in ["theta1", "theta2", "theta3", "d4"] {
        let peak = &summary["peak_velocity"][joint];
        assert!(peak["value"].as_f64().unwrap() <= peak["limit"].as_f64().unwrap(), "{peak:#}");
    }
    check_golden("virtual_robot/pick_place.check.json", &run.stdout);
    let text = biscara(&dir, &["check", "job.ngc"]);
    text.success();
    assert!(text.stdout.starts_with("job.ngc: clean: no problem found\nsummary:\n"), "{text}");
    // With its cell: the gripper sets down on the pallet's and the table's top faces (touching
    // is not a collision) ...
    let cell = repo_root().join("data/scenes/pick_place_cell.json");
    biscara(&dir, &["check", "job.ngc", "--scene", cell.to_str().expect("path")]).success();
    // ... but a post beside the pick pallet is in the way of chain 1's links on line 5.
    let post = repo_root().join("data/scenes/cell_with_post.json");
    let run =
        biscara(&dir, &["check", "job.ngc", "--scene", post.to_str().expect("path"), "--json"]);
    let report = json(run.expect_code(1));
    let hits = problems(&report, "scene_collision");
    assert!(!hits.is_empty(), "{report:#}");
    assert!(hits.iter().all(|p| p["subject"].as_str().unwrap().ends_with("in light curtain post")));
    assert_eq!(hits[0]["line"], 5, "{report:#}");
    assert_eq!(hits[0]["subject"], "distal link 1 in light curtain post", "{report:#}");
}

#[test]
fn bad_scene_files_name_file_line_and_column() {
    let cases: [(&str, &[u8], &str); 6] = [
        ("empty.json", b"", "empty.json:1:1: .: EOF while parsing a value"),
        ("binary.json", b"\x00\xff\xfe\x01garbage", "binary.json:1:1: .: expected value"),
        (
            "unknown.json",
            b"{\"boxes\": [{\"min\": [0,0,0], \"max\": [1,1,1], \"colour\": 3}]}",
            "unknown.json:1:52: boxes[0].colour: unknown field `colour`",
        ),
        (
            "inverted.json",
            b"{\"boxes\": [\n  {\"name\": \"pallet\", \"min\": [0,0,5], \"max\": [1,1,1]}\n]}",
            "inverted.json:3:1: boxes[0]: max must exceed min on every axis, but on z",
        ),
        (
            "nan.json",
            b"{\"boxes\": [{\"min\": [NaN,0,0], \"max\": [1,1,1]}]}",
            "nan.json:1:21: boxes[0].min[0]: expected value",
        ),
        (
            "huge.json",
            b"{\"boxes\": [{\"min\": [0,0,0], \"max\": [1e999,1,1]}]}",
            "huge.json:1:41: boxes[0].max[0]: number out of range",
        ),
    ];
    let dir = setup("check-bad-scene", &[("job.jsonl", BOX_PROGRAM)]);
    for (name, bytes, expected) in cases {
        std::fs::write(dir.join(name), bytes).expect("write scene");
        let run = biscara(&dir, &["check", "job.jsonl", "--scene", name, "-o", "report.json"]);
        run.expect_code(1).stderr_has(&format!("biscara: error: {expected}"));
        assert!(!run.stderr.contains("panicked"), "{run}");
        assert!(!dir.join("report.json").exists(), "partial output for {name}\n{run}");
    }
}

#[test]
fn workspace_prints_area_and_rectangle() {
    let dir = temp_dir("workspace");
    let run = biscara(&dir, &["workspace", "--json"]);
    run.success();
    assert_eq!(
        run.stdout,
        "{\"area_mm2\":311844.0,\"step_mm\":2.0,\"rectangle\":{\"min\":[-232.0,136.0],\"max\":[232.0,346.0]}}\n"
    );
    let text = biscara(&dir, &["workspace"]);
    check_golden("virtual_robot/workspace.txt", &text.success().stdout);
    let csv = biscara(&dir, &["workspace", "--csv", "--step", "10"]);
    let lines: Vec<&str> = csv.success().stdout.lines().collect();
    assert_eq!(lines[0], "x_mm,y_mm,reachable");
    assert!(lines.contains(&"0.000,400.000,1") && lines.contains(&"0.000,0.000,0"), "{csv}");
    let pictures = biscara(&dir, &["workspace", "--svg", "ws.svg", "--png", "ws.png"]);
    pictures.success();
    let svg = std::fs::read_to_string(dir.join("ws.svg")).expect("svg");
    assert!(
        svg.starts_with("<svg") && svg.contains("largest rectangle 464 x 210 mm"),
        "{svg:.300}"
    );
    let png = std::fs::read(dir.join("ws.png")).expect("png");
    assert!(png.starts_with(b"\x89PNG\r\n\x1a\n") && png.len() > 10_000);
    biscara(&dir, &["workspace", "--step", "0"]).expect_code(1).stderr_has("grid step");
}

/// A CAM-style engraving, 150 × 100 mm with its zero at the lower left corner.
fn engraving() -> std::path::PathBuf {
    repo_root().join("data/programs/engraving_arcs.ngc")
}

#[test]
fn fit_places_a_cam_program_in_the_rectangle_and_joints_then_succeeds() {
    let dir = temp_dir("fit");
    let program = engraving();
    let program = program.to_str().expect("path");
    // As written (zero at the part, near the base origin) the robot cannot run it.
    biscara(&dir, &["joints", program, "--origin", "0,0,20,0", "-o", "traj.csv"]).expect_code(1);
    let run =
        biscara(&dir, &["joints", program, "--origin", "0,0,20,0", "--fit", "-o", "traj.csv"]);
    run.success()
        .stderr_has("fitted: the program's XY extent x 0.000..150.000, y 0.000..100.000 mm");
    run.stderr_has("offset X-75.000 Y191.000");
    assert!(dir.join("traj.csv").exists());
    // interpret --fit writes the same placement: every end point inside the rectangle.
    let run = biscara(&dir, &["interpret", program, "--origin", "0,0,20,0", "--fit"]);
    run.success().stderr_has("offset X-75.000 Y191.000");
    let mut ends = 0;
    for line in run.stdout.lines() {
        let motion: Value = serde_json::from_str(line).expect("inter-file line");
        if let Some(end) = motion["end"].as_array() {
            let (x, y) = (end[0].as_f64().unwrap(), end[1].as_f64().unwrap());
            let at_home = x == 0.0 && (y - HOME_Y).abs() < 1e-6;
            assert!(
                at_home || ((-75.0..=75.0).contains(&x) && (191.0..=291.0).contains(&y)),
                "{line}"
            );
            ends += 1;
        }
    }
    assert!(ends > 10);
    // And check agrees.
    biscara(&dir, &["check", program, "--origin", "0,0,20,0", "--fit"]).success();
    // An inter-file is placed the same way.
    std::fs::write(
        dir.join("part.jsonl"),
        biscara(&dir, &["interpret", program]).success().stdout.as_bytes(),
    )
    .expect("write");
    let run = biscara(&dir, &["interpolate", "part.jsonl", "--fit", "-o", "path.csv"]);
    run.success().stderr_has("offset X-75.000 Y191.000");
}

#[test]
fn fit_refuses_a_program_larger_than_the_rectangle() {
    let program = r#"{"line":1,"kind":"rapid","end":[0.0,0.0,50.0,0.0]}
{"line":2,"kind":"linear","end":[500.0,100.0,50.0,0.0],"feed":3000.0}
"#;
    let dir = setup("fit-too-large", &[("job.jsonl", program)]);
    let run = biscara(&dir, &["joints", "job.jsonl", "--fit", "-o", "traj.csv"]);
    run.expect_code(1).stderr_has(
        "job.jsonl: cannot fit the program to the workspace: the program's XY extent 500.000 x 100.000 mm does not fit the \
         workspace rectangle 464.000 x 210.000 mm: as programmed, 36.000 mm too wide in X; \
         turned by 90° about Z, 290.000 mm too tall in Y",
    );
    assert!(!dir.join("traj.csv").exists());
    biscara(&dir, &["check", "-", "--fit"]).expect_code(1).stderr_has("not standard input");
    // A program with nothing to place: the library says why, the command line names the flag.
    std::fs::write(dir.join("lift.ngc"), "G0 Z10\nG0 Z20\nM2\n").unwrap();
    biscara(&dir, &["joints", "lift.ngc", "--fit", "-o", "lift.csv"]).expect_code(1).stderr_has(
        "lift.ngc: cannot fit the program to the workspace: the program has no move in X or Y \
         away from its start: there is nothing to place\n    (run it without --fit)",
    );
    assert!(!dir.join("lift.csv").exists());
}

#[test]
fn plot_draws_svg_and_png() {
    let dir = setup("plot", &[("job.jsonl", BOX_PROGRAM)]);
    let run = biscara(&dir, &["plot", "job.jsonl", "--at", "0,1,2", "-o", "plot.svg"]);
    run.success();
    let svg = std::fs::read_to_string(dir.join("plot.svg")).expect("svg");
    for text in
        ["<svg", "programmed path", "robot at t = 1 s", "robot at t = 2 s", "largest rectangle"]
    {
        assert!(svg.contains(text), "{text} missing");
    }
    let run = biscara(&dir, &["plot", "--joints", "job.jsonl", "-o", "joints.png"]);
    run.success();
    let png = std::fs::read(dir.join("joints.png")).expect("png");
    assert!(png.starts_with(b"\x89PNG\r\n\x1a\n"));
    let late = biscara(&dir, &["plot", "job.jsonl", "--at", "999", "-o", "late.svg"]);
    late.success().stderr_has("after the program's end");
}

#[test]
fn demo_writes_the_virtual_robot_outputs() {
    let dir = temp_dir("demo-virtual-robot");
    let run = biscara(&dir, &["demo", "out"]);
    run.success();
    for name in ["check.json", "workspace.svg", "plot.svg"] {
        assert!(run.stdout.contains(&format!("out/{name}")), "{run}");
    }
    let report: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("out/check.json")).expect("check"))
            .expect("JSON");
    assert_eq!(report["ok"], true);
    let svg = std::fs::read_to_string(dir.join("out/plot.svg")).expect("plot");
    assert!(svg.contains("programmed path"));
}

#[test]
fn help_texts_are_pinned() {
    let dir = temp_dir("virtual-robot-help");
    for command in ["check", "workspace", "plot", "cycle"] {
        let run = biscara(&dir, &[command, "--help"]);
        run.success();
        assert!(run.stdout.contains("Example:"), "{run}");
        check_golden(&format!("help/{command}.txt"), &run.stdout);
    }
}

/// `plot --torques`: the motors' torques against time with the ratings of a robot with motors
/// (their values as `joints --torques` writes them), the curves alone without motors.
#[test]
fn plot_torques_draws_the_motors_against_their_ratings() {
    let dir = temp_dir("plot-torques");
    let root = crate::util::repo_root();
    let robot = root.join("data/robots/servo-example.json");
    let program = root.join("data/programs/pick_place_inch.ngc");
    let (robot, program) = (robot.to_str().unwrap(), program.to_str().unwrap());
    biscara(&dir, &["--robot", robot, "plot", "--torques", program, "-o", "t.svg"]).success();
    let svg = std::fs::read_to_string(dir.join("t.svg")).unwrap();
    assert!(svg.contains("τ1 (N·m)") && svg.contains("f d4 (N)"), "axes");
    assert!(svg.contains("±peak red, ±rated orange"), "the ratings' legend");
    // θ1's axis reaches its ±48 N·m peak (labels every 10 N·m), far beyond its torques.
    assert!(svg.contains("\n-40.0\n") && svg.contains("\n40.0\n"), "the axis reaches the peak");
    biscara(&dir, &["plot", "--torques", program, "-o", "plain.png"]).success();
    let png = std::fs::read(dir.join("plain.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG");
    biscara(&dir, &["plot", "--torques", "--joints", program]).expect_code(2);
}

/// `check` with motors, end to end: the bundled job on small motors is clean under the default
/// (torque-limited) profile, and over the motors' peaks under the trapezoid profile, which knows
/// nothing of torques: `torque_limit` problems in the JSON, the summary's torque figures, and
/// the problems marked in `view`.
#[test]
fn check_reports_the_motors_torques_and_view_marks_them() {
    let dir = temp_dir("check-torques");
    let root = crate::util::repo_root();
    let robot = root.join("data/robots/small-motors.json");
    let robot = robot.to_str().unwrap();
    let job = root.join("data/jobs/pick_place.txt");
    biscara(&dir, &["gen", job.to_str().unwrap(), "-o", "job.ngc"]).success();
    biscara(&dir, &["--robot", robot, "check", "job.ngc", "--json", "-o", "clean.json"]).success();
    let clean: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("clean.json")).unwrap()).unwrap();
    assert_eq!(clean["ok"], true);
    for joint in ["theta1", "theta2", "theta3", "d4"] {
        let peak = &clean["summary"]["peak_torque"][joint];
        assert!(peak["value"].as_f64().unwrap() <= peak["limit"].as_f64().unwrap(), "{peak}");
        let rms = &clean["summary"]["rms_torque"][joint];
        assert!(rms["value"].as_f64().unwrap() <= rms["limit"].as_f64().unwrap(), "{rms}");
    }
    let args = ["--robot", robot, "check", "--profile", "trapezoid", "job.ngc", "--json"];
    biscara(&dir, &[&args[..], &["-o", "over.json"]].concat()).expect_code(1);
    let over: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("over.json")).unwrap()).unwrap();
    let problems = over["problems"].as_array().unwrap();
    assert!(!problems.is_empty() && problems.iter().all(|p| p["kind"] == "torque_limit"), "{over}");
    assert!(
        problems.iter().any(|p| p["message"].as_str().unwrap().contains("beyond its peak 2.5 N·m"))
    );
    biscara(&dir, &["--robot", robot, "joints", "job.ngc", "-o", "traj.csv"]).success();
    biscara(&dir, &["--robot", robot, "view", "traj.csv", "--check", "over.json", "-o", "v.html"])
        .success();
    let html = std::fs::read_to_string(dir.join("v.html")).unwrap();
    assert!(html.contains("\"torque_limit\""), "the viewer lists the torque problems");
}

/// The torque-limited profile on a move longer than the planner's window (ten turns of a 30 mm
/// circle: 1,885 mm, planned in windows of 512 mm) and on a blended chain (G64 P2): no motor
/// beyond its peak; only the RMS over this fast program is beyond the rating.
#[test]
fn the_torque_limits_hold_over_planning_windows_and_blended_chains() {
    let dir = temp_dir("torque-windows");
    let robot = repo_root().join("data/robots/small-motors.json");
    let program = "G21 G90 G61\nG0 X30 Y300 Z40\nG2 X30 Y300 I-30 J0 P10 F30000\n\
                   G1 X-100 Y250 F30000\nG64 P2\nG1 X100 Y250\nG1 X100 Y350\nG1 X-100 Y350\n\
                   G1 X-100 Y250\nM2\n";
    std::fs::write(dir.join("long.ngc"), program).unwrap();
    let run = biscara(&dir, &["--robot", robot.to_str().unwrap(), "check", "long.ngc", "--json"]);
    run.expect_code(1);
    let report: Value = serde_json::from_str(&run.stdout).unwrap();
    let kinds: Vec<&str> = report["problems"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["kind"].as_str().unwrap())
        .collect();
    assert_eq!(kinds, ["rms_torque", "rms_torque"], "{report}");
    for joint in ["theta1", "theta2", "theta3", "d4"] {
        let peak = &report["summary"]["peak_torque"][joint];
        assert!(peak["value"].as_f64().unwrap() <= peak["limit"].as_f64().unwrap(), "{peak}");
    }
    // The motors bind: slower than the robot without them.
    let plain = biscara(&dir, &["check", "long.ngc", "--json"]);
    let plain: Value = serde_json::from_str(&plain.success().stdout).unwrap();
    let duration = |report: &Value| report["summary"]["duration_s"].as_f64().unwrap();
    assert!(
        duration(&report) > 1.1 * duration(&plain),
        "{} vs {}",
        duration(&report),
        duration(&plain)
    );
}

#[test]
fn the_summary_names_the_home_pose_not_line_0() {
    // The default home pose lies at the edge of the reach: the program's nearest singularity is
    // there, at the first sample, before the program's first line.
    let dir = setup("check-home-pose", &[("job.jsonl", BOX_PROGRAM)]);
    let run = biscara(&dir, &["check", "job.jsonl"]);
    let run = run.success();
    let nearest =
        run.stdout.lines().find(|line| line.contains("nearest singularity")).expect("nearest");
    assert!(nearest.contains("(the home pose, t = 0.000 s)"), "{run}");
    assert!(!run.stdout.contains("line 0"), "{run}");
    // JSON keeps the number: line 0 is the home pose (docs/virtual-robot.md).
    let run = biscara(&dir, &["check", "job.jsonl", "--json"]);
    let report = json(run.success());
    assert_eq!(report["summary"]["min_singularity"]["line"], 0, "{report:#}");
}
