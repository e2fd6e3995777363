//! LinuxCNC's Python plug-ins: the O-word subroutines an INI file's `[PYTHON]` section loads
//! (`TOPLEVEL`, whose `oword` module holds them) and the Python of `;py,` lines and `(py,…)`
//! comments, run in a `python3` child process the caller's [`Environment`] starts.
//!
//! LinuxCNC embeds Python in its interpreter; biscara runs `python3` beside it, with stand-ins
//! for LinuxCNC's `interpreter` and `emccanon` modules (`python_plugin.py`), and answers over a
//! pipe what Python asks of the interpreter (parameters, a few attributes, moves) while a call
//! runs. The process starts at the first use and lives until the interpreter is dropped.

use std::ffi::OsString;
use std::path::{Path, PathBuf};

use crate::IniFile;
use crate::environment::{Environment, PythonProcess};

/// The host program `python3` runs.
const HOST: &str = include_str!("python_plugin.py");

/// Where the plug-ins are: an INI file's `[PYTHON]` section, its relative paths taken from the
/// INI file's folder (LinuxCNC takes them from its working folder, which is the configuration's).
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct PluginSetup {
    /// `TOPLEVEL`: the file run first (it imports `oword`).
    toplevel: Option<PathBuf>,
    /// `PATH_PREPEND` folders, in order.
    prepend: Vec<PathBuf>,
    /// `PATH_APPEND` folders, in order.
    append: Vec<PathBuf>,
}

impl PluginSetup {
    /// The setup `ini` asks for; `None` when it has no `[PYTHON]` section.
    pub(crate) fn from_ini(ini: &IniFile) -> Option<PluginSetup> {
        if !ini.has_section("PYTHON") {
            return None;
        }
        let resolve = |value: &str| match ini.folder() {
            Some(folder) if Path::new(value).is_relative() => folder.join(value),
            _ => PathBuf::from(value),
        };
        Some(PluginSetup {
            toplevel: ini.find("PYTHON", "TOPLEVEL").map(resolve),
            prepend: ini.find_all("PYTHON", "PATH_PREPEND").into_iter().map(resolve).collect(),
            append: ini.find_all("PYTHON", "PATH_APPEND").into_iter().map(resolve).collect(),
        })
    }
}

/// A parameter as Python names it: `params["_x"]` or `params[5220]`.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Key {
    Named(String),
    Numbered(i64),
}

/// What a finished call, `exec` or `callable` gave back.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Outcome {
    None,
    Float(f64),
    Int(i64),
    Text(String),
    Bool(bool),
    /// The function yields (LinuxCNC's `yield INTERP_EXECUTE_FINISH`).
    Generator,
    /// Anything else: its `repr` and type name.
    Other {
        repr: String,
        type_name: String,
    },
}

/// One message from Python while a request runs.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Message {
    Param(Key),
    SetParam(Key, f64),
    /// `params.locals()` (`true`) or `params.globals()`.
    Names {
        locals: bool,
    },
    Attribute(String),
    SetAttribute(String, f64),
    /// An `emccanon` call: its name and numbers.
    Canon {
        name: String,
        values: Vec<f64>,
    },
    /// The request ended.
    Done(Outcome),
    /// The request raised: the exception and where, on one line.
    Raised(String),
}

/// The answer to a [`Message`] that asks.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Answer {
    Ok,
    Value(f64),
    Text(String),
    Names(Vec<String>),
    /// Python raises `RuntimeError` with this message.
    Error(String),
}

/// The running `python3`.
#[derive(Debug)]
pub(crate) struct PythonPlugin {
    process: Box<dyn PythonProcess>,
}

impl PythonPlugin {
    /// Starts `python3` in `environment`, which runs `TOPLEVEL` (and its `__init__(self)`, if
    /// it has one): [`PythonPlugin::next_message`] follows it, to its `Done` or `Raised`.
    pub(crate) fn start(
        setup: &PluginSetup,
        environment: &dyn Environment,
    ) -> Result<PythonPlugin, String> {
        let mut arguments: Vec<OsString> = vec!["-c".into(), HOST.into()];
        arguments.push(setup.toplevel.as_deref().unwrap_or(Path::new("")).into());
        arguments.extend(setup.prepend.iter().map(OsString::from));
        arguments.push("--".into());
        arguments.extend(setup.append.iter().map(OsString::from));
        let process = environment
            .start_python(&arguments)
            .map_err(|err| format!("cannot run python3 for them: {err}"))?;
        Ok(PythonPlugin { process })
    }

    /// Asks whether `oword.NAME` is a Python function; answers every message until it is done.
    pub(crate) fn callable(&mut self, name: &str) -> Result<bool, String> {
        self.send(&["callable", &escape(name)])?;
        match self.next_message()? {
            Message::Done(Outcome::Bool(callable)) => Ok(callable),
            Message::Raised(message) => Err(message),
            other => Err(format!("python3 answered {other:?}")),
        }
    }

    /// Calls `oword.NAME(self, *arguments)`; [`PythonPlugin::next_message`] follows it.
    pub(crate) fn call(&mut self, name: &str, arguments: &[f64]) -> Result<(), String> {
        let numbers: Vec<String> = arguments.iter().map(|value| format!("{value:?}")).collect();
        let mut fields = vec!["call", name];
        fields.extend(numbers.iter().map(String::as_str));
        self.send(&fields)
    }

    /// Runs `code` (`as_file`: the file it names) in the plug-ins' `__main__`;
    /// [`PythonPlugin::next_message`] follows it.
    pub(crate) fn execute(&mut self, code: &str, as_file: bool) -> Result<(), String> {
        self.send(&["exec", if as_file { "1" } else { "0" }, &escape(code)])
    }

    /// Runs `TOPLEVEL` again (`(pyreload)`); [`PythonPlugin::next_message`] follows it.
    pub(crate) fn reload(&mut self) -> Result<(), String> {
        self.send(&["reload"])
    }

    /// The next message of the request running.
    pub(crate) fn next_message(&mut self) -> Result<Message, String> {
        let fields = self.read_fields()?;
        let field = |index: usize| fields.get(index).map_or("", String::as_str);
        let number = |index: usize| {
            field(index).parse::<f64>().map_err(|_| format!("python3 sent {fields:?}"))
        };
        let key = |kind: &str| match kind {
            "paramn" | "setparamn" => {
                field(1).parse().map(Key::Numbered).map_err(|_| format!("python3 sent {fields:?}"))
            }
            _ => Ok(Key::Named(unescape(field(1)))),
        };
        Ok(match field(0) {
            kind @ ("param" | "paramn") => Message::Param(key(kind)?),
            kind @ ("setparam" | "setparamn") => Message::SetParam(key(kind)?, number(2)?),
            "names" => Message::Names { locals: field(1) == "locals" },
            "attr" => Message::Attribute(field(1).to_owned()),
            "setattr" => Message::SetAttribute(field(1).to_owned(), number(2)?),
            "canon" => Message::Canon {
                name: field(1).to_owned(),
                values: (2..fields.len()).map(number).collect::<Result<_, _>>()?,
            },
            "raised" => Message::Raised(unescape(field(1))),
            "done" => Message::Done(match field(1) {
                "none" => Outcome::None,
                "float" => Outcome::Float(number(2)?),
                "int" => Outcome::Int(field(2).parse().unwrap_or(i64::MAX)),
                "str" => Outcome::Text(unescape(field(2))),
                "bool" => Outcome::Bool(field(2) == "1"),
                "generator" => Outcome::Generator,
                _ => Outcome::Other { repr: unescape(field(2)), type_name: unescape(field(3)) },
            }),
            _ => return Err(format!("python3 sent {fields:?}")),
        })
    }

    /// Answers the message just read.
    pub(crate) fn answer(&mut self, answer: Answer) -> Result<(), String> {
        match answer {
            Answer::Ok => self.send(&["ok"]),
            Answer::Value(value) => self.send(&["ok", &format!("{value:?}")]),
            Answer::Text(text) => self.send(&["str", &escape(&text)]),
            Answer::Names(names) => {
                let names: Vec<String> = names.iter().map(|name| escape(name)).collect();
                let mut fields = vec!["ok"];
                fields.extend(names.iter().map(String::as_str));
                self.send(&fields)
            }
            Answer::Error(message) => self.send(&["err", &escape(&message)]),
        }
    }

    fn send(&mut self, fields: &[&str]) -> Result<(), String> {
        let mut line = fields.join("\t");
        line.push('\n');
        let to = self.process.input();
        to.write_all(line.as_bytes()).and_then(|()| to.flush()).map_err(|_| self.ended())
    }

    fn read_fields(&mut self) -> Result<Vec<String>, String> {
        let mut line = String::new();
        match self.process.output().read_line(&mut line) {
            Ok(0) | Err(_) => Err(self.ended()),
            Ok(_) => Ok(line.trim_end_matches('\n').split('\t').map(str::to_owned).collect()),
        }
    }

    /// Why the pipe broke: python3 ended.
    fn ended(&mut self) -> String {
        format!("python3 ended unexpectedly ({})", self.process.wait())
    }
}

/// A text field: `\`, tab, newline and carriage return escaped.
fn escape(text: &str) -> String {
    text.replace('\\', "\\\\").replace('\t', "\\t").replace('\n', "\\n").replace('\r', "\\r")
}

/// The text of a field [`escape`]d.
fn unescape(field: &str) -> String {
    let mut text = String::with_capacity(field.len());
    let mut chars = field.chars();
    while let Some(c) = chars.next() {
        if c != '\\' {
            text.push(c);
            continue;
        }
        match chars.next() {
            Some('t') => text.push('\t'),
            Some('n') => text.push('\n'),
            Some('r') => text.push('\r'),
            _ => text.push('\\'),
        }
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fields_escape_and_come_back() {
        for text in ["plain", "a\tb", "line\nnext\r", "back\\slash\\t", ""] {
            assert_eq!(unescape(&escape(text)), text);
            assert!(!escape(text).contains(['\t', '\n', '\r']));
        }
    }

    #[test]
    fn the_setup_comes_from_the_python_section_beside_the_ini_file() {
        let text = "[PYTHON]\nPATH_PREPEND = .\nPATH_PREPEND = /opt/py\nTOPLEVEL = subs.py\n";
        let ini = IniFile::parse(text.as_bytes(), "test.ini")
            .expect("an INI file")
            .with_folder(PathBuf::from("/config"));
        let setup = PluginSetup::from_ini(&ini).expect("a [PYTHON] section");
        assert_eq!(setup.toplevel, Some(PathBuf::from("/config/subs.py")));
        assert_eq!(setup.prepend, [PathBuf::from("/config/."), PathBuf::from("/opt/py")]);
        assert!(setup.append.is_empty());
        let none = IniFile::parse("[EMC]\n".as_bytes(), "x.ini").expect("an INI file");
        assert_eq!(PluginSetup::from_ini(&none), None);
    }
}
