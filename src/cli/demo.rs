//! `biscara demo`: the whole pipeline on the bundled pick-and-place example.

use std::path::{Path, PathBuf};

use anyhow::Context;
use biscara::joints::TrajectorySummary;
use biscara::pipeline::{DemoReport, EXAMPLE_JOB, RobotModel};
use biscara_files::{located, open_input};
use clap::Args;

use super::files::write_output;
use super::run_command;

/// Runs the whole pipeline on the bundled pick-and-place job and writes every file into DIR.
///
/// points → CL file → G-code → inter-file → Cartesian path → joint trajectory, each
/// stage reading the file the previous one wrote, exactly as the commands `gen`, `interpret`,
/// `interpolate` and `joints` do. Prints what it wrote and a summary: duration, samples and the
/// peak speed of every joint. With a robot file that has `motors` (--robot), traj.csv also holds
/// the torques they must give (`joints --torques`, docs/dynamics.md).
#[derive(Debug, Args)]
#[command(
    about = "Run the bundled example through the whole pipeline (default folder out/)",
    after_long_help = "Example:\n  $ biscara demo\n  $ biscara demo /tmp/biscara-demo\n  \
                       $ biscara --robot data/robots/servo-example.json demo"
)]
pub(crate) struct DemoArgs {
    /// Folder to write into; created when missing.
    #[arg(value_name = "DIR", default_value = "out")]
    dir: PathBuf,
}

pub(crate) fn demo(model: &RobotModel, args: &DemoArgs) -> anyhow::Result<()> {
    let dir = &args.dir;
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let file = |name: &str| dir.join(name).to_string_lossy().into_owned();
    write_output(Some(&dir.join("robot.json")), |out| {
        Ok(writeln!(out, "{}", biscara::dynamics::robot_in_force(model.robot()).to_json_pretty())?)
    })?;
    write_output(Some(&dir.join("job.txt")), |out| Ok(out.write_all(EXAMPLE_JOB.as_bytes())?))?;
    let (points, cl, gcode, jsonl) =
        (file("job.txt"), file("job.cl"), file("job.ngc"), file("job.jsonl"));
    let (path, traj) = (file("path.csv"), file("traj.csv"));
    run_command(model, ["gen", &points, "-o", &gcode, "--clf", &cl])?;
    run_command(model, ["interpret", &gcode, "-o", &jsonl])?;
    run_command(model, ["interpolate", &jsonl, "--events", "-o", &path])?;
    // With motors, the trajectory carries the torques they must give (docs/dynamics.md).
    let torques = if model.robot().motors.is_some() { "--torques" } else { "--derivatives" };
    run_command(model, ["joints", &jsonl, torques, "-o", &traj])?;
    let summary = TrajectorySummary::of(open_input(Path::new(&traj))?)
        .map_err(|err| located(Path::new(&traj), err))?;
    run_command(model, ["check", &jsonl, "--json", "-o", &file("check.json")])?;
    run_command(
        model,
        ["workspace", "--svg", &file("workspace.svg"), "-o", &file("workspace.txt")],
    )?;
    let at = [0.0, 0.25, 0.5, 0.75].map(|f| format!("{:.3}", f * summary.duration)).join(",");
    run_command(model, ["plot", &jsonl, "--at", &at, "-o", &file("plot.svg")])?;
    run_command(model, ["view", &traj, "--program", &gcode, "-o", &file("view.html")])?;
    run_command(model, ["mjcf", "-o", &file("robot.xml"), "--traj", &traj])?;
    let report = DemoReport { dir: dir.clone(), motors: model.robot().motors.is_some(), summary };
    write_output(None, |out| Ok(write!(out, "{report}")?))
}
