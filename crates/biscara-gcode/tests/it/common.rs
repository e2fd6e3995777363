//! What the test modules share: the home pose they start from, a configuration per dialect, a
//! program run as a file, and what is read from its motions.

use std::io::Cursor;
use std::path::PathBuf;

use biscara_gcode::{Config, Dialect, GcodeError, interpret_seekable};
use biscara_motion::{Motion, MotionKind};

/// The pose the programs start from (mm, base frame).
pub const HOME: [f64; 4] = [0.0, 400.0, 100.0, 0.0];

/// The configuration from [`HOME`] in `dialect`.
pub fn config(dialect: Dialect) -> Config {
    Config { home: HOME, dialect, ..Config::default() }
}

/// What a program gave.
#[derive(Debug)]
pub struct Run {
    /// The motions before the first error.
    pub motions: Vec<Motion>,
    /// The first error.
    pub error: Option<GcodeError>,
    /// The dialect it was read as (`auto`'s choice).
    pub dialect: Dialect,
}

/// `program` read with `config` from an input it can jump in (a file), named `file` when given
/// (its extension tells `auto`; its folder holds the subroutines), up to its first error.
pub fn run_file(program: &str, config: &Config, file: Option<&str>) -> Run {
    let mut interpreter = interpret_seekable(Cursor::new(program.to_owned()), config);
    if let Some(file) = file {
        interpreter = interpreter.with_subroutines(Some(PathBuf::from(file)), Vec::new());
    }
    let mut motions = Vec::new();
    let mut error = None;
    for result in interpreter.by_ref() {
        match result {
            Ok(motion) => motions.push(motion),
            Err(err) => {
                error = Some(err);
                break;
            }
        }
    }
    Run { motions, error, dialect: interpreter.dialect() }
}

/// The end points of the motions that move.
pub fn ends(motions: &[Motion]) -> Vec<[f64; 4]> {
    motions.iter().filter_map(|motion| motion.kind.end()).collect()
}

/// The code events (`M3`, `T1`, …) in order.
pub fn codes(motions: &[Motion]) -> Vec<String> {
    motions
        .iter()
        .filter_map(|motion| match motion.kind {
            MotionKind::Code { code } => Some(code.to_string()),
            _ => None,
        })
        .collect()
}
