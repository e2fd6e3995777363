//! Programs that never end. A loop whose state (position, parameters, modes, call stack, loop
//! counters) at a jump back is the same as at the previous jump back from that line can only
//! repeat: it is refused there, at the end of its second pass, naming the loop. Any other
//! program stops at the bound on motions ([`Config::max_motions`]), exactly past it. Programs
//! written for these tests, one table, one runner.

use std::io::Cursor;

use biscara_gcode::{Config, Dialect, Setting, interpret, interpret_seekable};

use crate::common::{Run, run_file};

/// What a program must do.
#[derive(Debug, Clone, Copy)]
enum Outcome {
    /// Refused as a loop that repeats forever: the loop's line, the line of the jump back, and
    /// how many motions were given before.
    Repeats { loop_line: usize, at: usize, motions: usize },
    /// Stopped past the bound on motions, after exactly the bound.
    Bound,
    /// Ends normally with this many motions (the end included).
    Ends(usize),
}

/// The bound on motions these tests run with.
const BOUND: u64 = 500;

const CASES: &[(&str, Dialect, &str, Outcome)] = &[
    (
        "a while loop that moves back and forth",
        Dialect::Linuxcnc,
        "G21 G90\nG0 X0 Y400 Z100\no1 while [1]\nG1 X10 F3000\nG1 X0\no1 endwhile\nM2\n",
        Outcome::Repeats { loop_line: 3, at: 6, motions: 5 },
    ),
    (
        "a do-while loop whose parameter is set to the same value at every pass",
        Dialect::Linuxcnc,
        "G21\no1 do\n#1 = 5\nG0 X#1\nG0 X0\no1 while [#1 GT 0]\nM2\n",
        Outcome::Repeats { loop_line: 2, at: 6, motions: 4 },
    ),
    (
        "a loop with no motion at all",
        Dialect::Linuxcnc,
        "G21\no1 while [1]\no1 endwhile\nM2\n",
        Outcome::Repeats { loop_line: 2, at: 3, motions: 0 },
    ),
    (
        "a loop that calls a subroutine (the call's own jumps differ, the loop's repeat)",
        Dialect::Linuxcnc,
        "o100 sub\nG0 X#1\nG0 X0\no100 endsub\nG21\no1 while [1]\no100 call [3]\no1 endwhile\nM2\n",
        Outcome::Repeats { loop_line: 6, at: 8, motions: 4 },
    ),
    (
        "a loop that counts for three passes, then repeats",
        Dialect::Linuxcnc,
        "G21\no1 while [1]\no2 if [#1 LT 3]\n#1 = [#1 + 1]\no2 endif\nG0 X#1\nG0 X0\no1 endwhile\nM2\n",
        Outcome::Repeats { loop_line: 2, at: 8, motions: 10 },
    ),
    (
        "a Fanuc Macro B WHILE loop that moves",
        Dialect::Fanuc,
        "G21\nWHILE [1] DO1\nG0 X1\nG0 X0\nEND1\nM30\n",
        Outcome::Repeats { loop_line: 2, at: 5, motions: 4 },
    ),
    (
        "a Fanuc GOTO loop that moves",
        Dialect::Fanuc,
        "G21\nN10 G0 X1\nG0 X0\nGOTO 10\nM30\n",
        Outcome::Repeats { loop_line: 4, at: 4, motions: 4 },
    ),
    (
        "a loop in incremental moves (the position changes at every pass)",
        Dialect::Linuxcnc,
        "G21 G91\no1 while [1]\nG0 X0.01\no1 endwhile\nM2\n",
        Outcome::Bound,
    ),
    (
        "a loop that counts for ever while it moves",
        Dialect::Linuxcnc,
        "G21\no1 while [1]\n#1 = [#1 + 1]\nG0 X1\nG0 X0\no1 endwhile\nM2\n",
        Outcome::Bound,
    ),
    (
        "a repeat loop of a billion passes (its count changes at every pass)",
        Dialect::Linuxcnc,
        "G21\no1 repeat [1000000000]\nG0 X1\nG0 X0\no1 endrepeat\nM2\n",
        Outcome::Bound,
    ),
    (
        "a loop that moves the same way at every pass and ends on its count",
        Dialect::Linuxcnc,
        "G21\no1 while [#1 LT 100]\n#1 = [#1 + 1]\nG0 X1\nG0 X0\no1 endwhile\nM2\n",
        Outcome::Ends(201),
    ),
    (
        "a subroutine called twice from the same state on different lines",
        Dialect::Linuxcnc,
        "o100 sub\nG0 X1\no100 endsub\nG21\no100 call\no100 call\nM2\n",
        Outcome::Ends(3),
    ),
];

#[test]
fn programs_that_never_end_stop() {
    for &(name, dialect, program, outcome) in CASES {
        let config =
            Config { dialect, max_motions: BOUND, max_idle_jumps: 100, ..Config::default() };
        let Run { motions, error, .. } = run_file(program, &config, None);
        let given = motions.len();
        match (outcome, error) {
            (Outcome::Repeats { loop_line, at, motions }, Some(err)) => {
                let message = err.to_string();
                let expected = format!("{at}:1: the loop at line {loop_line} repeats forever");
                assert!(message.starts_with(&expected), "{name}: {message}");
                assert_eq!(given, motions, "{name}: motions before the error");
                assert_eq!(err.setting(), None, "{name}: no setting allows it");
            }
            (Outcome::Bound, Some(err)) => {
                let message = err.to_string();
                assert!(
                    message.contains(&format!("goes on past {BOUND} motions")),
                    "{name}: {message}"
                );
                assert!(!message.contains("--"), "{name}: no command-line flag in the library");
                assert_eq!(err.setting(), Some(Setting::MaxMotions), "{name}");
                assert_eq!(given, BOUND as usize, "{name}: exactly the bound");
            }
            (Outcome::Ends(motions), None) => assert_eq!(given, motions, "{name}"),
            (outcome, error) => panic!("{name}: expected {outcome:?}, got {error:?}"),
        }
    }
}

/// The same from standard input (an input read only forwards, whose loop lines are kept).
#[test]
fn a_loop_read_from_standard_input_is_judged_the_same() {
    let program = "G21\no1 while [1]\nG0 X1\nG0 X0\no1 endwhile\nM2\n";
    let err =
        interpret(program.as_bytes(), &Config::default()).find_map(Result::err).expect("an error");
    assert!(err.to_string().starts_with("5:1: the loop at line 2 repeats forever"), "{err}");
}

/// A program with no loop is bounded too: the bound counts motions, not jumps.
#[test]
fn the_bound_counts_every_motion() {
    let config = Config { max_motions: 2, ..Config::default() };
    let motions: Vec<_> = interpret("G0 X1\nG0 X2\nM2\n".as_bytes(), &config).collect();
    assert_eq!(motions.len(), 3);
    let err = motions[2].as_ref().expect_err("the end is a third motion");
    assert!(err.to_string().starts_with("3:1: the program goes on past 2 motions"), "{err}");
    let exact = Config { max_motions: 3, ..Config::default() };
    assert!(interpret("G0 X1\nG0 X2\nM2\n".as_bytes(), &exact).all(|m| m.is_ok()));
}

/// A pass that changes more parameters than the interpreter's log of changes holds (600
/// changes), and sets them back: compared in full, and refused at the second pass.
#[test]
fn a_loop_that_changes_many_parameters_and_sets_them_back_repeats() {
    let program = "G21\no1 while [1]\n#2 = 0\no2 while [#2 LT 300]\n#[#2 + 1000] = 1\n\
                   #2 = [#2 + 1]\no2 endwhile\n#2 = 0\no3 while [#2 LT 300]\n#[#2 + 1000] = 0\n\
                   #2 = [#2 + 1]\no3 endwhile\nG0 X1\nG0 X0\no1 endwhile\nM2\n";
    let results: Vec<_> = interpret_seekable(Cursor::new(program), &Config::default()).collect();
    assert_eq!(results.iter().filter(|result| result.is_ok()).count(), 4);
    let err = results.last().expect("a result").as_ref().expect_err("an error");
    assert!(err.to_string().starts_with("15:1: the loop at line 2 repeats forever"), "{err}");
}
