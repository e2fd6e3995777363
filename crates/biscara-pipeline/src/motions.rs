//! A program's motions: the G-code interpreter or the inter-file reader, errors located, and
//! what the interpreter has to say (the dialect it chose, the codes it recorded) as notes.

use std::cell::RefCell;
use std::io::BufRead;
use std::rc::Rc;

use std::path::{Path, PathBuf};

use biscara_gcode::{
    Config as GcodeConfig, Dialect, Forward, GcodeError, Interpreter, Seekable, interpret_seekable,
};
use biscara_kinematics::RobotModel;
use biscara_motion::{Motion, Position, read_jsonl};

use crate::{Note, PipelineError, ProgramKind, ProgramSource};

/// A program's motions as read, with errors located in the file.
pub(crate) type MotionReader = Box<dyn Iterator<Item = Result<Motion, PipelineError>>>;

/// Where notes go: the caller's function, shared by the stages that speak (the interpreter's
/// wrapper and the interpolator's slow-down callback).
#[derive(Clone)]
pub(crate) struct NoteSink(Option<SharedNotes>);

/// The caller's note function, shared.
type SharedNotes = Rc<RefCell<dyn FnMut(Note)>>;

impl NoteSink {
    /// The caller's function.
    pub(crate) fn new(notes: impl FnMut(Note) + 'static) -> NoteSink {
        NoteSink(Some(Rc::new(RefCell::new(notes))))
    }

    /// Nowhere: for a second reading of the same program (`--fit`'s extent).
    pub(crate) fn silent() -> NoteSink {
        NoteSink(None)
    }

    /// Tells the caller.
    pub(crate) fn say(&self, note: Note) {
        if let Some(notes) = &self.0 {
            (notes.borrow_mut())(note);
        }
    }
}

/// How a G-code program is read: its dialect and where its file subroutines are.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Reading<'a> {
    pub dialect: Dialect,
    pub subroutine_path: &'a [PathBuf],
    /// The G64 P of a program that never says G61 or G64.
    pub blend: Option<f64>,
}

/// The motions of a G-code program (read as `reading` says, with `origin` as its G54 offset)
/// or an inter-file.
pub(crate) fn read_motions(
    model: &RobotModel,
    source: &dyn ProgramSource,
    kind: ProgramKind,
    origin: Position,
    reading: &Reading<'_>,
    notes: NoteSink,
) -> Result<MotionReader, PipelineError> {
    let file = source.name().to_owned();
    let io_error = |source| PipelineError::Io { file: file.clone(), source };
    match kind {
        ProgramKind::Jsonl => Ok(Box::new(
            read_jsonl(source.open().map_err(io_error)?)
                .map(move |result| result.map_err(|err| PipelineError::program(&file, err))),
        )),
        ProgramKind::Gcode => {
            let config = GcodeConfig {
                home: model.home_position(),
                origin,
                dialect: reading.dialect,
                blend: reading.blend,
                ..GcodeConfig::default()
            };
            // A file is read with jumps (O-word loops and calls); standard input only forwards.
            let input: Box<dyn Seekable> = match source.open_seekable().map_err(io_error)? {
                Some(input) => input,
                None => Box::new(Forward(source.open().map_err(io_error)?)),
            };
            let interpreter = interpret_seekable(input, &config).with_subroutines(
                source.path().map(Path::to_path_buf),
                reading.subroutine_path.to_vec(),
            );
            Ok(Box::new(GcodeMotions { interpreter, file, notes, finished: false }))
        }
        ProgramKind::Path => Err(PipelineError::Unsupported {
            file,
            message: "a path CSV holds samples, not motions".to_owned(),
        }),
    }
}

/// The interpreter's motions, errors located; at the end, the dialect `auto` chose and the
/// no-motion codes it recorded go to the notes.
struct GcodeMotions<R> {
    interpreter: Interpreter<R>,
    file: String,
    notes: NoteSink,
    finished: bool,
}

impl<R: BufRead> GcodeMotions<R> {
    /// The error, located, with the line and a caret, and with the dialect `auto` chose when it
    /// is not LinuxCNC's (the error may be the dialect's, not the program's).
    fn located(&self, err: GcodeError) -> PipelineError {
        let mut snippet = err.location().map(|location| location.snippet());
        if let Some(detection) =
            self.interpreter.detection().filter(|d| d.dialect != Dialect::Linuxcnc)
        {
            let why = format!(
                "(read as {} G-code by --dialect auto: {}; give --dialect to choose another)",
                detection.dialect, detection.reason
            );
            snippet = Some(match snippet {
                Some(snippet) => format!("{snippet}\n{why}"),
                None => why,
            });
        }
        PipelineError::Program { file: self.file.clone(), error: Box::new(err), snippet }
    }

    /// The notes of a finished program.
    fn announce(&self) {
        // A program in which nothing tells the dialects apart is LinuxCNC's, as before the
        // dialects existed: no note.
        if let Some(detection) = self
            .interpreter
            .detection()
            .filter(|detection| detection.dialect != Dialect::Linuxcnc || detection.line.is_some())
        {
            self.notes.say(Note::Dialect { file: self.file.clone(), detection });
        }
        let summary = self.interpreter.summary();
        if !summary.codes.is_empty() {
            self.notes.say(Note::Codes { file: self.file.clone(), codes: summary.codes.clone() });
        }
        if !summary.unknown.is_empty() {
            let (file, dialect) = (self.file.clone(), self.interpreter.dialect());
            self.notes.say(Note::UnknownCodes { file, dialect, codes: summary.unknown.clone() });
        }
    }
}

impl<R: BufRead> Iterator for GcodeMotions<R> {
    type Item = Result<Motion, PipelineError>;

    #[inline]
    fn next(&mut self) -> Option<Self::Item> {
        if self.finished {
            return None;
        }
        match self.interpreter.next() {
            Some(Ok(motion)) => Some(Ok(motion)),
            Some(Err(err)) => {
                self.finished = true;
                Some(Err(self.located(err)))
            }
            None => {
                self.finished = true;
                self.announce();
                None
            }
        }
    }
}
