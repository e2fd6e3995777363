//! One pose's solution as `biscara ik` and `biscara fk` print it (README.md).

use biscara_text::fixed;
use serde::Serialize;

use crate::{FkSolution, IkSolution, Joints, Kinematics, KinematicsError, Pose};

/// A pose `biscara ik` cannot solve: the pose as typed (mm, degrees), and why.
#[derive(Debug, thiserror::Error)]
#[error("pose (x, y, z, c) = ({x}, {y}, {z}, {c}) is unreachable")]
pub struct PoseError {
    /// X, mm.
    pub x: f64,
    /// Y, mm.
    pub y: f64,
    /// Z, mm.
    pub z: f64,
    /// C, degrees.
    pub c: f64,
    /// Why.
    #[source]
    pub source: KinematicsError,
}

/// Joint values `biscara fk` cannot assemble: the values as typed (degrees, mm), and why.
#[derive(Debug, thiserror::Error)]
#[error("joints (θ1, θ2, θ3, d4) = ({theta1}, {theta2}, {theta3}, {d4}) have no pose")]
pub struct JointsError {
    /// θ1, degrees.
    pub theta1: f64,
    /// θ2, degrees.
    pub theta2: f64,
    /// θ3, degrees.
    pub theta3: f64,
    /// d4, mm.
    pub d4: f64,
    /// Why.
    #[source]
    pub source: KinematicsError,
}

impl Kinematics {
    /// `biscara ik`: the checked inverse kinematics ([`Kinematics::inverse_checked`]) of the
    /// pose `[x, y, z, c]` typed in mm and degrees.
    pub fn ik_typed(&self, [x, y, z, c]: [f64; 4]) -> Result<IkSolution, PoseError> {
        self.inverse_checked(&Pose::from_degrees(x, y, z, c)).map_err(|source| PoseError {
            x,
            y,
            z,
            c,
            source,
        })
    }

    /// `biscara fk`: the forward kinematics of the joints `[θ1, θ2, θ3, d4]` typed in degrees
    /// and mm (outside the limits too: [`Kinematics::fk_warnings`] says so).
    pub fn fk_typed(
        &self,
        [theta1, theta2, theta3, d4]: [f64; 4],
    ) -> Result<FkSolution, JointsError> {
        self.forward(&Joints::from_degrees(theta1, theta2, theta3, d4))
            .map_err(|source| JointsError { theta1, theta2, theta3, d4, source })
    }
}

#[derive(Serialize)]
struct IkJson {
    theta1: f64,
    theta2: f64,
    theta3: f64,
    d4: f64,
    working_mode: String,
    assembly_mode: String,
    singularity: SingularityJson,
}

#[derive(Serialize)]
struct SingularityJson {
    type1_deg: [f64; 2],
    type2_deg: f64,
}

#[derive(Serialize)]
struct FkJson {
    x: f64,
    y: f64,
    z: f64,
    c: f64,
    elbows: [[f64; 2]; 2],
    assembly_mode: String,
}

/// Negative zero as zero, for printed numbers.
fn clean(value: f64) -> f64 {
    value + 0.0
}

/// Four values with six decimals, separated by spaces, never a negative zero.
fn joined(values: [f64; 4]) -> String {
    values.map(|value| fixed(value, 6)).join(" ")
}

impl IkSolution {
    /// `θ1 θ2 θ3 d4` in degrees and millimetres, six decimals.
    pub fn to_text(&self) -> String {
        joined(self.joints.to_degrees())
    }

    /// `{"theta1":…,"theta2":…,"theta3":…,"d4":…,"working_mode":…,"assembly_mode":…,
    /// "singularity":{"type1_deg":[a1,a2],"type2_deg":b}}` (degrees, mm) for the robot `model`.
    pub fn to_json(&self, model: &Kinematics) -> String {
        let [theta1, theta2, theta3, d4] = self.joints.to_degrees().map(clean);
        let singularity = self.configuration.singularity();
        let json = IkJson {
            theta1,
            theta2,
            theta3,
            d4,
            working_mode: model.working_mode().to_string(),
            assembly_mode: self.assembly_mode().to_string(),
            singularity: SingularityJson {
                type1_deg: singularity.type1.map(f64::to_degrees),
                type2_deg: singularity.type2.to_degrees(),
            },
        };
        serde_json::to_string(&json).unwrap_or_default()
    }
}

impl FkSolution {
    /// The pose in millimetres and degrees with c wrapped into (−180°, 180°], as `ik` reads its
    /// input: `fk` of `ik`'s joints prints the pose `ik` was given.
    fn printed_pose(&self) -> [f64; 4] {
        let [x, y, z, _] = self.pose.to_degrees();
        [x, y, z, crate::kinematics::wrap_angle(self.pose.phi).to_degrees()]
    }

    /// `x y z c` in millimetres and degrees, six decimals; c in (−180°, 180°].
    pub fn to_text(&self) -> String {
        joined(self.printed_pose())
    }

    /// `{"x":…,"y":…,"z":…,"c":…,"elbows":[[x,y],[x,y]],"assembly_mode":…}` (mm, degrees; c in
    /// (−180°, 180°]).
    pub fn to_json(&self) -> String {
        let [x, y, z, c] = self.printed_pose().map(clean);
        let elbows = self.configuration.elbows.map(|elbow| [clean(elbow.x), clean(elbow.y)]);
        let assembly_mode = self.configuration.assembly_mode().to_string();
        serde_json::to_string(&FkJson { x, y, z, c, elbows, assembly_mode }).unwrap_or_default()
    }
}

impl Kinematics {
    /// What is wrong with a forward solution that a running robot could not take: joints
    /// outside their limits, another working mode, a pose near a singularity. Forward
    /// kinematics is a calculator and answers anyway; these say why the robot would not.
    pub fn fk_warnings(&self, solution: &FkSolution) -> Vec<String> {
        let mut warnings = Vec::new();
        if let Err(err) = self.check_limits(&solution.joints) {
            warnings.push(err.to_string());
        }
        let mode = solution.configuration.working_mode();
        if mode != self.working_mode() {
            warnings.push(format!(
                "the pose is in working mode {mode}, the robot runs in {}",
                self.working_mode()
            ));
        }
        if let Err(err) = self.check_singularity(&solution.configuration) {
            warnings.push(err.to_string());
        }
        warnings
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn typed_values_name_themselves_in_the_error() {
        let model = Kinematics::default();
        let solution = model.ik_typed([150.0, 320.0, 10.0, 30.0]).unwrap();
        let back = model.fk_typed(solution.joints.to_degrees()).unwrap();
        assert!((back.pose.x - 150.0).abs() < 1e-9 && (back.pose.y - 320.0).abs() < 1e-9);
        let err = model.ik_typed([900.0, 0.0, 0.0, 0.0]).unwrap_err();
        assert_eq!(err.to_string(), "pose (x, y, z, c) = (900, 0, 0, 0) is unreachable");
        assert!(matches!(err.source, KinematicsError::Unreachable { .. }), "{:?}", err.source);
        let err = model.fk_typed([-90.0, 90.0, 0.0, 0.0]).unwrap_err();
        assert_eq!(err.to_string(), "joints (θ1, θ2, θ3, d4) = (-90, 90, 0, 0) have no pose");
    }
}
