//! Reading text lines of bounded length.

use std::io::{self, BufRead, Read};

/// The longest line the stage readers accept, bytes: far above any real CSV row or inter-file
/// object, and small enough that a file with no line breaks cannot exhaust memory.
pub const MAX_LINE_BYTES: usize = 1 << 16;

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

    #[test]
    fn long_lines_are_refused_and_short_ones_read() {
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
