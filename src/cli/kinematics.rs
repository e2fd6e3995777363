//! `biscara ik`, `biscara fk` and `biscara robot`.

use std::path::PathBuf;

use biscara::kinematics::RobotModel;
use biscara_files::{Level, report};
use clap::Args;

use super::files::write_output;

/// Inverse kinematics of one pose: prints θ1 θ2 θ3 d4 (degrees, degrees, degrees, mm).
///
/// The pose must be reachable in the robot's working mode and assembly mode, inside the joint
/// limits and outside the singularity margin; otherwise the command exits with 1 and says why.
/// θ3 is the single-pose value φ − (ψ1 − ψ1_home) with the distal rotation wrapped into
/// (−180°, 180°].
#[derive(Debug, Args)]
#[command(
    about = "Joint values for one tool pose (inverse kinematics)",
    allow_negative_numbers = true,
    after_long_help = "Example:\n  $ biscara ik 150 320 10 30\n  prints θ1 θ2 θ3 d4 in degrees and mm\n  $ biscara ik --json -- -150 300 20 0"
)]
pub(crate) struct IkArgs {
    /// X of the tool point, mm.
    #[arg(value_name = "X")]
    x: f64,
    /// Y of the tool point, mm.
    #[arg(value_name = "Y")]
    y: f64,
    /// Z of the tool point, mm.
    #[arg(value_name = "Z")]
    z: f64,
    /// Rotation of the tool about +Z (G-code C), degrees.
    #[arg(value_name = "C")]
    c: f64,
    /// Print one JSON object with the modes and singularity angles.
    #[arg(long)]
    json: bool,
}

/// Forward kinematics of one joint vector: prints x y z c (mm, mm, mm, degrees).
///
/// The platform point is the one of the robot's assembly mode. Joint values outside their limits
/// are still solved, with a warning on stderr.
#[derive(Debug, Args)]
#[command(
    about = "Tool pose for one set of joint values (forward kinematics)",
    allow_negative_numbers = true,
    after_long_help = "Example:\n  $ biscara fk 10 -20 5 50\n  prints x y z c in mm and degrees\n  $ biscara fk --json 0 0 0 0"
)]
pub(crate) struct FkArgs {
    /// θ1, degrees.
    #[arg(value_name = "T1")]
    theta1: f64,
    /// θ2, degrees.
    #[arg(value_name = "T2")]
    theta2: f64,
    /// θ3, degrees.
    #[arg(value_name = "T3")]
    theta3: f64,
    /// d4, mm.
    #[arg(value_name = "D4")]
    d4: f64,
    /// Print one JSON object with the elbows and the assembly mode.
    #[arg(long)]
    json: bool,
}

/// Prints the robot in force (the built-in one, or the file given with --robot) as JSON: a
/// complete template to copy and edit.
#[derive(Debug, Args)]
#[command(
    about = "Print the robot description in force as JSON",
    after_long_help = "Example:\n  $ biscara robot -o my-robot.json\n  $ biscara --robot my-robot.json ik 0 400 50 0"
)]
pub(crate) struct RobotArgs {
    /// Write to FILE instead of standard output.
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,
}

pub(crate) fn ik(robot: &RobotModel, args: &IkArgs) -> anyhow::Result<()> {
    let model = robot.kinematics();
    let solution = model.ik_typed([args.x, args.y, args.z, args.c])?;
    write_output(None, |out| {
        let text = if args.json { solution.to_json(&model) } else { solution.to_text() };
        Ok(writeln!(out, "{text}")?)
    })
}

pub(crate) fn fk(robot: &RobotModel, args: &FkArgs) -> anyhow::Result<()> {
    let model = robot.kinematics();
    let solution = model.fk_typed([args.theta1, args.theta2, args.theta3, args.d4])?;
    // FK is a calculator: it answers outside the limits too, but says so.
    for warning in model.fk_warnings(&solution) {
        report(Level::Warning, warning);
    }
    write_output(None, |out| {
        let text = if args.json { solution.to_json() } else { solution.to_text() };
        Ok(writeln!(out, "{text}")?)
    })
}

pub(crate) fn robot(robot: &RobotModel, args: &RobotArgs) -> anyhow::Result<()> {
    write_output(args.output.as_deref(), |out| {
        writeln!(out, "{}", biscara::dynamics::robot_in_force(robot.robot()).to_json_pretty())?;
        Ok(())
    })
}
