//! The blender's properties: the blended path stays within P of the programmed polyline, is
//! continuous with continuous tangents inside a chain, and keeps the chain's end points.

mod arcs;
mod naive_cam;
mod strategies;

use biscara_blend::{Blended, Blender, Geometry, Piece, Speed};
use biscara_motion::{Feed, Motion, MotionKind};
use proptest::prelude::*;

const FEED: Feed = Feed { mm_per_min: 6000.0, inverse_time: false };

fn linear(line: usize, end: [f64; 4], blend: Option<f64>) -> Motion {
    Motion { blend, ..Motion::new(line, MotionKind::Linear { end, feed: FEED }) }
}

fn blend(motions: &[Motion], start: [f64; 4]) -> Vec<Blended> {
    Blender::new(motions.iter().copied().map(Ok::<_, ()>), start)
        .collect::<Result<_, _>>()
        .expect("no error")
}

fn pieces(items: &[Blended]) -> Vec<Piece> {
    items
        .iter()
        .map(|item| match item {
            Blended::Piece(piece) => *piece,
            Blended::Motion(motion) => panic!("not blended: {motion:?}"),
        })
        .collect()
}

/// Distance from `p` to the segment `a`–`b` (XYZ).
fn distance_to_segment(p: [f64; 3], a: [f64; 3], b: [f64; 3]) -> f64 {
    let ab: [f64; 3] = std::array::from_fn(|k| b[k] - a[k]);
    let ap: [f64; 3] = std::array::from_fn(|k| p[k] - a[k]);
    let length2: f64 = ab.iter().map(|v| v * v).sum();
    let t = if length2 > 0.0 {
        (ap.iter().zip(&ab).map(|(x, y)| x * y).sum::<f64>() / length2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (0..3).map(|k| (a[k] + t * ab[k] - p[k]).powi(2)).sum::<f64>().sqrt()
}

fn xyz(pose: [f64; 4]) -> [f64; 3] {
    [pose[0], pose[1], pose[2]]
}

fn close(a: [f64; 4], b: [f64; 4], epsilon: f64) -> bool {
    a.iter().zip(&b).all(|(x, y)| (x - y).abs() <= epsilon)
}

/// The worst distance of the blended path from the programmed polyline `vertices`, sampled
/// every 1/40 of each piece.
fn worst_deviation(pieces: &[Piece], vertices: &[[f64; 4]]) -> f64 {
    let mut worst: f64 = 0.0;
    for piece in pieces {
        for step in 0..=40 {
            let p = xyz(piece.point(f64::from(step) / 40.0));
            let nearest = vertices
                .windows(2)
                .map(|w| distance_to_segment(p, xyz(w[0]), xyz(w[1])))
                .fold(f64::INFINITY, f64::min);
            worst = worst.max(nearest);
        }
    }
    worst
}

#[test]
fn a_square_corner_gets_a_fillet_within_the_tolerance() {
    let motions = [
        linear(1, [10.0, 0.0, 0.0, 0.0], Some(0.05)),
        linear(2, [10.0, 10.0, 0.0, 0.0], Some(0.05)),
    ];
    let got = pieces(&blend(&motions, [0.0; 4]));
    assert_eq!(got.len(), 3, "{got:?}");
    let radius = got[1].radius().expect("a fillet");
    // r (√2 − 1) = 0.05 for a right angle.
    assert!((radius * (2f64.sqrt() - 1.0) - 0.05).abs() < 1e-12, "{radius}");
    let midpoint = got[1].point(0.5);
    let off = ((midpoint[0] - 10.0).powi(2) + midpoint[1].powi(2)).sqrt();
    assert!((off - 0.05).abs() < 1e-9, "{off}");
    assert_eq!(got[0].start(), [0.0; 4]);
    assert_eq!(got[2].end(), [10.0, 10.0, 0.0, 0.0]);
    assert!(got[2].ends_chain && !got[0].ends_chain && !got[1].ends_chain);
    assert_eq!((got[0].line, got[1].line, got[2].line), (1, 1, 2));
}

#[test]
fn c_rates_that_would_jump_stop_the_robot() {
    // C turns on the second move: its rate along the path would jump at the fillet.
    let turning = [
        linear(1, [10.0, 0.0, 0.0, 0.0], Some(0.05)),
        linear(2, [10.0, 10.0, 0.0, 90.0], Some(0.05)),
    ];
    let got = pieces(&blend(&turning, [0.0; 4]));
    assert_eq!(got.len(), 2, "{got:?}");
    assert!(got[0].ends_chain && got[0].radius().is_none());
    // Straight on with C turning at the same rate: no stop; at another rate: a stop.
    let same = [
        linear(1, [10.0, 0.0, 0.0, 10.0], Some(0.05)),
        linear(2, [30.0, 0.0, 0.0, 30.0], Some(0.05)),
    ];
    let got = pieces(&blend(&same, [0.0; 4]));
    assert!(!got[0].ends_chain && got[1].ends_chain, "{got:?}");
    let other = [
        linear(1, [10.0, 0.0, 0.0, 10.0], Some(0.05)),
        linear(2, [30.0, 0.0, 0.0, 10.0], Some(0.05)),
    ];
    let got = pieces(&blend(&other, [0.0; 4]));
    assert!(got[0].ends_chain && got[1].ends_chain, "{got:?}");
}

#[test]
fn short_moves_get_the_blend_that_fits_in_half_of_them() {
    // One-degree chords of a circle of radius 57.3 mm: the fillets rebuild the circle.
    let radius = 180.0 / std::f64::consts::PI;
    let vertices: Vec<[f64; 4]> = (0..=360)
        .map(|k| {
            let angle = f64::from(k).to_radians();
            [radius * angle.cos(), radius * angle.sin(), 0.0, 0.0]
        })
        .collect();
    let motions: Vec<Motion> =
        vertices[1..].iter().enumerate().map(|(k, &end)| linear(k + 1, end, Some(0.05))).collect();
    let got = pieces(&blend(&motions, vertices[0]));
    let chord = 2.0 * radius * 0.5f64.to_radians().sin();
    for piece in &got[1..got.len() - 1] {
        if let Some(r) = piece.radius() {
            // Cut at half of each chord: the fillet's radius is the circle's (nearly).
            assert!((r - chord / 2.0 / 0.5f64.to_radians().tan()).abs() < 1e-9, "{r}");
        } else {
            assert!(piece.length() < 1e-9, "{piece:?}");
        }
    }
    assert!(worst_deviation(&got, &vertices) < 0.003);
}

#[test]
fn what_cannot_be_blended_passes_unchanged() {
    let arc = Motion {
        blend: Some(0.1),
        ..Motion::new(
            3,
            MotionKind::Arc {
                end: [20.0, 0.0, 0.0, 0.0],
                center: [15.0, 0.0],
                plane: biscara_motion::Plane::Xy,
                clockwise: true,
                turns: 1,
                feed: FEED,
            },
        )
    };
    let motions = [
        linear(1, [10.0, 0.0, 0.0, 0.0], None),
        linear(2, [10.0, 0.0, 0.0, 45.0], Some(0.1)),
        arc,
        Motion::new(4, MotionKind::Pick),
        linear(5, [20.0, 10.0, 0.0, 0.0], Some(0.1)),
        // Straight back: an exact stop.
        linear(6, [20.0, 0.0, 0.0, 0.0], Some(0.1)),
    ];
    let got = blend(&motions, [0.0; 4]);
    let kinds: Vec<String> = got
        .iter()
        .map(|item| match item {
            Blended::Piece(piece) => format!("piece {} {}", piece.line, piece.ends_chain),
            Blended::Motion(motion) => format!("motion {}", motion.line),
        })
        .collect();
    // The arc under G64 joins nothing (a turn of C before it, an event after it): it passes.
    assert_eq!(
        kinds,
        ["motion 1", "motion 2", "motion 3", "motion 4", "piece 5 true", "piece 6 true"]
    );
}

/// An arc in XY ending at `end`, about `center`, under G64 P0.05.
fn arc(line: usize, end: [f64; 4], center: [f64; 2], clockwise: bool) -> Motion {
    let kind = MotionKind::Arc {
        end,
        center,
        plane: biscara_motion::Plane::Xy,
        clockwise,
        turns: 1,
        feed: FEED,
    };
    Motion { blend: Some(0.05), ..Motion::new(line, kind) }
}

#[test]
fn tangent_arcs_join_the_chain() {
    // A rectangle with rounded corners (radius 2): lines and quarter arcs, each tangent to the
    // next, under G64 P0.05: one chain, no fillet, no stop until its end.
    let motions = [
        linear(1, [10.0, 0.0, 0.0, 0.0], Some(0.05)),
        arc(2, [12.0, 2.0, 0.0, 0.0], [10.0, 2.0], false),
        linear(3, [12.0, 8.0, 0.0, 0.0], Some(0.05)),
        arc(4, [10.0, 10.0, 0.0, 0.0], [10.0, 8.0], false),
        linear(5, [0.0, 10.0, 0.0, 0.0], Some(0.05)),
        // A corner: the arc leaves at right angles to the line before it (upwards): a fillet.
        arc(6, [-2.0, 12.0, 0.0, 0.0], [-2.0, 10.0], false),
        // And a line that goes on from the arc's end the way it was going (tangent).
        linear(7, [-10.0, 12.0, 0.0, 0.0], Some(0.05)),
    ];
    let got = pieces(&blend(&motions, [0.0; 4]));
    let summary: Vec<(usize, bool, bool)> = got
        .iter()
        .map(|piece| (piece.line, matches!(piece.geometry, Geometry::Arc(_)), piece.ends_chain))
        .collect();
    assert_eq!(
        summary,
        [
            (1, false, false),
            (2, true, false),
            (3, false, false),
            (4, true, false),
            (5, false, false),
            (5, false, false),
            (6, true, false),
            (7, false, true),
        ]
    );
    assert!(matches!(got[5].geometry, Geometry::Fillet { .. }), "{:?}", got[5]);
    // The arcs are the programmed ones, end to end with their neighbours.
    for pair in got.windows(2) {
        assert!(close(pair[0].end(), pair[1].start(), 1e-12), "{pair:?}");
    }
    assert!(close(got[1].point(0.5), [10.0 + 2f64.sqrt(), 2.0 - 2f64.sqrt(), 0.0, 0.0], 1e-12));
    assert_eq!(got[1].radius(), Some(2.0));
    assert!((got[1].length() - std::f64::consts::PI).abs() < 1e-12);
}

/// Checks a blended chain against its programmed `vertices` and `tolerance`.
fn check_chain(got: &[Piece], vertices: &[[f64; 4]], tolerance: f64) -> Result<(), TestCaseError> {
    prop_assert!(!got.is_empty());
    prop_assert!(close(got[0].start(), vertices[0], 1e-9));
    let last = got[got.len() - 1];
    prop_assert!(close(last.end(), vertices[vertices.len() - 1], 1e-9));
    prop_assert!(last.ends_chain);
    for pair in got.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        prop_assert!(close(a.end(), b.start(), 1e-9), "gap between {a:?} and {b:?}");
        prop_assert!(close(a.point(1.0), a.end(), 1e-9), "{a:?} does not reach its end");
        if !a.ends_chain {
            let (ta, tb) = (a.tangent(1.0), b.tangent(0.0));
            let kink: f64 = (0..3).map(|k| (ta[k] - tb[k]).powi(2)).sum::<f64>().sqrt();
            prop_assert!(kink < 1e-7, "tangent jumps by {kink} between {a:?} and {b:?}");
        }
    }
    let worst = worst_deviation(got, vertices);
    prop_assert!(worst <= tolerance + 1e-9, "deviation {worst} above {tolerance}");
    // Every programmed vertex is kept where the chain stops.
    for piece in got.iter().filter(|piece| piece.ends_chain) {
        prop_assert!(vertices.iter().any(|v| close(*v, piece.end(), 1e-9)));
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn derivatives_match_finite_differences(
        vertices in strategies::polyline(),
        tolerance in 0.01..0.5f64,
        u in 0.05..0.95f64,
    ) {
        let motions: Vec<Motion> = vertices[1..]
            .iter()
            .enumerate()
            .map(|(k, &end)| linear(k + 1, end, Some(tolerance)))
            .collect();
        for piece in pieces(&blend(&motions, vertices[0])) {
            let length = piece.length();
            // A step of a thousandth of the piece's shortest scale (its length, its radius).
            let scale = piece.radius().map_or(length, |radius| radius.min(length));
            if scale < 0.01 {
                continue;
            }
            let step = 1e-3 * scale;
            let h = step / length;
            let (first, second) = piece.derivatives(u);
            let (before, here, after) = (piece.point(u - h), piece.point(u), piece.point(u + h));
            // Rounding of coordinates near 500 mm, amplified by the differences.
            let noise = 1e-13 * 500.0;
            for k in 0..4 {
                let slope = (after[k] - before[k]) / (2.0 * step);
                let bend = (after[k] - 2.0 * here[k] + before[k]) / (step * step);
                prop_assert!(
                    (slope - first[k]).abs() < 1e-6 + noise / step,
                    "axis {k}: {slope} vs {}", first[k]
                );
                prop_assert!(
                    (bend - second[k]).abs() < 1e-3 / scale + 4.0 * noise / (step * step),
                    "axis {k}: {bend} vs {}", second[k]
                );
            }
            if let Some(radius) = piece.radius() {
                let curvature = second[..3].iter().map(|v| v * v).sum::<f64>().sqrt();
                prop_assert!((curvature * radius - 1.0).abs() < 1e-9);
            }
        }
    }

    #[test]
    fn blended_polylines_stay_within_the_tolerance(
        vertices in strategies::polyline(),
        tolerance in prop_oneof![Just(0.0), 0.001..0.5f64],
    ) {
        let motions: Vec<Motion> = vertices[1..]
            .iter()
            .enumerate()
            .map(|(k, &end)| linear(k + 1, end, Some(tolerance)))
            .collect();
        let got = pieces(&blend(&motions, vertices[0]));
        let bound = if tolerance > 0.0 { tolerance } else { biscara_blend::NO_TOLERANCE_CAP_MM };
        check_chain(&got, &vertices, bound)?;
        // Every corner that turns gets a fillet or a stop, and the chain stops at its end.
        let stops = got.iter().filter(|piece| piece.ends_chain).count();
        let fillets = got.iter().filter(|piece| piece.radius().is_some()).count();
        let corners = vertices.len() - 2 - count_straight(&vertices);
        prop_assert_eq!(fillets + stops, corners + 1);
    }
}

/// The corners of `vertices` that go straight on (no fillet needed).
fn count_straight(vertices: &[[f64; 4]]) -> usize {
    vertices
        .windows(3)
        .filter(|w| {
            let a: [f64; 3] = std::array::from_fn(|k| w[1][k] - w[0][k]);
            let b: [f64; 3] = std::array::from_fn(|k| w[2][k] - w[1][k]);
            let cross =
                [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
            let dot: f64 = (0..3).map(|k| a[k] * b[k]).sum();
            cross.iter().map(|v| v * v).sum::<f64>().sqrt() < 1e-12 && dot > 0.0
        })
        .count()
}

#[test]
fn a_cam_polyline_runs_as_one_chain() {
    // A circle of 720 chords (half a degree each, radius 50 mm), then a 40 mm square from the
    // circle's start: every corner, the square's included, is a fillet; one stop, at the end.
    let radius = 50.0;
    let mut vertices: Vec<[f64; 4]> = (0..=720)
        .map(|k| {
            let angle = (f64::from(k) * 0.5).to_radians();
            [radius * angle.cos(), 400.0 + radius * angle.sin(), 50.0, 0.0]
        })
        .collect();
    let corner = vertices[0];
    for [dx, dy] in [[40.0, 0.0], [40.0, 40.0], [0.0, 40.0], [0.0, 0.0]] {
        vertices.push([corner[0] + dx, corner[1] + dy, 50.0, 0.0]);
    }
    let motions: Vec<Motion> =
        vertices[1..].iter().enumerate().map(|(k, &end)| linear(k + 1, end, Some(0.05))).collect();
    let got = pieces(&blend(&motions, vertices[0]));
    check_chain(&got, &vertices, 0.05).expect("a valid chain");
    assert_eq!(got.iter().filter(|piece| piece.ends_chain).count(), 1);
    let fillets: Vec<f64> = got.iter().filter_map(Piece::radius).collect();
    assert_eq!(fillets.len(), vertices.len() - 2);
    // The circle's chords are cut at half: the fillets rebuild a 50 mm circle; the square's
    // right angles get r = P / (√2 − 1).
    let smallest = fillets.iter().copied().fold(f64::INFINITY, f64::min);
    assert!((smallest - 0.05 / (2f64.sqrt() - 1.0)).abs() < 1e-9, "{smallest}");
    assert!(fillets[..719].iter().all(|r| (r - radius).abs() < 0.01), "{:?}", &fillets[..3]);
}

#[test]
fn a_fillet_between_speeds_is_cut_at_its_middle() {
    // A rapid, then a plunge at the feed: each half of the fillet at its own move's speed.
    let motions = [
        Motion {
            blend: Some(0.1),
            ..Motion::new(1, MotionKind::Rapid { end: [10.0, 0.0, 0.0, 0.0] })
        },
        linear(2, [10.0, 0.0, -10.0, 0.0], Some(0.1)),
    ];
    let got = pieces(&blend(&motions, [0.0; 4]));
    assert_eq!(got.len(), 4, "{got:?}");
    let (first, second) = (got[1], got[2]);
    assert_eq!((first.speed, first.line), (Speed::Rapid, 1));
    assert_eq!((second.speed, second.line), (Speed::Feed(FEED), 2));
    assert_eq!(first.end(), second.start());
    assert_eq!((first.start(), second.end()), (got[0].end(), got[3].start()));
    assert_eq!(first.radius(), second.radius());
    // The halves continue each other: the tangent at the first's end is the second's start.
    let (end, start) = (first.tangent(1.0), second.tangent(0.0));
    assert!((0..3).all(|k| (end[k] - start[k]).abs() < 1e-12), "{end:?} {start:?}");
    let midpoint = first.end();
    let off = (midpoint[0] - 10.0).hypot(midpoint[2]);
    assert!((off - 0.1).abs() < 1e-9, "{off}");
}
