//! `biscara interpret`: G-code → inter-file (JSON Lines).

use std::path::PathBuf;

use biscara::motion::write_motions;
use biscara::pipeline::{Pipeline, ProgramKind, RobotModel};
use biscara_files::{FileSource, NoteReporter};
use clap::Args;

use super::args::{DialectArgs, GcodeFilesArgs, PlacementArgs, placed_reading};
use super::files::write_output;

/// Interprets a G-code program as LinuxCNC does and writes its motions as the inter-file
///: one JSON object per motion or event, absolute positions in the robot's base
/// frame (offsets applied), millimetres and degrees; feeds in mm/min.
///
/// The language is LinuxCNC's RS274/NGC for the axes X Y Z C: G0 G1 G2 G3 (I J K or R, full
/// circles, P turns, helical, G17/G18/G19), G4, G10 L2/L20 (L2 R: a system rotated about Z),
/// G10 L0, polar `@` `^`, G20/G21 (inches become mm), G28/G30
/// (to the robot's home pose unless set with G28.1/G30.1), G53, G54–G59.3, G90/G91, G90.1/G91.1,
/// G92 G92.1 G92.2 G92.3, G93/G94, G40 G41 G42 G41.1 G42.1 (cutter radius compensation, in G17
/// or G18; the D of G41/G42 names a tool of --tool-table, G41.1/G42.1 D give the diameter), T M6
/// M61 G43 G43.1 G43.2 G49 G10 L1/L10/L11 (tools, with --tool-table), canned cycles G73 G74
/// G81–G89 G98 G99 G80, G52, M70–M73, M100–M199 M19 M62–M68 (events), M48–M53 and `$0`/`$-1`
/// (no effect here), G61 G61.1 G64 P (path control: each
/// move under G64 carries `"blend":P`, in mm, 0 when P is not given; a G1 under G64 Q carries
/// `"naive_cam":Q`, and runs of them within Q of one straight line are merged when timed, as
/// LinuxCNC's naive-CAM detector does), M0 M1 M2 M30 M60 (pause, end), M3 (pick), M4 (place), M5
/// (gripper off), M7 M8 M9, F S; numbered and named parameters and expressions; O-word
/// subroutines (also from files, with --subroutine-path) and control flow; G5 and G5.1 splines
/// in G17 (straight moves within 0.001 mm of the curve, on the spline's line). The program
/// starts at the robot's home pose, under exact stop (G61).
///
/// NURBS (G5.2) and the other codes LinuxCNC knows but this
/// command does not yet are refused with "… is not supported yet"; A, B, U, V, W words are
/// errors. On any error: `FILE:LINE:COLUMN: message`, the line with a caret, exit code 1, and
/// no -o file written (standard output is a stream: it ends at the error).
///
/// Programs written for other firmware are read as that firmware reads them (docs/gcode.md,
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
    #[command(flatten)]
    placement: PlacementArgs,
    #[command(flatten)]
    dialect: DialectArgs,
    #[command(flatten)]
    files: GcodeFilesArgs,
}

pub(crate) fn interpret(model: &RobotModel, args: &InterpretArgs) -> anyhow::Result<()> {
    let source = FileSource::new(&args.program);
    let config = placed_reading(&args.placement, &args.dialect, &args.files)?;
    let notes = NoteReporter::default();
    let motions =
        Pipeline::new(model, config).motions(&source, ProgramKind::Gcode, notes.sink())?;
    let motions = motions.map(|motion| motion.map_err(anyhow::Error::from));
    write_output(args.output.as_deref(), |out| write_motions(out, motions))?;
    notes.finish();
    Ok(())
}
