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
