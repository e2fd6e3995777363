//! Why CL text cannot be read.

use biscara_text::{LineError, ReadError, compact};

/// A CL reading failure: the syntax, counts and values of one statement. Every variant names the
/// 1-based line of the CL file, and its message starts with `LINE: ` so that a caller only
/// prefixes the file name (`job.cl:12: …`).
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ClError {
    /// Occurs when a line cannot be read: the file, its text, its length.
    #[error(transparent)]
    Read(#[from] ReadError),
    /// Occurs when a statement's major word is not one of the dialect's.
    #[error(
        "{line}: unknown CL statement `{word}`: expected GOTO, RAPID, FEDRAT, CIRCLE, DELAY, PICK, \
         PLACE, PPRINT, PARTNO, UNITS, END, FINI or a post word such as SPINDL"
    )]
    UnknownStatement {
        /// The line.
        line: usize,
        /// The word, as written (shortened when long).
        word: String,
    },
    /// Occurs when a statement is malformed: a missing `/`, or arguments where none belong.
    #[error("{line}: {word}: {message}")]
    Syntax {
        /// The line.
        line: usize,
        /// The statement's major word.
        word: &'static str,
        /// What is wrong and what would be right.
        message: String,
    },
    /// Occurs when a statement has the wrong number of values (a GOTO with 5 values).
    #[error("{line}: {word} takes {expected}, found {found} value{plural}", plural = if *found == 1 { "" } else { "s" })]
    WrongCount {
        /// The line.
        line: usize,
        /// The statement's major word.
        word: &'static str,
        /// What it takes (`3 (x,y,z), 4 (x,y,z,c) or 6 (x,y,z,i,j,k) values`).
        expected: &'static str,
        /// How many it had.
        found: usize,
    },
    /// Occurs when a value is not a number.
    #[error("{line}: {word}: `{text}` is not a number")]
    NotANumber {
        /// The line.
        line: usize,
        /// The statement's major word.
        word: &'static str,
        /// The text (shortened when long).
        text: String,
    },
    /// Occurs when a value is NaN or infinite (`1e999` overflows to infinity).
    #[error("{line}: {word}: `{text}` is not a finite number")]
    NotFinite {
        /// The line.
        line: usize,
        /// The statement's major word.
        word: &'static str,
        /// The text.
        text: String,
    },
    /// Occurs when a value is finite but outside what makes sense: a length beyond ±1e6, a
    /// non-positive feed, a negative delay.
    #[error("{line}: {word}: {} is out of range: {reason}", compact(*value))]
    OutOfRange {
        /// The line.
        line: usize,
        /// The statement's major word.
        word: &'static str,
        /// The value.
        value: f64,
        /// What the range is.
        reason: &'static str,
    },
    /// Occurs when a minor word is not one the statement takes (`UNITS/FEET`, `FEDRAT/MMPR,…`).
    #[error("{line}: {word}: unexpected `{minor}`: expected {expected}")]
    UnknownMinor {
        /// The line.
        line: usize,
        /// The statement's major word.
        word: &'static str,
        /// The minor word as written.
        minor: String,
        /// What would be right.
        expected: &'static str,
    },
}

impl ClError {
    /// The 1-based line of the CL file the error is about.
    pub fn line(&self) -> usize {
        match *self {
            ClError::Read(ref error) => error.line(),
            ClError::UnknownStatement { line, .. }
            | ClError::Syntax { line, .. }
            | ClError::WrongCount { line, .. }
            | ClError::NotANumber { line, .. }
            | ClError::NotFinite { line, .. }
            | ClError::OutOfRange { line, .. }
            | ClError::UnknownMinor { line, .. } => line,
        }
    }

    pub(crate) fn from_line_error(line: usize, error: LineError) -> ClError {
        ClError::Read(ReadError::new("CL", line, error))
    }
}
