//! `biscara interpret`: G-code → inter-file (JSON Lines).

use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use anyhow::anyhow;
use biscara::gcode::{Config, Dialect, GcodeError, Interpreter, interpret as interpret_gcode};
use biscara::kinematics::{Kinematics, Robot};
use biscara::motion::write_jsonl;
use clap::Args;

use super::display_path;
use super::input::open_input;
use super::output::write_output;

/// Interprets a G-code program as LinuxCNC does and writes its motions as the inter-file
/// (SPEC §4.2, §5): one JSON object per motion or event, absolute positions in the robot's base
/// frame (offsets applied), millimetres and degrees; feeds in mm/min.
///
/// The language is LinuxCNC's RS274/NGC for the axes X Y Z C: G0 G1 G2 G3 (I J K or R, full
/// circles, P turns, helical, G17/G18/G19), G4, G10 L2/L20, G20/G21 (inches become mm), G28/G30
/// (to the robot's home pose unless set with G28.1/G30.1), G53, G54–G59.3, G90/G91, G90.1/G91.1,
/// G92 G92.1 G92.2 G92.3, G93/G94, G40 G49 G80 G61 G64 (accepted, no effect here), M0 M1 M2 M30
/// M60 (pause, end), M3 (pick), M4 (place), M5 (gripper off), M6 M7 M8 M9, F S T; numbered and
/// named parameters and expressions. The program starts at the robot's home pose.
///
/// O-words, cutter compensation, canned cycles and the other codes LinuxCNC knows but this
/// command does not yet are refused with "… is not supported yet"; A, B, U, V, W words are
/// errors. On any error: `FILE:LINE:COLUMN: message`, the line with a caret, exit code 1, and
/// nothing written.
///
/// Programs written for other firmware are read as that firmware reads them (SPEC §4.3, README
/// "Dialects"): `--dialect auto` (the default) decides from the program's first 64 KiB
/// (generator comments, E words, printer M-codes, `$` lines, nested comments, `O0001` program
/// numbers) and says on stderr which dialect it chose and why, and lists the codes with no
/// motion that it recorded.
#[derive(Debug, Args)]
#[command(
    about = "G-code → inter-file (motions as JSON Lines)",
    after_long_help = "Example:\n  $ biscara interpret job.ngc -o job.jsonl\n  \
                       $ biscara interpret --origin 0,350,20,0 part.ngc > part.jsonl\n  \
                       $ biscara gen data/jobs/pick_place.txt | biscara interpret -"
)]
pub(crate) struct InterpretArgs {
    /// The G-code program; `-` reads standard input.
    #[arg(value_name = "FILE", help = "G-code program (`-` for standard input)")]
    program: PathBuf,
    /// Write to FILE instead of standard output.
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,
    /// Shift the whole program by X,Y,Z,C (mm, mm, mm, degrees): the G54 offset in force before
    /// the first line. CAM programs put their zero on the part; the robot's base origin is not
    /// reachable.
    #[arg(
        long,
        value_name = "X,Y,Z,C",
        allow_hyphen_values = true,
        value_parser = parse_pose,
        help = "G54 offset before the first line (mm, mm, mm, degrees)"
    )]
    origin: Option<[f64; 4]>,
    /// Place the program in the workspace: add to the origin the XY offset that centres the
    /// program's bounding box in the largest rectangle of `biscara workspace` (reported on
    /// stderr; a program larger than the rectangle is an error).
    #[arg(long, help = "Centre the program in the workspace rectangle (offset on stderr)")]
    fit: bool,
    /// Whose G-code the program is: `linuxcnc` (RS274/NGC exactly), `grbl` (Grbl 1.1), `marlin`
    /// (Marlin and RepRap printer firmware), `mach3`, or `auto` to decide from the program.
    #[arg(
        long,
        value_name = "DIALECT",
        default_value = "auto",
        value_parser = parse_dialect,
        help = "auto, linuxcnc, grbl, marlin or mach3 (auto: decided from the program)"
    )]
    dialect: Dialect,
}

fn parse_dialect(text: &str) -> Result<Dialect, String> {
    text.parse::<Dialect>().map_err(|err| err.to_string())
}

/// `X,Y,Z,C`: four finite numbers.
pub(crate) fn parse_pose(text: &str) -> Result<[f64; 4], String> {
    let values: Vec<&str> = text.split(',').map(str::trim).collect();
    if values.len() != 4 {
        return Err(format!("expected four numbers X,Y,Z,C, found {}", values.len()));
    }
    let mut pose = [0.0; 4];
    for (slot, value) in pose.iter_mut().zip(values) {
        *slot = value
            .parse::<f64>()
            .ok()
            .filter(|number| number.is_finite())
            .ok_or_else(|| format!("`{value}` is not a finite number"))?;
    }
    Ok(pose)
}

pub(crate) fn interpret(robot: &Robot, args: &InterpretArgs) -> anyhow::Result<()> {
    let home = Kinematics::new(robot)?.home().to_degrees();
    let (origin, _) = super::fit::placement(
        &args.program,
        super::trajectory::InputKind::Gcode,
        robot,
        args.origin,
        args.fit,
    )?;
    let config = Config { home, origin, dialect: args.dialect, ..Config::default() };
    let input = open_input(&args.program)?;
    write_output(args.output.as_deref(), |out| {
        // serde_json writes a motion in many small pieces: gather them in a buffer of a
        // concrete type rather than through `dyn Write`.
        let mut out = BufWriter::with_capacity(64 * 1024, out);
        let mut motions = interpret_gcode(input, &config);
        let mut failure = None;
        for motion in &mut motions {
            match motion {
                Ok(motion) => write_jsonl(&mut out, &motion)?,
                Err(err) => {
                    failure = Some(err);
                    break;
                }
            }
        }
        if let Some(err) = failure {
            // One error message (its first line is the error); the dialect `auto` chose, when
            // not LinuxCNC, on a line of its own below.
            let error = gcode_error(&args.program, &err);
            return Err(match motions.detection().filter(|d| d.dialect != Dialect::Linuxcnc) {
                Some(detection) => anyhow!(
                    "{error:#}\n    (read as {} G-code by --dialect auto: {}; give --dialect to \
                     choose another)",
                    detection.dialect,
                    detection.reason
                ),
                None => error,
            });
        }
        dialect_notes(&args.program, &motions);
        out.flush()?;
        Ok(())
    })
}

/// The dialect `auto` chose and the no-motion codes recorded, as notes on stderr.
fn dialect_notes<R: std::io::BufRead>(path: &Path, motions: &Interpreter<R>) {
    let name = display_path(path);
    let counted = |codes: &std::collections::BTreeMap<String, usize>| {
        codes.iter().map(|(code, count)| format!("{code} ×{count}")).collect::<Vec<_>>().join(", ")
    };
    #[allow(clippy::print_stderr)]
    {
        // A program in which nothing tells the dialects apart is LinuxCNC's, as before the
        // dialects existed: no note.
        if let Some(detection) = motions
            .detection()
            .filter(|detection| detection.dialect != Dialect::Linuxcnc || detection.line.is_some())
        {
            eprintln!(
                "biscara: note: {name}: read as {} G-code (--dialect auto): {}{}",
                detection.dialect,
                detection.reason,
                if detection.makerbot {
                    "; MakerBot flavour: the A word is the extruder"
                } else {
                    ""
                }
            );
        }
        let summary = motions.summary();
        if !summary.codes.is_empty() {
            eprintln!(
                "biscara: note: {name}: codes with no motion here, recorded as events: {}",
                counted(&summary.codes)
            );
        }
        if !summary.unknown.is_empty() {
            eprintln!(
                "biscara: note: {name}: codes {} does not know, skipped as it does (\"Unknown \
                 command\"), recorded as events: {}",
                motions.dialect(),
                counted(&summary.unknown)
            );
        }
    }
}

/// `FILE:LINE:COL: message`, then the line and a caret under the column.
pub(crate) fn gcode_error(path: &Path, err: &GcodeError) -> anyhow::Error {
    match err.location() {
        Some(location) => {
            let snippet = location.snippet().replace('\n', "\n    ");
            anyhow!("{}:{err}\n    {snippet}", display_path(path))
        }
        None => anyhow!("{}:{err}", display_path(path)),
    }
}
