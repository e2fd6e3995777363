//! Dialects through the library (docs/gcode.md): each dialect's rules where it differs from
//! LinuxCNC, `auto` detection and its reasons, the summary of no-motion codes, and the tool
//! events of docs/motion.md.

use biscara_gcode::{Config, Dialect, GcodeError, Tool, interpret};
use biscara_motion::{Motion, MotionKind};

use crate::common::{HOME, codes, config, ends};

/// The motions of `program` read as `dialect`.
#[track_caller]
fn read(program: &str, dialect: Dialect) -> Vec<Motion> {
    interpret(program.as_bytes(), &config(dialect))
        .collect::<Result<_, _>>()
        .unwrap_or_else(|err| panic!("{err}"))
}

/// The error of `program` read as `dialect`.
#[track_caller]
fn refused(program: &str, dialect: Dialect) -> GcodeError {
    interpret(program.as_bytes(), &config(dialect))
        .find_map(Result::err)
        .unwrap_or_else(|| panic!("no error for {program:?} as {dialect}"))
}

#[test]
fn linuxcnc_is_unchanged_and_the_library_default() {
    assert_eq!(Config::default().dialect, Dialect::Linuxcnc);
    let err = refused("G1 X1 E2 F100\nM2\n", Dialect::Linuxcnc);
    assert!(err.to_string().contains("E word with no G70"), "{err}");
    let err = refused("G0 X1\n", Dialect::Linuxcnc);
    assert!(matches!(err, GcodeError::NoProgramEnd { line: 1 }), "{err}");
    let err = refused(&format!("; {}\nM2\n", "c".repeat(300)), Dialect::Linuxcnc);
    assert!(matches!(err, GcodeError::LineTooLong { max: 252, .. }), "{err}");
    let err = refused("G0 (a (b))\nM2\n", Dialect::Linuxcnc);
    assert!(err.to_string().contains("Nested comment found"), "{err}");
}

#[test]
fn every_other_dialect_needs_no_program_end_and_reads_long_comment_lines() {
    let long = format!("; {}\nG0 X1\n", "thumbnail ".repeat(2000));
    for dialect in [Dialect::Grbl, Dialect::Marlin, Dialect::Mach3] {
        let motions = read(&long, dialect);
        assert_eq!(ends(&motions), [[1.0, 400.0, 100.0, 0.0]], "{dialect}");
        let err = refused(&format!("G1 X{}\n", "1".repeat(300)), dialect);
        assert!(err.to_string().contains("Command too long"), "{dialect}: {err}");
    }
}

#[test]
fn marlin_extrudes_on_the_move_absolute_or_relative() {
    let program = "G21\nG1 X10 E2 F600\nG1 X20 E5\nG92 E0\nG1 X30 E1\nM83\nG1 X40 E0.5\n\
                   G1 E-2 F2400\nM82\nG90\nG1 X50 E3\n";
    let motions = read(program, Dialect::Marlin);
    let extrusions: Vec<(usize, Option<f64>)> =
        motions.iter().filter(|m| m.kind.end().is_some()).map(|m| (m.line, m.extrude)).collect();
    assert_eq!(
        extrusions,
        [
            (2, Some(2.0)),
            (3, Some(3.0)),
            (5, Some(1.0)),
            (7, Some(0.5)),
            // A retraction: a move without length that carries its extrusion.
            (8, Some(-2.0)),
            // Absolute again, from the position E reached: 1 + 0.5 − 2.
            (11, Some(3.0 - -0.5)),
        ]
    );
    assert_eq!(codes(&motions), ["M83", "M82"]);
}

#[test]
fn makerbot_reads_the_a_word_as_the_extruder_when_named() {
    // No comment names MakerBot: `--dialect makerbot` says so where `auto` cannot tell.
    let program = "G21\nG1 X10 A2 F600\nG1 X20 A5\n";
    let motions = read(program, Dialect::Makerbot);
    let extrusions: Vec<Option<f64>> =
        motions.iter().filter(|m| m.kind.end().is_some()).map(|m| m.extrude).collect();
    assert_eq!(extrusions, [Some(2.0), Some(3.0)]);
    // Marlin has no A axis: the same program is refused there.
    let err = refused(program, Dialect::Marlin);
    assert!(err.to_string().contains("A axis word"), "{err}");
    assert_eq!("makerbot".parse::<Dialect>(), Ok(Dialect::Makerbot));
}

#[test]
fn marlin_dwells_s_in_seconds_p_in_milliseconds() {
    let motions = read("G4 P500\nG4 S2\nG4 S1 P9000\nG4\n", Dialect::Marlin);
    let seconds: Vec<f64> = motions
        .iter()
        .filter_map(|m| match m.kind {
            MotionKind::Dwell { seconds } => Some(seconds),
            _ => None,
        })
        .collect();
    assert_eq!(seconds, [0.5, 2.0, 1.0, 0.0]);
    // Grbl and LinuxCNC: P is seconds.
    let grbl = read("G4 P1.5\n", Dialect::Grbl);
    assert_eq!(grbl[0].kind, MotionKind::Dwell { seconds: 1.5 });
}

#[test]
fn marlin_homes_only_the_named_axes_with_no_intermediate_point() {
    let motions = read("G0 X10 Y20 Z30\nG28 X\nG28 Z0\nG0 X5\nG28\n", Dialect::Marlin);
    assert_eq!(
        ends(&motions),
        [
            [10.0, 20.0, 30.0, 0.0],
            [0.0, 20.0, 30.0, 0.0],
            [0.0, 20.0, 100.0, 0.0],
            [5.0, 20.0, 100.0, 0.0],
            HOME,
        ]
    );
    // LinuxCNC: G28 Z0 goes through Z0 first.
    let linuxcnc = read("G0 X10 Y20 Z30\nG28 Z0\nM2\n", Dialect::Linuxcnc);
    assert_eq!(ends(&linuxcnc)[1], [10.0, 20.0, 0.0, 0.0]);
}

#[test]
fn marlin_reads_one_command_a_line_and_records_the_others() {
    let program = "M104 S200\nM109 S200 ; wait\nM117 Printing (1/2)\nG29\nM2000\nG280\n\
                   G91 G0 Z5\nG90\nM107\nM104 S0\n";
    let mut interpreter = interpret(program.as_bytes(), &config(Dialect::Marlin));
    let motions: Vec<Motion> = (&mut interpreter).collect::<Result<_, _>>().expect("read");
    // G91 is the command of line 7: G0 and Z5 are its parameters (no move).
    assert!(ends(&motions).is_empty(), "{motions:?}");
    assert_eq!(codes(&motions), ["M104", "M109", "M117", "G29", "M2000", "G280", "M107", "M104"]);
    let summary = interpreter.summary();
    let known: Vec<(&str, usize)> = summary.codes.iter().map(|(c, n)| (c.as_str(), *n)).collect();
    assert_eq!(known, [("G29", 1), ("M104", 2), ("M107", 1), ("M109", 1), ("M117", 1)]);
    let unknown: Vec<&str> = summary.unknown.keys().map(String::as_str).collect();
    assert_eq!(unknown, ["G280", "M2000"]);
    // What Marlin has and this robot cannot do is refused with its place.
    let err = refused("G1 X1 F100\nG5 I1 J1 P1 Q1 X2 Y2\n", Dialect::Marlin);
    assert_eq!(err.location().map(|at| (at.line, at.column)), Some((2, 1)), "{err}");
    assert!(err.to_string().contains("G5 is not supported yet"), "{err}");
}

#[test]
fn marlin_feeds_at_its_default_before_the_first_f() {
    let motions = read("G1 X10\nG1 F1500\nG1 X20\n", Dialect::Marlin);
    assert!(
        matches!(motions[0].kind, MotionKind::Linear { feed, .. } if feed.mm_per_min == 4000.0)
    );
    // `G1 F1500` sets the feed rate and does not move (LinuxCNC makes a move of no length).
    assert_eq!(motions.len(), 2);
    assert!(
        matches!(motions[1].kind, MotionKind::Linear { feed, .. } if feed.mm_per_min == 1500.0)
    );
    assert_eq!(read("G1 X10 F100\nG1 F1500\nM2\n", Dialect::Linuxcnc).len(), 3);
}

#[test]
fn grbl_reads_dollar_lines_and_ignores_k_in_xy_arcs() {
    let motions = read("$H\n$32=1\nG1 X0 Y400 F100\nG2 X10 Y400 I5 J0 K7\n", Dialect::Grbl);
    assert_eq!(codes(&motions), ["$H", "$32"]);
    let arc = motions.iter().find(|m| matches!(m.kind, MotionKind::Arc { .. })).expect("arc");
    assert!(matches!(arc.kind, MotionKind::Arc { center, .. } if center == [5.0, 400.0]));
    let err = refused("G1 X0 Y400 F100\nG2 X10 Y400 I5 J0 K7\nM2\n", Dialect::Linuxcnc);
    assert!(err.to_string().contains("K word given for arc in xy plane"), "{err}");
    let err = refused("$J=G91 X10 F100\n", Dialect::Grbl);
    assert!(err.to_string().starts_with("1:1: $J= (jogging) is not supported yet"), "{err}");
}

#[test]
fn mach3_reads_nested_comments_and_program_numbers() {
    let motions = read("O0001 (PART)\n(tool (R) 1mm)\nG0 X1\nM30\n", Dialect::Mach3);
    assert!(codes(&motions).is_empty());
    assert_eq!(ends(&motions), [[1.0, 400.0, 100.0, 0.0]]);
    let err = refused("(a (b)\n", Dialect::Mach3);
    assert!(err.to_string().contains("Unclosed comment found"), "{err}");
}

#[test]
fn mach3_calls_subprograms_with_m98_and_returns_with_m99() {
    // Mach3's manual ("M98 – Call subroutine", "M99 – Return from subroutine"): the main
    // program ends with M30, the subprograms follow it, each from its `O` label to M99.
    let program = "%\nO0001 (MAIN)\nG21 G90\nG0 X1 Y1\nM98 P1000 L2\nG0 X0 Y0\nM30\n\
                   O1000 (STEP)\nG91 G1 X1 F100\nG90\nM99\n%\n";
    let motions = read(program, Dialect::Mach3);
    let lines: Vec<usize> = motions.iter().map(|motion| motion.line).collect();
    assert_eq!(lines, [4, 9, 9, 6, 7]);
    let xs: Vec<f64> = ends(&motions).iter().map(|end| end[0]).collect();
    assert_eq!(xs, [1.0, 2.0, 3.0, 0.0]);
    // A call to a label the file does not have is an error, not an early end.
    let err = refused("O0001\nG0 X1\nM98 P2000\nG0 X2\nM30\n", Dialect::Mach3);
    assert!(err.to_string().contains("seeking o-word: o<2000> from line: 3"), "{err}");
}

#[test]
fn auto_decides_from_the_first_lines_and_says_why() {
    let program = ";FLAVOR:Marlin\nM82\nG1 X1 E1 F100\n";
    let mut interpreter = interpret(program.as_bytes(), &config(Dialect::Auto));
    assert_eq!(interpreter.detection(), None);
    let first = interpreter.next().expect("a motion").expect("read");
    assert_eq!(first.line, 2);
    let detection = interpreter.detection().expect("decided");
    assert_eq!((detection.dialect, detection.line), (Dialect::Marlin, Some(1)));
    assert!(detection.reason.contains("FLAVOR:Marlin"), "{}", detection.reason);
    // Given, not detected: no detection.
    let mut given = interpret(program.as_bytes(), &config(Dialect::Marlin));
    given.next();
    assert_eq!(given.detection(), None);
}

#[test]
fn auto_without_evidence_is_linuxcnc_and_grbl_when_the_end_is_missing() {
    let mut ended = interpret("G0 X1\nM2\n".as_bytes(), &config(Dialect::Auto));
    assert!(ended.by_ref().all(|result| result.is_ok()));
    let detection = ended.detection().expect("decided");
    assert_eq!((detection.dialect, detection.line), (Dialect::Linuxcnc, None));
    let mut open = interpret("G0 X1\nG0 X2\n".as_bytes(), &config(Dialect::Auto));
    assert!(open.by_ref().all(|result| result.is_ok()));
    let detection = open.detection().expect("decided");
    assert_eq!(detection.dialect, Dialect::Grbl);
    assert!(detection.reason.contains("without M2 or M30"), "{}", detection.reason);
    // An empty program is not a program in any dialect.
    let err = refused("(nothing)\n", Dialect::Auto);
    assert!(matches!(err, GcodeError::NoProgramEnd { .. }), "{err}");
}

#[test]
fn auto_reads_ahead_64_kib_at_most() {
    let mut program = "G0 X1\n".repeat(20_000);
    program.push_str("M204 S200\nM2\n");
    let mut interpreter = interpret(program.as_bytes(), &config(Dialect::Auto));
    interpreter.next();
    // The M204 lies beyond the look-ahead: LinuxCNC, which then refuses it.
    assert_eq!(interpreter.dialect(), Dialect::Linuxcnc);
    let err = interpreter.find_map(Result::err).expect("refused");
    assert!(err.to_string().contains("M-code greater than 199: M204"), "{err}");
}

#[test]
fn the_tool_decides_what_m3_m4_m5_and_s_mean() {
    let program = "S300 M3\nG1 X1 F100 S500\nM4\nM5\nM2\n";
    let events = |tool: Tool| -> Vec<MotionKind> {
        let config = Config { home: HOME, tool, ..Config::default() };
        interpret(program.as_bytes(), &config)
            .filter_map(|result| result.ok())
            .map(|motion| motion.kind)
            .filter(|kind| kind.end().is_none() && *kind != MotionKind::End)
            .collect()
    };
    assert_eq!(
        events(Tool::Gripper),
        [MotionKind::Pick, MotionKind::Place, MotionKind::GripperOff]
    );
    assert_eq!(
        events(Tool::Laser),
        [
            MotionKind::LaserOn { power: 300.0, dynamic: false },
            MotionKind::LaserOn { power: 500.0, dynamic: false },
            MotionKind::LaserOn { power: 500.0, dynamic: true },
            MotionKind::LaserOff,
        ]
    );
    assert_eq!(
        events(Tool::Spindle),
        [
            MotionKind::SpindleOn { rpm: 300.0, clockwise: true },
            MotionKind::SpindleOn { rpm: 500.0, clockwise: true },
            MotionKind::SpindleOn { rpm: 500.0, clockwise: false },
            MotionKind::SpindleOff,
        ]
    );
    assert_eq!(events(Tool::Pen), [MotionKind::PenDown, MotionKind::PenDown, MotionKind::PenUp]);
    assert_eq!(events(Tool::Extruder).len(), 3);
}

#[test]
fn dialect_names_round_trip() {
    for dialect in Dialect::ALL {
        assert_eq!(dialect.to_string().parse::<Dialect>(), Ok(dialect));
    }
    assert!("haas".parse::<Dialect>().is_err());
}

/// Mach3's G41/G42 P (the radius, instead of the tool table's): the same moves as LinuxCNC's
/// G41.1/G42.1 D with twice that diameter; LinuxCNC itself refuses the P word.
#[test]
fn mach3_takes_the_compensation_radius_from_a_p_word() {
    for side in ["41", "42"] {
        let body = |comp: &str| {
            format!(
                "G21 G17 G90\nG0 X0 Y0 Z5\nG1 Z-1 F300\nG1 G{comp} X10 Y0\nG1 X10 Y10\n\
                 G3 X0 Y10 R5\nG1 X0 Y0\nG40 G1 X-5 Y-5\nM30\n"
            )
        };
        let mach3 = read(&body(&format!("{side} P1.5")), Dialect::Mach3);
        let linuxcnc = read(&body(&format!("{side}.1 D3")), Dialect::Linuxcnc);
        assert_eq!(ends(&mach3).len(), ends(&linuxcnc).len());
        for (a, b) in ends(&mach3).iter().zip(ends(&linuxcnc)) {
            assert!(a.iter().zip(b).all(|(a, b)| (a - b).abs() < 1e-9), "G{side}: {a:?} vs {b:?}");
        }
        // Compensated: the first cut ends at least the radius away from the programmed X10 Y0.
        let cut = ends(&mach3)[2];
        assert!((cut[0] - 10.0).hypot(cut[1]) > 1.5 - 1e-9, "{cut:?}");
        let err = refused(&body(&format!("{side} P1.5")), Dialect::Linuxcnc);
        assert!(err.to_string().contains("P word with no G2"), "{err}");
    }
    // Auto reads G41 with a P word as Mach3.
    let auto = read("G0 X0 Y0\nG1 G41 X10 Y0 P1 F100\nG40 G1 X20\nM30\n", Dialect::Auto);
    let end = ends(&auto)[1];
    assert!((end[1] - 1.0).abs() < 1e-9 || (end[1] + 1.0).abs() < 1e-9, "{end:?}");
}

#[test]
fn grbl_laser_mode_turns_the_laser_off_for_rapids_only() {
    // LightBurn's Grbl output: M4 once, then G0 between the shapes with the laser still on.
    let program = "M4 S0\nG0 X1 Y1\nG1 X2 S10 F600\nG0 X5\nG0 Y5\nG2 X6 Y6 I1 J0\nM5\nG0 X0\nM2\n";
    let kinds = |dialect: Dialect| -> Vec<(usize, MotionKind)> {
        let config = Config { home: HOME, dialect, tool: Tool::Laser, ..Config::default() };
        interpret(program.as_bytes(), &config)
            .map(|result| result.unwrap_or_else(|err| panic!("{err}")))
            .map(|motion| (motion.line, motion.kind))
            .filter(|(_, kind)| *kind != MotionKind::End)
            .collect()
    };
    let events = |motions: &[(usize, MotionKind)]| -> Vec<(usize, MotionKind)> {
        motions.iter().copied().filter(|(_, kind)| kind.end().is_none()).collect()
    };
    let on = |power: f64| MotionKind::LaserOn { power, dynamic: true };
    let grbl = kinds(Dialect::Grbl);
    // Off before the first rapid of a run (line 2 and 4, not again on 5), on again with the
    // power in force before the next feed move (line 3 and the arc on 6); M5 as programmed.
    assert_eq!(
        events(&grbl),
        [
            (1, on(0.0)),
            (2, MotionKind::LaserOff),
            (3, on(10.0)),
            (4, MotionKind::LaserOff),
            (6, on(10.0)),
            (7, MotionKind::LaserOff),
        ]
    );
    // Every move is still there, in order.
    let moves = |motions: &[(usize, MotionKind)]| -> Vec<(usize, [f64; 4])> {
        motions.iter().filter_map(|(line, kind)| kind.end().map(|end| (*line, end))).collect()
    };
    let linuxcnc = kinds(Dialect::Linuxcnc);
    assert_eq!(moves(&grbl), moves(&linuxcnc));
    // LinuxCNC keeps the laser on through the rapids (its M3/M4 are a spindle's).
    assert!(!events(&linuxcnc)[..2].contains(&(2, MotionKind::LaserOff)), "{linuxcnc:?}");
    // A spindle on Grbl keeps turning during rapids.
    let config =
        Config { home: HOME, dialect: Dialect::Grbl, tool: Tool::Spindle, ..Config::default() };
    let offs = interpret(program.as_bytes(), &config)
        .filter(|motion| motion.as_ref().is_ok_and(|m| m.kind == MotionKind::SpindleOff))
        .count();
    assert_eq!(offs, 1);
}

/// A laser program with nothing that tells the dialects apart but its missing M2: `auto` takes
/// it for Grbl's, and reads every line as Grbl does — its laser mode too, off during the G0
/// moves — not only the lines after its end (LaserGRBL's output, `lasergrbl-vector-snowflake`).
#[test]
fn auto_reads_a_program_without_an_end_as_grbl_from_its_first_line() {
    let program = "G21 G90\nM3 S500\nG0 X10 Y5\nG1 X20 F600\nG0 X30\nG1 X40\nM5\n";
    let kinds = |dialect: Dialect| -> Vec<(usize, MotionKind)> {
        let config = Config { home: HOME, dialect, tool: Tool::Laser, ..Config::default() };
        interpret(program.as_bytes(), &config)
            .map(|result| result.unwrap_or_else(|err| panic!("{err}")))
            .map(|motion| (motion.line, motion.kind))
            .collect()
    };
    let auto = kinds(Dialect::Auto);
    assert_eq!(auto, kinds(Dialect::Grbl));
    assert!(auto.contains(&(3, MotionKind::LaserOff)), "{auto:?}");
    // Decided before the first motion, and said so.
    let config =
        Config { home: HOME, dialect: Dialect::Auto, tool: Tool::Laser, ..config(Dialect::Auto) };
    let mut interpreter = interpret(program.as_bytes(), &config);
    interpreter.next();
    let detection = interpreter.detection().expect("decided");
    assert_eq!(detection.dialect, Dialect::Grbl);
    assert!(detection.reason.contains("ends at line 7 without M2 or M30"), "{}", detection.reason);
    // With M2, M30 or a `%` line, LinuxCNC's: the laser stays on through the rapids.
    for (start, end) in [("", "M2\n"), ("", "m30\n"), ("%\n", "%\n")] {
        let ended = format!("{start}{program}{end}");
        let motions = interpret(ended.as_bytes(), &config).collect::<Result<Vec<_>, _>>();
        let motions = motions.unwrap_or_else(|err| panic!("{end:?}: {err}"));
        let offs: Vec<usize> =
            motions.iter().filter(|m| m.kind == MotionKind::LaserOff).map(|m| m.line).collect();
        assert_eq!(offs, [7 + start.lines().count()], "{end:?}: only M5 turns the laser off");
    }
}

#[test]
fn auto_does_not_take_a_cnc_post_with_a_printer_m_code_for_marlin() {
    // Fusion 360's Makera Carvera post: M400 (wait for moves) amid motions that go on with no
    // G word. Marlin would skip `Z15.` and `X20`; the program is a CNC controller's.
    let program = "G90 G94\nG21\nM400\nS1000 M3\nG0 X10 Y10\nZ15.\nG1 X20 F100\nY20\nM30\n";
    let mut interpreter = interpret(program.as_bytes(), &config(Dialect::Auto));
    let err = interpreter.find_map(Result::err).expect("LinuxCNC refuses M400");
    assert!(err.to_string().contains("M-code greater than 199: M400"), "{err}");
    let detection = interpreter.detection().expect("decided");
    assert_eq!((detection.dialect, detection.line), (Dialect::Linuxcnc, Some(3)));
    assert!(
        detection.reason.contains("printer firmware M-code")
            && detection.reason.contains("line 6 goes on moving with no G word")
            && detection.reason.contains("`Z15.`"),
        "{}",
        detection.reason
    );
    // Other evidence, when there is some, decides: a K word in an XY arc is Grbl's.
    let grbl = "M400\nG0 X1\nY2\nG2 X3 Y2 I1 J0 K0 F100\nM2\n";
    let mut interpreter = interpret(grbl.as_bytes(), &config(Dialect::Auto));
    interpreter.next();
    assert_eq!(interpreter.dialect(), Dialect::Grbl);
    // A printer's program, every line a command, is still Marlin's (N numbers too).
    let print = "M104 S200\nN10 G1 X1 Y1 F600\nG1 X2 E1\nM84\n";
    let mut interpreter = interpret(print.as_bytes(), &config(Dialect::Auto));
    assert!(interpreter.by_ref().all(|result| result.is_ok()));
    let detection = interpreter.detection().expect("decided");
    assert_eq!((detection.dialect, detection.line), (Dialect::Marlin, Some(1)));
}

#[test]
fn marlin_reads_comments_that_start_with_a_number_as_comments() {
    // PrusaSlicer's default before-layer G-code writes `;[layer_z]`: `;0.2` on every layer.
    let program = "M83\n;LAYER_CHANGE\n;0.2\n; 0.4\n;-1\n(0.5)\nG1 X1 E1 F600\n;.5\nM84\n";
    let mut interpreter = interpret(program.as_bytes(), &config(Dialect::Marlin));
    let motions: Vec<Motion> = (&mut interpreter).collect::<Result<_, _>>().expect("read");
    assert_eq!(codes(&motions), ["M83", "M84"]);
    assert_eq!(ends(&motions).len(), 1);
    assert!(interpreter.summary().unknown.is_empty(), "{:?}", interpreter.summary());
    // A text line is still Marlin's unknown command.
    let mut interpreter = interpret("M83\nHELLO 1\n".as_bytes(), &config(Dialect::Marlin));
    assert!(interpreter.by_ref().all(|result| result.is_ok()));
    let unknown: Vec<&str> = interpreter.summary().unknown.keys().map(String::as_str).collect();
    assert_eq!(unknown, ["HELLO"]);
}

#[test]
fn grbl_closes_a_comment_at_the_end_of_its_line() {
    // A hand-edited Fusion 360 program for a Grbl 3018: `(Move across X-axis` never closed.
    let program = "G21 G90\nG1 X2 F100 (Move across X-axis\nG1 Y3 (MSG, open\nM2\n";
    let motions = read(program, Dialect::Grbl);
    assert_eq!(ends(&motions), [[2.0, HOME[1], HOME[2], 0.0], [2.0, 3.0, HOME[2], 0.0]]);
    // LinuxCNC refuses it where it opens.
    let err = refused(program, Dialect::Linuxcnc);
    assert_eq!(err.location().map(|at| (at.line, at.column)), Some((2, 12)), "{err}");
    assert!(err.to_string().contains("Unclosed comment found"), "{err}");
}

#[test]
fn marlin_selects_a_tool_with_the_firmware_s_own_parameters() {
    // PrusaSlicer's start G-code for the Prusa XL toolchanger: `T0 S1 L0 D0` picks tool 0
    // (S, L and D are Prusa's parameters, not LinuxCNC's words: D is no cutter compensation).
    let program = "M83\nT0 S1 L0 D0\nG1 X1 E1 F600\nT1\nG1 X2 E1\nM84\n";
    let mut interpreter = interpret(program.as_bytes(), &config(Dialect::Marlin));
    let motions: Vec<Motion> = (&mut interpreter).collect::<Result<_, _>>().expect("read");
    assert_eq!(codes(&motions), ["M83", "T0", "T1", "M84"]);
    assert_eq!(ends(&motions).len(), 2);
    let known: Vec<&str> = interpreter.summary().codes.keys().map(String::as_str).collect();
    assert!(known.contains(&"T0") && known.contains(&"T1"), "{known:?}");
    // LinuxCNC refuses the D word there.
    let err = refused("T0 S1 L0 D0\nM2\n", Dialect::Linuxcnc);
    assert!(err.to_string().contains("D word with no G41"), "{err}");
}

#[test]
fn grbl_ends_a_comment_at_its_first_parenthesis() {
    // Grbl's protocol.c ignores every character until `)`: an inner `(` is one of them.
    let motions = read("G0 X1 Y1 ( a ( b )\nG1 X2 F100\n", Dialect::Grbl);
    assert_eq!(ends(&motions), [[1.0, 1.0, 100.0, 0.0], [2.0, 1.0, 100.0, 0.0]]);
    // LinuxCNC refuses it; Mach3 reads a comment within the comment, which stays open here.
    let err = refused("G0 X1 ( a ( b )\nM2\n", Dialect::Linuxcnc);
    assert!(err.to_string().contains("Nested comment found"), "{err}");
    let err = refused("G0 X1 ( a ( b )\nM30\n", Dialect::Mach3);
    assert!(err.to_string().contains("Unclosed comment found"), "{err}");
}

#[test]
fn grbl_programs_count_what_grbl_itself_refuses() {
    // FreeCAD's grbl_post can write G83 (a peck-drilling cycle Grbl 1.1 answers with error 20):
    // read as LinuxCNC reads it, and counted for the note; Grbl's own codes are not.
    let program = "G21 G90 G17 G94 G54 G40 G49 G80 G61 G91.1\nM3 S1000\nG0 X1 Y2 Z5\n\
                   G98 G83 X5 Y5 Z-2 R1 Q1 F100\nX6\nG80\nM6 T2\nG43.1 Z1\n#1 = 3\nG1 X[#1 + 1]\n\
                   G41.1 D2\nG1 Y9\nG40\nG64 P0.1\no100 if [1]\nG1 X1\no100 endif\nG4 P0.1\nM5 M9\n\
                   G10 L2 P1 X0\nG10 L1 P1 Z2\n";
    let mut interpreter = interpret(program.as_bytes(), &config(Dialect::Grbl));
    let motions: Result<Vec<Motion>, _> = (&mut interpreter).collect();
    assert!(motions.is_ok(), "{motions:?}");
    let refused: Vec<(&str, usize)> = interpreter
        .summary()
        .refused_by_firmware
        .iter()
        .map(|(code, count)| (code.as_str(), *count))
        .collect();
    assert_eq!(
        refused,
        [
            ("G10 L1", 1),
            ("G41.1", 1),
            ("G64", 1),
            ("G83", 1),
            ("G98", 1),
            ("M6", 1),
            ("O-words", 2),
            ("expressions ([ ])", 1),
            ("parameters (#)", 2),
        ]
    );
    // The same program read as LinuxCNC counts nothing.
    let program = format!("{program}M2\n");
    let mut interpreter = interpret(program.as_bytes(), &config(Dialect::Linuxcnc));
    assert!(interpreter.by_ref().all(|result| result.is_ok()));
    assert!(interpreter.summary().refused_by_firmware.is_empty());
}

#[test]
fn mach3_probes_with_g31_logs_with_m40_m41_and_finds_o_labels_anywhere() {
    // pcb2gcode's Mach3 autoleveller: G31 probes (no probe trips: to the end point, no
    // backoff), the result in #2002 as well as #5063; M40/M41 open and close Mach3's probe log.
    let program = "G21 G90 F100\nG0 X10 Y20 Z5\nM40\nG31 Z-2 F50\nG1 X[#2000 + 1] Y#2001 Z#2002\n\
                   M41\nG1 Z#5063\nM30\n";
    let motions = read(program, Dialect::Mach3);
    assert_eq!(codes(&motions), ["M40", "G31", "M41"]);
    let moved = ends(&motions);
    assert_eq!(moved[1], [10.0, 20.0, -2.0, 0.0], "{moved:?}");
    assert_eq!(moved[2], [11.0, 20.0, -2.0, 0.0], "no backoff: {moved:?}");
    assert_eq!(moved[3], [11.0, 20.0, -2.0, 0.0], "{moved:?}");
    // LinuxCNC knows neither.
    assert!(refused(program, Dialect::Linuxcnc).to_string().contains("Unknown m code used: M40"));
    let g31 = "G21 G90 F100\nG31 Z-2\nM2\n";
    assert!(refused(g31, Dialect::Linuxcnc).to_string().contains("Unknown g code used"));
    // O3 calls O2, whose label was passed while reading on to O3: Mach3 finds it (rs274 reads
    // on from the call and refuses: "EOF in file … seeking o-word").
    let subs = "G21 G90 F100\nM98 P3\nM30\nO2\nG1 X#1\nM99\nO3\n#1 = 7\nM98 P2\nM99\n";
    assert_eq!(ends(&read(subs, Dialect::Mach3)), [[7.0, 400.0, 100.0, 0.0]]);
    assert!(refused(subs, Dialect::Linuxcnc).to_string().contains("seeking o-word: o<2>"));
}

#[test]
fn grbl_takes_g10_l2_and_l20_without_p_for_the_system_in_force() {
    // Grbl 1.1 wants P or L, and its P defaults to 0 (an OpenBuilds plasma post after probing).
    let program = "G21 G90\nG0 X10 Y20 Z30\nG10 L20 Z-2\nG0 Z0\nG10 L2 X1\nG0 X0\n";
    let moved = ends(&read(program, Dialect::Grbl));
    assert_eq!(moved[1], [10.0, 20.0, 32.0, 0.0], "{moved:?}");
    assert_eq!(moved[2], [1.0, 20.0, 32.0, 0.0], "{moved:?}");
    let linuxcnc = format!("{program}M2\n");
    let err = refused(&linuxcnc, Dialect::Linuxcnc).to_string();
    assert!(err.contains("P value out of range (0-9) with G10 L20"), "{err}");
}

#[test]
fn mach4_g65_calls_a_subprogram_with_its_letters_as_local_parameters() {
    // pcb2gcode's Mach4 autoleveller: `G65 P1 A… B… C…` runs O1 with #1 #2 #3 its own; the
    // caller's #1 comes back after the M99; L repeats.
    let program = "G21 G90 F100\n#1 = 5\nG65 P1 A10 (ten) B20 C-1\nG1 X#1\nG65 P2 L3 X1\nM30\n\
                   O1\nG1 X#1 Y#2 Z#3\nM99\nO2\nG91 G1 X#24\nG90\nM99\n";
    let moved = ends(&read(program, Dialect::Mach3));
    assert_eq!(
        moved,
        [
            [10.0, 20.0, -1.0, 0.0],
            [5.0, 20.0, -1.0, 0.0],
            [6.0, 20.0, -1.0, 0.0],
            [7.0, 20.0, -1.0, 0.0],
            [8.0, 20.0, -1.0, 0.0]
        ]
    );
    let bad = "G21 F100\nG65 P1 N2\nM30\nO1\nM99\n";
    let err = refused(bad, Dialect::Mach3).to_string();
    assert!(err.contains("2:8: N is not an argument of G65"), "{err}");
    let err = refused("G21\nG65 A1\nM30\n", Dialect::Mach3).to_string();
    assert!(err.contains("G65 with no P word"), "{err}");
    // LinuxCNC has no G65.
    let err = refused("G21\nG65 P1\nM2\n", Dialect::Linuxcnc).to_string();
    assert!(err.contains("Unknown g code used"), "{err}");
}

#[test]
fn marlin_probes_with_g38_as_a_build_with_g38_probe_target_does() {
    let program = "G21 G90\nG1 X10 Y20 Z5 F600\nG38.2 Z-3 F100\nG1 Z5\n";
    let motions = read(program, Dialect::Marlin);
    assert_eq!(codes(&motions), ["G38.2"]);
    assert_eq!(ends(&motions)[1], [10.0, 20.0, -3.0, 0.0], "no backoff outside LinuxCNC's");
}
