//! Joint trajectories (docs/motion.md), the paper's `trajectoryJoint`: every Cartesian sample
//! solved by inverse kinematics in the robot's working and assembly mode, θ3 kept continuous,
//! velocities and accelerations from finite differences, written as the joint CSV a virtual or real
//! robot follows.
//!
//! [`JointTrajectory`] turns an iterator of [`CartesianSample`]s into an iterator of
//! [`JointSample`]s and fails at the first sample the robot cannot take, naming its line and time.
//! [`JointSpeedLimit`] is the interpolator's [`biscara_interpolate::SpeedLimit`] from the joint
//! velocity limits. It streams: a batch of samples read ahead (solved together by batch IK) and
//! three solved samples are held.
//!
//! ```
//! use biscara_interpolate::CartesianSample;
//! use biscara_joints::JointTrajectory;
//! use biscara_kinematics::Kinematics;
//!
//! let home = [0.0, 460.798724079689, 100.0, 0.0];
//! let samples = [Ok::<_, std::convert::Infallible>(CartesianSample { t: 0.0, pose: home, line: 0, gripper: false })];
//! let rows: Vec<_> = JointTrajectory::new(samples.into_iter(), Kinematics::default())
//!     .collect::<Result<_, _>>()?;
//! assert!(rows[0].joints.theta1.abs() < 1e-9);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod csv;
mod differences;
mod limiter;
mod peaks;
mod solver;
mod torque;
mod trajectory;

pub use biscara_interpolate::CartesianSample;

pub use csv::{
    AngleUnit, JointCsvError, JointCsvFormat, JointCsvReader, JointCsvRow, JointCsvWriter,
    TOOL_COLUMNS, TORQUE_COLUMNS, TrajectorySummary, read_joint_csv,
};
pub use differences::{central_differences, end_derivatives, slope};
pub use limiter::{JointSpeedLimit, cartesian_limits};
pub use peaks::{JointPeaks, LIMIT_TOLERANCE, Peak, Peaks, user_unit};
pub use solver::{JointSolver, LimitViolation, PreparedSamples, SampleError};
pub use trajectory::{BATCH_SAMPLES, JointSample, JointTrajectory, JointsError};
