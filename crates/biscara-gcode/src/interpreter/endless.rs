//! Loops that can only repeat: a jump back made from the same line with the same machine state
//! (position, parameters, modes, call stack, loop counters) as the last jump back from there
//! repeats what followed it, forever. The interpreter stops such a program at that jump, the
//! end of the loop's second pass with nothing changed, rather than let it run without end.
//!
//! Only loops' turns are judged (`endwhile`, `while` of a `do`, `endrepeat`, `continue`, a
//! Fanuc `GOTO`), not calls. The state is compared in two steps: the position first (a loop
//! that moves on changes it at every pass, for the price of a few comparisons), then, only
//! when it is the same, the whole state: written out, and the parameters' values (compared
//! only when one was set to another value since).

use std::collections::HashMap;
use std::fmt::Write as _;
use std::path::Path;
use std::rc::Rc;

use super::Machine;
use crate::syntax::params::ParamsSnapshot;

/// The most jump points remembered: past them, all are forgotten (memory stays flat in a long
/// program whose calls are made from many lines; a loop's own points are met again at its next
/// pass, and an endless loop with more points than this is left to the bound on motions).
const MAX_POINTS: usize = 64;

/// Where a jump back is made from: the file (`None`: the main program) and its line.
type JumpPoint = (Option<Rc<Path>>, usize);

/// The jumps back made so far, by the point they were made from: the state at the last one.
#[derive(Debug, Default)]
pub(super) struct Visits {
    last: HashMap<JumpPoint, Visit>,
    /// Scratch space for the state written out.
    scratch: String,
}

/// The state at one jump back.
#[derive(Debug)]
struct Visit {
    /// What is compared first: the position's bits.
    quick: Quick,
    /// The parameters' values at the last jump (kept up to date by the changes since).
    params: ParamsSnapshot,
    /// The rest of the state written out, when it was taken at the last jump (only when the
    /// position and the parameters were the same as at the jump before is it needed).
    text: Option<String>,
}

/// The position (bits of `[x, y, z, c]`) and the extruder's position (bits).
type Quick = ([u64; 4], u64);

impl Visits {
    /// Records a jump back made from `point` with `machine` in its state, `control` (the
    /// control flow's state, written out) beside it: `true` when the state is the same as at
    /// the last jump back from there, which can then only repeat.
    pub(super) fn repeats(
        &mut self,
        point: JumpPoint,
        machine: &Machine,
        control: impl FnOnce(&mut String),
    ) -> bool {
        let quick = machine.quick_state();
        let params = &machine.state.params;
        if self.last.len() >= MAX_POINTS && !self.last.contains_key(&point) {
            self.last.clear();
        }
        let Some(visit) = self.last.get_mut(&point) else {
            let mut text = String::new();
            machine.write_state(&mut text);
            control(&mut text);
            self.last.insert(point, Visit { quick, params: params.snapshot(), text: Some(text) });
            return false;
        };
        if visit.quick != quick {
            // Moved on: what follows may differ.
            visit.quick = quick;
            visit.text = None;
            return false;
        }
        if !params.same_as(&visit.params) {
            params.refresh(&mut visit.params);
            visit.text = None;
            return false;
        }
        self.scratch.clear();
        machine.write_state(&mut self.scratch);
        control(&mut self.scratch);
        if visit.text.as_deref() == Some(self.scratch.as_str()) {
            return true;
        }
        // The first jump with this position and these parameters: kept to compare the next
        // one with.
        params.refresh(&mut visit.params);
        visit.text = Some(std::mem::take(&mut self.scratch));
        false
    }
}

impl Machine {
    /// What [`Visits`] compares first.
    fn quick_state(&self) -> Quick {
        (self.state.current.map(f64::to_bits), self.hooks.e_position.to_bits())
    }

    /// The machine's whole state but the parameters (compared apart) and what only reports (the
    /// counts of codes for the notes, the motions waiting to be given), written out.
    fn write_state(&self, out: &mut String) {
        let s = &self.state;
        let _ = write!(
            out,
            "{:?}",
            (
                (s.metric, s.incremental, s.ijk_absolute, s.plane, s.inverse_time),
                (s.feed_rate, s.feed_mm, s.motion, s.current, s.origin, s.axis_offset),
                (s.system, s.rotation, s.speed, s.tool_offset),
                (s.tool_offset_mm, s.tool_shift, s.resync, &s.tools, &s.cycle),
                (&s.modal_stack, s.spindle, s.mist, s.flood, &s.owords, s.blend, s.naive_cam),
                (&s.comp, s.zeroed_at_start),
            )
        );
        let h = &self.hooks;
        let _ = write!(
            out,
            "{:?}",
            (
                h.rules.dialect,
                h.provisional,
                h.tool,
                h.tool_on,
                h.laser_rapid_off,
                h.e_position,
                h.e_relative,
                h.pending_extrude,
                &h.fanuc,
            )
        );
    }
}
