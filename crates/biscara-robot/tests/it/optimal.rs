//! `check` agrees with the optimal profile (issue 16): on random programs — lines, tight arcs, C
//! rotations, moves near the workspace's outer edge (the stretched-out type-1 singularity) — on
//! the default and the weak-motor robot, the checker finds no velocity or acceleration problem in
//! the trajectory the default profile makes, wherever it finds no other problem (a program the
//! robot cannot follow at all is not the profile's to fix).

use std::convert::Infallible;

use biscara_interpolate::{InterpolationConfig, Interpolator, Profile, Segment, SlowDown};
use biscara_joints::{JointSpeedLimit, cartesian_limits};
use biscara_kinematics::{JointLimits, JointValues, Pose, Robot, RobotModel};
use biscara_motion::{Feed, Motion, MotionKind, Plane};
use biscara_robot::{Checker, ProblemKind, Scene};
use proptest::prelude::*;

/// The default robot (θ3 free to turn ±2 turns) or the weak-motor one of
/// `data/robots/weak-motors.json`.
fn robot(weak: bool) -> Robot {
    let robot = Robot::default();
    let robot = Robot {
        joint_limits: JointLimits { theta3: [-720.0, 720.0], ..robot.joint_limits },
        ..robot
    };
    if !weak {
        return robot;
    }
    let [v, a] = [robot.joint_max_velocity, robot.joint_max_acceleration];
    Robot {
        joint_max_velocity: JointValues { theta1: 120.0, theta2: 120.0, theta3: 400.0, ..v },
        joint_max_acceleration: JointValues { theta1: 1200.0, theta2: 1200.0, theta3: 4000.0, ..a },
        ..robot
    }
}

/// One move: `kind` 0 a line to `point` (x −150..150, y 250..400), 1 an arc of radius
/// `size` (2–20 mm) about a point beside the start, 2 a rotation of C by `angle`, 3 a line to a
/// point `size` mm inside the outer edge.
#[derive(Debug, Clone, Copy)]
struct Step {
    kind: u8,
    point: [f64; 3],
    size: f64,
    angle: f64,
    rapid: bool,
    feed: f64,
}

fn step() -> impl Strategy<Value = Step> {
    (
        0u8..4,
        [-150.0..150.0f64, 250.0..400.0f64, 0.0..100.0f64],
        2.0..25.0f64,
        -200.0..200.0f64,
        any::<bool>(),
        300.0..12000.0f64,
    )
        .prop_map(|(kind, point, size, angle, rapid, feed)| Step {
            kind,
            point,
            size,
            angle,
            rapid,
            feed,
        })
}

fn motions(steps: &[Step], model: &RobotModel) -> Vec<Motion> {
    let kinematics = model.kinematics();
    let mut pose = kinematics.home().to_degrees();
    let mut motions = Vec::new();
    for (index, step) in steps.iter().enumerate() {
        let feed = Feed { mm_per_min: step.feed, inverse_time: false };
        let line = |end: [f64; 4]| {
            if step.rapid { MotionKind::Rapid { end } } else { MotionKind::Linear { end, feed } }
        };
        let kind = match step.kind {
            0 => line([step.point[0], step.point[1], step.point[2], pose[3]]),
            1 => {
                let heading = step.angle.to_radians();
                let radius = step.size;
                let center = [pose[0] + radius * heading.cos(), pose[1] + radius * heading.sin()];
                let angle = heading + std::f64::consts::PI + step.point[2].to_radians() * 3.0;
                let end = [
                    center[0] + radius * angle.cos(),
                    center[1] + radius * angle.sin(),
                    pose[2],
                    pose[3],
                ];
                MotionKind::Arc {
                    end,
                    center,
                    plane: Plane::Xy,
                    clockwise: step.rapid,
                    turns: 1,
                    feed,
                }
            }
            2 => line([pose[0], pose[1], pose[2], pose[3] + step.angle]),
            _ => {
                let [b1, b2] = kinematics.bases();
                let reach = kinematics.l1() + kinematics.l2() - step.size;
                let (sin, cos) = (60.0 + step.point[2] * 0.6).to_radians().sin_cos();
                let base = if cos >= 0.0 { b2 } else { b1 };
                line([base.x + reach * cos, base.y + reach * sin, step.point[2], pose[3]])
            }
        };
        if let Some(end) = kind.end() {
            pose = end;
        }
        motions.push(Motion::new(index + 1, kind));
    }
    motions
}

/// Whether the robot can take every pose along `motions` (from its home pose), sampled every
/// 0.05 mm (or 0.05° of C): inside the joint limits, the assembly mode and the singularity margin.
fn followable(motions: &[Motion], model: &RobotModel) -> bool {
    let kinematics = model.kinematics();
    let takes = |p: [f64; 4]| {
        kinematics.inverse_checked(&Pose::from_degrees(p[0], p[1], p[2], p[3])).is_ok()
    };
    let mut from = kinematics.home().to_degrees();
    for motion in motions {
        let Some(to) = motion.kind.end() else { continue };
        let segment = match motion.kind {
            MotionKind::Arc { center, plane, clockwise, turns, .. } => {
                Segment::arc(from, to, center, plane, clockwise, turns)
            }
            _ => Segment::line(from, to),
        };
        let length = segment.length().max(segment.rotation().abs()).max(1.0);
        let steps = (length / 0.05).ceil().max(100.0) as usize;
        if !(0..=steps).all(|step| takes(segment.point(step as f64 / steps as f64))) {
            return false;
        }
        from = to;
    }
    true
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    #[test]
    fn check_finds_no_velocity_or_acceleration_problem_in_optimal_trajectories(
        steps in proptest::collection::vec(step(), 1..5),
        weak: bool,
    ) {
        let model = RobotModel::new(robot(weak)).expect("robot");
        let kinematics = model.kinematics();
        let config = InterpolationConfig {
            dt: 0.001,
            profile: Profile::default(),
            start: kinematics.home().to_degrees(),
            limits: cartesian_limits(model.robot()),
            grip_time: 0.0,
        };
        prop_assert_eq!(config.profile, Profile::Optimal);
        let motions = motions(&steps, &model);
        let samples = Interpolator::new(
            motions.iter().map(|m| Ok::<_, Infallible>(*m)),
            config,
            JointSpeedLimit::new(kinematics, model.robot()),
            |_: &SlowDown| {},
        );
        let mut checker = Checker::new(&model, Scene::new());
        let mut count = 0;
        for sample in samples {
            match sample {
                Ok(sample) => checker.push(&sample),
                Err(err) => {
                    // Only a path the robot cannot follow (through the singularity margin, out
                    // of reach) may be refused: it is not the profile's to fix.
                    prop_assert!(!followable(&motions, &model), "a followable path refused: {err}");
                    prop_assume!(false);
                }
            }
            count += 1;
        }
        let report = checker.finish();
        let derivative = |kind| matches!(kind, ProblemKind::VelocityLimit | ProblemKind::AccelerationLimit);
        prop_assume!(report.problems.iter().all(|p| derivative(p.kind)) || report.problems.is_empty());
        prop_assert!(count > 1);
        prop_assert!(report.problems.is_empty(), "{:#?}", report.problems);
    }
}
