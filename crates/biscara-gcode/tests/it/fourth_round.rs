//! Real-world programs, fourth round (issue 39), on programs written for these tests: Mach3's
//! evidence weighed over the program (bare axis words after G80, G53 without a move, the
//! `.tap` extension), Mach3's user macros, Marlin's bare G92 and its numbers with an
//! exponent, lathe programs refused as such. One table, one runner: each case is a program,
//! the dialect asked (`auto` or one), the file name it is read under, and what it must give.

use std::io::Cursor;

use biscara_gcode::{Dialect, interpret_seekable};
use biscara_motion::Motion;

use crate::common::{codes, config, ends, run_file};

/// What a program must give.
#[derive(Debug, Clone, Copy)]
enum Expect {
    /// Read as this dialect, with these end points (mm, base frame) and these code events.
    Read { dialect: Dialect, ends: &'static [[f64; 4]], codes: &'static [&'static str] },
    /// Refused with an error starting `LINE:COL:` and containing this text.
    Refused(&'static str, &'static str),
}

const CASES: &[(&str, Dialect, &str, &str, Expect)] = &[
    (
        "a Mach3 post's bare axis words after G80 (auto)",
        Dialect::Auto,
        "job.nc",
        "G21 G90\nG0 X10 Y400\nG81 X20 Y400 Z90 R95 F100\nG80\nX30 Y410\nM30\n",
        Expect::Read {
            dialect: Dialect::Mach3,
            ends: &[
                [10.0, 400.0, 100.0, 0.0],
                [20.0, 400.0, 100.0, 0.0],
                [20.0, 400.0, 95.0, 0.0],
                [20.0, 400.0, 90.0, 0.0],
                [20.0, 400.0, 95.0, 0.0],
                [30.0, 410.0, 95.0, 0.0],
            ],
            codes: &[],
        },
    ),
    (
        "the same read as LinuxCNC: refused as LinuxCNC refuses it",
        Dialect::Linuxcnc,
        "job.nc",
        "G21 G90\nG0 X10 Y400\nG81 X20 Y400 Z90 R95 F100\nG80\nX30 Y410\nM30\n",
        Expect::Refused("5:", "Cannot use axis values without a g code that uses them"),
    ),
    (
        "a Mach3 plasma post's G53 preamble (auto)",
        Dialect::Auto,
        "cut.nc",
        "G53 G90 G40\nG21\nG0 X5 Y400\nM30\n",
        Expect::Read { dialect: Dialect::Mach3, ends: &[[5.0, 400.0, 100.0, 0.0]], codes: &[] },
    ),
    (
        "a .tap program in which nothing else tells (auto)",
        Dialect::Auto,
        "part.tap",
        "G21 G90\nG0 X5 Y400\nM30\n",
        Expect::Read { dialect: Dialect::Mach3, ends: &[[5.0, 400.0, 100.0, 0.0]], codes: &[] },
    ),
    (
        "Mach3 user macros for the torch height (auto, .tap)",
        Dialect::Auto,
        "plasma.tap",
        "G21 G90\nG0 X5 Y400\nM900 (torch height on)\nG1 X6 F500\nM901\nM30\n",
        Expect::Read {
            dialect: Dialect::Mach3,
            ends: &[[5.0, 400.0, 100.0, 0.0], [6.0, 400.0, 100.0, 0.0]],
            codes: &["M900", "M901"],
        },
    ),
    (
        "a user macro read as LinuxCNC: refused, as LinuxCNC refuses M-codes above 199",
        Dialect::Linuxcnc,
        "plasma.ngc",
        "G21\nG0 X5\nM900\nM30\n",
        Expect::Refused("3:1:", "M-code greater than 199: M900"),
    ),
    (
        "Marlin's bare G92 zeroes every axis and the extruder",
        Dialect::Marlin,
        "laser.gcode",
        "G21\nG90\nG1 X10 Y400 E5 F1000\nG92\nG1 X5 Y2 E1\n",
        Expect::Read {
            dialect: Dialect::Marlin,
            ends: &[[10.0, 400.0, 100.0, 0.0], [15.0, 402.0, 100.0, 0.0]],
            codes: &[],
        },
    ),
    (
        "a bare G92 stays an error in LinuxCNC",
        Dialect::Linuxcnc,
        "laser.ngc",
        "G21\nG92\nM2\n",
        Expect::Refused("2:1:", "All axes missing with g52 or g92"),
    ),
    (
        "Marlin reads a number with an exponent as one number (strtod)",
        Dialect::Marlin,
        "arm.gcode",
        "G21\nG90\nG1 X6.2172489379e-15 Y45.0 E0.25 F1000\nG1 X1E1 Y4.5e+1\nG1 X2 E1\n",
        Expect::Read {
            dialect: Dialect::Marlin,
            ends: &[
                [6.2172489379e-15, 45.0, 100.0, 0.0],
                [10.0, 45.0, 100.0, 0.0],
                [2.0, 45.0, 100.0, 0.0],
            ],
            codes: &[],
        },
    ),
    (
        "Marlin: an E word after a blank is the extruder, not an exponent",
        Dialect::Marlin,
        "arm.gcode",
        "G21\nG90\nG1 X1 E2 F1000\nG1 X2 e-1\n",
        Expect::Read {
            dialect: Dialect::Marlin,
            ends: &[[1.0, 400.0, 100.0, 0.0], [2.0, 400.0, 100.0, 0.0]],
            codes: &[],
        },
    ),
    (
        "Grbl keeps refusing an exponent, and says why",
        Dialect::Grbl,
        "arm.nc",
        "G21\nG1 X6.2e-15 Y45 F1000\n",
        Expect::Refused("2:8:", "grbl G-code has no numbers with an exponent"),
    ),
    (
        "LinuxCNC keeps refusing an exponent, with its message, and says why",
        Dialect::Linuxcnc,
        "arm.ngc",
        "G21\nG1 X6.2e-15 Y45 E0.25 F1000\nM2\n",
        Expect::Refused("2:17:", "Multiple e words on one line (the `e` right after a number"),
    ),
    (
        "a Haas-style lathe program with a printer's M17 (auto): refused as a lathe program",
        Dialect::Auto,
        "shaft.nc",
        "G18 G20 G40\nG97 S500 M03\nT101\nM17\nG00 X1.2 Z0.1\nG32 X1.0 Z-1.0 F0.05\nM30\n",
        Expect::Refused("6:1:", "a lathe program (G32 threading after the lathe's XZ plane"),
    ),
    (
        "a lathe program's feed per revolution and turret tool (auto)",
        Dialect::Auto,
        "turn.nc",
        "G21 G18\nT0202\nG99 G1 X10 Z-5 F0.1\nM30\n",
        Expect::Refused("2:1:", "a lathe program (a turret tool number"),
    ),
    (
        "a lathe program's U and W words (auto)",
        Dialect::Auto,
        "turn.nc",
        "G18\nG0 X10 Z5\nG1 U-1 W-2 F50\nM30\n",
        Expect::Refused("3:1:", "a lathe program (a U or W word"),
    ),
    (
        "a mill's XZ arc and a G99 cycle retract outside G18 are no lathe",
        Dialect::Auto,
        "mill.ngc",
        "G21\nG0 X0 Y400 Z100\nG18 G2 X2 Z100 I1 K0 F100\nG17 G99 G81 X5 Y400 Z90 R95\nG80\nM2\n",
        Expect::Read {
            dialect: Dialect::Linuxcnc,
            ends: &[
                [0.0, 400.0, 100.0, 0.0],
                [2.0, 400.0, 100.0, 0.0],
                [5.0, 400.0, 100.0, 0.0],
                [5.0, 400.0, 95.0, 0.0],
                [5.0, 400.0, 90.0, 0.0],
                [5.0, 400.0, 95.0, 0.0],
            ],
            codes: &[],
        },
    ),
];

#[test]
fn real_world_fourth_round() {
    for &(name, dialect, file, program, expect) in CASES {
        let run = run_file(program, &config(dialect), Some(file));
        match (expect, run.error) {
            (Expect::Read { dialect: wanted, ends: wanted_ends, codes: wanted_codes }, None) => {
                assert_eq!(run.dialect, wanted, "{name}");
                let got = ends(&run.motions);
                assert_eq!(got.len(), wanted_ends.len(), "{name}: {got:?}");
                for (got, want) in got.iter().zip(wanted_ends) {
                    for axis in 0..4 {
                        assert!((got[axis] - want[axis]).abs() < 1e-9, "{name}: {got:?} {want:?}");
                    }
                }
                assert_eq!(codes(&run.motions), wanted_codes, "{name}");
            }
            (Expect::Refused(at, text), Some(err)) => {
                let message = err.to_string();
                assert!(message.starts_with(at) && message.contains(text), "{name}: {message}");
            }
            (expect, error) => panic!("{name}: expected {expect:?}, got {error:?}"),
        }
    }
}

/// Mach3's evidence past the look-ahead: the program is read as LinuxCNC (nothing told the
/// dialects apart) until a block only Mach3 reads, then as Mach3 — not refused.
#[test]
fn mach3_evidence_past_the_look_ahead_decides_there() {
    let mut program = String::from("G21 G90\nG0 X0 Y400\n");
    while program.len() < biscara_gcode::LOOKAHEAD_BYTES + 1000 {
        program.push_str("G1 X1 F500\nG1 X0\n");
    }
    let lines = program.lines().count();
    program.push_str("G81 X2 Y400 Z90 R95\nG80\nX3 Y401\nM30\n");
    let mut interpreter = interpret_seekable(Cursor::new(program.clone()), &config(Dialect::Auto));
    let motions: Vec<Motion> = interpreter.by_ref().collect::<Result<_, _>>().expect("read");
    assert_eq!(interpreter.dialect(), Dialect::Mach3);
    let detection = interpreter.detection().expect("a detection");
    assert_eq!(detection.line, Some(lines + 3), "{detection:?}");
    assert!(
        detection.reason.contains("axis words with no motion G-code after G80"),
        "{detection:?}"
    );
    let last = motions.iter().filter_map(|motion| motion.kind.end()).next_back();
    assert_eq!(last, Some([3.0, 401.0, 95.0, 0.0]));
    // Read as LinuxCNC, the same program is refused there.
    let err = run_file(&program, &config(Dialect::Linuxcnc), None).error;
    let err = err.expect("refused as LinuxCNC");
    assert!(err.to_string().starts_with(&format!("{}:", lines + 3)), "{err}");
}
