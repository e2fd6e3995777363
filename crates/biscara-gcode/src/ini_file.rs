//! LinuxCNC's INI file, as far as G-code reads it: the `#<_ini[SECTION]NAME>` variables of its
//! INI_VARS feature (LinuxCNC 2.9's `fetch_ini_param`).
//!
//! A value is found as LinuxCNC's `IniFile::Find` finds it: the first line that starts (after
//! blanks) with `[SECTION]` opens the section, which ends at the next line starting with `[`; in
//! it, the first line that starts with `NAME` followed by a blank or `=` holds the value, after
//! the `=` and without the blanks around it. Section and name match exactly (G-code names are
//! upper-cased before the search, so the INI file must spell them in capitals). A line ending
//! in `\` continues on the next one. The value must be a number as a whole (LinuxCNC's
//! `lexical_cast<double>`); anything else is no value. `[RS274NGC] INI_VARS = 0` turns the
//! feature off (it is on by default, as in LinuxCNC).

use std::fmt;
use std::io::BufRead;
use std::path::{Path, PathBuf};

use crate::environment::Environment;

/// The longest line read, bytes.
const MAX_LINE: usize = 64 * 1024;

/// The largest INI file read, bytes (LinuxCNC's own are a few kilobytes).
const MAX_FILE: usize = 4 * 1024 * 1024;

/// A LinuxCNC INI file, its lines (continued ones joined) kept for LinuxCNC's search (see the
/// module's documentation).
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct IniFile {
    lines: Vec<String>,
    /// The folder the file is in, when it was read from one: relative paths in it (the
    /// `[PYTHON]` section's) start there.
    folder: Option<PathBuf>,
}

/// An INI file that cannot be read: where and why.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct IniFileError {
    /// The file's name as given.
    pub file: String,
    /// 1-based line (0 when the file cannot be opened).
    pub line: usize,
    /// What is wrong.
    pub message: String,
}

impl fmt::Display for IniFileError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.line == 0 {
            write!(f, "{}: {}", self.file, self.message)
        } else {
            write!(f, "{}:{}: {}", self.file, self.line, self.message)
        }
    }
}

impl std::error::Error for IniFileError {}

impl IniFile {
    /// Reads the INI file `path`, opened in `environment`.
    pub fn read(environment: &dyn Environment, path: &Path) -> Result<IniFile, IniFileError> {
        let name = path.display().to_string();
        let file = environment.open(path).map_err(|err| IniFileError {
            file: name.clone(),
            line: 0,
            message: format!("cannot read the INI file: {err}"),
        })?;
        let folder = path.parent().map(|folder| {
            if folder.as_os_str().is_empty() { PathBuf::from(".") } else { folder.to_path_buf() }
        });
        Ok(IniFile { folder, ..IniFile::parse(file, &name)? })
    }

    /// The same file, its relative paths taken from `folder`.
    #[must_use]
    pub fn with_folder(self, folder: PathBuf) -> IniFile {
        IniFile { folder: Some(folder), ..self }
    }

    /// The folder relative paths in the file start from: the file's own when it was read with
    /// [`IniFile::read`]; `None` for one parsed from a reader.
    pub fn folder(&self) -> Option<&Path> {
        self.folder.as_deref()
    }

    /// Reads an INI file from `reader`; `name` names it in errors. Lines must be UTF-8 text of
    /// at most 64 KiB, the file at most 4 MiB.
    pub fn parse(mut reader: impl BufRead, name: &str) -> Result<IniFile, IniFileError> {
        let mut lines: Vec<String> = Vec::new();
        let mut buffer = Vec::new();
        let (mut total, mut number, mut continued) = (0, 0, false);
        loop {
            buffer.clear();
            number += 1;
            let fail =
                |message: String| IniFileError { file: name.to_owned(), line: number, message };
            let read = std::io::Read::take(&mut reader, MAX_LINE as u64 + 1)
                .read_until(b'\n', &mut buffer)
                .map_err(|err| fail(format!("cannot read the INI file: {err}")))?;
            if read == 0 {
                break;
            }
            if buffer.len() > MAX_LINE && buffer.last() != Some(&b'\n') {
                return Err(fail(format!("line longer than {MAX_LINE} bytes")));
            }
            total += read;
            if total > MAX_FILE {
                return Err(fail(format!("the INI file is larger than {MAX_FILE} bytes")));
            }
            let line = buffer.strip_suffix(b"\n").unwrap_or(&buffer);
            let line = line.strip_suffix(b"\r").unwrap_or(line);
            let text = std::str::from_utf8(line)
                .ok()
                .filter(|text| !text.contains('\0'))
                .ok_or_else(|| fail("not a text file (invalid UTF-8 or NUL bytes)".to_owned()))?;
            // A line ending in `\` continues on the next: lines are kept joined.
            match lines.last_mut() {
                Some(last) if continued => last.push_str(text),
                _ => lines.push(text.to_owned()),
            }
            continued = lines.last_mut().is_some_and(|last| {
                let ends = last.ends_with('\\');
                if ends {
                    last.pop();
                }
                ends
            });
        }
        Ok(IniFile { lines, folder: None })
    }

    /// The index of the first line that starts (after blanks) with `[section]`.
    fn section_start(&self, section: &str) -> Option<usize> {
        let header = format!("[{section}]");
        self.lines.iter().position(|line| line.trim_start().starts_with(&header))
    }

    /// The value of `name` in `[section]`, as LinuxCNC's `IniFile::Find` finds it.
    pub fn find(&self, section: &str, name: &str) -> Option<&str> {
        self.values(section, name).next().flatten()
    }

    /// Every value of `name` in `[section]`, in order (LinuxCNC's `Find(name, section, n)` for
    /// n = 1, 2, …, which stops at the first without a value).
    pub fn find_all(&self, section: &str, name: &str) -> Vec<&str> {
        self.values(section, name).map_while(|value| value).collect()
    }

    /// The lines of `name` in the first `[section]`: `Some(value)`, or `None` for a line
    /// without one.
    fn values<'a, 'n>(
        &'a self,
        section: &str,
        name: &'n str,
    ) -> impl Iterator<Item = Option<&'a str>> + use<'a, 'n> {
        let lines = match self.section_start(section) {
            Some(start) => &self.lines[start + 1..],
            None => &[],
        };
        lines
            .iter()
            .map(|line| line.trim_start_matches([' ', '\t', '\r']))
            .take_while(|text| !text.starts_with('['))
            .filter_map(move |text| {
                let rest = text.strip_prefix(name)?;
                if !rest.starts_with([' ', '\t', '\r', '=']) {
                    return None;
                }
                // The value: after the first `=`, blanks around it removed (none: no value).
                let value =
                    rest.split_once('=').map(|(_, value)| value.trim_matches([' ', '\t', '\r']));
                Some(value.filter(|value| !value.is_empty()))
            })
    }

    /// The folders where file subroutines are looked for, as LinuxCNC reads them: `[RS274NGC]
    /// SUBROUTINE_PATH`, a `:`-separated list, a relative folder taken from the INI file's own
    /// folder ([`folder`](Self::folder); LinuxCNC runs in it), the working directory when it
    /// has none.
    pub fn subroutine_dirs(&self) -> Vec<PathBuf> {
        self.dirs("RS274NGC", "SUBROUTINE_PATH")
    }

    /// The folders where LinuxCNC finds the programs of the user M-codes M100–M199 (a file
    /// named `M100` … `M199`): `[RS274NGC] USER_M_PATH`, then `[DISPLAY] PROGRAM_PREFIX`,
    /// relative ones from the INI file's folder; `None` when the file names neither (the
    /// machine's programs are then unknown).
    pub fn user_m_dirs(&self) -> Option<Vec<PathBuf>> {
        let mut dirs = self.dirs("RS274NGC", "USER_M_PATH");
        dirs.extend(self.dirs("DISPLAY", "PROGRAM_PREFIX"));
        (!dirs.is_empty()).then_some(dirs)
    }

    /// The `:`-separated folders of `[section] name`.
    fn dirs(&self, section: &str, name: &str) -> Vec<PathBuf> {
        self.find(section, name)
            .into_iter()
            .flat_map(|list| list.split(':'))
            .map(str::trim)
            .filter(|dir| !dir.is_empty())
            .map(|dir| match &self.folder {
                Some(folder) if Path::new(dir).is_relative() => folder.join(dir),
                _ => PathBuf::from(dir),
            })
            .collect()
    }

    /// Whether the file has a line starting with `[section]`.
    pub fn has_section(&self, section: &str) -> bool {
        self.section_start(section).is_some()
    }

    /// The number `name` in `[section]` holds; `None` when it is missing or not a finite number.
    pub fn number(&self, section: &str, name: &str) -> Option<f64> {
        self.find(section, name)?.parse::<f64>().ok().filter(|value| value.is_finite())
    }

    /// Whether G-code may read this file's variables: `[RS274NGC] INI_VARS`, on unless it is
    /// `0` (LinuxCNC reads the option as a C++ `bool`: `0` or `1`, anything else leaves it on).
    pub fn variables_enabled(&self) -> bool {
        self.find("RS274NGC", "INI_VARS") != Some("0")
    }

    /// The value of the G-code name `#<_ini[section]name>` (`name` as the interpreter holds
    /// it, lower case, without the `#<>`), as LinuxCNC's `fetch_ini_param` reads it: section and
    /// name upper-cased, the section closed by the first `]` from its second character on.
    pub fn variable(&self, name: &[u8]) -> Option<f64> {
        let (section, name) = split_variable(name)?;
        self.number(&section, &name)
    }

    /// Why the G-code name `#<_ini[section]name>` has no value here, in words.
    pub fn why_not(&self, name: &[u8]) -> String {
        let Some((section, name)) = split_variable(name) else {
            return "the name is not of the form #<_ini[SECTION]NAME>".to_owned();
        };
        let header = format!("[{section}]");
        if !self.has_section(&section) {
            return format!("the INI file has no section {header}");
        }
        match self.find(&section, &name) {
            None => format!(
                "the first {header} of the INI file has no {name} = value (names are matched in \
                 capitals)"
            ),
            Some(value) => {
                format!("the INI file's {header} {name} is `{value}`, not a finite number")
            }
        }
    }
}

/// The section and name of `_ini[section]name`, upper-cased, as `fetch_ini_param` splits them.
fn split_variable(name: &[u8]) -> Option<(String, String)> {
    if name.len() <= 7 || !name[..5].eq_ignore_ascii_case(b"_ini[") {
        return None;
    }
    let close = 6 + name[6..].iter().position(|&b| b == b']')?;
    let upper = |bytes: &[u8]| String::from_utf8_lossy(bytes).to_ascii_uppercase();
    Some((upper(&name[5..close]), upper(&name[close + 1..])))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ini(text: &str) -> IniFile {
        IniFile::parse(text.as_bytes(), "test.ini").expect("an INI file")
    }

    #[test]
    fn values_are_found_as_linuxcnc_finds_them() {
        let file = ini("[EMC]\nX = 1\n\n[VARS]\n  TOOLCHANGE_X = 10\nTOOLCHANGE_XY=12\n\
                        TOOLCHANGE_Y\t=\t-2.5e1 \nLONG = 1\\\n5\nTEXT = ten\nEMPTY =\n\
                        NOEQUAL 3\n[VARS]\nLATER = 4\n[OTHER]\nY = 2\n");
        assert_eq!(file.find("VARS", "TOOLCHANGE_X"), Some("10"));
        assert_eq!(file.number("VARS", "TOOLCHANGE_XY"), Some(12.0));
        assert_eq!(file.number("VARS", "TOOLCHANGE_Y"), Some(-25.0));
        assert_eq!(file.number("VARS", "LONG"), Some(15.0));
        // Not numbers, no value, no `=`: nothing.
        assert_eq!(file.find("VARS", "TEXT"), Some("ten"));
        assert_eq!(file.number("VARS", "TEXT"), None);
        assert_eq!(file.find("VARS", "EMPTY"), None);
        assert_eq!(file.find("VARS", "NOEQUAL"), None);
        // Only the first [VARS] is searched, up to the next section; names match exactly.
        assert_eq!(file.find("VARS", "LATER"), None);
        assert_eq!(file.find("VARS", "Y"), None);
        assert_eq!(file.find("vars", "TOOLCHANGE_X"), None);
        assert_eq!(file.find("VARS", "toolchange_x"), None);
        assert_eq!(file.number("EMC", "X"), Some(1.0));
        assert_eq!(file.number("NOWHERE", "X"), None);
    }

    #[test]
    fn g_code_names_are_upper_cased_and_split_at_the_first_bracket() {
        let file = ini("[VARS]\nTOOLCHANGE_X = 10\n[A]B]\nC = 3\n");
        assert_eq!(file.variable(b"_ini[vars]toolchange_x"), Some(10.0));
        assert_eq!(file.variable(b"_INI[Vars]TOOLCHANGE_X"), Some(10.0));
        assert_eq!(file.variable(b"_ini[vars]nosuchname"), None);
        assert_eq!(file.variable(b"_ini[a]b]c"), None);
        assert_eq!(file.variable(b"_ini[]x"), None);
        assert_eq!(file.variable(b"_ini[a]"), None);
        assert_eq!(file.variable(b"_x"), None);
    }

    #[test]
    fn missing_values_say_why() {
        let file = ini("[VARS]\nX = ten\ny = 1\n[VARS]\nZ = 2\n");
        assert_eq!(file.why_not(b"_ini[nope]x"), "the INI file has no section [NOPE]");
        assert_eq!(
            file.why_not(b"_ini[vars]x"),
            "the INI file's [VARS] X is `ten`, not a finite number"
        );
        for missing in [&b"_ini[vars]y"[..], b"_ini[vars]z"] {
            assert!(file.why_not(missing).starts_with("the first [VARS] of the INI file has no "));
        }
        assert_eq!(file.why_not(b"_ini[]"), "the name is not of the form #<_ini[SECTION]NAME>");
    }

    #[test]
    fn sections_are_found_by_their_header() {
        let file = ini("[EMC]\n  [PYTHON] ; plug-ins\nPATH_PREPEND = python\n");
        assert!(file.has_section("PYTHON") && file.has_section("EMC"));
        assert!(!file.has_section("python") && !file.has_section("PATH_PREPEND"));
    }

    /// LinuxCNC's own interpreter tests name their subroutine folders in the INI file
    /// (`SUBROUTINE_PATH = .:subs`): they are read relative to the INI file's folder, and so are
    /// the folders of the user M-codes' programs.
    #[test]
    fn folders_start_from_the_ini_files_folder() {
        let text = "[RS274NGC]\nSUBROUTINE_PATH = .:subs: /abs\nUSER_M_PATH = mcodes\n\
                    [DISPLAY]\nPROGRAM_PREFIX = /programs\n";
        let file = ini(text);
        assert_eq!(file.subroutine_dirs(), [".", "subs", "/abs"].map(PathBuf::from));
        let placed = file.with_folder(PathBuf::from("/machine"));
        assert_eq!(
            placed.subroutine_dirs(),
            ["/machine/.", "/machine/subs", "/abs"].map(PathBuf::from)
        );
        let user = placed.user_m_dirs().expect("named");
        assert_eq!(user, ["/machine/mcodes", "/programs"].map(PathBuf::from));
        assert!(ini("[VARS]\nX = 1\n").subroutine_dirs().is_empty());
        assert_eq!(ini("[VARS]\nX = 1\n").user_m_dirs(), None);
    }

    #[test]
    fn ini_vars_can_be_turned_off() {
        assert!(ini("[VARS]\nX = 1\n").variables_enabled());
        assert!(ini("[RS274NGC]\nINI_VARS = 1\n").variables_enabled());
        assert!(ini("[RS274NGC]\nINI_VARS = yes\n").variables_enabled());
        assert!(!ini("[RS274NGC]\nINI_VARS = 0\n").variables_enabled());
    }

    #[test]
    fn unreadable_files_are_errors_with_their_line() {
        let binary = IniFile::parse(&b"[VARS]\nX = \xff\n"[..], "m.ini").expect_err("binary");
        assert_eq!(binary.to_string(), "m.ini:2: not a text file (invalid UTF-8 or NUL bytes)");
        let long = format!("[VARS]\nX = {}\n", "1".repeat(MAX_LINE + 10));
        let long = IniFile::parse(long.as_bytes(), "m.ini").expect_err("long");
        assert_eq!(long.to_string(), format!("m.ini:2: line longer than {MAX_LINE} bytes"));
        let none = crate::NoEnvironment;
        let missing = IniFile::read(&none, Path::new("/nonexistent/m.ini")).expect_err("missing");
        assert!(missing.to_string().starts_with("/nonexistent/m.ini: cannot read the INI file"));
    }

    #[test]
    fn a_file_read_by_path_starts_its_relative_paths_in_its_folder() {
        let files = crate::InMemory::new()
            .with_file("conf/m.ini", "[RS274NGC]\nSUBROUTINE_PATH = subs\n")
            .with_file("m.ini", "[EMC]\n");
        let nested = IniFile::read(&files, Path::new("conf/m.ini")).expect("conf/m.ini");
        assert_eq!(nested.folder(), Some(Path::new("conf")));
        assert_eq!(nested.subroutine_dirs(), [PathBuf::from("conf/subs")]);
        let here = IniFile::read(&files, Path::new("m.ini")).expect("m.ini");
        assert_eq!(here.folder(), Some(Path::new(".")));
    }
}
