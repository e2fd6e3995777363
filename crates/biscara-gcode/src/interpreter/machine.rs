//! The machine that executes blocks, not generic over the input: the block being executed,
//! LinuxCNC's modal state (kept as LinuxCNC keeps it — positions and offsets in the program's
//! current length units, so that its tolerances apply exactly — and converted to absolute
//! millimetres in the robot's base frame as each motion is emitted), the motions made, and the
//! dialect's and the tool's hooks.

use super::*;

/// The machine that executes blocks, not generic over the input: the block being executed,
/// LinuxCNC's modal state, the motions made, and the dialect's and tool's hooks.
#[derive(Debug)]
pub(super) struct Machine {
    /// The line being read, as a block.
    pub(super) syntax: Syntax,
    /// LinuxCNC's modal state and position.
    pub(super) state: State,
    /// The motions made and not yet taken, and whether the program has ended.
    pub(super) output: Output,
    /// The dialect's and the tool's hooks.
    pub(super) hooks: hooks::Hooks,
}

/// The line being read: its significant characters, the block read from them, and how lines
/// are framed (block delete, `%`).
#[derive(Debug)]
pub(super) struct Syntax {
    pub(super) compact: Compact,
    pub(super) block: Block,
    /// The length of the raw line (for the columns of errors).
    pub(super) raw_len: usize,
    pub(super) block_delete: bool,
    pub(super) percent: Percent,
}

/// What the interpreter has made and not yet given.
#[derive(Debug)]
pub(super) struct Output {
    pub(super) queue: VecDeque<Motion>,
    /// Whether the program has ended (or failed): nothing more is read.
    pub(super) finished: bool,
    /// Whether any motion was emitted (an empty program is not a program).
    pub(super) moved: bool,
    /// Jumps back since the last motion.
    pub(super) idle_jumps: u64,
    /// Motions given so far.
    pub(super) given: u64,
    /// The most motions one run may give ([`Config::max_motions`](crate::Config::max_motions)).
    pub(super) max_motions: u64,
    /// The end point of the last motion (a move to where the robot is is no motion).
    pub(super) last_end: Option<[f64; 4]>,
}

impl Output {
    /// After a jump back: a move somewhere else than the last one went, or a wait, ends the
    /// run of jumps without motion. (Moves are looked at only after a jump, so that a program
    /// without loops pays one test a motion; the first move after a jump may compare with an
    /// older end point, and then there was a motion since.)
    #[cold]
    pub(super) fn moved_since_jump(&mut self, kind: &MotionKind) {
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
pub(super) enum Percent {
    /// Before the first line.
    Unknown,
    /// The program started with `%`: it ends at the next `%`.
    Open,
    /// The program did not start with `%`: it ends with M2 or M30.
    Absent,
}

/// LinuxCNC's modal state and position, in the program's current length units.
#[derive(Debug)]
pub(super) struct State {
    pub(super) metric: bool,
    pub(super) incremental: bool,
    pub(super) ijk_absolute: bool,
    pub(super) plane: Plane,
    pub(super) inverse_time: bool,
    /// The F number in force (program units per minute).
    pub(super) feed_rate: f64,
    /// The feed rate in force as the machine holds it: mm/min, converted when it was set.
    pub(super) feed_mm: f64,
    /// 0, 10, 20, 30 for G0–G3; `None` after G80 and at the start.
    pub(super) motion: Option<u16>,
    pub(super) current: [f64; 4],
    pub(super) origin: [f64; 4],
    pub(super) axis_offset: [f64; 4],
    pub(super) system: usize,
    /// The rotation of the system in force about Z, degrees (G10 L2 R; 0: none).
    pub(super) rotation: f64,
    pub(super) params: Params,
    pub(super) line: usize,
    pub(super) speed: f64,
    /// The tool length offset in force (G43…), in the program units in force when it was set:
    /// as in rs274, a change of units does not convert it (it is used so by later G43, G49,
    /// G53, G28 and G10 L10), though the machine keeps the offset it was given
    /// ([`State::tool_offset_mm`]).
    pub(super) tool_offset: [f64; 4],
    /// The tool length offset the machine applies, mm and degrees.
    pub(super) tool_offset_mm: [f64; 4],
    /// How far tool length offsets set since the last move have shifted the current point:
    /// rs274 takes its position back from the last move after M6 (its canon does not follow).
    pub(super) tool_shift: [f64; 4],
    /// A tool change (M6, M61) was made: the current point is taken back from the last move as
    /// the next line is read.
    pub(super) resync: bool,
    pub(super) tools: tools::Tools,
    /// The canned cycles' retract mode and sticky values.
    pub(super) cycle: canned::CycleState,
    /// The modal state M70/M73 saved.
    pub(super) modal_stack: modal_state::ModalStack,
    pub(super) spindle: u16,
    pub(super) mist: bool,
    pub(super) flood: bool,
    /// `#<_value>`, `#<_value_returned>`, `#<_call_level>`.
    pub(super) owords: control::Values,
    /// The path-control mode: `Some(p)` under G64 (0 when P was not given), `None` under
    /// G61/G61.1.
    pub(super) blend: Option<f64>,
    /// G64 Q in millimetres when positive (LinuxCNC's naive-CAM tolerance), `None` otherwise.
    pub(super) naive_cam: Option<f64>,
    /// Cutter radius compensation and the motions it holds back.
    pub(super) comp: cutter_comp::CutterComp,
    /// The INI file whose variables `#<_ini[…]…>` names read, when it allows it.
    pub(super) ini: Option<std::sync::Arc<IniFile>>,
    /// The axes (x y z c) a G92 named before the first motion: the program made its start
    /// point its zero there.
    pub(super) zeroed_at_start: [bool; 4],
}

impl State {
    pub(super) fn new(config: &Config) -> State {
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
    pub(super) fn factor(&self) -> f64 {
        if self.metric { 1.0 } else { MM_PER_INCH }
    }

    /// Program units → mm for `axis` (C is in degrees whatever the units).
    pub(super) fn to_mm(&self, axis: usize, value: f64) -> f64 {
        if axis == 3 { value } else { value * self.factor() }
    }

    pub(super) fn mm_to_program(&self, axis: usize, value: f64) -> f64 {
        if axis == 3 { value } else { value / self.factor() }
    }

    /// Whether the G92 offsets are in force (parameter 5210: G92 and G92.3 set it, G92.1 and
    /// G92.2 clear it).
    pub(super) fn g92_in_force(&self) -> bool {
        self.params.get(G92_ENABLED) != 0.0
    }

    /// A tool table entry's offsets `[x, y, z, c]` (mm, degrees) in program units.
    pub(super) fn offsets_in_program_units(&self, entry: &ToolEntry) -> [f64; 4] {
        std::array::from_fn(|axis| self.mm_to_program(axis, entry.offset[axis]))
    }

    /// A position in the current coordinate system → absolute mm and degrees.
    pub(super) fn absolute(&self, position: [f64; 4]) -> [f64; 4] {
        if self.rotation != 0.0 {
            return self.absolute_rotated(position);
        }
        std::array::from_fn(|axis| {
            self.to_mm(axis, position[axis] + self.origin[axis] + self.axis_offset[axis])
                + self.tool_offset_mm[axis]
        })
    }

    /// Parameters 5420–5428: the current position.
    pub(super) fn publish_position(&mut self) {
        for axis in 0..4 {
            self.params.set_mirror(5420 + axis_slot(axis), self.current[axis]);
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

impl Machine {
    /// A fault about the whole line.
    pub(super) fn line_fault(&self, message: impl Into<String>) -> Fault {
        Fault::invalid(0, self.syntax.raw_len.max(1), message)
    }

    /// Raw column range of the block's compact range `start..end`.
    pub(super) fn span(&self, start: usize, end: usize) -> (usize, usize) {
        let raw_len = self.syntax.raw_len;
        let first = self.syntax.compact.column(start, raw_len);
        let last =
            if end > start { self.syntax.compact.column(end - 1, raw_len) + 1 } else { first };
        (first, last.max(first + 1))
    }

    pub(super) fn fault_at(&self, start: usize, end: usize, message: impl Into<String>) -> Fault {
        let (first, last) = self.span(start, end);
        Fault::invalid(first, last, message)
    }

    pub(super) fn word_fault(&self, word: Word, message: impl Into<String>) -> Fault {
        self.fault_at(word.at, word.end, message)
    }

    pub(super) fn code_fault(&self, code: Code, message: impl Into<String>) -> Fault {
        self.fault_at(code.at, code.end, message)
    }

    pub(super) fn emit(&mut self, kind: MotionKind) {
        if self.hooks.tool == Tool::Laser && self.hooks.rules.gates_laser_in_rapids {
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
