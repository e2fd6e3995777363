//! `biscara plot`: pictures of a program on the virtual robot.

use std::path::PathBuf;

use anyhow::anyhow;
use biscara::dynamics::Dynamics;
use biscara::pipeline::{Pipeline, ProgramSource, RobotModel};
use biscara::robot::Workspace;
use biscara::text::parse_seconds;
use biscara::view::{
    JointCurves, TopView, TorqueCurves, TracedProgram, draw_joints, draw_top_view, draw_torques,
    trace_program, zoom_region,
};
use biscara_files::{Level, NoteReporter, image_format, load_scene, report};
use clap::Args;

use super::args::{ProgramArgs, SamplingArgs, TimeLimitArgs};
use super::files::write_output;

/// Draws a program on the virtual robot, in top view or as joint curves.
///
/// The top view shows the workspace (reachable region) with its largest rectangle, the
/// programmed path, the scene's boxes (--scene) and the robot (links, elbows, base joints and
/// gripper with a tick for c) at the times of --at. With --joints it draws θ1, θ2, θ3 (degrees)
/// and d4 (mm) against time instead, with the joint limits as dashed lines. With --torques it
/// draws the motors' torques (N·m) and d4's force (N) against time, as `joints --torques`
/// computes them, with each motor's ±peak and ±rated torque as dashed lines when the robot file
/// has `motors`.
///
/// The format follows the output's extension: `.png` is PNG, anything else SVG (also on standard
/// output). The program's kind comes from --from, else from its extension, else from its first
/// bytes (as for `biscara joints`).
#[derive(Debug, Args)]
#[command(
    about = "Draw a program: workspace, path and robot (top view), or joint curves",
    after_long_help = "Example:\n  $ biscara plot job.ngc --at 0,1.5,3 -o plot.svg\n  \
                       $ biscara plot --joints job.ngc -o joints.png\n  \
                       $ biscara --robot robot.json plot --torques job.ngc -o torques.svg"
)]
pub(crate) struct PlotArgs {
    #[command(flatten)]
    program: ProgramArgs,
    /// Write to FILE (`.svg` or `.png`) instead of SVG on standard output.
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,
    /// Times (s) at which to draw the robot, comma-separated (default: the start).
    #[arg(long, value_name = "T,…", value_delimiter = ',', value_parser = parse_seconds)]
    at: Vec<f64>,
    /// Draw the joint curves against time instead of the top view.
    #[arg(long)]
    joints: bool,
    /// Draw the motors' torques against time, with their ratings, instead of the top view.
    #[arg(long, conflicts_with_all = ["joints", "zoom", "at", "scene"])]
    torques: bool,
    /// Boxes around the robot to draw (JSON, as for check).
    #[arg(long, value_name = "FILE")]
    scene: Option<PathBuf>,
    /// Draw only the tool's work (or, for the gripper, the path without the travel from and
    /// to the home pose) with a margin, instead of the whole workspace.
    #[arg(long, conflicts_with = "joints")]
    zoom: bool,
    /// Grid step of the workspace, millimetres.
    #[arg(long, value_name = "MM", default_value = "2")]
    step: f64,
    #[command(flatten)]
    sampling: SamplingArgs,
    #[command(flatten)]
    time_limit: TimeLimitArgs,
}

pub(crate) fn plot(model: &RobotModel, args: &PlotArgs) -> anyhow::Result<()> {
    if args.torques {
        return plot_torques(model, args);
    }
    let scene = args.scene.as_deref().map(|path| load_scene(Some(path))).transpose()?;
    let (source, kind) = args.program.open()?;
    // Zoomed on the work, the robot is drawn only when asked for.
    let at = match args.at.is_empty() {
        true if args.zoom => Vec::new(),
        true => vec![0.0],
        false => args.at.clone(),
    };
    let notes = NoteReporter::default();
    let pipeline = Pipeline::new(model, args.sampling.config(&args.time_limit)?);
    let traced = trace_program(model, &pipeline, &source, kind, &at, notes.sink())?;
    let TracedProgram { trace, work, tool } = traced;
    for t in trace.missed_times() {
        let end = trace.duration();
        report(
            Level::Warning,
            format_args!("t = {t} s is after the program's end ({end:.3} s): not drawn"),
        );
    }
    let format = image_format(args.output.as_deref());
    let name = source.name();
    let bytes = if args.joints {
        let limits = model.robot().joint_limits.to_array();
        let title = format!("Joint trajectory of {name}");
        draw_joints(&JointCurves { title: &title, t: &trace.t, q: &trace.q, limits }, format)?
    } else {
        let workspace = Workspace::compute(&model.kinematics(), args.step)?;
        let rectangle = workspace.largest_rectangle()?;
        let title = format!("{name} on the virtual robot (top view)");
        let view = TopView {
            title: &title,
            workspace: Some(&workspace),
            rectangle: Some(&rectangle),
            path: &trace.path,
            process: Some(&work),
            process_label: tool.legend(),
            bodies: &trace.bodies,
            scene: scene.as_ref(),
            region: if args.zoom { zoom_region(&work, &trace.path) } else { None },
        };
        draw_top_view(&view, format).map_err(|err| anyhow!("{err}"))?
    };
    write_output(args.output.as_deref(), |out| Ok(out.write_all(&bytes)?))
}

/// `plot --torques`: the motors' torques of every sample, drawn against time.
fn plot_torques(model: &RobotModel, args: &PlotArgs) -> anyhow::Result<()> {
    let (source, kind) = args.program.open()?;
    let dynamics = Dynamics::new(model)?;
    let notes = NoteReporter::default();
    let pipeline = Pipeline::new(model, args.sampling.config(&args.time_limit)?);
    let (mut t, mut torques) = (Vec::new(), Vec::new());
    let name = source.name();
    pipeline.for_each_torque(&source, kind, &dynamics, notes.sink(), |row, torque| {
        t.push(row.t);
        torques.push(torque);
        Ok(())
    })?;
    notes.finish();
    let ratings = dynamics.motors().map(|motors| motors.map(|motor| [motor.peak, motor.rated]));
    let title = format!("Motor torques of {name}");
    let curves = TorqueCurves { title: &title, t: &t, torques: &torques, ratings };
    let bytes = draw_torques(&curves, image_format(args.output.as_deref()))?;
    write_output(args.output.as_deref(), |out| Ok(out.write_all(&bytes)?))
}
