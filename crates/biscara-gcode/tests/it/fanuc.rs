//! The Fanuc/Haas dialect, Mach3 as real posts use it, the bound on endless loops, the UTF-8
//! byte-order mark and `auto`'s weighing of a program's evidence.

use std::io::Cursor;
use std::sync::Arc;

use biscara_gcode::{Config, Dialect, GcodeError, ToolTable, interpret, interpret_seekable};
use biscara_motion::{Motion, MotionKind};

use crate::common::{config, ends, run_file};

/// The motions of `program` read as `config` says, from an input it can jump in (a file).
#[track_caller]
fn run(program: &str, config: &Config) -> Vec<Motion> {
    let run = run_file(program, config, None);
    if let Some(err) = run.error {
        panic!("{err}");
    }
    run.motions
}

#[track_caller]
fn refused(program: &str, config: &Config) -> GcodeError {
    run_file(program, config, None).error.unwrap_or_else(|| panic!("no error for {program:?}"))
}

fn xy(motions: &[Motion]) -> Vec<[f64; 2]> {
    ends(motions).iter().map(|end| [end[0], end[1]]).collect()
}

/// A Fusion 360 Haas post's shape: an O number, look-ahead codes, machine M-codes, G43 H with
/// the tool table, G04 P in milliseconds and X in seconds, K repeats, G28 G91 Z0.
#[test]
fn a_haas_post_runs_with_its_machine_codes_as_events() {
    let program = "%\nO01001 (PART)\nG90 G94 G17\nG21\nG187 P3 E0.01\nG5.1 Q1\nG08 P1\n\
                   T1 M06\nS5000 M03\nG54\nM31\nG00 X10. Y20.\nG43 Z15. H01\nM08 M88\n\
                   G01 Z5. F300.\nG04 P500\nG04 X1.5\nG98 G81 X20. Y20. Z-2. R3. F100. K2\nG80\n\
                   G28 G91 Z0.\nG90\nM05 M09\nM33\nM30\n%\n";
    let table = ToolTable::parse("T1 P1 Z10 D6\n".as_bytes(), "tools.tbl").expect("table");
    let config = Config { tool_table: Some(Arc::new(table)), ..config(Dialect::Fanuc) };
    let mut interpreter = interpret_seekable(Cursor::new(program), &config);
    let motions: Vec<Motion> = (&mut interpreter).collect::<Result<_, _>>().expect("runs");
    let codes = &interpreter.summary().codes;
    for (code, count) in [("G187", 1), ("G5.1", 1), ("G8", 1), ("M31", 1), ("M33", 1), ("M88", 1)] {
        assert_eq!(codes.get(code), Some(&count), "{code}: {codes:?}");
    }
    let dwells: Vec<f64> = motions
        .iter()
        .filter_map(|m| match m.kind {
            MotionKind::Dwell { seconds } => Some(seconds),
            _ => None,
        })
        .collect();
    assert_eq!(dwells, [0.5, 1.5]);
    // G43 H01: the tool's 10 mm length lifts the tool point.
    assert!(ends(&motions).contains(&[10.0, 20.0, 25.0, 0.0]), "{:?}", ends(&motions));
    // K2: the hole drilled twice.
    let bottoms = ends(&motions).iter().filter(|end| end[2] == -2.0 + 10.0).count();
    assert_eq!(bottoms, 2);
    // G28 G91 Z0: Z home, X Y where they were.
    assert_eq!(ends(&motions).last(), Some(&[20.0, 20.0, 100.0, 0.0]));
    assert_eq!(motions.last().map(|m| m.kind), Some(MotionKind::End));
}

#[test]
fn macro_b_loops_conditions_and_gotos() {
    let program = "O1000\nG21 G90 G01 F100\n#100=1\nWHILE [#100 LE 3] DO1\nX[10*#100] Y0\n\
                   #100=#100+1\nEND1\nIF [#100 GT 3] GOTO 50\nX99\nN50 X0 Y5\n\
                   IF [#100 EQ 4] THEN #101=7\nX#101\nDO2\nIF [#100 GE 6] GOTO 60\n\
                   #100=#100+1\nY#100\nEND2\nN60 M30\n";
    let motions = run(program, &config(Dialect::Fanuc));
    // (`G01 F100` with no axis word: a move of no length, as in LinuxCNC.)
    assert_eq!(
        xy(&motions),
        [
            [0.0, 400.0],
            [10.0, 0.0],
            [20.0, 0.0],
            [30.0, 0.0],
            [0.0, 5.0],
            [7.0, 5.0],
            [7.0, 5.0],
            [7.0, 6.0]
        ]
    );
}

/// Haas's M97: a local subprogram at a block number of the same program, L times, back after
/// the M97 at its M99.
#[test]
fn m97_runs_a_local_subprogram_l_times() {
    let program = "G21 G90 G00 X0 Y0\nM97 P1000 L2\nG00 X50\nM30\nN1000 G91 G01 X1 F100\n\
                   G90\nM99\n";
    let motions = run(program, &config(Dialect::Fanuc));
    assert_eq!(xy(&motions), [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [50.0, 0.0]]);
}

#[test]
fn fanuc_gotos_need_their_block_and_a_file() {
    let err = refused("G21\nGOTO 7\nM30\n", &config(Dialect::Fanuc));
    assert!(matches!(err, GcodeError::NoBlockNumber { line: 2, target: 7 }), "{err}");
    // Standard input cannot be read again from its start.
    let err = interpret("G21\nN7 G0 X1\nGOTO 7\nM30\n".as_bytes(), &config(Dialect::Fanuc))
        .find_map(Result::err)
        .expect("an error");
    assert!(err.to_string().contains("give the program as a file"), "{err}");
}

/// Autodesk's Mach3 post writes G80 and goes on with bare axis words, which Mach3 runs in the
/// motion mode from before the cycle; a Mach3 plasma post starts with `G53 G90 G40`. LinuxCNC
/// refuses both.
#[test]
fn mach3_runs_axis_words_after_g80_and_g53_without_a_move() {
    let program = "G53 G90 G40\nG21 G01 X1 Y1 F100\nG81 X5 Y5 Z-1 R1\nG80\nX10 Y10\nM30\n";
    let mut interpreter = interpret(program.as_bytes(), &config(Dialect::Mach3));
    let motions: Vec<Motion> = (&mut interpreter).collect::<Result<_, _>>().expect("runs");
    let last = motions.iter().rev().find(|m| m.kind.end().is_some()).expect("a move");
    assert!(matches!(last.kind, MotionKind::Linear { .. }), "{last:?}");
    // (At the cycle's R plane, G99's retract.)
    assert_eq!(last.kind.end(), Some([10.0, 10.0, 1.0, 0.0]));
    let adapted = &interpreter.summary().adapted;
    assert_eq!(adapted.len(), 2, "{adapted:?}");
    for linuxcnc in ["G53 G90 G40\nM2\n", "G1 X1 F100\nG81 X5 Z-1 R1\nG80\nX2\nM2\n"] {
        assert!(interpret(linuxcnc.as_bytes(), &config(Dialect::Linuxcnc)).any(|r| r.is_err()));
    }
}

/// An endless loop with no motion stops with an error naming the loop's line after the bound;
/// one that moves and changes its state streams until the bound on motions.
#[test]
fn endless_loops_without_motion_stop_at_the_bound() {
    let bounded = Config { max_idle_jumps: 50, ..config(Dialect::Linuxcnc) };
    let program = "G21\nG0 X1\no1 while [1]\n#1 = [#1 + 1]\nG0 X1\no1 endwhile\nM2\n";
    let err = refused(program, &bounded);
    let message = err.to_string();
    assert!(message.starts_with("6:1: the loop at line 3 has jumped back 50 times"), "{message}");
    assert_eq!(err.setting(), Some(biscara_gcode::Setting::MaxIdleJumps));
    // The same loop read from standard input (its lines kept while it runs).
    let err = interpret(program.as_bytes(), &bounded).find_map(Result::err).expect("an error");
    assert!(err.to_string().contains("the loop at line 3"), "{err}");
    // A loop that computes for a while, then moves, is not endless.
    let counting = "G21\no1 while [#1 LT 40]\n#1 = [#1 + 1]\no1 endwhile\nG0 X#1\nM2\n";
    assert_eq!(ends(&run(counting, &bounded)), [[40.0, 400.0, 100.0, 0.0]]);
    // A loop that moves and counts streams: 1000 moves are read, and more would follow.
    let moving = "G21\no1 while [1]\n#2 = [#2 + 1]\nG0 X0\nG0 X1\no1 endwhile\nM2\n";
    let moves = interpret_seekable(Cursor::new(moving), &bounded).take(1000);
    assert_eq!(moves.filter(Result::is_ok).count(), 1000);
    // A Fanuc GOTO loop.
    let fanuc = Config { max_idle_jumps: 50, ..config(Dialect::Fanuc) };
    let err = refused("G21\nN10 #1=#1+1\nGOTO 10\nM30\n", &fanuc);
    assert!(err.to_string().contains("the loop at line 3"), "{err}");
}

#[test]
fn a_utf8_byte_order_mark_is_skipped() {
    let program = "\u{feff}G21 G90\nG0 X1 Y2\nM2\n";
    let motions = interpret(program.as_bytes(), &config(Dialect::Linuxcnc))
        .collect::<Result<Vec<_>, _>>()
        .expect("runs");
    assert_eq!(ends(&motions), [[1.0, 2.0, 100.0, 0.0]]);
    let auto = Config { dialect: Dialect::Auto, ..config(Dialect::Auto) };
    let marlin = "\u{feff};FLAVOR:Marlin\nG1 X1 E1 F100\n";
    let mut interpreter = interpret(marlin.as_bytes(), &auto);
    assert!(interpreter.all(|r| r.is_ok()));
    assert_eq!(interpreter.detection().map(|d| d.dialect), Some(Dialect::Marlin));
}

/// Found on a Mr Beam (Grbl laser) program: a 300-character `;` comment on line 2 was read as
/// LinuxCNC's and refused for its length; Grbl drops comments before its line buffer. Beyond the
/// look-ahead, such a line decides too.
#[test]
fn a_line_long_only_in_its_comment_says_grbl() {
    let auto = config(Dialect::Auto);
    let program = format!("G21 G90\n;{}\nG0 X1\nG1 X3 F100\n", "x".repeat(300));
    let mut interpreter = interpret(program.as_bytes(), &auto);
    assert_eq!((&mut interpreter).filter(|r| r.is_ok()).count(), 2);
    let detection = interpreter.detection().expect("decided");
    assert_eq!((detection.dialect, detection.line), (Dialect::Grbl, Some(2)));
    assert!(detection.reason.contains("only in its comment"), "{}", detection.reason);
    let far = format!("{}; {}\nG0 X2\n", "G0 X1\n".repeat(12_000), "c".repeat(300));
    let mut interpreter = interpret(far.as_bytes(), &auto);
    assert!(interpreter.all(|r| r.is_ok()));
    assert_eq!(interpreter.detection().map(|d| d.dialect), Some(Dialect::Grbl));
    // A long command is refused as before.
    let long = format!("G21\nG0 X{}\nM2\n", "1".repeat(300));
    let err = interpret(long.as_bytes(), &auto).find_map(Result::err).expect("refused");
    assert!(matches!(err, GcodeError::LineTooLong { max: 252, .. }), "{err}");
}

/// `auto` weighs the whole look-ahead: Fanuc's own codes outweigh an `O` number (Mach3's too)
/// and numbered parameters (LinuxCNC's too).
#[test]
fn auto_tells_fanuc_from_its_codes() {
    let auto = config(Dialect::Auto);
    for (program, dialect) in [
        ("O0001\nG21\nG187 P1\nG0 X1\nM30\n", Dialect::Fanuc),
        ("O0001\nG21\nM31\nG0 X1\nM30\n", Dialect::Fanuc),
        ("#1=2\nWHILE [#1 LT 3] DO1\n#1=#1+1\nEND1\nM30\n", Dialect::Fanuc),
        ("G21\nM97 P10\nM30\nN10 G0 X1\nM99\n", Dialect::Fanuc),
        ("O0001\nG21\nG0 X1\nM30\n", Dialect::Mach3),
        ("#1=2\nG0 X#1\nM2\n", Dialect::Linuxcnc),
    ] {
        let mut interpreter = interpret_seekable(Cursor::new(program), &auto);
        for result in &mut interpreter {
            result.unwrap_or_else(|err| panic!("{program:?}: {err}"));
        }
        let detection = interpreter.detection().expect("decided");
        assert_eq!(detection.dialect, dialect, "{program:?}: {}", detection.reason);
    }
}
