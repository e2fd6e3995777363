//! Grbl 1.1 (also for LaserGRBL, LightBurn, LaserWeb, bCNC output): its `$` lines and real-time
//! characters, long comment lines, a `(` comment that ends at its line's end, no program end,
//! G10 L2/L20 without P, K ignored in XY arcs, no probe back-off, its laser mode, and a count
//! of what Grbl itself would refuse.

use biscara_motion::MotionKind;

use super::{DialectHooks, Rules};
use crate::dialect::{Dialect, Prelude, Summary, g_name, grbl_prelude, grbl_runs_g, grbl_runs_m};
use crate::interpreter::Machine;
use crate::syntax::lexer::{Fault, InnerParen};

/// Grbl's hooks.
#[derive(Debug)]
pub(in crate::interpreter) struct Grbl;

/// Grbl ends a `(` comment at the end of its line (protocol.c: "ignore all characters until
/// ')' or EOL"); Grbl 1.1 wants P or L in G10 (`gc_execute_line`: "P/L word missing"), and its P
/// defaults to 0: the system in force (an OpenBuilds plasma post's `G10 L20 Z-2`).
const RULES: Rules = Rules {
    dialect: Dialect::Grbl,
    has_prelude: true,
    inner_paren: InnerParen::Ignored,
    closes_comment_at_line_end: true,
    g10_p_optional: true,
    ignores_k_in_xy_arc: true,
    gates_laser_in_rapids: true,
    ..Rules::FIRMWARE
};

impl DialectHooks for Grbl {
    fn rules(&self) -> &'static Rules {
        &RULES
    }

    fn prelude(&self, raw: &[u8]) -> Prelude {
        grbl_prelude(raw)
    }

    fn count_refused_o_word(&self, summary: &mut Summary) {
        summary.count_refused("O-words");
    }

    /// Grbl changes no block; it counts what Grbl itself would refuse in it.
    fn adapt_block(&self, machine: &mut Machine) -> Result<bool, Fault> {
        machine.count_refused_by_grbl();
        Ok(false)
    }
}

impl Machine {
    /// Grbl 1.1: counts what this block uses that Grbl itself refuses (error 20), read here as
    /// LinuxCNC reads it: G and M codes outside its list, parameters and expressions.
    fn count_refused_by_grbl(&mut self) {
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

    /// Grbl's laser mode (wiki "Grbl v1.1 Laser Mode"): the laser burns only in G1, G2 and G3
    /// motion; a G0 never turns it on and always turns it off. Before the first rapid with the
    /// laser on, a `laser_off` is emitted; before the next feed move, a `laser_on` with the
    /// power and mode in force.
    pub(in crate::interpreter) fn grbl_laser_gate(&mut self, kind: &MotionKind) {
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
}
