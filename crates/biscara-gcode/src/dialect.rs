//! Dialects: the firmware a program was written for (docs/gcode.md), and what each reads
//! differently from LinuxCNC.
//!
//! The interpreter is LinuxCNC's; a dialect only adds hooks around it: lines it reads before
//! LinuxCNC's reader sees them (Grbl's `$` lines, Marlin's no-motion codes, Mach3's program
//! numbers), words it takes out of a block (Marlin's E) and rules it changes (program end,
//! line length, nested comments, Marlin's G4 and G28, Grbl's K in G17). [`Dialect::Linuxcnc`]
//! has no hook at all.

use biscara_motion::CodeName;
use std::collections::BTreeMap;
use std::fmt;
use std::str::FromStr;

/// The firmware whose reading of G-code the interpreter follows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Dialect {
    /// Decide from the program's content (see [`detect_dialect`]).
    Auto,
    /// LinuxCNC's RS274/NGC, exactly (docs/gcode.md): conformance with `rs274` holds here.
    Linuxcnc,
    /// Grbl 1.1 (also for LaserGRBL, LightBurn, LaserWeb, bCNC output).
    Grbl,
    /// Marlin and the RepRap family of printer firmware (slicer output).
    Marlin,
    /// MakerBot's flavour of printer G-code (Miracle-Grue, ReplicatorG, Sailfish): Marlin's
    /// reading, with the A word as the extruder (absolute, mm), as `auto` reads a program that
    /// names MakerBot.
    Makerbot,
    /// Mach3 (Fanuc-style posts: `O0001` program numbers, nested comments).
    Mach3,
    /// Fanuc and Haas controls (industrial posts): O-number programs, machine M-codes,
    /// look-ahead codes, G04 P in milliseconds, M97 local subprograms, K repeats, Macro B.
    Fanuc,
}

impl Dialect {
    /// Every dialect, `auto` first, as the command line lists them.
    pub const ALL: [Dialect; 7] = [
        Dialect::Auto,
        Dialect::Linuxcnc,
        Dialect::Grbl,
        Dialect::Marlin,
        Dialect::Makerbot,
        Dialect::Mach3,
        Dialect::Fanuc,
    ];

    /// The dialect's name on the command line (`linuxcnc`, `grbl`, …).
    pub fn name(self) -> &'static str {
        match self {
            Dialect::Auto => "auto",
            Dialect::Linuxcnc => "linuxcnc",
            Dialect::Grbl => "grbl",
            Dialect::Marlin => "marlin",
            Dialect::Makerbot => "makerbot",
            Dialect::Mach3 => "mach3",
            Dialect::Fanuc => "fanuc",
        }
    }
}

impl fmt::Display for Dialect {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A dialect name that is not one of [`Dialect::ALL`].
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error(
    "unknown dialect `{0}`: expected one of auto, linuxcnc, grbl, marlin, makerbot, mach3, fanuc"
)]
pub struct UnknownDialect(pub String);

impl FromStr for Dialect {
    type Err = UnknownDialect;

    fn from_str(text: &str) -> Result<Dialect, UnknownDialect> {
        Dialect::ALL
            .into_iter()
            .find(|dialect| dialect.name().eq_ignore_ascii_case(text.trim()))
            .ok_or_else(|| UnknownDialect(text.to_owned()))
    }
}

/// Which dialect `auto` chose, and why: a value for the caller to show (libraries never print).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Detection {
    /// The dialect chosen (never [`Dialect::Auto`]).
    pub dialect: Dialect,
    /// Why, in words: the evidence and where it is ("line 1: `;FLAVOR:Marlin` (Cura)").
    pub reason: String,
    /// The 1-based line of the evidence, when there is one.
    pub line: Option<usize>,
    /// MakerBot's flavour of printer G-code: the A word is the extruder (absolute, mm).
    pub makerbot: bool,
}

/// What a program did besides moving, for one note at the end: the no-motion codes it used
/// (each with how many times), as the dialect accepted them.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Summary {
    /// Codes the dialect knows and that have no motion here (`M104`, `G29`, `$H`, `O0001`), with
    /// their counts, in code order.
    pub codes: BTreeMap<String, usize>,
    /// Codes the firmware does not know and skips (Marlin answers "Unknown command" and goes
    /// on), with their counts.
    pub unknown: BTreeMap<String, usize>,
    /// What the firmware itself would refuse and this interpreter reads as LinuxCNC does
    /// (Grbl 1.1's unsupported commands: canned cycles, G41/G42, M6, O-words, parameters, …),
    /// with their counts: the program runs here, not on that machine.
    pub refused_by_firmware: BTreeMap<String, usize>,
    /// Probe moves (G38.2–G38.5), with their counts: run as LinuxCNC's `rs274` simulates them,
    /// with no probe that trips.
    pub probes: BTreeMap<String, usize>,
    /// What LinuxCNC refuses and the dialect's firmware runs, read as that firmware runs it
    /// (Mach3's bare axis words after G80, its G53 without a move), with their counts.
    pub adapted: BTreeMap<String, usize>,
}

impl Summary {
    /// Whether nothing was recorded.
    pub fn is_empty(&self) -> bool {
        self.codes.is_empty()
            && self.unknown.is_empty()
            && self.refused_by_firmware.is_empty()
            && self.probes.is_empty()
            && self.adapted.is_empty()
    }

    /// Counts one use of `what`, read as the dialect's firmware runs it.
    pub(crate) fn count_adapted(&mut self, what: &str) {
        bump(&mut self.adapted, what);
    }

    /// Counts one probe move `code` (`G38.2`).
    pub(crate) fn count_probe(&mut self, code: &str) {
        bump(&mut self.probes, code);
    }

    /// Counts one use of `what`, which the firmware would refuse.
    pub(crate) fn count_refused(&mut self, what: &str) {
        bump(&mut self.refused_by_firmware, what);
    }

    pub(crate) fn count(&mut self, code: &str, known: bool) {
        bump(if known { &mut self.codes } else { &mut self.unknown }, code);
    }
}

/// One more `key` in `counts` (the key allocated only the first time).
fn bump(counts: &mut BTreeMap<String, usize>, key: &str) {
    match counts.get_mut(key) {
        Some(count) => *count += 1,
        None => {
            counts.insert(key.to_owned(), 1);
        }
    }
}

/// How many bytes `auto` reads ahead for evidence before the first line is interpreted.
pub const LOOKAHEAD_BYTES: usize = 64 * 1024;

/// The longest line the dialects other than LinuxCNC accept (a thumbnail or a long comment),
/// bytes; LinuxCNC's own limit is 252 characters.
pub const MAX_LONG_LINE: usize = 65_535;

/// Decides the dialect of a program from its first bytes (`auto`): the first generator comment
/// that names a firmware or a program written for one wins; otherwise the first line only one
/// dialect can read (E words or printer M-codes → Marlin, `$` lines or K in an XY arc → Grbl,
/// nested comments, an `O0001` program number or G41/G42 with a P word → Mach3, LinuxCNC's O-words
/// or named parameters → LinuxCNC). Only complete lines are looked at (all of them when `complete`
/// says the text is the whole program). `None` when nothing decides.
// Run once per program: kept out of the interpreter's line loop.
#[inline(never)]
pub fn detect_dialect(text: &[u8], complete: bool) -> Option<Detection> {
    let text = text.strip_prefix(crate::syntax::lexer::UTF8_BOM).unwrap_or(text);
    let end = if complete {
        text.len()
    } else {
        text.iter().rposition(|&byte| byte == b'\n').map_or(0, |index| index + 1)
    };
    // Whether a comment names a MakerBot program, so far (the lines after a deciding generator
    // comment are searched then).
    let mut makerbot = false;
    let mut parts = LineParts::default();
    let mut content: Option<Detection> = None;
    // The first evidence that is not a printer M-code, and the first line that continues a
    // motion with no G word (which a CNC post writes and Marlin does not read).
    let mut other: Option<Detection> = None;
    let mut modal: Option<(usize, String)> = None;
    let mut plane_xy = true;
    let (mut fanuc, mut machine_m): (Option<Detection>, Option<Detection>) = (None, None);
    let mut long_comment: Option<(usize, usize)> = None;
    // What only Mach3 (and Fanuc) read, and whether a G80 ended a plain motion mode.
    let (mut mach3, mut after_g80): (Option<Detection>, Option<bool>) = (None, None);
    for (index, raw) in text[..end].split(|&byte| byte == b'\n').enumerate() {
        let line = index + 1;
        let raw = raw.strip_suffix(b"\r").unwrap_or(raw);
        parts.split(raw);
        let (code, comment, squeezed) = (&parts.code[..], &parts.comment[..], &parts.squeezed[..]);
        makerbot = makerbot || names_any(comment, MAKERBOT_NAMES);
        if let Some((dialect, name)) = generator(comment) {
            let shown = String::from_utf8_lossy(raw.trim_ascii());
            let makerbot = dialect == Dialect::Marlin
                && (makerbot || names_any_line(&text[..end], MAKERBOT_NAMES, &mut parts));
            return Some(Detection {
                dialect,
                reason: format!("line {line} names {name}: `{}`", shorten(&shown)),
                line: Some(line),
                makerbot,
            });
        }
        // Content evidence comes from text lines only (binary garbage proves nothing).
        if !is_text(raw, false) {
            continue;
        }
        if modal.is_none() && continues_motion(code) {
            modal = Some((line, shorten(&String::from_utf8_lossy(raw.trim_ascii()))));
        }
        let located = |why: &str| Detection {
            dialect: Dialect::Fanuc,
            reason: format!(
                "line {line}: {why}: `{}`",
                shorten(&String::from_utf8_lossy(raw.trim_ascii()))
            ),
            line: Some(line),
            makerbot: false,
        };
        if fanuc.is_none()
            && let Some(why) = fanuc_evidence(squeezed)
        {
            fanuc = Some(located(why));
        }
        if let Some(why) = mach3_only(squeezed, code, &mut after_g80)
            && mach3.is_none()
        {
            mach3 = Some(Detection { dialect: Dialect::Mach3, ..located(why) });
        }
        if machine_m.is_none() && has_machine_m(squeezed) {
            machine_m = Some(located("a machine M-code only Fanuc and Haas controls have"));
        }
        if long_comment.is_none() && long_only_in_comment(raw) {
            long_comment = Some((line, raw.len()));
        }
        if content.is_none() || other.is_none() {
            // `makerbot` is settled after the last line.
            let found =
                evidence(raw, code, squeezed, &mut plane_xy).map(|(dialect, why)| Detection {
                    dialect,
                    reason: format!(
                        "line {line}: {why}: `{}`",
                        shorten(&String::from_utf8_lossy(raw.trim_ascii()))
                    ),
                    line: Some(line),
                    makerbot: false,
                });
            if let Some(found) = found {
                let printer = found.reason.contains(PRINTER_M_CODE);
                if other.is_none() && !printer {
                    other = Some(found.clone());
                }
                if content.is_none() {
                    content = Some(found);
                }
            }
        }
    }
    // A MakerBot name anywhere in the comments makes Marlin's evidence MakerBot's.
    for found in [&mut content, &mut other].into_iter().flatten() {
        found.makerbot = makerbot && found.dialect == Dialect::Marlin;
    }
    // Fanuc's and Haas's own codes (look-ahead, M97, Macro B) outweigh an `O` program number
    // (Mach3's too) and numbered parameters (LinuxCNC's too).
    if let Some(found) = fanuc {
        return Some(found);
    }
    // What LinuxCNC refuses and Mach3 reads outweighs what both read, and a printer M-code
    // (a CNC post's controller code: no printer writes G80 or G53).
    let printer_only = content.as_ref().is_some_and(|found| found.reason.contains(PRINTER_M_CODE));
    if let Some(found) = mach3.filter(|_| mach3_reads_too(content.as_ref()) || printer_only) {
        return Some(found);
    }
    // A machine M-code no other dialect has (Haas's M31 chip conveyor) says Fanuc where
    // nothing else does, or where only an `O` program number does.
    let only_program_number =
        content.as_ref().is_some_and(|found| found.reason.contains(PROGRAM_NUMBER));
    if let Some(found) = machine_m.filter(|_| content.is_none() || only_program_number) {
        return Some(found);
    }
    // A line longer than LinuxCNC's limit only in its comment: Grbl drops comments before its
    // line buffer (and Marlin, Mach3 read such lines too), LinuxCNC refuses the line.
    if let (None, Some((line, length))) = (&content, long_comment) {
        return Some(Detection {
            dialect: Dialect::Grbl,
            reason: format!(
                "line {line} is {length} characters long, longer than LinuxCNC's {} only in its \
                 comment, which Grbl drops before its line buffer (nothing else tells the \
                 dialects apart)",
                crate::syntax::lexer::MAX_LINE
            ),
            line: Some(line),
            makerbot: false,
        });
    }
    // A printer M-code (M400, M851 …) in a program whose motions go on without G words is a
    // CNC post's controller code, not Marlin's (Marlin would skip those lines): the other
    // evidence decides, else LinuxCNC's language, which says what it does not know.
    match (content, modal) {
        (Some(found), Some((line, shown))) if found.reason.contains(PRINTER_M_CODE) => {
            Some(other.unwrap_or_else(|| Detection {
                dialect: Dialect::Linuxcnc,
                reason: format!(
                    "{}, but line {line} goes on moving with no G word, which Marlin does not \
                     read: `{shown}`",
                    found.reason
                ),
                line: found.line,
                makerbot: false,
            }))
        }
        (content, _) => content,
    }
}

/// Whether a line is longer than LinuxCNC's limit only by its comment: text, with at most that
/// many characters outside comments (and not counting blanks), which Grbl, Marlin and Mach3
/// read and LinuxCNC refuses.
pub(crate) fn long_only_in_comment(raw: &[u8]) -> bool {
    if raw.len() <= crate::syntax::lexer::MAX_LINE {
        return false;
    }
    if !is_text(raw, true) {
        return false;
    }
    let mut parts = LineParts::default();
    parts.split(raw);
    !parts.comment.is_empty() && parts.squeezed.len() <= crate::syntax::lexer::MAX_LINE
}

/// Whether a line is text: valid UTF-8 with no control character but tabs (and carriage
/// returns, when `return_too`).
fn is_text(raw: &[u8], return_too: bool) -> bool {
    // Printable ASCII and tabs, the common case, without decoding.
    let plain = |b: u8| (b' '..=b'~').contains(&b) | (b == b'\t') | (return_too & (b == b'\r'));
    raw.iter().fold(true, |all, &b| all & plain(b))
        || std::str::from_utf8(raw).is_ok_and(|text| {
            text.chars().all(|c| !c.is_control() || c == '\t' || (return_too && c == '\r'))
        })
}

/// The evidence an expression or a numbered parameter gives: LinuxCNC's language, and Mach3's
/// too (which says so by other signs).
const LINUXCNC_EXPRESSION: &str = "a LinuxCNC expression or numbered parameter";

/// Whether `found` says LinuxCNC only by what Mach3 reads too (an expression or a numbered
/// parameter), or says nothing.
fn mach3_reads_too(found: Option<&Detection>) -> bool {
    found.is_none_or(|found| found.reason.contains(LINUXCNC_EXPRESSION))
}

/// The file's extension as evidence, weighed after the content ([`detect_dialect`]): `.tap` is
/// Mach3's own extension, so a `.tap` program in which nothing tells the dialects apart, or
/// only what Mach3 reads too (or a printer M-code, which a Mach3 user macro looks like), is
/// read as Mach3's. `file` is the program's name.
pub(crate) fn weigh_extension(
    found: Option<Detection>,
    file: Option<&std::path::Path>,
) -> Option<Detection> {
    let tap = file
        .and_then(std::path::Path::extension)
        .is_some_and(|extension| extension.eq_ignore_ascii_case("tap"));
    // A printer M-code alone in a `.tap` file is a CNC post's controller code (Mach3's user
    // macros are M-codes above 199, as many of Marlin's are).
    let printer_only = found.as_ref().is_some_and(|found| found.reason.contains(PRINTER_M_CODE));
    if !tap || !(mach3_reads_too(found.as_ref()) || printer_only) {
        return found;
    }
    let but = found
        .map_or_else(String::new, |found| format!(" ({}, which Mach3 reads too)", found.reason));
    Some(Detection {
        dialect: Dialect::Mach3,
        reason: format!(
            "the file's extension `.tap` is Mach3's, and nothing in it says another dialect{but}"
        ),
        line: None,
        makerbot: false,
    })
}

/// What LinuxCNC refuses and Mach3 reads, on a line (`squeezed`: lower case, outside comments,
/// without blanks), given whether a G80 ended the last motion mode after a G0–G3 (`after_g80`,
/// kept from line to line): bare axis words after G80 (Mach3 runs them in the motion from
/// before the cycle), G53 with no axis word (a Mach3 post's `G53 G90 G40`: no move).
fn mach3_only(squeezed: &[u8], code: &[u8], after_g80: &mut Option<bool>) -> Option<&'static str> {
    let mut g53 = false;
    let mut g_codes = false;
    for (at, &byte) in squeezed.iter().enumerate() {
        if byte != b'g' || (at > 0 && squeezed[at - 1].is_ascii_alphabetic()) {
            continue;
        }
        g_codes = true;
        match number_after(squeezed, at) {
            // `G0`–`G3` (not G2.5…): a plain motion mode, from now on.
            Some(0..=3) => *after_g80 = Some(false),
            Some(73 | 76 | 81..=89) if *after_g80 == Some(true) => *after_g80 = Some(false),
            Some(80) if after_g80.is_some() => *after_g80 = Some(true),
            Some(53) => g53 = true,
            _ => {}
        }
    }
    let axis_word = squeezed.iter().enumerate().any(|(at, &byte)| {
        matches!(byte, b'x' | b'y' | b'z' | b'a' | b'b' | b'c')
            && (at == 0 || !squeezed[at - 1].is_ascii_alphabetic())
    });
    if g53 && !axis_word {
        return Some("G53 with no axis word, which LinuxCNC refuses and Mach3 reads as no move");
    }
    if !g_codes && *after_g80 == Some(true) && continues_motion(code) {
        return Some(
            "axis words with no motion G-code after G80, which LinuxCNC refuses and Mach3 runs \
             in the motion from before the cycle",
        );
    }
    None
}

/// A lathe program's evidence ([`lathe_evidence`]).
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Lathe {
    /// The 1-based line of the evidence.
    pub(crate) line: usize,
    /// What it is.
    pub(crate) why: String,
    /// The line's text.
    pub(crate) text: String,
}

/// The first sign that a program turns a part on a lathe, with its line, in its first bytes
/// (`complete`: the whole program): the XZ plane (G18, or LinuxCNC's G7 diameter mode) with,
/// from then on, threading (G32, G33, G76), feed per revolution (G99 in the XZ plane: Fanuc's
/// lathe G-code), a turret tool number (`T0101`: tool and offset), or a diameter or Z
/// increment word (U, W). A mill never writes these; a printer M-code in the same program
/// (Haas's M17 turret rotation) is outweighed.
pub(crate) fn lathe_evidence(text: &[u8], complete: bool) -> Option<Lathe> {
    let text = text.strip_prefix(crate::syntax::lexer::UTF8_BOM).unwrap_or(text);
    let end = if complete {
        text.len()
    } else {
        text.iter().rposition(|&byte| byte == b'\n').map_or(0, |index| index + 1)
    };
    let mut parts = LineParts::default();
    let mut turning_plane: Option<usize> = None;
    let mut xz = false;
    for (index, raw) in text[..end].split(|&byte| byte == b'\n').enumerate() {
        let line = index + 1;
        parts.split(raw.strip_suffix(b"\r").unwrap_or(raw));
        let squeezed = &parts.squeezed[..];
        let mut why = None;
        for (at, &byte) in squeezed.iter().enumerate() {
            if at > 0 && squeezed[at - 1].is_ascii_alphabetic() {
                continue;
            }
            let number = number_after(squeezed, at);
            let fraction = squeezed.get(at + 1..).is_some_and(|rest| {
                let digits = rest.iter().take_while(|b| b.is_ascii_digit()).count();
                rest.get(digits) == Some(&b'.')
            });
            match (byte, number) {
                (b'g', Some(7 | 18)) if !fraction => {
                    xz = true;
                    turning_plane = turning_plane.or(Some(line));
                }
                (b'g', Some(17 | 19)) if !fraction => xz = false,
                (b'g', Some(32)) if !fraction => why = why.or(Some("G32 threading")),
                (b'g', Some(33)) if !fraction => why = why.or(Some("G33 threading")),
                (b'g', Some(76)) if !fraction => why = why.or(Some("a G76 threading cycle")),
                (b'g', Some(99)) if xz => why = why.or(Some("G99 feed per revolution")),
                (b't', Some(_)) => {
                    let digits = squeezed[at + 1..].iter().take_while(|b| b.is_ascii_digit());
                    if digits.count() == 4 && !contains(squeezed, "m6") {
                        why = why.or(Some("a turret tool number (tool and offset, `T0101`)"));
                    }
                }
                (b'u' | b'w', _)
                    if squeezed.get(at + 1).is_some_and(|b| {
                        b.is_ascii_digit() || matches!(*b, b'-' | b'+' | b'.')
                    }) =>
                {
                    why = why.or(Some("a U or W word (a lathe's diameter or Z increment)"));
                }
                _ => {}
            }
        }
        if let (Some(why), Some(plane)) = (why, turning_plane) {
            let raw = raw.strip_suffix(b"\r").unwrap_or(raw);
            return Some(Lathe {
                line,
                why: format!("{why} after the lathe's XZ plane (G18, line {plane})"),
                text: String::from_utf8_lossy(raw).into_owned(),
            });
        }
    }
    None
}

/// The evidence an `O0001` line gives (Mach3's, and Fanuc's).
const PROGRAM_NUMBER: &str = "an `O` program number";

/// What only Fanuc and Haas controls read, on a line (`squeezed`: lower case, outside comments,
/// without blanks): their look-ahead and smoothing codes, Haas's M97, Macro B's control flow.
fn fanuc_evidence(squeezed: &[u8]) -> Option<&'static str> {
    let first = {
        let mut at = 0;
        if squeezed.first() == Some(&b'n') {
            at = 1 + squeezed[1..].iter().take_while(|b| b.is_ascii_digit()).count();
        }
        &squeezed[at..]
    };
    let keyword = |word: &[u8]| {
        first.starts_with(word)
            && first.get(word.len()).is_some_and(|b| *b == b'[' || b.is_ascii_digit())
    };
    if keyword(b"if") || keyword(b"while") || keyword(b"goto") || keyword(b"end") || keyword(b"do")
    {
        return Some("Macro B control flow (IF, WHILE … DO, GOTO, END)");
    }
    for (at, &byte) in squeezed.iter().enumerate() {
        if !matches!(byte, b'g' | b'm') || (at > 0 && squeezed[at - 1].is_ascii_alphabetic()) {
            continue;
        }
        match (byte, number_after(squeezed, at)) {
            (b'g', Some(187)) => return Some("Haas's G187 (smoothness)"),
            (b'g', Some(103)) => return Some("Haas's G103 (look-ahead)"),
            (b'g', Some(8)) if contains(squeezed, "p") && !contains(squeezed, "g8.") => {
                return Some("Fanuc's G08 P (advanced preview control)");
            }
            (b'g', Some(5)) if contains(squeezed, "g5.1q") || contains(squeezed, "g05.1q") => {
                return Some("Fanuc's G05.1 Q (AI contour control)");
            }
            (b'm', Some(97)) => return Some("Haas's M97 (local subprogram)"),
            _ => {}
        }
    }
    None
}

/// Whether a line (`squeezed`: lower case, outside comments, without blanks) has an M-code that
/// only Fanuc and Haas controls have among the dialects (none of LinuxCNC's, Mach3's or a
/// printer's).
fn has_machine_m(squeezed: &[u8]) -> bool {
    squeezed.iter().enumerate().any(|(at, &byte)| {
        byte == b'm'
            && (at == 0 || !squeezed[at - 1].is_ascii_alphabetic())
            && number_after(squeezed, at).is_some_and(|number| {
                (10..100).contains(&number)
                    && !matches!(number, 10 | 11 | 19 | 30 | 40 | 41 | 47..=53 | 60..=73 | 98 | 99)
                    && !printer_m_code(number)
            })
    })
}

/// A whole program (`text`, all of it, text only) with an X, Y or Z word and no program end: no M2, M30 or M99
/// and no `%` line. LinuxCNC refuses it at its end and Grbl runs it, so `auto`, which found no
/// other evidence, can take it for Grbl's before its first line rather than at its end (where
/// the lines before were read as LinuxCNC reads them: a G0 with the laser on burns, where
/// Grbl's laser mode turns it off). `Some(number of lines)` when so.
pub(crate) fn open_ended(text: &[u8]) -> Option<usize> {
    let text = text.strip_prefix(crate::syntax::lexer::UTF8_BOM).unwrap_or(text);
    let mut parts = LineParts::default();
    let (mut lines, mut moves) = (0, false);
    for raw in text.split(|&byte| byte == b'\n') {
        lines += 1;
        let raw = raw.strip_suffix(b"\r").unwrap_or(raw);
        // Binary garbage is no program of any dialect's.
        if !is_text(raw, false) {
            return None;
        }
        parts.split(raw);
        let squeezed = &parts.squeezed[..];
        if squeezed.first() == Some(&b'%') {
            return None;
        }
        for (at, &byte) in squeezed.iter().enumerate() {
            if at > 0 && squeezed[at - 1].is_ascii_alphabetic() {
                continue;
            }
            match byte {
                b'm' if matches!(number_after(squeezed, at), Some(2 | 30 | 99)) => return None,
                b'x' | b'y' | b'z' => {
                    let value = squeezed.get(at + 1);
                    moves |= value
                        .is_some_and(|b| b.is_ascii_digit() || matches!(*b, b'-' | b'+' | b'.'));
                }
                _ => {}
            }
        }
    }
    // The empty piece after a final line ending is no line.
    let lines = if text.ends_with(b"\n") { lines - 1 } else { lines };
    moves.then_some(lines)
}

/// The evidence a printer firmware M-code gives (for Marlin).
const PRINTER_M_CODE: &str = "a printer firmware M-code";

/// A line (lower case, outside comments) that begins with an X, Y or Z word after an optional
/// N number: a motion in the modal G0/G1/G2/G3 of an earlier line.
fn continues_motion(code: &[u8]) -> bool {
    let mut rest = code.trim_ascii();
    if rest.first() == Some(&b'n') {
        let digits = rest[1..].iter().take_while(|b| b.is_ascii_digit()).count();
        rest = rest[1 + digits..].trim_ascii_start();
    }
    matches!(rest.first(), Some(b'x' | b'y' | b'z'))
        && rest[1..]
            .iter()
            .find(|b| **b != b' ')
            .is_some_and(|b| b.is_ascii_digit() || matches!(*b, b'-' | b'+' | b'.'))
}

const MAKERBOT_NAMES: &[&str] = &["makerbot", "replicatorg", "miracle-grue", "sailfish"];

/// Generator names (lower case) and the dialect their output is written for.
const GENERATORS: &[(&str, Dialect, &str)] = &[
    ("flavor:marlin", Dialect::Marlin, "Cura's Marlin flavour"),
    ("flavor:reprap", Dialect::Marlin, "Cura's RepRap flavour"),
    ("flavor:griffin", Dialect::Marlin, "Cura's Griffin (Ultimaker) flavour"),
    ("flavor:ultigcode", Dialect::Marlin, "Cura's UltiGCode flavour"),
    ("cura_steamengine", Dialect::Marlin, "the Cura slicer"),
    ("cura_profile_string", Dialect::Marlin, "the Cura slicer"),
    ("prusaslicer", Dialect::Marlin, "the PrusaSlicer slicer"),
    ("superslicer", Dialect::Marlin, "the SuperSlicer slicer"),
    ("slic3r", Dialect::Marlin, "the Slic3r slicer"),
    ("bambustudio", Dialect::Marlin, "the BambuStudio slicer"),
    ("orcaslicer", Dialect::Marlin, "the OrcaSlicer slicer"),
    ("kisslicer", Dialect::Marlin, "the KISSlicer slicer"),
    ("simplify3d", Dialect::Marlin, "the Simplify3D slicer"),
    ("skeinforge", Dialect::Marlin, "the Skeinforge slicer"),
    ("miracle-grue", Dialect::Marlin, "the Miracle-Grue slicer (MakerBot)"),
    ("makerbot", Dialect::Marlin, "MakerBot"),
    ("ideamaker", Dialect::Marlin, "the ideaMaker slicer"),
    ("marlin", Dialect::Marlin, "Marlin"),
    ("lasergrbl", Dialect::Grbl, "LaserGRBL"),
    ("lightburn", Dialect::Grbl, "LightBurn"),
    ("laserweb", Dialect::Grbl, "LaserWeb"),
    ("grbl", Dialect::Grbl, "Grbl"),
    ("bcnc", Dialect::Grbl, "bCNC"),
    ("mr beam", Dialect::Grbl, "Mr Beam (Grbl)"),
    ("mrbeam", Dialect::Grbl, "Mr Beam (Grbl)"),
    ("carbide create", Dialect::Grbl, "Carbide Create (Grbl)"),
    ("inkburn", Dialect::Grbl, "InkBurn (Grbl)"),
    ("klipper", Dialect::Marlin, "Klipper"),
    ("lulzbot", Dialect::Marlin, "LulzBot's Cura"),
    ("haas", Dialect::Fanuc, "Haas"),
    ("fanuc", Dialect::Fanuc, "Fanuc"),
    ("mach3", Dialect::Mach3, "Mach3"),
    ("mach4", Dialect::Mach3, "Mach4"),
    ("linuxcnc", Dialect::Linuxcnc, "LinuxCNC"),
    ("emc2", Dialect::Linuxcnc, "EMC2 (LinuxCNC)"),
];

/// Whether `needle` (not empty) is in `haystack`, ignoring ASCII case.
fn contains(haystack: &[u8], needle: &str) -> bool {
    let needle = needle.as_bytes();
    let Some((first, rest)) = needle.split_first() else { return true };
    let Some(last_start) = haystack.len().checked_sub(needle.len()) else { return false };
    haystack[..=last_start].iter().enumerate().any(|(at, byte)| {
        byte.eq_ignore_ascii_case(first)
            && haystack[at + 1..at + needle.len()].eq_ignore_ascii_case(rest)
    })
}

/// Whether a comment's text names any of `needles`.
fn names_any(comment: &[u8], needles: &[&str]) -> bool {
    !comment.is_empty() && needles.iter().any(|needle| contains(comment, needle))
}

/// Whether a comment on any line of `text` names any of `needles` (`parts` is scratch space).
fn names_any_line(text: &[u8], needles: &[&str], parts: &mut LineParts) -> bool {
    text.split(|&byte| byte == b'\n').any(|line| {
        parts.split(line);
        names_any(&parts.comment, needles)
    })
}

fn generator(comment: &[u8]) -> Option<(Dialect, &'static str)> {
    if comment.is_empty() {
        return None;
    }
    GENERATORS
        .iter()
        .find(|(needle, _, _)| contains(comment, needle))
        .map(|&(_, dialect, name)| (dialect, name))
}

fn shorten(text: &str) -> String {
    const SHOWN: usize = 60;
    if text.chars().count() <= SHOWN {
        text.to_owned()
    } else {
        format!("{}…", text.chars().take(SHOWN).collect::<String>())
    }
}

/// One line split into its parts, lower case, in buffers reused from line to line.
#[derive(Debug, Default)]
struct LineParts {
    /// The text outside comments.
    code: Vec<u8>,
    /// The comments' text: each parenthesised comment's text with its closing parenthesis (and
    /// the nested ones), then what follows a `;`.
    comment: Vec<u8>,
    /// [`Self::code`] without its blanks (ASCII whitespace).
    squeezed: Vec<u8>,
}

impl LineParts {
    /// Splits `raw` (one line) into the buffers.
    fn split(&mut self, raw: &[u8]) {
        self.code.clear();
        self.comment.clear();
        let mut rest = raw;
        while let Some(at) = rest.iter().position(|&b| b == b'(' || b == b';') {
            self.code.extend_from_slice(&rest[..at]);
            if rest[at] == b';' {
                self.comment.extend_from_slice(&rest[at + 1..]);
                rest = &[];
                break;
            }
            // A parenthesised comment: its text up to the parenthesis that closes it, with it.
            let inner = &rest[at + 1..];
            let mut depth = 1usize;
            let end = inner
                .iter()
                .position(|&b| {
                    match b {
                        b'(' => depth += 1,
                        b')' => depth -= 1,
                        _ => {}
                    }
                    depth == 0
                })
                .map_or(inner.len(), |close| close + 1);
            self.comment.extend_from_slice(&inner[..end]);
            rest = &inner[end..];
        }
        self.code.extend_from_slice(rest);
        self.code.make_ascii_lowercase();
        self.comment.make_ascii_lowercase();
        self.squeezed.clear();
        self.squeezed.resize(self.code.len(), 0);
        let mut kept = 0;
        for &byte in &self.code {
            self.squeezed[kept] = byte;
            kept += usize::from(!byte.is_ascii_whitespace());
        }
        self.squeezed.truncate(kept);
    }
}

/// M-codes no LinuxCNC program uses and Marlin (or another printer firmware) does: evidence
/// for Marlin.
fn printer_m_code(code: u32) -> bool {
    // Not M100–M199 in general: those are LinuxCNC's user M-codes too. Below 100, Marlin's pin,
    // print-job, power and steps-per-unit codes, which LinuxCNC, Grbl and Mach3 lack.
    matches!(
        code,
        17 | 18 | 42 | 43 | 75..=78 | 80 | 81 | 82 | 83 | 84 | 92 | 104..=107 | 109 | 117 | 140
            | 141 | 190 | 191 | 200..
    )
}

/// The number after a letter at `at` in `code` (digits only, after any spaces; `None` when
/// there are none or the number overflows).
fn number_after(code: &[u8], at: usize) -> Option<u32> {
    let rest = &code[at + 1..];
    let start = rest.iter().position(|&b| b != b' ').unwrap_or(rest.len());
    let digits = rest[start..].iter().take_while(|b| b.is_ascii_digit());
    let mut value: Option<u32> = None;
    for digit in digits {
        value = Some(value.unwrap_or(0).checked_mul(10)?.checked_add(u32::from(digit - b'0'))?);
    }
    value
}

/// Content that only one dialect reads, on one line: `code` is the lower-case text outside
/// comments, `squeezed` the same without its blanks.
fn evidence(
    raw: &[u8],
    code: &[u8],
    squeezed: &[u8],
    plane_xy: &mut bool,
) -> Option<(Dialect, &'static str)> {
    let trimmed = code.trim_ascii();
    if trimmed.first() == Some(&b'$') {
        return Some((Dialect::Grbl, "a Grbl `$` system line"));
    }
    let mut raw_depth = 0usize;
    for &byte in raw {
        match byte {
            b'(' if raw_depth > 0 => return Some((Dialect::Mach3, "a nested comment")),
            b'(' => raw_depth = 1,
            b')' => raw_depth = raw_depth.saturating_sub(1),
            b';' if raw_depth == 0 => break,
            _ => {}
        }
    }
    if squeezed.first() == Some(&b'o') {
        if squeezed.len() > 1 && squeezed[1..].iter().all(u8::is_ascii_digit) {
            return Some((Dialect::Mach3, PROGRAM_NUMBER));
        }
        return Some((Dialect::Linuxcnc, "a LinuxCNC O-word"));
    }
    if contains(squeezed, "#<") {
        return Some((Dialect::Linuxcnc, "a LinuxCNC named parameter"));
    }
    // An E word stands after a space or at the start (`X1E2` could be a number's exponent).
    let e_word = code.iter().enumerate().any(|(at, &byte)| {
        byte == b'e'
            && (at == 0 || code[at - 1] == b' ' || code[at - 1] == b'\t')
            && code.get(at + 1).is_some_and(|b| b.is_ascii_digit() || matches!(*b, b'-' | b'.'))
    });
    let mut motion_arc = false;
    let mut k_word = false;
    let mut g_motion = false;
    let mut compensation = false;
    let mut p_word = false;
    for (at, &byte) in squeezed.iter().enumerate() {
        let previous = if at == 0 { b' ' } else { squeezed[at - 1] };
        if previous.is_ascii_alphabetic() {
            continue;
        }
        match byte {
            b'm' => {
                if let Some(number) = number_after(squeezed, at)
                    && printer_m_code(number)
                {
                    return Some((Dialect::Marlin, PRINTER_M_CODE));
                }
            }
            b'g' => match number_after(squeezed, at) {
                Some(0 | 1) => g_motion = true,
                Some(2 | 3) => {
                    g_motion = true;
                    motion_arc = true;
                }
                Some(17) => *plane_xy = true,
                Some(18 | 19) => *plane_xy = false,
                Some(29) => return Some((Dialect::Marlin, "Marlin's G29 (bed levelling)")),
                Some(92) => g_motion = true,
                // G41/G42, not G41.1/G42.1 (whose D is a diameter).
                Some(41 | 42) => {
                    let digits = squeezed[at + 1..].iter().take_while(|b| b.is_ascii_digit());
                    compensation = squeezed.get(at + 1 + digits.count()) != Some(&b'.');
                }
                _ => {}
            },
            b'k' => k_word = true,
            b'p' => p_word = true,
            _ => {}
        }
    }
    if e_word && g_motion {
        return Some((Dialect::Marlin, "an E (extruder) word"));
    }
    // Letters next to letters are no G-code words: a line of text or base64 (a thumbnail a
    // program embeds without a comment marker) is no evidence of a G41 P or an XY K word.
    let words = !squeezed.windows(2).any(|pair| pair.iter().all(u8::is_ascii_alphabetic));
    if compensation && p_word && words {
        return Some((Dialect::Mach3, "Mach3's compensation radius in a G41/G42 P word"));
    }
    if k_word && motion_arc && *plane_xy && words {
        return Some((Dialect::Grbl, "a K word in an XY-plane arc (Grbl ignores it)"));
    }
    // A word whose value is an expression (`F[150*60]`) or a numbered parameter (`#1=10`,
    // `X#1`): LinuxCNC's language (Mach3's too, which says so by other signs); Grbl and Marlin
    // read neither, so a program using them is not called Grbl for lacking an M2.
    let expression =
        squeezed.windows(2).any(|pair| pair[0].is_ascii_alphabetic() && pair[1] == b'[');
    let parameter = squeezed.windows(2).any(|pair| pair[0] == b'#' && pair[1].is_ascii_digit());
    if expression || parameter {
        return Some((Dialect::Linuxcnc, LINUXCNC_EXPRESSION));
    }
    None
}

/// What a dialect makes of a line before LinuxCNC's reader sees it.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Prelude {
    /// An ordinary block: LinuxCNC's reader reads it (with the dialect's hooks).
    Block,
    /// A code with no motion: recorded as an event and counted; `known` is whether the
    /// firmware knows it (Marlin skips a code it does not know, with "Unknown command").
    Event { name: String, known: bool },
    /// Marlin's M82 (E absolute) or M83 (E relative), also recorded as an event.
    ExtruderMode { name: String, relative: bool },
    /// Marlin's G28: home the named axes (`[x, y, z, c]`), all of them when none is named; the
    /// values after the letters do not matter (`G28 X0 Y0` and `G28 X Y` are the same).
    Home { axes: [bool; 4] },
    /// A code the dialect has but this robot cannot do: refused (`start..end` in the line).
    Refuse { start: usize, end: usize, code: String, note: &'static str },
}

/// Reads the line's first command (after spaces and an N number): its letter (upper case), its
/// number as written (`29`, `862.3`), and the byte range it covers.
fn first_command(raw: &[u8]) -> Option<(u8, &[u8], usize, usize)> {
    let mut at = 0;
    let skip_spaces = |at: &mut usize| {
        while raw.get(*at).is_some_and(|b| *b == b' ' || *b == b'\t') {
            *at += 1;
        }
    };
    skip_spaces(&mut at);
    if raw.get(at).is_some_and(|b| b.eq_ignore_ascii_case(&b'n')) {
        at += 1;
        while raw.get(at).is_some_and(u8::is_ascii_digit) {
            at += 1;
        }
        skip_spaces(&mut at);
    }
    let start = at;
    // A letter: `;0.2` (PrusaSlicer's `;[layer_z]`) is a comment, not a command `;`.
    let letter = raw.get(at).filter(|b| b.is_ascii_alphabetic())?.to_ascii_uppercase();
    at += 1;
    skip_spaces(&mut at);
    let digits = at;
    while raw.get(at).is_some_and(|b| b.is_ascii_digit() || *b == b'.') {
        at += 1;
    }
    if at == digits {
        return None;
    }
    Some((letter, &raw[digits..at], start, at))
}

/// Whether the rest of a line holds a word (a letter outside `( … )` and `;` comments).
fn has_words(rest: &[u8]) -> bool {
    let mut depth = 0usize;
    for &byte in rest {
        match byte {
            b';' if depth == 0 => return false,
            b'(' => depth += 1,
            b')' => depth = depth.saturating_sub(1),
            _ if depth == 0 && byte.is_ascii_alphabetic() => return true,
            _ => {}
        }
    }
    false
}

/// The number part of a code as an integer and its fraction digit (`862.3` → 862, Some(3)).
fn code_number(number: &[u8]) -> Option<(u32, bool)> {
    let text = std::str::from_utf8(number).ok()?;
    let (whole, fraction) = match text.split_once('.') {
        Some((whole, fraction)) => (whole, !fraction.trim_end_matches('0').is_empty()),
        None => (text, false),
    };
    Some((whole.parse().ok()?, fraction))
}

/// Cuts `name` to at most `max` bytes at a character boundary (names come from arbitrary bytes,
/// decoded lossily: `String::truncate` would panic inside a multi-byte character).
fn truncate_chars(name: &mut String, max: usize) {
    if name.len() > max {
        let end = (0..=max).rev().find(|&index| name.is_char_boundary(index)).unwrap_or(0);
        name.truncate(end);
    }
}

fn code_name(letter: u8, number: &[u8]) -> String {
    let text = String::from_utf8_lossy(number);
    let trimmed = text.trim_start_matches('0');
    let shown = if trimmed.is_empty() || trimmed.starts_with('.') {
        format!("0{trimmed}")
    } else {
        trimmed.to_owned()
    };
    let mut name = format!("{}{shown}", char::from(letter));
    truncate_chars(&mut name, CodeName::MAX);
    name
}

/// M-codes in Marlin's G-code reference (marlinfw.org/meta/gcode) that have no motion here.
fn marlin_knows_m(code: u32) -> bool {
    matches!(
        code,
        10 | 11 | 16 | 17 | 18 | 20..=34 | 42 | 43 | 48 | 73 | 75..=78 | 80 | 81 | 84 | 85 | 86
            | 87 | 92 | 100 | 102 | 104..=129 | 140 | 141 | 143 | 145 | 149 | 150 | 154 | 155
            | 163..=166 | 190..=193 | 200..=209 | 211 | 217 | 218 | 220 | 221 | 226 | 240 | 250
            | 255 | 256 | 260 | 261 | 280..=282 | 290 | 300..=306 | 350 | 351 | 355 | 360..=364
            | 380 | 381 | 400..=407 | 410 | 412 | 413 | 420..=423 | 425 | 428 | 430 | 486 | 493
            | 500..=504 | 510..=512 | 524 | 540 | 569 | 575 | 592 | 593 | 600 | 603 | 605 | 665
            | 666 | 672 | 701 | 702 | 710 | 808 | 851 | 852 | 860..=869 | 871 | 876 | 900
            | 906..=919 | 928 | 951 | 993..=995 | 997 | 999 | 7219
    )
}

/// The line as Grbl reads it before the block reader: its `$` system commands (Grbl wiki, "Grbl
/// v1.1 Commands": settings, homing, unlock, reports) and real-time characters are events; `$J=`
/// jogging is motion, refused. (LinuxCNC, Mach3 and Fanuc have no such hook: Mach3's `O0001`
/// program numbers and `O1000` subprogram labels are LinuxCNC's Fanuc-style O lines.)
pub(crate) fn grbl_prelude(raw: &[u8]) -> Prelude {
    let start = raw.iter().position(|b| !b.is_ascii_whitespace()).unwrap_or(raw.len());
    if let Some(name) = grbl_realtime_line(&raw[start..]) {
        return Prelude::Event { name, known: true };
    }
    if raw.get(start) != Some(&b'$') {
        return Prelude::Block;
    }
    let rest = &raw[start..];
    let end = rest.iter().position(|b| *b == b'=' || b.is_ascii_whitespace()).unwrap_or(rest.len());
    let mut name = String::from_utf8_lossy(&rest[..end]).to_ascii_uppercase();
    if name == "$J" {
        return Prelude::Refuse {
            start,
            end: raw.len(),
            code: "$J= (jogging)".to_owned(),
            note: "a jog is an operator's move, not part of a program",
        };
    }
    truncate_chars(&mut name, CodeName::MAX);
    Prelude::Event { name, known: true }
}

/// A line of Grbl's real-time commands `?` (status report) and `~` (cycle start, resume) with
/// nothing after them but spaces and a comment: Grbl's serial reader takes these characters out
/// of the stream before its line buffer (wiki "Grbl v1.1 Commands", real-time commands), so the
/// line that is left is empty. Neither moves the machine: an event named by the characters.
fn grbl_realtime_line(text: &[u8]) -> Option<String> {
    let commands = text.iter().take_while(|b| matches!(b, b'?' | b'~' | b' ' | b'\t')).count();
    let rest = &text[commands..];
    let name: String = text[..commands]
        .iter()
        .filter(|b| !b.is_ascii_whitespace())
        .map(|&b| char::from(b))
        .collect();
    let nothing_after = rest.iter().all(u8::is_ascii_whitespace)
        || rest.first() == Some(&b';')
        || (rest.first() == Some(&b'(') && rest.trim_ascii_end().ends_with(b")"));
    (!name.is_empty() && nothing_after).then(|| {
        let mut name = name;
        truncate_chars(&mut name, CodeName::MAX);
        name
    })
}

/// Whether Grbl 1.1 runs G-code `code` (ten times its number): its README's list of supported
/// G-codes (motion, G4, G10 L2/L20, G17–G19, G20/G21, G28/G30 and .1, G38.2–G38.5, G40, G43.1,
/// G49, G53–G59, G61, G80, G90/G91, G91.1, G92, G92.1, G93/G94). Anything else is its error 20
/// ("Unsupported or invalid g-code command found in block").
pub(crate) fn grbl_runs_g(code: u16) -> bool {
    matches!(
        code,
        0 | 10
            | 20
            | 30
            | 40
            | 100
            | 170
            | 180
            | 190
            | 200
            | 210
            | 280
            | 281
            | 300
            | 301
            | 382
            | 383
            | 384
            | 385
            | 400
            | 431
            | 490
            | 530
            | 540
            | 550
            | 560
            | 570
            | 580
            | 590
            | 610
            | 800
            | 900
            | 910
            | 911
            | 920
            | 921
            | 930
            | 940
    )
}

/// Whether Grbl 1.1 runs M-code `code`: M0 M1 M2 M30, M3 M4 M5, M7 M8 M9 and M56 (its README);
/// anything else, M6 included, is its error 20.
pub(crate) fn grbl_runs_m(code: u16) -> bool {
    matches!(code, 0 | 1 | 2 | 30 | 3 | 4 | 5 | 7 | 8 | 9 | 56)
}

/// The name of G-code `code` (ten times its number): `G81`, `G41.1`.
pub(crate) fn g_name(code: u16) -> String {
    if code.is_multiple_of(10) {
        format!("G{}", code / 10)
    } else {
        format!("G{}.{}", code / 10, code % 10)
    }
}

/// Marlin reads one command per line (marlinfw.org "G-code"): the first G, M or T word. A line
/// that starts with anything else (text without a `;`) is an unknown command, skipped.
pub(crate) fn marlin_prelude(raw: &[u8]) -> Prelude {
    let Some((letter, number, start, end)) = first_command(raw) else {
        return unknown_text(raw);
    };
    let Some((code, fraction)) = code_number(number) else { return Prelude::Block };
    match letter {
        b'M' => match code {
            82 | 83 if !fraction => {
                Prelude::ExtruderMode { name: code_name(letter, number), relative: code == 83 }
            }
            0..=9 | 30 if !fraction => Prelude::Block,
            _ => Prelude::Event { name: code_name(letter, number), known: marlin_knows_m(code) },
        },
        b'G' => match code {
            28 if !fraction => {
                let mut axes = [false; 4];
                let mut depth = 0usize;
                for &byte in &raw[end..] {
                    match byte {
                        b';' if depth == 0 => break,
                        b'(' => depth += 1,
                        b')' => depth = depth.saturating_sub(1),
                        _ if depth > 0 => {}
                        _ => {
                            if let Some(axis) =
                                b"xyzc".iter().position(|l| l.eq_ignore_ascii_case(&byte))
                            {
                                axes[axis] = true;
                            }
                        }
                    }
                }
                if !axes.iter().any(|&axis| axis) {
                    axes = [true; 4];
                }
                Prelude::Home { axes }
            }
            // Firmware retract and recover, mesh and probe codes, nozzle park, calibrations,
            // save position: no motion of the program's own.
            10 | 11 | 26 | 27 | 29 | 30..=35 | 60 | 76 | 425 => {
                Prelude::Event { name: code_name(letter, number), known: true }
            }
            // A G5 with no word moves nowhere: a default Marlin build (no BEZIER_CURVE_SUPPORT)
            // skips it as unknown, one with it draws a curve from here to here.
            5 if !fraction && !has_words(&raw[end..]) => {
                Prelude::Event { name: code_name(letter, number), known: true }
            }
            // G38.2–G38.5 (a build with G38_PROBE_TARGET): probe moves, as in the other
            // dialects (no probe trips; Marlin has no parameters to read the point from).
            38 if fraction => Prelude::Block,
            5 | 6 | 12 | 38 | 42 | 61 => Prelude::Refuse {
                start,
                end,
                code: code_name(letter, number),
                note: match code {
                    5 => "Marlin's Bézier curve",
                    6 => "Marlin's direct stepper move",
                    12 => "Marlin's nozzle cleaning moves",
                    38 => "probing",
                    42 => "Marlin's move to a mesh point",
                    _ => "Marlin's return to a saved position",
                },
            },
            // A G-code neither Marlin nor LinuxCNC knows (Ultimaker's G280 prime): skipped.
            _ if code > 99 || crate::syntax::parser::g_group(code as u16 * 10).is_none() => {
                Prelude::Event { name: code_name(letter, number), known: false }
            }
            _ => Prelude::Block,
        },
        // Tool (extruder) selection, no motion; its parameters are the firmware's (Prusa's
        // `T0 S1 L0 D0` on the XL toolchanger), not LinuxCNC words.
        b'T' if !fraction => Prelude::Event { name: code_name(letter, number), known: true },
        b'T' => Prelude::Block,
        // No command letter (Marlin has no modal motion by default): "Unknown command".
        _ => Prelude::Event { name: code_name(letter, number), known: false },
    }
}

/// A line that does not start with a command: an empty or comment line is a block (nothing to
/// do); text starting with a letter is Marlin's "Unknown command", recorded by its first word.
fn unknown_text(raw: &[u8]) -> Prelude {
    let text = raw.trim_ascii_start();
    let Some(&first) = text.first() else { return Prelude::Block };
    // Text that starts with a character no block starts with (NovaMaker's `<Slice> Blank`):
    // Marlin finds no command letter and answers "Unknown command" too.
    let foreign = first.is_ascii_punctuation() && !b";(%/#[*+-.@".contains(&first);
    if !first.is_ascii_alphabetic() && !foreign {
        return Prelude::Block;
    }
    if first_command(raw).is_some_and(|(letter, ..)| matches!(letter, b'G' | b'M' | b'T')) {
        return Prelude::Block;
    }
    let word: String = text
        .iter()
        .take_while(|b| b.is_ascii_graphic() && **b != b';' && **b != b'(')
        .take(CodeName::MAX)
        .map(|&b| char::from(b))
        .collect();
    Prelude::Event { name: word, known: false }
}

#[cfg(test)]
mod tests;
