//! `biscara mjcf` and `biscara view` on the command line (issue 7): outputs, the joint-CSV reader's
//! errors (`FILE:LINE:COL`, exit 1, nothing written), help texts.

use crate::util::{biscara, temp_dir};

const HEADER: &str = "t_s,theta1_rad,theta2_rad,theta3_rad,d4_mm\n";

/// Bad trajectories for both commands: message prefix, exit 1, no output file.
#[test]
fn bad_trajectories_name_file_line_and_column_and_write_nothing() {
    let cases: [(&str, Vec<u8>, &str); 6] = [
        ("empty", Vec::new(), "traj.csv:1:1: expected a joint CSV header"),
        ("binary", b"\x00\x01\xff\xfe\x80garbage\n".to_vec(), "traj.csv:1:1: "),
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
        let dir = temp_dir(&format!("view-bad-{name}"));
        std::fs::write(dir.join("traj.csv"), &input).expect("write input");
        let run = biscara(&dir, &["mjcf", "-o", "robot.xml", "--traj", "traj.csv"]);
        run.expect_code(1).stderr_has(expected);
        let left: Vec<_> = std::fs::read_dir(&dir)
            .expect("read dir")
            .map(|entry| entry.expect("entry").file_name().to_string_lossy().into_owned())
            .collect();
        assert_eq!(left, ["traj.csv"], "{name}: files left behind\n{run}");
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
const PINNED_HELP: &[&str] = &["mjcf"];

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
