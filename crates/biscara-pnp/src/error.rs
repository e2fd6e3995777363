//! Why a points file cannot be turned into a program.

use std::io;

use biscara_kinematics::KinematicsError;
use biscara_text::{LineError, ReadError, compact};

/// A points-file failure. Every variant but [`PointsError::Write`] names the 1-based line it is
/// about, and its message starts with `LINE: ` so that a caller only prefixes the file name
/// (`points.txt:7: …`). Lengths are millimetres, angles degrees.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PointsError {
    /// Occurs when a line cannot be read: the file, its text, its length.
    #[error(transparent)]
    Read(#[from] ReadError),
    /// Occurs when a line starts with a word that is not a keyword.
    #[error(
        "{line}: unknown keyword `{word}`: expected home, approach, feed, dwell, pick or place"
    )]
    UnknownKeyword {
        /// The line.
        line: usize,
        /// The word as written (shortened when long).
        word: String,
    },
    /// Occurs when a keyword has the wrong number of values (a pose with 3 numbers).
    #[error("{line}: `{keyword}` takes {expected}, found {found} value{plural}", plural = if *found == 1 { "" } else { "s" })]
    WrongCount {
        /// The line.
        line: usize,
        /// The keyword.
        keyword: &'static str,
        /// What it takes.
        expected: &'static str,
        /// How many values it had.
        found: usize,
    },
    /// Occurs when a value is not a number.
    #[error("{line}: `{text}` is not a number")]
    NotANumber {
        /// The line.
        line: usize,
        /// The text (shortened when long).
        text: String,
    },
    /// Occurs when a value is NaN or infinite (`1e999` overflows to infinity).
    #[error("{line}: `{text}` is not a finite number")]
    NotFinite {
        /// The line.
        line: usize,
        /// The text (shortened when long).
        text: String,
    },
    /// Occurs when a value is out of its range: a non-positive feed, a negative dwell, a
    /// coordinate beyond ±1e6.
    #[error("{line}: `{keyword}` {} is out of range: {reason}", compact(*value))]
    OutOfRange {
        /// The line.
        line: usize,
        /// The keyword.
        keyword: &'static str,
        /// The value.
        value: f64,
        /// The range.
        reason: &'static str,
    },
    /// Occurs when a setting is given twice.
    #[error("{line}: `{keyword}` is given twice (first on line {first_line})")]
    Duplicate {
        /// The line of the second one.
        line: usize,
        /// The keyword.
        keyword: &'static str,
        /// The line of the first one.
        first_line: usize,
    },
    /// Occurs when a setting comes after the first pick: settings apply to the whole job.
    #[error("{line}: `{keyword}` must come before the first pick (line {pick_line})")]
    SettingAfterPick {
        /// The line of the setting.
        line: usize,
        /// The keyword.
        keyword: &'static str,
        /// The line of the first pick.
        pick_line: usize,
    },
    /// Occurs when a place comes with no pick before it.
    #[error("{line}: place before pick: each place must follow a pick")]
    PlaceBeforePick {
        /// The line of the place.
        line: usize,
    },
    /// Occurs when two picks follow each other.
    #[error(
        "{line}: pick after pick: the pick on line {pick_line} has no place yet (pick and place \
         must alternate)"
    )]
    PickAfterPick {
        /// The line of the second pick.
        line: usize,
        /// The line of the first pick.
        pick_line: usize,
    },
    /// Occurs when a pose, or the approach pose above it, cannot be taken by the robot:
    /// unreachable, beyond a type-2 singularity, outside the joint limits or near a singularity.
    #[error(
        "{line}: {what} (x, y, z, c) = ({}, {}, {}, {}) is unreachable: {reason}",
        compact(pose[0]), compact(pose[1]), compact(pose[2]), compact(pose[3])
    )]
    Unreachable {
        /// The line.
        line: usize,
        /// Which pose: `pick`, `approach pose above the place`, `home`, …
        what: &'static str,
        /// The pose, mm and degrees.
        pose: [f64; 4],
        /// Why, from the kinematics.
        reason: KinematicsError,
    },
    /// Occurs when the file has no pick/place pair (an empty file, only settings).
    #[error(
        "{line}: no pick/place pair: a job needs at least one `pick` line followed by a `place` line"
    )]
    NoPairs {
        /// The last line of the file (1 for an empty file).
        line: usize,
    },
    /// Occurs when the file ends after a pick (an odd count of pick and place lines).
    #[error("{line}: the pick on this line has no place: a job must end with a place")]
    UnpairedPick {
        /// The line of the pick.
        line: usize,
    },
    /// Occurs when the CL text cannot be written ([`crate::write_cl`]).
    #[error("cannot write the CL file")]
    Write(#[source] io::Error),
}

impl PointsError {
    /// The 1-based line of the points file the error is about; `None` for a write error.
    pub fn line(&self) -> Option<usize> {
        Some(match *self {
            PointsError::Read(ref error) => error.line(),
            PointsError::UnknownKeyword { line, .. }
            | PointsError::WrongCount { line, .. }
            | PointsError::NotANumber { line, .. }
            | PointsError::NotFinite { line, .. }
            | PointsError::OutOfRange { line, .. }
            | PointsError::Duplicate { line, .. }
            | PointsError::SettingAfterPick { line, .. }
            | PointsError::PlaceBeforePick { line }
            | PointsError::PickAfterPick { line, .. }
            | PointsError::Unreachable { line, .. }
            | PointsError::NoPairs { line }
            | PointsError::UnpairedPick { line } => line,
            PointsError::Write(_) => return None,
        })
    }

    pub(crate) fn from_line_error(line: usize, error: LineError) -> PointsError {
        PointsError::Read(ReadError::new("points", line, error))
    }
}
