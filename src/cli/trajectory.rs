//! `biscara interpolate` and `biscara joints`: programs → Cartesian path → joint trajectory.

use std::path::PathBuf;

use biscara::joints::{AngleUnit, JointCsvFormat};
use biscara::pipeline::{Pipeline, RobotModel};
use biscara_files::NoteReporter;
use clap::Args;

use super::args::{ProgramArgs, SamplingArgs, TimeLimitArgs};
use super::files::write_output;

/// Samples a program at a fixed time step: the Cartesian path.
///
/// Writes the CSV `t_s,x_mm,y_mm,z_mm,c_deg` (and `gripper` with --events), first row t = 0 at
/// the robot's home pose, one row per time step. Every programmed end point is hit exactly: each
/// motion's duration is rounded up to whole steps. Except with `--profile constant`, motions are
/// slowed so that C stays within `rapid_rotation` and no joint exceeds `joint_max_velocity`;
/// slowed motions are listed on stderr with their lines.
///
/// The program's kind comes from --from, else from its extension: `.jsonl` is an inter-file;
/// without a known extension (standard input) a first `{` means an inter-file, else G-code.
#[derive(Debug, Args)]
#[command(
    about = "Sample a program in time: the Cartesian path CSV",
    after_long_help = "Example:\n  $ biscara interpolate job.ngc -o path.csv\n  \
                       $ biscara interpolate --from jsonl --dt 0.01 --profile constant job.jsonl"
)]
pub(crate) struct InterpolateArgs {
    #[command(flatten)]
    program: ProgramArgs,
    /// Write to FILE instead of standard output.
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,
    #[command(flatten)]
    sampling: SamplingArgs,
    #[command(flatten)]
    time_limit: TimeLimitArgs,
    /// Add the tool's column: `gripper` (1 from a pick to the next place),
    /// `laser_power` (the S power while on, 0 off), `spindle_rpm` (negative: M4),
    /// `extruded_mm` (filament fed since the start) or `pen_down` (1 down, 0 up).
    #[arg(
        long,
        help = "Add the tool's column: gripper, laser_power, spindle_rpm, extruded_mm or pen_down"
    )]
    events: bool,
}

/// Joint time series of a program, for a virtual or real robot.
///
/// Every sample is solved by IK in the robot's working and assembly mode; θ3 is continuous. The
/// CSV is `t_s,theta1_rad,theta2_rad,theta3_rad,d4_mm` (`_deg` with --angle-unit deg), with
/// velocity and acceleration columns (finite differences of the positions) after --derivatives.
/// With --torques, after them, the torques the motors must give (docs/dynamics.md):
/// `tau_theta1_Nm,tau_theta2_Nm,tau_theta3_Nm,f_d4_N,payload_kg`, each row's inverse dynamics of
/// its own joints, velocities and accelerations, with the robot's payload while the gripper holds
/// it. The command fails (exit 1, no -o file written; standard output, a stream, ends there) at
/// the first sample that is unreachable, outside the joint limits or near a singularity, naming
/// the program's line and the time.
///
/// The program's kind comes from --from, else from its extension: `.jsonl` is an inter-file,
/// `.csv` a path CSV, `.ngc`/`.nc`/`.gcode`/… G-code; else from its first bytes: `{` starts an
/// inter-file, `t_s,` a path CSV, anything else is G-code.
#[derive(Debug, Args)]
#[command(
    about = "Joint trajectory CSV of a program (IK of every sample)",
    after_long_help = "Example:\n  $ biscara joints job.ngc -o traj.csv\n  \
                       $ biscara joints --derivatives --angle-unit deg --from path path.csv\n  \
                       $ biscara --robot robot.json joints job.ngc --torques -o traj.csv"
)]
pub(crate) struct JointsArgs {
    #[command(flatten)]
    program: ProgramArgs,
    /// Write to FILE instead of standard output.
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,
    #[command(flatten)]
    sampling: SamplingArgs,
    #[command(flatten)]
    time_limit: TimeLimitArgs,
    /// Add velocity and acceleration columns for every joint.
    #[arg(long)]
    derivatives: bool,
    /// Add the motors' torques (N·m) and d4's force (N) after the derivatives (implies
    /// --derivatives), and the payload held (kg).
    #[arg(
        long,
        help = "Add the motors' torques and d4's force, N·m and N (implies --derivatives)"
    )]
    torques: bool,
    /// Unit of the angle columns.
    #[arg(long, value_enum, default_value = "rad")]
    angle_unit: AngleUnit,
    /// Add the tool's column after the joints, as `interpolate --events` does:
    /// `gripper`, `laser_power`, `spindle_rpm`, `extruded_mm` or `pen_down`.
    #[arg(
        long,
        help = "Add the tool's column: gripper, laser_power, spindle_rpm, extruded_mm or pen_down"
    )]
    events: bool,
}

pub(crate) fn interpolate(model: &RobotModel, args: &InterpolateArgs) -> anyhow::Result<()> {
    let (source, kind) = args.program.open()?;
    let notes = NoteReporter::default();
    let pipeline = Pipeline::new(model, args.sampling.config(&args.time_limit)?);
    let decimals = usize::from(args.sampling.precision);
    write_output(args.output.as_deref(), |out| {
        Ok(pipeline.write_path_csv(&source, kind, out, decimals, args.events, notes.sink())?)
    })?;
    notes.finish();
    Ok(())
}

pub(crate) fn joints(model: &RobotModel, args: &JointsArgs) -> anyhow::Result<()> {
    let (source, kind) = args.program.open()?;
    let notes = NoteReporter::default();
    let pipeline = Pipeline::new(model, args.sampling.config(&args.time_limit)?);
    let format = JointCsvFormat {
        angle_unit: args.angle_unit,
        derivatives: args.derivatives,
        precision: usize::from(args.sampling.precision),
    };
    let dynamics = args.torques.then(|| biscara::dynamics::Dynamics::new(model)).transpose()?;
    write_output(args.output.as_deref(), |out| {
        let (events, dynamics) = (args.events, dynamics.as_ref());
        Ok(pipeline.write_joints(&source, kind, out, format, events, dynamics, notes.sink())?)
    })?;
    notes.finish();
    Ok(())
}
