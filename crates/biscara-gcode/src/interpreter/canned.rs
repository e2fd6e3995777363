//! Canned cycles: G73, G74, G81–G89 with G98/G99, L repeats, incremental mode and the sticky
//! R, Z, P, Q, I, J, K values, making exactly the moves LinuxCNC's `rs274` makes
//! (`convert_cycle`, `convert_cycle_xy`/`_yz`/`_zx` and the cycles of `interp_cycles.cc`).
//!
//! In the selected plane, `aa` and `bb` are its two axes and `cc` the axis normal to it: XY
//! (x, y, z), YZ (y, z, x), XZ (z, x, y). What the spindle does (G74/G84 reverse it, G86–G88
//! stop it) is emitted as the tool's events, as M3, M4 and M5 are.

use biscara_motion::{Feed, MotionKind, Plane};

use super::{AXES, Machine};
use crate::syntax::lexer::Fault;

/// LinuxCNC's `G83_RAPID_DELTA`: how far above the last depth a peck restarts, inches.
const RAPID_DELTA_INCH: f64 = 0.010;

/// The values a canned cycle remembers from one block to the next.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct CycleState {
    /// G98 (retract to the initial level) rather than G99 (to R), which is rs274's default.
    pub retract_to_old: bool,
    /// The initial level: the normal axis's position when the cycles began (G98 returns
    /// there, and incremental R counts from it); `None` out of cycles.
    pub initial_level: Option<f64>,
    /// The last R, bottom (Z in XY), P, Q, I, J, K.
    r: f64,
    bottom: f64,
    p: f64,
    q: f64,
    ijk: [f64; 3],
}

impl CycleState {
    /// The I and J a G5 without them takes: rs274 keeps the last G5's (−P, −Q) where it keeps
    /// G87's I and J (`cycle_i`, `cycle_j`), so each reads what the other left.
    pub(super) fn spline_ij(&self) -> [f64; 2] {
        [self.ijk[0], self.ijk[1]]
    }

    /// Keeps a G5's (−P, −Q) for the next G5 (see [`CycleState::spline_ij`]).
    pub(super) fn set_spline_ij(&mut self, ij: [f64; 2]) {
        self.ijk[0] = ij[0];
        self.ijk[1] = ij[1];
    }
}

/// The axes (x = 0, y = 1, z = 2) of `aa`, `bb` and `cc` in `plane`.
fn plane_axes(plane: Plane) -> [usize; 3] {
    match plane {
        Plane::Xy => [0, 1, 2],
        Plane::Yz => [1, 2, 0],
        Plane::Xz => [2, 0, 1],
    }
}

/// Whether `motion` (ten times the G number) is a canned cycle.
pub(super) fn is_cycle(motion: u16) -> bool {
    // The range first: G0–G3 leave after one comparison (this runs on every motion line).
    motion >= 730
        && matches!(motion, 730 | 740 | 810 | 820 | 830 | 840 | 850 | 860 | 870 | 880 | 890)
}

/// The plane's name in rs274's messages.
fn plane_name(plane: Plane) -> &'static str {
    match plane {
        Plane::Xy => "xy",
        Plane::Yz => "yz",
        Plane::Xz => "xz",
    }
}

/// One canned-cycle block as it runs: the plane's axes, where the holes are, the levels and the
/// values each cycle reads (`convert_cycle_xy` and its siblings' locals).
#[derive(Debug, Clone, Copy)]
struct Cycle {
    /// The cycle (ten times its G number).
    motion: u16,
    plane: Plane,
    /// The axes of `aa`, `bb` and `cc` in the plane.
    axes: [usize; 3],
    /// The hole's position in the plane.
    aa: f64,
    bb: f64,
    /// The R plane, the bottom, and the level the tool climbs back to after each hole.
    r: f64,
    cc: f64,
    clear_cc: f64,
    /// The dwell (P), the peck (Q), G87's offsets and back-bore top (I, J, K).
    p: f64,
    q: f64,
    ijk: [f64; 3],
    /// The spindle's M-code when the cycle began (3, 4 or 5).
    spindle: u16,
}

/// The words of a canned-cycle block, with the sticky values filled in.
#[derive(Debug, Clone, Copy)]
struct CycleWords {
    /// R and the bottom as written (or kept).
    r: f64,
    bottom: f64,
    /// How many holes (L).
    repeats: u32,
}

impl Cycle {
    /// A rapid move to `cc` at the hole.
    fn traverse(&self, machine: &mut Machine, cc: f64) {
        machine.cycle_traverse(self.axes, self.aa, self.bb, cc);
    }

    /// A feed move to `cc` at the hole.
    fn feed(&self, machine: &mut Machine, cc: f64) {
        machine.cycle_feed(self.axes, self.aa, self.bb, cc);
    }
}

impl Machine {
    /// A point of the cycle: `aa`, `bb`, `cc` in the plane's axes, the others unchanged.
    fn cycle_point(&self, axes: [usize; 3], aa: f64, bb: f64, cc: f64) -> [f64; 4] {
        let mut point = self.state.current;
        point[axes[0]] = aa;
        point[axes[1]] = bb;
        point[axes[2]] = cc;
        point
    }

    fn cycle_traverse(&mut self, axes: [usize; 3], aa: f64, bb: f64, cc: f64) {
        let point = self.cycle_point(axes, aa, bb, cc);
        self.move_to(point, None);
    }

    fn cycle_feed(&mut self, axes: [usize; 3], aa: f64, bb: f64, cc: f64) {
        let point = self.cycle_point(axes, aa, bb, cc);
        self.move_to(point, Some(Feed { mm_per_min: self.state.feed_mm, inverse_time: false }));
    }

    /// The value of the block's word `letter`.
    fn cycle_word(&self, letter: u8) -> Option<f64> {
        self.syntax.block.letters[usize::from(letter - b'a')].map(|word| word.value)
    }

    /// A canned cycle (`convert_cycle` and `convert_cycle_xy`/`_yz`/`_zx`).
    /// `same`: the cycle was the motion mode before this block (its values are sticky).
    ///
    /// As in `convert_cycle_xy`, the cycle's moves after the climb to the R plane run in exact
    /// path mode (G61) whatever the path control mode, which holds again after the cycle (an
    /// error ends the program, so it need not be restored on one).
    pub(super) fn canned_cycle(&mut self, motion: u16, same: bool) -> Result<(), Fault> {
        self.check_cycle_modes()?;
        let words = self.cycle_words(same)?;
        let (mut cycle, current_cc, increment) = self.cycle_levels(motion, words)?;
        let path_control = self.state.blend.take();
        self.cycle_values(&mut cycle, same)?;
        let mut increment = increment;
        let polar = self.state.incremental && self.syntax.block.polar();
        for repeat in 0..words.repeats {
            if polar
                && repeat > 0
                && let Some([x, y]) = self.polar_repeat([cycle.aa, cycle.bb])
            {
                increment = [x - cycle.aa, y - cycle.bb];
            }
            cycle.aa += increment[0];
            cycle.bb += increment[1];
            if repeat == 0 && current_cc > cycle.r {
                cycle.traverse(self, current_cc);
                cycle.traverse(self, cycle.r);
            } else {
                cycle.traverse(self, cycle.clear_cc);
                if cycle.clear_cc > cycle.r {
                    cycle.traverse(self, cycle.r);
                }
            }
            self.cycle_hole(&cycle)?;
        }
        let end = self.cycle_point(cycle.axes, cycle.aa, cycle.bb, cycle.clear_cc);
        self.state.current = end;
        self.state.cycle.r = words.r;
        self.state.cycle.bottom = words.bottom;
        self.state.blend = path_control;
        Ok(())
    }

    /// The modes a canned cycle cannot run in.
    fn check_cycle_modes(&self) -> Result<(), Fault> {
        if self.state.feed_rate == 0.0 {
            return Err(self.motion_fault("Cannot feed with zero feed rate"));
        }
        if self.state.comp.on() {
            return Err(self.motion_fault("Cannot use canned cycles with cutter compensation on"));
        }
        if self.state.inverse_time {
            return Err(self.motion_fault("Cannot use inverse time feed with canned cycles"));
        }
        Ok(())
    }

    /// The block's R, bottom and L (R and the bottom sticky when the cycle goes on).
    fn cycle_words(&self, same: bool) -> Result<CycleWords, Fault> {
        let r = match self.cycle_word(b'r') {
            Some(r) => r,
            None if same => self.state.cycle.r,
            None => return Err(self.motion_fault("R clearance plane unspecified in cycle")),
        };
        let repeats = match self.syntax.block.word(b'l') {
            None => 1,
            Some(l) if l.value == 0.0 => {
                return Err(self.word_fault(l, "Cannot do zero repeats of cycle"));
            }
            // Not negative: the reader refuses that.
            Some(l) => l.value as u32,
        };
        let normal = AXES[plane_axes(self.state.plane)[2]];
        let bottom = match self.cycle_word(normal) {
            Some(value) => value,
            None if same => self.state.cycle.bottom,
            None => {
                return Err(self.motion_fault(format!(
                    "{} value unspecified in {} plane canned cycle",
                    char::from(normal).to_ascii_uppercase(),
                    plane_name(self.state.plane)
                )));
            }
        };
        Ok(CycleWords { r, bottom, repeats })
    }

    /// The cycle's first hole, R plane, bottom and clearance level (incremental R and bottom
    /// count from the initial level), after the climb to the R plane when the tool is below
    /// it; with the level the tool was at and the increment between holes.
    fn cycle_levels(
        &mut self,
        motion: u16,
        words: CycleWords,
    ) -> Result<(Cycle, f64, [f64; 2]), Fault> {
        let plane = self.state.plane;
        let axes = plane_axes(plane);
        let letters = axes.map(|axis| AXES[axis]);
        let current = self.state.current;
        let mut current_cc = current[axes[2]];
        let mut old_cc = *self.state.cycle.initial_level.get_or_insert(current_cc);
        let (aa, bb, r, cc, increment) = if self.state.incremental {
            let r = words.r + old_cc;
            let increment = [
                self.cycle_word(letters[0]).unwrap_or(0.0),
                self.cycle_word(letters[1]).unwrap_or(0.0),
            ];
            (current[axes[0]], current[axes[1]], r, r + words.bottom, increment)
        } else {
            let aa = self.cycle_word(letters[0]).unwrap_or(current[axes[0]]);
            let bb = self.cycle_word(letters[1]).unwrap_or(current[axes[1]]);
            (aa, bb, words.r, words.bottom, [0.0, 0.0])
        };
        if r < cc {
            return Err(self.motion_fault(format!(
                "R less than {} in cycle in {} plane",
                char::from(letters[2]),
                plane_name(plane)
            )));
        }
        if old_cc < r {
            self.cycle_traverse(axes, current[axes[0]], current[axes[1]], r);
            old_cc = r;
            current_cc = r;
        }
        let clear_cc = if self.state.cycle.retract_to_old { old_cc } else { r };
        let cycle = Cycle {
            motion,
            plane,
            axes,
            aa,
            bb,
            r,
            cc,
            clear_cc,
            p: 0.0,
            q: 0.0,
            ijk: [0.0; 3],
            spindle: self.state.spindle,
        };
        Ok((cycle, current_cc, increment))
    }

    /// The P, Q, I, J, K the cycle needs, sticky when the cycle goes on, kept for the next
    /// cycle. A cycle that reads no P (or Q) leaves the one in store: LinuxCNC keeps `cycle_p`
    /// for a later G74/G84, whose dwell is the last P any cycle read (G82 P0.6, then G83, then
    /// G84 dwells 0.6 s).
    fn cycle_values(&mut self, cycle: &mut Cycle, same: bool) -> Result<(), Fault> {
        let motion = cycle.motion;
        let kept = self.state.cycle;
        let missing = |letter: char| format!("{letter} word missing with g{}", motion / 10);
        cycle.p = match motion {
            740 | 840 => match self.cycle_word(b'p') {
                Some(p) if p != -1.0 => p,
                _ => kept.p,
            },
            820 | 860 | 880 | 890 => match self.cycle_word(b'p') {
                Some(p) if p != -1.0 => p,
                _ if same => kept.p,
                _ => {
                    return Err(self
                        .motion_fault(format!("Dwell time p word missing with g{}", motion / 10)));
                }
            },
            _ => kept.p,
        };
        cycle.q = match motion {
            730 | 830 => match self.cycle_word(b'q') {
                Some(q) if q != -1.0 => q,
                _ if same => kept.q,
                _ => return Err(self.motion_fault(missing('Q'))),
            },
            _ => kept.q,
        };
        cycle.ijk = kept.ijk;
        if motion == 870 {
            for (index, letter) in [b'i', b'j', b'k'].into_iter().enumerate() {
                match self.cycle_word(letter) {
                    Some(value) => cycle.ijk[index] = value,
                    None if same => {}
                    None => {
                        let name = char::from(letter).to_ascii_uppercase();
                        return Err(self.motion_fault(missing(name)));
                    }
                }
            }
        }
        self.state.cycle.p = cycle.p;
        self.state.cycle.q = cycle.q;
        self.state.cycle.ijk = cycle.ijk;
        Ok(())
    }

    /// One hole of the cycle, from the R plane back to the clearance level.
    fn cycle_hole(&mut self, cycle: &Cycle) -> Result<(), Fault> {
        match cycle.motion {
            810 => self.drill(cycle),
            820 => self.drill_dwell(cycle),
            730 | 830 => return self.peck_drill(cycle),
            740 | 840 => return self.tap(cycle),
            850 => self.bore(cycle),
            860 | 870 | 880 => return self.bore_spindle_stopped(cycle),
            _ => self.bore_dwell(cycle),
        }
        Ok(())
    }

    /// G81: drill.
    fn drill(&mut self, cycle: &Cycle) {
        cycle.feed(self, cycle.cc);
        cycle.traverse(self, cycle.clear_cc);
    }

    /// G82: drill, dwell at the bottom.
    fn drill_dwell(&mut self, cycle: &Cycle) {
        cycle.feed(self, cycle.cc);
        self.emit(MotionKind::Dwell { seconds: cycle.p });
        cycle.traverse(self, cycle.clear_cc);
    }

    /// G73 (chip break) and G83 (peck, back to R after each peck).
    fn peck_drill(&mut self, cycle: &Cycle) -> Result<(), Fault> {
        if cycle.q <= 0.0 {
            return Err(self.motion_fault("Negative or zero q value used"));
        }
        let rapid_delta =
            if self.state.metric { RAPID_DELTA_INCH * 25.4 } else { RAPID_DELTA_INCH };
        let mut depth = cycle.r - cycle.q;
        while depth > cycle.cc {
            cycle.feed(self, depth);
            if cycle.motion == 830 {
                cycle.traverse(self, cycle.r);
            }
            cycle.traverse(self, depth + rapid_delta);
            depth -= cycle.q;
        }
        cycle.feed(self, cycle.cc);
        cycle.traverse(self, cycle.clear_cc);
        Ok(())
    }

    /// G74 (left hand) and G84 (right hand): tap, the spindle reversed at the bottom.
    fn tap(&mut self, cycle: &Cycle) -> Result<(), Fault> {
        let message = match (cycle.spindle, cycle.motion) {
            (3, 740) => Some("Spindle turning clockwise in G74"),
            (4, 840) => Some("Spindle turning counterclockwise in G84"),
            (3 | 4, _) => None,
            _ if cycle.motion == 740 => Some("Spindle not turning in G74"),
            _ => Some("Spindle not turning in G84"),
        };
        if let Some(message) = message {
            return Err(self.motion_fault(message));
        }
        // rs274's argument order in the YZ and XZ planes, as it is.
        let (aa, bb) = (cycle.aa, cycle.bb);
        let point = |depth: f64| match cycle.plane {
            Plane::Xy => (aa, bb, depth),
            Plane::Yz => (depth, aa, bb),
            Plane::Xz => (bb, depth, aa),
        };
        let (a, b, c) = point(cycle.cc);
        self.cycle_feed(cycle.axes, a, b, c);
        self.tool_event(5);
        self.tool_event(if cycle.motion == 840 { 4 } else { 3 });
        self.emit(MotionKind::Dwell { seconds: cycle.p });
        let (a, b, c) = point(cycle.clear_cc);
        self.cycle_feed(cycle.axes, a, b, c);
        self.tool_event(5);
        self.tool_event(cycle.spindle);
        Ok(())
    }

    /// G85: bore, feed out.
    fn bore(&mut self, cycle: &Cycle) {
        cycle.feed(self, cycle.cc);
        cycle.feed(self, cycle.r);
        cycle.traverse(self, cycle.clear_cc);
    }

    /// G86 (bore, spindle stop, rapid out), G87 (back bore) and G88 (bore, spindle stop,
    /// manual out): the spindle must turn, and turns again after.
    fn bore_spindle_stopped(&mut self, cycle: &Cycle) -> Result<(), Fault> {
        if !matches!(cycle.spindle, 3 | 4) {
            return Err(self.motion_fault(format!("Spindle not turning in g{}", cycle.motion / 10)));
        }
        match cycle.motion {
            860 => {
                cycle.feed(self, cycle.cc);
                self.emit(MotionKind::Dwell { seconds: cycle.p });
                self.tool_event(5);
                cycle.traverse(self, cycle.clear_cc);
            }
            870 => self.back_bore(cycle),
            _ => {
                cycle.feed(self, cycle.cc);
                self.emit(MotionKind::Dwell { seconds: cycle.p });
                self.tool_event(5);
                self.emit(MotionKind::Pause);
            }
        }
        self.tool_event(cycle.spindle);
        Ok(())
    }

    /// G87: back bore, in through the hole off centre by I, J with the spindle stopped, up to
    /// the K level and back.
    fn back_bore(&mut self, cycle: &Cycle) {
        let Cycle { axes, aa, bb, r, cc, clear_cc, ijk, spindle, .. } = *cycle;
        let back_bore_top = if self.state.incremental { cc + ijk[2] } else { ijk[2] };
        let (offset_a, offset_b) = (aa + ijk[0], bb + ijk[1]);
        self.cycle_traverse(axes, offset_a, offset_b, r);
        self.tool_event(5);
        self.cycle_traverse(axes, offset_a, offset_b, cc);
        self.cycle_traverse(axes, aa, bb, cc);
        self.tool_event(spindle);
        self.cycle_feed(axes, aa, bb, back_bore_top);
        self.cycle_feed(axes, aa, bb, cc);
        self.tool_event(5);
        self.cycle_traverse(axes, offset_a, offset_b, cc);
        self.cycle_traverse(axes, offset_a, offset_b, clear_cc);
        self.cycle_traverse(axes, aa, bb, clear_cc);
    }

    /// G89: bore, dwell at the bottom, feed out.
    fn bore_dwell(&mut self, cycle: &Cycle) {
        cycle.feed(self, cycle.cc);
        self.emit(MotionKind::Dwell { seconds: cycle.p });
        cycle.feed(self, cycle.clear_cc);
    }
}
