//! The tool (docs/motion.md) from the command line: `--tool`, `interpolate --events` columns, and
//! what `check` finds that only a tool can get wrong.

use crate::util::{biscara, repo_root, temp_dir};

/// The rows of a CSV with a header: the header and the numbers.
fn csv(text: &str) -> (String, Vec<Vec<f64>>) {
    let mut lines = text.lines();
    let header = lines.next().expect("header").to_owned();
    let rows =
        lines.map(|line| line.split(',').map(|v| v.parse().expect("number")).collect()).collect();
    (header, rows)
}

#[test]
fn interpolate_events_gives_the_lasers_power_on_its_cuts_and_zero_on_travel() {
    let dir = temp_dir("tool-laser-events");
    let program = repo_root().join("data/programs/laser_engraving.ngc");
    let program = program.to_str().expect("path");
    let args = ["interpolate", program, "--origin", "-30,250,0,0", "--events", "--dt", "0.01"];
    let run = biscara(&dir, &args);
    run.success().stderr_has("tool: laser (a comment names a laser");
    let (header, rows) = csv(&run.stdout);
    assert_eq!(header, "t_s,x_mm,y_mm,z_mm,c_deg,laser_power");
    // The frame's corners are (−30, 250) and (30, 310); the ring about (0, 280), radius 15.
    let on_frame = |r: &Vec<f64>| {
        let (x, y) = (r[1], r[2]);
        let edge = |v: f64, a: f64| (v - a).abs() < 1e-6;
        (edge(y, 250.0) || edge(y, 310.0)) && (-30.0..=30.0).contains(&x)
            || (edge(x, -30.0) || edge(x, 30.0)) && (250.0..=310.0).contains(&y)
    };
    let on_ring = |r: &Vec<f64>| ((r[1]).hypot(r[2] - 280.0) - 15.0).abs() < 1e-6;
    let (mut full, mut ring) = (0, 0);
    for row in &rows {
        match row[5] {
            1000.0 => {
                assert!(on_frame(row), "{row:?}");
                full += 1;
            }
            400.0 => {
                assert!(on_ring(row), "{row:?}");
                ring += 1;
            }
            0.0 => {}
            other => panic!("power {other} in {row:?}"),
        }
    }
    assert!(full > 1000 && ring > 300, "{full} {ring}");
    // Travel inside the frame (the G0 to the ring) is dark.
    assert!(rows.iter().any(|r| r[5] == 0.0 && r[1] > -29.0 && r[1] < 14.0 && r[2] > 251.0));
    // --tool gripper reads the same program as pick and place: the gripper column.
    let run = biscara(&dir, &[&args[..], &["--tool", "gripper"]].concat());
    assert!(run.success().stdout.starts_with("t_s,x_mm,y_mm,z_mm,c_deg,gripper\n"), "{run}");
}

#[test]
fn interpolate_events_counts_the_filament_along_the_moves() {
    let dir = temp_dir("tool-extruder-events");
    let program = "M83\nG0 X0 Y250 Z10\nG1 X20 E2 F1200\nG1 Y270 E1\nG1 E-0.5 F600\nG0 X0\nM2\n";
    std::fs::write(dir.join("print.gcode"), program).expect("write");
    let run = biscara(&dir, &["interpolate", "print.gcode", "--events", "--dt", "0.01"]);
    run.success().stderr_has("tool: extruder (printer codes");
    let (header, rows) = csv(&run.stdout);
    assert!(header.ends_with(",extruded_mm"), "{header}");
    // Proportional along each move: half-way along the first cut, 1 mm is fed.
    for row in &rows {
        let first_cut = (row[2] - 250.0).abs() < 1e-9 && (0.0..=20.0).contains(&row[1]);
        if first_cut && row[3] == 10.0 && row[5] <= 2.0 {
            assert!((row[5] - row[1] / 10.0).abs() < 1e-6, "{row:?}");
        }
    }
    let last = rows.last().expect("rows");
    assert!((last[5] - 2.5).abs() < 1e-9, "{last:?}");
}

#[test]
fn check_finds_a_laser_burning_during_a_rapid() {
    let dir = temp_dir("tool-check");
    let laser = "G0 X0 Y250\nM3 S500\nG1 X20 F1200\nG0 X40\nG1 X60\nM5\nG0 X0\nM2\n";
    std::fs::write(dir.join("laser.nc"), laser).expect("write");
    let run = biscara(&dir, &["check", "laser.nc", "--tool", "laser"]);
    run.expect_code(1);
    assert!(
        run.stdout.contains("laser.nc:4: tool (laser on during a rapid move)")
            && run.stdout.contains("the laser burns at power S500 during a G0 move"),
        "{run}"
    );
    assert!(!run.stdout.contains("laser.nc:7:"), "the laser is off on line 7: {run}");
    let run = biscara(&dir, &["check", "laser.nc", "--tool", "laser", "--json"]);
    assert!(run.stdout.contains(r#""kind":"tool""#), "{run}");
    // The same program for a spindle: a rapid with the spindle on is no problem.
    biscara(&dir, &["check", "laser.nc", "--tool", "spindle"]).success();
    // Marlin's G0 is its G1: a G0 with an E word extrudes along a move at the feed rate, as
    // Marlin runs it, which is no problem.
    let print = "M83\nG0 X0 Y250 Z10\nG1 X20 E2 F1200\nG0 X40 E1\nM2\n";
    std::fs::write(dir.join("print.gcode"), print).expect("write");
    biscara(&dir, &["check", "print.gcode"]).success();
}

#[test]
fn an_unknown_tool_is_refused_with_the_kinds() {
    let dir = temp_dir("tool-bad");
    let program = repo_root().join("data/programs/laser_engraving.ngc");
    let run = biscara(&dir, &["interpret", program.to_str().expect("path"), "--tool", "torch"]);
    run.expect_code(2)
        .stderr_has("`torch` is not a tool: gripper, laser, spindle, extruder or pen");
    assert_eq!(run.stdout, "");
}

#[test]
fn plot_draws_the_burnt_trace_darker_for_more_power_apart_from_travel() {
    let dir = temp_dir("tool-plot");
    let program = repo_root().join("data/programs/laser_engraving.ngc");
    let program = program.to_str().expect("path");
    let args = ["plot", program, "--origin", "-30,250,0,0", "--step", "10", "-o", "laser.svg"];
    biscara(&dir, &args).success();
    let svg = std::fs::read_to_string(dir.join("laser.svg")).expect("svg");
    assert!(svg.contains("laser: burnt trace (darker: more power)"), "legend");
    assert!(svg.contains("travel"), "legend");
    // Full power (S1000 of 1000) is the darkest colour, S400 a lighter one: both drawn.
    let full = "#1E0F05";
    let part = "#937856";
    assert!(svg.to_uppercase().contains(full), "no stroke at full power");
    assert!(svg.to_uppercase().contains(part), "no stroke at 40 % power");
    // --zoom draws the frame's region, 60 mm wide, not the workspace: ticks every 10 mm from
    // x = −30, y up to 310, none at the workspace's 400 mm; no robot unless --at asks.
    let ticks = |svg: &str| -> Vec<String> {
        svg.split("<text").filter_map(|t| t.lines().nth(1).map(str::to_owned)).collect()
    };
    biscara(&dir, &[&args[..], &["--zoom"]].concat()).success();
    let zoomed = ticks(&std::fs::read_to_string(dir.join("laser.svg")).expect("svg"));
    for tick in ["-30.0", "0.0", "30.0", "250.0", "310.0"] {
        assert!(zoomed.iter().any(|t| t == tick), "{tick} in {zoomed:?}");
    }
    assert!(!zoomed.iter().any(|t| t == "400.0" || t.starts_with("t = ")), "{zoomed:?}");
    // The gripper draws no process.
    let args = [&args[..], &["--tool", "gripper"]].concat();
    biscara(&dir, &args).success();
    let svg = std::fs::read_to_string(dir.join("laser.svg")).expect("svg");
    assert!(!svg.contains("burnt trace") && svg.contains("programmed path"));
}

#[test]
fn joints_events_carry_the_same_tool_column_as_interpolate_and_view_reads_them() {
    let dir = temp_dir("tool-joints-events");
    let print = "M83\nG0 X0 Y250 Z10\nG1 X20 E2 F1200\nG1 Y270 E1\nG1 E-0.5 F600\nG0 X0\nM2\n";
    std::fs::write(dir.join("print.gcode"), print).expect("write");
    let laser = repo_root().join("data/programs/laser_engraving.ngc");
    let laser = laser.to_str().expect("path");
    let cases = [
        (laser, "laser_power", &["--origin", "-30,250,0,0"][..]),
        ("print.gcode", "extruded_mm", &[][..]),
    ];
    for (program, column, extra) in cases {
        let common = [&[program, "--events", "--dt", "0.01"][..], extra].concat();
        let path = biscara(&dir, &[&["interpolate"][..], &common].concat());
        let joints = biscara(&dir, &[&["joints", "--derivatives"][..], &common].concat());
        let (path_header, path_rows) = csv(&path.success().stdout);
        let (header, rows) = csv(&joints.success().stdout);
        assert!(path_header.ends_with(&format!(",{column}")), "{path_header}");
        assert!(
            header.starts_with("t_s,theta1_rad,")
                && header.ends_with(&format!("ddd4_mm_s2,{column}")),
            "{header}"
        );
        // Row by row, the same time and the same tool value.
        assert_eq!(rows.len(), path_rows.len(), "{program}");
        for (row, path_row) in rows.iter().zip(&path_rows) {
            assert_eq!((row[0], row[13]), (path_row[0], path_row[5]), "{program}: {row:?}");
        }
        assert!(rows.iter().any(|row| row[13] != 0.0), "{program}: the tool never works");
        // The viewer and mjcf read a joint CSV with the tool's column.
        std::fs::write(dir.join("traj.csv"), &joints.stdout).expect("write");
        biscara(&dir, &["view", "traj.csv", "-o", "view.html"]).success();
        biscara(&dir, &["mjcf", "--traj", "traj.csv", "-o", "robot.xml"]).success();
    }
}

#[test]
fn a_reprap_program_that_feeds_no_filament_is_no_extruder_job() {
    let Some(realworld) = crate::dialects::realworld() else { return };
    // A PCB mill driven by RepRap firmware: M104 (its spindle) and no E word anywhere.
    let program = realworld.join("other/gcode-exporter-pcb-reprap.gcode");
    let dir = temp_dir("tool-reprap-mill");
    let path = program.to_str().expect("a UTF-8 path");
    let run = biscara(&dir, &["interpret", path]);
    run.success().stderr_has("read as marlin G-code");
    assert!(!run.stderr.contains("tool: extruder"), "{run}");
    // The same text with an E word is a printer's again.
    let text = std::fs::read_to_string(&program).expect("read").replace("G1 Z-0.2 F60", "G92 E0");
    std::fs::write(dir.join("printer.gcode"), text).expect("write");
    biscara(&dir, &["interpret", "printer.gcode"])
        .success()
        .stderr_has("tool: extruder (printer codes");
}
