//! The path CSV (docs/motion.md): `t_s,x_mm,y_mm,z_mm,c_deg[,gripper]`.

use std::io::{self, BufRead, Write};

use biscara_text::{CsvError, NumericCsvReader, RowBuffer};

use crate::CartesianSample;

/// The header of a path CSV, without and with the gripper column.
pub const PATH_HEADER: &str = "t_s,x_mm,y_mm,z_mm,c_deg";

/// Writes samples as a path CSV; rows reach the output in chunks of [`biscara_text::FLUSH_AT`]
/// bytes and at [`PathCsvWriter::finish`], which must be called.
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

    /// A writer with `decimals` decimals and the extra columns `columns` after the pose (the
    /// tool's, docs/motion.md `--events`), whose values [`PathCsvWriter::write_with`] takes; writes
    /// the header at once.
    pub fn with_columns(mut out: W, decimals: usize, columns: &[&str]) -> io::Result<Self> {
        out.write_all(PATH_HEADER.as_bytes())?;
        for column in columns {
            write!(out, ",{column}")?;
        }
        out.write_all(b"\n")?;
        Ok(PathCsvWriter { out, decimals, events: false, row: RowBuffer::new() })
    }

    /// Writes one sample with the values of the extra columns (see
    /// [`PathCsvWriter::with_columns`]), with the writer's decimals.
    pub fn write_with(&mut self, sample: &CartesianSample, values: &[f64]) -> io::Result<()> {
        let [x, y, z, c] = sample.pose;
        self.row.push_fixed_list([sample.t, x, y, z, c], self.decimals);
        for value in values {
            self.row.push(b',');
            self.row.push_fixed(*value, self.decimals);
        }
        self.row.push(b'\n');
        if self.row.is_full() {
            self.row.write_to(&mut self.out)?;
        }
        Ok(())
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

/// A path CSV that cannot be read (the numeric CSV reader's error).
pub type PathCsvError = CsvError;

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

biscara_text::record_reader!(PathCsvReader, CartesianSample, CsvError, next_sample, failed);

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
