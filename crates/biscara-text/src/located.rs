//! The one shape of a reader's error: where in the file, and what is wrong.

use std::error::Error;
use std::fmt;

/// An error at a place of a text file: the 1-based line, the 1-based column and the byte span
/// within the line where the reader knows them, and what is wrong ([`kind`](Located::kind):
/// one enum per reader, its message without the place).
///
/// `Display` is `LINE: message` or `LINE:COL: message`: the caller prefixes the file's name
/// once (`job.cl:12: …`), as only it knows the name. Every reader of user input in biscara
/// reports this way; the G-code interpreter's errors add the line's text for a caret.
///
/// ```
/// use biscara_text::Located;
///
/// #[derive(Debug, thiserror::Error)]
/// enum Kind {
///     #[error("`{0}` is not a number")]
///     NotANumber(String),
/// }
/// let error = Located::at(7, 12, Kind::NotANumber("1,5".into()));
/// assert_eq!(error.to_string(), "7:12: `1,5` is not a number");
/// assert_eq!(Located::at_line(3, Kind::NotANumber("x".into())).to_string(), "3: `x` is not a number");
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Located<K> {
    /// 1-based line of the file.
    pub line: usize,
    /// 1-based column (in bytes) within the line, where known (a line holds at most
    /// [`MAX_LINE_BYTES`](crate::MAX_LINE_BYTES) bytes, so 32 bits hold any column).
    pub column: Option<u32>,
    /// Byte range within the line the error is about (`start..end`, 0-based), where known.
    pub span: Option<(u32, u32)>,
    /// What is wrong.
    pub kind: K,
}

impl<K> Located<K> {
    /// `kind` on `line` (1-based), with no column.
    pub fn at_line(line: usize, kind: K) -> Located<K> {
        Located { line, column: None, span: None, kind }
    }

    /// `kind` at `line` and `column` (both 1-based).
    pub fn at(line: usize, column: usize, kind: K) -> Located<K> {
        Located { line, column: Some(saturate(column)), span: None, kind }
    }

    /// The same place with another kind: `map(ClErrorKind::Read)` turns a line reader's error
    /// into a format's.
    pub fn map<L>(self, kind: impl FnOnce(K) -> L) -> Located<L> {
        Located { line: self.line, column: self.column, span: self.span, kind: kind(self.kind) }
    }

    /// The same error with the byte span `start..end` of its line.
    #[must_use]
    pub fn with_span(self, start: usize, end: usize) -> Located<K> {
        Located { span: Some((saturate(start), saturate(end))), ..self }
    }
}

/// A byte offset within a line as 32 bits (saturated: no line is that long).
fn saturate(offset: usize) -> u32 {
    u32::try_from(offset).unwrap_or(u32::MAX)
}

impl<K: fmt::Display> fmt::Display for Located<K> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.column {
            Some(column) => write!(f, "{}:{column}: {}", self.line, self.kind),
            None => write!(f, "{}: {}", self.line, self.kind),
        }
    }
}

impl<K: Error> Error for Located<K> {
    fn source(&self) -> Option<&(dyn Error + 'static)> {
        self.kind.source()
    }
}

#[cfg(test)]
mod tests {
    use std::error::Error as _;
    use std::io;

    use super::*;
    use crate::LineError;

    #[test]
    fn map_keeps_the_place_and_source_is_the_kinds() {
        let read = Located::at(4, 9, LineError::Io(io::Error::other("gone"))).with_span(8, 12);
        #[derive(Debug, thiserror::Error)]
        enum Kind {
            #[error(transparent)]
            Read(LineError),
        }
        let error = read.map(Kind::Read);
        assert_eq!((error.line, error.column, error.span), (4, Some(9), Some((8, 12))));
        assert_eq!(error.to_string(), "4:9: cannot read the file: gone");
        assert_eq!(error.source().map(ToString::to_string).as_deref(), Some("gone"));
        assert_eq!(Located::at(1, usize::MAX, "x").column, Some(u32::MAX));
    }
}
