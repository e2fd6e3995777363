//! θ3 from one pose: shifted by a turn into its limits when only that makes it fit (as θ1 and
//! θ2 are), and a path that starts there continues from it.

use std::f64::consts::TAU;

use approx::relative_eq;
use biscara_kinematics::{Joint, Kinematics, KinematicsError, Pose, Theta3Unwrapper, wrap_angle};
use proptest::prelude::*;

use crate::strategies::{any_pose, models, models_with};

/// The test models, and each again with θ3's range moved off centre ([−90°, 270°]), so that
/// both a shift up and a shift down are needed somewhere.
fn models_with_theta3_ranges() -> Vec<(String, Kinematics)> {
    let mut all = models();
    for (name, model) in models_with(|robot| robot.joint_limits.theta3 = [-90.0, 270.0]) {
        all.push((format!("{name}, theta3 in [-90, 270]"), model));
    }
    all
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1000))]

    /// θ3 is `φ − ψ` or one turn from it: unchanged when `φ − ψ` is inside the limits, inside
    /// them when a turn puts it there; FK of the joints gives the pose back (φ to a turn).
    #[test]
    fn theta3_is_shifted_into_its_limits_when_only_that_fits(pose in any_pose()) {
        for (name, model) in models_with_theta3_ranges() {
            let Ok(ik) = model.inverse(&pose) else { continue };
            let [min, max] = model.limits(Joint::Theta3);
            let inside = |angle: f64| (min..=max).contains(&angle);
            let unshifted = pose.phi - ik.distal_rotation;
            let theta3 = ik.joints.theta3;
            let turns = (theta3 - unshifted) / TAU;
            prop_assert!(relative_eq!(turns, turns.round(), epsilon = 1e-9) && turns.abs() < 1.5, "{name}: theta3 {theta3} vs {unshifted}");
            if inside(unshifted) {
                prop_assert_eq!(theta3, unshifted, "{}", name);
            } else if inside(unshifted + TAU) || inside(unshifted - TAU) {
                prop_assert!(inside(theta3), "{name}: theta3 {theta3} outside [{min}, {max}]");
            } else {
                prop_assert_eq!(theta3, unshifted, "{}", name);
            }
            let fk = model.forward_in(&ik.joints, ik.assembly_mode()).expect("FK of an IK solution");
            prop_assert!(relative_eq!(wrap_angle(fk.pose.phi - pose.phi), 0.0, epsilon = 1e-9), "{name}: phi");
            // No joint-limit error on θ3 for a pose some turn of θ3 fits.
            if inside(theta3)
                && let Err(KinematicsError::JointLimit { joint, .. }) = model.check_limits(&ik.joints)
            {
                prop_assert_ne!(joint, Joint::Theta3, "{}", name);
            }
        }
    }

    /// A path starts at the single-pose θ3 and goes on continuously from it.
    #[test]
    fn a_path_starts_at_the_single_pose_theta3(pose in any_pose(), step in -2.0..2.0f64) {
        for (name, model) in models_with_theta3_ranges() {
            let Ok(mut first) = model.inverse(&pose) else { continue };
            let next_pose = Pose::new(pose.x + step, pose.y - step, pose.z, pose.phi + step.to_radians());
            let Ok(mut next) = model.inverse(&next_pose) else { continue };
            let single = first.joints.theta3;
            let mut unwrapper = Theta3Unwrapper::new();
            unwrapper.apply(&mut first);
            prop_assert_eq!(first.joints.theta3, single, "{}", name);
            unwrapper.apply(&mut next);
            let expected = single + (next_pose.phi - pose.phi)
                - wrap_angle(next.distal_rotation - first.distal_rotation);
            prop_assert!(relative_eq!(next.joints.theta3, expected, epsilon = 1e-9), "{name}: theta3 {} after {single}, expected {expected}", next.joints.theta3);
        }
    }
}
