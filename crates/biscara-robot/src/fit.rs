//! A program's XY extent and the offset that places it in the workspace rectangle (`--fit`).

use std::f64::consts::FRAC_PI_2;

use biscara_interpolate::Segment;
use biscara_motion::{Motion, MotionKind, Plane};

use crate::{Rectangle, VirtualRobotError};

/// The bounding box of a program's moves: every end point, and the true extremes of arcs
/// (where the circle crosses its axes' directions), millimetres. The start pose before the first
/// move is not part of the program and is left out of the XY extent, and so are straight moves
/// that end at the start pose's XY: a CAM program's first `G0 Z…` before any X or Y word, or a
/// return home, stay at the robot's home when the program is placed (see [`place_motion`]). The
/// Z extent leaves out only moves that end exactly at the start pose (a return home).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bounds {
    /// Smallest x and y, millimetres.
    pub min: [f64; 2],
    /// Largest x and y, millimetres.
    pub max: [f64; 2],
    /// Smallest and largest z of the program's moves, millimetres (`[+∞, −∞]` when none).
    pub z: [f64; 2],
    /// The pose the next move starts from.
    current: [f64; 4],
    /// The start pose.
    home: [f64; 4],
    /// Whether any move was seen.
    any: bool,
    /// Whether a straight move ended at the start pose's XY (left out of the extent).
    at_home: bool,
    /// Whether a point at the start pose's Z was left out of the Z extent.
    at_home_z: bool,
}

impl Bounds {
    /// Empty bounds for a program starting at `start` (`[x, y, z, c]`, the robot's home pose).
    pub fn new(start: [f64; 4]) -> Bounds {
        Bounds {
            min: [f64::INFINITY; 2],
            max: [f64::NEG_INFINITY; 2],
            z: [f64::INFINITY, f64::NEG_INFINITY],
            current: start,
            home: start,
            any: false,
            at_home: false,
            at_home_z: false,
        }
    }

    /// The bounds of all moves of `motions`, from `start`.
    pub fn of<'a>(start: [f64; 4], motions: impl IntoIterator<Item = &'a Motion>) -> Bounds {
        let mut bounds = Bounds::new(start);
        for motion in motions {
            bounds.push(motion);
        }
        bounds
    }

    /// Whether at least one move was added.
    pub fn is_empty(&self) -> bool {
        !self.any
    }

    /// Width (X), millimetres.
    pub fn width(&self) -> f64 {
        self.max[0] - self.min[0]
    }

    /// Height (Y), millimetres.
    pub fn height(&self) -> f64 {
        self.max[1] - self.min[1]
    }

    /// The start pose's XY.
    pub fn home(&self) -> [f64; 2] {
        [self.home[0], self.home[1]]
    }

    /// Counts the moves that ended at the start pose's XY as part of the extent: for a program
    /// that made the start point its zero (`G92 X0 Y0`), where `X0 Y0` is a point of the part.
    pub fn include_home(&mut self) {
        if self.at_home {
            self.include_xy(self.home());
        }
    }

    /// Counts the points at the start pose's Z as part of the Z extent: for a program that made
    /// the start point's Z its zero (`G92 Z0`), where `Z0` is a height of the part.
    pub fn include_home_z(&mut self) {
        if self.at_home_z {
            self.z = [self.z[0].min(self.home[2]), self.z[1].max(self.home[2])];
        }
    }

    fn include_xy(&mut self, point: [f64; 2]) {
        for (axis, value) in point.into_iter().enumerate() {
            self.min[axis] = self.min[axis].min(value);
            self.max[axis] = self.max[axis].max(value);
        }
        self.any = true;
    }

    fn include(&mut self, point: [f64; 4]) {
        self.include_xy([point[0], point[1]]);
        self.include_z(point);
    }

    fn include_z(&mut self, point: [f64; 4]) {
        if point[2] == self.home[2] {
            self.at_home_z = true;
        } else {
            self.z = [self.z[0].min(point[2]), self.z[1].max(point[2])];
        }
    }

    /// Adds one motion (events are ignored).
    pub fn push(&mut self, motion: &Motion) {
        let start = self.current;
        match motion.kind {
            MotionKind::Rapid { end } | MotionKind::Linear { end, .. } => {
                if at_home(end, self.home()) {
                    self.at_home = true;
                    self.include_z(end);
                } else {
                    self.include(end);
                }
            }
            MotionKind::Arc { end, center, plane, clockwise, turns, .. } => {
                let segment = Segment::arc(start, end, center, plane, clockwise, turns);
                for quarter in 0..4 {
                    for s in segment.parameters_at_angle(f64::from(quarter) * FRAC_PI_2) {
                        self.include(segment.point(s));
                    }
                }
                self.include(end);
            }
            _ => return,
        }
        if let Some(end) = motion.kind.end() {
            self.current = end;
        }
    }

    /// The XY extent of the program turned by +90° about the start pose's XY.
    fn rotated(&self) -> ([f64; 2], [f64; 2]) {
        let [hx, hy] = self.home();
        let min = [hx - (self.max[1] - hy), hy + (self.min[0] - hx)];
        let max = [hx - (self.min[1] - hy), hy + (self.max[0] - hx)];
        (min, max)
    }
}

/// Where a program goes when placed in the workspace rectangle: first turned by +90° about the
/// start pose's XY when `rotated`, then moved by `offset`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fit {
    /// The XY offset to add to every position after the turn, millimetres.
    pub offset: [f64; 2],
    /// Whether the program is turned by +90° (counter-clockwise seen from above) about the
    /// start pose's XY: only when it fits the rectangle that way and not as programmed.
    pub rotated: bool,
    /// The program's bounds before the turn and the shift.
    pub bounds: Bounds,
    /// The rectangle it was centred in.
    pub rectangle: Rectangle,
}

impl Fit {
    /// The placement as a transform of motions, with no Z shift.
    pub fn transform(&self) -> Transform {
        Transform {
            home: self.bounds.home(),
            rotated: self.rotated,
            offset: [self.offset[0], self.offset[1], 0.0],
        }
    }
}

/// The offset that centres `bounds` in `rectangle` (docs/gcode.md `--fit`), turning the program by
/// 90° about Z only when it fits that way and not as programmed; fails when it fits neither
/// way, saying by how much in each orientation.
pub fn fit(bounds: &Bounds, rectangle: &Rectangle) -> Result<Fit, VirtualRobotError> {
    if bounds.is_empty() {
        return Err(VirtualRobotError::NoMoves);
    }
    let (width, height) = (bounds.width(), bounds.height());
    // Tolerate rounding: a program exactly as wide as the rectangle fits.
    const TOLERANCE_MM: f64 = 1e-9;
    let fits = |w: f64, h: f64| {
        w <= rectangle.width() + TOLERANCE_MM && h <= rectangle.height() + TOLERANCE_MM
    };
    let center = rectangle.center();
    let centred = |min: [f64; 2], max: [f64; 2]| {
        [center[0] - 0.5 * (min[0] + max[0]), center[1] - 0.5 * (min[1] + max[1])]
    };
    if fits(width, height) {
        let offset = centred(bounds.min, bounds.max);
        return Ok(Fit { offset, rotated: false, bounds: *bounds, rectangle: *rectangle });
    }
    if fits(height, width) {
        let (min, max) = bounds.rotated();
        let offset = centred(min, max);
        return Ok(Fit { offset, rotated: true, bounds: *bounds, rectangle: *rectangle });
    }
    Err(VirtualRobotError::DoesNotFit {
        width_mm: width,
        height_mm: height,
        rect_width_mm: rectangle.width(),
        rect_height_mm: rectangle.height(),
    })
}

fn at_home(end: [f64; 4], home: [f64; 2]) -> bool {
    end[0] == home[0] && end[1] == home[1]
}

/// A placement of motions: a turn by +90° about `home`'s XY (when `rotated`; C turns with the
/// program), then a shift by `offset` (`[x, y, z]`, mm). Straight moves that end exactly at
/// `home` stay there, as a G-code program's moves without X and Y words do when its origin
/// moves; they are not part of the program's [`Bounds`] either.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Transform {
    /// The start pose's XY, the centre of the turn, mm.
    pub home: [f64; 2],
    /// Whether to turn by +90°.
    pub rotated: bool,
    /// The shift after the turn, `[x, y, z]`, mm.
    pub offset: [f64; 3],
}

impl Transform {
    /// Whether the transform changes nothing.
    pub fn is_identity(&self) -> bool {
        !self.rotated && self.offset == [0.0; 3]
    }

    /// The turn of `point` (`[x, y]`) about `home`.
    fn turn(&self, [x, y]: [f64; 2]) -> [f64; 2] {
        if self.rotated {
            let [hx, hy] = self.home;
            [hx - (y - hy), hy + (x - hx)]
        } else {
            [x, y]
        }
    }

    /// The position moved: turned, then shifted; C turned with the program.
    pub fn position(&self, [x, y, z, c]: [f64; 4]) -> [f64; 4] {
        let [x, y] = self.turn([x, y]);
        let c = if self.rotated { c + 90.0 } else { c };
        [x + self.offset[0], y + self.offset[1], z + self.offset[2], c]
    }

    /// The inverse turn of an XY vector: what to shift a program by before the turn so that it
    /// ends up shifted by `vector` after it (`R⁻¹ v`).
    pub fn unturn_vector(&self, [x, y]: [f64; 2]) -> [f64; 2] {
        if self.rotated { [y, -x] } else { [x, y] }
    }

    /// `motion` placed (see [`Transform`]).
    pub fn motion(&self, motion: Motion) -> Motion {
        let kind = match motion.kind {
            MotionKind::Rapid { end } | MotionKind::Linear { end, .. }
                if at_home(end, self.home) =>
            {
                motion.kind
            }
            MotionKind::Rapid { end } => MotionKind::Rapid { end: self.position(end) },
            MotionKind::Linear { end, feed } => {
                MotionKind::Linear { end: self.position(end), feed }
            }
            MotionKind::Arc { end, center, plane, clockwise, turns, feed } => {
                let [dx, dy, dz] = self.offset;
                let (center, plane, clockwise) = match (plane, self.rotated) {
                    (Plane::Xy, _) => {
                        let [x, y] = self.turn(center);
                        ([x + dx, y + dy], plane, clockwise)
                    }
                    // The centre is in the plane's axes: xz → (z, x), yz → (y, z).
                    (Plane::Xz, false) => ([center[0] + dz, center[1] + dx], plane, clockwise),
                    (Plane::Yz, false) => ([center[0] + dy, center[1] + dz], plane, clockwise),
                    // Turned by +90°: x → y, so an XZ arc (normal +Y) becomes a YZ arc whose
                    // normal is −X: seen from +X it turns the other way.
                    (Plane::Xz, true) => {
                        let [_, y] = self.turn([center[1], 0.0]);
                        ([y + dy, center[0] + dz], Plane::Yz, !clockwise)
                    }
                    // y → −x: a YZ arc (normal +X) becomes an XZ arc with normal +Y.
                    (Plane::Yz, true) => {
                        let [x, _] = self.turn([0.0, center[0]]);
                        ([center[1] + dz, x + dx], Plane::Xz, clockwise)
                    }
                };
                MotionKind::Arc { end: self.position(end), center, plane, clockwise, turns, feed }
            }
            other => other,
        };
        Motion { kind, ..motion }
    }
}

/// `motion` moved by `offset` in X and Y (end points and arc centres; z and c unchanged).
/// Straight moves that end exactly at `home`'s XY (the robot's home pose) stay there, as a
/// G-code program's moves without X and Y words do when its origin moves; they are not part of
/// the program's [`Bounds`] either.
pub fn shift_motion(motion: Motion, offset: [f64; 2], home: [f64; 2]) -> Motion {
    Transform { home, rotated: false, offset: [offset[0], offset[1], 0.0] }.motion(motion)
}

/// `motion` placed by `transform` (see [`Transform`]).
pub fn place_motion(motion: Motion, transform: &Transform) -> Motion {
    transform.motion(motion)
}

#[cfg(test)]
mod tests {
    use approx::assert_relative_eq;
    use biscara_motion::Feed;

    use super::*;

    const HOME: [f64; 4] = [0.0, 460.0, 100.0, 0.0];
    const FEED: Feed = Feed { mm_per_min: 600.0, inverse_time: false };

    fn linear(line: usize, end: [f64; 4]) -> Motion {
        Motion::new(line, MotionKind::Linear { end, feed: FEED })
    }

    fn arc(line: usize, end: [f64; 4], center: [f64; 2], clockwise: bool) -> Motion {
        Motion {
            line,
            kind: MotionKind::Arc {
                end,
                center,
                plane: Plane::Xy,
                clockwise,
                turns: 1,
                feed: FEED,
            },
            extrude: None,
            blend: None,
            naive_cam: None,
        }
    }

    #[test]
    fn bounds_of_lines_leave_out_the_start_and_moves_at_home() {
        let home = [0.0, 460.0, 100.0, 0.0];
        let motions = [
            linear(1, [0.0, 460.0, 5.0, 0.0]), // G0 Z5 before any X or Y word
            linear(2, [10.0, 20.0, 0.0, 0.0]),
            linear(3, [-5.0, 30.0, 0.0, 0.0]),
        ];
        let bounds = Bounds::of(home, &motions);
        assert_eq!((bounds.min, bounds.max), ([-5.0, 20.0], [10.0, 30.0]));
        let shifted = shift_motion(motions[0], [1.0, 2.0], [0.0, 460.0]);
        assert_eq!(shifted, motions[0]);
        assert_eq!(
            shift_motion(motions[1], [1.0, 2.0], [0.0, 460.0]).kind.end(),
            Some([11.0, 22.0, 0.0, 0.0])
        );
    }

    #[test]
    fn arcs_count_with_their_true_extent() {
        // A counter-clockwise half circle of radius 10 about the origin from (10, 0) to (−10, 0)
        // passes (0, 10); the clockwise one passes (0, −10). A full circle covers all four.
        let start = linear(1, [10.0, 0.0, 0.0, 0.0]);
        let ccw = Bounds::of([0.0; 4], &[start, arc(2, [-10.0, 0.0, 0.0, 0.0], [0.0, 0.0], false)]);
        assert_relative_eq!(ccw.max[1], 10.0, epsilon = 1e-12);
        assert_relative_eq!(ccw.min[1], 0.0, epsilon = 1e-12);
        let cw = Bounds::of([0.0; 4], &[start, arc(2, [-10.0, 0.0, 0.0, 0.0], [0.0, 0.0], true)]);
        assert_relative_eq!(cw.min[1], -10.0, epsilon = 1e-12);
        assert_relative_eq!(cw.max[1], 0.0, epsilon = 1e-12);
        let full = Bounds::of([0.0; 4], &[start, arc(2, [10.0, 0.0, 0.0, 0.0], [0.0, 0.0], true)]);
        assert_relative_eq!(full.min[0], -10.0, epsilon = 1e-12);
        assert_relative_eq!(full.max[1], 10.0, epsilon = 1e-12);
        assert_relative_eq!(full.min[1], -10.0, epsilon = 1e-12);
    }

    #[test]
    fn fit_centres_or_says_by_how_much_it_misses() {
        let rectangle = Rectangle { min: [-100.0, 200.0], max: [100.0, 300.0] };
        let motions = [linear(1, [0.0, 0.0, 5.0, 0.0]), linear(2, [150.0, 80.0, 5.0, 0.0])];
        let bounds = Bounds::of(HOME, &motions);
        let placed = fit(&bounds, &rectangle).unwrap();
        assert_eq!(placed.offset, [-75.0, 210.0]);
        let shifted: Vec<_> =
            motions.iter().map(|m| shift_motion(*m, placed.offset, [0.0, 460.0])).collect();
        let after = Bounds::of(HOME, &shifted);
        assert_eq!((after.min, after.max), ([-75.0, 210.0], [75.0, 290.0]));
        let wide = Bounds::of(HOME, &[linear(1, [0.0; 4]), linear(2, [230.0, 120.0, 0.0, 0.0])]);
        let err = fit(&wide, &rectangle).unwrap_err();
        assert_eq!(
            err.to_string(),
            "the program's XY extent 230.000 x 120.000 mm does not fit the workspace rectangle \
             200.000 x 100.000 mm: as programmed, 30.000 mm too wide in X and 20.000 mm too tall \
             in Y; turned by 90° about Z, 130.000 mm too tall in Y"
        );
        assert_eq!(
            fit(&Bounds::new([0.0; 4]), &rectangle).unwrap_err(),
            VirtualRobotError::NoMoves
        );
        // Found on a resin printer's program (NovaMaker): it only lifts and lowers Z, which
        // moves nowhere in XY, and the error says so instead of "no move".
        let lifts = [linear(1, [0.0, 0.0, 4.0, 0.0]), linear(2, [0.0, 0.0, 0.05, 0.0])];
        let err = fit(&Bounds::of([0.0; 4], &lifts), &rectangle).unwrap_err();
        assert_eq!(err, VirtualRobotError::NoMoves);
        assert!(err.to_string().contains("no move in X or Y away from its start"), "{err}");
    }

    #[test]
    fn shifted_arcs_keep_their_shape() {
        let motions = [
            linear(1, [10.0, 0.0, 0.0, 0.0]),
            arc(2, [-10.0, 0.0, 0.0, 0.0], [0.0, 0.0], false),
            Motion {
                line: 3,
                kind: MotionKind::Arc {
                    end: [-10.0, 0.0, 20.0, 0.0],
                    center: [10.0, -10.0],
                    plane: Plane::Xz,
                    clockwise: false,
                    turns: 1,
                    feed: FEED,
                },
                extrude: None,
                blend: None,
                naive_cam: None,
            },
        ];
        let offset = [3.0, 4.0];
        let shifted: Vec<_> =
            motions.iter().map(|m| shift_motion(*m, offset, [0.0, 460.0])).collect();
        let (a, b) = (Bounds::of([0.0; 4], &motions), Bounds::of([0.0; 4], &shifted));
        for (axis, shift) in offset.into_iter().enumerate() {
            assert_relative_eq!(b.min[axis], a.min[axis] + shift, epsilon = 1e-9);
            assert_relative_eq!(b.max[axis], a.max[axis] + shift, epsilon = 1e-9);
        }
    }

    #[test]
    fn turned_arcs_in_every_plane_are_the_turned_curves() {
        // Each arc's points, turned and shifted, are the points of the turned arc.
        let transform = Transform { home: [5.0, 460.0], rotated: true, offset: [7.0, -3.0, 2.0] };
        let start = [10.0, 2.0, 3.0, 0.0];
        for (plane, center, end) in [
            (Plane::Xy, [4.0, 6.0], [0.0, 10.0, 3.0, 20.0]),
            (Plane::Xz, [1.0, 4.0], [0.0, 2.0, -1.0, 20.0]),
            (Plane::Yz, [5.0, 1.0], [10.0, 8.0, 1.0, 20.0]),
        ] {
            for clockwise in [true, false] {
                let motion = arc(1, end, center, clockwise);
                let motion = Motion {
                    kind: match motion.kind {
                        MotionKind::Arc { end, center, clockwise, turns, feed, .. } => {
                            MotionKind::Arc { end, center, plane, clockwise, turns, feed }
                        }
                        other => other,
                    },
                    ..motion
                };
                let turned = transform.motion(motion);
                let MotionKind::Arc {
                    end: e2, center: c2, plane: p2, clockwise: cw2, turns, ..
                } = turned.kind
                else {
                    panic!("{turned:?}")
                };
                let original = Segment::arc(start, end, center, plane, clockwise, 1);
                let moved = Segment::arc(transform.position(start), e2, c2, p2, cw2, turns);
                for step in 0..=10 {
                    let s = f64::from(step) / 10.0;
                    let want = transform.position(original.point(s));
                    let got = moved.point(s);
                    for axis in 0..4 {
                        assert_relative_eq!(got[axis], want[axis], epsilon = 1e-9);
                    }
                }
            }
        }
    }
}
