//! Rows of numbers: what the path and joint CSV readers share.

use std::io::{self, BufRead};

use crate::Located;
use crate::lines::read_bounded_line;

/// A CSV of numbers (path or joint CSV) that cannot be read, at its line (and column).
pub type CsvError = Located<CsvErrorKind>;

/// What is wrong in a CSV of numbers.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum CsvErrorKind {
    /// Occurs when the underlying reader fails (including text that is not UTF-8 and lines over
    /// [`crate::MAX_LINE_BYTES`]).
    #[error("{0}")]
    Io(#[source] io::Error),
    /// Occurs when the file is empty or its first line is not the header the reader expects.
    #[error("expected {expected}, found `{found}`")]
    Header {
        /// The headers the reader accepts, in words.
        expected: &'static str,
        /// The first line as found (shortened).
        found: String,
    },
    /// Occurs when a row has the wrong number of fields or a field that is not a finite number,
    /// or time does not increase.
    #[error("{0}")]
    Row(String),
}

/// The most columns a [`NumericCsvReader`] row may have.
pub const MAX_CSV_COLUMNS: usize = 24;

/// What the path and joint CSV readers share: bounded lines read one at a time, rows of finite
/// numbers with `FILE`-relative line and column errors, and a first column (time) that increases.
#[derive(Debug)]
pub struct NumericCsvReader<R> {
    reader: R,
    line: usize,
    buffer: String,
    previous_t: f64,
}

impl<R: BufRead> NumericCsvReader<R> {
    /// A reader at the start of `reader`.
    pub fn new(reader: R) -> NumericCsvReader<R> {
        NumericCsvReader { reader, line: 0, buffer: String::new(), previous_t: f64::NEG_INFINITY }
    }

    fn read_line(&mut self) -> Result<bool, CsvError> {
        self.buffer.clear();
        self.line += 1;
        let line = self.line;
        read_bounded_line(&mut self.reader, &mut self.buffer)
            .map_err(|source| Located::at_line(line, CsvErrorKind::Io(source)))
    }

    /// The first line without its line break (empty for an empty input), for the caller to
    /// recognise; [`NumericCsvReader::header_error`] makes the error when it does not.
    pub fn header(&mut self) -> Result<&str, CsvError> {
        if !self.read_line()? {
            self.buffer.clear();
        }
        Ok(self.buffer.trim_end())
    }

    /// The error for a header that is not one of `expected`.
    pub fn header_error(&self, expected: &'static str) -> CsvError {
        let found = self.buffer.trim_end().chars().take(80).collect();
        Located::at(1, 1, CsvErrorKind::Header { expected, found })
    }

    /// The next non-blank row as exactly `columns` (at most [`MAX_CSV_COLUMNS`]) finite numbers,
    /// with its 1-based line; `None` at the end of the input.
    pub fn row(
        &mut self,
        columns: usize,
    ) -> Result<Option<(usize, [f64; MAX_CSV_COLUMNS])>, CsvError> {
        loop {
            if !self.read_line()? {
                return Ok(None);
            }
            if !self.buffer.trim().is_empty() {
                break;
            }
        }
        let line = self.line;
        let text = self.buffer.trim_end_matches(['\n', '\r']);
        let error = |column, message| Located::at(line, column, CsvErrorKind::Row(message));
        let columns = columns.min(MAX_CSV_COLUMNS);
        let mut values = [0.0; MAX_CSV_COLUMNS];
        let mut count = 0;
        let mut column = 1;
        for field in text.split(',') {
            if count == columns {
                return Err(error(column, format!("expected {columns} fields, found more")));
            }
            let shown = field.chars().take(40).collect::<String>();
            let shown = shown.escape_debug();
            let value: f64 = field
                .trim()
                .parse()
                .map_err(|_| error(column, format!("`{shown}` is not a number")))?;
            if !value.is_finite() {
                return Err(error(column, format!("`{shown}` is not a finite number")));
            }
            values[count] = value;
            count += 1;
            column += field.len() + 1;
        }
        if count < columns {
            return Err(error(text.len() + 1, format!("expected {columns} fields, found {count}")));
        }
        if values[0] <= self.previous_t {
            return Err(error(1, format!("time {} does not increase", values[0])));
        }
        self.previous_t = values[0];
        Ok(Some((line, values)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[track_caller]
    fn check_error(text: &str, columns: usize, expected: &str) {
        let mut csv = NumericCsvReader::new(text.as_bytes());
        assert_eq!(csv.header().unwrap(), "a,b");
        let err = loop {
            match csv.row(columns) {
                Ok(Some(_)) => {}
                Ok(None) => panic!("no error in {text:?}"),
                Err(err) => break err,
            }
        };
        assert_eq!(err.to_string(), expected);
    }

    #[test]
    fn rows_are_finite_numbers_with_increasing_time() {
        let mut csv = NumericCsvReader::new("a,b\n0, 1.5\n\n1,-2\n".as_bytes());
        assert_eq!(csv.header().unwrap(), "a,b");
        let (line, values) = csv.row(2).unwrap().unwrap();
        assert_eq!((line, values[0], values[1]), (2, 0.0, 1.5));
        let (line, values) = csv.row(2).unwrap().unwrap();
        assert_eq!((line, values[0], values[1]), (4, 1.0, -2.0));
        assert!(csv.row(2).unwrap().is_none());
        assert_eq!(csv.header_error("`a,b`").to_string(), "1:1: expected `a,b`, found ``");
    }

    #[test]
    fn bad_rows_are_located() {
        check_error("a,b\n0\n", 2, "2:2: expected 2 fields, found 1");
        check_error("a,b\n0,1,2\n", 2, "2:5: expected 2 fields, found more");
        check_error("a,b\n0,x\n", 2, "2:3: `x` is not a number");
        check_error("a,b\n0,inf\n", 2, "2:3: `inf` is not a finite number");
        check_error("a,b\n1,0\n1,0\n", 2, "3:1: time 1 does not increase");
    }
}
