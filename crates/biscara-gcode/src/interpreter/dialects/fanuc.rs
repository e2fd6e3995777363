//! Fanuc and Haas controls: Mach3's Fanuc-style reading (nested comments, G65, `O` labels
//! anywhere, bare axis words after G80, G53 without a move), Macro B's control flow, M97 and
//! the machine M-codes (`interpreter/fanuc.rs`), G04 P in milliseconds and a cycle's K repeats.

use super::{DialectHooks, Rules};
use crate::dialect::Dialect;
use crate::interpreter::Machine;
use crate::syntax::lexer::{Fault, InnerParen};

/// Fanuc's and Haas's hooks.
#[derive(Debug)]
pub(in crate::interpreter) struct Fanuc;

const RULES: Rules = Rules {
    dialect: Dialect::Fanuc,
    inner_paren: InnerParen::Opens,
    reads_macro_b: true,
    fanuc_subprograms: true,
    ..Rules::FIRMWARE
};

impl DialectHooks for Fanuc {
    fn rules(&self) -> &'static Rules {
        &RULES
    }

    fn adapt_block(&self, machine: &mut Machine) -> Result<bool, Fault> {
        machine.adapt_fanuc_style_block();
        machine.adapt_fanuc_words();
        Ok(false)
    }
}
