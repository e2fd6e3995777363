//! LinuxCNC's tool table (`.tbl`): one tool a line, `T1 P1 Z25.4 D6.35 ;comment`.
//!
//! Each line holds words — `T` tool number, `P` pocket, `X Y Z A B C U V W` offsets, `D`
//! diameter, `I` front angle, `J` back angle, `Q` orientation — in any order, and a comment
//! after `;`. Blank and comment-only lines are skipped. Values are in the machine's units,
//! which for this robot are millimetres (and degrees for C). The offsets of the axes this robot
//! has not (A B U V W) are read and ignored.
//!
//! Where it differs from LinuxCNC, on purpose: LinuxCNC skips a line it cannot read with a
//! message on stderr and goes on; here a bad line is an error (`FILE:LINE:COL: what is wrong`),
//! as is a tool listed twice, and LinuxCNC's old numbers-only format is refused.

use std::fmt;
use std::io::BufRead;
use std::path::Path;

use crate::environment::Environment;

/// One tool of the table: its number, pocket, offsets and diameter.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ToolEntry {
    /// The tool number (`T`).
    pub tool: u32,
    /// The pocket the tool sits in (`P`; 0 when not given).
    pub pocket: u32,
    /// The offsets `[x, y, z, c]` (`X Y Z C`): millimetres, degrees. Z is the tool's length.
    pub offset: [f64; 4],
    /// The diameter (`D`), mm.
    pub diameter: f64,
    /// The front angle (`I`), degrees (lathe tools; stored, unused).
    pub front_angle: f64,
    /// The back angle (`J`), degrees (lathe tools; stored, unused).
    pub back_angle: f64,
    /// The orientation (`Q`; lathe tools; stored, unused).
    pub orientation: i32,
}

/// A tool table: the tools in the order the file lists them.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ToolTable {
    entries: Vec<ToolEntry>,
}

/// A tool table that cannot be read: where and why.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ToolTableError {
    /// The file's name as given.
    pub file: String,
    /// 1-based line (0 when the file cannot be opened).
    pub line: usize,
    /// 1-based column.
    pub column: usize,
    /// What is wrong.
    pub message: String,
}

impl fmt::Display for ToolTableError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.line == 0 {
            write!(f, "{}: {}", self.file, self.message)
        } else {
            write!(f, "{}:{}:{}: {}", self.file, self.line, self.column, self.message)
        }
    }
}

impl std::error::Error for ToolTableError {}

/// The longest line read (LinuxCNC's `CANON_TOOL_ENTRY_LEN` is 256).
const MAX_LINE: usize = 1024;

impl ToolTable {
    /// An empty table.
    pub fn new() -> ToolTable {
        ToolTable::default()
    }

    /// Reads the table in file `path`, opened in `environment`.
    pub fn read(environment: &dyn Environment, path: &Path) -> Result<ToolTable, ToolTableError> {
        let name = path.display().to_string();
        let file = environment.open(path).map_err(|err| ToolTableError {
            file: name.clone(),
            line: 0,
            column: 0,
            message: format!("cannot read the tool table: {err}"),
        })?;
        ToolTable::parse(file, &name)
    }

    /// Reads a table from `reader`; `name` names it in errors.
    pub fn parse(mut reader: impl BufRead, name: &str) -> Result<ToolTable, ToolTableError> {
        let mut table = ToolTable::new();
        let mut buffer = Vec::new();
        let mut number = 0;
        loop {
            buffer.clear();
            number += 1;
            let fail = |column: usize, message: String| ToolTableError {
                file: name.to_owned(),
                line: number,
                column,
                message,
            };
            let read = std::io::Read::take(&mut reader, MAX_LINE as u64 + 1)
                .read_until(b'\n', &mut buffer)
                .map_err(|err| fail(1, format!("cannot read the tool table: {err}")))?;
            if read == 0 {
                break;
            }
            if buffer.len() > MAX_LINE && buffer.last() != Some(&b'\n') {
                return Err(fail(MAX_LINE + 1, format!("line longer than {MAX_LINE} bytes")));
            }
            let line = buffer.strip_suffix(b"\n").unwrap_or(&buffer);
            let line = line.strip_suffix(b"\r").unwrap_or(line);
            if let Some(entry) =
                parse_line(line).map_err(|(column, message)| fail(column, message))?
            {
                if table.get(entry.tool).is_some() {
                    return Err(fail(
                        1,
                        format!("tool {} is listed twice in the tool table", entry.tool),
                    ));
                }
                table.entries.push(entry);
            }
        }
        Ok(table)
    }

    /// The tools, in the order of the file (then those G10 L1 added).
    pub fn entries(&self) -> &[ToolEntry] {
        &self.entries
    }

    /// Tool `tool`, if the table has it.
    pub fn get(&self, tool: u32) -> Option<&ToolEntry> {
        self.entries.iter().find(|entry| entry.tool == tool)
    }

    /// The diameter of tool `tool` (mm), if the table has it: what cutter compensation uses.
    pub fn diameter(&self, tool: u32) -> Option<f64> {
        self.get(tool).map(|entry| entry.diameter)
    }

    /// Tool `tool`, to change (G10 L1, L10, L11).
    pub(crate) fn get_mut(&mut self, tool: u32) -> Option<&mut ToolEntry> {
        self.entries.iter_mut().find(|entry| entry.tool == tool)
    }

    /// Adds a tool, or replaces the one with its number.
    pub fn insert(&mut self, entry: ToolEntry) {
        match self.get_mut(entry.tool) {
            Some(slot) => *slot = entry,
            None => self.entries.push(entry),
        }
    }
}

/// A word as shown in a message: control characters replaced, long words cut.
fn shown(token: &[u8]) -> String {
    let text: String = String::from_utf8_lossy(token)
        .chars()
        .map(|c| if c.is_control() { '\u{fffd}' } else { c })
        .collect();
    match text.char_indices().nth(24) {
        Some((end, _)) => format!("{}…", &text[..end]),
        None => text,
    }
}

/// One line: `Ok(None)` for a blank or comment line; `Err((column, message))`.
fn parse_line(line: &[u8]) -> Result<Option<ToolEntry>, (usize, String)> {
    let body = match line.iter().position(|&byte| byte == b';') {
        Some(end) => &line[..end],
        None => line,
    };
    let mut entry = ToolEntry::default();
    let mut tool = None;
    let mut seen = [false; 26];
    let mut at = 0;
    while at < body.len() {
        if body[at].is_ascii_whitespace() {
            at += 1;
            continue;
        }
        let start = at;
        while at < body.len() && !body[at].is_ascii_whitespace() {
            at += 1;
        }
        let token = &body[start..at];
        let column = start + 1;
        let letter = token[0].to_ascii_uppercase();
        if !letter.is_ascii_uppercase() {
            let shown = shown(token);
            return Err((
                column,
                if token[0].is_ascii_digit() || token[0] == b'-' {
                    format!(
                        "`{shown}`: a tool table word starts with a letter (T P X Y Z A B C U V \
                         W D I J Q); LinuxCNC's old numbers-only format is not read"
                    )
                } else {
                    format!("`{shown}` is not a tool table word (T P X Y Z A B C U V W D I J Q)")
                },
            ));
        }
        let slot = usize::from(letter - b'A');
        if seen[slot] {
            return Err((column, format!("{} given twice on one line", char::from(letter))));
        }
        seen[slot] = true;
        let text = std::str::from_utf8(&token[1..]).unwrap_or("");
        let integer = |what: &str| -> Result<i64, (usize, String)> {
            text.parse::<i64>().map_err(|_| {
                (column, format!("`{}`: the {what} must be a whole number", shown(token)))
            })
        };
        let real = || -> Result<f64, (usize, String)> {
            let shown = shown(token);
            match text.parse::<f64>() {
                Ok(value) if value.is_finite() && value.abs() <= 1e6 => Ok(value),
                Ok(_) => Err((column, format!("`{shown}` is out of range (±1e6)"))),
                Err(_) => {
                    Err((column, format!("`{shown}`: {} needs a number", char::from(letter))))
                }
            }
        };
        match letter {
            b'T' => {
                let value = integer("tool number")?;
                tool = Some(u32::try_from(value).map_err(|_| {
                    (column, format!("tool number {value} is out of range (0 to 4294967295)"))
                })?);
            }
            b'P' => {
                let value = integer("pocket")?;
                entry.pocket = u32::try_from(value)
                    .map_err(|_| (column, format!("pocket {value} is out of range (0 or more)")))?;
            }
            b'Q' => {
                let value = integer("orientation")?;
                entry.orientation = i32::try_from(value)
                    .ok()
                    .filter(|value| (0..=9).contains(value))
                    .ok_or((column, format!("orientation {value} is out of range (0 to 9)")))?;
            }
            b'X' => entry.offset[0] = real()?,
            b'Y' => entry.offset[1] = real()?,
            b'Z' => entry.offset[2] = real()?,
            b'C' => entry.offset[3] = real()?,
            b'A' | b'B' | b'U' | b'V' | b'W' => {
                real()?;
            }
            b'D' => {
                let value = real()?;
                if value < 0.0 {
                    return Err((column, format!("diameter {value} is negative")));
                }
                entry.diameter = value;
            }
            b'I' => entry.front_angle = real()?,
            b'J' => entry.back_angle = real()?,
            _ => {
                return Err((
                    column,
                    format!(
                        "`{}` is not a tool table word (T P X Y Z A B C U V W D I J Q)",
                        shown(token)
                    ),
                ));
            }
        }
    }
    if !seen.iter().any(|&seen| seen) {
        return Ok(None);
    }
    let Some(tool) = tool else {
        let first = body.iter().position(|byte| !byte.is_ascii_whitespace()).unwrap_or(0);
        return Err((first + 1, "tool line without a T word (tool number)".to_owned()));
    };
    entry.tool = tool;
    Ok(Some(entry))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<ToolTable, String> {
        ToolTable::parse(text.as_bytes(), "t.tbl").map_err(|err| err.to_string())
    }

    #[test]
    fn reads_linuxcnc_lines_and_comments() {
        let table = parse(
            "; header\n\nT1 P1 Z25.4 D6.35 ;end mill\r\nt2 p5 x1 z-3.5 d2 I10 J20 Q3 A1 W2\n   \n",
        )
        .unwrap();
        assert_eq!(table.entries().len(), 2);
        let one = table.get(1).unwrap();
        assert_eq!((one.pocket, one.offset, one.diameter), (1, [0.0, 0.0, 25.4, 0.0], 6.35));
        let two = table.get(2).unwrap();
        assert_eq!(two.offset, [1.0, 0.0, -3.5, 0.0]);
        assert_eq!((two.front_angle, two.back_angle, two.orientation), (10.0, 20.0, 3));
        assert_eq!(table.diameter(2), Some(2.0));
        assert_eq!(table.diameter(3), None);
    }

    #[test]
    fn bad_lines_name_line_and_column() {
        for (text, expected) in [
            ("T1 Z1\nT2 Z1.2.3\n", "t.tbl:2:4: `Z1.2.3`: Z needs a number"),
            ("T1 P1 K3\n", "t.tbl:1:7: `K3` is not a tool table word"),
            ("P1 Z3\n", "t.tbl:1:1: tool line without a T word"),
            ("T-1 Z3\n", "t.tbl:1:1: tool number -1 is out of range"),
            ("T1.5\n", "t.tbl:1:1: `T1.5`: the tool number must be a whole number"),
            ("T1\nT1 Z2\n", "t.tbl:2:1: tool 1 is listed twice"),
            ("1 1 0.5 0.25\n", "t.tbl:1:1: `1`: a tool table word starts with a letter"),
            ("T1 Z1 Z2\n", "t.tbl:1:7: Z given twice on one line"),
            ("T1 D-2\n", "t.tbl:1:4: diameter -2 is negative"),
            ("T1 Zinf\n", "t.tbl:1:4: `Zinf` is out of range"),
            ("T1 Z1e9\n", "t.tbl:1:4: `Z1e9` is out of range"),
            ("T1 Q12\n", "t.tbl:1:4: orientation 12 is out of range"),
            ("T1 #\n", "t.tbl:1:4: `#` is not a tool table word"),
        ] {
            let err = parse(text).unwrap_err();
            assert!(err.starts_with(expected), "{text:?}: {err}");
        }
        let long = format!("T1 ;{}\n", "x".repeat(2000));
        assert!(parse(&long).unwrap_err().starts_with("t.tbl:1:1025: line longer"));
        let garbage: Vec<u8> = (0..=255u8).collect();
        assert!(ToolTable::parse(&garbage[..], "g").is_err());
    }

    #[test]
    fn a_missing_file_is_named() {
        let none = crate::NoEnvironment;
        let err = ToolTable::read(&none, Path::new("/nonexistent/tools.tbl")).unwrap_err();
        assert!(err.to_string().starts_with("/nonexistent/tools.tbl: cannot read the tool table"));
        let files = crate::InMemory::new().with_file("tools.tbl", "T1 P1 Z10 D6\n");
        let table = ToolTable::read(&files, Path::new("tools.tbl")).expect("read from memory");
        assert_eq!(table.get(1).map(|entry| entry.offset[2]), Some(10.0));
    }
}
