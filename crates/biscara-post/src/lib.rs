//! CL (cutter-location) files and the postprocessor that turns them into LinuxCNC G-code: the
//! paper's `gcodeGeneration`, file to file (SPEC §3, §4.1).
//!
//! [`ClReader`] reads APT-style CL data one [`Statement`] at a time from any `BufRead`: the
//! dialect `biscara clf` writes and the forms 3-axis CAM systems write (GOTO with 3, 4 or 6
//! values, FEDRAT in MMPM or IPM in either order, UNITS/INCHES, CIRCLE + GOTO arcs, `$`
//! continuations, post words such as SPINDL). [`write_statement`] writes a statement back as CL
//! text. [`Postprocessor`] turns statements into G-code as they come, writing to any `Write`;
//! [`post`] does both for a whole file.
//!
//! It deliberately knows nothing of the robot's kinematics: reachability is checked where the
//! points are made (`biscara-pnp`) or where the motion is run. It never collects a program:
//! memory stays flat however long the file is.
//!
//! ```
//! use biscara_post::{PostOptions, post};
//!
//! let cl = "PARTNO/DEMO\nUNITS/MM\nRAPID\nGOTO/0,400,100,0\nFEDRAT/MMPM,3000\nGOTO/0,400,50,0\nPICK\nFINI\n";
//! let mut gcode = Vec::new();
//! post(cl.as_bytes(), &mut gcode, PostOptions::default())?;
//! assert_eq!(
//!     String::from_utf8(gcode)?,
//!     "%\n(DEMO)\nG21 G17 G90 G94\nG0 X0.000 Y400.000 Z100.000 C0.000\nG1 Z50.000 F3000.0\nM3 (pick)\nM2\n%\n"
//! );
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod cl;
mod error;
mod fmt;
pub mod lines;
mod post;

pub use cl::{
    Circle, ClReader, Feed, FeedUnit, Goto, MAX_VALUE, POST_WORDS, Record, Statement, Units,
    parse_statement, write_statement,
};
pub use error::{PostError, compact};
pub use post::{IgnoredWord, PostOptions, PostSummary, Postprocessor, post};
