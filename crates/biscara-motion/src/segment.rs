//! The geometry of one move: where the tool is at each value of the path parameter s ∈ [0, 1].

use std::f64::consts::TAU;

use crate::Plane;

/// One move's geometry, from `start` to `end` (`[x, y, z, c]`, mm and degrees), traversed as the
/// path parameter `s` runs from 0 to 1. C moves in proportion to `s` (docs/motion.md).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Segment {
    start: [f64; 4],
    end: [f64; 4],
    shape: Shape,
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Shape {
    Line,
    /// A circle (or spiral, when the end radius differs slightly from the start radius, as
    /// LinuxCNC tolerates) in the plane's axes, with the normal axis moving linearly (helix).
    Arc {
        axes: [usize; 3],
        center: [f64; 2],
        start_radius: f64,
        end_radius: f64,
        start_angle: f64,
        sweep: f64,
    },
    /// A circular arc in any plane (a corner's fillet under G64): `center + cos φ · radial +
    /// sin φ · across` for φ = s · `sweep`, where `radial` (from the centre to the start) and
    /// `across` (the radius times the start's unit tangent) are orthogonal and as long as the
    /// radius.
    Fillet {
        center: [f64; 3],
        radial: [f64; 3],
        across: [f64; 3],
        sweep: f64,
    },
}

/// A planar arc in its plane (see [`Segment::planar_arc`], [`Segment::circle`]): what a
/// corner's blend needs to fit a fillet tangent to it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Circle {
    /// The plane's axes, as [`Plane::axes`]: the first two span the plane, the third is its
    /// normal (indices into `[x, y, z, c]`).
    pub axes: [usize; 3],
    /// The centre, in the plane's first two axes, mm.
    pub center: [f64; 2],
    /// The radius at the start, mm.
    pub radius: f64,
    /// The radius at the end, mm (the start's, but for a spiral).
    pub end_radius: f64,
    /// The angle swept, radians: positive counter-clockwise seen from the plane's normal.
    pub sweep: f64,
}

/// Gap below which an arc's start and end angles count as equal (a full circle).
const FULL_CIRCLE_EPSILON: f64 = 1e-12;

impl Segment {
    /// A straight move.
    pub fn line(start: [f64; 4], end: [f64; 4]) -> Segment {
        Segment { start, end, shape: Shape::Line }
    }

    /// A circular or helical move about `center` (in the plane's axes, see [`Plane`]):
    /// clockwise seen from the plane's normal when `clockwise`, with `turns` ≥ 1 passes (1 ends
    /// at the first arrival at `end`; a start equal to the end is a full circle).
    pub fn arc(
        start: [f64; 4],
        end: [f64; 4],
        center: [f64; 2],
        plane: Plane,
        clockwise: bool,
        turns: u32,
    ) -> Segment {
        let axes = plane.axes();
        let offset = |point: [f64; 4]| [point[axes[0]] - center[0], point[axes[1]] - center[1]];
        let (from, to) = (offset(start), offset(end));
        let start_angle = from[1].atan2(from[0]);
        let end_angle = to[1].atan2(to[0]);
        let gap = if clockwise { start_angle - end_angle } else { end_angle - start_angle };
        let mut sweep = gap.rem_euclid(TAU);
        if sweep < FULL_CIRCLE_EPSILON || TAU - sweep < FULL_CIRCLE_EPSILON && same_point(from, to)
        {
            sweep = TAU;
        }
        sweep += TAU * f64::from(turns.max(1) - 1);
        if clockwise {
            sweep = -sweep;
        }
        Segment {
            start,
            end,
            shape: Shape::Arc {
                axes,
                center,
                start_radius: from[0].hypot(from[1]),
                end_radius: to[0].hypot(to[1]),
                start_angle,
                sweep,
            },
        }
    }

    /// A circular fillet from `start`, leaving along the unit vector `tangent`, turning by
    /// `sweep` radians (in (0, π]) about `center`, to `end`; C goes linearly (a corner's blend,
    /// see `biscara-blend`).
    pub fn fillet(
        start: [f64; 4],
        end: [f64; 4],
        center: [f64; 3],
        tangent: [f64; 3],
        sweep: f64,
    ) -> Segment {
        let radial: [f64; 3] = std::array::from_fn(|k| start[k] - center[k]);
        let radius = radial.iter().map(|value| value * value).sum::<f64>().sqrt();
        let across = std::array::from_fn(|k| radius * tangent[k]);
        Segment { start, end, shape: Shape::Fillet { center, radial, across, sweep } }
    }

    /// The part of the move between the path parameters `from` and `to` (0 ≤ `from` < `to` ≤ 1),
    /// traversed the same way: a line's piece, or an arc's with the same centre and radius law
    /// and a shorter sweep (a corner's blend trims the moves it joins). Its ends are
    /// `point(from)` and `point(to)`, so a part to 1 ends exactly at `end`.
    pub fn part(&self, from: f64, to: f64) -> Segment {
        let start = if from <= 0.0 { self.start } else { self.point(from) };
        let end = self.point(to);
        let shape = match self.shape {
            Shape::Line => Shape::Line,
            Shape::Arc { axes, center, start_radius, end_radius, start_angle, sweep } => {
                let change = end_radius - start_radius;
                let (mut first, mut last) =
                    (start_radius + from * change, start_radius + to * change);
                // A circle whose radii differ by rounding stays a circle: on a short part, a
                // rounding difference of its radii would tilt its tangent (by the difference
                // over the part's length).
                if change.abs() <= 1e-9 * start_radius.max(1.0) {
                    let middle = start_radius + 0.5 * (from + to) * change;
                    (first, last) = (middle, middle);
                }
                Shape::Arc {
                    axes,
                    center,
                    start_radius: first,
                    end_radius: last,
                    start_angle: start_angle + from * sweep,
                    sweep: (to - from) * sweep,
                }
            }
            Shape::Fillet { center, radial, across, sweep } => {
                let (sin, cos) = (from * sweep).sin_cos();
                Shape::Fillet {
                    center,
                    radial: std::array::from_fn(|k| cos * radial[k] + sin * across[k]),
                    across: std::array::from_fn(|k| cos * across[k] - sin * radial[k]),
                    sweep: (to - from) * sweep,
                }
            }
        };
        Segment { start, end, shape }
    }

    /// A planar arc's geometry in its plane (an arc that does not move along the plane's
    /// normal: a circle, or a spiral whose end radius differs from its start radius); `None`
    /// for a line, a fillet or a helix.
    pub fn planar_arc(&self) -> Option<Circle> {
        let Shape::Arc { axes, center, start_radius, end_radius, sweep, .. } = self.shape else {
            return None;
        };
        let planar = self.delta()[axes[2]] == 0.0;
        planar.then_some(Circle { axes, center, radius: start_radius, end_radius, sweep })
    }

    /// The arc's circle when it is a planar circular arc ([`planar_arc`](Self::planar_arc)
    /// with its start and end radii equal within 1e-9 of the radius); `None` for a line, a
    /// fillet, a helix or a spiral.
    pub fn circle(&self) -> Option<Circle> {
        self.planar_arc().filter(|circle| {
            (circle.end_radius - circle.radius).abs() <= 1e-9 * circle.radius.max(1.0)
        })
    }

    /// The path parameters s ∈ [0, 1] at which an arc passes the angle `angle` (radians, in its
    /// plane's axes, from the first axis toward the second), in no particular order; none for a
    /// line. With the angles 0, π/2, π and 3π/2 these are the only places besides the ends where
    /// a coordinate of the plane can be extreme.
    pub fn parameters_at_angle(&self, angle: f64) -> impl Iterator<Item = f64> {
        let (start_angle, sweep) = match self.shape {
            Shape::Arc { start_angle, sweep, .. } => (start_angle, sweep),
            Shape::Line | Shape::Fillet { .. } => (0.0, 0.0),
        };
        let delta = if sweep < 0.0 { start_angle - angle } else { angle - start_angle };
        let length = sweep.abs();
        let first = delta.rem_euclid(TAU);
        (0..)
            .map(move |turn| first + TAU * f64::from(turn))
            .take_while(move |&delta| length > 0.0 && delta <= length)
            .map(move |delta| delta / length)
    }

    /// The start pose.
    pub fn start(&self) -> [f64; 4] {
        self.start
    }

    /// The end pose.
    pub fn end(&self) -> [f64; 4] {
        self.end
    }

    /// Length of the XYZ path, mm (for an arc whose radius changes, the mean radius is used).
    pub fn length(&self) -> f64 {
        match self.shape {
            Shape::Line => {
                let [dx, dy, dz, _] = self.delta();
                (dx * dx + dy * dy + dz * dz).sqrt()
            }
            Shape::Arc { axes, start_radius, end_radius, sweep, .. } => {
                let around = 0.5 * (start_radius + end_radius) * sweep.abs();
                around.hypot(self.delta()[axes[2]])
            }
            Shape::Fillet { radial, sweep, .. } => {
                radial.iter().map(|value| value * value).sum::<f64>().sqrt() * sweep
            }
        }
    }

    /// Rotation of C over the move, degrees (signed).
    pub fn rotation(&self) -> f64 {
        self.end[3] - self.start[3]
    }

    /// The radius of an arc (the smaller of its start and end radii, when they differ) or of a
    /// fillet, in its plane, mm; `None` for a line. A helix bends less than its radius says: the
    /// centripetal acceleration at speed v is at most v² over this.
    pub fn radius(&self) -> Option<f64> {
        match self.shape {
            Shape::Line => None,
            Shape::Arc { start_radius, end_radius, .. } => Some(start_radius.min(end_radius)),
            Shape::Fillet { radial, .. } => {
                Some(radial.iter().map(|value| value * value).sum::<f64>().sqrt())
            }
        }
    }

    /// How far the direction of travel turns over the move, degrees: an arc's sweep, 0 for a
    /// line.
    pub fn turning(&self) -> f64 {
        match self.shape {
            Shape::Line => 0.0,
            Shape::Arc { sweep, .. } | Shape::Fillet { sweep, .. } => sweep.abs().to_degrees(),
        }
    }

    /// The pose at path parameter `s` (exactly `end` at `s = 1`).
    #[inline]
    pub fn point(&self, s: f64) -> [f64; 4] {
        if s >= 1.0 {
            return self.end;
        }
        let delta = self.delta();
        let mut point = [0.0; 4];
        for axis in 0..4 {
            point[axis] = self.start[axis] + s * delta[axis];
        }
        if let Shape::Arc { axes, center, start_radius, end_radius, start_angle, sweep } =
            self.shape
        {
            let radius = start_radius + s * (end_radius - start_radius);
            let (sin, cos) = (start_angle + s * sweep).sin_cos();
            point[axes[0]] = center[0] + radius * cos;
            point[axes[1]] = center[1] + radius * sin;
        } else if let Shape::Fillet { center, radial, across, sweep } = self.shape {
            let (sin, cos) = (s * sweep).sin_cos();
            for k in 0..3 {
                point[k] = center[k] + cos * radial[k] + sin * across[k];
            }
        }
        point
    }

    /// `d pose / ds` at path parameter `s` (mm and degrees per unit of s).
    pub fn derivative(&self, s: f64) -> [f64; 4] {
        let mut derivative = self.delta();
        if let Shape::Arc { axes, start_radius, end_radius, start_angle, sweep, .. } = self.shape {
            let radius = start_radius + s * (end_radius - start_radius);
            let radius_rate = end_radius - start_radius;
            let (sin, cos) = (start_angle + s * sweep).sin_cos();
            derivative[axes[0]] = radius_rate * cos - radius * sweep * sin;
            derivative[axes[1]] = radius_rate * sin + radius * sweep * cos;
        } else if let Shape::Fillet { radial, across, sweep, .. } = self.shape {
            let (sin, cos) = (s * sweep).sin_cos();
            for k in 0..3 {
                derivative[k] = sweep * (cos * across[k] - sin * radial[k]);
            }
        }
        derivative
    }

    /// The pose at `s` and its first and second derivatives along the move (mm and degrees per
    /// unit of s and of s²): one `sin_cos` for the three.
    pub fn derivatives(&self, s: f64) -> [[f64; 4]; 3] {
        let delta = self.delta();
        let mut point = [0.0; 4];
        for axis in 0..4 {
            point[axis] = self.start[axis] + s * delta[axis];
        }
        let mut derivative = delta;
        let mut second = [0.0; 4];
        if let Shape::Arc { axes, center, start_radius, end_radius, start_angle, sweep } =
            self.shape
        {
            let radius = start_radius + s * (end_radius - start_radius);
            let radius_rate = end_radius - start_radius;
            let (sin, cos) = (start_angle + s * sweep).sin_cos();
            point[axes[0]] = center[0] + radius * cos;
            point[axes[1]] = center[1] + radius * sin;
            derivative[axes[0]] = radius_rate * cos - radius * sweep * sin;
            derivative[axes[1]] = radius_rate * sin + radius * sweep * cos;
            let (twice, square) = (2.0 * radius_rate * sweep, radius * sweep * sweep);
            second[axes[0]] = -twice * sin - square * cos;
            second[axes[1]] = twice * cos - square * sin;
        } else if let Shape::Fillet { center, radial, across, sweep } = self.shape {
            let (sin, cos) = (s * sweep).sin_cos();
            for k in 0..3 {
                let out = cos * radial[k] + sin * across[k];
                point[k] = center[k] + out;
                derivative[k] = sweep * (cos * across[k] - sin * radial[k]);
                second[k] = -sweep * sweep * out;
            }
        }
        if s >= 1.0 {
            point = self.end;
        }
        [point, derivative, second]
    }

    /// The distance from `point`'s XYZ to this move's XYZ path, mm (for tests and checks).
    pub fn distance_to(&self, point: [f64; 3]) -> f64 {
        match self.shape {
            Shape::Line => {
                let start = [self.start[0], self.start[1], self.start[2]];
                let [dx, dy, dz, _] = self.delta();
                let direction = [dx, dy, dz];
                let length2: f64 = direction.iter().map(|d| d * d).sum();
                let along = if length2 == 0.0 {
                    0.0
                } else {
                    (0..3).map(|i| (point[i] - start[i]) * direction[i]).sum::<f64>() / length2
                };
                let along = along.clamp(0.0, 1.0);
                (0..3)
                    .map(|i| (point[i] - start[i] - along * direction[i]).powi(2))
                    .sum::<f64>()
                    .sqrt()
            }
            Shape::Arc { .. } | Shape::Fillet { .. } => {
                // The nearest point of a helix has no closed form; search s finely, then refine.
                let distance = |s: f64| {
                    let p = self.point(s);
                    (0..3).map(|i| (point[i] - p[i]).powi(2)).sum::<f64>().sqrt()
                };
                let steps = 2000;
                let mut best = (0.0, distance(0.0));
                for k in 1..=steps {
                    let s = f64::from(k) / f64::from(steps);
                    let d = distance(s);
                    if d < best.1 {
                        best = (s, d);
                    }
                }
                let (mut low, mut high) =
                    ((best.0 - 1.0 / 2000.0).max(0.0), (best.0 + 1.0 / 2000.0).min(1.0));
                for _ in 0..100 {
                    let (a, b) = (low + (high - low) / 3.0, high - (high - low) / 3.0);
                    if distance(a) < distance(b) {
                        high = b;
                    } else {
                        low = a;
                    }
                }
                distance(0.5 * (low + high)).min(best.1)
            }
        }
    }

    fn delta(&self) -> [f64; 4] {
        [
            self.end[0] - self.start[0],
            self.end[1] - self.start[1],
            self.end[2] - self.start[2],
            self.end[3] - self.start[3],
        ]
    }
}

fn same_point(a: [f64; 2], b: [f64; 2]) -> bool {
    (a[0] - b[0]).hypot(a[1] - b[1]) < 1e-9
}

#[cfg(test)]
mod tests {
    use approx::assert_relative_eq;

    use super::*;

    /// A spiral helix in the XZ plane (two turns, its end off the start's radius) and a line
    /// moving every axis: the moves the derivative tests run on.
    fn spiral_and_line() -> [Segment; 2] {
        let spiral = Segment::arc(
            [10.0, 1.0, 0.0, 5.0],
            [0.0, 3.0, 10.5, 30.0],
            [0.0, 0.0],
            Plane::Xz,
            false,
            2,
        );
        [spiral, Segment::line([1.0, 2.0, 3.0, 4.0], [-5.0, 7.0, 1.0, 0.0])]
    }

    #[test]
    fn quarter_circles_in_both_directions() {
        let start = [10.0, 0.0, 0.0, 0.0];
        let end = [0.0, 10.0, 0.0, 90.0];
        let ccw = Segment::arc(start, end, [0.0, 0.0], Plane::Xy, false, 1);
        assert_relative_eq!(ccw.length(), 10.0 * std::f64::consts::FRAC_PI_2, epsilon = 1e-12);
        let middle = ccw.point(0.5);
        assert_relative_eq!(middle[0], 10.0 * 0.5f64.sqrt(), epsilon = 1e-12);
        assert_relative_eq!(middle[1], 10.0 * 0.5f64.sqrt(), epsilon = 1e-12);
        assert_relative_eq!(middle[3], 45.0);
        let cw = Segment::arc(start, end, [0.0, 0.0], Plane::Xy, true, 1);
        assert_relative_eq!(cw.length(), 10.0 * 1.5 * std::f64::consts::PI, epsilon = 1e-12);
        assert_relative_eq!(cw.point(1.0 / 3.0)[1], -10.0, epsilon = 1e-12);
        assert_eq!(cw.point(1.0), end);
    }

    #[test]
    fn full_circle_with_turns_and_helix() {
        let start = [10.0, 0.0, 0.0, 0.0];
        let end = [10.0, 0.0, 6.0, 0.0];
        let helix = Segment::arc(start, end, [0.0, 0.0], Plane::Xy, false, 2);
        let around = 2.0 * TAU * 10.0;
        assert_relative_eq!(helix.length(), around.hypot(6.0), epsilon = 1e-9);
        let quarter = helix.point(0.125);
        assert_relative_eq!(quarter[0], 0.0, epsilon = 1e-9);
        assert_relative_eq!(quarter[1], 10.0, epsilon = 1e-9);
        assert_relative_eq!(quarter[2], 0.75, epsilon = 1e-12);
    }

    #[test]
    fn other_planes_use_their_canonical_axes() {
        // XZ plane: centre [z, x]; G3 is counter-clockwise about +Y, from +Z toward +X.
        let start = [0.0, 5.0, 10.0, 0.0];
        let end = [10.0, 5.0, 0.0, 0.0];
        let arc = Segment::arc(start, end, [0.0, 0.0], Plane::Xz, false, 1);
        assert_relative_eq!(arc.length(), 10.0 * std::f64::consts::FRAC_PI_2, epsilon = 1e-12);
        let middle = arc.point(0.5);
        assert_relative_eq!(middle[0], 10.0 * 0.5f64.sqrt(), epsilon = 1e-12);
        assert_relative_eq!(middle[2], 10.0 * 0.5f64.sqrt(), epsilon = 1e-12);
        assert_relative_eq!(middle[1], 5.0);
    }

    #[test]
    fn derivative_matches_finite_differences() {
        let arc = Segment::arc(
            [10.0, 0.0, 0.0, 0.0],
            [0.0, 10.5, 4.0, 30.0],
            [0.0, 0.0],
            Plane::Xy,
            true,
            1,
        );
        let h = 1e-6;
        for s in [0.1, 0.5, 0.9] {
            let (after, before) = (arc.point(s + h), arc.point(s - h));
            let derivative = arc.derivative(s);
            for axis in 0..4 {
                assert_relative_eq!(
                    derivative[axis],
                    (after[axis] - before[axis]) / (2.0 * h),
                    epsilon = 1e-4
                );
            }
        }
    }

    /// `derivatives` agrees with `point` and `derivative`, and its second derivative with their
    /// differences, on a spiral helix in a plane other than XY and on a line.
    #[test]
    fn second_derivative_matches_finite_differences() {
        let [spiral, line] = spiral_and_line();
        let h = 1e-5;
        for segment in [spiral, line] {
            for s in [0.0, 0.1, 0.5, 0.9, 1.0] {
                let [point, first, second] = segment.derivatives(s);
                let (after, before) = (segment.derivative(s + h), segment.derivative(s - h));
                for axis in 0..4 {
                    assert_relative_eq!(point[axis], segment.point(s)[axis], epsilon = 1e-12);
                    assert_relative_eq!(first[axis], segment.derivative(s)[axis], epsilon = 1e-12);
                    let expected = (after[axis] - before[axis]) / (2.0 * h);
                    assert_relative_eq!(
                        second[axis],
                        expected,
                        epsilon = 1e-4,
                        max_relative = 1e-6
                    );
                }
            }
        }
    }

    /// A part of a move runs along the move: its points, derivatives along the length and
    /// ends are the move's at the matching parameters.
    #[test]
    fn parts_follow_the_move() {
        let [spiral, line] = spiral_and_line();
        let fillet = Segment::fillet(
            [1.0, 0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0, 0.0],
            [0.0; 3],
            [0.0, 1.0, 0.0],
            1.5,
        );
        for segment in [spiral, line, fillet] {
            let (from, to) = (0.2, 0.7);
            let part = segment.part(from, to);
            assert_eq!(part.start(), segment.point(from));
            assert_eq!(part.end(), segment.point(to));
            // (A spiral's length uses its mean radius: its part's is near, not equal.)
            assert_relative_eq!(part.length(), (to - from) * segment.length(), max_relative = 1e-2);
            for u in [0.0, 0.3, 0.5, 1.0] {
                let s = from + u * (to - from);
                let (here, whole) = (part.point(u), segment.point(s));
                let (slope, whole_slope) = (part.derivative(u), segment.derivative(s));
                for axis in 0..4 {
                    assert_relative_eq!(here[axis], whole[axis], epsilon = 1e-9);
                    // d/du of the part is (to − from) × d/ds of the move.
                    assert_relative_eq!(
                        slope[axis],
                        (to - from) * whole_slope[axis],
                        epsilon = 1e-9
                    );
                }
            }
            // A part to the end ends exactly there, a part from 0 starts exactly at the start.
            assert_eq!(segment.part(0.4, 1.0).end(), segment.end());
            assert_eq!(segment.part(0.0, 0.4).start(), segment.start());
        }
    }

    #[test]
    fn only_planar_circular_arcs_have_a_circle() {
        let start = [10.0, 0.0, 3.0, 0.0];
        let quarter = Segment::arc(start, [0.0, 10.0, 3.0, 0.0], [0.0, 0.0], Plane::Xy, true, 1);
        let circle = quarter.circle().expect("a circle");
        assert_eq!((circle.axes, circle.center, circle.radius), ([0, 1, 2], [0.0, 0.0], 10.0));
        assert_eq!(circle.end_radius, 10.0);
        assert_relative_eq!(circle.sweep, -1.5 * std::f64::consts::PI, epsilon = 1e-12);
        let helix = Segment::arc(start, [0.0, 10.0, 4.0, 0.0], [0.0, 0.0], Plane::Xy, false, 1);
        let spiral = Segment::arc(start, [0.0, 10.1, 3.0, 0.0], [0.0, 0.0], Plane::Xy, false, 1);
        let line = Segment::line(start, [0.0; 4]);
        assert!(helix.circle().is_none() && spiral.circle().is_none() && line.circle().is_none());
        let axes = |segment: Segment| segment.planar_arc().map(|arc| arc.axes);
        assert_eq!((axes(quarter), axes(spiral)), (Some([0, 1, 2]), Some([0, 1, 2])));
        assert_eq!((axes(helix), axes(line)), (None, None));
        assert!((spiral.planar_arc().unwrap().end_radius - 10.1).abs() < 1e-12);
    }

    #[test]
    fn distance_to_the_path() {
        let line = Segment::line([0.0, 0.0, 0.0, 0.0], [10.0, 0.0, 0.0, 0.0]);
        assert_relative_eq!(line.distance_to([5.0, 3.0, 0.0]), 3.0);
        assert_relative_eq!(line.distance_to([-4.0, 3.0, 0.0]), 5.0);
        let arc = Segment::arc(
            [10.0, 0.0, 0.0, 0.0],
            [0.0, 10.0, 0.0, 0.0],
            [0.0, 0.0],
            Plane::Xy,
            false,
            1,
        );
        assert_relative_eq!(arc.distance_to([0.0, 12.0, 0.0]), 2.0, epsilon = 1e-9);
        assert!(arc.distance_to(arc.point(0.37)[..3].try_into().unwrap()) < 1e-9);
    }
}
