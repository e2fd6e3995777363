//! `biscara check`: a program run on the virtual robot, every problem reported (SPEC §8.1).

use std::path::{Path, PathBuf};

use anyhow::anyhow;
use biscara::kinematics::{Joint, Kinematics, Robot};
use biscara::robot::{Checker, Problem, Report, Scene};
use biscara::text::fixed;
use clap::Args;
use serde_json::{Value, json};

use super::display_path;
use super::output::write_output;
use super::trajectory::{
    InputKind, SamplingArgs, input_kind, report_slow_total, samples, slow_down_reporter,
};

/// Runs a program on the virtual robot and reports every problem (SPEC §8.1).
///
/// The program is interpreted, interpolated and solved by IK sample by sample, and nothing
/// stops at the first problem: unreachable poses, joint positions outside `joint_limits`, joint
/// velocities and accelerations (central differences) above `joint_max_velocity` and
/// `joint_max_acceleration`, poses within `singularity_margin` of a singularity, self-collisions
/// (non-adjacent links closer than `link_width`; the distal links folded onto each other) and
/// collisions with the boxes of --scene (links as capsules at `link_height`, the gripper and the
/// Z column as cylinders). Consecutive samples with the same problem are one entry with its time
/// span, program line and pose. A summary follows: duration, path length, peak joint velocity and
/// acceleration with their lines, and the smallest singularity angle.
///
/// Exit code 0 when the program is clean, 1 when anything was found. The program's kind comes
/// from --from, else from its extension: `.jsonl` is an inter-file, `.csv` a path CSV, anything
/// else G-code.
#[derive(Debug, Args)]
#[command(
    about = "Run a program on the virtual robot and report every problem",
    after_long_help = "Example:\n  $ biscara check job.ngc\n  \
                       $ biscara check --scene cell.json --json job.ngc > check.json\n\n\
                       A scene is JSON: {\"boxes\":[{\"name\":\"pallet\",\"min\":[x,y,z],\"max\":[x,y,z]}]}"
)]
pub(crate) struct CheckArgs {
    /// The program (G-code, inter-file or path CSV); `-` reads standard input.
    #[arg(value_name = "PROGRAM")]
    program: PathBuf,
    /// The program's kind (default: from the extension).
    #[arg(long, value_enum, value_name = "KIND")]
    from: Option<InputKind>,
    /// Boxes around the robot that no part of it may touch (JSON, millimetres, base frame).
    #[arg(long, value_name = "FILE")]
    scene: Option<PathBuf>,
    /// Print the report as one JSON object (SPEC §9).
    #[arg(long)]
    json: bool,
    /// Write the report to FILE instead of standard output.
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,
    #[command(flatten)]
    sampling: SamplingArgs,
}

/// Reads a scene file (`-`: standard input), errors as `FILE:LINE:COL: key: message`.
pub(crate) fn read_scene(path: &Path) -> anyhow::Result<Scene> {
    let bytes = if path == Path::new("-") {
        let mut bytes = Vec::new();
        std::io::Read::read_to_end(&mut std::io::stdin(), &mut bytes)?;
        bytes
    } else {
        std::fs::read(path).map_err(|err| anyhow!("cannot read {}: {err}", path.display()))?
    };
    Scene::from_json(&bytes).map_err(|err| anyhow!("{}:{err}", display_path(path)))
}

/// Runs `program` on the virtual robot.
pub(crate) fn run_check(
    robot: &Robot,
    program: &Path,
    kind: InputKind,
    sampling: &SamplingArgs,
    scene: Scene,
) -> anyhow::Result<Report> {
    let model = Kinematics::new(robot)?;
    let (on_slow, slowed) = slow_down_reporter(display_path(program));
    let mut checker = Checker::new(robot, scene)?;
    for sample in samples(program, kind, sampling, robot, model, on_slow)? {
        checker.push(&sample?);
    }
    report_slow_total(slowed.get());
    Ok(checker.finish())
}

pub(crate) fn check(robot: &Robot, args: &CheckArgs) -> anyhow::Result<()> {
    let scene = match &args.scene {
        Some(path) => read_scene(path)?,
        None => Scene::new(),
    };
    let kind = input_kind(&args.program, args.from);
    let report = run_check(robot, &args.program, kind, &args.sampling, scene)?;
    let name = display_path(&args.program);
    write_output(args.output.as_deref(), |out| {
        if args.json {
            writeln!(out, "{}", report_json(&report))?;
        } else {
            write_text(out, &name, &report)?;
        }
        Ok(())
    })?;
    if report.ok() {
        Ok(())
    } else {
        let count = report.problems.len();
        Err(anyhow!("{name}: the check found {count} problem{}", if count == 1 { "" } else { "s" }))
    }
}

/// A number rounded to 6 decimals, negative zero cleaned, for JSON.
fn round6(value: f64) -> Value {
    let rounded = (value * 1e6).round() / 1e6 + 0.0;
    json!(rounded)
}

fn pose_json(pose: &[f64; 4]) -> Value {
    Value::Array(pose.iter().map(|&v| round6(v)).collect())
}

fn problem_json(problem: &Problem) -> Value {
    json!({
        "kind": problem.kind.name(),
        "line": problem.line,
        "t_s": round6(problem.t_start),
        "t_end_s": round6(problem.t_end),
        "line_end": problem.line_end,
        "samples": problem.samples,
        "subject": problem.subject,
        "pose": pose_json(&problem.pose),
        "worst": {
            "t_s": round6(problem.t_worst),
            "line": problem.line_worst,
            "pose": pose_json(&problem.pose_worst),
        },
        "message": problem.message(),
    })
}

/// The report as SPEC §9's `{"ok":…,"problems":[…],"summary":{…}}`.
pub(crate) fn report_json(report: &Report) -> Value {
    let summary = &report.summary;
    let peaks = |peaks: &[biscara::robot::Peak; 4], per: &str| {
        let mut map = serde_json::Map::new();
        for (joint, peak) in Joint::ALL.into_iter().zip(peaks) {
            let unit = if joint.is_revolute() { "deg" } else { "mm" };
            map.insert(
                joint.name().to_owned(),
                json!({
                    "value": round6(peak.value),
                    "limit": round6(peak.limit),
                    "unit": format!("{unit}{per}"),
                    "line": peak.line,
                    "t_s": round6(peak.t),
                }),
            );
        }
        Value::Object(map)
    };
    json!({
        "ok": report.ok(),
        "problems": report.problems.iter().map(problem_json).collect::<Vec<_>>(),
        "summary": {
            "samples": summary.samples,
            "duration_s": round6(summary.duration_s),
            "path_length_mm": round6(summary.path_length_mm),
            "peak_velocity": peaks(&summary.peak_velocity, "/s"),
            "peak_acceleration": peaks(&summary.peak_acceleration, "/s2"),
            "min_singularity": summary.min_singularity.as_ref().map(|nearest| json!({
                "angle_deg": round6(nearest.angle_deg),
                "kind": nearest.kind,
                "line": nearest.line,
                "t_s": round6(nearest.t),
            })),
        },
    })
}

fn write_text(out: &mut dyn std::io::Write, name: &str, report: &Report) -> anyhow::Result<()> {
    let count = report.problems.len();
    if report.ok() {
        writeln!(out, "{name}: clean: no problem found")?;
    } else {
        writeln!(out, "{name}: {count} problem{}", if count == 1 { "" } else { "s" })?;
    }
    for problem in &report.problems {
        let [x, y, z, c] = problem.pose.map(|v| fixed(v, 3));
        writeln!(
            out,
            "{name}:{}: {} ({}) at t = {} s, pose (x, y, z, c) = ({x}, {y}, {z}, {c}): {}",
            problem.line,
            problem.kind,
            problem.subject,
            fixed(problem.t_start, 3),
            problem.message()
        )?;
    }
    let summary = &report.summary;
    writeln!(out, "summary:")?;
    writeln!(
        out,
        "  duration {} s ({} sample{}), path length {} mm",
        fixed(summary.duration_s, 3),
        summary.samples,
        if summary.samples == 1 { "" } else { "s" },
        fixed(summary.path_length_mm, 3)
    )?;
    for (what, peaks, per) in [
        ("velocity", &summary.peak_velocity, "/s"),
        ("acceleration", &summary.peak_acceleration, "/s²"),
    ] {
        writeln!(out, "  peak joint {what}:")?;
        for (joint, peak) in Joint::ALL.into_iter().zip(peaks) {
            let unit = if joint.is_revolute() { "°" } else { "mm" };
            writeln!(
                out,
                "    {:<7} {:>12} {unit}{per} (limit {}; line {}, t = {} s)",
                joint.name(),
                fixed(peak.value, 3),
                peak.limit,
                peak.line,
                fixed(peak.t, 3)
            )?;
        }
    }
    match &summary.min_singularity {
        Some(nearest) => writeln!(
            out,
            "  nearest singularity: {}° from the {} (line {}, t = {} s)",
            fixed(nearest.angle_deg, 3),
            nearest.kind,
            nearest.line,
            fixed(nearest.t, 3)
        )?,
        None => writeln!(out, "  nearest singularity: no reachable sample")?,
    }
    Ok(())
}
