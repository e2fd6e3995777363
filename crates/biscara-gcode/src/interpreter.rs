//! Executing blocks: LinuxCNC's modal state, order of execution, offsets, arcs and feeds.
//!
//! The state is kept as LinuxCNC keeps it — positions and offsets in the program's current
//! length units, so that its tolerances apply exactly — and every motion is converted to
//! absolute millimetres in the robot's base frame when it is emitted.

use std::collections::VecDeque;
use std::io::BufRead;

use biscara_motion::{Feed, Motion, MotionKind, Plane};

use crate::dialect::{Detection, Dialect, LOOKAHEAD_BYTES, Summary};
use crate::error::{GcodeError, Location};
use crate::ini_file::IniFile;
use crate::syntax::lexer::{
    Compact, Fault, FaultKind, InnerParen, LineReader, MAX_LINE, Seekable, UNCLOSED_COMMENT,
    compact,
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
/// O-word control flow: subroutines, conditions and loops (SPEC §4.2 tier 3).
mod control;
/// Cutter radius compensation (G40, G41, G42, G41.1, G42.1).
mod cutter_comp;
/// A block executed in LinuxCNC's order.
mod execute;
/// The Fanuc/Haas dialect: Macro B control flow, M97, machine M-codes, look-ahead codes.
mod fanuc;
/// The dialects' and the tool's hooks (SPEC §4.3, §1.6), kept apart from LinuxCNC's execution.
mod hooks;
/// M19, M48–M53, M62–M68 and the `$` word.
mod io_codes;
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
    /// Whose G-code the program is (SPEC §4.3). [`Dialect::Linuxcnc`] by default: exactly
    /// LinuxCNC's reading. [`Dialect::Auto`] decides from the program (see
    /// [`Interpreter::detection`]).
    pub dialect: Dialect,
    /// What the robot carries: what M3, M4, M5 and S mean (SPEC §1.6). The gripper by default.
    pub tool: Tool,
    /// Infer the tool from the program's first [`LOOKAHEAD_BYTES`](crate::LOOKAHEAD_BYTES) ([`crate::infer_tool`]);
    /// `tool` is kept when nothing tells. See [`Interpreter::tool_inference`].
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

/// The machine that executes blocks, not generic over the input: the block being executed,
/// LinuxCNC's modal state, the motions made, and the dialect's and tool's hooks.
#[derive(Debug)]
struct Machine {
    /// The line being read, as a block.
    syntax: Syntax,
    /// LinuxCNC's modal state and position.
    state: State,
    /// The motions made and not yet taken, and whether the program has ended.
    output: Output,
    /// The dialect's and the tool's hooks.
    hooks: hooks::Hooks,
}

/// The line being read: its significant characters, the block read from them, and how lines
/// are framed (block delete, `%`).
#[derive(Debug)]
struct Syntax {
    compact: Compact,
    block: Block,
    /// The length of the raw line (for the columns of errors).
    raw_len: usize,
    block_delete: bool,
    percent: Percent,
}

/// What the interpreter has made and not yet given.
#[derive(Debug)]
struct Output {
    queue: VecDeque<Motion>,
    /// Whether the program has ended (or failed): nothing more is read.
    finished: bool,
    /// Whether any motion was emitted (an empty program is not a program).
    moved: bool,
    /// Jumps back since the last motion.
    idle_jumps: u64,
    /// The end point of the last motion (a move to where the robot is is no motion).
    last_end: Option<[f64; 4]>,
}

impl Output {
    /// After a jump back: a move somewhere else than the last one went, or a wait, ends the
    /// run of jumps without motion. (Moves are looked at only after a jump, so that a program
    /// without loops pays one test a motion; the first move after a jump may compare with an
    /// older end point, and then there was a motion since.)
    #[cold]
    fn moved_since_jump(&mut self, kind: &MotionKind) {
        let end = kind.end();
        let waits = matches!(*kind, MotionKind::Dwell { seconds } if seconds > 0.0);
        if (end.is_some() && end != self.last_end) || waits {
            self.idle_jumps = 0;
        }
        if end.is_some() {
            self.last_end = end;
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Percent {
    /// Before the first line.
    Unknown,
    /// The program started with `%`: it ends at the next `%`.
    Open,
    /// The program did not start with `%`: it ends with M2 or M30.
    Absent,
}

/// LinuxCNC's modal state and position, in the program's current length units.
#[derive(Debug)]
struct State {
    metric: bool,
    incremental: bool,
    ijk_absolute: bool,
    plane: Plane,
    inverse_time: bool,
    /// The F number in force (program units per minute).
    feed_rate: f64,
    /// The feed rate in force as the machine holds it: mm/min, converted when it was set.
    feed_mm: f64,
    /// 0, 10, 20, 30 for G0–G3; `None` after G80 and at the start.
    motion: Option<u16>,
    current: [f64; 4],
    origin: [f64; 4],
    axis_offset: [f64; 4],
    system: usize,
    /// The rotation of the system in force about Z, degrees (G10 L2 R; 0: none).
    rotation: f64,
    params: Params,
    line: usize,
    speed: f64,
    /// The tool length offset in force (G43…), in the program units in force when it was set:
    /// as in rs274, a change of units does not convert it (it is used so by later G43, G49,
    /// G53, G28 and G10 L10), though the machine keeps the offset it was given
    /// ([`State::tool_offset_mm`]).
    tool_offset: [f64; 4],
    /// The tool length offset the machine applies, mm and degrees.
    tool_offset_mm: [f64; 4],
    /// How far tool length offsets set since the last move have shifted the current point:
    /// rs274 takes its position back from the last move after M6 (its canon does not follow).
    tool_shift: [f64; 4],
    /// A tool change (M6, M61) was made: the current point is taken back from the last move as
    /// the next line is read.
    resync: bool,
    tools: tools::Tools,
    /// The canned cycles' retract mode and sticky values.
    cycle: canned::CycleState,
    /// The modal state M70/M73 saved.
    modal_stack: modal_state::ModalStack,
    spindle: u16,
    mist: bool,
    flood: bool,
    /// `#<_value>`, `#<_value_returned>`, `#<_call_level>`.
    owords: control::Values,
    /// The path-control mode: `Some(p)` under G64 (0 when P was not given), `None` under
    /// G61/G61.1.
    blend: Option<f64>,
    /// G64 Q in millimetres when positive (LinuxCNC's naive-CAM tolerance), `None` otherwise.
    naive_cam: Option<f64>,
    /// Cutter radius compensation and the motions it holds back.
    comp: cutter_comp::CutterComp,
    /// The INI file whose variables `#<_ini[…]…>` names read, when it allows it.
    ini: Option<std::sync::Arc<IniFile>>,
    /// The axes (x y z c) a G92 named before the first motion: the program made its start
    /// point its zero there.
    zeroed_at_start: [bool; 4],
}

impl State {
    fn new(config: &Config) -> State {
        let mut params = Params::new();
        for axis in 0..4 {
            params.set(G28_HOME + axis_slot(axis), config.home[axis]);
            params.set(G30_HOME + axis_slot(axis), config.home[axis]);
            params.set(coordinate_system_base(1) + axis_slot(axis), config.origin[axis]);
        }
        params.set(COORDINATE_SYSTEM, 1.0);
        let start = config.start.unwrap_or(config.home);
        let current = std::array::from_fn(|axis| start[axis] - config.origin[axis]);
        let mut state = State {
            metric: true,
            incremental: false,
            ijk_absolute: false,
            plane: Plane::Xy,
            inverse_time: false,
            feed_rate: 0.0,
            feed_mm: 0.0,
            motion: None,
            current,
            origin: config.origin,
            axis_offset: [0.0; 4],
            system: 1,
            rotation: 0.0,
            params,
            line: 0,
            speed: 0.0,
            tool_offset: [0.0; 4],
            tool_offset_mm: [0.0; 4],
            tool_shift: [0.0; 4],
            resync: false,
            tools: tools::Tools::new(config.tool_table.as_deref()),
            cycle: canned::CycleState::default(),
            modal_stack: modal_state::ModalStack::default(),
            spindle: 5,
            mist: false,
            flood: false,
            owords: control::Values::default(),
            blend: config.blend,
            naive_cam: None,
            comp: cutter_comp::CutterComp::new(),
            ini: config.ini.clone().filter(|ini| ini.variables_enabled()),
            zeroed_at_start: [false; 4],
        };
        state.publish_position();
        state
    }

    /// Millimetres per program unit.
    fn factor(&self) -> f64 {
        if self.metric { 1.0 } else { MM_PER_INCH }
    }

    /// Program units → mm for `axis` (C is in degrees whatever the units).
    fn to_mm(&self, axis: usize, value: f64) -> f64 {
        if axis == 3 { value } else { value * self.factor() }
    }

    fn mm_to_program(&self, axis: usize, value: f64) -> f64 {
        if axis == 3 { value } else { value / self.factor() }
    }

    /// Whether the G92 offsets are in force (parameter 5210: G92 and G92.3 set it, G92.1 and
    /// G92.2 clear it).
    fn g92_in_force(&self) -> bool {
        self.params.get(G92_ENABLED) != 0.0
    }

    /// A tool table entry's offsets `[x, y, z, c]` (mm, degrees) in program units.
    fn offsets_in_program_units(&self, entry: &ToolEntry) -> [f64; 4] {
        std::array::from_fn(|axis| self.mm_to_program(axis, entry.offset[axis]))
    }

    /// A position in the current coordinate system → absolute mm and degrees.
    fn absolute(&self, position: [f64; 4]) -> [f64; 4] {
        if self.rotation != 0.0 {
            return self.absolute_rotated(position);
        }
        std::array::from_fn(|axis| {
            self.to_mm(axis, position[axis] + self.origin[axis] + self.axis_offset[axis])
                + self.tool_offset_mm[axis]
        })
    }

    /// Parameters 5420–5428: the current position.
    fn publish_position(&mut self) {
        for axis in 0..4 {
            self.params.set(5420 + axis_slot(axis), self.current[axis]);
        }
    }
}

impl Predefined for State {
    fn predefined(&self, name: &[u8]) -> Option<f64> {
        let flag = |condition: bool| if condition { 1.0 } else { 0.0 };
        let machine = |axis: usize| self.machine(self.current)[axis];
        Some(match name {
            b"_x" => self.current[0],
            b"_y" => self.current[1],
            b"_z" => self.current[2],
            b"_c" => self.current[3],
            b"_a" | b"_b" | b"_u" | b"_v" | b"_w" => 0.0,
            b"_abs_x" => machine(0),
            b"_abs_y" => machine(1),
            b"_abs_z" => machine(2),
            b"_abs_c" => machine(3),
            b"_abs_a" | b"_abs_b" | b"_abs_u" | b"_abs_v" | b"_abs_w" => 0.0,
            b"_metric" => flag(self.metric),
            b"_imperial" => flag(!self.metric),
            b"_absolute" => flag(!self.incremental),
            b"_incremental" => flag(self.incremental),
            b"_inverse_time" => flag(self.inverse_time),
            b"_units_per_minute" => flag(!self.inverse_time),
            b"_units_per_rev" => 0.0,
            b"_ijk_absolute_mode" => flag(self.ijk_absolute),
            b"_coord_system" => match self.system {
                7..=9 => 590.0 + (self.system - 6) as f64,
                n => 530.0 + 10.0 * n as f64,
            },
            b"_plane" => match self.plane {
                Plane::Xy => 170.0,
                Plane::Xz => 180.0,
                Plane::Yz => 190.0,
            },
            b"_motion_mode" => self.motion.map_or(800.0, f64::from),
            b"_ccomp" => self.comp.code(),
            b"_feed" => self.feed_rate,
            b"_rpm" => self.speed,
            b"_current_tool" => f64::from(self.tools.spindle.tool),
            b"_selected_tool" => self.tools.selected_tool,
            b"_current_pocket" => self.tools.current_pocket,
            b"_selected_pocket" => self.tools.selected_pocket,
            b"_tool_offset" => flag(self.tools.offset_active),
            b"_spindle_on" => flag(self.spindle != 5),
            b"_spindle_cw" => flag(self.spindle == 3),
            b"_mist" => flag(self.mist),
            b"_flood" => flag(self.flood),
            b"_line" => self.line as f64,
            b"_lathe_diameter_mode" => 0.0,
            b"_lathe_radius_mode" => 1.0,
            b"_spindle_rpm_mode" => 1.0,
            b"_spindle_css_mode" => 0.0,
            b"_speed_override" | b"_feed_override" | b"_adaptive_feed" | b"_feed_hold" => 0.0,
            b"_value" => self.owords.value,
            b"_value_returned" => flag(self.owords.returned),
            b"_call_level" => self.owords.level as f64,
            b"_remap_level" | b"_task" => 0.0,
            b"_vmajor" => 2.0,
            b"_vminor" => 9.0,
            // An INI file variable: read-only, as LinuxCNC caches it.
            _ => return self.ini.as_ref()?.variable(name),
        })
    }

    fn defining_sub(&self) -> bool {
        self.owords.defining
    }

    fn ini_why_not(&self, name: &[u8]) -> Option<String> {
        Some(self.ini.as_ref()?.why_not(name))
    }
}

/// What the program told so far, as the caller asks.
impl<R: BufRead> Interpreter<R> {
    /// The dialect being read: the configured one, or what `auto` chose so far.
    pub fn dialect(&self) -> Dialect {
        self.machine.hooks.dialect
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

    /// The tool the program was found to be written for, when [`Config::infer_tool`](crate::Config::infer_tool)
    /// asked and something told (known once the first motion is read).
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
        let raw = &self.lines.line;
        let shown = &raw[..raw.len().min(MAX_LINE + 1)];
        let text: String = String::from_utf8_lossy(shown)
            .chars()
            .map(|c| if c.is_control() && c != '\t' { '\u{fffd}' } else { c })
            .collect();
        let file = self.control.file.as_ref().map(|path| path.display().to_string().into());
        Location { line: self.lines.number, column: start + 1, span: (start, end), text, file }
    }

    fn error(&self, fault: Fault) -> GcodeError {
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
                if let Some(err) = self.control_end() {
                    return Err(err);
                }
                if let Some((target, line)) = self.machine.hooks.fanuc.seeking {
                    return Err(GcodeError::NoBlockNumber { line, target });
                }
                if self.machine.hooks.dialect != Dialect::Linuxcnc {
                    self.machine.flush_cutter_comp().map_err(|fault| self.error(fault))?;
                }
                return self.end_of_input();
            }
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
                continue;
            }
            if self.machine.syntax.percent == Percent::Unknown {
                if trimmed.first() == Some(&b'%') {
                    self.machine.syntax.percent = Percent::Open;
                    continue;
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
                return Ok(());
            }
            self.machine.state.line = self.lines.number;
            if self.machine.state.resync {
                self.machine.resync_position();
            }
            if self.machine.hooks.dialect != Dialect::Linuxcnc && self.dialect_prelude()? {
                if !self.machine.output.queue.is_empty() {
                    return Ok(());
                }
                continue;
            }
            let inner = match self.machine.hooks.dialect {
                Dialect::Mach3 | Dialect::Marlin | Dialect::Fanuc => InnerParen::Opens,
                Dialect::Grbl => InnerParen::Ignored,
                _ => InnerParen::Refused,
            };
            if let Err(fault) = compact(&self.lines.line, &mut self.machine.syntax.compact, inner) {
                // Grbl ends a `(` comment at the end of its line (protocol.c: "ignore all
                // characters until ')' or EOL"): closed there, the line is read.
                if self.fanuc_seeking() {
                    continue;
                }
                if self.machine.hooks.dialect != Dialect::Grbl || fault.message != UNCLOSED_COMMENT
                {
                    return Err(self.error(fault));
                }
            }
            if self.machine.hooks.makerbot {
                self.machine.rename_makerbot_a();
            }
            if self.machine.syntax.compact.bytes().is_empty() {
                continue;
            }
            if self.machine.syntax.block_delete && self.machine.syntax.compact.bytes()[0] == b'/' {
                continue;
            }
            if self.machine.hooks.dialect == Dialect::Fanuc
                && let fanuc::FanucLine::Done =
                    self.fanuc_line().map_err(|fault| self.error(fault))?
            {
                if !self.machine.output.queue.is_empty() {
                    return Ok(());
                }
                continue;
            }
            let bytes = self.machine.syntax.compact.bytes();
            let g65 = matches!(self.machine.hooks.dialect, Dialect::Mach3 | Dialect::Fanuc)
                && control::may_call_g65(bytes);
            if (self.control.engaged() || control::may_control(bytes) || g65)
                && self.control_line()?
            {
                // (A line skipped inside a false `if` is no O-word of its own.)
                if self.machine.hooks.dialect == Dialect::Grbl
                    && control::may_control(self.machine.syntax.compact.bytes())
                {
                    self.machine.hooks.summary.count_refused("O-words");
                }
                if !self.machine.output.queue.is_empty() {
                    // A Python subroutine's move.
                    return Ok(());
                }
                continue;
            }
            if self.machine.syntax.compact.bytes()[0] == b';'
                && self.machine.hooks.dialect == Dialect::Linuxcnc
                && self.lines.line.starts_with(b";py,")
            {
                // LinuxCNC runs a line that starts with `;py,` as it reads it (`read_semicolon`).
                let code = self.lines.line[4..].to_vec();
                self.python_comment(comments::PythonComment::Run, &code)
                    .map_err(|fault| self.error(fault))?;
                if !self.machine.output.queue.is_empty() {
                    return Ok(());
                }
                continue;
            }
            let raw_len = self.lines.line.len();
            let result = {
                let mut reader = Reader::new(
                    &self.machine.syntax.compact,
                    raw_len,
                    &self.machine.state.params,
                    &self.machine.state,
                )
                .mach3(self.machine.hooks.dialect == Dialect::Mach3);
                reader.read_block(&mut self.machine.syntax.block)
            };
            result.map_err(|fault| self.error(fault))?;
            if self.machine.hooks.dialect != Dialect::Linuxcnc {
                if self.machine.hooks.dialect == Dialect::Grbl {
                    self.machine.count_refused_by_grbl();
                }
                self.machine.hooks.pending_extrude = None;
                if self.machine.adapt_block().map_err(|fault| self.error(fault))? {
                    continue;
                }
            }
            self.execute_block().map_err(|fault| self.error(fault))?;
            if !self.machine.output.queue.is_empty() || self.machine.output.finished {
                return Ok(());
            }
        }
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
        if self.machine.hooks.dialect != Dialect::Linuxcnc || !self.lines.line.contains(&b'(') {
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

impl Machine {
    /// A fault about the whole line.
    fn line_fault(&self, message: impl Into<String>) -> Fault {
        Fault::invalid(0, self.syntax.raw_len.max(1), message)
    }

    /// Raw column range of the block's compact range `start..end`.
    fn span(&self, start: usize, end: usize) -> (usize, usize) {
        let raw_len = self.syntax.raw_len;
        let first = self.syntax.compact.column(start, raw_len);
        let last =
            if end > start { self.syntax.compact.column(end - 1, raw_len) + 1 } else { first };
        (first, last.max(first + 1))
    }

    fn fault_at(&self, start: usize, end: usize, message: impl Into<String>) -> Fault {
        let (first, last) = self.span(start, end);
        Fault::invalid(first, last, message)
    }

    fn word_fault(&self, word: Word, message: impl Into<String>) -> Fault {
        self.fault_at(word.at, word.end, message)
    }

    fn code_fault(&self, code: Code, message: impl Into<String>) -> Fault {
        self.fault_at(code.at, code.end, message)
    }

    fn emit(&mut self, kind: MotionKind) {
        if self.hooks.dialect == Dialect::Grbl && self.hooks.tool == Tool::Laser {
            self.grbl_laser_gate(&kind);
        }
        let extrude = if kind.end().is_some() { self.hooks.pending_extrude.take() } else { None };
        self.output.moved = true;
        if self.output.idle_jumps != 0 {
            self.output.moved_since_jump(&kind);
        }
        let blend = kind.end().and(self.state.blend);
        let naive_cam = self.naive_cam(&kind, blend);
        let motion = Motion { line: self.state.line, kind, extrude, blend, naive_cam };
        if self.state.comp.holding() {
            self.state.comp.hold(motion);
        } else {
            self.output.queue.push_back(motion);
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
