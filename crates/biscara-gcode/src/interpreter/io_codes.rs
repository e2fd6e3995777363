//! The machine-control M-codes with no motion, and the spindle number word `$`, as LinuxCNC's
//! `rs274` reads them with one spindle.
//!
//! - M48–M53 (feed and speed override switches, adaptive feed, feed hold): accepted and checked
//!   as rs274 checks them; nothing is emitted (overrides are the operator's, and a simulation
//!   runs at the programmed feed).
//! - M62–M65 (digital outputs), M66 (wait for an input), M67/M68 (analog outputs): an event
//!   with the code, as the user M-codes M100–M199, and listed in the note of codes with no
//!   motion (a robot's controller may drive its gripper or a conveyor with them).
//! - M19 (spindle orientation): an event with the code; as in LinuxCNC it stops the spindle's
//!   modal state (M72 turns it on again) without a spindle-off event.
//! - `$`: the spindle, truncated to an integer: 0, or −1 (all spindles) where rs274 takes it;
//!   any other number is refused with rs274's message.

use super::Machine;
use crate::syntax::lexer::Fault;
use crate::syntax::parser::Word;

/// rs274's message for a `$` word no code on the line uses.
const UNUSED_DOLLAR: &str = "$ (spindle selection) word with no M3, M4, M5, M19, M51, G33, G33.1, \
                             G76, G95, G96 or G97 to use it";

/// LinuxCNC's `round_to_int`.
fn round(value: f64) -> f64 {
    (value + if value < 0.0 { -0.5 } else { 0.5 }).trunc()
}

impl Machine {
    /// Whether a `$` word is on the line but no code uses it (`check_other_codes`).
    pub(super) fn check_dollar(&self) -> Result<(), Fault> {
        let Some(dollar) = self.syntax.block.extra().and_then(|extra| extra.spindle) else {
            return Ok(());
        };
        let m7 = self.syntax.block.m[7].is_some_and(|code| matches!(code.code, 3 | 4 | 5 | 19));
        let m51 = self.syntax.block.m[9].is_some_and(|code| code.code == 51);
        // rs274 names G97 in its message, but does not take `$` for it alone.
        if m7 || m51 || self.syntax.block.word(b's').is_some() {
            Ok(())
        } else {
            Err(self.word_fault(dollar, UNUSED_DOLLAR))
        }
    }

    /// The `$` checks of G97, S and M3/M4/M5/M19, in rs274's order, before the block runs.
    pub(super) fn check_spindle_number(&self) -> Result<(), Fault> {
        let Some(dollar) = self.syntax.block.extra().and_then(|extra| extra.spindle) else {
            return Ok(());
        };
        let number = dollar.value.trunc();
        let valid = number == 0.0 || number == -1.0;
        if self.syntax.block.g[14].is_some() && !valid {
            return Err(
                self.word_fault(dollar, "Invalid spindle ($) number in Spindle Mode command")
            );
        }
        if self.syntax.block.word(b's').is_some() && !valid {
            return Err(
                self.word_fault(dollar, "Invalid spindle ($) number in Spindle speed command")
            );
        }
        if let Some(code) =
            self.syntax.block.m[7].filter(|code| matches!(code.code, 3 | 4 | 5 | 19))
        {
            let valid = if code.code == 19 { number == 0.0 } else { valid };
            if !valid {
                return Err(self.word_fault(
                    dollar,
                    format!("Spindle ($) number out of range in M{} Command", code.code),
                ));
            }
        }
        if self.syntax.block.m[9].is_some_and(|code| code.code == 51) {
            return Err(self.word_fault(dollar, "Invalid spindle ($) number in M51 command"));
        }
        Ok(())
    }

    /// Whether the P word is used by an M-code of this module (`check_other_codes`).
    pub(super) fn io_uses_p(&self) -> bool {
        self.syntax.block.m[9].is_some_and(|code| code.code >= 50)
            || self.syntax.block.m[5].is_some_and(|code| code.code <= 66)
            || self.syntax.block.m[7].is_some_and(|code| code.code == 19)
    }

    /// Whether the Q word is used by an M-code of this module.
    pub(super) fn io_uses_q(&self) -> bool {
        self.syntax.block.m[5].is_some_and(|code| code.code >= 66)
            || self.syntax.block.m[7].is_some_and(|code| code.code == 19)
    }

    /// Whether the E word is used (M66, M67, M68).
    pub(super) fn io_uses_e(&self) -> bool {
        self.syntax.block.m[5].is_some_and(|code| code.code >= 66)
    }

    /// Whether the L word is used (M66).
    pub(super) fn io_uses_l(&self) -> bool {
        self.syntax.block.m[5].is_some_and(|code| code.code == 66)
    }

    /// M62–M68 (group 5, the first of `convert_m`).
    pub(super) fn io_output(&mut self) -> Result<(), Fault> {
        let Some(code) = self.syntax.block.m[5] else { return Ok(()) };
        let at = (code.at, code.end);
        let word = |letter: u8| self.syntax.block.word(letter);
        let p = word(b'p').map(|p| round(p.value));
        let e = word(b'e').map(|e| round(e.value));
        match code.code {
            62..=65 => {
                let what = match code.code {
                    62 => "motion output",
                    63 => "motion digital output",
                    _ => "auxiliary digital output",
                };
                self.refuse_with_comp(
                    at,
                    &format!("Cannot set {what} with cutter radius compensation on"),
                )?;
                if p.is_none() {
                    return Err(
                        self.code_fault(code, format!("No valid P word with M{}", code.code))
                    );
                }
            }
            66 => {
                let digital = p.is_some_and(|p| p >= 0.0);
                let analog = e.is_some_and(|e| e >= 0.0);
                if !digital && !analog {
                    return Err(self.code_fault(
                        code,
                        "Need to have either a valid P or a valid E word with M66",
                    ));
                }
                if digital && analog {
                    return Err(self.code_fault(
                        code,
                        "Invalid to select both a digital and an analog input with M66",
                    ));
                }
                let wait_type = word(b'l').map_or(0.0, |l| l.value);
                let timeout = word(b'q').map_or(-1.0, |q| q.value);
                if wait_type != 0.0 && timeout <= 0.0 {
                    return Err(
                        self.code_fault(code, "Zero timeout with wait type != immediate return")
                    );
                }
                if analog && wait_type != 0.0 {
                    return Err(self.code_fault(
                        code,
                        "Can't select analog input with wait type != immediate return",
                    ));
                }
                let what = if digital { "digital" } else { "analog" };
                self.refuse_with_comp(
                    at,
                    &format!("Cannot wait for {what} input with cutter radius compensation on"),
                )?;
            }
            _ => {
                if e.is_none_or(|e| e < 0.0) {
                    return Err(
                        self.code_fault(code, format!("Invalid analog index with M{}", code.code))
                    );
                }
                let what = if code.code == 67 { "motion" } else { "auxiliary" };
                self.refuse_with_comp(
                    at,
                    &format!("Cannot set {what} analog output with cutter radius compensation on"),
                )?;
            }
        }
        self.record(&format!("M{}", code.code), true);
        Ok(())
    }

    /// M19: the spindle's orientation (an event; the spindle counts as stopped).
    pub(super) fn orient_spindle(&mut self) -> Result<(), Fault> {
        let word = |letter: u8| self.syntax.block.word(letter);
        if let Some(r) = word(b'r')
            && !(0.0..=360.0).contains(&r.value)
        {
            return Err(self.word_fault(r, "R value must be within 0..360 with M19"));
        }
        if let Some(p) = word(b'p')
            && !(0.0..=2.0).contains(&round(p.value))
        {
            return Err(self.word_fault(p, "P value must be 0,1,or 2 with M19"));
        }
        if let Some(q) = word(b'q')
            && q.value <= 0.0
        {
            return Err(self.word_fault(q, "Q word with M19 requires a value > 0"));
        }
        self.state.spindle = 5;
        self.record("M19", true);
        Ok(())
    }

    /// M48–M53: checked, with no effect here.
    pub(super) fn overrides(&self) -> Result<(), Fault> {
        let Some(code) = self.syntax.block.m[9] else { return Ok(()) };
        let message = if code.code == 49 {
            "Cannot disable overrides with cutter radius compensation on"
        } else {
            "Cannot enable overrides with cutter radius compensation on"
        };
        self.refuse_with_comp((code.at, code.end), message)
    }

    /// The P word of M19 and of G2/G3 must be an integer (`check_other_codes`).
    pub(super) fn m19_p_integer(&self, p: Word) -> Result<(), Fault> {
        if self.syntax.block.m[7].is_some_and(|code| code.code == 19)
            && (round(p.value) - p.value).abs() > 0.001
        {
            return Err(self.word_fault(p, "P value not an integer with M19 G2 or G3"));
        }
        Ok(())
    }
}
