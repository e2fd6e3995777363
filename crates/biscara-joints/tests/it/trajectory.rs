//! Joint trajectories: FK of every row on the programmed path, θ3 continuous, derivatives consistent with the
//! positions, joint-velocity slow-down, failures naming line and time.

use std::convert::Infallible;

use biscara_interpolate::{
    InterpolationConfig, Interpolator, NoSpeedLimit, Profile, Segment, SlowDown,
};
use biscara_joints::{
    JointSample, JointSpeedLimit, JointTrajectory, JointsError, SampleError, cartesian_limits,
};
use biscara_kinematics::{Kinematics, KinematicsError, Robot};
use biscara_motion::{Feed, Motion, MotionKind, Plane};
use proptest::prelude::*;

fn config(robot: &Robot, profile: Profile, dt: f64) -> InterpolationConfig {
    let model = Kinematics::new(robot).expect("robot");
    InterpolationConfig {
        dt,
        profile,
        start: model.home().to_degrees(),
        limits: cartesian_limits(robot),
        grip_time: 0.0,
    }
}

fn feed(mm_per_min: f64) -> Feed {
    Feed { mm_per_min, inverse_time: false }
}

/// The default robot with θ3 free to turn ±2 turns, for programs that turn C past 180°.
fn turning_robot() -> Robot {
    Robot {
        joint_limits: biscara_kinematics::JointLimits {
            theta3: [-720.0, 720.0],
            ..Robot::default().joint_limits
        },
        ..Robot::default()
    }
}

/// A pick-and-place-like program with a helical arc and C turned past a full turn.
fn program() -> Vec<Motion> {
    let kinds = [
        MotionKind::Rapid { end: [0.0, 400.0, 100.0, 0.0] },
        MotionKind::Rapid { end: [150.0, 320.0, 60.0, 30.0] },
        MotionKind::Linear { end: [150.0, 320.0, 10.0, 30.0], feed: feed(3000.0) },
        MotionKind::Pick,
        MotionKind::Arc {
            end: [50.0, 420.0, 40.0, 200.0],
            center: [50.0, 320.0],
            plane: Plane::Xy,
            clockwise: false,
            turns: 1,
            feed: feed(2400.0),
        },
        MotionKind::Linear { end: [-150.0, 300.0, 20.0, 400.0], feed: feed(3000.0) },
        MotionKind::Place,
        MotionKind::Rapid { end: [0.0, 400.0, 100.0, 0.0] },
    ];
    kinds.into_iter().enumerate().map(|(index, kind)| Motion::new(index + 1, kind)).collect()
}

fn joints_of(motions: &[Motion], robot: &Robot, profile: Profile, dt: f64) -> Vec<JointSample> {
    let model = Kinematics::new(robot).expect("robot");
    let samples = Interpolator::new(
        motions.iter().map(|m| Ok::<_, Infallible>(*m)),
        config(robot, profile, dt),
        JointSpeedLimit::new(model, robot),
        |_: &SlowDown| {},
    );
    JointTrajectory::new(samples, model).collect::<Result<_, _>>().expect("trajectory")
}

#[test]
fn fk_of_every_row_lies_on_the_programmed_path() {
    let robot = turning_robot();
    let model = Kinematics::new(&robot).expect("robot");
    let motions = program();
    let rows = joints_of(&motions, &robot, Profile::Trapezoid, 0.001);
    let mut start = model.home().to_degrees();
    let mut segments = std::collections::HashMap::new();
    for motion in &motions {
        let segment = match motion.kind {
            MotionKind::Arc { end, center, plane, clockwise, turns, .. } => {
                Segment::arc(start, end, center, plane, clockwise, turns)
            }
            kind => match kind.end() {
                Some(end) => Segment::line(start, end),
                None => continue,
            },
        };
        start = segment.end();
        segments.insert(motion.line, segment);
    }
    let mut worst: f64 = 0.0;
    for row in rows.iter().filter(|row| row.line > 0) {
        let fk = model.forward(&row.joints).expect("FK of a row");
        let [x, y, z, c] = fk.pose.to_degrees();
        let segment = segments[&row.line];
        worst = worst.max(segment.distance_to([x, y, z]));
        // C is unwrapped along the path; FK gives c modulo nothing: θ3 carries the turns.
        assert!((c - row.pose[3]).abs() < 1e-6, "t = {}: c {c} vs {}", row.t, row.pose[3]);
    }
    assert!(worst < 1e-6, "FK strays {worst} mm from the path");
}

#[test]
fn theta3_is_continuous_through_more_than_a_turn() {
    let robot = turning_robot();
    let rows = joints_of(&program(), &robot, Profile::Trapezoid, 0.001);
    let mut largest_step: f64 = 0.0;
    for pair in rows.windows(2) {
        largest_step = largest_step.max((pair[1].joints.theta3 - pair[0].joints.theta3).abs());
    }
    assert!(largest_step < 0.05, "θ3 jumps by {largest_step} rad");
    // Back at c = 0 after turning C to 400° and back, θ3 is the single-pose value again.
    let last = rows.last().expect("rows");
    let model = Kinematics::new(&robot).expect("robot");
    let [x, y, z, c] = last.pose;
    let single = model.inverse(&biscara_kinematics::Pose::from_degrees(x, y, z, c)).expect("IK");
    assert!((last.joints.theta3 - single.joints.theta3).abs() < 1e-9);
    let peak = rows.iter().map(|row| row.joints.theta3).fold(f64::MIN, f64::max);
    assert!(peak > 5.0, "θ3 went past a full turn: peak {peak} rad");
}

#[test]
fn without_derivatives_the_positions_are_the_same_and_the_derivatives_zero() {
    let robot = turning_robot();
    let model = Kinematics::new(&robot).expect("robot");
    let motions = program();
    let with = joints_of(&motions, &robot, Profile::Optimal, 0.001);
    let samples = Interpolator::new(
        motions.iter().map(|m| Ok::<_, Infallible>(*m)),
        config(&robot, Profile::Optimal, 0.001),
        JointSpeedLimit::new(model, &robot),
        |_: &SlowDown| {},
    );
    let without: Vec<JointSample> = JointTrajectory::new(samples, model)
        .without_derivatives()
        .collect::<Result<_, _>>()
        .expect("trajectory");
    assert_eq!(with.len(), without.len());
    assert!(with.iter().any(|row| row.velocity != [0.0; 4]));
    for (a, b) in with.iter().zip(&without) {
        assert_eq!(
            (a.t, a.line, a.pose, a.joints, a.gripper),
            (b.t, b.line, b.pose, b.joints, b.gripper)
        );
        assert_eq!((b.velocity, b.acceleration), ([0.0; 4], [0.0; 4]));
    }
}

#[test]
fn derivatives_are_the_finite_differences_of_the_positions() {
    let rows = joints_of(&program(), &turning_robot(), Profile::Trapezoid, 0.002);
    for triple in rows.windows(3) {
        let [a, b, c] = [&triple[0], &triple[1], &triple[2]];
        let (qa, qb, qc) = (a.joints.to_array(), b.joints.to_array(), c.joints.to_array());
        for j in 0..4 {
            let velocity = (qc[j] - qa[j]) / (c.t - a.t);
            let acceleration =
                ((qc[j] - qb[j]) / (c.t - b.t) - (qb[j] - qa[j]) / (b.t - a.t)) * 2.0 / (c.t - a.t);
            assert!(
                (b.velocity[j] - velocity).abs() < 1e-9,
                "velocity of joint {j} at t = {}",
                b.t
            );
            assert!((b.acceleration[j] - acceleration).abs() < 1e-6, "acceleration of joint {j}");
        }
    }
    let (first, second) = (&rows[0], &rows[1]);
    let q = (first.joints.to_array(), second.joints.to_array());
    assert!((first.velocity[0] - (q.1[0] - q.0[0]) / (second.t - first.t)).abs() < 1e-12);
}

#[test]
fn joint_velocity_limits_slow_fast_moves_down() {
    // A slow θ1 makes the long rapid exceed it unless slowed.
    let mut robot = Robot::default();
    robot.joint_max_velocity.theta1 = 30.0;
    let motions = [Motion::new(5, MotionKind::Rapid { end: [-200.0, 300.0, 100.0, 0.0] })];
    let model = Kinematics::new(&robot).expect("robot");
    let dt = 0.001;
    let run = |limited: bool| -> (Vec<JointSample>, Vec<SlowDown>) {
        let mut slow = Vec::new();
        let motions = motions.iter().map(|m| Ok::<_, Infallible>(*m));
        let settings = config(&robot, Profile::Trapezoid, dt);
        let rows = if limited {
            let samples = Interpolator::new(
                motions,
                settings,
                JointSpeedLimit::new(model, &robot),
                |s: &SlowDown| slow.push(*s),
            );
            JointTrajectory::new(samples, model).collect::<Result<Vec<_>, _>>()
        } else {
            let samples =
                Interpolator::new(motions, settings, NoSpeedLimit, |s: &SlowDown| slow.push(*s));
            JointTrajectory::new(samples, model).collect::<Result<Vec<_>, _>>()
        };
        (rows.expect("trajectory"), slow)
    };
    let peak = |rows: &[JointSample]| {
        rows.iter().map(|row| row.velocity[0].abs().to_degrees()).fold(0.0, f64::max)
    };
    let (fast, none) = run(false);
    assert!(none.is_empty());
    assert!(peak(&fast) > 30.0, "the test move must be too fast for θ1: {}", peak(&fast));
    let (slowed, slow) = run(true);
    assert_eq!(slow.len(), 1);
    assert_eq!((slow[0].line, slow[0].cause), (5, "theta1"));
    assert!(peak(&slowed) <= 30.0 * 1.001, "θ1 peaks at {} °/s", peak(&slowed));
}

#[test]
fn an_unreachable_sample_names_its_line_and_time() {
    let motions = [
        Motion::new(1, MotionKind::Rapid { end: [0.0, 400.0, 50.0, 0.0] }),
        Motion {
            line: 2,
            kind: MotionKind::Linear { end: [0.0, 600.0, 50.0, 0.0], feed: feed(6000.0) },
            extrude: None,
            blend: None,
            naive_cam: None,
        },
    ];
    let robot = Robot::default();
    let model = Kinematics::new(&robot).expect("robot");
    let samples = Interpolator::new(
        motions.iter().map(|m| Ok::<_, Infallible>(*m)),
        config(&robot, Profile::Constant, 0.01),
        NoSpeedLimit,
        |_: &SlowDown| {},
    );
    let results: Vec<_> = JointTrajectory::new(samples, model).collect();
    let err = results.into_iter().find_map(Result::err).expect("an error");
    match &err {
        JointsError::Pose(SampleError { line, t, source, .. }) => {
            assert_eq!(*line, 2);
            assert!(*t > 0.0);
            assert!(
                matches!(
                    source,
                    KinematicsError::NearSingular { .. } | KinematicsError::Unreachable { .. }
                ),
                "{source:?}"
            );
        }
        other => panic!("unexpected {other:?}"),
    }
    assert!(err.to_string().starts_with("2: at t = "), "{err}");
}

fn reachable_pose() -> impl Strategy<Value = [f64; 4]> {
    [-150.0..150.0f64, 260.0..420.0f64, 10.0..90.0f64, -90.0..90.0f64]
}

/// Lines and arcs (centre on the bisector of start and end) inside the reachable region.
fn random_program() -> impl Strategy<Value = Vec<Motion>> {
    let kind = (reachable_pose(), any::<bool>(), any::<bool>(), -40.0..40.0f64, 300.0..6000.0f64);
    proptest::collection::vec(kind, 1..6).prop_map(|kinds| {
        let mut pose = Kinematics::default().home().to_degrees();
        let mut motions = Vec::new();
        for (index, (end, arc, clockwise, offset, mm_per_min)) in kinds.into_iter().enumerate() {
            let feed = feed(mm_per_min);
            let kind = if arc {
                let (mx, my) = (0.5 * (pose[0] + end[0]), 0.5 * (pose[1] + end[1]));
                let (dx, dy) = (end[0] - pose[0], end[1] - pose[1]);
                let length = dx.hypot(dy).max(1e-9);
                let center = [mx - dy / length * offset, my + dx / length * offset];
                MotionKind::Arc { end, center, plane: Plane::Xy, clockwise, turns: 1, feed }
            } else {
                MotionKind::Linear { end, feed }
            };
            pose = end;
            motions.push(Motion::new(index + 1, kind));
        }
        motions
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// FK of every joint row lies on the programmed segment or arc, within 1e-6 mm
    /// (before rounding), and its C is the sample's.
    #[test]
    fn fk_of_every_row_lies_on_its_motion(motions in random_program()) {
        let robot = turning_robot();
        let model = Kinematics::new(&robot).expect("robot");
        let samples = Interpolator::new(
            motions.iter().map(|m| Ok::<_, Infallible>(*m)),
            config(&robot, Profile::Trapezoid, 0.005),
            JointSpeedLimit::new(model, &robot),
            |_: &SlowDown| {},
        );
        let rows: Result<Vec<_>, _> = JointTrajectory::new(samples, model).collect();
        // Arcs may bulge out of the reachable region: those programs prove nothing here.
        prop_assume!(rows.is_ok());
        let rows = rows.unwrap_or_default();
        let mut start = model.home().to_degrees();
        let mut segments = std::collections::HashMap::new();
        for motion in &motions {
            let segment = match motion.kind {
                MotionKind::Arc { end, center, plane, clockwise, turns, .. } => {
                    Segment::arc(start, end, center, plane, clockwise, turns)
                }
                kind => Segment::line(start, kind.end().unwrap_or(start)),
            };
            start = segment.end();
            segments.insert(motion.line, segment);
        }
        // Every 7th row (and every motion's last): the arc distance search is slow in debug builds.
        let checked = rows.iter().enumerate().filter(|(index, row)| {
            row.line > 0 && (index % 7 == 0 || rows.get(index + 1).is_none_or(|next| next.line != row.line))
        });
        for (_, row) in checked {
            let fk = model.forward(&row.joints).expect("FK of a row");
            let [x, y, z, c] = fk.pose.to_degrees();
            let distance = segments[&row.line].distance_to([x, y, z]);
            prop_assert!(distance < 1e-6, "line {}: FK {} mm off the path", row.line, distance);
            prop_assert!((c - row.pose[3]).abs() < 1e-6);
        }
    }
}
