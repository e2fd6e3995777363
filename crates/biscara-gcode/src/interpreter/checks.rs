//! The checks LinuxCNC makes of a block before executing it (`check_g_codes`,
//! `check_other_codes`, `check_items`), and the range of the values this robot accepts.

use super::*;

impl Machine {
    /// Refuses motions whose positions or feeds are beyond any robot (a typo such as a
    /// 240-digit number), rather than passing them on.
    pub(super) fn check_range(&self) -> Result<(), Fault> {
        let far = |value: &f64| value.abs() > MAX_COORDINATE;
        for motion in &self.output.queue {
            let value = match &motion.kind {
                MotionKind::Arc { end, center, .. } => end.iter().chain(center).copied().find(far),
                MotionKind::Rapid { end } | MotionKind::Linear { end, .. } => {
                    end.iter().copied().find(far)
                }
                kind => kind.end().and_then(|end| end.into_iter().find(far)),
            };
            if let Some(value) = value {
                let word = self.first_axis_word().map_or((0, 1), |word| (word.at, word.end));
                return Err(self.fault_at(
                    word.0,
                    word.1,
                    format!(
                        "{value:e} is out of range: positions must lie within ±{MAX_COORDINATE:e} \
                         mm (or degrees)"
                    ),
                ));
            }
        }
        Ok(())
    }

    pub(super) fn first_axis_word(&self) -> Option<Word> {
        AXES.iter()
            .filter_map(|&letter| self.syntax.block.word(letter))
            .chain(self.first_polar_word())
            .min_by_key(|word| word.at)
    }

    /// Where an error of the block's motion points: its G code, or else its first axis word
    /// (a modal motion), or else the line's start.
    pub(super) fn motion_span(&self) -> (usize, usize) {
        self.syntax.block.g[1].map_or_else(
            || self.first_axis_word().map_or((0, 1), |word| (word.at, word.end)),
            |code| (code.at, code.end),
        )
    }

    /// An error of the block's motion, at [`Machine::motion_span`].
    pub(super) fn motion_fault(&self, message: impl Into<String>) -> Fault {
        let (start, end) = self.motion_span();
        self.fault_at(start, end, message)
    }

    /// LinuxCNC's checks of G4 and G10 (in `check_g_codes`, before the other words').
    pub(super) fn check_group_zero(&self) -> Result<(), Fault> {
        let Some(zero) = self.syntax.block.g[0] else { return Ok(()) };
        let p = self.syntax.block.word(b'p');
        match zero.code {
            // P-1 is LinuxCNC's "no P" value.
            40 if p.is_none_or(|p| p.value == -1.0) => {
                Err(self.code_fault(zero, "Dwell time missing with g4"))
            }
            100 => {
                let l = self.syntax.block.word(b'l').map(|l| l.value as i64);
                let Some(l @ (0 | 1 | 2 | 10 | 11 | 20)) = l else {
                    return Err(self.code_fault(
                        zero,
                        "Line with G10 does not have L0, L1, L10, L11, L2, or L20",
                    ));
                };
                // (Grbl takes no P as P0: see `set_coordinate_data`.)
                let grbl_p0 = p.is_none() && self.hooks.rules.g10_p_optional;
                if matches!(l, 2 | 20)
                    && !grbl_p0
                    && !p.is_some_and(|p| (0.0..=9.0).contains(&p.value) && p.value.fract() == 0.0)
                {
                    return Err(
                        self.code_fault(zero, format!("P value out of range (0-9) with G10 L{l}"))
                    );
                }
                Ok(())
            }
            520 | 920 if AXES.iter().all(|&letter| self.syntax.block.word(letter).is_none()) => {
                Err(self.code_fault(zero, "All axes missing with g52 or g92"))
            }
            _ => Ok(()),
        }
    }

    /// Refuses codes and words this interpreter does not implement.
    pub(super) fn check_support(&self) -> Result<(), Fault> {
        if !self.syntax.block.unsupported {
            return Ok(());
        }
        for code in self.syntax.block.g.iter().flatten() {
            let name = || {
                if code.code % 10 == 0 {
                    format!("G{}", code.code / 10)
                } else {
                    format!("G{}.{}", code.code / 10, code.code % 10)
                }
            };
            // The span only for a refusal: this runs on every code of every line.
            match g_group(code.code) {
                Some((_, Support::No(note))) => {
                    let (first, last) = self.span(code.at, code.end);
                    return Err(Fault::not_supported(first, last, name(), note));
                }
                Some((_, Support::Cannot(reason))) => {
                    let (first, last) = self.span(code.at, code.end);
                    return Err(Fault::cannot(first, last, name(), reason));
                }
                _ => {}
            }
        }
        for code in self.syntax.block.m.iter().flatten() {
            if let Some((_, Support::No(note))) = m_group(code.code) {
                let (first, last) = self.span(code.at, code.end);
                return Err(Fault::not_supported(first, last, format!("M{}", code.code), note));
            }
        }
        Ok(())
    }

    /// LinuxCNC's checks of words no code in the block uses (`check_other_codes`, in its order:
    /// D E H I J K L P Q R).
    pub(super) fn check_other_words(&self, motion: Option<u16>) -> Result<(), Fault> {
        let block = &self.syntax.block;
        let group0 = block.g[0].map(|code| code.code);
        let arc = matches!(motion, Some(20 | 30));
        let g5 = motion == Some(50);
        let spline = g5 || motion == Some(51);
        let g10 = group0 == Some(100);
        let comp_on = block.g[7].is_some_and(|code| code.code != 400);
        let cycle = motion.is_some_and(canned::is_cycle);
        let g87 = motion == Some(870);
        if cycle && let Some(c) = block.word(b'c') {
            return Err(self.word_fault(c, "Cannot put a c in canned cycle"));
        }
        if block.extra.is_some() {
            // rs274 checks the `$` word between D and E.
            if let Some(d) = block.word(b'd')
                && !comp_on
            {
                return Err(self.word_fault(
                    d,
                    "D word with no G41, G41.1, G42, G42.1, G71, G71.1, G71.2 or G96 to use it",
                ));
            }
            self.check_dollar()?;
        }
        // The use of a word is looked at only when the block has it: this runs on every line.
        for letter in [b'd', b'e', b'h', b'i', b'j', b'k', b'l'] {
            let Some(word) = block.word(letter) else { continue };
            let (used, message) = match letter {
                b'd' => (
                    comp_on,
                    "D word with no G41, G41.1, G42, G42.1, G71, G71.1, G71.2 or G96 to use it",
                ),
                b'e' => (self.io_uses_e(), "E word with no G70, G76, M66, M67 or M68 to use it"),
                b'h' => (
                    block.g[8].is_some_and(|code| matches!(code.code, 430 | 432)),
                    "H word with no G43 or G76 to use it",
                ),
                b'i' => (
                    arc || spline || g10 || g87,
                    "I word with no G2, G3, G5, G5.1, G10, G33.1, G76, or G87 to use it",
                ),
                b'j' => (
                    arc || spline || g10 || g87,
                    "J word with no G2, G3, G5, G5.1, G10, G76 or G87 to use it",
                ),
                b'k' => (arc || g87, "K word with no G2, G3, G33, G33.1, G76, or G87 to use it"),
                _ => (
                    g10 || comp_on || cycle || self.io_uses_l(),
                    "L word with no G10, cutter compensation, canned cycle, digital/analog input, \
                     M98 or NURBS code",
                ),
            };
            if !used {
                return Err(self.word_fault(word, message));
            }
        }
        // Mach3 takes the compensation radius from a P word (G41 P1.5): G41/G42 use it.
        let mach3_radius = self.hooks.rules.comp_radius_in_p
            && block.g[7].is_some_and(|code| matches!(code.code, 410 | 420));
        if let Some(p) = block.word(b'p')
            && !mach3_radius
        {
            let g64 = block.g[13].is_some_and(|code| code.code == 640);
            let dwell_cycle = matches!(motion, Some(740 | 820 | 840 | 860 | 880 | 890));
            let user_m = block.m[10].is_some();
            let used = arc
                || g5
                || matches!(group0, Some(40 | 100))
                || g64
                || dwell_cycle
                || user_m
                || self.io_uses_p();
            if !used {
                return Err(self.word_fault(
                    p,
                    "P word with no G2 G3 G4 G10 G64 G5 G5.2 G76 G82 G86 G88 G89 or M50 M51 M52 \
                     M53 M62 M63 M64 M65 M66 M98 or user M code to use it",
                ));
            }
            // The turns of an arc, checked here with the block, before the arc's own checks.
            self.m19_p_integer(p)?;
            if arc && (round_to_int(p.value) - p.value).abs() > 0.001 {
                return Err(self.word_fault(p, "P value not an integer with M19 G2 or G3"));
            }
            if arc && round_to_int(p.value) < 1.0 {
                return Err(self.word_fault(p, "P value should be 1 or greater with G2 or G3"));
            }
        }
        if let Some(q) = block.word(b'q') {
            let g64 = block.g[13].is_some_and(|code| code.code == 640);
            let m61 = block.m[6].is_some_and(|code| code.code == 61);
            let peck = matches!(motion, Some(730 | 830));
            if !g5 && !g64 && !g10 && !m61 && !peck && block.m[10].is_none() && !self.io_uses_q() {
                return Err(self.word_fault(
                    q,
                    "Q word with no G5, G10, G64, G73, G76, G83, M19, M66, M67, M68 or user M code \
                     that uses it",
                ));
            }
        }
        let m19 = block.m[7].is_some_and(|code| code.code == 19);
        if let Some(r) = block.word(b'r')
            && !(arc || g10 || cycle || m19)
        {
            return Err(self.word_fault(r, "R word with no g code that uses it"));
        }
        Ok(())
    }
}
