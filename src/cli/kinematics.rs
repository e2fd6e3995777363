//! `biscara ik`, `biscara fk` and `biscara robot`.

use std::path::PathBuf;

use anyhow::Context;
use biscara::kinematics::{FkSolution, IkSolution, Joints, Kinematics, Pose, Robot};
use biscara::text::fixed;
use clap::Args;
use serde::Serialize;

use super::fmt::clean;
use super::output::write_output;

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

#[derive(Serialize)]
struct IkJson {
    theta1: f64,
    theta2: f64,
    theta3: f64,
    d4: f64,
    working_mode: String,
    assembly_mode: String,
    singularity: SingularityJson,
}

#[derive(Serialize)]
struct SingularityJson {
    type1_deg: [f64; 2],
    type2_deg: f64,
}

#[derive(Serialize)]
struct FkJson {
    x: f64,
    y: f64,
    z: f64,
    c: f64,
    elbows: [[f64; 2]; 2],
    assembly_mode: String,
}

pub(crate) fn ik(robot: &Robot, args: &IkArgs) -> anyhow::Result<()> {
    let model = Kinematics::new(robot)?;
    let pose = Pose::from_degrees(args.x, args.y, args.z, args.c);
    let solution = model.inverse_checked(&pose).with_context(|| {
        format!(
            "pose (x, y, z, c) = ({}, {}, {}, {}) is unreachable",
            args.x, args.y, args.z, args.c
        )
    })?;
    write_output(None, |out| {
        if args.json {
            serde_json::to_writer(&mut *out, &ik_json(&solution, &model))?;
            writeln!(out)?;
        } else {
            writeln!(out, "{}", joined(solution.joints.to_degrees()))?;
        }
        Ok(())
    })
}

fn ik_json(solution: &IkSolution, model: &Kinematics) -> IkJson {
    let [theta1, theta2, theta3, d4] = solution.joints.to_degrees().map(clean);
    let singularity = solution.configuration.singularity();
    IkJson {
        theta1,
        theta2,
        theta3,
        d4,
        working_mode: model.working_mode().to_string(),
        assembly_mode: solution.assembly_mode().to_string(),
        singularity: SingularityJson {
            type1_deg: singularity.type1.map(f64::to_degrees),
            type2_deg: singularity.type2.to_degrees(),
        },
    }
}

pub(crate) fn fk(robot: &Robot, args: &FkArgs) -> anyhow::Result<()> {
    let model = Kinematics::new(robot)?;
    let joints = Joints::from_degrees(args.theta1, args.theta2, args.theta3, args.d4);
    let solution = model.forward(&joints).with_context(|| {
        format!(
            "joints (θ1, θ2, θ3, d4) = ({}, {}, {}, {}) have no pose",
            args.theta1, args.theta2, args.theta3, args.d4
        )
    })?;
    warn_about_fk(&model, &solution);
    write_output(None, |out| {
        if args.json {
            serde_json::to_writer(&mut *out, &fk_json(&solution))?;
            writeln!(out)?;
        } else {
            writeln!(out, "{}", joined(solution.pose.to_degrees()))?;
        }
        Ok(())
    })
}

fn fk_json(solution: &FkSolution) -> FkJson {
    let [x, y, z, c] = solution.pose.to_degrees().map(clean);
    let elbows = solution.configuration.elbows.map(|elbow| [clean(elbow.x), clean(elbow.y)]);
    FkJson { x, y, z, c, elbows, assembly_mode: solution.configuration.assembly_mode().to_string() }
}

/// FK is a calculator: it answers outside the limits too, but says so.
fn warn_about_fk(model: &Kinematics, solution: &FkSolution) {
    let mut warnings = Vec::new();
    if let Err(err) = model.check_limits(&solution.joints) {
        warnings.push(err.to_string());
    }
    let mode = solution.configuration.working_mode();
    if mode != model.working_mode() {
        warnings.push(format!(
            "the pose is in working mode {mode}, the robot runs in {}",
            model.working_mode()
        ));
    }
    if let Err(err) = model.check_singularity(&solution.configuration) {
        warnings.push(err.to_string());
    }
    for warning in warnings {
        #[allow(clippy::print_stderr)]
        {
            eprintln!("biscara: warning: {warning}");
        }
    }
}

pub(crate) fn robot(robot: &Robot, args: &RobotArgs) -> anyhow::Result<()> {
    write_output(args.output.as_deref(), |out| {
        writeln!(out, "{}", robot.to_json_pretty())?;
        Ok(())
    })
}

/// Four values with six decimals, separated by spaces.
fn joined(values: [f64; 4]) -> String {
    values.map(|value| fixed(value, 6)).join(" ")
}
