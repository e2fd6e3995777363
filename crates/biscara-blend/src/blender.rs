//! The streaming blender.

use std::collections::VecDeque;

use biscara_motion::{Circle, Motion, MotionKind, Segment};

use crate::arcs::{self, Leg};
use crate::piece::{Geometry, Piece, Speed, dot, norm, sub, unit, xyz};

/// The tolerance of G64 with no P (or `P0`, LinuxCNC's "no tolerance given"), mm: the blend is
/// otherwise bounded only by the half-move rule, which on long moves would cut corners by
/// centimetres.
pub const NO_TOLERANCE_CAP_MM: f64 = 1.0;

/// The sharpest turn blended, degrees: a move that comes back on itself stops.
pub const MAX_TURN_DEG: f64 = 179.0;

/// The shortest blend made, mm along each move: a corner that can only get less is an exact stop.
pub const MIN_TRIM_MM: f64 = 1e-4;

/// Turns below this, radians, are straight on: no fillet needed (between two lines), or a
/// tangent junction (where an arc meets a line or an arc).
const COLLINEAR_RAD: f64 = 1e-9;

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

/// What the [`Blender`] yields.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Blended {
    /// A piece of a blended chain.
    Piece(Piece),
    /// A motion left as it is: an event, a move under exact stop or with no XYZ length, an arc
    /// tangent to neither neighbour.
    Motion(Motion),
}

/// A move under G64 (straight, or an arc) waiting for the next motion to know how its end is
/// blended.
#[derive(Debug, Clone, Copy)]
struct Pending {
    line: usize,
    /// Programmed start and end.
    from: [f64; 4],
    to: [f64; 4],
    /// Where the piece starts: `from`, or past the fillet that cut its start, and the fraction
    /// of the move there.
    start: [f64; 4],
    start_u: f64,
    speed: Speed,
    tolerance: f64,
    /// An arc's geometry and the motion as programmed (`None` for a straight move): an arc
    /// that joins nothing passes as it is.
    arc: Option<(Segment, Motion)>,
    /// Whether the move goes on from the one before it without a stop.
    joined: bool,
}

impl Pending {
    fn length(&self) -> f64 {
        match self.arc {
            Some((arc, _)) => arc.length(),
            None => norm(sub(xyz(self.to), xyz(self.from))),
        }
    }

    /// The unit XYZ direction of travel a fraction `u` along.
    fn direction(&self, u: f64) -> [f64; 3] {
        unit(match self.arc {
            Some((arc, _)) => xyz(arc.derivative(u)),
            None => sub(xyz(self.to), xyz(self.from)),
        })
    }

    /// C's change per mm of XYZ path, degrees.
    fn rotation_rate(&self) -> f64 {
        (self.to[3] - self.from[3]) / self.length()
    }

    /// The programmed pose a fraction `u` of the move along (C in proportion).
    fn at(&self, u: f64) -> [f64; 4] {
        match self.arc {
            Some((arc, _)) => arc.point(u),
            None => std::array::from_fn(|k| self.from[k] + u * (self.to[k] - self.from[k])),
        }
    }

    /// What the move is when the robot stops at its end: its last piece, or the motion itself
    /// for an arc that joins nothing (timed alone, as a move under exact stop is).
    fn last(&self) -> Blended {
        match self.arc {
            Some((_, motion)) if !self.joined => Blended::Motion(motion),
            _ => Blended::Piece(self.piece(1.0, true)),
        }
    }

    /// The piece from where the move starts to the fraction `end_u` along it (exactly the
    /// programmed end at 1).
    fn piece(&self, end_u: f64, ends_chain: bool) -> Piece {
        let geometry = match self.arc {
            Some((arc, _)) if self.start_u == 0.0 && end_u == 1.0 => Geometry::Arc(arc),
            Some((arc, _)) => Geometry::Arc(arc.part(self.start_u, end_u)),
            None => {
                let end = if end_u == 1.0 { self.to } else { self.at(end_u) };
                Geometry::Line { start: self.start, end }
            }
        };
        Piece { line: self.line, geometry, speed: self.speed, ends_chain }
    }
}

/// Joins the moves programmed under G64 by fillets; see the crate documentation.
///
/// Holds one motion of look-ahead and at most four items to yield: memory does not grow with
/// the program.
#[derive(Debug)]
pub struct Blender<I> {
    motions: I,
    position: [f64; 4],
    pending: Option<Pending>,
    out: VecDeque<Blended>,
    done: bool,
    enabled: bool,
}

impl<I, E> Blender<I>
where
    I: Iterator<Item = Result<Motion, E>>,
{
    /// Blends `motions`, the first of which starts at `start` (`[x, y, z, c]`, mm and degrees).
    pub fn new(motions: I, start: [f64; 4]) -> Blender<I> {
        Blender {
            motions,
            position: start,
            pending: None,
            out: VecDeque::new(),
            done: false,
            enabled: true,
        }
    }

    /// Whether nothing waits in the blender: its next item would be the source's next motion.
    /// A caller may then take motions from [`source`](Self::source) itself and hand the
    /// blender only those under G64 ([`take_from`](Self::take_from)).
    pub fn is_idle(&self) -> bool {
        self.out.is_empty() && self.pending.is_none() && !self.done
    }

    /// The motions being blended.
    pub fn source(&mut self) -> &mut I {
        &mut self.motions
    }

    /// Takes `motion`, which starts at `from`, as if it had come from the source (for a
    /// caller that reads the source itself while the blender is idle).
    pub fn take_from(&mut self, motion: Motion, from: [f64; 4]) {
        self.position = from;
        self.take(motion);
    }

    /// Whether to blend at all: with `false`, every motion passes unchanged (an exact stop at
    /// every corner, for timing laws that cannot run through one).
    pub fn blending(self, enabled: bool) -> Blender<I> {
        Blender { enabled, ..self }
    }

    fn flush(&mut self) {
        if let Some(pending) = self.pending.take() {
            self.out.push_back(pending.last());
        }
    }

    fn take(&mut self, motion: Motion) {
        let from = self.position;
        if let Some(end) = motion.kind.end() {
            self.position = end;
        }
        let (to, speed, arc) = match motion.kind {
            MotionKind::Rapid { end } => (end, Speed::Rapid, None),
            MotionKind::Linear { end, feed } => (end, Speed::Feed(feed), None),
            MotionKind::Arc { end, center, plane, clockwise, turns, feed } => {
                let arc = Segment::arc(from, end, center, plane, clockwise, turns);
                (end, Speed::Feed(feed), Some(arc))
            }
            _ => {
                self.flush();
                self.out.push_back(Blended::Motion(motion));
                return;
            }
        };
        let Some(blend) = motion.blend else {
            self.flush();
            self.out.push_back(Blended::Motion(motion));
            return;
        };
        let length = arc.map_or_else(|| norm(sub(xyz(to), xyz(from))), |arc| arc.length());
        if length <= 1e-9 {
            self.flush();
            self.out.push_back(Blended::Motion(motion));
            return;
        }
        let tolerance = if blend > 0.0 { blend } else { NO_TOLERANCE_CAP_MM };
        let mut next = Pending {
            line: motion.line,
            from,
            to,
            start: from,
            start_u: 0.0,
            speed,
            tolerance,
            arc: arc.map(|arc| (arc, motion)),
            joined: false,
        };
        if let Some(previous) = self.pending.take() {
            match corner(&previous, &next) {
                Corner::Straight => {
                    self.out.push_back(Blended::Piece(previous.piece(1.0, false)));
                    next.joined = true;
                }
                Corner::Stop => self.out.push_back(previous.last()),
                Corner::Fillet { end_u, start_u, fillet } => {
                    // (What is left of a line shorter than 1e-9 mm is dropped; of an arc,
                    // kept: the fillets at its ends are tangent to it, not to each other.)
                    let left = (end_u - previous.start_u) * previous.length();
                    if left > 1e-9 || previous.arc.is_some() && left > 0.0 {
                        self.out.push_back(Blended::Piece(previous.piece(end_u, false)));
                    }
                    if previous.speed == next.speed {
                        self.out.push_back(Blended::Piece(fillet));
                    } else {
                        let [first, second] = halves(fillet, next.line, next.speed);
                        self.out.push_back(Blended::Piece(first));
                        self.out.push_back(Blended::Piece(second));
                    }
                    next.start = next.at(start_u);
                    next.start_u = start_u;
                    next.joined = true;
                }
            }
        }
        self.pending = Some(next);
    }
}

enum Corner {
    /// The moves go straight on: no fillet, no stop.
    Straight,
    /// No blend fits: an exact stop.
    Stop,
    /// The move before the corner ends a fraction `end_u` along it, the move after it starts
    /// a fraction `start_u` along it, and `fillet` joins them.
    Fillet { end_u: f64, start_u: f64, fillet: Piece },
}

fn corner(a: &Pending, b: &Pending) -> Corner {
    let ua = a.direction(1.0);
    let ub = b.direction(0.0);
    let cos = dot(ua, ub).clamp(-1.0, 1.0);
    // (From the sine and the cosine: acos alone cannot tell turns below 1.5e-8 rad from 0.)
    let turn = norm(cross(ua, ub)).atan2(dot(ua, ub));
    // C's rate along the path, degrees per mm: it must not jump where the robot does not stop
    // (a jump in a joint's dq/ds at speed is an unbounded acceleration).
    let (rate_a, rate_b) = (a.rotation_rate(), b.rotation_rate());
    if turn < COLLINEAR_RAD {
        let same = (rate_a - rate_b).abs() <= 1e-9 * (1.0 + rate_a.abs().max(rate_b.abs()));
        return if same { Corner::Straight } else { Corner::Stop };
    }
    if rate_a != 0.0 || rate_b != 0.0 || turn > MAX_TURN_DEG.to_radians() {
        return Corner::Stop;
    }
    let tolerance = a.tolerance.min(b.tolerance);
    if a.arc.is_some() || b.arc.is_some() {
        return arc_corner(a, b, turn, tolerance).unwrap_or(Corner::Stop);
    }
    let half = turn / 2.0;
    // Deviation of the fillet's midpoint from the corner: r (1/cos(θ/2) − 1) = r · 2 sin²(θ/4)
    // / cos(θ/2), written without the cancellation of 1 − cos for small turns.
    let quarter_sin = (turn / 4.0).sin();
    let radius_for_tolerance = tolerance * half.cos() / (2.0 * quarter_sin * quarter_sin);
    let trim = (radius_for_tolerance * half.tan()).min(a.length() / 2.0).min(b.length() / 2.0);
    if trim < MIN_TRIM_MM {
        return Corner::Stop;
    }
    let radius = trim / half.tan();
    let (end_u, start_u) = ((a.length() - trim) / a.length(), trim / b.length());
    let start = a.at(end_u);
    let end = b.at(start_u);
    // Towards the centre: the part of ub across ua.
    let across: [f64; 3] = std::array::from_fn(|k| ub[k] - cos * ua[k]);
    let across_norm = norm(across);
    let inward: [f64; 3] = std::array::from_fn(|k| across[k] / across_norm);
    let center = std::array::from_fn(|k| start[k] + radius * inward[k]);
    let fillet = Piece {
        line: a.line,
        geometry: Geometry::Fillet { start, end, center, radius, tangent: ua, sweep: turn },
        speed: a.speed,
        ends_chain: false,
    };
    Corner::Fillet { end_u, start_u, fillet }
}

/// The corner between `a` and `b` where one or both are arcs: a fillet in the arc's plane
/// (see [`arcs`]), or `None` (an exact stop) when the arcs are not planar circles in one plane,
/// a line leaves that plane, or no fillet fits.
fn arc_corner(a: &Pending, b: &Pending, turn: f64, tolerance: f64) -> Option<Corner> {
    let axes_of =
        |pending: &Pending| pending.arc.map(|(arc, _)| arc.planar_arc().map(|arc| arc.axes));
    let axes = match (axes_of(a), axes_of(b)) {
        (Some(Some(first)), Some(Some(second))) if first == second => first,
        (Some(Some(axes)), None) | (None, Some(Some(axes))) => axes,
        _ => return None,
    };
    // A line must lie in the arc's plane.
    let in_plane = |pending: &Pending| pending.to[axes[2]] == pending.from[axes[2]];
    if !(in_plane(a) && in_plane(b)) {
        return None;
    }
    let flat = |v: [f64; 3]| [v[axes[0]], v[axes[1]]];
    let corner = [a.to[axes[0]], a.to[axes[1]]];
    let (ua, ub) = (flat(a.direction(1.0)), flat(b.direction(0.0)));
    let side = (ua[0] * ub[1] - ua[1] * ub[0]).signum();
    // A line as a leg leaving the corner (backwards for the move before it).
    let line_leg = |pending: &Pending, backwards: bool| {
        let d = flat(sub(xyz(pending.to), xyz(pending.from)));
        let (length, sign) = (d[0].hypot(d[1]), if backwards { -1.0 } else { 1.0 });
        Leg::Line { direction: [sign * d[0] / length, sign * d[1] / length], limit: length / 2.0 }
    };
    // An arc's point and direction of travel at the parameter `u`, in the plane.
    let on = |arc: Segment, u: f64| (flat(xyz(arc.point(u))), flat(unit(xyz(arc.derivative(u)))));
    // The fraction of each move cut away at the corner, and its length in mm.
    let ([cut_a, start_u], [mm_a, mm_b], found) = match (a.arc, b.arc) {
        (Some((arc, _)), None) => {
            let leg = line_leg(b, false);
            let found =
                arcs::fit_line_arc(corner, leg, |tau| on(arc, 1.0 - tau), true, side, tolerance)?;
            let [tau, trim] = found.trims;
            ([tau, trim / b.length()], [tau * arc.length(), trim], found)
        }
        (None, Some((arc, _))) => {
            let leg = line_leg(a, true);
            let found =
                arcs::fit_line_arc(corner, leg, |tau| on(arc, tau), false, side, tolerance)?;
            let [trim, tau] = found.trims;
            ([trim / a.length(), tau], [trim, tau * arc.length()], found)
        }
        (Some((first, _)), Some((second, _))) => {
            // Two arcs: both circles, each a leg leaving the corner with its trim in radians.
            let (Some(one), Some(other)) = (first.circle(), second.circle()) else {
                return None;
            };
            let leg = |circle: Circle, backwards: bool| Leg::Circle {
                center: circle.center,
                radius: circle.radius,
                turn: if backwards { -circle.sweep.signum() } else { circle.sweep.signum() },
                limit: circle.sweep.abs() / 2.0,
            };
            let found =
                arcs::fit(corner, leg(one, true), leg(other, false), turn, side, tolerance)?;
            let [angle_a, angle_b] = found.trims;
            (
                [angle_a / one.sweep.abs(), angle_b / other.sweep.abs()],
                [angle_a * one.radius, angle_b * other.radius],
                found,
            )
        }
        (None, None) => return None,
    };
    if mm_a.min(mm_b) < MIN_TRIM_MM {
        return None;
    }
    let end_u = 1.0 - cut_a;
    let (start, end) = (a.at(end_u), b.at(start_u));
    // The fillet in 3D: in the plane, at the corner's height along the normal.
    let lift = |point: [f64; 2], normal: f64| {
        let mut v = [0.0; 3];
        v[axes[0]] = point[0];
        v[axes[1]] = point[1];
        v[axes[2]] = normal;
        v
    };
    let center = lift(found.center, a.to[axes[2]]);
    let (radial_a, radial_b) = (
        [start[axes[0]] - found.center[0], start[axes[1]] - found.center[1]],
        [end[axes[0]] - found.center[0], end[axes[1]] - found.center[1]],
    );
    let on_circle =
        |radial: [f64; 2]| (radial[0].hypot(radial[1]) - found.radius).abs() <= arcs::FIT_MM;
    if !(on_circle(radial_a) && on_circle(radial_b)) {
        return None;
    }
    let sweep = side
        * (radial_a[0] * radial_b[1] - radial_a[1] * radial_b[0])
            .atan2(radial_a[0] * radial_b[0] + radial_a[1] * radial_b[1]);
    // The fillet leaves along the move before the corner and arrives along the move after it:
    // its tangent and sweep from the moves' own directions where they are cut (exact, where a
    // small fillet's radials hold only as many digits as it is small). They must agree with
    // its radials: the fillet then ends within 1e-10 mm of the cut.
    let (leaving, arriving) = (a.direction(end_u), b.direction(start_u));
    let (ta, tb) = (flat(leaving), flat(arriving));
    let turned = side * (ta[0] * tb[1] - ta[1] * tb[0]).atan2(ta[0] * tb[0] + ta[1] * tb[1]);
    if (turned - sweep).abs() * found.radius > arcs::FIT_MM {
        return None;
    }
    let (sweep, tangent) = (turned, leaving);
    let fillet = Piece {
        line: a.line,
        geometry: Geometry::Fillet { start, end, center, radius: found.radius, tangent, sweep },
        speed: a.speed,
        ends_chain: false,
    };
    Some(Corner::Fillet { end_u, start_u, fillet })
}

/// A fillet between moves of different speeds, cut at its middle: the first half keeps the
/// speed (and line) of the move before the corner, the second takes `line` and `speed`, those
/// of the move after it — each half replaces a part of its own move.
fn halves(fillet: Piece, line: usize, speed: Speed) -> [Piece; 2] {
    let Geometry::Fillet { start, end, center, radius, tangent, sweep } = fillet.geometry else {
        return [fillet, fillet];
    };
    let middle = fillet.point(0.5);
    let half = sweep / 2.0;
    let first = Geometry::Fillet { start, end: middle, center, radius, tangent, sweep: half };
    let turned = fillet.tangent(0.5);
    let second =
        Geometry::Fillet { start: middle, end, center, radius, tangent: turned, sweep: half };
    [Piece { geometry: first, ..fillet }, Piece { line, geometry: second, speed, ..fillet }]
}

impl<I, E> Iterator for Blender<I>
where
    I: Iterator<Item = Result<Motion, E>>,
{
    type Item = Result<Blended, E>;

    fn next(&mut self) -> Option<Self::Item> {
        loop {
            if let Some(item) = self.out.pop_front() {
                return Some(Ok(item));
            }
            if self.done {
                return None;
            }
            match self.motions.next() {
                // Nothing waits and the motion is not blended: it passes at once.
                Some(Ok(motion))
                    if self.pending.is_none() && !(self.enabled && motion.blend.is_some()) =>
                {
                    if let Some(end) = motion.kind.end() {
                        self.position = end;
                    }
                    return Some(Ok(Blended::Motion(motion)));
                }
                // (Nothing is pending unless blending is enabled.)
                Some(Ok(motion)) => self.take(motion),
                Some(Err(err)) => {
                    self.done = true;
                    return Some(Err(err));
                }
                None => {
                    self.done = true;
                    self.flush();
                }
            }
        }
    }
}
