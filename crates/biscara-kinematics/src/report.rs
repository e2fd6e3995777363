//! One pose's solution as `biscara ik` and `biscara fk` print it (README.md).

use biscara_text::fixed;
use serde::Serialize;

use crate::{FkSolution, IkSolution, Kinematics};

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
