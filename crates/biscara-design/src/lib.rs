//! Robot design for the BiSCARA: sweep the proximal and distal link lengths and the distance
//! between the base joints, and measure each design as the lab building the robot would.
//!
//! A design keeps everything of a robot file but l1, l2 and the base joints (placed
//! symmetrically at ±base/2). [`Evaluator::evaluate`] computes its workspace exactly as
//! `biscara workspace` does (a grid of points reachable in the working and assembly mode,
//! within the joint limits, outside the singularity margin), its area, the largest axis-aligned
//! rectangle inside it, and over that rectangle's grid points the local conditioning index
//! LCI = 1/cond(J) of the planar Jacobian J = ∂(x, y)/∂(θ1, θ2): its mean (the global
//! conditioning index, GCI, of Gosselin and Angeles) and its worst value.
//!
//! [`Sweep`] evaluates a [`DesignGrid`] on worker threads (rayon) and hands the evaluations
//! back in order, a block at a time, so memory does not grow with the sweep; a [`Shard`] takes
//! a deterministic part of the grid and [`merge`] joins the shards' CSVs. [`Best`] and
//! [`ParetoFront`] choose designs as the rows go by; a [`ProgramTimer`] adds the time the design
//! takes to run given programs (the trajectories `biscara joints` computes).
//!
//! Sans-IO: rows are written to and read from `impl Write`/`impl BufRead`; nothing here opens a
//! path.
//!
//! ```
//! use biscara_design::{Design, Evaluator};
//! use biscara_kinematics::Robot;
//!
//! let evaluator = Evaluator::new(Robot::default(), 10.0, None)?;
//! let design = Design { index: 0, l1: 210.0, l2: 270.0, base: 200.0 };
//! let evaluation = evaluator.evaluate(design);
//! assert!(evaluation.rectangle_area() > 0.0 && evaluation.gci > 0.0);
//! # Ok::<(), biscara_design::DesignError>(())
//! ```

mod csv;
mod error;
mod evaluate;
mod grid;
mod request;
mod select;
mod sweep;
mod time;

pub use csv::{COLUMNS, Columns, RowReader, header, merge, parse_row, read_header, write_row};
pub use error::{CsvFault, DesignError, MergeFault};
pub use evaluate::{DesignStatus, Evaluation, Evaluator, conditioning, covers, lci};
pub use grid::{Design, DesignGrid, MAX_DESIGNS, ParamRange, Shard, Task};
pub use request::SweepRequest;
pub use select::{AtlasValue, Best, Collector, Objective, ParetoFront, SweepOutcome, eligible};
pub use sweep::{Sweep, SweepOptions};
pub use time::ProgramTimer;
