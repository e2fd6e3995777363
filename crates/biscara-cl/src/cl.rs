//! CL statements: the typed form, the reader and the writer.

use std::io::{self, BufRead, Write};

use biscara_text::{LineError, LineReader, Located, MAX_LINE_BYTES, fixed, shorten};

use crate::error::{ClError, ClErrorKind};

/// Post words that mean nothing to this robot: [`ClReader`] passes them on as
/// [`Statement::PostWord`], and the postprocessor writes them as comments and lists them.
///
/// Words that change the path (CYCLE, CUTCOM, FROM, MSYS, …) are not among them: they are errors.
pub const POST_WORDS: &[&str] = &[
    "AUXFUN", "CLRSRF", "COOLNT", "CUTTER", "DISPLY", "INSERT", "INTOL", "LINTOL", "LOADTL",
    "MACHIN", "MULTAX", "OPSKIP", "OPSTOP", "OUTTOL", "PAINT", "PLABEL", "PREFUN", "SELCTL",
    "SEQNO", "SPINDL", "TITLES", "TLAXIS", "TLDATA", "TOLER", "TOOLNO",
];

/// The largest magnitude a CL number may have (mm or inches): beyond it a value is a mistake.
pub const MAX_VALUE: f64 = 1e6;

/// Length units of a CL file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Units {
    /// `UNITS/MM`.
    Millimetres,
    /// `UNITS/INCHES`: lengths and unit-less feeds are inches; the postprocessor converts.
    Inches,
}

/// The unit of a `FEDRAT`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FeedUnit {
    /// `MMPM`: millimetres per minute.
    Mmpm,
    /// `IPM`: inches per minute.
    Ipm,
}

/// A `GOTO`: the end point of a motion, in the file's length units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Goto {
    /// X of the tool point.
    pub x: f64,
    /// Y of the tool point.
    pub y: f64,
    /// Z of the tool point.
    pub z: f64,
    /// Rotation about +Z (G-code C), degrees: `GOTO/x,y,z,c`; `None` keeps the current one.
    pub c: Option<f64>,
    /// The tool axis `(i, j, k)` of a 6-value `GOTO/x,y,z,i,j,k`.
    pub axis: Option<[f64; 3]>,
}

/// A `CIRCLE/cx,cy,cz,i,j,k,r`: the next GOTO moves along this circle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Circle {
    /// Centre, in the file's length units.
    pub center: [f64; 3],
    /// Axis `(i, j, k)`: the motion runs counter-clockwise about it.
    pub axis: [f64; 3],
    /// Radius, in the file's length units.
    pub radius: f64,
}

/// A `FEDRAT`: the feed of the following feed moves.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Feed {
    /// The value.
    pub value: f64,
    /// Its unit; `None` means the file's length units per minute.
    pub unit: Option<FeedUnit>,
}

/// One CL statement.
///
/// Not `#[non_exhaustive]`: it is the contract between two crates, and a new statement must
/// fail to compile in the postprocessor's `match` rather than fall into a wildcard there.
#[derive(Debug, Clone, PartialEq)]
pub enum Statement {
    /// `PARTNO/text`: the program's name.
    PartNo(String),
    /// `UNITS/MM` or `UNITS/INCHES`.
    Units(Units),
    /// `RAPID`: the next motion is a rapid move (that motion only).
    Rapid,
    /// `GOTO/…`: a straight motion, or the end of an arc after a CIRCLE.
    Goto(Goto),
    /// `FEDRAT/…`.
    Feed(Feed),
    /// `CIRCLE/…`.
    Circle(Circle),
    /// `DELAY/s`: wait, seconds.
    Delay(f64),
    /// `PICK`: grip.
    Pick,
    /// `PLACE`: release.
    Place,
    /// `PPRINT/text`: an operator message, written as a comment.
    Pprint(String),
    /// A post word of [`POST_WORDS`], ignored: `word` is its name, `text` the whole statement.
    PostWord {
        /// The major word, upper case.
        word: String,
        /// The statement as written (continuations joined).
        text: String,
    },
    /// `END`: end of the program.
    End,
    /// `FINI`: end of the CL data.
    Fini,
}

impl Statement {
    /// The statement's major word (`GOTO`, `FEDRAT`, …).
    pub fn word(&self) -> &str {
        match self {
            Statement::PartNo(_) => "PARTNO",
            Statement::Units(_) => "UNITS",
            Statement::Rapid => "RAPID",
            Statement::Goto(_) => "GOTO",
            Statement::Feed(_) => "FEDRAT",
            Statement::Circle(_) => "CIRCLE",
            Statement::Delay(_) => "DELAY",
            Statement::Pick => "PICK",
            Statement::Place => "PLACE",
            Statement::Pprint(_) => "PPRINT",
            Statement::PostWord { word, .. } => word,
            Statement::End => "END",
            Statement::Fini => "FINI",
        }
    }
}

/// A statement and the 1-based line it starts on.
#[derive(Debug, Clone, PartialEq)]
pub struct Record {
    /// The line the statement starts on.
    pub line: usize,
    /// The statement.
    pub statement: Statement,
}

/// Reads CL statements from text, one [`Record`] at a time (an iterator: nothing is collected).
///
/// The syntax: one statement a line, `WORD` or `WORD/arguments`, arguments separated by commas,
/// spaces allowed around `/` and `,`, words in any case; `$$` starts a comment; a `$` at the end
/// of a line continues the statement on the next one. The reader checks syntax and counts; the
/// meaning (units, tool axis, arcs) is the postprocessor's. After an error it yields nothing more.
#[derive(Debug)]
pub struct ClReader<R> {
    lines: LineReader<R>,
    statement: String,
    done: bool,
}

impl<R: BufRead> ClReader<R> {
    /// A reader over `input`.
    pub fn new(input: R) -> ClReader<R> {
        ClReader { lines: LineReader::new(input), statement: String::new(), done: false }
    }

    /// The number of the last line read.
    pub fn line(&self) -> usize {
        self.lines.line()
    }

    fn read(&mut self) -> Result<Option<Record>, ClError> {
        loop {
            self.statement.clear();
            let mut first_line = 0;
            loop {
                let Some((line, text)) =
                    self.lines.next_line().map_err(|err| err.map(ClErrorKind::Read))?
                else {
                    if first_line == 0 {
                        return Ok(None);
                    }
                    break;
                };
                if first_line == 0 {
                    first_line = line;
                }
                let text = text.find("$$").map_or(text, |comment| &text[..comment]).trim();
                let (text, continues) = match text.strip_suffix('$') {
                    Some(head) => (head, true),
                    None => (text, false),
                };
                if self.statement.len() + text.len() > MAX_LINE_BYTES {
                    return Err(Located::at_line(line, ClErrorKind::Read(LineError::TooLong)));
                }
                self.statement.push_str(text);
                if !continues {
                    break;
                }
            }
            let text = self.statement.trim();
            if !text.is_empty() {
                return parse_statement(first_line, text)
                    .map(|statement| Some(Record { line: first_line, statement }));
            }
        }
    }
}

biscara_text::record_reader!(ClReader, Record, ClError, read, done);

/// Parses one statement (comments removed, continuations joined) that starts on `line`.
pub fn parse_statement(line: usize, text: &str) -> Result<Statement, ClError> {
    statement(text).map_err(|kind| Located::at_line(line, kind))
}

/// Parses one statement; what is wrong, without its line.
fn statement(text: &str) -> Result<Statement, ClErrorKind> {
    let text = text.trim();
    let end =
        text.find(|ch: char| !(ch.is_ascii_alphanumeric() || ch == '_')).unwrap_or(text.len());
    let (word, rest) = text.split_at(end);
    let upper = word.to_ascii_uppercase();
    let rest = rest.trim_start();
    // `WORD/arguments`, or the free text of PARTNO and PPRINT (some systems omit the slash).
    let (has_slash, arguments) = match rest.strip_prefix('/') {
        Some(arguments) => (true, arguments.trim()),
        None => (false, rest),
    };
    let unknown = || ClErrorKind::UnknownStatement { word: shorten(text) };
    if word.is_empty() {
        return Err(unknown());
    }
    let statement = match upper.as_str() {
        "PARTNO" => Statement::PartNo(arguments.trim().to_owned()),
        "PPRINT" => Statement::Pprint(arguments.trim().to_owned()),
        "RAPID" | "PICK" | "PLACE" | "END" | "FINI" => {
            if !arguments.is_empty() || has_slash {
                let word = static_word(&upper);
                return Err(ClErrorKind::Syntax {
                    word,
                    message: format!("takes no arguments, found `{}`", shorten(rest)),
                });
            }
            match upper.as_str() {
                "RAPID" => Statement::Rapid,
                "PICK" => Statement::Pick,
                "PLACE" => Statement::Place,
                "END" => Statement::End,
                _ => Statement::Fini,
            }
        }
        "GOTO" => {
            let values = numbers("GOTO", require_slash("GOTO", has_slash, arguments)?)?;
            match values[..] {
                [x, y, z] => Statement::Goto(Goto { x, y, z, c: None, axis: None }),
                [x, y, z, c] => Statement::Goto(Goto { x, y, z, c: Some(c), axis: None }),
                [x, y, z, i, j, k] => {
                    Statement::Goto(Goto { x, y, z, c: None, axis: Some([i, j, k]) })
                }
                _ => {
                    return Err(ClErrorKind::WrongCount {
                        word: "GOTO",
                        expected: "3 (x,y,z), 4 (x,y,z,c) or 6 (x,y,z,i,j,k) values",
                        found: values.len(),
                    });
                }
            }
        }
        "CIRCLE" => {
            let values = numbers("CIRCLE", require_slash("CIRCLE", has_slash, arguments)?)?;
            // Some systems append tolerances: CIRCLE/cx,cy,cz,i,j,k,r,tol,dtol,…
            if values.len() != 7 && values.len() != 11 {
                return Err(ClErrorKind::WrongCount {
                    word: "CIRCLE",
                    expected: "7 values (cx,cy,cz,i,j,k,r), or 11 with tolerances",
                    found: values.len(),
                });
            }
            let radius = values[6];
            if radius <= 0.0 {
                return Err(ClErrorKind::OutOfRange {
                    word: "CIRCLE",
                    value: radius,
                    reason: "the radius must be positive",
                });
            }
            Statement::Circle(Circle {
                center: [values[0], values[1], values[2]],
                axis: [values[3], values[4], values[5]],
                radius,
            })
        }
        "DELAY" => {
            let values = numbers("DELAY", require_slash("DELAY", has_slash, arguments)?)?;
            let [seconds] = values[..] else {
                return Err(ClErrorKind::WrongCount {
                    word: "DELAY",
                    expected: "1 value (seconds)",
                    found: values.len(),
                });
            };
            if seconds < 0.0 {
                return Err(ClErrorKind::OutOfRange {
                    word: "DELAY",
                    value: seconds,
                    reason: "a delay cannot be negative",
                });
            }
            Statement::Delay(seconds)
        }
        "FEDRAT" => Statement::Feed(feed(require_slash("FEDRAT", has_slash, arguments)?)?),
        "UNITS" => {
            let minor = require_slash("UNITS", has_slash, arguments)?.trim();
            match minor.to_ascii_uppercase().as_str() {
                "MM" => Statement::Units(Units::Millimetres),
                "INCHES" | "INCH" => Statement::Units(Units::Inches),
                _ => {
                    return Err(ClErrorKind::UnknownMinor {
                        word: "UNITS",
                        minor: shorten(minor),
                        expected: "MM or INCHES",
                    });
                }
            }
        }
        _ if POST_WORDS.contains(&upper.as_str()) => {
            Statement::PostWord { word: upper, text: text.to_owned() }
        }
        _ => return Err(unknown()),
    };
    Ok(statement)
}

fn static_word(upper: &str) -> &'static str {
    ["RAPID", "PICK", "PLACE", "END", "FINI"].into_iter().find(|&word| word == upper).unwrap_or("?")
}

fn require_slash<'a>(
    word: &'static str,
    has_slash: bool,
    arguments: &'a str,
) -> Result<&'a str, ClErrorKind> {
    if has_slash {
        Ok(arguments)
    } else {
        Err(ClErrorKind::Syntax { word, message: format!("expected `{word}/` and its values") })
    }
}

/// Parses one number of statement `word`: finite and within ±[`MAX_VALUE`].
fn number(word: &'static str, text: &str) -> Result<f64, ClErrorKind> {
    let text = text.trim();
    if text.is_empty() {
        return Err(ClErrorKind::Syntax {
            word,
            message: "a value is missing (two commas in a row, or a comma at the end)".to_owned(),
        });
    }
    let value: f64 =
        text.parse().map_err(|_| ClErrorKind::NotANumber { word, text: shorten(text) })?;
    if !value.is_finite() {
        return Err(ClErrorKind::NotFinite { word, text: shorten(text) });
    }
    if value.abs() > MAX_VALUE {
        return Err(ClErrorKind::OutOfRange {
            word,
            value,
            reason: "CL values must lie within ±1e6",
        });
    }
    Ok(value)
}

fn numbers(word: &'static str, arguments: &str) -> Result<Vec<f64>, ClErrorKind> {
    arguments.split(',').map(|text| number(word, text)).collect()
}

fn feed(arguments: &str) -> Result<Feed, ClErrorKind> {
    let parts: Vec<&str> = arguments.split(',').map(str::trim).collect();
    let unit_of = |text: &str| -> Result<Option<FeedUnit>, ClErrorKind> {
        if text.starts_with(|ch: char| ch.is_ascii_alphabetic()) {
            match text.to_ascii_uppercase().as_str() {
                "MMPM" => Ok(Some(FeedUnit::Mmpm)),
                "IPM" => Ok(Some(FeedUnit::Ipm)),
                _ => Err(ClErrorKind::UnknownMinor {
                    word: "FEDRAT",
                    minor: shorten(text),
                    expected: "MMPM or IPM (feed per minute; per-revolution feeds are not supported)",
                }),
            }
        } else {
            Ok(None)
        }
    };
    let (value, unit) = match parts[..] {
        [value] => (value, None),
        [first, second] => match (unit_of(first)?, unit_of(second)?) {
            (Some(unit), None) => (second, Some(unit)),
            (None, Some(unit)) => (first, Some(unit)),
            _ => {
                return Err(ClErrorKind::Syntax {
                    word: "FEDRAT",
                    message: format!(
                        "expected a feed and a unit (`FEDRAT/MMPM,f` or `FEDRAT/f,MMPM`), found `{}`",
                        shorten(arguments)
                    ),
                });
            }
        },
        _ => {
            return Err(ClErrorKind::WrongCount {
                word: "FEDRAT",
                expected: "a feed, and optionally MMPM or IPM",
                found: parts.len(),
            });
        }
    };
    let value = number("FEDRAT", value)?;
    if value <= 0.0 {
        return Err(ClErrorKind::OutOfRange {
            word: "FEDRAT",
            value,
            reason: "a feed must be positive",
        });
    }
    Ok(Feed { value, unit })
}

/// Writes `statement` as one CL line, numbers with 4 decimals (the dialect `biscara clf` writes).
pub fn write_statement(out: &mut impl Write, statement: &Statement) -> io::Result<()> {
    let joined = |values: &[f64]| values.iter().map(|&v| fixed(v, 4)).collect::<Vec<_>>().join(",");
    match statement {
        Statement::PartNo(text) => writeln!(out, "PARTNO/{text}"),
        Statement::Units(Units::Millimetres) => writeln!(out, "UNITS/MM"),
        Statement::Units(Units::Inches) => writeln!(out, "UNITS/INCHES"),
        Statement::Rapid => writeln!(out, "RAPID"),
        Statement::Goto(goto) => {
            let mut values = vec![goto.x, goto.y, goto.z];
            values.extend(goto.c);
            values.extend(goto.axis.iter().flatten());
            writeln!(out, "GOTO/{}", joined(&values))
        }
        Statement::Feed(Feed { value, unit }) => match unit {
            Some(FeedUnit::Mmpm) => writeln!(out, "FEDRAT/MMPM,{}", fixed(*value, 4)),
            Some(FeedUnit::Ipm) => writeln!(out, "FEDRAT/IPM,{}", fixed(*value, 4)),
            None => writeln!(out, "FEDRAT/{}", fixed(*value, 4)),
        },
        Statement::Circle(circle) => {
            let [cx, cy, cz] = circle.center;
            let [i, j, k] = circle.axis;
            writeln!(out, "CIRCLE/{}", joined(&[cx, cy, cz, i, j, k, circle.radius]))
        }
        Statement::Delay(seconds) => writeln!(out, "DELAY/{}", fixed(*seconds, 4)),
        Statement::Pick => writeln!(out, "PICK"),
        Statement::Place => writeln!(out, "PLACE"),
        Statement::Pprint(text) => writeln!(out, "PPRINT/{text}"),
        Statement::PostWord { text, .. } => writeln!(out, "{text}"),
        Statement::End => writeln!(out, "END"),
        Statement::Fini => writeln!(out, "FINI"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[track_caller]
    fn check(text: &str, expected: Statement) {
        assert_eq!(parse_statement(1, text).expect(text), expected);
    }

    #[track_caller]
    fn check_error(text: &str, message: &str) {
        let err = parse_statement(7, text).expect_err(text).to_string();
        assert!(err.starts_with("7: ") && err.contains(message), "{text}: {err}");
    }

    fn goto(x: f64, y: f64, z: f64, c: Option<f64>, axis: Option<[f64; 3]>) -> Statement {
        Statement::Goto(Goto { x, y, z, c, axis })
    }

    #[test]
    fn reads_every_form() {
        check("GOTO/1,2,3", goto(1.0, 2.0, 3.0, None, None));
        check("goto / 1 , 2.5 ,-3, 30", goto(1.0, 2.5, -3.0, Some(30.0), None));
        check("GOTO/1,2,3,0,0,1", goto(1.0, 2.0, 3.0, None, Some([0.0, 0.0, 1.0])));
        check("FEDRAT/200", Statement::Feed(Feed { value: 200.0, unit: None }));
        check(
            "FEDRAT / 200, MMPM",
            Statement::Feed(Feed { value: 200.0, unit: Some(FeedUnit::Mmpm) }),
        );
        check("FEDRAT/IPM,12.5", Statement::Feed(Feed { value: 12.5, unit: Some(FeedUnit::Ipm) }));
        check("UNITS/INCHES", Statement::Units(Units::Inches));
        check("PARTNO PICK AND PLACE", Statement::PartNo("PICK AND PLACE".to_owned()));
        check("PPRINT/Hello, world / 2", Statement::Pprint("Hello, world / 2".to_owned()));
        check(
            "SPINDL/ON, CLW",
            Statement::PostWord { word: "SPINDL".to_owned(), text: "SPINDL/ON, CLW".to_owned() },
        );
        check(
            "CIRCLE/1,2,3,0,0,-1,5,0.01,0.5,1,0",
            Statement::Circle(Circle {
                center: [1.0, 2.0, 3.0],
                axis: [0.0, 0.0, -1.0],
                radius: 5.0,
            }),
        );
        check("fini", Statement::Fini);
    }

    #[test]
    fn rejects_bad_statements() {
        check_error(
            "GOTO/1,2,3,4,5",
            "GOTO takes 3 (x,y,z), 4 (x,y,z,c) or 6 (x,y,z,i,j,k) values, found 5",
        );
        check_error("GOTO/1,nan,3", "`nan` is not a finite number");
        check_error("GOTO/1,inf,3", "not a finite number");
        check_error("GOTO/1,1e999,3", "`1e999` is not a finite number");
        check_error("GOTO/1,1e300,3", "out of range");
        check_error("GOTO/1,x,3", "`x` is not a number");
        check_error("GOTO 1,2,3", "expected `GOTO/`");
        check_error("CYCLE/DRILL,5", "unknown CL statement `CYCLE/DRILL,5`");
        check_error("FEDRAT/MMPR,0.1", "unexpected `MMPR`");
        check_error("FEDRAT/0", "a feed must be positive");
        check_error("FEDRAT/MMPM,IPM", "expected a feed and a unit");
        check_error("DELAY/-1", "cannot be negative");
        check_error("UNITS/FEET", "expected MM or INCHES");
        check_error("PICK/1", "takes no arguments");
        check_error("/5", "unknown CL statement");
    }

    #[test]
    fn reader_joins_continuations_and_skips_comments() {
        let text = "$$ header\nPARTNO/JOB\n\nGOTO/1,$\n  2,3 $$ end point\nFINI\n";
        let records: Vec<Record> = ClReader::new(text.as_bytes()).map(Result::unwrap).collect();
        assert_eq!(
            records,
            vec![
                Record { line: 2, statement: Statement::PartNo("JOB".to_owned()) },
                Record { line: 4, statement: goto(1.0, 2.0, 3.0, None, None) },
                Record { line: 6, statement: Statement::Fini },
            ]
        );
    }

    #[test]
    fn written_statements_read_back() {
        let statements = [
            Statement::PartNo("PICK AND PLACE".to_owned()),
            Statement::Units(Units::Inches),
            Statement::Rapid,
            goto(1.5, -2.0, 3.0, Some(-45.0), None),
            goto(1.5, -2.0, 3.0, None, Some([0.0, 0.0, 1.0])),
            Statement::Feed(Feed { value: 3000.0, unit: Some(FeedUnit::Mmpm) }),
            Statement::Feed(Feed { value: 10.0, unit: Some(FeedUnit::Ipm) }),
            Statement::Feed(Feed { value: 10.0, unit: None }),
            Statement::Circle(Circle {
                center: [1.0, 2.0, 0.0],
                axis: [0.0, 0.0, 1.0],
                radius: 3.0,
            }),
            Statement::Delay(0.3),
            Statement::Pick,
            Statement::Place,
            Statement::Pprint("hello".to_owned()),
            Statement::PostWord { word: "COOLNT".to_owned(), text: "COOLNT/ON".to_owned() },
            Statement::End,
            Statement::Fini,
        ];
        for statement in statements {
            let mut text = Vec::new();
            write_statement(&mut text, &statement).unwrap();
            let text = String::from_utf8(text).unwrap();
            assert_eq!(parse_statement(1, &text).unwrap(), statement, "{text}");
        }
    }
}
