//! `biscara cycle` (issue 36): the Adept cycle's time, torques and sustained rate.

use serde_json::Value;

use crate::util::{biscara, temp_dir};

/// The default robot with motors that bind on the cycle, and `payload_kg` in its dynamics.
fn robot_with_motors(dir: &std::path::Path, payload_kg: f64) -> String {
    let mut robot: Value =
        serde_json::from_str(&biscara(dir, &["robot"]).success().stdout).expect("robot JSON");
    robot["motors"] = serde_json::json!({
        "theta1": {"peak": 0.8, "rated": 0.3, "rotor_inertia": 0.002, "coulomb": 0.02},
        "theta2": {"peak": 0.8, "rated": 0.3, "rotor_inertia": 0.002, "coulomb": 0.02},
        "theta3": {"peak": 0.05, "rated": 0.02},
        "d4": {"peak": 40.0, "rated": 20.0, "rotor_inertia": 0.3, "coulomb": 0.5}
    });
    robot["dynamics"]["payload"] = serde_json::json!({"mass": payload_kg});
    let path = dir.join("motors.json");
    std::fs::write(&path, robot.to_string()).expect("robot file");
    path.to_str().expect("path").to_owned()
}

fn cycle_json(dir: &std::path::Path, args: &[&str]) -> Value {
    let run = biscara(dir, args);
    run.success();
    serde_json::from_str(&run.stdout).expect("cycle JSON")
}

fn duration_of(csv: &std::path::Path) -> f64 {
    let text = std::fs::read_to_string(csv).expect("joint CSV");
    text.lines().last().and_then(|l| l.split(',').next()?.parse().ok()).expect("time")
}

/// Without motors: centred at the largest rectangle's centre, and as long as the same rapids
/// timed by `joints` (from the home pose, less the approach to the start point).
#[test]
fn the_cycle_is_the_rapids_that_joints_times() {
    let dir = temp_dir("cycle-plain");
    let report = cycle_json(&dir, &["cycle", "--json"]);
    let workspace: Value =
        serde_json::from_str(&biscara(&dir, &["workspace", "--json"]).success().stdout)
            .expect("workspace JSON");
    let (min, max) = (&workspace["rectangle"]["min"], &workspace["rectangle"]["max"]);
    let centre =
        [0, 1].map(|k| 0.5 * (min[k].as_f64().expect("min") + max[k].as_f64().expect("max")));
    assert_eq!(report["at"], serde_json::json!(centre));
    assert_eq!(report["z"], 40.0);
    assert!(report["sustained_cycles_per_min"].is_null(), "{report}");
    assert!(report["peak"]["theta1"]["limit"].is_null(), "{report}");
    let [x, y] = centre;
    let (left, right) = (x - 152.5, x + 152.5);
    let approach = format!("G21 G90 G61\nG0 X{left} Y{y} Z40 C0\n");
    let cycle = format!("{approach}G0 Z65\nG0 X{right}\nG0 Z40\nG0 Z65\nG0 X{left}\nG0 Z40\nM2\n");
    std::fs::write(dir.join("approach.ngc"), format!("{approach}M2\n")).expect("write");
    std::fs::write(dir.join("cycle.ngc"), cycle).expect("write");
    biscara(&dir, &["joints", "approach.ngc", "-o", "a.csv"]).success();
    biscara(&dir, &["joints", "cycle.ngc", "-o", "c.csv"]).success();
    let expected = duration_of(&dir.join("c.csv")) - duration_of(&dir.join("a.csv"));
    let cycle_s = report["cycle_s"].as_f64().expect("cycle_s");
    assert!((cycle_s - expected).abs() < 1e-9, "cycle {cycle_s} s, joints {expected} s");
}

/// With motors: every peak within the motor's peak (the torque-limited profile), a payload
/// makes the cycle slower and loads d4 more, blending makes it faster, and the sustained rate
/// is the cycle plus its dwell.
#[test]
fn motors_bound_the_cycle_and_set_the_sustained_rate() {
    let dir = temp_dir("cycle-motors");
    let robot = robot_with_motors(&dir, 0.0);
    let light = cycle_json(&dir, &["--robot", &robot, "cycle", "--json"]);
    let heavy = cycle_json(&dir, &["--robot", &robot, "cycle", "--json", "--payload", "1.5"]);
    let blended = cycle_json(
        &dir,
        &["--robot", &robot, "cycle", "--json", "--payload", "1.5", "--blend", "5"],
    );
    let number = |report: &Value, path: &[&str]| {
        path.iter()
            .fold(report, |value, key| &value[*key])
            .as_f64()
            .unwrap_or_else(|| panic!("{}", path.join(".")))
    };
    for report in [&light, &heavy, &blended] {
        for joint in ["theta1", "theta2", "theta3", "d4"] {
            let peak = number(report, &["peak", joint, "value"]);
            let limit = number(report, &["peak", joint, "limit"]);
            assert!(peak <= limit * (1.0 + 1e-6), "{joint}: {peak} > {limit}\n{report}");
            assert!(number(report, &["rms", joint, "value"]) <= peak + 1e-9, "{report}");
        }
        let (cycle, dwell) = (number(report, &["cycle_s"]), number(report, &["dwell_s"]));
        let rate = number(report, &["sustained_cycles_per_min"]);
        assert!((rate - 60.0 / (cycle + dwell)).abs() < 1e-3, "{report}");
    }
    assert!(number(&heavy, &["cycle_s"]) > number(&light, &["cycle_s"]), "{light}\n{heavy}");
    assert!(number(&heavy, &["rms", "d4", "value"]) > number(&light, &["rms", "d4", "value"]));
    assert!(number(&blended, &["cycle_s"]) < number(&heavy, &["cycle_s"]), "{blended}");
    assert_eq!(heavy["payload_kg"], 1.5);
    // The binding motors (θ1, θ2 at 0.8 N·m) need a dwell to keep within 0.3 N·m RMS.
    assert!(number(&heavy, &["dwell_s"]) > 0.0, "{heavy}");
    let text = biscara(&dir, &["--robot", &robot, "cycle"]);
    text.success();
    assert!(text.stdout.contains("cycle time: ") && text.stdout.contains("sustained: "), "{text}");
}

#[test]
fn an_unreachable_cycle_names_its_corner() {
    let dir = temp_dir("cycle-unreachable");
    let run = biscara(&dir, &["cycle", "--at", "0,600"]);
    run.expect_code(1)
        .stderr_has("the cycle's start (left, low) at (x, y, z) = (-152.500, 600.000");
    assert!(run.stdout.is_empty(), "{run}");
    // 25 mm up from z 95 is beyond d4's range.
    let run = biscara(&dir, &["cycle", "--at", "0,200", "--z", "95"]);
    run.expect_code(1)
        .stderr_has("the cycle's left, up at (x, y, z) = (-152.500, 200.000, 120.000)");
    biscara(&dir, &["cycle", "--at", "1,2,3"])
        .expect_code(2)
        .stderr_has("expected two numbers X,Y");
    biscara(&dir, &["cycle", "--payload=-1"]).expect_code(1).stderr_has("the payload must be");
    // A negative number after the flag is its value, not another flag.
    biscara(&dir, &["cycle", "--payload", "-1"]).expect_code(1).stderr_has("the payload must be");
    biscara(&dir, &["cycle", "--blend", "-1"])
        .expect_code(1)
        .stderr_has("the blend tolerance must be");
}
