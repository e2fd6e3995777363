//! The optimal profile (issue 16): on random programs (lines, tight arcs, C rotations, moves near
//! the workspace's edge) and on a strong and a weak robot, the joint trajectory's own central
//! differences — as `check` computes them — never exceed a velocity or acceleration limit, and
//! the optimal profile is never slower than the trapezoid where the trapezoid keeps the limits.

use std::convert::Infallible;

use biscara_interpolate::{InterpolationConfig, Interpolator, Profile, Segment, SlowDown};
use biscara_joints::{JointSample, JointSpeedLimit, JointTrajectory, cartesian_limits};
use biscara_kinematics::{JointLimits, JointValues, Kinematics, Robot};
use biscara_motion::{Feed, Motion, MotionKind, Plane};
use proptest::prelude::*;

/// Relative tolerance on the limits: the optimal profile's margins (0.2 % on velocity, 1 % on
/// acceleration, none on d4) must absorb the grid and the finite differences; this only covers
/// rounding, as `check`'s own slack does.
pub(crate) const TOLERANCE: f64 = 1e-6;

/// θ3 free to turn ±2 turns, so that C rotations do not hit its position limit.
fn turning(robot: Robot) -> Robot {
    Robot { joint_limits: JointLimits { theta3: [-720.0, 720.0], ..robot.joint_limits }, ..robot }
}

/// The default robot, or the weak-motor one of `data/robots/weak-motors.json`.
pub(crate) fn robot(weak: bool) -> Robot {
    let robot = Robot::default();
    if !weak {
        return turning(robot);
    }
    turning(Robot {
        joint_max_velocity: JointValues {
            theta1: 120.0,
            theta2: 120.0,
            theta3: 400.0,
            ..robot.joint_max_velocity
        },
        joint_max_acceleration: JointValues {
            theta1: 1200.0,
            theta2: 1200.0,
            theta3: 4000.0,
            ..robot.joint_max_acceleration
        },
        ..robot
    })
}

pub(crate) fn feed(mm_per_min: f64) -> Feed {
    Feed { mm_per_min, inverse_time: false }
}

/// One move, relative to where the previous one ended.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Step {
    /// A G0 or G1 to a point of the workspace's middle.
    Line { end: [f64; 4], rapid: bool, feed: f64 },
    /// A full or partial circle of small radius (2–20 mm) about a point beside the start.
    Arc { radius: f64, heading: f64, sweep_end: f64, clockwise: bool, dz: f64, feed: f64 },
    /// C alone.
    Rotate { by: f64, rapid: bool, feed: f64 },
    /// A G1 to a point 4–30 mm inside the outer edge of the workspace (θ2 − θ1 near the
    /// stretched-out type-1 singularity).
    Edge { angle: f64, inside: f64, z: f64, feed: f64 },
}

pub(crate) fn step() -> impl Strategy<Value = Step> {
    let feed = 300.0..12000.0f64;
    prop_oneof![
        (
            [-150.0..150.0f64, 250.0..400.0f64, 0.0..100.0f64, -150.0..150.0f64],
            any::<bool>(),
            feed.clone()
        )
            .prop_map(|(end, rapid, feed)| Step::Line { end, rapid, feed }),
        (
            2.0..20.0f64,
            0.0..std::f64::consts::TAU,
            0.0..std::f64::consts::TAU,
            any::<bool>(),
            -5.0..5.0f64,
            feed.clone()
        )
            .prop_map(|(radius, heading, sweep_end, clockwise, dz, feed)| Step::Arc {
                radius,
                heading,
                sweep_end,
                clockwise,
                dz,
                feed
            }),
        (-200.0..200.0f64, any::<bool>(), feed.clone())
            .prop_map(|(by, rapid, feed)| Step::Rotate { by, rapid, feed }),
        (60.0..120.0f64, 4.0..30.0f64, 0.0..100.0f64, feed)
            .prop_map(|(angle, inside, z, feed)| Step::Edge { angle, inside, z, feed }),
    ]
}

/// The motions of `steps` from the home pose, and their count.
pub(crate) fn motions(steps: &[Step], home: [f64; 4], model: &Kinematics) -> Vec<Motion> {
    let mut pose = home;
    let mut motions = Vec::new();
    for (index, step) in steps.iter().enumerate() {
        let kind = match *step {
            Step::Line { end, rapid: true, .. } => MotionKind::Rapid { end },
            Step::Line { end, feed: f, .. } => MotionKind::Linear { end, feed: feed(f) },
            Step::Arc { radius, heading, sweep_end, clockwise, dz, feed: f } => {
                let center = [pose[0] + radius * heading.cos(), pose[1] + radius * heading.sin()];
                let start_angle =
                    (heading + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU);
                let angle = start_angle + sweep_end;
                let end = [
                    center[0] + radius * angle.cos(),
                    center[1] + radius * angle.sin(),
                    pose[2] + dz,
                    pose[3],
                ];
                MotionKind::Arc {
                    end,
                    center,
                    plane: Plane::Xy,
                    clockwise,
                    turns: 1,
                    feed: feed(f),
                }
            }
            Step::Rotate { by, rapid, feed: f } => {
                let end = [pose[0], pose[1], pose[2], pose[3] + by];
                if rapid {
                    MotionKind::Rapid { end }
                } else {
                    MotionKind::Linear { end, feed: feed(f) }
                }
            }
            Step::Edge { angle, inside, z, feed: f } => {
                // The outer edge about the bases' midpoint is at most l1 + l2 from each base.
                let [b1, b2] = model.bases();
                let reach = model.l1() + model.l2() - inside;
                let (sin, cos) = angle.to_radians().sin_cos();
                let base = if cos >= 0.0 { b2 } else { b1 };
                let end = [base.x + reach * cos, base.y + reach * sin, z, pose[3]];
                MotionKind::Linear { end, feed: feed(f) }
            }
        };
        if let Some(end) = kind.end() {
            pose = end;
        }
        motions.push(Motion::new(index + 1, kind));
    }
    motions
}

/// The joint trajectory of `motions` under `profile`, or `None` where the robot cannot follow
/// the path (unreachable, near a singularity, a joint limit): such programs are `check`'s.
pub(crate) fn trajectory(
    motions: &[Motion],
    robot: &Robot,
    profile: Profile,
) -> Option<Vec<JointSample>> {
    let model = Kinematics::new(robot).expect("robot");
    let config = InterpolationConfig {
        dt: 0.001,
        profile,
        start: model.home().to_degrees(),
        limits: cartesian_limits(robot),
        grip_time: 0.0,
    };
    let samples = Interpolator::new(
        motions.iter().map(|m| Ok::<_, Infallible>(*m)),
        config,
        JointSpeedLimit::new(model, robot),
        |_: &SlowDown| {},
    );
    JointTrajectory::new(samples, model).collect::<Result<_, _>>().ok()
}

/// The limits in radians and mm: velocity, acceleration.
fn limits(robot: &Robot) -> ([f64; 4], [f64; 4]) {
    let convert = |values: [f64; 4]| {
        [values[0].to_radians(), values[1].to_radians(), values[2].to_radians(), values[3]]
    };
    (convert(robot.joint_max_velocity.to_array()), convert(robot.joint_max_acceleration.to_array()))
}

/// The largest ratio of a central-difference velocity and acceleration to its limit, over the
/// interior samples, per joint: `check`'s differences.
pub(crate) fn peak_ratios(rows: &[JointSample], robot: &Robot) -> ([f64; 4], [f64; 4]) {
    let (max_velocity, max_acceleration) = limits(robot);
    let (mut velocity, mut acceleration) = ([0.0f64; 4], [0.0f64; 4]);
    for window in rows.windows(3) {
        let (before, middle, after) = (&window[0], &window[1], &window[2]);
        let (q0, q1, q2) =
            (before.joints.to_array(), middle.joints.to_array(), after.joints.to_array());
        let span = after.t - before.t;
        let (back, ahead) = (middle.t - before.t, after.t - middle.t);
        for j in 0..4 {
            let v = (q2[j] - q0[j]) / span;
            let a = 2.0 * ((q2[j] - q1[j]) / ahead - (q1[j] - q0[j]) / back) / span;
            velocity[j] = velocity[j].max(v.abs() / max_velocity[j]);
            acceleration[j] = acceleration[j].max(a.abs() / max_acceleration[j]);
        }
    }
    (velocity, acceleration)
}

/// Every motion's segment, for the on-path check.
pub(crate) fn segments(motions: &[Motion], home: [f64; 4]) -> Vec<(usize, Segment)> {
    let mut pose = home;
    let mut segments = Vec::new();
    for motion in motions {
        let segment = match motion.kind {
            MotionKind::Arc { end, center, plane, clockwise, turns, .. } => {
                Segment::arc(pose, end, center, plane, clockwise, turns)
            }
            kind => Segment::line(pose, kind.end().unwrap_or(pose)),
        };
        pose = segment.end();
        segments.push((motion.line, segment));
    }
    segments
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 48,
        max_global_rejects: 10_000,
        ..ProptestConfig::default()
    })]

    /// No joint exceeds a velocity or acceleration limit in the trajectory's own differences;
    /// FK of rows lies on the path; and where the trapezoid keeps the limits too (so that it is
    /// a plan the optimal profile could have made), the optimal one is no slower, up to the
    /// rounding of each motion to whole steps.
    #[test]
    fn optimal_keeps_every_joint_limit(
        steps in proptest::collection::vec(step(), 1..5),
        weak: bool,
    ) {
        let robot = robot(weak);
        let model = Kinematics::new(&robot).expect("robot");
        let home = model.home().to_degrees();
        let motions = motions(&steps, home, &model);
        let optimal = trajectory(&motions, &robot, Profile::Optimal);
        prop_assume!(optimal.is_some());
        let optimal = optimal.unwrap_or_default();
        let (velocity, acceleration) = peak_ratios(&optimal, &robot);
        for j in 0..4 {
            prop_assert!(velocity[j] <= 1.0 + TOLERANCE, "joint {j} velocity at {:.6} of its limit", velocity[j]);
            prop_assert!(
                acceleration[j] <= 1.0 + TOLERANCE,
                "joint {j} acceleration at {:.6} of its limit",
                acceleration[j]
            );
        }
        // FK of every 25th row and of every motion's last row lies on that motion's path.
        let segments = segments(&motions, home);
        for (index, row) in optimal.iter().enumerate() {
            let last_of_motion = optimal.get(index + 1).is_none_or(|next| next.line != row.line);
            if row.line == 0 || (index % 25 != 0 && !last_of_motion) {
                continue;
            }
            let fk = model.forward(&row.joints).expect("FK").pose;
            let segment = segments.iter().find(|(line, _)| *line == row.line).expect("segment").1;
            let distance = segment.distance_to([fk.x, fk.y, fk.z]);
            prop_assert!(distance < 1e-6, "row {index} is {distance} mm off line {}", row.line);
            if last_of_motion {
                let end = segment.end();
                prop_assert!((fk.x - end[0]).hypot(fk.y - end[1]) < 1e-6);
            }
        }
        let trapezoid = trajectory(&motions, &robot, Profile::Trapezoid);
        prop_assume!(trapezoid.is_some());
        let trapezoid = trapezoid.unwrap_or_default();
        let (_, trapezoid_acceleration) = peak_ratios(&trapezoid, &robot);
        if trapezoid_acceleration.iter().all(|&ratio| ratio <= 0.99) {
            let (t_optimal, t_trapezoid) =
                (optimal.last().map_or(0.0, |r| r.t), trapezoid.last().map_or(0.0, |r| r.t));
            let rounding = motions.len() as f64 * 0.001;
            prop_assert!(
                t_optimal <= t_trapezoid + rounding + 1e-9,
                "optimal {t_optimal} s, trapezoid {t_trapezoid} s"
            );
        }
    }
}

/// A helix of 5 turns (942 mm, about 2,800 grid intervals) is planned in more than one window of
/// the planner (1,024 intervals + 1,024 of look-ahead): the trajectory still keeps every limit, ends on the programmed point, and takes the
/// time of the feed (plus the ramps, a few ms).
#[test]
fn a_long_helix_is_planned_in_windows() {
    let robot = robot(true);
    let start = [30.0, 350.0, 90.0, 0.0];
    let motions = [
        Motion::new(1, MotionKind::Rapid { end: start }),
        Motion::new(
            2,
            MotionKind::Arc {
                end: [30.0, 350.0, 10.0, 90.0],
                center: [0.0, 350.0],
                plane: Plane::Xy,
                clockwise: true,
                turns: 5,
                feed: feed(600.0),
            },
        ),
    ];
    let rows = trajectory(&motions, &robot, Profile::Optimal).expect("trajectory");
    let (velocity, acceleration) = peak_ratios(&rows, &robot);
    for j in 0..4 {
        assert!(velocity[j] <= 1.0 + TOLERANCE, "joint {j}: {velocity:?}");
        assert!(acceleration[j] <= 1.0 + TOLERANCE, "joint {j}: {acceleration:?}");
    }
    let last = rows.last().expect("rows");
    assert_eq!(last.pose, [30.0, 350.0, 10.0, 90.0]);
    let helix = rows.iter().filter(|row| row.line == 2).count() as f64 * 0.001;
    let length = (5.0 * std::f64::consts::TAU * 30.0f64).hypot(80.0);
    let at_feed = length / 10.0;
    assert!(
        helix >= at_feed && helix <= at_feed + 0.05,
        "{helix} s against {at_feed} s at the feed"
    );
}
