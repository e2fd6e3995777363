//! Executing blocks: LinuxCNC's modal state, order of execution, offsets, arcs and feeds.
//!
//! The state is kept as LinuxCNC keeps it — positions and offsets in the program's current
//! length units, so that its tolerances apply exactly — and every motion is converted to
//! absolute millimetres in the robot's base frame when it is emitted.

use std::collections::VecDeque;
use std::io::BufRead;

use biscara_motion::{Feed, Motion, MotionKind, Plane};

use crate::dialect::{Detection, Dialect, Summary};
use crate::error::{GcodeError, Location};
use crate::ini_file::IniFile;
use crate::lexer::{
    Compact, Fault, FaultKind, InnerParen, LineReader, MAX_LINE, Seekable, UNCLOSED_COMMENT,
    compact,
};
use crate::params::{
    COORDINATE_SYSTEM, G28_HOME, G30_HOME, G92_ENABLED, G92_OFFSET, Params, axis_slot,
    coordinate_system_base,
};
use crate::parser::{Block, Code, Predefined, Reader, Support, Word, g_group, m_group};
use crate::tool::{Tool, ToolInference};
use crate::tool_table::{ToolEntry, ToolTable};

/// Canned cycles: G73, G74, G81–G89, G98/G99.
mod canned;
/// O-word control flow: subroutines, conditions and loops (SPEC §4.2 tier 3).
mod control;
/// Cutter radius compensation (G40, G41, G42, G41.1, G42.1).
mod cutter_comp;
/// The Fanuc/Haas dialect: Macro B control flow, M97, machine M-codes, look-ahead codes.
mod fanuc;
/// The dialects' and the tool's hooks (SPEC §4.3, §1.6), kept apart from LinuxCNC's execution.
mod hooks;
/// M19, M48–M53, M62–M68 and the `$` word.
mod io_codes;
/// M70–M73: the modal state saved and restored.
mod modal_state;
/// Polar coordinates (`@`, `^`).
mod polar;
/// Probing, G38.2–G38.5.
mod probe;
/// A program's Python: LinuxCNC's Python plug-ins (`[PYTHON]`), `;py,` lines, `(py,…)`.
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

/// The iterator returned by [`interpret`].
#[derive(Debug)]
pub struct Interpreter<R> {
    lines: LineReader<R>,
    compact: Compact,
    block: Block,
    state: State,
    queue: VecDeque<Motion>,
    block_delete: bool,
    percent: Percent,
    finished: bool,
    /// The dialect being read ([`Dialect::Linuxcnc`] while `auto` has not decided).
    dialect: Dialect,
    /// Whether `auto` still has to read ahead (before the first line).
    undecided: bool,
    /// `auto` found nothing in its look-ahead: read as LinuxCNC, and perhaps decided at the end.
    provisional: bool,
    detection: Option<Detection>,
    summary: Summary,
    tool: Tool,
    /// Whether the tool is still to be inferred from the look-ahead.
    infer_tool: bool,
    /// What the inference found.
    tool_inference: Option<ToolInference>,
    /// Whether the tool is on (M3/M4 until M5 or M6).
    tool_on: bool,
    /// Grbl's laser mode: the laser, on, is off during the rapids since the last feed move
    /// (a `laser_off` was emitted before the first of them; the next feed move turns it on).
    laser_rapid_off: bool,
    /// MakerBot's flavour: the A word is the extruder.
    makerbot: bool,
    /// Marlin's extruder: position (mm) and whether E words are relative (M83, G91).
    e_position: f64,
    e_relative: bool,
    /// The extrusion of the block being executed, for its first move.
    pending_extrude: Option<f64>,
    /// Whether any motion was emitted (an empty program is not a program).
    moved: bool,
    /// The axes (x y z c) a G92 named before the first motion: the program made its start
    /// point its zero there.
    zeroed_at_start: [bool; 4],
    /// O-word control flow.
    control: Box<control::Control>,
    /// The Fanuc dialect's control flow (GOTO, WHILE … DO, M97).
    fanuc: fanuc::Fanuc,
    /// The Python plug-ins the INI file's `[PYTHON]` section loads (`None`: it has none).
    python: Option<Box<python::Python>>,
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

impl<R: BufRead> Interpreter<R> {
    fn new(reader: R, config: &Config) -> Interpreter<R> {
        Interpreter {
            lines: LineReader::new(reader),
            compact: Compact::default(),
            block: Block::default(),
            state: State::new(config),
            queue: VecDeque::with_capacity(8),
            block_delete: config.block_delete,
            percent: Percent::Unknown,
            finished: false,
            dialect: if config.dialect == Dialect::Auto {
                Dialect::Linuxcnc
            } else {
                config.dialect
            },
            undecided: config.dialect == Dialect::Auto,
            provisional: false,
            detection: None,
            summary: Summary::default(),
            tool: config.tool,
            infer_tool: config.infer_tool,
            tool_inference: None,
            tool_on: false,
            laser_rapid_off: false,
            makerbot: false,
            e_position: 0.0,
            e_relative: false,
            pending_extrude: None,
            moved: false,
            zeroed_at_start: [false; 4],
            control: Box::new(control::Control::new(config.ini.as_deref(), config.max_idle_jumps)),
            fanuc: fanuc::Fanuc::default(),
            python: config
                .ini
                .as_deref()
                .and_then(crate::python_plugin::PluginSetup::from_ini)
                .map(|setup| Box::new(python::Python::new(setup))),
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
        }
    }

    /// Reads and executes lines until a motion is queued, the program ends, or an error.
    fn step(&mut self) -> Result<(), GcodeError> {
        if self.undecided {
            self.decide()?;
        }
        if self.infer_tool {
            self.infer_tool()?;
        }
        if self.python_paused() {
            self.resume_python().map_err(|fault| self.error(fault))?;
            if !self.queue.is_empty() {
                return Ok(());
            }
        }
        loop {
            let more = self
                .lines
                .next_line()
                .map_err(|source| GcodeError::Read { line: self.lines.number + 1, source })?;
            if !more {
                if let Some(err) = self.control_end() {
                    return Err(err);
                }
                if let Some((target, line)) = self.fanuc.seeking {
                    return Err(GcodeError::NoBlockNumber { line, target });
                }
                if self.dialect != Dialect::Linuxcnc {
                    self.flush_cutter_comp().map_err(|fault| self.error(fault))?;
                }
                return self.end_of_input();
            }
            if self.provisional && self.lines.line.len() > MAX_LINE {
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
            if self.percent == Percent::Unknown {
                if trimmed.first() == Some(&b'%') {
                    self.percent = Percent::Open;
                    continue;
                }
                self.percent = Percent::Absent;
            } else if self.percent == Percent::Open && trimmed == b"%" && !self.lines.in_file() {
                if let Some(err) = self.control_percent() {
                    return Err(err);
                }
                // rs274 never sends the motions cutter compensation holds at a closing `%`.
                self.state.comp.discard();
                self.finished = true;
                return Ok(());
            }
            self.state.line = self.lines.number;
            if self.state.resync {
                self.resync_position();
            }
            if self.dialect != Dialect::Linuxcnc && self.dialect_prelude()? {
                if !self.queue.is_empty() {
                    return Ok(());
                }
                continue;
            }
            let inner = match self.dialect {
                Dialect::Mach3 | Dialect::Marlin | Dialect::Fanuc => InnerParen::Opens,
                Dialect::Grbl => InnerParen::Ignored,
                _ => InnerParen::Refused,
            };
            if let Err(fault) = compact(&self.lines.line, &mut self.compact, inner) {
                // Grbl ends a `(` comment at the end of its line (protocol.c: "ignore all
                // characters until ')' or EOL"): closed there, the line is read.
                if self.fanuc_seeking() {
                    continue;
                }
                if self.dialect != Dialect::Grbl || fault.message != UNCLOSED_COMMENT {
                    return Err(self.error(fault));
                }
            }
            if self.makerbot {
                self.rename_makerbot_a();
            }
            if self.compact.bytes().is_empty() {
                continue;
            }
            if self.block_delete && self.compact.bytes()[0] == b'/' {
                continue;
            }
            if self.dialect == Dialect::Fanuc
                && let fanuc::FanucLine::Done =
                    self.fanuc_line().map_err(|fault| self.error(fault))?
            {
                if !self.queue.is_empty() {
                    return Ok(());
                }
                continue;
            }
            let bytes = self.compact.bytes();
            let g65 = matches!(self.dialect, Dialect::Mach3 | Dialect::Fanuc)
                && control::may_call_g65(bytes);
            if (self.control.engaged() || control::may_control(bytes) || g65)
                && self.control_line()?
            {
                // (A line skipped inside a false `if` is no O-word of its own.)
                if self.dialect == Dialect::Grbl && control::may_control(self.compact.bytes()) {
                    self.summary.count_refused("O-words");
                }
                if !self.queue.is_empty() {
                    // A Python subroutine's move.
                    return Ok(());
                }
                continue;
            }
            if self.compact.bytes()[0] == b';'
                && self.dialect == Dialect::Linuxcnc
                && self.lines.line.starts_with(b";py,")
            {
                // LinuxCNC runs a line that starts with `;py,` as it reads it (`read_semicolon`).
                let code = self.lines.line[4..].to_vec();
                self.python_comment(python::PythonComment::Run, &code)
                    .map_err(|fault| self.error(fault))?;
                if !self.queue.is_empty() {
                    return Ok(());
                }
                continue;
            }
            let raw_len = self.lines.line.len();
            let result = {
                let mut reader =
                    Reader::new(&self.compact, raw_len, &self.state.params, &self.state)
                        .mach3(self.dialect == Dialect::Mach3);
                reader.read_block(&mut self.block)
            };
            result.map_err(|fault| self.error(fault))?;
            if self.dialect != Dialect::Linuxcnc {
                if self.dialect == Dialect::Grbl {
                    self.count_refused_by_grbl();
                }
                self.pending_extrude = None;
                if self.adapt_block().map_err(|fault| self.error(fault))? {
                    continue;
                }
            }
            self.execute().map_err(|fault| self.error(fault))?;
            if !self.queue.is_empty() || self.finished {
                return Ok(());
            }
        }
    }

    /// The line's last comment, as LinuxCNC executes it first (`convert_comment`): `abort,`
    /// ([`Interpreter::abort_comment`]), or Python's `py,`, `pyrun,`, `pyreload`, run to their
    /// end before the rest of the line.
    fn convert_comment(&mut self) -> Result<(), Fault> {
        if self.dialect != Dialect::Linuxcnc || !self.lines.line.contains(&b'(') {
            return Ok(());
        }
        if let Some((_, text, close)) = self.last_comment()
            && let Some((action, code)) = python::PythonComment::of(&self.lines.line[text..close])
        {
            let code = code.to_vec();
            self.python_comment(action, &code)?;
            while self.python_paused() {
                self.resume_python()?;
            }
            return Ok(());
        }
        self.abort_comment()
    }

    /// Where the line's last `( … )` comment before any `;` is: its `(`, its text (after the
    /// blanks that follow the `(`) and its `)`.
    fn last_comment(&self) -> Option<(usize, usize, usize)> {
        let line = &self.lines.line;
        let mut last = None;
        let mut at = 0;
        while let Some(open) = line[at..].iter().position(|&b| b == b'(').map(|i| at + i) {
            if line[at..open].contains(&b';') {
                break;
            }
            let Some(close) = line[open..].iter().position(|&b| b == b')').map(|i| open + i) else {
                break;
            };
            last = Some((open, close));
            at = close + 1;
        }
        let (open, close) = last?;
        let blanks = line[open + 1..close].iter().take_while(|b| b.is_ascii_whitespace()).count();
        Some((open, open + 1 + blanks, close))
    }

    /// LinuxCNC's `(ABORT, text)`: the line's last comment, when it reads `abort,` (spaces
    /// before it allowed, any case), stops the program with its text as the message, `#n` and
    /// `#<name>` in it replaced by their values (`######` when undefined).
    fn abort_comment(&self) -> Result<(), Fault> {
        let line = &self.lines.line;
        let Some((open, text, close)) = self.last_comment() else { return Ok(()) };
        let text = &line[text..close];
        if !text.get(..6).is_some_and(|head| head.eq_ignore_ascii_case(b"abort,")) {
            return Ok(());
        }
        let text = &text[6..];
        let mut message = String::new();
        let mut index = 0;
        while index < text.len() {
            if text[index] != b'#' {
                let run =
                    text[index..].iter().position(|&b| b == b'#').unwrap_or(text.len() - index);
                message.push_str(&String::from_utf8_lossy(&text[index..index + run]));
                index += run;
                continue;
            }
            let rest = &text[index + 1..];
            if rest.first() == Some(&b'<')
                && let Some(end) = rest.iter().position(|&b| b == b'>')
            {
                let name: Vec<u8> = rest[1..end]
                    .iter()
                    .filter(|b| !b.is_ascii_whitespace())
                    .map(u8::to_ascii_lowercase)
                    .collect();
                let value = if name.first() == Some(&b'_') {
                    self.state.predefined(&name).or_else(|| self.state.params.named(&name))
                } else {
                    self.state.params.named(&name)
                };
                match value {
                    Some(value) => message.push_str(&format!("{value:.6}")),
                    None => message.push_str("######"),
                }
                index += end + 2;
                continue;
            }
            let digits = rest.iter().take_while(|b| b.is_ascii_digit()).count();
            let number = std::str::from_utf8(&rest[..digits]).ok().and_then(|d| d.parse().ok());
            match number.filter(|&n: &usize| (1..crate::params::MAX_PARAMETERS).contains(&n)) {
                Some(number) => message.push_str(&format!("{:.6}", self.state.params.get(number))),
                None if digits == 0 => message.push('#'),
                None => message.push_str("######"),
            }
            index += 1 + digits;
        }
        if message.is_empty() {
            message.push_str("Unknown error, bad error code");
        }
        let (first, last) = (open, close + 1);
        Err(Fault::invalid(first, last, message))
    }

    /// Raw column range of the block's compact range `start..end`.
    fn span(&self, start: usize, end: usize) -> (usize, usize) {
        let raw_len = self.lines.line.len();
        let first = self.compact.column(start, raw_len);
        let last = if end > start { self.compact.column(end - 1, raw_len) + 1 } else { first };
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
        if self.dialect == Dialect::Grbl && self.tool == Tool::Laser {
            self.grbl_laser_gate(&kind);
        }
        let extrude = if kind.end().is_some() { self.pending_extrude.take() } else { None };
        self.moved = true;
        if self.control.idle_jumps != 0 {
            self.moved_since_jump(&kind);
        }
        let blend = kind.end().and(self.state.blend);
        let naive_cam = self.naive_cam(&kind, blend);
        let motion = Motion { line: self.state.line, kind, extrude, blend, naive_cam };
        if self.state.comp.holding() {
            self.state.comp.hold(motion);
        } else {
            self.queue.push_back(motion);
        }
    }

    /// Executes the block just read, in LinuxCNC's order of execution.
    fn execute(&mut self) -> Result<(), Fault> {
        let block = &self.block;
        if block.empty {
            return self.convert_comment();
        }
        self.check_support()?;
        if self.block.extra.is_some() {
            self.check_polar_words()?;
        }
        let motion_code = self.block.g[1];
        let group0 = self.block.g[0];
        let axis_words =
            AXES.iter().any(|&letter| self.block.word(letter).is_some()) || self.block.polar();
        // rs274 checks the axis words of a motion other than G0–G3 first of all
        // (`enhance_block`).
        if let Some(code) = motion_code
            && !matches!(code.code, 0 | 10 | 20 | 30 | 800)
            && !axis_words
        {
            return Err(self.code_fault(code, "All axes missing with motion code"));
        }
        let uses_axes = |code: u16| matches!(code, 100 | 280 | 300 | 520 | 920);
        // check_g_codes / check_other_codes
        if let (Some(zero), Some(_)) = (group0, motion_code)
            && uses_axes(zero.code)
        {
            return Err(self.code_fault(zero, "Cannot use two g codes that both use axis values"));
        }
        // G43.1 and G43.2 use the axis words too (without making the modal motion move).
        let group0_uses_axes = group0.is_some_and(|zero| uses_axes(zero.code))
            || self.block.g[8].is_some_and(|code| matches!(code.code, 431 | 432));
        let modal_motion = match motion_code {
            Some(code) => Some(code.code),
            None => self.state.motion,
        };
        if axis_words && !group0_uses_axes {
            if motion_code.is_some_and(|code| code.code == 800) {
                let word = self.first_axis_word().unwrap_or(Word { value: 0.0, at: 0, end: 1 });
                return Err(self.word_fault(word, "Cannot use axis values with g80"));
            }
            if modal_motion.is_none() {
                let word = self.first_axis_word().unwrap_or(Word { value: 0.0, at: 0, end: 1 });
                return Err(
                    self.word_fault(word, "Cannot use axis values without a g code that uses them")
                );
            }
        }
        let motion_to_be = match motion_code {
            Some(code) if code.code != 800 => Some(code.code),
            Some(_) => None,
            None if axis_words && !group0_uses_axes => self.state.motion,
            None => None,
        };
        self.check_group_zero()?;
        if let Some(zero) = group0.filter(|zero| zero.code == 530) {
            if !matches!(motion_to_be, Some(0 | 10)) {
                return Err(self.code_fault(zero, "Must use g0 or g1 with g53"));
            }
            let incremental = match self.block.g[3] {
                Some(code) => code.code == 910,
                None => self.state.incremental,
            };
            if incremental {
                return Err(self.code_fault(zero, "Cannot use g53 incremental"));
            }
        }

        self.check_other_words(motion_to_be)?;
        // Read-only names are refused when the settings are stored, after the block's checks
        // (rs274 reports an unused E word on `#<_x>=1 E1`, not the assignment).
        for &(start, end, _) in &self.block.named {
            let name = &self.compact.bytes()[start..end];
            if name.first() == Some(&b'_') && self.state.predefined(name).is_some() {
                return Err(self.fault_at(
                    start.saturating_sub(2),
                    end + 1,
                    format!(
                        "Cannot assign to read-only parameter #<{}>",
                        String::from_utf8_lossy(name)
                    ),
                ));
            }
        }
        // Parameter settings take effect after the whole line is read.
        for index in 0..self.block.numbered.len() {
            let (number, value) = self.block.numbered[index];
            self.state.params.set(number, value);
        }
        for index in 0..self.block.named.len() {
            let (start, end, value) = self.block.named[index];
            self.state.params.set_named(&self.compact.bytes()[start..end], value);
        }
        self.convert_comment()?;

        // 3. feed mode
        if let Some(code) = self.block.g[5] {
            if code.code == 930 {
                self.state.inverse_time = true;
            } else {
                self.state.inverse_time = false;
                self.state.feed_rate = 0.0;
                self.state.feed_mm = 0.0;
            }
        }
        // 4. feed rate
        if let Some(f) = self.block.word(b'f')
            && !self.state.inverse_time
        {
            self.state.feed_rate = f.value;
            self.state.feed_mm = f.value * self.state.factor();
        }
        if self.block.extra.is_some() {
            self.check_spindle_number()?;
        }
        // 5, 6. spindle speed, tool selection: no effect on motion (a new power or speed
        // for a laser or spindle that is on).
        if let Some(s) = self.block.word(b's') {
            let changed = s.value != self.state.speed;
            self.state.speed = s.value;
            let powered = matches!(self.tool, Tool::Laser | Tool::Spindle);
            if changed && powered && self.tool_on && self.block.m[7].is_none() {
                self.tool_event(self.state.spindle);
            }
        }
        // (Calls into the tier-3 modules only when the block has their words: every line
        // passes here.)
        if self.block.word(b't').is_some() {
            self.select_tool()?;
        }
        // 7. digital and analog outputs and inputs
        if self.block.m[5].is_some() {
            self.io_output()?;
        }
        // 8. tool change: LinuxCNC stops the spindle first (here: gripper off); M61 says which
        // tool is in the spindle.
        if let Some(code) = self.block.m[6] {
            if code.code == 61 {
                self.set_current_tool(code)?;
            } else {
                self.refuse_with_comp(
                    (code.at, code.end),
                    "Cannot change tools with cutter radius compensation on",
                )?;
                self.change_tool();
                self.state.spindle = 5;
                self.tool_event(5);
            }
        }
        // 9. spindle: the gripper (or the tool)
        if let Some(code) = self.block.m[7].filter(|code| code.code >= 70) {
            if self.modal_state(code)? {
                // rs274 read the restoring codes into this block's place: the rest is lost.
                self.state.publish_position();
                return Ok(());
            }
        } else if self.block.m[7].is_some_and(|code| code.code == 19) {
            self.orient_spindle()?;
        } else if let Some(code) = self.block.m[7] {
            self.state.spindle = code.code;
            self.tool_event(code.code);
        }
        // 11. coolant
        if let Some(code) = self.block.m[8] {
            match code.code {
                7 => self.state.mist = true,
                8 => self.state.flood = true,
                _ => (self.state.mist, self.state.flood) = (false, false),
            }
        }
        // overrides
        if self.block.m[9].is_some() {
            self.overrides()?;
        }
        // 12. user M codes: LinuxCNC runs an external program; here an event, with a note.
        // With an INI file that says where the programs are, one that is not there is
        // LinuxCNC's unknown M code.
        if let Some(code) = self.block.m[10] {
            let name = format!("M{}", code.code);
            if let Some(dirs) = self.control.user_m_dirs()
                && (100..200).contains(&code.code)
                && !dirs.iter().any(|dir| dir.join(&name).is_file())
            {
                return Err(self.code_fault(
                    code,
                    format!(
                        "Unknown M code used: {name} (no program {name} in the INI file's \
                         USER_M_PATH or PROGRAM_PREFIX)"
                    ),
                ));
            }
            self.record(&name, true);
        }
        // 14. dwell
        if group0.is_some_and(|zero| zero.code == 40)
            && let Some(p) = self.block.word(b'p')
        {
            if p.value < 0.0 {
                return Err(
                    self.word_fault(p, format!("a dwell time must not be negative: P{}", p.value))
                );
            }
            self.emit(MotionKind::Dwell { seconds: p.value });
        }
        // 15. plane
        if let Some(code) = self.block.g[2] {
            let plane = match code.code {
                170 => Plane::Xy,
                180 => Plane::Xz,
                _ => Plane::Yz,
            };
            if plane != self.state.plane {
                self.refuse_with_comp(
                    (code.at, code.end),
                    "Cannot change planes with cutter radius compensation on",
                )?;
            }
            self.state.plane = plane;
        }
        // 16. length units
        if let Some(code) = self.block.g[6] {
            self.set_units(code.code == 210);
        }
        // 17. cutter radius compensation
        if self.block.g[7].is_some() {
            self.set_cutter_comp()?;
        }
        // 18. tool length offset
        if let Some(code) = self.block.g[8] {
            self.tool_length_offset(code)?;
        }
        // 19. coordinate system
        if let Some(code) = self.block.g[12] {
            let system = match code.code {
                540 => 1,
                550 => 2,
                560 => 3,
                570 => 4,
                580 => 5,
                590 => 6,
                591 => 7,
                592 => 8,
                _ => 9,
            };
            self.refuse_with_comp(
                (code.at, code.end),
                "Cannot change coordinate systems with cutter radius compensation on",
            )?;
            self.select_system(system);
        }
        // 20. path control mode
        if let Some(code) = self.block.g[13] {
            self.set_path_control(code)?;
        }
        // 21. distance modes
        if let Some(code) = self.block.g[3] {
            self.state.incremental = code.code == 910;
        }
        if let Some(code) = self.block.g[4] {
            self.state.ijk_absolute = code.code == 901;
        }
        // 23. G10, G28, G30, G92 family
        if let Some(zero) = group0 {
            match zero.code {
                100 => self.set_coordinate_data(zero)?,
                280 | 300 => {
                    self.refuse_with_comp(
                        (zero.at, zero.end),
                        "Cannot use g28 or g30 with cutter radius comp",
                    )?;
                    self.go_home(zero)?;
                }
                281 | 301 => {
                    self.refuse_with_comp(
                        (zero.at, zero.end),
                        "Cannot set reference point with cutter compensation in effect",
                    )?;
                    let base = if zero.code == 281 { G28_HOME } else { G30_HOME };
                    let machine = self.state.machine(self.state.current);
                    for (axis, machine) in machine.into_iter().enumerate() {
                        let value = self.state.to_mm(axis, machine);
                        self.state.params.set(base + axis_slot(axis), value);
                    }
                }
                920 | 520 => {
                    self.refuse_with_comp(
                        (zero.at, zero.end),
                        "Cannot change axis offsets with cutter radius comp",
                    )?;
                    if zero.code == 920 {
                        self.set_axis_offsets(zero)?;
                    } else {
                        self.set_local_offsets();
                    }
                }
                _ => {}
            }
        }
        // (rs274 ignores G92.1, G92.2 and G92.3 while cutter compensation is on)
        if let Some(code) = self.block.g[11].filter(|_| !self.state.comp.on()) {
            self.apply_g92(code.code == 923);
            if code.code == 921 {
                for slot in 0..10 {
                    self.state.params.set(G92_ENABLED + slot, 0.0);
                }
            }
        }
        // 22. retract mode
        if let Some(code) = self.block.g[10] {
            self.state.cycle.retract_to_old = code.code == 980;
        }
        // 24. motion
        let previous_motion = self.state.motion;
        // A spline leaves the modal motion as it was.
        if let Some(code) = motion_code.filter(|code| !spline::is_spline(code.code)) {
            self.state.motion = if code.code == 800 { None } else { Some(code.code) };
            if !canned::is_cycle(code.code) {
                self.state.cycle.initial_level = None;
            }
        }
        if let Some(motion) = motion_to_be {
            let g53 = group0.is_some_and(|zero| zero.code == 530);
            if self.block.extra.is_some() {
                self.apply_polar(motion, g53)?;
            }
            match motion {
                0 | 10 => self.straight(motion, g53)?,
                20 | 30 => self.arc(motion == 20)?,
                50 | 51 => self.spline(motion)?,
                code if probe::is_probe(code) => self.probe(code)?,
                _ => self.canned_cycle(motion, previous_motion == Some(motion))?,
            }
        }
        self.check_range()?;
        // 25. stop
        if let Some(code) = self.block.m[4] {
            self.flush_cutter_comp()?;
            match code.code {
                2 | 30 => {
                    self.state.comp = cutter_comp::CutterComp::new();
                    self.emit(MotionKind::End);
                    self.finished = true;
                }
                _ => self.emit(MotionKind::Pause),
            }
        }
        self.state.publish_position();
        Ok(())
    }

    /// Refuses motions whose positions or feeds are beyond any robot (a typo such as a
    /// 240-digit number), rather than passing them on.
    fn check_range(&self) -> Result<(), Fault> {
        let far = |value: &f64| value.abs() > MAX_COORDINATE;
        for motion in &self.queue {
            let value = match &motion.kind {
                MotionKind::Arc { end, center, .. } => end.iter().chain(center).copied().find(far),
                MotionKind::Rapid { end } | MotionKind::Linear { end, .. } => {
                    end.iter().copied().find(far)
                }
                kind => kind.end().and_then(|end| end.into_iter().find(far)),
            };
            if let Some(value) = value {
                let word = self.first_axis_word().map_or((0, 1), |word| (word.at, word.end));
                return Err(self.fault_at(
                    word.0,
                    word.1,
                    format!(
                        "{value:e} is out of range: positions must lie within ±{MAX_COORDINATE:e} \
                         mm (or degrees)"
                    ),
                ));
            }
        }
        Ok(())
    }

    fn first_axis_word(&self) -> Option<Word> {
        AXES.iter()
            .filter_map(|&letter| self.block.word(letter))
            .chain(self.first_polar_word())
            .min_by_key(|word| word.at)
    }

    /// Where an error of the block's motion points: its G code, or else its first axis word
    /// (a modal motion), or else the line's start.
    fn motion_span(&self) -> (usize, usize) {
        self.block.g[1].map_or_else(
            || self.first_axis_word().map_or((0, 1), |word| (word.at, word.end)),
            |code| (code.at, code.end),
        )
    }

    /// An error of the block's motion, at [`Interpreter::motion_span`].
    fn motion_fault(&self, message: impl Into<String>) -> Fault {
        let (start, end) = self.motion_span();
        self.fault_at(start, end, message)
    }

    /// LinuxCNC's checks of G4 and G10 (in `check_g_codes`, before the other words').
    fn check_group_zero(&self) -> Result<(), Fault> {
        let Some(zero) = self.block.g[0] else { return Ok(()) };
        let p = self.block.word(b'p');
        match zero.code {
            // P-1 is LinuxCNC's "no P" value.
            40 if p.is_none_or(|p| p.value == -1.0) => {
                Err(self.code_fault(zero, "Dwell time missing with g4"))
            }
            100 => {
                let l = self.block.word(b'l').map(|l| l.value as i64);
                let Some(l @ (0 | 1 | 2 | 10 | 11 | 20)) = l else {
                    return Err(self.code_fault(
                        zero,
                        "Line with G10 does not have L0, L1, L10, L11, L2, or L20",
                    ));
                };
                // (Grbl takes no P as P0: see `set_coordinate_data`.)
                let grbl_p0 = p.is_none() && self.dialect == Dialect::Grbl;
                if matches!(l, 2 | 20)
                    && !grbl_p0
                    && !p.is_some_and(|p| (0.0..=9.0).contains(&p.value) && p.value.fract() == 0.0)
                {
                    return Err(
                        self.code_fault(zero, format!("P value out of range (0-9) with G10 L{l}"))
                    );
                }
                Ok(())
            }
            520 | 920 if AXES.iter().all(|&letter| self.block.word(letter).is_none()) => {
                Err(self.code_fault(zero, "All axes missing with g52 or g92"))
            }
            _ => Ok(()),
        }
    }

    /// Refuses codes and words this interpreter does not implement.
    fn check_support(&self) -> Result<(), Fault> {
        if !self.block.unsupported {
            return Ok(());
        }
        for code in self.block.g.iter().flatten() {
            let name = || {
                if code.code % 10 == 0 {
                    format!("G{}", code.code / 10)
                } else {
                    format!("G{}.{}", code.code / 10, code.code % 10)
                }
            };
            // The span only for a refusal: this runs on every code of every line.
            match g_group(code.code) {
                Some((_, Support::No(note))) => {
                    let (first, last) = self.span(code.at, code.end);
                    return Err(Fault::not_supported(first, last, name(), note));
                }
                Some((_, Support::Cannot(reason))) => {
                    let (first, last) = self.span(code.at, code.end);
                    return Err(Fault::cannot(first, last, name(), reason));
                }
                _ => {}
            }
        }
        for code in self.block.m.iter().flatten() {
            if let Some((_, Support::No(note))) = m_group(code.code) {
                let (first, last) = self.span(code.at, code.end);
                return Err(Fault::not_supported(first, last, format!("M{}", code.code), note));
            }
        }
        Ok(())
    }

    /// LinuxCNC's checks of words no code in the block uses (`check_other_codes`, in its order:
    /// D E H I J K L P Q R).
    fn check_other_words(&self, motion: Option<u16>) -> Result<(), Fault> {
        let block = &self.block;
        let group0 = block.g[0].map(|code| code.code);
        let arc = matches!(motion, Some(20 | 30));
        let g5 = motion == Some(50);
        let spline = g5 || motion == Some(51);
        let g10 = group0 == Some(100);
        let comp_on = block.g[7].is_some_and(|code| code.code != 400);
        let cycle = motion.is_some_and(canned::is_cycle);
        let g87 = motion == Some(870);
        if cycle && let Some(c) = block.word(b'c') {
            return Err(self.word_fault(c, "Cannot put a c in canned cycle"));
        }
        if block.extra.is_some() {
            // rs274 checks the `$` word between D and E.
            if let Some(d) = block.word(b'd')
                && !comp_on
            {
                return Err(self.word_fault(
                    d,
                    "D word with no G41, G41.1, G42, G42.1, G71, G71.1, G71.2 or G96 to use it",
                ));
            }
            self.check_dollar()?;
        }
        // The use of a word is looked at only when the block has it: this runs on every line.
        for letter in [b'd', b'e', b'h', b'i', b'j', b'k', b'l'] {
            let Some(word) = block.word(letter) else { continue };
            let (used, message) = match letter {
                b'd' => (
                    comp_on,
                    "D word with no G41, G41.1, G42, G42.1, G71, G71.1, G71.2 or G96 to use it",
                ),
                b'e' => (self.io_uses_e(), "E word with no G70, G76, M66, M67 or M68 to use it"),
                b'h' => (
                    block.g[8].is_some_and(|code| matches!(code.code, 430 | 432)),
                    "H word with no G43 or G76 to use it",
                ),
                b'i' => (
                    arc || spline || g10 || g87,
                    "I word with no G2, G3, G5, G5.1, G10, G33.1, G76, or G87 to use it",
                ),
                b'j' => (
                    arc || spline || g10 || g87,
                    "J word with no G2, G3, G5, G5.1, G10, G76 or G87 to use it",
                ),
                b'k' => (arc || g87, "K word with no G2, G3, G33, G33.1, G76, or G87 to use it"),
                _ => (
                    g10 || comp_on || cycle || self.io_uses_l(),
                    "L word with no G10, cutter compensation, canned cycle, digital/analog input, \
                     M98 or NURBS code",
                ),
            };
            if !used {
                return Err(self.word_fault(word, message));
            }
        }
        // Mach3 takes the compensation radius from a P word (G41 P1.5): G41/G42 use it.
        let mach3_radius = self.dialect == Dialect::Mach3
            && block.g[7].is_some_and(|code| matches!(code.code, 410 | 420));
        if let Some(p) = block.word(b'p')
            && !mach3_radius
        {
            let g64 = block.g[13].is_some_and(|code| code.code == 640);
            let dwell_cycle = matches!(motion, Some(740 | 820 | 840 | 860 | 880 | 890));
            let user_m = block.m[10].is_some();
            let used = arc
                || g5
                || matches!(group0, Some(40 | 100))
                || g64
                || dwell_cycle
                || user_m
                || self.io_uses_p();
            if !used {
                return Err(self.word_fault(
                    p,
                    "P word with no G2 G3 G4 G10 G64 G5 G5.2 G76 G82 G86 G88 G89 or M50 M51 M52 \
                     M53 M62 M63 M64 M65 M66 M98 or user M code to use it",
                ));
            }
            // The turns of an arc, checked here with the block, before the arc's own checks.
            self.m19_p_integer(p)?;
            if arc && (round_to_int(p.value) - p.value).abs() > 0.001 {
                return Err(self.word_fault(p, "P value not an integer with M19 G2 or G3"));
            }
            if arc && round_to_int(p.value) < 1.0 {
                return Err(self.word_fault(p, "P value should be 1 or greater with G2 or G3"));
            }
        }
        if let Some(q) = block.word(b'q') {
            let g64 = block.g[13].is_some_and(|code| code.code == 640);
            let m61 = block.m[6].is_some_and(|code| code.code == 61);
            let peck = matches!(motion, Some(730 | 830));
            if !g5 && !g64 && !g10 && !m61 && !peck && block.m[10].is_none() && !self.io_uses_q() {
                return Err(self.word_fault(
                    q,
                    "Q word with no G5, G10, G64, G73, G76, G83, M19, M66, M67, M68 or user M code \
                     that uses it",
                ));
            }
        }
        let m19 = block.m[7].is_some_and(|code| code.code == 19);
        if let Some(r) = block.word(b'r')
            && !(arc || g10 || cycle || m19)
        {
            return Err(self.word_fault(r, "R word with no g code that uses it"));
        }
        Ok(())
    }

    /// G61, G61.1 (exact stop) and G64 P… Q… (blending within P of the corners, in the program's
    /// length unit, kept in millimetres; no P, or a negative one, is LinuxCNC's tolerance 0: no
    /// tolerance given).
    ///
    /// Q is LinuxCNC's naive-CAM tolerance: its motion layer (not its interpreter) may merge
    /// nearly collinear feed moves into one when every point left out lies within Q of it. The
    /// interpreter keeps every move and marks the straight feed moves under G64 with a positive
    /// Q ([`Motion::naive_cam`], millimetres); the merging is `biscara-blend`'s `NaiveCam`, before
    /// the blends. (rs274 reads Q the same way: its canonical calls carry only P.)
    fn set_path_control(&mut self, code: Code) -> Result<(), Fault> {
        if code.code != 640 {
            self.state.blend = None;
            self.state.naive_cam = None;
            return Ok(());
        }
        let scale = if self.state.metric { 1.0 } else { MM_PER_INCH };
        let p = self.block.word(b'p').map_or(0.0, |p| p.value.max(0.0));
        self.state.blend = Some(p * scale);
        let q = self.block.word(b'q').map_or(0.0, |q| q.value);
        self.state.naive_cam = (q > 0.0).then_some(q * scale);
        Ok(())
    }

    /// The naive-CAM tolerance a motion carries: G64 Q on a straight feed move under G64.
    fn naive_cam(&self, kind: &MotionKind, blend: Option<f64>) -> Option<f64> {
        let straight = matches!(kind, MotionKind::Linear { .. });
        self.state.naive_cam.filter(|_| straight && blend.is_some())
    }

    fn set_units(&mut self, metric: bool) {
        if self.state.metric == metric {
            return;
        }
        let scale = if metric { MM_PER_INCH } else { 1.0 / MM_PER_INCH };
        self.state.comp.scale(scale);
        for axis in 0..3 {
            self.state.current[axis] *= scale;
            self.state.origin[axis] *= scale;
            self.state.axis_offset[axis] *= scale;
            // rs274 keeps the tool length offset's number: it changes with the units.
        }
        self.state.metric = metric;
    }

    fn select_system(&mut self, system: usize) {
        self.change_system(system, false);
    }

    /// G10 L2 and L20.
    fn set_coordinate_data(&mut self, code: Code) -> Result<(), Fault> {
        let Some(l) = self.block.word(b'l') else {
            return Err(
                self.code_fault(code, "Line with G10 does not have L0, L1, L10, L11, L2, or L20")
            );
        };
        let l_value = l.value as i64;
        match l_value {
            2 | 20 => {}
            1 | 10 | 11 => return self.set_tool_data(code, l_value),
            0 => {
                // Reloading the tool table: rs274 keeps the table as the program changed it,
                // and refuses while a tool is in the spindle.
                let loaded = self.state.tools.spindle.tool;
                if loaded > 0 {
                    return Err(self.code_fault(
                        code,
                        format!("G10 L0 not allowed with loaded tool <{loaded}>"),
                    ));
                }
                return Ok(());
            }
            _ => {
                return Err(
                    self.word_fault(l, "Line with G10 does not have L0, L1, L10, L11, L2, or L20")
                );
            }
        }
        let system = match self.block.word(b'p') {
            Some(p) if (0.0..=9.0).contains(&p.value) && p.value.fract() == 0.0 => p.value as usize,
            // Grbl 1.1 wants P or L (`gc_execute_line`: "P/L word missing"), and its P defaults
            // to 0: the system in force (an OpenBuilds plasma post's `G10 L20 Z-2`).
            None if self.dialect == Dialect::Grbl => 0,
            _ => {
                return Err(self
                    .code_fault(code, format!("P value out of range (0-9) with G10 L{l_value}")));
            }
        };
        if system == 0 || system == self.state.system {
            self.refuse_with_comp(
                (code.at, code.end),
                "Cannot change the active coordinate system with cutter radius compensation on",
            )?;
        }
        let r = self.block.word(b'r');
        if let Some(r) = r
            && l_value == 20
        {
            return Err(self.word_fault(r, "R not allowed in G10 L20"));
        }
        let system = if system == 0 { self.state.system } else { system };
        let base = coordinate_system_base(system);
        let rotated_l20 = if l_value == 20 { self.rotated_l20_origin(system) } else { None };
        for (axis, &letter) in AXES.iter().enumerate() {
            let Some(word) = self.block.word(letter) else { continue };
            let origin = match rotated_l20 {
                Some(xy) if axis < 2 => xy[axis],
                _ if l_value == 2 => word.value,
                _ => self.state.current[axis] + self.state.origin[axis] - word.value,
            };
            let value = self.state.to_mm(axis, origin);
            self.state.params.set(base + axis_slot(axis), value);
        }
        if let Some(xy) = rotated_l20 {
            // In a rotated system both X and Y change, whichever was given.
            for (axis, value) in xy.into_iter().enumerate() {
                let value = self.state.to_mm(axis, value);
                self.state.params.set(base + axis_slot(axis), value);
            }
        }
        if let Some(r) = r {
            self.state.params.set(rotation::rotation_parameter(system), r.value);
        }
        if system == self.state.system {
            self.change_system(system, true);
        }
        Ok(())
    }

    /// G92: offsets that make the current point have the given coordinates.
    fn set_axis_offsets(&mut self, code: Code) -> Result<(), Fault> {
        if AXES.iter().all(|&letter| self.block.word(letter).is_none()) {
            return Err(self.code_fault(code, "All axes missing with g52 or g92"));
        }
        let mut offsets = self.state.axis_offset;
        for (axis, &letter) in AXES.iter().enumerate() {
            if let Some(word) = self.block.word(letter) {
                self.zeroed_at_start[axis] |= !self.moved;
                offsets[axis] =
                    self.state.current[axis] + self.state.axis_offset[axis] - word.value;
            }
        }
        self.apply_axis_offsets(offsets);
        for (axis, offset) in offsets.into_iter().enumerate() {
            let value = self.state.to_mm(axis, offset);
            self.state.params.set(G92_OFFSET + axis_slot(axis), value);
        }
        self.state.params.set(G92_ENABLED, 1.0);
        Ok(())
    }

    /// G52: local offsets, kept in G92's offsets (as LinuxCNC does): the given axes' offsets
    /// become the given values.
    fn set_local_offsets(&mut self) {
        let mut offsets = self.state.axis_offset;
        for (axis, &letter) in AXES.iter().enumerate() {
            if let Some(word) = self.block.word(letter) {
                offsets[axis] = word.value;
            }
        }
        self.apply_axis_offsets(offsets);
        for (axis, offset) in offsets.into_iter().enumerate() {
            let value = self.state.to_mm(axis, offset);
            self.state.params.set(G92_OFFSET + axis_slot(axis), value);
        }
        self.state.params.set(G92_ENABLED, 1.0);
    }

    /// G92.3 (`on`: the offsets of parameters 5211–5219 in force again) or G92.2 (none in
    /// force, the parameters kept); 5210 says which, as in rs274.
    pub(super) fn apply_g92(&mut self, on: bool) {
        let offsets = std::array::from_fn(|axis| {
            let value = if on { self.state.params.get(G92_OFFSET + axis_slot(axis)) } else { 0.0 };
            self.state.mm_to_program(axis, value)
        });
        self.apply_axis_offsets(offsets);
        self.state.params.set(G92_ENABLED, if on { 1.0 } else { 0.0 });
    }

    fn apply_axis_offsets(&mut self, offsets: [f64; 4]) {
        for (axis, offset) in offsets.into_iter().enumerate() {
            self.state.current[axis] += self.state.axis_offset[axis] - offset;
            self.state.axis_offset[axis] = offset;
        }
    }

    /// End point of a move (`find_ends`).
    fn find_ends(&self, g53: bool) -> [f64; 4] {
        let rotated = (g53 && self.state.rotation != 0.0).then(|| self.rotated_g53_ends());
        // Without compensation the base is the current point (checked once, not per axis).
        let comp = self.state.comp.on() && !g53;
        std::array::from_fn(|axis| {
            if let Some(Some(xy)) = rotated
                && axis < 2
            {
                return xy[axis];
            }
            let word = self.block.word(AXES[axis]).map(|word| word.value);
            let current = if comp {
                self.state.comp.base(axis, self.state.plane).unwrap_or(self.state.current[axis])
            } else {
                self.state.current[axis]
            };
            match word {
                None => current,
                Some(value) if g53 => {
                    value
                        - self.state.origin[axis]
                        - self.state.axis_offset[axis]
                        - self.state.tool_offset[axis]
                }
                Some(value) if self.state.incremental => current + value,
                Some(value) => value,
            }
        })
    }

    /// G28 and G30: through the intermediate point to the stored position.
    fn go_home(&mut self, code: Code) -> Result<(), Fault> {
        let intermediate = self.find_ends(false);
        self.move_to(intermediate, None);
        let base = if code.code == 280 { G28_HOME } else { G30_HOME };
        let any = AXES.iter().any(|&letter| self.block.word(letter).is_some());
        let mut end = intermediate;
        let home = std::array::from_fn(|axis| {
            self.state.mm_to_program(axis, self.state.params.get(base + axis_slot(axis)))
        });
        let home = self.state.program_of(home);
        for (axis, &letter) in AXES.iter().enumerate() {
            if any && self.block.word(letter).is_none() {
                continue;
            }
            end[axis] = home[axis];
        }
        self.move_to(end, None);
        Ok(())
    }

    /// Emits a rapid (`feed` = None) or linear move and makes `end` the current point.
    fn move_to(&mut self, end: [f64; 4], feed: Option<Feed>) {
        let absolute = self.state.absolute(end);
        self.emit(match feed {
            None => MotionKind::Rapid { end: absolute },
            Some(feed) => MotionKind::Linear { end: absolute, feed },
        });
        self.state.current = end;
        self.state.tool_shift = [0.0; 4];
    }

    fn straight(&mut self, motion: u16, g53: bool) -> Result<(), Fault> {
        self.comp_straight_seen();
        let end = self.find_ends(g53);
        if motion == 0 && self.state.comp.active() {
            return self.comp_straight(true, end, None, g53);
        }
        // Marlin moves G0 as G1, at the feed rate in force (its G0_G1; a separate G0 feed rate
        // is a build option, off by default), so a slicer's `G0 F9000` travels at 150 mm/s.
        if motion == 0 && self.dialect == Dialect::Marlin {
            self.move_to(end, Some(Feed { mm_per_min: self.state.feed_mm, inverse_time: false }));
            return Ok(());
        }
        if motion == 0 {
            self.move_to(end, None);
            return Ok(());
        }
        let feed = if self.state.inverse_time {
            let Some(f) = self.block.word(b'f') else {
                let code = self.block.g[1].map_or((0, 1), |code| (code.at, code.end));
                return Err(self.fault_at(
                    code.0,
                    code.1,
                    "F word missing with inverse time g1 move",
                ));
            };
            let start = self.comp_start().unwrap_or(self.state.current);
            let length = straight_length(start, end);
            let rate = (length * f.value).max(0.1);
            self.set_inverse_time_rate(rate)
        } else {
            if self.state.feed_rate == 0.0 {
                return Err(self.motion_fault(
                    "Cannot do g1 with zero feed rate: program a feed rate with an F word (mm/min, \
                     or in/min under G20) before or on this line",
                ));
            }
            Feed { mm_per_min: self.state.feed_mm, inverse_time: false }
        };
        if self.state.comp.active() {
            return self.comp_straight(false, end, Some(feed), g53);
        }
        self.move_to(end, Some(feed));
        Ok(())
    }

    /// The feed of a move under G93 at `rate` (program units per minute: its length times F),
    /// which becomes the feed rate in force (`#<_feed>`, what M70 saves), as rs274's
    /// `inverse_time_rate_straight` and `inverse_time_rate_arc` make it.
    fn set_inverse_time_rate(&mut self, rate: f64) -> Feed {
        self.state.feed_rate = rate;
        self.state.feed_mm = rate * self.state.factor();
        Feed { mm_per_min: self.state.feed_mm, inverse_time: true }
    }

    /// G2 (`clockwise`) and G3 (`convert_arc`, `convert_arc2`, `arc_data_ijk`, `arc_data_r`).
    fn arc(&mut self, clockwise: bool) -> Result<(), Fault> {
        self.comp_arc_allowed()?;
        let word = |letter: u8| self.block.word(letter);
        let (i, j, mut k, r) = (word(b'i'), word(b'j'), word(b'k'), word(b'r'));
        // Grbl reads the K word of an XY-plane arc and ignores it.
        if self.dialect == Dialect::Grbl && self.state.plane == Plane::Xy {
            k = None;
        }
        let ijk = i.is_some() || j.is_some() || k.is_some();
        if r.is_none() && !ijk {
            return Err(self.motion_fault(
                "R i j k words all missing for arc: give the centre with I J K (offsets from the \
                 start) or the radius with R",
            ));
        }
        if r.is_some() && ijk {
            return Err(self.motion_fault("Mixed radius ijk format for arc"));
        }
        let f = self.block.word(b'f');
        if self.state.inverse_time {
            if f.is_none() {
                return Err(self.motion_fault("F word missing with inverse time arc move"));
            }
        } else if self.state.feed_rate == 0.0 {
            return Err(self.motion_fault(
                "Cannot make arc with zero feed rate: program a feed rate with an F word",
            ));
        }
        let plane = self.state.plane;
        let [first, second, normal] = plane.axes();
        let letters = [b'i', b'j', b'k'];
        let offsets = [i, j, k];
        let mut offset1 = 0.0;
        let mut offset2 = 0.0;
        if ijk {
            if let Some(word) = offsets[normal] {
                let name = match plane {
                    Plane::Xy => "K word given for arc in xy plane",
                    Plane::Xz => "J word given for arc in xz plane",
                    Plane::Yz => "I word given for arc in yz plane",
                };
                return Err(self.word_fault(word, name));
            }
            for (value, axis) in [(&mut offset1, first), (&mut offset2, second)] {
                match offsets[axis] {
                    Some(word) => *value = word.value,
                    None if self.state.ijk_absolute => {
                        return Err(self.motion_fault(format!(
                            "{} word missing in absolute center arc",
                            char::from(letters[axis]).to_ascii_uppercase()
                        )));
                    }
                    None => *value = 0.0,
                }
            }
        } else {
            let has = |axis: usize| self.block.word(AXES[axis]).is_some();
            if !has(first) && !has(second) {
                let message = match plane {
                    Plane::Xy => "X and y words missing for arc in xy plane",
                    Plane::Xz => "X and z words missing for arc in xz plane",
                    Plane::Yz => "Y and z words missing for arc in yz plane",
                };
                return Err(self.motion_fault(message));
            }
        }
        let turns = match self.block.word(b'p') {
            None => 1,
            Some(p) => {
                // An integer ≥ 1 within 0.001 (`check_other_words`).
                let rounded = round_to_int(p.value);
                if rounded > 1e6 {
                    return Err(
                        self.word_fault(p, "P value is too large (more than 1000000 turns)")
                    );
                }
                rounded as u32
            }
        };
        let end = self.find_ends(false);
        self.comp_arc_checks(clockwise, end, r.map(|r| r.value))?;
        let current = self.comp_start().unwrap_or(self.state.current);
        let (c1, c2) = (current[first], current[second]);
        let (e1, e2) = (end[first], end[second]);
        let inch = !self.state.metric;
        let radius_tolerance =
            if inch { RADIUS_TOLERANCE_INCH } else { RADIUS_TOLERANCE_INCH * MM_PER_INCH };
        let names = [
            char::from(AXES[first]).to_ascii_uppercase(),
            char::from(AXES[second]).to_ascii_uppercase(),
        ];
        let (center1, center2) = if let Some(r) = r {
            if e1 == c1 && e2 == c2 {
                return Err(self.motion_fault("Current point same as end point of arc"));
            }
            let radius = r.value;
            let abs_radius = radius.abs();
            let mid1 = (e1 + c1) / 2.0;
            let mid2 = (e2 + c2) / 2.0;
            let mut half_length = (mid1 - e1).hypot(mid2 - e2);
            if half_length - abs_radius > radius_tolerance {
                return Err(self.motion_fault(format!(
                    "Arc radius too small to reach end point: R{abs_radius} cannot span the \
                         {:.4} between start and end",
                    2.0 * half_length
                )));
            }
            if half_length / abs_radius > 1.0 - TINY {
                half_length = abs_radius;
            }
            let base = (e2 - c2).atan2(e1 - c1);
            let theta = if (clockwise && radius > 0.0) || (!clockwise && radius < 0.0) {
                base - std::f64::consts::FRAC_PI_2
            } else {
                base + std::f64::consts::FRAC_PI_2
            };
            let turn2 = (half_length / abs_radius).asin();
            let offset = abs_radius * turn2.cos();
            (mid1 + offset * theta.cos(), mid2 + offset * theta.sin())
        } else {
            let (center1, center2) = if self.state.ijk_absolute {
                (offset1, offset2)
            } else {
                (c1 + offset1, c2 + offset2)
            };
            let radius = (center1 - c1).hypot(center2 - c2);
            let radius2 = (center1 - e1).hypot(center2 - e2);
            let describe = || {
                format!(
                    "start=({a}{c1:.4},{b}{c2:.4}) center=({a}{center1:.4},{b}{center2:.4}) \
                     end=({a}{e1:.4},{b}{e2:.4}) r1={radius:.4} r2={radius2:.4}",
                    a = names[0],
                    b = names[1],
                )
            };
            if radius < radius_tolerance || radius2 < radius_tolerance {
                return Err(self.motion_fault(format!("Zero-radius arc: {}", describe())));
            }
            let abs_err = (radius - radius2).abs();
            let rel_err = abs_err / radius.max(radius2);
            let spiral = if inch {
                CENTER_ARC_RADIUS_TOLERANCE_INCH
            } else {
                CENTER_ARC_RADIUS_TOLERANCE_MM
            };
            // LinuxCNC's test: beyond the tolerance and 0.1 %, or beyond 100 tolerances.
            if (abs_err > spiral && rel_err > SPIRAL_RELATIVE_TOLERANCE) || abs_err > 100.0 * spiral
            {
                return Err(self.motion_fault(format!(
                    "Radius to end of arc differs from radius to start: {} abs_err={} \
                         rel_err={:.4}% (LinuxCNC allows {:.4} {unit}, or 0.1% up to {:.4} \
                         {unit})",
                    describe(),
                    format_g4(abs_err),
                    rel_err * 100.0,
                    spiral,
                    100.0 * spiral,
                    unit = if inch { "in" } else { "mm" },
                )));
            }
            (center1, center2)
        };
        let feed = if self.state.inverse_time {
            let f = f.map_or(0.0, |word| word.value);
            let turn = if clockwise { -(turns as i32) } else { turns as i32 };
            let length = arc_length(
                [c1, c2, current[normal]],
                [center1, center2],
                turn,
                [e1, e2, end[normal]],
            );
            let rate = (length * f).max(0.1);
            self.set_inverse_time_rate(rate)
        } else {
            Feed { mm_per_min: self.state.feed_mm, inverse_time: false }
        };
        if self.comp_arcs() {
            let turn = if clockwise { -(turns as i32) } else { turns as i32 };
            let center = [center1, center2];
            let arc = cutter_comp::CompArc { start: current, end, center, turn, feed };
            return self.comp_arc(arc);
        }
        if self.state.rotation != 0.0 && plane != Plane::Xy {
            let arc = ([current, end], [center1, center2]);
            let moved = self.tilted_arc(arc.0, arc.1, clockwise, turns, feed);
            return moved.map_err(|message| self.motion_fault(message));
        }
        let mut center_position = self.state.current;
        center_position[first] = center1;
        center_position[second] = center2;
        let center_absolute = self.state.absolute(center_position);
        let absolute = self.state.absolute(end);
        self.emit(MotionKind::Arc {
            end: absolute,
            center: [center_absolute[first], center_absolute[second]],
            plane,
            clockwise,
            turns,
            feed,
        });
        self.state.current = end;
        self.state.tool_shift = [0.0; 4];
        Ok(())
    }
}

/// LinuxCNC's `find_straight_length` for X Y Z C: the XYZ length, or the C length for a move
/// with no XYZ motion.
fn straight_length(from: [f64; 4], to: [f64; 4]) -> f64 {
    let linear = (0..3).any(|axis| from[axis] != to[axis]) || from[3] == to[3];
    if linear {
        ((to[0] - from[0]).powi(2) + (to[1] - from[1]).powi(2) + (to[2] - from[2]).powi(2)).sqrt()
    } else {
        (to[3] - from[3]).abs()
    }
}

/// LinuxCNC's `find_turn`: the signed angle swept from `start` to `end` about `center`, `turn`
/// times round (negative: clockwise; 0: no turn).
fn find_turn(start: [f64; 2], center: [f64; 2], turn: i32, end: [f64; 2]) -> f64 {
    use std::f64::consts::PI;
    if turn == 0 {
        return 0.0;
    }
    let mut alpha = (start[1] - center[1]).atan2(start[0] - center[0]);
    let mut beta = (end[1] - center[1]).atan2(end[0] - center[0]);
    if turn > 0 {
        if beta <= alpha {
            beta += 2.0 * PI;
        }
        beta - alpha + f64::from(turn - 1) * 2.0 * PI
    } else {
        if alpha <= beta {
            alpha += 2.0 * PI;
        }
        beta - alpha + f64::from(turn + 1) * 2.0 * PI
    }
}

/// LinuxCNC's `find_arc_length`: `turn` is negative for clockwise (never 0 here: an arc turns
/// at least once).
fn arc_length(start: [f64; 3], center: [f64; 2], turn: i32, end: [f64; 3]) -> f64 {
    let radius = (center[0] - start[0]).hypot(center[1] - start[1]);
    let theta = find_turn([start[0], start[1]], center, turn, [end[0], end[1]]);
    if end[2] == start[2] {
        radius * theta.abs()
    } else {
        (radius * theta).hypot(end[2] - start[2])
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
            if let Some(motion) = self.queue.pop_front() {
                return Some(Ok(motion));
            }
            if self.finished {
                return None;
            }
            if let Err(err) = self.step() {
                self.finished = true;
                self.queue.clear();
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
