//! CL (cutter-location) statements, the neutral contract between the stage that makes a program
//! (`biscara-pnp`, `biscara clf`) and the postprocessor that turns it into G-code
//! (`biscara-post`): the typed [`Statement`], the [`ClReader`] and [`write_statement`]
//! (docs/programming.md).
//!
//! [`ClReader`] reads APT-style CL data one [`Record`] at a time from any `BufRead`: the dialect
//! `biscara clf` writes and the forms 3-axis CAM systems write (GOTO with 3, 4 or 6 values,
//! FEDRAT in MMPM or IPM in either order, UNITS/INCHES, CIRCLE + GOTO arcs, `$` continuations,
//! `$$` comments, post words such as SPINDL). It checks syntax, counts and finite values only:
//! what a statement means (units, tool axis, arcs, END/FINI order) is the postprocessor's. It
//! knows nothing of G-code or of the robot, and it never collects a program.
//!
//! ```
//! use biscara_cl::{ClReader, Goto, Statement, write_statement};
//!
//! let mut records = ClReader::new("$$ a job\nGOTO/1,2,$\n 3\n".as_bytes());
//! let record = records.next().unwrap()?;
//! assert_eq!(record.line, 2);
//! let goto = Goto { x: 1.0, y: 2.0, z: 3.0, c: None, axis: None };
//! assert_eq!(record.statement, Statement::Goto(goto));
//! let mut text = Vec::new();
//! write_statement(&mut text, &record.statement)?;
//! assert_eq!(text, b"GOTO/1.0000,2.0000,3.0000\n");
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod cl;
mod error;

pub use cl::{
    Circle, ClReader, Feed, FeedUnit, Goto, MAX_VALUE, POST_WORDS, Record, Statement, Units,
    parse_statement, write_statement,
};
pub use error::{ClError, ClErrorKind};
