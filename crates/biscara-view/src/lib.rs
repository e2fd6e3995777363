//! Pictures of the BiSCARA in motion (docs/virtual-robot.md): a self-contained HTML viewer of a
//! joint trajectory (`biscara view`), a MuJoCo model of the robot (`biscara mjcf`), and SVG/PNG
//! plots (`biscara plot`, `workspace --svg/--png`).
//!
//! All are built from the robot description, forward kinematics and the virtual robot's bodies
//! and workspace; none reads files or prints. [`draw_top_view`], [`draw_joints`] and
//! [`draw_workspace`] return SVG or PNG bytes (plotters; DejaVu Sans embedded for PNG text).
//! [`write_mjcf`] writes the model, [`QposWriter`] the companion file that plays a joint trajectory
//! on it (the model's joints in MuJoCo's units, the elbows from our FK, and the tool pose FK
//! expects). [`Viewer`] gathers a trajectory (every sample up to 1 048 576, packed as binary), the
//! programmed path, the tool's work, `check`'s problems and a [`Scene`], and writes one HTML file
//! with its data, three.js (bundled by `scripts/bundle-three.sh`) and the page's JavaScript inside:
//! a WebGL scene, no network, no other files. [`read_stl`] reads the STL meshes `robot.json` may
//! name for the robot's parts (from a reader the caller opened); [`Viewer::add_mesh`] draws one in
//! place of its part's box or cylinder.
//!
//! ```
//! use biscara_dynamics::Dynamics;
//! use biscara_kinematics::RobotModel;
//! use biscara_view::{MjcfOptions, Scene, write_mjcf};
//!
//! let (model, mut xml) = (RobotModel::default(), Vec::new());
//! let dynamics = Dynamics::new(&model)?;
//! write_mjcf(&mut xml, &model, &dynamics, &Scene::default(), &MjcfOptions::default())?;
//! assert!(String::from_utf8(xml)?.contains("<site name=\"tool\""));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod decimate;
mod error;
mod html;
mod mjcf;
mod plot;
mod program;
mod stl;
mod trace;
mod work;

pub use biscara_robot::{Scene, SceneBox};
pub use error::ViewError;
pub use html::{Viewer, ViewerOptions};
pub use mjcf::{MjcfOptions, QPOS_HEADER, QposWriter, write_mjcf};
pub use plot::{
    ATLAS_MAX_PANELS, Atlas, AtlasCell, ImageFormat, JointCurves, TopView, draw_atlas, draw_joints,
    draw_top_view, draw_workspace, zoom_region,
};
pub use plot::{TorqueCurves, draw_torques};
pub use program::{TracedProgram, trace_program};
pub use stl::{BinaryFault, MAX_MESH_TRIANGLES, StlError, StlMesh, read_stl};
pub use trace::ProgramTrace;
pub use work::{MAX_WORK_POINTS, ProgramOverlay, ToolWork, WorkPoint};
