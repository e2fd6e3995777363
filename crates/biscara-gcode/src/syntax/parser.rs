//! Blocks: the words of one line, with parameters and expressions evaluated as LinuxCNC reads
//! them (`read_items`, `read_real_value`, `read_real_expression`).

use crate::syntax::degrees;
use crate::syntax::lexer::{Compact, Fault};
use crate::syntax::params::{MAX_PARAMETERS, Params};

/// LinuxCNC's modal groups of G and M codes, and what is implemented here.
mod groups;

pub(crate) use groups::{Support, g_group, m_group};

/// Number of G modal groups (LinuxCNC numbers them 0 … 15).
pub(crate) const G_GROUPS: usize = 16;
/// Number of M modal groups (LinuxCNC numbers them 0 … 10).
pub(crate) const M_GROUPS: usize = 11;
/// LinuxCNC's `MAX_EMS`.
const MAX_M_CODES: usize = 4;

/// One word: its value and where it is (compact indices of its letter and its end).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Word {
    pub value: f64,
    pub at: usize,
    pub end: usize,
}

/// One G or M code of a block.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Code {
    /// Ten times the number for G (G92.1 = 921), the number for M.
    pub code: u16,
    pub at: usize,
    pub end: usize,
}

/// A parsed block. Reused from line to line (no allocation once warm).
#[derive(Debug, Default)]
pub(crate) struct Block {
    /// Words by letter (`a` = 0); G, M, N and O are not stored here.
    pub letters: [Option<Word>; 26],
    pub g: [Option<Code>; G_GROUPS],
    pub m: [Option<Code>; M_GROUPS],
    pub m_count: usize,
    /// `#n=value` settings, in order, applied after the line is read.
    pub numbered: Vec<(usize, f64)>,
    /// `#<name>=value` settings: the name's compact range and the value.
    pub named: Vec<(usize, usize, f64)>,
    /// Whether the line holds nothing but (perhaps) a line number, a comment or `/`.
    pub empty: bool,
    /// `@`, `^` (polar radius and angle) and `$` (spindle number): rare, kept out of
    /// [`Block::letters`]; the last `@` or `^` of a line counts, as in LinuxCNC.
    pub extra: Option<Box<ExtraWords>>,
    /// Whether a G or M code that is not implemented here (not [`Support::Yes`]) was read: the
    /// interpreter looks for the one to refuse only then, not on every line.
    pub unsupported: bool,
}

/// The words LinuxCNC reads besides the letters: polar coordinates and the spindle number.
#[derive(Debug, Default, Clone, Copy)]
pub(crate) struct ExtraWords {
    /// `@`: the polar radius.
    pub radius: Option<Word>,
    /// `^`: the polar angle, degrees.
    pub theta: Option<Word>,
    /// `$`: the spindle.
    pub spindle: Option<Word>,
    /// A Mach3 user macro M-code (`M900`), which runs the machine's own macro file.
    pub user_macro: Option<Code>,
}

impl Block {
    pub(crate) fn clear(&mut self) {
        self.letters = [None; 26];
        self.g = [None; G_GROUPS];
        self.m = [None; M_GROUPS];
        self.m_count = 0;
        self.numbered.clear();
        self.named.clear();
        self.empty = true;
        self.unsupported = false;
        if let Some(extra) = &mut self.extra {
            **extra = ExtraWords::default();
        }
    }

    /// The `@`, `^` and `$` words of the line, if any.
    pub(crate) fn extra(&self) -> Option<&ExtraWords> {
        self.extra.as_deref().filter(|extra| {
            extra.radius.is_some() || extra.theta.is_some() || extra.spindle.is_some()
        })
    }

    /// Whether the line has a polar coordinate (`@` or `^`).
    pub(crate) fn polar(&self) -> bool {
        self.extra().is_some_and(|extra| extra.radius.is_some() || extra.theta.is_some())
    }

    /// The word for `letter` (lower case).
    pub(crate) fn word(&self, letter: u8) -> Option<Word> {
        self.letters[usize::from(letter - b'a')]
    }
}

/// What the reader needs to know of the interpreter: LinuxCNC's predefined read-only named
/// parameters (`#<_x>`, `#<_metric>`, …).
pub(crate) trait Predefined {
    /// The value of predefined parameter `name` (without `#<` `>`, lower case, with its `_`).
    fn predefined(&self, name: &[u8]) -> Option<f64>;

    /// Whether an O-word subroutine definition is being passed over: LinuxCNC then reads an
    /// undefined named parameter as 0 instead of refusing it.
    fn defining_sub(&self) -> bool {
        false
    }

    /// Why the INI file gives `#<_ini[SECTION]NAME>` no value; `None` when no INI file is read
    /// (such names are then global names).
    fn ini_why_not(&self, _name: &[u8]) -> Option<String> {
        None
    }
}

/// LinuxCNC's ROUND: `(double) (int) (x ± 0.5)`, half away from zero through a C `int`. A zero
/// result is +0 (ATAN tells it from −0), and beyond the `int` range, or for NaN, the conversion
/// gives `INT_MIN` on x86-64, as rs274 prints.
fn round_to_c_int(x: f64) -> f64 {
    let shifted = x + if x < 0.0 { -0.5 } else { 0.5 };
    let truncated = shifted.trunc();
    if (-2_147_483_648.0..=2_147_483_647.0).contains(&truncated) {
        f64::from(truncated as i32)
    } else {
        -2_147_483_648.0
    }
}

/// Binary operators with LinuxCNC's precedence.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Op {
    RightBracket,
    And,
    Or,
    Xor,
    Eq,
    Ne,
    Gt,
    Ge,
    Lt,
    Le,
    Plus,
    Minus,
    Times,
    Divide,
    Modulo,
    Power,
}

impl Op {
    fn precedence(self) -> u8 {
        match self {
            Op::RightBracket => 1,
            Op::And | Op::Or | Op::Xor => 2,
            Op::Eq | Op::Ne | Op::Gt | Op::Ge | Op::Lt | Op::Le => 3,
            Op::Plus | Op::Minus => 4,
            Op::Times | Op::Divide | Op::Modulo => 5,
            Op::Power => 6,
        }
    }
}

/// The number at `start` of `bytes` (`[+-]`, then the digits and points that follow) when it is
/// `[+-]digits[.digits]` with at most 15 digits, with the offset just past it; `None` for
/// anything else (which takes the general path). Read in one pass, converted exactly: the digits
/// as an integer (exact below 2^53) divided by a power of ten (exact up to 10^22) is correctly
/// rounded, as `str::parse` would give.
fn scan_decimal(bytes: &[u8], start: usize) -> Option<(f64, usize)> {
    const POWERS: [f64; 16] =
        [1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15];
    let (negative, mut at) = match bytes.get(start) {
        Some(b'-') => (true, start + 1),
        Some(b'+') => (false, start + 1),
        _ => (false, start),
    };
    let mut mantissa: u64 = 0;
    let mut digits = 0usize;
    // Digits after the point; `usize::MAX` before it.
    let mut decimals = usize::MAX;
    while let Some(&byte) = bytes.get(at) {
        match byte {
            b'0'..=b'9' => {
                if digits == 15 {
                    return None;
                }
                mantissa = mantissa * 10 + u64::from(byte - b'0');
                digits += 1;
                decimals = decimals.wrapping_add(usize::from(decimals != usize::MAX));
            }
            b'.' if decimals == usize::MAX => decimals = 0,
            b'.' => return None,
            _ => break,
        }
        at += 1;
    }
    if digits == 0 {
        return None;
    }
    let value = mantissa as f64 / POWERS[if decimals == usize::MAX { 0 } else { decimals }];
    Some((if negative { -value } else { value }, at))
}

/// [`scan_decimal`] of the whole of `text`; `None` when anything follows the number.
#[cfg(test)]
fn fast_decimal(text: &[u8]) -> Option<f64> {
    scan_decimal(text, 0).filter(|&(_, end)| end == text.len()).map(|(value, _)| value)
}

/// LinuxCNC's `TOLERANCE_EQUAL` for EQ and NE.
const TOLERANCE_EQUAL: f64 = 0.0001;

/// Reads one line's compact bytes into a block.
pub(crate) struct Reader<'a> {
    bytes: &'a [u8],
    compact: &'a Compact,
    raw_len: usize,
    params: &'a Params,
    predefined: &'a dyn Predefined,
    pos: usize,
    /// Names assigned earlier on this line (compact ranges): LinuxCNC creates a named parameter,
    /// holding 0, as soon as it reads its assignment, so that it reads as 0 later on the line.
    created: [(u8, u8); 64],
    created_count: usize,
    /// Mach3's codes LinuxCNC lacks are read too: G31 (its straight probe) and the probe log
    /// macros M40 and M41 (as user M codes).
    mach3: bool,
    /// Numbers take an exponent written right after them (`6.2e-15`), as C's `strtod` reads
    /// them in Marlin; LinuxCNC and Grbl read the `e` as a word letter.
    exponents: bool,
}

impl<'a> Reader<'a> {
    pub(crate) fn new(
        compact: &'a Compact,
        raw_len: usize,
        params: &'a Params,
        predefined: &'a dyn Predefined,
    ) -> Reader<'a> {
        Reader {
            bytes: compact.bytes(),
            compact,
            raw_len,
            params,
            predefined,
            pos: 0,
            created: [(0, 0); 64],
            created_count: 0,
            mach3: false,
            exponents: false,
        }
    }

    /// Raw column range of compact range `start..end`.
    pub(crate) fn span(&self, start: usize, end: usize) -> (usize, usize) {
        let first = self.compact.column(start, self.raw_len);
        let last = if end > start { self.compact.column(end - 1, self.raw_len) + 1 } else { first };
        (first, last.max(first + 1))
    }

    fn syntax(&self, start: usize, end: usize, message: impl Into<String>) -> Fault {
        let (first, last) = self.span(start, end);
        Fault::syntax(first, last, message)
    }

    fn invalid(&self, start: usize, end: usize, message: impl Into<String>) -> Fault {
        let (first, last) = self.span(start, end);
        Fault::invalid(first, last, message)
    }

    fn peek(&self) -> u8 {
        self.bytes.get(self.pos).copied().unwrap_or(0)
    }

    fn peek_at(&self, offset: usize) -> u8 {
        self.bytes.get(self.pos + offset).copied().unwrap_or(0)
    }

    /// Reads the whole line into `block` (`read_items`). Inlined into the interpreter's one
    /// call: as a call, its `Result` went through memory (+1 % of `interpret`'s instructions).
    #[inline(always)]
    pub(crate) fn read_block(&mut self, block: &mut Block) -> Result<(), Fault> {
        block.clear();
        if self.peek() == b'/' {
            self.pos += 1;
        }
        if self.peek() == b'n' {
            // LinuxCNC's `read_n_number`: an unsigned integer, optionally `.` and more digits.
            let start = self.pos;
            self.pos += 1;
            for part in 0..2 {
                if part == 1 {
                    if self.peek() != b'.' {
                        break;
                    }
                    self.pos += 1;
                }
                let digits = self.pos;
                while self.peek().is_ascii_digit() {
                    self.pos += 1;
                }
                if self.pos == digits {
                    return Err(self.syntax(start, self.pos + 1, "Bad format unsigned integer"));
                }
            }
        }
        while self.pos < self.bytes.len() && self.peek() != b';' {
            self.read_item(block)?;
        }
        // Assignments are stored, and read-only names refused, by the interpreter after the
        // block's checks.
        Ok(())
    }

    /// The compact index of the next byte to read.
    pub(crate) fn position(&self) -> usize {
        self.pos
    }

    /// Reads on from compact index `pos`.
    pub(crate) fn set_position(&mut self, pos: usize) {
        self.pos = pos;
    }

    /// One word, setting or comment (`read_one_item`). Inlined into `read_block`'s loop, as it
    /// was before O-words called it too (2 % of `interpret`'s instructions as a call).
    #[inline(always)]
    pub(crate) fn read_item(&mut self, block: &mut Block) -> Result<(), Fault> {
        let start = self.pos;
        let letter = self.peek();
        match letter {
            b'(' => {
                self.pos += 1;
                return Ok(());
            }
            b'#' => {
                block.empty = false;
                return self.read_setting(block);
            }
            b'@' | b'^' | b'$' => {
                block.empty = false;
                let extra = block.extra.get_or_insert_with(Box::default);
                if letter == b'$' && extra.spindle.is_some() {
                    return Err(self.syntax(
                        start,
                        start + 1,
                        "Multiple spindle choice ($) words on one line",
                    ));
                }
                self.pos += 1;
                let value = self.read_real_value()?;
                let word = Some(Word { value, at: start, end: self.pos });
                let extra = block.extra.get_or_insert_with(Box::default);
                match letter {
                    b'@' => extra.radius = word,
                    b'^' => extra.theta = word,
                    _ => extra.spindle = word,
                }
                return Ok(());
            }
            b'a' | b'b' | b'u' | b'v' | b'w' => {
                let (first, _) = self.span(start, start + 1);
                let mut end = start + 1;
                while end < self.bytes.len() && !self.bytes[end].is_ascii_lowercase() {
                    end += 1;
                }
                let (_, last) = self.span(start, end);
                return Err(Fault {
                    start: first,
                    end: last,
                    kind: crate::syntax::lexer::FaultKind::ForeignAxis(
                        char::from(letter).to_ascii_uppercase(),
                    ),
                    message: String::new(),
                });
            }
            b'g' => {
                block.empty = false;
                self.pos += 1;
                return self.read_g(block, start);
            }
            b'm' => {
                block.empty = false;
                self.pos += 1;
                return self.read_m(block, start);
            }
            b'c' | b'd' | b'e' | b'f' | b'h' | b'i' | b'j' | b'k' | b'l' | b'p' | b'q' | b'r'
            | b's' | b't' | b'x' | b'y' | b'z' => {}
            _ => {
                let shown = if letter.is_ascii_graphic() {
                    format!("'{}'", char::from(letter))
                } else {
                    format!("byte 0x{letter:02x}")
                };
                return Err(self.syntax(start, start + 1, format!("Bad character {shown} used")));
            }
        }
        block.empty = false;
        let slot = usize::from(letter - b'a');
        if block.letters[slot].is_some() {
            return Err(self.syntax(
                start,
                start + 1,
                format!("Multiple {} words on one line", char::from(letter)),
            ));
        }
        self.pos += 1;
        let value = match letter {
            b'l' | b't' | b'h' => self.read_integer_value()? as f64,
            _ => self.read_real_value()?,
        };
        match letter {
            b'f' if value < 0.0 => {
                return Err(self.invalid(start, self.pos, "Negative f word used"));
            }
            b's' if value < 0.0 => {
                return Err(self.invalid(start, self.pos, "Negative spindle speed used"));
            }
            b'l' if value < 0.0 => {
                return Err(self.invalid(start, self.pos, "Negative l word used"));
            }
            // Checked as it is read (`read_t`), before the rest of the line.
            b't' if value < 0.0 => {
                return Err(self.invalid(start, self.pos, "Negative tool id (tool not found)"));
            }
            _ => {}
        }
        block.letters[slot] = Some(Word { value, at: start, end: self.pos });
        Ok(())
    }

    /// Reads an exponent written right after a literal number (`on`; Marlin's `strtod`).
    pub(crate) fn exponents(mut self, on: bool) -> Reader<'a> {
        self.exponents = on;
        self
    }

    /// The end of an exponent (`e-15`, `E+3`, `e7`) at `at` in the compact line, written right
    /// after the number's last character (no blank between them in the raw line), when there
    /// is one.
    fn exponent_end(&self, at: usize) -> Option<usize> {
        if self.bytes.get(at) != Some(&b'e') || at == 0 {
            return None;
        }
        let adjacent =
            self.compact.column(at, self.raw_len) == self.compact.column(at - 1, self.raw_len) + 1;
        let mut end = at + 1;
        if matches!(self.bytes.get(end), Some(b'+' | b'-')) {
            end += 1;
        }
        let digits = self.bytes[end.min(self.bytes.len())..]
            .iter()
            .take_while(|b| b.is_ascii_digit())
            .count();
        // Each character of the exponent written right after the one before it.
        let joined = (at + 1..end + digits).all(|index| {
            self.compact.column(index, self.raw_len)
                == self.compact.column(index - 1, self.raw_len) + 1
        });
        (adjacent && joined && digits > 0).then_some(end + digits)
    }

    /// Reads Mach3's G31, M40 and M41 too (`on`), which LinuxCNC does not know.
    pub(crate) fn mach3(mut self, on: bool) -> Reader<'a> {
        self.mach3 = on;
        self
    }

    fn read_g(&mut self, block: &mut Block, start: usize) -> Result<(), Fault> {
        let value = self.read_real_value()? * 10.0;
        let end = self.pos;
        let mut code = value.floor();
        if value - code > 0.999 {
            code = value.ceil();
        } else if value - code > 0.001 {
            return Err(self.syntax(start, end, "G-code out of range"));
        }
        if code > 999.0 {
            return Err(self.syntax(start, end, "G-code out of range"));
        }
        if code < 0.0 {
            return Err(self.syntax(start, end, "Negative g code used"));
        }
        let code = code as u16;
        let mach3 = || (self.mach3 && code == 310).then_some((1, Support::Yes));
        let Some((group, support)) = g_group(code).or_else(mach3) else {
            return Err(self.syntax(start, end, "Unknown g code used"));
        };
        block.unsupported |= support != Support::Yes;
        if let Some(before) = block.g[group] {
            // rs274's `read_g` lets G80 share a block with another motion code, which wins.
            if group == 1 && (before.code == 800 || code == 800) {
                if before.code == 800 {
                    block.g[group] = Some(Code { code, at: start, end });
                }
                return Ok(());
            }
            return Err(self.syntax(start, end, "Two g codes used from same modal group"));
        }
        block.g[group] = Some(Code { code, at: start, end });
        Ok(())
    }

    fn read_m(&mut self, block: &mut Block, start: usize) -> Result<(), Fault> {
        let value = self.read_integer_value()?;
        let end = self.pos;
        if value < 0 {
            return Err(self.syntax(start, end, "Negative m code used"));
        }
        let known = (0..=199).contains(&value)
            && (m_group(value as u16).is_some() || (self.mach3 && matches!(value, 40 | 41)));
        if self.mach3 && !known && value <= i64::from(u16::MAX) {
            // A Mach3 user macro (`M900`: the machine's own macro file).
            let extra = block.extra.get_or_insert_with(Box::default);
            if extra.user_macro.is_some() {
                return Err(self.syntax(start, end, "Two user macro M-codes on one line"));
            }
            extra.user_macro = Some(Code { code: value as u16, at: start, end });
            return Ok(());
        }
        if value > 199 {
            return Err(self.syntax(start, end, format!("M-code greater than 199: M{value}")));
        }
        let code = value as u16;
        let mach3 = || (self.mach3 && matches!(code, 40 | 41)).then_some((10, Support::Yes));
        let Some((group, support)) = m_group(code).or_else(mach3) else {
            return Err(self.syntax(start, end, format!("Unknown m code used: M{value}")));
        };
        block.unsupported |= support != Support::Yes;
        if block.m[group].is_some() {
            return Err(self.syntax(start, end, "Two m codes used from same modal group"));
        }
        block.m_count += 1;
        if block.m_count > MAX_M_CODES {
            return Err(self.syntax(start, end, "Too many m codes on line"));
        }
        block.m[group] = Some(Code { code, at: start, end });
        Ok(())
    }

    /// `#index=value` or `#<name>=value` (`read_parameter_setting`).
    fn read_setting(&mut self, block: &mut Block) -> Result<(), Fault> {
        let start = self.pos;
        self.pos += 1;
        if self.peek() == b'<' {
            let (name_start, name_end) = self.read_name()?;
            self.expect_equals(start)?;
            if self.created_count < self.created.len() {
                self.created[self.created_count] = (name_start as u8, name_end as u8);
                self.created_count += 1;
            }
            let value = self.read_real_value()?;
            block.named.push((name_start, name_end, value));
        } else {
            let index = self.read_integer_value()?;
            let index = self.check_index(index, start)?;
            self.expect_equals(start)?;
            let value = self.read_real_value()?;
            block.numbered.push((index, value));
        }
        Ok(())
    }

    fn expect_equals(&mut self, start: usize) -> Result<(), Fault> {
        if self.peek() != b'=' {
            return Err(self.syntax(
                start,
                self.pos + 1,
                "Equal sign missing in parameter setting",
            ));
        }
        self.pos += 1;
        Ok(())
    }

    fn check_index(&self, index: i64, start: usize) -> Result<usize, Fault> {
        if index < 1 || index >= MAX_PARAMETERS as i64 {
            return Err(self.syntax(start, self.pos, "Parameter number out of range"));
        }
        Ok(index as usize)
    }

    /// `<name>` after a `#`: returns the compact range of the name. `#<_ini[section]name>` is
    /// read like any global name: the INI file's values, when one is given, are among the
    /// predefined names ([`Predefined::predefined`]).
    fn read_name(&mut self) -> Result<(usize, usize), Fault> {
        let open = self.pos;
        self.pos += 1;
        let start = self.pos;
        while self.pos < self.bytes.len() && self.bytes[self.pos] != b'>' {
            if self.bytes[self.pos] == b'(' {
                break;
            }
            self.pos += 1;
        }
        if self.peek() != b'>' {
            return Err(self.syntax(open, self.pos, "Named parameter not terminated"));
        }
        let end = self.pos;
        self.pos += 1;
        if end == start {
            return Err(self.syntax(open, self.pos, "Named parameter has no name"));
        }
        Ok((start, end))
    }

    /// A real value (`read_real_value`): a number, a parameter, an expression, a unary
    /// function, or a sign before one of those.
    pub(crate) fn read_real_value(&mut self) -> Result<f64, Fault> {
        let start = self.pos;
        let c = self.peek();
        let next = self.peek_at(1);
        let value = match c {
            0 => {
                return Err(self.syntax(start, start, "No characters found in reading real value"));
            }
            b'[' => self.read_expression()?,
            b'#' => self.read_parameter()?,
            b'+' if next != 0 && !next.is_ascii_digit() && next != b'.' => {
                self.pos += 1;
                self.read_real_value()?
            }
            b'-' if next != 0 && !next.is_ascii_digit() && next != b'.' => {
                self.pos += 1;
                -self.read_real_value()?
            }
            b'a'..=b'z' => self.read_unary()?,
            _ => self.read_number()?,
        };
        if !value.is_finite() {
            return Err(self.invalid(start, self.pos, "the value is not a finite number"));
        }
        Ok(value)
    }

    /// An integer value (`read_integer_value`): a real value within 0.0001 of an integer.
    pub(crate) fn read_integer_value(&mut self) -> Result<i64, Fault> {
        let start = self.pos;
        let value = self.read_real_value()?;
        let mut integer = value.floor();
        if value - integer > 0.9999 {
            integer = value.ceil();
        } else if value - integer > 0.0001 {
            return Err(self.syntax(start, self.pos, "Non integer value for integer"));
        }
        if integer.abs() > 1e15 {
            return Err(self.invalid(start, self.pos, "the value is too large for an integer"));
        }
        Ok(integer as i64)
    }

    /// A literal number: optional sign, digits and one decimal point (no exponent: `e` is a
    /// word letter).
    fn read_number(&mut self) -> Result<f64, Fault> {
        let start = self.pos;
        if let Some((value, end)) = scan_decimal(self.bytes, start) {
            if !self.exponents {
                self.pos = end;
                return Ok(value);
            }
            if let Some(exponent_end) = self.exponent_end(end) {
                return self.read_with_exponent(start, exponent_end);
            }
            self.pos = end;
            return Ok(value);
        }
        if matches!(self.peek(), b'+' | b'-') {
            self.pos += 1;
        }
        while matches!(self.peek(), b'0'..=b'9' | b'.') {
            self.pos += 1;
        }
        if self.exponents
            && let Some(end) = self.exponent_end(self.pos)
        {
            return self.read_with_exponent(start, end);
        }
        let text = &self.bytes[start..self.pos];
        let text = std::str::from_utf8(text).unwrap_or("");
        let dots = text.bytes().filter(|&b| b == b'.').count();
        // As C's strtod, which LinuxCNC calls: nothing converts unless a digit comes first, or a
        // point and then a digit (`..5` fails to convert; `1..5` converts `1.` and leaves `.5`).
        let body = text.trim_start_matches(['+', '-']).as_bytes();
        let converts = body.first().is_some_and(u8::is_ascii_digit)
            || (body.first() == Some(&b'.') && body.get(1).is_some_and(u8::is_ascii_digit));
        if !converts {
            return Err(self.syntax(
                start,
                self.pos + 1,
                format!("bad number format (conversion failed) parsing '{text}'"),
            ));
        }
        if dots > 1 {
            return Err(self.syntax(
                start,
                self.pos,
                format!("bad number format (trailing characters) parsing '{text}'"),
            ));
        }
        let value: f64 = text.parse().map_err(|_| {
            self.syntax(start, self.pos, format!("bad number format parsing '{text}'"))
        })?;
        if !value.is_finite() {
            return Err(self.invalid(start, self.pos, format!("{text} is not a finite number")));
        }
        Ok(value)
    }

    /// The number `start..end` with its exponent, as `strtod` reads it (Marlin).
    #[cold]
    fn read_with_exponent(&mut self, start: usize, end: usize) -> Result<f64, Fault> {
        let text = std::str::from_utf8(&self.bytes[start..end]).unwrap_or("");
        let value: f64 = text
            .parse()
            .map_err(|_| self.syntax(start, end, format!("bad number format parsing '{text}'")))?;
        self.pos = end;
        if !value.is_finite() {
            return Err(self.invalid(start, end, format!("{text} is not a finite number")));
        }
        Ok(value)
    }

    /// `#n`, `##n`, `#[expr]`, `#<name>`.
    fn read_parameter(&mut self) -> Result<f64, Fault> {
        let start = self.pos;
        self.pos += 1;
        if self.peek() == b'<' {
            let (name_start, name_end) = self.read_name()?;
            let name = &self.bytes[name_start..name_end];
            let value = self.named_value(name);
            let value = value.or_else(|| self.predefined.defining_sub().then_some(0.0));
            return value.ok_or_else(|| {
                let shown = String::from_utf8_lossy(name);
                // LinuxCNC's wording, and why for a name only its INI file would define.
                let why = if !name.starts_with(b"_ini[") {
                    String::new()
                } else if let Some(why) = self.predefined.ini_why_not(name) {
                    format!(" ({why}, and the program did not set it)")
                } else {
                    " (an INI file variable, and no INI file is read: none was given, or its \
                     [RS274NGC] INI_VARS is 0; the name is then a global one that the program \
                     must set first, as in LinuxCNC without an INI file)"
                        .to_owned()
                };
                self.invalid(
                    start,
                    self.pos,
                    format!("Named parameter #<{shown}> not defined{why}"),
                )
            });
        }
        let index = self.read_integer_value()?;
        let index = self.check_index(index, start)?;
        Ok(self.params.get(index))
    }

    fn named_value(&self, name: &[u8]) -> Option<f64> {
        if name.first() == Some(&b'_')
            && let Some(value) = self.predefined.predefined(name)
        {
            return Some(value);
        }
        self.params.named(name).or_else(|| {
            let created = &self.created[..self.created_count];
            created
                .iter()
                .any(|&(start, end)| &self.bytes[usize::from(start)..usize::from(end)] == name)
                .then_some(0.0)
        })
    }

    /// A unary function: `abs[…]`, `atan[…]/[…]`, `exists[#<name>]`, ….
    fn read_unary(&mut self) -> Result<f64, Fault> {
        // LinuxCNC's `read_operation_unary`: the first letter chooses, the name is matched as a
        // prefix (so `absx[` is ABS followed by a missing bracket).
        let start = self.pos;
        const NAMES: [&[u8]; 14] = [
            b"abs", b"acos", b"asin", b"atan", b"cos", b"exp", b"exists", b"fix", b"fup", b"ln",
            b"round", b"sin", b"sqrt", b"tan",
        ];
        let rest = &self.bytes[start..];
        let first = rest[0];
        let Some(name) = NAMES.iter().copied().find(|name| rest.starts_with(name)) else {
            let message = if b"aceflrst".contains(&first) {
                format!("Unknown word starting with {}", char::from(first))
            } else {
                "Unknown word where unary operation could be".to_owned()
            };
            return Err(self.syntax(start, start + 1, message));
        };
        self.pos += name.len();
        let name_end = self.pos;
        if self.peek() != b'[' {
            return Err(self.syntax(
                start,
                self.pos + 1,
                "Left bracket missing after unary operation name",
            ));
        }
        if name == b"exists" {
            // LinuxCNC's `read_bracketed_parameter` with `check_exists`: `[#<name>]` is whether
            // the name is defined, `[#n]` (n any integer value, `##1` included) whether n is a
            // parameter number.
            self.pos += 1;
            if self.peek() != b'#' {
                return Err(self.syntax(start, self.pos + 1, "Expected # reading parameter"));
            }
            self.pos += 1;
            let exists = if self.peek() == b'<' {
                let (name_start, end) = self.read_name()?;
                self.named_value(&self.bytes[name_start..end]).is_some()
            } else {
                let index = self.read_integer_value()?;
                (1..MAX_PARAMETERS as i64).contains(&index)
            };
            if self.peek() != b']' {
                return Err(self.syntax(
                    start,
                    self.pos + 1,
                    "Expected ] reading bracketed parameter",
                ));
            }
            self.pos += 1;
            return Ok(if exists { 1.0 } else { 0.0 });
        }
        let argument = self.read_expression()?;
        let fail = |message: &str| self.invalid(start, name_end, message);
        // LinuxCNC's `execute_unary`; the trigonometry in `degrees`.
        let value = match name {
            // `if x < 0 then −x`: −0 stays −0 (which ATAN tells from +0).
            b"abs" => {
                if argument < 0.0 {
                    -argument
                } else {
                    argument
                }
            }
            b"acos" => {
                if !(-1.0..=1.0).contains(&argument) {
                    return Err(fail("Argument to acos out of range"));
                }
                degrees::acos(argument)
            }
            b"asin" => {
                if !(-1.0..=1.0).contains(&argument) {
                    return Err(fail("Argument to asin out of range"));
                }
                degrees::asin(argument)
            }
            b"atan" => {
                if self.peek() != b'/' {
                    return Err(self.syntax(
                        start,
                        self.pos + 1,
                        "Slash missing after first atan argument",
                    ));
                }
                self.pos += 1;
                if self.peek() != b'[' {
                    return Err(self.syntax(
                        start,
                        self.pos + 1,
                        "Left bracket missing after slash with atan",
                    ));
                }
                let x = self.read_expression()?;
                degrees::atan2(argument, x)
            }
            b"cos" => degrees::cos(argument),
            b"exp" => argument.exp(),
            b"fix" => argument.floor(),
            b"fup" => argument.ceil(),
            b"ln" => {
                if argument <= 0.0 {
                    return Err(fail("Zero or negative argument to ln"));
                }
                argument.ln()
            }
            b"round" => round_to_c_int(argument),
            b"sin" => degrees::sin(argument),
            b"sqrt" => {
                if argument < 0.0 {
                    return Err(fail("Negative argument to sqrt"));
                }
                argument.sqrt()
            }
            _ => degrees::tan(argument),
        };
        Ok(value)
    }

    /// `[ … ]` with LinuxCNC's precedence climbing (`read_real_expression`).
    pub(crate) fn read_expression(&mut self) -> Result<f64, Fault> {
        let start = self.pos;
        self.pos += 1;
        let mut values = [0.0f64; 8];
        let mut ops = [Op::RightBracket; 8];
        let mut op_at = [0usize; 8];
        values[0] = self.read_real_value()?;
        op_at[0] = self.pos;
        ops[0] = self.read_operation(start)?;
        let mut index = 1;
        while ops[index - 1] != Op::RightBracket {
            values[index] = self.read_real_value()?;
            op_at[index] = self.pos;
            ops[index] = self.read_operation(start)?;
            if ops[index].precedence() > ops[index - 1].precedence() {
                index += 1;
                continue;
            }
            loop {
                let left = values[index - 1];
                values[index - 1] =
                    self.binary(left, ops[index - 1], values[index], op_at[index - 1])?;
                ops[index - 1] = ops[index];
                op_at[index - 1] = op_at[index];
                if index > 1 && ops[index - 1].precedence() <= ops[index - 2].precedence() {
                    index -= 1;
                } else {
                    break;
                }
            }
        }
        let value = values[0];
        if value.is_nan() {
            return Err(self.invalid(start, self.pos, "Calculation resulted in 'not a number'"));
        }
        if value.is_infinite() {
            return Err(self.invalid(start, self.pos, "Calculation resulted in 'infinity'"));
        }
        Ok(value)
    }

    fn read_operation(&mut self, open: usize) -> Result<Op, Fault> {
        let start = self.pos;
        let c = self.peek();
        let next = self.peek_at(1);
        let next2 = self.peek_at(2);
        let (op, length) = match c {
            0 => return Err(self.syntax(open, self.pos, "Unclosed expression")),
            b']' => (Op::RightBracket, 1),
            b'+' => (Op::Plus, 1),
            b'-' => (Op::Minus, 1),
            b'/' => (Op::Divide, 1),
            b'*' if next == b'*' => (Op::Power, 2),
            b'*' => (Op::Times, 1),
            b'a' if next == b'n' && next2 == b'd' => (Op::And, 3),
            b'm' if next == b'o' && next2 == b'd' => (Op::Modulo, 3),
            b'x' if next == b'o' && next2 == b'r' => (Op::Xor, 3),
            b'o' if next == b'r' => (Op::Or, 2),
            b'e' if next == b'q' => (Op::Eq, 2),
            b'n' if next == b'e' => (Op::Ne, 2),
            b'g' if next == b't' => (Op::Gt, 2),
            b'g' if next == b'e' => (Op::Ge, 2),
            b'l' if next == b't' => (Op::Lt, 2),
            b'l' if next == b'e' => (Op::Le, 2),
            b'a'..=b'z' => {
                return Err(self.syntax(
                    start,
                    start + 1,
                    format!("Unknown operation name starting with {}", char::from(c)),
                ));
            }
            _ => return Err(self.syntax(start, start + 1, "Unknown operation")),
        };
        self.pos += length;
        Ok(op)
    }

    fn binary(&self, left: f64, op: Op, right: f64, at: usize) -> Result<f64, Fault> {
        let fail = |message: &str| self.invalid(at, at + 1, message);
        let truth = |condition: bool| if condition { 1.0 } else { 0.0 };
        let value = match op {
            Op::RightBracket => right,
            Op::And => truth(left != 0.0 && right != 0.0),
            Op::Or => truth(left != 0.0 || right != 0.0),
            Op::Xor => truth((left != 0.0) != (right != 0.0)),
            Op::Eq => truth((left - right).abs() < TOLERANCE_EQUAL),
            Op::Ne => truth((left - right).abs() >= TOLERANCE_EQUAL),
            Op::Gt => truth(left > right),
            Op::Ge => truth(left >= right),
            Op::Lt => truth(left < right),
            Op::Le => truth(left <= right),
            Op::Plus => left + right,
            Op::Minus => left - right,
            Op::Times => left * right,
            Op::Divide => {
                if right == 0.0 {
                    return Err(fail("Attempt to divide by zero"));
                }
                left / right
            }
            Op::Modulo => {
                // fmod; by zero it is NaN, refused at the end of the expression, as LinuxCNC
                let value = left % right;
                if value < 0.0 { value + right.abs() } else { value }
            }
            Op::Power => {
                if left < 0.0 && right.floor() != right {
                    return Err(fail("Attempt to raise negative to non integer power"));
                }
                left.powf(right)
            }
        };
        Ok(value)
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::fast_decimal;

    #[test]
    fn fast_decimals_are_the_parsed_values() {
        for text in ["0", "-0", "5.", ".5", "+1.25", "-0004.250", "123456789012345", "0.1", "9.99"]
        {
            let parsed: f64 = text.parse().unwrap();
            assert_eq!(fast_decimal(text.as_bytes()), Some(parsed), "{text}");
        }
        for text in ["", ".", "-", "1.2.3", "1234567890123456", "1e5", "+-1"] {
            assert_eq!(fast_decimal(text.as_bytes()), None, "{text}");
        }
    }

    proptest! {
        #[test]
        fn fast_decimals_round_correctly(int in 0u64..10_000_000, frac in 0u64..100_000_000, sign: bool) {
            let text = format!("{}{int}.{frac:08}", if sign { "-" } else { "" });
            let parsed: f64 = text.parse().unwrap();
            prop_assert_eq!(fast_decimal(text.as_bytes()), Some(parsed));
        }
    }
}
