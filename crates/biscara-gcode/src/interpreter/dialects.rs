//! The dialects as implementations of one trait, `DialectHooks`: what the interpreter asks of
//! the firmware a program was written for, at the points where a firmware reads G-code
//! differently from LinuxCNC. The answers that are values are the dialect's `Rules`; the ones
//! that act (a raw line read before the block reader, a block changed after it) are the
//! trait's other methods. Every default is LinuxCNC's reading, so `Linuxcnc` implements
//! nothing; Grbl, Marlin, Mach3 and Fanuc (`dialects/`) answer where they differ. The machine
//! holds the hooks in force (`Hooks::dialect`, `Hooks::rules`) and the executor asks them,
//! never which dialect it reads; `auto` swaps them when it decides, before or during the
//! program.

use std::fmt::Debug;

use super::Machine;
use crate::dialect::{Dialect, MAX_LONG_LINE, Prelude, Summary};
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

/// What a dialect reads differently from LinuxCNC, where the answer is a value.
#[derive(Debug)]
pub(super) struct Rules {
    /// The dialect these rules are.
    pub(super) dialect: Dialect,
    /// The longest line read, bytes.
    pub(super) max_line: usize,
    /// The feed rate (mm/min) in force before the program's first F word (`None`: zero, so a
    /// feed move needs an F word first).
    pub(super) default_feed: Option<f64>,
    /// Whether [`DialectHooks::prelude`] can take a line (a line costs no call otherwise).
    pub(super) has_prelude: bool,
    /// What a `(` inside a `( )` comment is.
    pub(super) inner_paren: InnerParen,
    /// Whether a `(` comment left open ends at the end of its line (rather than being an error).
    pub(super) closes_comment_at_line_end: bool,
    /// Whether Fanuc Custom Macro B lines (`IF`, `WHILE … DO`, `GOTO`), M97 and the machine
    /// M-codes are read before the O-word control flow (`interpreter/fanuc.rs`).
    pub(super) reads_macro_b: bool,
    /// Whether `G65 P…` calls a subprogram, and an `O` label is found anywhere in the file
    /// (Fanuc-style subprograms, as Mach3 and Fanuc run them).
    pub(super) fanuc_subprograms: bool,
    /// Whether the block reader takes Mach3's G31 probe and its M40/M41 gear ranges.
    pub(super) reads_mach3_codes: bool,
    /// Whether a number takes an exponent written right after it (`6.2e-15`: C's `strtod`).
    pub(super) reads_exponents: bool,
    /// Whether LinuxCNC's executed comments run: `(abort,…)`, `(py,…)` and `;py,` lines.
    pub(super) executes_comments: bool,
    /// Whether [`DialectHooks::adapt_block`] changes blocks (a block costs no call otherwise).
    pub(super) adapts_blocks: bool,
    /// Whether a program must end with M2, M30 or its closing `%` (otherwise it ends where its
    /// input ends, and the motions cutter compensation holds are sent then).
    pub(super) needs_program_end: bool,
    /// Whether G10 L2/L20 without P sets the coordinate system in force (as P0).
    pub(super) g10_p_optional: bool,
    /// Whether G41/G42 take the compensation radius from a P word (program units).
    pub(super) comp_radius_in_p: bool,
    /// Whether G0 moves at the feed rate in force.
    pub(super) rapid_at_feed: bool,
    /// Whether a K word of an XY-plane arc is read and ignored.
    pub(super) ignores_k_in_xy_arc: bool,
    /// Whether the robot stops back from a probe's end point, as LinuxCNC's simulated probe
    /// does.
    pub(super) probe_backs_off: bool,
    /// Whether the laser is turned off for rapids and on again for the next feed move (Grbl's
    /// laser mode).
    pub(super) gates_laser_in_rapids: bool,
}

impl Rules {
    /// LinuxCNC's reading.
    const LINUXCNC: Rules = Rules {
        dialect: Dialect::Linuxcnc,
        max_line: MAX_LINE,
        default_feed: None,
        has_prelude: false,
        inner_paren: InnerParen::Refused,
        closes_comment_at_line_end: false,
        reads_macro_b: false,
        fanuc_subprograms: false,
        reads_mach3_codes: false,
        reads_exponents: false,
        executes_comments: true,
        adapts_blocks: false,
        needs_program_end: true,
        g10_p_optional: false,
        comp_radius_in_p: false,
        rapid_at_feed: false,
        ignores_k_in_xy_arc: false,
        probe_backs_off: true,
        gates_laser_in_rapids: false,
    };

    /// What the firmware dialects (all but LinuxCNC) share: long lines (a thumbnail, a long
    /// comment), no executed comments, blocks of their own, no program end needed, no probe
    /// back-off.
    const FIRMWARE: Rules = Rules {
        max_line: MAX_LONG_LINE,
        executes_comments: false,
        adapts_blocks: true,
        needs_program_end: false,
        probe_backs_off: false,
        ..Rules::LINUXCNC
    };
}

/// What a dialect decides where firmware reads G-code differently from LinuxCNC. The defaults
/// are LinuxCNC's reading.
pub(super) trait DialectHooks: Debug + Sync {
    /// The dialect's answers that are values.
    fn rules(&self) -> &'static Rules {
        &Rules::LINUXCNC
    }

    /// The tool a program in this dialect is written for when nothing in it tells.
    fn implied_tool(&self) -> Option<ToolInference> {
        None
    }

    /// What the dialect makes of a raw line before LinuxCNC's reader sees it (asked only when
    /// [`Rules::has_prelude`]).
    fn prelude(&self, _raw: &[u8]) -> Prelude {
        Prelude::Block
    }

    /// Counts what the firmware refuses in an O-word line read as LinuxCNC reads it.
    fn count_refused_o_word(&self, _summary: &mut Summary) {}

    /// The dialect's changes to the block just read, before it runs (asked only when
    /// [`Rules::adapts_blocks`]); `Ok(true)` when the block is done with.
    fn adapt_block(&self, _machine: &mut Machine) -> Result<bool, Fault> {
        Ok(false)
    }
}

/// LinuxCNC's RS274/NGC: every hook as the trait's default.
#[derive(Debug)]
pub(super) struct Linuxcnc;

impl DialectHooks for Linuxcnc {}

/// The hooks of `dialect` (LinuxCNC's for [`Dialect::Auto`], which reads as LinuxCNC until it
/// decides).
pub(super) fn hooks_of(dialect: Dialect) -> &'static dyn DialectHooks {
    match dialect {
        Dialect::Auto | Dialect::Linuxcnc => &Linuxcnc,
        Dialect::Grbl => &grbl::Grbl,
        // MakerBot's flavour is Marlin's reading; its A word is renamed (`Hooks::makerbot`).
        Dialect::Marlin | Dialect::Makerbot => &marlin::Marlin,
        Dialect::Mach3 => &mach3::Mach3,
        Dialect::Fanuc => &fanuc::Fanuc,
    }
}
