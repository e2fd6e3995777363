//! Corner blending under G64 P (issue 17) end to end: the "done when" of the issue — a CAM-style
//! polyline (a circle of 720 one-degree chords at F6000, then a square) under `G64 P0.05` takes
//! at most half the time of the same program under G61, no sample leaves the 0.05 mm tolerance,
//! no joint exceeds a limit in the CSV's own differences, and `check` finds nothing; `--blend`
//! gives a program that never says G61/G64 the same run as `G64 P`.

use std::fmt::Write as _;

use crate::util::{biscara, temp_dir};

/// The circle's centre and radius (a 1 mm chord per degree), the square's side, mm.
const CENTER: [f64; 2] = [0.0, 400.0];
const SIDE: f64 = 40.0;

fn radius() -> f64 {
    0.5 / 0.5f64.to_radians().sin()
}

/// The programmed polyline: the circle's start, 720 chords, the square.
fn vertices() -> Vec<[f64; 2]> {
    let r = radius();
    let mut points: Vec<[f64; 2]> = (0..=720)
        .map(|k| {
            let angle = f64::from(k).to_radians();
            [CENTER[0] + r * angle.cos(), CENTER[1] + r * angle.sin()]
        })
        .collect();
    let [x, y] = [CENTER[0] + r, CENTER[1]];
    points.extend([[x, y + SIDE], [x - SIDE, y + SIDE], [x - SIDE, y], [x, y]]);
    points
}

/// The program, with `mode` (G61, G64 P0.05 or nothing) on its second line. Coordinates are
/// written with 6 decimals, so that the programmed path is the polyline of `vertices` up to
/// 5e-7 mm.
fn program(mode: &str) -> String {
    let mut text = format!("G21 G90 G17\n{mode}\nG0 Z50\n");
    let points = vertices();
    let _ = writeln!(text, "G0 X{:.6} Y{:.6}", points[0][0], points[0][1]);
    text.push_str("F6000\n");
    for [x, y] in &points[1..] {
        let _ = writeln!(text, "G1 X{x:.6} Y{y:.6}");
    }
    text.push_str("M2\n");
    text
}

fn distance_to_segment(p: [f64; 3], a: [f64; 3], b: [f64; 3]) -> f64 {
    let ab = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let length2: f64 = ab.iter().map(|d| d * d).sum();
    let along: f64 = (0..3).map(|k| (p[k] - a[k]) * ab[k]).sum();
    let t = if length2 > 0.0 { (along / length2).clamp(0.0, 1.0) } else { 0.0 };
    (0..3).map(|k| (p[k] - a[k] - t * ab[k]).powi(2)).sum::<f64>().sqrt()
}

fn rows(csv: &str) -> Vec<Vec<f64>> {
    csv.lines()
        .skip(1)
        .map(|line| line.split(',').map(|value| value.parse().expect("number")).collect())
        .collect()
}

/// The path CSV of `interpolate NAME --precision 9` in `dir`, as rows.
fn interpolated(dir: &std::path::Path, name: &str) -> Vec<Vec<f64>> {
    let run = biscara(dir, &["interpolate", name, "--precision", "9"]);
    run.success();
    rows(&run.stdout)
}

/// The slowest XY speed from one row to the next of a path CSV's `rows`, leaving out the first
/// and last tenth (where the robot starts and stops), mm/s.
fn slowest_between_the_ends(rows: &[Vec<f64>]) -> f64 {
    let speeds: Vec<f64> = rows
        .windows(2)
        .map(|pair| {
            (pair[1][1] - pair[0][1]).hypot(pair[1][2] - pair[0][2]) / (pair[1][0] - pair[0][0])
        })
        .collect();
    let middle = &speeds[speeds.len() / 10..speeds.len() * 9 / 10];
    middle.iter().copied().fold(f64::INFINITY, f64::min)
}

/// The largest ratio of a joint's central-difference acceleration to its limit (the default
/// robot), over the rows of a joint CSV in radians and mm.
fn peak_acceleration_ratio(joints: &[Vec<f64>]) -> f64 {
    let robot = biscara::kinematics::Robot::default();
    let limits = robot.joint_max_acceleration.to_array();
    let limits =
        [limits[0].to_radians(), limits[1].to_radians(), limits[2].to_radians(), limits[3]];
    let mut peak = 0.0f64;
    for window in joints.windows(3) {
        let dt = window[2][0] - window[1][0];
        for j in 0..4 {
            let a = (window[2][j + 1] - 2.0 * window[1][j + 1] + window[0][j + 1]) / (dt * dt);
            peak = peak.max(a.abs() / limits[j]);
        }
    }
    peak
}

/// `joints` on `program` in `dir` keeps every joint's acceleration (its CSV's own central
/// differences) within the limit, and `check` finds nothing.
fn assert_within_the_joint_limits_and_clean(dir: &std::path::Path, program: &str) {
    let joints = biscara(dir, &["joints", program, "--precision", "9"]);
    joints.success();
    let ratio = peak_acceleration_ratio(&rows(&joints.stdout));
    assert!(ratio <= 1.0 + 1e-3, "a joint accelerates at {ratio} of its limit");
    let check = biscara(dir, &["check", program]);
    check.success();
    assert!(check.stdout.contains("no problem found"), "{}", check.stdout);
}

#[test]
fn a_cam_circle_under_g64_p0_05_takes_half_the_time_of_exact_stop() {
    let dir = temp_dir("blending");
    std::fs::write(dir.join("g61.ngc"), program("G61")).expect("write");
    std::fs::write(dir.join("g64.ngc"), program("G64 P0.05")).expect("write");
    std::fs::write(dir.join("plain.ngc"), program("")).expect("write");
    let path = |name: &str, extra: &[&str]| {
        let mut args = vec!["interpolate", name, "--precision", "9"];
        args.extend(extra);
        let run = biscara(&dir, &args);
        run.success();
        run.stdout.clone()
    };
    let exact = rows(&path("g61.ngc", &[]));
    let blended_csv = path("g64.ngc", &[]);
    let blended = rows(&blended_csv);
    // --blend on a program that never says G61/G64 is G64 P; on one that says G61, nothing.
    assert_eq!(path("plain.ngc", &["--blend", "0.05"]), blended_csv);
    assert_eq!(rows(&path("g61.ngc", &["--blend", "0.05"])), exact);
    assert_eq!(rows(&path("plain.ngc", &[])), exact);

    let (t_exact, t_blended) = (exact[exact.len() - 1][0], blended[blended.len() - 1][0]);
    assert!(t_blended <= 0.5 * t_exact, "G64 P0.05 takes {t_blended} s, G61 {t_exact} s");
    // Every sample within 0.05 mm of the programmed path: from the home pose (the first row)
    // up to Z50, across to the circle's start, the chords and the square.
    let home = [blended[0][1], blended[0][2], blended[0][3]];
    let points = vertices();
    let mut path = vec![home, [home[0], home[1], 50.0]];
    path.extend(points.iter().map(|&[x, y]| [x, y, 50.0]));
    let mut worst = 0.0f64;
    for row in &blended {
        let distance = path
            .windows(2)
            .map(|pair| distance_to_segment([row[1], row[2], row[3]], pair[0], pair[1]))
            .fold(f64::INFINITY, f64::min);
        worst = worst.max(distance);
    }
    assert!(worst <= 0.05 + 1e-6, "a sample is {worst} mm off the path");
    assert!(worst > 0.01, "the corners are cut: {worst}");
    // The chain stops on the last programmed point.
    let last = &blended[blended.len() - 1];
    assert!((last[1] - points[0][0]).abs() < 1e-6 && (last[2] - points[0][1]).abs() < 1e-6);

    assert_within_the_joint_limits_and_clean(&dir, "g64.ngc");
}

#[test]
fn a_bad_blend_tolerance_is_refused() {
    let dir = temp_dir("blending-bad");
    std::fs::write(dir.join("plain.ngc"), program("")).expect("write");
    for bad in ["abc", "-1", "1000", "NaN"] {
        let run = biscara(&dir, &["interpolate", "plain.ngc", &format!("--blend={bad}")]);
        run.expect_code(2);
        assert!(run.stdout.is_empty(), "{run}");
        assert!(run.stderr.contains("--blend"), "{run}");
    }
}

/// A stadium (two half circles of radius 2 mm joined by 4 mm lines, each tangent to the next),
/// 20 times round at F3000, with `mode` on its second line.
fn stadium(mode: &str) -> String {
    let mut text = format!("G21 G90 G17\n{mode}\nG0 Z50\nG0 X-2 Y398\nF3000\n");
    for _ in 0..20 {
        text.push_str("G1 X2 Y398\nG3 X2 Y402 I0 J2\nG1 X-2 Y402\nG3 X-2 Y398 I0 J-2\n");
    }
    text.push_str("M2\n");
    text
}

#[test]
fn lines_and_tangent_arcs_run_through_without_stopping() {
    let dir = temp_dir("blending-arcs");
    std::fs::write(dir.join("g61.ngc"), stadium("G61")).expect("write");
    std::fs::write(dir.join("g64.ngc"), stadium("G64 P0.05")).expect("write");
    let path = |name: &str| interpolated(&dir, name);
    let (exact, blended) = (path("g61.ngc"), path("g64.ngc"));
    // From the first arrival at the stadium's start, every sample lies on it: the arcs are run
    // as programmed (no fillet: every junction is tangent) ...
    let start = blended
        .iter()
        .position(|row| (row[1] + 2.0).abs() < 1e-9 && (row[2] - 398.0).abs() < 1e-9)
        .expect("the stadium's start");
    let on_stadium = &blended[start..];
    for row in on_stadium {
        let d =
            distance_to_segment([row[1], row[2], row[3]], [-2.0, 400.0, 50.0], [2.0, 400.0, 50.0]);
        assert!((d - 2.0).abs() < 1e-6, "t = {}: {} mm off the stadium", row[0], (d - 2.0).abs());
    }
    // ... and the robot never stops on the way round: the slowest step, away from the two
    // ends, is well above half the feed (50 mm/s).
    let slowest = slowest_between_the_ends(on_stadium);
    assert!(slowest > 25.0, "the robot slows to {slowest} mm/s between the ends");
    let (t_exact, t_blended) = (exact[exact.len() - 1][0], blended[blended.len() - 1][0]);
    // (80 stops saved, a hundredth of a second each at this feed.)
    assert!(t_blended < 0.95 * t_exact, "G64 P0.05 takes {t_blended} s, G61 {t_exact} s");

    assert_within_the_joint_limits_and_clean(&dir, "g64.ngc");
}

/// A keyhole (a 6 mm slot up into a circle of radius 8 mm, the circle's arc meeting the slot's
/// sides at corners of 68°), 10 times round at F3000, with `mode` on its second line.
fn keyhole(mode: &str) -> String {
    let mut text = format!("G21 G90 G17\n{mode}\nG0 Z50\nG0 X-3 Y390\nF3000\n");
    for _ in 0..10 {
        text.push_str("G1 X3 Y390\nG1 X3 Y402.584\nG3 X-3 Y402.584 I-3 J7.416\nG1 X-3 Y390\n");
    }
    text.push_str("M2\n");
    text
}

/// The distance from `p` to the keyhole's programmed path (its lines and its arc).
fn distance_to_keyhole(p: [f64; 3]) -> f64 {
    let corners = [[-3.0, 390.0], [3.0, 390.0], [3.0, 402.584], [-3.0, 402.584]];
    let lines = [(corners[0], corners[1]), (corners[1], corners[2]), (corners[3], corners[0])];
    let line = lines
        .iter()
        .map(|(a, b)| distance_to_segment(p, [a[0], a[1], 50.0], [b[0], b[1], 50.0]))
        .fold(f64::INFINITY, f64::min);
    // The arc: the circle about (0, 410) of radius 8 except below y = 402.584 between the
    // slot's sides.
    let (dx, dy) = (p[0], p[1] - 410.0);
    let arc = if dy < -7.416 && dx.abs() < 3.0 {
        f64::INFINITY
    } else {
        ((dx.hypot(dy) - 3f64.hypot(7.416)).powi(2) + (p[2] - 50.0).powi(2)).sqrt()
    };
    line.min(arc)
}

#[test]
fn lines_meeting_arcs_at_corners_are_blended_within_the_tolerance() {
    let dir = temp_dir("blending-keyhole");
    std::fs::write(dir.join("g61.ngc"), keyhole("G61")).expect("write");
    std::fs::write(dir.join("g64.ngc"), keyhole("G64 P0.05")).expect("write");
    let path = |name: &str| interpolated(&dir, name);
    let (exact, blended) = (path("g61.ngc"), path("g64.ngc"));
    // Every sample within P of the programmed path (from the home pose up to Z50, across to
    // the keyhole's start, round it), and the corners (the arc's with the slot's sides among
    // them) cut.
    let home = [blended[0][1], blended[0][2], blended[0][3]];
    let approach = [home, [home[0], home[1], 50.0], [-3.0, 390.0, 50.0]];
    let worst =
        blended
            .iter()
            .map(|row| {
                let p = [row[1], row[2], row[3]];
                let near = distance_to_segment(p, approach[0], approach[1])
                    .min(distance_to_segment(p, approach[1], approach[2]));
                distance_to_keyhole(p).min(near)
            })
            .fold(0.0f64, f64::max);
    assert!(worst <= 0.05 + 1e-6, "a sample is {worst} mm off the keyhole");
    assert!(worst > 0.01, "the corners are cut: {worst}");
    let start = blended.iter().position(|row| row[2] < 390.5).expect("the keyhole");
    let on_keyhole = &blended[start..];
    // Near the arc's corner with the slot's right side, the blended path leaves the line
    // before the corner and joins the arc after it: no sample on the corner itself.
    let at_corner = on_keyhole
        .iter()
        .map(|row| (row[1] - 3.0).hypot(row[2] - 402.584))
        .fold(f64::INFINITY, f64::min);
    assert!(at_corner > 0.01, "a sample {at_corner} mm from the corner");
    // The robot never stops on the way round: the slowest step, away from the ends, above a
    // fifth of the feed (50 mm/s).
    let slowest = slowest_between_the_ends(on_keyhole);
    assert!(slowest > 10.0, "the robot slows to {slowest} mm/s between the ends");
    let (t_exact, t_blended) = (exact[exact.len() - 1][0], blended[blended.len() - 1][0]);
    assert!(t_blended <= t_exact, "G64 P0.05 takes {t_blended} s, G61 {t_exact} s");

    assert_within_the_joint_limits_and_clean(&dir, "g64.ngc");
}

#[test]
fn g64_q_merges_nearly_collinear_chords_within_p_plus_q() {
    // The CAM circle under G64 P0.01 Q0.05: runs of chords within 0.05 mm of one straight move
    // are merged (LinuxCNC's naive-CAM detector) before the corners are blended, so the path
    // strays up to P + Q from the chords, and the robot, with fewer corners, is no slower.
    let dir = temp_dir("blending-q");
    std::fs::write(dir.join("p.ngc"), program("G64 P0.01")).expect("write");
    std::fs::write(dir.join("pq.ngc"), program("G64 P0.01 Q0.05")).expect("write");
    let path = |name: &str| interpolated(&dir, name);
    let (p, pq) = (path("p.ngc"), path("pq.ngc"));
    let home = [pq[0][1], pq[0][2], pq[0][3]];
    let mut programmed = vec![home, [home[0], home[1], 50.0]];
    programmed.extend(vertices().iter().map(|&[x, y]| [x, y, 50.0]));
    let worst = |rows: &[Vec<f64>]| {
        rows.iter()
            .map(|row| {
                programmed
                    .windows(2)
                    .map(|pair| distance_to_segment([row[1], row[2], row[3]], pair[0], pair[1]))
                    .fold(f64::INFINITY, f64::min)
            })
            .fold(0.0f64, f64::max)
    };
    let (worst_p, worst_pq) = (worst(&p), worst(&pq));
    assert!(worst_p <= 0.01 + 1e-6, "P0.01 alone: {worst_p} mm off");
    assert!(worst_pq <= 0.06 + 1e-6, "P0.01 Q0.05: {worst_pq} mm off");
    assert!(worst_pq > 0.02, "no chord merged: {worst_pq} mm off at most");
    let (t_p, t_pq) = (p[p.len() - 1][0], pq[pq.len() - 1][0]);
    assert!(t_pq <= t_p, "Q0.05 takes {t_pq} s, without Q {t_p} s");
    assert_within_the_joint_limits_and_clean(&dir, "pq.ngc");
}
