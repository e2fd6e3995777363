//! Why a G-code program cannot be interpreted.

use std::fmt;
use std::io;

/// Where in the program an error was found: the 1-based line and column, the byte span within
/// the line, and the line itself (to show it with a caret under the column).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Location {
    /// 1-based line of the file.
    pub line: usize,
    /// 1-based column (in bytes) within the line.
    pub column: usize,
    /// Byte range within the line that the error is about (`start..end`, 0-based).
    pub span: (usize, usize),
    /// The text of the line (lossily decoded, without its line ending; shortened when long).
    pub text: String,
    /// The file subroutine (`o<name> call` → `name.ngc`) the line is in, as its path was found;
    /// `None` when it is the program's own line. A caller prefixes this name instead of the
    /// program's.
    pub file: Option<Box<str>>,
}

impl Location {
    /// The line with a caret under the column, two lines, for a diagnostic.
    pub fn snippet(&self) -> String {
        let prefix: String = self
            .text
            .bytes()
            .take(self.column.saturating_sub(1))
            .map(|byte| if byte == b'\t' { '\t' } else { ' ' })
            .collect();
        let width = (self.span.1.saturating_sub(self.span.0)).clamp(1, 80);
        format!("{}\n{prefix}{}", self.text, "^".repeat(width))
    }
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}", self.line, self.column)
    }
}

/// A G-code program that cannot be interpreted. Every variant carries where; its message starts
/// with `LINE:COLUMN: ` so that a caller only prefixes the file name (`job.ngc:12:5: …`) and may
/// show [`Location::snippet`] below it. Wording follows LinuxCNC's where it has one.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum GcodeError {
    /// Occurs when the reader fails.
    #[error("{line}:1: cannot read the program: {source}")]
    Read {
        /// The line being read.
        line: usize,
        /// The underlying error.
        source: io::Error,
    },
    /// Occurs when a line is longer than LinuxCNC's limit (it reports "Command too long").
    #[error("{}: Command too long: the line has more than {max} characters (LinuxCNC's limit)", at)]
    LineTooLong {
        /// Where.
        at: Location,
        /// The limit, in bytes.
        max: usize,
    },
    /// Occurs when the text breaks the language's grammar: a bad character, an unclosed
    /// comment or expression, a word without a number, two words of one kind, two codes of one
    /// modal group, an unknown G or M code.
    #[error("{at}: {message}")]
    Syntax {
        /// Where.
        at: Location,
        /// What is wrong (LinuxCNC's wording where it has one).
        message: String,
    },
    /// Occurs when a block is well formed but cannot be executed: a G1 with no feed rate, an arc
    /// whose radii differ, a division by zero, an undefined parameter, a number that is not
    /// finite, a missing word.
    #[error("{at}: {message}")]
    Invalid {
        /// Where.
        at: Location,
        /// What is wrong (LinuxCNC's wording where it has one).
        message: String,
    },
    /// Occurs for a code of LinuxCNC's language that this interpreter does not implement yet
    /// (O-words, splines, canned cycles, threading, …): refused rather than
    /// interpreted wrongly.
    #[error("{at}: {code} is not supported yet{}", note_suffix(note))]
    NotSupported {
        /// Where.
        at: Location,
        /// The code, as LinuxCNC names it (`G41`, `O-word`, `G10 L1`).
        code: String,
        /// What it is, when that helps.
        note: &'static str,
    },
    /// Occurs for a code of LinuxCNC's language this robot cannot do: lathe modes and cycles,
    /// spindle-synchronised motion (docs/gcode.md).
    #[error("{at}: {code} is refused: {reason}")]
    CannotRun {
        /// Where.
        at: Location,
        /// The code, as LinuxCNC names it (`G33`, `G76`).
        code: String,
        /// Why this robot cannot do it.
        reason: &'static str,
    },
    /// Occurs for an A, B, U, V or W word: the robot's axes are X Y Z C.
    #[error("{at}: {letter} axis word: this robot has the axes X Y Z C only")]
    ForeignAxis {
        /// Where.
        at: Location,
        /// The letter, upper case.
        letter: char,
    },
    /// Occurs when the program needs something of the caller it was not given, or goes past a
    /// bound the caller set: Python plug-ins without an INI file that loads them, a file
    /// subroutine named with a path, an endless loop. [`GcodeError::setting`] says which
    /// setting would help (a command line names its flag).
    #[error("{at}: {message}")]
    NeedsSetting {
        /// Where.
        at: Location,
        /// What is wrong.
        message: String,
        /// The caller's setting that would help.
        setting: Setting,
    },
    /// Occurs when the file ends before `M2`, `M30` or a closing `%`.
    #[error(
        "{line}:1: File ended with no percent sign or program end: end the program with M2 or \
         M30 (or enclose it in % lines)"
    )]
    NoProgramEnd {
        /// The last line of the file (1 for an empty file).
        line: usize,
    },
    /// Occurs when a Fanuc `GOTO n` or `M97 P n` names a block number no line of the program
    /// has.
    #[error("{line}:1: no block N{target} in the program to go to")]
    NoBlockNumber {
        /// The line of the `GOTO` or `M97`.
        line: usize,
        /// The block number.
        target: u32,
    },
    /// Occurs when a file that starts with `%` ends before the closing `%`.
    #[error(
        "{line}:1: File ended with no percent sign: a program that starts with % must end with a % line"
    )]
    NoClosingPercent {
        /// The last line of the file.
        line: usize,
    },
}

/// A setting of the caller's that would help a refused program: the library says what is
/// wrong, a command line adds how to give it (its flag).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Setting {
    /// An INI file ([`Config::ini`](crate::Config::ini)), whose `[PYTHON]` section loads the
    /// Python plug-ins.
    Ini,
    /// The folders file subroutines are found in
    /// ([`Interpreter::with_subroutines`](crate::Interpreter::with_subroutines)).
    SubroutinePath,
    /// How many jumps back without a motion are allowed
    /// ([`Config::max_idle_jumps`](crate::Config::max_idle_jumps)).
    MaxIdleJumps,
    /// How many motions one run may make
    /// ([`Config::max_motions`](crate::Config::max_motions)).
    MaxMotions,
}

fn note_suffix(note: &str) -> String {
    if note.is_empty() { String::new() } else { format!(" ({note})") }
}

impl GcodeError {
    /// The 1-based line of the program the error is about.
    pub fn line(&self) -> usize {
        match self {
            GcodeError::Read { line, .. }
            | GcodeError::NoProgramEnd { line }
            | GcodeError::NoBlockNumber { line, .. }
            | GcodeError::NoClosingPercent { line } => *line,
            // Every other error points into its line.
            _ => self.location().map_or(0, |at| at.line),
        }
    }

    /// Where the error is, when it points into a line.
    pub fn location(&self) -> Option<&Location> {
        match self {
            GcodeError::LineTooLong { at, .. }
            | GcodeError::Syntax { at, .. }
            | GcodeError::Invalid { at, .. }
            | GcodeError::NotSupported { at, .. }
            | GcodeError::CannotRun { at, .. }
            | GcodeError::ForeignAxis { at, .. }
            | GcodeError::NeedsSetting { at, .. } => Some(at),
            _ => None,
        }
    }

    /// The caller's setting that would help, when the program needs one
    /// ([`GcodeError::NeedsSetting`]).
    pub fn setting(&self) -> Option<Setting> {
        match self {
            GcodeError::NeedsSetting { setting, .. } => Some(*setting),
            _ => None,
        }
    }
}
