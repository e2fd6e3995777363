//! A program's Python, with the plug-ins an INI file's `[PYTHON]` section loads: O-word
//! subroutines written in Python (`o<name> call` asks them first, as LinuxCNC does), `;py,`
//! lines and `(py,…)`, `(pyrun,…)` and `(pyreload)` comments.
//!
//! A request to Python runs until it is done; a move it makes (`emccanon.STRAIGHT_FEED`, …)
//! pauses it until the motion has been taken, so that Python's moves stream like the program's.
//! Without a `[PYTHON]` section a program's Python is refused: a G-code file alone never runs
//! code (LinuxCNC's standalone `rs274` runs `;py,` lines whatever its INI file says).

use std::rc::Rc;

use biscara_motion::{Feed, MotionKind};

use super::comments::PythonComment;
use super::control::Control;
use super::{MAX_COORDINATE, Machine};
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

/// What Python reaches of the interpreter while a request runs: the machine (parameters,
/// attributes, moves) and the control flow (the environment it starts in, the file's name).
pub(super) struct Reach<'a> {
    pub(super) machine: &'a mut Machine,
    pub(super) control: &'a Control,
}

/// Whether a Python subroutine call has returned (its call level is then left).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Returned {
    No,
    Yes,
}

/// The refusal of a program's Python when no plug-ins are loaded.
pub(super) fn refused(machine: &Machine) -> Fault {
    Fault {
        kind: FaultKind::Needs(crate::error::Setting::Ini),
        ..machine.line_fault(
            "this line's Python runs only with LinuxCNC's Python plug-ins: give an INI file with \
             a [PYTHON] section; a program alone never runs code",
        )
    }
}

impl Python {
    /// Whether a request to Python is paused (a move it made waits to be taken).
    pub(super) fn paused(&self) -> bool {
        self.running.is_some()
    }

    /// Whether `o<name> call` calls a Python function of the plug-ins' `oword` module.
    pub(super) fn callable(&mut self, r: &mut Reach<'_>, name: &str) -> Result<bool, Fault> {
        let callable = self.plugin(r)?.callable(name);
        callable.map_err(|message| plugin_failed(r, &message))
    }

    /// Calls the Python subroutine `name` with `arguments`, its call level entered.
    pub(super) fn call(
        &mut self,
        r: &mut Reach<'_>,
        name: Rc<str>,
        arguments: &[f64],
    ) -> Result<Returned, Fault> {
        r.machine.state.owords.value = 0.0;
        r.machine.state.owords.returned = false;
        let sent = self.plugin(r)?.call(&name, arguments);
        self.send(r, sent, Running::Call(name))
    }

    /// Runs a comment's Python: `code` (a file name for [`PythonComment::RunFile`]).
    pub(super) fn comment(
        &mut self,
        r: &mut Reach<'_>,
        action: PythonComment,
        code: &[u8],
    ) -> Result<Returned, Fault> {
        let code = String::from_utf8_lossy(code).into_owned();
        let plugin = self.plugin(r)?;
        let (sent, running) = match action {
            PythonComment::Run => (plugin.execute(&code, false), Running::Execute),
            PythonComment::RunFile => (plugin.execute(code.trim(), true), Running::Execute),
            PythonComment::Reload => (plugin.reload(), Running::Reload),
        };
        self.send(r, sent, running)
    }

    /// Goes on with the request paused, once its move has been taken.
    pub(super) fn resume(&mut self, r: &mut Reach<'_>) -> Result<Returned, Fault> {
        match self.pump(r)? {
            Progress::Paused => Ok(Returned::No),
            Progress::Done(outcome) => self.done(r, outcome),
            Progress::Raised(message) => Err(self.raised(r, &message)),
        }
    }

    /// A request was sent (`sent`): its messages are answered.
    fn send(
        &mut self,
        r: &mut Reach<'_>,
        sent: Result<(), String>,
        running: Running,
    ) -> Result<Returned, Fault> {
        sent.map_err(|message| plugin_failed(r, &message))?;
        self.running = Some(running);
        self.resume(r)
    }

    /// The plug-ins, started (and `TOPLEVEL` run) at the first use.
    fn plugin(&mut self, r: &mut Reach<'_>) -> Result<&mut PythonPlugin, Fault> {
        if self.plugin.is_none() {
            let started = PythonPlugin::start(&self.setup, &*r.control.environment);
            let cannot = |message: String| {
                format!("the INI file's Python plug-ins ([PYTHON]) cannot be loaded: {message}")
            };
            let plugin = started.map_err(|message| r.machine.line_fault(cannot(message)))?;
            self.plugin = Some(plugin);
            self.running = Some(Running::Start);
            match self.pump(r)? {
                Progress::Done(_) => {}
                Progress::Raised(message) => return Err(r.machine.line_fault(cannot(message))),
                Progress::Paused => {
                    return Err(r.machine.line_fault(cannot("it moved".to_owned())));
                }
            }
            self.running = None;
        }
        let missing = r.machine.line_fault("no Python plug-ins");
        self.plugin.as_mut().ok_or(missing)
    }

    /// Answers the running request's messages until it ends or a move of it is queued.
    fn pump(&mut self, r: &mut Reach<'_>) -> Result<Progress, Fault> {
        loop {
            let Some(plugin) = self.plugin.as_mut() else {
                return Ok(Progress::Done(Outcome::None));
            };
            let message = plugin.next_message();
            let message = message.map_err(|message| plugin_failed(r, &message))?;
            let answer = match message {
                Message::Done(outcome) => return Ok(Progress::Done(outcome)),
                Message::Raised(message) => return Ok(Progress::Raised(message)),
                Message::Param(key) => param(r, &key),
                Message::SetParam(key, value) => set_param(r, key, value),
                Message::Names { locals } => Answer::Names(r.machine.state.params.names(!locals)),
                Message::Attribute(name) => attribute(r, &name),
                Message::SetAttribute(name, value) => set_attribute(r, &name, value),
                Message::Canon { name, values } => match self.canon(r, &name, &values) {
                    Ok(()) => Answer::Ok,
                    Err(message) => Answer::Error(message),
                },
            };
            let Some(plugin) = self.plugin.as_mut() else {
                return Ok(Progress::Done(Outcome::None));
            };
            let answered = plugin.answer(answer);
            answered.map_err(|message| plugin_failed(r, &message))?;
            if !r.machine.output.queue.is_empty() {
                return Ok(Progress::Paused);
            }
        }
    }

    /// The request ended with `outcome`.
    fn done(&mut self, r: &mut Reach<'_>, outcome: Outcome) -> Result<Returned, Fault> {
        self.foreign_axis = None;
        let Some(Running::Call(name)) = self.running.take() else { return Ok(Returned::No) };
        let refuse = |message: String| Err(r.machine.line_fault(message));
        match outcome {
            Outcome::None => {}
            Outcome::Float(value) => {
                r.machine.state.owords.value = value;
                r.machine.state.owords.returned = true;
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
        Ok(Returned::Yes)
    }

    /// The request raised `message`.
    fn raised(&mut self, r: &Reach<'_>, message: &str) -> Fault {
        let (running, foreign_axis) = (self.running.take(), self.foreign_axis.take());
        if let Some(letter) = foreign_axis {
            let mut fault = r.machine.line_fault(message);
            fault.kind = FaultKind::ForeignAxis(letter);
            return fault;
        }
        r.machine.line_fault(match running {
            Some(Running::Call(name)) => format!("Python subroutine o<{name}> failed: {message}"),
            Some(Running::Reload) => format!("(pyreload) failed: {message}"),
            _ => format!("this line's Python failed: {message}"),
        })
    }

    /// An `emccanon` call that moves. Its position is in the program's units and coordinate
    /// system, as LinuxCNC's canon takes it; it does not change the interpreter's current
    /// point (LinuxCNC's does not follow the canon either).
    fn canon(&mut self, r: &mut Reach<'_>, name: &str, values: &[f64]) -> Result<(), String> {
        match (name, values) {
            ("STRAIGHT_FEED" | "STRAIGHT_TRAVERSE", &[x, y, z, a, b, c, u, v, w]) => {
                for (letter, value) in [('A', a), ('B', b), ('U', u), ('V', v), ('W', w)] {
                    if value != 0.0 {
                        self.foreign_axis = Some(letter);
                        return Err(format!(
                            "emccanon.{name} moves the {letter} axis to {value}: this robot has \
                             X, Y, Z and C only"
                        ));
                    }
                }
                if r.machine.state.comp.active() {
                    return Err(format!(
                        "emccanon.{name} under cutter radius compensation is not supported"
                    ));
                }
                let end = r.machine.state.absolute([x, y, z, c]);
                if end.iter().any(|value| !value.is_finite() || value.abs() > MAX_COORDINATE) {
                    return Err(format!(
                        "emccanon.{name} to ({x}, {y}, {z}, C{c}): beyond ±{MAX_COORDINATE} mm"
                    ));
                }
                let kind = if name == "STRAIGHT_FEED" {
                    if r.machine.state.feed_mm <= 0.0 {
                        return Err("emccanon.STRAIGHT_FEED with zero feed rate: program an F \
                                    word before the call"
                            .to_owned());
                    }
                    let feed = Feed { mm_per_min: r.machine.state.feed_mm, inverse_time: false };
                    MotionKind::Linear { end, feed }
                } else {
                    MotionKind::Rapid { end }
                };
                r.machine.emit(kind);
                Ok(())
            }
            ("DWELL", &[seconds]) if seconds.is_finite() && seconds >= 0.0 => {
                r.machine.emit(MotionKind::Dwell { seconds });
                Ok(())
            }
            ("DWELL", _) => Err("emccanon.DWELL needs a time of 0 s or more".to_owned()),
            _ => Err(format!("emccanon.{name} is not supported")),
        }
    }
}

/// The error for a broken conversation with `python3` (it ended, or sent nonsense).
fn plugin_failed(r: &Reach<'_>, message: &str) -> Fault {
    r.machine.line_fault(format!("the Python plug-ins failed: {message}"))
}

/// `params[key]`: LinuxCNC's `ParamClass::getitem`.
fn param(r: &Reach<'_>, key: &Key) -> Answer {
    match key {
        Key::Numbered(index) => match usize::try_from(*index) {
            Ok(index) if index < MAX_PARAMETERS => Answer::Value(r.machine.state.params.get(index)),
            _ => Answer::Error(format!(
                "params subscript out of range : {index} - must be between 0 and \
                 {MAX_PARAMETERS}"
            )),
        },
        Key::Named(name) => {
            let bytes = name.as_bytes();
            let value = if bytes.first() == Some(&b'_') {
                r.machine.state.predefined(bytes).or_else(|| r.machine.state.params.named(bytes))
            } else {
                r.machine.state.params.named(bytes)
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
fn set_param(r: &mut Reach<'_>, key: Key, value: f64) -> Answer {
    match key {
        Key::Numbered(index) => match usize::try_from(index) {
            Ok(index) if index < MAX_PARAMETERS => {
                r.machine.state.params.set(index, value);
                Answer::Ok
            }
            _ => Answer::Error(format!(
                "params subscript out of range : {index} - must be between 0 and \
                 {MAX_PARAMETERS}"
            )),
        },
        Key::Named(name) => {
            let bytes = name.as_bytes();
            if (bytes.first() == Some(&b'_') && r.machine.state.predefined(bytes).is_some())
                || !value.is_finite()
            {
                return Answer::Error(format!("can't assign value to parameter: {name}"));
            }
            r.machine.state.params.set_named(bytes, value);
            Answer::Ok
        }
    }
}

/// `self.NAME` for the interpreter's attributes Python may read.
fn attribute(r: &Reach<'_>, name: &str) -> Answer {
    Answer::Value(match name {
        "return_value" => r.machine.state.owords.value,
        "value_returned" => f64::from(u8::from(r.machine.state.owords.returned)),
        "call_level" => r.machine.state.owords.level as f64,
        "remap_level" | "task" => 0.0,
        "sequence_number" => r.machine.state.line as f64,
        "current_x" => r.machine.state.current[0],
        "current_y" => r.machine.state.current[1],
        "current_z" => r.machine.state.current[2],
        "feed_rate" => r.machine.state.feed_rate,
        "filename" => return Answer::Text(r.control.file_name()),
        _ => return Answer::Error(format!("no attribute {name}")),
    })
}

/// `self.NAME = value` for the attributes Python may set.
fn set_attribute(r: &mut Reach<'_>, name: &str, value: f64) -> Answer {
    match name {
        "return_value" => r.machine.state.owords.value = value,
        "value_returned" => r.machine.state.owords.returned = value != 0.0,
        _ => return Answer::Error(format!("can't set attribute {name}")),
    }
    Answer::Ok
}
