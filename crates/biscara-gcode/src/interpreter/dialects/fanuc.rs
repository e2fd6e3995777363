//! Fanuc and Haas controls: Mach3's Fanuc-style reading (nested comments, G65, `O` labels
//! anywhere, bare axis words after G80, G53 without a move), Macro B's control flow, M97 and
//! the machine M-codes (`interpreter/fanuc.rs`), G04 P in milliseconds and a cycle's K repeats.

use super::DialectHooks;
use crate::dialect::{Dialect, MAX_LONG_LINE};
use crate::interpreter::Machine;
use crate::syntax::lexer::{Fault, InnerParen};

/// Fanuc's and Haas's hooks.
#[derive(Debug)]
pub(in crate::interpreter) struct Fanuc;

impl DialectHooks for Fanuc {
    fn dialect(&self) -> Dialect {
        Dialect::Fanuc
    }

    fn max_line(&self) -> usize {
        MAX_LONG_LINE
    }

    fn inner_paren(&self) -> InnerParen {
        InnerParen::Opens
    }

    fn reads_macro_b(&self) -> bool {
        true
    }

    fn fanuc_subprograms(&self) -> bool {
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
        machine.adapt_fanuc_words();
        Ok(false)
    }

    fn needs_program_end(&self) -> bool {
        false
    }

    fn probe_backs_off(&self) -> bool {
        false
    }
}
