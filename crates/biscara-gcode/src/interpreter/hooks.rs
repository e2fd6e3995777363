//! The dialect's and the tool's state on the machine (`Hooks`: the dialect's hooks in force,
//! what `auto` found, the tool, Marlin's extruder, the Fanuc control flow), and what M3/M4/M5/S
//! emit for each tool (docs/gcode.md, docs/motion.md). What each dialect reads differently is
//! its implementation of `DialectHooks` (`dialects/`); the hooks that read the input
//! (`auto`'s look-ahead, a line before the block reader, the end of the input) are the
//! interpreter's.

use biscara_motion::{CodeName, MotionKind};

use super::Machine;
use super::dialects::{DialectHooks, Rules, hooks_of};
use crate::dialect::{Detection, Dialect, Summary};
use crate::tool::{Tool, ToolInference};

/// The dialect's and the tool's state: which dialect is read (and what `auto` found), the
/// tool and whether it is on, Grbl's laser gate, Marlin's extruder, the Fanuc control flow.
#[derive(Debug)]
pub(super) struct Hooks {
    /// The hooks of the dialect being read (LinuxCNC's while `auto` has not decided).
    pub(super) dialect: &'static dyn DialectHooks,
    /// Their rules (`dialect.rules()`, kept at hand: the reader asks them on every line).
    pub(super) rules: &'static Rules,
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
            dialect: hooks_of(config.dialect),
            rules: hooks_of(config.dialect).rules(),
            undecided: auto,
            provisional: false,
            detection: None,
            summary: Summary::default(),
            tool: config.tool,
            infer_tool: config.infer_tool,
            tool_inference: None,
            tool_on: false,
            laser_rapid_off: false,
            makerbot: config.dialect == Dialect::Makerbot,
            e_position: 0.0,
            e_relative: false,
            pending_extrude: None,
            fanuc: super::fanuc::Fanuc::default(),
        }
    }

    /// Reads on in `dialect` (what `auto` decided).
    pub(super) fn set_dialect(&mut self, dialect: Dialect) {
        self.dialect = hooks_of(dialect);
        self.rules = self.dialect.rules();
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
