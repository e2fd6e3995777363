//! A build without LinuxCNC's Python plug-ins (the cargo feature `python` off): no Python
//! subroutine is ever callable, and a `;py,` line or a `(py,…)`, `(pyrun,…)` or `(pyreload)`
//! comment is refused.

use std::io::BufRead;
use std::rc::Rc;

use super::Interpreter;
use super::comments::PythonComment;
use crate::IniFile;
use crate::syntax::lexer::Fault;

/// No plug-ins can be loaded in this build.
#[derive(Debug)]
pub(super) enum Python {}

impl Python {
    /// Never any plug-ins.
    pub(super) fn from_ini(_ini: &IniFile) -> Option<Python> {
        None
    }
}

impl<R: BufRead> Interpreter<R> {
    /// No request to Python is ever paused.
    pub(super) fn python_paused(&self) -> bool {
        false
    }

    /// No Python function is callable.
    pub(super) fn python_callable(&mut self, _name: &str) -> Result<bool, Fault> {
        Ok(false)
    }

    /// Never called ([`Interpreter::python_callable`] is always false).
    pub(super) fn python_call(&mut self, _name: Rc<str>, _arguments: &[f64]) -> Result<(), Fault> {
        Ok(())
    }

    /// A comment's Python is refused.
    pub(super) fn python_comment(
        &mut self,
        _action: PythonComment,
        _code: &[u8],
    ) -> Result<(), Fault> {
        Err(self.line_fault(
            "this line's Python runs only with LinuxCNC's Python plug-ins, which this build \
             leaves out (the cargo feature `python` of biscara-gcode); a program alone never runs \
             code",
        ))
    }

    /// Nothing to resume.
    pub(super) fn resume_python(&mut self) -> Result<(), Fault> {
        Ok(())
    }
}
