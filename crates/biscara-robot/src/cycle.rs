//! The Adept cycle (docs/dynamics.md): the industry's pick-and-place benchmark run on the
//! virtual robot, with its motors' torques against their ratings.

use std::convert::Infallible;
use std::fmt;

use biscara_dynamics::{Dynamics, DynamicsError};
use biscara_interpolate::{InterpolationConfig, Interpolator, Profile, SlowDown};
use biscara_joints::{JointSpeedLimit, JointTrajectory, JointsError, cartesian_limits};
use biscara_kinematics::{Joint, Pose, Robot, RobotError, RobotModel};
use biscara_motion::{Motion, MotionKind};
use biscara_text::{fixed, round_to};
use serde_json::{Value, json};

use crate::{VirtualRobotError, Workspace};

/// How high the cycle lifts, mm.
pub const CYCLE_LIFT_MM: f64 = 25.0;
/// How far the cycle travels along x, mm.
pub const CYCLE_ACROSS_MM: f64 = 305.0;
/// The cycle's height by default, mm.
pub const CYCLE_Z_MM: f64 = 40.0;
/// The grid step of the workspace whose largest rectangle centres the cycle by default, mm (the
/// default of `biscara workspace`).
const WORKSPACE_STEP_MM: f64 = 2.0;

/// Where and how the Adept cycle runs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CycleConfig {
    /// The cycle's centre `[x, y]` (mm); `None`: the centre of the workspace's largest rectangle.
    pub at: Option<[f64; 2]>,
    /// The height of its low points, mm.
    pub z: f64,
    /// The payload carried all the way, kg; `None`: the robot file's `dynamics.payload`.
    pub payload_kg: Option<f64>,
    /// Blend the corners within this many mm (G64 P); `None`: an exact stop at each corner.
    pub blend_mm: Option<f64>,
    /// Time step of the sampled trajectory, s.
    pub dt: f64,
}

impl Default for CycleConfig {
    /// At the largest rectangle's centre, z 40 mm, the robot's payload, exact stops, 1 ms.
    fn default() -> CycleConfig {
        CycleConfig { at: None, z: CYCLE_Z_MM, payload_kg: None, blend_mm: None, dt: 0.001 }
    }
}

/// One motor's torques over a cycle: N·m for θ1–θ3, N for d4.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CycleMotor {
    /// The largest |torque| over the cycle.
    pub peak: f64,
    /// The root mean square of the torque over the cycle.
    pub rms: f64,
    /// The torque that holds the robot at rest at the cycle's start (d4: the slide and payload's
    /// weight), which a dwell costs.
    pub holding: f64,
    /// The motor's `peak` and `rated` torques, when the robot file has `motors`.
    pub ratings: Option<[f64; 2]>,
}

/// The Adept cycle's figures.
#[derive(Debug, Clone, PartialEq)]
pub struct CycleReport {
    /// The cycle's duration, s.
    pub cycle_s: f64,
    /// Its centre `[x, y]`, mm.
    pub at: [f64; 2],
    /// The height of its low points, mm.
    pub z: f64,
    /// The payload carried, kg.
    pub payload_kg: f64,
    /// Each motor's torques, `[theta1, theta2, theta3, d4]`.
    pub motors: [CycleMotor; 4],
    /// The shortest dwell at the end of each cycle that keeps every motor's RMS torque within its
    /// rating when the cycle repeats, s (0 when none is needed); `None` without motors, or when
    /// no dwell is enough (a motor's holding torque alone is beyond its rating).
    pub dwell_s: Option<f64>,
}

impl CycleReport {
    /// The most cycles a minute the motors sustain: `60 / (cycle_s + dwell_s)`; `None` where
    /// [`dwell_s`](Self::dwell_s) is.
    pub fn sustained_cycles_per_min(&self) -> Option<f64> {
        self.dwell_s.map(|dwell| 60.0 / (self.cycle_s + dwell))
    }

    /// The report as JSON: `{"cycle_s","at":[x,y],"z","payload_kg","peak":{…},"rms":{…},
    /// "dwell_s","sustained_cycles_per_min"}`, each joint's torque as `{"value","limit","unit"}`,
    /// numbers rounded to 6 decimals (`null` where a figure is unknown).
    pub fn to_json(&self) -> Value {
        let (mut peak, mut rms) = (serde_json::Map::new(), serde_json::Map::new());
        for (joint, motor) in Joint::ALL.into_iter().zip(&self.motors) {
            let [peak_limit, rated] = match motor.ratings {
                Some([peak, rated]) => [round6(peak), round6(rated)],
                None => [Value::Null, Value::Null],
            };
            let name = joint.name().to_owned();
            let unit = torque_unit(joint);
            peak.insert(
                name.clone(),
                json!({"value": round6(motor.peak), "limit": peak_limit, "unit": unit}),
            );
            rms.insert(name, json!({"value": round6(motor.rms), "limit": rated, "unit": unit}));
        }
        json!({
            "cycle_s": round6(self.cycle_s),
            "at": [round6(self.at[0]), round6(self.at[1])],
            "z": round6(self.z),
            "payload_kg": round6(self.payload_kg),
            "peak": peak,
            "rms": rms,
            "dwell_s": self.dwell_s.map(round6),
            "sustained_cycles_per_min": self.sustained_cycles_per_min().map(round6),
        })
    }
}

/// A number rounded to 6 decimals, for JSON.
fn round6(value: f64) -> Value {
    json!(round_to(value, 6))
}

/// The unit of a joint's torque: N·m for a revolute joint, N for the prismatic d4.
fn torque_unit(joint: Joint) -> &'static str {
    if joint.is_revolute() { "N·m" } else { "N" }
}

/// The report as `biscara cycle` prints it: the cycle, its time, each motor's peak and RMS
/// torque against its ratings, and the sustained rate (or why there is none).
impl fmt::Display for CycleReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "Adept cycle at ({}, {}) mm, z {} mm, payload {} kg: 25 mm up, 305 mm across, 25 mm \
             down and back",
            fixed(self.at[0], 3),
            fixed(self.at[1], 3),
            fixed(self.z, 3),
            self.payload_kg
        )?;
        writeln!(f, "cycle time: {} s", fixed(self.cycle_s, 3))?;
        writeln!(f, "motor torques (peak against peak, RMS against rated):")?;
        for (joint, motor) in Joint::ALL.into_iter().zip(&self.motors) {
            let unit = torque_unit(joint);
            let (peak_limit, rated) = match motor.ratings {
                Some([peak, rated]) => (format!(" (peak {peak})"), format!(" (rated {rated})")),
                None => (String::new(), String::new()),
            };
            writeln!(
                f,
                "  {:<7} peak {:>10} {unit}{peak_limit}, RMS {:>10} {unit}{rated}",
                joint.name(),
                fixed(motor.peak, 3),
                fixed(motor.rms, 3),
            )?;
        }
        match (self.dwell_s, self.sustained_cycles_per_min()) {
            (Some(dwell), Some(rate)) if dwell > 0.0 => writeln!(
                f,
                "sustained: {} cycles/min, with a dwell of {} s after each cycle (RMS within \
                 rated)",
                fixed(rate, 1),
                fixed(dwell, 3)
            ),
            (Some(_), Some(rate)) => writeln!(
                f,
                "sustained: {} cycles/min, back to back (RMS within rated)",
                fixed(rate, 1)
            ),
            _ if self.motors[0].ratings.is_none() => {
                writeln!(f, "sustained: unknown: the robot file has no motors")
            }
            _ => writeln!(
                f,
                "sustained: none: a motor's torque holding the robot at rest is beyond its rating"
            ),
        }
    }
}

/// Why the cycle cannot be run.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum CycleError {
    /// Occurs when a corner of the cycle is out of the robot's reach (or beyond a joint limit
    /// or within the singularity margin).
    #[error(
        "the cycle's {point} at (x, y, z) = ({x:.3}, {y:.3}, {z:.3}) mm cannot be reached: {reason}"
    )]
    Unreachable {
        /// Which corner: `start (left, low)`, `left, up`, `right, up`, `right, low`.
        point: &'static str,
        /// Its coordinates, mm.
        x: f64,
        /// Its coordinates, mm.
        y: f64,
        /// Its coordinates, mm.
        z: f64,
        /// What the kinematics said.
        reason: String,
    },
    /// Occurs when a sample between the corners cannot be taken (the straight line between two
    /// reachable corners leaves the workspace or meets a singularity).
    #[error("the cycle leaves the workspace between its corners: {reason}")]
    Path {
        /// What the joint solver said.
        reason: String,
    },
    /// Occurs when a setting is not a finite number, or the payload is negative.
    #[error("{what} must be a finite number{} (got {value})", if *.non_negative { " ≥ 0" } else { "" })]
    Setting {
        /// Which setting.
        what: &'static str,
        /// Its value.
        value: f64,
        /// Whether it must also be ≥ 0.
        non_negative: bool,
    },
    /// Occurs when the workspace (for the default centre) cannot be computed.
    #[error(transparent)]
    Workspace(#[from] VirtualRobotError),
    /// Occurs when the robot with the cycle's payload cannot be modelled.
    #[error(transparent)]
    Robot(#[from] RobotError),
    /// Occurs when the dynamic model cannot be built (d4's motor too weak for the payload).
    #[error(transparent)]
    Dynamics(#[from] DynamicsError),
    /// Occurs when the cycle cannot be timed.
    #[error("the cycle cannot be timed: {reason}")]
    Timing {
        /// What the interpolator said.
        reason: String,
    },
}

/// The cycle's corners, in the order they are visited from the start.
const CORNERS: [&str; 4] = ["start (left, low)", "left, up", "right, up", "right, low"];

/// Runs the Adept cycle on `model` (docs/dynamics.md): from the start, 25 mm up, 305 mm across
/// along +x, 25 mm down, and back the same way, centred at `config.at`, each segment a rapid
/// (G0) under the default optimal profile — with `motors`, bounded by their torques — carrying
/// the payload all the way; then the motors' peak and RMS torques over the cycle (inverse
/// dynamics of the sampled trajectory's central differences), and the dwell that lets the
/// motors repeat it without exceeding their rated torque.
pub fn adept_cycle(model: &RobotModel, config: &CycleConfig) -> Result<CycleReport, CycleError> {
    let setting = |what: &'static str, value: f64, non_negative: bool| {
        if value.is_finite() && (!non_negative || value >= 0.0) {
            Ok(())
        } else {
            Err(CycleError::Setting { what, value, non_negative })
        }
    };
    setting("z", config.z, false)?;
    if let Some([x, y]) = config.at {
        setting("x", x, false)?;
        setting("y", y, false)?;
    }
    if let Some(payload) = config.payload_kg {
        setting("the payload", payload, true)?;
    }
    if let Some(blend) = config.blend_mm {
        setting("the blend tolerance", blend, true)?;
    }
    let at = match config.at {
        Some(at) => at,
        None => Workspace::compute(&model.kinematics(), WORKSPACE_STEP_MM)?
            .largest_rectangle()?
            .center(),
    };
    let mut robot: Robot = model.robot().clone();
    if let Some(payload) = config.payload_kg {
        let mut dynamics = robot.dynamics.unwrap_or_default();
        dynamics.payload.mass = Some(payload);
        robot.dynamics = Some(dynamics);
    }
    let model = RobotModel::new(robot)?;
    let kinematics = model.kinematics();
    let (half, z) = (0.5 * CYCLE_ACROSS_MM, config.z);
    let (left, right) = (at[0] - half, at[0] + half);
    let corners = [
        [left, at[1], z, 0.0],
        [left, at[1], z + CYCLE_LIFT_MM, 0.0],
        [right, at[1], z + CYCLE_LIFT_MM, 0.0],
        [right, at[1], z, 0.0],
    ];
    for (point, corner) in CORNERS.into_iter().zip(corners) {
        let [x, y, z, c] = corner;
        let reached =
            kinematics.inverse_checked(&Pose::from_degrees(x, y, z, c)).and_then(|solution| {
                kinematics.check_limits(&solution.joints)?;
                kinematics.check_singularity(&solution.configuration)
            });
        if let Err(err) = reached {
            return Err(CycleError::Unreachable { point, x, y, z, reason: err.to_string() });
        }
    }
    let dynamics = Dynamics::new(&model)?;
    let payload = dynamics.bodies().payload;
    let mut motions = vec![Motion::new(1, MotionKind::Pick)];
    for (index, corner) in [1, 2, 3, 2, 1, 0].into_iter().enumerate() {
        let motion = Motion::new(index + 2, MotionKind::Rapid { end: corners[corner] });
        motions.push(Motion { blend: config.blend_mm, ..motion });
    }
    let sampling = InterpolationConfig {
        dt: config.dt,
        profile: Profile::Optimal,
        start: corners[0],
        limits: cartesian_limits(model.robot()),
        grip_time: 0.0,
    };
    let limit = JointSpeedLimit::new(kinematics, model.robot()).with_motors(&model)?;
    let samples = Interpolator::new(
        motions.into_iter().map(Ok::<_, Infallible>),
        sampling,
        limit,
        |_: &SlowDown| {},
    );
    let (mut peak, mut squares) = ([0.0f64; 4], [0.0f64; 4]);
    let (mut previous_t, mut cycle_s) = (0.0, 0.0);
    let mut first = true;
    for row in JointTrajectory::new(samples, kinematics) {
        let row = row.map_err(|err| match err {
            JointsError::Input(err) => CycleError::Timing { reason: err.to_string() },
            other => CycleError::Path { reason: other.to_string() },
        })?;
        let torques =
            dynamics.torques(row.joints.to_array(), row.velocity, row.acceleration, payload)?;
        // Each sample stands for the time since the one before (a trapezoid rule's weights
        // but at the ends): the sum is the cycle's duration.
        let weight = if first { 0.0 } else { row.t - previous_t };
        first = false;
        for j in 0..4 {
            peak[j] = peak[j].max(torques[j].abs());
            squares[j] += torques[j] * torques[j] * weight;
        }
        previous_t = row.t;
        cycle_s = row.t;
    }
    let start = kinematics.inverse(&Pose::from_degrees(left, at[1], z, 0.0)).map_err(|err| {
        CycleError::Unreachable { point: CORNERS[0], x: left, y: at[1], z, reason: err.to_string() }
    })?;
    let holding = dynamics.rigid_torques(start.joints.to_array(), [0.0; 4], [0.0; 4], payload)?;
    // Torques near f64's range square to infinity: an error, never an RMS of `inf`.
    const SQUARES: [&str; 4] =
        ["theta1's RMS torque", "theta2's RMS torque", "theta3's RMS torque", "d4's RMS force"];
    if let Some(joint) = squares.iter().position(|square| !square.is_finite()) {
        return Err(DynamicsError::NotFinite { what: SQUARES[joint] }.into());
    }
    let ratings = dynamics.motors().map(|motors| motors.map(|motor| [motor.peak, motor.rated]));
    let motors: [CycleMotor; 4] = std::array::from_fn(|j| CycleMotor {
        peak: peak[j],
        rms: if cycle_s > 0.0 { (squares[j] / cycle_s).sqrt() } else { 0.0 },
        holding: holding[j].abs(),
        ratings: ratings.map(|ratings| ratings[j]),
    });
    let dwell_s = ratings.and_then(|ratings| {
        dwell(cycle_s, &squares, &motors.map(|motor| motor.holding), &ratings.map(|r| r[1]))
    });
    Ok(CycleReport { cycle_s, at, z, payload_kg: payload, motors, dwell_s })
}

/// The shortest dwell `d` after a cycle of `cycle_s` (∫ τ² dt = `squares`) such that every
/// motor's RMS over the cycle and the dwell, `√((squares + d · holding²) / (cycle_s + d))`, is
/// within `rated`; `None` when no dwell is enough.
fn dwell(cycle_s: f64, squares: &[f64; 4], holding: &[f64; 4], rated: &[f64; 4]) -> Option<f64> {
    let mut dwell = 0.0f64;
    for j in 0..4 {
        let excess = squares[j] - rated[j] * rated[j] * cycle_s;
        if excess <= 0.0 {
            continue;
        }
        let relief = rated[j] * rated[j] - holding[j] * holding[j];
        if relief <= 0.0 {
            return None;
        }
        dwell = dwell.max(excess / relief);
    }
    Some(dwell)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_dwell_brings_the_rms_down_to_the_rating() {
        // 1 s at an RMS of 2 against a rating of 1, holding 0: 3 s of dwell.
        let dwell = dwell(1.0, &[4.0, 0.0, 0.0, 0.0], &[0.0; 4], &[1.0; 4]).expect("a dwell");
        assert!((dwell - 3.0).abs() < 1e-12);
        // Holding 0.5: (4 + 0.25 d) / (1 + d) = 1 → d = 4.
        let dwell = dwell_of(0.5);
        assert!((dwell.expect("a dwell") - 4.0).abs() < 1e-12);
        // Holding at the rating: no dwell helps.
        assert_eq!(dwell_of(1.0), None);
        // Within the rating: no dwell needed.
        assert_eq!(super::dwell(1.0, &[0.5; 4], &[0.9; 4], &[1.0; 4]), Some(0.0));
    }

    fn report(ratings: Option<[f64; 2]>, dwell_s: Option<f64>) -> CycleReport {
        let motor = CycleMotor { peak: 2.5, rms: 1.25, holding: 0.0, ratings };
        CycleReport {
            cycle_s: 0.5,
            at: [10.0, 250.0],
            z: 40.0,
            payload_kg: 2.0,
            motors: [motor; 4],
            dwell_s,
        }
    }

    #[test]
    fn the_report_prints_its_figures_and_the_sustained_rate() {
        let text = report(Some([3.0, 1.0]), Some(0.5)).to_string();
        assert!(text.starts_with("Adept cycle at (10.000, 250.000) mm, z 40.000 mm, payload 2 kg"));
        assert!(text.contains("cycle time: 0.500 s\n"));
        assert!(
            text.contains("  theta1  peak      2.500 N·m (peak 3), RMS      1.250 N·m (rated 1)\n")
        );
        assert!(text.contains("  d4      peak      2.500 N (peak 3)"));
        // 60 / (0.5 + 0.5) cycles a minute.
        assert!(text.ends_with("sustained: 60.0 cycles/min, with a dwell of 0.500 s after each cycle (RMS within rated)\n"));
        let text = report(Some([3.0, 1.0]), Some(0.0)).to_string();
        assert!(text.ends_with("sustained: 120.0 cycles/min, back to back (RMS within rated)\n"));
        assert!(
            report(None, None).to_string().ends_with("unknown: the robot file has no motors\n")
        );
        assert!(report(Some([3.0, 1.0]), None).to_string().ends_with("beyond its rating\n"));
    }

    #[test]
    fn the_json_report_has_each_joint_with_its_unit_and_limits() {
        let json = report(Some([3.0, 1.0]), Some(0.5)).to_json();
        assert_eq!(json["cycle_s"], 0.5);
        assert_eq!(json["peak"]["theta2"]["limit"], 3.0);
        assert_eq!(json["rms"]["d4"], json!({"value": 1.25, "limit": 1.0, "unit": "N"}));
        assert_eq!(json["sustained_cycles_per_min"], 60.0);
        let json = report(None, None).to_json();
        assert_eq!(json["peak"]["theta1"]["limit"], Value::Null);
        assert_eq!(json["dwell_s"], Value::Null);
    }

    fn dwell_of(holding: f64) -> Option<f64> {
        dwell(1.0, &[4.0, 0.0, 0.0, 0.0], &[holding, 0.0, 0.0, 0.0], &[1.0; 4])
    }
}
