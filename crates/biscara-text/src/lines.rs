//! Reading text one line at a time from any `BufRead`, with a bound on the line length.
//!
//! [`read_capped_line`] reads one line as bytes with a cap given by the caller, keeping the head
//! of a longer one: the G-code lexer uses it with LinuxCNC's 252 characters. [`LineReader`] reads
//! text on it (64 KiB, lines numbered from 1, UTF-8 and NUL checked): the front end of the CL
//! and points readers. [`read_bounded_line`] reads text on it too, with `BufRead::read_line`'s
//! `io::Error`s: the inter-file, the CSV readers and `diff`.

use std::io::{self, BufRead};

use crate::Located;

/// The longest line a reader accepts, in bytes (64 KiB): a longer one is an error, so a binary
/// file or a runaway line cannot make a reader hold unbounded memory.
pub const MAX_LINE_BYTES: usize = 64 * 1024;

/// Why a line could not be read.
#[derive(Debug, thiserror::Error)]
pub enum LineError {
    /// Occurs when reading fails.
    #[error("cannot read the file: {0}")]
    Io(#[source] io::Error),
    /// Occurs when the line is not valid UTF-8 or holds NUL bytes.
    #[error("not a text file (invalid UTF-8 or NUL bytes)")]
    NotText,
    /// Occurs when the line is longer than [`MAX_LINE_BYTES`].
    #[error("the line is longer than {MAX_LINE_BYTES} bytes")]
    TooLong,
}

/// Reads lines from `R`, numbering them from 1; `\r\n` and `\n` both end a line, and a leading
/// byte-order mark is dropped. After an error it reads nothing more.
#[derive(Debug)]
pub struct LineReader<R> {
    inner: R,
    buffer: Vec<u8>,
    line: usize,
    done: bool,
}

impl<R: BufRead> LineReader<R> {
    /// A reader over `inner`.
    pub fn new(inner: R) -> LineReader<R> {
        LineReader { inner, buffer: Vec::new(), line: 0, done: false }
    }

    /// The 1-based number of the line last returned (0 before the first).
    pub fn line(&self) -> usize {
        self.line
    }

    /// The next line without its line ending, with its 1-based number; `Ok(None)` at the end.
    ///
    /// An error carries the number of the line it occurred on.
    pub fn next_line(&mut self) -> Result<Option<(usize, &str)>, Located<LineError>> {
        if self.done {
            return Ok(None);
        }
        let too_long = match read_capped_line(&mut self.inner, &mut self.buffer, MAX_LINE_BYTES) {
            Ok(Some(too_long)) => too_long,
            Ok(None) => {
                self.done = true;
                return Ok(None);
            }
            Err(err) => {
                self.done = true;
                return Err(Located::at_line(self.line + 1, LineError::Io(err)));
            }
        };
        self.line += 1;
        if too_long {
            self.done = true;
            return Err(Located::at_line(self.line, LineError::TooLong));
        }
        let mut text = match std::str::from_utf8(&self.buffer) {
            Ok(text) => text,
            Err(_) => {
                self.done = true;
                return Err(Located::at_line(self.line, LineError::NotText));
            }
        };
        if self.line == 1 {
            text = text.strip_prefix('\u{feff}').unwrap_or(text);
        }
        if text.contains('\0') {
            self.done = true;
            return Err(Located::at_line(self.line, LineError::NotText));
        }
        Ok(Some((self.line, text)))
    }
}

/// Reads the next line of `reader` into `line` (cleared first) as bytes, without its `\n` and a
/// `\r` before it, keeping at most `max + 1` bytes of it: `Ok(None)` at the end of the input,
/// else `Ok(Some(too_long))`, `too_long` telling that the line has more than `max` bytes (then
/// `line` holds its first `max + 1` and the rest is read and dropped, so that memory stays
/// bounded and the next call starts on the next line).
///
/// The one bounded line reader: [`LineReader`] reads text on it with [`MAX_LINE_BYTES`], the
/// G-code lexer reads bytes with LinuxCNC's 252 characters. `Interrupted` reads are retried.
///
/// ```
/// let mut input = "G0 X1\r\nG1 X123456\n".as_bytes();
/// let mut line = Vec::new();
/// assert_eq!(biscara_text::read_capped_line(&mut input, &mut line, 8)?, Some(false));
/// assert_eq!(line, b"G0 X1");
/// assert_eq!(biscara_text::read_capped_line(&mut input, &mut line, 8)?, Some(true));
/// assert_eq!(line, b"G1 X12345"); // the first max + 1 bytes
/// assert_eq!(biscara_text::read_capped_line(&mut input, &mut line, 8)?, None);
/// # Ok::<(), std::io::Error>(())
/// ```
#[inline]
pub fn read_capped_line(
    reader: &mut impl BufRead,
    line: &mut Vec<u8>,
    max: usize,
) -> io::Result<Option<bool>> {
    line.clear();
    let mut length = 0usize;
    let mut any = false;
    loop {
        let available = match reader.fill_buf() {
            Ok(available) => available,
            Err(err) if err.kind() == io::ErrorKind::Interrupted => continue,
            Err(err) => return Err(err),
        };
        if available.is_empty() {
            break;
        }
        any = true;
        let (chunk, used, done) = match available.iter().position(|&byte| byte == b'\n') {
            Some(index) => (&available[..index], index + 1, true),
            None => (available, available.len(), false),
        };
        let room = (max + 2).saturating_sub(line.len());
        line.extend_from_slice(&chunk[..chunk.len().min(room)]);
        length += chunk.len();
        reader.consume(used);
        if done {
            break;
        }
    }
    if !any {
        return Ok(None);
    }
    if line.last() == Some(&b'\r') && length <= max + 1 {
        line.pop();
        length -= 1;
    }
    let too_long = length > max;
    if too_long {
        line.truncate(max + 1);
    }
    Ok(Some(too_long))
}

/// Reads the next line of `reader` into `buffer` (replacing what it held), without its line
/// ending: `Ok(false)` at the end of the input. [`read_capped_line`] with [`MAX_LINE_BYTES`] and
/// `BufRead::read_line`'s errors, for the readers whose messages are `io::Error`s (the
/// inter-file, the CSV readers, `diff`): a longer line is an [`io::ErrorKind::InvalidData`]
/// error "the line is longer than 65536 bytes", text that is not UTF-8 one "stream did not
/// contain valid UTF-8".
pub fn read_bounded_line(reader: &mut impl BufRead, buffer: &mut String) -> io::Result<bool> {
    let mut bytes = std::mem::take(buffer).into_bytes();
    match read_capped_line(reader, &mut bytes, MAX_LINE_BYTES)? {
        None => Ok(false),
        Some(true) => Err(io::Error::new(
            io::ErrorKind::InvalidData,
            format!("the line is longer than {MAX_LINE_BYTES} bytes"),
        )),
        Some(false) => {
            *buffer = String::from_utf8(bytes).map_err(|_| {
                io::Error::new(io::ErrorKind::InvalidData, "stream did not contain valid UTF-8")
            })?;
            Ok(true)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lines(bytes: &[u8]) -> Vec<Result<(usize, String), usize>> {
        let mut reader = LineReader::new(bytes);
        let mut out = Vec::new();
        loop {
            match reader.next_line() {
                Ok(Some((line, text))) => out.push(Ok((line, text.to_owned()))),
                Ok(None) => break,
                Err(err) => {
                    out.push(Err(err.line));
                    break;
                }
            }
        }
        out
    }

    #[test]
    fn read_errors_name_their_line() {
        let io = Located::at_line(3, LineError::Io(io::Error::other("disk gone")));
        assert_eq!(io.to_string(), "3: cannot read the file: disk gone");
        assert_eq!(std::error::Error::source(&io).unwrap().to_string(), "disk gone");
        let binary = Located::at_line(2, LineError::NotText);
        assert_eq!(binary.to_string(), "2: not a text file (invalid UTF-8 or NUL bytes)");
        let long = Located::at_line(7, LineError::TooLong);
        assert_eq!(long.to_string(), "7: the line is longer than 65536 bytes");
    }

    #[test]
    fn numbers_lines_and_strips_endings() {
        assert_eq!(
            lines(b"\xef\xbb\xbfa\r\nb\n\nc"),
            vec![
                Ok((1, "a".to_owned())),
                Ok((2, "b".to_owned())),
                Ok((3, String::new())),
                Ok((4, "c".to_owned()))
            ]
        );
        assert!(lines(b"").is_empty());
    }

    #[test]
    fn rejects_binary_and_huge_lines() {
        assert_eq!(lines(b"ok\n\xff\xfe\n"), vec![Ok((1, "ok".to_owned())), Err(2)]);
        assert_eq!(lines(b"a\0b\n"), vec![Err(1)]);
        let huge = vec![b'x'; MAX_LINE_BYTES + 10];
        assert_eq!(lines(&huge), vec![Err(1)]);
        let exact = vec![b'x'; MAX_LINE_BYTES];
        assert_eq!(lines(&exact).len(), 1);
    }

    #[test]
    fn capped_lines_keep_the_head_of_a_long_line_and_go_on() {
        let mut input = "abc\r\nabcd\r\nxyz\rabc\r".as_bytes();
        let mut line = Vec::new();
        let mut next = || {
            let result = read_capped_line(&mut input, &mut line, 3).unwrap();
            result.map(|too_long| (String::from_utf8(line.clone()).unwrap(), too_long))
        };
        assert_eq!(next(), Some(("abc".to_owned(), false)));
        assert_eq!(next(), Some(("abcd".to_owned(), true)));
        // A `\r` inside a line is kept; only the one before the line's end is dropped.
        assert_eq!(next(), Some(("xyz\r".to_owned(), true)));
        let input = "x".repeat(10_000) + "\nok\n";
        let mut bytes = input.as_bytes();
        assert_eq!(read_capped_line(&mut bytes, &mut line, 5).unwrap(), Some(true));
        assert_eq!(line.len(), 6);
        assert_eq!(read_capped_line(&mut bytes, &mut line, 5).unwrap(), Some(false));
        assert_eq!(line, b"ok");
        assert_eq!(read_capped_line(&mut bytes, &mut line, 5).unwrap(), None);
    }

    #[test]
    fn bounded_lines_refuse_long_lines_and_read_short_ones() {
        let mut text = "a\n".to_owned();
        text.push_str(&"x".repeat(MAX_LINE_BYTES + 10));
        let mut reader = text.as_bytes();
        let mut line = String::new();
        assert!(read_bounded_line(&mut reader, &mut line).unwrap());
        assert_eq!(line, "a");
        let err = read_bounded_line(&mut reader, &mut line).unwrap_err();
        assert_eq!(err.to_string(), "the line is longer than 65536 bytes");
        let exact = "y".repeat(MAX_LINE_BYTES) + "\r\n\n";
        let mut reader = exact.as_bytes();
        assert!(read_bounded_line(&mut reader, &mut line).unwrap());
        assert_eq!(line.len(), MAX_LINE_BYTES);
        assert!(read_bounded_line(&mut reader, &mut line).unwrap());
        assert_eq!(line, "");
        assert!(!read_bounded_line(&mut reader, &mut line).unwrap());
        let err = read_bounded_line(&mut &b"ok\xff\n"[..], &mut line).unwrap_err();
        assert_eq!(err.to_string(), "stream did not contain valid UTF-8");
    }
}
