//! A program's motions: the G-code interpreter or the inter-file reader, errors located, and
//! what the interpreter has to say (the dialect it chose, the codes it recorded) as notes.

use std::cell::{Cell, RefCell};
use std::io::BufRead;
use std::rc::Rc;
use std::sync::Arc;

use std::path::{Path, PathBuf};

use biscara_gcode::{
    Config as GcodeConfig, Dialect, Forward, GcodeError, IniFile, Interpreter, Seekable, Tool,
    ToolTable, interpret_seekable,
};
use biscara_kinematics::RobotModel;
use biscara_motion::{Motion, MotionKind, Position, read_jsonl};

use crate::{Hint, Note, PipelineError, ProgramKind, ProgramSource, SamplingConfig};

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
/// dialect, its tool (`None`: inferred from the program, the gripper when nothing tells), where
/// its file subroutines are, the tool table, the INI file and the default G64 P.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Reading<'a> {
    pub(crate) origin: Position,
    pub(crate) start: Option<Position>,
    pub(crate) dialect: Dialect,
    pub(crate) tool: Option<Tool>,
    pub(crate) subroutine_path: &'a [PathBuf],
    pub(crate) tool_table: Option<&'a Arc<ToolTable>>,
    pub(crate) ini: Option<&'a Arc<IniFile>>,
    /// The G64 P of a program that never says G61 or G64.
    pub(crate) blend: Option<f64>,
    /// Jumps back allowed without a motion (endless loops).
    pub(crate) max_idle_jumps: u64,
    /// Motions allowed in one run (programs that never end).
    pub(crate) max_motions: u64,
}

impl<'a> Reading<'a> {
    /// How `config` says G-code is read, from `origin` and `start`, with `tool`.
    pub(crate) fn of(
        config: &'a SamplingConfig,
        origin: Position,
        start: Option<Position>,
        tool: Option<Tool>,
    ) -> Self {
        Reading {
            origin,
            start,
            dialect: config.dialect,
            tool,
            subroutine_path: &config.subroutine_path,
            tool_table: config.tool_table.as_ref(),
            ini: config.ini.as_ref(),
            blend: config.blend,
            max_idle_jumps: config.max_idle_jumps,
            max_motions: config.max_motions,
        }
    }
}

/// What a G-code reading tells besides its motions: the axes the program zeroed with G92 before
/// its first motion, once it is read (see [`Interpreter::zeroed_at_start`]), and the tool it
/// drives, from its first motion on.
#[derive(Default, Clone)]
pub(crate) struct Told {
    pub(crate) zeroed: Option<Rc<Cell<[bool; 4]>>>,
    pub(crate) tool: Option<Rc<Cell<Option<Tool>>>>,
}

/// The motions of a G-code program (read as `reading` says) or an inter-file; what the G-code
/// reading tells goes to `told`.
pub(crate) fn read_motions(
    model: &RobotModel,
    source: &dyn ProgramSource,
    kind: ProgramKind,
    reading: &Reading<'_>,
    notes: NoteSink,
    told: Told,
) -> Result<MotionReader, PipelineError> {
    let Reading { origin, start, dialect, tool, .. } = *reading;
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
                start,
                dialect,
                tool: tool.unwrap_or_default(),
                infer_tool: tool.is_none(),
                tool_table: reading.tool_table.cloned(),
                ini: reading.ini.cloned(),
                blend: reading.blend,
                max_idle_jumps: reading.max_idle_jumps,
                max_motions: reading.max_motions,
                ..GcodeConfig::default()
            };
            // A file is read with jumps (O-word loops and calls); standard input only forwards.
            let input: Box<dyn Seekable> = match source.open_seekable().map_err(io_error)? {
                Some(input) => input,
                None => Box::new(Forward(source.open().map_err(io_error)?)),
            };
            let interpreter = interpret_seekable(input, &config)
                .with_subroutines(
                    source.path().map(Path::to_path_buf),
                    reading.subroutine_path.to_vec(),
                )
                .with_environment(source.environment());
            Ok(Box::new(GcodeMotions {
                interpreter,
                file,
                notes,
                told,
                started: false,
                tool_said: false,
                finished: false,
            }))
        }
        ProgramKind::Path => {
            Err(PipelineError::unsupported(&file, "a path CSV holds samples, not motions"))
        }
    }
}

/// The interpreter's motions, errors located; at the end, the dialect `auto` chose and the
/// no-motion codes it recorded go to the notes.
struct GcodeMotions<R> {
    interpreter: Interpreter<R>,
    file: String,
    notes: NoteSink,
    told: Told,
    started: bool,
    tool_said: bool,
    finished: bool,
}

impl<R: BufRead> GcodeMotions<R> {
    /// The error, located (in the program, or in the file subroutine whose line it is), with
    /// the line and a caret, and with the dialect `auto` chose when it is not LinuxCNC's (the
    /// error may be the dialect's, not the program's).
    fn located(&self, err: GcodeError) -> PipelineError {
        let snippet = err.location().map(|location| location.snippet());
        // The library says what is wrong; the caller words the setting that helps.
        let mut hints: Vec<Hint> = err.setting().and_then(Hint::for_setting).into_iter().collect();
        if let Some(detection) =
            self.interpreter.detection().filter(|d| d.dialect != Dialect::Linuxcnc)
        {
            hints.push(Hint::DialectDetected(detection));
        }
        // An error in a file subroutine names that file, not the program.
        let file = err.location().and_then(|location| location.file.as_deref());
        let file = file.map_or_else(|| self.file.clone(), str::to_owned);
        PipelineError::Program { file, error: Box::new(err), snippet, hints }
    }

    /// The tool inferred, once.
    fn say_tool(&mut self) {
        if self.tool_said {
            return;
        }
        self.tool_said = true;
        if let Some(inference) = self.interpreter.tool_inference() {
            let (file, inference) = (self.file.clone(), inference.clone());
            self.notes.say(Note::Tool { file, inference });
        }
    }

    /// The notes of a finished program.
    fn announce(&mut self) {
        self.say_tool();
        if let Some(zeroed) = &self.told.zeroed {
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
        if self.interpreter.tools_without_table() {
            self.notes.say(Note::ToolsWithoutTable { file: self.file.clone() });
        }
        let summary = self.interpreter.summary();
        if !summary.codes.is_empty() {
            self.notes.say(Note::Codes { file: self.file.clone(), codes: summary.codes.clone() });
        }
        if !summary.probes.is_empty() {
            let (file, dialect) = (self.file.clone(), self.interpreter.dialect());
            self.notes.say(Note::Probes { file, dialect, codes: summary.probes.clone() });
        }
        if !summary.unknown.is_empty() {
            let (file, dialect) = (self.file.clone(), self.interpreter.dialect());
            self.notes.say(Note::UnknownCodes { file, dialect, codes: summary.unknown.clone() });
        }
        if !summary.adapted.is_empty() {
            let (file, dialect) = (self.file.clone(), self.interpreter.dialect());
            let codes = summary.adapted.clone();
            self.notes.say(Note::Adapted { file, dialect, codes });
        }
        if !summary.refused_by_firmware.is_empty() {
            let (file, dialect) = (self.file.clone(), self.interpreter.dialect());
            let codes = summary.refused_by_firmware.clone();
            self.notes.say(Note::RefusedByFirmware { file, dialect, codes });
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
            Some(Ok(motion)) => {
                if !self.started {
                    self.started = true;
                    if let Some(tool) = &self.told.tool {
                        tool.set(Some(self.interpreter.tool()));
                    }
                }
                // Said at the program's end (M2 or M30: the interpolator may read no further),
                // so that an error stays the only message of a program that fails.
                if matches!(motion.kind, MotionKind::End) {
                    self.say_tool();
                }
                Some(Ok(motion))
            }
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
