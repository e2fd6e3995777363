//! The pipeline's errors and notes.

use std::collections::BTreeMap;
use std::fmt;
use std::io;

use biscara_gcode::{Detection, Dialect, Setting, ToolInference};
use biscara_interpolate::SlowDown;
use biscara_robot::{Fit, VirtualRobotError};
use biscara_text::fixed;

/// A pipeline failure, located: its `Display` is the whole message the user sees, starting with
/// the file name (`job.ngc:12:5: …`).
///
/// Every reader of the stages below reports its position the same way, as its error's `Display`
/// starting with `LINE:` or `LINE:COL:` (1-based; G-code errors add the line and a caret below);
/// this type adds the file name once, here.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PipelineError {
    /// Occurs when the program (or a stage reading it) finds something wrong at a line:
    /// a G-code, inter-file or CSV error, a motion that cannot be timed, a sample the robot
    /// cannot take.
    #[error("{file}:{error}{}", Snippet(snippet.as_deref()))]
    Program {
        /// The program's name (`<stdin>` for standard input).
        file: String,
        /// What is wrong; its `Display` starts with `LINE:` or `LINE:COL:`.
        error: Box<dyn std::error::Error + Send + Sync>,
        /// The offending line with a caret under the column, where the reader has one.
        snippet: Option<String>,
        /// What the user can change about it, for the caller to word ([`PipelineError::hints`]).
        hints: Vec<Hint>,
    },
    /// Occurs when a program has been sampled past the configured robot time
    /// ([`time_limit`](crate::SamplingConfig::time_limit)): a program that never ends.
    #[error(
        "{file}:{line}: the program has run {limit} s of robot time, past the time limit: an \
         endless loop that moves?"
    )]
    TimeLimit {
        /// The program's name.
        file: String,
        /// The line of the first sample past the limit.
        line: usize,
        /// The limit, seconds.
        limit: f64,
    },
    /// Occurs when the program cannot be opened or read.
    #[error("cannot read {file}")]
    Io {
        /// The program's name.
        file: String,
        /// The operating system's reason.
        source: io::Error,
    },
    /// Occurs when the program cannot be fitted to the workspace ([`SamplingConfig::fit`]): it
    /// is larger than the workspace rectangle, or it has no extent.
    ///
    /// [`SamplingConfig::fit`]: crate::SamplingConfig::fit
    #[error("{file}: cannot fit the program to the workspace: {error}")]
    Fit {
        /// The program's name.
        file: String,
        /// Why it does not fit, with the numbers.
        error: VirtualRobotError,
    },
    /// Occurs when the workspace to fit the program to cannot be computed.
    #[error(transparent)]
    Workspace(VirtualRobotError),
    /// Occurs when a program of this kind cannot be used this way (fitting standard input or
    /// a path CSV, a path CSV where motions are needed, fitting a program that moves forever).
    #[error("{file}: {message}")]
    Unsupported {
        /// The program's name.
        file: String,
        /// What cannot be done and what would work.
        message: String,
        /// What the user can change about it, for the caller to word ([`PipelineError::hints`]).
        hints: Vec<Hint>,
    },
    /// Occurs when the output cannot be written (a full disk, a closed pipe).
    #[error("cannot write the output")]
    Write(#[from] io::Error),
    /// Occurs when the robot's dynamic model cannot be built for its motors (d4's motor too
    /// weak to hold the slide and the payload).
    #[error(transparent)]
    Dynamics(#[from] biscara_dynamics::DynamicsError),
}

/// Shows a snippet on the lines below a message, indented.
struct Snippet<'a>(Option<&'a str>);

impl fmt::Display for Snippet<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.0 {
            Some(snippet) => write!(f, "\n    {}", snippet.replace('\n', "\n    ")),
            None => Ok(()),
        }
    }
}

impl PipelineError {
    /// A located error of the program `file`.
    pub fn program(file: &str, error: impl std::error::Error + Send + Sync + 'static) -> Self {
        let (file, error) = (file.to_owned(), Box::new(error));
        PipelineError::Program { file, error, snippet: None, hints: Vec::new() }
    }

    /// What cannot be done with the program `file`, and why.
    pub(crate) fn unsupported(file: &str, message: impl Into<String>) -> Self {
        let (file, message) = (file.to_owned(), message.into());
        PipelineError::Unsupported { file, message, hints: Vec::new() }
    }

    /// The program the error is about, as its message names it first (`FILE:…`); `None` for
    /// the errors about no program (the workspace, the dynamic model, the output).
    pub fn file(&self) -> Option<&str> {
        match self {
            PipelineError::Program { file, .. }
            | PipelineError::TimeLimit { file, .. }
            | PipelineError::Io { file, .. }
            | PipelineError::Fit { file, .. }
            | PipelineError::Unsupported { file, .. } => Some(file),
            PipelineError::Workspace(_) | PipelineError::Write(_) | PipelineError::Dynamics(_) => {
                None
            }
        }
    }

    /// What the user can change about this error, in the order to show them. The message
    /// ([`Display`](fmt::Display)) is whole without them; a caller words them for its own
    /// settings (the command line names its flags, [`Hint`]'s `Display` names the settings).
    pub fn hints(&self) -> &[Hint] {
        match self {
            PipelineError::Program { hints, .. } | PipelineError::Unsupported { hints, .. } => {
                hints
            }
            PipelineError::Fit { error: VirtualRobotError::NoMoves, .. } => &[Hint::DoNotFit],
            PipelineError::TimeLimit { .. } => &[Hint::MoreTime],
            _ => &[],
        }
    }
}

/// What a user can change to get past an error: the library names the remedy, the caller words
/// it for its own settings (the command line names its flags). `Display` is a wording in terms
/// of [`SamplingConfig`](crate::SamplingConfig)'s fields.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Hint {
    /// A loop jumped back more often without a motion than allowed: a larger
    /// [`max_idle_jumps`](crate::SamplingConfig::max_idle_jumps) allows a loop that computes
    /// long.
    MoreIdleJumps,
    /// A program went on past the motions one run may make: a larger
    /// [`max_motions`](crate::SamplingConfig::max_motions) allows a longer program.
    MoreMotions,
    /// A program was sampled past the robot time allowed: a larger
    /// [`time_limit`](crate::SamplingConfig::time_limit) allows a longer program.
    MoreTime,
    /// The dialect was chosen from the program's content (the error may be the dialect's, not
    /// the program's): another can be set ([`dialect`](crate::SamplingConfig::dialect)).
    DialectDetected(Detection),
    /// The program can be placed by hand ([`origin`](crate::SamplingConfig::origin)) rather
    /// than fitted.
    PlaceByOrigin,
    /// The program has nothing to fit: run it without [`fit`](crate::SamplingConfig::fit).
    DoNotFit,
    /// The program's Python needs LinuxCNC's INI file with a `[PYTHON]` section
    /// ([`ini`](crate::SamplingConfig::ini)).
    GiveIni,
    /// A file subroutine's name cannot hold a folder: add the folder to the places file
    /// subroutines are found in ([`subroutine_path`](crate::SamplingConfig::subroutine_path)).
    AddSubroutineFolder,
}

impl Hint {
    /// The hint for a setting the interpreter says would help.
    pub(crate) fn for_setting(setting: Setting) -> Option<Hint> {
        match setting {
            Setting::MaxIdleJumps => Some(Hint::MoreIdleJumps),
            Setting::MaxMotions => Some(Hint::MoreMotions),
            Setting::Ini => Some(Hint::GiveIni),
            Setting::SubroutinePath => Some(Hint::AddSubroutineFolder),
            _ => None,
        }
    }
}

impl fmt::Display for Hint {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Hint::MoreIdleJumps => {
                f.write_str("(a larger max_idle_jumps allows more, for a loop that computes long)")
            }
            Hint::MoreMotions => {
                f.write_str("(a larger max_motions allows more, for a program that long)")
            }
            Hint::MoreTime => {
                f.write_str("(a larger time_limit allows more, for a program that long)")
            }
            Hint::DialectDetected(detection) => write!(
                f,
                "(read as {} G-code, the dialect found in the program: {}; set the dialect to \
                 choose another)",
                detection.dialect, detection.reason
            ),
            Hint::PlaceByOrigin => f.write_str("(place it by an origin instead)"),
            Hint::DoNotFit => f.write_str("(run it without fitting it)"),
            Hint::GiveIni => f.write_str("(set the INI file)"),
            Hint::AddSubroutineFolder => f.write_str("(add the folder to the subroutine path)"),
        }
    }
}

/// Something the pipeline has to say besides its output; its `Display` is the message, the
/// caller adds its own prefix (`biscara: note: `).
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Note {
    /// The program was fitted to the workspace: its extent, the rectangle, the offset, the
    /// turn, and its Z.
    Placed {
        /// The program's name.
        file: String,
        /// The placement in XY.
        fit: Fit,
        /// The program's Z extent as read, `[lowest, highest]` mm (`[+∞, −∞]` when none).
        z: [f64; 2],
        /// The robot's Z stroke, `[lowest, highest]` mm.
        stroke: [f64; 2],
        /// The Z shift: zero when the Z extent is inside the stroke, else what centres it there.
        dz: f64,
        /// Whether the program made its start point its zero with G92, so that its start moved.
        by_start: bool,
    },
    /// The dialect was chosen from the program (only when something in the program told).
    Dialect {
        /// The program's name.
        file: String,
        /// The dialect and why.
        detection: Detection,
    },
    /// No tool set and no `tool.kind` in the robot file: the tool was inferred from the program.
    Tool {
        /// The program's name.
        file: String,
        /// The tool and why.
        inference: ToolInference,
    },
    /// The program used codes with no motion here (temperatures, fans, `$` lines, …), recorded
    /// as events; one note with their counts.
    Codes {
        /// The program's name.
        file: String,
        /// Each code and how many times it occurs.
        codes: BTreeMap<String, usize>,
    },
    /// The program used codes its firmware does not know and skips (Marlin's "Unknown
    /// command"), recorded as events; one note with their counts.
    UnknownCodes {
        /// The program's name.
        file: String,
        /// The dialect the program was read in.
        dialect: Dialect,
        /// Each code and how many times it occurs.
        codes: BTreeMap<String, usize>,
    },
    /// The program uses what its firmware itself refuses (Grbl 1.1's unsupported commands),
    /// read here as LinuxCNC reads it; one note with their counts.
    RefusedByFirmware {
        /// The program's name.
        file: String,
        /// The dialect the program was read in.
        dialect: Dialect,
        /// Each code or feature and how many lines use it.
        codes: BTreeMap<String, usize>,
    },
    /// The program uses what LinuxCNC refuses and its firmware runs (Mach3's bare axis words
    /// after G80, its G53 without a move), read as that firmware runs it; one note with the
    /// counts.
    Adapted {
        /// The program's name.
        file: String,
        /// The dialect the program was read in.
        dialect: Dialect,
        /// Each reading and how many lines use it.
        codes: BTreeMap<String, usize>,
    },
    /// The program probes (G38.2–G38.5): run as LinuxCNC's `rs274` simulates probing, with no
    /// probe that trips; one note with the counts.
    Probes {
        /// The program's name.
        file: String,
        /// The dialect the program was read in: LinuxCNC's stops 0.254 mm back, as rs274 does.
        dialect: Dialect,
        /// Each probe code and how many probe moves use it.
        codes: BTreeMap<String, usize>,
    },
    /// The program used tool offsets (G43, G43.2, G10 L1/L10/L11, M61) with no tool table
    /// given: every tool has zero length and diameter.
    ToolsWithoutTable {
        /// The program's name.
        file: String,
    },
    /// The motors' torques of a path CSV in which no sample has the gripper closed, for a robot
    /// with a payload: the payload was never carried (a path CSV tells the gripper's state only
    /// in its `gripper` column).
    NoPayloadCarried {
        /// The program's name.
        file: String,
        /// The robot's payload, kg.
        payload_kg: f64,
    },
    /// A motion runs slower than programmed (a joint or C speed limit).
    SlowedDown {
        /// The program's name.
        file: String,
        /// Which motion, by how much and why.
        slow: SlowDown,
    },
}

impl fmt::Display for Note {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Note::Placed { file, fit, z, stroke, dz, by_start } => {
                let (bounds, rectangle) = (&fit.bounds, &fit.rectangle);
                let [dx, dy] = fit.offset;
                let n = |v: f64| fixed(v, 3);
                write!(
                    f,
                    "{file}: fitted: the program's XY extent x {}..{}, y {}..{} mm ({} x {} mm) ",
                    n(bounds.min[0]),
                    n(bounds.max[0]),
                    n(bounds.min[1]),
                    n(bounds.max[1]),
                    n(bounds.width()),
                    n(bounds.height()),
                )?;
                if fit.rotated {
                    let [hx, hy] = bounds.home();
                    write!(
                        f,
                        "fits the workspace only turned: it is turned by 90° counter-clockwise \
                         about Z at X{} Y{} (C turns with it), then ",
                        n(hx),
                        n(hy)
                    )?;
                }
                write!(
                    f,
                    "is centred in the workspace rectangle x {}..{}, y {}..{} mm by the offset X{} \
                     Y{}",
                    n(rectangle.min[0]),
                    n(rectangle.max[0]),
                    n(rectangle.min[1]),
                    n(rectangle.max[1]),
                    n(dx),
                    n(dy)
                )?;
                if *by_start {
                    f.write_str(
                        " (it zeroes itself with G92 at its start: its start point moves)",
                    )?;
                }
                if *dz != 0.0 {
                    write!(
                        f,
                        "; its Z extent {}..{} mm is outside the stroke {}..{} mm: Z moves by {} \
                         to centre it",
                        n(z[0]),
                        n(z[1]),
                        n(stroke[0]),
                        n(stroke[1]),
                        n(*dz)
                    )
                } else if fit.rotated {
                    f.write_str(" (z unchanged)")
                } else {
                    f.write_str(" (z and c unchanged)")
                }
            }
            Note::Dialect { file, detection } => write!(
                f,
                "{file}: read as {} G-code, the dialect found in the program: {}{}",
                detection.dialect,
                detection.reason,
                if detection.makerbot {
                    "; MakerBot flavour: the A word is the extruder"
                } else {
                    ""
                }
            ),
            Note::Tool { file, inference } => write!(
                f,
                "{file}{}: tool: {} ({}; inferred: no tool set and no tool.kind in the robot file)",
                inference.line.map(|line| format!(":{line}")).unwrap_or_default(),
                inference.tool,
                inference.reason
            ),
            Note::Codes { file, codes } => write!(
                f,
                "{file}: codes with no motion here, recorded as events: {}",
                Counted(codes)
            ),
            Note::UnknownCodes { file, dialect, codes } => write!(
                f,
                "{file}: codes {dialect} does not know, skipped as it does (\"Unknown command\"), \
                 recorded as events: {}",
                Counted(codes)
            ),
            Note::RefusedByFirmware { file, dialect, codes } => write!(
                f,
                "{file}: {dialect} itself refuses these (its error 20, unsupported command); read \
                 here as LinuxCNC reads them, so the program runs here but not on that machine: {}",
                Counted(codes)
            ),
            Note::Adapted { file, dialect, codes } => write!(
                f,
                "{file}: read as {dialect} runs them (LinuxCNC would refuse them): {}",
                Counted(codes)
            ),
            Note::Probes { file, dialect: Dialect::Linuxcnc, codes } => write!(
                f,
                "{file}: probe moves run as LinuxCNC's rs274 simulates them, with no probe to \
                 trip: each goes to its end point and stops 0.254 mm back, and #5061–#5063 read \
                 the end point with #5070 = 0 (not tripped): {}",
                Counted(codes)
            ),
            Note::Probes { file, dialect, codes } => {
                let parameters = if *dialect == Dialect::Mach3 {
                    "#2000–#2002 as in Mach3, and #5061–#5063 as in Mach4"
                } else {
                    "#5061–#5063, as LinuxCNC names them"
                };
                write!(
                    f,
                    "{file}: probe moves run with no probe to trip: each goes to its end point, \
                     which the next line reads as the probed point ({parameters}): {}",
                    Counted(codes)
                )
            }
            Note::ToolsWithoutTable { file } => write!(
                f,
                "{file}: the program uses tool offsets (G43, G10 L1, …) but no tool table was \
                 given: every tool has zero length and diameter"
            ),
            Note::NoPayloadCarried { file, payload_kg } => write!(
                f,
                "{file}: no sample has the gripper closed, so the torques carry none of the \
                 robot's {payload_kg} kg payload: a path CSV tells the gripper's state only in \
                 its `gripper` column (written with the tool's events)"
            ),
            Note::SlowedDown { file, slow }
                if slow.cause == biscara_interpolate::PLANNER_FALLBACK =>
            {
                write!(
                    f,
                    "{file}:{}: the time-optimal planner found no timing along this move (its \
                     bounds admit no motion somewhere on it): timed instead with the trapezoid \
                     profile at {:.1}% of the programmed speed, within the joints' speed limits",
                    slow.line,
                    100.0 * slow.factor
                )
            }
            Note::SlowedDown { file, slow } => write!(
                f,
                "{file}:{}: slowed to {:.1}% of the programmed speed ({} limit)",
                slow.line,
                100.0 * slow.factor,
                slow.cause
            ),
        }
    }
}

/// Codes with their counts: `M104 ×2, M140 ×1`.
struct Counted<'a>(&'a BTreeMap<String, usize>);

impl fmt::Display for Counted<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (index, (code, count)) in self.0.iter().enumerate() {
            let separator = if index == 0 { "" } else { ", " };
            write!(f, "{separator}{code} ×{count}")?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_error_about_a_program_names_its_file() {
        let io = || io::Error::other("disk on fire");
        let errors = [
            PipelineError::program("job.ngc", io()),
            PipelineError::TimeLimit { file: "job.ngc".to_owned(), line: 3, limit: 2.0 },
            PipelineError::Io { file: "job.ngc".to_owned(), source: io() },
            PipelineError::Fit { file: "job.ngc".to_owned(), error: VirtualRobotError::NoMoves },
            PipelineError::unsupported("job.ngc", "no"),
        ];
        for err in errors {
            assert_eq!(err.file(), Some("job.ngc"), "{err}");
            assert!(err.to_string().contains("job.ngc"), "{err}");
        }
        assert_eq!(PipelineError::Write(io()).file(), None);
        assert_eq!(PipelineError::Workspace(VirtualRobotError::NoMoves).file(), None);
    }
}
