//! `biscara linuxcnc config` and `biscara linuxcnc run`: the robot on LinuxCNC.

use std::fs;
use std::io::{BufWriter, Write as _};
use std::path::{Path, PathBuf};

use anyhow::Context as _;
use biscara::joints::{AngleUnit, JointCsvFormat, JointCsvWriter};
use biscara::kinematics::{RobotModel, ToolKind};
use biscara::linuxcnc::runner::{self, RunRequest, TempFolder};
use biscara::linuxcnc::{
    AxisLimitSource, ConfigOptions, Configuration, RecordingStart, configuration, read_recording,
    write_stream_sample,
};
use biscara::pipeline::{Pipeline, SamplingConfig};
use clap::{Args, Subcommand, ValueEnum};

use super::args::{ProfileArg, parse_pose};
use super::diag::{Level, NoteReporter, report};
use super::files::{FileSource, display_path, write_output};
use super::trajectory::AngleUnitArg;

/// The robot on LinuxCNC: a configuration with this robot's kinematics, and runs of programs on
/// LinuxCNC itself, headless.
#[derive(Debug, Args)]
#[command(
    about = "The robot on LinuxCNC: write its configuration, run programs on LinuxCNC itself",
    after_long_help = "Example:\n  $ biscara linuxcnc config -o biscara-config\n  \
                       $ biscara linuxcnc run job.ngc --config biscara-config -o run.csv\n  \
                       $ biscara linuxcnc run job.ngc --stream -o streamed.csv"
)]
pub(crate) struct LinuxcncArgs {
    #[command(subcommand)]
    command: LinuxcncCommand,
}

#[derive(Debug, Subcommand)]
enum LinuxcncCommand {
    Config(ConfigArgs),
    Run(RunArgs),
}

/// The tool a configuration wires, as named on the command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
enum ToolArg {
    /// M3 picks, M4 places, M5 off (spindle.0.forward / reverse / on).
    Gripper,
    /// M3/M4 on, M5 off, S the power (spindle.0.on, spindle.0.speed-out).
    Laser,
    /// M3 clockwise, M4 counter-clockwise, M5 off, S in rpm.
    Spindle,
    /// M3/M4 pen down, M5 up (spindle.0.on).
    Pen,
}

impl From<ToolArg> for ToolKind {
    fn from(tool: ToolArg) -> ToolKind {
        match tool {
            ToolArg::Gripper => ToolKind::Gripper,
            ToolArg::Laser => ToolKind::Laser,
            ToolArg::Spindle => ToolKind::Spindle,
            ToolArg::Pen => ToolKind::Pen,
        }
    }
}

/// Where the axis limits come from, as named on the command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
enum LimitsArg {
    /// Derived from the joint limits: LinuxCNC's planner cannot exceed a joint's limit in the
    /// workspace rectangle.
    Derived,
    /// The robot file's Cartesian motion limits as they are (LinuxCNC's planner then exceeds the
    /// joints' limits; for comparison).
    Cartesian,
}

/// How a configuration is made: shared by `config` and by `run` without --config.
#[derive(Debug, Args)]
struct ConfigChoice {
    /// The tool whose codes the HAL wires (default: the robot file's tool.kind, else gripper).
    #[arg(long, value_enum, value_name = "KIND")]
    tool: Option<ToolArg>,
    /// Where the axis limits come from.
    #[arg(long, value_enum, default_value = "derived")]
    limits: LimitsArg,
}

impl ConfigChoice {
    fn options(&self, model: &RobotModel) -> ConfigOptions {
        let tool = match self.tool {
            Some(tool) => tool.into(),
            None => model.robot().tool.kind.unwrap_or(ToolKind::Gripper),
        };
        let limits = match self.limits {
            LimitsArg::Derived => AxisLimitSource::Derived,
            LimitsArg::Cartesian => AxisLimitSource::Cartesian,
        };
        ConfigOptions { tool, limits, ..ConfigOptions::default() }
    }
}

/// Writes a complete LinuxCNC (2.9) configuration for the robot in force into DIR.
///
/// The files: `biscarakins.comp` (the kinematics component: forward and inverse kinematics
/// identical to `biscara fk` and `biscara ik`, the robot's numbers as HAL pins), `biscara.ini`
/// (joints 0 θ1, 1 θ2, 2 d4, 3 θ3; axes X Y Z C; mm and degrees; servo period 1 ms; the joint
/// limits; axis limits derived from the joint limits so that LinuxCNC's planner cannot exceed
/// any joint's velocity or acceleration limit in the workspace rectangle, with the derivation in
/// comments), `biscara.hal` (kinematics, motion, the stream path streamer → limit3 → mux2 per
/// joint, the recorder, the tool's codes), `sim.hal` (a simulated machine that runs headless),
/// `hardware.hal` (a commented template for the real robot), `biscara_run.py` (the headless
/// display) and a README that says how to install the component, start LinuxCNC, run a program
/// and stream a trajectory. An extruder is refused: LinuxCNC has no E axis here.
#[derive(Debug, Args)]
#[command(
    about = "Write a LinuxCNC configuration (kinematics component, INI, HAL) for the robot",
    after_long_help = "Example:\n  $ biscara linuxcnc config -o biscara-config\n  \
                       $ biscara --robot my-robot.json linuxcnc config --tool laser -o laser-config"
)]
struct ConfigArgs {
    /// The folder to write (created if missing; its files are replaced).
    #[arg(short, long, value_name = "DIR")]
    output: PathBuf,
    #[command(flatten)]
    choice: ConfigChoice,
}

/// Runs a G-code program on LinuxCNC itself, headless, and writes what its joints did.
///
/// Builds and installs the kinematics component when the installed one was built from another
/// source (installing needs root), starts LinuxCNC with the configuration (--config DIR, else
/// one written for the robot in force), homes it, runs PROGRAM and records every servo cycle
/// (1 ms). Writes the joint CSV with the columns and units of `biscara joints`
/// (`t_s,theta1_rad,theta2_rad,theta3_rad,d4_mm`; t = 0 at the last cycle before the first
/// motion), which `biscara diff` and `biscara view` read; --path also writes LinuxCNC's
/// commanded poses as a path CSV, which `biscara check` reads. Prints a summary on stderr: the
/// duration and each joint's peak speed and acceleration against its limits.
///
/// With --stream, LinuxCNC's planner is not used: `biscara joints PROGRAM` (the time-optimal
/// profile by default) is played sample for sample through the stream path (streamer → limit3 →
/// mux2) with the machine off and homed; t = 0 is the stream's first sample.
///
/// LinuxCNC's errors (an unreachable move, a soft limit) are errors here: exit 1 with
/// LinuxCNC's message and the program's line, and nothing written. LinuxCNC runs one instance
/// per machine, in real time: a program of 10 s takes about 15 s.
#[derive(Debug, Args)]
#[command(
    about = "Run a program on LinuxCNC itself (headless) and write its joint trajectory CSV",
    after_long_help = "Example:\n  $ biscara linuxcnc run job.ngc -o run.csv\n  \
                       $ biscara linuxcnc run job.ngc --config biscara-config --stream -o run.csv\n  \
                       $ biscara diff run.csv traj.csv --tol 0.01"
)]
struct RunArgs {
    /// The G-code program (LinuxCNC's dialect).
    #[arg(value_name = "PROGRAM")]
    program: PathBuf,
    /// A configuration folder written by `biscara linuxcnc config` (default: one written for
    /// the robot in force, in a temporary folder).
    #[arg(long, value_name = "DIR")]
    config: Option<PathBuf>,
    #[command(flatten)]
    choice: ConfigChoice,
    /// Play `biscara joints PROGRAM` through the stream path instead of running the program on
    /// LinuxCNC's planner.
    #[arg(long)]
    stream: bool,
    /// The velocity profile of the streamed trajectory.
    #[arg(long, value_enum, default_value = "optimal", requires = "stream")]
    profile: ProfileArg,
    /// A G-code program to run on LinuxCNC's planner after the stream, from where it ended.
    #[arg(long, value_name = "PROGRAM", requires = "stream")]
    then: Option<PathBuf>,
    /// A G54 offset X,Y,Z,C (mm, degrees) in force before the program's first line.
    #[arg(long, value_name = "X,Y,Z,C", allow_hyphen_values = true, value_parser = parse_pose)]
    origin: Option<[f64; 4]>,
    /// Write the joint CSV to FILE instead of standard output.
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,
    /// Also write LinuxCNC's commanded Cartesian position every cycle, as a path CSV
    /// (`t_s,x_mm,y_mm,z_mm,c_deg`, the format of `biscara interpolate`).
    #[arg(long, value_name = "FILE")]
    path: Option<PathBuf>,
    /// Add velocity and acceleration columns for every joint.
    #[arg(long)]
    derivatives: bool,
    /// Unit of the angle columns.
    #[arg(long, value_enum, default_value = "rad")]
    angle_unit: AngleUnitArg,
    /// Decimals of every number in the CSV.
    #[arg(long, value_name = "N", default_value = "6", value_parser = clap::value_parser!(u8).range(0..=12))]
    precision: u8,
    /// Give up when the program (or the stream) has not ended after SECONDS.
    #[arg(long, value_name = "SECONDS", default_value = "3600")]
    timeout: f64,
}

pub(crate) fn linuxcnc(model: &RobotModel, args: &LinuxcncArgs) -> anyhow::Result<()> {
    match &args.command {
        LinuxcncCommand::Config(args) => config(model, args),
        LinuxcncCommand::Run(args) => run(model, args),
    }
}

/// Writes `configuration` into `folder`.
fn write_configuration(configuration: &Configuration, folder: &Path) -> anyhow::Result<()> {
    fs::create_dir_all(folder).with_context(|| display_path(folder))?;
    for file in &configuration.files {
        let path = folder.join(file.name);
        write_output(Some(&path), |out| Ok(out.write_all(file.contents.as_bytes())?))?;
        if file.executable {
            use std::os::unix::fs::PermissionsExt as _;
            fs::set_permissions(&path, fs::Permissions::from_mode(0o755))
                .with_context(|| display_path(&path))?;
        }
    }
    Ok(())
}

fn config(model: &RobotModel, args: &ConfigArgs) -> anyhow::Result<()> {
    let configuration = configuration(model, &args.choice.options(model))?;
    write_configuration(&configuration, &args.output)?;
    let limits = &configuration.limits;
    report(
        Level::Note,
        format_args!(
            "wrote {} files into {}; axis limits: X and Y {:.1} mm/s, {:.1} mm/s², Z {:.1} mm/s, \
             C {:.1} °/s; install the kinematics once with `halcompile --install {}`",
            configuration.files.len(),
            display_path(&args.output),
            limits.xy_velocity,
            limits.xy_acceleration,
            limits.z_velocity,
            limits.c_velocity,
            display_path(&args.output.join("biscarakins.comp")),
        ),
    );
    Ok(())
}

/// Writes the stream file of `program`'s joint trajectory into `path`.
fn write_stream(model: &RobotModel, args: &RunArgs, path: &Path) -> anyhow::Result<usize> {
    let source = FileSource::new(&args.program);
    let kind = source.kind(None)?;
    let config = SamplingConfig {
        profile: args.profile.into(),
        origin: args.origin,
        ..SamplingConfig::default()
    };
    let notes = NoteReporter::default();
    let pipeline = Pipeline::new(model, config);
    let mut samples = pipeline.joints(&source, kind, notes.sink())?.without_derivatives();
    let file = fs::File::create(path).with_context(|| display_path(path))?;
    let mut out = BufWriter::new(file);
    let mut count = 0;
    while let Some(sample) = samples.next_sample() {
        write_stream_sample(&mut out, &sample?.joints)?;
        count += 1;
    }
    out.flush()?;
    notes.finish();
    Ok(count)
}

fn run(model: &RobotModel, args: &RunArgs) -> anyhow::Result<()> {
    if !(args.timeout > 0.0 && args.timeout.is_finite()) {
        anyhow::bail!("--timeout must be a positive number of seconds (got {})", args.timeout);
    }
    for program in std::iter::once(&args.program).chain(&args.then) {
        fs::File::open(program).with_context(|| display_path(program))?;
    }
    runner::check_installed()?;
    let work = TempFolder::new("biscara-linuxcnc-run")?;
    let config_dir = match &args.config {
        Some(dir) => dir.clone(),
        None => {
            let dir = work.path().join("config");
            write_configuration(&configuration(model, &args.choice.options(model))?, &dir)?;
            dir
        }
    };
    if runner::ensure_component(&config_dir)? == runner::ComponentStatus::Updated {
        report(Level::Note, "built and installed the kinematics component biscarakins");
    }
    let stream = if args.stream {
        let path = work.path().join("stream.txt");
        let samples = write_stream(model, args, &path)?;
        report(Level::Note, format_args!("streaming {samples} samples of `biscara joints`"));
        Some(path)
    } else {
        None
    };
    let program = if args.stream { args.then.clone() } else { Some(args.program.clone()) };
    let request = RunRequest {
        config: config_dir,
        program: program.clone(),
        stream,
        origin: if args.stream { None } else { args.origin },
        timeout: args.timeout,
    };
    let run = runner::run(&request)?;
    for message in run.messages.iter().filter(|message| !message.error) {
        report(Level::Note, format_args!("LinuxCNC: {}", message.text));
    }
    if !run.ok {
        let errors: Vec<&str> =
            run.messages.iter().filter(|m| m.error).map(|m| m.text.as_str()).collect();
        let what = if errors.is_empty() {
            run.failure.clone().unwrap_or_else(|| "stopped".to_owned())
        } else {
            errors.join("; ")
        };
        let line = line_of(&errors).unwrap_or(run.line);
        let name = program.as_deref().map_or_else(|| display_path(&args.program), display_path);
        if line > 0 {
            anyhow::bail!("{name}:{line}: LinuxCNC: {what}");
        }
        anyhow::bail!("{name}: LinuxCNC: {what}");
    }
    let format = JointCsvFormat {
        angle_unit: match args.angle_unit {
            AngleUnitArg::Rad => AngleUnit::Radians,
            AngleUnitArg::Deg => AngleUnit::Degrees,
        },
        derivatives: args.derivatives,
        precision: usize::from(args.precision),
    };
    let start = if args.stream { RecordingStart::Stream } else { RecordingStart::FirstMotion };
    let decimals = usize::from(args.precision);
    let samples_path = run.samples();
    let open_recording = || -> anyhow::Result<std::io::BufReader<fs::File>> {
        Ok(std::io::BufReader::new(fs::File::open(&samples_path).context("LinuxCNC's recording")?))
    };
    let mut summary = None;
    write_output(args.output.as_deref(), |out| {
        let mut joints = JointCsvWriter::new(out, format)?;
        summary = Some(read_recording(open_recording()?, start, model.robot(), |sample, _| {
            joints.write(sample)?;
            anyhow::Ok(())
        })?);
        joints.finish()?;
        Ok(())
    })?;
    if let Some(path) = &args.path {
        write_output(Some(path), |out| {
            writeln!(out, "t_s,x_mm,y_mm,z_mm,c_deg")?;
            read_recording(open_recording()?, start, model.robot(), |sample, recorded| {
                let [x, y, z, c] = recorded.axes;
                let t = sample.t;
                writeln!(
                    out,
                    "{t:.decimals$},{x:.decimals$},{y:.decimals$},{z:.decimals$},{c:.decimals$}"
                )?;
                anyhow::Ok(())
            })?;
            Ok(())
        })?;
    }
    if let Some(summary) = summary {
        let what = if args.stream { "streamed" } else { "ran" };
        report(
            Level::Note,
            format_args!(
                "LinuxCNC {what} {}: {:.3} s, {} samples of 1 ms",
                display_path(&args.program),
                summary.duration,
                summary.samples
            ),
        );
        for peak in summary.peaks {
            let unit = if peak.joint.is_revolute() { "°" } else { "mm" };
            let level = if peak.velocity_ratio() > 1.0 || peak.acceleration_ratio() > 1.0 {
                Level::Warning
            } else {
                Level::Note
            };
            report(
                level,
                format_args!(
                    "{}: peak {:.1} {unit}/s of {} ({:.0} %), {:.0} {unit}/s² of {} ({:.0} %)",
                    peak.joint.name(),
                    peak.velocity,
                    peak.velocity_limit,
                    100.0 * peak.velocity_ratio(),
                    peak.acceleration,
                    peak.acceleration_limit,
                    100.0 * peak.acceleration_ratio()
                ),
            );
        }
    }
    Ok(())
}

/// The program line a LinuxCNC message names (`… on line 12 …`).
fn line_of(messages: &[&str]) -> Option<usize> {
    messages.iter().find_map(|text| {
        let rest = &text[text.find("line ")? + 5..];
        let digits: String = rest.chars().take_while(char::is_ascii_digit).collect();
        digits.parse().ok()
    })
}
