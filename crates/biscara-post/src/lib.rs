//! The postprocessor that turns CL (cutter-location) files into LinuxCNC G-code: the paper's
//! `gcodeGeneration`, file to file (docs/programming.md).
//!
//! The CL statements, their reader and their writer are `biscara-cl`'s, the contract this crate
//! shares with the stage that makes programs (`biscara-pnp`). [`Postprocessor`] turns statements
//! into G-code as they come, writing to any `Write`; [`post()`] reads a whole CL file with
//! `biscara_cl::ClReader` and posts it.
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

mod error;
mod post;

pub use error::PostError;
pub use post::{IgnoredWord, PostOptions, PostSummary, Postprocessor, post};
