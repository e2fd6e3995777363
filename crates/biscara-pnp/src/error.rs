//! Why a points file cannot be turned into a program.

use std::io;

use biscara_kinematics::KinematicsError;
use biscara_text::{LineError, Located, compact};

/// A points-file failure at its line: its message starts with `LINE: ` so that a caller only
/// prefixes the file name (`points.txt:7: …`).
pub type PointsError = Located<PointsErrorKind>;

/// What is wrong in a points file: its text, a line, or the job's order. Lengths are
/// millimetres, angles degrees.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PointsErrorKind {
    /// Occurs when a line cannot be read: the file, its text, its length.
    #[error(transparent)]
    Read(LineError),
    /// Occurs when a line starts with a word that is not a keyword.
    #[error("unknown keyword `{word}`: expected home, approach, feed, dwell, pick or place")]
    UnknownKeyword {
        /// The word as written (shortened when long).
        word: String,
    },
    /// Occurs when a keyword has the wrong number of values (a pose with 3 numbers).
    #[error("`{keyword}` takes {expected}, found {found} value{plural}", plural = if *found == 1 { "" } else { "s" })]
    WrongCount {
        /// The keyword.
        keyword: &'static str,
        /// What it takes.
        expected: &'static str,
        /// How many values it had.
        found: usize,
    },
    /// Occurs when a value is not a number.
    #[error("`{text}` is not a number")]
    NotANumber {
        /// The text (shortened when long).
        text: String,
    },
    /// Occurs when a value is NaN or infinite (`1e999` overflows to infinity).
    #[error("`{text}` is not a finite number")]
    NotFinite {
        /// The text (shortened when long).
        text: String,
    },
    /// Occurs when a value is out of its range: a non-positive feed, a negative dwell, a
    /// coordinate beyond ±1e6.
    #[error("`{keyword}` {} is out of range: {reason}", compact(*value))]
    OutOfRange {
        /// The keyword.
        keyword: &'static str,
        /// The value.
        value: f64,
        /// The range.
        reason: &'static str,
    },
    /// Occurs when a setting is given twice.
    #[error("`{keyword}` is given twice (first on line {first_line})")]
    Duplicate {
        /// The keyword.
        keyword: &'static str,
        /// The line of the first one.
        first_line: usize,
    },
    /// Occurs when a setting comes after the first pick: settings apply to the whole job.
    #[error("`{keyword}` must come before the first pick (line {pick_line})")]
    SettingAfterPick {
        /// The keyword.
        keyword: &'static str,
        /// The line of the first pick.
        pick_line: usize,
    },
    /// Occurs when a place comes with no pick before it.
    #[error("place before pick: each place must follow a pick")]
    PlaceBeforePick,
    /// Occurs when two picks follow each other.
    #[error(
        "pick after pick: the pick on line {pick_line} has no place yet (pick and place \
         must alternate)"
    )]
    PickAfterPick {
        /// The line of the first pick.
        pick_line: usize,
    },
    /// Occurs when a pose, or the approach pose above it, cannot be taken by the robot:
    /// unreachable, beyond a type-2 singularity, outside the joint limits or near a singularity.
    #[error(
        "{what} (x, y, z, c) = ({}, {}, {}, {}) is unreachable: {reason}",
        compact(pose[0]), compact(pose[1]), compact(pose[2]), compact(pose[3])
    )]
    Unreachable {
        /// Which pose: `pick`, `approach pose above the place`, `home`, …
        what: &'static str,
        /// The pose, mm and degrees.
        pose: [f64; 4],
        /// Why, from the kinematics.
        reason: KinematicsError,
    },
    /// Occurs when the file has no pick/place pair (an empty file, only settings).
    #[error("no pick/place pair: a job needs at least one `pick` line followed by a `place` line")]
    NoPairs,
    /// Occurs when the file ends after a pick (an odd count of pick and place lines).
    #[error("the pick on this line has no place: a job must end with a place")]
    UnpairedPick,
}

/// Why [`crate::write_cl`] failed: the points file, or writing the CL text.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum WriteClError {
    /// Occurs when the points file is wrong.
    #[error(transparent)]
    Points(#[from] PointsError),
    /// Occurs when the CL text cannot be written.
    #[error("cannot write the CL file")]
    Write(#[source] io::Error),
}

impl WriteClError {
    /// The 1-based line of the points file the error is about; `None` for a write error.
    pub fn line(&self) -> Option<usize> {
        match self {
            WriteClError::Points(error) => Some(error.line),
            WriteClError::Write(_) => None,
        }
    }
}
