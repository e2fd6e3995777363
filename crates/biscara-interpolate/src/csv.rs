//! The path CSV (SPEC §6): `t_s,x_mm,y_mm,z_mm,c_deg[,gripper]`, and fixed-decimal numbers.

use std::io::{self, BufRead, Write};

use crate::CartesianSample;
use crate::fixed::RowBuffer;

/// The header of a path CSV, without and with the gripper column.
pub const PATH_HEADER: &str = "t_s,x_mm,y_mm,z_mm,c_deg";

/// Writes samples as a path CSV; rows reach the output in chunks of [`crate::FLUSH_AT`] bytes and at
/// [`PathCsvWriter::finish`], which must be called.
#[derive(Debug)]
pub struct PathCsvWriter<W: Write> {
    out: W,
    decimals: usize,
    events: bool,
    /// Rows not yet handed to `out`.
    row: RowBuffer,
}

impl<W: Write> PathCsvWriter<W> {
    /// A writer with `decimals` decimals for every number, and the `gripper` column when
    /// `events`; writes the header at once.
    pub fn new(mut out: W, decimals: usize, events: bool) -> io::Result<Self> {
        out.write_all(PATH_HEADER.as_bytes())?;
        out.write_all(if events { b",gripper\n" } else { b"\n" })?;
        Ok(PathCsvWriter { out, decimals, events, row: RowBuffer::new() })
    }

    /// Writes one sample.
    pub fn write(&mut self, sample: &CartesianSample) -> io::Result<()> {
        let [x, y, z, c] = sample.pose;
        self.row.push_fixed_list([sample.t, x, y, z, c], self.decimals);
        if self.events {
            self.row.extend_from_slice(if sample.gripper { b",1" } else { b",0" });
        }
        self.row.push(b'\n');
        if self.row.is_full() {
            self.row.write_to(&mut self.out)?;
        }
        Ok(())
    }

    /// Writes the rows still buffered, flushes and returns the underlying writer.
    pub fn finish(mut self) -> io::Result<W> {
        self.row.write_to(&mut self.out)?;
        self.out.flush()?;
        Ok(self.out)
    }
}

/// A CSV of numbers (path or joint CSV) that cannot be read.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum CsvError {
    /// Occurs when the underlying reader fails (including text that is not UTF-8 and lines over
    /// [`biscara_motion::MAX_LINE_BYTES`]).
    #[error("{line}: {source}")]
    Io {
        /// 1-based line being read.
        line: usize,
        /// The I/O error.
        source: io::Error,
    },
    /// Occurs when the file is empty or its first line is not the header the reader expects.
    #[error("1:1: expected {expected}, found `{found}`")]
    Header {
        /// The headers the reader accepts, in words.
        expected: &'static str,
        /// The first line as found (shortened).
        found: String,
    },
    /// Occurs when a row has the wrong number of fields or a field that is not a finite number,
    /// or time does not increase.
    #[error("{line}:{column}: {message}")]
    Row {
        /// 1-based line.
        line: usize,
        /// 1-based column where the offending field starts.
        column: usize,
        /// What is wrong.
        message: String,
    },
}

/// A path CSV that cannot be read.
pub type PathCsvError = CsvError;

/// The most columns a [`NumericCsvReader`] row may have.
pub const MAX_CSV_COLUMNS: usize = 16;

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
        match biscara_motion::read_bounded_line(&mut self.reader, &mut self.buffer) {
            Ok(read) => Ok(read > 0),
            Err(source) => Err(CsvError::Io { line: self.line, source }),
        }
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
        CsvError::Header { expected, found: self.buffer.trim_end().chars().take(80).collect() }
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
        let error = |column, message| CsvError::Row { line, column, message };
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

/// Reads a path CSV written by `biscara interpolate`, streaming. Each sample's `line` is its line
/// in the CSV file.
pub fn read_path_csv<R: BufRead>(reader: R) -> PathCsvReader<R> {
    PathCsvReader { csv: NumericCsvReader::new(reader), columns: None, failed: false }
}

/// The iterator returned by [`read_path_csv`]; stops after the first error.
#[derive(Debug)]
pub struct PathCsvReader<R> {
    csv: NumericCsvReader<R>,
    /// 5, or 6 with the gripper column; known once the header is read.
    columns: Option<usize>,
    failed: bool,
}

impl<R: BufRead> PathCsvReader<R> {
    fn next_sample(&mut self) -> Result<Option<CartesianSample>, CsvError> {
        let columns = match self.columns {
            Some(columns) => columns,
            None => {
                let header = self.csv.header()?;
                let columns = if header == PATH_HEADER {
                    5
                } else if header.strip_prefix(PATH_HEADER) == Some(",gripper") {
                    6
                } else {
                    return Err(self.csv.header_error(
                        "the header `t_s,x_mm,y_mm,z_mm,c_deg` (optionally `,gripper`)",
                    ));
                };
                *self.columns.insert(columns)
            }
        };
        Ok(self.csv.row(columns)?.map(|(line, values)| CartesianSample {
            t: values[0],
            pose: [values[1], values[2], values[3], values[4]],
            line,
            gripper: columns == 6 && values[5] != 0.0,
        }))
    }
}

impl<R: BufRead> Iterator for PathCsvReader<R> {
    type Item = Result<CartesianSample, CsvError>;

    fn next(&mut self) -> Option<Self::Item> {
        if self.failed {
            return None;
        }
        let result = self.next_sample();
        self.failed = result.is_err();
        result.transpose()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_round_trip() {
        let sample =
            CartesianSample { t: 0.5, pose: [1.0, -2.0, 3.25, 90.0], line: 2, gripper: true };
        let mut writer = PathCsvWriter::new(Vec::new(), 6, true).unwrap();
        writer.write(&sample).unwrap();
        let text = writer.finish().unwrap();
        assert_eq!(
            String::from_utf8(text.clone()).unwrap(),
            "t_s,x_mm,y_mm,z_mm,c_deg,gripper\n0.500000,1.000000,-2.000000,3.250000,90.000000,1\n"
        );
        let back: Vec<_> = read_path_csv(&text[..]).collect::<Result<_, _>>().unwrap();
        assert_eq!(back, [sample]);
    }

    #[track_caller]
    fn check_error(text: &str, expected: &str) {
        let err = read_path_csv(text.as_bytes()).find_map(Result::err).expect("an error");
        assert_eq!(err.to_string(), expected);
    }

    #[test]
    fn bad_files_are_reported_with_line_and_column() {
        check_error(
            "",
            "1:1: expected the header `t_s,x_mm,y_mm,z_mm,c_deg` (optionally `,gripper`), found ``",
        );
        check_error(
            "t,x\n",
            "1:1: expected the header `t_s,x_mm,y_mm,z_mm,c_deg` (optionally `,gripper`), found `t,x`",
        );
        check_error("t_s,x_mm,y_mm,z_mm,c_deg\n0,1,2,3\n", "2:8: expected 5 fields, found 4");
        check_error(
            "t_s,x_mm,y_mm,z_mm,c_deg\n0,1,2,3,4,5\n",
            "2:11: expected 5 fields, found more",
        );
        check_error("t_s,x_mm,y_mm,z_mm,c_deg\n0,1,x,3,4\n", "2:5: `x` is not a number");
        check_error("t_s,x_mm,y_mm,z_mm,c_deg\n0,1,NaN,3,4\n", "2:5: `NaN` is not a finite number");
        check_error(
            "t_s,x_mm,y_mm,z_mm,c_deg\n1,1,2,3,4\n0.5,1,2,3,4\n",
            "3:1: time 0.5 does not increase",
        );
    }
}
