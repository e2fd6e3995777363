//! G5 (cubic spline) and G5.1 (quadratic B-spline) in the XY plane, read as rs274 reads them
//! (`convert_spline`), run as straight moves that stay within
//! [`CHORD_TOLERANCE_MM`](crate::interpreter::spline::CHORD_TOLERANCE_MM) of the
//! curve.
//!
//! rs274 checks a spline block and hands its control points to the motion planner as a NURBS
//! (`NURBS_FEED`): the curve is a Bézier from the current point to the end point.
//! - G5: cubic, control points start, start + (I, J), end + (P, Q), end. Without I and J, the
//!   first control point continues the previous G5 smoothly: rs274 keeps (−P, −Q) of the last
//!   G5 in the place where the canned cycles keep G87's I and J (`cycle_i`, `cycle_j`), so a
//!   first G5 without I J starts along (0, 0) or along G87's last I J, as rs274's does.
//! - G5.1: quadratic, control points start, start + (I, J), end (I and J required).
//!
//! Neither changes the modal motion: a line of axis words after a spline moves as the G0, G1,
//! … in force before it.
//!
//! The curve becomes `n` straight moves at equal steps of its parameter. The chord of a
//! parameter interval of length `h` stays within `h² · max|B''| / 8` of the curve, and
//! `max|B''| ≤ 6 · max(|P0 − 2P1 + P2|, |P1 − 2P2 + P3|)` for a cubic Bézier (a quadratic is
//! raised to the cubic it equals), so `n = ⌈√(0.75 · M / tolerance)⌉` with `M` the larger
//! second difference keeps every move within the tolerance. The moves are queued with the
//! block's line; a block makes at most
//! [`MAX_SEGMENTS`](crate::interpreter::spline::MAX_SEGMENTS) of them (memory stays bounded), and a
//! spline that would need more is refused (its control points then lie metres apart).

use biscara_motion::{Feed, Plane};

use super::Machine;
use crate::syntax::lexer::Fault;

/// How far the straight moves of a spline may be from its curve, mm.
pub(super) const CHORD_TOLERANCE_MM: f64 = 0.001;
/// The most straight moves one spline block makes.
pub(super) const MAX_SEGMENTS: usize = 4096;

/// Whether `motion` (ten times the G number) is G5 or G5.1.
pub(super) fn is_spline(motion: u16) -> bool {
    matches!(motion, 50 | 51)
}

impl Machine {
    /// G5 (`motion` 50) or G5.1 (51): the checks of rs274's `convert_spline`, in its order,
    /// then the curve's straight moves.
    pub(super) fn spline(&mut self, motion: u16) -> Result<(), Fault> {
        let code_at = self.syntax.block.g[1].map_or((0, 1), |code| (code.at, code.end));
        let fail = |this: &Self, message: &str| this.fault_at(code_at.0, code_at.1, message);
        if self.state.comp.on() {
            return Err(fail(
                self,
                "Cannot convert spline with cutter radius compensation: turn it off with G40 \
                 first",
            ));
        }
        if self.state.inverse_time {
            if self.syntax.block.word(b'f').is_none() {
                return Err(fail(self, "F word missing with inverse time arc move"));
            }
            let (first, last) = self.span(code_at.0, code_at.1);
            return Err(Fault::not_supported(
                first,
                last,
                if motion == 50 { "G5 under G93" } else { "G5.1 under G93" },
                "a spline in inverse time: LinuxCNC sets no feed rate for it",
            ));
        }
        if self.state.feed_rate == 0.0 {
            return Err(fail(
                self,
                "Cannot make arc with zero feed rate: program a feed rate with an F word",
            ));
        }
        if self.state.plane != Plane::Xy {
            return Err(fail(self, "Splines must be in the XY plane: select it with G17"));
        }
        if let Some(word) =
            [b'z', b'c'].iter().filter_map(|&letter| self.syntax.block.word(letter)).next()
        {
            return Err(self.word_fault(word, "Splines may not have motion in Z, A, B, or C"));
        }
        let value = |letter: u8| self.syntax.block.word(letter).map(|word| word.value);
        let start = self.state.current;
        let end = self.find_ends(false);
        let (i, j) = (value(b'i'), value(b'j'));
        let controls = if motion == 50 {
            let first = match (i, j) {
                (Some(i), Some(j)) => [start[0] + i, start[1] + j],
                (None, None) => {
                    let [i, j] = self.state.cycle.spline_ij();
                    [start[0] + i, start[1] + j]
                }
                _ => return Err(fail(self, "Must specify both I and J, or neither")),
            };
            let (Some(p), Some(q)) = (value(b'p'), value(b'q')) else {
                return Err(fail(self, "Must specify both P and Q with G5"));
            };
            self.state.cycle.set_spline_ij([-p, -q]);
            [first, [end[0] + p, end[1] + q]]
        } else {
            let (Some(i), Some(j)) = (i, j) else {
                return Err(fail(self, "Must specify both I and J with G5.1"));
            };
            // The quadratic with control point `middle`, as the cubic it equals.
            let middle = [start[0] + i, start[1] + j];
            let raise = |from: f64, to: f64| from + 2.0 / 3.0 * (to - from);
            [
                [raise(start[0], middle[0]), raise(start[1], middle[1])],
                [raise(end[0], middle[0]), raise(end[1], middle[1])],
            ]
        };
        let points = [[start[0], start[1]], controls[0], controls[1], [end[0], end[1]]];
        let count = segments(&points, self.state.factor()).ok_or_else(|| {
            fail(
                self,
                &format!(
                    "Spline too large: more than {MAX_SEGMENTS} straight moves would be needed \
                     to stay within {CHORD_TOLERANCE_MM} mm of its curve; split it into shorter \
                     splines"
                ),
            )
        })?;
        let feed = Feed { mm_per_min: self.state.feed_mm, inverse_time: false };
        for step in 1..count {
            let [x, y] = bezier(&points, step as f64 / count as f64);
            self.move_to([x, y, start[2], start[3]], Some(feed));
        }
        self.move_to(end, Some(feed));
        Ok(())
    }
}

/// The number of equal parameter steps that keep the chords of the cubic Bézier `points`
/// (program units, `factor` mm each) within [`CHORD_TOLERANCE_MM`]; `None` above
/// [`MAX_SEGMENTS`].
fn segments(points: &[[f64; 2]; 4], factor: f64) -> Option<usize> {
    let second = |a: [f64; 2], b: [f64; 2], c: [f64; 2]| {
        (a[0] - 2.0 * b[0] + c[0]).hypot(a[1] - 2.0 * b[1] + c[1])
    };
    let most = second(points[0], points[1], points[2]).max(second(points[1], points[2], points[3]));
    let count = (0.75 * most * factor / CHORD_TOLERANCE_MM).sqrt().ceil();
    // Not a number (an overflowing control point) is refused too.
    (count <= MAX_SEGMENTS as f64).then_some((count as usize).max(1))
}

/// The cubic Bézier `points` at parameter `t`.
fn bezier(points: &[[f64; 2]; 4], t: f64) -> [f64; 2] {
    let u = 1.0 - t;
    let weights = [u * u * u, 3.0 * u * u * t, 3.0 * u * t * t, t * t * t];
    std::array::from_fn(|axis| {
        points.iter().zip(weights).map(|(point, weight)| point[axis] * weight).sum()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The largest distance from the curve to the chords, sampled finely.
    fn deviation(points: &[[f64; 2]; 4], count: usize) -> f64 {
        let mut worst = 0.0f64;
        for step in 0..count {
            let (t0, t1) = (step as f64 / count as f64, (step + 1) as f64 / count as f64);
            let (a, b) = (bezier(points, t0), bezier(points, t1));
            for k in 0..=50 {
                let s = k as f64 / 50.0;
                let on_curve = bezier(points, t0 + s * (t1 - t0));
                let on_chord = [a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1])];
                worst = worst.max((on_curve[0] - on_chord[0]).hypot(on_curve[1] - on_chord[1]));
            }
        }
        worst
    }

    #[test]
    fn chords_stay_within_the_tolerance() {
        let curves = [
            [[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]],
            [[0.0, 0.0], [100.0, 50.0], [-80.0, 30.0], [20.0, 0.0]],
            [[1.0, 1.0], [2.0, 1.0], [6.0, 5.0], [5.0, 5.0]],
        ];
        for points in &curves {
            let count = segments(points, 1.0).unwrap();
            assert!(deviation(points, count) <= CHORD_TOLERANCE_MM, "{points:?}: {count}");
            // And the bound is not wasteful: half as many moves would stray beyond it.
            assert!(deviation(points, count / 2) > CHORD_TOLERANCE_MM, "{points:?}: {count}");
        }
    }

    #[test]
    fn a_straight_spline_is_one_move_and_a_huge_one_is_refused() {
        let line = [[0.0, 0.0], [1.0, 1.0], [2.0, 2.0], [3.0, 3.0]];
        assert_eq!(segments(&line, 1.0), Some(1));
        let huge = [[0.0, 0.0], [1e6, 0.0], [0.0, 1e6], [0.0, 0.0]];
        assert_eq!(segments(&huge, 1.0), None);
        assert_eq!(segments(&[[f64::NAN; 2]; 4], 1.0), None);
        // Inches: 25.4 times the second difference in mm, so more moves.
        let curve = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        assert!(segments(&curve, 25.4).unwrap() > segments(&curve, 1.0).unwrap());
    }

    #[test]
    fn the_curve_runs_from_the_first_point_to_the_last() {
        let points = [[1.0, 2.0], [3.0, 5.0], [7.0, -1.0], [4.0, 4.0]];
        assert_eq!(bezier(&points, 0.0), [1.0, 2.0]);
        assert_eq!(bezier(&points, 1.0), [4.0, 4.0]);
    }
}
