//! Command-line parsing, dispatch, exit codes and diagnostics.

mod args;
mod check;
mod clf;
mod cycle;
mod demo;
mod design;
mod diff;
mod files;
mod generate;
mod interpret;
mod kinematics;
mod linuxcnc;
mod mjcf;
mod plot;
mod post;
mod trajectory;
mod view;
mod workspace;

use std::io::{self, Write as _};
use std::path::PathBuf;
use std::process::ExitCode;

use biscara::kinematics::RobotModel;
use biscara::linuxcnc::LinuxcncError;
use biscara_files::{error_message, is_broken_pipe};
use clap::{Parser, Subcommand};

/// Offline programming and simulation of the BiSCARA: a five-bar planar parallel robot with a
/// vertical prismatic axis and a rotary axis about Z.
///
/// Lengths are millimetres and angles degrees on the command line and in every file.
#[derive(Debug, Parser)]
#[command(name = "biscara", version, propagate_version = true, max_term_width = 100)]
pub(crate) struct Cli {
    /// The robot description (robot.json) to use instead of the built-in robot; `-` reads
    /// standard input. `biscara robot` prints a template.
    #[arg(long, global = true, value_name = "FILE", help = "Robot description file (robot.json)")]
    robot: Option<PathBuf>,

    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    Ik(kinematics::IkArgs),
    Fk(kinematics::FkArgs),
    Robot(kinematics::RobotArgs),
    Demo(demo::DemoArgs),
    Clf(clf::ClfArgs),
    Post(post::PostArgs),
    Gen(generate::GenArgs),
    Interpret(interpret::InterpretArgs),
    Interpolate(trajectory::InterpolateArgs),
    Joints(trajectory::JointsArgs),
    Diff(diff::DiffArgs),
    Mjcf(mjcf::MjcfArgs),
    View(view::ViewArgs),
    Check(check::CheckArgs),
    Workspace(workspace::WorkspaceArgs),
    Cycle(cycle::CycleArgs),
    Design(design::DesignArgs),
    Plot(plot::PlotArgs),
    Linuxcnc(linuxcnc::LinuxcncArgs),
}

/// Runs the command line and turns the outcome into an exit code: 0 success, 1 bad input or a
/// failed check, 2 wrong usage (130, interrupted while writing a file, is set in `main.rs`).
pub(crate) fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(err) => {
            let _ = err.print();
            return ExitCode::from(u8::try_from(err.exit_code()).unwrap_or(2));
        }
    };
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(err) if is_broken_pipe(&*err) => ExitCode::SUCCESS,
        Err(err) if LinuxcncError::is_interrupted(&*err) => {
            let _ = writeln!(io::stderr(), "biscara: {}", error_message(&*err));
            ExitCode::from(130)
        }
        Err(err) => {
            // (Written even to a closed stderr without a panic: the exit code says it.)
            let _ = writeln!(io::stderr(), "biscara: error: {}", error_message(&*err));
            ExitCode::from(1)
        }
    }
}

fn run(cli: Cli) -> anyhow::Result<()> {
    let model = biscara_files::load_robot(cli.robot.as_deref())?;
    if let Command::Linuxcnc(args) = &cli.command {
        // A LinuxCNC configuration carries its robot: --robot must agree with it.
        return linuxcnc::linuxcnc(&model, cli.robot.as_deref(), args);
    }
    dispatch(&model, cli.command)
}

/// Runs one subcommand with the robot already in force.
fn dispatch(robot: &RobotModel, command: Command) -> anyhow::Result<()> {
    match command {
        Command::Ik(args) => kinematics::ik(robot, &args),
        Command::Fk(args) => kinematics::fk(robot, &args),
        Command::Robot(args) => kinematics::robot(robot, &args),
        Command::Demo(args) => demo::demo(robot, &args),
        Command::Clf(args) => clf::clf(robot, &args),
        Command::Post(args) => post::post(&args),
        Command::Gen(args) => generate::generate(robot, &args),
        Command::Interpret(args) => interpret::interpret(robot, &args),
        Command::Interpolate(args) => trajectory::interpolate(robot, &args),
        Command::Joints(args) => trajectory::joints(robot, &args),
        Command::Diff(args) => diff::diff(&args),
        Command::Mjcf(args) => mjcf::mjcf(robot, &args),
        Command::View(args) => view::view(robot, &args),
        Command::Check(args) => check::check(robot, &args),
        Command::Workspace(args) => workspace::workspace(robot, &args),
        Command::Cycle(args) => cycle::cycle(robot, &args),
        Command::Design(args) => design::design(robot, &args),
        Command::Plot(args) => plot::plot(robot, &args),
        Command::Linuxcnc(args) => linuxcnc::linuxcnc(robot, None, &args),
    }
}

/// Runs `biscara ARGS…` in this process with `robot` in force, as if typed on the command line:
/// the demo chains the pipeline's commands this way, so it runs exactly what users run.
fn run_command<I, T>(robot: &RobotModel, args: I) -> anyhow::Result<()>
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    let args = std::iter::once(std::ffi::OsString::from("biscara"))
        .chain(args.into_iter().map(Into::into));
    let cli = Cli::try_parse_from(args)?;
    dispatch(robot, cli.command)
}

#[cfg(test)]
mod tests {
    use clap::CommandFactory;

    use super::*;

    #[test]
    fn verify_cli() {
        Cli::command().debug_assert();
    }
}
