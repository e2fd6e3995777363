//! Probing, G38.2–G38.5, as LinuxCNC's standalone `rs274` simulates it (`convert_probe`, and
//! `STRAIGHT_PROBE` and the probe queries of its canon, `saicanon.cc`).
//!
//! A virtual robot has no probe input, so no probe ever trips:
//! - the probe move runs at the feed in force, straight to its end point;
//! - in LinuxCNC's dialect the robot then stops 0.254 mm (0.01 inch) back from that point along
//!   the move, as rs274 does; this is a second, short straight move here, because motions must
//!   be continuous (Grbl and Mach3 stay at the end point);
//! - the next line reads the end point in #5061–#5063 (#5066 for C) and 0 ("not tripped") in
//!   #5070; Mach3's G31 (its straight probe, which goes on without an error when nothing
//!   trips, as G38.3 does) also in #2000–#2002 (#2005 for C), where Mach3 puts it.
//!
//! Before the moves comes an event with the code (`G38.2`), so that a time series shows where
//! the robot probes, and the program's notes count the probe moves.

use biscara_motion::{CodeName, Feed, MotionKind};

use super::Machine;
use crate::dialect::g_name;
use crate::syntax::lexer::Fault;
use crate::syntax::params::axis_slot;

/// First of the parameters that receive the probed point (x y z a b c u v w follow).
const PROBED_POINT: usize = 5061;
/// Whether the probe tripped: 1, or 0 (always here: nothing to touch).
const PROBE_TRIPPED: usize = 5070;
/// First of the parameters where Mach3 puts the probed point (x y z a b c).
const MACH3_PROBED_POINT: usize = 2000;
/// How far rs274 stops back from a probe's end point, millimetres (0.01 inch).
const BACKOFF_MM: f64 = 0.254;

/// Whether G code `code` (ten times the number) is a probe move: G38.2–G38.5, or Mach3's G31
/// (which the block reader takes only in the Mach3 dialect).
pub(super) fn is_probe(code: u16) -> bool {
    matches!(code, 382..=385 | 310)
}

impl Machine {
    /// G38.2 (`code` 382: toward the work, error on no contact), G38.3 (383: no error), G38.4
    /// (384: away from the work, error on no loss of contact), G38.5 (385: no error) and
    /// Mach3's G31 (310: toward the work, no error).
    pub(super) fn probe(&mut self, code: u16) -> Result<(), Fault> {
        let name = g_name(code);
        if self.state.comp.on() {
            return Err(self.motion_fault("Cannot probe with cutter radius comp on"));
        }
        if self.state.inverse_time {
            // rs274 probes at the last F read, whatever it meant; LinuxCNC's motion controller
            // takes no inverse-time feed for a probe.
            let (start, end) = self.motion_span();
            return Err(Fault::not_supported(
                start,
                end,
                name,
                "probing in inverse time mode, G93: program G94 and a feed rate",
            ));
        }
        if self.state.feed_rate == 0.0 {
            return Err(self.motion_fault("Cannot probe with zero feed rate"));
        }
        let end = self.find_ends(false);
        // rs274's canon backs off toward where it last moved: tool length offsets set since
        // then moved the interpreter's current point, not the canon's.
        let current = self.state.current;
        let start: [f64; 4] =
            std::array::from_fn(|axis| current[axis] - self.state.tool_shift[axis]);
        // G38.2 and G38.4 fail when the probe cannot move; G38.3 and G38.5 just report.
        let must_move = matches!(code, 382 | 384);
        if must_move && current == end {
            return Err(self.motion_fault("Start point too close to probe point"));
        }
        self.hooks.summary.count_probe(&name);
        if let Some(name) = CodeName::new(&name) {
            self.emit(MotionKind::Code { code: name });
        }
        let feed = Feed { mm_per_min: self.state.feed_mm, inverse_time: false };
        self.move_to(end, Some(feed));
        for (axis, &value) in end.iter().enumerate() {
            self.state.params.set(PROBED_POINT + axis_slot(axis), value);
            if code == 310 {
                self.state.params.set(MACH3_PROBED_POINT + axis_slot(axis), value);
            }
        }
        self.state.params.set(PROBE_TRIPPED, 0.0);
        let distance = (0..3).map(|axis| (start[axis] - end[axis]).powi(2)).sum::<f64>().sqrt();
        if distance != 0.0 && self.hooks.rules.probe_backs_off {
            let backoff = BACKOFF_MM / self.state.factor();
            let mut stop = end;
            for axis in 0..3 {
                stop[axis] = end[axis] + backoff * (start[axis] - end[axis]) / distance;
            }
            self.move_to(stop, Some(feed));
        }
        Ok(())
    }
}
