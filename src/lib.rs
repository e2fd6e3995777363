//! biscara: offline programming and simulation of a 4-axis robot with hybrid kinematics — a
//! five-bar (5R, "BiSCARA") planar parallel mechanism plus a vertical prismatic axis and a rotary
//! axis about Z.
//!
//! This facade re-exports the stage crates, one per step of the pipeline; the `biscara` binary is
//! a thin command line over them. Stages so far:
//!
//! - [`kinematics`]: the robot model (`robot.json`) and exact inverse and forward kinematics.
//! - [`dynamics`]: the rigid-body model and inverse dynamics (the motors' torques).
//! - [`motion`]: the motions of a program and their file form, the inter-file.
//! - [`interpolate`]: Cartesian samples at a fixed time step, and the path CSV.
//! - [`joints`]: joint trajectories from Cartesian samples, and the joint CSV.
//! - [`diff`]: numeric comparison of outputs within a tolerance (golden-file checks).
//! - [`pnp`]: pick-and-place points files and the CL program they make (`biscara clf`).
//! - [`robot`]: the virtual robot: body poses, scenes, collisions, `check`, the workspace and
//!   its rectangle, placing programs (`--fit`).
//! - [`cl`]: CL statements, read and written: the contract between `pnp` and `post`.
//! - [`post`]: CL files posted to LinuxCNC G-code (`biscara post`).
//! - [`gcode`]: LinuxCNC's G-code interpreted into motions (`biscara interpret`).
//! - [`view`]: the HTML viewer, the MuJoCo model and the SVG/PNG plots of a trajectory
//!   (`biscara view`, `mjcf`, `plot`).
//! - [`design`]: robot design sweeps (link lengths, base) against workspace and conditioning
//!   (`biscara design`).
//! - [`text`]: the text plumbing the stages share: bounded lines, fixed decimals, numeric CSV.
//!
//! ```
//! use biscara::kinematics::{Kinematics, Pose};
//!
//! let model = Kinematics::default();
//! let ik = model.inverse_checked(&Pose::from_degrees(150.0, 320.0, 10.0, 30.0))?;
//! println!("{:?}", ik.joints.to_degrees());
//! # Ok::<(), biscara::kinematics::KinematicsError>(())
//! ```

pub use biscara_cl as cl;
pub use biscara_design as design;
pub use biscara_diff as diff;
pub use biscara_dynamics as dynamics;
pub use biscara_gcode as gcode;
pub use biscara_interpolate as interpolate;
pub use biscara_joints as joints;
pub use biscara_kinematics as kinematics;
pub use biscara_linuxcnc as linuxcnc;
pub use biscara_motion as motion;
pub use biscara_pipeline as pipeline;
pub use biscara_pnp as pnp;
pub use biscara_post as post;
pub use biscara_robot as robot;
pub use biscara_text as text;
pub use biscara_view as view;
