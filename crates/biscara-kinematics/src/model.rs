//! The validated robot: built once when the robot file is loaded.

use crate::{Kinematics, Robot, RobotError};

/// A robot that has been validated, with its kinematics precomputed: what every later stage
/// takes instead of a [`Robot`] it would have to validate again.
///
/// Built once, when the robot file is read ([`RobotModel::from_json`]) or from a [`Robot`]
/// value ([`RobotModel::new`]); the fields are private, so a `RobotModel` is valid by
/// construction. Cheap to share by reference.
#[derive(Debug, Clone, PartialEq)]
pub struct RobotModel {
    robot: Robot,
    kinematics: Kinematics,
}

impl RobotModel {
    /// Validates `robot` and precomputes its kinematics.
    pub fn new(robot: Robot) -> Result<RobotModel, RobotError> {
        let kinematics = Kinematics::new(&robot)?;
        Ok(RobotModel { robot, kinematics })
    }

    /// Reads, validates and models a robot from the text of a `robot.json` file; errors carry
    /// the line, column and key (see [`Robot::from_json`]).
    pub fn from_json(text: &str) -> Result<RobotModel, RobotError> {
        RobotModel::new(Robot::from_json(text)?)
    }

    /// The robot file's values (degrees, millimetres): limits, motion limits, geometry.
    pub fn robot(&self) -> &Robot {
        &self.robot
    }

    /// The kinematics, in millimetres and radians (`Copy`: solving a pose allocates nothing).
    pub fn kinematics(&self) -> Kinematics {
        self.kinematics
    }

    /// The home pose `[x, y, z, c]` in millimetres and degrees: where every program starts.
    pub fn home_position(&self) -> [f64; 4] {
        self.kinematics.home().to_degrees()
    }
}

impl Default for RobotModel {
    /// The built-in robot of docs/kinematics.md.
    fn default() -> RobotModel {
        RobotModel { robot: Robot::default(), kinematics: Kinematics::default() }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_model_is_the_default_robot_validated() {
        let model = RobotModel::default();
        assert_eq!(model, RobotModel::new(Robot::default()).expect("default robot"));
        let [x, y, z, c] = model.home_position();
        assert!(x.abs() < 1e-9 && (y - 460.7987).abs() < 1e-4 && z == 100.0 && c == 0.0);
    }

    #[test]
    fn an_impossible_robot_is_refused_with_its_key() {
        let err = RobotModel::from_json(r#"{"links": {"l1": -1.0, "l2": 270.0}}"#)
            .expect_err("negative length");
        assert_eq!(err.key(), "links.l1");
    }
}
