//! A program's XY extent and the offset that places it in the workspace rectangle (`--fit`).

use std::f64::consts::FRAC_PI_2;

use biscara_interpolate::Segment;
use biscara_motion::{Motion, MotionKind, Plane};

use crate::{Rectangle, VirtualRobotError};

/// The XY bounding box of a program's moves: every end point, and the true extremes of arcs
/// (where the circle crosses its axes' directions), millimetres. The start pose before the first
/// move is not part of the program and is left out, and so are straight moves that end at the
/// start pose's XY: a CAM program's first `G0 Z…` before any X or Y word, or a return home, stay
/// at the robot's home when the program is placed (see [`shift_motion`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bounds {
    /// Smallest x and y, millimetres.
    pub min: [f64; 2],
    /// Largest x and y, millimetres.
    pub max: [f64; 2],
    /// The pose the next move starts from.
    current: [f64; 4],
    /// XY of the start pose.
    home: [f64; 2],
    /// Whether any move was seen.
    any: bool,
}

impl Bounds {
    /// Empty bounds for a program starting at `start` (`[x, y, z, c]`, the robot's home pose).
    pub fn new(start: [f64; 4]) -> Bounds {
        Bounds {
            min: [f64::INFINITY; 2],
            max: [f64::NEG_INFINITY; 2],
            current: start,
            home: [start[0], start[1]],
            any: false,
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

    fn include(&mut self, point: [f64; 4]) {
        for (axis, value) in point.into_iter().take(2).enumerate() {
            self.min[axis] = self.min[axis].min(value);
            self.max[axis] = self.max[axis].max(value);
        }
        self.any = true;
    }

    /// Adds one motion (events are ignored).
    pub fn push(&mut self, motion: &Motion) {
        let start = self.current;
        match motion.kind {
            MotionKind::Rapid { end } | MotionKind::Linear { end, .. } => {
                if !at_home(end, self.home) {
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
}

/// Where a program goes when placed in the workspace rectangle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fit {
    /// The XY offset to add to every position, millimetres.
    pub offset: [f64; 2],
    /// The program's bounds before the shift.
    pub bounds: Bounds,
    /// The rectangle it was centred in.
    pub rectangle: Rectangle,
}

/// The offset that centres `bounds` in `rectangle` (SPEC §4.2 `--fit`); fails when the program
/// is wider or taller than the rectangle, saying by how much.
pub fn fit(bounds: &Bounds, rectangle: &Rectangle) -> Result<Fit, VirtualRobotError> {
    if bounds.is_empty() {
        return Err(VirtualRobotError::NoMoves);
    }
    let (width, height) = (bounds.width(), bounds.height());
    // Tolerate rounding: a program exactly as wide as the rectangle fits.
    const TOLERANCE_MM: f64 = 1e-9;
    if width > rectangle.width() + TOLERANCE_MM || height > rectangle.height() + TOLERANCE_MM {
        return Err(VirtualRobotError::DoesNotFit {
            width_mm: width,
            height_mm: height,
            rect_width_mm: rectangle.width(),
            rect_height_mm: rectangle.height(),
        });
    }
    let center = rectangle.center();
    let offset = [
        center[0] - 0.5 * (bounds.min[0] + bounds.max[0]),
        center[1] - 0.5 * (bounds.min[1] + bounds.max[1]),
    ];
    Ok(Fit { offset, bounds: *bounds, rectangle: *rectangle })
}

fn at_home(end: [f64; 4], home: [f64; 2]) -> bool {
    end[0] == home[0] && end[1] == home[1]
}

/// `motion` moved by `offset` in X and Y (end points and arc centres; z and c unchanged).
/// Straight moves that end exactly at `home`'s XY (the robot's home pose) stay there, as a
/// G-code program's moves without X and Y words do when its origin moves; they are not part of
/// the program's [`Bounds`] either.
pub fn shift_motion(motion: Motion, offset: [f64; 2], home: [f64; 2]) -> Motion {
    let shift = |mut end: [f64; 4]| {
        end[0] += offset[0];
        end[1] += offset[1];
        end
    };
    let kind = match motion.kind {
        MotionKind::Rapid { end } | MotionKind::Linear { end, .. } if at_home(end, home) => {
            motion.kind
        }
        MotionKind::Rapid { end } => MotionKind::Rapid { end: shift(end) },
        MotionKind::Linear { end, feed } => MotionKind::Linear { end: shift(end), feed },
        MotionKind::Arc { end, center, plane, clockwise, turns, feed } => {
            // The centre is in the plane's axes: xy → (x, y), xz → (z, x), yz → (y, z).
            let center = match plane {
                Plane::Xy => [center[0] + offset[0], center[1] + offset[1]],
                Plane::Xz => [center[0], center[1] + offset[0]],
                Plane::Yz => [center[0] + offset[1], center[1]],
            };
            MotionKind::Arc { end: shift(end), center, plane, clockwise, turns, feed }
        }
        other => other,
    };
    Motion { kind, ..motion }
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
             200.000 x 100.000 mm: 30.000 mm too wide in X and 20.000 mm too tall in Y"
        );
        assert_eq!(
            fit(&Bounds::new([0.0; 4]), &rectangle).unwrap_err(),
            VirtualRobotError::NoMoves
        );
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
}
