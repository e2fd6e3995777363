//! The one exception, `biscara.Error`, and the failures that become it.

use std::error::Error as StdError;
use std::fmt::Display;

use pyo3::exceptions::PyException;
use pyo3::prelude::*;

pyo3::create_exception!(
    biscara,
    Error,
    PyException,
    "An error of biscara: the command line's message, with `path`, `line` and `column` \
     (None where they do not apply)."
);

/// A failure of a call, made while the GIL is released: the message the command line prints
/// (without its `biscara: error: ` prefix) and where it is, or a Python exception raised while
/// the call checked for signals (Ctrl-C).
#[derive(Debug)]
pub(crate) enum Failure {
    /// A `biscara.Error`.
    Located {
        /// The whole message.
        message: String,
        /// The file it is in (None for text given as `source=`, or no file).
        path: Option<String>,
        /// 1-based line, where the message names one.
        line: Option<usize>,
        /// 1-based column, where the message names one.
        column: Option<usize>,
    },
    /// A Python exception (KeyboardInterrupt from a signal handler).
    Python(PyErr),
    /// An argument's value is not one the call takes: `ValueError`, the message naming it.
    Value(String),
}

/// The name a program given as text has in messages.
pub(crate) const SOURCE_NAME: &str = "<source>";

impl Failure {
    /// A failure with no place.
    pub(crate) fn plain(message: impl Display) -> Failure {
        Failure::Located { message: message.to_string(), path: None, line: None, column: None }
    }

    /// `err` with its causes (`what: why`, a cause left out where the message already ends with
    /// it, as the command line shows them), located in `file` when its message starts with
    /// `FILE:LINE[:COL]:`.
    pub(crate) fn of(err: &(dyn StdError + 'static), file: Option<&str>) -> Failure {
        Failure::message_in(chain(err), file)
    }

    /// A reader's error whose message starts with `LINE[:COL]:`, in the file `path` (None: text
    /// given as `source=`, named `<source>` in the message).
    pub(crate) fn located(err: &(dyn StdError + 'static), path: Option<&str>) -> Failure {
        let name = path.unwrap_or(SOURCE_NAME);
        let message = format!("{name}:{}", chain(err));
        Failure::message_in(message, Some(name))
    }

    /// `message` about the file `path` as a whole (no line: it cannot be read, say).
    pub(crate) fn in_file(message: impl Display, path: &str) -> Failure {
        let (message, path) = (message.to_string(), Some(path.to_owned()));
        Failure::Located { message, path, line: None, column: None }
    }

    /// `message`, located in `file` when it starts with `FILE:LINE[:COL]:`.
    pub(crate) fn message_in(message: String, file: Option<&str>) -> Failure {
        let file = file.filter(|name| message.starts_with(&format!("{name}:")));
        let (line, column) = match file {
            Some(name) => position(&message[name.len() + 1..]),
            None => (None, None),
        };
        let path = file.filter(|name| *name != SOURCE_NAME).map(str::to_owned);
        Failure::Located { message, path, line, column }
    }

    /// The Python exception: `biscara.Error` with its attributes set.
    pub(crate) fn into_py(self, py: Python<'_>) -> PyErr {
        match self {
            Failure::Python(err) => err,
            Failure::Value(message) => pyo3::exceptions::PyValueError::new_err(message),
            Failure::Located { message, path, line, column } => {
                let err = Error::new_err(message);
                let value = err.value(py);
                let set = || -> PyResult<()> {
                    value.setattr("path", path)?;
                    value.setattr("line", line)?;
                    value.setattr("column", column)?;
                    Ok(())
                };
                match set() {
                    Ok(()) => err,
                    Err(other) => other,
                }
            }
        }
    }
}

impl From<PyErr> for Failure {
    fn from(err: PyErr) -> Failure {
        Failure::Python(err)
    }
}

impl From<biscara_design::DesignError> for Failure {
    fn from(err: biscara_design::DesignError) -> Failure {
        Failure::of(&err, None)
    }
}

impl From<biscara_dynamics::DynamicsError> for Failure {
    fn from(err: biscara_dynamics::DynamicsError) -> Failure {
        Failure::of(&err, None)
    }
}

impl From<biscara_pipeline::PipelineError> for Failure {
    fn from(err: biscara_pipeline::PipelineError) -> Failure {
        let mut message = chain(&err);
        for hint in err.hints() {
            // A hint is its own parenthesised sentence.
            message.push_str(&format!("\n    {hint}"));
        }
        Failure::message_in(message, err.file())
    }
}

/// The message of `err` followed by those of its causes not already at its end.
fn chain(err: &(dyn StdError + 'static)) -> String {
    let mut message = err.to_string();
    let mut cause = err.source();
    while let Some(next) = cause {
        let text = next.to_string();
        if !message.ends_with(&text) {
            message.push_str(": ");
            message.push_str(&text);
        }
        cause = next.source();
    }
    message
}

/// The `LINE` and `COL` of a message that goes on `LINE[:COL]:` (after its file name).
fn position(rest: &str) -> (Option<usize>, Option<usize>) {
    let number = |text: &str| -> Option<(usize, usize)> {
        let digits = text.bytes().take_while(u8::is_ascii_digit).count();
        let value = text[..digits].parse().ok()?;
        text[digits..].starts_with(':').then_some((value, digits + 1))
    };
    let Some((line, used)) = number(rest) else { return (None, None) };
    (Some(line), number(&rest[used..]).map(|(column, _)| column))
}

/// Checks for a pending signal (Ctrl-C raises KeyboardInterrupt), taking the GIL for it.
pub(crate) fn check_signals() -> Result<(), Failure> {
    Python::attach(|py| py.check_signals()).map_err(Failure::Python)
}
