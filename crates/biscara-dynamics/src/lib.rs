//! The BiSCARA's rigid-body model and inverse dynamics (docs/dynamics.md): the closed five-bar
//! chain with its passive elbows, the Z slide and the rotary tool, driven by four motors.
//!
//! [`Dynamics`] is built once from a validated robot; [`Dynamics::torques`] gives the torques
//! (N·m) and the force (N) the motors must give at a joint position, velocity and acceleration
//! with a payload. The crate is sans-IO and knows no G-code or trajectory: one sample at a time,
//! allocating nothing.
//!
//! ```
//! use biscara_dynamics::Dynamics;
//! use biscara_kinematics::RobotModel;
//!
//! let dynamics = Dynamics::new(&RobotModel::default())?;
//! let [tau1, tau2, tau3, f_d4] = dynamics.torques([0.0; 4], [0.0; 4], [0.0; 4], 0.5)?;
//! // At rest only the slide feels gravity: holding it takes −(slide + payload)·g along +d4.
//! assert!(tau1 == 0.0 && tau2 == 0.0 && tau3 == 0.0);
//! let slide = dynamics.bodies().slide;
//! assert!((f_d4 + (slide + 0.5) * 9.80665).abs() < 1e-9);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod bodies;
mod inverse;

pub use biscara_kinematics::Motor;
pub use bodies::{ALUMINIUM_DENSITY, Bodies, Link, STANDARD_GRAVITY, robot_in_force};
pub use inverse::{Dynamics, Linkage, PathCoefficients};

/// Why the dynamics cannot be built or a pose's torques cannot be computed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum DynamicsError {
    /// Occurs when d4's motor is too weak to hold the slide and the payload against gravity.
    #[error(
        "motors.d4.peak: the d4 motor's peak force {} N cannot hold the slide and the payload \
         against gravity: that takes (slide {} kg + payload {} kg) × {} m/s² = {} N",
        Micro(*peak_n), Micro(*slide_kg), Micro(*payload_kg), Micro(*gravity), Micro(*needed_n)
    )]
    WeakSlideMotor {
        /// The d4 motor's peak force, N.
        peak_n: f64,
        /// The force holding the slide and payload takes, N.
        needed_n: f64,
        /// The slide's mass, kg.
        slide_kg: f64,
        /// The payload's mass, kg.
        payload_kg: f64,
        /// Gravity, m/s².
        gravity: f64,
    },
    /// Occurs when the joints θ1, θ2 do not assemble the five-bar (the distal links cannot meet).
    #[error(
        "the five-bar does not assemble at theta1 = {theta1_deg:.4} deg, theta2 = {theta2_deg:.4} deg: {source}"
    )]
    Assembly {
        /// θ1, degrees.
        theta1_deg: f64,
        /// θ2, degrees.
        theta2_deg: f64,
        /// What the kinematics said.
        source: biscara_kinematics::KinematicsError,
    },
    /// Occurs at a parallel (type 2) singularity, where the distal links are aligned and the
    /// motors cannot hold the platform: the torques are unbounded.
    #[error(
        "the distal links are aligned at theta1 = {theta1_deg:.4} deg, theta2 = {theta2_deg:.4} \
         deg (a parallel singularity): the torques are unbounded there"
    )]
    Singular {
        /// θ1, degrees.
        theta1_deg: f64,
        /// θ2, degrees.
        theta2_deg: f64,
    },
    /// Occurs when a joint value, rate or the payload is not a finite number, or when a torque
    /// (or its square summed over a cycle) overflows: rates far beyond any robot's.
    #[error("{what} is not a finite number")]
    NotFinite {
        /// What is not finite.
        what: &'static str,
    },
}

/// A number in a message: rounded to 6 decimals (µN, mg), trailing zeros dropped, so that a
/// computed mass or force reads `0.246714`, not `0.24671397333050854`.
struct Micro(f64);

impl std::fmt::Display for Micro {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let text = format!("{:.6}", self.0);
        let text = if text.contains('.') {
            text.trim_end_matches('0').trim_end_matches('.')
        } else {
            &text
        };
        f.write_str(if text == "-0" { "0" } else { text })
    }
}

impl DynamicsError {
    /// The `robot.json` key this error is about, when it is about the robot file.
    pub fn key(&self) -> Option<&'static str> {
        match self {
            DynamicsError::WeakSlideMotor { .. } => Some("motors.d4.peak"),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_weak_slide_message_rounds_its_computed_figures() {
        let err = DynamicsError::WeakSlideMotor {
            peak_n: 20.0,
            needed_n: 51.452_687_586_561_63,
            slide_kg: 0.246_713_973_330_508_54,
            payload_kg: 5.0,
            gravity: 9.80665,
        };
        assert_eq!(
            err.to_string(),
            "motors.d4.peak: the d4 motor's peak force 20 N cannot hold the slide and the payload \
             against gravity: that takes (slide 0.246714 kg + payload 5 kg) × 9.80665 m/s² = \
             51.452688 N"
        );
        assert_eq!(Micro(29.41995).to_string(), "29.41995");
        assert_eq!(Micro(1e9 + 0.25).to_string(), "1000000000.25");
        assert_eq!(Micro(-1e-9).to_string(), "0");
    }
}
