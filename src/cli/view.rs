//! `biscara view`: the HTML viewer of a joint trajectory.

use std::path::PathBuf;

use biscara::interpolate::Profile;
use biscara::pipeline::{ProgramKind, ProgramSource, RobotModel, SamplingConfig, parse_grip_time};
use biscara::robot::Report;
use biscara::text::parse_sizes;
use biscara::view::{Viewer, ViewerOptions};
use biscara_files::{
    FileSource, Level, file_name, load_meshes, load_scene, located, open_input, read_joint_rows,
    report,
};
use clap::Args;

use super::args::{BlendArgs, DialectArgs, GcodeFilesArgs, PlacementArgs, placed_reading};
use super::files::write_output;

/// Writes one self-contained HTML file that animates a joint trajectory in 3D.
///
/// A WebGL scene (three.js, inlined): the base, the proximal and distal links (the passive
/// joints from forward kinematics), the Z column, the rotary axis and the tool by its kind
/// (gripper jaws opening and closing, spindle, laser with its beam while on, nozzle, pen), the
/// work surface, the scene's boxes and the tool's trace; parts for which robot.json names an STL
/// mesh (`meshes`) are drawn with it. With --program: the programmed path,
/// the pick (M3) and place (M4) points, the objects (each pick takes the object standing at its
/// pose, carries it, leaves it at the place), the program line being executed, and for a laser,
/// an extruder, a pen or a spindle the work done so far (the burnt trace, darker for more
/// power; the deposited track with a layer slider; the strokes; the cuts). Orbit, pan and zoom
/// with the mouse; Iso, Top, Front, Side and Work cameras and one following the tool;
/// play/pause, speed, a time slider reaching every sample, joint curves with the current time.
/// The file needs no network and no other file. Opening it as `view.html#t=2.5` shows the robot
/// paused at t = 2.5 s; `view.html#t=2.5&probe` writes `{"t","duration","webgl","tool",
/// "objects"}` (mm, the tool point taken from the scene) into the element `#biscara-probe`, and
/// the page's `window.biscara` offers `duration`, `seek(t)`, `toolPosition()`, `objects()`.
/// Samples are kept as binary (48 bytes each): 1 048 576 of them (17 minutes at 1 ms) make a
/// page of about 51 MB; longer trajectories keep every 2nd (4th, …) row.
///
/// TRAJ is a joint CSV from `biscara joints` (radians or degrees, with or without derivatives).
/// The program (G-code, an inter-file or a path CSV, as --from or its extension says) is sampled
/// as `joints` samples it, at TRAJ's time step: give the --origin, --fit, --profile and
/// --grip-time TRAJ was made with (a warning says when the durations disagree).
#[derive(Debug, Args)]
#[command(
    about = "Animated 3D HTML view of a joint trajectory (WebGL, no network)",
    after_long_help = "Example:\n  $ biscara joints job.ngc -o traj.csv\n  \
                       $ biscara view traj.csv --program job.ngc -o view.html\n  \
                       $ firefox 'view.html#t=2.5'"
)]
pub(crate) struct ViewArgs {
    /// The joint trajectory CSV; `-` reads standard input.
    #[arg(value_name = "TRAJ")]
    traj: PathBuf,
    /// Write to FILE instead of standard output.
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,
    /// The program TRAJ was made from: its path, events and lines are shown.
    #[arg(long, value_name = "PROGRAM", help = "G-code or inter-file TRAJ was made from")]
    program: Option<PathBuf>,
    /// A scene file: `{"boxes":[{"name":…,"min":[x,y,z],"max":[x,y,z]}]}` (mm).
    #[arg(long, value_name = "FILE", help = "Scene boxes to draw")]
    scene: Option<PathBuf>,
    #[command(flatten)]
    placement: PlacementArgs,
    #[command(flatten)]
    dialect: DialectArgs,
    #[command(flatten)]
    files: GcodeFilesArgs,
    /// The velocity profile TRAJ was made with, as `biscara joints --profile`.
    #[arg(long, value_enum, default_value = "optimal", help = "Profile TRAJ was made with")]
    profile: Profile,
    #[command(flatten)]
    blend: BlendArgs,
    /// The grip time TRAJ was made with, as `biscara joints --grip-time`.
    #[arg(
        long,
        value_name = "SECONDS",
        default_value = "0",
        value_parser = parse_grip_time,
        help = "Grip time TRAJ was made with"
    )]
    grip_time: f64,
    /// The size of the objects picked, `WxLxH` in mm (default: from the gripper's size).
    #[arg(long, value_name = "WxLxH", value_parser = parse_sizes, help = "Size of the objects picked (mm)")]
    object: Option<[f64; 3]>,
    /// A `biscara check --json` report: its problems are marked in the scene and on the timeline.
    #[arg(long, value_name = "FILE", help = "check --json report whose problems to mark")]
    check: Option<PathBuf>,
    /// The program's kind (default: from the extension, else from its first bytes).
    #[arg(long, value_enum, value_name = "KIND")]
    from: Option<ProgramKind>,
}

pub(crate) fn view(model: &RobotModel, args: &ViewArgs) -> anyhow::Result<()> {
    let scene = load_scene(args.scene.as_deref())?;
    let title =
        format!("biscara view · {}", file_name(args.program.as_ref().unwrap_or(&args.traj)));
    let mut viewer = Viewer::new(model, scene, ViewerOptions { title, ..ViewerOptions::default() });
    load_meshes(model.robot(), &mut viewer)?;
    read_joint_rows(&args.traj, open_input(&args.traj)?, |row| viewer.push_row(row))?;
    let duration = viewer.duration().unwrap_or_default();
    if let Some(size) = args.object {
        viewer.set_object_size(size);
    }
    if let Some(path) = &args.check {
        let report = biscara_files::read_bytes(path)?;
        for problem in Report::read_problems(&report).map_err(|err| located(path, err))? {
            viewer.add_problem(&problem);
        }
    }
    let Some(program) = &args.program else {
        return write_output(args.output.as_deref(), |out| Ok(viewer.write_html(out)?));
    };
    // The program sampled as `joints` sampled it, at the trajectory's time step.
    let source = FileSource::new(program);
    let kind = source.kind(args.from)?;
    let config = SamplingConfig {
        profile: args.profile,
        grip_time: args.grip_time,
        blend: args.blend.blend,
        ..placed_reading(&args.placement, &args.dialect, &args.files)?
    };
    if let Some(end) = viewer.add_program(model, config, &source, kind)? {
        let name = source.name();
        report(
            Level::Warning,
            format_args!(
                "{name} takes {end:.3} s as sampled here, the trajectory {duration:.3} s: the \
                 program lines shown may be off (was the trajectory made with other --profile, \
                 --grip-time, --origin or --fit?)"
            ),
        );
    }
    write_output(args.output.as_deref(), |out| Ok(viewer.write_html(out)?))
}
