//! A chain of blended moves (G64 P) timed as one path by the optimal profile.
//!
//! The pieces of the chain (trimmed lines, the fillets between them and programmed arcs tangent
//! to their neighbours, from `biscara-blend`) are laid end to end: the path parameter is the
//! length along the chain, mm. The planner
//! ([`TimeOptimal::plan_streamed`](biscara_timing::TimeOptimal::plan_streamed)) asks for grid
//! points one by one; the chain pulls pieces from the blender as it needs them and drops those
//! the sampling has passed, so it holds only the pieces of the planner's window.
//!
//! Each piece gets its own grid ([`GRID_MM`] or [`GRID_SECONDS`] at the feed, whichever is
//! shorter, [`GRID_TURN_DEGREES`], at least one interval; a line's or an arc's ends refined as a
//! single move's are), so that every junction (the ends of every fillet) is a grid point.
//! TOPP-RA loses a little time in the interval where the speed stops changing, and nothing when
//! that happens on a grid point: a line or an arc also gets the points where its Cartesian ramps
//! would end, from the speed its neighbours allow at its ends (rest at the chain's ends, the
//! centripetal limit on a fillet) to its own. The second derivative of the path jumps at a
//! junction; a junction point carries two sets of constraints, the piece before it at its end and
//! the piece after it at its start, each held on its own side of the point
//! ([`PathConstraints::sided`]).

use std::collections::VecDeque;

use biscara_blend::{Blended, Geometry, Piece, Speed};
use biscara_motion::Motion;
use biscara_timing::{Constraint, Grid, PathConstraints};

use crate::interpolator::{GRID_MM, GRID_TURN_DEGREES, MAX_REFINE, REFINE_RATIO, fill_torque_rows};
use crate::{
    CartesianLimits, InterpolateError, MAX_JOINTS, RateLimit, Segment, SlowDown, SpeedLimit,
};

/// The longest time an interval of a chain's grid takes at the programmed speed, s.
const GRID_SECONDS: f64 = 0.01;

/// The shortest piece timed inside a chain, mm: a shorter one is passed over (see
/// [`ChainBounds::pull`]).
const SHORTEST_PIECE_MM: f64 = 1e-9;

/// One piece of the chain with where it starts along the chain.
#[derive(Debug, Clone, Copy)]
struct ChainPiece {
    segment: Segment,
    /// Chain parameter (mm) at its start, and its length.
    start: f64,
    length: f64,
    /// The piece's grid over its fraction along it.
    grid: Grid,
    line: usize,
    /// Largest path speed (the feed), mm/s; NaN for a rapid piece.
    speed: f64,
    /// |dC/ds|, degrees per mm.
    rotation_rate: f64,
    /// Radius of a fillet, mm (infinite for a line or a programmed arc).
    radius: f64,
    /// A corner's fillet (short, and run at the speed its ends allow): no extra grid points.
    fillet: bool,
    /// The path acceleration (with C's), mm/s², and the largest ṡ² the Cartesian limits allow
    /// (for a programmed arc, which the joints bound instead, the centripetal estimate used to
    /// place the grid's ramp points).
    acceleration: f64,
    cap: f64,
    ends_chain: bool,
    /// The programmed speed (mm/s) and the lowest a joint velocity or C allows at its grid
    /// points, when lower.
    programmed: f64,
    slowest: Option<RateLimit>,
}

/// The state of a chain between calls: the pieces held and where the grid has got to.
#[derive(Debug, Clone)]
pub(crate) struct Chain {
    /// The pieces from the one being sampled to the last one the planner has asked for.
    pieces: VecDeque<ChainPiece>,
    /// Absolute index of `pieces[0]`.
    front: usize,
    /// The piece (absolute index) and interval of the last grid point given.
    piece: usize,
    interval: usize,
    /// The current piece's extra grid points (fractions along it, increasing; infinite when
    /// none), the next of them to give, and the last fraction given.
    extra: [f64; 2],
    extra_next: usize,
    last_u: f64,
    /// The Cartesian ṡ² cap where the current piece starts.
    x_in: f64,
    /// The last grid point given was the chain's end.
    at_end: bool,
    /// The sides of the last grid point given: (absolute piece, fraction along it), before and
    /// after it (the same but at a junction).
    sides: [(usize, f64); 2],
    /// The pose where the chain ends (known once its last piece is pulled).
    pub(crate) end: Option<[f64; 4]>,
    /// The slowed pieces passed (one report per line), for the interpolator to pass on, and
    /// the line reported last.
    pub(crate) reports: Vec<SlowDown>,
    reported: usize,
    /// A motion the blender gave where a piece was expected (never, by its contract): the
    /// interpolator runs it after the chain.
    pub(crate) deferred: Option<Motion>,
}

impl Chain {
    /// A chain starting with `first`.
    pub(crate) fn new<E>(
        first: Piece,
        limits: CartesianLimits,
    ) -> Result<Chain, InterpolateError<E>> {
        let mut chain = Chain {
            pieces: VecDeque::new(),
            front: 0,
            piece: 0,
            interval: 0,
            extra: [f64::INFINITY; 2],
            extra_next: 0,
            last_u: 0.0,
            x_in: 0.0,
            at_end: false,
            sides: [(0, 0.0); 2],
            end: None,
            reports: Vec::new(),
            reported: 0,
            deferred: None,
        };
        chain.push(first, 0.0, limits)?;
        Ok(chain)
    }

    fn push<E>(
        &mut self,
        piece: Piece,
        start: f64,
        limits: CartesianLimits,
    ) -> Result<(), InterpolateError<E>> {
        let segment = match piece.geometry {
            Geometry::Line { start, end } => Segment::line(start, end),
            Geometry::Fillet { start, end, center, tangent, sweep, .. } => {
                Segment::fillet(start, end, center, tangent, sweep)
            }
            Geometry::Arc(segment) => segment,
        };
        let length = piece.length();
        let speed = match piece.speed {
            Speed::Rapid => f64::NAN,
            Speed::Feed(feed) => {
                let per_second = feed.mm_per_min / 60.0;
                if !(per_second.is_finite() && per_second > 0.0) {
                    return Err(InterpolateError::Motion {
                        line: piece.line,
                        message: format!("the feed {} mm/min is not positive", feed.mm_per_min),
                    });
                }
                per_second
            }
        };
        // At most GRID_MM, and at most GRID_SECONDS at the feed: TOPP-RA's loss where the
        // optimum switches off the grid is a part of one interval's time.
        let along = if speed.is_nan() { limits.rapid_velocity } else { speed };
        let spacing = GRID_MM.min(along * GRID_SECONDS).max(GRID_MM / 100.0);
        let per_unit = (length / spacing + segment.turning() / GRID_TURN_DEGREES).ceil();
        if !(length.is_finite() && length > 0.0 && per_unit < 1e9) {
            return Err(InterpolateError::Motion {
                line: piece.line,
                message: "the move is too slow to count in time steps".to_owned(),
            });
        }
        if piece.ends_chain {
            self.end = Some(piece.end());
        }
        // TOPP-RA loses time in the interval where the speed stops changing, and the ramps
        // from rest, to rest and to and from a slow fillet end near a line's or an arc's ends:
        // its first and last intervals are cut geometrically down to an eighth of the Cartesian
        // ramp (as a single move's refined grid is).
        let intervals = per_unit.max(1.0);
        let mut grid = Grid::uniform(intervals as usize);
        let fillet = matches!(piece.geometry, Geometry::Fillet { .. });
        if !fillet {
            let ramp = along * along / (2.0 * limits.acceleration) / length;
            let refine =
                ((ramp * intervals / 8.0).ln() / REFINE_RATIO.ln()).ceil().clamp(0.0, MAX_REFINE);
            if refine > 0.0 {
                grid = Grid::refined((intervals as usize).max(2), refine as u32, REFINE_RATIO);
            }
        }
        let rotation_rate = (segment.rotation() / length).abs();
        let acceleration = limits.acceleration.min(limits.rotation_acceleration / rotation_rate);
        let along = along.min(limits.rapid_rotation / rotation_rate);
        // A fillet's centripetal acceleration within the path acceleration; a programmed arc
        // (or what a corner's fillets leave of it) is bounded as when it runs alone, by the
        // joints: blending its corners never slows it down.
        let radius = if fillet { piece.radius().unwrap_or(f64::INFINITY) } else { f64::INFINITY };
        // Where the ramps end is placed from the speed a piece will run at: a tight
        // programmed arc's estimated by its centripetal acceleration too (its joints bound it
        // near there), or the line after it would get no grid point where it stops speeding up.
        let bend = piece.radius().unwrap_or(f64::INFINITY);
        let cap = (along * along).min(limits.acceleration * bend);
        self.pieces.push_back(ChainPiece {
            segment,
            start,
            length,
            grid,
            line: piece.line,
            speed,
            rotation_rate,
            radius,
            fillet,
            acceleration,
            cap,
            programmed: along,
            slowest: None,
            ends_chain: piece.ends_chain,
        });
        Ok(())
    }

    /// Number of pieces held.
    #[cfg(test)]
    pub(crate) fn held(&self) -> usize {
        self.pieces.len()
    }

    fn get(&self, index: usize) -> &ChainPiece {
        &self.pieces[index - self.front]
    }

    /// Reports `piece` if it was slowed and its line has not been reported yet.
    fn report(&mut self, piece: ChainPiece) {
        // (Below the programmed speed by more than rounding: a vertical move at d4's limit.)
        if let Some(slowest) = piece.slowest
            && piece.line != self.reported
            && slowest.rate < piece.programmed * (1.0 - 1e-9)
        {
            self.reported = piece.line;
            let factor = slowest.rate / piece.programmed;
            self.reports.push(SlowDown { line: piece.line, cause: slowest.cause, factor });
        }
    }

    /// At the chain's end: reports the pieces still held.
    pub(crate) fn finish(&mut self) {
        while let Some(piece) = self.pieces.pop_front() {
            self.report(piece);
            self.front += 1;
        }
    }

    /// The pose at chain parameter `s` and the line of its piece; drops the pieces before it.
    pub(crate) fn pose(&mut self, s: f64) -> ([f64; 4], usize) {
        while self.pieces.len() > 1 && self.front < self.piece {
            let first = self.pieces[0];
            if s <= first.start + first.length {
                break;
            }
            self.report(first);
            self.pieces.pop_front();
            self.front += 1;
        }
        let piece = &self.pieces[0];
        let u = ((s - piece.start) / piece.length).clamp(0.0, 1.0);
        (piece.segment.point(u), piece.line)
    }
}

/// The chain as [`PathConstraints`]: pulls pieces from `source` as the planner needs them.
pub(crate) struct ChainBounds<'a, B, L, E> {
    pub(crate) chain: &'a mut Chain,
    pub(crate) source: &'a mut B,
    pub(crate) limit: &'a mut L,
    pub(crate) limits: CartesianLimits,
    /// The first error met (an input error, or a piece that cannot be timed): the chain ends
    /// there, and the interpolator reports it.
    pub(crate) error: &'a mut Option<InterpolateError<E>>,
}

impl<B, L, E> ChainBounds<'_, B, L, E>
where
    B: Iterator<Item = Result<Blended, E>>,
    L: SpeedLimit,
{
    /// Pulls the piece after the last one held; `false` when there is none.
    ///
    /// A piece shorter than [`SHORTEST_PIECE_MM`] inside the chain (what two fillets leave of
    /// an arc between them) is passed over: the pieces on either side meet within its length,
    /// and its own grid could not be told apart from its start along a long chain.
    fn pull(&mut self) -> bool {
        let last = self.chain.pieces[self.chain.pieces.len() - 1];
        let start = last.start + last.length;
        let next = loop {
            match self.source.next() {
                Some(Ok(Blended::Piece(piece)))
                    if !piece.ends_chain && piece.length() < SHORTEST_PIECE_MM => {}
                next => break next,
            }
        };
        match next {
            Some(Ok(Blended::Piece(piece))) => match self.chain.push(piece, start, self.limits) {
                Ok(()) => true,
                Err(err) => {
                    *self.error = Some(err);
                    false
                }
            },
            Some(Ok(Blended::Motion(motion))) => {
                self.chain.deferred = Some(motion);
                false
            }
            Some(Err(err)) => {
                *self.error = Some(InterpolateError::Input(err));
                false
            }
            None => false,
        }
    }

    /// Starts giving the grid of the current piece: pulls the piece after it (to know the
    /// speed at its end), and for a line, the extra points where its Cartesian ramps end.
    fn begin_piece(&mut self) {
        let current = *self.chain.get(self.chain.piece);
        let held = self.chain.piece + 1 - self.chain.front < self.chain.pieces.len();
        let has_next = !current.ends_chain && (held || self.pull());
        let chain = &mut *self.chain;
        chain.interval = 0;
        chain.extra_next = 0;
        chain.last_u = 0.0;
        chain.extra = [f64::INFINITY; 2];
        if current.fillet {
            return;
        }
        let x_out = if has_next { current.cap.min(chain.get(chain.piece + 1).cap) } else { 0.0 };
        let twice = 2.0 * current.acceleration * current.length;
        let head = (current.cap - chain.x_in) / twice;
        let tail = (current.cap - x_out) / twice;
        chain.extra = if head + tail >= 1.0 {
            // No cruise: the ramps up and down meet.
            [(x_out - chain.x_in + twice) / (2.0 * twice), f64::INFINITY]
        } else {
            [head, 1.0 - tail]
        };
        for extra in &mut chain.extra {
            if !(*extra > 0.0 && *extra < 1.0) {
                *extra = f64::INFINITY;
            }
        }
        chain.extra.sort_by(f64::total_cmp);
    }

    /// The constraints of one side of a grid point into `out` (1 + joints rows); the largest ṡ².
    fn side(&mut self, (index, u): (usize, f64), out: &mut [Constraint]) -> f64 {
        let piece = *self.chain.get(index);
        let limits = self.limits;
        let acceleration =
            limits.acceleration.min(limits.rotation_acceleration / piece.rotation_rate);
        out[0] = Constraint { a: 1.0, b: 0.0, c: 0.0, lo: -acceleration, hi: acceleration };
        // A rapid piece (NaN) runs at the rapid speed.
        let along = if piece.speed.is_nan() { limits.rapid_velocity } else { piece.speed };
        let mut speed = along;
        let mut slowest = None;
        let rotation = limits.rapid_rotation / piece.rotation_rate;
        if rotation < speed {
            speed = rotation;
            slowest = Some(RateLimit { rate: rotation, cause: "C rotation" });
        }
        // The acceleration towards a fillet's centre within the path acceleration too.
        let mut x_max = (speed * speed).min(limits.acceleration * piece.radius);
        let joints = self.limit.joint_bounds().len().min(MAX_JOINTS);
        let (mut first, mut second) = ([0.0; MAX_JOINTS], [0.0; MAX_JOINTS]);
        let known =
            self.limit.joint_derivatives(
                &piece.segment,
                u,
                &mut first[..joints],
                &mut second[..joints],
            ) && first[..joints].iter().chain(&second[..joints]).all(|value| value.is_finite());
        let (per_mm, per_mm2) = (1.0 / piece.length, 1.0 / (piece.length * piece.length));
        for (j, bound) in self.limit.joint_bounds()[..joints].iter().enumerate() {
            if !known {
                out[1 + j] = Constraint { lo: f64::NEG_INFINITY, hi: f64::INFINITY, ..out[0] };
                continue;
            }
            let a = bound.max_acceleration;
            let (q1, q2) = (first[j] * per_mm, second[j] * per_mm2);
            (first[j], second[j]) = (q1, q2);
            out[1 + j] = Constraint { a: q1, b: q2, c: 0.0, lo: -a, hi: a };
            let joint = bound.max_velocity / q1.abs();
            if joint < speed {
                speed = joint;
                slowest = Some(RateLimit { rate: joint, cause: bound.name });
            }
        }
        fill_torque_rows(
            self.limit,
            known,
            &first[..joints],
            &second[..joints],
            &mut out[1 + joints..],
        );
        if let Some(slowest) = slowest {
            let held = &mut self.chain.pieces[index - self.chain.front];
            if held.slowest.is_none_or(|known| slowest.rate < known.rate) {
                held.slowest = Some(slowest);
            }
        }
        x_max = x_max.min(speed * speed);
        x_max
    }
}

impl<B, L, E> PathConstraints for ChainBounds<'_, B, L, E>
where
    B: Iterator<Item = Result<Blended, E>>,
    L: SpeedLimit,
{
    fn count(&self) -> usize {
        2 * (1 + self.limit.joint_bounds().len().min(MAX_JOINTS) + self.limit.torque_rows())
    }

    fn sided(&self) -> bool {
        true
    }

    fn point(&mut self, index: usize) -> Option<f64> {
        if index == 0 {
            self.chain.x_in = 0.0;
            self.begin_piece();
            let chain = &mut *self.chain;
            chain.sides = [(chain.piece, 0.0); 2];
            return Some(chain.get(chain.piece).start);
        }
        if self.chain.at_end {
            return None;
        }
        let chain = &mut *self.chain;
        let piece = *chain.get(chain.piece);
        let on_grid = piece.grid.s(chain.interval + 1);
        while chain.extra_next < 2 && chain.extra[chain.extra_next] <= chain.last_u + 1e-9 {
            chain.extra_next += 1;
        }
        let extra =
            if chain.extra_next < 2 { chain.extra[chain.extra_next] } else { f64::INFINITY };
        let u = if extra < on_grid - 1e-9 {
            chain.extra_next += 1;
            extra
        } else {
            chain.interval += 1;
            on_grid
        };
        chain.last_u = u;
        if u < 1.0 {
            chain.sides = [(chain.piece, u); 2];
            return Some(piece.start + u * piece.length);
        }
        let end = piece.start + piece.length;
        let before = (chain.piece, 1.0);
        let next = chain.piece + 1 - chain.front;
        if piece.ends_chain || next >= chain.pieces.len() {
            chain.at_end = true;
            chain.sides = [before; 2];
            if chain.end.is_none() {
                chain.end = Some(piece.segment.end());
            }
            return Some(end);
        }
        chain.x_in = piece.cap.min(chain.pieces[next].cap);
        chain.piece += 1;
        chain.sides = [before, (chain.piece, 0.0)];
        self.begin_piece();
        Some(end)
    }

    fn evaluate(&mut self, _s: f64, out: &mut [Constraint]) -> f64 {
        let rows = out.len() / 2;
        let [before, after] = self.chain.sides;
        let (left, right) = out.split_at_mut(rows);
        let x_max = self.side(before, left);
        if after == before {
            right.copy_from_slice(left);
            x_max
        } else {
            x_max.min(self.side(after, right))
        }
    }
}

#[cfg(test)]
mod tests {
    use std::convert::Infallible;

    use biscara_motion::{Feed, Motion, MotionKind};

    use crate::{CartesianLimits, InterpolationConfig, Interpolator, NoSpeedLimit, Profile};

    /// A zigzag of `count` chords of 0.5 mm turning ±3° under G64 P0.05: one chain.
    fn zigzag(count: usize) -> impl Iterator<Item = Result<Motion, Infallible>> {
        let feed = Feed { mm_per_min: 6000.0, inverse_time: false };
        let mut point = [0.0f64, 0.0, 0.0, 0.0];
        (0..count).map(move |k| {
            let heading = if k % 2 == 0 { 3f64.to_radians() } else { -3f64.to_radians() };
            point = [point[0] + 0.5 * heading.cos(), point[1] + 0.5 * heading.sin(), 0.0, 0.0];
            let kind = MotionKind::Linear { end: point, feed };
            Ok(Motion { blend: Some(0.05), ..Motion::new(k + 1, kind) })
        })
    }

    /// A chain of 40,000 moves (20 m) is one path of about 80,000 grid intervals: the pieces held
    /// stay within the planner's window (a grid interval at least per piece), whatever the
    /// length, and the chain runs at the feed and ends on its last point.
    #[test]
    fn a_long_chain_holds_a_window_of_pieces() {
        let count = 40_000;
        let config = InterpolationConfig {
            dt: 0.001,
            profile: Profile::Optimal,
            start: [0.0; 4],
            limits: CartesianLimits {
                rapid_velocity: 500.0,
                rapid_rotation: 360.0,
                acceleration: 5000.0,
                rotation_acceleration: 7200.0,
            },
            grip_time: 0.0,
        };
        let mut samples = Interpolator::new(zigzag(count), config, NoSpeedLimit, |_| {});
        let (mut most, mut last, mut rows) = (0, None, 0usize);
        while let Some(sample) = samples.next() {
            last = Some(sample.expect("sample"));
            rows += 1;
            most = most.max(samples.held_pieces());
        }
        let window = 2 * crate::interpolator::WINDOW + 2;
        assert!(most > 100 && most <= window, "{most} pieces held");
        let last = last.expect("samples");
        let end = zigzag(count).last().and_then(|motion| motion.ok()?.kind.end());
        assert_eq!(Some(last.pose), end);
        // 20 m at 100 mm/s (each chord's projection on the x axis is 0.5 cos 3°).
        let at_feed = count as f64 * 0.5 / 100.0;
        assert!(last.t >= at_feed * 0.99 && last.t <= at_feed + 0.1, "{} s", last.t);
        assert_eq!(rows as f64, (last.t / 0.001).round() + 1.0);
    }
}
