//! Mach3 (Fanuc-style posts): long lines, nested comments, G31, M40/M41, Fanuc-style
//! subprograms (G65, `O` labels anywhere), the compensation radius in G41/G42's P word, bare
//! axis words after G80, G53 without a move, no program end, no probe back-off.

use super::DialectHooks;
use crate::dialect::{Dialect, MAX_LONG_LINE};
use crate::interpreter::Machine;
use crate::syntax::lexer::{Fault, InnerParen};

/// Mach3's hooks.
#[derive(Debug)]
pub(in crate::interpreter) struct Mach3;

impl DialectHooks for Mach3 {
    fn dialect(&self) -> Dialect {
        Dialect::Mach3
    }

    fn max_line(&self) -> usize {
        MAX_LONG_LINE
    }

    fn inner_paren(&self) -> InnerParen {
        InnerParen::Opens
    }

    fn fanuc_subprograms(&self) -> bool {
        true
    }

    fn reads_mach3_codes(&self) -> bool {
        true
    }

    fn executes_comments(&self) -> bool {
        false
    }

    fn adapts_blocks(&self) -> bool {
        true
    }

    fn adapt_block(&self, machine: &mut Machine) -> Result<bool, Fault> {
        machine.adapt_fanuc_style_block();
        Ok(false)
    }

    fn needs_program_end(&self) -> bool {
        false
    }

    /// Mach3's G41/G42 P: the radius itself, program units, instead of the tool table's (a
    /// Fusion 360 Mach3 post writes P1.587 for its 3.175 mm cutter).
    fn comp_radius_in_p(&self) -> bool {
        true
    }

    fn probe_backs_off(&self) -> bool {
        false
    }
}
