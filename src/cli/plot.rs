//! `biscara plot`: pictures of a program on the virtual robot (SPEC §8.3), and the pictures
//! `workspace --svg/--png` and `demo` write.

use std::path::{Path, PathBuf};

use anyhow::anyhow;
use biscara::kinematics::{Kinematics, Pose, Robot, Theta3Unwrapper};
use biscara::robot::{Body, Rectangle, Scene, VirtualRobot, Workspace};
use biscara::view::{
    ImageFormat, JointCurves, TopView, draw_joints, draw_top_view, draw_workspace,
};
use clap::Args;

use super::check::read_scene;
use super::display_path;
use super::output::write_output;
use super::trajectory::{InputKind, SamplingArgs, input_kind, samples, slow_down_reporter};

/// Draws a program on the virtual robot, in top view or as joint curves (SPEC §8.3).
///
/// The top view shows the workspace (reachable region) with its largest rectangle, the
/// programmed path, the scene's boxes (--scene) and the robot (links, elbows, base joints and
/// gripper with a tick for c) at the times of --at. With --joints it draws θ1, θ2, θ3 (degrees)
/// and d4 (mm) against time instead, with the joint limits as dashed lines.
///
/// The format follows the output's extension: `.png` is PNG, anything else SVG (also on standard
/// output). The program's kind comes from --from, else from its extension.
#[derive(Debug, Args)]
#[command(
    about = "Draw a program: workspace, path and robot (top view), or joint curves",
    after_long_help = "Example:\n  $ biscara plot job.ngc --at 0,1.5,3 -o plot.svg\n  \
                       $ biscara plot --joints job.ngc -o joints.png"
)]
pub(crate) struct PlotArgs {
    /// The program (G-code, inter-file or path CSV); `-` reads standard input.
    #[arg(value_name = "PROGRAM")]
    program: PathBuf,
    /// Write to FILE (`.svg` or `.png`) instead of SVG on standard output.
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,
    /// The program's kind (default: from the extension).
    #[arg(long, value_enum, value_name = "KIND")]
    from: Option<InputKind>,
    /// Times (s) at which to draw the robot, comma-separated (default: the start).
    #[arg(long, value_name = "T,…", value_delimiter = ',', value_parser = parse_time)]
    at: Vec<f64>,
    /// Draw the joint curves against time instead of the top view.
    #[arg(long)]
    joints: bool,
    /// Boxes around the robot to draw (JSON, as for check).
    #[arg(long, value_name = "FILE")]
    scene: Option<PathBuf>,
    /// Grid step of the workspace, millimetres.
    #[arg(long, value_name = "MM", default_value = "2")]
    step: f64,
    #[command(flatten)]
    sampling: SamplingArgs,
}

fn parse_time(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(value) if value.is_finite() && value >= 0.0 => Ok(value),
        _ => Err(format!("`{text}` is not a time in seconds (a number ≥ 0)")),
    }
}

/// The format a path asks for: PNG for `.png`, else SVG.
fn format_of(path: Option<&Path>) -> ImageFormat {
    match path.and_then(|p| p.extension()).and_then(|e| e.to_str()) {
        Some(ext) if ext.eq_ignore_ascii_case("png") => ImageFormat::Png,
        _ => ImageFormat::Svg,
    }
}

fn write_bytes(path: Option<&Path>, bytes: &[u8]) -> anyhow::Result<()> {
    write_output(path, |out| Ok(out.write_all(bytes)?))
}

/// Draws the workspace picture (`workspace --svg/--png`) into `path`.
pub(crate) fn write_workspace_picture(
    path: &Path,
    robot: &Robot,
    workspace: &Workspace,
    rectangle: &Rectangle,
) -> anyhow::Result<()> {
    let virtual_robot = VirtualRobot::new(robot)?;
    let home = virtual_robot.body(&Default::default())?;
    let title = format!("Workspace of {} (grid {} mm)", robot.name, workspace.step());
    let bytes = draw_workspace(workspace, rectangle, Some(&home), &title, format_of(Some(path)))?;
    write_bytes(Some(path), &bytes)
}

/// What a program looks like on the robot: the decimated path, bodies at times, joint curves.
struct Drawn {
    path: Vec<[f64; 2]>,
    bodies: Vec<(f64, Body)>,
    t: Vec<f64>,
    q: Vec<[f64; 4]>,
}

/// Most points a picture keeps of the path and of the joint curves: past it every other point is
/// dropped and the spacing doubled, so memory stays bounded however long the program is.
const MAX_POINTS: usize = 20_000;

/// Keeps every other element (the first, the third, …).
fn thin<T>(points: &mut Vec<T>) {
    let mut keep = false;
    points.retain(|_| {
        keep = !keep;
        keep
    });
}

/// Runs the program's samples through IK, keeping what the pictures need.
fn trace(
    robot: &Robot,
    program: &Path,
    kind: InputKind,
    sampling: &SamplingArgs,
    at: &[f64],
) -> anyhow::Result<Drawn> {
    let model = Kinematics::new(robot)?;
    let virtual_robot = VirtualRobot::new(robot)?;
    let (on_slow, _) = slow_down_reporter(display_path(program));
    let mut drawn = Drawn { path: Vec::new(), bodies: Vec::new(), t: Vec::new(), q: Vec::new() };
    let mut theta3 = Theta3Unwrapper::new();
    let mut wanted: Vec<f64> = at.to_vec();
    wanted.sort_by(f64::total_cmp);
    let mut next_time = 0;
    let mut last_t = 0.0;
    // Path points at least 0.5 mm apart and joint points 5 ms apart: plenty for a picture.
    let (mut path_spacing, mut time_spacing) = (0.5, 0.005);
    for sample in samples(program, kind, sampling, robot, model, on_slow)? {
        let sample = sample?;
        last_t = sample.t;
        let [x, y, z, c] = sample.pose;
        if drawn.path.last().is_none_or(|p| (p[0] - x).hypot(p[1] - y) >= path_spacing) {
            drawn.path.push([x, y]);
            if drawn.path.len() > MAX_POINTS {
                thin(&mut drawn.path);
                path_spacing *= 2.0;
            }
        }
        let pose = Pose::from_degrees(x, y, z, c);
        let Ok(mut solution) = model.inverse(&pose) else { continue };
        theta3.apply(&mut solution);
        if drawn.t.last().is_none_or(|&t| sample.t - t >= time_spacing) {
            drawn.t.push(sample.t);
            drawn.q.push(solution.joints.to_degrees());
            if drawn.t.len() > MAX_POINTS {
                thin(&mut drawn.t);
                thin(&mut drawn.q);
                time_spacing *= 2.0;
            }
        }
        while next_time < wanted.len() && wanted[next_time] <= sample.t + 1e-9 {
            drawn.bodies.push((
                wanted[next_time],
                virtual_robot.body_at(solution.configuration, pose.z, pose.phi),
            ));
            next_time += 1;
        }
    }
    for &t in &wanted[next_time..] {
        #[allow(clippy::print_stderr)]
        {
            eprintln!(
                "biscara: warning: t = {t} s is after the program's end ({last_t:.3} s): not drawn"
            );
        }
    }
    Ok(drawn)
}

pub(crate) fn plot(robot: &Robot, args: &PlotArgs) -> anyhow::Result<()> {
    let scene = match &args.scene {
        Some(path) => Some(read_scene(path)?),
        None => None,
    };
    let kind = input_kind(&args.program, args.from);
    let at = if args.at.is_empty() { vec![0.0] } else { args.at.clone() };
    let drawn = trace(robot, &args.program, kind, &args.sampling, &at)?;
    let format = format_of(args.output.as_deref());
    let name = display_path(&args.program);
    let bytes = if args.joints {
        let limits = robot.joint_limits.to_array();
        let title = format!("Joint trajectory of {name}");
        draw_joints(&JointCurves { title: &title, t: &drawn.t, q: &drawn.q, limits }, format)?
    } else {
        let (workspace, rectangle) = super::workspace::compute(robot, args.step)?;
        top_view(&name, &workspace, &rectangle, &drawn, scene.as_ref(), format)?
    };
    write_bytes(args.output.as_deref(), &bytes)
}

fn top_view(
    name: &str,
    workspace: &Workspace,
    rectangle: &Rectangle,
    drawn: &Drawn,
    scene: Option<&Scene>,
    format: ImageFormat,
) -> anyhow::Result<Vec<u8>> {
    let title = format!("{name} on the virtual robot (top view)");
    let view = TopView {
        title: &title,
        workspace: Some(workspace),
        rectangle: Some(rectangle),
        path: &drawn.path,
        bodies: &drawn.bodies,
        scene,
    };
    draw_top_view(&view, format).map_err(|err| anyhow!("{err}"))
}

/// The virtual robot's outputs of the demo: `check.json`, `workspace.svg` and `plot.svg` for
/// `program` (an inter-file or G-code) in `dir`. Returns the files written.
pub(crate) fn write_virtual_robot_outputs(
    dir: &Path,
    robot: &Robot,
    program: &Path,
) -> anyhow::Result<Vec<PathBuf>> {
    let kind = input_kind(program, None);
    let sampling = default_sampling()?;
    let report = super::check::run_check(robot, program, kind, &sampling, Scene::new())?;
    let check_path = dir.join("check.json");
    write_output(Some(&check_path), |out| {
        Ok(writeln!(out, "{}", super::check::report_json(&report))?)
    })?;
    let (workspace, rectangle) = super::workspace::compute(robot, 2.0)?;
    let workspace_path = dir.join("workspace.svg");
    write_workspace_picture(&workspace_path, robot, &workspace, &rectangle)?;
    let duration = report.summary.duration_s;
    let at = [0.0, 0.25 * duration, 0.5 * duration, 0.75 * duration]
        .map(|t| (t * 1000.0).round() / 1000.0);
    let drawn = trace(robot, program, kind, &sampling, &at)?;
    let name = program
        .file_name()
        .map_or_else(|| display_path(program), |n| n.to_string_lossy().into_owned());
    let bytes = top_view(&name, &workspace, &rectangle, &drawn, None, ImageFormat::Svg)?;
    let plot_path = dir.join("plot.svg");
    write_bytes(Some(&plot_path), &bytes)?;
    Ok(vec![check_path, workspace_path, plot_path])
}

/// The sampling options at their defaults, as the command line would give them.
fn default_sampling() -> anyhow::Result<SamplingArgs> {
    use clap::{Args as _, FromArgMatches as _};
    let matches =
        SamplingArgs::augment_args(clap::Command::new("demo")).try_get_matches_from(["demo"])?;
    Ok(SamplingArgs::from_arg_matches(&matches)?)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thin_keeps_every_other_point() {
        let mut points: Vec<u32> = (0..7).collect();
        thin(&mut points);
        assert_eq!(points, [0, 2, 4, 6]);
    }
}
