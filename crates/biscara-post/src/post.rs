//! The postprocessor: CL statements in, LinuxCNC G-code out (docs/programming.md), one
//! statement at a time.

use std::io::{BufRead, Write};

use biscara_cl::{Circle, ClReader, Feed, FeedUnit, Goto, Statement, Units};
use biscara_text::fixed;

use crate::error::PostError;

/// Millimetres per inch.
const MM_PER_INCH: f64 = 25.4;

/// How far an arc's end may lie off the circle through its start, millimetres: CAM files round
/// to 4 decimals of an inch (0.0025 mm); LinuxCNC itself accepts somewhat more.
const ARC_TOLERANCE_MM: f64 = 0.01;

/// The longest comment text written: LinuxCNC refuses blocks longer than 255 characters.
const MAX_COMMENT_CHARS: usize = 200;

/// How far a tool axis may be from (0, 0, 1) and still count as vertical.
const AXIS_TOLERANCE: f64 = 1e-6;

/// Settings of the postprocessor.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct PostOptions {
    /// Number the blocks `N10`, `N20`, … (the `%` lines excepted).
    pub line_numbers: bool,
}

/// A post word that was passed through as a comment.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct IgnoredWord {
    /// The word (`SPINDL`).
    pub word: String,
    /// The line of its first occurrence.
    pub first_line: usize,
    /// How many times it occurred.
    pub count: usize,
}

/// What a finished postprocessor run reports besides the G-code.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct PostSummary {
    /// Post words with no meaning for this robot, in order of first occurrence.
    pub ignored: Vec<IgnoredWord>,
    /// Motion blocks written (G0, G1, G2, G3).
    pub motions: usize,
}

impl PostSummary {
    /// The note that lists the ignored post words (`ignored post words with no meaning for this
    /// robot (written as comments): SPINDL (line 3), COOLNT (2 times, first on line 5)`), or
    /// `None` when there were none.
    pub fn ignored_note(&self) -> Option<String> {
        if self.ignored.is_empty() {
            return None;
        }
        let words: Vec<String> = self
            .ignored
            .iter()
            .map(|ignored| match ignored.count {
                1 => format!("{} (line {})", ignored.word, ignored.first_line),
                count => format!(
                    "{} ({count} times, first on line {})",
                    ignored.word, ignored.first_line
                ),
            })
            .collect();
        Some(format!(
            "ignored post words with no meaning for this robot (written as comments): {}",
            words.join(", ")
        ))
    }
}

/// An arc waiting for its GOTO: the CIRCLE's line and the circle in millimetres.
#[derive(Debug, Clone, Copy)]
struct PendingArc {
    line: usize,
    center: [f64; 2],
    radius: f64,
    clockwise: bool,
}

/// Turns CL statements into G-code, writing each block as soon as it is known.
///
/// Feed [`Postprocessor::apply`] every statement in order, then call [`Postprocessor::finish`].
/// The G-code: `%`, the PARTNO as a comment, `G21 G17 G90 G94`, then one block per motion
/// (`G0` rapid, `G1` feed, `G2`/`G3` arcs with `I J` from the start point), `M3` for PICK, `M4`
/// for PLACE, `G4 P…` for DELAY, `M2` and `%`. Axis words and `F` are written only when their
/// printed value changes; lengths and angles have 3 decimals, feeds 1. Inches become
/// millimetres.
#[derive(Debug)]
pub struct Postprocessor<W> {
    out: W,
    options: PostOptions,
    block_number: u64,
    started: bool,
    setup_written: bool,
    /// Length units of the CL file: millimetres per unit.
    scale: f64,
    /// The modal CL feed, mm/min.
    feed: Option<f64>,
    rapid_next: bool,
    arc: Option<PendingArc>,
    /// The current point (mm), known after the first GOTO.
    position: Option<[f64; 3]>,
    /// The last value written for X, Y, Z, C.
    written: [Option<String>; 4],
    written_feed: Option<String>,
    ended: bool,
    finished: bool,
    summary: PostSummary,
}

impl<W: Write> Postprocessor<W> {
    /// A postprocessor writing to `out`.
    pub fn new(out: W, options: PostOptions) -> Postprocessor<W> {
        Postprocessor {
            out,
            options,
            block_number: 0,
            started: false,
            setup_written: false,
            scale: 1.0,
            feed: None,
            rapid_next: false,
            arc: None,
            position: None,
            written: Default::default(),
            written_feed: None,
            ended: false,
            finished: false,
            summary: PostSummary::default(),
        }
    }

    /// Posts one statement, which starts on `line` of the CL file.
    pub fn apply(&mut self, line: usize, statement: &Statement) -> Result<(), PostError> {
        if !self.started {
            self.started = true;
            self.raw("%")?;
        }
        if self.finished {
            return Err(PostError::AfterEnd {
                line,
                word: statement.word().to_owned(),
                after: "FINI",
            });
        }
        if self.ended
            && !matches!(
                statement,
                Statement::Fini | Statement::Pprint(_) | Statement::PostWord { .. }
            )
        {
            return Err(PostError::AfterEnd {
                line,
                word: statement.word().to_owned(),
                after: "END",
            });
        }
        if let Some(arc) = self.arc
            && !matches!(
                statement,
                Statement::Goto(_)
                    | Statement::Feed(_)
                    | Statement::Pprint(_)
                    | Statement::PostWord { .. }
            )
        {
            return Err(PostError::CircleWithoutGoto {
                line: arc.line,
                found: format!("{} on line {line}", statement.word()),
            });
        }
        match statement {
            Statement::PartNo(text) | Statement::Pprint(text) => self.comment(text),
            Statement::PostWord { word, text } => {
                match self.summary.ignored.iter_mut().find(|ignored| ignored.word == *word) {
                    Some(ignored) => ignored.count += 1,
                    None => self.summary.ignored.push(IgnoredWord {
                        word: word.clone(),
                        first_line: line,
                        count: 1,
                    }),
                }
                self.comment(text)
            }
            Statement::Units(units) => {
                self.scale = match units {
                    Units::Millimetres => 1.0,
                    Units::Inches => MM_PER_INCH,
                };
                Ok(())
            }
            Statement::Rapid => {
                self.rapid_next = true;
                Ok(())
            }
            Statement::Feed(Feed { value, unit }) => {
                self.feed = Some(
                    value
                        * match unit {
                            Some(FeedUnit::Mmpm) => 1.0,
                            Some(FeedUnit::Ipm) => MM_PER_INCH,
                            None => self.scale,
                        },
                );
                Ok(())
            }
            Statement::Circle(circle) => self.circle(line, circle),
            Statement::Goto(goto) => self.goto(line, goto),
            Statement::Delay(seconds) => self.block(&format!("G4 P{}", fixed(*seconds, 3))),
            Statement::Pick => self.block("M3 (pick)"),
            Statement::Place => self.block("M4 (place)"),
            Statement::End => {
                self.ended = true;
                self.block("M2")
            }
            Statement::Fini => {
                if !self.ended {
                    self.ended = true;
                    self.block("M2")?;
                }
                self.finished = true;
                self.raw("%")
            }
        }
    }

    /// Ends the run: fails when FINI is missing (`last_line` is the file's last line), and
    /// flushes the output.
    pub fn finish(mut self, last_line: usize) -> Result<PostSummary, PostError> {
        if let Some(arc) = self.arc {
            return Err(PostError::CircleWithoutGoto {
                line: arc.line,
                found: "the end of the file".to_owned(),
            });
        }
        if !self.started {
            return Err(PostError::Empty { line: last_line.max(1) });
        }
        if !self.finished {
            return Err(PostError::MissingFini { line: last_line.max(1) });
        }
        self.out.flush().map_err(PostError::Write)?;
        Ok(self.summary)
    }

    fn circle(&mut self, line: usize, circle: &Circle) -> Result<(), PostError> {
        let [i, j, k] = circle.axis;
        let norm = (i * i + j * j + k * k).sqrt();
        if norm == 0.0 || (i / norm).abs() > AXIS_TOLERANCE || (j / norm).abs() > AXIS_TOLERANCE {
            return Err(PostError::ArcPlane { line, axis: circle.axis });
        }
        if self.rapid_next {
            return Err(PostError::RapidArc { line });
        }
        if self.position.is_none() {
            return Err(PostError::NoStartPoint { line });
        }
        self.arc = Some(PendingArc {
            line,
            center: [circle.center[0] * self.scale, circle.center[1] * self.scale],
            radius: circle.radius * self.scale,
            clockwise: k < 0.0,
        });
        Ok(())
    }

    fn goto(&mut self, line: usize, goto: &Goto) -> Result<(), PostError> {
        if let Some(axis) = goto.axis {
            let [i, j, k] = axis;
            if i.abs() > AXIS_TOLERANCE
                || j.abs() > AXIS_TOLERANCE
                || (k - 1.0).abs() > AXIS_TOLERANCE
            {
                return Err(PostError::ToolAxis { line, axis });
            }
        }
        let end = [goto.x * self.scale, goto.y * self.scale, goto.z * self.scale];
        let rapid = std::mem::take(&mut self.rapid_next);
        let arc = self.arc.take();
        let start = self.position.replace(end);
        let mut words = Vec::with_capacity(8);
        let values = [Some(end[0]), Some(end[1]), Some(end[2]), goto.c];
        let changed: Vec<(usize, String)> = values
            .iter()
            .enumerate()
            .filter_map(|(axis, value)| value.map(|value| (axis, fixed(value, 3))))
            .filter(|(axis, text)| self.written[*axis].as_deref() != Some(text.as_str()))
            .collect();
        if let (Some(arc), Some(start)) = (arc, start) {
            let start_mm = (start[0] - arc.center[0]).hypot(start[1] - arc.center[1]);
            let end_mm = (end[0] - arc.center[0]).hypot(end[1] - arc.center[1]);
            if (start_mm - end_mm).abs() > ARC_TOLERANCE_MM
                || (start_mm - arc.radius).abs() > ARC_TOLERANCE_MM
            {
                return Err(PostError::ArcRadius { line, start_mm, end_mm, radius_mm: arc.radius });
            }
            words.push(if arc.clockwise { "G2" } else { "G3" }.to_owned());
            // X and Y always: LinuxCNC refuses an arc without axis words (a full circle).
            for axis in 0..2 {
                let text = fixed(end[axis], 3);
                words.push(format!("{}{text}", AXIS_LETTERS[axis]));
                self.written[axis] = Some(text);
            }
            for (axis, text) in changed.into_iter().filter(|(axis, _)| *axis >= 2) {
                words.push(format!("{}{text}", AXIS_LETTERS[axis]));
                self.written[axis] = Some(text);
            }
            // The offsets from the start point as LinuxCNC will read it back (printed values).
            let printed = |value: f64| fixed(value, 3).parse::<f64>().unwrap_or(value);
            words.push(format!("I{}", fixed(arc.center[0] - printed(start[0]), 3)));
            words.push(format!("J{}", fixed(arc.center[1] - printed(start[1]), 3)));
        } else {
            if changed.is_empty() {
                return Ok(());
            }
            words.push(if rapid { "G0" } else { "G1" }.to_owned());
            for (axis, text) in changed {
                words.push(format!("{}{text}", AXIS_LETTERS[axis]));
                self.written[axis] = Some(text);
            }
        }
        if !rapid {
            let feed = self.feed.ok_or(PostError::NoFeed { line })?;
            let text = fixed(feed, 1);
            if self.written_feed.as_deref() != Some(text.as_str()) {
                words.push(format!("F{text}"));
                self.written_feed = Some(text);
            }
        }
        self.summary.motions += 1;
        self.block(&words.join(" "))
    }

    /// Writes a comment block, `(text)`, made safe for LinuxCNC.
    fn comment(&mut self, text: &str) -> Result<(), PostError> {
        self.numbered(&format!("({})", comment_text(text)))
    }

    /// Writes a block that does something, after the setup block.
    fn block(&mut self, text: &str) -> Result<(), PostError> {
        if !self.setup_written {
            self.setup_written = true;
            self.numbered("G21 G17 G90 G94")?;
        }
        self.numbered(text)
    }

    fn numbered(&mut self, text: &str) -> Result<(), PostError> {
        if self.options.line_numbers {
            self.block_number += 10;
            writeln!(self.out, "N{} {text}", self.block_number).map_err(PostError::Write)
        } else {
            self.raw(text)
        }
    }

    fn raw(&mut self, text: &str) -> Result<(), PostError> {
        writeln!(self.out, "{text}").map_err(PostError::Write)
    }
}

const AXIS_LETTERS: [char; 4] = ['X', 'Y', 'Z', 'C'];

/// Comment text LinuxCNC reads as a plain comment: no nested parentheses, printable ASCII only,
/// at most 200 characters (longer text is cut and ends in `...`), and no leading
/// `MSG,`/`DEBUG,`/`PRINT,`/`LOG…`/`PROBE…`/`ABORT,` (which LinuxCNC would act on).
fn comment_text(text: &str) -> String {
    let cut = text.chars().count() > MAX_COMMENT_CHARS;
    let mut clean: String = text
        .chars()
        .take(if cut { MAX_COMMENT_CHARS - 3 } else { MAX_COMMENT_CHARS })
        .map(|ch| match ch {
            '(' => '[',
            ')' => ']',
            ' '..='~' => ch,
            _ => '?',
        })
        .collect();
    if cut {
        clean.push_str("...");
    }
    let upper = clean.trim_start().to_ascii_uppercase();
    let active = ["MSG", "DEBUG", "PRINT", "LOG", "PROBE", "ABORT"];
    if active.iter().any(|word| upper.starts_with(word)) { format!("- {clean}") } else { clean }
}

/// Reads a whole CL file from `input` and writes its G-code to `out`, streaming.
pub fn post(
    input: impl BufRead,
    out: impl Write,
    options: PostOptions,
) -> Result<PostSummary, PostError> {
    let mut reader = ClReader::new(input);
    let mut post = Postprocessor::new(out, options);
    for record in reader.by_ref() {
        let record = record?;
        post.apply(record.line, &record.statement)?;
    }
    post.finish(reader.line())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[track_caller]
    fn check(cl: &str, expected: &str) {
        let mut out = Vec::new();
        post(cl.as_bytes(), &mut out, PostOptions::default()).expect(cl);
        assert_eq!(String::from_utf8(out).unwrap(), expected);
    }

    #[track_caller]
    fn check_error(cl: &str, message: &str) {
        let err = post(cl.as_bytes(), Vec::new(), PostOptions::default()).expect_err(cl);
        assert!(err.to_string().contains(message), "{err}");
    }

    #[test]
    fn writes_only_what_changes() {
        check(
            "PARTNO/P\nUNITS/MM\nRAPID\nGOTO/0,400,100,0\nFEDRAT/MMPM,3000\nGOTO/0,400,50,0\n\
             GOTO/0,400,50,0\nGOTO/10,400,50\nPICK\nDELAY/0.3\nPLACE\nEND\nFINI\n",
            "%\n(P)\nG21 G17 G90 G94\nG0 X0.000 Y400.000 Z100.000 C0.000\nG1 Z50.000 F3000.0\n\
             G1 X10.000\nM3 (pick)\nG4 P0.300\nM4 (place)\nM2\n%\n",
        );
    }

    #[test]
    fn rapid_applies_to_the_next_motion_only() {
        check(
            "FEDRAT/100\nRAPID\nGOTO/1,2,3\nGOTO/1,2,4\nGOTO/1,2,5\nFINI",
            "%\nG21 G17 G90 G94\nG0 X1.000 Y2.000 Z3.000\nG1 Z4.000 F100.0\nG1 Z5.000\nM2\n%\n",
        );
    }

    #[test]
    fn inches_and_arcs() {
        check(
            "UNITS/INCHES\nFEDRAT/10\nRAPID\nGOTO/1,0,0\nCIRCLE/0,0,0,0,0,1,1\nGOTO/0,1,0\n\
             CIRCLE/0,0,0,0,0,-1,1\nGOTO/1,0,0\nFEDRAT/MMPM,500\nGOTO/1,0,1\nFINI",
            "%\nG21 G17 G90 G94\nG0 X25.400 Y0.000 Z0.000\n\
             G3 X0.000 Y25.400 I-25.400 J0.000 F254.0\nG2 X25.400 Y0.000 I0.000 J-25.400\n\
             G1 Z25.400 F500.0\nM2\n%\n",
        );
    }

    #[test]
    fn line_numbers_and_comments() {
        let mut out = Vec::new();
        let cl = "PARTNO/A (B)\nSPINDL/ON\nPPRINT/MSG,hi\nRAPID\nGOTO/1,2,3\nSPINDL/OFF\nFINI\n";
        let summary = post(cl.as_bytes(), &mut out, PostOptions { line_numbers: true }).unwrap();
        assert_eq!(
            String::from_utf8(out).unwrap(),
            "%\nN10 (A [B])\nN20 (SPINDL/ON)\nN30 (- MSG,hi)\nN40 G21 G17 G90 G94\n\
             N50 G0 X1.000 Y2.000 Z3.000\nN60 (SPINDL/OFF)\nN70 M2\n%\n"
        );
        assert_eq!(
            summary.ignored,
            vec![IgnoredWord { word: "SPINDL".to_owned(), first_line: 2, count: 2 }]
        );
    }

    #[test]
    fn long_comments_are_cut_to_fit_a_linuxcnc_block() {
        let mut out = Vec::new();
        let cl = format!("PPRINT/{}\nFINI\n", "é".repeat(300));
        post(cl.as_bytes(), &mut out, PostOptions::default()).unwrap();
        let text = String::from_utf8(out).unwrap();
        let comment = text.lines().nth(1).unwrap();
        assert_eq!(comment, format!("({}...)", "?".repeat(197)));
    }

    #[test]
    fn feeds_may_come_between_circle_and_goto() {
        check(
            "RAPID\nGOTO/1,0,0\nCIRCLE/0,0,0,0,0,1,1\nFEDRAT/60\nGOTO/0,1,0\nFINI",
            "%\nG21 G17 G90 G94\nG0 X1.000 Y0.000 Z0.000\nG3 X0.000 Y1.000 I-1.000 J0.000 F60.0\nM2\n%\n",
        );
    }

    #[test]
    fn semantic_errors_name_the_line() {
        check_error("", "1: the CL file is empty");
        check_error("RAPID\nGOTO/1,2,3\n", "2: the CL file ends without FINI");
        check_error("GOTO/1,2,3\nFINI", "1: GOTO is a feed move but no FEDRAT");
        check_error("RAPID\nGOTO/1,2,3,0,0.5,0.866\nFINI", "2: GOTO: tool axis");
        check_error(
            "RAPID\nGOTO/1,0,0\nCIRCLE/0,0,0,0,0,1,1\nPICK\nFINI",
            "3: CIRCLE is not followed by a GOTO (found PICK on line 4)",
        );
        check_error(
            "RAPID\nGOTO/1,0,0\nCIRCLE/0,0,0,0,0,1,1\n",
            "3: CIRCLE is not followed by a GOTO (found the end of the file)",
        );
        check_error("CIRCLE/0,0,0,0,0,1,1\nGOTO/1,0,0\nFINI", "1: CIRCLE before any GOTO");
        check_error("RAPID\nGOTO/1,0,0\nCIRCLE/0,0,0,0,1,0,1\nGOTO/0,1,0\nFINI", "3: CIRCLE: axis");
        check_error(
            "FEDRAT/1\nRAPID\nGOTO/1,0,0\nCIRCLE/0,0,0,0,0,1,1\nGOTO/0,2,0\nFINI",
            "5: the arc's end point is 2.0000 mm",
        );
        check_error(
            "RAPID\nGOTO/1,0,0\nRAPID\nCIRCLE/0,0,0,0,0,1,1\nGOTO/0,1,0\nFINI",
            "4: RAPID before CIRCLE",
        );
        check_error("END\nRAPID\nFINI", "2: RAPID after END");
        check_error("FINI\nFINI", "2: FINI after FINI");
    }
}
