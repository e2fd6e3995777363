//! Polar coordinates: the `@` (radius) and `^` (angle, degrees) words, as LinuxCNC's `rs274`
//! reads them.
//!
//! In the XY plane of the current coordinate system (refused unless G17 is in force when the
//! line is read): under G90
//! the end is at radius `@` and angle `^` from the origin; a missing `@` keeps the current
//! point's radius and a missing `^` its angle (refused at the origin, where there is none).
//! Under G91 both are relative to the current point's own radius and angle (refused at the
//! origin). The end point becomes the block's X and Y words, so that lines, arcs and canned
//! cycles take it as they take X and Y (an incremental cycle's repeats step on in polar
//! coordinates, as in rs274); a line without `@` or `^` does no work here.

use biscara_motion::Plane;

use super::Machine;
use crate::syntax::lexer::Fault;
use crate::syntax::parser::Word;

impl Machine {
    /// X or Y words with `@` or `^` (read with the line, before its other checks).
    pub(super) fn check_polar_words(&self) -> Result<(), Fault> {
        let Some(extra) = self.syntax.block.extra() else { return Ok(()) };
        let Some(polar) = extra.radius.or(extra.theta) else { return Ok(()) };
        // The plane in force when the line is read.
        if self.state.plane != Plane::Xy {
            return Err(self.word_fault(polar, "Cannot use polar coordinate except in G17 plane"));
        }
        if let Some(x) = self.syntax.block.word(b'x') {
            return Err(self.word_fault(x, "Cannot specify both polar coordinate and X word"));
        }
        if let Some(y) = self.syntax.block.word(b'y') {
            return Err(self.word_fault(y, "Cannot specify both polar coordinate and Y word"));
        }
        let group0 = self.syntax.block.g[0].map(|code| code.code);
        let g43 = self.syntax.block.g[8].is_some_and(|code| matches!(code.code, 431 | 432));
        if matches!(group0, Some(100 | 280 | 300 | 520 | 920)) || g43 {
            return Err(self.word_fault(polar, "Polar coordinates can only be used for motion"));
        }
        Ok(())
    }

    /// The first polar word of the line (for messages), if any.
    pub(super) fn first_polar_word(&self) -> Option<Word> {
        let extra = self.syntax.block.extra()?;
        match (extra.radius, extra.theta) {
            (Some(r), Some(t)) => Some(if r.at < t.at { r } else { t }),
            (r, t) => r.or(t),
        }
    }

    /// The next hole of an incremental canned cycle with polar words, from hole `[x, y]`:
    /// rs274 applies the `@` and `^` steps again at each repeat (a bolt circle: `G91 G81 ^60
    /// L6`).
    pub(super) fn polar_repeat(&self, [x, y]: [f64; 2]) -> Option<[f64; 2]> {
        let extra = self.syntax.block.extra()?;
        if extra.radius.is_none() && extra.theta.is_none() {
            return None;
        }
        let radius = x.hypot(y) + extra.radius.map_or(0.0, |r| r.value);
        let theta = y.atan2(x) + extra.theta.map_or(0.0, |t| t.value.to_radians());
        Some([radius * theta.cos(), radius * theta.sin()])
    }

    /// Turns `@` and `^` into the block's X and Y words, before its motion (`find_ends`).
    pub(super) fn apply_polar(&mut self, motion: u16, g53: bool) -> Result<(), Fault> {
        let Some(extra) = self.syntax.block.extra().copied() else { return Ok(()) };
        let Some(first) = self.first_polar_word() else { return Ok(()) };
        if g53 {
            return Err(self.word_fault(first, "Cannot use polar coordinates with G53"));
        }
        let plane = self.state.plane;
        if matches!(motion, 20 | 30) && plane != Plane::Xy {
            // rs274 looks for the plane's own words.
            let (letters, message) = if plane == Plane::Xz {
                ([b'x', b'z'], "X and z words missing for arc in xz plane")
            } else {
                ([b'y', b'z'], "Y and z words missing for arc in yz plane")
            };
            if letters.iter().all(|&letter| self.syntax.block.word(letter).is_none()) {
                let at = self.syntax.block.g[1]
                    .map_or((first.at, first.end), |code| (code.at, code.end));
                return Err(self.fault_at(at.0, at.1, message));
            }
        }
        let [x, y, ..] = self.state.current;
        let at_origin = x == 0.0 && y == 0.0;
        // rs274's canned cycles take the angle at the origin as 0, and refuse only an
        // incremental polar move from there (after the climb to the R plane).
        let cycle = super::canned::is_cycle(motion);
        if cycle && at_origin && self.state.incremental {
            return Err(self.word_fault(
                first,
                "Incremental motion with polar coordinates is indeterminate when at the origin",
            ));
        }
        let mut radius = match extra.radius {
            Some(r) => r.value,
            None => x.hypot(y),
        };
        let mut theta = match extra.theta {
            Some(t) => t.value.to_radians(),
            None => {
                if at_origin && !self.state.incremental && !cycle {
                    return Err(self.word_fault(
                        first,
                        "Must specify angle in polar coordinate if at the origin",
                    ));
                }
                y.atan2(x)
            }
        };
        if self.state.incremental {
            if extra.radius.is_some() {
                if at_origin {
                    return Err(self.word_fault(
                        first,
                        "Incremental motion with polar coordinates is indeterminate when at the \
                         origin",
                    ));
                }
                radius += x.hypot(y);
            }
            if extra.theta.is_some() {
                if at_origin {
                    return Err(self.word_fault(
                        first,
                        "G91 motion with polar coordinates is indeterminate when at the origin",
                    ));
                }
                theta += y.atan2(x);
            }
        }
        let end = [radius * theta.cos(), radius * theta.sin()];
        for (axis, letter) in [b'x', b'y'].into_iter().enumerate() {
            // Under G91 the words are offsets from the point the move starts from.
            let start = match self.state.comp.base(axis, plane) {
                Some(programmed) => programmed,
                None => self.state.current[axis],
            };
            let value = if self.state.incremental { end[axis] - start } else { end[axis] };
            self.syntax.block.letters[usize::from(letter - b'a')] =
                Some(Word { value, at: first.at, end: first.end });
        }
        Ok(())
    }
}
