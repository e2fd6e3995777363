//! A build without LinuxCNC's Python plug-ins (the cargo feature `python` off): no plug-ins are
//! ever loaded, so no Python subroutine is callable, and a `;py,` line or a `(py,…)`,
//! `(pyrun,…)` or `(pyreload)` comment is refused.

use std::rc::Rc;

use super::Machine;
use super::comments::PythonComment;
use super::control::Control;
use crate::IniFile;
use crate::syntax::lexer::Fault;

/// No plug-ins can be loaded in this build: there is no value of this type.
#[derive(Debug)]
pub(super) enum Python {}

/// What Python would reach of the interpreter (the same shape as the plug-ins' build; never
/// read here, as there is no Python).
#[allow(dead_code, reason = "the plug-ins' build reads these; this one has no Python")]
pub(super) struct Reach<'a> {
    pub(super) machine: &'a mut Machine,
    pub(super) control: &'a Control,
}

/// Whether a Python subroutine call has returned (never made in this build).
#[allow(dead_code, reason = "the plug-ins' build constructs these; this one has no Python")]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Returned {
    No,
    Yes,
}

/// The refusal of a program's Python.
pub(super) fn refused(machine: &Machine) -> Fault {
    machine.line_fault(
        "this line's Python runs only with LinuxCNC's Python plug-ins, which this build leaves \
         out (the cargo feature `python` of biscara-gcode); a program alone never runs code",
    )
}

impl Python {
    /// Never any plug-ins.
    pub(super) fn from_ini(_ini: &IniFile) -> Option<Python> {
        None
    }

    pub(super) fn paused(&self) -> bool {
        match *self {}
    }

    pub(super) fn callable(&mut self, _r: &mut Reach<'_>, _name: &str) -> Result<bool, Fault> {
        match *self {}
    }

    pub(super) fn call(
        &mut self,
        _r: &mut Reach<'_>,
        _name: Rc<str>,
        _arguments: &[f64],
    ) -> Result<Returned, Fault> {
        match *self {}
    }

    pub(super) fn comment(
        &mut self,
        _r: &mut Reach<'_>,
        _action: PythonComment,
        _code: &[u8],
    ) -> Result<Returned, Fault> {
        match *self {}
    }

    pub(super) fn resume(&mut self, _r: &mut Reach<'_>) -> Result<Returned, Fault> {
        match *self {}
    }
}
