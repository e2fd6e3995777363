//! The virtual robot of docs/virtual-robot.md: the BiSCARA's whole body at every sample, the scene
//! around it, and the checks a program must pass before it reaches the real robot.
//!
//! - [`VirtualRobot`] and [`Body`]: base joints, proximal and distal links, elbows, platform,
//!   Z column and gripper of one pose, from forward kinematics (or an IK configuration), with
//!   the dimensions of `robot.json`'s `geometry`.
//! - [`Scene`]: the boxes around the robot (`{"boxes":[{"name":…,"min":[x,y,z],"max":[x,y,z]}]}`),
//!   read with errors that name line, column and key.
//! - [`self_collisions`] and [`scene_collisions`]: links as capsules `link_width` wide at
//!   `link_height`, gripper and Z column as vertical cylinders.
//! - [`Checker`]: every sample of a program checked for every problem of docs/virtual-robot.md
//!   without stopping, grouped into [`Problem`]s with their time spans, and a [`Summary`].
//! - [`Workspace`]: the reachable XY grid of docs/virtual-robot.md, its area and the largest
//!   axis-aligned [`Rectangle`] inside it; [`Bounds`] and [`fit()`]: a program's XY extent (arcs
//!   included) and the offset that centres it in that rectangle.
//!
//! It is sans-IO: it takes samples, motions and bytes, and returns values; it never prints
//! or opens files. It knows nothing of G-code text.
//!
//! ```
//! use biscara_interpolate::CartesianSample;
//! use biscara_kinematics::RobotModel;
//! use biscara_robot::{Checker, Scene};
//!
//! let mut checker = Checker::new(&RobotModel::default(), Scene::new());
//! for step in 0..=100 {
//!     let t = f64::from(step) * 0.01;
//!     checker.push(&CartesianSample { t, pose: [t * 10.0, 400.0, 50.0, 0.0], line: 1, gripper: false });
//! }
//! let report = checker.finish();
//! assert!(report.ok());
//! assert!((report.summary.path_length_mm - 10.0).abs() < 1e-9);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod body;
mod check;
mod collision;
mod cycle;
mod error;
mod fit;
mod geometry;
mod report;
mod scene;
mod workspace;

pub use biscara_joints::{Peak, Peaks};
pub use body::{Body, Cylinder, Link, LinkName, VirtualRobot};
pub use check::{Checker, MotorTorque, Problem, ProblemKind, Report, SingularityDistance, Summary};
pub use collision::{BodyPart, SceneCollision, SelfCollision, scene_collisions, self_collisions};
pub use cycle::{
    CYCLE_ACROSS_MM, CYCLE_LIFT_MM, CYCLE_Z_MM, CycleConfig, CycleError, CycleMotor, CycleReport,
    adept_cycle,
};
pub use error::VirtualRobotError;
pub use fit::{Bounds, Fit, Transform, fit, place_motion, shift_motion};
pub use report::ReportedProblem;
pub use scene::{Scene, SceneBox};
pub use workspace::{MAX_STEP_MM, MIN_STEP_MM, Rectangle, Workspace};
