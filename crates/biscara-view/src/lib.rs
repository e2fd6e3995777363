//! Pictures of the BiSCARA in motion (SPEC §8.3): a self-contained HTML viewer of a joint
//! trajectory (`biscara view`) and a MuJoCo model of the robot (`biscara mjcf`).
//!
//! Both are built from the robot description and forward kinematics alone; neither reads files
//! nor prints. [`write_mjcf`] writes the model, [`QposWriter`] the companion file that plays a
//! joint trajectory on it (the model's joints in MuJoCo's units, the elbows from our FK, and the
//! tool pose FK expects). [`Viewer`] gathers a trajectory (decimated so that an hour-long program
//! stays a few megabytes), the programmed path and a [`Scene`], and writes one HTML file with
//! its data and hand-written JavaScript inside: no network, no other files.
//!
//! ```
//! use biscara_kinematics::RobotModel;
//! use biscara_view::{MjcfOptions, Scene, write_mjcf};
//!
//! let mut xml = Vec::new();
//! write_mjcf(&mut xml, &RobotModel::default(), &Scene::default(), &MjcfOptions::default())?;
//! assert!(String::from_utf8(xml)?.contains("<site name=\"tool\""));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod error;
mod html;
mod mjcf;
mod trace;

pub use biscara_robot::{Scene, SceneBox};
pub use error::ViewError;
pub use html::{Viewer, ViewerOptions};
pub use mjcf::{MjcfOptions, QPOS_HEADER, QposWriter, write_mjcf};
pub use trace::ProgramTrace;
