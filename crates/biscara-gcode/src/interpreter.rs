//! The interpreter: [`Interpreter`] reads lines (generic over the input), runs the O-word
//! control flow and the Python plug-ins that jump and move in them, and the dialects' hooks
//! that read the input (`auto`'s look-ahead, the tool's inference, a line before the block
//! reader, the end of the input); a non-generic [`Machine`] executes each block read
//! (`machine.rs`, and the files of the codes it executes).

use std::collections::VecDeque;
use std::io::BufRead;

use biscara_motion::{Feed, Motion, MotionKind, Plane};

use crate::dialect::{
    Detection, Dialect, LOOKAHEAD_BYTES, MAX_LONG_LINE, Prelude, Summary, detect_dialect,
};
use crate::error::{GcodeError, Location, Setting};
use crate::ini_file::IniFile;
use crate::syntax::lexer::{
    Compact, Fault, FaultKind, LineReader, MAX_LINE, Seekable, UNCLOSED_COMMENT, compact,
};
use crate::syntax::params::{
    COORDINATE_SYSTEM, G28_HOME, G30_HOME, G92_ENABLED, G92_OFFSET, Params, axis_slot,
    coordinate_system_base,
};
use crate::syntax::parser::{Block, Code, Predefined, Reader, Support, Word, g_group, m_group};
use crate::tool::{Tool, ToolInference};
use crate::tool_table::{ToolEntry, ToolTable};

/// Canned cycles: G73, G74, G81–G89, G98/G99.
mod canned;
/// The checks of a block before it is executed.
mod checks;
/// Comments LinuxCNC executes (ABORT, Python).
mod comments;
/// O-word control flow: subroutines, conditions and loops (docs/gcode.md tier 3).
mod control;
/// Cutter radius compensation (G40, G41, G42, G41.1, G42.1).
mod cutter_comp;
/// The dialects' hooks: one implementation of `DialectHooks` per dialect.
mod dialects;
/// Loops that can only repeat: the same state at the same jump back.
mod endless;
/// A block executed in LinuxCNC's order.
mod execute;
/// The Fanuc/Haas dialect: Macro B control flow, M97, machine M-codes, look-ahead codes.
mod fanuc;
/// The dialect's and the tool's state, and the tool's events (docs/gcode.md, docs/motion.md).
mod hooks;
/// M19, M48–M53, M62–M68 and the `$` word.
mod io_codes;
/// The machine that executes blocks: its parts and LinuxCNC's modal state.
mod machine;
/// M70–M73: the modal state saved and restored.
mod modal_state;
/// Modes and offsets: path control, units, coordinate systems, G10 L2/L20, G92, G52.
mod modes;
/// Straight moves, arcs, G28/G30.
mod motion;
/// Polar coordinates (`@`, `^`).
mod polar;
/// Probing, G38.2–G38.5.
mod probe;
/// A program's Python: LinuxCNC's Python plug-ins (`[PYTHON]`), `;py,` lines, `(py,…)`.
#[cfg(feature = "python")]
mod python;
/// A build without the Python plug-ins (the cargo feature `python` off): a program's Python is
/// refused.
#[cfg(not(feature = "python"))]
#[path = "interpreter/no_python.rs"]
mod python;
/// G10 L2 R: coordinate systems rotated about Z.
mod rotation;
/// G5 and G5.1 splines, run as straight moves.
mod spline;
/// Tools: T, M6, M61, G43/G43.1/G43.2/G49, G10 L1/L10/L11.
mod tools;

use comments::PythonComment;
use machine::{Machine, Output, Percent, State, Syntax};
use python::{Reach, Returned};
use std::rc::Rc;

const MM_PER_INCH: f64 = 25.4;
/// LinuxCNC's `RADIUS_TOLERANCE_INCH` (and × 25.4 for mm): the least radius of an arc.
const RADIUS_TOLERANCE_INCH: f64 = 0.00005;
/// LinuxCNC's default `CENTER_ARC_RADIUS_TOLERANCE_INCH` (2 · 0.001 · √2).
const CENTER_ARC_RADIUS_TOLERANCE_INCH: f64 = 2.0 * 0.001 * std::f64::consts::SQRT_2;
/// LinuxCNC's default `CENTER_ARC_RADIUS_TOLERANCE_MM` (2 · 0.01 · √2).
const CENTER_ARC_RADIUS_TOLERANCE_MM: f64 = 2.0 * 0.01 * std::f64::consts::SQRT_2;
/// LinuxCNC's `SPIRAL_RELATIVE_TOLERANCE`.
const SPIRAL_RELATIVE_TOLERANCE: f64 = 0.001;
/// LinuxCNC's `TINY` (for R-format arcs).
const TINY: f64 = 1e-12;
/// The largest position accepted, mm or degrees.
const MAX_COORDINATE: f64 = 1e6;
/// The axis letters, in our axis order x y z c.
const AXES: [u8; 4] = [b'x', b'y', b'z', b'c'];

/// How to start interpreting a program.
#[derive(Debug, Clone, PartialEq)]
pub struct Config {
    /// The pose the robot is in before the first line, `[x, y, z, c]` in millimetres and
    /// degrees, base frame; also where G28 and G30 go until G28.1 or G30.1 set them.
    pub home: [f64; 4],
    /// The G54 offset in force before the first line, `[x, y, z, c]` (mm, degrees): shifts the
    /// whole program (`--origin`).
    pub origin: [f64; 4],
    /// Where the robot is before the first line when that is not `home` (`[x, y, z, c]`, mm and
    /// degrees, base frame): a program that makes its start point its zero (`G92 X0 Y0`) is
    /// placed by moving its start (`--fit`). `None`: at `home`. G28 and G30 still go to `home`.
    pub start: Option<[f64; 4]>,
    /// LinuxCNC's block delete switch: when on, lines starting with `/` are skipped. Off by
    /// default, as in LinuxCNC.
    pub block_delete: bool,
    /// Whose G-code the program is (docs/gcode.md). [`Dialect::Linuxcnc`] by default: exactly
    /// LinuxCNC's reading. [`Dialect::Auto`] decides from the program (see
    /// [`Interpreter::detection`]).
    pub dialect: Dialect,
    /// What the robot carries: what M3, M4, M5 and S mean (docs/motion.md). The gripper by default.
    pub tool: Tool,
    /// Infer the tool from the program's first [`crate::LOOKAHEAD_BYTES`]
    /// ([`crate::infer_tool`]); `tool` is kept when nothing tells. See
    /// [`Interpreter::tool_inference`].
    pub infer_tool: bool,
    /// The path-control mode before the program says one (`--blend`): `None`, exact stop, by
    /// default; `Some(p)` as if the program began with `G64 P{p}`. See [`Motion::blend`].
    pub blend: Option<f64>,
    /// LinuxCNC's tool table (`--tool-table`): the tools' offsets (G43) and diameters. `None`:
    /// every tool has zero length and diameter ([`Interpreter::tools_without_table`] says
    /// whether the program used them).
    pub tool_table: Option<std::sync::Arc<ToolTable>>,
    /// How many times the program may jump back (a loop's turn, a subroutine call, a `GOTO`)
    /// without a motion in between before it is stopped as an endless loop
    /// ([`MAX_IDLE_JUMPS`](crate::MAX_IDLE_JUMPS) by default).
    pub max_idle_jumps: u64,
    /// How many motions one run may make ([`MAX_MOTIONS`](crate::MAX_MOTIONS) by default):
    /// the motion after them is an error, so that a program that never ends (a loop that moves
    /// and changes its state at every pass) stops instead of writing without end.
    pub max_motions: u64,
    /// LinuxCNC's INI file (`--ini`): the values of `#<_ini[SECTION]NAME>` (its INI_VARS
    /// feature), read-only, and the Python plug-ins its `[PYTHON]` section loads (a program's
    /// Python runs only with them; read the file with [`IniFile::read`] so that their relative
    /// paths start from its folder). `None`: such names are global names like any other, as in
    /// LinuxCNC without an INI file.
    pub ini: Option<std::sync::Arc<IniFile>>,
}

impl Default for Config {
    fn default() -> Config {
        Config {
            home: [0.0; 4],
            origin: [0.0; 4],
            start: None,
            block_delete: false,
            dialect: Dialect::Linuxcnc,
            tool: Tool::Gripper,
            infer_tool: false,
            blend: None,
            tool_table: None,
            max_idle_jumps: crate::MAX_IDLE_JUMPS,
            max_motions: crate::MAX_MOTIONS,
            ini: None,
        }
    }
}

/// Interprets the G-code read from `reader`: an iterator of motions in program order, which
/// stops after the first error. Memory does not grow with the program's length.
pub fn interpret<R: BufRead>(reader: R, config: &Config) -> Interpreter<R> {
    Interpreter::new(reader, config)
}

/// Interprets the G-code read from `reader`, an input it can jump in (a file): O-word loops
/// and subroutine calls go back to a line by its byte offset. [`interpret`] reads only
/// forwards: a jump back is an error there. Set where file subroutines are found with
/// [`Interpreter::with_subroutines`].
pub fn interpret_seekable<R: Seekable>(reader: R, config: &Config) -> Interpreter<R> {
    let mut interpreter = Interpreter::new(reader, config);
    if interpreter.lines.source_can_jump() {
        interpreter.lines.set_jump(|reader: &mut R, from, to| reader.jump(from, to));
    }
    interpreter
}

/// What the reader does after a step of a line ([`Interpreter::step`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Flow {
    /// The line goes on to the next step.
    Go,
    /// The line is done with: read the next one.
    Next,
    /// Motions are ready, or the program has ended: give them.
    Yield,
}

/// The iterator returned by [`interpret`]: the line reader, generic over the input, with the
/// O-word control flow and the Python plug-ins that move in it, and the machine that executes
/// the blocks read.
#[derive(Debug)]
pub struct Interpreter<R> {
    /// The program's lines (and the file subroutines').
    lines: LineReader<R>,
    /// The machine: everything that does not read lines.
    machine: Machine,
    /// O-word control flow.
    control: Box<control::Control>,
    /// The Python plug-ins the INI file's `[PYTHON]` section loads (`None`: it has none).
    #[cfg_attr(not(feature = "python"), allow(dead_code))]
    python: Option<Box<python::Python>>,
}

/// What the program told so far, as the caller asks.
impl<R: BufRead> Interpreter<R> {
    /// The dialect being read: the configured one, or what `auto` chose so far.
    pub fn dialect(&self) -> Dialect {
        self.machine.hooks.rules.dialect
    }

    /// What `auto` chose and why, once the first motion (or error) has been returned; `None`
    /// when the dialect was given. A program in which nothing tells the dialects apart is read
    /// as LinuxCNC — unless it ends without M2/M30, which LinuxCNC refuses and Grbl accepts:
    /// then it is Grbl, decided at its last line (the detection changes at the end).
    pub fn detection(&self) -> Option<Detection> {
        if let Some(detection) = &self.machine.hooks.detection {
            return Some(detection.clone());
        }
        self.machine.hooks.provisional.then(|| Detection {
            dialect: Dialect::Linuxcnc,
            reason: format!(
                "nothing in the first {} KiB tells the dialects apart (no generator comment, E \
                 word, printer M-code, `$` line, nested comment or program number)",
                LOOKAHEAD_BYTES / 1024
            ),
            line: None,
            makerbot: false,
        })
    }

    /// The axes (x, y, z, c) that a G92 named before the program's first motion: the program
    /// made the point where it starts its zero on them (`G92 X0 Y0 Z0`), so it is placed by
    /// moving its start ([`Config::start`](crate::Config::start)) rather than its G54 origin.
    pub fn zeroed_at_start(&self) -> [bool; 4] {
        self.machine.state.zeroed_at_start
    }

    /// The no-motion codes read so far, with their counts (complete once the iterator ends).
    pub fn summary(&self) -> &Summary {
        &self.machine.hooks.summary
    }

    /// The tool the program was found to be written for, when
    /// [`Config::infer_tool`](crate::Config::infer_tool) asked and something told (known once the
    /// first motion is read).
    pub fn tool_inference(&self) -> Option<&ToolInference> {
        self.machine.hooks.tool_inference.as_ref()
    }

    /// The tool M3, M4, M5 and S drive.
    pub fn tool(&self) -> Tool {
        self.machine.hooks.tool
    }

    /// Whether the program used G43, G43.2, G10 L1/L10/L11 or M61 while no tool table was
    /// given (every tool then has zero length and diameter).
    pub fn tools_without_table(&self) -> bool {
        self.machine.state.tools.used_without_table
    }

    /// The tool table as the program has changed it so far (G10 L1, L10, L11): what cutter
    /// compensation looks diameters up in.
    pub fn tool_table(&self) -> &ToolTable {
        &self.machine.state.tools.table
    }

    /// The tool in the spindle (after M6; zero offsets before any).
    pub fn current_tool(&self) -> ToolEntry {
        self.machine.state.tools.spindle
    }
}

impl<R: BufRead> Interpreter<R> {
    fn new(reader: R, config: &Config) -> Interpreter<R> {
        Interpreter {
            lines: LineReader::new(reader),
            machine: Machine {
                syntax: Syntax {
                    compact: Compact::default(),
                    block: Block::default(),
                    raw_len: 0,
                    block_delete: config.block_delete,
                    percent: Percent::Unknown,
                },
                state: State::new(config),
                output: Output {
                    queue: VecDeque::with_capacity(8),
                    finished: false,
                    moved: false,
                    idle_jumps: 0,
                    given: 0,
                    max_motions: config.max_motions,
                    last_end: None,
                },
                hooks: hooks::Hooks::new(config),
            },
            control: Box::new(control::Control::new(config.ini.as_deref(), config.max_idle_jumps)),
            python: config.ini.as_deref().and_then(python::Python::from_ini).map(Box::new),
        }
        .with_line_limit()
    }

    fn location(&self, start: usize, end: usize) -> Location {
        self.location_of(self.lines.number, &self.lines.line, start, end)
    }

    /// Where `start..end` of `raw`, line `line` of the file being read, is.
    fn location_of(&self, line: usize, raw: &[u8], start: usize, end: usize) -> Location {
        let shown = &raw[..raw.len().min(MAX_LINE + 1)];
        let text: String = String::from_utf8_lossy(shown)
            .chars()
            .map(|c| if c.is_control() && c != '\t' { '\u{fffd}' } else { c })
            .collect();
        let file = self.control.file.as_ref().map(|path| path.display().to_string().into());
        Location { line, column: start + 1, span: (start, end), text, file }
    }

    fn error(&self, mut fault: Fault) -> GcodeError {
        let raw = &self.lines.line;
        let e_word = fault.message.contains(" e word") || fault.message.contains("E word");
        if !self.machine.hooks.rules.reads_exponents
            && (exponent_at(raw, fault.start)
                || (e_word && (0..raw.len()).any(|at| exponent_at(raw, at))))
        {
            fault.message.push_str(&format!(
                " (the `e` right after a number is read as an E word: {} G-code has no numbers \
                 with an exponent, as Marlin's has; write the number in plain decimals)",
                self.machine.hooks.rules.dialect
            ));
        }
        let at = self.location(fault.start, fault.end);
        match fault.kind {
            FaultKind::Syntax => GcodeError::Syntax { at, message: fault.message },
            FaultKind::Invalid => GcodeError::Invalid { at, message: fault.message },
            FaultKind::NotSupported { code, note } => GcodeError::NotSupported { at, code, note },
            FaultKind::Cannot { code, reason } => GcodeError::CannotRun { at, code, reason },
            FaultKind::ForeignAxis(letter) => GcodeError::ForeignAxis { at, letter },
            FaultKind::Needs(setting) => {
                GcodeError::NeedsSetting { at, message: fault.message, setting }
            }
        }
    }

    /// Reads and executes lines until a motion is queued, the program ends, or an error.
    fn step(&mut self) -> Result<(), GcodeError> {
        if self.machine.hooks.undecided {
            self.decide()?;
        }
        if self.machine.hooks.infer_tool {
            self.infer_tool()?;
        }
        if self.python_paused() {
            self.resume_python().map_err(|fault| self.error(fault))?;
            if !self.machine.output.queue.is_empty() {
                return Ok(());
            }
        }
        loop {
            let more = self
                .lines
                .next_line()
                .map_err(|source| GcodeError::Read { line: self.lines.number + 1, source })?;
            self.machine.syntax.raw_len = self.lines.line.len();
            if !more {
                return self.input_ended();
            }
            let mut flow = self.frame_line()?;
            if flow == Flow::Go {
                flow = self.significant_line()?;
            }
            if flow == Flow::Go {
                flow = self.control_flow_line()?;
            }
            if flow == Flow::Go {
                flow = self.block_line()?;
            }
            if flow == Flow::Yield {
                return Ok(());
            }
        }
    }

    /// The end of the input: an O-word or a Fanuc jump left open is an error; then the end of
    /// the program as the dialect wants it.
    fn input_ended(&mut self) -> Result<(), GcodeError> {
        if let Some(err) = self.control_end() {
            return Err(err);
        }
        if let Some((target, line)) = self.machine.hooks.fanuc.seeking {
            return Err(GcodeError::NoBlockNumber { line, target });
        }
        if !self.machine.hooks.rules.needs_program_end {
            self.machine.flush_cutter_comp().map_err(|fault| self.error(fault))?;
        }
        self.end_of_input()
    }

    /// The line's framing: its length, the program's opening and closing `%`; the line's
    /// number for the motions it makes.
    fn frame_line(&mut self) -> Result<Flow, GcodeError> {
        if self.machine.hooks.provisional && self.lines.line.len() > MAX_LINE {
            self.long_line_decides()?;
        }
        if self.lines.too_long {
            let max = self.lines.max;
            return Err(GcodeError::LineTooLong {
                at: self.location(max.min(MAX_LINE), max.min(MAX_LINE) + 1),
                max,
            });
        }
        let trimmed = self.lines.line.trim_ascii();
        if trimmed.first() == Some(&b'%') && self.fanuc_seeking() {
            return Ok(Flow::Next);
        }
        if self.machine.syntax.percent == Percent::Unknown {
            if trimmed.first() == Some(&b'%') {
                self.machine.syntax.percent = Percent::Open;
                return Ok(Flow::Next);
            }
            self.machine.syntax.percent = Percent::Absent;
        } else if self.machine.syntax.percent == Percent::Open
            && trimmed == b"%"
            && !self.lines.in_file()
        {
            if let Some(err) = self.control_percent() {
                return Err(err);
            }
            // rs274 never sends the motions cutter compensation holds at a closing `%`.
            self.machine.state.comp.discard();
            self.machine.output.finished = true;
            return Ok(Flow::Yield);
        }
        self.machine.state.line = self.lines.number;
        if self.machine.state.resync {
            self.machine.resync_position();
        }
        Ok(Flow::Go)
    }

    /// The dialect's look at the raw line, then its significant characters (comments and
    /// spaces out, lower case); a line with none, or deleted by the block delete switch, is
    /// done with.
    fn significant_line(&mut self) -> Result<Flow, GcodeError> {
        if self.machine.hooks.rules.has_prelude && self.dialect_prelude()? {
            return Ok(self.made_or_next());
        }
        let inner = self.machine.hooks.rules.inner_paren;
        if let Err(fault) = compact(&self.lines.line, &mut self.machine.syntax.compact, inner) {
            if self.fanuc_seeking() {
                return Ok(Flow::Next);
            }
            // Closed at the end of its line, the line is read.
            if !self.machine.hooks.rules.closes_comment_at_line_end
                || fault.message != UNCLOSED_COMMENT
            {
                return Err(self.error(fault));
            }
        }
        if self.machine.hooks.makerbot {
            self.machine.rename_makerbot_a();
        }
        let bytes = self.machine.syntax.compact.bytes();
        if bytes.is_empty() || (self.machine.syntax.block_delete && bytes[0] == b'/') {
            return Ok(Flow::Next);
        }
        Ok(Flow::Go)
    }

    /// The control flow a line may be part of: the dialect's Macro B, O-words (and M98, M99,
    /// G65), LinuxCNC's `;py,` lines.
    fn control_flow_line(&mut self) -> Result<Flow, GcodeError> {
        if self.machine.hooks.rules.reads_macro_b
            && let fanuc::FanucLine::Done = self.fanuc_line().map_err(|fault| self.error(fault))?
        {
            return Ok(self.made_or_next());
        }
        let bytes = self.machine.syntax.compact.bytes();
        let g65 = self.machine.hooks.rules.fanuc_subprograms && control::may_call_g65(bytes);
        if (self.control.engaged() || control::may_control(bytes) || g65) && self.control_line()? {
            // (A line skipped inside a false `if` is no O-word of its own.)
            if control::may_control(self.machine.syntax.compact.bytes()) {
                self.machine.hooks.dialect.count_refused_o_word(&mut self.machine.hooks.summary);
            }
            // (A Python subroutine's move.)
            return Ok(self.made_or_next());
        }
        if self.machine.syntax.compact.bytes()[0] == b';'
            && self.machine.hooks.rules.executes_comments
            && self.lines.line.starts_with(b";py,")
        {
            // LinuxCNC runs a line that starts with `;py,` as it reads it (`read_semicolon`).
            let code = self.lines.line[4..].to_vec();
            self.python_comment(comments::PythonComment::Run, &code)
                .map_err(|fault| self.error(fault))?;
            return Ok(self.made_or_next());
        }
        Ok(Flow::Go)
    }

    /// The line read as a block, changed by the dialect, and executed.
    fn block_line(&mut self) -> Result<Flow, GcodeError> {
        let raw_len = self.lines.line.len();
        let result = {
            let mut reader = Reader::new(
                &self.machine.syntax.compact,
                raw_len,
                &self.machine.state.params,
                &self.machine.state,
            )
            .mach3(self.machine.hooks.rules.reads_mach3_codes)
            .exponents(self.machine.hooks.rules.reads_exponents);
            reader.read_block(&mut self.machine.syntax.block)
        };
        result.map_err(|fault| self.error(fault))?;
        if self.machine.hooks.provisional
            && let Some(why) = self.machine.mach3_only_block()
        {
            self.mach3_decides(why);
        }
        let dialect = self.machine.hooks.dialect;
        if self.machine.hooks.rules.adapts_blocks
            && dialect.adapt_block(&mut self.machine).map_err(|fault| self.error(fault))?
        {
            return Ok(Flow::Next);
        }
        self.execute_block().map_err(|fault| self.error(fault))?;
        if !self.machine.output.queue.is_empty() || self.machine.output.finished {
            return Ok(Flow::Yield);
        }
        Ok(Flow::Next)
    }

    /// After a line a hook took: give the motions it made, else read the next line.
    fn made_or_next(&self) -> Flow {
        if self.machine.output.queue.is_empty() { Flow::Next } else { Flow::Yield }
    }

    /// Executes the block just read, in LinuxCNC's order of execution: the machine's, with the
    /// comment LinuxCNC executes (which may run Python) in its place.
    fn execute_block(&mut self) -> Result<(), Fault> {
        if self.machine.syntax.block.empty {
            return self.convert_comment();
        }
        let plan = self.machine.execute_settings()?;
        self.convert_comment()?;
        let user_m_missing = self.user_m_missing();
        self.machine.execute(plan, user_m_missing)
    }

    /// The line's last comment, as LinuxCNC executes it first (`convert_comment`): `abort,`
    /// ([`Machine::abort_comment`]), or Python's `py,`, `pyrun,`, `pyreload`, run to their
    /// end before the rest of the line.
    pub(super) fn convert_comment(&mut self) -> Result<(), Fault> {
        if !self.machine.hooks.rules.executes_comments || !self.lines.line.contains(&b'(') {
            return Ok(());
        }
        if let Some((_, text, close)) = comments::last_comment(&self.lines.line)
            && let Some((action, code)) = comments::PythonComment::of(&self.lines.line[text..close])
        {
            let code = code.to_vec();
            self.python_comment(action, &code)?;
            while self.python_paused() {
                self.resume_python()?;
            }
            return Ok(());
        }
        self.machine.abort_comment(&self.lines.line)
    }

    /// Whether a request to Python is paused (a move it made waits to be taken).
    fn python_paused(&self) -> bool {
        self.python.as_ref().is_some_and(|python| python.paused())
    }

    /// Whether `o<name> call` calls a Python function of the plug-ins' `oword` module.
    fn python_callable(&mut self, name: &str) -> Result<bool, Fault> {
        let Some(python) = self.python.as_mut() else { return Ok(false) };
        python.callable(&mut Reach { machine: &mut self.machine, control: &self.control }, name)
    }

    /// Calls the Python subroutine `name` with `arguments`, its call level entered.
    fn python_call(&mut self, name: Rc<str>, arguments: &[f64]) -> Result<(), Fault> {
        let Some(python) = self.python.as_mut() else { return Ok(()) };
        let reach = &mut Reach { machine: &mut self.machine, control: &self.control };
        let returned = python.call(reach, name, arguments)?;
        self.python_returned(returned)
    }

    /// Runs a comment's Python: `code` (a file name for [`PythonComment::RunFile`]); refused
    /// without plug-ins.
    fn python_comment(&mut self, action: PythonComment, code: &[u8]) -> Result<(), Fault> {
        let Some(python) = self.python.as_mut() else {
            return Err(python::refused(&self.machine));
        };
        let reach = &mut Reach { machine: &mut self.machine, control: &self.control };
        let returned = python.comment(reach, action, code)?;
        self.python_returned(returned)
    }

    /// Goes on with the request to Python paused, once its move has been taken.
    fn resume_python(&mut self) -> Result<(), Fault> {
        let Some(python) = self.python.as_mut() else { return Ok(()) };
        let returned =
            python.resume(&mut Reach { machine: &mut self.machine, control: &self.control })?;
        self.python_returned(returned)
    }

    /// A Python subroutine that returned leaves its call level.
    fn python_returned(&mut self, returned: Returned) -> Result<(), Fault> {
        match returned {
            Returned::Yes => self.leave_context(),
            Returned::No => Ok(()),
        }
    }

    /// Whether the block's user M-code (M100–M199) has no program where the INI file says
    /// they are (LinuxCNC's unknown M code); `false` without an INI file that says.
    fn user_m_missing(&self) -> bool {
        let Some(code) = self.machine.syntax.block.m[10] else { return false };
        let name = format!("M{}", code.code);
        self.control.user_m_dirs().is_some_and(|dirs| {
            (100..200).contains(&code.code)
                && !dirs.iter().any(|dir| self.control.environment.is_file(&dir.join(&name)))
        })
    }
}

/// The dialects' and the tool's hooks that read the input: `auto`'s look-ahead, the tool's
/// inference, a dialect's look at a line before the block reader, the end of the input.
impl<R: BufRead> Interpreter<R> {
    /// The interpreter with its dialect's settings applied (a given dialect; `auto`'s come
    /// with its decision).
    pub(super) fn with_line_limit(mut self) -> Self {
        self.apply_dialect();
        self
    }

    /// What the dialect sets before the first line: the longest line, and the feed rate before
    /// any F word (Marlin's `DEFAULT_FEEDRATE_MM_M`, 4000 mm/min).
    pub(super) fn apply_dialect(&mut self) {
        self.lines.max = self.machine.hooks.rules.max_line;
        if let Some(feed) = self.machine.hooks.rules.default_feed
            && self.machine.state.feed_rate == 0.0
        {
            self.machine.state.feed_rate = feed;
            self.machine.state.feed_mm = feed;
        }
    }

    /// Reads up to [`LOOKAHEAD_BYTES`] ahead and infers the tool from them (and from whether
    /// they are the whole program).
    pub(super) fn infer_tool(&mut self) -> Result<(), GcodeError> {
        self.machine.hooks.infer_tool = false;
        let complete = self
            .lines
            .source()
            .read_ahead(LOOKAHEAD_BYTES)
            .map_err(|source| GcodeError::Read { line: 1, source })?;
        let head = self.lines.source().head();
        // A printer's dialect implies the extruder unless the whole program feeds no filament.
        let inference = crate::tool::infer_tool(head, complete).or_else(|| {
            (!complete || crate::tool::feeds(head))
                .then(|| self.machine.hooks.dialect.implied_tool())
                .flatten()
        });
        if let Some(inference) = inference {
            self.machine.hooks.tool = inference.tool;
            self.machine.hooks.tool_inference = Some(inference);
        }
        Ok(())
    }

    /// `auto`: reads up to [`LOOKAHEAD_BYTES`] ahead and decides from them.
    pub(super) fn decide(&mut self) -> Result<(), GcodeError> {
        self.machine.hooks.undecided = false;
        let complete = self
            .lines
            .source()
            .read_ahead(LOOKAHEAD_BYTES)
            .map_err(|source| GcodeError::Read { line: 1, source })?;
        if let Some(lathe) = crate::dialect::lathe_evidence(self.lines.source().head(), complete) {
            return Err(self.lathe_program(lathe));
        }
        let found = detect_dialect(self.lines.source().head(), complete);
        let open_ended =
            complete.then(|| crate::dialect::open_ended(self.lines.source().head())).flatten();
        match (crate::dialect::weigh_extension(found, self.control.program()), open_ended) {
            (Some(detection), _) => {
                self.machine.hooks.set_dialect(detection.dialect);
                self.machine.hooks.makerbot = detection.makerbot;
                self.machine.hooks.detection = Some(detection);
                self.apply_dialect();
            }
            (None, Some(lines)) => {
                // The whole program is in the look-ahead and it has no end: Grbl's from its
                // first line, as the end would decide (`end_of_input`).
                self.machine.hooks.set_dialect(Dialect::Grbl);
                self.machine.hooks.detection = Some(Detection {
                    dialect: Dialect::Grbl,
                    reason: format!(
                        "nothing tells the dialects apart, and the program ends at line {lines} \
                         without M2 or M30, which LinuxCNC requires and Grbl does not"
                    ),
                    line: None,
                    makerbot: false,
                });
                self.apply_dialect();
            }
            (None, None) => {
                self.machine.hooks.provisional = true;
                // A long comment line further on is evidence too ([`Self::long_line_decides`]).
                self.lines.max = MAX_LONG_LINE;
            }
        }
        Ok(())
    }

    /// `auto` found nothing in its look-ahead, and the block just read is one LinuxCNC refuses
    /// and Mach3 reads (`why`): the program is Mach3's from here (every line before read the
    /// same in both).
    #[cold]
    #[inline(never)]
    fn mach3_decides(&mut self, why: &str) {
        self.machine.hooks.provisional = false;
        self.machine.hooks.set_dialect(Dialect::Mach3);
        self.machine.hooks.detection = Some(Detection {
            dialect: Dialect::Mach3,
            reason: format!(
                "nothing in the first {} KiB tells the dialects apart, and line {} has {why}, \
                 which LinuxCNC refuses and Mach3 reads",
                LOOKAHEAD_BYTES / 1024,
                self.lines.number
            ),
            line: Some(self.lines.number),
            makerbot: false,
        });
        self.apply_dialect();
    }

    /// The refusal of a lathe program, before its first line is run, at the line of its
    /// evidence.
    #[cold]
    fn lathe_program(&mut self, lathe: crate::dialect::Lathe) -> GcodeError {
        self.machine.output.finished = true;
        let end = lathe.text.trim_ascii_end().len().max(1);
        let text: String = lathe
            .text
            .chars()
            .take(MAX_LINE + 1)
            .map(|c| if c.is_control() && c != '\t' { '\u{fffd}' } else { c })
            .collect();
        let file = self.control.file.as_ref().map(|path| path.display().to_string().into());
        let at = Location { line: lathe.line, column: 1, span: (0, end), text, file };
        let message = format!(
            "a lathe program ({}): this robot is an X Y Z C arm, not a lathe, and turns no part",
            lathe.why
        );
        GcodeError::Invalid { at, message }
    }

    /// `auto` found nothing in its look-ahead, and a line further on is longer than LinuxCNC's
    /// limit: LinuxCNC would refuse it, Grbl drops its comment before its line buffer, so a line
    /// long only in its comment decides Grbl (every line before read the same in both); a long
    /// command is refused as LinuxCNC refuses it.
    #[cold]
    #[inline(never)]
    pub(super) fn long_line_decides(&mut self) -> Result<(), GcodeError> {
        if self.lines.too_long || !crate::dialect::long_only_in_comment(&self.lines.line) {
            return Err(GcodeError::LineTooLong {
                at: self.location(MAX_LINE, MAX_LINE + 1),
                max: MAX_LINE,
            });
        }
        self.machine.hooks.provisional = false;
        self.machine.hooks.set_dialect(Dialect::Grbl);
        self.machine.hooks.detection = Some(Detection {
            dialect: Dialect::Grbl,
            reason: format!(
                "nothing in the first {} KiB tells the dialects apart, and line {} is longer than \
                 LinuxCNC's {MAX_LINE} characters only in its comment, which Grbl drops before \
                 its line buffer",
                LOOKAHEAD_BYTES / 1024,
                self.lines.number
            ),
            line: Some(self.lines.number),
            makerbot: false,
        });
        self.apply_dialect();
        Ok(())
    }

    /// The end of the input: LinuxCNC wants M2, M30 or the closing `%`; the other dialects
    /// need no program end.
    pub(super) fn end_of_input(&mut self) -> Result<(), GcodeError> {
        self.machine.output.finished = true;
        if self.machine.hooks.provisional && self.machine.output.moved {
            self.machine.hooks.provisional = false;
            self.machine.hooks.set_dialect(Dialect::Grbl);
            self.machine.hooks.detection = Some(Detection {
                dialect: Dialect::Grbl,
                reason: format!(
                    "nothing tells the dialects apart, and the program ends at line {} without \
                     M2 or M30, which LinuxCNC requires and Grbl does not (the lines before, \
                     past the look-ahead, were read as LinuxCNC reads them: as Grbl does, but for \
                     Grbl's laser mode, which turns a laser off during each G0)",
                    self.lines.number
                ),
                line: None,
                makerbot: false,
            });
        }
        if !self.machine.hooks.rules.needs_program_end {
            return Ok(());
        }
        Err(match self.machine.syntax.percent {
            Percent::Open => GcodeError::NoClosingPercent { line: self.lines.number.max(1) },
            _ => GcodeError::NoProgramEnd { line: self.lines.number.max(1) },
        })
    }

    /// A dialect's look at the line before the block reader; `Ok(true)` when it consumed it.
    pub(super) fn dialect_prelude(&mut self) -> Result<bool, GcodeError> {
        match self.machine.hooks.dialect.prelude(&self.lines.line) {
            Prelude::Block => Ok(false),
            Prelude::Event { name, known } => {
                self.machine.record(&name, known);
                Ok(true)
            }
            Prelude::ExtruderMode { name, relative } => {
                self.machine.hooks.e_relative = relative;
                self.machine.record(&name, true);
                Ok(true)
            }
            Prelude::Home { axes } => {
                // One rapid of the named axes to the home pose (G28's stored position), with no
                // intermediate point.
                let mut end = self.machine.state.current;
                for axis in (0..4).filter(|&axis| axes[axis]) {
                    let machine = self.machine.state.mm_to_program(
                        axis,
                        self.machine.state.params.get(G28_HOME + axis_slot(axis)),
                    );
                    end[axis] = machine
                        - self.machine.state.origin[axis]
                        - self.machine.state.axis_offset[axis];
                }
                self.machine.move_to(end, None);
                self.machine.state.publish_position();
                Ok(true)
            }
            Prelude::Refuse { start, end, code, note } => {
                Err(self.error(Fault::not_supported(start, end, code, note)))
            }
        }
    }
}

/// C's `%.4g`, roughly: four significant digits, trailing zeros dropped.
fn format_g4(value: f64) -> String {
    if value == 0.0 {
        return "0".to_owned();
    }
    let exponent = value.abs().log10().floor() as i32;
    if !(-5..4).contains(&exponent) {
        return format!("{value:.3e}");
    }
    let decimals = (3 - exponent).max(0) as usize;
    let text = format!("{value:.decimals$}");
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_owned()
    } else {
        text
    }
}

impl<R: BufRead> Iterator for Interpreter<R> {
    type Item = Result<Motion, GcodeError>;

    fn next(&mut self) -> Option<Self::Item> {
        loop {
            if let Some(motion) = self.machine.output.queue.pop_front() {
                if self.machine.output.given == self.machine.output.max_motions {
                    return Some(Err(self.too_many_motions(motion.line)));
                }
                self.machine.output.given += 1;
                return Some(Ok(motion));
            }
            if self.machine.output.finished {
                return None;
            }
            if let Err(err) = self.step() {
                self.machine.output.finished = true;
                self.machine.output.queue.clear();
                return Some(Err(err));
            }
        }
    }
}

impl<R: BufRead> Interpreter<R> {
    /// The error of a program that goes on past [`Config::max_motions`] motions, at the line
    /// of the first motion past them; nothing more is read.
    #[cold]
    #[inline(never)]
    fn too_many_motions(&mut self, line: usize) -> GcodeError {
        self.machine.output.finished = true;
        self.machine.output.queue.clear();
        let max = self.machine.output.max_motions;
        let message = format!(
            "the program goes on past {max} motions, the most one run may make (line {line} \
             makes the next): an endless loop that moves? (a longer program needs more \
             motions allowed)"
        );
        self.error(Fault {
            kind: FaultKind::Needs(Setting::MaxMotions),
            ..self.machine.line_fault(message)
        })
    }
}

/// Whether `raw[at..]` is an exponent written right after a number (`e-15` in `6.2e-15`).
fn exponent_at(raw: &[u8], at: usize) -> bool {
    let Some(rest) = raw.get(at..) else { return false };
    let after_number = at > 0 && matches!(raw[at - 1], b'0'..=b'9' | b'.');
    let rest = match rest {
        [b'e' | b'E', b'+' | b'-', rest @ ..] | [b'e' | b'E', rest @ ..] => rest,
        _ => return false,
    };
    after_number && rest.first().is_some_and(u8::is_ascii_digit)
}

/// LinuxCNC's `round_to_int`: `floor(x + 0.5)` (as a float: the caller bounds it).
fn round_to_int(x: f64) -> f64 {
    (x + 0.5).floor()
}

#[cfg(test)]
mod tests {
    use super::motion::arc_length;
    use super::*;

    #[test]
    fn g4_formats_like_c() {
        assert_eq!(format_g4(0.03), "0.03");
        assert_eq!(format_g4(1.0), "1");
        assert_eq!(format_g4(0.123456), "0.1235");
    }

    #[test]
    fn arc_lengths_follow_the_turns() {
        let quarter = arc_length([1.0, 0.0, 0.0], [0.0, 0.0], 1, [0.0, 1.0, 0.0]);
        assert!((quarter - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
        let three_quarters = arc_length([1.0, 0.0, 0.0], [0.0, 0.0], -1, [0.0, 1.0, 0.0]);
        assert!((three_quarters - 3.0 * std::f64::consts::FRAC_PI_2).abs() < 1e-12);
        let full = arc_length([1.0, 0.0, 0.0], [0.0, 0.0], 2, [1.0, 0.0, 0.0]);
        assert!((full - 4.0 * std::f64::consts::PI).abs() < 1e-12);
    }
}
