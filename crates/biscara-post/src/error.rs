//! Why a CL file cannot be read or posted.

use std::io;

use crate::lines::{LineError, MAX_LINE_BYTES};

/// A CL reading or postprocessing failure. Every variant but [`PostError::Write`] names the
/// 1-based line of the CL file, and its message starts with `LINE: ` so that a caller only
/// prefixes the file name (`job.cl:12: …`). Lengths in messages are as written in the file.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PostError {
    /// Occurs when the CL file cannot be read.
    #[error("{line}: cannot read the CL file: {source}")]
    Read {
        /// The line being read.
        line: usize,
        /// The underlying error.
        source: io::Error,
    },
    /// Occurs when a line is not UTF-8 text (or holds NUL bytes): a binary file.
    #[error("{line}: not a text file (invalid UTF-8 or NUL bytes)")]
    NotText {
        /// The line.
        line: usize,
    },
    /// Occurs when a line, or a statement continued with `$`, is longer than 64 KiB.
    #[error("{line}: the line is longer than {max} bytes", max = MAX_LINE_BYTES)]
    LineTooLong {
        /// The line.
        line: usize,
    },
    /// Occurs when the file holds no statement at all.
    #[error("{line}: the CL file is empty: expected statements ending with FINI")]
    Empty {
        /// The last line of the file (1 for an empty file).
        line: usize,
    },
    /// Occurs when a statement's major word is not one this postprocessor knows.
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
    /// Occurs when a 6-value GOTO's tool axis is not (0, 0, 1).
    #[error(
        "{line}: GOTO: tool axis (i, j, k) = ({}, {}, {}) is not (0, 0, 1): this robot's tool is \
         always vertical (5-axis CL data cannot be posted)",
        axis[0], axis[1], axis[2]
    )]
    ToolAxis {
        /// The line.
        line: usize,
        /// The axis as written.
        axis: [f64; 3],
    },
    /// Occurs when a CIRCLE's axis is not (0, 0, ±1): only arcs in the XY plane are posted.
    #[error(
        "{line}: CIRCLE: axis (i, j, k) = ({}, {}, {}) is not (0, 0, 1) or (0, 0, -1): only arcs \
         in the XY plane can be posted",
        axis[0], axis[1], axis[2]
    )]
    ArcPlane {
        /// The line.
        line: usize,
        /// The axis as written.
        axis: [f64; 3],
    },
    /// Occurs when a CIRCLE is not followed by the GOTO that ends the arc.
    #[error("{line}: CIRCLE is not followed by a GOTO (found {found}): an arc needs its end point")]
    CircleWithoutGoto {
        /// The line of the CIRCLE.
        line: usize,
        /// What came instead: a statement and its line, or the end of the file.
        found: String,
    },
    /// Occurs when a CIRCLE comes before any GOTO: the arc has no start point.
    #[error("{line}: CIRCLE before any GOTO: the arc has no start point")]
    NoStartPoint {
        /// The line of the CIRCLE.
        line: usize,
    },
    /// Occurs when an arc's start and end points are not on one circle about its centre.
    #[error(
        "{line}: the arc's end point is {end_mm:.4} mm from the centre but its start point is \
         {start_mm:.4} mm (CIRCLE radius {radius_mm:.4} mm): they must agree within 0.01 mm"
    )]
    ArcRadius {
        /// The line of the GOTO ending the arc.
        line: usize,
        /// Distance from the centre to the start point, millimetres.
        start_mm: f64,
        /// Distance from the centre to the end point, millimetres.
        end_mm: f64,
        /// The CIRCLE's radius, millimetres.
        radius_mm: f64,
    },
    /// Occurs when RAPID is followed by a CIRCLE: an arc cannot be a rapid move.
    #[error("{line}: RAPID before CIRCLE: an arc cannot be a rapid move")]
    RapidArc {
        /// The line of the CIRCLE.
        line: usize,
    },
    /// Occurs when a feed move comes before any FEDRAT.
    #[error("{line}: GOTO is a feed move but no FEDRAT has been given (or put RAPID before it)")]
    NoFeed {
        /// The line.
        line: usize,
    },
    /// Occurs when a statement other than FINI, PPRINT or a post word follows END, or any
    /// statement follows FINI.
    #[error("{line}: {word} after {after}: the program has ended")]
    AfterEnd {
        /// The line.
        line: usize,
        /// The statement.
        word: String,
        /// `END` or `FINI`.
        after: &'static str,
    },
    /// Occurs when the file ends without FINI (a truncated file).
    #[error("{line}: the CL file ends without FINI (is it truncated?)")]
    MissingFini {
        /// The last line.
        line: usize,
    },
    /// Occurs when the G-code cannot be written.
    #[error("cannot write the G-code")]
    Write(#[source] io::Error),
}

impl PostError {
    /// The 1-based line of the CL file the error is about; `None` for a write error.
    pub fn line(&self) -> Option<usize> {
        match *self {
            PostError::Read { line, .. }
            | PostError::NotText { line }
            | PostError::LineTooLong { line }
            | PostError::Empty { line }
            | PostError::UnknownStatement { line, .. }
            | PostError::Syntax { line, .. }
            | PostError::WrongCount { line, .. }
            | PostError::NotANumber { line, .. }
            | PostError::NotFinite { line, .. }
            | PostError::OutOfRange { line, .. }
            | PostError::UnknownMinor { line, .. }
            | PostError::ToolAxis { line, .. }
            | PostError::ArcPlane { line, .. }
            | PostError::CircleWithoutGoto { line, .. }
            | PostError::NoStartPoint { line }
            | PostError::ArcRadius { line, .. }
            | PostError::RapidArc { line }
            | PostError::NoFeed { line }
            | PostError::AfterEnd { line, .. }
            | PostError::MissingFini { line } => Some(line),
            PostError::Write(_) => None,
        }
    }

    pub(crate) fn from_line_error(line: usize, error: LineError) -> PostError {
        match error {
            LineError::Io(source) => PostError::Read { line, source },
            LineError::NotText => PostError::NotText { line },
            LineError::TooLong => PostError::LineTooLong { line },
        }
    }
}

/// `text` cut to at most 40 characters, with `…` when cut, for quoting input in messages.
pub(crate) fn shorten(text: &str) -> String {
    let mut chars = text.chars();
    let head: String = chars.by_ref().take(40).collect();
    if chars.next().is_some() { format!("{head}…") } else { head }
}

/// `value` as written by a person: plain for ordinary magnitudes, `1e300` for huge or tiny ones.
pub fn compact(value: f64) -> String {
    let magnitude = value.abs();
    if magnitude != 0.0 && !(1e-4..1e7).contains(&magnitude) {
        format!("{value:e}")
    } else {
        format!("{value}")
    }
}
