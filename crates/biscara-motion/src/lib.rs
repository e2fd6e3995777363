//! Motions: what a G-code program asks the robot to do, one entry per move or event, in program
//! order — and their file form, the inter-file (JSON Lines, docs/motion.md).
//!
//! The G-code interpreter produces [`Motion`]s, the interpolator consumes them; this crate is the
//! contract between the two and knows neither G-code nor kinematics. Positions are absolute, in
//! the robot's base frame, millimetres and degrees, as `[x, y, z, c]`. [`Segment`] is the
//! geometry of a move (line, arc, helix, a corner's fillet) as a function of a path parameter,
//! shared by the corner blender and the interpolator.
//!
//! ```
//! use biscara_motion::{Motion, MotionKind, read_jsonl, write_jsonl};
//!
//! let motion = Motion::new(3, MotionKind::Rapid { end: [0.0, 400.0, 100.0, 0.0] });
//! let mut text = Vec::new();
//! write_jsonl(&mut text, &motion)?;
//! assert_eq!(text, b"{\"line\":3,\"kind\":\"rapid\",\"end\":[0.0,400.0,100.0,0.0]}\n");
//! let back: Vec<Motion> = read_jsonl(&text[..]).collect::<Result<_, _>>()?;
//! assert_eq!(back, [motion]);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod jsonl;
mod motion;
mod segment;
mod tool;

pub use jsonl::{
    InterFileError, InterFileErrorKind, JsonlReader, read_jsonl, write_jsonl, write_motions,
};
pub use motion::{CodeName, Feed, Motion, MotionKind, Plane};
pub use segment::{Circle, Segment};
pub use tool::{Tool, UnknownTool};

/// A position at a stage boundary: `[x, y, z, c]` in the robot's base frame, millimetres for
/// x, y, z and **degrees** for c (the G-code C word), as in every file the stages exchange.
///
/// The name for what motions end at, what Cartesian samples are and what the home pose and the
/// G54 origin are given as; inside the kinematics the same place is a `Pose` in radians.
pub type Position = [f64; 4];
