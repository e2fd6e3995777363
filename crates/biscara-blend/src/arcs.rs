//! The fillet at a corner where a programmed arc meets a line or another arc, in the arc's
//! plane (plane coordinates, 2D).
//!
//! Each move is trimmed back from the corner `P` to where the fillet touches it (a line by a
//! length, an arc by a part of its sweep: the trimmed arc keeps its centre and radius), at
//! most half of it; the fillet lies on the inside of the corner and is the largest for which
//! the distance of `P` from it is at most the tolerance. Two searches, by bisection:
//!
//! - a line and an arc ([`fit_line_arc`]): on the arc's trim. The fillet touches the arc where
//!   it is cut, with the arc's own tangent there (its centre on the arc's normal), and its
//!   radius makes it tangent to the line: exact for a spiral too (an arc whose end radius
//!   differs from its start radius, as rounded CAM coordinates make);
//! - two circles ([`fit`]): on the radius `r`. Both moves are seen leaving the corner (the one
//!   before it run backwards), and the fillet's centre lies `R − r` (inside an arc's circle,
//!   when the arc bends towards the fillet) or `R + r` (outside) from each arc's centre.

use crate::blender::MAX_TURN_DEG;

/// The largest fillet radius tried, mm: a nearly tangent corner would otherwise get a fillet
/// so large that its points lose precision (its centre kilometres away). Corners that turn by
/// less than 2e-8 rad are then exact stops (their fillets would trim less than `MIN_TRIM_MM`).
const MAX_RADIUS_MM: f64 = 1e4;

/// How far a fillet's ends may lie off its circle, mm.
pub(crate) const FIT_MM: f64 = 1e-10;

/// `(−y, x)`: `v` turned a quarter counter-clockwise.
fn left(v: [f64; 2]) -> [f64; 2] {
    [-v[1], v[0]]
}

fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

fn dot(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

fn norm(a: [f64; 2]) -> f64 {
    a[0].hypot(a[1])
}

/// The signed angle from `a` to `b`, radians, counter-clockwise positive.
fn angle(a: [f64; 2], b: [f64; 2]) -> f64 {
    cross(a, b).atan2(dot(a, b))
}

/// One move at the corner, leaving it.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Leg {
    /// A straight move: its unit direction leaving the corner, and the longest trim, mm.
    Line { direction: [f64; 2], limit: f64 },
    /// An arc: its centre and radius, `turn` +1 when it bends left (counter-clockwise) leaving
    /// the corner and −1 when it bends right, and the longest trim, radians.
    Circle { center: [f64; 2], radius: f64, turn: f64, limit: f64 },
}

/// A fillet that fits the corner.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Fit {
    /// Its centre and radius.
    pub center: [f64; 2],
    pub radius: f64,
    /// How far each leg is trimmed back from the corner: mm for a line; for an arc, radians
    /// ([`fit`]) or the fraction of it ([`fit_line_arc`]).
    pub trims: [f64; 2],
}

impl Leg {
    /// How far the leg is trimmed back from the corner (mm for a line, radians for an arc) to
    /// where a fillet centred at `center` touches it, and that point.
    fn trim_at(self, corner: [f64; 2], center: [f64; 2]) -> (f64, [f64; 2]) {
        match self {
            Leg::Line { direction, .. } => {
                let along = dot(sub(center, corner), direction);
                (along, [corner[0] + along * direction[0], corner[1] + along * direction[1]])
            }
            Leg::Circle { center: o, radius, turn, .. } => {
                let out = sub(center, o);
                let length = norm(out);
                let point = [o[0] + radius * out[0] / length, o[1] + radius * out[1] / length];
                (turn * angle(sub(corner, o), sub(point, o)), point)
            }
        }
    }

    /// The unit direction of the leg, leaving the corner, at its point `point`.
    fn direction_at(self, point: [f64; 2]) -> [f64; 2] {
        match self {
            Leg::Line { direction, .. } => direction,
            Leg::Circle { center, radius, turn, .. } => {
                let out = left(sub(point, center));
                [turn * out[0] / radius, turn * out[1] / radius]
            }
        }
    }

    fn limit(self) -> f64 {
        match self {
            Leg::Line { limit, .. } | Leg::Circle { limit, .. } => limit,
        }
    }
}

/// The distance of the fillet's centre from an arc leg's centre: `R − r` when the arc bends
/// towards the fillet's side `side` of it, else `R + r`; `None` when `r` does not fit inside.
fn offset_radius(radius: f64, turn: f64, side: f64, r: f64) -> Option<f64> {
    let rho = radius - turn * side * r;
    (rho > 1e-9 * radius).then_some(rho)
}

/// The centre of the fillet of radius `r`, `side_a` and `side_b` being the sides of the legs
/// (+1 left) on which it lies; `None` when there is none near the corner.
fn center(corner: [f64; 2], a: Leg, b: Leg, sides: [f64; 2], r: f64) -> Option<[f64; 2]> {
    match (a, b) {
        (
            Leg::Circle { center: o1, radius: r1, turn: t1, .. },
            Leg::Circle { center: o2, radius: r2, turn: t2, .. },
        ) => {
            let rho1 = offset_radius(r1, t1, sides[0], r)?;
            let rho2 = offset_radius(r2, t2, sides[1], r)?;
            let between = sub(o2, o1);
            let d = norm(between);
            if d < 1e-12 {
                return None;
            }
            let along = (rho1 * rho1 - rho2 * rho2 + d * d) / (2.0 * d);
            let h2 = rho1 * rho1 - along * along;
            if h2 < 0.0 {
                return None;
            }
            let (u, h) = ([between[0] / d, between[1] / d], h2.sqrt());
            let base = [o1[0] + along * u[0], o1[1] + along * u[1]];
            let across = left(u);
            let one = [base[0] + h * across[0], base[1] + h * across[1]];
            let other = [base[0] - h * across[0], base[1] - h * across[1]];
            Some(if norm(sub(one, corner)) <= norm(sub(other, corner)) { one } else { other })
        }
        // (A line and an arc: `fit_line_arc`.)
        _ => None,
    }
}

/// The fillet of radius `r` at `corner` between the legs `a` (the move before the corner, run
/// backwards) and `b`, on the inside of a turn to the side `side` (+1 left): `None` unless
/// both trims are positive and within their limits and the corner within `tolerance` of it.
fn fit_at(corner: [f64; 2], a: Leg, b: Leg, side: f64, tolerance: f64, r: f64) -> Option<Fit> {
    // Seen leaving the corner, the fillet lies right of the first leg for a left turn.
    let center = center(corner, a, b, [-side, side], r)?;
    let (trim_a, point_a) = a.trim_at(corner, center);
    let (trim_b, point_b) = b.trim_at(corner, center);
    let within = |trim: f64, leg: Leg| trim > 0.0 && trim <= leg.limit();
    if !(within(trim_a, a) && within(trim_b, b)) {
        return None;
    }
    let (ra, rb) = (sub(point_a, center), sub(point_b, center));
    let sweep = fillet_sweep(center, r, [point_a, point_b], side)?;
    // The fillet runs the way the moves do: against leg a (which leaves the corner backwards),
    // along leg b.
    let (ta, tb) = (left(ra), left(rb));
    let along = dot(ta, a.direction_at(point_a)) * side < 0.0
        && dot(tb, b.direction_at(point_b)) * side > 0.0;
    if !(sweep > 0.0 && along) {
        return None;
    }
    let deviation = corner_deviation(corner, center, r, [point_a, point_b], side, sweep);
    (deviation <= tolerance).then_some(Fit { center, radius: r, trims: [trim_a, trim_b] })
}

/// The sweep (radians, positive when the fillet turns to `side`) of the fillet of radius `r`
/// about `center` from `ends[0]` to `ends[1]`; `None` when an end is off its circle. Where a
/// line is nearly tangent to an arc and the fillet nearly its circle, the centre is
/// ill-conditioned: a fillet whose ends are not on it (to [`FIT_MM`]) is none. A fillet that
/// would turn by more than [`MAX_TURN_DEG`] is none too: where arcs bend towards each other
/// their fillet turns by more than the corner does, up to a reversal (two arcs meeting almost
/// head-on), which stays an exact stop as a straight corner that sharp does.
fn fillet_sweep(center: [f64; 2], r: f64, ends: [[f64; 2]; 2], side: f64) -> Option<f64> {
    let [ra, rb] = ends.map(|end| sub(end, center));
    if (norm(ra) - r).abs() > FIT_MM || (norm(rb) - r).abs() > FIT_MM {
        return None;
    }
    let sweep = side * angle(ra, rb);
    (sweep.abs() <= MAX_TURN_DEG.to_radians()).then_some(sweep)
}

/// How far `corner` is from the fillet of radius `r` about `center` from `ends[0]` sweeping
/// `sweep` to `side`: from its circle where the corner faces the fillet, else from the nearer
/// end.
fn corner_deviation(
    corner: [f64; 2],
    center: [f64; 2],
    r: f64,
    ends: [[f64; 2]; 2],
    side: f64,
    sweep: f64,
) -> f64 {
    let towards = sub(corner, center);
    let at = side * angle(sub(ends[0], center), towards);
    if (0.0..=sweep).contains(&at) {
        (norm(towards) - r).abs()
    } else {
        norm(sub(corner, ends[0])).min(norm(sub(corner, ends[1])))
    }
}

/// The largest fillet at `corner` between the legs `a` (the move before the corner, run
/// backwards) and `b` that keeps the corner within `tolerance` and each trim within its leg's
/// limit; `turn` is the corner's turn (radians), `side` +1 for a left turn, −1 for a right one.
/// `None` when none fits.
pub(crate) fn fit(
    corner: [f64; 2],
    a: Leg,
    b: Leg,
    turn: f64,
    side: f64,
    tolerance: f64,
) -> Option<Fit> {
    // A start: the radius of the fillet between the two tangents at the tolerance.
    let quarter_sin = (turn / 4.0).sin();
    let mut high =
        (tolerance * (turn / 2.0).cos() / (2.0 * quarter_sin * quarter_sin)).min(MAX_RADIUS_MM);
    let mut best = None;
    while let Some(found) = fit_at(corner, a, b, side, tolerance, high) {
        best = Some(found);
        if high >= MAX_RADIUS_MM {
            return best;
        }
        high = (2.0 * high).min(MAX_RADIUS_MM);
    }
    let mut low = best.map_or(0.0, |found: Fit| found.radius);
    for _ in 0..60 {
        let middle = 0.5 * (low + high);
        match fit_at(corner, a, b, side, tolerance, middle) {
            Some(found) => {
                best = Some(found);
                low = middle;
            }
            None => high = middle,
        }
        if high - low <= 1e-12 * high {
            break;
        }
    }
    best
}

/// The fillet at `corner` between a line and an arc, the arc given by its own geometry: `arc`
/// maps a trim τ (the fraction of the arc cut away from the corner, in (0, ½]) to the arc's
/// point there and its unit direction of travel, exactly as the trimmed arc will run (a spiral
/// too: an arc whose end radius differs from its start radius, as CAM output rounded to a few
/// decimals makes). The fillet touches the arc at that point with the arc's own tangent, and is
/// tangent to the line; τ is the largest (by bisection) that keeps the corner within
/// `tolerance` of the fillet and the line's trim within its limit.
///
/// `line` leaves the corner (`Leg::Line`), `arc_first` says whether the arc comes before the
/// corner, `side` is the corner's turn (+1 left). The fit's trims are the line's (mm) and τ.
pub(crate) fn fit_line_arc(
    corner: [f64; 2],
    line: Leg,
    arc: impl Fn(f64) -> ([f64; 2], [f64; 2]),
    arc_first: bool,
    side: f64,
    tolerance: f64,
) -> Option<Fit> {
    let Leg::Line { direction, limit } = line else { return None };
    // The line's normal towards the fillet: left of its direction of travel for a left turn.
    let forward = if arc_first { direction } else { [-direction[0], -direction[1]] };
    let normal = left(forward);
    let towards = [side * normal[0], side * normal[1]];
    let fit_at = |tau: f64| -> Option<Fit> {
        let (point, tangent) = arc(tau);
        // The fillet's centre: r from the arc's point, on the turn's side of its tangent, and
        // r from the line: (point − corner)·n + r (m·n) = r.
        let inward = left(tangent);
        let inward = [side * inward[0], side * inward[1]];
        let denominator = 1.0 - dot(inward, towards);
        if denominator.is_nan() || denominator <= 1e-12 {
            return None;
        }
        let r = dot(sub(point, corner), towards) / denominator;
        if !(r > 0.0 && r < MAX_RADIUS_MM) {
            return None;
        }
        let center = [point[0] + r * inward[0], point[1] + r * inward[1]];
        let trim = dot(sub(center, corner), direction);
        if !(trim > 0.0 && trim <= limit) {
            return None;
        }
        let foot = [corner[0] + trim * direction[0], corner[1] + trim * direction[1]];
        let (start, end) = if arc_first { (point, foot) } else { (foot, point) };
        let (ra, rb) = (sub(start, center), sub(end, center));
        let sweep = fillet_sweep(center, r, [start, end], side)?;
        // The fillet runs along the line where it touches it.
        let along_line = if arc_first { rb } else { ra };
        if !(sweep > 0.0 && side * dot(left(along_line), forward) > 0.0) {
            return None;
        }
        let deviation = corner_deviation(corner, center, r, [start, end], side, sweep);
        let trims = if arc_first { [tau, trim] } else { [trim, tau] };
        (deviation <= tolerance).then_some(Fit { center, radius: r, trims })
    };
    if let Some(found) = fit_at(0.5) {
        return Some(found);
    }
    let (mut low, mut high, mut best) = (0.0, 0.5, None);
    for _ in 0..60 {
        let middle = 0.5 * (low + high);
        match fit_at(middle) {
            Some(found) => {
                best = Some(found);
                low = middle;
            }
            None => high = middle,
        }
    }
    best
}
