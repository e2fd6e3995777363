//! Numeric comparison of two outputs of the same kind — joint or path CSVs, inter-files — within
//! a tolerance, for golden-file regression checks (`biscara diff`, and the project's own tests).
//!
//! CSV files must have the same header; fields that parse as numbers in both files are equal when
//! they differ by at most the tolerance, other fields when they are the same text. JSON Lines are
//! compared value by value with the same rule for numbers. Both files are read line by line:
//! memory does not grow with their length.
//!
//! ```
//! use biscara_diff::{DiffOptions, diff};
//!
//! let a = "t_s,x_mm\n0.000000,1.000000\n";
//! let b = "t_s,x_mm\n0.000000,1.0000004\n";
//! let report = diff(a.as_bytes(), b.as_bytes(), DiffOptions { tolerance: 1e-6 })?;
//! assert!(report.is_equal());
//! # Ok::<(), biscara_diff::DiffError>(())
//! ```

use std::fmt;
use std::io::{self, BufRead};

use serde_json::Value;

/// Settings of a comparison.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DiffOptions {
    /// Largest absolute difference of two numbers that still counts as equal.
    pub tolerance: f64,
}

impl Default for DiffOptions {
    /// A tolerance of 1e-6.
    fn default() -> Self {
        DiffOptions { tolerance: 1e-6 }
    }
}

/// Which of the two inputs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// The first file.
    A,
    /// The second file.
    B,
}

impl fmt::Display for Side {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Side::A => "A",
            Side::B => "B",
        })
    }
}

/// The first place where the two inputs differ.
#[derive(Debug, Clone, PartialEq)]
pub struct Difference {
    /// 1-based line in both files.
    pub line: usize,
    /// The column (CSV header name) or JSON path (`end[1]`) that differs; `<row>` when one file
    /// has a line the other lacks or the rows have different numbers of fields.
    pub column: String,
    /// The value in A (`<none>` when A has no such line).
    pub a: String,
    /// The value in B (`<none>` when B has no such line).
    pub b: String,
}

/// The outcome of a comparison.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct DiffReport {
    /// Data lines compared (the longer file's count).
    pub rows: usize,
    /// Data lines with at least one difference.
    pub differing_rows: usize,
    /// The first difference.
    pub first: Option<Difference>,
    /// The largest numeric difference seen (including those within the tolerance).
    pub largest_difference: f64,
}

impl DiffReport {
    /// Whether every value agrees within the tolerance.
    pub fn is_equal(&self) -> bool {
        self.differing_rows == 0
    }
}

impl DiffReport {
    /// The verdict with the inputs named `a` and `b`: their agreement when no value differs by
    /// more than `tolerance`, else the first difference.
    pub fn verdict(&self, a: &str, b: &str, tolerance: f64) -> Result<Agreement, Box<Mismatch>> {
        match &self.first {
            None => Ok(Agreement { tolerance, rows: self.rows, largest: self.largest_difference }),
            Some(first) => Err(Box::new(Mismatch {
                a: a.to_owned(),
                b: b.to_owned(),
                first: first.clone(),
                differing_rows: self.differing_rows,
                rows: self.rows,
                tolerance,
            })),
        }
    }
}

/// Two inputs that agree: `equal within TOL: N rows, largest difference X`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Agreement {
    /// The tolerance compared within.
    pub tolerance: f64,
    /// Data lines compared.
    pub rows: usize,
    /// The largest numeric difference seen.
    pub largest: f64,
}

impl fmt::Display for Agreement {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "equal within {}: {} rows, largest difference {:e}",
            self.tolerance, self.rows, self.largest
        )
    }
}

/// Two named inputs that differ beyond the tolerance: where first, and in how many rows.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error(
    "{b}:{}: `{}` differs: {a} has {}, {b} has {}; {differing_rows} of {rows} rows differ \
     (tolerance {tolerance})",
    first.line, first.column, first.a, first.b
)]
pub struct Mismatch {
    /// The name of the expected input.
    pub a: String,
    /// The name of the input checked.
    pub b: String,
    /// The first difference.
    pub first: Difference,
    /// Data lines with at least one difference.
    pub differing_rows: usize,
    /// Data lines compared.
    pub rows: usize,
    /// The tolerance compared within.
    pub tolerance: f64,
}

/// Inputs that cannot be compared.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum DiffError {
    /// Occurs when reading an input fails (including text that is not UTF-8).
    #[error("{side}:{line}: {source}")]
    Io {
        /// Which input.
        side: Side,
        /// 1-based line being read.
        line: usize,
        /// The I/O error.
        source: io::Error,
    },
    /// Occurs when the inputs are not of the same kind: different CSV headers, or CSV against
    /// JSON Lines.
    #[error("the files are of different kinds: A starts `{a}`, B starts `{b}`")]
    Kind {
        /// A's first line (shortened).
        a: String,
        /// B's first line (shortened).
        b: String,
    },
    /// Occurs when a line of a JSON Lines input is not JSON.
    #[error("{side}:{line}: not JSON: {message}")]
    Json {
        /// Which input.
        side: Side,
        /// 1-based line.
        line: usize,
        /// The parser's message.
        message: String,
    },
}

impl DiffError {
    /// The error's message with the inputs named `a` and `b`: `NAME:LINE: …` for a fault of
    /// one input, `A and B: …` for the two together.
    pub fn named(&self, a: &str, b: &str) -> String {
        let name = |side: &Side| if *side == Side::A { a } else { b };
        match self {
            DiffError::Io { side, line, source } => format!("{}:{line}: {source}", name(side)),
            DiffError::Json { side, line, message } => {
                format!("{}:{line}: not JSON: {message}", name(side))
            }
            other => format!("{a} and {b}: {other}"),
        }
    }
}

/// Compares two inputs line by line.
pub fn diff(
    a: impl BufRead,
    b: impl BufRead,
    options: DiffOptions,
) -> Result<DiffReport, DiffError> {
    let mut a = Lines { reader: a, side: Side::A, line: 0, text: String::new() };
    let mut b = Lines { reader: b, side: Side::B, line: 0, text: String::new() };
    let mut report = DiffReport::default();
    let (first_a, first_b) = (a.next()?, b.next()?);
    let shorten = |text: Option<&str>| text.unwrap_or("").chars().take(60).collect::<String>();
    let json = first_a.as_deref().is_some_and(|t| t.starts_with('{'));
    if json != first_b.as_deref().is_some_and(|t| t.starts_with('{'))
        || (!json && first_a != first_b)
    {
        return Err(DiffError::Kind {
            a: shorten(first_a.as_deref()),
            b: shorten(first_b.as_deref()),
        });
    }
    let header: Vec<String> = if json {
        Vec::new()
    } else {
        first_a.as_deref().unwrap_or("").split(',').map(str::to_owned).collect()
    };
    let mut pending = if json { Some((first_a, first_b)) } else { None };
    loop {
        let (row_a, row_b) = match pending.take() {
            Some(rows) => rows,
            None => (a.next()?, b.next()?),
        };
        let line = a.line.max(b.line);
        let mut first: Option<Difference> = None;
        match (&row_a, &row_b) {
            (None, None) => break,
            (Some(text_a), Some(text_b)) => {
                if json {
                    let parse = |side, text: &str| {
                        serde_json::from_str::<Value>(text).map_err(|err| DiffError::Json {
                            side,
                            line,
                            message: err.to_string(),
                        })
                    };
                    let (value_a, value_b) = (parse(Side::A, text_a)?, parse(Side::B, text_b)?);
                    compare_json(
                        &value_a,
                        &value_b,
                        String::new(),
                        line,
                        options,
                        &mut report,
                        &mut first,
                    );
                } else {
                    compare_csv(text_a, text_b, &header, line, options, &mut report, &mut first);
                }
            }
            (a_row, b_row) => {
                first = Some(Difference {
                    line,
                    column: "<row>".to_owned(),
                    a: a_row.clone().unwrap_or_else(|| "<none>".to_owned()),
                    b: b_row.clone().unwrap_or_else(|| "<none>".to_owned()),
                });
            }
        }
        report.rows += 1;
        if let Some(difference) = first {
            report.differing_rows += 1;
            report.first.get_or_insert(difference);
        }
    }
    Ok(report)
}

fn compare_numbers(a: f64, b: f64, options: DiffOptions, report: &mut DiffReport) -> bool {
    let difference = (a - b).abs();
    if difference.is_finite() {
        report.largest_difference = report.largest_difference.max(difference);
    }
    difference <= options.tolerance || (a == b)
}

#[allow(clippy::too_many_arguments)]
fn compare_csv(
    a: &str,
    b: &str,
    header: &[String],
    line: usize,
    options: DiffOptions,
    report: &mut DiffReport,
    first: &mut Option<Difference>,
) {
    let (fields_a, fields_b): (Vec<&str>, Vec<&str>) =
        (a.split(',').collect(), b.split(',').collect());
    if fields_a.len() != fields_b.len() {
        *first =
            Some(Difference { line, column: "<row>".to_owned(), a: a.to_owned(), b: b.to_owned() });
        return;
    }
    for (index, (field_a, field_b)) in fields_a.iter().zip(&fields_b).enumerate() {
        let equal = match (field_a.trim().parse::<f64>(), field_b.trim().parse::<f64>()) {
            (Ok(x), Ok(y)) => compare_numbers(x, y, options, report),
            _ => field_a == field_b,
        };
        if !equal && first.is_none() {
            let column =
                header.get(index).cloned().unwrap_or_else(|| format!("column {}", index + 1));
            *first = Some(Difference {
                line,
                column,
                a: (*field_a).to_owned(),
                b: (*field_b).to_owned(),
            });
        }
    }
}

fn compare_json(
    a: &Value,
    b: &Value,
    path: String,
    line: usize,
    options: DiffOptions,
    report: &mut DiffReport,
    first: &mut Option<Difference>,
) {
    let mut differ = |path: String| {
        if first.is_none() {
            *first = Some(Difference { line, column: path, a: a.to_string(), b: b.to_string() });
        }
    };
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (x.as_f64().unwrap_or(f64::NAN), y.as_f64().unwrap_or(f64::NAN));
            if !compare_numbers(x, y, options, report) {
                differ(path);
            }
        }
        (Value::Array(xs), Value::Array(ys)) if xs.len() == ys.len() => {
            for (index, (x, y)) in xs.iter().zip(ys).enumerate() {
                compare_json(x, y, format!("{path}[{index}]"), line, options, report, first);
            }
        }
        (Value::Object(xs), Value::Object(ys))
            if xs.len() == ys.len() && xs.keys().all(|key| ys.contains_key(key)) =>
        {
            for (key, x) in xs {
                let child = if path.is_empty() { key.clone() } else { format!("{path}.{key}") };
                compare_json(x, &ys[key], child, line, options, report, first);
            }
        }
        _ if a == b => {}
        _ => differ(if path.is_empty() { "<row>".to_owned() } else { path }),
    }
}

/// Non-blank lines of one input, with their 1-based numbers.
struct Lines<R> {
    reader: R,
    side: Side,
    line: usize,
    text: String,
}

impl<R: BufRead> Lines<R> {
    fn next(&mut self) -> Result<Option<String>, DiffError> {
        loop {
            self.text.clear();
            self.line += 1;
            let read = biscara_text::read_bounded_line(&mut self.reader, &mut self.text)
                .map_err(|source| DiffError::Io { side: self.side, line: self.line, source })?;
            if !read {
                return Ok(None);
            }
            let trimmed = self.text.trim_end_matches(['\n', '\r']);
            if !trimmed.trim().is_empty() {
                return Ok(Some(trimmed.to_owned()));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(a: &str, b: &str, tolerance: f64) -> DiffReport {
        diff(a.as_bytes(), b.as_bytes(), DiffOptions { tolerance }).expect("comparable")
    }

    #[test]
    fn the_verdict_names_the_inputs() {
        let header = "t_s,x_mm\n";
        let equal = run(&format!("{header}0,1\n"), &format!("{header}0,1.5\n"), 1.0);
        let agreement = equal.verdict("a.csv", "b.csv", 1.0).unwrap();
        assert_eq!(agreement.to_string(), "equal within 1: 1 rows, largest difference 5e-1");
        let differ = run(&format!("{header}0,1\n1,2\n"), &format!("{header}0,1\n1,2.5\n"), 1e-6);
        let mismatch = differ.verdict("a.csv", "b.csv", 1e-6).unwrap_err();
        assert_eq!(
            mismatch.to_string(),
            "b.csv:3: `x_mm` differs: a.csv has 2, b.csv has 2.5; 1 of 2 rows differ (tolerance \
             0.000001)"
        );
        let err = diff("{\n".as_bytes(), "{\n".as_bytes(), DiffOptions::default()).unwrap_err();
        assert!(err.named("a.jsonl", "b.jsonl").starts_with("a.jsonl:1: not JSON: "), "{err}");
        let err = diff("a\n".as_bytes(), "b\n".as_bytes(), DiffOptions::default()).unwrap_err();
        assert!(err.named("a", "b").starts_with("a and b: the files are of different kinds"));
    }

    #[test]
    fn csv_within_and_beyond_the_tolerance() {
        let a = "t_s,x_mm\n0.000,1.000\n0.001,2.000\n0.002,3.000\n";
        let b = "t_s,x_mm\n0.000,1.000\n0.001,2.010\n0.002,3.020\n";
        assert!(run(a, b, 0.05).is_equal());
        let report = run(a, b, 0.001);
        assert_eq!(report.differing_rows, 2);
        assert_eq!(
            report.first,
            Some(Difference {
                line: 3,
                column: "x_mm".into(),
                a: "2.000".into(),
                b: "2.010".into()
            })
        );
        assert!((report.largest_difference - 0.02).abs() < 1e-12);
    }

    #[test]
    fn missing_rows_count_as_differences() {
        let report = run("t\n1\n2\n", "t\n1\n", 1e-6);
        assert_eq!(report.differing_rows, 1);
        assert_eq!(report.first.map(|d| (d.line, d.b)), Some((3, "<none>".to_owned())));
    }

    #[test]
    fn json_lines_compare_numbers_by_value() {
        let a = "{\"line\":3,\"kind\":\"rapid\",\"end\":[0.0,400.0,100.0,0.0]}\n";
        let b = "{\"kind\":\"rapid\",\"line\":3,\"end\":[0,400.0000001,100,0]}\n";
        assert!(run(a, b, 1e-6).is_equal());
        let c = "{\"line\":3,\"kind\":\"linear\",\"end\":[0,400,100,0]}\n";
        let report = run(a, c, 1e-6);
        assert_eq!(
            report.first.map(|d| (d.column, d.a, d.b)),
            Some(("kind".to_owned(), "\"rapid\"".to_owned(), "\"linear\"".to_owned()))
        );
        let d = "{\"line\":3,\"kind\":\"rapid\",\"end\":[0,401,100,0]}\n";
        assert_eq!(run(a, d, 1e-6).first.map(|d| d.column), Some("end[1]".to_owned()));
    }

    #[test]
    fn different_kinds_are_an_error() {
        let err = diff("t,x\n".as_bytes(), "t,y\n".as_bytes(), DiffOptions::default()).unwrap_err();
        assert!(err.to_string().contains("different kinds"), "{err}");
        let err = diff("t,x\n".as_bytes(), "{}\n".as_bytes(), DiffOptions::default()).unwrap_err();
        assert!(matches!(err, DiffError::Kind { .. }));
        let err = diff("{\n".as_bytes(), "{}\n".as_bytes(), DiffOptions::default()).unwrap_err();
        assert!(matches!(err, DiffError::Json { side: Side::A, line: 1, .. }), "{err:?}");
    }
}
