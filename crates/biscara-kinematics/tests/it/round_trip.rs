//! IK and FK round trips, in all four working modes, on a symmetric and an asymmetric robot.

use std::f64::consts::TAU;

use approx::relative_eq;
use biscara_kinematics::{Kinematics, wrap_angle};
use proptest::prelude::*;

use crate::strategies::{any_joints, any_pose, models};

/// Whether a configuration's every singularity angle is at least the robot's margin.
fn outside_margin(
    model: &Kinematics,
    configuration: &biscara_kinematics::PlanarConfiguration,
) -> bool {
    model.check_singularity(configuration).is_ok()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    /// FK(IK(x)) = x to 1e-7 mm and 1e-9 rad (φ to a whole turn), FK taken in the IK solution's
    /// assembly mode.
    #[test]
    fn fk_of_ik_is_the_pose(pose in any_pose()) {
        for (name, model) in models() {
            let Ok(ik) = model.inverse(&pose) else { continue };
            if !outside_margin(&model, &ik.configuration) {
                continue;
            }
            prop_assert_eq!(ik.configuration.working_mode(), model.working_mode(), "{}", name);
            let fk = model.forward_in(&ik.joints, ik.assembly_mode()).expect("FK of an IK solution");
            prop_assert!(relative_eq!(fk.pose.x, pose.x, epsilon = 1e-7), "{name}: x {} vs {}", fk.pose.x, pose.x);
            prop_assert!(relative_eq!(fk.pose.y, pose.y, epsilon = 1e-7), "{name}: y {} vs {}", fk.pose.y, pose.y);
            prop_assert!(relative_eq!(fk.pose.z, pose.z, epsilon = 1e-7), "{name}: z");
            // φ to a turn: θ3 may have been shifted by one into its limits.
            prop_assert!(relative_eq!(wrap_angle(fk.pose.phi - pose.phi), 0.0, epsilon = 1e-9), "{name}: phi {} vs {}", fk.pose.phi, pose.phi);
            for chain in 0..2 {
                let (a, b) = (fk.configuration.elbows[chain], ik.configuration.elbows[chain]);
                prop_assert!((a - b).norm() < 1e-7, "{name}: elbow {chain}");
            }
        }
    }

    /// IK(FK(q)) = q for q inside the limits whose pose is in the configured modes and outside
    /// the singularity margin.
    #[test]
    fn ik_of_fk_is_the_joints(joints in any_joints()) {
        for (name, model) in models() {
            if model.check_limits(&joints).is_err() {
                continue;
            }
            let Ok(fk) = model.forward(&joints) else { continue };
            if fk.configuration.working_mode() != model.working_mode()
                || !outside_margin(&model, &fk.configuration)
            {
                continue;
            }
            let ik = model.inverse_checked(&fk.pose).expect("IK of an FK pose in the robot's modes");
            let back = ik.joints;
            prop_assert!(relative_eq!(wrap_angle(back.theta1 - joints.theta1), 0.0, epsilon = 1e-9), "{name}: theta1 {} vs {}", back.theta1, joints.theta1);
            prop_assert!(relative_eq!(wrap_angle(back.theta2 - joints.theta2), 0.0, epsilon = 1e-9), "{name}: theta2");
            // θ3 from one pose is φ − wrap(ψ1 − ψ1_home): equal to q's θ3 modulo a whole turn.
            let turns = (back.theta3 - joints.theta3) / TAU;
            prop_assert!(relative_eq!(turns, turns.round(), epsilon = 1e-9), "{name}: theta3 {} vs {}", back.theta3, joints.theta3);
            prop_assert!(relative_eq!(back.d4, joints.d4, epsilon = 1e-9), "{name}: d4");
        }
    }

    /// The IK solution bends each chain as the working mode says, and its elbows are at l1 and
    /// l2 from the base joint and the platform point.
    #[test]
    fn ik_solution_closes_the_loop(pose in any_pose()) {
        for (name, model) in models() {
            let Ok(ik) = model.inverse(&pose) else { continue };
            let configuration = ik.configuration;
            for chain in biscara_kinematics::Chain::BOTH {
                prop_assert!(relative_eq!(configuration.proximal(chain).norm(), model.l1(), epsilon = 1e-9), "{name}");
                prop_assert!(relative_eq!(configuration.distal(chain).norm(), model.l2(), epsilon = 1e-9), "{name}");
            }
            let angles = configuration.singularity();
            // On the boundary (a chain exactly stretched) both roots coincide; elsewhere the mode holds.
            if angles.type1[0] > 1e-6 && angles.type1[1] > 1e-6 {
                prop_assert_eq!(configuration.working_mode(), model.working_mode(), "{}", name);
            }
        }
    }
}

/// Every pose of a dense grid that one mode reaches is reached by exactly the roots the modes
/// predict: the four working modes give four distinct elbow pairs.
#[test]
fn four_working_modes_give_four_distinct_solutions() {
    let model = Kinematics::default();
    let pose = biscara_kinematics::Pose::from_degrees(20.0, 330.0, 50.0, 0.0);
    let mut elbows = Vec::new();
    for mode in biscara_kinematics::WorkingMode::ALL {
        let ik = model.with_working_mode(mode).inverse(&pose).expect("reachable in every mode");
        assert_eq!(ik.configuration.working_mode(), mode);
        elbows.push(ik.configuration.elbows);
    }
    for i in 0..4 {
        for j in i + 1..4 {
            assert!(elbows[i] != elbows[j], "modes {i} and {j} coincide");
        }
    }
}

/// The properties above skip poses a model cannot take; make sure each model takes plenty, so
/// that no property holds vacuously.
#[test]
fn the_round_trip_properties_are_not_vacuous() {
    use biscara_kinematics::{Joints, Pose};
    let mut per_working_mode = std::collections::BTreeMap::new();
    for (name, model) in models() {
        let (mut poses, mut joint_vectors) = (0, 0);
        for i in 0..50 {
            for j in 0..50 {
                let (u, v) = (f64::from(i) / 49.0, f64::from(j) / 49.0);
                let pose = Pose::from_degrees(-520.0 + 1040.0 * u, -520.0 + 1080.0 * v, 50.0, 10.0);
                if model.inverse(&pose).is_ok_and(|ik| outside_margin(&model, &ik.configuration)) {
                    poses += 1;
                }
                let joints =
                    Joints::from_degrees(-180.0 + 360.0 * u, -180.0 + 360.0 * v, 0.0, 50.0);
                if model.check_limits(&joints).is_ok()
                    && model.forward(&joints).is_ok_and(|fk| {
                        fk.configuration.working_mode() == model.working_mode()
                            && outside_margin(&model, &fk.configuration)
                    })
                {
                    joint_vectors += 1;
                }
            }
        }
        assert!(poses > 250, "{name}: only {poses} of 2500 grid poses are reachable");
        let mode = model.working_mode();
        *per_working_mode.entry(format!("{name:.10} {mode}")).or_insert(0) += joint_vectors;
    }
    for (mode, count) in per_working_mode {
        assert!(count > 100, "{mode}: only {count} joint vectors qualify in either assembly mode");
    }
}
