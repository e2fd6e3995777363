//! The design CSV: one row per design, written as the sweep goes, read back for pictures and
//! merged from shards.

use std::io::{BufRead, Write};

use biscara_robot::Rectangle;

use crate::{CsvFault, Design, DesignError, DesignStatus, Evaluation, MergeFault};

/// The columns every design CSV has, in order (`task_ok` follows when a task is given, then
/// `time_s` when programs are timed, then `cycle_s` when the Adept cycle is timed).
pub const COLUMNS: [&str; 12] = [
    "index",
    "l1",
    "l2",
    "base",
    "area_mm2",
    "rect_w_mm",
    "rect_h_mm",
    "rect_x0_mm",
    "rect_y0_mm",
    "gci",
    "lci_min",
    "status",
];

/// Which optional columns a design CSV has.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Columns {
    /// `task_ok`: a task rectangle was given.
    pub task: bool,
    /// `time_s`: programs were timed.
    pub time: bool,
    /// `cycle_s`: the Adept cycle was timed (`--objective cycle`).
    pub cycle: bool,
}

impl Columns {
    fn count(self) -> usize {
        COLUMNS.len() + usize::from(self.task) + usize::from(self.time) + usize::from(self.cycle)
    }
}

/// The header line (without its newline).
pub fn header(columns: Columns) -> String {
    let mut header = COLUMNS.join(",");
    if columns.task {
        header.push_str(",task_ok");
    }
    if columns.time {
        header.push_str(",time_s");
    }
    if columns.cycle {
        header.push_str(",cycle_s");
    }
    header
}

/// Writes one row (with its newline) with `columns`: lengths as given, the area and rectangle to
/// 0.001 mm, the indices to 1e-6, the time to 1 ms (empty when the programs cannot run).
pub fn write_row(
    out: &mut dyn Write,
    columns: Columns,
    evaluation: &Evaluation,
) -> std::io::Result<()> {
    let Design { index, l1, l2, base } = evaluation.design;
    let (w, h, x0, y0) = evaluation
        .rectangle
        .map_or((0.0, 0.0, 0.0, 0.0), |r| (r.width(), r.height(), r.min[0], r.min[1]));
    write!(
        out,
        "{index},{l1},{l2},{base},{:.3},{w:.3},{h:.3},{x0:.3},{y0:.3},{:.6},{:.6},{}",
        evaluation.area_mm2,
        evaluation.gci,
        evaluation.lci_min,
        evaluation.status.as_str()
    )?;
    if columns.task {
        write!(out, ",{}", u8::from(evaluation.task_ok == Some(true)))?;
    }
    for (shown, value) in [(columns.time, evaluation.time_s), (columns.cycle, evaluation.cycle_s)] {
        match value {
            Some(seconds) if shown => write!(out, ",{seconds:.3}")?,
            _ if shown => write!(out, ",")?,
            _ => {}
        }
    }
    writeln!(out)
}

/// Reads one data line of a design CSV with `columns` (`line` from 1, for errors).
pub fn parse_row(text: &str, line: usize, columns: Columns) -> Result<Evaluation, DesignError> {
    let fail = |fault: CsvFault| DesignError::Csv { line, fault };
    let fields: Vec<&str> = text.split(',').collect();
    let expected = columns.count();
    if fields.len() != expected {
        return Err(fail(CsvFault::FieldCount { found: fields.len(), expected }));
    }
    let number = |k: usize| -> Result<f64, DesignError> {
        let value: f64 = fields[k].trim().parse().map_err(|_| {
            fail(CsvFault::NotANumber { column: column(k), text: fields[k].into() })
        })?;
        if value.is_finite() {
            Ok(value)
        } else {
            Err(fail(CsvFault::NotFinite { column: column(k), text: fields[k].into() }))
        }
    };
    let index: u64 =
        fields[0].trim().parse().map_err(|_| fail(CsvFault::Index { text: fields[0].into() }))?;
    let status = DesignStatus::parse(fields[11].trim())
        .ok_or_else(|| fail(CsvFault::Status { text: fields[11].into() }))?;
    let (w, h, x0, y0) = (number(5)?, number(6)?, number(7)?, number(8)?);
    let task_ok = if columns.task {
        match fields[12].trim() {
            "1" => Some(true),
            "0" => Some(false),
            other => return Err(fail(CsvFault::TaskOk { text: other.into() })),
        }
    } else {
        None
    };
    // The optional seconds: time_s, then cycle_s, each empty where not known.
    let seconds = |shown: bool, k: usize| -> Result<Option<f64>, DesignError> {
        if shown && !fields[k].trim().is_empty() { number(k).map(Some) } else { Ok(None) }
    };
    let cycle_s = seconds(columns.cycle, expected - 1)?;
    let time_s = seconds(columns.time, expected - 1 - usize::from(columns.cycle))?;
    Ok(Evaluation {
        design: Design { index, l1: number(1)?, l2: number(2)?, base: number(3)? },
        status,
        area_mm2: number(4)?,
        rectangle: (status == DesignStatus::Ok)
            .then_some(Rectangle { min: [x0, y0], max: [x0 + w, y0 + h] }),
        gci: number(9)?,
        lci_min: number(10)?,
        task_ok,
        time_s,
        cycle_s,
    })
}

fn column(k: usize) -> &'static str {
    COLUMNS.get(k).copied().unwrap_or("time_s")
}

/// The columns of a design CSV whose header is `line`, if it is one.
pub fn read_header(line: &str) -> Option<Columns> {
    (0..8)
        .map(|bits| Columns { task: bits & 1 != 0, time: bits & 2 != 0, cycle: bits & 4 != 0 })
        .find(|&columns| header(columns) == line)
}

/// The rows of a design CSV, one at a time (the header checked first).
pub struct RowReader<R> {
    input: R,
    line: usize,
    columns: Columns,
    buffer: String,
}

impl<R: BufRead> RowReader<R> {
    /// Reads the header of `input`.
    pub fn new(mut input: R) -> Result<RowReader<R>, DesignError> {
        let mut buffer = String::new();
        input.read_line(&mut buffer)?;
        let columns = read_header(buffer.trim_end()).ok_or_else(|| DesignError::Csv {
            line: 1,
            fault: CsvFault::Header { expected: header(Columns::default()) },
        })?;
        Ok(RowReader { input, line: 1, columns, buffer })
    }

    /// The CSV's optional columns.
    pub fn columns(&self) -> Columns {
        self.columns
    }

    /// The next row and its line, its text kept in [`RowReader::text`].
    fn next_row(&mut self) -> Option<Result<(usize, Evaluation), DesignError>> {
        self.buffer.clear();
        match self.input.read_line(&mut self.buffer) {
            Ok(0) => None,
            Ok(_) => {
                self.line += 1;
                let text = self.buffer.trim_end_matches(['\n', '\r']);
                Some(parse_row(text, self.line, self.columns).map(|row| (self.line, row)))
            }
            Err(err) => Some(Err(err.into())),
        }
    }

    /// The text of the row last read, without its newline.
    pub fn text(&self) -> &str {
        self.buffer.trim_end_matches(['\n', '\r'])
    }
}

impl<R: BufRead> Iterator for RowReader<R> {
    type Item = Result<Evaluation, DesignError>;

    fn next(&mut self) -> Option<Self::Item> {
        self.next_row().map(|row| row.map(|(_, evaluation)| evaluation))
    }
}

/// Joins the CSVs of a sharded sweep into the CSV the whole sweep writes: rows by design index,
/// streaming (one row per input in memory). Every input needs the same header and rising
/// indices; a design in two files, or in none below the largest, is an error. Returns how many
/// rows were written.
pub fn merge(
    inputs: Vec<(String, Box<dyn BufRead>)>,
    out: &mut dyn Write,
) -> Result<u64, DesignError> {
    let mut readers = Vec::with_capacity(inputs.len());
    let mut columns = None;
    for (name, input) in inputs {
        let reader = RowReader::new(input).map_err(|err| in_file(&name, err))?;
        if columns.is_some_and(|c| c != reader.columns()) {
            return Err(DesignError::Merge {
                file: name,
                line: 1,
                fault: MergeFault::HeaderDiffers,
            });
        }
        columns = Some(reader.columns());
        readers.push((name, reader));
    }
    writeln!(out, "{}", header(columns.unwrap_or_default()))?;
    // The next row of each input: (index, line, text).
    let mut heads: Vec<Option<(u64, usize, String)>> = Vec::with_capacity(readers.len());
    for (name, reader) in &mut readers {
        heads.push(advance(name, reader, None)?);
    }
    let mut expected = 0u64;
    loop {
        let next = heads
            .iter()
            .enumerate()
            .filter_map(|(k, head)| head.as_ref().map(|(index, ..)| (*index, k)))
            .min();
        let Some((index, k)) = next else { break };
        let (name, reader) = &mut readers[k];
        let (_, line, text) = heads[k].take().unwrap_or_default();
        if index < expected {
            return Err(DesignError::Merge {
                file: name.clone(),
                line,
                fault: MergeFault::Repeated { index },
            });
        }
        if index > expected {
            return Err(DesignError::Missing { index: expected });
        }
        writeln!(out, "{text}")?;
        expected += 1;
        heads[k] = advance(name, reader, Some(index))?;
    }
    Ok(expected)
}

fn in_file(name: &str, err: DesignError) -> DesignError {
    match err {
        DesignError::Csv { line, fault } => {
            DesignError::Merge { file: name.to_owned(), line, fault: fault.into() }
        }
        other => other,
    }
}

/// The next row of one merge input, checked to rise above `previous`.
fn advance<R: BufRead>(
    name: &str,
    reader: &mut RowReader<R>,
    previous: Option<u64>,
) -> Result<Option<(u64, usize, String)>, DesignError> {
    let Some(row) = reader.next_row() else { return Ok(None) };
    let (line, row) = row.map_err(|err| in_file(name, err))?;
    let index = row.design.index;
    if previous.is_some_and(|p| index <= p) {
        return Err(DesignError::Merge {
            file: name.to_owned(),
            line,
            fault: MergeFault::OutOfOrder { index, previous: previous.unwrap_or(0) },
        });
    }
    Ok(Some((index, line, reader.text().to_owned())))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn csv(rows: &[u64]) -> String {
        let mut text = header(Columns::default()) + "\n";
        for &index in rows {
            text.push_str(&format!(
                "{index},1,2,3,4.000,0.000,0.000,0.000,0.000,0.000000,0.000000,empty\n"
            ));
        }
        text
    }

    fn merged(files: &[String]) -> Result<String, DesignError> {
        let inputs = files
            .iter()
            .enumerate()
            .map(|(k, text)| {
                (
                    format!("part{k}.csv"),
                    Box::new(std::io::Cursor::new(text.clone())) as Box<dyn BufRead>,
                )
            })
            .collect();
        let mut out = Vec::new();
        merge(inputs, &mut out)?;
        Ok(String::from_utf8(out).unwrap())
    }

    #[test]
    fn the_optional_seconds_read_back() {
        for bits in 0..8 {
            let columns =
                Columns { task: bits & 1 != 0, time: bits & 2 != 0, cycle: bits & 4 != 0 };
            let line = header(columns);
            assert_eq!(read_header(&line), Some(columns), "{line}");
            let evaluation = Evaluation {
                design: Design { index: 4, l1: 200.0, l2: 260.0, base: 150.0 },
                status: DesignStatus::Ok,
                area_mm2: 1000.0,
                rectangle: Some(Rectangle { min: [-10.0, 200.0], max: [10.0, 230.0] }),
                gci: 0.5,
                lci_min: 0.25,
                task_ok: columns.task.then_some(true),
                time_s: columns.time.then_some(12.5),
                cycle_s: None,
            };
            for cycle_s in [None, Some(0.875)] {
                let evaluation =
                    Evaluation { cycle_s: cycle_s.filter(|_| columns.cycle), ..evaluation };
                let mut row = Vec::new();
                write_row(&mut row, columns, &evaluation).unwrap();
                let text = String::from_utf8(row).unwrap();
                assert_eq!(parse_row(text.trim_end(), 2, columns).unwrap(), evaluation, "{text}");
            }
        }
    }

    #[test]
    fn shards_merge_in_design_order() {
        let whole = merged(&[csv(&[0, 3, 6]), csv(&[1, 4]), csv(&[2, 5])]).unwrap();
        assert_eq!(whole, csv(&[0, 1, 2, 3, 4, 5, 6]));
    }

    #[test]
    fn merging_finds_missing_repeated_and_broken_rows() {
        let err = merged(&[csv(&[0, 2]), csv(&[3])]).unwrap_err().to_string();
        assert_eq!(err, "design 1 is in none of the files: a shard is missing");
        let err = merged(&[csv(&[0, 1]), csv(&[1])]).unwrap_err().to_string();
        assert_eq!(err, "part1.csv:2: design 1 is in another file too");
        let err = merged(&[csv(&[0, 1, 1])]).unwrap_err().to_string();
        assert_eq!(err, "part0.csv:4: design 1 follows design 1: rows out of order or repeated");
        let err = merged(&["l1,l2\n1,2\n".to_owned()]).unwrap_err().to_string();
        assert!(err.starts_with("part0.csv:1: not a design CSV"), "{err}");
        let broken = csv(&[0]).replace("4.000", "NaN");
        let err = merged(&[broken]).unwrap_err().to_string();
        assert_eq!(err, "part0.csv:2: area_mm2 'NaN' is not finite");
        let short = header(Columns::default()) + "\n0,1,2\n";
        let err = merged(&[short]).unwrap_err().to_string();
        assert_eq!(err, "part0.csv:2: 3 fields, the header has 12");
    }
}
