//! The points file (docs/programming.md): the reader.

use std::io::BufRead;

use biscara_text::{LineReader, Located, shorten};

use crate::error::{PointsError, PointsErrorKind};

/// A tool pose as written in a points file: millimetres and degrees.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Point {
    /// X, millimetres.
    pub x: f64,
    /// Y, millimetres.
    pub y: f64,
    /// Z, millimetres.
    pub z: f64,
    /// Rotation about +Z (G-code C), degrees.
    pub c: f64,
}

impl Point {
    /// `[x, y, z, c]`.
    pub fn to_array(self) -> [f64; 4] {
        [self.x, self.y, self.z, self.c]
    }

    /// The same point `height` millimetres higher.
    pub fn raised(self, height: f64) -> Point {
        Point { z: self.z + height, ..self }
    }
}

/// One statement of a points file.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PointsStatement {
    /// `home x y z c`: the start and end pose.
    Home(Point),
    /// `approach h`: millimetres above each pick and place point.
    Approach(f64),
    /// `feed f`: millimetres per minute of the approach and retract moves.
    Feed(f64),
    /// `dwell s`: seconds to wait after each grip or release.
    Dwell(f64),
    /// `pick x y z c`.
    Pick(Point),
    /// `place x y z c`.
    Place(Point),
}

/// A statement and its 1-based line.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointsRecord {
    /// The line.
    pub line: usize,
    /// The statement.
    pub statement: PointsStatement,
}

/// Reads a points file one [`PointsRecord`] at a time (an iterator: nothing is collected).
///
/// One statement a line; `#` starts a comment; keywords in any case; numbers separated by
/// spaces, tabs or commas. The reader checks each line on its own (keyword, count, finite
/// numbers, setting ranges); the order rules and reachability are [`crate::ClProgram`]'s. After
/// an error it yields nothing more.
#[derive(Debug)]
pub struct PointsReader<R> {
    lines: LineReader<R>,
    done: bool,
}

impl<R: BufRead> PointsReader<R> {
    /// A reader over `input`.
    pub fn new(input: R) -> PointsReader<R> {
        PointsReader { lines: LineReader::new(input), done: false }
    }

    /// The number of the last line read.
    pub fn line(&self) -> usize {
        self.lines.line()
    }

    fn read(&mut self) -> Result<Option<PointsRecord>, PointsError> {
        loop {
            let Some((line, text)) =
                self.lines.next_line().map_err(|err| err.map(PointsErrorKind::Read))?
            else {
                return Ok(None);
            };
            let text = text.find('#').map_or(text, |comment| &text[..comment]);
            let mut words =
                text.split(|ch: char| ch == ',' || ch.is_whitespace()).filter(|w| !w.is_empty());
            let Some(keyword) = words.next() else { continue };
            let values = words;
            let statement =
                parse_line(keyword, values).map_err(|kind| Located::at_line(line, kind))?;
            return Ok(Some(PointsRecord { line, statement }));
        }
    }
}

biscara_text::record_reader!(PointsReader, PointsRecord, PointsError, read, done);

fn parse_line<'a>(
    keyword: &str,
    values: impl Iterator<Item = &'a str>,
) -> Result<PointsStatement, PointsErrorKind> {
    let lower = keyword.to_ascii_lowercase();
    let keyword: &'static str = match lower.as_str() {
        "home" => "home",
        "approach" => "approach",
        "feed" => "feed",
        "dwell" => "dwell",
        "pick" => "pick",
        "place" => "place",
        _ => return Err(PointsErrorKind::UnknownKeyword { word: shorten(keyword) }),
    };
    let values = values.map(number).collect::<Result<Vec<f64>, _>>()?;
    let pose = || match values[..] {
        [x, y, z, c] => match [x, y, z, c].into_iter().find(|value| value.abs() > 1e6) {
            Some(value) => Err(PointsErrorKind::OutOfRange {
                keyword,
                value,
                reason: "coordinates must lie within ±1e6 (mm, degrees)",
            }),
            None => Ok(Point { x, y, z, c }),
        },
        _ => Err(PointsErrorKind::WrongCount {
            keyword,
            expected: "a pose of 4 values: x y z c (mm, mm, mm, degrees)",
            found: values.len(),
        }),
    };
    let single = |expected: &'static str| match values[..] {
        [value] => Ok(value),
        _ => Err(PointsErrorKind::WrongCount { keyword, expected, found: values.len() }),
    };
    let range = |value: f64, ok: bool, reason: &'static str| {
        if ok { Ok(value) } else { Err(PointsErrorKind::OutOfRange { keyword, value, reason }) }
    };
    Ok(match keyword {
        "home" => PointsStatement::Home(pose()?),
        "pick" => PointsStatement::Pick(pose()?),
        "place" => PointsStatement::Place(pose()?),
        "approach" => {
            let value = single("1 value: the height in mm")?;
            PointsStatement::Approach(range(
                value,
                value > 0.0 && value <= 1e6,
                "the approach height must be positive (mm)",
            )?)
        }
        "feed" => {
            let value = single("1 value: the feed in mm/min")?;
            PointsStatement::Feed(range(
                value,
                value > 0.0 && value <= 1e6,
                "the feed must be positive and at most 1e6 mm/min",
            )?)
        }
        _ => {
            let value = single("1 value: the time in seconds")?;
            PointsStatement::Dwell(range(
                value,
                (0.0..=1e5).contains(&value),
                "the dwell must lie within [0, 1e5] s",
            )?)
        }
    })
}

fn number(text: &str) -> Result<f64, PointsErrorKind> {
    let value: f64 =
        text.parse().map_err(|_| PointsErrorKind::NotANumber { text: shorten(text) })?;
    if value.is_finite() {
        Ok(value)
    } else {
        Err(PointsErrorKind::NotFinite { text: shorten(text) })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(text: &str) -> Result<Vec<PointsRecord>, PointsError> {
        PointsReader::new(text.as_bytes()).collect()
    }

    #[track_caller]
    fn check_error(text: &str, message: &str) {
        let err = read(text).expect_err(text).to_string();
        assert!(err.contains(message), "{text:?}: {err}");
    }

    #[test]
    fn reads_the_spec_example_forms() {
        let records = read(
            "# job\nHOME 0 400 100 0 # start\n\napproach\t50\nFeed 3000\ndwell 0.3\n\
             pick 150,320, 10 ,30\nplace -150 300 20 0\n",
        )
        .unwrap();
        let statements: Vec<_> = records.iter().map(|r| (r.line, r.statement)).collect();
        let point = |x, y, z, c| Point { x, y, z, c };
        assert_eq!(
            statements,
            vec![
                (2, PointsStatement::Home(point(0.0, 400.0, 100.0, 0.0))),
                (4, PointsStatement::Approach(50.0)),
                (5, PointsStatement::Feed(3000.0)),
                (6, PointsStatement::Dwell(0.3)),
                (7, PointsStatement::Pick(point(150.0, 320.0, 10.0, 30.0))),
                (8, PointsStatement::Place(point(-150.0, 300.0, 20.0, 0.0))),
            ]
        );
    }

    #[test]
    fn bad_lines_name_the_line_and_the_reason() {
        check_error(
            "pick 1 2 3",
            "1: `pick` takes a pose of 4 values: x y z c (mm, mm, mm, degrees), found 3 values",
        );
        check_error("\npick 1 NaN 3 4", "2: `NaN` is not a finite number");
        check_error("pick 1 inf 3 4", "`inf` is not a finite number");
        check_error("pick 1 1e999 3 4", "`1e999` is not a finite number");
        check_error("pick 1 x 3 4", "`x` is not a number");
        check_error("move 1 2 3 4", "1: unknown keyword `move`");
        check_error("feed 0", "`feed` 0 is out of range");
        check_error("dwell -1", "`dwell` -1 is out of range");
        check_error("approach 1 2", "`approach` takes 1 value: the height in mm, found 2 values");
    }
}
