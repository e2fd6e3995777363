//! `biscara check`: a program run on the virtual robot, every problem reported.

use std::path::PathBuf;

use anyhow::anyhow;
use biscara::pipeline::{Pipeline, ProgramSource, RobotModel};
use biscara_files::{NoteReporter, load_scene};
use clap::Args;

use super::args::{ProgramArgs, SamplingArgs, TimeLimitArgs};
use super::files::write_output;

/// Runs a program on the virtual robot and reports every problem.
///
/// The program is interpreted, interpolated and solved by IK sample by sample, and nothing
/// stops at the first problem: unreachable poses, joint positions outside `joint_limits`, joint
/// velocities and accelerations (central differences) above `joint_max_velocity` and
/// `joint_max_acceleration`, poses within `singularity_margin` of a singularity, self-collisions
/// (non-adjacent links closer than `link_width`; the distal links folded onto each other) and
/// collisions with the boxes of --scene (links as capsules at `link_height`, the gripper and the
/// Z column as cylinders), and with `motors` in the robot file, motor torques beyond their `peak`
/// (torque_limit) and RMS torques over the program beyond their `rated` torque (rms_torque).
/// Consecutive samples with the same problem are one entry with its time span, program line and
/// pose. A summary follows: duration, path length, peak joint velocity and acceleration with
/// their lines, the smallest singularity angle, and each motor's peak and RMS torque.
///
/// Exit code 0 when the program is clean, 1 when anything was found. The program's kind comes
/// from --from, else from its extension: `.jsonl` is an inter-file, `.csv` a path CSV,
/// `.ngc`/`.nc`/`.gcode`/… G-code; else from its first bytes (`{`: an inter-file, `t_s,`: a path
/// CSV, anything else G-code).
#[derive(Debug, Args)]
#[command(
    about = "Run a program on the virtual robot and report every problem",
    after_long_help = "Example:\n  $ biscara check job.ngc\n  \
                       $ biscara check --scene cell.json --json job.ngc > check.json\n\n\
                       A scene is JSON: {\"boxes\":[{\"name\":\"pallet\",\"min\":[x,y,z],\"max\":[x,y,z]}]}"
)]
pub(crate) struct CheckArgs {
    #[command(flatten)]
    program: ProgramArgs,
    /// Boxes around the robot that no part of it may touch (JSON, millimetres, base frame).
    #[arg(long, value_name = "FILE")]
    scene: Option<PathBuf>,
    /// Print the report as one JSON object.
    #[arg(long)]
    json: bool,
    /// Write the report to FILE instead of standard output.
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,
    #[command(flatten)]
    sampling: SamplingArgs,
    #[command(flatten)]
    time_limit: TimeLimitArgs,
}

pub(crate) fn check(model: &RobotModel, args: &CheckArgs) -> anyhow::Result<()> {
    let scene = load_scene(args.scene.as_deref())?;
    let (source, kind) = args.program.open()?;
    let notes = NoteReporter::default();
    let pipeline = Pipeline::new(model, args.sampling.config(&args.time_limit)?);
    let report = pipeline.check(&source, kind, scene, notes.sink())?;
    notes.finish();
    let name = source.name();
    write_output(args.output.as_deref(), |out| {
        if args.json {
            writeln!(out, "{}", report.to_json())?;
        } else {
            report.write_text(out, name)?;
        }
        Ok(())
    })?;
    if report.ok() {
        Ok(())
    } else {
        let count = report.problems.len();
        Err(anyhow!("{name}: the check found {count} problem{}", if count == 1 { "" } else { "s" }))
    }
}
