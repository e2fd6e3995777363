//! Streaming: the interpreter reads as it goes and its memory does not grow with the program.
//!
//! The workspace forbids `unsafe`, so no counting global allocator: instead a generated
//! 5-million-line program is fed through a counting reader and (1) every motion is yielded
//! before the reader has been asked for more than the line it comes from plus one buffer, and
//! (2) the resident memory of a process running only this test (`VmRSS`, sampled every
//! 100,000 lines; `memory.rs`) stays within a few MiB of where it started — a program that collected its
//! input or its motions would grow by hundreds of MiB.

use std::cell::Cell;
use std::io::{self, BufReader, Read};
use std::rc::Rc;

use biscara_gcode::{Config, interpret};
use biscara_motion::MotionKind;

use crate::memory::{in_a_process_of_its_own, resident_kib};

/// A generated program of `lines` blocks of mixed moves, produced as it is read.
struct Generated {
    lines: usize,
    next: usize,
    line: Vec<u8>,
    offset: usize,
    /// Bytes handed out so far (shared with the test).
    consumed: Rc<Cell<usize>>,
    /// A square profile under cutter compensation instead of mixed moves.
    compensated: bool,
}

impl Generated {
    fn new(lines: usize) -> (Generated, Rc<Cell<usize>>) {
        let consumed = Rc::new(Cell::new(0));
        let generated = Generated {
            lines,
            next: 0,
            line: Vec::with_capacity(64),
            offset: 0,
            consumed: Rc::clone(&consumed),
            compensated: false,
        };
        (generated, consumed)
    }

    /// `lines` blocks going round a 20 mm square under G41.1 (a concave corner at each).
    fn compensated(lines: usize) -> (Generated, Rc<Cell<usize>>) {
        let (mut generated, consumed) = Generated::new(lines);
        generated.compensated = true;
        (generated, consumed)
    }

    fn refill(&mut self) -> bool {
        use std::io::Write;
        self.line.clear();
        self.offset = 0;
        let n = self.next;
        self.next += 1;
        let _ = match n {
            0 if self.compensated => writeln!(self.line, "G21 G90 F1000 G41.1 D2"),
            0 => writeln!(self.line, "G21 G90 F1000"),
            n if n == self.lines + 1 => writeln!(self.line, "M2"),
            n if n > self.lines + 1 => return false,
            n if self.compensated => match n % 4 {
                1 => writeln!(self.line, "G1 X20 Y0"),
                2 => writeln!(self.line, "G1 X20 Y20"),
                3 => writeln!(self.line, "G1 X0 Y20"),
                _ => writeln!(self.line, "G1 X0 Y0"),
            },
            n => match n % 4 {
                0 => writeln!(self.line, "G1 X{}.5 Y{}.25", n % 100, (n * 7) % 100),
                1 => writeln!(self.line, "G2 I5 J0"),
                2 => writeln!(self.line, "G0 Z{}.125 C{}", n % 50, n % 360),
                _ => writeln!(self.line, "#1=[#1+1] G3 X[#<_x>+1] R2"),
            },
        };
        true
    }
}

impl Read for Generated {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        if self.offset == self.line.len() && !self.refill() {
            return Ok(0);
        }
        let count = buf.len().min(self.line.len() - self.offset);
        buf[..count].copy_from_slice(&self.line[self.offset..self.offset + count]);
        self.offset += count;
        self.consumed.set(self.consumed.get() + count);
        Ok(count)
    }
}

/// The longest generated line, rounded up.
const LINE_BYTES: usize = 40;

#[test]
fn a_five_million_line_program_streams_in_flat_memory() {
    if !in_a_process_of_its_own("streaming::a_five_million_line_program_streams_in_flat_memory") {
        return;
    }
    const LINES: usize = 5_000_000;
    const BUFFER: usize = 8 * 1024;
    let config = Config::default();
    let (generated, consumed) = Generated::new(LINES);
    let reader = BufReader::with_capacity(BUFFER, generated);
    let motions = interpret(reader, &config);
    let start = resident_kib();
    let mut peak = start.unwrap_or(0);
    let mut count = 0usize;
    let mut last_line = 0;
    for motion in motions {
        let motion = motion.expect("the generated program is valid");
        count += 1;
        last_line = motion.line;
        if count.is_multiple_of(100_000) {
            peak = peak.max(resident_kib().unwrap_or(0));
            // Read so far: at most this line, the next one and one buffer ahead.
            assert!(consumed.get() <= (motion.line + 1) * LINE_BYTES + BUFFER, "read ahead");
        }
        if matches!(motion.kind, MotionKind::End) {
            break;
        }
    }
    assert_eq!(last_line, LINES + 2, "every line was read, the last one is M2");
    assert_eq!(count, LINES + 1, "one motion per move line, and the end");
    if let Some(start) = start {
        let growth = peak.saturating_sub(start);
        assert!(growth < 16 * 1024, "resident memory grew by {growth} KiB over {LINES} lines");
    }
}

#[test]
fn each_motion_comes_before_more_than_its_line_is_read() {
    // A reader that counts what it hands out: when the motion of line k is yielded, no more
    // than lines 1..=k and one (small) buffer may have been read.
    const BUFFER: usize = 64;
    let (generated, consumed) = Generated::new(20_000);
    let config = Config::default();
    let mut count = 0;
    for motion in interpret(BufReader::with_capacity(BUFFER, generated), &config) {
        let motion = motion.expect("valid");
        count += 1;
        assert!(
            consumed.get() <= motion.line * LINE_BYTES + BUFFER,
            "line {}: {} bytes read already",
            motion.line,
            consumed.get()
        );
    }
    assert_eq!(count, 20_001);
}

#[test]
fn cutter_compensation_holds_back_one_motion_in_flat_memory() {
    // Each compensated move waits for the next block (its corner), no longer: when the motion
    // of line k is yielded, at most lines 1..=k+1 and one buffer have been read.
    const LINES: usize = 1_000_000;
    const BUFFER: usize = 64;
    let (generated, consumed) = Generated::compensated(LINES);
    let config = Config::default();
    let start = resident_kib();
    let mut peak = start.unwrap_or(0);
    let mut count = 0usize;
    for motion in interpret(BufReader::with_capacity(BUFFER, generated), &config) {
        let motion = motion.expect("the compensated square is valid");
        count += 1;
        assert!(
            consumed.get() <= (motion.line + 1) * LINE_BYTES + BUFFER,
            "line {}: {} bytes read already",
            motion.line,
            consumed.get()
        );
        if count.is_multiple_of(100_000) {
            peak = peak.max(resident_kib().unwrap_or(0));
        }
        if let MotionKind::Linear { end, .. } = motion.kind {
            // Inside the square, one radius from its sides.
            assert!(end[0] >= 0.999 && end[0] <= 19.001 && end[1] >= -0.001, "{end:?}");
        }
    }
    assert_eq!(count, LINES + 1, "one motion per move line, and the end");
    if let Some(start) = start {
        let growth = peak.saturating_sub(start);
        assert!(growth < 16 * 1024, "resident memory grew by {growth} KiB over {LINES} lines");
    }
}
