//! Reading text one line at a time from any `BufRead`, with a bound on the line length.
//!
//! [`LineReader`] numbers lines from 1 and checks each is text (UTF-8, no NUL): the front end of
//! the CL and points readers. [`read_bounded_line`] is `BufRead::read_line` with the same bound,
//! for the readers whose messages are `io::Error`'s (the inter-file, the CSV readers, `diff`).

use std::io::{self, BufRead, Read};

/// The longest line a reader accepts, in bytes (64 KiB): a longer one is an error, so a binary
/// file or a runaway line cannot make a reader hold unbounded memory.
pub const MAX_LINE_BYTES: usize = 64 * 1024;

/// Why a line could not be read.
#[derive(Debug, thiserror::Error)]
pub enum LineError {
    /// Occurs when reading fails.
    #[error("cannot read: {0}")]
    Io(io::Error),
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
    pub fn next_line(&mut self) -> Result<Option<(usize, &str)>, (usize, LineError)> {
        if self.done {
            return Ok(None);
        }
        self.buffer.clear();
        let mut read_any = false;
        loop {
            let available = match self.inner.fill_buf() {
                Ok(available) => available,
                Err(err) if err.kind() == io::ErrorKind::Interrupted => continue,
                Err(err) => {
                    self.done = true;
                    return Err((self.line + 1, LineError::Io(err)));
                }
            };
            if available.is_empty() {
                break;
            }
            read_any = true;
            let (taken, ends) = match available.iter().position(|&byte| byte == b'\n') {
                Some(end) => (end + 1, true),
                None => (available.len(), false),
            };
            if self.buffer.len() + taken > MAX_LINE_BYTES + 2 {
                self.done = true;
                return Err((self.line + 1, LineError::TooLong));
            }
            self.buffer.extend_from_slice(&available[..taken]);
            self.inner.consume(taken);
            if ends {
                break;
            }
        }
        if !read_any {
            self.done = true;
            return Ok(None);
        }
        self.line += 1;
        if self.buffer.last() == Some(&b'\n') {
            self.buffer.pop();
        }
        if self.buffer.last() == Some(&b'\r') {
            self.buffer.pop();
        }
        if self.buffer.len() > MAX_LINE_BYTES {
            self.done = true;
            return Err((self.line, LineError::TooLong));
        }
        let mut text = match std::str::from_utf8(&self.buffer) {
            Ok(text) => text,
            Err(_) => {
                self.done = true;
                return Err((self.line, LineError::NotText));
            }
        };
        if self.line == 1 {
            text = text.strip_prefix('\u{feff}').unwrap_or(text);
        }
        if text.contains('\0') {
            self.done = true;
            return Err((self.line, LineError::NotText));
        }
        Ok(Some((self.line, text)))
    }
}

/// Appends the next line (with its `\n`) of `reader` to `buffer`, like [`BufRead::read_line`], but
/// fails with [`io::ErrorKind::InvalidData`] instead of growing past [`MAX_LINE_BYTES`]. Returns
/// the bytes read, 0 at the end of input.
pub fn read_bounded_line(reader: &mut impl BufRead, buffer: &mut String) -> io::Result<usize> {
    let limit = (MAX_LINE_BYTES + 1) as u64;
    let read = reader.by_ref().take(limit).read_line(buffer)?;
    if read > MAX_LINE_BYTES && !buffer.ends_with('\n') {
        return Err(io::Error::new(
            io::ErrorKind::InvalidData,
            format!("the line is longer than {MAX_LINE_BYTES} bytes"),
        ));
    }
    Ok(read)
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
                Err((line, _)) => {
                    out.push(Err(line));
                    break;
                }
            }
        }
        out
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
    fn bounded_lines_refuse_long_lines_and_read_short_ones() {
        let mut text = "a\n".to_owned();
        text.push_str(&"x".repeat(MAX_LINE_BYTES + 10));
        let mut reader = text.as_bytes();
        let mut line = String::new();
        assert_eq!(read_bounded_line(&mut reader, &mut line).unwrap(), 2);
        line.clear();
        let err = read_bounded_line(&mut reader, &mut line).unwrap_err();
        assert_eq!(err.to_string(), "the line is longer than 65536 bytes");
        let exact = "y".repeat(MAX_LINE_BYTES);
        let mut line = String::new();
        assert_eq!(read_bounded_line(&mut exact.as_bytes(), &mut line).unwrap(), MAX_LINE_BYTES);
    }
}
