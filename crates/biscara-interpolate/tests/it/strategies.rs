//! proptest strategies: random programs of lines, arcs, dwells and events.

use biscara_motion::{Feed, Motion, MotionKind, Plane};
use proptest::prelude::*;

fn pose() -> impl Strategy<Value = [f64; 4]> {
    [-200.0..200.0f64, 200.0..450.0f64, 0.0..100.0f64, -360.0..360.0f64]
}

fn feed() -> impl Strategy<Value = Feed> {
    (10.0..20000.0f64).prop_map(|mm_per_min| Feed { mm_per_min, inverse_time: false })
}

/// One motion kind; arcs get their centre later, from the start point.
fn kind() -> impl Strategy<Value = MotionKind> {
    prop_oneof![
        pose().prop_map(|end| MotionKind::Rapid { end }),
        (pose(), feed()).prop_map(|(end, feed)| MotionKind::Linear { end, feed }),
        (pose(), feed(), any::<bool>(), 1..3u32, -50.0..50.0f64, -50.0..50.0f64).prop_map(
            |(end, feed, clockwise, turns, cu, cv)| MotionKind::Arc {
                end,
                center: [cu, cv],
                plane: Plane::Xy,
                clockwise,
                turns,
                feed,
            }
        ),
        (0.0..0.5f64).prop_map(|seconds| MotionKind::Dwell { seconds }),
        Just(MotionKind::Pick),
        Just(MotionKind::Place),
    ]
}

/// A program of up to `len` motions with line numbers 1, 2, …; arcs end on their circle (the
/// centre is placed between start and end so that both radii agree).
pub fn program(len: usize) -> impl Strategy<Value = Vec<Motion>> {
    proptest::collection::vec(kind(), 1..len).prop_map(|kinds| {
        let mut pose = [0.0, 400.0, 50.0, 0.0];
        let mut motions = Vec::new();
        for (index, mut kind) in kinds.into_iter().enumerate() {
            if let MotionKind::Arc { end, ref mut center, .. } = kind {
                // A centre on the perpendicular bisector of start and end, offset by `center[0]`.
                let (mx, my) = (0.5 * (pose[0] + end[0]), 0.5 * (pose[1] + end[1]));
                let (dx, dy) = (end[0] - pose[0], end[1] - pose[1]);
                let length = dx.hypot(dy).max(1e-9);
                *center = [mx - dy / length * center[0], my + dx / length * center[0]];
            }
            if let Some(end) = kind.end() {
                pose = end;
            }
            motions.push(Motion::new(index + 1, kind));
        }
        motions
    })
}
