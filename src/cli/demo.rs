//! `biscara demo`: the whole pipeline on the bundled pick-and-place example.

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};

use anyhow::{Context, anyhow};
use biscara::kinematics::Robot;
use clap::Args;

use super::output::write_output;
use super::run_command;

/// Runs the whole pipeline on the bundled pick-and-place job and writes every file into DIR.
///
/// points (SPEC §2) → CL file → G-code → inter-file → Cartesian path → joint trajectory, each
/// stage reading the file the previous one wrote, exactly as the commands `gen`, `interpret`,
/// `interpolate` and `joints` do. Prints what it wrote and a summary: duration, samples and the
/// peak speed of every joint.
#[derive(Debug, Args)]
#[command(
    about = "Run the bundled example through the whole pipeline (default folder out/)",
    after_long_help = "Example:\n  $ biscara demo\n  $ biscara demo /tmp/biscara-demo"
)]
pub(crate) struct DemoArgs {
    /// Folder to write into; created when missing.
    #[arg(value_name = "DIR", default_value = "out")]
    dir: PathBuf,
}

/// The bundled job: SPEC §2's example points file (also `data/jobs/pick_place.txt`).
const EXAMPLE_JOB: &str = include_str!("../../data/jobs/pick_place.txt");

pub(crate) fn demo(robot: &Robot, args: &DemoArgs) -> anyhow::Result<()> {
    let dir = &args.dir;
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let file = |name: &str| dir.join(name);
    let text = |path: PathBuf| path.to_string_lossy().into_owned();
    let mut written = Vec::new();

    let robot_file = file("robot.json");
    write_output(Some(&robot_file), |out| Ok(writeln!(out, "{}", robot.to_json_pretty())?))?;
    written.push((robot_file, "the robot in force"));
    let points = file("job.txt");
    write_output(Some(&points), |out| Ok(out.write_all(EXAMPLE_JOB.as_bytes())?))?;
    written.push((points.clone(), "the pick-and-place points (SPEC §2)"));

    let (cl, gcode, jsonl) = (file("job.cl"), file("job.ngc"), file("job.jsonl"));
    run_command(
        robot,
        ["gen", &text(points), "-o", &text(gcode.clone()), "--clf", &text(cl.clone())],
    )?;
    written.push((cl, "CL file (biscara clf)"));
    written.push((gcode.clone(), "G-code for LinuxCNC (biscara post)"));
    run_command(robot, ["interpret", &text(gcode), "-o", &text(jsonl.clone())])?;
    written.push((jsonl.clone(), "motions, the inter-file (biscara interpret)"));
    let (path, trajectory) = (file("path.csv"), file("traj.csv"));
    run_command(
        robot,
        ["interpolate", &text(jsonl.clone()), "--events", "-o", &text(path.clone())],
    )?;
    written.push((path, "Cartesian samples at 1 ms (biscara interpolate)"));
    run_command(
        robot,
        ["joints", &text(jsonl.clone()), "--derivatives", "-o", &text(trajectory.clone())],
    )?;
    written.push((
        trajectory.clone(),
        "joint trajectory with velocities and accelerations (biscara joints)",
    ));
    let virtual_robot = super::plot::write_virtual_robot_outputs(dir, robot, &jsonl)?;
    let what = [
        "the virtual robot's report (biscara check --json)",
        "the workspace and its largest rectangle (biscara workspace --svg)",
        "workspace, path and robot in top view (biscara plot)",
    ];
    written.extend(virtual_robot.into_iter().zip(what));

    written.extend(super::view::demo_pictures(robot, dir)?);

    let summary = summarize(&trajectory)?;
    print_summary(&summary, &written);
    Ok(())
}

/// Duration, samples and peak joint speeds of a joint CSV with derivative columns.
struct Summary {
    duration: f64,
    samples: usize,
    /// |velocity| peaks: rad/s for θ, mm/s for d4.
    peak_velocity: [f64; 4],
}

fn summarize(trajectory: &Path) -> anyhow::Result<Summary> {
    let reader = BufReader::new(
        std::fs::File::open(trajectory)
            .with_context(|| format!("cannot read {}", trajectory.display()))?,
    );
    let mut summary = Summary { duration: 0.0, samples: 0, peak_velocity: [0.0; 4] };
    for line in reader.lines().skip(1) {
        let line = line?;
        let fields: Vec<f64> = line
            .split(',')
            .map(str::parse)
            .collect::<Result<_, _>>()
            .map_err(|err| anyhow!("{}: {err}", trajectory.display()))?;
        summary.duration = fields[0];
        summary.samples += 1;
        for joint in 0..4 {
            summary.peak_velocity[joint] =
                summary.peak_velocity[joint].max(fields[5 + joint].abs());
        }
    }
    Ok(summary)
}

#[allow(clippy::print_stdout)]
fn print_summary(summary: &Summary, written: &[(PathBuf, &str)]) {
    println!("biscara demo: the bundled pick-and-place job through the whole pipeline");
    for (path, what) in written {
        println!("  wrote {:<24} {what}", path.display());
    }
    let [t1, t2, t3, d4] = summary.peak_velocity;
    println!(
        "duration {:.3} s, {} samples; peak joint speeds: theta1 {:.1} °/s, theta2 {:.1} °/s, \
         theta3 {:.1} °/s, d4 {:.1} mm/s",
        summary.duration,
        summary.samples,
        t1.to_degrees(),
        t2.to_degrees(),
        t3.to_degrees(),
        d4
    );
}
