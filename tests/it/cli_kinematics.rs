//! `biscara ik`, `fk`, `robot`, the `--robot` option, exit codes and help texts.

use crate::golden::check_golden;
use crate::util::{biscara, biscara_with_input, temp_dir};

fn numbers(text: &str) -> Vec<f64> {
    text.split_whitespace().map(|word| word.parse().expect("a number")).collect()
}

#[test]
fn ik_then_fk_gives_the_pose_back() {
    let dir = temp_dir("ik-fk");
    let ik = biscara(&dir, &["ik", "150", "320", "10", "30"]);
    ik.success();
    let joints = numbers(&ik.stdout);
    assert_eq!(joints.len(), 4, "{ik}");
    assert_eq!(joints[3], 90.0, "d4 = lp - z");
    let args: Vec<String> = joints.iter().map(|value| format!("{value}")).collect();
    let mut fk_args = vec!["fk"];
    fk_args.extend(args.iter().map(String::as_str));
    let fk = biscara(&dir, &fk_args);
    fk.success();
    let pose = numbers(&fk.stdout);
    for (got, want) in pose.iter().zip([150.0, 320.0, 10.0, 30.0]) {
        assert!((got - want).abs() < 1e-5, "{fk}");
    }
}

/// `fk` prints c wrapped into (−180°, 180°], as `ik` reads it: `fk(ik(p))` is p for a c given
/// outside that range too (it printed −320.107 for a pose `ik` was given as 39.893).
#[test]
fn fk_prints_c_wrapped_as_ik_reads_it() {
    let dir = temp_dir("fk-wrap");
    for (given, printed) in [(39.893, 39.893), (-320.107, 39.893), (200.0, -160.0), (-180.0, 180.0)]
    {
        let c = format!("{given}");
        let ik = biscara(&dir, &["ik", "100", "300", "10", &c]);
        ik.success();
        let mut args = vec!["fk".to_owned()];
        args.extend(numbers(&ik.stdout).iter().map(|value| format!("{value}")));
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let fk = biscara(&dir, &args);
        fk.success();
        let pose = numbers(&fk.stdout);
        assert!((pose[3] - printed).abs() < 1e-5, "c {given}: {fk}");
        let json = biscara(&dir, &[&["fk", "--json"][..], &args[1..]].concat());
        let value: serde_json::Value = serde_json::from_str(&json.stdout).expect("JSON");
        assert!((value["c"].as_f64().unwrap_or(f64::NAN) - printed).abs() < 1e-5, "{json}");
    }
}

#[test]
fn negative_numbers_are_values_not_flags() {
    let dir = temp_dir("negative");
    let run = biscara(&dir, &["ik", "-150", "300", "20", "0"]);
    run.success();
    assert_eq!(numbers(&run.stdout).len(), 4);
    biscara(&dir, &["fk", "-10", "20", "-5", "50"]).success();
}

#[test]
fn json_outputs_have_the_spec_fields() {
    let dir = temp_dir("json");
    let run = biscara(&dir, &["ik", "--json", "0", "460.798724079689", "100", "0"]);
    run.success();
    let value: serde_json::Value = serde_json::from_str(&run.stdout).expect("JSON");
    for key in ["theta1", "theta2", "theta3", "d4"] {
        assert!(value[key].as_f64().expect(key).abs() < 1e-9, "{run}");
    }
    assert_eq!(value["working_mode"], "+-");
    assert_eq!(value["assembly_mode"], "+");
    assert_eq!(value["singularity"]["type1_deg"].as_array().map(Vec::len), Some(2));
    assert!(value["singularity"]["type2_deg"].as_f64().is_some());

    let run = biscara(&dir, &["fk", "--json", "0", "0", "0", "0"]);
    run.success();
    check_golden("cli/fk_home.json", &run.stdout);
}

#[test]
fn exit_code_1_for_unreachable_poses_with_the_reason() {
    let dir = temp_dir("unreachable");
    biscara(&dir, &["ik", "900", "0", "0", "0"])
        .expect_code(1)
        .stderr_has("biscara: error: ")
        .stderr_has("chain 1 cannot reach")
        .stderr_has("320.000 mm too far");
    biscara(&dir, &["ik", "0", "60", "50", "0"]).expect_code(1).stderr_has("type-2 singularity");
    biscara(&dir, &["ik", "0", "400", "120", "0"])
        .expect_code(1)
        .stderr_has("d4 = -20.000 mm is outside its limits [0, 100] by 20.000 mm");
    biscara(&dir, &["ik", "nan", "400", "50", "0"]).expect_code(1).stderr_has("not a finite");
    biscara(&dir, &["fk", "0", "0", "0", "0"]).success();
    // Elbows 620 mm apart, more than 2·l2 = 540: the links cannot meet.
    biscara(&dir, &["fk", "-90", "90", "0", "0"]).expect_code(1).stderr_has("cannot meet");
}

#[test]
fn fk_outside_the_limits_answers_with_a_warning() {
    let dir = temp_dir("fk-warning");
    biscara(&dir, &["fk", "0", "0", "200", "50"])
        .success()
        .stderr_has("warning: theta3 = 200.000° is outside its limits");
}

#[test]
fn exit_code_2_for_wrong_usage() {
    let dir = temp_dir("usage");
    biscara(&dir, &["ik", "1", "2"]).expect_code(2);
    biscara(&dir, &["ik", "a", "2", "3", "4"]).expect_code(2);
    biscara(&dir, &["no-such-command"]).expect_code(2);
    biscara(&dir, &["ik", "--bogus", "1", "2", "3", "4"]).expect_code(2);
}

#[test]
fn robot_prints_a_template_that_reads_back() {
    let dir = temp_dir("robot");
    let run = biscara(&dir, &["robot"]);
    run.success();
    std::fs::write(dir.join("copy.json"), &run.stdout).expect("write");
    let again = biscara(&dir, &["--robot", "copy.json", "robot"]);
    assert_eq!(again.success().stdout, run.stdout);
    biscara(&dir, &["robot", "-o", "written.json"]).success();
    assert_eq!(std::fs::read_to_string(dir.join("written.json")).expect("read"), run.stdout);
}

#[test]
fn robot_file_from_standard_input() {
    let dir = temp_dir("robot-stdin");
    let run = biscara_with_input(&dir, &["--robot", "-", "robot"], Some(br#"{"lp": 120}"#));
    run.success();
    assert!(run.stdout.contains("\"lp\": 120.0"), "{run}");
}

#[test]
fn bad_robot_files_name_the_file_line_and_key() {
    let dir = temp_dir("bad-robot");
    let cases: [(&str, &str, &str); 8] = [
        ("unknown.json", "{\n  \"links\": {\"l1\": 210, \"l3\": 1}\n}", "unknown.json:2:"),
        (
            "negative.json",
            "{\n  \"links\": {\n    \"l2\": -5\n  }\n}",
            "negative.json:3:5: links.l2: must be positive",
        ),
        (
            "base.json",
            r#"{"base": {"b1x": -100, "b2x": 100}}"#,
            "base.b1x: must be greater than base.b2x",
        ),
        (
            "limits.json",
            r#"{"joint_limits": {"theta1": [90, -90]}}"#,
            "joint_limits.theta1: the range [90, -90] is empty",
        ),
        ("mode.json", r#"{"working_mode": "+"}"#, "working_mode: unknown working mode `+`"),
        ("empty.json", "", "empty.json:1: EOF while parsing"),
        ("binary.json", "\u{0}\u{1}\u{2}", "binary.json:1:1"),
        ("trailing.json", "{} {}", "trailing characters"),
    ];
    for (name, text, message) in cases {
        std::fs::write(dir.join(name), text).expect("write");
        biscara(&dir, &["--robot", name, "ik", "0", "400", "50", "0"])
            .expect_code(1)
            .stderr_has(message);
    }
    std::fs::write(dir.join("latin1.json"), b"{\"name\": \"caf\xe9\"}").expect("write");
    biscara(&dir, &["--robot", "latin1.json", "robot"]).expect_code(1).stderr_has("not UTF-8");
    biscara(&dir, &["--robot", "missing.json", "robot"])
        .expect_code(1)
        .stderr_has("cannot read missing.json");
}

#[test]
fn a_failed_robot_output_leaves_no_file() {
    let dir = temp_dir("robot-atomic");
    std::fs::write(dir.join("bad.json"), "{\"lp\": [}").expect("write");
    biscara(&dir, &["--robot", "bad.json", "robot", "-o", "out.json"]).expect_code(1);
    assert!(!dir.join("out.json").exists());
    let leftovers: Vec<_> = std::fs::read_dir(&dir).expect("dir").collect();
    assert_eq!(leftovers.len(), 1, "only bad.json remains");
}

#[test]
fn every_help_text_is_pinned() {
    let dir = temp_dir("help");
    let main = biscara(&dir, &["--help"]);
    check_golden("help/biscara.txt", &main.success().stdout);
    for command in ["ik", "fk", "robot", "demo"] {
        let run = biscara(&dir, &[command, "--help"]);
        run.success();
        assert!(run.stdout.contains("Example:"), "{run}");
        check_golden(&format!("help/{command}.txt"), &run.stdout);
    }
}
