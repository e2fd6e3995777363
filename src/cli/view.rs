//! `biscara view` (the HTML viewer) and the pictures `biscara demo` adds to its folder.

use std::io::BufRead;
use std::path::{Path, PathBuf};

use anyhow::anyhow;
use biscara::gcode::{Config as GcodeConfig, interpret as interpret_gcode};
use biscara::interpolate::{InterpolateError, InterpolationConfig, Interpolator, Profile};
use biscara::joints::{JointSpeedLimit, cartesian_limits, read_joint_csv};
use biscara::kinematics::{Kinematics, Robot};
use biscara::motion::{Motion, read_jsonl};
use biscara::view::{Viewer, ViewerOptions};
use clap::Args;

use super::input::open_input;
use super::interpret::{gcode_error, parse_pose};
use super::mjcf::load_scene;
use super::output::write_output;
use super::trajectory::{ProfileArg, parse_duration};
use super::{display_path, run_command};

/// Writes one self-contained HTML file that animates a joint trajectory (SPEC §8.3).
///
/// A top view (X–Y) and a side view (Y–Z) of the robot — base, links, elbows, Z column,
/// gripper — with the tool's trace, the scene's boxes, and with --program the programmed path,
/// the pick (M3) and place (M4) events and the program line being executed. Play/pause, speed
/// and a time slider; the time, joint values, tool pose and program line are shown as it plays.
/// The file needs no network and no other file: its data and JavaScript are inside. Opening it
/// as `view.html#t=2.5` shows the robot paused at t = 2.5 s; without `#t=` it plays from the
/// start. Long trajectories are decimated for display (at most 40 000 frames, every Nth row).
///
/// TRAJ is a joint CSV from `biscara joints` (radians or degrees, with or without derivatives).
/// The program (G-code, or an inter-file with the `.jsonl` extension) is sampled as `joints`
/// samples it, at TRAJ's time step: give the --origin, --profile and --grip-time TRAJ was made
/// with (a warning says when the durations disagree).
#[derive(Debug, Args)]
#[command(
    about = "Animated HTML view of a joint trajectory (top and side views, no network)",
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
    /// Shift a G-code program by X,Y,Z,C, as `biscara joints --origin`.
    #[arg(
        long,
        value_name = "X,Y,Z,C",
        allow_hyphen_values = true,
        value_parser = parse_pose,
        help = "G54 offset before the first line of a G-code program"
    )]
    origin: Option<[f64; 4]>,
    /// The velocity profile TRAJ was made with, as `biscara joints --profile`.
    #[arg(long, value_enum, default_value = "trapezoid", help = "Profile TRAJ was made with")]
    profile: ProfileArg,
    /// The grip time TRAJ was made with, as `biscara joints --grip-time`.
    #[arg(
        long,
        value_name = "SECONDS",
        default_value = "0",
        value_parser = parse_duration,
        help = "Grip time TRAJ was made with"
    )]
    grip_time: f64,
}

pub(crate) fn view(robot: &Robot, args: &ViewArgs) -> anyhow::Result<()> {
    let scene = load_scene(args.scene.as_deref())?;
    let traj_name = display_path(&args.traj);
    let title = match &args.program {
        Some(program) => format!("biscara view · {}", file_name(program)),
        None => format!("biscara view · {}", file_name(&args.traj)),
    };
    let mut viewer =
        Viewer::new(robot, scene, ViewerOptions { title, ..ViewerOptions::default() })?;
    for row in read_joint_csv(open_input(&args.traj)?) {
        let row = row.map_err(|err| anyhow!("{traj_name}:{err}"))?;
        viewer.push_row(&row).map_err(|err| anyhow!("{traj_name}:{}: {err}", row.line))?;
    }
    if viewer.duration().is_none() {
        return Err(anyhow!("{traj_name}: the trajectory has no rows"));
    }
    if let Some(program) = &args.program {
        let sampling = ProgramSampling {
            origin: args.origin.unwrap_or([0.0; 4]),
            profile: args.profile.into(),
            grip_time: args.grip_time,
        };
        add_program(&mut viewer, robot, program, sampling)?;
    }
    write_output(args.output.as_deref(), |out| Ok(viewer.write_html(out)?))
}

/// The last component of a path, for titles.
fn file_name(path: &Path) -> String {
    path.file_name().map_or_else(|| display_path(path), |name| name.to_string_lossy().into_owned())
}

/// How the program is sampled: as `joints` sampled it for the trajectory.
#[derive(Debug, Clone, Copy)]
struct ProgramSampling {
    origin: [f64; 4],
    profile: Profile,
    grip_time: f64,
}

/// Samples the program at the trajectory's time step and adds its path, events and line texts.
fn add_program(
    viewer: &mut Viewer,
    robot: &Robot,
    program: &Path,
    sampling: ProgramSampling,
) -> anyhow::Result<()> {
    let origin = sampling.origin;
    let name = display_path(program);
    let model = Kinematics::new(robot)?;
    let input = open_input(program)?;
    let motions: Box<dyn Iterator<Item = anyhow::Result<Motion>>> =
        if program.extension().is_some_and(|ext| ext == "jsonl") {
            let name = name.clone();
            Box::new(read_jsonl(input).map(move |r| r.map_err(|err| anyhow!("{name}:{err}"))))
        } else {
            let config =
                GcodeConfig { home: model.home().to_degrees(), origin, ..GcodeConfig::default() };
            let path = program.to_owned();
            Box::new(
                interpret_gcode(input, &config).map(move |r| r.map_err(|e| gcode_error(&path, &e))),
            )
        };
    let config = InterpolationConfig {
        dt: viewer.time_step().filter(|dt| *dt > 0.0).unwrap_or(0.001),
        profile: sampling.profile,
        start: model.home().to_degrees(),
        limits: cartesian_limits(robot),
        grip_time: sampling.grip_time,
    };
    let limit = JointSpeedLimit::new(model, robot);
    let mut end = 0.0;
    for sample in Interpolator::new(motions, config, limit, |_| {}) {
        let sample = sample.map_err(|err| match err {
            InterpolateError::Input(err) => err,
            InterpolateError::Motion { line, message } => anyhow!("{name}:{line}: {message}"),
            other => anyhow!("{name}: {other}"),
        })?;
        viewer.push_path_sample(sample.t, sample.pose, sample.line, sample.gripper);
        end = sample.t;
    }
    if let Some(duration) = viewer.duration()
        && (duration - end).abs() > 1e-6 + viewer.time_step().unwrap_or(0.0)
    {
        #[allow(clippy::print_stderr)]
        {
            eprintln!(
                "biscara: warning: {name} takes {end:.3} s as sampled here, the trajectory \
                 {duration:.3} s: the program lines shown may be off (was the trajectory made \
                 with other --profile, --grip-time or --origin?)"
            );
        }
    }
    // The text of the lines the page shows, read again line by line.
    let wanted = viewer.referenced_lines();
    let mut wanted = wanted.into_iter().peekable();
    for (index, line) in open_input(program)?.lines().enumerate() {
        let Some(&next) = wanted.peek() else { break };
        if index + 1 == next {
            viewer.set_line_text(next, &line?);
            wanted.next();
        }
    }
    Ok(())
}

/// Writes the demo's pictures into `dir` from its `job.ngc` and `traj.csv`: the viewer
/// (`view.html`) and the MuJoCo model (`robot.xml` with the companion `robot.traj.csv`); returns
/// what it wrote, for the demo's summary.
pub(crate) fn demo_pictures(
    robot: &Robot,
    dir: &Path,
) -> anyhow::Result<Vec<(PathBuf, &'static str)>> {
    let text = |name: &str| dir.join(name).to_string_lossy().into_owned();
    run_command(
        robot,
        ["view", &text("traj.csv"), "--program", &text("job.ngc"), "-o", &text("view.html")],
    )?;
    run_command(robot, ["mjcf", "-o", &text("robot.xml"), "--traj", &text("traj.csv")])?;
    Ok(vec![
        (dir.join("view.html"), "the robot in motion, open in a browser (biscara view)"),
        (dir.join("robot.xml"), "MuJoCo model (biscara mjcf)"),
        (dir.join("robot.traj.csv"), "the trajectory in the model's joints (mjcf --traj)"),
    ])
}
