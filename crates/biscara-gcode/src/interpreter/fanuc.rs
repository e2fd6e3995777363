//! The Fanuc/Haas dialect's line hook (docs/gcode.md): what a Fanuc or Haas control reads that
//! LinuxCNC does not, turned into what the interpreter runs, before the O-word control flow
//! and the block reader see the line.
//!
//! - Macro B's control flow (Fanuc Custom Macro B, as Haas runs it): `IF [cond] GOTO n`,
//!   `IF [cond] THEN statement`, `GOTO n`, `WHILE [cond] DO n … END n` (and `DO n … END n`,
//!   an endless loop). A loop becomes LinuxCNC's `o<…> while` / `endwhile` with a label
//!   named after the `WHILE` line; `GOTO n` reads the program again from its start to the
//!   block numbered `N n` (no table of block numbers is kept: memory does not grow with the
//!   program). An assignment whose value is an expression without brackets (`#1=#1+1`) reads
//!   as `#1=[#1+1]`.
//! - Haas's M97 local subprograms: `M97 P n [L k]` runs from block `N n` of the same program to
//!   its `M99`, `k` times, and comes back after the `M97`.
//! - Look-ahead and smoothing codes with no motion (G187, G103, G8 P, G5.1 Q, G05 P): recorded,
//!   counted in one note.
//! - Machine M-codes outside the list the interpreter runs (chip conveyor M31, through-spindle
//!   coolant M88, …): taken out of their block, recorded as events and counted.

use std::io::BufRead;

use super::{Interpreter, control};
use crate::syntax::lexer::Fault;
use crate::syntax::parser::Reader;

/// M97 calls deeper than this are an error (Haas nests local subprograms a few levels deep;
/// LinuxCNC allows ten call levels).
const MAX_LOCAL_CALLS: usize = 10;

/// The dialect's state between lines.
#[derive(Debug, Default)]
pub(super) struct Fanuc {
    /// The block number being looked for (`GOTO n`, `M97 P n`): lines are passed over until the
    /// one numbered `N n`; and the line that asked, for the error when there is none.
    pub(super) seeking: Option<(u32, usize)>,
    /// `WHILE … DO n` loops: `n` and the line of their `WHILE`, innermost last.
    loops: Vec<(u32, usize)>,
    /// M97 calls being run, innermost last.
    calls: Vec<LocalCall>,
    /// The last G0–G3 motion mode (Mach3 and Fanuc: bare axis words after G80 run in it).
    plain_motion: Option<u16>,
}

/// One M97 call.
#[derive(Debug, Clone, Copy)]
struct LocalCall {
    /// Where to come back: the byte offset and number of the line after the M97 line's.
    offset: u64,
    line: usize,
    /// The O-word call level it was made at (an M99 at that level returns from it).
    level: usize,
    /// The block called and how many more times.
    target: u32,
    repeats: u32,
}

/// M-codes the Fanuc dialect runs as LinuxCNC does; every other is a machine code, an event.
fn runs_m(code: u32) -> bool {
    matches!(code, 0..=9 | 19 | 30 | 98 | 99)
}

/// The number of an `n` word at the start of `bytes` (after an optional `/`).
fn block_number(bytes: &[u8]) -> Option<u32> {
    let at = usize::from(bytes.first() == Some(&b'/'));
    if bytes.get(at) != Some(&b'n') {
        return None;
    }
    let digits = bytes[at + 1..].iter().take_while(|b| b.is_ascii_digit()).count();
    std::str::from_utf8(&bytes[at + 1..at + 1 + digits]).ok()?.parse().ok()
}

/// The unsigned integer at `bytes[at..]` and where it ends.
fn integer_at(bytes: &[u8], at: usize) -> Option<(u32, usize)> {
    let digits = bytes.get(at..)?.iter().take_while(|b| b.is_ascii_digit()).count();
    let value = std::str::from_utf8(&bytes[at..at + digits]).ok()?.parse().ok()?;
    Some((value, at + digits))
}

/// The index of the `]` that closes the `[` at `open`.
fn closing_bracket(bytes: &[u8], open: usize) -> Option<usize> {
    let mut depth = 0usize;
    for (index, &byte) in bytes.iter().enumerate().skip(open) {
        match byte {
            b'[' => depth += 1,
            b']' => {
                depth -= 1;
                if depth == 0 {
                    return Some(index);
                }
            }
            _ => {}
        }
    }
    None
}

/// The G code at `bytes[at..]` (`g`, then its number, leading zeros allowed), ten times its
/// number (`g05.1` → 51), and where it ends.
fn g_code_at(bytes: &[u8], at: usize) -> Option<(u32, usize)> {
    if bytes.get(at) != Some(&b'g') {
        return None;
    }
    let (whole, mut end) = integer_at(bytes, at + 1)?;
    let mut tenth = 0;
    if bytes.get(end) == Some(&b'.') {
        let (fraction, after) = integer_at(bytes, end + 1).unwrap_or((0, end + 1));
        if fraction > 9 {
            return None;
        }
        tenth = fraction;
        end = after;
    }
    Some((whole.checked_mul(10)?.checked_add(tenth)?, end))
}

/// Whether `letter` is a word of `rest` outside brackets.
fn has_letter(rest: &[u8], letter: u8) -> bool {
    let mut depth = 0usize;
    rest.iter().any(|&byte| {
        match byte {
            b'[' => depth += 1,
            b']' => depth = depth.saturating_sub(1),
            _ => {}
        }
        depth == 0 && byte == letter
    })
}

/// What the hook made of a line.
pub(super) enum FanucLine {
    /// Read it on as a block (possibly rewritten).
    Block,
    /// Done with: passed over, or run here.
    Done,
}

impl<R: BufRead> Interpreter<R> {
    /// Whether lines are being passed over to a block number (`GOTO`, `M97`).
    pub(super) fn fanuc_seeking(&self) -> bool {
        self.machine.hooks.fanuc.seeking.is_some()
    }

    /// The Fanuc dialect's look at a line, after its significant characters are known.
    pub(super) fn fanuc_line(&mut self) -> Result<FanucLine, Fault> {
        if self.control.engaged() {
            // Lines passed over (a loop that ends, a subprogram defined): only the loops' ends
            // are named, for the loop being left to find its end.
            let bytes = self.machine.syntax.compact.bytes();
            let at = control::first_item(bytes);
            if let Some(rest) = bytes[at..].strip_prefix(b"end")
                && rest.first().is_some_and(u8::is_ascii_digit)
            {
                return self.fanuc_end(at);
            }
            return Ok(FanucLine::Block);
        }
        let bytes = self.machine.syntax.compact.bytes();
        if let Some((target, _)) = self.machine.hooks.fanuc.seeking {
            if block_number(bytes) != Some(target) {
                return Ok(FanucLine::Done);
            }
            self.machine.hooks.fanuc.seeking = None;
        }
        let at = control::first_item(bytes);
        let rest = &bytes[at..];
        if rest.starts_with(b"if[") {
            return self.fanuc_if(at);
        }
        if rest.starts_with(b"while[") {
            return self.fanuc_while(at);
        }
        if rest.starts_with(b"goto") {
            let target = self.fanuc_integer(at + 4)?;
            self.fanuc_goto(target, true)?;
            return Ok(FanucLine::Done);
        }
        if let Some(rest) = rest.strip_prefix(b"do")
            && rest.first().is_some_and(u8::is_ascii_digit)
        {
            let (number, _) = integer_at(rest, 0).unwrap_or((0, 0));
            return self.fanuc_loop_start(at, bytes.len(), number, b"[1]".to_vec());
        }
        if let Some(rest) = rest.strip_prefix(b"end")
            && rest.first().is_some_and(u8::is_ascii_digit)
        {
            return self.fanuc_end(at);
        }
        if let Some((code, end)) = g_code_at(bytes, at)
            && let Some(name) = self.fanuc_no_op(code, &bytes[end..])
        {
            self.machine.record(name, true);
            return Ok(FanucLine::Done);
        }
        if rest.first() == Some(&b'#') {
            self.fanuc_bracket_assignment(at);
        }
        if self.fanuc_m_codes()? {
            return Ok(FanucLine::Done);
        }
        let bytes = self.machine.syntax.compact.bytes();
        let at = control::first_item(bytes);
        if bytes[at..].starts_with(b"m97") && !bytes.get(at + 3).is_some_and(u8::is_ascii_digit) {
            return self.fanuc_m97(at);
        }
        if bytes[at..].starts_with(b"m99")
            && !bytes.get(at + 3).is_some_and(u8::is_ascii_digit)
            && self
                .machine
                .hooks
                .fanuc
                .calls
                .last()
                .is_some_and(|call| call.level == self.control_level())
        {
            self.fanuc_return()?;
            return Ok(FanucLine::Done);
        }
        Ok(FanucLine::Block)
    }

    /// The name of a look-ahead or smoothing code with no motion here, `code` ten times its
    /// number, `rest` the line after it.
    fn fanuc_no_op(&self, code: u32, rest: &[u8]) -> Option<&'static str> {
        let curve_words = [b'x', b'y', b'i', b'j'].iter().any(|&letter| has_letter(rest, letter));
        Some(match code {
            // Haas: G187 smoothness and accuracy, G103 block look-ahead limit.
            1870 => "G187",
            1030 => "G103",
            // Fanuc: G08 P1 advanced preview control (LinuxCNC's G8 is lathe radius mode).
            80 if has_letter(rest, b'p') => "G8",
            // Fanuc: G05.1 Q1 AI contour control (LinuxCNC's G5.1 is a quadratic spline).
            51 if has_letter(rest, b'q') && !curve_words => "G5.1",
            // Fanuc: G05 P10000 high-speed machining (LinuxCNC's G5 is a cubic spline).
            50 if has_letter(rest, b'p') && !curve_words => "G5",
            _ => return None,
        })
    }

    /// The O-word call level (0 in the main program).
    fn control_level(&self) -> usize {
        self.machine.state.owords.level
    }

    /// The integer value at compact index `at` (a number or a parameter).
    fn fanuc_integer(&self, at: usize) -> Result<u32, Fault> {
        let mut reader = Reader::new(
            &self.machine.syntax.compact,
            self.lines.line.len(),
            &self.machine.state.params,
            &self.machine.state,
        );
        reader.set_position(at);
        let value = reader.read_integer_value()?;
        u32::try_from(value).map_err(|_| {
            self.machine.fault_at(
                at,
                self.machine.syntax.compact.bytes().len(),
                "a block number must be 0 or more",
            )
        })
    }

    /// The value of the bracketed condition opening at compact index `open`, and the index
    /// after its `]`.
    fn fanuc_condition(&self, open: usize) -> Result<(f64, usize), Fault> {
        let mut reader = Reader::new(
            &self.machine.syntax.compact,
            self.lines.line.len(),
            &self.machine.state.params,
            &self.machine.state,
        );
        reader.set_position(open);
        let value = reader.read_expression()?;
        Ok((value, reader.position()))
    }

    /// `IF [cond] GOTO n` and `IF [cond] THEN statement`.
    fn fanuc_if(&mut self, at: usize) -> Result<FanucLine, Fault> {
        let (value, after) = self.fanuc_condition(at + 2)?;
        let bytes = self.machine.syntax.compact.bytes();
        if bytes[after..].starts_with(b"goto") {
            let target = self.fanuc_integer(after + 4)?;
            if value != 0.0 {
                self.fanuc_goto(target, true)?;
            }
            return Ok(FanucLine::Done);
        }
        if bytes[after..].starts_with(b"then") {
            if value == 0.0 {
                return Ok(FanucLine::Done);
            }
            // The statement runs as the block, its N number kept.
            self.machine.syntax.compact.remove(at..after + 4);
            let at = control::first_item(self.machine.syntax.compact.bytes());
            if self.machine.syntax.compact.bytes().get(at) == Some(&b'#') {
                self.fanuc_bracket_assignment(at);
            }
            return Ok(FanucLine::Block);
        }
        Err(self.machine.fault_at(
            at,
            bytes.len(),
            "IF [condition] must be followed by GOTO n or THEN",
        ))
    }

    /// `WHILE [cond] DO n`.
    fn fanuc_while(&mut self, at: usize) -> Result<FanucLine, Fault> {
        let bytes = self.machine.syntax.compact.bytes();
        let open = at + 5;
        let close = closing_bracket(bytes, open).ok_or_else(|| {
            self.machine.fault_at(open, bytes.len(), "WHILE's [condition] is not closed")
        })?;
        let Some((number, end)) = bytes
            .get(close + 1..)
            .filter(|rest| rest.starts_with(b"do"))
            .and_then(|_| integer_at(bytes, close + 3))
        else {
            return Err(self.machine.fault_at(
                at,
                bytes.len(),
                "WHILE [condition] must be followed by DO n",
            ));
        };
        let condition = bytes[open..=close].to_vec();
        self.fanuc_loop_start(at, end, number, condition)
    }

    /// A loop `DO number` from compact index `at` to `end`, run while `condition` (`[…]`).
    fn fanuc_loop_start(
        &mut self,
        at: usize,
        end: usize,
        number: u32,
        condition: Vec<u8>,
    ) -> Result<FanucLine, Fault> {
        let line = self.lines.number;
        // A new loop with the same number ends the scope of an earlier one.
        self.machine.hooks.fanuc.loops.retain(|&(other, _)| other != number);
        self.machine.hooks.fanuc.loops.push((number, line));
        let mut text = format!("o<fanuc_do{number}_line{line}>while").into_bytes();
        text.extend_from_slice(&condition);
        if !self.machine.syntax.compact.replace(at..end, &text) {
            return Err(self.machine.fault_at(at, end, "the WHILE line is too long"));
        }
        Ok(FanucLine::Block)
    }

    /// `END n`: the end of the loop `DO n`.
    fn fanuc_end(&mut self, at: usize) -> Result<FanucLine, Fault> {
        let bytes = self.machine.syntax.compact.bytes();
        let (number, end) = integer_at(bytes, at + 3).unwrap_or((0, bytes.len()));
        let Some(&(_, line)) =
            self.machine.hooks.fanuc.loops.iter().rev().find(|(other, _)| *other == number)
        else {
            return Err(self.machine.fault_at(
                at,
                end,
                format!("END {number} with no DO {number} before it"),
            ));
        };
        let text = format!("o<fanuc_do{number}_line{line}>endwhile").into_bytes();
        if !self.machine.syntax.compact.replace(at..end, &text) {
            return Err(self.machine.fault_at(at, end, "the END line is too long"));
        }
        Ok(FanucLine::Block)
    }

    /// `#n=value`: an expression without brackets (`#1=#1+1`, which Macro B reads and
    /// LinuxCNC does not) is put in brackets.
    fn fanuc_bracket_assignment(&mut self, at: usize) {
        let bytes = self.machine.syntax.compact.bytes();
        let Some(equals) = bytes[at..].iter().position(|&b| b == b'=').map(|i| at + i) else {
            return;
        };
        let end = bytes[equals..]
            .iter()
            .position(|&b| b == b'(' || b == b';')
            .map_or(bytes.len(), |i| equals + i);
        let value = &bytes[equals + 1..end];
        let mut depth = 0usize;
        let mut operator = false;
        for (index, &byte) in value.iter().enumerate() {
            match byte {
                b'[' => depth += 1,
                b']' => depth = depth.saturating_sub(1),
                // A second assignment: LinuxCNC's several settings on one line, left alone.
                b'=' => return,
                b'+' | b'-' | b'*' | b'/' if depth == 0 && index > 0 => operator = true,
                _ if depth == 0 && byte.is_ascii_alphabetic() => operator = true,
                _ => {}
            }
        }
        if operator {
            // Within the line's length (a longer one is refused by the block reader as is).
            if self.machine.syntax.compact.replace(end..end, b"]")
                && !self.machine.syntax.compact.replace(equals + 1..equals + 1, b"[")
            {
                self.machine.syntax.compact.remove(end..end + 1);
            }
        }
    }

    /// Takes the machine M-codes out of the line, each an event; `Ok(true)` when nothing is
    /// left of the line.
    fn fanuc_m_codes(&mut self) -> Result<bool, Fault> {
        let mut index = 0;
        let mut depth = 0usize;
        let mut found = false;
        while index < self.machine.syntax.compact.bytes().len() {
            let bytes = self.machine.syntax.compact.bytes();
            match bytes[index] {
                b'[' => depth += 1,
                b']' => depth = depth.saturating_sub(1),
                b'(' | b';' => break,
                b'm' if depth == 0 => {
                    if let Some((code, end)) = integer_at(bytes, index + 1)
                        && end > index + 1
                        && !runs_m(code)
                        && code != 97
                    {
                        self.machine.record(&format!("M{code}"), true);
                        self.machine.syntax.compact.remove(index..end);
                        found = true;
                        continue;
                    }
                }
                _ => {}
            }
            index += 1;
        }
        if !found {
            return Ok(false);
        }
        let bytes = self.machine.syntax.compact.bytes();
        let at = control::first_item(bytes);
        Ok(bytes[at..].iter().all(|&b| b == b'(' || b == b';'))
    }

    /// `M97 P n [L k]`: runs the same program's block `N n` to its M99, `k` times.
    fn fanuc_m97(&mut self, at: usize) -> Result<FanucLine, Fault> {
        let bytes = self.machine.syntax.compact.bytes();
        let word =
            |letter: u8| bytes[at + 3..].iter().position(|&b| b == letter).map(|i| at + 3 + i + 1);
        let (p, l) = (word(b'p'), word(b'l'));
        let Some(p) = p else {
            return Err(self.machine.fault_at(at, at + 3, "M97 needs P, the block number to call"));
        };
        let target = self.fanuc_integer(p)?;
        let repeats = match l {
            Some(l) => self.fanuc_integer(l)?,
            None => 1,
        };
        if repeats == 0 {
            return Ok(FanucLine::Done);
        }
        if self.machine.hooks.fanuc.calls.len() >= MAX_LOCAL_CALLS {
            return Err(self.machine.fault_at(
                at,
                at + 3,
                format!("M97 calls nested more than {MAX_LOCAL_CALLS} deep"),
            ));
        }
        self.machine.hooks.fanuc.calls.push(LocalCall {
            offset: self.lines.next_offset(),
            line: self.lines.number,
            level: self.control_level(),
            target,
            repeats: repeats - 1,
        });
        self.fanuc_goto(target, false)?;
        Ok(FanucLine::Done)
    }

    /// M99 at the end of an M97 subprogram: again, or back after the M97.
    fn fanuc_return(&mut self) -> Result<(), Fault> {
        let Some(call) = self.machine.hooks.fanuc.calls.pop() else { return Ok(()) };
        if call.repeats > 0 {
            self.machine.hooks.fanuc.calls.push(LocalCall { repeats: call.repeats - 1, ..call });
            return self.fanuc_goto(call.target, false);
        }
        self.go_to(call.offset, call.line)
    }

    /// `GOTO n`: reads the program again from its start, passing over the lines before the
    /// block numbered `N n` (an error at the end of the input if there is none).
    /// `looping`: a `GOTO` (which may close a loop), not an M97 call.
    fn fanuc_goto(&mut self, target: u32, looping: bool) -> Result<(), Fault> {
        if looping {
            self.repeats_forever(self.lines.number)?;
        }
        self.count_jump(self.lines.number)?;
        self.machine.hooks.fanuc.seeking = Some((target, self.lines.number));
        self.go_to(0, 0)
    }
}

/// Canned cycles whose repeat count Fanuc gives in K (LinuxCNC's L): G73, G81–G86, G88, G89
/// (G87's K is its back-bore depth in LinuxCNC).
fn repeats_in_k(motion: u16) -> bool {
    matches!(motion, 730 | 810..=860 | 880 | 890)
}

impl super::Machine {
    /// The Mach3 and Fanuc dialects' changes to the block just read (before it is run):
    /// - bare axis words after G80 run in the motion mode from before the cycle (G0–G3), as
    ///   Fanuc and Mach3 do (Autodesk's posts write G80 and go on with `X… Y…`);
    /// - G53 with no axis word moves nowhere (a Mach3 post's `G53 G90 G40` preamble): dropped.
    pub(super) fn adapt_fanuc_style_block(&mut self) {
        if let Some(code) =
            self.syntax.block.extra.as_mut().and_then(|extra| extra.user_macro.take())
        {
            // Mach3 runs a user macro from the machine's macro folder: an event here, noted.
            let name = format!("M{}", code.code);
            self.hooks.summary.count_adapted(&format!(
                "{name} (a user macro: the machine's own macro file, not run in the simulation)"
            ));
            if let Some(code) = biscara_motion::CodeName::new(&name) {
                self.emit(biscara_motion::MotionKind::Code { code });
            }
        }
        let axis_words = super::AXES.iter().any(|&letter| self.syntax.block.word(letter).is_some());
        if let Some(code) = self.syntax.block.g[1]
            && matches!(code.code, 0 | 10 | 20 | 30)
        {
            self.hooks.fanuc.plain_motion = Some(code.code);
        }
        let group0 = self.syntax.block.g[0].map(|code| code.code);
        if group0 == Some(530) && !axis_words {
            self.syntax.block.g[0] = None;
            self.hooks.summary.count_adapted("G53 without axis words (no move)");
        }
        let uses_axes = group0.is_some_and(|code| matches!(code, 100 | 280 | 300 | 520 | 920));
        if axis_words
            && self.syntax.block.g[1].is_none()
            && self.state.motion.is_none()
            && !uses_axes
            && let Some(motion) = self.hooks.fanuc.plain_motion
        {
            self.state.motion = Some(motion);
            self.hooks.summary.count_adapted(match motion {
                0 => "axis words after G80, run in G0 (the motion before the cycle)",
                10 => "axis words after G80, run in G1 (the motion before the cycle)",
                20 => "axis words after G80, run in G2 (the motion before the cycle)",
                _ => "axis words after G80, run in G3 (the motion before the cycle)",
            });
        }
    }

    /// While `auto` has found nothing that tells the dialects apart: what of the block just
    /// read only Mach3 (and Fanuc) read, if anything — G53 with no axis word, axis words with
    /// no motion code after G80 — keeping the last G0–G3 mode as Mach3 keeps it.
    pub(super) fn mach3_only_block(&mut self) -> Option<&'static str> {
        if let Some(code) = self.syntax.block.g[1]
            && matches!(code.code, 0 | 10 | 20 | 30)
        {
            self.hooks.fanuc.plain_motion = Some(code.code);
        }
        let axis_words = super::AXES.iter().any(|&letter| self.syntax.block.word(letter).is_some());
        let group0 = self.syntax.block.g[0].map(|code| code.code);
        if group0 == Some(530) && !axis_words {
            return Some("G53 with no axis word");
        }
        let uses_axes = group0.is_some_and(|code| matches!(code, 100 | 280 | 300 | 520 | 920));
        (axis_words
            && self.syntax.block.g[1].is_none()
            && self.state.motion.is_none()
            && !uses_axes
            && self.hooks.fanuc.plain_motion.is_some())
        .then_some("axis words with no motion G-code after G80")
    }

    /// The Fanuc dialect's changes to the block just read, after
    /// [`Self::adapt_fanuc_style_block`]: G04 P is milliseconds and X seconds; a canned cycle's
    /// K is its repeat count.
    pub(super) fn adapt_fanuc_words(&mut self) {
        let letter = |letter: u8| usize::from(letter - b'a');
        let group0 = self.syntax.block.g[0].map(|code| code.code);
        if group0 == Some(40) {
            // G04 X seconds, else P milliseconds.
            let x = self.syntax.block.letters[letter(b'x')].take();
            let p = self.syntax.block.letters[letter(b'p')];
            let seconds = match (x, p) {
                (Some(x), _) => Some(crate::syntax::parser::Word { value: x.value, ..x }),
                (None, Some(p)) => {
                    Some(crate::syntax::parser::Word { value: p.value / 1000.0, ..p })
                }
                (None, None) => None,
            };
            self.syntax.block.letters[letter(b'p')] = seconds;
        }
        let cycle = self.syntax.block.g[1].map(|code| code.code).or(self.state.motion);
        if cycle.is_some_and(repeats_in_k)
            && self.syntax.block.letters[letter(b'l')].is_none()
            && let Some(k) = self.syntax.block.letters[letter(b'k')].take()
        {
            self.syntax.block.letters[letter(b'l')] = Some(k);
        }
    }
}
