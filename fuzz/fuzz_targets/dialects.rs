//! Dialect detection and each dialect's reader on arbitrary bytes: the first byte chooses the
//! dialect (auto, linuxcnc, grbl, marlin, mach3, fanuc), the rest is the program, read from an
//! input it can jump in (Fanuc's GOTO and M97, O-word loops). Detection must agree with the
//! interpreter's `auto` choice when it decides from the look-ahead, and no reader may panic,
//! hang (a loop without motion stops at its bound; one that moves is read for 100 000 motions)
//! or emit a number that is not finite.
#![no_main]

use std::io::Cursor;

use biscara::gcode::{Config, Dialect, Tool, detect_dialect, interpret_seekable};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Some((&selector, program)) = data.split_first() else { return };
    let dialect = Dialect::ALL[usize::from(selector) % Dialect::ALL.len()];
    let tool = [Tool::Gripper, Tool::Laser, Tool::Spindle, Tool::Extruder, Tool::Pen]
        [usize::from(selector / 8) % 5];
    let detected = detect_dialect(program, true);
    if let Some(detection) = &detected {
        assert_ne!(detection.dialect, Dialect::Auto);
    }
    let config = Config {
        home: [0.0, 460.0, 100.0, 0.0],
        dialect,
        tool,
        max_idle_jumps: 1000,
        ..Config::default()
    };
    let mut interpreter = interpret_seekable(Cursor::new(program), &config);
    for motion in (&mut interpreter).take(100_000) {
        let Ok(motion) = motion else { break };
        if let Some(end) = motion.kind.end() {
            assert!(end.iter().all(|value| value.is_finite()));
        }
        if let Some(extrude) = motion.extrude {
            assert!(extrude.is_finite());
        }
    }
    if dialect == Dialect::Auto && program.len() < biscara::gcode::LOOKAHEAD_BYTES {
        if let (Some(detected), Some(chosen)) = (detected, interpreter.detection()) {
            assert_eq!(detected.dialect, chosen.dialect);
        }
    }
});
