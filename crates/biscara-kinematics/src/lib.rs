//! The robot model and exact kinematics of the BiSCARA: a five-bar (5R) planar parallel
//! mechanism carrying a vertical prismatic axis and a rotary axis about Z.
//!
//! This crate reads and validates `robot.json` ([`Robot`]), solves inverse and forward kinematics
//! in all four working modes and both assembly modes ([`Kinematics`]), computes the planar
//! Jacobian and the singularity angles, checks joint limits, and keeps θ3 continuous along a
//! path ([`Theta3Unwrapper`]); [`Kinematics::inverse_batch`] and
//! [`Kinematics::reachable_batch`] solve many poses at once, vectorised for the CPU found at run
//! time. Units are millimetres and radians; degrees appear only in [`Robot`] (the file's units)
//! and in error messages.
//!
//! It deliberately knows nothing of G-code, files or trajectories: callers hand it one pose or
//! one joint vector at a time, and solving one allocates nothing.
//!
//! ```
//! use biscara_kinematics::{Kinematics, Pose, Robot};
//!
//! let robot = Robot::default();
//! let model = Kinematics::new(&robot)?;
//! let pose = Pose::from_degrees(150.0, 320.0, 10.0, 30.0);
//! let ik = model.inverse_checked(&pose)?;
//! let fk = model.forward(&ik.joints)?;
//! assert!((fk.pose.x - 150.0).abs() < 1e-9 && (fk.pose.y - 320.0).abs() < 1e-9);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod batch;
mod dynamics;
mod error;
mod jacobian;
mod kinematics;
mod meshes;
mod mode;
mod model;
mod object;
mod pose;
mod report;
mod robot;
mod unwrap;

pub use nalgebra as na;

pub use batch::{
    BatchSolution, BatchStatus, Dispatch, LANES, PoseColumns, SolutionColumns, atan2 as batch_atan2,
};
pub use dynamics::{
    BodySpec, DynamicsSpec, MAX_GRAVITY, MAX_INERTIA_KG_M2, MAX_MASS_KG, MAX_MOTOR_EFFORT,
    MAX_ROTOR_INERTIA, Motor, Motors, PointSpec, ToolBodySpec,
};
pub use error::{KinematicsError, Shortfall, SingularityKind};
pub use jacobian::PlanarJacobian;
pub use kinematics::{
    FkSolution, IkSolution, Kinematics, PassiveJoints, PlanarConfiguration, SingularityAngles,
    wrap_angle,
};
pub use meshes::{MeshSpec, Meshes, Part};
pub use mode::{AssemblyMode, ParseModeError, Sign, WorkingMode};
pub use model::RobotModel;
pub use pose::{Chain, Joint, Joints, Pose};
pub use report::{JointsError, PoseError};
pub use robot::{
    Base, Geometry, JointLimits, JointValues, Links, MotionLimits, Robot, RobotError, ToolKind,
    ToolSpec,
};
pub use unwrap::{AngleUnwrapper, Theta3Unwrapper};
