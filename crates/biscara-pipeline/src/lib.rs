//! The pipeline every command that runs a program goes through, as a library: a program
//! source and a sampling configuration in; motions, Cartesian samples and joint samples out.
//!
//! - [`ProgramKind`]: G-code, inter-file or path CSV, chosen by the caller, by the name's
//!   extension or by the content ([`ProgramKind::detect`]).
//! - [`ProgramSource`]: where the program's text comes from (a file the caller opens, standard
//!   input, a string); the crate itself never opens a path.
//! - [`Pipeline`]: one robot ([`RobotModel`]) and one [`SamplingConfig`] (time step, profile,
//!   grip time, origin, fitting to the workspace); [`Pipeline::motions`], [`Pipeline::samples`] and
//!   [`Pipeline::joints`] are the stages, wired once, here; [`Pipeline::write_path_csv`] and
//!   [`Pipeline::write_joint_csv`] write the last two as the commands' CSV files;
//!   [`parse_time_step`] and its siblings read its settings as a user types them.
//! - [`Note`]: what the pipeline has to say besides its output (the chosen placement, slowed
//!   motions); the caller decides how to show them. Errors are [`PipelineError`]s, located as
//!   `FILE:LINE[:COL]: message`, with [`Hint`]s the caller words for its own settings.
//!
//! - [`generate()`]: the other pipeline, points → CL → G-code (`biscara gen`).
//! - [`DemoReport`]: what `biscara demo` wrote of the bundled job ([`EXAMPLE_JOB`]).
//!
//! It deliberately holds no whole program: motions and samples are iterators, and fitting
//! reads the program twice (once for its extent) rather than keeping it.
//!
//! ```
//! use biscara_kinematics::RobotModel;
//! use biscara_pipeline::{Pipeline, ProgramKind, SamplingConfig, TextSource};
//!
//! let model = RobotModel::default();
//! let pipeline = Pipeline::new(&model, SamplingConfig::default());
//! let program = TextSource::new("job.ngc", "G0 X0 Y400 Z50\nG1 X10 F600\nM2\n");
//! let mut rows = 0;
//! for row in pipeline.joints(&program, ProgramKind::Gcode, |_| {})? {
//!     let row = row?;
//!     assert!(row.joints.theta1.is_finite());
//!     rows += 1;
//! }
//! assert!(rows > 1000);
//! # Ok::<(), biscara_pipeline::PipelineError>(())
//! ```

mod check;
mod csv;
mod demo;
mod error;
mod generate;
mod kind;
mod motions;
mod pipeline;
mod placement;
mod settings;
mod source;
mod tool;
mod torques;
mod write;

pub use biscara_kinematics::RobotModel;

pub use csv::{held_payload, sample_torques, torque_columns};
pub use error::{Hint, Note, PipelineError};
pub use generate::{GenerateError, generate};
pub use kind::ProgramKind;
pub use pipeline::{
    DEFAULT_TIME_LIMIT, JointSamples, MAX_FIT_MOTIONS, Motions, Pipeline, Samples, SamplingConfig,
    SlowDownNotes,
};
pub use placement::{Placement, place};
pub use settings::{parse_blend, parse_grip_time, parse_time_limit, parse_time_step};
pub use source::{ProgramSource, TextSource};
pub use tool::{ToolJointSamples, ToolSamples, ToolState};

// `biscara demo`'s bundled job and its report.
pub use demo::{DemoReport, EXAMPLE_JOB};
