//! `biscara linuxcnc config` and `biscara linuxcnc run`: the robot on LinuxCNC.

use std::path::{Path, PathBuf};

use biscara::gcode::Tool;
use biscara::interpolate::Profile;
use biscara::joints::{AngleUnit, JointCsvFormat};
use biscara::kinematics::RobotModel;
use biscara::linuxcnc::job::{ConfigRequest, RegionChoice};
use biscara::linuxcnc::runner::Event;
use biscara::linuxcnc::{AxisLimitSource, ConfigOptions, configuration, job};
use biscara::text::parse_xyzc;
use biscara_files::{FileSource, Level, NoteReporter, report};
use clap::{Args, Subcommand};

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

/// How a configuration is made: shared by `config` and by `run` without --config.
#[derive(Debug, Args)]
struct ConfigChoice {
    /// The tool whose codes the HAL wires: gripper, laser, spindle or pen (default: the robot
    /// file's tool.kind, else gripper); LinuxCNC has no extruder axis here.
    #[arg(long, value_name = "KIND")]
    tool: Option<Tool>,
    /// Where the axis limits come from.
    #[arg(long, value_enum, default_value = "derived")]
    limits: AxisLimitSource,
    /// Derive the axis limits over this program's own XY extent (placed by --origin, or by
    /// --fit with `config`; from the robot's home pose) plus --margin, and set LinuxCNC's soft
    /// limits to that region: faster than over the whole workspace, and LinuxCNC refuses a
    /// move that leaves the region.
    #[arg(long = "for", value_name = "PROGRAM", conflicts_with = "region")]
    for_program: Option<PathBuf>,
    /// The margin around the program's extent, mm.
    #[arg(long, value_name = "MM", default_value = "10", requires = "for_program")]
    margin: f64,
    /// Derive the axis limits over this rectangle and set LinuxCNC's soft limits to it, mm.
    #[arg(long, value_name = "X0:X1,Y0:Y1", allow_hyphen_values = true, value_parser = job::parse_region)]
    region: Option<[f64; 4]>,
}

impl ConfigChoice {
    /// The configuration's options; `origin` or `fit` places the --for program.
    fn options(
        &self,
        model: &RobotModel,
        origin: Option<[f64; 4]>,
        fit: bool,
    ) -> anyhow::Result<ConfigOptions> {
        let program = self.for_program.as_deref();
        let region = RegionChoice::of(program, self.margin, self.region, origin, fit);
        let notes = NoteReporter::default();
        let request = ConfigRequest { tool: self.tool, limits: self.limits, region };
        let options = request.options::<anyhow::Error>(model, notes.sink())?;
        notes.finish();
        Ok(options)
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
    /// The G54 offset X,Y,Z,C (mm, degrees) the --for program runs with (give `run` the same).
    #[arg(
        long,
        value_name = "X,Y,Z,C",
        allow_hyphen_values = true,
        value_parser = parse_xyzc,
        requires = "for_program"
    )]
    origin: Option<[f64; 4]>,
    /// Place the --for program as `biscara joints --fit` does (the placement is reported; give
    /// `run` the same --origin).
    #[arg(long, requires = "for_program", conflicts_with = "origin")]
    fit: bool,
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
/// mux2) with the machine on, inside its enable chain (E-stop, machine off, a joint fault or a
/// following error stop it at once, the joints holding); t = 0 is the stream's first sample.
/// A stream must start where the joints stand after homing.
///
/// LinuxCNC's errors (an unreachable move, a soft limit) are errors here: exit 1 with
/// LinuxCNC's message and the program's line, and nothing written. LinuxCNC runs one instance
/// per machine, in real time: a program of 10 s takes about 15 s.
#[derive(Debug, Args)]
#[command(group(clap::ArgGroup::new("streaming").args(["stream", "stream_csv"])))]
#[command(
    about = "Run a program on LinuxCNC itself (headless) and write its joint trajectory CSV",
    after_long_help = "Example:\n  $ biscara linuxcnc run job.ngc -o run.csv\n  \
                       $ biscara linuxcnc run job.ngc --config biscara-config --stream -o run.csv\n  \
                       $ biscara diff run.csv traj.csv --tol 0.01"
)]
struct RunArgs {
    /// The G-code program (LinuxCNC's dialect).
    #[arg(value_name = "PROGRAM", required_unless_present = "stream_csv")]
    program: Option<PathBuf>,
    /// A configuration folder written by `biscara linuxcnc config` (default: one written for
    /// the robot in force, in a temporary folder).
    #[arg(long, value_name = "DIR")]
    config: Option<PathBuf>,
    #[command(flatten)]
    choice: ConfigChoice,
    /// Play `biscara joints PROGRAM` through the stream path instead of running the program on
    /// LinuxCNC's planner.
    #[arg(long, conflicts_with = "stream_csv")]
    stream: bool,
    /// Play a joint CSV through the stream path: the columns and units `biscara joints` writes
    /// (radians or degrees, with or without derivatives), one row per servo cycle of 1 ms,
    /// checked against the robot's joint position, velocity and acceleration limits before
    /// anything moves (refused with the first offending row) and starting where the joints
    /// stand.
    #[arg(long, value_name = "TRAJ.csv", conflicts_with = "program")]
    stream_csv: Option<PathBuf>,
    /// The velocity profile of the streamed trajectory.
    #[arg(long, value_enum, default_value = "optimal", requires = "stream")]
    profile: Profile,
    /// A G-code program to run on LinuxCNC's planner after the stream, from where it ended.
    #[arg(long, value_name = "PROGRAM", requires = "streaming")]
    then: Option<PathBuf>,
    /// A G54 offset X,Y,Z,C (mm, degrees) in force before the program's first line.
    #[arg(long, value_name = "X,Y,Z,C", allow_hyphen_values = true, value_parser = parse_xyzc)]
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
    angle_unit: AngleUnit,
    /// Decimals of every number in the CSV.
    #[arg(long, value_name = "N", default_value = "6", value_parser = clap::value_parser!(u8).range(0..=12))]
    precision: u8,
    /// Commissioning: press E-stop SECONDS after the stream (or the program) started. The run
    /// still writes what the joints did, and exits 1 naming the event and its time.
    #[arg(
        long,
        value_name = "SECONDS",
        conflicts_with = "machine_off_at",
        allow_negative_numbers = true
    )]
    estop_at: Option<f64>,
    /// Commissioning: switch the machine off SECONDS after the stream (or the program) started;
    /// as --estop-at.
    #[arg(long, value_name = "SECONDS", allow_negative_numbers = true)]
    machine_off_at: Option<f64>,
    /// Give up when the program (or the stream) has not ended after SECONDS.
    #[arg(long, value_name = "SECONDS", default_value = "3600")]
    timeout: f64,
}

pub(crate) fn linuxcnc(
    model: &RobotModel,
    robot_file: Option<&Path>,
    args: &LinuxcncArgs,
) -> anyhow::Result<()> {
    match &args.command {
        LinuxcncCommand::Config(args) => config(model, args),
        LinuxcncCommand::Run(args) => run(model, robot_file, args),
    }
}

fn config(model: &RobotModel, args: &ConfigArgs) -> anyhow::Result<()> {
    let options = args.choice.options(model, args.origin, args.fit)?;
    let configuration = configuration(model, &options)?;
    job::write_configuration(&configuration, &args.output)?;
    report(Level::Note, job::written_note(&configuration, &args.output));
    Ok(())
}

fn run(model: &RobotModel, robot_file: Option<&Path>, args: &RunArgs) -> anyhow::Result<()> {
    // An interrupt stops LinuxCNC and removes its folders before the run ends (exit 130).
    biscara_files::catch_interrupts();
    let program = match (&args.program, &args.stream_csv) {
        (Some(program), _) | (None, Some(program)) => program,
        (None, None) => anyhow::bail!("give a PROGRAM or --stream-csv TRAJ.csv"),
    };
    let source = FileSource::new(program);
    let (csv, profile) = (args.stream_csv.as_deref(), args.profile);
    let stream = job::Stream::of(csv, args.stream, &source, profile, args.origin)?;
    let job = job::Job {
        config: args.config.as_deref(),
        robot_file,
        options: args.choice.options(model, args.origin, false)?,
        program,
        stream,
        then: args.then.as_deref(),
        origin: args.origin,
        timeout: args.timeout,
        event: Event::at(args.estop_at, args.machine_off_at),
    };
    let notes = NoteReporter::default();
    let finished = job::run_job::<anyhow::Error>(model, &job, notes.sink(), &mut |note| {
        report(Level::Note, note);
    })?;
    notes.finish();
    let format = JointCsvFormat {
        angle_unit: args.angle_unit,
        derivatives: args.derivatives,
        precision: usize::from(args.precision),
    };
    let outputs =
        job::Outputs { joints: args.output.as_deref(), path: args.path.as_deref(), format };
    finished.write_outputs::<anyhow::Error>(&outputs, &mut |level, message| report(level, message))
}
