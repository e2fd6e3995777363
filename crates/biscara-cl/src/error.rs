//! Why CL text cannot be read.

use biscara_text::{LineError, Located, compact};

/// A CL reading failure at its line of the CL file: its message starts with `LINE: ` so that a
/// caller only prefixes the file name (`job.cl:12: …`).
pub type ClError = Located<ClErrorKind>;

/// What is wrong in a CL file: the file's text, or the syntax, counts and values of one
/// statement.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ClErrorKind {
    /// Occurs when a line cannot be read: the file, its text, its length.
    #[error(transparent)]
    Read(LineError),
    /// Occurs when a statement's major word is not one of the dialect's.
    #[error(
        "unknown CL statement `{word}`: expected GOTO, RAPID, FEDRAT, CIRCLE, DELAY, PICK, \
         PLACE, PPRINT, PARTNO, UNITS, END, FINI or a post word such as SPINDL"
    )]
    UnknownStatement {
        /// The word, as written (shortened when long).
        word: String,
    },
    /// Occurs when a statement is malformed: a missing `/`, or arguments where none belong.
    #[error("{word}: {message}")]
    Syntax {
        /// The statement's major word.
        word: &'static str,
        /// What is wrong and what would be right.
        message: String,
    },
    /// Occurs when a statement has the wrong number of values (a GOTO with 5 values).
    #[error("{word} takes {expected}, found {found} value{plural}", plural = if *found == 1 { "" } else { "s" })]
    WrongCount {
        /// The statement's major word.
        word: &'static str,
        /// What it takes (`3 (x,y,z), 4 (x,y,z,c) or 6 (x,y,z,i,j,k) values`).
        expected: &'static str,
        /// How many it had.
        found: usize,
    },
    /// Occurs when a value is not a number.
    #[error("{word}: `{text}` is not a number")]
    NotANumber {
        /// The statement's major word.
        word: &'static str,
        /// The text (shortened when long).
        text: String,
    },
    /// Occurs when a value is NaN or infinite (`1e999` overflows to infinity).
    #[error("{word}: `{text}` is not a finite number")]
    NotFinite {
        /// The statement's major word.
        word: &'static str,
        /// The text.
        text: String,
    },
    /// Occurs when a value is finite but outside what makes sense: a length beyond ±1e6, a
    /// non-positive feed, a negative delay.
    #[error("{word}: {} is out of range: {reason}", compact(*value))]
    OutOfRange {
        /// The statement's major word.
        word: &'static str,
        /// The value.
        value: f64,
        /// What the range is.
        reason: &'static str,
    },
    /// Occurs when a minor word is not one the statement takes (`UNITS/FEET`, `FEDRAT/MMPR,…`).
    #[error("{word}: unexpected `{minor}`: expected {expected}")]
    UnknownMinor {
        /// The statement's major word.
        word: &'static str,
        /// The minor word as written.
        minor: String,
        /// What would be right.
        expected: &'static str,
    },
}
