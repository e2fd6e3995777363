//! G64 Q (LinuxCNC's naive-CAM detector) before blending: nearly collinear feed moves merged
//! while every left-out end point lies within Q of the merged move; the blended path within
//! P + Q of the program.

use biscara_blend::{Blended, Blender, MAX_MERGED, NaiveCam, Piece};
use biscara_motion::{Feed, Motion, MotionKind};

const FEED: Feed = Feed { mm_per_min: 6000.0, inverse_time: false };

fn linear(line: usize, end: [f64; 4], blend: Option<f64>) -> Motion {
    Motion { blend, ..Motion::new(line, MotionKind::Linear { end, feed: FEED }) }
}

/// `motions`, each straight feed move under G64 given the naive-CAM tolerance `q` (none for 0),
/// through the stage.
fn merge(motions: &[Motion], start: [f64; 4], q: f64) -> Vec<Motion> {
    let with_q = motions.iter().map(|motion| {
        let straight = matches!(motion.kind, MotionKind::Linear { .. }) && motion.blend.is_some();
        let naive_cam = (straight && q > 0.0).then_some(q);
        Ok::<_, ()>(Motion { naive_cam, ..*motion })
    });
    NaiveCam::new(with_q, start).collect::<Result<_, _>>().expect("no error")
}

/// [`super::distance_to_segment`] of poses: their XYZ.
fn distance_to_segment(p: [f64; 4], a: [f64; 4], b: [f64; 4]) -> f64 {
    let xyz = |pose: [f64; 4]| [pose[0], pose[1], pose[2]];
    super::distance_to_segment(xyz(p), xyz(a), xyz(b))
}

/// A circle of 720 half-degree chords (radius 50 mm) at Z50.
fn circle() -> Vec<[f64; 4]> {
    (0..=720)
        .map(|k| {
            let angle = (f64::from(k) * 0.5).to_radians();
            [50.0 * angle.cos(), 400.0 + 50.0 * angle.sin(), 50.0, 0.0]
        })
        .collect()
}

/// The end points of `motions` from `start`.
fn ends(motions: &[Motion], start: [f64; 4]) -> Vec<[f64; 4]> {
    std::iter::once(start).chain(motions.iter().filter_map(|m| m.kind.end())).collect()
}

#[test]
fn a_cam_circle_under_q_merges_its_chords_within_q() {
    let vertices = circle();
    let program_with = |q: f64, p: f64| -> Vec<Motion> {
        let motions: Vec<Motion> =
            vertices[1..].iter().enumerate().map(|(k, &end)| linear(k + 1, end, Some(p))).collect();
        merge(&motions, vertices[0], q)
    };
    let program = |q: f64| program_with(q, 0.0);
    // Q0 merges nothing; Q0.05 merges: a chord of a 50 mm circle is within 0.05 mm of its arc
    // up to 2·acos(1 − 0.05/50) = 5.1° of it, ten half-degree chords a move.
    let (kept, merged) = (program(0.0), program(0.05));
    assert_eq!(kept.len(), 720);
    assert_eq!(merged.len(), 72, "{} moves", merged.len());
    let merged_ends = ends(&merged, vertices[0]);
    assert_eq!(merged_ends[merged_ends.len() - 1], vertices[720]);
    // Every merged move ends on a programmed point, and every programmed point it leaves out
    // lies within Q of it.
    let mut next = 0;
    for pair in merged_ends.windows(2) {
        let from = next;
        assert_eq!(pair[0], vertices[from]);
        let to = from
            + 1
            + vertices[from + 1..].iter().position(|v| *v == pair[1]).expect("a programmed end");
        assert!(to - from <= MAX_MERGED);
        for dropped in &vertices[from + 1..to] {
            let d = distance_to_segment(*dropped, pair[0], pair[1]);
            assert!(d <= 0.05, "a dropped point {d} mm off");
        }
        next = to;
    }
    // Lines: each merged move carries the line of the last move it replaces.
    assert_eq!(merged[merged.len() - 1].line, 720);

    // Blended afterwards: fewer pieces (G64 P0 Q0.05 against P0 Q0), and with P0.01 the
    // blended path within P + Q of the programmed chords.
    let blend = |motions: Vec<Motion>| -> Vec<Piece> {
        Blender::new(motions.into_iter().map(Ok::<_, ()>), vertices[0])
            .map(|item| match item.expect("no error") {
                Blended::Piece(piece) => piece,
                Blended::Motion(motion) => panic!("not blended: {motion:?}"),
            })
            .collect()
    };
    let (plain, fewer) = (blend(kept), blend(merged));
    assert!(fewer.len() < plain.len() / 5, "{} vs {} pieces", fewer.len(), plain.len());
    let mut worst = 0.0f64;
    for piece in &blend(program_with(0.05, 0.01)) {
        for step in 0..=20 {
            let p = piece.point(f64::from(step) / 20.0);
            let nearest = vertices
                .windows(2)
                .map(|w| distance_to_segment(p, w[0], w[1]))
                .fold(f64::INFINITY, f64::min);
            worst = worst.max(nearest);
        }
    }
    assert!(worst <= 0.06 + 1e-9, "{worst}");
    // (Q's part is there: merged chords leave the circle by up to 0.05 mm.)
    assert!(worst > 0.04, "{worst}");
}

#[test]
fn only_g1_moves_alike_are_merged() {
    let start = [0.0, 400.0, 50.0, 0.0];
    let slow = Feed { mm_per_min: 600.0, inverse_time: false };
    let motions = [
        linear(1, [1.0, 400.0, 50.0, 0.0], Some(0.1)),
        linear(2, [2.0, 400.001, 50.0, 0.0], Some(0.1)),
        // Another feed: not merged with the two before it.
        Motion {
            blend: Some(0.1),
            ..Motion::new(3, MotionKind::Linear { end: [3.0, 400.0, 50.0, 0.0], feed: slow })
        },
        // A rapid, a move under exact stop, a move turning C, an event: each ends the chain.
        Motion {
            blend: Some(0.1),
            ..Motion::new(4, MotionKind::Rapid { end: [4.0, 400.0, 50.0, 0.0] })
        },
        linear(5, [5.0, 400.0, 50.0, 0.0], Some(0.1)),
        linear(6, [6.0, 400.0, 50.0, 0.0], None),
        linear(7, [7.0, 400.0, 50.0, 0.0], Some(0.1)),
        linear(8, [8.0, 400.0, 50.0, 10.0], Some(0.1)),
        linear(9, [9.0, 400.0, 50.0, 10.0], Some(0.1)),
        Motion::new(10, MotionKind::Pick),
        linear(11, [10.0, 400.0, 50.0, 10.0], Some(0.1)),
        linear(12, [11.0, 400.0, 50.0, 10.0], Some(0.1)),
        // A corner beyond Q: not merged.
        linear(13, [11.0, 401.0, 50.0, 10.0], Some(0.1)),
    ];
    let got: Vec<usize> = merge(&motions, start, 0.01).iter().map(|m| m.line).collect();
    assert_eq!(got, [2, 3, 4, 5, 6, 7, 8, 9, 10, 12, 13]);
    let merged = merge(&motions, start, 0.01);
    assert_eq!(merged[0].kind.end(), Some([2.0, 400.001, 50.0, 0.0]));
    // No Q: everything passes as it is.
    assert_eq!(merge(&motions, start, 0.0), motions);
    // Another Q ends the chain too.
    let mut other = merge(&motions[..2], start, 0.0);
    other[0].naive_cam = Some(0.01);
    other[1].naive_cam = Some(0.02);
    let got = NaiveCam::new(other.iter().copied().map(Ok::<_, ()>), start);
    assert_eq!(got.count(), 2);
}

#[test]
fn an_error_comes_after_what_was_read_before_it() {
    let start = [0.0, 400.0, 50.0, 0.0];
    let source = [
        Ok(linear(1, [1.0, 400.0, 50.0, 0.0], Some(0.1))),
        Ok(linear(2, [2.0, 400.0, 50.0, 0.0], Some(0.1))),
        Err("bad line 3"),
        Ok(linear(4, [3.0, 400.0, 50.0, 0.0], Some(0.1))),
    ];
    let source = source.map(|item| item.map(|motion| Motion { naive_cam: Some(0.1), ..motion }));
    let got: Vec<Result<Motion, &str>> = NaiveCam::new(source.into_iter(), start).collect();
    assert_eq!(got.len(), 2, "{got:?}");
    assert_eq!(got[0].as_ref().map(|m| m.line), Ok(2));
    assert_eq!(got[1], Err("bad line 3"));
}

#[test]
fn moves_that_feed_filament_are_never_merged() {
    // Three collinear moves: merged without E, each kept with its own E.
    let start = [0.0, 400.0, 50.0, 0.0];
    let motions: Vec<Motion> =
        (1..=3).map(|k| linear(k, [f64::from(k as u32), 400.0, 50.0, 0.0], Some(0.0))).collect();
    assert_eq!(merge(&motions, start, 0.05).len(), 1);
    let fed: Vec<Motion> =
        motions.iter().map(|motion| Motion { extrude: Some(0.1), ..*motion }).collect();
    let kept = merge(&fed, start, 0.05);
    assert_eq!(kept.len(), 3);
    assert!(kept.iter().all(|motion| motion.extrude == Some(0.1)));
}
