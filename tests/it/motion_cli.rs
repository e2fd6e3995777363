//! `biscara interpolate`, `joints` and `diff` on inter-files and path CSVs.

use crate::golden::check_golden;
use crate::util::{Run, biscara, temp_dir};

/// A short pick-and-place program as an inter-file: rapids, a feed move, a dwell, an arc.
const PROGRAM: &str = r#"{"line":1,"kind":"rapid","end":[0.0,400.0,100.0,0.0]}
{"line":2,"kind":"rapid","end":[150.0,320.0,60.0,30.0]}
{"line":3,"kind":"linear","end":[150.0,320.0,10.0,30.0],"feed":3000.0}
{"line":4,"kind":"pick"}
{"line":5,"kind":"dwell","seconds":0.3}
{"line":6,"kind":"arc","end":[50.0,420.0,40.0,90.0],"center":[50.0,320.0],"plane":"xy","clockwise":false,"turns":1,"feed":2400.0}
{"line":7,"kind":"place"}
{"line":8,"kind":"end"}
"#;

fn rows(text: &str) -> Vec<Vec<f64>> {
    text.lines()
        .skip(1)
        .map(|line| line.split(',').map(|f| f.parse().expect("number")).collect())
        .collect()
}

fn setup(name: &str) -> std::path::PathBuf {
    let dir = temp_dir(name);
    std::fs::write(dir.join("job.jsonl"), PROGRAM).expect("write program");
    dir
}

#[test]
fn interpolate_starts_at_home_and_hits_every_end_point() {
    let dir = setup("interpolate");
    let run = biscara(&dir, &["interpolate", "job.jsonl", "--events"]);
    run.success();
    assert!(
        run.stdout.starts_with(
            "t_s,x_mm,y_mm,z_mm,c_deg,gripper\n0.000000,0.000000,460.798724,100.000000,0.000000,0\n"
        ),
        "{run}"
    );
    let rows = rows(&run.stdout);
    for end in [
        [0.0, 400.0, 100.0, 0.0],
        [150.0, 320.0, 60.0, 30.0],
        [150.0, 320.0, 10.0, 30.0],
        [50.0, 420.0, 40.0, 90.0],
    ] {
        assert!(rows.iter().any(|row| row[1..5] == end), "end point {end:?} not hit");
    }
    for (index, row) in rows.iter().enumerate() {
        assert!((row[0] - index as f64 * 0.001).abs() < 5e-7, "uniform time");
    }
    // The dwell: 300 rows at the pick pose with the gripper closed.
    let held = rows.iter().filter(|row| row[1..5] == [150.0, 320.0, 10.0, 30.0]).count();
    assert_eq!(held, 301);
    assert_eq!(
        rows.last().expect("rows")[5],
        1.0,
        "the place is the last event: gripper closed until then"
    );
    let coarse = biscara(&dir, &["interpolate", "job.jsonl", "--events", "--dt", "0.01"]);
    check_golden("motion/job.path.csv", &coarse.success().stdout);
}

#[test]
fn joints_with_derivatives_are_consistent_with_the_positions() {
    let dir = setup("joints-derivatives");
    let run = biscara(
        &dir,
        &["joints", "job.jsonl", "--derivatives", "--dt", "0.01", "--precision", "9"],
    );
    run.success();
    let header = run.stdout.lines().next().expect("header");
    assert_eq!(
        header,
        "t_s,theta1_rad,theta2_rad,theta3_rad,d4_mm,dtheta1_rad_s,dtheta2_rad_s,dtheta3_rad_s,dd4_mm_s,ddtheta1_rad_s2,ddtheta2_rad_s2,ddtheta3_rad_s2,ddd4_mm_s2"
    );
    let rows = rows(&run.stdout);
    let dt = 0.01;
    for triple in rows.windows(3) {
        for joint in 1..5 {
            let central = (triple[2][joint] - triple[0][joint]) / (2.0 * dt);
            // Printed with 9 decimals: the difference quotient is good to 1e-9 / dt.
            assert!(
                (triple[1][joint + 4] - central).abs() < 2e-7,
                "velocity of column {joint} at t = {}",
                triple[1][0]
            );
        }
    }
}

#[test]
fn joints_in_degrees_and_from_a_path_csv_agree() {
    let dir = setup("joints-path");
    biscara(&dir, &["interpolate", "job.jsonl", "-o", "path.csv"]).success();
    biscara(&dir, &["joints", "job.jsonl", "-o", "direct.csv"]).success();
    biscara(&dir, &["joints", "path.csv", "-o", "via-path.csv"]).success();
    biscara(&dir, &["diff", "direct.csv", "via-path.csv", "--tol", "2e-6"]).success();
    let degrees = biscara(&dir, &["joints", "job.jsonl", "--angle-unit", "deg"]);
    degrees.success();
    assert!(degrees.stdout.starts_with("t_s,theta1_deg,theta2_deg,theta3_deg,d4_mm\n"));
    let radians = rows(&std::fs::read_to_string(dir.join("direct.csv")).expect("read"));
    let degrees = rows(&degrees.stdout);
    for (r, d) in radians.iter().zip(&degrees).step_by(97) {
        assert!((r[1].to_degrees() - d[1]).abs() < 1e-4);
    }
}

#[test]
fn constant_profile_and_time_step() {
    let dir = setup("constant");
    let run = biscara(&dir, &["interpolate", "job.jsonl", "--profile", "constant", "--dt", "0.01"]);
    run.success();
    let trapezoid = biscara(&dir, &["interpolate", "job.jsonl", "--dt", "0.01"]);
    assert!(rows(&run.stdout).len() < rows(&trapezoid.stdout).len(), "no acceleration phases");
    biscara(&dir, &["interpolate", "job.jsonl", "--dt", "0"]).expect_code(2);
    biscara(&dir, &["interpolate", "job.jsonl", "--profile", "blend"]).expect_code(2);
}

#[test]
fn an_unreachable_program_fails_with_its_line_and_writes_nothing() {
    let dir = temp_dir("joints-unreachable");
    std::fs::write(dir.join("far.jsonl"), "{\"line\":1,\"kind\":\"rapid\",\"end\":[0,400,50,0]}\n\n{\"line\":3,\"kind\":\"linear\",\"end\":[0,700,50,0],\"feed\":1000}\n").expect("write");
    std::fs::write(dir.join("traj.csv"), "good old file\n").expect("write");
    let run = biscara(&dir, &["joints", "far.jsonl", "-o", "traj.csv"]);
    run.expect_code(1).stderr_has("far.jsonl:3: at t = ").stderr_has("cannot be taken");
    assert_eq!(std::fs::read_to_string(dir.join("traj.csv")).expect("read"), "good old file\n");
    assert_eq!(std::fs::read_dir(&dir).expect("dir").count(), 2, "no temporary file left");
}

#[test]
fn slowed_motions_are_listed_with_their_lines() {
    let dir = temp_dir("slowed");
    // C turns 180° over 10 mm at 6000 mm/min: 500°/s would exceed rapid_rotation (360°/s).
    std::fs::write(
        dir.join("spin.jsonl"),
        "{\"line\":4,\"kind\":\"linear\",\"end\":[10,460,100,180],\"feed\":6000}\n",
    )
    .expect("write");
    biscara(&dir, &["interpolate", "spin.jsonl"]).success().stderr_has("spin.jsonl:4: slowed to");
}

#[test]
fn bad_inter_files_and_path_csvs_name_file_line_and_column() {
    let dir = temp_dir("bad-motion-input");
    let cases: [(&str, &str, &[&str], &str); 5] = [
        (
            "kind.jsonl",
            "{\"line\":1,\"kind\":\"rapid\",\"end\":[0,400,50,0]}\n{\"line\":2,\"kind\":\"fly\"}\n",
            &["interpolate"],
            "kind.jsonl:2:",
        ),
        (
            "nan.jsonl",
            "{\"line\":1,\"kind\":\"dwell\",\"seconds\":-1}\n",
            &["interpolate"],
            "nan.jsonl:1: \"seconds\" must be",
        ),
        ("empty.csv", "", &["joints"], "empty.csv:1:1: expected the header"),
        ("short.csv", "t_s,x_mm,y_mm,z_mm,c_deg\n0,0,400,50\n", &["joints"], "short.csv:2:"),
        ("binary.jsonl", "\u{0}\u{1}garbage", &["joints"], "binary.jsonl:1:"),
    ];
    for (name, text, command, message) in cases {
        std::fs::write(dir.join(name), text).expect("write");
        let mut args = command.to_vec();
        args.extend([name, "-o", "out.csv"]);
        biscara(&dir, &args).expect_code(1).stderr_has(message);
        assert!(!dir.join("out.csv").exists(), "{name}: partial output");
    }
    biscara(&dir, &["interpolate", "missing.jsonl"])
        .expect_code(1)
        .stderr_has("cannot read missing.jsonl");
}

#[test]
fn diff_exit_codes_and_message() {
    let dir = temp_dir("diff");
    std::fs::write(dir.join("a.csv"), "t_s,x_mm\n0.0,1.0\n0.1,2.0\n0.2,3.0\n").expect("write");
    std::fs::write(dir.join("b.csv"), "t_s,x_mm\n0.0,1.0\n0.1,2.5\n0.2,3.5\n").expect("write");
    std::fs::write(dir.join("c.csv"), "t_s,y_mm\n0.0,1.0\n").expect("write");
    biscara(&dir, &["diff", "a.csv", "a.csv"]).success();
    let run: Run = biscara(&dir, &["diff", "a.csv", "b.csv"]);
    run.expect_code(1)
        .stderr_has("b.csv:3: `x_mm` differs: a.csv has 2.0, b.csv has 2.5; 2 of 3 rows differ");
    biscara(&dir, &["diff", "a.csv", "b.csv", "--tol", "0.6"]).success();
    biscara(&dir, &["diff", "a.csv", "c.csv"]).expect_code(1).stderr_has("different kinds");
    biscara(&dir, &["diff", "a.csv", "b.csv", "--tol", "-1"]).expect_code(2);
}

#[test]
fn help_texts_are_pinned() {
    let dir = temp_dir("motion-help");
    for command in ["interpolate", "joints", "diff"] {
        let run = biscara(&dir, &[command, "--help"]);
        run.success();
        assert!(run.stdout.contains("Example:"), "{run}");
        check_golden(&format!("help/{command}.txt"), &run.stdout);
    }
}

/// Writes `program` as `name` in `dir` and runs `joints` on it, expecting failure at `line`.
#[track_caller]
fn check_fails_at(dir: &std::path::Path, name: &str, program: &str, line: usize, reason: &str) {
    std::fs::write(dir.join(name), program).expect("write");
    biscara(dir, &["joints", name, "-o", "traj.csv"])
        .expect_code(1)
        .stderr_has(&format!("{name}:{line}: at t = "))
        .stderr_has(reason);
    assert!(!dir.join("traj.csv").exists());
}

#[test]
fn gcode_programs_that_leave_the_workspace_fail_at_their_line() {
    let dir = temp_dir("gcode-failures");
    let start = "G21 G90 G94\nG0 X0 Y400 Z50 C0\n";
    check_fails_at(
        &dir,
        "type2.ngc",
        &format!("{start}(down through the base line)\nG1 Y60 F3000\nM2\n"),
        4,
        "type-2 singularity",
    );
    check_fails_at(&dir, "limit.ngc", &format!("{start}G1 Z80 F3000\nG1 Z120\nM2\n"), 4, "d4 = ");
    check_fails_at(
        &dir,
        "reach.ngc",
        &format!("{start}G1 X0 Y700 F3000\nM2\n"),
        3,
        "singularity of chain",
    );
    check_fails_at(
        &dir,
        "theta3.ngc",
        &format!("{start}G1 C170 F20000\nG1 C220\nM2\n"),
        4,
        "theta3 = ",
    );
}

#[test]
fn gcode_fast_rotation_is_slowed_and_says_so() {
    let dir = temp_dir("gcode-slowed");
    std::fs::write(dir.join("spin.ngc"), "G21 G90 G94\nG0 X0 Y400 Z50\nG1 X10 C180 F6000\nM2\n")
        .expect("write");
    biscara(&dir, &["joints", "spin.ngc"])
        .success()
        .stderr_has("spin.ngc:3: slowed to")
        .stderr_has("C rotation");
}

#[test]
fn origin_shifts_a_gcode_program() {
    let dir = temp_dir("origin");
    std::fs::write(dir.join("part.ngc"), "G21 G90 G94\nG0 X0 Y0 Z0 C0\nG1 X10 F600\nM2\n")
        .expect("write");
    // Without an origin the part zero is the base frame's origin: not reachable.
    biscara(&dir, &["joints", "part.ngc"]).expect_code(1);
    let run = biscara(&dir, &["interpolate", "part.ngc", "--origin", "-20,380,30,0"]);
    run.success();
    let last = run.stdout.lines().last().expect("rows");
    assert_eq!(
        last,
        format!("{},-10.000000,380.000000,30.000000,0.000000", last.split(',').next().expect("t"))
    );
}

/// Every velocity and acceleration column of a joint CSV written with `--derivatives` (finite
/// differences of the positions) within the default robot's limits: the default profile keeps
/// them (docs/motion.md). At 10 ms the differences average the motion over a step, so they stay within
/// what holds at every instant; the slack covers the printed decimals.
fn within_default_limits(name: &str, csv: &str) {
    let robot = biscara::kinematics::Robot::default();
    let radians = |values: [f64; 4]| {
        [values[0].to_radians(), values[1].to_radians(), values[2].to_radians(), values[3]]
    };
    let velocity = radians(robot.joint_max_velocity.to_array());
    let acceleration = radians(robot.joint_max_acceleration.to_array());
    let mut rows = 0;
    for line in csv.lines().skip(1) {
        let values: Vec<f64> = line.split(',').map(|v| v.parse().expect("number")).collect();
        assert_eq!(values.len(), 13, "{name}: {line}");
        for j in 0..4 {
            let (v, a) = (values[5 + j].abs(), values[9 + j].abs());
            assert!(v <= velocity[j] * (1.0 + 1e-6) + 1e-6, "{name}: joint {j} velocity in {line}");
            assert!(
                a <= acceleration[j] * (1.0 + 1e-6) + 1e-6,
                "{name}: joint {j} acceleration in {line}"
            );
        }
        rows += 1;
    }
    assert!(rows > 10, "{name}: {rows} rows");
}

/// Golden path and joint CSVs (every 10th row at 10 ms) of every G-code program in `data/`, of
/// the G-code `gen` makes from every job and of the G-code `post` makes from every CL file.
#[test]
fn data_programs_have_golden_paths_and_trajectories() {
    let dir = temp_dir("data-golden");
    let root = crate::util::repo_root();
    let mut programs: Vec<(String, std::path::PathBuf)> = Vec::new();
    for entry in std::fs::read_dir(root.join("data/programs")).expect("data/programs") {
        let path = entry.expect("entry").path();
        let name = path.file_stem().and_then(|s| s.to_str()).expect("name").to_owned();
        programs.push((name, path));
    }
    for entry in std::fs::read_dir(root.join("data/jobs")).expect("data/jobs") {
        let path = entry.expect("entry").path();
        let name = path.file_stem().and_then(|s| s.to_str()).expect("name").to_owned();
        let gcode = dir.join(format!("{name}.ngc"));
        biscara(&dir, &["gen", path.to_str().expect("path"), "-o", gcode.to_str().expect("path")])
            .success();
        programs.push((format!("job_{name}"), gcode));
    }
    // CAM CL files put their zero on the part: placed in the workspace with --origin.
    for entry in std::fs::read_dir(root.join("data/cl")).expect("data/cl") {
        let path = entry.expect("entry").path();
        let name = path.file_stem().and_then(|s| s.to_str()).expect("name").to_owned();
        let gcode = dir.join(format!("cl_{name}.ngc"));
        biscara(&dir, &["post", path.to_str().expect("path"), "-o", gcode.to_str().expect("path")])
            .success();
        programs.push((format!("cl_{name}"), gcode));
    }
    programs.sort();
    assert!(programs.len() >= 5, "{programs:?}");
    for (name, path) in programs {
        let program = path.to_str().expect("path");
        // A program whose zero is on the part says where to place it: `--origin X,Y,Z,C` in a
        // comment; CL files from CAM are placed at one common spot.
        let text = std::fs::read_to_string(&path).expect("read program");
        let origin = match text.split("--origin ").nth(1) {
            Some(rest) => rest.split([' ', ')']).next().expect("origin").to_owned(),
            None if name.starts_with("cl_") => "-50,300,30,0".to_owned(),
            None => "0,0,0,0".to_owned(),
        };
        let origin = origin.as_str();
        let path_csv = biscara(&dir, &["interpolate", program, "--dt", "0.01", "--origin", origin]);
        path_csv.success();
        let joints = biscara(
            &dir,
            &["joints", program, "--dt", "0.01", "--derivatives", "--origin", origin],
        );
        joints.success();
        within_default_limits(&name, &joints.stdout);
        check_golden(
            &format!("motion/{name}.path.every-10th-row.csv"),
            &crate::golden::decimate(&path_csv.stdout, 10),
        );
        check_golden(
            &format!("motion/{name}.traj.every-10th-row.csv"),
            &crate::golden::decimate(&joints.stdout, 10),
        );
    }
}
