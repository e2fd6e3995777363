//! Why a pose or a joint vector cannot be used.

use std::fmt;

use crate::{AssemblyMode, Chain, Joint};

/// Which side of a chain's reach an unreachable point lies on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Shortfall {
    /// Farther from the base joint than `l1 + l2`.
    TooFar,
    /// Closer to the base joint than `|l1 − l2|`.
    TooClose,
}

/// The two kinds of singularity of the five-bar (docs/kinematics.md).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SingularityKind {
    /// Type 1 (serial): the chain is stretched or folded.
    Type1(Chain),
    /// Type 2 (parallel): the two distal links are collinear.
    Type2,
}

impl fmt::Display for SingularityKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SingularityKind::Type1(chain) => write!(f, "type-1 singularity of {chain}"),
            SingularityKind::Type2 => f.write_str("type-2 singularity"),
        }
    }
}

/// A kinematics failure, with the numbers a user needs to fix the program or the robot file.
/// Lengths are millimetres, angles degrees (the user-facing units).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum KinematicsError {
    /// Occurs when a chain cannot reach the platform point: it lies farther from the chain's base
    /// joint than `l1 + l2`, or closer than `|l1 − l2|`.
    #[error(
        "{chain} cannot reach (x, y) = ({x:.3}, {y:.3}): {shortfall_mm:.3} mm {}",
        match side { Shortfall::TooFar => "too far", Shortfall::TooClose => "too close to its base joint" }
    )]
    Unreachable {
        /// The chain that cannot reach.
        chain: Chain,
        /// X of the platform point, millimetres.
        x: f64,
        /// Y of the platform point, millimetres.
        y: f64,
        /// How far outside the chain's reach the point lies, millimetres.
        shortfall_mm: f64,
        /// Whether the point is too far or too close.
        side: Shortfall,
    },
    /// Occurs when both chains reach the point in the robot's working mode, but the distal links
    /// then meet in the other assembly mode: the robot would have to pass a type-2 singularity.
    #[error(
        "(x, y) = ({x:.3}, {y:.3}) is beyond a type-2 singularity: there the distal links meet in \
         assembly mode {found}, the robot is assembled in {expected}"
    )]
    BeyondType2 {
        /// X of the platform point, millimetres.
        x: f64,
        /// Y of the platform point, millimetres.
        y: f64,
        /// The assembly mode of the IK solution.
        found: AssemblyMode,
        /// The robot's assembly mode.
        expected: AssemblyMode,
    },
    /// Occurs when a joint value lies outside its `joint_limits`.
    #[error(
        "{joint} = {value:.3}{unit} is outside its limits [{min}, {max}] by {excess:.3}{unit}",
        unit = joint.unit(),
        excess = if value < min { min - value } else { value - max }
    )]
    JointLimit {
        /// The joint.
        joint: Joint,
        /// Its value: degrees for θ, millimetres for d4.
        value: f64,
        /// Lower limit, same unit.
        min: f64,
        /// Upper limit, same unit.
        max: f64,
    },
    /// Occurs when a pose lies within `singularity_margin` of a singularity.
    #[error("near a {kind}: {angle_deg:.3}° from it, closer than the margin of {margin_deg}°")]
    NearSingular {
        /// Which singularity.
        kind: SingularityKind,
        /// The angle of §1.2 (0° at the singularity), degrees.
        angle_deg: f64,
        /// The robot's `singularity_margin`, degrees.
        margin_deg: f64,
    },
    /// Occurs in FK when the two elbows are farther apart than `2·l2` (or coincide), so the
    /// distal links cannot meet at one platform point.
    #[error(
        "the distal links cannot meet: the elbows are {elbow_distance_mm:.3} mm apart, and they must \
         be apart by more than 0 and at most 2*l2 = {max_mm:.3} mm"
    )]
    NoAssembly {
        /// Distance between the elbows, millimetres.
        elbow_distance_mm: f64,
        /// `2·l2`, millimetres.
        max_mm: f64,
    },
    /// Occurs when a pose or joint value is NaN or infinite.
    #[error("{what} is not a finite number")]
    NotFinite {
        /// Which input (`x`, `theta1`, …).
        what: &'static str,
    },
}

impl KinematicsError {
    /// For a [`KinematicsError::JointLimit`], how far the value lies outside its range (degrees
    /// or millimetres); 0 for other errors.
    pub fn excess(&self) -> f64 {
        match *self {
            KinematicsError::JointLimit { value, min, max, .. } => {
                if value < min {
                    min - value
                } else {
                    value - max
                }
            }
            _ => 0.0,
        }
    }
}
