//! Pick-and-place jobs: the points file and the CL program it makes (docs/programming.md) — the
//! paper's `trajectoryWorld`.
//!
//! [`PointsReader`] reads a points file one statement at a time from any `BufRead`;
//! [`ClProgram`] turns it into CL [`Statement`](biscara_cl::Statement)s, checking the order
//! rules and that the robot can take every pose and every approach pose above it (inverse
//! kinematics with limits, assembly mode and singularity margin). [`write_cl`] writes the
//! program as CL text (`biscara clf`); feeding the statements to
//! `biscara_post::Postprocessor` gives G-code in the same pass (`biscara gen`).
//!
//! It deliberately knows nothing of G-code, and it checks poses only, not the motions between
//! them (that is the trajectory stages' job). It keeps at most one pick/place pair in memory.
//!
//! ```
//! use biscara_kinematics::Kinematics;
//! use biscara_pnp::write_cl;
//!
//! let points = "approach 40\npick 150 320 10 30\nplace -150 300 20 0\n";
//! let mut cl = Vec::new();
//! write_cl(points.as_bytes(), &Kinematics::default(), &mut cl)?;
//! let cl = String::from_utf8(cl)?;
//! assert!(cl.starts_with("PARTNO/PICK AND PLACE\nUNITS/MM\nRAPID\n"));
//! assert!(cl.contains("GOTO/150.0000,320.0000,50.0000,30.0000\n"));
//! assert!(cl.ends_with("END\nFINI\n"));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod error;
mod points;
mod program;

pub use error::{PointsError, PointsErrorKind, WriteClError};
pub use points::{Point, PointsReader, PointsRecord, PointsStatement};
pub use program::{ClProgram, JobSettings, PART_NAME, write_cl};
