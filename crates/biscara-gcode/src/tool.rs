//! The tool a program was written for, guessed from what it uses.

/// The end effector the program drives: what M3, M4, M5 and S mean (the one tool kind every
/// crate shares).
pub use biscara_motion::Tool;

/// The tool a program was written for, as [`infer_tool`] decided it, and why.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ToolInference {
    /// The tool.
    pub tool: Tool,
    /// What in the program told, for the note.
    pub reason: String,
    /// The 1-based line that told, when one did.
    pub line: Option<usize>,
}

/// The tool `text` (a program's first bytes) was written for, from what it uses, in this order:
/// printer codes (M82, M83, M104, M109) → extruder, unless `complete` (`text` is the whole
/// program) and nothing in it feeds filament (no E word on a move or G92, no RepRap M101, M102
/// or M108): a RepRap firmware's codes on a machine that feeds none, such as a PCB mill's
/// `M104` spindle speed; a comment that names a laser → laser; a
/// comment that names a pen or a plotter → pen; a non-zero E word on a move → extruder; M4
/// (Grbl's dynamic laser power) with S → laser; M3 or M4 with S and Z words → spindle; M3 or M4
/// with S and no Z word → laser; M3 or M4 with no S word in a program whose comments name a cut
/// (words such as `cut`, `pocket` or `penetrate`: gcodetools' `(Penetrate)`, PartKam's
/// `(pocket 1)`) → spindle. Otherwise M3 and M4 with no S word are the gripper's pick and
/// place. `None` when nothing tells (the caller keeps the gripper).
pub fn infer_tool(text: &[u8], complete: bool) -> Option<ToolInference> {
    let text =
        String::from_utf8_lossy(text.strip_prefix(crate::syntax::lexer::UTF8_BOM).unwrap_or(text));
    let found = |tool: Tool, reason: &str, line: usize| {
        Some(ToolInference { tool, reason: reason.to_owned(), line: Some(line) })
    };
    let (mut spindle_word, mut s_word, mut z_word) = (None, false, false);
    let (mut laser_comment, mut pen_comment, mut dynamic) = (None, None, None);
    let (mut extrusion, mut cut_comment, mut printer) = (None, None, None);
    let mut feeds = false;
    for (index, raw) in text.lines().enumerate() {
        let number = index + 1;
        let lower = raw.to_ascii_lowercase();
        let (code, comment) = split_comment(&lower);
        if comment.contains("laser") && laser_comment.is_none() {
            laser_comment = Some(number);
        }
        if (has_word(comment, "pen") || comment.contains("plotter")) && pen_comment.is_none() {
            pen_comment = Some(number);
        }
        if cut_comment.is_none() {
            cut_comment = CUT_WORDS.iter().find(|word| has_word(comment, word)).copied();
        }
        let words = words(&code);
        let has = |letter: u8| words.iter().any(|(l, _)| *l == letter);
        let is = |letter: u8, value: f64| words.iter().any(|(l, v)| *l == letter && *v == value);
        let moves = is(b'g', 0.0) || is(b'g', 1.0) || is(b'g', 2.0) || is(b'g', 3.0);
        if [82.0, 83.0, 104.0, 109.0].iter().any(|&m| is(b'm', m)) && printer.is_none() {
            printer = Some(number);
        }
        feeds |= feeds_filament(&words);
        if moves && words.iter().any(|(l, v)| *l == b'e' && *v != 0.0) && extrusion.is_none() {
            extrusion = Some(number);
        }
        // M3/M4 with no S word anywhere is the paper's gripper (pick, place).
        if is(b'm', 3.0) || is(b'm', 4.0) {
            spindle_word.get_or_insert(number);
            if is(b'm', 4.0) && has(b's') {
                dynamic.get_or_insert(number);
            }
        }
        s_word |= has(b's');
        // Any Z in the code: `Z-1`, `Z#<_zcut>`, `Z[#1]`.
        z_word |= code.contains('z');
    }
    if let Some(line) = printer.filter(|_| feeds || !complete) {
        return found(Tool::Extruder, "printer codes (M82, M83, M104, M109)", line);
    }
    if let Some(line) = laser_comment {
        return found(Tool::Laser, "a comment names a laser", line);
    }
    if let Some(line) = pen_comment {
        return found(Tool::Pen, "a comment names a pen or a plotter", line);
    }
    if let Some(line) = extrusion {
        return found(Tool::Extruder, "E words on moves", line);
    }
    if let Some(line) = dynamic {
        return found(Tool::Laser, "M4 with S: Grbl's dynamic laser power", line);
    }
    match spindle_word {
        Some(line) if z_word && s_word => {
            found(Tool::Spindle, "M3/M4 with S speed and Z moves: a cutting spindle", line)
        }
        Some(line) if s_word => {
            found(Tool::Laser, "M3/M4 with S power and no Z move: a laser", line)
        }
        Some(line) => cut_comment.and_then(|word| {
            let reason = format!(
                "M3/M4 with no S in a program whose comments name a cut (`{word}`): a cutting \
                 spindle"
            );
            found(Tool::Spindle, &reason, line)
        }),
        None => None,
    }
}

/// Whether the code of `text` feeds filament: an E word on a move or a G92 (`G1 X10 E0.5`, `G92
/// E0`), or an old RepRap extruder code (M101 on, M102 reversed, M108 its speed: KISSlicer,
/// Skeinforge). A whole program with none is no extruder job, whatever its firmware.
pub(crate) fn feeds(text: &[u8]) -> bool {
    let text =
        String::from_utf8_lossy(text.strip_prefix(crate::syntax::lexer::UTF8_BOM).unwrap_or(text));
    text.lines().any(|raw| feeds_filament(&words(&split_comment(&raw.to_ascii_lowercase()).0)))
}

/// Whether a block's words (lower case) feed filament (see [`feeds`]).
fn feeds_filament(words: &[(u8, f64)]) -> bool {
    let is = |letter: u8, value: f64| words.iter().any(|(l, v)| *l == letter && *v == value);
    let moves_or_sets = [0.0, 1.0, 2.0, 3.0, 92.0].iter().any(|&g| is(b'g', g));
    (moves_or_sets && words.iter().any(|(l, _)| *l == b'e'))
        || [101.0, 102.0, 108.0].iter().any(|&m| is(b'm', m))
}

/// Comment words that say a program cuts (whole words, lower case): a bare M3 (no S, the speed
/// set on the machine) in such a program turns a spindle on, as its firmware does.
const CUT_WORDS: [&str; 18] = [
    "cut",
    "cuts",
    "cutting",
    "mill",
    "milling",
    "endmill",
    "pocket",
    "pocketing",
    "profile",
    "contour",
    "drill",
    "drilling",
    "engrave",
    "engraving",
    "penetrate",
    "plunge",
    "spindle",
    "router",
];

/// A line (lower case) split into its code and its comments (`( … )` and `; …`).
fn split_comment(line: &str) -> (String, &str) {
    let mut code = String::with_capacity(line.len());
    let mut depth = 0usize;
    for (at, ch) in line.char_indices() {
        match ch {
            ';' if depth == 0 => return (code, &line[at..]),
            '(' => depth += 1,
            ')' => depth = depth.saturating_sub(1),
            _ if depth == 0 => code.push(ch),
            _ => {}
        }
    }
    let comment = line.find('(').map_or("", |at| &line[at..]);
    (code, comment)
}

/// Whether `text` holds `word` as a whole word.
fn has_word(text: &str, word: &str) -> bool {
    text.split(|c: char| !c.is_ascii_alphanumeric()).any(|w| w == word)
}

/// The letter-number words of a line of code (lower case), numbers that do not parse skipped.
fn words(code: &str) -> Vec<(u8, f64)> {
    let bytes = code.as_bytes();
    let mut words = Vec::new();
    let mut at = 0;
    while at < bytes.len() {
        let letter = bytes[at];
        at += 1;
        if !letter.is_ascii_lowercase() {
            continue;
        }
        let start = at;
        while at < bytes.len() && (bytes[at].is_ascii_digit() || b"+-. ".contains(&bytes[at])) {
            at += 1;
        }
        let number: String = code[start..at].chars().filter(|c| *c != ' ').collect();
        if let Ok(value) = number.parse::<f64>() {
            words.push((letter, value));
        }
    }
    words
}

#[cfg(test)]
mod tests {
    use super::*;

    fn inferred(program: &str) -> Option<Tool> {
        infer_tool(program.as_bytes(), true).map(|inference| inference.tool)
    }

    #[test]
    fn programs_tell_their_tool() {
        assert_eq!(inferred("G1 X10 Y10 E0.5 F1200\n"), Some(Tool::Extruder));
        assert_eq!(inferred("M104 S200\nG92 E0\nG1 X1\n"), Some(Tool::Extruder));
        assert_eq!(inferred("M104 S195\nM101\nM108 S31\nG1 X1\n"), Some(Tool::Extruder));
        // Printer codes in a whole program that feeds no filament: a RepRap-driven PCB mill
        // (M104 its spindle), not a printer; in a program's first bytes only, still a printer.
        let mill = "G0 Z1\nM104 S255\nG1 Z-0.2 F60\nG1 X14 Y30\nM104 S0\nM2\n";
        assert_eq!(inferred(mill), None);
        assert_eq!(infer_tool(mill.as_bytes(), false).map(|i| i.tool), Some(Tool::Extruder));
        assert!(feeds(b"G1 X1 E0.2\n") && feeds(b"G92 E0\n") && feeds(b"M101\n"));
        assert!(!feeds(b"M104 S200 (E3D hot end)\nM203 E25\nG1 X1\n"));
        assert_eq!(inferred("(LaserGRBL)\nM3 S0\nG1 X1 S300\n"), Some(Tool::Laser));
        assert_eq!(inferred("M4 S500\nG1 X1 F100\nM5\n"), Some(Tool::Laser));
        assert_eq!(inferred("M3 S0\nG1 X1 F100\nS300\nG1 X2\nM5\n"), Some(Tool::Laser));
        assert_eq!(inferred("(pen plotter)\nG0 X1\n"), Some(Tool::Pen));
        assert_eq!(inferred("; pen down\nG0 X1\n"), Some(Tool::Pen));
        assert_eq!(inferred("; open file\nG0 X1\n"), None);
        assert_eq!(inferred("S12000 M3\nG0 Z5\nG1 Z-1 F100\n"), Some(Tool::Spindle));
        assert_eq!(inferred("G0 X1 Y2\nM2\n"), None);
        // The paper's pick and place: M3 and M4 with no S.
        assert_eq!(inferred("G0 X1 Z5\nG1 Z0 F60\nM3\nG0 Z5\nM4\nM2\n"), None);
        // A comment is not code: an E in a comment is no extrusion.
        assert_eq!(inferred("G1 X1 (E5)\n"), None);
        // A plotter that says "no extrusion" to a printer firmware.
        assert_eq!(inferred("G00 E0; no extrusion\nG0 Z8; pen park\n"), Some(Tool::Pen));
        let inference = infer_tool(b"G0 X1\nM4 S100\n", true).unwrap();
        assert_eq!(inference.line, Some(2));
    }

    /// Found on real programs (Inkscape gcodetools, PartKam): a milling program that turns the
    /// spindle on with a bare `M3` (its speed set on the machine) and says in its comments that
    /// it cuts. The firmware turns a spindle on; it is no gripper's pick.
    #[test]
    fn a_bare_m3_in_a_program_whose_comments_name_a_cut_is_a_spindle() {
        let gcodetools = "(Start cutting path id: path27)\nM3\nG00 Z5\nG01 Z-1 F100 (Penetrate)\n\
                          G01 X10 F400\nM5\nM2\n";
        assert_eq!(inferred(gcodetools), Some(Tool::Spindle));
        assert_eq!(
            inferred("(pocket 1)\nG0 Z3\nM3\nG1 Z-0.8 F10\nG1 X5 F500\nM5\nM30\n"),
            Some(Tool::Spindle)
        );
        assert_eq!(inferred("M3 (spindle on)\nG1 Z-1 F100\nM5\nM2\n"), Some(Tool::Spindle));
        let inference = infer_tool(gcodetools.as_bytes(), true).unwrap();
        assert_eq!(inference.line, Some(2), "the M3 line tells");
        // The paper's pick and place stays the gripper's, whatever its comments say.
        assert_eq!(inferred("(pick the part)\nG1 Z0 F60\nM3\nG0 Z5 (place it)\nM4\nM2\n"), None);
        // A word that only contains a cut word is no cut ("cutter" in a shortcut, "profiles").
        assert_eq!(inferred("(shortcut)\nM3\nG1 Z0 F60\nM4\nM2\n"), None);
        // A comment after M3 S still lets S and Z decide, as before.
        assert_eq!(inferred("(cut)\nM3 S300\nG1 X5 F100\nM5\n"), Some(Tool::Laser));
    }
}
