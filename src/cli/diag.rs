//! Diagnostics on stderr: notes and warnings go through here, one line each, prefixed once.

use std::fmt::Display;
use std::io::Write as _;
use std::path::Path;

use biscara::pipeline::{Hint, Note, PipelineError};
use biscara::post::PostError;
use biscara_files::display_path;

/// How a diagnostic is labelled.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Level {
    /// Information: what was chosen or adjusted.
    Note,
    /// Something the user should look at; the command still succeeds.
    Warning,
}

/// Prints `biscara: note: …` or `biscara: warning: …` on stderr (a closed stderr is not an
/// error: the note is lost, the command goes on).
pub(crate) fn report(level: Level, message: impl Display) {
    let label = match level {
        Level::Note => "note",
        Level::Warning => "warning",
    };
    let _ = writeln!(std::io::stderr(), "biscara: {label}: {message}");
}

/// The error's message as the command line shows it: the library's message with its causes
/// (`what: why`, a cause left out where the message already ends with it, as an error that
/// names a file and its I/O error does), then each hint of a pipeline error on a line of its
/// own, worded with this command line's flags.
pub(crate) fn error_message(err: &anyhow::Error) -> String {
    let mut message = err.to_string();
    for cause in err.chain().skip(1) {
        let cause = cause.to_string();
        if !message.ends_with(&cause) {
            message.push_str(": ");
            message.push_str(&cause);
        }
    }
    let hints = err.chain().find_map(|cause| cause.downcast_ref::<PipelineError>());
    for hint in hints.map(PipelineError::hints).unwrap_or_default() {
        message.push_str("\n    ");
        message.push_str(&hint_text(hint));
    }
    message
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

/// An error of a reader whose `Display` starts with `LINE[:COL]:`, located in `path`: the one
/// place the binary prefixes a file name.
pub(crate) fn located(path: &Path, err: impl Display) -> anyhow::Error {
    anyhow::anyhow!("{}:{err}", display_path(path))
}

/// A postprocessor error, as `CL_FILE:LINE: …` when it has a line.
pub(crate) fn post_error(path: &Path, err: PostError) -> anyhow::Error {
    if err.line().is_some() { located(path, err) } else { anyhow::Error::from(err) }
}

/// Most slowed motions listed one by one; past it only their count is printed, at the end.
const SLOWED_SHOWN: usize = 20;

/// Reports the pipeline's notes: slowed motions one by one up to [`SLOWED_SHOWN`], then counted
/// ([`NoteReporter::finish`] prints the total).
#[derive(Debug, Default)]
pub(crate) struct NoteReporter {
    slowed: std::rc::Rc<std::cell::Cell<usize>>,
}

impl NoteReporter {
    /// A function the pipeline calls with each note.
    pub(crate) fn sink(&self) -> impl FnMut(Note) + use<> {
        let slowed = std::rc::Rc::clone(&self.slowed);
        move |note| {
            if let Note::SlowedDown { .. } = note {
                slowed.set(slowed.get() + 1);
                if slowed.get() > SLOWED_SHOWN {
                    return;
                }
            }
            report(Level::Note, note);
        }
    }

    /// Prints how many motions were slowed when not all were listed.
    pub(crate) fn finish(self) {
        let count = self.slowed.get();
        if count > SLOWED_SHOWN {
            report(Level::Note, format_args!("{count} motions slowed in all"));
        }
    }
}
