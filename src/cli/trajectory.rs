//! `biscara interpolate` and `biscara joints`: programs → Cartesian path → joint trajectory.

use std::cell::Cell;
use std::io::BufRead;
use std::path::{Path, PathBuf};
use std::rc::Rc;

use anyhow::anyhow;
use biscara::gcode::{Config as GcodeConfig, interpret as interpret_gcode};
use biscara::interpolate::{
    CartesianSample, InterpolateError, InterpolationConfig, Interpolator, PathCsvReader,
    PathCsvWriter, Profile, SlowDown, read_path_csv,
};
use biscara::joints::{
    AngleUnit, JointCsvFormat, JointCsvWriter, JointSpeedLimit, JointTrajectory, JointsError,
    cartesian_limits,
};
use biscara::kinematics::{Kinematics, Robot};
use biscara::motion::{Motion, read_jsonl};
use biscara::robot::shift_motion;
use clap::{Args, ValueEnum};

use super::display_path;
use super::interpret::{gcode_error, parse_pose};
use super::output::write_output;
use super::progress::open_with_progress;

/// What kind of file a program is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum InputKind {
    /// RS274/NGC G-code (LinuxCNC's dialect).
    Gcode,
    /// An inter-file (JSON Lines) written by `biscara interpret`.
    Jsonl,
    /// A path CSV written by `biscara interpolate` (joints only).
    Path,
}

/// The velocity profile, as named on the command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum ProfileArg {
    /// Constant speed from a motion's first sample to its last (the paper).
    Constant,
    /// Accelerate, cruise, decelerate: an exact stop at every corner.
    Trapezoid,
    /// Time-optimal under every joint's velocity and acceleration limits (TOPP-RA), with an
    /// exact stop at every corner.
    Optimal,
}

/// The angle unit of the joint CSV, as named on the command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum AngleUnitArg {
    /// Radians.
    Rad,
    /// Degrees.
    Deg,
}

impl From<ProfileArg> for Profile {
    fn from(profile: ProfileArg) -> Profile {
        match profile {
            ProfileArg::Constant => Profile::Constant,
            ProfileArg::Trapezoid => Profile::Trapezoid,
            ProfileArg::Optimal => Profile::Optimal,
        }
    }
}

/// Options shared by the commands that sample a program in time.
#[derive(Debug, Args)]
pub(crate) struct SamplingArgs {
    /// Time step, seconds.
    #[arg(long, value_name = "SECONDS", default_value = "0.001", value_parser = parse_step)]
    dt: f64,
    /// Velocity profile of every motion.
    #[arg(long, value_enum, default_value = "trapezoid")]
    profile: ProfileArg,
    /// Seconds each pick (M3) and place (M4) holds the pose; by default they take no time.
    #[arg(long, value_name = "SECONDS", default_value = "0", value_parser = parse_duration)]
    grip_time: f64,
    /// Shift a G-code program by X,Y,Z,C (mm, mm, mm, degrees): the G54 offset in force before
    /// its first line, as `biscara interpret --origin`.
    #[arg(
        long,
        value_name = "X,Y,Z,C",
        allow_hyphen_values = true,
        value_parser = parse_pose,
        help = "G54 offset before the first line of a G-code program"
    )]
    origin: Option<[f64; 4]>,
    /// Place the program in the workspace: shift it in X and Y so that its bounding box (arcs
    /// included) is centred in the largest rectangle of `biscara workspace`; z and c unchanged.
    /// The offset is reported on stderr; a program larger than the rectangle is an error.
    #[arg(long, help = "Centre the program in the workspace rectangle (offset on stderr)")]
    fit: bool,
    /// Decimals of every number in the CSV.
    #[arg(long, value_name = "N", default_value = "6", value_parser = clap::value_parser!(u8).range(0..=12))]
    precision: u8,
}

/// Samples a program at a fixed time step: the Cartesian path (SPEC §6).
///
/// Writes the CSV `t_s,x_mm,y_mm,z_mm,c_deg` (and `gripper` with --events), first row t = 0 at
/// the robot's home pose, one row per time step. Every programmed end point is hit exactly: each
/// motion's duration is rounded up to whole steps. Except with `--profile constant`, motions are
/// slowed so that C stays within `rapid_rotation` and no joint exceeds `joint_max_velocity`;
/// slowed motions are listed on stderr with their lines.
///
/// The program's kind comes from --from, else from its extension: `.jsonl` is an inter-file,
/// anything else G-code.
#[derive(Debug, Args)]
#[command(
    about = "Sample a program in time: the Cartesian path CSV",
    after_long_help = "Example:\n  $ biscara interpolate job.ngc -o path.csv\n  \
                       $ biscara interpolate --from jsonl --dt 0.01 --profile constant job.jsonl"
)]
pub(crate) struct InterpolateArgs {
    /// The program (G-code or inter-file); `-` reads standard input.
    #[arg(value_name = "PROGRAM")]
    program: PathBuf,
    /// Write to FILE instead of standard output.
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,
    /// The program's kind (default: from the extension).
    #[arg(long, value_enum, value_name = "KIND")]
    from: Option<InputKind>,
    #[command(flatten)]
    sampling: SamplingArgs,
    /// Add a `gripper` column: 1 from a pick to the next place.
    #[arg(long)]
    events: bool,
}

/// Joint time series of a program, for a virtual or real robot (SPEC §7).
///
/// Every sample is solved by IK in the robot's working and assembly mode; θ3 is continuous. The
/// CSV is `t_s,theta1_rad,theta2_rad,theta3_rad,d4_mm` (`_deg` with --angle-unit deg), with
/// velocity and acceleration columns (finite differences of the positions) after --derivatives.
/// The command fails (exit 1, nothing written) at the first sample that is unreachable, outside
/// the joint limits or near a singularity, naming the program's line and the time.
///
/// The program's kind comes from --from, else from its extension: `.jsonl` is an inter-file,
/// `.csv` a path CSV, anything else G-code.
#[derive(Debug, Args)]
#[command(
    about = "Joint trajectory CSV of a program (IK of every sample)",
    after_long_help = "Example:\n  $ biscara joints job.ngc -o traj.csv\n  \
                       $ biscara joints --derivatives --angle-unit deg --from path path.csv"
)]
pub(crate) struct JointsArgs {
    /// The program (G-code, inter-file or path CSV); `-` reads standard input.
    #[arg(value_name = "PROGRAM")]
    program: PathBuf,
    /// Write to FILE instead of standard output.
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,
    /// The program's kind (default: from the extension).
    #[arg(long, value_enum, value_name = "KIND")]
    from: Option<InputKind>,
    #[command(flatten)]
    sampling: SamplingArgs,
    /// Add velocity and acceleration columns for every joint.
    #[arg(long)]
    derivatives: bool,
    /// Unit of the angle columns.
    #[arg(long, value_enum, default_value = "rad")]
    angle_unit: AngleUnitArg,
}

fn parse_step(text: &str) -> Result<f64, String> {
    let value: f64 = text.parse().map_err(|_| format!("`{text}` is not a number"))?;
    if value.is_finite() && (1e-6..=10.0).contains(&value) {
        Ok(value)
    } else {
        Err(format!("the time step must lie in [0.000001, 10] s, got {text}"))
    }
}

pub(crate) fn parse_duration(text: &str) -> Result<f64, String> {
    let value: f64 = text.parse().map_err(|_| format!("`{text}` is not a number"))?;
    if value.is_finite() && (0.0..=3600.0).contains(&value) {
        Ok(value)
    } else {
        Err(format!("expected seconds in [0, 3600], got {text}"))
    }
}

/// The kind of `path`, from `--from` or its extension.
pub(crate) fn input_kind(path: &Path, from: Option<InputKind>) -> InputKind {
    from.unwrap_or_else(|| match path.extension().and_then(|e| e.to_str()) {
        Some("jsonl") => InputKind::Jsonl,
        Some("csv") => InputKind::Path,
        _ => InputKind::Gcode,
    })
}

type Motions = Box<dyn Iterator<Item = anyhow::Result<Motion>>>;

/// The Cartesian samples of a program, read from a path CSV or interpolated from its motions,
/// with errors as `FILE:LINE: message`.
///
/// A concrete type rather than a boxed iterator, so that `joints` can inline the step from one
/// sample to the next: a sample passed through a `dyn Iterator` and a `map` was stored and
/// loaded back twice, with a store-forwarding stall each time (with `Interpolator::next`
/// inlined as well: 0.429 → 0.423 s for `joints` on the engraving program).
pub(crate) enum Samples<F> {
    /// A path CSV.
    Path { reader: PathCsvReader<Box<dyn BufRead>>, name: String },
    /// A program's motions, interpolated.
    Program { interpolator: Box<Interpolator<Motions, JointSpeedLimit, F>>, name: String },
}

impl<F: FnMut(&SlowDown)> Iterator for Samples<F> {
    type Item = anyhow::Result<CartesianSample>;

    #[inline(always)]
    fn next(&mut self) -> Option<Self::Item> {
        match self {
            Samples::Path { reader, name } => {
                Some(reader.next()?.map_err(|err| anyhow!("{name}:{err}")))
            }
            Samples::Program { interpolator, name } => {
                Some(interpolator.next()?.map_err(|err| match err {
                    InterpolateError::Input(err) => err,
                    InterpolateError::Motion { line, message } => {
                        anyhow!("{name}:{line}: {message}")
                    }
                    other => anyhow!("{name}: {other}"),
                }))
            }
        }
    }
}

/// The motions of a program file.
pub(crate) fn motions(
    path: &Path,
    kind: InputKind,
    robot: &Robot,
    origin: [f64; 4],
) -> anyhow::Result<Motions> {
    let name = display_path(path);
    let input = open_with_progress(path)?;
    match kind {
        InputKind::Jsonl => Ok(Box::new(
            read_jsonl(input).map(move |result| result.map_err(|err| anyhow!("{name}:{err}"))),
        )),
        InputKind::Gcode => {
            let config = GcodeConfig {
                home: Kinematics::new(robot)?.home().to_degrees(),
                origin,
                ..GcodeConfig::default()
            };
            let path = path.to_owned();
            Ok(Box::new(
                interpret_gcode(input, &config)
                    .map(move |result| result.map_err(|err| gcode_error(&path, &err))),
            ))
        }
        InputKind::Path => Err(anyhow!("{name}: a path CSV holds samples, not motions")),
    }
}

/// Reports slowed motions on stderr: the first few in full, then a count.
pub(crate) fn slow_down_reporter(name: String) -> (impl FnMut(&SlowDown), Rc<Cell<usize>>) {
    const SHOWN: usize = 20;
    let count = Rc::new(Cell::new(0));
    let seen = Rc::clone(&count);
    let report = move |slow: &SlowDown| {
        seen.set(seen.get() + 1);
        if seen.get() <= SHOWN {
            #[allow(clippy::print_stderr)]
            {
                eprintln!(
                    "biscara: note: {name}:{}: slowed to {:.1}% of the programmed speed ({} limit)",
                    slow.line,
                    100.0 * slow.factor,
                    slow.cause
                );
            }
        }
    };
    (report, count)
}

#[allow(clippy::print_stderr)]
pub(crate) fn report_slow_total(count: usize) {
    if count > 20 {
        eprintln!("biscara: note: {count} motions slowed in all");
    }
}

/// The Cartesian samples of a program: read from a path CSV, or interpolated from its motions.
pub(crate) fn samples<F: FnMut(&SlowDown)>(
    path: &Path,
    kind: InputKind,
    sampling: &SamplingArgs,
    robot: &Robot,
    model: Kinematics,
    on_slow: F,
) -> anyhow::Result<Samples<F>> {
    let name = display_path(path);
    if kind == InputKind::Path {
        if sampling.fit {
            return Err(anyhow!("{name}: --fit places a program, not a path CSV"));
        }
        let reader = read_path_csv(open_with_progress(path)?);
        return Ok(Samples::Path { reader, name });
    }
    let config = InterpolationConfig {
        dt: sampling.dt,
        profile: sampling.profile.into(),
        start: model.home().to_degrees(),
        limits: cartesian_limits(robot),
        grip_time: sampling.grip_time,
    };
    let limit = JointSpeedLimit::new(model, robot);
    let (origin, shift) = super::fit::placement(path, kind, robot, sampling.origin, sampling.fit)?;
    let mut motions = motions(path, kind, robot, origin)?;
    if let Some(offset) = shift {
        let [x, y, ..] = config.start;
        motions = Box::new(motions.map(move |m| m.map(|m| shift_motion(m, offset, [x, y]))));
    }
    let interpolator = Box::new(Interpolator::new(motions, config, limit, on_slow));
    Ok(Samples::Program { interpolator, name })
}

pub(crate) fn interpolate(robot: &Robot, args: &InterpolateArgs) -> anyhow::Result<()> {
    let model = Kinematics::new(robot)?;
    let kind = input_kind(&args.program, args.from);
    if kind == InputKind::Path {
        return Err(anyhow!("interpolate reads G-code or an inter-file, not a path CSV"));
    }
    let (on_slow, slowed) = slow_down_reporter(display_path(&args.program));
    let samples = samples(&args.program, kind, &args.sampling, robot, model, on_slow)?;
    write_output(args.output.as_deref(), |out| {
        let mut writer =
            PathCsvWriter::new(out, usize::from(args.sampling.precision), args.events)?;
        for sample in samples {
            writer.write(&sample?)?;
        }
        writer.finish()?;
        Ok(())
    })?;
    report_slow_total(slowed.get());
    Ok(())
}

pub(crate) fn joints(robot: &Robot, args: &JointsArgs) -> anyhow::Result<()> {
    let model = Kinematics::new(robot)?;
    let kind = input_kind(&args.program, args.from);
    let name = display_path(&args.program);
    let (on_slow, slowed) = slow_down_reporter(name.clone());
    let samples = samples(&args.program, kind, &args.sampling, robot, model, on_slow)?;
    let format = JointCsvFormat {
        angle_unit: match args.angle_unit {
            AngleUnitArg::Rad => AngleUnit::Radians,
            AngleUnitArg::Deg => AngleUnit::Degrees,
        },
        derivatives: args.derivatives,
        precision: usize::from(args.sampling.precision),
    };
    write_output(args.output.as_deref(), |out| {
        let mut writer = JointCsvWriter::new(out, format)?;
        let mut trajectory = JointTrajectory::new(samples, model);
        while let Some(row) = trajectory.next_sample() {
            writer.write(row.map_err(|err| joints_error(&name, err))?)?;
        }
        writer.finish()?;
        Ok(())
    })?;
    report_slow_total(slowed.get());
    Ok(())
}

/// A joint-trajectory failure as `FILE:LINE: at t = …: reason`.
fn joints_error(name: &str, err: JointsError<anyhow::Error>) -> anyhow::Error {
    match err {
        JointsError::Input(err) => err,
        JointsError::Pose { line, t, pose, source } => anyhow!(
            "{name}:{line}: at t = {t:.3} s the pose (x, y, z, c) = ({:.3}, {:.3}, {:.3}, {:.3}) \
             cannot be taken: {source}",
            pose[0],
            pose[1],
            pose[2],
            pose[3]
        ),
        other => anyhow!("{name}: {other}"),
    }
}
