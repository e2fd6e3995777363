//! No input makes the interpreter panic or run away: every outcome is motions, then at most one
//! error, then the end.

use biscara_gcode::{Config, Dialect, Tool, interpret};
use proptest::prelude::*;

use crate::strategies;

/// Interprets `input`, checking that the iterator stops after the first error and that every
/// motion is finite.
fn run(input: &[u8]) -> Result<usize, String> {
    run_as(input, Dialect::Linuxcnc, Tool::Gripper)
}

fn run_as(input: &[u8], dialect: Dialect, tool: Tool) -> Result<usize, String> {
    let config = Config { home: [0.0, 400.0, 100.0, 0.0], dialect, tool, ..Config::default() };
    let mut iterator = interpret(input, &config);
    let mut count = 0;
    for result in iterator.by_ref() {
        match result {
            Ok(motion) => {
                if let Some(end) = motion.kind.end() {
                    assert!(end.iter().all(|v| v.is_finite()), "{motion:?}");
                }
                assert!(motion.extrude.is_none_or(f64::is_finite), "{motion:?}");
                count += 1;
            }
            Err(err) => {
                let message = err.to_string();
                assert!(iterator.next().is_none(), "more after the error {message}");
                return Err(message);
            }
        }
    }
    Ok(count)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

    #[test]
    fn arbitrary_bytes_never_panic(input in strategies::bytes()) {
        let _ = run(&input);
    }

    #[test]
    fn token_soups_never_panic(input in strategies::token_soup()) {
        let _ = run(input.as_bytes());
    }

    #[test]
    fn every_dialect_survives_token_soups_and_bytes(
        input in strategies::token_soup(),
        bytes in strategies::bytes(),
        dialect in 0..Dialect::ALL.len(),
        tool in 0..5usize,
    ) {
        let dialect = Dialect::ALL[dialect];
        let tool = [Tool::Gripper, Tool::Laser, Tool::Spindle, Tool::Extruder, Tool::Pen][tool];
        let printer = format!("M83\nG92 E0\n{input}\nG1 X1 E2\nG28 X\nG4 S1\n$H\nO0001\n");
        let _ = run_as(printer.as_bytes(), dialect, tool);
        let _ = run_as(&bytes, dialect, tool);
    }

    #[test]
    fn plausible_programs_never_panic(program in strategies::program()) {
        if let Err(message) = run(program.as_bytes()) {
            // Every error names a line and column.
            let mut parts = message.splitn(3, ':');
            let line = parts.next().and_then(|p| p.parse::<usize>().ok());
            let column = parts.next().and_then(|p| p.parse::<usize>().ok());
            prop_assert!(line.is_some() && column.is_some(), "{message}");
        }
    }
}
