//! Lines and their significant characters.
//!
//! LinuxCNC reads a block by first dropping spaces and tabs everywhere and lowering the case of
//! everything outside comments (`close_and_downcase`); then it parses words from what is left.
//! [`compact`] does the same into reused buffers, keeping for every byte left its column in the
//! original line (for error messages). A `( … )` comment becomes one `(` byte, so that it still
//! separates what stands on either side of it, as it does in LinuxCNC.

use std::io::{self, BufRead};

/// LinuxCNC refuses lines longer than this ("Command too long").
pub(crate) const MAX_LINE: usize = 252;

/// Where a problem is (byte offsets into the raw line) and what it is.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Fault {
    /// First byte (0-based) within the raw line.
    pub start: usize,
    /// One past the last byte.
    pub end: usize,
    /// What kind of problem.
    pub kind: FaultKind,
    /// The message.
    pub message: String,
}

/// The kinds of [`Fault`], mapped onto [`crate::GcodeError`] variants.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum FaultKind {
    Syntax,
    Invalid,
    NotSupported { code: String, note: &'static str },
    ForeignAxis(char),
}

impl Fault {
    pub(crate) fn syntax(start: usize, end: usize, message: impl Into<String>) -> Fault {
        Fault { start, end, kind: FaultKind::Syntax, message: message.into() }
    }

    pub(crate) fn invalid(start: usize, end: usize, message: impl Into<String>) -> Fault {
        Fault { start, end, kind: FaultKind::Invalid, message: message.into() }
    }

    pub(crate) fn not_supported(
        start: usize,
        end: usize,
        code: impl Into<String>,
        note: &'static str,
    ) -> Fault {
        let code = code.into();
        Fault { start, end, kind: FaultKind::NotSupported { code, note }, message: String::new() }
    }
}

/// Reads lines into one reused buffer, never holding more than `MAX_LINE + 1` bytes of a line
/// (`biscara_text::read_capped_line` with LinuxCNC's cap).
#[derive(Debug)]
pub(crate) struct LineReader<R> {
    reader: R,
    /// The current line (without `\n`, and without a `\r` before it), truncated to
    /// `MAX_LINE + 1` bytes.
    pub line: Vec<u8>,
    /// Whether the current line was longer than `MAX_LINE`.
    pub too_long: bool,
    /// 1-based number of the current line (0 before the first).
    pub number: usize,
}

impl<R: BufRead> LineReader<R> {
    pub(crate) fn new(reader: R) -> LineReader<R> {
        LineReader { reader, line: Vec::with_capacity(MAX_LINE + 2), too_long: false, number: 0 }
    }

    /// Reads the next line; `Ok(false)` at the end of the input.
    pub(crate) fn next_line(&mut self) -> io::Result<bool> {
        self.too_long = false;
        match biscara_text::read_capped_line(&mut self.reader, &mut self.line, MAX_LINE)? {
            Some(too_long) => {
                self.number += 1;
                self.too_long = too_long;
                Ok(true)
            }
            None => Ok(false),
        }
    }
}

/// The significant characters of one line (at most [`MAX_LINE`] of them: fixed arrays, no
/// allocation, no capacity checks).
#[derive(Debug)]
pub(crate) struct Compact {
    bytes: [u8; MAX_LINE + 4],
    /// For each byte of `bytes`, its 0-based byte offset in the raw line (< 256).
    columns: [u8; MAX_LINE + 4],
    len: usize,
}

impl Default for Compact {
    fn default() -> Compact {
        Compact { bytes: [0; MAX_LINE + 4], columns: [0; MAX_LINE + 4], len: 0 }
    }
}

impl Compact {
    /// Lower-case characters outside comments, without spaces and tabs; a comment is one `(`.
    pub(crate) fn bytes(&self) -> &[u8] {
        &self.bytes[..self.len]
    }

    /// The raw offset of compact index `index` (the line's end for `index >= len`).
    pub(crate) fn column(&self, index: usize, raw_len: usize) -> usize {
        if index < self.len { usize::from(self.columns[index]) } else { raw_len }
    }

    fn push(&mut self, byte: u8, column: usize) {
        // `compact` is only given lines of at most MAX_LINE bytes.
        if self.len < self.bytes.len() {
            self.bytes[self.len] = byte;
            self.columns[self.len] = column.min(255) as u8;
            self.len += 1;
        }
    }
}

/// Fills `out` with the significant characters of `raw` (LinuxCNC's `close_and_downcase`);
/// `raw` holds at most [`MAX_LINE`] bytes.
pub(crate) fn compact(raw: &[u8], out: &mut Compact) -> Result<(), Fault> {
    out.len = 0;
    let mut comment_start: Option<usize> = None;
    for (index, &byte) in raw.iter().enumerate() {
        if let Some(start) = comment_start {
            match byte {
                b')' => comment_start = None,
                b'(' => return Err(Fault::syntax(start, index + 1, "Nested comment found")),
                _ => {}
            }
            continue;
        }
        match byte {
            b' ' | b'\t' => {}
            b'(' => {
                comment_start = Some(index);
                out.push(b'(', index);
            }
            b';' => {
                // LinuxCNC keeps the `;` (a value cannot be read from it); the rest is comment.
                out.push(b';', index);
                break;
            }
            _ => out.push(byte.to_ascii_lowercase(), index),
        }
    }
    if let Some(start) = comment_start {
        return Err(Fault::syntax(start, raw.len(), "Unclosed comment found"));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn squeeze(raw: &str) -> Result<(String, Vec<u32>), String> {
        let mut out = Compact::default();
        compact(raw.as_bytes(), &mut out).map_err(|fault| fault.message)?;
        let columns = (0..out.bytes().len()).map(|i| out.column(i, raw.len()) as u32).collect();
        Ok((String::from_utf8(out.bytes().to_vec()).unwrap(), columns))
    }

    #[test]
    fn spaces_go_case_folds_comments_shrink() {
        let (text, columns) = squeeze("G0 X1 (move) y 2.5 ; rest").unwrap();
        assert_eq!(text, "g0x1(y2.5;");
        assert_eq!(columns, [0, 1, 3, 4, 6, 13, 15, 16, 17, 19]);
        assert_eq!(squeeze("G0 (a(b))").unwrap_err(), "Nested comment found");
        assert_eq!(squeeze("G0 (open").unwrap_err(), "Unclosed comment found");
    }

    #[test]
    fn lines_are_read_without_endings_and_capped() {
        let text = format!("a\r\nb\n{}\nlast", "x".repeat(1000));
        let mut reader = LineReader::new(text.as_bytes());
        let mut seen = Vec::new();
        while reader.next_line().unwrap() {
            seen.push((reader.number, reader.line.len(), reader.too_long));
        }
        assert_eq!(seen, [(1, 1, false), (2, 1, false), (3, MAX_LINE + 1, true), (4, 4, false)]);
    }
}
