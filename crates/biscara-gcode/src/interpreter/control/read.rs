//! Reading an O-word line, `M98`/`M99` or Mach4's `G65` into an [`OBlock`] (LinuxCNC's
//! `read_o` and the end of `read_items`).

use std::rc::Rc;

use super::*;
use crate::interpreter::Machine;

impl Control {
    /// Reads an O-word line (`read_o` and the end of `read_items`); `None` when LinuxCNC stops
    /// reading it (a line skipped over).
    pub(super) fn read_o(
        &mut self,
        machine: &mut Machine,
        at: usize,
        m_number: Option<i64>,
    ) -> Result<Option<OBlock>, Fault> {
        let mut block = OBlock::new(OType::None, CallType::None);
        let (bare, mut pos) = match m_number {
            Some(98) => read_m98(machine, at, &mut block)?,
            Some(99) => self.read_m99(machine, at, &mut block)?,
            _ => read_label(machine, at, &mut block)?,
        };
        block.name = self.scoped_name(block.kind, bare);
        if !self.read_o_words(machine, &mut block, &mut pos)? {
            return Ok(None);
        }
        if self.skipping_o.is_some() {
            return Ok(Some(block));
        }
        only_comments_after(machine, pos)?;
        Ok(Some(block))
    }

    /// `M99`: the name of the subroutine it returns from, and where its line goes on.
    fn read_m99(
        &self,
        machine: &Machine,
        at: usize,
        block: &mut OBlock,
    ) -> Result<(String, usize), Fault> {
        if self.defining_sub {
            return Err(machine.line_fault("Found 'M99' instead of 'O endsub' after 'O sub'"));
        }
        block.kind = OType::M99;
        let mut reader = Reader::new(
            &machine.syntax.compact,
            machine.syntax.raw_len,
            &machine.state.params,
            &machine.state,
        );
        reader.set_position(at + 1);
        reader.read_integer_value()?;
        let bare = self.frames[self.level()].name.as_deref().unwrap_or("").to_owned();
        Ok((bare, reader.position()))
    }

    /// The label's name as LinuxCNC keeps it: a subroutine's (and a call's, a return's) as
    /// written, any other (a loop's, a condition's) scoped by the subroutine it is in
    /// (`sub#label`).
    fn scoped_name(&self, kind: OType, bare: String) -> Rc<str> {
        match kind {
            OType::Sub
            | OType::Fanuc
            | OType::EndSub
            | OType::Call
            | OType::M98
            | OType::Return
            | OType::M99 => Rc::from(bare),
            _ => {
                let level = self.level();
                let scope = if level > 0 {
                    self.frames[level].name.clone()
                } else if self.defining_sub {
                    self.sub_name.clone()
                } else {
                    None
                };
                Rc::from(format!("{}#{bare}", scope.as_deref().unwrap_or("")))
            }
        }
    }

    /// What follows the keyword, by kind: a return value, a call's arguments, a condition.
    /// `Ok(false)` when LinuxCNC stops reading the line (a line skipped over).
    fn read_o_words(
        &mut self,
        machine: &mut Machine,
        block: &mut OBlock,
        pos: &mut usize,
    ) -> Result<bool, Fault> {
        let skipping_other =
            self.skipping_o.as_ref().is_some_and(|skipping| **skipping != *block.name);
        match block.kind {
            OType::Sub | OType::Fanuc => {
                if self.defining_sub {
                    return Err(machine.line_fault("Nested subroutine definition"));
                }
            }
            OType::EndSub | OType::Return | OType::M99 => {
                if skipping_other {
                    return Ok(false);
                }
                read_return_value(machine, block.kind, pos)?;
            }
            _ if self.defining_sub => block.kind = OType::None,
            OType::Call => {
                if self.skipping_o.is_some() {
                    return Ok(false);
                }
                block.call_type = CallType::Oword;
                read_call_arguments(machine, block, pos)?;
            }
            OType::M98 => block.call_type = CallType::M98,
            OType::While | OType::Repeat | OType::If | OType::ElseIf => {
                if skipping_other {
                    return Ok(false);
                }
                if machine.syntax.compact.bytes().get(*pos) != Some(&b'[') {
                    return Err(machine.line_fault(format!(
                        "Left bracket missing after '{}'",
                        block.kind.name()
                    )));
                }
                self.test_value = machine.expression(pos)?;
            }
            OType::Do
            | OType::Else
            | OType::EndIf
            | OType::Break
            | OType::Continue
            | OType::EndWhile
            | OType::EndRepeat => {}
            OType::None => return Err(machine.line_fault("Unknown control command in o word")),
        }
        Ok(true)
    }
}

/// `M98 P… L…`: the subprogram's number (P) and repeat count (L), and the line's end.
fn read_m98(
    machine: &mut Machine,
    at: usize,
    block: &mut OBlock,
) -> Result<(String, usize), Fault> {
    block.kind = OType::M98;
    // The rest of the line: P and L words (LinuxCNC reads them with `read_one_item`).
    let mut reader = Reader::new(
        &machine.syntax.compact,
        machine.syntax.raw_len,
        &machine.state.params,
        &machine.state,
    );
    let m_end = {
        reader.set_position(at + 1);
        reader.read_integer_value()?;
        reader.position()
    };
    reader.set_position(m_end);
    let words = &mut machine.syntax.block;
    words.clear();
    let bytes = machine.syntax.compact.bytes();
    while reader.position() < bytes.len() && bytes[reader.position()] != b';' {
        reader.read_item(words)?;
    }
    let Some(p) = words.word(b'p') else {
        return Err(machine.line_fault("Found 'm98' code with no P-word"));
    };
    let mut number = p.value.floor();
    if p.value - number > 0.9999 {
        number = p.value.ceil();
    } else if p.value - number > 0.0001 {
        let (first, last) = machine.span(p.at, p.end);
        return Err(Fault::syntax(first, last, "Non integer value for integer"));
    }
    block.l = words.word(b'l').map(|word| word.value);
    Ok((format!("{}", number as i32), bytes.len()))
}

/// An `O` line's label (`o100`, `o<name>`) and its keyword (`sub`, `while`, …; none: a
/// Fanuc-style program number), and where the line goes on after them.
fn read_label(machine: &Machine, at: usize, block: &mut OBlock) -> Result<(String, usize), Fault> {
    let bytes = machine.syntax.compact.bytes();
    let mut pos = at + 1;
    let bare;
    if bytes.get(pos) == Some(&b'<') {
        let start = pos + 1;
        let end = bytes[start..].iter().position(|&b| b == b'>').map(|i| start + i);
        match end {
            Some(end) => {
                bare = String::from_utf8_lossy(&bytes[start..end]).into_owned();
                pos = end + 1;
            }
            None => {
                // LinuxCNC ignores `read_name`'s error here: the rest is the name.
                bare = String::from_utf8_lossy(&bytes[start..]).into_owned();
                pos = bytes.len();
            }
        }
    } else {
        let mut reader = Reader::new(
            &machine.syntax.compact,
            machine.syntax.raw_len,
            &machine.state.params,
            &machine.state,
        );
        reader.set_position(pos);
        let number = reader.read_integer_value()?;
        pos = reader.position();
        bare = format!("{}", number as i32);
    }
    let rest = &bytes[pos..];
    block.kind = match KEYWORDS.iter().find(|(word, _)| rest.starts_with(word)) {
        Some(&(word, kind)) => {
            pos += word.len();
            kind
        }
        None if matches!(rest.first(), None | Some(b'(' | b';')) => OType::Fanuc,
        None => OType::None,
    };
    Ok((bare, pos))
}

/// `endsub [value]`, `return [value]`: the value returned (`#<_value>`), none for M99.
fn read_return_value(machine: &mut Machine, kind: OType, pos: &mut usize) -> Result<(), Fault> {
    if kind != OType::M99 && machine.syntax.compact.bytes().get(*pos) == Some(&b'[') {
        let value = machine.expression(pos)?;
        machine.state.owords.value = value;
        machine.state.owords.returned = true;
    } else {
        machine.state.owords.value = 0.0;
        machine.state.owords.returned = false;
    }
    Ok(())
}

/// A call's arguments `[…] […]`, up to [`SUB_PARAMS`] (comments between them passed over).
fn read_call_arguments(
    machine: &mut Machine,
    block: &mut OBlock,
    pos: &mut usize,
) -> Result<(), Fault> {
    let mut count = 0;
    while let Some(&byte) = machine.syntax.compact.bytes().get(*pos) {
        match byte {
            b'(' => *pos += 1,
            b'[' => {
                if count >= SUB_PARAMS {
                    return Err(machine.line_fault("Too many subroutine parameters"));
                }
                block.params[count] = machine.expression(pos)?;
                count += 1;
            }
            _ => break,
        }
    }
    block.count = count;
    Ok(())
}

/// After `if [...]` and the like, nothing but comments.
fn only_comments_after(machine: &Machine, mut pos: usize) -> Result<(), Fault> {
    let bytes = machine.syntax.compact.bytes();
    while let Some(&byte) = bytes.get(pos) {
        match byte {
            b'(' => pos += 1,
            b';' => break,
            _ => {
                let (first, last) = machine.span(pos, bytes.len());
                return Err(Fault::syntax(first, last, "Unexpected character after O-word"));
            }
        }
    }
    Ok(())
}

impl Machine {
    /// Mach4's `G65 P… L… A… …` at compact index `at`: a call of subprogram P (L times) with
    /// its letters as the subprogram's own parameters (unset ones 0, as in an `o… call`).
    pub(super) fn read_g65(&mut self, at: usize) -> Result<OBlock, Fault> {
        let mut block = OBlock::new(OType::M98, CallType::G65);
        let digits =
            self.syntax.compact.bytes()[at + 1..].iter().take_while(|b| b.is_ascii_digit()).count();
        let mut reader =
            Reader::new(&self.syntax.compact, self.syntax.raw_len, &self.state.params, &self.state);
        reader.set_position(at + 1 + digits);
        let mut program = None;
        loop {
            let pos = reader.position();
            let Some(&letter) = self.syntax.compact.bytes().get(pos) else { break };
            if letter == b';' {
                break;
            }
            reader.set_position(pos + 1);
            if letter == b'(' {
                // Where a comment stood.
                continue;
            }
            let value = reader.read_real_value()?;
            match letter {
                b'p' => program = Some(value),
                b'l' => block.l = Some(value),
                _ => match g65_argument(letter) {
                    Some(index) => block.params[index - 1] = value,
                    None => {
                        let (first, last) = self.span(pos, pos + 1);
                        return Err(Fault::syntax(
                            first,
                            last,
                            format!(
                                "{} is not an argument of G65 (A–F, H–K, M, Q–Z; P the subprogram, L \
                                 the repeats)",
                                char::from(letter).to_ascii_uppercase()
                            ),
                        ));
                    }
                },
            }
        }
        let Some(program) = program else {
            return Err(self.line_fault("G65 with no P word: which subprogram to call"));
        };
        if program.fract() != 0.0 || program < 0.0 {
            return Err(self.line_fault(format!("G65 P{program}: not a subprogram number")));
        }
        block.name = Rc::from(format!("{}", program as i64));
        Ok(block)
    }

    /// A `[ … ]` expression at compact index `pos` (moved past it).
    pub(super) fn expression(&self, pos: &mut usize) -> Result<f64, Fault> {
        let mut reader =
            Reader::new(&self.syntax.compact, self.syntax.raw_len, &self.state.params, &self.state);
        reader.set_position(*pos);
        let value = reader.read_expression()?;
        *pos = reader.position();
        Ok(value)
    }
}

/// Whether a line's significant characters may be an O-word line, `M98` or `M99`: the only
/// look at an ordinary line.
#[inline]
pub(in crate::interpreter) fn may_control(bytes: &[u8]) -> bool {
    let mut at = usize::from(bytes.first() == Some(&b'/'));
    if bytes.get(at) == Some(&b'n') {
        at += 1;
        while matches!(bytes.get(at), Some(b'0'..=b'9' | b'.')) {
            at += 1;
        }
    }
    match bytes.get(at) {
        Some(b'o') => true,
        Some(b'm') => !matches!(bytes.get(at + 1), Some(b'1'..=b'8')),
        _ => false,
    }
}

/// Whether a line's first item is G65 (`g65`, `g065`, not `g65.1`): Mach4's macro call, looked
/// for only in the Mach3 dialect.
pub(in crate::interpreter) fn may_call_g65(bytes: &[u8]) -> bool {
    let at = first_item(bytes);
    let Some(item) = bytes.get(at..).filter(|item| item.first() == Some(&b'g')) else {
        return false;
    };
    let digits = item[1..].iter().take_while(|b| b.is_ascii_digit()).count();
    let number = &item[1..1 + digits];
    let number = &number[number.iter().take_while(|&&b| b == b'0').count()..];
    number == b"65" && item.get(1 + digits) != Some(&b'.')
}

/// Where the first item of a line starts (after `/` and the N number).
pub(in crate::interpreter) fn first_item(bytes: &[u8]) -> usize {
    let mut at = usize::from(bytes.first() == Some(&b'/'));
    if bytes.get(at) == Some(&b'n') {
        at += 1;
        while matches!(bytes.get(at), Some(b'0'..=b'9' | b'.')) {
            at += 1;
        }
    }
    at
}

/// Fanuc's argument specification I: the local parameter a G65 letter sets.
fn g65_argument(letter: u8) -> Option<usize> {
    Some(match letter {
        b'a' => 1,
        b'b' => 2,
        b'c' => 3,
        b'i' => 4,
        b'j' => 5,
        b'k' => 6,
        b'd' => 7,
        b'e' => 8,
        b'f' => 9,
        b'h' => 11,
        b'm' => 13,
        b'q' => 17,
        b'r' => 18,
        b's' => 19,
        b't' => 20,
        b'u' => 21,
        b'v' => 22,
        b'w' => 23,
        b'x' => 24,
        b'y' => 25,
        b'z' => 26,
        _ => return None,
    })
}
