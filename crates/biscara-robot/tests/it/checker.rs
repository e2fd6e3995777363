//! The checker on hand-made sample streams.

use biscara_interpolate::CartesianSample;
use biscara_kinematics::RobotModel;
use biscara_robot::{Checker, ProblemKind, Scene};

fn sample(t: f64, pose: [f64; 4], line: usize) -> CartesianSample {
    CartesianSample { t, pose, line, gripper: false }
}

#[test]
fn one_long_violation_is_one_problem_with_its_span() {
    let mut checker = Checker::new(&RobotModel::default(), Scene::new());
    // z from 90 to 130 in 1 mm steps, 10 ms apart: d4 = 100 − z is below 0 for z > 100.
    for k in 0..=40 {
        let z = 90.0 + f64::from(k);
        checker.push(&sample(0.01 * f64::from(k), [0.0, 400.0, z, 0.0], 7));
    }
    let report = checker.finish();
    let limits: Vec<_> =
        report.problems.iter().filter(|p| p.kind == ProblemKind::JointLimit).collect();
    assert_eq!(limits.len(), 1, "{:#?}", report.problems);
    let problem = limits[0];
    assert_eq!(problem.subject, "d4");
    assert_eq!(problem.line, 7);
    assert!((problem.t_start - 0.11).abs() < 1e-12, "{problem:?}"); // z = 101
    assert!((problem.t_end - 0.40).abs() < 1e-12, "{problem:?}"); // z = 130
    assert_eq!(problem.samples, 30);
    assert_eq!(problem.pose[2], 101.0);
    assert_eq!(problem.pose_worst[2], 130.0);
    assert!(problem.message().contains("by 30.000 mm"), "{}", problem.message());
}

#[test]
fn an_unreachable_stretch_does_not_stop_the_check() {
    let mut checker = Checker::new(&RobotModel::default(), Scene::new());
    let ys = [400.0, 450.0, 600.0, 700.0, 450.0, 400.0];
    for (k, y) in ys.iter().enumerate() {
        checker.push(&sample(k as f64, [0.0, *y, 50.0, 0.0], k + 1));
    }
    let report = checker.finish();
    let unreachable: Vec<_> =
        report.problems.iter().filter(|p| p.kind == ProblemKind::Unreachable).collect();
    assert_eq!(unreachable.len(), 1, "{:#?}", report.problems);
    assert_eq!((unreachable[0].line, unreachable[0].line_end), (3, 4));
    assert_eq!(report.summary.samples, 6);
    assert!(!report.ok());
}

/// The default robot with motors (θ's strong, d4's `peak` and `rated` as given) and a payload
/// of 1 kg.
fn with_motors(d4_peak: f64, d4_rated: f64) -> RobotModel {
    let mut json = serde_json::to_value(biscara_kinematics::Robot::default()).expect("robot");
    let strong = serde_json::json!({"peak": 50.0, "rated": 20.0});
    json["motors"] = serde_json::json!({
        "theta1": strong, "theta2": strong, "theta3": strong,
        "d4": {"peak": d4_peak, "rated": d4_rated, "coulomb": 0.0}
    });
    json["dynamics"] = serde_json::json!({"payload": {"mass": 1.0}});
    RobotModel::from_json(&json.to_string()).expect("robot with motors")
}

/// d4 holds the slide (and the payload while the gripper holds it) against gravity: its
/// force at rest is its RMS and its peak; a rating below it is an `rms_torque` problem over the
/// whole program, at its first motion's line.
#[test]
fn holding_the_slide_at_rest_is_the_rms_of_d4() {
    let model = with_motors(40.0, 1.0);
    let bodies = *biscara_dynamics::Dynamics::new(&model).expect("dynamics").bodies();
    for gripper in [false, true] {
        let mut checker = Checker::new(&model, Scene::new());
        for k in 0..=100 {
            let line = if k == 0 { 0 } else { 3 };
            let pose = [0.0, 400.0, 50.0, 0.0];
            checker.push(&CartesianSample { t: 0.01 * f64::from(k), pose, line, gripper });
        }
        let report = checker.finish();
        let torques = report.summary.torques.expect("motors");
        let mass = bodies.slide + if gripper { bodies.payload } else { 0.0 };
        let weight = mass * bodies.gravity;
        assert!((torques[3].rms - weight).abs() < 1e-9 * weight, "{torques:?}");
        assert!((torques[3].peak.value - weight).abs() < 1e-9 * weight, "{torques:?}");
        assert_eq!((torques[3].peak.limit, torques[3].rated), (40.0, 1.0));
        assert!(torques[0].rms.abs() < 1e-9, "{torques:?}");
        let kinds: Vec<_> = report.problems.iter().map(|p| (p.kind, p.subject.as_str())).collect();
        assert_eq!(kinds, [(ProblemKind::RmsTorque, "d4")], "{:#?}", report.problems);
        assert_eq!((report.problems[0].line, report.problems[0].line_end), (3, 3));
        let json = report.to_json();
        assert_eq!(json["problems"][0]["kind"], "rms_torque");
        assert_eq!(json["summary"]["rms_torque"]["d4"]["limit"], 1.0);
        assert!(json["summary"]["peak_torque"]["theta1"]["value"].is_number());
    }
}

/// A slide shaken up and down harder than d4's motor can push: `torque_limit` problems on d4,
/// each run of samples one problem; a clean robot file without motors has no torque figures.
#[test]
fn a_force_beyond_the_peak_is_a_torque_limit_problem() {
    // z = 50 + 10 sin(2π · 5 t): up to 10 · (10π)² ≈ 9870 mm/s², about 10 m/s² on top of g.
    let shake = |k: u32| {
        let t = 0.001 * f64::from(k);
        let z = 50.0 + 10.0 * (std::f64::consts::TAU * 5.0 * t).sin();
        CartesianSample { t, pose: [0.0, 400.0, z, 0.0], line: 2, gripper: true }
    };
    let mut checker = Checker::new(&with_motors(20.0, 15.0), Scene::new());
    for k in 0..=400 {
        checker.push(&shake(k));
    }
    let report = checker.finish();
    let over: Vec<_> =
        report.problems.iter().filter(|p| p.kind == ProblemKind::TorqueLimit).collect();
    // Beyond the peak once per period, where the slide is pushed up hardest (z lowest).
    assert_eq!(over.len(), 2, "{:#?}", report.problems);
    assert!(over.iter().all(|p| p.subject == "d4" && p.detail.contains("beyond its peak 20 N")));
    let peak = report.summary.torques.expect("motors")[3].peak;
    assert!(peak.value > 20.0 && peak.limit == 20.0, "{peak:?}");
    let mut plain = Checker::new(&RobotModel::default(), Scene::new());
    for k in 0..=400 {
        plain.push(&shake(k));
    }
    let report = plain.finish();
    assert!(report.summary.torques.is_none());
    assert!(report.to_json()["summary"].get("peak_torque").is_none());
}
