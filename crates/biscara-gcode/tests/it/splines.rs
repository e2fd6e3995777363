//! G5 and G5.1 splines: the straight moves follow the Bézier curve the control points define
//! (computed here from I J P Q independently of the interpreter), within 0.001 mm.

use biscara_gcode::{Config, interpret};
use biscara_motion::{Motion, MotionKind};

const HOME: [f64; 4] = [0.0, 400.0, 100.0, 0.0];

fn motions(program: &str) -> Vec<Motion> {
    let config = Config { home: HOME, ..Config::default() };
    interpret(program.as_bytes(), &config)
        .collect::<Result<_, _>>()
        .unwrap_or_else(|err| panic!("{err}"))
}

/// The Bézier curve of `points` (3 or 4 of them) at `t`.
fn bezier(points: &[[f64; 2]], t: f64) -> [f64; 2] {
    let u = 1.0 - t;
    let weights: Vec<f64> = if points.len() == 4 {
        vec![u * u * u, 3.0 * u * u * t, 3.0 * u * t * t, t * t * t]
    } else {
        vec![u * u, 2.0 * u * t, t * t]
    };
    let mut point = [0.0; 2];
    for (p, w) in points.iter().zip(weights) {
        point[0] += p[0] * w;
        point[1] += p[1] * w;
    }
    point
}

/// Distance from `p` to the segment `a`–`b`.
fn to_segment(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let length2 = dx * dx + dy * dy;
    let t = if length2 == 0.0 {
        0.0
    } else {
        (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / length2).clamp(0.0, 1.0)
    };
    (p[0] - a[0] - t * dx).hypot(p[1] - a[1] - t * dy)
}

/// Checks that the moves of `line` form a path from `points[0]` along the curve to its last
/// point, every point of the curve within 0.001 mm of the path and every corner on the curve.
#[track_caller]
fn follows(all: &[Motion], line: usize, points: &[[f64; 2]], feed: f64) -> Vec<[f64; 2]> {
    let mut path = vec![points[0]];
    for motion in all.iter().filter(|motion| motion.line == line) {
        let MotionKind::Linear { end, feed: f } = motion.kind else {
            panic!("line {line}: not a linear move: {motion:?}")
        };
        assert_eq!((end[2], end[3], f.mm_per_min), (HOME[2], HOME[3], feed), "line {line}");
        path.push([end[0], end[1]]);
    }
    assert!(path.len() > 2, "line {line}: {} moves", path.len() - 1);
    assert_eq!(*path.last().unwrap(), *points.last().unwrap(), "line {line}: the end");
    for k in 0..=4000 {
        let on_curve = bezier(points, f64::from(k) / 4000.0);
        let nearest = path
            .windows(2)
            .map(|chord| to_segment(on_curve, chord[0], chord[1]))
            .fold(f64::INFINITY, f64::min);
        assert!(nearest <= 0.001 + 1e-9, "line {line}: {on_curve:?} is {nearest} mm off the path");
    }
    for corner in &path {
        let nearest = (0..=20000)
            .map(|k| {
                let c = bezier(points, f64::from(k) / 20000.0);
                (c[0] - corner[0]).hypot(c[1] - corner[1])
            })
            .fold(f64::INFINITY, f64::min);
        assert!(nearest < 0.002, "line {line}: corner {corner:?} is {nearest} mm off the curve");
    }
    path
}

#[test]
fn splines_follow_their_bezier_curves_and_g5_continues_smoothly() {
    let all = motions(
        "G0 X10 Y400\nG5 I10 J0 P0 Q-10 X30 Y420 F600\nG5 P0 Q-10 X50 Y440\n\
         G5.1 I10 J-20 X60 Y430\nM2\n",
    );
    let first = [[10.0, 400.0], [20.0, 400.0], [30.0, 410.0], [30.0, 420.0]];
    let a = follows(&all, 2, &first, 600.0);
    // Without I J: the first control point mirrors the last one of the previous G5.
    let second = [[30.0, 420.0], [30.0, 430.0], [50.0, 430.0], [50.0, 440.0]];
    let b = follows(&all, 3, &second, 600.0);
    follows(&all, 4, &[[50.0, 440.0], [60.0, 420.0], [60.0, 430.0]], 600.0);
    // Smooth where they meet: the last move of one and the first of the next turn by less
    // than a degree.
    let direction = |p: [f64; 2], q: [f64; 2]| (q[1] - p[1]).atan2(q[0] - p[0]);
    let turn = direction(a[a.len() - 2], a[a.len() - 1]) - direction(b[0], b[1]);
    assert!(turn.abs().to_degrees() < 1.0, "turn of {} degrees", turn.to_degrees());
    assert_eq!(all.last().map(|motion| motion.kind), Some(MotionKind::End));
}

#[test]
fn a_spline_keeps_the_modal_motion_and_a_huge_one_is_refused() {
    let all = motions("G0 X0 Y400\nG5 I1 J0 P1 Q0 X5 Y405 F100\nX7\nM2\n");
    let last_move = all.iter().rev().find(|motion| motion.line == 3).expect("line 3 moves");
    assert_eq!(last_move.kind, MotionKind::Rapid { end: [7.0, 405.0, 100.0, 0.0] });

    let err = interpret(&b"G5 I100000 J0 P0 Q100000 X0 Y1 F10\nM2\n"[..], &Config::default())
        .find_map(Result::err)
        .expect("an error");
    assert!(err.to_string().starts_with("1:1: Spline too large"), "{err}");
}
