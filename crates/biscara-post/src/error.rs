//! Why a CL file cannot be read or posted.

use std::io;

use biscara_cl::ClError;

/// A CL reading or postprocessing failure. Every variant but [`PostError::Write`] names the
/// 1-based line of the CL file, and its message starts with `LINE: ` so that a caller only
/// prefixes the file name (`job.cl:12: …`). Lengths in messages are as written in the file.
/// Reading errors are the CL reader's ([`PostError::Cl`]); the others are the postprocessor's.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PostError {
    /// Occurs when the CL text cannot be read: a syntax, count or value error, or a read,
    /// text or line-length error (the message is the reader's).
    #[error(transparent)]
    Cl(#[from] ClError),
    /// Occurs when the file holds no statement at all.
    #[error("{line}: the CL file is empty: expected statements ending with FINI")]
    Empty {
        /// The last line of the file (1 for an empty file).
        line: usize,
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
            PostError::Cl(ref err) => Some(err.line),
            PostError::Empty { line }
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
}
