//! O-word control flow (docs/gcode.md tier 3) as LinuxCNC's rs274 runs it — `read_o`,
//! `convert_control_functions`, `control_back_to`, `execute_call`, `execute_return` — with
//! its quirks: one global "skipping to" label, labels remembered by name (`sub#label` for
//! the local ones), conditions not evaluated while skipping, #1–#30 saved and restored around
//! a call, ten call levels, and its error messages word for word.
//!
//! Nothing of the program is held: a jump goes back to the byte offset of a line (remembered
//! when the line was passed) and reads it again; a label not yet seen is found by reading on.
//! File subroutines (`o<name> call` of a name not defined so far) are opened as LinuxCNC opens
//! them, `NAME.ngc`, beside the program or in the `--subroutine-path` folders. A program read
//! only forwards (standard input) cannot jump: the error says so. A line that is not an O-word
//! line costs one look at its first letter (`may_control`).

use std::collections::HashMap;
use std::io::BufRead;
use std::path::{Path, PathBuf};
use std::rc::Rc;
use std::sync::Arc;

use super::{Interpreter, round_to_int};

/// Reading O-word lines, M98/M99 and G65 (`read_o`).
mod read;
use crate::environment::{Environment, NoEnvironment};
use crate::error::GcodeError;
use crate::error::Setting;
use crate::syntax::lexer::{Fault, FaultKind};
use crate::syntax::parser::Reader;
pub(super) use read::{first_item, may_call_g65, may_control};

/// LinuxCNC's `INTERP_SUB_PARAMS`: a call's arguments are #1 … #30.
const SUB_PARAMS: usize = 30;
/// LinuxCNC's `INTERP_SUB_ROUTINE_LEVELS`: call levels, the main program's included.
const SUB_LEVELS: usize = 10;

/// The kinds of O-word lines (LinuxCNC's `o_type`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum OType {
    None,
    Sub,
    EndSub,
    Call,
    Do,
    While,
    If,
    ElseIf,
    Else,
    EndIf,
    Break,
    Continue,
    EndWhile,
    Return,
    Repeat,
    EndRepeat,
    M98,
    M99,
    /// A bare `O1234` line: a Fanuc-style program or subprogram number.
    Fanuc,
}

impl OType {
    /// How LinuxCNC names the kind in its messages (`o_ops[type] + 2`).
    fn name(self) -> &'static str {
        match self {
            OType::None => "none",
            OType::Sub => "sub",
            OType::EndSub => "endsub",
            OType::Call => "call",
            OType::Do => "do",
            OType::While => "while",
            OType::If => "if",
            OType::ElseIf => "elseif",
            OType::Else => "else",
            OType::EndIf => "endif",
            OType::Break => "break",
            OType::Continue => "continue",
            OType::EndWhile => "endwhile",
            OType::Return => "return",
            OType::Repeat => "repeat",
            OType::EndRepeat => "endrepeat",
            OType::M98 => "98",
            OType::M99 => "99",
            OType::Fanuc => "",
        }
    }
}

/// The keywords after an O-word's label, in the order LinuxCNC tries them (as prefixes).
const KEYWORDS: [(&[u8], OType); 15] = [
    (b"sub", OType::Sub),
    (b"endsub", OType::EndSub),
    (b"call", OType::Call),
    (b"do", OType::Do),
    (b"while", OType::While),
    (b"repeat", OType::Repeat),
    (b"if", OType::If),
    (b"elseif", OType::ElseIf),
    (b"else", OType::Else),
    (b"endif", OType::EndIf),
    (b"break", OType::Break),
    (b"continue", OType::Continue),
    (b"endwhile", OType::EndWhile),
    (b"endrepeat", OType::EndRepeat),
    (b"return", OType::Return),
];

/// How a call frame was entered.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum CallType {
    /// The main program.
    None,
    /// `o… call`.
    Oword,
    /// `M98 P…`.
    M98,
    /// Mach4's `G65 P… A… B…` (Fanuc's macro call): an `M98` call whose letters become the
    /// subprogram's own #1… (A #1, B #2, C #3, I #4, J #5, K #6, D #7, …, Z #26).
    G65,
}

/// Where a label was seen (LinuxCNC's `offset_map` entry).
#[derive(Debug, Clone)]
struct Label {
    kind: OType,
    /// Byte offset of the label's line.
    offset: u64,
    /// The file subroutine it is in (`None`: the main program).
    file: Option<Rc<Path>>,
    /// Its 1-based line number.
    line: usize,
    /// A `repeat`'s remaining count (−1: not started).
    repeat_count: i64,
}

/// A call level (LinuxCNC's `sub_context` entry).
#[derive(Debug)]
struct Frame {
    name: Option<Rc<str>>,
    call_type: CallType,
    /// The caller's #1 … #30, restored on return.
    saved_params: [f64; SUB_PARAMS],
    /// Where to return: byte offset, file, line number of the call.
    position: u64,
    file: Option<Rc<Path>>,
    line: usize,
    /// This level's local named parameters while a deeper level runs.
    locals: HashMap<Vec<u8>, f64>,
    /// `M98 … L`: the repeats left.
    m98_loop_counter: i64,
    /// This level's M70/M73 state while a deeper level runs.
    modes: super::modal_state::ModalStack,
}

impl Frame {
    fn new(name: Option<Rc<str>>, call_type: CallType) -> Frame {
        Frame {
            name,
            call_type,
            saved_params: [0.0; SUB_PARAMS],
            position: 0,
            file: None,
            line: 0,
            locals: HashMap::new(),
            m98_loop_counter: -1,
            modes: super::modal_state::ModalStack::default(),
        }
    }
}

/// What `#<_value>`, `#<_value_returned>` and `#<_call_level>` read.
#[derive(Debug, Default, Clone, Copy)]
pub(super) struct Values {
    /// The last `endsub [value]` or `return [value]` (0 when none was given).
    pub value: f64,
    /// Whether the last return gave a value.
    pub returned: bool,
    /// The call level (0 in the main program).
    pub level: usize,
    /// Whether a subroutine definition is being passed over.
    pub defining: bool,
}

/// The control-flow state (LinuxCNC's `skipping_o`, `offset_map`, `sub_context`, …).
#[derive(Debug)]
pub(super) struct Control {
    labels: HashMap<Rc<str>, Label>,
    skipping_o: Option<Rc<str>>,
    skipping_to_sub: Option<Rc<str>>,
    skipping_start: usize,
    /// The text of the line that began reading on to a subroutine in its own file (where one
    /// not found is reported).
    skipping_call: Option<Box<[u8]>>,
    defining_sub: bool,
    sub_name: Option<Rc<str>>,
    executed_if: bool,
    doing_break: bool,
    doing_continue: bool,
    frames: Vec<Frame>,
    test_value: f64,
    /// The file subroutine being read (`None`: the main program).
    pub(super) file: Option<Rc<Path>>,
    /// The program's path, for messages and to find file subroutines beside it.
    program: Option<PathBuf>,
    /// `--subroutine-path` folders.
    dirs: Vec<PathBuf>,
    /// Where files are found and opened, and Python started.
    pub(super) environment: Arc<dyn Environment>,
    /// The INI file's `[RS274NGC] SUBROUTINE_PATH` folders, after `dirs`.
    ini_dirs: Vec<PathBuf>,
    /// Where the user M-codes' programs are (`USER_M_PATH`, `PROGRAM_PREFIX`), when the INI
    /// file says.
    user_m_dirs: Option<Vec<PathBuf>>,
    /// The loops of the main program being run (for an input read only forwards, whose lines
    /// are kept while a loop runs).
    open_loops: Vec<Rc<str>>,
    /// Whether the lines of an input read only forwards are being kept (`Some(true)`: for good).
    recording: Option<bool>,
    /// How many jumps back are allowed without a motion.
    max_idle_jumps: u64,
    /// A call in the main program reads on to find its subroutine: the lines from the call on
    /// are kept (an input read only forwards), to come back to.
    forward: bool,
    /// The state at the last jump back from each line (loops that can only repeat).
    visits: super::endless::Visits,
}

impl Default for Control {
    fn default() -> Control {
        Control {
            labels: HashMap::new(),
            skipping_o: None,
            skipping_to_sub: None,
            skipping_start: 0,
            skipping_call: None,
            defining_sub: false,
            sub_name: None,
            executed_if: false,
            doing_break: false,
            doing_continue: false,
            frames: vec![Frame::new(None, CallType::None)],
            test_value: 0.0,
            file: None,
            program: None,
            dirs: Vec::new(),
            environment: Arc::new(NoEnvironment),
            ini_dirs: Vec::new(),
            user_m_dirs: None,
            open_loops: Vec::new(),
            recording: None,
            max_idle_jumps: crate::MAX_IDLE_JUMPS,
            forward: false,
            visits: super::endless::Visits::default(),
        }
    }
}

impl Control {
    /// Where the user M-codes' programs are, when the INI file says.
    pub(super) fn user_m_dirs(&self) -> Option<&[PathBuf]> {
        self.user_m_dirs.as_deref()
    }

    /// The state before the first line, with the folders the INI file `ini` names and
    /// `max_idle_jumps` jumps back allowed without a motion.
    pub(super) fn new(ini: Option<&crate::IniFile>, max_idle_jumps: u64) -> Control {
        Control {
            ini_dirs: ini.map(crate::IniFile::subroutine_dirs).unwrap_or_default(),
            user_m_dirs: ini.and_then(crate::IniFile::user_m_dirs),
            max_idle_jumps,
            ..Control::default()
        }
    }

    /// The program's path, when the caller gave it.
    pub(super) fn program(&self) -> Option<&Path> {
        self.program.as_deref()
    }

    /// Whether lines are being skipped (then every line goes through the control flow).
    pub(super) fn engaged(&self) -> bool {
        self.skipping_o.is_some() || self.skipping_to_sub.is_some()
    }

    /// The name LinuxCNC gives the file being read, in messages.
    pub(super) fn file_name(&self) -> String {
        match (&self.file, &self.program) {
            (Some(file), _) => file.display().to_string(),
            (None, Some(program)) => program.display().to_string(),
            (None, None) => "<stdin>".to_owned(),
        }
    }

    /// Whether lines are skipped to the label `name`.
    fn skipping_to(&self, name: &str) -> bool {
        self.skipping_o.as_deref() == Some(name)
    }

    fn level(&self) -> usize {
        self.frames.len() - 1
    }

    /// The control flow's state, written out for [`super::endless::Visits`]: all of it but
    /// the labels' places (only their count and the `repeat` counts, which change as loops
    /// turn) and what only finds files.
    fn write_state(&self, out: &mut String) {
        use std::fmt::Write as _;
        let mut repeats: Vec<(usize, i64)> = self
            .labels
            .values()
            .filter(|label| label.kind == OType::Repeat)
            .map(|label| (label.line, label.repeat_count))
            .collect();
        repeats.sort_unstable();
        let _ = write!(
            out,
            "{:?}",
            (
                (&self.skipping_o, &self.skipping_to_sub, self.skipping_start, self.defining_sub),
                (&self.sub_name, self.executed_if, self.doing_break, self.doing_continue),
                (&self.frames, self.test_value, &self.file, &self.open_loops, self.recording),
                (self.forward, self.labels.len(), repeats),
            )
        );
    }
}

/// One O-word line, read.
#[derive(Debug)]
pub(super) struct OBlock {
    kind: OType,
    name: Rc<str>,
    call_type: CallType,
    params: [f64; SUB_PARAMS],
    /// How many of `params` a `call` gave.
    count: usize,
    /// `M98`'s L word.
    l: Option<f64>,
}

impl OBlock {
    /// A block of `kind` called as `call_type`, with no name, parameters or L word yet.
    fn new(kind: OType, call_type: CallType) -> OBlock {
        OBlock { kind, name: Rc::from(""), call_type, params: [0.0; SUB_PARAMS], count: 0, l: None }
    }
}

impl<R: BufRead> Interpreter<R> {
    /// Sets where file subroutines are found: beside `program` (also named in messages) and
    /// in `dirs`, in that order.
    pub fn with_subroutines(mut self, program: Option<PathBuf>, dirs: Vec<PathBuf>) -> Self {
        self.control.program = program;
        self.control.dirs = dirs;
        self
    }

    /// Sets where the files the program names (file subroutines, user M-code programs) are
    /// found and opened, and how Python is started: [`crate::NoEnvironment`]
    /// by default, which has neither files nor Python.
    pub fn with_environment(mut self, environment: Arc<dyn Environment>) -> Self {
        self.control.environment = environment;
        self
    }

    /// The end of the input while a subroutine was being looked for: rs274's message, at the
    /// line that called it when the search began in the caller's own file (a file subroutine
    /// might have defined it: the setting that adds its folder would help).
    pub(super) fn control_end(&self) -> Option<GcodeError> {
        let name = self.control.skipping_to_sub.as_ref()?;
        let message = format!(
            "EOF in file:{} seeking o-word: o<{name}> from line: {}",
            self.control.file_name(),
            self.control.skipping_start
        );
        match &self.control.skipping_call {
            Some(call) => {
                let end = call.trim_ascii_end().len().max(1);
                let at = self.location_of(self.control.skipping_start, call, 0, end);
                Some(GcodeError::NeedsSetting { at, message, setting: Setting::SubroutinePath })
            }
            None => Some(self.error(self.line_fault(message))),
        }
    }

    /// The closing `%` while lines are being skipped (to a subroutine being called, to the
    /// end of a subroutine being defined, or to the O line a control-flow word jumps to): rs274
    /// stops there with its own message, the rest of the file unsearched.
    pub(super) fn control_percent(&self) -> Option<GcodeError> {
        let name = self.control.skipping_to_sub.as_ref().or(self.control.skipping_o.as_ref())?;
        let message = format!("Failed to find sub 'O{name}' before EOF");
        Some(self.error(self.line_fault(message)))
    }

    /// Runs the line if it is an O-word line (or M98/M99), or skips it while skipping;
    /// `Ok(true)` when the line is done with, `Ok(false)` when it is an ordinary block.
    pub(super) fn control_line(&mut self) -> Result<bool, GcodeError> {
        self.control_step().map_err(|fault| self.error(fault))
    }

    fn control_step(&mut self) -> Result<bool, Fault> {
        let at = first_item(self.machine.syntax.compact.bytes());
        let lead = self.machine.syntax.compact.bytes().get(at).copied();
        let m_number = if lead == Some(b'm') {
            let mut reader = Reader::new(
                &self.machine.syntax.compact,
                self.lines.line.len(),
                &self.machine.state.params,
                &self.machine.state,
            );
            reader.set_position(at + 1);
            reader.read_integer_value().ok()
        } else {
            None
        };
        let skipping = self.control.engaged();
        let g65 = lead == Some(b'g');
        if g65 && (!self.machine.hooks.rules.fanuc_subprograms || skipping) {
            return Ok(skipping);
        }
        match (lead, m_number) {
            (Some(b'o' | b'g'), _) | (_, Some(98)) => {}
            (_, Some(99)) if self.control.level() > 0 => {}
            (_, Some(99)) if !skipping => {
                // M99 in the main program: the standalone rs274 ends the program there, as M2
                // (LinuxCNC loops only when its INI file asks for it).
                let bytes = self.machine.syntax.compact.bytes_mut();
                if bytes.get(at..at + 3) == Some(b"m99") {
                    bytes[at + 1] = b'0';
                    bytes[at + 2] = b'2';
                }
                return Ok(false);
            }
            _ => return Ok(skipping),
        }
        let block = if g65 {
            Some(self.machine.read_g65(at)?)
        } else {
            self.control.read_o(&mut self.machine, at, m_number)?
        };
        let Some(block) = block else { return Ok(true) };
        self.convert_control(&block)?;
        if !self.lines.can_jump() && self.control.file.is_none() {
            self.update_recording();
        }
        Ok(true)
    }

    /// An input read only forwards: keeps the lines of the main program's loops while they
    /// run and of its subroutine definitions for good, so that jumps can read them again.
    fn update_recording(&mut self) {
        let want = if self.control.defining_sub || self.control.forward {
            Some(true)
        } else if !self.control.open_loops.is_empty() {
            Some(false)
        } else {
            None
        };
        if want != self.control.recording {
            self.lines.set_recording(want);
            self.control.recording = want;
        }
    }

    /// A loop of the main program starts (`open`) or ends: its lines are kept while it runs.
    fn track_loop(&mut self, name: &Rc<str>, open: bool) {
        if self.control.level() != 0 || self.control.file.is_some() || self.lines.can_jump() {
            return;
        }
        let loops = &mut self.control.open_loops;
        if open {
            if !loops.contains(name) {
                loops.push(name.clone());
            }
        } else {
            loops.retain(|other| other != name);
        }
    }

    /// The raw line as LinuxCNC quotes it in messages (trailing blanks dropped).
    fn line_text(&self) -> String {
        String::from_utf8_lossy(self.lines.line.trim_ascii_end()).into_owned()
    }

    pub(super) fn line_fault(&self, message: impl Into<String>) -> Fault {
        self.machine.line_fault(message)
    }

    /// The line refused until the caller gives `setting`.
    pub(super) fn setting_fault(&self, message: impl Into<String>, setting: Setting) -> Fault {
        Fault { kind: FaultKind::Needs(setting), ..self.line_fault(message) }
    }

    /// The label of a `repeat` or `while` on `line`: remembered where it is first met; met again
    /// elsewhere, rs274's "duplicate O-word label" (unless it was defined by `shared_with`, as a
    /// `do` shares its label with the `while` that closes it).
    fn claim_loop_label(
        &mut self,
        block: &OBlock,
        line: usize,
        shared_with: Option<OType>,
    ) -> Result<(), Fault> {
        match self.label_of(&block.name) {
            Some(label) if Some(label.kind) != shared_with && label.line != line => Err(self
                .line_fault(format!(
                    "{line}: duplicate O-word label: '{}' - defined in line {}",
                    self.line_text(),
                    label.line
                ))),
            Some(_) => Ok(()),
            None => self.save_offset(block),
        }
    }

    fn label_of(&self, name: &str) -> Option<&Label> {
        self.control.labels.get(name)
    }

    /// Remembers where the label of `block` is (`control_save_offset`).
    fn save_offset(&mut self, block: &OBlock) -> Result<(), Fault> {
        let line = self.lines.number;
        if let Some(label) = self.label_of(&block.name) {
            let file = self.control.file_name();
            let message = if label.line == line {
                format!("File:{file} line:{line} sub: o|{}| found in illegal location", block.name)
            } else {
                let defined = label
                    .file
                    .as_ref()
                    .map(|path| path.display().to_string())
                    .unwrap_or_else(|| self.control.file_name());
                format!(
                    "File:{file} line:{line} redefining sub: o|{}| already defined in file:{defined}",
                    block.name
                )
            };
            return Err(self.line_fault(message));
        }
        let label = Label {
            kind: block.kind,
            offset: self.lines.start,
            file: self.control.file.clone(),
            line,
            repeat_count: -1,
        };
        self.control.labels.insert(block.name.clone(), label);
        Ok(())
    }

    /// Reads `file` (`None`: the main program) from now on, if it is not the one being read.
    fn switch_to(&mut self, file: Option<Rc<Path>>) -> Result<(), Fault> {
        let same = match (&file, &self.control.file) {
            (None, None) => true,
            (Some(a), Some(b)) => a == b,
            _ => false,
        };
        if same {
            return Ok(());
        }
        match &file {
            None => self.lines.close_file(),
            Some(path) => {
                let file = self.open_subroutine(path)?;
                self.lines.open_file(file);
            }
        }
        self.control.file = file;
        Ok(())
    }

    /// One more jump back (a loop's turn, a call) since the last motion: an error once there
    /// have been more than [`Config::max_idle_jumps`](crate::Config::max_idle_jumps), naming
    /// `loop_line`, the line jumped to — an endless loop that never moves would run forever.
    pub(super) fn count_jump(&mut self, loop_line: usize) -> Result<(), Fault> {
        self.machine.output.idle_jumps += 1;
        if self.machine.output.idle_jumps > self.control.max_idle_jumps {
            let message = format!(
                "the loop at line {loop_line} has jumped back {} times without a motion: an \
                 endless loop? (that many jumps back without a motion are allowed)",
                self.control.max_idle_jumps
            );
            return Err(self.setting_fault(message, Setting::MaxIdleJumps));
        }
        Ok(())
    }

    /// An error when this jump back (to `loop_line`) is made with the same state as the last
    /// one from this line: the program can only repeat the same pass forever. (A program with
    /// Python plug-ins is not judged: their own state is not seen.)
    pub(super) fn repeats_forever(&mut self, loop_line: usize) -> Result<(), Fault> {
        if self.python.is_some() {
            return Ok(());
        }
        let point = (self.control.file.clone(), self.lines.number);
        let mut visits = std::mem::take(&mut self.control.visits);
        let control = &self.control;
        let repeats =
            visits.repeats(point, &self.machine, |out: &mut String| control.write_state(out));
        self.control.visits = visits;
        if repeats {
            return Err(self.line_fault(format!(
                "the loop at line {loop_line} repeats forever: the machine's state (position, \
                 parameters, modes) as line {} jumps back is the same as at its previous jump \
                 back, so every pass from here is the same",
                self.lines.number
            )));
        }
        Ok(())
    }

    /// Goes to byte offset `offset`, the next line read being line `line + 1`.
    pub(super) fn go_to(&mut self, offset: u64, line: usize) -> Result<(), Fault> {
        if let Err(err) = self.lines.seek(offset) {
            let message = if self.control.file.is_none() && !self.lines.can_jump() {
                format!(
                    "this O-word jumps back to a line of a program read only forwards \
                     (standard input), which keeps only the lines of loops being run and of \
                     subroutines defined before their calls, up to 16 MiB ({err}): give the \
                     program as a file"
                )
            } else {
                format!("cannot move in the program: {err}")
            };
            return Err(self.line_fault(message));
        }
        self.lines.number = line;
        Ok(())
    }

    /// Jumps to a label seen before, or else reads on to find it — in a file subroutine
    /// `NAME.ngc` if there is one (`control_back_to`). `looping`: a loop's turn (whose state
    /// is compared with its last turn's), not a call.
    fn back_to(&mut self, name: &Rc<str>, looping: bool) -> Result<(), Fault> {
        if let Some(label) = self.label_of(name).cloned() {
            if looping {
                self.repeats_forever(label.line)?;
            }
            self.count_jump(label.line)?;
            self.switch_to(label.file)?;
            return self.go_to(label.offset, label.line - 1);
        }
        if let Some(path) = self.find_file(name)? {
            let path: Rc<Path> = Rc::from(path);
            let file = self.open_subroutine(&path)?;
            self.lines.open_file(file);
            self.control.file = Some(path);
            self.lines.number = 0;
            self.control.skipping_call = None;
        } else {
            self.control.forward |= self.control.file.is_none();
            self.control.skipping_call = Some(self.lines.line.as_slice().into());
        }
        self.control.skipping_o = Some(name.clone());
        self.control.skipping_to_sub = Some(name.clone());
        self.control.skipping_start = self.lines.number;
        Ok(())
    }

    /// The file subroutine `path`, opened from its start.
    fn open_subroutine(&self, path: &Path) -> Result<Box<dyn crate::Seekable>, Fault> {
        self.control.environment.open(path).map_err(|err| {
            self.line_fault(format!("Unable to open file: {} ({err})", path.display()))
        })
    }

    /// `NAME.ngc` beside the program, else in a `--subroutine-path` folder, else in one the INI
    /// file names.
    fn find_file(&self, name: &str) -> Result<Option<PathBuf>, Fault> {
        if name.contains('/') || name.contains("..") || name.contains('\\') {
            let message = format!(
                "o<{name}>: a subroutine name with '/' or '..' is refused (file subroutines \
                 are found by name alone, beside the program or in the subroutine folders)"
            );
            return Err(self.setting_fault(message, Setting::SubroutinePath));
        }
        if name.is_empty() || name.contains('#') {
            return Ok(None);
        }
        let file = format!("{name}.ngc");
        let beside = self.control.program.as_ref().map(|program| {
            program.parent().filter(|dir| !dir.as_os_str().is_empty()).unwrap_or(Path::new("."))
        });
        Ok(beside
            .into_iter()
            .chain(self.control.dirs.iter().map(PathBuf::as_path))
            .chain(self.control.ini_dirs.iter().map(PathBuf::as_path))
            .map(|dir| dir.join(&file))
            .find(|path| self.control.environment.is_file(path)))
    }

    /// A new call level (`enter_context`).
    pub(super) fn enter_context(&mut self, block: &OBlock) -> Result<(), Fault> {
        if self.control.frames.len() >= SUB_LEVELS {
            return Err(self.line_fault("Too many subroutine levels"));
        }
        let locals = self.machine.state.params.take_locals();
        let modes = std::mem::take(&mut self.machine.state.modal_stack);
        if let Some(caller) = self.control.frames.last_mut() {
            caller.locals = locals;
            caller.modes = modes;
        }
        self.control.frames.push(Frame::new(Some(block.name.clone()), block.call_type));
        self.machine.state.owords.level = self.control.level();
        Ok(())
    }

    /// Back to the caller's level (`leave_context`).
    pub(super) fn leave_context(&mut self) -> Result<(), Fault> {
        // M73: the modal state saved at this level comes back as the subroutine returns.
        self.machine.restore_on_return()?;
        if self.control.frames.len() > 1 {
            self.control.frames.pop();
        }
        let modes = self.control.frames.last_mut().map(|caller| std::mem::take(&mut caller.modes));
        self.machine.state.modal_stack = modes.unwrap_or_default();
        let locals =
            self.control.frames.last_mut().map(|caller| std::mem::take(&mut caller.locals));
        self.machine.state.params.restore_locals(locals.unwrap_or_default());
        self.machine.state.owords.level = self.control.level();
        Ok(())
    }

    /// `o… call` and `M98` (`execute_call`).
    fn execute_call(&mut self, block: &OBlock) -> Result<(), Fault> {
        self.control.skipping_o = None;
        let caller = self.control.level() - 1;
        if block.call_type != CallType::M98 {
            for index in 0..SUB_PARAMS {
                self.control.frames[caller].saved_params[index] =
                    self.machine.state.params.get(index + 1);
                self.machine.state.params.set(index + 1, block.params[index]);
            }
        }
        let frame = &mut self.control.frames[caller];
        frame.position = self.lines.next;
        frame.file = self.control.file.clone();
        frame.line = self.lines.number;
        if block.kind == OType::M98
            && let Some(l) = block.l
        {
            if frame.m98_loop_counter == -1 {
                frame.m98_loop_counter = round_to_int(l) as i64;
            }
            frame.m98_loop_counter -= 1;
            if frame.m98_loop_counter > 0 {
                // Come back to this line for the next repeat.
                frame.position = self.lines.start;
                frame.line -= 1;
            } else {
                frame.m98_loop_counter = -1;
            }
        }
        if block.kind == OType::M98 && block.l == Some(0.0) {
            // `M98 … L0`: no call — and, as in LinuxCNC, the call level entered stays.
            return Ok(());
        }
        self.back_to(&block.name, false)
    }

    /// `endsub`, `return`, `M99` (`execute_return`).
    fn execute_return(&mut self, block: &OBlock, call_type: CallType) -> Result<(), Fault> {
        if self.control.skipping_o.is_some() && block.kind == OType::EndSub {
            self.control.skipping_o = None;
        }
        let level = self.control.level();
        if level != 0 {
            let caller = level - 1;
            if call_type != CallType::M98 {
                for index in 0..SUB_PARAMS {
                    let saved = self.control.frames[caller].saved_params[index];
                    self.machine.state.params.set(index + 1, saved);
                }
            }
            let frame = &self.control.frames[caller];
            let (file, position, line) = (frame.file.clone(), frame.position, frame.line);
            self.switch_to(file)?;
            self.go_to(position, line)?;
            self.leave_context()?;
            self.control.sub_name = self.control.frames.last().and_then(|f| f.name.clone());
            if self.control.level() == 0 {
                self.control.forward = false;
            }
        } else if block.kind == OType::EndSub {
            if !self.control.defining_sub {
                return Err(self.line_fault("Not in subroutine definition"));
            }
            self.control.skipping_o = None;
            self.control.defining_sub = false;
            self.control.sub_name = None;
            self.machine.state.owords.defining = false;
        }
        Ok(())
    }

    fn undefined(&self) -> Fault {
        let line = self.lines.number;
        self.line_fault(format!("{line}: undefined O-word label: '{}'", self.line_text()))
    }

    /// Skips to the line with this block's label.
    fn skip_to(&mut self, block: &OBlock) {
        self.control.skipping_o = Some(block.name.clone());
        self.control.skipping_start = self.lines.number;
    }

    /// Executes an O-word line (`convert_control_functions`).
    fn convert_control(&mut self, block: &OBlock) -> Result<(), Fault> {
        if let Some(skipping) = &self.control.skipping_o
            && **skipping != *block.name
        {
            // Mach3 finds a subprogram's `O` label anywhere in the file (pcb2gcode's Mach3
            // posts call O2 from O3, defined after it): one passed while reading on to another
            // is remembered. rs274 refuses such a call ("EOF in file … seeking o-word").
            if self.machine.hooks.rules.fanuc_subprograms
                && block.kind == OType::Fanuc
                && self.label_of(&block.name).is_none()
            {
                self.save_offset(block)?;
            }
            return Ok(());
        }
        if self.control.skipping_to_sub.is_some()
            && !matches!(block.kind, OType::Sub | OType::Fanuc)
        {
            return Ok(());
        }
        match block.kind {
            OType::None => {}
            OType::Sub | OType::Fanuc => self.convert_sub(block)?,
            OType::EndSub | OType::Return | OType::M99 => self.convert_return(block)?,
            OType::Call if self.python_callable(&block.name)? => {
                // LinuxCNC asks its Python plug-ins first.
                self.enter_context(block)?;
                self.python_call(block.name.clone(), &block.params[..block.count])?;
            }
            OType::Call | OType::M98 => {
                self.enter_context(block)?;
                self.execute_call(block)?;
            }
            OType::Do | OType::Repeat | OType::While => self.convert_loop_start(block)?,
            OType::If | OType::ElseIf | OType::Else | OType::EndIf => self.convert_if(block)?,
            OType::Break | OType::Continue | OType::EndWhile | OType::EndRepeat => {
                self.convert_loop_end(block)?;
            }
        }
        Ok(())
    }

    /// `sub` and a Fanuc-style `O` label: a definition passed over, or the subroutine a call
    /// looked for.
    fn convert_sub(&mut self, block: &OBlock) -> Result<(), Fault> {
        let level = self.control.level();
        let call_type = self.control.frames[level].call_type;
        if block.kind == OType::Fanuc
            && !matches!(call_type, CallType::M98 | CallType::G65 | CallType::None)
        {
            return Err(self.line_fault("Fanuc 'O....' subroutine must be called with 'M98'"));
        }
        if block.kind == OType::Sub && !matches!(call_type, CallType::Oword | CallType::None) {
            return Err(self.line_fault("'O.... sub' subroutine must be called with 'O.... call'"));
        }
        if self.control.skipping_o.is_some() {
            self.save_offset(block)?;
            self.control.skipping_o = None;
        }
        self.control.skipping_to_sub = None;
        self.control.skipping_call = None;
        if block.kind == OType::Sub && level == 0 {
            if self.control.defining_sub {
                return Err(self.line_fault("Nested subroutine definition"));
            }
            self.save_offset(block)?;
            self.skip_to(block);
            self.control.defining_sub = true;
            self.control.sub_name = Some(block.name.clone());
            self.machine.state.owords.defining = true;
        }
        Ok(())
    }

    /// `endsub`, `return` and `M99`: back to the caller.
    fn convert_return(&mut self, block: &OBlock) -> Result<(), Fault> {
        let line = self.lines.number;
        let level = self.control.level();
        if level == 0 && self.control.sub_name.is_none() {
            return Err(self.line_fault(format!(
                "{line}: not in a subroutine definition: '{}'",
                self.line_text()
            )));
        }
        let call_type = self.control.frames[level].call_type;
        if matches!(call_type, CallType::M98 | CallType::G65) && block.kind != OType::M99 {
            return Err(self.line_fault("Fanuc 'O....' subroutine definition must end with 'M99'"));
        }
        if call_type == CallType::Oword && block.kind == OType::M99 {
            return Err(self.line_fault(
                "'O.... endsub' or 'O.... return' must follow 'O.... sub' subroutine \
                 definition",
            ));
        }
        self.execute_return(block, call_type)?;
        Ok(())
    }

    /// A loop's start (`do`, `repeat`) and `while`, which starts a `while` loop or closes a
    /// `do`.
    fn convert_loop_start(&mut self, block: &OBlock) -> Result<(), Fault> {
        let line = self.lines.number;
        match block.kind {
            OType::Do => {
                self.track_loop(&block.name, true);
                self.control.skipping_o = None;
                if self.label_of(&block.name).is_none() {
                    self.save_offset(block)?;
                }
            }
            OType::Repeat => {
                self.claim_loop_label(block, line, None)?;
                self.control.skipping_o = None;
                self.track_loop(&block.name, true);
                let test = self.control.test_value;
                let Some(label) = self.control.labels.get_mut(&block.name) else {
                    return Ok(());
                };
                if label.kind == OType::Repeat {
                    if label.repeat_count == -1 {
                        label.repeat_count = round_to_int(test) as i64;
                    }
                    if label.repeat_count > 0 {
                        label.repeat_count -= 1;
                    } else {
                        label.repeat_count = -1;
                        self.skip_to(block);
                    }
                }
            }
            OType::While => {
                self.claim_loop_label(block, line, Some(OType::Do))?;
                self.control.skipping_o = None;
                let kind = self.label_of(&block.name).map_or(OType::While, |label| label.kind);
                if kind == OType::While {
                    self.track_loop(&block.name, true);
                    if self.control.test_value == 0.0 {
                        self.skip_to(block);
                    }
                } else if self.control.test_value != 0.0 && !self.control.doing_break {
                    self.back_to(&block.name, true)?;
                } else {
                    self.control.doing_break = false;
                    self.track_loop(&block.name, false);
                }
            }
            _ => {}
        }
        Ok(())
    }

    /// `if`, `elseif`, `else` and `endif`.
    fn convert_if(&mut self, block: &OBlock) -> Result<(), Fault> {
        let line = self.lines.number;
        match block.kind {
            OType::If => {
                match self.label_of(&block.name) {
                    Some(label) if label.line != line => {
                        return Err(self.line_fault(format!(
                            "{line}: duplicate O-word label - already defined in line {}: '{}'",
                            label.line,
                            self.line_text()
                        )));
                    }
                    Some(_) => {}
                    None => self.save_offset(block)?,
                }
                if self.control.test_value != 0.0 {
                    self.control.skipping_o = None;
                    self.control.executed_if = true;
                } else {
                    self.skip_to(block);
                    self.control.executed_if = false;
                }
            }
            OType::ElseIf | OType::Else => {
                let Some(label) = self.label_of(&block.name) else { return Err(self.undefined()) };
                if label.kind != OType::If {
                    return Err(self.line_fault(format!(
                        "{line}: no matching 'if' label: '{}' (found '{}' in line {})",
                        self.line_text(),
                        label.kind.name(),
                        label.line
                    )));
                }
                let skipping_this = self.control.skipping_to(&block.name);
                if self.control.executed_if {
                    self.skip_to(block);
                } else if block.kind == OType::ElseIf {
                    if self.control.test_value != 0.0 {
                        self.control.skipping_o = None;
                        self.control.executed_if = true;
                    }
                } else if skipping_this {
                    self.control.executed_if = true;
                    self.control.skipping_o = None;
                }
            }
            OType::EndIf => {
                let Some(label) = self.label_of(&block.name) else { return Err(self.undefined()) };
                if label.kind != OType::If {
                    return Err(self.line_fault(format!(
                        "{line}: no matching label: '{}' (found '{}' in line {}): '{}'",
                        block.name,
                        label.kind.name(),
                        label.line,
                        self.line_text()
                    )));
                }
                self.control.skipping_o = None;
                self.control.executed_if = true;
            }
            _ => {}
        }
        Ok(())
    }

    /// `break`, `continue`, `endwhile` and `endrepeat`.
    fn convert_loop_end(&mut self, block: &OBlock) -> Result<(), Fault> {
        let line = self.lines.number;
        match block.kind {
            OType::Break | OType::Continue => {
                let Some(label) = self.label_of(&block.name) else { return Err(self.undefined()) };
                if !matches!(label.kind, OType::While | OType::Do) {
                    return Err(self.line_fault(format!(
                        "{line}: no matching while/do label: '{}' (found '{}' in line {})",
                        self.line_text(),
                        label.kind.name(),
                        label.line
                    )));
                }
                if block.kind == OType::Break {
                    self.skip_to(block);
                    self.control.doing_break = true;
                } else if !self.control.skipping_to(&block.name) {
                    self.skip_to(block);
                    self.control.doing_continue = true;
                }
            }
            OType::EndWhile | OType::EndRepeat => {
                let Some(label) = self.label_of(&block.name) else { return Err(self.undefined()) };
                let wanted =
                    if block.kind == OType::EndWhile { OType::While } else { OType::Repeat };
                if label.kind != wanted {
                    return Err(self.line_fault(format!(
                        "{line}: no matching label: '{}' (found '{}' in line {})",
                        self.line_text(),
                        label.kind.name(),
                        label.line
                    )));
                }
                if self.control.skipping_to(&block.name) {
                    self.control.skipping_o = None;
                    if self.control.doing_continue {
                        self.control.doing_continue = false;
                        self.back_to(&block.name, true)?;
                    } else {
                        self.track_loop(&block.name, false);
                    }
                } else {
                    self.back_to(&block.name, true)?;
                }
            }
            _ => {}
        }
        Ok(())
    }
}
