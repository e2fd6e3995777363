//! LinuxCNC's RS274/NGC G-code for a robot with the axes X Y Z C, interpreted into
//! [`Motion`](biscara_motion::Motion)s: the paper's `gcodeInterpreter`, made a real
//! interpreter (docs/gcode.md).
//!
//! It reads programs exactly as LinuxCNC's interpreter reads them — words and blocks, modal
//! groups and their checks, the order of execution within a block, numbered and named
//! parameters, expressions with LinuxCNC's operators, precedence and functions, arcs in the
//! I J K and R forms with LinuxCNC's tolerances, G20 inches, the G54–G59.3, G92 and G53
//! offsets, G28/G30, G93 inverse time, cutter radius compensation — and emits every move as
//! absolute millimetres and degrees in the robot's base frame. It streams: the interpreter is an
//! iterator over an [`std::io::BufRead`] that holds one line at a time.
//!
//! It deliberately does not: know the robot (no kinematics; the home pose is a plain number),
//! print, or guess. Of tier 3 it reads tool offsets with a LinuxCNC tool table
//! ([`Config::tool_table`], [`ToolTable`]), canned cycles, cutter radius compensation, G52,
//! M70–M73 and user M codes (events), G5/G5.1 splines in G17 (as straight moves within
//! 0.001 mm of the curve), probing G38.2–G38.5 (as `rs274` simulates it: no probe trips); NURBS
//! and the rest are refused with "… is not supported yet", never interpreted wrongly; lathe
//! codes and spindle-synchronised motion are refused as this robot cannot do them; A, B, U, V
//! and W words are errors.
//!
//! Where it differs from LinuxCNC, on purpose:
//! - A, B, U, V, W words are errors (LinuxCNC machines may have those axes; this robot has not).
//! - Parameters hold millimetres: G28.1/G30.1, G10 and G92 store mm in 5161–5390, where
//!   LinuxCNC stores its configured user unit (the standalone `rs274` uses inches).
//! - A value that is not finite (`EXP[1000]`), a position beyond ±1e6 mm and a negative dwell
//!   (`G4 P-0.5`) are errors.
//! - M19 and M62–M68 are events (`code`), M48–M53 do nothing; of the `$` (spindle) word only
//!   what rs274 takes with one spindle (0, or −1 for all) is accepted.
//! - In a rotated coordinate system (G10 L2 R), an arc in the XZ or YZ plane lies in a tilted
//!   plane the inter-file cannot describe: it becomes straight moves within 0.001 mm of it.
//!   Cutter compensation in the XZ plane of a rotated system, whose corner arcs would be
//!   tilted too, is refused as not supported yet.
//! - A probe move (G38.2–G38.5) is an event `code` (`G38.2`) and two straight moves: to its
//!   end point and 0.254 mm back along it, where `rs274` puts the position without a move; it
//!   is refused under G93, where LinuxCNC's motion controller has no feed for it.
//! - M6 emits `gripper_off`: LinuxCNC stops the spindle before a tool change.
//! - The tool table is in millimetres, and 5401–5410 hold millimetres (rs274's hold inches);
//!   a tool table line LinuxCNC would skip is an error.
//! - A program's Python (`;py,` lines, `(py,…)` comments, Python O-word subroutines) runs only
//!   with an INI file whose `[PYTHON]` section loads LinuxCNC's Python plug-ins
//!   ([`Config::ini`]), in a `python3` child process with stand-ins for LinuxCNC's `interpreter`
//!   and `emccanon` modules (a subset: parameters, a few attributes, straight moves and dwells);
//!   without one it is refused (the standalone `rs274` runs `;py,` lines always). The plug-ins
//!   are the cargo feature `python`, on by default.
//!
//! It opens no file and starts no process: the files a program names (file subroutines, user
//! M-code programs, a tool table, an INI file) and `python3` are reached through an
//! [`Environment`] the caller gives ([`Interpreter::with_environment`]; the command line's is
//! `biscara_files::FileSystem`, tests give [`InMemory`] files). Without one there are none
//! ([`NoEnvironment`]).
//! - A program that ends at a closing `%` emits no `end` (LinuxCNC calls that `FINISH`, not
//!   `PROGRAM_END`); M2 and M30 do.
//!
//! Programs written for other firmware are read as that firmware reads them when
//! [`Config::dialect`] says so ([`Dialect`]: Grbl, Marlin, Mach3; docs/gcode.md), or when it is
//! [`Dialect::Auto`]: the interpreter then reads the first [`LOOKAHEAD_BYTES`] ahead and decides
//! from them ([`detect_dialect`]), and reports its choice and reason as a value
//! ([`Interpreter::detection`]), with the no-motion codes it recorded ([`Interpreter::summary`]).
//! What M3, M4, M5 and S mean depends on [`Config::tool`] ([`Tool`], docs/motion.md). The library's
//! default is [`Dialect::Linuxcnc`], which has none of the dialects' hooks.
//!
//! ```
//! use biscara_gcode::{Config, Dialect, interpret};
//!
//! let program = ";FLAVOR:Marlin\nM104 S200\nG1 X10 E0.5 F1200\n";
//! let config = Config { dialect: Dialect::Auto, ..Config::default() };
//! let mut interpreter = interpret(program.as_bytes(), &config);
//! let motions: Vec<_> = (&mut interpreter).collect::<Result<_, _>>()?;
//! assert_eq!(motions[1].extrude, Some(0.5));
//! assert_eq!(interpreter.detection().map(|d| d.dialect), Some(Dialect::Marlin));
//! assert_eq!(interpreter.summary().codes.get("M104"), Some(&1));
//! # Ok::<(), biscara_gcode::GcodeError>(())
//! ```
//!
//! Like LinuxCNC, it refuses a file that ends without M2, M30 or a closing `%` (a truncated
//! file), lines longer than 252 characters ("Command too long"), and emits a zero-length move
//! for a motion block without axis words (`G1 F100`) and the intermediate point of G28/G30.
//!
//! ```
//! use biscara_gcode::{Config, interpret};
//! use biscara_motion::MotionKind;
//!
//! let program = "G21 G90\nG0 X10 Y20\nG1 X20 F600\nG2 X30 Y30 I5 J5\nM2\n";
//! let config = Config { home: [0.0, 400.0, 100.0, 0.0], ..Config::default() };
//! let motions: Vec<_> = interpret(program.as_bytes(), &config).collect::<Result<_, _>>()?;
//! assert_eq!(motions[0].kind, MotionKind::Rapid { end: [10.0, 20.0, 100.0, 0.0] });
//! assert_eq!(motions.last().map(|motion| motion.kind), Some(MotionKind::End));
//! # Ok::<(), biscara_gcode::GcodeError>(())
//! ```

#![warn(missing_docs)]

mod dialect;
mod environment;
mod error;
mod ini_file;
mod interpreter;
#[cfg(feature = "python")]
mod python_plugin;
mod syntax;
mod tool;
mod tool_table;

pub use dialect::{
    Detection, Dialect, LOOKAHEAD_BYTES, MAX_LONG_LINE, Summary, UnknownDialect, detect_dialect,
};
pub use environment::{Environment, InMemory, NoEnvironment, PythonProcess};
pub use error::{GcodeError, Location, Setting};
pub use ini_file::{IniFile, IniFileError};
pub use interpreter::{Config, Interpreter, interpret, interpret_seekable};
pub use syntax::lexer::{Forward, Seekable};
pub use tool::{Tool, ToolInference, infer_tool};
pub use tool_table::{ToolEntry, ToolTable, ToolTableError};

/// How many times a program may jump back (a loop's turn, a subroutine call, a Fanuc `GOTO`)
/// with no motion in between before it is stopped as an endless loop, by default
/// ([`Config::max_idle_jumps`]): a loop that computes without moving may turn this often.
pub const MAX_IDLE_JUMPS: u64 = 100_000;

/// How many motions one run may make, by default ([`Config::max_motions`]): ten million, many
/// times the longest print or CAM program (a few hundred thousand moves; a five-million-line
/// program still runs), about 0.7 GB of inter-file, written in about 25 s of CPU.
pub const MAX_MOTIONS: u64 = 10_000_000;
