//! A program's motions: the G-code interpreter or the inter-file reader, errors located, and
//! what the interpreter has to say (the dialect it chose, the codes it recorded) as notes.

use std::cell::{Cell, RefCell};
use std::io::BufRead;
use std::rc::Rc;

use biscara_gcode::{Config as GcodeConfig, Dialect, GcodeError, Interpreter, Tool, interpret};
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

/// How a G-code program is read: its G54 offset, where it starts (`None`: the home pose), its
/// dialect and its tool (`None`: inferred from the program, the gripper when nothing tells).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Reading {
    pub(crate) origin: Position,
    pub(crate) start: Option<Position>,
    pub(crate) dialect: Dialect,
    pub(crate) tool: Option<Tool>,
}

/// Where the axes a G-code program zeroed with G92 before its first motion are told, once the
/// program is read (see [`Interpreter::zeroed_at_start`]).
pub(crate) type Zeroed = Rc<Cell<[bool; 4]>>;

/// The motions of a G-code program (read as `reading` says) or an inter-file; with `zeroed`, the
/// axes the program zeroed with G92 at its start are stored there at its end.
pub(crate) fn read_motions(
    model: &RobotModel,
    source: &dyn ProgramSource,
    kind: ProgramKind,
    reading: Reading,
    notes: NoteSink,
    zeroed: Option<Zeroed>,
) -> Result<MotionReader, PipelineError> {
    let Reading { origin, start, dialect, tool } = reading;
    let file = source.name().to_owned();
    let input = source.open().map_err(|source| PipelineError::Io { file: file.clone(), source })?;
    match kind {
        ProgramKind::Jsonl => Ok(Box::new(
            read_jsonl(input)
                .map(move |result| result.map_err(|err| PipelineError::program(&file, err))),
        )),
        ProgramKind::Gcode => {
            let config = GcodeConfig {
                home: model.home_position(),
                origin,
                start,
                dialect,
                tool: tool.unwrap_or_default(),
                infer_tool: tool.is_none(),
                ..GcodeConfig::default()
            };
            let interpreter = interpret(input, &config);
            Ok(Box::new(GcodeMotions { interpreter, file, notes, zeroed, finished: false }))
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
    zeroed: Option<Zeroed>,
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
        if let Some(zeroed) = &self.zeroed {
            zeroed.set(self.interpreter.zeroed_at_start());
        }
        // A program in which nothing tells the dialects apart is LinuxCNC's, as before the
        // dialects existed: no note.
        if let Some(detection) = self
            .interpreter
            .detection()
            .filter(|detection| detection.dialect != Dialect::Linuxcnc || detection.line.is_some())
        {
            self.notes.say(Note::Dialect { file: self.file.clone(), detection });
        }
        if let Some(inference) = self.interpreter.tool_inference() {
            let (file, inference) = (self.file.clone(), inference.clone());
            self.notes.say(Note::Tool { file, inference });
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
