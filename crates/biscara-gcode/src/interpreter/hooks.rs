//! The dialects' hooks around LinuxCNC's execution (docs/gcode.md) and the tool's events (§1.6),
//! on the machine: their state (`Hooks`), what a dialect makes of a block after the block
//! reader, and what M3/M4/M5/S emit for each tool. None of them runs in [`Dialect::Linuxcnc`]
//! except [`Machine::tool_event`] (the gripper's pick, place, off). The hooks that read the
//! input (`auto`'s look-ahead, a line before the block reader, the end of the input) are the
//! interpreter's.

use biscara_motion::{CodeName, MotionKind};

use super::{AXES, MM_PER_INCH, Machine};
use crate::dialect::{Detection, Dialect, Summary, g_name, grbl_runs_g, grbl_runs_m};
use crate::syntax::lexer::Fault;
use crate::syntax::parser::Word;
use crate::tool::{Tool, ToolInference};

/// Marlin's feed rate before the first F word, mm/min (`DEFAULT_FEEDRATE_MM_M`, Marlin 2.1).
pub(super) const MARLIN_DEFAULT_FEED: f64 = 4000.0;
/// The largest extruder position (E word) accepted, mm.
const MAX_EXTRUSION: f64 = 1e9;

/// The dialect's and the tool's state: which dialect is read (and what `auto` found), the
/// tool and whether it is on, Grbl's laser gate, Marlin's extruder, the Fanuc control flow.
#[derive(Debug)]
pub(super) struct Hooks {
    /// The dialect being read ([`Dialect::Linuxcnc`] while `auto` has not decided).
    pub(super) dialect: Dialect,
    /// Whether `auto` still has to read ahead (before the first line).
    pub(super) undecided: bool,
    /// `auto` found nothing in its look-ahead: read as LinuxCNC, and perhaps decided at the end.
    pub(super) provisional: bool,
    pub(super) detection: Option<Detection>,
    pub(super) summary: Summary,
    pub(super) tool: Tool,
    /// Whether the tool is still to be inferred from the look-ahead.
    pub(super) infer_tool: bool,
    /// What the inference found.
    pub(super) tool_inference: Option<ToolInference>,
    /// Whether the tool is on (M3/M4 until M5 or M6).
    pub(super) tool_on: bool,
    /// Grbl's laser mode: the laser, on, is off during the rapids since the last feed move
    /// (a `laser_off` was emitted before the first of them; the next feed move turns it on).
    pub(super) laser_rapid_off: bool,
    /// MakerBot's flavour: the A word is the extruder.
    pub(super) makerbot: bool,
    /// Marlin's extruder: position (mm) and whether E words are relative (M83, G91).
    pub(super) e_position: f64,
    pub(super) e_relative: bool,
    /// The extrusion of the block being executed, for its first move.
    pub(super) pending_extrude: Option<f64>,
    /// The Fanuc dialect's control flow (GOTO, WHILE … DO, M97).
    pub(super) fanuc: super::fanuc::Fanuc,
}

impl Hooks {
    /// The hooks `config` asks for, before the first line.
    pub(super) fn new(config: &super::Config) -> Hooks {
        let auto = config.dialect == Dialect::Auto;
        Hooks {
            dialect: if auto { Dialect::Linuxcnc } else { config.dialect },
            undecided: auto,
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
            fanuc: super::fanuc::Fanuc::default(),
        }
    }
}

impl Machine {
    /// Records a no-motion code as an event.
    pub(super) fn record(&mut self, name: &str, known: bool) {
        self.hooks.summary.count(name, known);
        if let Some(code) = CodeName::new(name) {
            self.emit(MotionKind::Code { code });
        }
    }

    /// Grbl 1.1: counts what this block uses that Grbl itself refuses (error 20), read here as
    /// LinuxCNC reads it: G and M codes outside its list, parameters and expressions.
    pub(super) fn count_refused_by_grbl(&mut self) {
        for code in self.syntax.block.g.iter().flatten() {
            if !grbl_runs_g(code.code) {
                self.hooks.summary.count_refused(&g_name(code.code));
            }
        }
        // Grbl's G10 sets coordinate systems only (L2, L20), not tools (L1, L10, L11).
        if self.syntax.block.g[0].is_some_and(|code| code.code == 100)
            && let Some(l) =
                self.syntax.block.word(b'l').filter(|l| l.value != 2.0 && l.value != 20.0)
        {
            self.hooks.summary.count_refused(&format!("G10 L{}", l.value));
        }
        for code in self.syntax.block.m.iter().flatten() {
            if !grbl_runs_m(code.code) {
                self.hooks.summary.count_refused(&format!("M{}", code.code));
            }
        }
        let bytes = self.syntax.compact.bytes();
        if bytes.contains(&b'#') {
            self.hooks.summary.count_refused("parameters (#)");
        }
        if bytes.contains(&b'[') {
            self.hooks.summary.count_refused("expressions ([ ])");
        }
    }

    /// A dialect's changes to the block just read; `Ok(true)` when the block is done with.
    pub(super) fn adapt_block(&mut self) -> Result<bool, Fault> {
        if self.hooks.dialect != Dialect::Marlin {
            if matches!(self.hooks.dialect, Dialect::Mach3 | Dialect::Fanuc) {
                self.adapt_fanuc_block();
            }
            return Ok(false);
        }
        // One command per line: later G and M words are the command's parameters.
        let first = self
            .syntax
            .block
            .g
            .iter()
            .chain(self.syntax.block.m.iter())
            .flatten()
            .map(|code| code.at)
            .min();
        if let Some(first) = first {
            for slot in self.syntax.block.g.iter_mut().chain(self.syntax.block.m.iter_mut()) {
                if slot.is_some_and(|code| code.at != first) {
                    *slot = None;
                }
            }
        }
        if let Some(code) = self.syntax.block.g[3] {
            self.hooks.e_relative = code.code == 910;
        }
        let group0 = self.syntax.block.g[0].map(|code| code.code);
        if self.syntax.block.g[1].is_none() && group0 != Some(920) {
            // Axis words of a command that is not a move are its parameters: no modal motion.
            for &letter in &AXES {
                self.syntax.block.letters[usize::from(letter - b'a')] = None;
            }
        }
        let factor = if self.syntax.block.g[6].map_or(self.state.metric, |code| code.code == 210) {
            1.0
        } else {
            MM_PER_INCH
        };
        let e = self.syntax.block.letters[usize::from(b'e' - b'a')].take();
        let axis_words = AXES.iter().any(|&letter| self.syntax.block.word(letter).is_some());
        if e.is_none() && !axis_words && self.syntax.block.g[1].is_some_and(|code| code.code <= 30)
        {
            // `G1 F1500`: a feed rate, no move (LinuxCNC would make a move of no length).
            self.syntax.block.g[1] = None;
        }
        if group0 == Some(40) {
            // G4: S seconds, else P milliseconds, else no wait.
            let s = self.syntax.block.letters[usize::from(b's' - b'a')].take();
            let p = self.syntax.block.word(b'p');
            let (seconds, word) = match (s, p) {
                (Some(s), _) => (s.value, s),
                (None, Some(p)) => (p.value / 1000.0, p),
                (None, None) => {
                    let code = self.syntax.block.g[0].map_or((0, 1), |code| (code.at, code.end));
                    (0.0, Word { value: 0.0, at: code.0, end: code.1 })
                }
            };
            self.syntax.block.letters[usize::from(b'p' - b'a')] =
                Some(Word { value: seconds, ..word });
        }
        if let Some(e) = e {
            let value = e.value * factor;
            if value.is_nan() || value.abs() > MAX_EXTRUSION {
                return Err(self.word_fault(
                    e,
                    format!("{value:e} is out of range: E must lie within ±{MAX_EXTRUSION:e} mm"),
                ));
            }
            if group0 == Some(920) {
                self.hooks.e_position = value;
                if AXES.iter().all(|&letter| self.syntax.block.word(letter).is_none()) {
                    return Ok(true);
                }
            } else if self.syntax.block.g[1].is_some()
                || (self.state.motion.is_some()
                    && AXES.iter().any(|&letter| self.syntax.block.word(letter).is_some()))
            {
                let delta =
                    if self.hooks.e_relative { value } else { value - self.hooks.e_position };
                self.hooks.e_position += delta;
                self.hooks.pending_extrude = Some(delta);
            }
        }
        Ok(false)
    }

    /// MakerBot's flavour: an A word is the extruder's E.
    pub(super) fn rename_makerbot_a(&mut self) {
        let bytes = self.syntax.compact.bytes_mut();
        for index in 0..bytes.len() {
            let before = if index == 0 { b'(' } else { bytes[index - 1] };
            let after = bytes.get(index + 1).copied().unwrap_or(0);
            if bytes[index] == b'a'
                && !before.is_ascii_alphabetic()
                && (after.is_ascii_digit() || matches!(after, b'-' | b'+' | b'.'))
            {
                bytes[index] = b'e';
            }
        }
    }

    /// Grbl's laser mode (wiki "Grbl v1.1 Laser Mode"): the laser burns only in G1, G2 and G3
    /// motion; a G0 never turns it on and always turns it off. Before the first rapid with the
    /// laser on, a `laser_off` is emitted; before the next feed move, a `laser_on` with the
    /// power and mode in force.
    pub(super) fn grbl_laser_gate(&mut self, kind: &MotionKind) {
        match kind {
            MotionKind::LaserOn { .. } | MotionKind::LaserOff => self.hooks.laser_rapid_off = false,
            MotionKind::Rapid { .. } if self.hooks.tool_on && !self.hooks.laser_rapid_off => {
                self.hooks.laser_rapid_off = true;
                self.emit(MotionKind::LaserOff);
                self.hooks.laser_rapid_off = true;
            }
            MotionKind::Linear { .. } | MotionKind::Arc { .. } if self.hooks.laser_rapid_off => {
                let power = self.state.speed;
                self.emit(MotionKind::LaserOn { power, dynamic: self.state.spindle == 4 });
            }
            _ => {}
        }
    }

    /// The tool's event for M3, M4 or M5 (`code`), or for a new S while on.
    pub(super) fn tool_event(&mut self, code: u16) {
        self.hooks.tool_on = code != 5;
        let speed = self.state.speed;
        let kind = match (self.hooks.tool, code) {
            (Tool::Gripper, 3) => MotionKind::Pick,
            (Tool::Gripper, 4) => MotionKind::Place,
            (Tool::Gripper, _) => MotionKind::GripperOff,
            (Tool::Laser, 3 | 4) => MotionKind::LaserOn { power: speed, dynamic: code == 4 },
            (Tool::Laser, _) => MotionKind::LaserOff,
            (Tool::Spindle, 3 | 4) => MotionKind::SpindleOn { rpm: speed, clockwise: code == 3 },
            (Tool::Spindle, _) => MotionKind::SpindleOff,
            (Tool::Pen, 3 | 4) => MotionKind::PenDown,
            (Tool::Pen, _) => MotionKind::PenUp,
            (Tool::Extruder, _) => {
                let name = format!("M{code}");
                self.hooks.summary.count(&name, true);
                match CodeName::new(&name) {
                    Some(code) => MotionKind::Code { code },
                    None => return,
                }
            }
        };
        self.emit(kind);
    }
}
