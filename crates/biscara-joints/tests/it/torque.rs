//! The torque-limited optimal profile (issue 36): with `motors` in the robot file, the torques
//! of the joint trajectory's own central differences (as `joints --torques` and `check` compute
//! them, by the inverse dynamics of `biscara-dynamics`) stay within every motor's peak, with the
//! payload while the gripper holds it; and the motors slow the robot down only where they bind.

use std::convert::Infallible;

use biscara_dynamics::Dynamics;
use biscara_interpolate::{InterpolationConfig, Interpolator, Profile, SlowDown};
use biscara_joints::{JointSample, JointSpeedLimit, JointTrajectory, cartesian_limits};
use biscara_kinematics::{Robot, RobotModel};
use biscara_motion::{Motion, MotionKind};
use proptest::prelude::*;

use crate::optimal::{motions, robot, step};

/// The torques of the differenced trajectory may exceed a motor's peak by this fraction: only
/// rounding. The planner keeps 99 % of each revolute joint's peak at its grid points (d4: 100 %,
/// its path is linear in s) less the friction, which bounds the excess between grid points
/// and the noise of the central differences where a joint stops and turns back (Coulomb
/// friction flipping sign at one sample: `biscara_joints`' `torque` module). Measured over
/// these cases: at most 0.988 of a peak (θ2).
const TOLERANCE: f64 = 1e-6;

/// `robot` with motors that bind (weaker than its acceleration limits on most moves) and a
/// payload of `payload_kg`.
fn with_motors(robot: &Robot, payload_kg: f64) -> RobotModel {
    let mut json = serde_json::to_value(robot).expect("robot as JSON");
    json["motors"] = serde_json::json!({
        "theta1": {"peak": 1.2, "rated": 0.5, "rotor_inertia": 0.002, "viscous": 0.02, "coulomb": 0.1},
        "theta2": {"peak": 1.2, "rated": 0.5, "rotor_inertia": 0.002, "viscous": 0.02, "coulomb": 0.1},
        "theta3": {"peak": 0.04, "rated": 0.02, "rotor_inertia": 0.0001, "viscous": 0.001, "coulomb": 0.01},
        "d4": {"peak": 30.0, "rated": 25.0, "rotor_inertia": 0.5, "viscous": 5.0, "coulomb": 2.0}
    });
    json["dynamics"] = serde_json::json!({"payload": {"mass": payload_kg}});
    RobotModel::from_json(&json.to_string()).expect("robot with motors")
}

/// The joint trajectory of `motions` with (or without) the motors' torque bounds.
fn trajectory(motions: &[Motion], model: &RobotModel, torques: bool) -> Option<Vec<JointSample>> {
    let robot = model.robot();
    let kinematics = model.kinematics();
    let config = InterpolationConfig {
        dt: 0.001,
        profile: Profile::Optimal,
        start: kinematics.home().to_degrees(),
        limits: cartesian_limits(robot),
        grip_time: 0.0,
    };
    let mut limit = JointSpeedLimit::new(kinematics, robot);
    if torques {
        limit = limit.with_motors(model).expect("dynamics");
    }
    let samples = Interpolator::new(
        motions.iter().map(|m| Ok::<_, Infallible>(*m)),
        config,
        limit,
        |_: &SlowDown| {},
    );
    JointTrajectory::new(samples, kinematics).collect::<Result<_, _>>().ok()
}

/// The largest |τ| / peak per motor over the interior rows (the first and last rows have
/// one-sided differences).
fn torque_ratios(rows: &[JointSample], model: &RobotModel) -> [f64; 4] {
    let dynamics = Dynamics::new(model).expect("dynamics");
    let motors = *dynamics.motors().expect("motors");
    let payload = dynamics.bodies().payload;
    let mut ratios = [0.0f64; 4];
    for row in &rows[1..rows.len().saturating_sub(1)] {
        let load = if row.gripper { payload } else { 0.0 };
        let torques = dynamics
            .torques(row.joints.to_array(), row.velocity, row.acceleration, load)
            .expect("torques");
        for j in 0..4 {
            ratios[j] = ratios[j].max(torques[j].abs() / motors[j].peak);
        }
    }
    ratios
}

proptest! {
    /// The planner takes the torques at rest from the home pose: gravity is along −z and the
    /// revolute joints turn about vertical axes, so they are the same in every pose.
    #[test]
    fn the_torques_at_rest_are_the_same_in_every_pose(
        x in -200.0..200.0f64, y in 200.0..420.0f64, z in 0.0..100.0f64, c in -150.0..150.0f64,
        payload in 0.0..2.5f64,
    ) {
        let model = with_motors(&robot(false), payload);
        let kinematics = model.kinematics();
        let solution = kinematics.inverse(&biscara_kinematics::Pose::from_degrees(x, y, z, c));
        prop_assume!(solution.is_ok());
        let q = solution.map(|s| s.joints.to_array()).unwrap_or_default();
        let dynamics = Dynamics::new(&model).expect("dynamics");
        let at = |q| dynamics.rigid_torques(q, [0.0; 4], [0.0; 4], payload).expect("torques");
        let (here, home) = (at(q), at([0.0; 4]));
        for j in 0..4 {
            prop_assert!((here[j] - home[j]).abs() <= 1e-9 * (1.0 + home[j].abs()), "{here:?} vs {home:?}");
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 32,
        max_global_rejects: 10_000,
        ..ProptestConfig::default()
    })]

    /// Every motor within its peak in the trajectory's own differences, holding a payload or
    /// not; never faster than without the motors.
    #[test]
    fn torques_stay_within_the_peaks(
        steps in proptest::collection::vec(step(), 1..5),
        holding: bool,
        weak: bool,
    ) {
        let model = with_motors(&robot(weak), 2.0);
        let home = model.kinematics().home().to_degrees();
        let mut motions = motions(&steps, home, &model.kinematics());
        if holding {
            motions.insert(0, Motion::new(0, MotionKind::Pick));
        }
        let limited = trajectory(&motions, &model, true);
        prop_assume!(limited.is_some());
        let limited = limited.unwrap_or_default();
        let ratios = torque_ratios(&limited, &model);
        for (j, ratio) in ratios.iter().enumerate() {
            prop_assert!(*ratio <= 1.0 + TOLERANCE, "motor {j} at {ratio:.6} of its peak");
        }
        let free = trajectory(&motions, &model, false).unwrap_or_default();
        let (t_limited, t_free) = (limited.last().map_or(0.0, |r| r.t), free.last().map_or(0.0, |r| r.t));
        prop_assert!(t_limited >= t_free - 1e-9 * t_free.max(1.0) - 0.001 * motions.len() as f64);
    }
}

/// A rapid across the workspace holding the payload: without the torque bounds the motors of
/// θ1 and θ2 would need more than their peaks; with them, they stay within, and the move takes
/// longer.
#[test]
fn the_motors_slow_a_rapid_they_cannot_drive() {
    let model = with_motors(&robot(false), 2.0);
    let motions = [
        Motion::new(1, MotionKind::Pick),
        Motion::new(2, MotionKind::Rapid { end: [-150.0, 300.0, 50.0, 0.0] }),
        Motion::new(3, MotionKind::Rapid { end: [150.0, 380.0, 20.0, 90.0] }),
    ];
    let free = trajectory(&motions, &model, false).expect("reachable");
    let limited = trajectory(&motions, &model, true).expect("reachable");
    let (free_ratios, limited_ratios) =
        (torque_ratios(&free, &model), torque_ratios(&limited, &model));
    assert!(free_ratios[0].max(free_ratios[1]) > 1.5, "{free_ratios:?}");
    assert!(limited_ratios.iter().all(|ratio| *ratio <= 1.0 + TOLERANCE), "{limited_ratios:?}");
    let duration = |rows: &[JointSample]| rows.last().map_or(0.0, |row| row.t);
    assert!(
        duration(&limited) > 1.1 * duration(&free),
        "{} vs {}",
        duration(&limited),
        duration(&free)
    );
}
