//! Motion: the end point of a block, G28/G30, straight moves and arcs with LinuxCNC's
//! tolerances, and LinuxCNC's length and turn helpers.

use super::*;

impl Machine {
    /// End point of a move (`find_ends`).
    pub(super) fn find_ends(&self, g53: bool) -> [f64; 4] {
        let rotated = (g53 && self.state.rotation != 0.0).then(|| self.rotated_g53_ends());
        // Without compensation the base is the current point (checked once, not per axis).
        let comp = self.state.comp.on() && !g53;
        std::array::from_fn(|axis| {
            if let Some(Some(xy)) = rotated
                && axis < 2
            {
                return xy[axis];
            }
            let word = self.syntax.block.word(AXES[axis]).map(|word| word.value);
            let current = if comp {
                self.state.comp.base(axis, self.state.plane).unwrap_or(self.state.current[axis])
            } else {
                self.state.current[axis]
            };
            match word {
                None => current,
                Some(value) if g53 => {
                    value
                        - self.state.origin[axis]
                        - self.state.axis_offset[axis]
                        - self.state.tool_offset[axis]
                }
                Some(value) if self.state.incremental => current + value,
                Some(value) => value,
            }
        })
    }

    /// G28 and G30: through the intermediate point to the stored position.
    pub(super) fn go_home(&mut self, code: Code) -> Result<(), Fault> {
        let intermediate = self.find_ends(false);
        self.move_to(intermediate, None);
        let base = if code.code == 280 { G28_HOME } else { G30_HOME };
        let any = AXES.iter().any(|&letter| self.syntax.block.word(letter).is_some());
        let mut end = intermediate;
        let home = std::array::from_fn(|axis| {
            self.state.mm_to_program(axis, self.state.params.get(base + axis_slot(axis)))
        });
        let home = self.state.program_of(home);
        for (axis, &letter) in AXES.iter().enumerate() {
            if any && self.syntax.block.word(letter).is_none() {
                continue;
            }
            end[axis] = home[axis];
        }
        self.move_to(end, None);
        Ok(())
    }

    /// Emits a rapid (`feed` = None) or linear move and makes `end` the current point.
    pub(super) fn move_to(&mut self, end: [f64; 4], feed: Option<Feed>) {
        let absolute = self.state.absolute(end);
        self.emit(match feed {
            None => MotionKind::Rapid { end: absolute },
            Some(feed) => MotionKind::Linear { end: absolute, feed },
        });
        self.state.current = end;
        self.state.tool_shift = [0.0; 4];
    }

    pub(super) fn straight(&mut self, motion: u16, g53: bool) -> Result<(), Fault> {
        self.comp_straight_seen();
        let end = self.find_ends(g53);
        if motion == 0 && self.state.comp.active() {
            return self.comp_straight(true, end, None, g53);
        }
        // Marlin moves G0 as G1, at the feed rate in force.
        if motion == 0 && self.hooks.rules.rapid_at_feed {
            self.move_to(end, Some(Feed { mm_per_min: self.state.feed_mm, inverse_time: false }));
            return Ok(());
        }
        if motion == 0 {
            self.move_to(end, None);
            return Ok(());
        }
        let feed = if self.state.inverse_time {
            let Some(f) = self.syntax.block.word(b'f') else {
                let code = self.syntax.block.g[1].map_or((0, 1), |code| (code.at, code.end));
                return Err(self.fault_at(
                    code.0,
                    code.1,
                    "F word missing with inverse time g1 move",
                ));
            };
            let start = self.comp_start().unwrap_or(self.state.current);
            let length = straight_length(start, end);
            let rate = (length * f.value).max(0.1);
            self.set_inverse_time_rate(rate)
        } else {
            if self.state.feed_rate == 0.0 {
                return Err(self.motion_fault(
                    "Cannot do g1 with zero feed rate: program a feed rate with an F word (mm/min, \
                     or in/min under G20) before or on this line",
                ));
            }
            Feed { mm_per_min: self.state.feed_mm, inverse_time: false }
        };
        if self.state.comp.active() {
            return self.comp_straight(false, end, Some(feed), g53);
        }
        self.move_to(end, Some(feed));
        Ok(())
    }

    /// The feed of a move under G93 at `rate` (program units per minute: its length times F),
    /// which becomes the feed rate in force (`#<_feed>`, what M70 saves), as rs274's
    /// `inverse_time_rate_straight` and `inverse_time_rate_arc` make it.
    pub(super) fn set_inverse_time_rate(&mut self, rate: f64) -> Feed {
        self.state.feed_rate = rate;
        self.state.feed_mm = rate * self.state.factor();
        Feed { mm_per_min: self.state.feed_mm, inverse_time: true }
    }

    /// G2 (`clockwise`) and G3 (`convert_arc`, `convert_arc2`, `arc_data_ijk`, `arc_data_r`).
    pub(super) fn arc(&mut self, clockwise: bool) -> Result<(), Fault> {
        self.comp_arc_allowed()?;
        let word = |letter: u8| self.syntax.block.word(letter);
        let (i, j, mut k, r) = (word(b'i'), word(b'j'), word(b'k'), word(b'r'));
        // Grbl reads the K word of an XY-plane arc and ignores it.
        if self.state.plane == Plane::Xy && self.hooks.rules.ignores_k_in_xy_arc {
            k = None;
        }
        let ijk = i.is_some() || j.is_some() || k.is_some();
        if r.is_none() && !ijk {
            return Err(self.motion_fault(
                "R i j k words all missing for arc: give the centre with I J K (offsets from the \
                 start) or the radius with R",
            ));
        }
        if r.is_some() && ijk {
            return Err(self.motion_fault("Mixed radius ijk format for arc"));
        }
        let f = self.syntax.block.word(b'f');
        if self.state.inverse_time {
            if f.is_none() {
                return Err(self.motion_fault("F word missing with inverse time arc move"));
            }
        } else if self.state.feed_rate == 0.0 {
            return Err(self.motion_fault(
                "Cannot make arc with zero feed rate: program a feed rate with an F word",
            ));
        }
        let plane = self.state.plane;
        let [first, second, normal] = plane.axes();
        let letters = [b'i', b'j', b'k'];
        let offsets = [i, j, k];
        let mut offset1 = 0.0;
        let mut offset2 = 0.0;
        if ijk {
            if let Some(word) = offsets[normal] {
                let name = match plane {
                    Plane::Xy => "K word given for arc in xy plane",
                    Plane::Xz => "J word given for arc in xz plane",
                    Plane::Yz => "I word given for arc in yz plane",
                };
                return Err(self.word_fault(word, name));
            }
            for (value, axis) in [(&mut offset1, first), (&mut offset2, second)] {
                match offsets[axis] {
                    Some(word) => *value = word.value,
                    None if self.state.ijk_absolute => {
                        return Err(self.motion_fault(format!(
                            "{} word missing in absolute center arc",
                            char::from(letters[axis]).to_ascii_uppercase()
                        )));
                    }
                    None => *value = 0.0,
                }
            }
        } else {
            let has = |axis: usize| self.syntax.block.word(AXES[axis]).is_some();
            if !has(first) && !has(second) {
                let message = match plane {
                    Plane::Xy => "X and y words missing for arc in xy plane",
                    Plane::Xz => "X and z words missing for arc in xz plane",
                    Plane::Yz => "Y and z words missing for arc in yz plane",
                };
                return Err(self.motion_fault(message));
            }
        }
        let turns = match self.syntax.block.word(b'p') {
            None => 1,
            Some(p) => {
                // An integer ≥ 1 within 0.001 (`check_other_words`).
                let rounded = round_to_int(p.value);
                if rounded > 1e6 {
                    return Err(
                        self.word_fault(p, "P value is too large (more than 1000000 turns)")
                    );
                }
                rounded as u32
            }
        };
        let end = self.find_ends(false);
        self.comp_arc_checks(clockwise, end, r.map(|r| r.value))?;
        let current = self.comp_start().unwrap_or(self.state.current);
        let (c1, c2) = (current[first], current[second]);
        let (e1, e2) = (end[first], end[second]);
        let inch = !self.state.metric;
        let radius_tolerance =
            if inch { RADIUS_TOLERANCE_INCH } else { RADIUS_TOLERANCE_INCH * MM_PER_INCH };
        let names = [
            char::from(AXES[first]).to_ascii_uppercase(),
            char::from(AXES[second]).to_ascii_uppercase(),
        ];
        let (center1, center2) = if let Some(r) = r {
            if e1 == c1 && e2 == c2 {
                return Err(self.motion_fault("Current point same as end point of arc"));
            }
            let radius = r.value;
            let abs_radius = radius.abs();
            let mid1 = (e1 + c1) / 2.0;
            let mid2 = (e2 + c2) / 2.0;
            let mut half_length = (mid1 - e1).hypot(mid2 - e2);
            if half_length - abs_radius > radius_tolerance {
                return Err(self.motion_fault(format!(
                    "Arc radius too small to reach end point: R{abs_radius} cannot span the \
                         {:.4} between start and end",
                    2.0 * half_length
                )));
            }
            if half_length / abs_radius > 1.0 - TINY {
                half_length = abs_radius;
            }
            let base = (e2 - c2).atan2(e1 - c1);
            let theta = if (clockwise && radius > 0.0) || (!clockwise && radius < 0.0) {
                base - std::f64::consts::FRAC_PI_2
            } else {
                base + std::f64::consts::FRAC_PI_2
            };
            let turn2 = (half_length / abs_radius).asin();
            let offset = abs_radius * turn2.cos();
            (mid1 + offset * theta.cos(), mid2 + offset * theta.sin())
        } else {
            let (center1, center2) = if self.state.ijk_absolute {
                (offset1, offset2)
            } else {
                (c1 + offset1, c2 + offset2)
            };
            let radius = (center1 - c1).hypot(center2 - c2);
            let radius2 = (center1 - e1).hypot(center2 - e2);
            let describe = || {
                format!(
                    "start=({a}{c1:.4},{b}{c2:.4}) center=({a}{center1:.4},{b}{center2:.4}) \
                     end=({a}{e1:.4},{b}{e2:.4}) r1={radius:.4} r2={radius2:.4}",
                    a = names[0],
                    b = names[1],
                )
            };
            if radius < radius_tolerance || radius2 < radius_tolerance {
                return Err(self.motion_fault(format!("Zero-radius arc: {}", describe())));
            }
            let abs_err = (radius - radius2).abs();
            let rel_err = abs_err / radius.max(radius2);
            let spiral = if inch {
                CENTER_ARC_RADIUS_TOLERANCE_INCH
            } else {
                CENTER_ARC_RADIUS_TOLERANCE_MM
            };
            // LinuxCNC's test: beyond the tolerance and 0.1 %, or beyond 100 tolerances.
            if (abs_err > spiral && rel_err > SPIRAL_RELATIVE_TOLERANCE) || abs_err > 100.0 * spiral
            {
                return Err(self.motion_fault(format!(
                    "Radius to end of arc differs from radius to start: {} abs_err={} \
                         rel_err={:.4}% (LinuxCNC allows {:.4} {unit}, or 0.1% up to {:.4} \
                         {unit})",
                    describe(),
                    format_g4(abs_err),
                    rel_err * 100.0,
                    spiral,
                    100.0 * spiral,
                    unit = if inch { "in" } else { "mm" },
                )));
            }
            (center1, center2)
        };
        let feed = if self.state.inverse_time {
            let f = f.map_or(0.0, |word| word.value);
            let turn = if clockwise { -(turns as i32) } else { turns as i32 };
            let length = arc_length(
                [c1, c2, current[normal]],
                [center1, center2],
                turn,
                [e1, e2, end[normal]],
            );
            let rate = (length * f).max(0.1);
            self.set_inverse_time_rate(rate)
        } else {
            Feed { mm_per_min: self.state.feed_mm, inverse_time: false }
        };
        if self.comp_arcs() {
            let turn = if clockwise { -(turns as i32) } else { turns as i32 };
            let center = [center1, center2];
            let arc = cutter_comp::CompArc { start: current, end, center, turn, feed };
            return self.comp_arc(arc);
        }
        if self.state.rotation != 0.0 && plane != Plane::Xy {
            let arc = ([current, end], [center1, center2]);
            let moved = self.tilted_arc(arc.0, arc.1, clockwise, turns, feed);
            return moved.map_err(|message| self.motion_fault(message));
        }
        let mut center_position = self.state.current;
        center_position[first] = center1;
        center_position[second] = center2;
        let center_absolute = self.state.absolute(center_position);
        let absolute = self.state.absolute(end);
        self.emit(MotionKind::Arc {
            end: absolute,
            center: [center_absolute[first], center_absolute[second]],
            plane,
            clockwise,
            turns,
            feed,
        });
        self.state.current = end;
        self.state.tool_shift = [0.0; 4];
        Ok(())
    }
}

/// LinuxCNC's `find_straight_length` for X Y Z C: the XYZ length, or the C length for a move
/// with no XYZ motion.
pub(super) fn straight_length(from: [f64; 4], to: [f64; 4]) -> f64 {
    let linear = (0..3).any(|axis| from[axis] != to[axis]) || from[3] == to[3];
    if linear {
        ((to[0] - from[0]).powi(2) + (to[1] - from[1]).powi(2) + (to[2] - from[2]).powi(2)).sqrt()
    } else {
        (to[3] - from[3]).abs()
    }
}

/// LinuxCNC's `find_turn`: the signed angle swept from `start` to `end` about `center`, `turn`
/// times round (negative: clockwise; 0: no turn).
pub(super) fn find_turn(start: [f64; 2], center: [f64; 2], turn: i32, end: [f64; 2]) -> f64 {
    use std::f64::consts::PI;
    if turn == 0 {
        return 0.0;
    }
    let mut alpha = (start[1] - center[1]).atan2(start[0] - center[0]);
    let mut beta = (end[1] - center[1]).atan2(end[0] - center[0]);
    if turn > 0 {
        if beta <= alpha {
            beta += 2.0 * PI;
        }
        beta - alpha + f64::from(turn - 1) * 2.0 * PI
    } else {
        if alpha <= beta {
            alpha += 2.0 * PI;
        }
        beta - alpha + f64::from(turn + 1) * 2.0 * PI
    }
}

/// LinuxCNC's `find_arc_length`: `turn` is negative for clockwise (never 0 here: an arc turns
/// at least once).
pub(super) fn arc_length(start: [f64; 3], center: [f64; 2], turn: i32, end: [f64; 3]) -> f64 {
    let radius = (center[0] - start[0]).hypot(center[1] - start[1]);
    let theta = find_turn([start[0], start[1]], center, turn, [end[0], end[1]]);
    if end[2] == start[2] {
        radius * theta.abs()
    } else {
        (radius * theta).hypot(end[2] - start[2])
    }
}
