//! Mach3 (Fanuc-style posts): long lines, nested comments, G31, M40/M41, Fanuc-style
//! subprograms (G65, `O` labels anywhere), the compensation radius in G41/G42's P word, bare
//! axis words after G80, G53 without a move, no program end, no probe back-off.

use super::{DialectHooks, Rules};
use crate::dialect::Dialect;
use crate::interpreter::Machine;
use crate::syntax::lexer::{Fault, InnerParen};

/// Mach3's hooks.
#[derive(Debug)]
pub(in crate::interpreter) struct Mach3;

/// Mach3's G41/G42 P is the radius itself, program units, instead of the tool table's (a
/// Fusion 360 Mach3 post writes P1.587 for its 3.175 mm cutter).
const RULES: Rules = Rules {
    dialect: Dialect::Mach3,
    inner_paren: InnerParen::Opens,
    fanuc_subprograms: true,
    reads_mach3_codes: true,
    comp_radius_in_p: true,
    ..Rules::FIRMWARE
};

impl DialectHooks for Mach3 {
    fn rules(&self) -> &'static Rules {
        &RULES
    }

    fn adapt_block(&self, machine: &mut Machine) -> Result<bool, Fault> {
        machine.adapt_fanuc_style_block();
        Ok(false)
    }
}
