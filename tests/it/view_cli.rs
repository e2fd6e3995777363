//! `biscara mjcf` and `biscara view` on the command line (issue 7): outputs, the joint-CSV reader's
//! errors (`FILE:LINE:COL`, exit 1, nothing written), help texts.

use crate::util::{biscara, temp_dir};

const HEADER: &str = "t_s,theta1_rad,theta2_rad,theta3_rad,d4_mm\n";

/// Bad trajectories for both commands: message prefix, exit 1, no output file.
#[test]
fn bad_trajectories_name_file_line_and_column_and_write_nothing() {
    let cases: [(&str, Vec<u8>, &str); 7] = [
        (
            "huge",
            format!("{HEADER}0,{}", "9".repeat(200_000)).into_bytes(),
            "traj.csv:2: the line is longer than 65536 bytes",
        ),
        ("empty", Vec::new(), "traj.csv:1:1: expected a joint CSV header"),
        ("binary", b"\x00\x01\xff\xfe\x80garbage\n".to_vec(), "traj.csv:1: stream did not contain"),
        ("header", b"t,a,b\n0,0,0\n".to_vec(), "traj.csv:1:1: expected a joint CSV header"),
        ("columns", format!("{HEADER}0,0,0,0\n").into_bytes(), "traj.csv:2:8: expected 5 fields"),
        (
            "nan",
            format!("{HEADER}0,0,nan,0,0\n").into_bytes(),
            "traj.csv:2:5: `nan` is not a finite",
        ),
        (
            "assembly",
            format!("{HEADER}0,0,0,0,0\n0.001,-1.6,1.6,0,0\n").into_bytes(),
            "traj.csv:3: at t = 0.001 s the joints do not assemble",
        ),
    ];
    for (name, input, expected) in cases {
        for command in [
            &["mjcf", "-o", "robot.xml", "--traj", "traj.csv"][..],
            &["view", "traj.csv", "-o", "view.html"][..],
        ] {
            let dir = temp_dir(&format!("view-bad-{name}"));
            std::fs::write(dir.join("traj.csv"), &input).expect("write input");
            let run = biscara(&dir, command);
            run.expect_code(1).stderr_has(expected);
            let left: Vec<_> = std::fs::read_dir(&dir)
                .expect("read dir")
                .map(|entry| entry.expect("entry").file_name().to_string_lossy().into_owned())
                .collect();
            assert_eq!(left, ["traj.csv"], "{name}: files left behind\n{run}");
        }
    }
}

#[test]
fn mjcf_writes_the_model_and_reads_scenes() {
    let dir = temp_dir("mjcf-scene");
    std::fs::write(
        dir.join("scene.json"),
        r#"{"boxes":[{"name":"pallet","min":[100,250,0],"max":[200,350,10]}]}"#,
    )
    .expect("write scene");
    let run = biscara(&dir, &["mjcf", "--scene", "scene.json"]);
    run.success();
    assert!(run.stdout.starts_with("<!--") && run.stdout.contains("name=\"scene_pallet\""));
    std::fs::write(dir.join("bad.json"), "{\"boxes\": [\n  {\"name\": \"a\", \"min\": [0,0]}]}")
        .expect("write scene");
    biscara(&dir, &["mjcf", "--scene", "bad.json", "-o", "robot.xml"])
        .expect_code(1)
        .stderr_has("bad.json:2:");
    assert!(!dir.join("robot.xml").exists());
    // --traj needs a file to write beside.
    biscara(&dir, &["mjcf", "--traj", "traj.csv"]).expect_code(2);
}

/// The subcommands of issue 7 whose help is pinned in tests/golden/help/.
const PINNED_HELP: &[&str] = &["mjcf", "view"];

#[test]
fn view_and_mjcf_help_texts_are_pinned() {
    let dir = temp_dir("view-help");
    for &command in PINNED_HELP {
        let run = biscara(&dir, &[command, "--help"]);
        run.success();
        assert!(run.stdout.contains("Example:"), "{run}");
        crate::golden::check_golden(&format!("help/{command}.txt"), &run.stdout);
    }
}

#[test]
fn view_writes_one_self_contained_page_with_the_program() {
    let dir = temp_dir("view-page");
    biscara(&dir, &["demo", "out"]).success();
    std::fs::write(
        dir.join("scene.json"),
        r#"{"boxes":[{"name":"pallet","min":[100,250,0],"max":[200,350,10]}]}"#,
    )
    .expect("write scene");
    let run = biscara(
        &dir,
        &["view", "out/traj.csv", "--program", "out/job.ngc", "--scene", "scene.json"],
    );
    run.success();
    let page = &run.stdout;
    assert!(page.starts_with("<!DOCTYPE html>"), "{}", &page[..100.min(page.len())]);
    // Nothing from the network or other files: no URLs, no src/href attributes. The one URI
    // of the page is the XHTML namespace three.js passes to createElementNS (a name, never
    // fetched).
    assert_eq!(page.matches("http://www.w3.org/1999/xhtml").count(), 1);
    let page = &page.replace("http://www.w3.org/1999/xhtml", "");
    for needle in
        ["http:", "https:", " src=", " href=", "@import", "url(", "fetch(", "XMLHttpRequest"]
    {
        assert!(!page.contains(needle), "the page refers to something outside: {needle}");
    }
    assert!(page.contains("\"name\":\"pallet\""), "scene");
    assert!(page.contains("G1 Z10.000 F3000.0"), "the G-code text of the feed moves");
    // Two picks and two places of the demo job.
    let events = page.split("\"events\":[").nth(1).and_then(|rest| rest.split("]]").next());
    let events = events.expect("events");
    assert_eq!(events.matches(",1,").count(), 2, "{events}");
    assert_eq!(events.matches(",0,").count(), 2, "{events}");
    // The inter-file gives the same lines and events as the G-code it came from.
    let from_jsonl = biscara(
        &dir,
        &["view", "out/traj.csv", "--program", "out/job.jsonl", "--scene", "scene.json"],
    );
    from_jsonl.success();
    let lines = |page: &str| {
        page.split("\"lines\":[").nth(1).map(|s| s[..s.find(']').unwrap_or(0)].to_owned())
    };
    assert_eq!(lines(&from_jsonl.stdout), lines(page));
    // Without a program the page still works: no path, no lines.
    let bare = biscara(&dir, &["view", "out/traj.csv"]);
    bare.success();
    assert!(bare.stdout.contains("\"path\":[],\"lines\":[]"));
}

#[test]
fn view_samples_the_program_as_the_trajectory_was_made() {
    let dir = temp_dir("view-sampling");
    biscara(&dir, &["demo", "out"]).success();
    let made = ["joints", "out/job.ngc", "--profile", "constant", "--grip-time", "0.3"];
    biscara(&dir, &[&made[..], &["-o", "slow.csv"]].concat()).success();
    // With the defaults the program runs shorter than the trajectory: a warning.
    let defaults = biscara(&dir, &["view", "slow.csv", "--program", "out/job.ngc"]);
    defaults.success();
    assert!(defaults.stderr.contains("warning"), "{defaults}");
    // With the same sampling, no warning, and the events fall where the trajectory has them.
    let same = biscara(
        &dir,
        &[
            "view",
            "slow.csv",
            "--program",
            "out/job.ngc",
            "--profile",
            "constant",
            "--grip-time",
            "0.3",
        ],
    );
    same.success();
    assert!(!same.stderr.contains("warning"), "{same}");
    // Each pick and place is where the trajectory's tool is at that time (FK of its row), and
    // when the gripper's state changes in the samples `interpolate --events` writes.
    let trajectory = std::fs::read_to_string(dir.join("slow.csv")).expect("trajectory");
    let model = biscara::kinematics::RobotModel::default().kinematics();
    let tool_at = |t: f64| -> [f64; 3] {
        let row: Vec<f64> = trajectory
            .lines()
            .skip(1)
            .map(|line| line.split(',').map(|v| v.parse().expect("number")).collect::<Vec<f64>>())
            .find(|row| (row[0] - t).abs() < 1e-9)
            .unwrap_or_else(|| panic!("no row at t = {t}"));
        let joints = biscara::kinematics::Joints {
            theta1: row[1],
            theta2: row[2],
            theta3: row[3],
            d4: row[4],
        };
        let pose = model.forward(&joints).expect("FK").pose;
        [pose.x, pose.y, pose.z]
    };
    let samples = biscara(
        &dir,
        &["interpolate", "out/job.ngc", "--profile", "constant", "--grip-time", "0.3", "--events"],
    );
    let mut changes = Vec::new();
    let mut gripper = "0";
    for line in samples.success().stdout.lines().skip(1) {
        let (t, state) =
            line.split_once(',').map(|(t, rest)| (t, rest.rsplit(',').next())).unwrap();
        let state = state.expect("gripper");
        if state != gripper {
            changes.push(t.parse::<f64>().expect("time"));
            gripper = if state == "0" { "0" } else { "1" };
        }
    }
    let events = page_events(&same.stdout);
    let events: Vec<&[f64]> = events.chunks(5).collect();
    assert_eq!(events.len(), 4, "two picks and two places");
    for (event, change) in events.iter().zip(&changes) {
        assert!((event[0] - change).abs() < 1e-9, "event at {} s, change at {change} s", event[0]);
        let at = tool_at(event[0]);
        let off = (0..3).map(|k| (at[k] - event[2 + k]).powi(2)).sum::<f64>().sqrt();
        assert!(off < 1e-3, "event {event:?}: the tool is at {at:?}");
    }
    // Sampled otherwise, the events fall where the trajectory's tool is not.
    let elsewhere = page_events(&defaults.stdout);
    let off = elsewhere.chunks(5).map(|event| {
        let at = trajectory
            .lines()
            .skip(1)
            .any(|line| {
                line.split(',').next().and_then(|t| t.parse::<f64>().ok()) == Some(event[0])
            })
            .then(|| tool_at(event[0]));
        at.map_or(f64::INFINITY, |at| {
            (0..3).map(|k| (at[k] - event[2 + k]).powi(2)).sum::<f64>().sqrt()
        })
    });
    assert!(off.fold(0.0, f64::max) > 1.0, "the default sampling's events matched too");
    let bad = biscara(&dir, &["view", "slow.csv", "--program", "out/job.ngc", "--grip-time", "-1"]);
    assert_eq!(bad.code, 2, "{bad}");
}

/// The numbers of a page's events, `"events":[[t,pick,x,y,z],…]`, in a row.
fn page_events(page: &str) -> Vec<f64> {
    let rest = page.split("\"events\":[").nth(1).expect("events");
    let list = &rest[..rest.find("]]").map_or(0, |end| end + 1)];
    let numbers = list.split([',', '[', ']']).filter(|v| !v.is_empty());
    numbers.map(|v| v.parse().expect("number")).collect()
}

/// The numbers of a page's data array `"name":[…]`.
fn page_numbers(page: &str, name: &str) -> Vec<f64> {
    let rest = page.split(&format!("\"{name}\":[")).nth(1).expect(name);
    let list = &rest[..rest.find(']').expect("]")];
    list.split(',').filter(|v| !v.is_empty()).map(|v| v.parse().expect("number")).collect()
}

/// The print's page holds its track layer by layer and the pen's its strokes (issue 14): the
/// process points `[t, x, y, z, strength, start]`, only where the tool works.
#[test]
fn view_holds_the_print_track_by_layer_and_the_pen_strokes() {
    let dir = temp_dir("view-process");
    let root = crate::util::repo_root();
    for (program, origin, tool, layers) in [
        ("print_square.gcode", "-10,270,0,0", "extruder", 2),
        ("pen_plot.ngc", "-30,280,10,0", "pen", 1),
    ] {
        let path = root.join("data/programs").join(program);
        let path = path.to_str().expect("path");
        let placed = ["--origin", origin];
        biscara(&dir, &[&["joints", path, "-o", "traj.csv"][..], &placed].concat()).success();
        let run = biscara(&dir, &[&["view", "traj.csv", "--program", path][..], &placed].concat());
        let page = &run.success().stdout;
        assert!(page.contains(&format!("\"tool\":{{\"kind\":\"{tool}\"")), "{program}");
        let points = page_numbers(page, "process");
        assert!(
            points.len() > 6 * 50 && points.len().is_multiple_of(6),
            "{program}: {}",
            points.len()
        );
        let mut heights: Vec<f64> = points.chunks(6).map(|p| p[3]).collect();
        heights.dedup();
        assert_eq!(heights.len(), layers, "{program}: layer heights {heights:?}");
        // Strokes: the print's walls and infills, the pen's star and circle.
        let strokes = points.chunks(6).filter(|p| p[5] == 1.0).count();
        assert_eq!(strokes, if tool == "pen" { 2 } else { 4 }, "{program}");
        // Every point is on the work: the print's 20 mm square, the pen's star-in-a-circle.
        for p in points.chunks(6) {
            let inside = match tool {
                "pen" => (p[1] + 0.0).hypot(p[2] - 310.0) <= 25.0 + 1e-3,
                _ => {
                    (-10.0 - 1e-3..=10.0 + 1e-3).contains(&p[1])
                        && (270.0 - 1e-3..=290.0 + 1e-3).contains(&p[2])
                }
            };
            assert!(inside, "{program}: {p:?} is not on the work");
        }
        // The work starts and stops: on (1) and off (−1) alternate.
        let work = page_numbers(page, "work");
        let states: Vec<f64> = work.chunks(2).map(|w| w[1]).collect();
        assert_eq!(states.len(), 2 * strokes, "{program}: {states:?}");
    }
}

/// `view --check REPORT` marks a `check --json` report's problems (time, kind, message in the
/// page's data); a bad report names the file (and line and column for bad JSON), exits 1 and
/// writes nothing.
#[test]
fn view_marks_the_problems_of_a_check_report_and_rejects_bad_reports() {
    let dir = temp_dir("view-check");
    biscara(&dir, &["demo", "out"]).success();
    std::fs::write(
        dir.join("report.json"),
        r#"{"ok":false,"problems":[{"kind":"scene_collision","line":9,"t_s":3.25,"message":"the tool hits pallet"}],"summary":{}}"#,
    )
    .expect("write report");
    let run = biscara(&dir, &["view", "out/traj.csv", "--check", "report.json"]);
    run.success();
    assert!(
        run.stdout.contains(r#""problems":[[3.25,"scene_collision","the tool hits pallet"]]"#),
        "problems"
    );
    // The demo's own report is clean: no problem to mark.
    let clean = biscara(&dir, &["view", "out/traj.csv", "--check", "out/check.json"]);
    clean.success();
    assert!(clean.stdout.contains(r#""problems":[]"#));
    let cases = [
        ("{\"problems\": [\n  {\"kind\": }]}", "bad.json:2:12: not a check --json report"),
        ("{\"ok\": true}", "bad.json:1:12: not a check --json report: .: missing field `problems`"),
        (
            "{\"problems\":[{\"kind\":\"tool\"}]}",
            "bad.json:1:28: not a check --json report: problems[0]: missing field `t_s`",
        ),
        (
            "{\"problems\":[{\"kind\":\"limit\",\"t_s\":1}]}",
            "bad.json:1:28: not a check --json report: problems[0].kind: unknown kind `limit`",
        ),
    ];
    for (text, expected) in cases {
        std::fs::write(dir.join("bad.json"), text).expect("write bad report");
        let run =
            biscara(&dir, &["view", "out/traj.csv", "--check", "bad.json", "-o", "view.html"]);
        run.expect_code(1).stderr_has(expected);
        assert!(!dir.join("view.html").exists(), "{expected}: a page was written");
    }
}

/// `view --object WxLxH` sets the objects' size in the page; a malformed size is wrong usage.
#[test]
fn view_takes_the_object_size_and_rejects_malformed_ones() {
    let dir = temp_dir("view-object");
    biscara(&dir, &["demo", "out"]).success();
    let run = biscara(&dir, &["view", "out/traj.csv", "--object", "30x20x15.5"]);
    run.success();
    assert!(run.stdout.contains("\"object\":[30,20,15.5]"));
    let default = biscara(&dir, &["view", "out/traj.csv"]);
    assert!(default.stdout.contains("\"object\":null"));
    for bad in ["30x20", "30x20x0", "axbxc", "30x20x15x1", "30x-2x15"] {
        let run = biscara(&dir, &["view", "out/traj.csv", "--object", bad, "-o", "v.html"]);
        run.expect_code(2).stderr_has("is not WxLxH");
        assert!(!dir.join("v.html").exists(), "{bad}");
    }
}

/// The twelve triangles of the box from `min` to `max`, outward winding.
fn box_triangles(min: [f64; 3], max: [f64; 3]) -> Vec<[[f64; 3]; 3]> {
    let corner = |k: usize| {
        [
            if k & 4 == 0 { min[0] } else { max[0] },
            if k & 2 == 0 { min[1] } else { max[1] },
            if k & 1 == 0 { min[2] } else { max[2] },
        ]
    };
    let faces = [
        [0, 1, 3],
        [0, 3, 2],
        [4, 6, 7],
        [4, 7, 5],
        [0, 4, 5],
        [0, 5, 1],
        [2, 3, 7],
        [2, 7, 6],
        [0, 2, 6],
        [0, 6, 4],
        [1, 5, 7],
        [1, 7, 3],
    ];
    faces.iter().map(|face| face.map(corner)).collect()
}

/// Writes the box from `min` to `max` as an STL file: ASCII, or binary with a header that
/// begins with `solid` as some CAD programs write it.
pub(crate) fn write_box_stl(path: &std::path::Path, min: [f64; 3], max: [f64; 3], ascii: bool) {
    let triangles = box_triangles(min, max);
    let bytes = if ascii {
        let mut text = String::from("solid box\n");
        for triangle in &triangles {
            text.push_str(" facet normal 0 0 0\n  outer loop\n");
            for [x, y, z] in triangle {
                text.push_str(&format!("   vertex {x} {y} {z}\n"));
            }
            text.push_str("  endloop\n endfacet\n");
        }
        text.push_str("endsolid box\n");
        text.into_bytes()
    } else {
        let mut bytes = format!("{:<80}", "solid box, binary").into_bytes();
        bytes.extend(u32::try_from(triangles.len()).expect("count").to_le_bytes());
        for triangle in &triangles {
            bytes.extend([0u8; 12]);
            for value in triangle.iter().flatten() {
                bytes.extend((*value as f32).to_le_bytes());
            }
            bytes.extend([0u8; 2]);
        }
        bytes
    };
    std::fs::write(path, bytes).expect("write STL");
}

/// A trajectory of two rows the default robot takes.
const TWO_ROWS: &str =
    "t_s,theta1_rad,theta2_rad,theta3_rad,d4_mm\n0,0,0,0,10\n0.001,0.01,0,0,10\n";

/// Meshes named by robot.json: read from the robot file's folder (binary and ASCII, a scale),
/// embedded in the page; a missing file, an unknown part and malformed STL are located errors
/// with exit 1 and no page written.
#[test]
fn view_embeds_the_robot_files_meshes_and_rejects_bad_ones() {
    let dir = temp_dir("view-meshes");
    std::fs::create_dir_all(dir.join("robot/parts")).expect("mkdir");
    std::fs::write(dir.join("traj.csv"), TWO_ROWS).expect("write traj");
    write_box_stl(&dir.join("robot/parts/arm.stl"), [0.0, -10.0, -5.0], [210.0, 10.0, 5.0], true);
    write_box_stl(&dir.join("robot/tool.stl"), [-0.01, -0.01, 0.0], [0.01, 0.01, 0.03], false);
    let robot = "{\n  \"meshes\": {\n    \"proximal1\": \"parts/arm.stl\",\n    \
                 \"tool\": {\"file\": \"tool.stl\", \"scale\": 1000}\n  }\n}\n";
    std::fs::write(dir.join("robot/robot.json"), robot).expect("write robot");
    let view = ["--robot", "robot/robot.json", "view", "traj.csv", "-o", "view.html"];
    biscara(&dir, &view).success();
    let page = std::fs::read_to_string(dir.join("view.html")).expect("page");
    assert!(page.contains("\"meshes\":[{\"part\":\"proximal1\",\"triangles\":12,\"data\":\""));
    assert!(page.contains("{\"part\":\"tool\",\"triangles\":12,\"data\":\""));
    std::fs::remove_file(dir.join("view.html")).expect("rm");

    let cases: [(&str, &str, &[u8], &str); 6] = [
        (
            "\"proximal1\": \"parts/missing.stl\"",
            "arm.stl",
            b"",
            "robot.json:3:5: meshes.proximal1: cannot read the STL file",
        ),
        (
            "\"elbow\": \"parts/arm.stl\"",
            "arm.stl",
            b"",
            "robot.json:3:11: meshes.elbow: unknown field `elbow`",
        ),
        (
            "\"proximal1\": \"parts/bad.stl\"",
            "bad.stl",
            b"solid x\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 nan\n",
            "bad.stl:4:15: the vertex's z = NaN is not a finite number",
        ),
        (
            "\"proximal1\": \"parts/bad.stl\"",
            "bad.stl",
            b"solid x\n facet normal 0 0 1\n  outer loop\n   vertex 0 0",
            "bad.stl:4:14: the file ends where the vertex's z should be",
        ),
        (
            "\"proximal1\": \"parts/bad.stl\"",
            "bad.stl",
            &[7u8; 100],
            "bad.stl: byte 80: the header announces 117901063 triangles: more than 200000",
        ),
        (
            "\"proximal1\": \"parts/bad.stl\"",
            "bad.stl",
            b"\x89PNG\r\n",
            "bad.stl: byte 6: not an STL file",
        ),
    ];
    for (entry, file, bytes, expected) in cases {
        if !bytes.is_empty() {
            std::fs::write(dir.join("robot/parts").join(file), bytes).expect("write STL");
        }
        let robot = format!("{{\n  \"meshes\": {{\n    {entry}\n  }}\n}}\n");
        std::fs::write(dir.join("robot/robot.json"), robot).expect("write robot");
        biscara(&dir, &view).expect_code(1).stderr_has(expected);
        assert!(!dir.join("view.html").exists(), "{expected}: a page was written");
    }
}
