//! Marlin and the RepRap family of printer firmware (slicer output): one command per line, its
//! no-motion codes as events, G28 homing, the E word as the extruder, G4 S/P, G0 at the feed
//! rate in force, a default feed rate, long lines, nested comments, no program end, no probe
//! back-off; a program read as Marlin's is a 3D printer's.

use super::{DialectHooks, Rules};
use crate::dialect::{Dialect, Prelude, marlin_prelude};
use crate::interpreter::{AXES, MM_PER_INCH, Machine};
use crate::syntax::lexer::{Fault, InnerParen};
use crate::syntax::parser::Word;
use crate::tool::{Tool, ToolInference};

/// Marlin's feed rate before the first F word, mm/min (`DEFAULT_FEEDRATE_MM_M`, Marlin 2.1).
const MARLIN_DEFAULT_FEED: f64 = 4000.0;
/// The largest extruder position (E word) accepted, mm.
const MAX_EXTRUSION: f64 = 1e9;

/// Marlin's hooks.
#[derive(Debug)]
pub(in crate::interpreter) struct Marlin;

/// Marlin's feed rate before the first F word is its `DEFAULT_FEEDRATE_MM_M`; it moves G0 as G1,
/// at the feed rate in force (its G0_G1; a separate G0 feed rate is a build option, off by
/// default), so a slicer's `G0 F9000` travels at 150 mm/s.
const RULES: Rules = Rules {
    dialect: Dialect::Marlin,
    default_feed: Some(MARLIN_DEFAULT_FEED),
    has_prelude: true,
    inner_paren: InnerParen::Opens,
    rapid_at_feed: true,
    reads_exponents: true,
    ..Rules::FIRMWARE
};

impl DialectHooks for Marlin {
    fn rules(&self) -> &'static Rules {
        &RULES
    }

    /// A slicer's thumbnail can fill the look-ahead: its dialect still tells.
    fn implied_tool(&self) -> Option<ToolInference> {
        Some(ToolInference {
            tool: Tool::Extruder,
            reason: "read as Marlin G-code: a 3D printer".to_owned(),
            line: None,
        })
    }

    fn prelude(&self, raw: &[u8]) -> Prelude {
        marlin_prelude(raw)
    }

    fn adapt_block(&self, machine: &mut Machine) -> Result<bool, Fault> {
        machine.adapt_marlin_block()
    }
}

impl Machine {
    /// Marlin's reading of the block just read: one command a line (later G and M words are
    /// its parameters), the E word as the extruder's move, `G1 F…` alone as a feed rate, G4's
    /// S seconds or P milliseconds, `G92` alone as every axis zero; `Ok(true)` when the block is done with (G92 of E alone).
    fn adapt_marlin_block(&mut self) -> Result<bool, Fault> {
        self.hooks.pending_extrude = None;
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
        if group0 == Some(920) && e.is_none() && !axis_words {
            // `G92` alone: Marlin (and RepRap firmware) make every axis, the extruder's too,
            // zero where they are.
            let (at, end) = self.syntax.block.g[0].map_or((0, 1), |code| (code.at, code.end));
            for &letter in &AXES {
                self.syntax.block.letters[usize::from(letter - b'a')] =
                    Some(Word { value: 0.0, at, end });
            }
            self.hooks.e_position = 0.0;
            return Ok(false);
        }
        if group0 == Some(40) {
            self.marlin_dwell();
        }
        let Some(e) = e else { return Ok(false) };
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
            let delta = if self.hooks.e_relative { value } else { value - self.hooks.e_position };
            self.hooks.e_position += delta;
            self.hooks.pending_extrude = Some(delta);
        }
        Ok(false)
    }

    /// Marlin's G4: S seconds, else P milliseconds, else no wait.
    fn marlin_dwell(&mut self) {
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
        self.syntax.block.letters[usize::from(b'p' - b'a')] = Some(Word { value: seconds, ..word });
    }
}
