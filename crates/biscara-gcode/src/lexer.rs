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
    Cannot { code: String, reason: &'static str },
    ForeignAxis(char),
}

impl Fault {
    pub(crate) fn syntax(start: usize, end: usize, message: impl Into<String>) -> Fault {
        Fault { start, end, kind: FaultKind::Syntax, message: message.into() }
    }

    pub(crate) fn invalid(start: usize, end: usize, message: impl Into<String>) -> Fault {
        Fault { start, end, kind: FaultKind::Invalid, message: message.into() }
    }

    pub(crate) fn cannot(start: usize, end: usize, code: String, reason: &'static str) -> Fault {
        Fault { start, end, kind: FaultKind::Cannot { code, reason }, message: String::new() }
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

/// Reads lines into one reused buffer, never holding more than `max + 1` bytes of a line
/// (`biscara_text::read_capped_line` with the dialect's cap).
#[derive(Debug)]
pub(crate) struct LineReader<R> {
    reader: Prefixed<R>,
    /// The current line (without `\n`, and without a `\r` before it), truncated to
    /// `max + 1` bytes.
    pub line: Vec<u8>,
    /// Whether the current line was longer than `max`.
    pub too_long: bool,
    /// 1-based number of the current line (0 before the first).
    pub number: usize,
    /// The longest line accepted, bytes: LinuxCNC's [`MAX_LINE`] unless a dialect says more.
    pub max: usize,
}

impl<R: BufRead> LineReader<R> {
    pub(crate) fn new(reader: R) -> LineReader<R> {
        LineReader {
            reader: Prefixed { head: Vec::new(), position: 0, inner: reader },
            line: Vec::with_capacity(MAX_LINE + 2),
            too_long: false,
            number: 0,
            max: MAX_LINE,
        }
    }

    /// The input, to read ahead in it before the first line.
    pub(crate) fn source(&mut self) -> &mut Prefixed<R> {
        &mut self.reader
    }

    /// Reads the next line; `Ok(false)` at the end of the input.
    pub(crate) fn next_line(&mut self) -> io::Result<bool> {
        self.too_long = false;
        match biscara_text::read_capped_line(&mut self.reader, &mut self.line, self.max)? {
            Some(too_long) => {
                self.number += 1;
                self.too_long = too_long;
                Ok(true)
            }
            None => Ok(false),
        }
    }
}

/// An input with the bytes already read ahead from it (for `auto` dialect detection) put back
/// in front.
#[derive(Debug)]
pub(crate) struct Prefixed<R> {
    head: Vec<u8>,
    position: usize,
    inner: R,
}

impl<R: BufRead> Prefixed<R> {
    /// Reads up to `limit` bytes ahead (before anything was consumed); returns whether that
    /// is the whole input.
    pub(crate) fn read_ahead(&mut self, limit: usize) -> io::Result<bool> {
        while self.head.len() < limit {
            let available = match self.inner.fill_buf() {
                Ok(available) => available,
                Err(err) if err.kind() == io::ErrorKind::Interrupted => continue,
                Err(err) => return Err(err),
            };
            if available.is_empty() {
                return Ok(true);
            }
            let take = available.len().min(limit - self.head.len());
            self.head.extend_from_slice(&available[..take]);
            self.inner.consume(take);
        }
        Ok(false)
    }

    /// The bytes read ahead.
    pub(crate) fn head(&self) -> &[u8] {
        &self.head
    }
}

impl<R: BufRead> io::Read for Prefixed<R> {
    fn read(&mut self, out: &mut [u8]) -> io::Result<usize> {
        let available = self.fill_buf()?;
        let count = available.len().min(out.len());
        out[..count].copy_from_slice(&available[..count]);
        self.consume(count);
        Ok(count)
    }
}

impl<R: BufRead> BufRead for Prefixed<R> {
    fn fill_buf(&mut self) -> io::Result<&[u8]> {
        if self.position < self.head.len() {
            return Ok(&self.head[self.position..]);
        }
        self.inner.fill_buf()
    }

    fn consume(&mut self, amount: usize) {
        if self.position < self.head.len() {
            self.position += amount;
            if self.position >= self.head.len() {
                // Read ahead once: give the memory back.
                self.head = Vec::new();
                self.position = 0;
            }
        } else {
            self.inner.consume(amount);
        }
    }
}

/// The significant characters of one line (at most [`MAX_LINE`] of them: fixed arrays, no
/// allocation, no capacity checks).
#[derive(Debug)]
pub(crate) struct Compact {
    bytes: [u8; MAX_LINE + 4],
    /// For each byte of `bytes`, its 0-based byte offset in the raw line (< 65 536).
    columns: [u16; MAX_LINE + 4],
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

    /// Mutable significant characters (a dialect renames a word's letter).
    pub(crate) fn bytes_mut(&mut self) -> &mut [u8] {
        &mut self.bytes[..self.len]
    }

    /// The raw offset of compact index `index` (the line's end for `index >= len`).
    pub(crate) fn column(&self, index: usize, raw_len: usize) -> usize {
        if index < self.len { usize::from(self.columns[index]) } else { raw_len }
    }

    fn push(&mut self, byte: u8, column: usize) {
        // `compact` is only given lines of at most MAX_LINE bytes.
        if self.len < self.bytes.len() {
            self.bytes[self.len] = byte;
            self.columns[self.len] = column.min(usize::from(u16::MAX)) as u16;
            self.len += 1;
        }
    }
}

/// Fills `out` with the significant characters of `raw` (LinuxCNC's `close_and_downcase`).
/// With `nested` (Mach3), a `(` inside a comment opens a comment within it; otherwise it is
/// LinuxCNC's "Nested comment found". A line longer than [`MAX_LINE`] (a dialect's long comment)
/// is refused if more than [`MAX_LINE`] significant characters remain.
pub(crate) fn compact(raw: &[u8], out: &mut Compact, nested: bool) -> Result<(), Fault> {
    out.len = 0;
    let mut comment_start: Option<usize> = None;
    let mut depth = 0usize;
    for (index, &byte) in raw.iter().enumerate() {
        if let Some(start) = comment_start {
            match byte {
                b')' if depth > 1 => depth -= 1,
                b')' => comment_start = None,
                b'(' if nested => depth += 1,
                b'(' => return Err(Fault::syntax(start, index + 1, "Nested comment found")),
                _ => {}
            }
            continue;
        }
        match byte {
            b' ' | b'\t' => {}
            b'(' => {
                comment_start = Some(index);
                depth = 1;
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
    if out.len > MAX_LINE {
        let start = out.column(MAX_LINE, raw.len());
        return Err(Fault::syntax(
            start,
            raw.len(),
            format!(
                "Command too long: more than {MAX_LINE} characters outside comments (the \
                 dialect accepts long comment lines, not long commands)"
            ),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn squeeze(raw: &str) -> Result<(String, Vec<u32>), String> {
        let mut out = Compact::default();
        compact(raw.as_bytes(), &mut out, false).map_err(|fault| fault.message)?;
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
    fn nested_comments_close_at_their_own_parenthesis() {
        let mut out = Compact::default();
        compact(b"G0 (a (b) c) X1", &mut out, true).unwrap();
        assert_eq!(out.bytes(), b"g0(x1");
        assert_eq!(out.column(3, 15), 13);
        let fault = compact(b"G0 (a (b) c", &mut out, true).unwrap_err();
        assert_eq!(fault.message, "Unclosed comment found");
    }

    #[test]
    fn long_lines_keep_columns_and_refuse_long_commands() {
        let mut out = Compact::default();
        let long = format!("({}) G1 X1", "c".repeat(1000));
        compact(long.as_bytes(), &mut out, false).unwrap();
        assert_eq!(out.bytes(), b"(g1x1");
        assert_eq!(out.column(1, long.len()), 1003);
        let command = format!("G1 X{}", "1".repeat(400));
        let fault = compact(command.as_bytes(), &mut out, false).unwrap_err();
        assert!(fault.message.starts_with("Command too long"), "{}", fault.message);
    }

    #[test]
    fn read_ahead_bytes_are_read_again() {
        let mut reader = LineReader::new("first\nsecond\nthird".as_bytes());
        assert!(!reader.source().read_ahead(8).unwrap());
        assert_eq!(reader.source().head(), b"first\nse");
        let mut seen = Vec::new();
        while reader.next_line().unwrap() {
            seen.push(String::from_utf8(reader.line.clone()).unwrap());
        }
        assert_eq!(seen, ["first", "second", "third"]);
        let mut whole = LineReader::new("a\n".as_bytes());
        assert!(whole.source().read_ahead(64).unwrap());
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
