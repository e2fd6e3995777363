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

    /// A canned cycle (`convert_cycle` and `convert_cycle_xy`/`_yz`/`_zx`).
    /// `same`: the cycle was the motion mode before this block (its values are sticky).
    ///
    /// As in `convert_cycle_xy`, the cycle's moves after the climb to the R plane run in exact
    /// path mode (G61) whatever the path control mode, which holds again after the cycle (an
    /// error ends the program, so it need not be restored on one).
    pub(super) fn canned_cycle(&mut self, motion: u16, same: bool) -> Result<(), Fault> {
        if self.state.feed_rate == 0.0 {
            return Err(self.motion_fault("Cannot feed with zero feed rate"));
        }
        if self.state.comp.on() {
            return Err(self.motion_fault("Cannot use canned cycles with cutter compensation on"));
        }
        if self.state.inverse_time {
            return Err(self.motion_fault("Cannot use inverse time feed with canned cycles"));
        }
        let letters = self.syntax.block.letters;
        let word = |letter: u8| letters[usize::from(letter - b'a')].map(|word| word.value);
        let r_word = match word(b'r') {
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
        let plane = self.state.plane;
        let axes = plane_axes(plane);
        let plane_letters = axes.map(|axis| AXES[axis]);
        let (normal_name, plane_name) = match plane {
            Plane::Xy => ('z', "xy"),
            Plane::Yz => ('x', "yz"),
            Plane::Xz => ('y', "xz"),
        };
        let bottom_word = match word(plane_letters[2]) {
            Some(value) => value,
            None if same => self.state.cycle.bottom,
            None => {
                return Err(self.motion_fault(format!(
                    "{} value unspecified in {plane_name} plane canned cycle",
                    normal_name.to_ascii_uppercase()
                )));
            }
        };
        let current = self.state.current;
        let mut current_cc = current[axes[2]];
        let mut old_cc = *self.state.cycle.initial_level.get_or_insert(current_cc);
        let (mut aa, mut bb, r, cc, increment) = if self.state.incremental {
            let r = r_word + old_cc;
            let increment =
                [word(plane_letters[0]).unwrap_or(0.0), word(plane_letters[1]).unwrap_or(0.0)];
            (current[axes[0]], current[axes[1]], r, r + bottom_word, increment)
        } else {
            let aa = word(plane_letters[0]).unwrap_or(current[axes[0]]);
            let bb = word(plane_letters[1]).unwrap_or(current[axes[1]]);
            (aa, bb, r_word, bottom_word, [0.0, 0.0])
        };
        if r < cc {
            return Err(self.motion_fault(format!(
                "R less than {normal_name} in cycle in {plane_name} plane"
            )));
        }
        if old_cc < r {
            let (a, b) = (current[axes[0]], current[axes[1]]);
            self.cycle_traverse(axes, a, b, r);
            old_cc = r;
            current_cc = r;
        }
        let clear_cc = if self.state.cycle.retract_to_old { old_cc } else { r };
        let path_control = self.state.blend.take();
        // The values each cycle needs, sticky when the cycle goes on. A cycle that reads no P
        // (or Q) leaves the one in store: LinuxCNC keeps `cycle_p` for a later G74/G84, whose
        // dwell is the last P any cycle read (G82 P0.6, then G83, then G84 dwells 0.6 s).
        let cycle = self.state.cycle;
        let missing = |letter: char| format!("{letter} word missing with g{}", motion / 10);
        let p = match motion {
            740 | 840 => match word(b'p') {
                Some(p) if p != -1.0 => p,
                _ => cycle.p,
            },
            820 | 860 | 880 | 890 => match word(b'p') {
                Some(p) if p != -1.0 => p,
                _ if same => cycle.p,
                _ => {
                    return Err(self
                        .motion_fault(format!("Dwell time p word missing with g{}", motion / 10)));
                }
            },
            _ => cycle.p,
        };
        let q = match motion {
            730 | 830 => match word(b'q') {
                Some(q) if q != -1.0 => q,
                _ if same => cycle.q,
                _ => return Err(self.motion_fault(missing('Q'))),
            },
            _ => cycle.q,
        };
        let mut ijk = cycle.ijk;
        if motion == 870 {
            for (index, letter) in [b'i', b'j', b'k'].into_iter().enumerate() {
                match word(letter) {
                    Some(value) => ijk[index] = value,
                    None if same => {}
                    None => {
                        let name = char::from(letter).to_ascii_uppercase();
                        return Err(self.motion_fault(missing(name)));
                    }
                }
            }
        }
        self.state.cycle.p = p;
        self.state.cycle.q = q;
        self.state.cycle.ijk = ijk;
        let spindle = self.state.spindle;
        let rapid_delta =
            if self.state.metric { RAPID_DELTA_INCH * 25.4 } else { RAPID_DELTA_INCH };
        let back_bore_top = if self.state.incremental { cc + ijk[2] } else { ijk[2] };
        let mut increment = increment;
        let polar = self.state.incremental && self.syntax.block.polar();
        for repeat in 0..repeats {
            if polar
                && repeat > 0
                && let Some([x, y]) = self.polar_repeat([aa, bb])
            {
                increment = [x - aa, y - bb];
            }
            aa += increment[0];
            bb += increment[1];
            if repeat == 0 && current_cc > r {
                self.cycle_traverse(axes, aa, bb, current_cc);
                self.cycle_traverse(axes, aa, bb, r);
            } else {
                self.cycle_traverse(axes, aa, bb, clear_cc);
                if clear_cc > r {
                    self.cycle_traverse(axes, aa, bb, r);
                }
            }
            match motion {
                810 => {
                    self.cycle_feed(axes, aa, bb, cc);
                    self.cycle_traverse(axes, aa, bb, clear_cc);
                }
                820 => {
                    self.cycle_feed(axes, aa, bb, cc);
                    self.emit(MotionKind::Dwell { seconds: p });
                    self.cycle_traverse(axes, aa, bb, clear_cc);
                }
                730 | 830 => {
                    if q <= 0.0 {
                        return Err(self.motion_fault("Negative or zero q value used"));
                    }
                    let mut depth = r - q;
                    while depth > cc {
                        self.cycle_feed(axes, aa, bb, depth);
                        if motion == 830 {
                            self.cycle_traverse(axes, aa, bb, r);
                        }
                        self.cycle_traverse(axes, aa, bb, depth + rapid_delta);
                        depth -= q;
                    }
                    self.cycle_feed(axes, aa, bb, cc);
                    self.cycle_traverse(axes, aa, bb, clear_cc);
                }
                740 | 840 => {
                    let message = match (spindle, motion) {
                        (3, 740) => Some("Spindle turning clockwise in G74"),
                        (4, 840) => Some("Spindle turning counterclockwise in G84"),
                        (3 | 4, _) => None,
                        _ if motion == 740 => Some("Spindle not turning in G74"),
                        _ => Some("Spindle not turning in G84"),
                    };
                    if let Some(message) = message {
                        return Err(self.motion_fault(message));
                    }
                    // rs274's argument order in the YZ and XZ planes, as it is.
                    let point = |depth: f64| match plane {
                        Plane::Xy => (aa, bb, depth),
                        Plane::Yz => (depth, aa, bb),
                        Plane::Xz => (bb, depth, aa),
                    };
                    let (a, b, c) = point(cc);
                    self.cycle_feed(axes, a, b, c);
                    self.tool_event(5);
                    self.tool_event(if motion == 840 { 4 } else { 3 });
                    self.emit(MotionKind::Dwell { seconds: p });
                    let (a, b, c) = point(clear_cc);
                    self.cycle_feed(axes, a, b, c);
                    self.tool_event(5);
                    self.tool_event(spindle);
                }
                850 => {
                    self.cycle_feed(axes, aa, bb, cc);
                    self.cycle_feed(axes, aa, bb, r);
                    self.cycle_traverse(axes, aa, bb, clear_cc);
                }
                860 | 870 | 880 => {
                    if !matches!(spindle, 3 | 4) {
                        return Err(
                            self.motion_fault(format!("Spindle not turning in g{}", motion / 10))
                        );
                    }
                    match motion {
                        860 => {
                            self.cycle_feed(axes, aa, bb, cc);
                            self.emit(MotionKind::Dwell { seconds: p });
                            self.tool_event(5);
                            self.cycle_traverse(axes, aa, bb, clear_cc);
                        }
                        870 => {
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
                        _ => {
                            self.cycle_feed(axes, aa, bb, cc);
                            self.emit(MotionKind::Dwell { seconds: p });
                            self.tool_event(5);
                            self.emit(MotionKind::Pause);
                        }
                    }
                    self.tool_event(spindle);
                }
                _ => {
                    self.cycle_feed(axes, aa, bb, cc);
                    self.emit(MotionKind::Dwell { seconds: p });
                    self.cycle_feed(axes, aa, bb, clear_cc);
                }
            }
        }
        let end = self.cycle_point(axes, aa, bb, clear_cc);
        self.state.current = end;
        self.state.cycle.r = r_word;
        self.state.cycle.bottom = bottom_word;
        self.state.blend = path_control;
        Ok(())
    }
}
