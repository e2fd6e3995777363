//! proptest strategies: robots, reachable poses and joint vectors.

use biscara_kinematics::{AssemblyMode, Joints, Kinematics, Pose, Robot, Sign, WorkingMode};
use proptest::prelude::*;

/// The default robot (`biscara robot`).
pub fn default_robot() -> Robot {
    Robot::default()
}

/// A robot that is not symmetric about the Y axis, with a long distal link.
pub fn asymmetric_robot() -> Robot {
    let mut robot = Robot::default();
    robot.links.l1 = 180.0;
    robot.links.l2 = 320.0;
    robot.base.b1x = 60.0;
    robot.base.b2x = -90.0;
    robot.joint_limits.theta1 = [-180.0, 180.0];
    robot.joint_limits.theta2 = [-180.0, 180.0];
    robot
}

/// Both test robots in each of the four working modes and both assembly modes.
pub fn models() -> Vec<(String, Kinematics)> {
    models_with(|_| {})
}

/// [`models`], with `edit` applied to both robots first.
pub fn models_with(edit: impl Fn(&mut Robot)) -> Vec<(String, Kinematics)> {
    let mut models = Vec::new();
    for (name, mut robot) in [("default", default_robot()), ("asymmetric", asymmetric_robot())] {
        edit(&mut robot);
        let model = Kinematics::new(&robot).expect("valid test robot");
        for mode in WorkingMode::ALL {
            for assembly in [Sign::Plus, Sign::Minus] {
                let assembly = AssemblyMode(assembly);
                models.push((
                    format!("{name} robot in working mode {mode}, assembly mode {assembly}"),
                    model.with_working_mode(mode).with_assembly_mode(assembly),
                ));
            }
        }
    }
    models
}

/// Any pose in a box around the workspace (mm, radians); many are unreachable.
pub fn any_pose() -> impl Strategy<Value = Pose> {
    (-520.0..520.0f64, -520.0..560.0f64, -50.0..150.0f64, -400.0..400.0f64)
        .prop_map(|(x, y, z, c)| Pose::from_degrees(x, y, z, c))
}

/// Any joint vector with θ1, θ2 over the full turn (radians, mm).
pub fn any_joints() -> impl Strategy<Value = Joints> {
    (-180.0..180.0f64, -180.0..180.0f64, -180.0..180.0f64, 0.0..100.0f64)
        .prop_map(|(t1, t2, t3, d4)| Joints::from_degrees(t1, t2, t3, d4))
}
