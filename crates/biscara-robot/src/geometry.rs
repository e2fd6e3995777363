//! Distances between the primitives the collision tests need: points, segments and
//! axis-aligned rectangles in the plane.

use nalgebra as na;

type P2 = na::Point2<f64>;

/// An axis-aligned rectangle in the XY plane, millimetres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Rect {
    pub(crate) min: P2,
    pub(crate) max: P2,
}

impl Rect {
    fn contains(&self, p: &P2) -> bool {
        (self.min.x..=self.max.x).contains(&p.x) && (self.min.y..=self.max.y).contains(&p.y)
    }

    fn corners(&self) -> [P2; 4] {
        [self.min, P2::new(self.max.x, self.min.y), self.max, P2::new(self.min.x, self.max.y)]
    }
}

/// Distance from `p` to the segment `a`–`b`.
pub(crate) fn point_segment(p: &P2, a: &P2, b: &P2) -> f64 {
    let ab = b - a;
    let length2 = ab.norm_squared();
    let along = if length2 == 0.0 { 0.0 } else { ((p - a).dot(&ab) / length2).clamp(0.0, 1.0) };
    (p - (a + along * ab)).norm()
}

/// `(b − a) × (c − a)`: positive when `c` lies left of the line `a → b`.
fn orient(a: &P2, b: &P2, c: &P2) -> f64 {
    (b - a).perp(&(c - a))
}

fn on_segment(p: &P2, a: &P2, b: &P2) -> bool {
    p.x >= a.x.min(b.x) && p.x <= a.x.max(b.x) && p.y >= a.y.min(b.y) && p.y <= a.y.max(b.y)
}

/// Whether the closed segments `a0`–`a1` and `b0`–`b1` share a point.
pub(crate) fn segments_intersect(a0: &P2, a1: &P2, b0: &P2, b1: &P2) -> bool {
    let d1 = orient(b0, b1, a0);
    let d2 = orient(b0, b1, a1);
    let d3 = orient(a0, a1, b0);
    let d4 = orient(a0, a1, b1);
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
        && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
    {
        return true;
    }
    (d1 == 0.0 && on_segment(a0, b0, b1))
        || (d2 == 0.0 && on_segment(a1, b0, b1))
        || (d3 == 0.0 && on_segment(b0, a0, a1))
        || (d4 == 0.0 && on_segment(b1, a0, a1))
}

/// Distance between the segments `a0`–`a1` and `b0`–`b1` (0 when they meet).
pub(crate) fn segment_segment(a0: &P2, a1: &P2, b0: &P2, b1: &P2) -> f64 {
    if segments_intersect(a0, a1, b0, b1) {
        return 0.0;
    }
    point_segment(a0, b0, b1)
        .min(point_segment(a1, b0, b1))
        .min(point_segment(b0, a0, a1))
        .min(point_segment(b1, a0, a1))
}

/// Distance from `p` to the rectangle (0 inside it).
pub(crate) fn point_rect(p: &P2, rect: &Rect) -> f64 {
    let dx = (rect.min.x - p.x).max(p.x - rect.max.x).max(0.0);
    let dy = (rect.min.y - p.y).max(p.y - rect.max.y).max(0.0);
    dx.hypot(dy)
}

/// Distance from the segment `a`–`b` to the rectangle (0 when they meet).
pub(crate) fn segment_rect(a: &P2, b: &P2, rect: &Rect) -> f64 {
    if rect.contains(a) || rect.contains(b) {
        return 0.0;
    }
    let corners = rect.corners();
    let mut best = f64::INFINITY;
    for k in 0..4 {
        let (c0, c1) = (corners[k], corners[(k + 1) % 4]);
        best = best.min(segment_segment(a, b, &c0, &c1));
    }
    best
}

/// Length of the gap between the intervals `[a0, a1]` and `[b0, b1]` (0 when they overlap).
pub(crate) fn interval_gap(a0: f64, a1: f64, b0: f64, b1: f64) -> f64 {
    (b0 - a1).max(a0 - b1).max(0.0)
}

#[cfg(test)]
mod tests {
    use approx::assert_relative_eq;

    use super::*;

    fn p(x: f64, y: f64) -> P2 {
        P2::new(x, y)
    }

    #[test]
    fn point_to_segment() {
        assert_relative_eq!(point_segment(&p(0.0, 1.0), &p(-1.0, 0.0), &p(1.0, 0.0)), 1.0);
        assert_relative_eq!(point_segment(&p(3.0, 4.0), &p(-1.0, 0.0), &p(0.0, 0.0)), 5.0);
        assert_relative_eq!(point_segment(&p(3.0, 4.0), &p(0.0, 0.0), &p(0.0, 0.0)), 5.0);
    }

    #[test]
    fn segment_to_segment() {
        // Crossing.
        assert_eq!(segment_segment(&p(-1.0, 0.0), &p(1.0, 0.0), &p(0.0, -1.0), &p(0.0, 1.0)), 0.0);
        // Touching at an end.
        assert_eq!(segment_segment(&p(0.0, 0.0), &p(1.0, 0.0), &p(1.0, 0.0), &p(1.0, 5.0)), 0.0);
        // Parallel, 2 apart.
        assert_relative_eq!(
            segment_segment(&p(0.0, 0.0), &p(4.0, 0.0), &p(1.0, 2.0), &p(3.0, 2.0)),
            2.0
        );
        // A T that does not reach.
        assert_relative_eq!(
            segment_segment(&p(-1.0, 0.0), &p(1.0, 0.0), &p(0.0, 0.5), &p(0.0, 3.0)),
            0.5
        );
        // Collinear, apart.
        assert_relative_eq!(
            segment_segment(&p(0.0, 0.0), &p(1.0, 0.0), &p(3.0, 0.0), &p(4.0, 0.0)),
            2.0
        );
    }

    #[test]
    fn segment_to_rectangle() {
        let rect = Rect { min: p(0.0, 0.0), max: p(10.0, 5.0) };
        assert_eq!(segment_rect(&p(-5.0, 2.0), &p(15.0, 2.0), &rect), 0.0); // passes through
        assert_eq!(segment_rect(&p(1.0, 1.0), &p(2.0, 2.0), &rect), 0.0); // inside
        assert_relative_eq!(segment_rect(&p(-5.0, 7.0), &p(15.0, 7.0), &rect), 2.0); // above
        assert_relative_eq!(segment_rect(&p(13.0, 9.0), &p(20.0, 9.0), &rect), 5.0); // corner
        assert_relative_eq!(point_rect(&p(13.0, 9.0), &rect), 5.0);
        assert_eq!(point_rect(&p(3.0, 3.0), &rect), 0.0);
    }

    #[test]
    fn gaps_between_intervals() {
        assert_eq!(interval_gap(0.0, 1.0, 0.5, 3.0), 0.0);
        assert_eq!(interval_gap(0.0, 1.0, 3.0, 4.0), 2.0);
        assert_eq!(interval_gap(5.0, 6.0, 3.0, 4.0), 1.0);
    }
}
