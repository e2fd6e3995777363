//! The dialects as implementations of one trait, [`DialectHooks`]: the questions the
//! interpreter asks of the firmware a program was written for, at the points where a firmware
//! reads G-code differently from LinuxCNC. Each method's default is LinuxCNC's own reading, so
//! [`Linuxcnc`] implements none of them; Grbl, Marlin, Mach3 and Fanuc (`dialects/`) implement
//! the ones where they differ. The executor asks the hooks in force
//! ([`Hooks::dialect`](super::hooks::Hooks)) and never which dialect it reads; `auto` swaps the
//! hooks when it decides, before or during the program.

use std::fmt::Debug;

use super::Machine;
use crate::dialect::{Dialect, Prelude, Summary};
use crate::syntax::lexer::{Fault, InnerParen, MAX_LINE};
use crate::tool::ToolInference;

/// Fanuc and Haas controls.
mod fanuc;
/// Grbl 1.1.
mod grbl;
/// Mach3.
mod mach3;
/// Marlin and the RepRap family.
mod marlin;

/// What a dialect decides where firmware reads G-code differently from LinuxCNC. The defaults
/// are LinuxCNC's reading.
pub(super) trait DialectHooks: Debug + Sync {
    /// The dialect these hooks are.
    fn dialect(&self) -> Dialect;

    /// The longest line read, bytes.
    fn max_line(&self) -> usize {
        MAX_LINE
    }

    /// The feed rate (mm/min) in force before the program's first F word (`None`: zero, so a
    /// feed move needs an F word first).
    fn default_feed(&self) -> Option<f64> {
        None
    }

    /// The tool a program in this dialect is written for when nothing in it tells.
    fn implied_tool(&self) -> Option<ToolInference> {
        None
    }

    /// What the dialect makes of a raw line before LinuxCNC's reader sees it.
    fn prelude(&self, _raw: &[u8]) -> Prelude {
        Prelude::Block
    }

    /// Whether the hook of [`Self::prelude`] can take lines (a line costs no call otherwise).
    fn has_prelude(&self) -> bool {
        false
    }

    /// What a `(` inside a `( )` comment is.
    fn inner_paren(&self) -> InnerParen {
        InnerParen::Refused
    }

    /// Whether a `(` comment left open ends at the end of its line (rather than being an error).
    fn closes_comment_at_line_end(&self) -> bool {
        false
    }

    /// Whether Fanuc Custom Macro B lines (`IF`, `WHILE … DO`, `GOTO`), M97 and the machine
    /// M-codes are read before the O-word control flow (`interpreter/fanuc.rs`).
    fn reads_macro_b(&self) -> bool {
        false
    }

    /// Whether `G65 P…` calls a subprogram, and an `O` label is found anywhere in the file
    /// (Fanuc-style subprograms, as Mach3 and Fanuc run them).
    fn fanuc_subprograms(&self) -> bool {
        false
    }

    /// The block reader's extra codes: Mach3's G31 probe and its M40/M41 gear ranges.
    fn reads_mach3_codes(&self) -> bool {
        false
    }

    /// Counts what the firmware refuses in an O-word line read as LinuxCNC reads it.
    fn count_refused_o_word(&self, _summary: &mut Summary) {}

    /// Whether LinuxCNC's executed comments run: `(abort,…)`, `(py,…)` and `;py,` lines.
    fn executes_comments(&self) -> bool {
        true
    }

    /// Whether the block just read is changed by the dialect before it runs (a call to
    /// [`Self::adapt_block`] otherwise costs nothing).
    fn adapts_blocks(&self) -> bool {
        false
    }

    /// The dialect's changes to the block just read, before it runs; `Ok(true)` when the
    /// block is done with.
    fn adapt_block(&self, _machine: &mut Machine) -> Result<bool, Fault> {
        Ok(false)
    }

    /// Whether a program must end with M2, M30 or its closing `%` (the others end where their
    /// input ends, and the motions cutter compensation holds are sent then).
    fn needs_program_end(&self) -> bool {
        true
    }

    /// Whether G10 L2/L20 without P sets the coordinate system in force (as P0).
    fn g10_p_optional(&self) -> bool {
        false
    }

    /// Whether G41/G42 take the compensation radius from a P word (program units).
    fn comp_radius_in_p(&self) -> bool {
        false
    }

    /// Whether G0 moves at the feed rate in force.
    fn rapid_at_feed(&self) -> bool {
        false
    }

    /// Whether a K word of an XY-plane arc is read and ignored.
    fn ignores_k_in_xy_arc(&self) -> bool {
        false
    }

    /// Whether the robot stops back from a probe's end point, as LinuxCNC's simulated probe
    /// does.
    fn probe_backs_off(&self) -> bool {
        true
    }

    /// Whether the laser is turned off for rapids and on again for the next feed move (Grbl's
    /// laser mode).
    fn gates_laser_in_rapids(&self) -> bool {
        false
    }
}

/// LinuxCNC's RS274/NGC: every hook as the trait's default.
#[derive(Debug)]
pub(super) struct Linuxcnc;

impl DialectHooks for Linuxcnc {
    fn dialect(&self) -> Dialect {
        Dialect::Linuxcnc
    }
}

/// The hooks of `dialect` (LinuxCNC's for [`Dialect::Auto`], which reads as LinuxCNC until it
/// decides).
pub(super) fn hooks_of(dialect: Dialect) -> &'static dyn DialectHooks {
    match dialect {
        Dialect::Auto | Dialect::Linuxcnc => &Linuxcnc,
        Dialect::Grbl => &grbl::Grbl,
        Dialect::Marlin => &marlin::Marlin,
        Dialect::Mach3 => &mach3::Mach3,
        Dialect::Fanuc => &fanuc::Fanuc,
    }
}
