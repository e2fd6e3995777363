//! The pieces of a blended path.

use biscara_motion::{Feed, Segment};

/// How fast a piece may go: the programmed feed, or the rapid limits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Speed {
    /// A G0 move (or a fillet between two of them): the rapid limits.
    Rapid,
    /// A feed move (or a fillet touching one): this feed along the XYZ path.
    Feed(Feed),
}

impl Speed {
    /// The slower of two: a feed over a rapid, the lower of two feeds.
    pub fn slower(self, other: Speed) -> Speed {
        match (self, other) {
            (Speed::Rapid, other) => other,
            (this, Speed::Rapid) => this,
            (Speed::Feed(a), Speed::Feed(b)) => {
                Speed::Feed(if b.mm_per_min < a.mm_per_min { b } else { a })
            }
        }
    }
}

/// The shape of a piece.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Geometry {
    /// A straight piece from `start` to `end` (`[x, y, z, c]`, mm and degrees).
    Line {
        /// Start pose.
        start: [f64; 4],
        /// End pose.
        end: [f64; 4],
    },
    /// A circular fillet: from `start`, leaving along the unit vector `tangent`, turning by
    /// `sweep` radians about `center` with radius `radius`, to `end`; C goes linearly.
    Fillet {
        /// Start pose.
        start: [f64; 4],
        /// End pose.
        end: [f64; 4],
        /// Centre of the circle, mm.
        center: [f64; 3],
        /// Radius, mm.
        radius: f64,
        /// Unit tangent at the start.
        tangent: [f64; 3],
        /// Angle swept, radians, in (0, π].
        sweep: f64,
    },
    /// A programmed arc (G2/G3, helical or not), or the part of it a corner's fillets leave
    /// (same centre and radius, a shorter sweep): it joins a chain where its ends are tangent
    /// to its neighbours or blended with them.
    Arc(Segment),
}

/// One piece of a blended chain.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Piece {
    /// 1-based line of the move this piece comes from (for a fillet: the move whose end it cuts).
    pub line: usize,
    /// Its shape.
    pub geometry: Geometry,
    /// Its speed limit.
    pub speed: Speed,
    /// Whether the chain ends (the robot stops) at the end of this piece.
    pub ends_chain: bool,
}

pub(crate) fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

pub(crate) fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub(crate) fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

/// `a` scaled to unit length.
pub(crate) fn unit(a: [f64; 3]) -> [f64; 3] {
    let n = norm(a);
    [a[0] / n, a[1] / n, a[2] / n]
}

pub(crate) fn xyz(pose: [f64; 4]) -> [f64; 3] {
    [pose[0], pose[1], pose[2]]
}

impl Piece {
    /// Start pose.
    pub fn start(&self) -> [f64; 4] {
        match self.geometry {
            Geometry::Line { start, .. } | Geometry::Fillet { start, .. } => start,
            Geometry::Arc(segment) => segment.start(),
        }
    }

    /// End pose.
    pub fn end(&self) -> [f64; 4] {
        match self.geometry {
            Geometry::Line { end, .. } | Geometry::Fillet { end, .. } => end,
            Geometry::Arc(segment) => segment.end(),
        }
    }

    /// The radius of a fillet, or the smallest radius of an arc in its plane, mm; `None` for a
    /// straight piece.
    pub fn radius(&self) -> Option<f64> {
        match self.geometry {
            Geometry::Line { .. } => None,
            Geometry::Fillet { radius, .. } => Some(radius),
            Geometry::Arc(segment) => segment.radius(),
        }
    }

    /// XYZ length, mm.
    pub fn length(&self) -> f64 {
        match self.geometry {
            Geometry::Line { start, end } => norm(sub(xyz(end), xyz(start))),
            Geometry::Fillet { radius, sweep, .. } => radius * sweep,
            Geometry::Arc(segment) => segment.length(),
        }
    }

    /// The pose a fraction `u` ∈ [0, 1] of the length along.
    pub fn point(&self, u: f64) -> [f64; 4] {
        match self.geometry {
            Geometry::Line { start, end } => {
                std::array::from_fn(|k| start[k] + u * (end[k] - start[k]))
            }
            Geometry::Fillet { start, end, center, radius, tangent, sweep } => {
                let angle = u * sweep;
                let (sin, cos) = angle.sin_cos();
                let radial = sub(xyz(start), center);
                let mut pose = [0.0; 4];
                for k in 0..3 {
                    pose[k] = center[k] + cos * radial[k] + sin * radius * tangent[k];
                }
                pose[3] = start[3] + u * (end[3] - start[3]);
                pose
            }
            Geometry::Arc(segment) => segment.point(u),
        }
    }

    /// Unit XYZ tangent a fraction `u` ∈ [0, 1] of the length along.
    pub fn tangent(&self, u: f64) -> [f64; 3] {
        match self.geometry {
            Geometry::Line { start, end } => unit(sub(xyz(end), xyz(start))),
            Geometry::Fillet { start, center, radius, tangent, sweep, .. } => {
                let (sin, cos) = (u * sweep).sin_cos();
                let radial = sub(xyz(start), center);
                std::array::from_fn(|k| -sin * radial[k] / radius + cos * tangent[k])
            }
            Geometry::Arc(segment) => unit(xyz(segment.derivative(u))),
        }
    }

    /// The first and second derivatives of the pose `[x, y, z, c]` with respect to the XYZ arc
    /// length (mm) a fraction `u` ∈ [0, 1] of the length along: what a timing law needs to map
    /// a path speed and acceleration to the axes (for C, degrees per mm). On a line the second
    /// is zero; on a fillet it points to the centre with length 1/radius. The second derivative
    /// jumps where a line meets a fillet: a timing law holds its bounds on both sides there.
    pub fn derivatives(&self, u: f64) -> ([f64; 4], [f64; 4]) {
        if let Geometry::Arc(segment) = self.geometry {
            return arc_length_derivatives(&segment, u);
        }
        let length = self.length();
        let c_rate = (self.end()[3] - self.start()[3]) / length;
        let tangent = self.tangent(u);
        let mut first = [tangent[0], tangent[1], tangent[2], c_rate];
        if !c_rate.is_finite() {
            first[3] = 0.0;
        }
        let second = match self.geometry {
            Geometry::Line { .. } => [0.0; 4],
            Geometry::Fillet { start, center, radius, tangent, sweep, .. } => {
                let (sin, cos) = (u * sweep).sin_cos();
                let radial = sub(xyz(start), center);
                let mut second = [0.0; 4];
                for k in 0..3 {
                    second[k] = (-cos * radial[k] / radius - sin * tangent[k]) / radius;
                }
                second
            }
            Geometry::Arc(_) => unreachable!("arcs are differentiated above"),
        };
        (first, second)
    }
}

/// The first and second derivatives of an arc's pose with respect to its XYZ arc length, from
/// those with respect to its parameter (`p′`, `p″`): `p′/|p′|` and `(p″ − (p″·t) t)/|p′|²` with
/// `t` the unit tangent (C's rate in proportion; its second derivative, zero along the parameter,
/// is taken as zero along the length).
fn arc_length_derivatives(segment: &Segment, u: f64) -> ([f64; 4], [f64; 4]) {
    let [_, d1, d2] = segment.derivatives(u);
    let speed = norm(xyz(d1));
    let tangent: [f64; 3] = std::array::from_fn(|k| d1[k] / speed);
    let along = dot(xyz(d2), tangent);
    let mut first = [tangent[0], tangent[1], tangent[2], d1[3] / speed];
    if !first[3].is_finite() {
        first[3] = 0.0;
    }
    let mut second = [0.0; 4];
    for k in 0..3 {
        second[k] = (d2[k] - along * tangent[k]) / (speed * speed);
    }
    (first, second)
}
