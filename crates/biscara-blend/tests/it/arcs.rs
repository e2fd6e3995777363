//! Corners where a programmed arc meets a line or another arc: the fillet in the arc's plane,
//! within P of the programmed path, tangent at both ends, the trims within half of each move;
//! and the corners that stay exact stops.

use biscara_blend::{Blended, Blender, Geometry, Piece, Speed};
use biscara_motion::{Feed, Motion, MotionKind, Plane, Segment};
use proptest::prelude::*;

const FEED: Feed = Feed { mm_per_min: 6000.0, inverse_time: false };

fn linear(line: usize, end: [f64; 4], tolerance: f64) -> Motion {
    Motion { blend: Some(tolerance), ..Motion::new(line, MotionKind::Linear { end, feed: FEED }) }
}

/// An arc in the XY plane from `from`, leaving along the heading `heading` (radians), of
/// radius `radius`, bending left (counter-clockwise) when `sweep` (radians) is positive.
fn arc_from(line: usize, from: [f64; 4], heading: f64, radius: f64, sweep: f64) -> Motion {
    spiral_from(line, from, heading, radius, sweep, 0.0)
}

/// [`arc_from`], its end `rounding` mm further from the centre (a spiral, as CAM output whose
/// coordinates are rounded to a few decimals makes).
fn spiral_from(
    line: usize,
    from: [f64; 4],
    heading: f64,
    radius: f64,
    sweep: f64,
    rounding: f64,
) -> Motion {
    let side = sweep.signum();
    let center = [from[0] - side * radius * heading.sin(), from[1] + side * radius * heading.cos()];
    let start_angle = (from[1] - center[1]).atan2(from[0] - center[0]);
    let end_angle = start_angle + sweep;
    let end = [
        center[0] + (radius + rounding) * end_angle.cos(),
        center[1] + (radius + rounding) * end_angle.sin(),
        from[2],
        from[3],
    ];
    let kind = MotionKind::Arc {
        end,
        center,
        plane: Plane::Xy,
        clockwise: sweep < 0.0,
        turns: 1,
        feed: FEED,
    };
    Motion::new(line, kind)
}

fn with_tolerance(motion: Motion, tolerance: f64) -> Motion {
    Motion { blend: Some(tolerance), ..motion }
}

/// The programmed geometry of `motions` from `start`.
fn programmed(motions: &[Motion], start: [f64; 4]) -> Vec<Segment> {
    let mut from = start;
    motions
        .iter()
        .filter_map(|motion| {
            let segment = match motion.kind {
                MotionKind::Linear { end, .. } | MotionKind::Rapid { end } => {
                    Segment::line(from, end)
                }
                MotionKind::Arc { end, center, plane, clockwise, turns, .. } => {
                    Segment::arc(from, end, center, plane, clockwise, turns)
                }
                _ => return None,
            };
            from = segment.end();
            Some(segment)
        })
        .collect()
}

/// The blended path of `motions`: the pieces, and the motions passed unchanged as pieces that
/// stop at their end (arcs that join nothing).
fn blend(motions: &[Motion], start: [f64; 4]) -> Vec<Piece> {
    let items: Vec<Blended> = Blender::new(motions.iter().copied().map(Ok::<_, ()>), start)
        .collect::<Result<_, _>>()
        .expect("no error");
    let mut from = start;
    items
        .into_iter()
        .map(|item| {
            let piece = match item {
                Blended::Piece(piece) => piece,
                Blended::Motion(motion) => {
                    let segment = programmed(&[motion], from)[0];
                    Piece {
                        line: motion.line,
                        geometry: Geometry::Arc(segment),
                        speed: Speed::Feed(FEED),
                        ends_chain: true,
                    }
                }
            };
            from = piece.end();
            piece
        })
        .collect()
}

fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt()
}

fn xyz(pose: [f64; 4]) -> [f64; 3] {
    [pose[0], pose[1], pose[2]]
}

/// The distance from `p` to the programmed move `segment` (a line or a planar arc in XY),
/// exact.
fn distance_to(segment: &Segment, p: [f64; 3]) -> f64 {
    let Some(arc) = segment.planar_arc() else {
        return segment.distance_to(p);
    };
    let [cx, cy] = arc.center;
    let start = segment.start();
    let (from, to) = ([start[0] - cx, start[1] - cy], [p[0] - cx, p[1] - cy]);
    let along = (from[0] * to[1] - from[1] * to[0]).atan2(from[0] * to[0] + from[1] * to[1]);
    let along = if arc.sweep < 0.0 { -along } else { along };
    let along = along.rem_euclid(std::f64::consts::TAU);
    if along <= arc.sweep.abs() {
        // (A spiral's radius at that angle: for the micrometres a spiral differs from a
        // circle, its nearest point to p.)
        let u = along / arc.sweep.abs();
        let radial = to[0].hypot(to[1]) - (arc.radius + u * (arc.end_radius - arc.radius));
        radial.hypot(p[2] - start[2])
    } else {
        distance(p, xyz(start)).min(distance(p, xyz(segment.end())))
    }
}

/// The worst distance of `pieces` (sampled every 1/200 of each) from the programmed path.
fn worst_deviation(pieces: &[Piece], path: &[Segment]) -> f64 {
    let mut worst: f64 = 0.0;
    for piece in pieces {
        for step in 0..=200 {
            let p = xyz(piece.point(f64::from(step) / 200.0));
            let nearest =
                path.iter().map(|segment| distance_to(segment, p)).fold(f64::INFINITY, f64::min);
            worst = worst.max(nearest);
        }
    }
    worst
}

/// The angle between two unit vectors, radians.
fn angle_between(a: [f64; 3], b: [f64; 3]) -> f64 {
    let cross = [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
    let dot: f64 = (0..3).map(|k| a[k] * b[k]).sum();
    cross.iter().map(|v| v * v).sum::<f64>().sqrt().atan2(dot)
}

/// Checks a blended path: end to end, tangent (within 1e-9 rad) wherever the robot does not
/// stop, within `tolerance` of the programmed path, ending on its end.
fn check_path(got: &[Piece], path: &[Segment], tolerance: f64) -> Result<(), TestCaseError> {
    prop_assert!(!got.is_empty());
    prop_assert!(distance(xyz(got[0].start()), xyz(path[0].start())) < 1e-9);
    let last = got[got.len() - 1];
    prop_assert!(distance(xyz(last.end()), xyz(path[path.len() - 1].end())) < 1e-9);
    prop_assert!(last.ends_chain);
    for pair in got.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        prop_assert!(distance(xyz(a.end()), xyz(b.start())) < 1e-9, "gap between {a:?} and {b:?}");
        prop_assert!(
            distance(xyz(a.point(1.0)), xyz(a.end())) < 1e-9,
            "{a:?} does not reach its end"
        );
    }
    // No kink where the robot does not stop. (A straight piece's direction comes from its end
    // points, whose coordinates near 400 mm hold 6e-14 mm: on what rounding leaves of a line
    // trimmed by nearly half at both ends, a micrometre or less, it is that over its length.)
    let resolution = |piece: &Piece| match piece.geometry {
        Geometry::Line { .. } => 2e-13 / piece.length(),
        _ => 0.0,
    };
    for pair in got.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        if !a.ends_chain {
            let kink = angle_between(a.tangent(1.0), b.tangent(0.0));
            let allowed = 1e-9 + resolution(&a) + resolution(&b);
            prop_assert!(kink < allowed, "tangent turns by {kink} rad between {a:?} and {b:?}");
        }
    }
    let worst = worst_deviation(got, path);
    prop_assert!(worst <= tolerance + 1e-9, "deviation {worst} above {tolerance}");
    Ok(())
}

/// The fillets of `got`.
fn fillets(got: &[Piece]) -> Vec<Piece> {
    got.iter().copied().filter(|piece| matches!(piece.geometry, Geometry::Fillet { .. })).collect()
}

/// The distance of the programmed `corner` from `fillet` (sampled finely).
fn corner_deviation(fillet: &Piece, corner: [f64; 4]) -> f64 {
    (0..=20_000)
        .map(|k| distance(xyz(fillet.point(f64::from(k) / 20_000.0)), xyz(corner)))
        .fold(f64::INFINITY, f64::min)
}

const P: f64 = 0.05;
const START: [f64; 4] = [0.0, 400.0, 50.0, 0.0];

/// A line along +X, then an arc leaving at 60° to its left: bending left (towards the fillet,
/// which lies inside its circle) or right (the fillet outside).
fn line_then_arc(sweep: f64) -> Vec<Motion> {
    let corner = [10.0, 400.0, 50.0, 0.0];
    vec![
        linear(1, corner, P),
        with_tolerance(arc_from(2, corner, 60f64.to_radians(), 5.0, sweep), P),
    ]
}

#[test]
fn a_line_meeting_an_arc_gets_a_fillet_inside_or_outside_its_circle() {
    for sweep in [90f64.to_radians(), -90f64.to_radians()] {
        let motions = line_then_arc(sweep);
        let path = programmed(&motions, START);
        let got = blend(&motions, START);
        check_path(&got, &path, P).expect("a valid path");
        // A trimmed line, the fillet, the trimmed arc: one chain.
        assert_eq!(got.len(), 3, "{got:?}");
        assert!(!got[0].ends_chain && !got[1].ends_chain && got[2].ends_chain);
        let fillet = got[1];
        let radius = fillet.radius().expect("a fillet");
        // The corner is P from the fillet: the largest fillet the tolerance allows.
        let deviation = corner_deviation(&fillet, path[0].end());
        assert!((deviation - P).abs() < 1e-7, "{deviation}");
        // Inside the arc's circle when it bends towards the fillet (left, like the turn).
        let Geometry::Fillet { center, .. } = fillet.geometry else { unreachable!() };
        let from_arc = distance(
            center,
            [path[1].circle().unwrap().center[0], path[1].circle().unwrap().center[1], 50.0],
        );
        let expected = if sweep > 0.0 { 5.0 - radius } else { 5.0 + radius };
        assert!((from_arc - expected).abs() < 1e-9, "{from_arc} vs {expected}");
        // The trimmed line and arc: within half of each, the arc keeps its centre and radius.
        assert!(got[0].length() >= 5.0 && got[0].length() < 10.0);
        let Geometry::Arc(trimmed) = got[2].geometry else { panic!("{:?}", got[2]) };
        let (kept, whole) = (trimmed.circle().expect("a circle"), path[1].circle().unwrap());
        assert_eq!(kept.center, whole.center);
        assert!((kept.radius - whole.radius).abs() < 1e-12);
        assert!(
            kept.sweep.abs() >= whole.sweep.abs() / 2.0 && kept.sweep.abs() < whole.sweep.abs()
        );
        assert_eq!(trimmed.end(), path[1].end());
    }
}

#[test]
fn an_arc_meeting_a_line_is_the_mirror_of_a_line_meeting_an_arc() {
    // The arc of `line_then_arc` run backwards, then the line backwards: the same fillet.
    for sweep in [90f64.to_radians(), -90f64.to_radians()] {
        let forward = line_then_arc(sweep);
        let path = programmed(&forward, START);
        let arc_start = path[1].end();
        let Some(circle) = path[1].circle() else { panic!() };
        let kind = MotionKind::Arc {
            end: path[1].start(),
            center: circle.center,
            plane: Plane::Xy,
            clockwise: sweep > 0.0,
            turns: 1,
            feed: FEED,
        };
        let motions = [with_tolerance(Motion::new(1, kind), P), linear(2, START, P)];
        let back = programmed(&motions, arc_start);
        let got = blend(&motions, arc_start);
        check_path(&got, &back, P).expect("a valid path");
        assert_eq!(got.len(), 3, "{got:?}");
        let (there, here) = (blend(&forward, START)[1], got[1]);
        assert!((there.radius().unwrap() - here.radius().unwrap()).abs() < 1e-9);
        assert!(distance(xyz(there.start()), xyz(here.end())) < 1e-9);
        assert!(distance(xyz(there.end()), xyz(here.start())) < 1e-9);
        assert!((corner_deviation(&here, back[0].end()) - P).abs() < 1e-7);
    }
}

#[test]
fn two_arcs_meeting_at_a_corner_get_a_fillet() {
    let corner = [10.0, 400.0, 50.0, 0.0];
    // Arcs ending at the corner heading +X (bending left or right), arcs leaving it at 70° to
    // the left or to the right, bending either way.
    for (first, heading, second) in
        [(1.0, 70.0, 1.0), (1.0, 70.0, -1.0), (-1.0, -70.0, 1.0), (-1.0, 110.0, -1.0)]
    {
        // The first arc: leave the corner backwards (heading 180°) with the opposite bend, then
        // reverse it.
        let reversed = arc_from(1, corner, std::f64::consts::PI, 8.0, -first * 1.2);
        let MotionKind::Arc { end: start, center, .. } = reversed.kind else { unreachable!() };
        let kind = MotionKind::Arc {
            end: corner,
            center,
            plane: Plane::Xy,
            clockwise: first < 0.0,
            turns: 1,
            feed: FEED,
        };
        let motions = [
            with_tolerance(Motion::new(1, kind), P),
            with_tolerance(arc_from(2, corner, f64::to_radians(heading), 4.0, second * 1.5), P),
        ];
        let path = programmed(&motions, start);
        assert!(distance(xyz(path[0].end()), xyz(corner)) < 1e-12);
        let got = blend(&motions, start);
        check_path(&got, &path, P).expect("a valid path");
        assert_eq!(got.len(), 3, "{first} {heading} {second}: {got:?}");
        let deviation = corner_deviation(&got[1], corner);
        assert!((deviation - P).abs() < 1e-7, "{first} {heading} {second}: {deviation}");
    }
}

#[test]
fn short_arcs_and_lines_are_trimmed_by_at_most_half() {
    // A 0.1 mm line into a 2° arc of radius 2: the tolerance would allow a bigger fillet than
    // fits; each move is cut back by at most half.
    let corner = [10.0, 400.0, 50.0, 0.0];
    let motions = [
        linear(1, [9.9, 400.0, 50.0, 0.0], 0.5),
        linear(2, corner, 0.5),
        with_tolerance(arc_from(3, corner, 1.2, 2.0, -2f64.to_radians()), 0.5),
        linear(4, [30.0, 420.0, 50.0, 0.0], 0.5),
    ];
    let path = programmed(&motions, START);
    let got = blend(&motions, START);
    check_path(&got, &path, 0.5).expect("a valid path");
    // The arc (0.07 mm) is trimmed by half at each end: the two fillets meet at its middle
    // (with what rounding leaves of it between them).
    assert!(
        got.iter()
            .all(|piece| !matches!(piece.geometry, Geometry::Arc(_)) || piece.length() < 1e-9),
        "{got:?}"
    );
    let between = fillets(&got);
    assert_eq!(between.len(), 2, "{got:?}");
    let middle = xyz(path[2].point(0.5));
    assert!(distance(xyz(between[0].end()), middle) < 1e-9);
    assert!(distance(xyz(between[1].start()), middle) < 1e-9);
    // The lines keep at least half of themselves.
    for piece in &got {
        if let Geometry::Line { .. } = piece.geometry {
            let line = path[piece.line - 1];
            assert!(piece.length() >= line.length() / 2.0 - 1e-9, "{piece:?}");
        }
    }
}

#[test]
fn corners_that_cannot_be_blended_stop() {
    let corner = [10.0, 400.0, 50.0, 0.0];
    let arc = |end: [f64; 4]| {
        let kind = MotionKind::Arc {
            end,
            center: [10.0, 405.0],
            plane: Plane::Xy,
            clockwise: false,
            turns: 1,
            feed: FEED,
        };
        with_tolerance(Motion::new(2, kind), P)
    };
    let cases = [
        // A helix.
        [linear(1, corner, P), arc([15.0, 405.0, 51.0, 0.0])],
        // A line leaving the arc's plane (it climbs in Z).
        [linear(1, [10.0, 400.0, 50.0, 0.0], P), arc([15.0, 405.0, 50.0, 0.0])],
        // C turns on the arc.
        [linear(1, corner, P), arc([15.0, 405.0, 50.0, 30.0])],
        // The arc comes back along the line (a turn of nearly 180°).
        [
            linear(1, corner, P),
            with_tolerance(arc_from(2, corner, 179.5f64.to_radians(), 5.0, 1.0), P),
        ],
    ];
    let starts = [START, [10.0, 380.0, 40.0, 0.0], START, START];
    for (motions, start) in cases.iter().zip(starts) {
        // (The arc leaves the corner heading +Y: a right-angle corner with the line.)
        let items: Vec<Blended> = Blender::new(motions.iter().copied().map(Ok::<_, ()>), start)
            .collect::<Result<_, ()>>()
            .expect("no error");
        let stopped = items.iter().all(|item| match item {
            Blended::Piece(piece) => {
                piece.ends_chain && !matches!(piece.geometry, Geometry::Fillet { .. })
            }
            Blended::Motion(_) => true,
        });
        assert!(stopped, "{items:?}");
    }
}

#[test]
fn a_fillet_between_a_rapid_and_an_arc_is_cut_at_its_middle() {
    let corner = [10.0, 400.0, 50.0, 0.0];
    let rapid = Motion { blend: Some(P), ..Motion::new(1, MotionKind::Rapid { end: corner }) };
    let motions = [rapid, with_tolerance(arc_from(2, corner, 1.0, 5.0, 1.0), P)];
    let got = blend(&motions, START);
    check_path(&got, &programmed(&motions, START), P).expect("a valid path");
    assert_eq!(got.len(), 4, "{got:?}");
    assert_eq!(
        (got[1].speed, got[1].line, got[2].speed, got[2].line),
        (Speed::Rapid, 1, Speed::Feed(FEED), 2)
    );
    assert!((got[1].radius().unwrap() - got[2].radius().unwrap()).abs() < 1e-12);
}

/// One step of a random chain: a line (length, turn in degrees from the heading) or an arc
/// (turn at its start in degrees, radius, sweep in degrees, signed).
#[derive(Debug, Clone, Copy)]
enum Step {
    Line(f64, f64),
    Arc(f64, f64, f64),
}

fn step() -> impl Strategy<Value = Step> {
    let turn = prop_oneof![-179.9..179.9f64, -10.0..10.0f64, Just(0.0)];
    prop_oneof![
        (prop_oneof![0.01..1.0f64, 1.0..30.0f64], turn.clone()).prop_map(|(l, t)| Step::Line(l, t)),
        (
            turn,
            prop_oneof![0.05..1.0f64, 1.0..50.0f64],
            prop_oneof![-350.0..-0.5f64, 0.5..350.0f64]
        )
            .prop_map(|(t, r, s)| Step::Arc(t, r, s)),
    ]
}

/// The motions of `steps` from `START`, heading +X, each under `tolerance`.
fn chain(steps: &[Step], tolerance: f64) -> Vec<Motion> {
    spirals(steps, tolerance, 0.0)
}

/// [`chain`], each arc's end `rounding` mm off its circle.
fn spirals(steps: &[Step], tolerance: f64, rounding: f64) -> Vec<Motion> {
    let (mut pose, mut heading) = (START, 0.0f64);
    let mut motions = Vec::new();
    for (index, step) in steps.iter().enumerate() {
        let motion = match *step {
            Step::Line(length, turn) => {
                heading += turn.to_radians();
                let end = [
                    pose[0] + length * heading.cos(),
                    pose[1] + length * heading.sin(),
                    pose[2],
                    0.0,
                ];
                linear(index + 1, end, tolerance)
            }
            Step::Arc(turn, radius, sweep) => {
                heading += turn.to_radians();
                let sweep = sweep.to_radians();
                let arc = spiral_from(index + 1, pose, heading, radius, sweep, rounding);
                let motion = with_tolerance(arc, tolerance);
                heading += sweep;
                motion
            }
        };
        pose = motion.kind.end().expect("a move");
        motions.push(motion);
    }
    motions
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Random chains of lines and arcs meeting at any angle: every point of the blended path
    /// within P of the programmed path, no kink where the robot does not stop, every trim
    /// within half its move.
    #[test]
    fn blended_line_arc_chains_stay_within_the_tolerance(
        steps in prop::collection::vec(step(), 1..12),
        tolerance in prop_oneof![0.001..0.5f64, Just(0.05)],
    ) {
        let motions = chain(&steps, tolerance);
        let path = programmed(&motions, START);
        let got = blend(&motions, START);
        check_path(&got, &path, tolerance)?;
        // Every corner that turns gets a fillet or a stop, and the chain stops at its end.
        let turning = steps[1..]
            .iter()
            .filter(|step| match step {
                Step::Line(_, turn) | Step::Arc(turn, _, _) => *turn != 0.0,
            })
            .count();
        let stops = got.iter().filter(|piece| piece.ends_chain).count();
        prop_assert_eq!(fillets(&got).len() + stops, turning + 1);
        // Each move is trimmed by at most half at either end: its midpoint stays on the
        // blended path, on what is left of it or (trimmed by exactly half at both ends) where
        // two fillets meet.
        for segment in &path {
            let middle = xyz(segment.point(0.5));
            let kept = got.iter().any(|piece| match piece.geometry {
                Geometry::Line { start, end } => Segment::line(start, end).distance_to(middle) < 1e-9,
                Geometry::Arc(arc) => distance_to(&arc, middle) < 1e-9,
                Geometry::Fillet { start, end, .. } => {
                    distance(xyz(start), middle).min(distance(xyz(end), middle)) < 1e-9
                }
            });
            prop_assert!(kept, "the middle of {segment:?} is cut away: {got:?}");
        }
    }

    /// The same with the arcs' ends off their circles by up to 0.1 µm (spirals, as rounded
    /// CAM coordinates make): the fillets touch the spirals themselves.
    #[test]
    fn blended_line_spiral_chains_stay_within_the_tolerance(
        steps in prop::collection::vec(step(), 1..12),
        tolerance in prop_oneof![0.001..0.5f64, Just(0.05)],
        rounding in prop_oneof![-1e-4..-1e-7f64, 1e-7..1e-4f64],
    ) {
        let motions = spirals(&steps, tolerance, rounding);
        let path = programmed(&motions, START);
        check_path(&blend(&motions, START), &path, tolerance)?;
    }
}

#[test]
fn a_line_meeting_a_spiral_gets_a_fillet_touching_it() {
    // A line, a quarter arc of radius 5 whose end is 0.1 µm off its circle (rounded CAM
    // coordinates), a line: both corners blended, the arc trimmed at both ends.
    let corner = [10.0, 400.0, 50.0, 0.0];
    let arc = with_tolerance(spiral_from(2, corner, 1.0, 5.0, 1.5, 1e-4), P);
    let end = arc.kind.end().expect("an end");
    let motions =
        [linear(1, corner, P), arc, linear(3, [end[0] + 5.0, end[1] + 5.0, 50.0, 0.0], P)];
    let path = programmed(&motions, START);
    assert!(path[1].circle().is_none() && path[1].planar_arc().is_some(), "a spiral");
    let got = blend(&motions, START);
    check_path(&got, &path, P).expect("a valid path");
    assert_eq!(fillets(&got).len(), 2, "{got:?}");
    assert_eq!(got.iter().filter(|piece| piece.ends_chain).count(), 1);
    let Geometry::Arc(trimmed) = got[2].geometry else { panic!("{:?}", got[2]) };
    assert!(trimmed.planar_arc().expect("an arc").center == path[1].planar_arc().unwrap().center);
}

#[test]
fn arcs_meeting_almost_head_on_get_no_fillet_turning_more_than_max_turn() {
    // Found by `biscara-joints`' random line-and-arc profiles: a 10 mm arc meets a 0.27 mm one
    // that leaves almost back along it. The corner turns by less than 179°, but the arcs bend
    // towards each other, so the fillet between them turns by nearly 180° — where its sweep's
    // sign is rounding (a fillet of −π, run backwards, that the planner could not time).
    let start = [-0.5612621765331802, 338.67592880479896, 50.0, 0.0];
    let counter_clockwise = |line: usize, end: [f64; 2], center: [f64; 2]| {
        let end = [end[0], end[1], 50.0, 0.0];
        let kind = MotionKind::Arc {
            end,
            center,
            plane: Plane::Xy,
            clockwise: false,
            turns: 1,
            feed: FEED,
        };
        with_tolerance(Motion::new(line, kind), 0.05)
    };
    let motions = [
        counter_clockwise(
            1,
            [-16.384842660851945, 325.9537539020059],
            [-7.753613430981999, 331.4200178807983],
        ),
        counter_clockwise(
            2,
            [-16.792286464034948, 325.6323076223935],
            [-16.634861150176746, 325.85171322013076],
        ),
    ];
    let path = programmed(&motions, start);
    let got = blend(&motions, start);
    check_path(&got, &path, 0.05).expect("a valid path");
    for piece in &got {
        if let Geometry::Fillet { sweep, .. } = piece.geometry {
            assert!(sweep.abs() <= biscara_blend::MAX_TURN_DEG.to_radians(), "{piece:?}");
            assert!(sweep > 0.0, "the corner turns left, its fillet too: {piece:?}");
        }
    }
}
