//! The command line's diagnostics on stderr: notes and warnings, one line each, prefixed once;
//! the text of an error with its causes and the pipeline's hints worded with the command line's
//! flags; errors located in a file.

use std::error::Error;
use std::fmt::Display;
use std::io::{self, Write as _};
use std::path::Path;

use biscara_pipeline::{Hint, Note, PipelineError};

use crate::{FileError, display_path};

/// How a diagnostic is labelled.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Level {
    /// Information: what was chosen or adjusted.
    Note,
    /// Something the user should look at; the command still succeeds.
    Warning,
}

/// Prints `biscara: note: …` or `biscara: warning: …` on stderr (a closed stderr is not an
/// error: the note is lost, the command goes on).
pub fn report(level: Level, message: impl Display) {
    let _ = writeln!(io::stderr(), "{}", diagnostic(level, message));
}

/// The line [`report`] prints, without its line end.
fn diagnostic(level: Level, message: impl Display) -> String {
    let label = match level {
        Level::Note => "note",
        Level::Warning => "warning",
    };
    format!("biscara: {label}: {message}")
}

/// The error's message as the command line shows it: the error's message with its causes
/// (`what: why`, a cause left out where the message already ends with it, as an error that
/// names a file and its I/O error does), then each hint of a pipeline error on a line of its
/// own, worded with the command line's flags.
pub fn error_message(err: &(dyn Error + 'static)) -> String {
    let mut message = err.to_string();
    for cause in causes(err).skip(1) {
        let cause = cause.to_string();
        if !message.ends_with(&cause) {
            message.push_str(": ");
            message.push_str(&cause);
        }
    }
    let hints = causes(err).find_map(|cause| cause.downcast_ref::<PipelineError>());
    for hint in hints.map(PipelineError::hints).unwrap_or_default() {
        message.push_str("\n    ");
        message.push_str(&hint_text(hint));
    }
    message
}

/// Whether the error is a closed pipe on output (`biscara joints … | head`): a success.
pub fn is_broken_pipe(err: &(dyn Error + 'static)) -> bool {
    causes(err).any(|cause| {
        cause.downcast_ref::<io::Error>().is_some_and(|io| io.kind() == io::ErrorKind::BrokenPipe)
    })
}

/// The error and its sources, outermost first.
fn causes<'a>(err: &'a (dyn Error + 'static)) -> impl Iterator<Item = &'a (dyn Error + 'static)> {
    std::iter::successors(Some(err), |&cause| cause.source())
}

/// A pipeline hint in terms of the flags that change it.
fn hint_text(hint: &Hint) -> String {
    match hint {
        Hint::MoreIdleJumps => {
            "(--max-idle-jumps N allows more, for a loop that computes long)".to_owned()
        }
        Hint::MoreMotions => "(--max-motions N allows more, for a program that long)".to_owned(),
        Hint::MoreTime => "(--time-limit SECONDS allows more, for a program that long)".to_owned(),
        Hint::DialectDetected(detection) => format!(
            "(read as {} G-code by --dialect auto: {}; give --dialect to choose another)",
            detection.dialect, detection.reason
        ),
        Hint::PlaceByOrigin => "(place it with --origin instead of --fit)".to_owned(),
        Hint::DoNotFit => "(run it without --fit)".to_owned(),
        Hint::GiveIni => "(--ini FILE gives the INI file)".to_owned(),
        Hint::AddSubroutineFolder => {
            "(--subroutine-path DIR adds a folder file subroutines are found in)".to_owned()
        }
        other => other.to_string(),
    }
}

/// An error of a reader whose `Display` starts with `LINE[:COL]:`, located in `path`
/// (`FILE:LINE[:COL]: …`): the one place a file name is prefixed to a reader's error.
pub fn located(path: &Path, err: impl Display) -> FileError {
    FileError::Located { path: display_path(path), message: err.to_string() }
}

/// `err` located in `path` when it has a `line` (its `Display` then starts with it), else as it
/// is.
pub fn located_at<E: Error + Send + Sync + 'static>(
    path: &Path,
    line: Option<usize>,
    err: E,
) -> FileError {
    match line {
        Some(_) => located(path, err),
        None => FileError::Other(Box::new(err)),
    }
}

/// Most slowed motions listed one by one; past it only their count is printed, at the end.
const SLOWED_SHOWN: usize = 20;

/// Reports the pipeline's notes: slowed motions one by one up to 20, then counted
/// ([`NoteReporter::finish`] prints the total).
#[derive(Debug, Default)]
pub struct NoteReporter {
    slowed: std::rc::Rc<std::cell::Cell<usize>>,
}

impl NoteReporter {
    /// A function the pipeline calls with each note.
    pub fn sink(&self) -> impl FnMut(Note) + use<> {
        let slowed = std::rc::Rc::clone(&self.slowed);
        move |note| {
            if shown(&slowed, matches!(note, Note::SlowedDown { .. })) {
                report(Level::Note, note);
            }
        }
    }

    /// Prints how many motions were slowed when not all were listed.
    pub fn finish(self) {
        if let Some(total) = slowed_total(self.slowed.get()) {
            report(Level::Note, total);
        }
    }
}

/// Whether a note is printed, counting in `slowed` the slowed motions (`is_slowed`).
fn shown(slowed: &std::cell::Cell<usize>, is_slowed: bool) -> bool {
    if is_slowed {
        slowed.set(slowed.get() + 1);
        return slowed.get() <= SLOWED_SHOWN;
    }
    true
}

/// The closing note for `count` slowed motions, when not all of them were listed.
fn slowed_total(count: usize) -> Option<String> {
    (count > SLOWED_SHOWN).then(|| format!("{count} motions slowed in all"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, thiserror::Error)]
    #[error("cannot read job.ngc: {0}")]
    struct Outer(#[source] io::Error);

    #[test]
    fn a_cause_is_added_once() {
        let err = Outer(io::Error::new(io::ErrorKind::NotFound, "no such file"));
        assert_eq!(error_message(&err), "cannot read job.ngc: no such file");
        let err =
            FileError::Write { path: "out.csv".to_owned(), source: io::Error::other("disk full") };
        assert_eq!(error_message(&err), "cannot write out.csv: disk full");
        assert!(!is_broken_pipe(&err));
        let pipe = Outer(io::Error::new(io::ErrorKind::BrokenPipe, "closed"));
        assert!(is_broken_pipe(&pipe));
    }

    #[test]
    fn located_errors_name_the_file() {
        assert_eq!(located(Path::new("-"), "3:5: bad").to_string(), "<stdin>:3:5: bad");
        let err = io::Error::other("12: a fault");
        assert_eq!(located_at(Path::new("a.cl"), Some(12), err).to_string(), "a.cl:12: a fault");
        let err = io::Error::other("empty");
        assert_eq!(located_at(Path::new("a.cl"), None, err).to_string(), "empty");
    }

    #[test]
    fn hints_name_the_flags() {
        assert_eq!(hint_text(&Hint::DoNotFit), "(run it without --fit)");
        assert_eq!(
            hint_text(&Hint::MoreTime),
            "(--time-limit SECONDS allows more, for a program that long)"
        );
    }

    #[test]
    fn slowed_motions_are_listed_up_to_a_bound_then_counted() {
        let slowed = std::cell::Cell::new(0);
        let printed = (0..25).filter(|_| shown(&slowed, true)).count();
        assert_eq!(printed, SLOWED_SHOWN);
        assert!(shown(&slowed, false), "other notes are always shown");
        assert_eq!(slowed_total(slowed.get()).as_deref(), Some("25 motions slowed in all"));
        assert_eq!(slowed_total(SLOWED_SHOWN), None);
        assert_eq!(diagnostic(Level::Warning, "x"), "biscara: warning: x");
    }
}
