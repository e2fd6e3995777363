//! Features through the library: the home pose, the origin, G28, units, errors and their
//! locations. (Conformance with LinuxCNC itself: `conformance.rs`, on `tests/conformance/`,
//! against rs274's recorded results.)

use biscara_gcode::{Config, GcodeError, interpret};
use biscara_motion::{Feed, MotionKind, Plane};

const HOME: [f64; 4] = [0.0, 460.8, 100.0, 0.0];

/// The motions of `program` started at [`HOME`] with `origin`.
#[track_caller]
fn motions(program: &str, origin: [f64; 4]) -> Vec<(usize, MotionKind)> {
    let config = Config { home: HOME, origin, ..Config::default() };
    interpret(program.as_bytes(), &config)
        .map(|result| result.map(|motion| (motion.line, motion.kind)))
        .collect::<Result<_, _>>()
        .unwrap_or_else(|err| panic!("{err}"))
}

/// The error of `program`, as `LINE:COL: message`.
#[track_caller]
fn error(program: &str) -> GcodeError {
    interpret(program.as_bytes(), &Config::default())
        .find_map(Result::err)
        .unwrap_or_else(|| panic!("no error for {program:?}"))
}

fn feed(mm_per_min: f64) -> Feed {
    Feed { mm_per_min, inverse_time: false }
}

#[test]
fn the_program_starts_at_home_and_g28_returns_there() {
    let got = motions("G91 G0 X10\nG90 G28\nM2\n", [0.0; 4]);
    assert_eq!(got[0], (1, MotionKind::Rapid { end: [10.0, 460.8, 100.0, 0.0] }));
    // G28: the intermediate point (here: where it is), then home.
    assert_eq!(got[1], (2, MotionKind::Rapid { end: [10.0, 460.8, 100.0, 0.0] }));
    assert_eq!(got[2], (2, MotionKind::Rapid { end: HOME }));
    assert_eq!(got[3], (3, MotionKind::End));
}

#[test]
fn the_origin_is_a_g54_offset_before_the_first_line() {
    let origin = [5.0, 300.0, 20.0, 90.0];
    let got = motions("G0 X0 Y0 Z0 C0\nG55 G0 X0\nG54 G1 X1 F100\nG53 G0 X0\nM2\n", origin);
    assert_eq!(got[0].1, MotionKind::Rapid { end: [5.0, 300.0, 20.0, 90.0] });
    assert_eq!(got[1].1, MotionKind::Rapid { end: [0.0, 300.0, 20.0, 90.0] });
    assert_eq!(got[2].1, MotionKind::Linear { end: [6.0, 300.0, 20.0, 90.0], feed: feed(100.0) });
    assert_eq!(got[3].1, MotionKind::Rapid { end: [0.0, 300.0, 20.0, 90.0] });
}

#[test]
fn inches_become_millimetres_and_arcs_keep_their_centres() {
    let got = motions("G20 G0 X1 Y10 Z1\nG2 X2 Y11 I0 J1 F10\nG18 G3 X1 Z2 R1\nM2\n", [0.0; 4]);
    assert_eq!(got[0].1, MotionKind::Rapid { end: [25.4, 254.0, 25.4, 0.0] });
    let MotionKind::Arc { end, center, plane, clockwise, turns, feed: f } = got[1].1 else {
        panic!("{got:?}")
    };
    assert!((end[0] - 50.8).abs() < 1e-9 && (end[1] - 279.4).abs() < 1e-9);
    assert!((center[0] - 25.4).abs() < 1e-9 && (center[1] - 279.4).abs() < 1e-9);
    assert_eq!((plane, clockwise, turns), (Plane::Xy, true, 1));
    assert!((f.mm_per_min - 254.0).abs() < 1e-9);
    let MotionKind::Arc { plane, clockwise, .. } = got[2].1 else { panic!("{got:?}") };
    assert_eq!((plane, clockwise), (Plane::Xz, false));
}

#[test]
fn inverse_time_feeds_become_mm_per_minute() {
    // 30 mm at F2 (half a minute) = 60 mm/min; a C-only move: the feed is in deg/min.
    let got = motions("G0 X0 Y0 Z0\nG93 G1 X30 F2\nG1 C90 F4\nM2\n", [0.0; 4]);
    let inverse = |mm_per_min| Feed { mm_per_min, inverse_time: true };
    assert_eq!(got[1].1, MotionKind::Linear { end: [30.0, 0.0, 0.0, 0.0], feed: inverse(60.0) });
    assert_eq!(got[2].1, MotionKind::Linear { end: [30.0, 0.0, 0.0, 90.0], feed: inverse(360.0) });
}

#[test]
fn gripper_events_come_in_linuxcncs_order_within_a_block() {
    let got = motions("M3 G4 P0.5 G0 X1 M0\nM2\n", [0.0; 4]);
    let kinds: Vec<&str> = got.iter().map(|(_, kind)| kind.name()).collect();
    assert_eq!(kinds, ["pick", "dwell", "rapid", "pause", "end"]);
}

#[test]
fn errors_point_at_the_word() {
    let err = error("G1 F100\nG1 X1 Y[2 + SQRT[-4]]\nM2\n");
    assert_eq!(err.to_string(), "2:13: Negative argument to sqrt");
    let location = err.location().expect("a location");
    assert_eq!(location.snippet(), "G1 X1 Y[2 + SQRT[-4]]\n            ^^^^");
    let err = error("G0 X1\n  G0 Z2 A3\nM2\n");
    assert_eq!(err.to_string(), "2:9: A axis word: this robot has the axes X Y Z C only");
    assert!(matches!(err, GcodeError::ForeignAxis { letter: 'A', .. }));
    let err = error("G0 X1\nG83 X1 Z-1 R1 F10\nM2\n");
    assert_eq!(err.to_string(), "2:1: Q word missing with g83");
    let err = error("o10 if [1]\nG0 X1\no10 endif\no10 if [1]\no10 endif\nM2\n");
    assert_eq!(
        err.to_string(),
        "4:1: 4: duplicate O-word label - already defined in line 1: 'o10 if [1]'"
    );
}

/// The value of expression `expression`, read back as the X of a rapid.
#[track_caller]
fn value(expression: &str) -> f64 {
    let program = format!("#1=2 #<r>=3\nG0 X{expression}\nM2\n");
    match motions(&program, [0.0; 4])[0].1 {
        MotionKind::Rapid { end } => end[0],
        other => panic!("{other:?}"),
    }
}

#[test]
fn expressions_follow_linuxcncs_precedence_and_functions() {
    let cases: [(&str, f64); 24] = [
        ("[1+2*3]", 7.0),
        ("[2**3**2]", 64.0), // left to right, as LinuxCNC
        ("[-2**2]", 4.0),    // unary minus binds to the number
        ("[1-2-3]", -4.0),
        ("[10/4/5]", 0.5),
        ("[7 MOD 3]", 1.0),
        ("[-7 MOD 3]", 2.0), // the result takes the divisor's sign
        ("[1 EQ 1.00002]", 1.0),
        ("[1 EQ 1.0002]", 0.0),
        ("[1+2*3 LT 7]", 0.0),
        ("[3 GT 2 AND 0]", 0.0),
        ("[0 OR 2]", 1.0),
        ("[1 XOR 1]", 0.0),
        ("[ROUND[-2.5]]", -3.0),
        ("[FIX[-2.5]]", -3.0),
        ("[FUP[-2.5]]", -2.0),
        ("[ATAN[1]/[-1]]", 135.0),
        ("[SQRT[[3**2]+[4**2]]]", 5.0),
        ("[ABS[-#1]]", 2.0),
        ("#[#1-1]", 2.0),
        ("[#<r>*2]", 6.0),
        ("[EXISTS[#<r>]+EXISTS[#<nope>]]", 1.0),
        ("-[1+1]", -2.0),
        ("[s i n[90]]", 1.0),
    ];
    for (expression, expected) in cases {
        let got = value(expression);
        assert!((got - expected).abs() < 1e-12, "{expression} = {got}, expected {expected}");
    }
}

#[test]
fn assignments_take_effect_after_the_line() {
    let got = motions(
        "#1=2 #1=3 G0 X#1\nG0 X#1\n#<a>=1 #<a>=[#<a>+1] G0 Y#<a>\nG0 Y#<a>\nM2\n",
        [0.0; 4],
    );
    let xs: Vec<f64> = got.iter().filter_map(|(_, kind)| kind.end()).map(|end| end[0]).collect();
    let ys: Vec<f64> = got.iter().filter_map(|(_, kind)| kind.end()).map(|end| end[1]).collect();
    assert_eq!(xs, [0.0, 3.0, 3.0, 3.0]);
    // LinuxCNC creates #<a> (= 0) when it reads the assignment: the second assignment reads 0,
    // and Y#<a> on the same line reads 0 too.
    assert_eq!(ys[2..], [0.0, 1.0][..]);
}

/// The blend tolerance each move carries, for `program` interpreted with `config`.
#[track_caller]
fn blends(program: &str, config: &Config) -> Vec<(usize, Option<f64>)> {
    interpret(program.as_bytes(), config)
        .map(|result| result.map(|motion| (motion.line, motion.blend)))
        .collect::<Result<_, _>>()
        .unwrap_or_else(|err| panic!("{err}"))
}

#[test]
fn moves_carry_the_path_control_mode() {
    let program = "G1 X1 F100\nG64 P0.05\nG1 X2\nG0 X3\nG2 X4 I0.5\nG4 P1\nG64\nG1 X5\n\
                   G64 P-1\nG1 X6\nG61\nG1 X7\nG64 P0.1 Q0\nG1 X8\nG61.1\nG1 X9\nM2\n";
    let got = blends(program, &Config::default());
    let expected = [
        (1, None),
        (3, Some(0.05)),
        (4, Some(0.05)),
        (5, Some(0.05)),
        // A dwell is not a move and carries none.
        (6, None),
        (8, Some(0.0)),
        (10, Some(0.0)),
        (12, None),
        (14, Some(0.1)),
        (16, None),
        (17, None),
    ];
    assert_eq!(got, expected);
    // Inches: P is in the program's units, like every length.
    let inches = blends("G20 G64 P0.01\nG1 X1 F10\nM2\n", &Config::default());
    assert!((inches[0].1.unwrap() - 0.254).abs() < 1e-12, "{inches:?}");
}

#[test]
fn the_configured_path_control_mode_holds_until_the_program_says_one() {
    let config = Config { blend: Some(0.02), ..Config::default() };
    let got = blends("G1 X1 F100\nG61\nG1 X2\nM2\n", &config);
    assert_eq!(got, [(1, Some(0.02)), (3, None), (4, None)]);
}

#[test]
fn straight_feed_moves_carry_the_naive_cam_tolerance() {
    // The interpreter keeps every move (the merging is biscara-blend's, before the blends); a
    // G1 under G64 with a positive Q carries Q in millimetres, nothing else does.
    let config = Config::default();
    let naive_cam = |program: &str| -> Vec<(usize, Option<f64>, Option<f64>)> {
        interpret(program.as_bytes(), &config)
            .map(|result| result.map(|motion| (motion.line, motion.blend, motion.naive_cam)))
            .collect::<Result<_, _>>()
            .unwrap_or_else(|err| panic!("{err}"))
    };
    for program in ["G64 P0.05 Q0.06\n", "G64 P0.05 Q0.05\n", "G64 P0.05 Q0.01\n", "G64 Q0.2\n"] {
        let text = format!("{program}G1 X1 F100\nG1 X2 Y0.001\nG0 X3\nG2 X4 I0.5\nM2\n");
        let p = if program.contains("P0.05") { 0.05 } else { 0.0 };
        let q: f64 = program.split('Q').nth(1).and_then(|q| q.trim().parse().ok()).expect("Q");
        // (M2 ends the program: an event, under no blend.)
        let expected = vec![
            (2, Some(p), Some(q)),
            (3, Some(p), Some(q)),
            (4, Some(p), None),
            (5, Some(p), None),
            (6, None, None),
        ];
        assert_eq!(naive_cam(&text), expected, "{program}");
    }
    // Q0, a negative Q, G61 after G64 Q: none; inches: Q in the program's units.
    let got = naive_cam("G64 P0.1 Q0\nG1 X1 F100\nG64 Q-1\nG1 X2\nG64 Q0.1\nG61\nG1 X3\nM2\n");
    assert!(got.iter().all(|(_, _, q)| q.is_none()), "{got:?}");
    let inches = naive_cam("G20 G64 P0.01 Q0.01\nG1 X1 F10\nM2\n");
    assert!((inches[0].2.unwrap() - 0.254).abs() < 1e-12, "{inches:?}");
}

/// The XY end of a move (of any kind with one).
fn xy(kind: &MotionKind) -> [f64; 2] {
    let end = kind.end().unwrap_or_else(|| panic!("no end: {kind:?}"));
    [end[0], end[1]]
}

#[track_caller]
fn assert_near(got: [f64; 2], want: [f64; 2]) {
    assert!(
        (got[0] - want[0]).abs() < 1e-9 && (got[1] - want[1]).abs() < 1e-9,
        "{got:?} != {want:?}"
    );
}

#[test]
fn cutter_compensation_offsets_the_path_and_rounds_convex_corners() {
    // A 20 mm square cut on its outside with a 4 mm tool on the left of the path (clockwise):
    // entry perpendicular to the first side, an arc about each corner, exit back to the line.
    let program = "G21 G90 F100 G0 X0 Y0\nG41.1 D4\nG1 X0 Y20\nG1 X20\nG1 Y0\nG40 G1 X0 Y0\nM2\n";
    let got = motions(&program.replace("G0 X0 Y0", "G0 X0 Y-10"), [0.0; 4]);
    let kinds: Vec<&MotionKind> = got.iter().map(|(_, kind)| kind).collect();
    // The entry: to one radius left of (0, 20) seen from (0, -10).
    assert_near(xy(kinds[1]), [-2.0, 20.0]);
    // Round the corner (0, 20) clockwise to one radius above it.
    let MotionKind::Arc { center, clockwise: true, .. } = *kinds[2] else { panic!("{kinds:?}") };
    assert_near(center, [0.0, 20.0]);
    assert_near(xy(kinds[2]), [0.0, 22.0]);
    assert_near(xy(kinds[3]), [20.0, 22.0]);
    assert_near(xy(kinds[4]), [22.0, 20.0]);
    assert_near(xy(kinds[5]), [22.0, 0.0]);
    // G40: the exit move goes to the programmed point itself.
    assert_near(xy(kinds[6]), [0.0, 0.0]);
    // Each held move carries its own line.
    assert_eq!(got[3].0, 4);
    assert_eq!(got[5].0, 5);
}

#[test]
fn cutter_compensation_shortens_moves_into_concave_corners() {
    // A tool on the right turning right: the first move stops one radius before the wall.
    let start = "G21 G90 F100 G0 X0 Y0\nG42.1 D2\nG1 X10\n";
    let got = motions(&format!("{start}G1 Y-10\nG40 G1 X0 Y0\nM2\n"), [0.0; 4]);
    assert_near(xy(&got[1].1), [9.0, -1.0]);
    assert_near(xy(&got[2].1), [9.0, -10.0]);
    // Turning left is convex for it: to the corner's side, round it, on.
    let got = motions(&format!("{start}G1 Y10\nG40 G1 X0 Y0\nM2\n"), [0.0; 4]);
    assert_near(xy(&got[1].1), [10.0, -1.0]);
    assert!(matches!(got[2].1, MotionKind::Arc { clockwise: false, .. }), "{got:?}");
    assert_near(xy(&got[2].1), [11.0, 0.0]);
    assert_near(xy(&got[3].1), [11.0, 10.0]);
}

#[test]
fn cutter_compensation_errors_name_the_block() {
    let err = error("G21 F100\nG41.1 D4\nG1 X10\nG1 X12 Y-0.5\nG1 X13 Y5\nM2\n");
    assert_eq!(
        err.to_string(),
        "5:1: Straight feed in concave corner cannot be reached by the tool without gouging"
    );
    let err = error("G21 F100\nG41.1 D4\nG1 X10\nG92 X0\nM2\n");
    assert_eq!(err.to_string(), "4:1: Cannot change axis offsets with cutter radius comp");
    let err = error("G21 F100\nG41 D1.5\nM2\n");
    assert_eq!(err.to_string(), "2:5: G41 requires D word to be a whole number");
    let err = error("G21 F100\n  G42.1\nM2\n");
    assert_eq!(err.to_string(), "2:3: G42.1 with no D word");
    let err = error("G21 F100\nG41.1 D2\nG1 X10\nG40\nG3 X0 R5\nM2\n");
    assert!(err.to_string().starts_with("5:1: The move just after exiting"), "{err}");
}

/// The end point of motion `index` of `got`, checked to 1e-9.
#[track_caller]
fn assert_end(got: &[(usize, MotionKind)], index: usize, want: [f64; 3]) {
    let end = got[index].1.end().unwrap_or_else(|| panic!("{got:?}"));
    for axis in 0..3 {
        assert!((end[axis] - want[axis]).abs() < 1e-9, "motion {index}: {end:?}, want {want:?}");
    }
}

#[test]
fn polar_words_place_the_end_from_the_origin_or_the_current_point() {
    let program = "G0 X0 Y0 Z0\nG1 @10 ^90 F100\nG1 ^180\nG91 G1 @5\nG91 G1 ^-90\nM2\n";
    let got = motions(program, [0.0; 4]);
    assert_end(&got, 1, [0.0, 10.0, 0.0]);
    // The radius kept, the angle given.
    assert_end(&got, 2, [-10.0, 0.0, 0.0]);
    // G91: radius 10 + 5 at the same angle, then a quarter turn back.
    assert_end(&got, 3, [-15.0, 0.0, 0.0]);
    assert_end(&got, 4, [0.0, 15.0, 0.0]);
    let err = error("G0 X0 Y0\nG1 @10 X1 F100\nM2\n");
    assert!(err.to_string().contains("Cannot specify both polar coordinate and X word"), "{err}");
}

#[test]
fn a_rotated_coordinate_system_turns_moves_and_arcs_about_its_origin() {
    let program =
        "G10 L2 P1 X10 Y5 R90\nG0 X0 Y0 Z0\nG1 X1 F100\nG2 X3 Y0 I1 J0\nG53 G0 X0 Y0\nM2\n";
    let got = motions(program, [0.0; 4]);
    assert_end(&got, 0, [10.0, 5.0, 0.0]);
    // X in the system is Y on the machine.
    assert_end(&got, 1, [10.0, 6.0, 0.0]);
    let MotionKind::Arc { end, center, clockwise, .. } = got[2].1 else { panic!("{got:?}") };
    assert!((end[0] - 10.0).abs() < 1e-9 && (end[1] - 8.0).abs() < 1e-9, "{end:?}");
    assert!((center[0] - 10.0).abs() < 1e-9 && (center[1] - 7.0).abs() < 1e-9, "{center:?}");
    assert!(clockwise);
    assert_end(&got, 3, [0.0, 0.0, 0.0]);
}

/// The straight moves of line `line` of `got` and the point before them.
fn chords(got: &[(usize, MotionKind)], line: usize) -> Vec<[f64; 3]> {
    let first = got.iter().position(|(at, _)| *at == line).expect("the line's moves");
    let mut points = vec![got[first - 1].1.end().expect("a move before")];
    for (_, kind) in got.iter().filter(|(at, _)| *at == line) {
        let MotionKind::Linear { end, feed: f } = kind else { panic!("{kind:?}") };
        assert_eq!(*f, feed(100.0));
        points.push(*end);
    }
    points.iter().map(|p| [p[0], p[1], p[2]]).collect()
}

#[test]
fn xz_and_yz_arcs_of_a_rotated_system_run_as_chords_of_the_tilted_arc() {
    // Turned by 30° about Z (and shifted): the XZ plane's normal, Y, becomes (−sin 30°, cos 30°).
    let program = "G10 L2 P1 X5 Y2 Z1 R30\nG54 G0 X0 Y3 Z0\nG18 G2 X10 Z0 I5 K0 F100\n\
                   G19 G3 X17 Y3 Z0 J4 K0 P2\nM2\n";
    let got = motions(program, [0.0; 4]);
    let (sin, cos) = 30f64.to_radians().sin_cos();
    let turn = |x: f64, y: f64| [5.0 + x * cos - y * sin, 2.0 + x * sin + y * cos];
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    // (The arc, its normal, its radius, whether it climbs along the normal.)
    let [cx, cy] = turn(5.0, 3.0);
    let [ux, uy] = turn(0.0, 7.0);
    let arcs = [
        (3, [cx, cy, 1.0], [-sin, cos, 0.0], 5.0),
        // Centre (y, z) = (3 + 4, 0): the normal is X turned; a helix going 7 along it in two
        // turns.
        (4, [ux + 10.0 * cos, uy + 10.0 * sin, 1.0], [cos, sin, 0.0], 4.0),
    ];
    for (line, centre, normal, radius) in arcs {
        let points = chords(&got, line);
        assert!(points.len() > 50, "line {line}: {} points", points.len());
        for pair in points.windows(2) {
            for point in pair {
                let off = sub(*point, centre);
                let along = dot(off, normal);
                let across = (dot(off, off) - along * along).sqrt();
                assert!((across - radius).abs() < 1e-9, "line {line}: {point:?} is {across} away");
                if line == 3 {
                    assert!(along.abs() < 1e-9, "line {line}: {point:?} leaves the plane");
                }
            }
            // The chord's middle, off the arc by its sagitta only.
            let middle = [0, 1, 2].map(|axis| (pair[0][axis] + pair[1][axis]) / 2.0);
            let off = sub(middle, centre);
            let along = dot(off, normal);
            let sagitta = radius - (dot(off, off) - along * along).sqrt();
            assert!((0.0..=0.001).contains(&sagitta), "line {line}: sagitta {sagitta}");
        }
    }
    // G2 in G18 turns clockwise in (Z, X), LinuxCNC's order for that plane: from X0 to X10
    // it dips to Z −5 (as it does unrotated), here Z 1 − 5 with the system's Z offset.
    let lowest = chords(&got, 3).iter().map(|p| p[2]).fold(f64::INFINITY, f64::min);
    assert!((lowest + 4.0).abs() < 0.001, "{lowest}");
    // The helix ends where it was asked to.
    let helix = chords(&got, 4);
    let (last, [x, y]) = (helix.last().unwrap(), turn(17.0, 3.0));
    assert!((last[0] - x).abs() < 1e-9 && (last[1] - y).abs() < 1e-9, "{last:?}");
    assert!((last[2] - 1.0).abs() < 1e-9, "{last:?}");
    let too_large = error("G10 L2 P1 R30\nG18 G2 X0 Z0 I5000 K0 P3 F10\nM2\n");
    assert!(too_large.to_string().contains("Arc too large in a rotated coordinate system"));
}

#[test]
fn outputs_are_events_and_overrides_do_nothing() {
    let got = motions("M62 P1\nM48\nM68 E0 Q2\nM19 R90\nM3 $0\nM5 $-1\nM2\n", [0.0; 4]);
    let codes: Vec<String> = got
        .iter()
        .filter_map(|(_, kind)| match kind {
            MotionKind::Code { code } => Some(code.to_string()),
            _ => None,
        })
        .collect();
    assert_eq!(codes, ["M62", "M68", "M19"]);
    let err = error("M3 $1\nM2\n");
    assert!(err.to_string().contains("Spindle ($) number out of range in M3 Command"), "{err}");
}

#[test]
fn m73_in_a_subroutine_restores_the_modes_when_it_returns() {
    let program = "o1 sub\nM73\nG20 G91\no1 endsub\nG0 X0 Y0 Z0\no1 call\nG0 X2\nM2\n";
    let got = motions(program, [0.0; 4]);
    // Millimetres and absolute again after the call.
    assert_end(&got, 1, [2.0, 0.0, 0.0]);
}

#[test]
fn a_probe_move_goes_to_its_end_and_stands_back_with_the_end_in_5061() {
    // No probe trips: to Z-5, then 0.254 mm back toward the start; the next line reads the end
    // point in #5061–#5063 and 0 in #5070.
    let program = "G21 G90 F100\nG0 X1 Y2 Z3\nG38.2 Z-5\nG1 X[#5061 + 10] Y[#5070]\n\
                   G20 G38.3 Z-1\nG1 X[#5063]\nM2\n";
    let got = motions(program, [0.0; 4]);
    let code = |name: &str| MotionKind::Code { code: biscara_motion::CodeName::new(name).unwrap() };
    assert_eq!(got[1], (3, code("G38.2")));
    assert_eq!(got[2], (3, MotionKind::Linear { end: [1.0, 2.0, -5.0, 0.0], feed: feed(100.0) }));
    let MotionKind::Linear { end: back, .. } = got[3].1 else { panic!("{:?}", got[3]) };
    assert!((back[2] - -4.746).abs() < 1e-12, "{back:?}");
    let MotionKind::Linear { end, .. } = got[4].1 else { panic!("{:?}", got[4]) };
    assert_eq!([end[0], end[1]], [11.0, 0.0]);
    // In inches: the end is -1 inch, the stop 0.01 inch back, #5063 in inches.
    assert_eq!(got[5], (5, code("G38.3")));
    let MotionKind::Linear { end: back, .. } = got[7].1 else { panic!("{:?}", got[7]) };
    assert!((back[2] - (-25.4 + 0.254)).abs() < 1e-9, "{back:?}");
    let MotionKind::Linear { end, .. } = got[8].1 else { panic!("{:?}", got[8]) };
    assert!((end[0] - -25.4).abs() < 1e-9, "{end:?}");
}

#[test]
fn a_probe_refuses_as_linuxcnc_does() {
    for (program, message) in [
        ("G0 X1\nG38.2 Z-5\nM2\n", "2:1: Cannot probe with zero feed rate"),
        ("F100 G0 X1\nG38.2 X1\nM2\n", "2:1: Start point too close to probe point"),
        ("F100\nG38.3\nM2\n", "2:1: All axes missing with motion code"),
        ("F100 G41.1 D2\nG1 X9\nG38.2 Z-5\nM2\n", "3:1: Cannot probe with cutter radius comp on"),
        ("G93\nG38.2 Z-5 F2\nM2\n", "2:1: G38.2 is not supported yet"),
    ] {
        let err = error(program).to_string();
        assert!(err.contains(message), "{program:?}: {err}");
    }
}
