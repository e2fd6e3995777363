//! A program's Python, with the plug-ins an INI file's `[PYTHON]` section loads: O-word
//! subroutines written in Python (`o<name> call` asks them first, as LinuxCNC does), `;py,`
//! lines and `(py,…)`, `(pyrun,…)` and `(pyreload)` comments.
//!
//! A request to Python runs until it is done; a move it makes (`emccanon.STRAIGHT_FEED`, …)
//! pauses it until the motion has been taken, so that Python's moves stream like the program's.
//! Without a `[PYTHON]` section a program's Python is refused: a G-code file alone never runs
//! code (LinuxCNC's standalone `rs274` runs `;py,` lines whatever its INI file says).

use std::io::BufRead;
use std::rc::Rc;

use biscara_motion::{Feed, MotionKind};

use super::comments::PythonComment;
use super::{Interpreter, MAX_COORDINATE};
use crate::IniFile;
use crate::python_plugin::{Answer, Key, Message, Outcome, PluginSetup, PythonPlugin};
use crate::syntax::lexer::{Fault, FaultKind};
use crate::syntax::params::MAX_PARAMETERS;
use crate::syntax::parser::Predefined;

/// The plug-ins, and the request running.
#[derive(Debug)]
pub(super) struct Python {
    setup: PluginSetup,
    /// Started at the first use.
    plugin: Option<PythonPlugin>,
    /// The request whose messages are being answered (it is paused while a move it made waits
    /// to be taken).
    running: Option<Running>,
    /// The axis letter (A, B, U, V, W) of a move refused during the request: if it raises, the
    /// error is that axis.
    foreign_axis: Option<char>,
}

impl Python {
    /// The plug-ins the INI file's `[PYTHON]` section names, not started yet; `None` when it
    /// has no such section.
    pub(super) fn from_ini(ini: &IniFile) -> Option<Python> {
        let setup = PluginSetup::from_ini(ini)?;
        Some(Python { setup, plugin: None, running: None, foreign_axis: None })
    }
}

/// What Python is running.
#[derive(Debug, Clone, PartialEq)]
enum Running {
    /// `TOPLEVEL` and its `__init__`, at the start.
    Start,
    /// A Python O-word subroutine.
    Call(Rc<str>),
    /// A `;py,` line or a `(py,…)` or `(pyrun,…)` comment.
    Execute,
    /// `(pyreload)`.
    Reload,
}

/// Where a request stands after its messages were answered.
enum Progress {
    /// A move was queued: the request goes on when the motion has been taken.
    Paused,
    Done(Outcome),
    Raised(String),
}

impl<R: BufRead> Interpreter<R> {
    /// Whether a request to Python is paused (a move it made waits to be taken).
    pub(super) fn python_paused(&self) -> bool {
        self.python.as_ref().is_some_and(|python| python.running.is_some())
    }

    /// Whether `o<name> call` calls a Python function of the plug-ins' `oword` module.
    pub(super) fn python_callable(&mut self, name: &str) -> Result<bool, Fault> {
        if self.python.is_none() {
            return Ok(false);
        }
        let callable = self.plugin()?.callable(name);
        callable.map_err(|message| self.plugin_failed(&message))
    }

    /// Calls the Python subroutine `name` with `arguments`, its call level entered.
    pub(super) fn python_call(&mut self, name: Rc<str>, arguments: &[f64]) -> Result<(), Fault> {
        self.machine.state.owords.value = 0.0;
        self.machine.state.owords.returned = false;
        let sent = self.plugin()?.call(&name, arguments);
        self.send_python(sent, Running::Call(name))
    }

    /// Runs a comment's Python: `code` (a file name for [`PythonComment::RunFile`]).
    pub(super) fn python_comment(
        &mut self,
        action: PythonComment,
        code: &[u8],
    ) -> Result<(), Fault> {
        if self.python.is_none() {
            return Err(self.setting_fault(
                "this line's Python runs only with LinuxCNC's Python plug-ins: give an INI file \
                 with a [PYTHON] section; a program alone never runs code",
                crate::error::Setting::Ini,
            ));
        }
        let code = String::from_utf8_lossy(code).into_owned();
        let plugin = self.plugin()?;
        let (sent, running) = match action {
            PythonComment::Run => (plugin.execute(&code, false), Running::Execute),
            PythonComment::RunFile => (plugin.execute(code.trim(), true), Running::Execute),
            PythonComment::Reload => (plugin.reload(), Running::Reload),
        };
        self.send_python(sent, running)
    }

    /// Goes on with the request paused, once its move has been taken.
    pub(super) fn resume_python(&mut self) -> Result<(), Fault> {
        match self.pump_python()? {
            Progress::Paused => Ok(()),
            Progress::Done(outcome) => self.python_done(outcome),
            Progress::Raised(message) => Err(self.python_raised(&message)),
        }
    }

    /// A request was sent (`sent`): its messages are answered.
    fn send_python(&mut self, sent: Result<(), String>, running: Running) -> Result<(), Fault> {
        sent.map_err(|message| self.plugin_failed(&message))?;
        if let Some(python) = self.python.as_mut() {
            python.running = Some(running);
        }
        self.resume_python()
    }

    /// The error for a broken conversation with `python3` (it ended, or sent nonsense).
    fn plugin_failed(&self, message: &str) -> Fault {
        self.line_fault(format!("the Python plug-ins failed: {message}"))
    }

    /// The plug-ins, started (and `TOPLEVEL` run) at the first use.
    fn plugin(&mut self) -> Result<&mut PythonPlugin, Fault> {
        let Some(python) = self.python.as_mut() else {
            return Err(self.line_fault("no Python plug-ins"));
        };
        if python.plugin.is_none() {
            let started = PythonPlugin::start(&python.setup, &*self.control.environment);
            let cannot = |message: String| {
                format!("the INI file's Python plug-ins ([PYTHON]) cannot be loaded: {message}")
            };
            let plugin = started.map_err(|message| self.line_fault(cannot(message)))?;
            if let Some(python) = self.python.as_mut() {
                python.plugin = Some(plugin);
                python.running = Some(Running::Start);
            }
            match self.pump_python()? {
                Progress::Done(_) => {}
                Progress::Raised(message) => return Err(self.line_fault(cannot(message))),
                Progress::Paused => return Err(self.line_fault(cannot("it moved".to_owned()))),
            }
            if let Some(python) = self.python.as_mut() {
                python.running = None;
            }
        }
        let missing = self.line_fault("no Python plug-ins");
        self.python.as_mut().and_then(|python| python.plugin.as_mut()).ok_or(missing)
    }

    /// Answers the running request's messages until it ends or a move of it is queued.
    fn pump_python(&mut self) -> Result<Progress, Fault> {
        loop {
            let Some(python) = self.python.as_mut() else {
                return Ok(Progress::Done(Outcome::None));
            };
            let Some(plugin) = python.plugin.as_mut() else {
                return Ok(Progress::Done(Outcome::None));
            };
            let message = plugin.next_message();
            let message = message.map_err(|message| self.plugin_failed(&message))?;
            let answer = match message {
                Message::Done(outcome) => return Ok(Progress::Done(outcome)),
                Message::Raised(message) => return Ok(Progress::Raised(message)),
                Message::Param(key) => self.python_param(&key),
                Message::SetParam(key, value) => self.python_set_param(key, value),
                Message::Names { locals } => {
                    Answer::Names(self.machine.state.params.names(!locals))
                }
                Message::Attribute(name) => self.python_attribute(&name),
                Message::SetAttribute(name, value) => self.python_set_attribute(&name, value),
                Message::Canon { name, values } => match self.python_canon(&name, &values) {
                    Ok(()) => Answer::Ok,
                    Err(message) => Answer::Error(message),
                },
            };
            let Some(plugin) = self.python.as_mut().and_then(|python| python.plugin.as_mut())
            else {
                return Ok(Progress::Done(Outcome::None));
            };
            let answered = plugin.answer(answer);
            answered.map_err(|message| self.plugin_failed(&message))?;
            if !self.machine.output.queue.is_empty() {
                return Ok(Progress::Paused);
            }
        }
    }

    /// The request ended with `outcome`.
    fn python_done(&mut self, outcome: Outcome) -> Result<(), Fault> {
        let running = self.python.as_mut().and_then(|python| {
            python.foreign_axis = None;
            python.running.take()
        });
        let Some(Running::Call(name)) = running else { return Ok(()) };
        let refuse = |message: String| Err(self.line_fault(message));
        match outcome {
            Outcome::None => {}
            Outcome::Float(value) => {
                self.machine.state.owords.value = value;
                self.machine.state.owords.returned = true;
            }
            Outcome::Int(value) => {
                return refuse(format!(
                    "Python subroutine o<{name}> returned the int {value}: LinuxCNC 2.9 stops \
                     there (it takes an int from an O-word subroutine for an error); return a \
                     float"
                ));
            }
            // LinuxCNC: a string returned is the error message.
            Outcome::Text(message) => return refuse(message),
            Outcome::Generator => {
                return refuse(format!(
                    "Python subroutine o<{name}> yields (LinuxCNC's INTERP_EXECUTE_FINISH): not \
                     supported"
                ));
            }
            Outcome::Other { repr, type_name } => {
                return refuse(format!(
                    "Python call oword.{name} returned '{repr}' - expected generator, int, or \
                     float value, got {type_name}"
                ));
            }
            Outcome::Bool(_) => {
                return refuse(format!("Python subroutine o<{name}> answered oddly"));
            }
        }
        self.leave_context()
    }

    /// The request raised `message`.
    fn python_raised(&mut self, message: &str) -> Fault {
        let (running, foreign_axis) = match self.python.as_mut() {
            Some(python) => (python.running.take(), python.foreign_axis.take()),
            None => (None, None),
        };
        if let Some(letter) = foreign_axis {
            let mut fault = self.line_fault(message);
            fault.kind = FaultKind::ForeignAxis(letter);
            return fault;
        }
        self.line_fault(match running {
            Some(Running::Call(name)) => format!("Python subroutine o<{name}> failed: {message}"),
            Some(Running::Reload) => format!("(pyreload) failed: {message}"),
            _ => format!("this line's Python failed: {message}"),
        })
    }

    /// `params[key]`: LinuxCNC's `ParamClass::getitem`.
    fn python_param(&self, key: &Key) -> Answer {
        match key {
            Key::Numbered(index) => match usize::try_from(*index) {
                Ok(index) if index < MAX_PARAMETERS => {
                    Answer::Value(self.machine.state.params.get(index))
                }
                _ => Answer::Error(format!(
                    "params subscript out of range : {index} - must be between 0 and \
                     {MAX_PARAMETERS}"
                )),
            },
            Key::Named(name) => {
                let bytes = name.as_bytes();
                let value = if bytes.first() == Some(&b'_') {
                    self.machine
                        .state
                        .predefined(bytes)
                        .or_else(|| self.machine.state.params.named(bytes))
                } else {
                    self.machine.state.params.named(bytes)
                };
                value.map_or_else(
                    || Answer::Error(format!("parameter does not exist: {name}")),
                    Answer::Value,
                )
            }
        }
    }

    /// `params[key] = value`: LinuxCNC's `ParamClass::setitem` (a name not starting with `_`
    /// is local to the Python subroutine's call level).
    fn python_set_param(&mut self, key: Key, value: f64) -> Answer {
        match key {
            Key::Numbered(index) => match usize::try_from(index) {
                Ok(index) if index < MAX_PARAMETERS => {
                    self.machine.state.params.set(index, value);
                    Answer::Ok
                }
                _ => Answer::Error(format!(
                    "params subscript out of range : {index} - must be between 0 and \
                     {MAX_PARAMETERS}"
                )),
            },
            Key::Named(name) => {
                let bytes = name.as_bytes();
                if (bytes.first() == Some(&b'_') && self.machine.state.predefined(bytes).is_some())
                    || !value.is_finite()
                {
                    return Answer::Error(format!("can't assign value to parameter: {name}"));
                }
                self.machine.state.params.set_named(bytes, value);
                Answer::Ok
            }
        }
    }

    /// `self.NAME` for the interpreter's attributes Python may read.
    fn python_attribute(&self, name: &str) -> Answer {
        Answer::Value(match name {
            "return_value" => self.machine.state.owords.value,
            "value_returned" => f64::from(u8::from(self.machine.state.owords.returned)),
            "call_level" => self.machine.state.owords.level as f64,
            "remap_level" | "task" => 0.0,
            "sequence_number" => self.machine.state.line as f64,
            "current_x" => self.machine.state.current[0],
            "current_y" => self.machine.state.current[1],
            "current_z" => self.machine.state.current[2],
            "feed_rate" => self.machine.state.feed_rate,
            "filename" => return Answer::Text(self.control.file_name()),
            _ => return Answer::Error(format!("no attribute {name}")),
        })
    }

    /// `self.NAME = value` for the attributes Python may set.
    fn python_set_attribute(&mut self, name: &str, value: f64) -> Answer {
        match name {
            "return_value" => self.machine.state.owords.value = value,
            "value_returned" => self.machine.state.owords.returned = value != 0.0,
            _ => return Answer::Error(format!("can't set attribute {name}")),
        }
        Answer::Ok
    }

    /// An `emccanon` call that moves. Its position is in the program's units and coordinate
    /// system, as LinuxCNC's canon takes it; it does not change the interpreter's current
    /// point (LinuxCNC's does not follow the canon either).
    fn python_canon(&mut self, name: &str, values: &[f64]) -> Result<(), String> {
        match (name, values) {
            ("STRAIGHT_FEED" | "STRAIGHT_TRAVERSE", &[x, y, z, a, b, c, u, v, w]) => {
                for (letter, value) in [('A', a), ('B', b), ('U', u), ('V', v), ('W', w)] {
                    if value != 0.0 {
                        if let Some(python) = self.python.as_mut() {
                            python.foreign_axis = Some(letter);
                        }
                        return Err(format!(
                            "emccanon.{name} moves the {letter} axis to {value}: this robot has \
                             X, Y, Z and C only"
                        ));
                    }
                }
                if self.machine.state.comp.active() {
                    return Err(format!(
                        "emccanon.{name} under cutter radius compensation is not supported"
                    ));
                }
                let end = self.machine.state.absolute([x, y, z, c]);
                if end.iter().any(|value| !value.is_finite() || value.abs() > MAX_COORDINATE) {
                    return Err(format!(
                        "emccanon.{name} to ({x}, {y}, {z}, C{c}): beyond ±{MAX_COORDINATE} mm"
                    ));
                }
                let kind = if name == "STRAIGHT_FEED" {
                    if self.machine.state.feed_mm <= 0.0 {
                        return Err("emccanon.STRAIGHT_FEED with zero feed rate: program an F \
                                    word before the call"
                            .to_owned());
                    }
                    let feed = Feed { mm_per_min: self.machine.state.feed_mm, inverse_time: false };
                    MotionKind::Linear { end, feed }
                } else {
                    MotionKind::Rapid { end }
                };
                self.machine.emit(kind);
                Ok(())
            }
            ("DWELL", &[seconds]) if seconds.is_finite() && seconds >= 0.0 => {
                self.machine.emit(MotionKind::Dwell { seconds });
                Ok(())
            }
            ("DWELL", _) => Err("emccanon.DWELL needs a time of 0 s or more".to_owned()),
            _ => Err(format!("emccanon.{name} is not supported")),
        }
    }
}
