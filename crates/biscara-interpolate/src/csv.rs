//! The path CSV (SPEC §6): `t_s,x_mm,y_mm,z_mm,c_deg[,gripper]`, and fixed-decimal numbers.

use std::io::{self, BufRead, Write};

use crate::CartesianSample;

/// The header of a path CSV, without and with the gripper column.
pub const PATH_HEADER: &str = "t_s,x_mm,y_mm,z_mm,c_deg";

/// The largest number of decimals [`push_fixed`] writes.
pub const MAX_DECIMALS: usize = 12;

const POWERS_OF_TEN: [f64; MAX_DECIMALS + 1] =
    [1.0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12];

/// Two-digit decimal strings "00" to "99", for writing digits two at a time.
const DIGIT_PAIRS: &[u8; 200] = b"\
0001020304050607080910111213141516171819\
2021222324252627282930313233343536373839\
4041424344454647484950515253545556575859\
6061626364656667686970717273747576777879\
8081828384858687888990919293949596979899";

/// Powers of ten as integers, for splitting a scaled value into integer part and fraction.
const INTEGER_POWERS_OF_TEN: [u64; MAX_DECIMALS + 1] = [
    1,
    10,
    100,
    1_000,
    10_000,
    100_000,
    1_000_000,
    10_000_000,
    100_000_000,
    1_000_000_000,
    10_000_000_000,
    100_000_000_000,
    1_000_000_000_000,
];

/// Appends `value` with exactly `decimals` decimals (at most [`MAX_DECIMALS`]), never a
/// negative zero.
///
/// The CSV writers' hot spot (40 % of the instructions of `joints` with a digit-at-a-time
/// writer). It scales to an integer, writes the digits two at a time, right to left, into a stack
/// array whose length is counted first, and appends the whole array with one fixed-size copy
/// before trimming it: no variable-length `memcpy` call per number, and divisions by constants
/// only (callgrind, `joints` on a 30,000-line program: 3.84 G instructions with the first
/// version, 2.41 G with this one). It agrees with `format!` except, rarely, in the last digit of
/// a value within rounding noise of a tie. Values too large to scale exactly fall back to
/// `format!`.
pub fn push_fixed(buffer: &mut Vec<u8>, value: f64, decimals: usize) {
    // One instance per number of decimals, so that the divisions by 10^decimals are by
    // constants (a multiplication) rather than a 64-bit `div`.
    match decimals {
        0 => push_fixed_with::<0>(buffer, value),
        1 => push_fixed_with::<1>(buffer, value),
        2 => push_fixed_with::<2>(buffer, value),
        3 => push_fixed_with::<3>(buffer, value),
        4 => push_fixed_with::<4>(buffer, value),
        5 => push_fixed_with::<5>(buffer, value),
        6 => push_fixed_with::<6>(buffer, value),
        7 => push_fixed_with::<7>(buffer, value),
        8 => push_fixed_with::<8>(buffer, value),
        9 => push_fixed_with::<9>(buffer, value),
        10 => push_fixed_with::<10>(buffer, value),
        11 => push_fixed_with::<11>(buffer, value),
        _ => push_fixed_with::<12>(buffer, value),
    }
}

/// [`push_fixed`] with `DECIMALS` ≤ [`MAX_DECIMALS`] decimals.
#[inline]
fn push_fixed_with<const DECIMALS: usize>(buffer: &mut Vec<u8>, value: f64) {
    let scaled = value * POWERS_OF_TEN[DECIMALS];
    if scaled.is_nan() || scaled.abs() >= 4.0e15 {
        let text = format!("{value:.DECIMALS$}");
        let negative_zero =
            text.starts_with('-') && text[1..].bytes().all(|byte| byte == b'0' || byte == b'.');
        buffer.extend_from_slice(&text.as_bytes()[usize::from(negative_zero)..]);
        return;
    }
    // Round half away from zero, as `f64::round`, by truncating `|x| + 0.5`; through i64, whose
    // conversion is one instruction where `round` and the u64 conversion are several.
    let magnitude = (scaled.abs() + 0.5) as i64 as u64;
    let negative = scaled < 0.0 && magnitude != 0;
    let unit = INTEGER_POWERS_OF_TEN[DECIMALS];
    let (mut integer, mut fraction) = (magnitude / unit, magnitude % unit);
    let integer_digits =
        1 + INTEGER_POWERS_OF_TEN[1..].iter().take_while(|&&power| integer >= power).count();
    let length =
        usize::from(negative) + integer_digits + if DECIMALS > 0 { DECIMALS + 1 } else { 0 };
    // < 4e15 has at most 16 integer digits: 1 + 16 + 1 + 12 = 30 bytes fit in 32.
    let mut digits = [0u8; 32];
    let mut at = length;
    let mut left = DECIMALS;
    while left >= 2 {
        let pair = (fraction % 100) as usize * 2;
        fraction /= 100;
        at -= 2;
        digits[at..at + 2].copy_from_slice(&DIGIT_PAIRS[pair..pair + 2]);
        left -= 2;
    }
    if left == 1 {
        at -= 1;
        digits[at] = b'0' + (fraction % 10) as u8;
    }
    if DECIMALS > 0 {
        at -= 1;
        digits[at] = b'.';
    }
    while integer >= 100 {
        let pair = (integer % 100) as usize * 2;
        integer /= 100;
        at -= 2;
        digits[at..at + 2].copy_from_slice(&DIGIT_PAIRS[pair..pair + 2]);
    }
    if integer >= 10 {
        let pair = integer as usize * 2;
        at -= 2;
        digits[at..at + 2].copy_from_slice(&DIGIT_PAIRS[pair..pair + 2]);
    } else {
        at -= 1;
        digits[at] = b'0' + integer as u8;
    }
    if negative {
        at -= 1;
        digits[at] = b'-';
    }
    debug_assert_eq!(at, 0, "the length was counted right");
    buffer.extend_from_slice(&digits);
    buffer.truncate(buffer.len() - (digits.len() - length));
}

/// Rows are gathered in the writer's own buffer and handed to the output in chunks of about this
/// many bytes: one copy per byte instead of two (row buffer, then `BufWriter`).
pub const FLUSH_AT: usize = 1 << 16;

/// Writes samples as a path CSV; rows reach the output in chunks of [`FLUSH_AT`] bytes and at
/// [`PathCsvWriter::finish`], which must be called.
#[derive(Debug)]
pub struct PathCsvWriter<W: Write> {
    out: W,
    decimals: usize,
    events: bool,
    /// Rows not yet handed to `out`.
    row: Vec<u8>,
}

impl<W: Write> PathCsvWriter<W> {
    /// A writer with `decimals` decimals for every number, and the `gripper` column when
    /// `events`; writes the header at once.
    pub fn new(mut out: W, decimals: usize, events: bool) -> io::Result<Self> {
        out.write_all(PATH_HEADER.as_bytes())?;
        out.write_all(if events { b",gripper\n" } else { b"\n" })?;
        Ok(PathCsvWriter { out, decimals, events, row: Vec::with_capacity(FLUSH_AT + 512) })
    }

    /// Writes one sample.
    pub fn write(&mut self, sample: &CartesianSample) -> io::Result<()> {
        push_fixed(&mut self.row, sample.t, self.decimals);
        for value in sample.pose {
            self.row.push(b',');
            push_fixed(&mut self.row, value, self.decimals);
        }
        if self.events {
            self.row.extend_from_slice(if sample.gripper { b",1" } else { b",0" });
        }
        self.row.push(b'\n');
        if self.row.len() >= FLUSH_AT {
            self.out.write_all(&self.row)?;
            self.row.clear();
        }
        Ok(())
    }

    /// Writes the rows still buffered, flushes and returns the underlying writer.
    pub fn finish(mut self) -> io::Result<W> {
        self.out.write_all(&self.row)?;
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

    fn fixed(value: f64, decimals: usize) -> String {
        let mut buffer = Vec::new();
        push_fixed(&mut buffer, value, decimals);
        String::from_utf8(buffer).unwrap()
    }

    #[test]
    fn fixed_agrees_with_format() {
        for value in
            [0.0, 1.0, -1.5, 123.456789, -0.0004, 0.0005, 1e-7, 460.798724079689, 1e9, -42.0]
        {
            for decimals in [0, 3, 6] {
                let expected = format!("{value:.decimals$}");
                let expected = if expected.starts_with('-')
                    && expected[1..].bytes().all(|b| b == b'0' || b == b'.')
                {
                    expected[1..].to_owned()
                } else {
                    expected
                };
                assert_eq!(fixed(value, decimals), expected, "{value} with {decimals}");
            }
        }
        // Many values of every magnitude: equal to `format!` unless within noise of a tie.
        let mut state = 0x2545_f491_4f6c_dd1du64;
        for _ in 0..20000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let mantissa = (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
            let value = mantissa * 10f64.powi((state % 13) as i32);
            for decimals in [0, 3, 6] {
                let expected = format!("{value:.decimals$}");
                let got = fixed(value, decimals);
                let scaled = value.abs() * 10f64.powi(decimals as i32);
                let near_tie = (scaled - scaled.trunc() - 0.5).abs() < 1e-6;
                let zero = expected.trim_start_matches('-').bytes().all(|b| b == b'0' || b == b'.');
                if !near_tie && !zero {
                    assert_eq!(got, expected, "{value} with {decimals}");
                }
            }
        }
        assert_eq!(fixed(-0.0000001, 6), "0.000000");
        assert_eq!(fixed(1e300, 2).len(), 304);
    }

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
