//! `biscara workspace`: the reachable XY region, its area and largest rectangle (SPEC §8.2).

use std::io::Write;
use std::path::PathBuf;

use biscara::kinematics::{Kinematics, Robot};
use biscara::robot::{Rectangle, Workspace};
use biscara::text::fixed;
use clap::Args;

use super::output::write_output;

/// The reachable region of the XY plane and the largest axis-aligned rectangle inside it
/// (SPEC §8.2, the paper's "reduced workspace", Fig. 5).
///
/// A grid of points at multiples of --step is tested: a point is reachable when IK solves it in
/// the robot's working mode and assembly mode, θ1 and θ2 lie within their limits, and the pose
/// is outside the singularity margin. z and c are free (d4 and θ3 are taken at the middle of
/// their ranges), so they never decide. The area counts each reachable point as one step × step
/// cell. The rectangle is exact on the grid: its corners are grid points, every grid point in it
/// is reachable, and no larger one exists (maximal-rectangle algorithm).
///
/// Prints text by default, `--json` the object of SPEC §9, `--csv` the grid (`x_mm,y_mm,reachable`);
/// `--svg FILE` and `--png FILE` also draw it.
#[derive(Debug, Args)]
#[command(
    about = "Reachable XY region, its area and the largest rectangle inside it",
    after_long_help = "Example:\n  $ biscara workspace\n  $ biscara workspace --step 1 --json\n  \
                       $ biscara workspace --svg workspace.svg"
)]
pub(crate) struct WorkspaceArgs {
    /// Grid step, millimetres.
    #[arg(long, value_name = "MM", default_value = "2")]
    step: f64,
    /// Print `{"area_mm2":…,"step_mm":…,"rectangle":{"min":[x,y],"max":[x,y]}}`.
    #[arg(long, conflicts_with = "csv")]
    json: bool,
    /// Print the grid as CSV: `x_mm,y_mm,reachable` (1 or 0), one row per grid point.
    #[arg(long)]
    csv: bool,
    /// Write the text, JSON or CSV to FILE instead of standard output.
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,
    /// Also draw the workspace and its rectangle as an SVG picture.
    #[arg(long, value_name = "FILE")]
    svg: Option<PathBuf>,
    /// Also draw the workspace and its rectangle as a PNG picture.
    #[arg(long, value_name = "FILE")]
    png: Option<PathBuf>,
}

/// The workspace of `robot` and its largest rectangle.
pub(crate) fn compute(robot: &Robot, step: f64) -> anyhow::Result<(Workspace, Rectangle)> {
    let model = Kinematics::new(robot)?;
    let workspace = Workspace::compute(&model, step)?;
    let rectangle = workspace.largest_rectangle()?;
    Ok((workspace, rectangle))
}

/// The JSON object of SPEC §9, keys in its order.
#[derive(serde::Serialize)]
struct WorkspaceJson {
    area_mm2: f64,
    step_mm: f64,
    rectangle: RectangleJson,
}

#[derive(serde::Serialize)]
struct RectangleJson {
    min: [f64; 2],
    max: [f64; 2],
}

/// `{"area_mm2":…,"step_mm":…,"rectangle":{"min":[x,y],"max":[x,y]}}` (SPEC §9).
pub(crate) fn workspace_json(workspace: &Workspace, rectangle: &Rectangle) -> String {
    let r = |v: f64| (v * 1e6).round() / 1e6 + 0.0;
    let value = WorkspaceJson {
        area_mm2: r(workspace.area_mm2()),
        step_mm: workspace.step(),
        rectangle: RectangleJson { min: rectangle.min.map(r), max: rectangle.max.map(r) },
    };
    serde_json::to_string(&value).unwrap_or_default()
}

pub(crate) fn workspace(robot: &Robot, args: &WorkspaceArgs) -> anyhow::Result<()> {
    let (workspace, rectangle) = compute(robot, args.step)?;
    if let Some(path) = &args.svg {
        super::plot::write_workspace_picture(path, robot, &workspace, &rectangle)?;
    }
    if let Some(path) = &args.png {
        super::plot::write_workspace_picture(path, robot, &workspace, &rectangle)?;
    }
    write_output(args.output.as_deref(), |out| {
        if args.json {
            writeln!(out, "{}", workspace_json(&workspace, &rectangle))?;
        } else if args.csv {
            write_csv(out, &workspace)?;
        } else {
            write_text(out, robot, &workspace, &rectangle)?;
        }
        Ok(())
    })
}

fn write_csv(out: &mut dyn Write, workspace: &Workspace) -> anyhow::Result<()> {
    writeln!(out, "x_mm,y_mm,reachable")?;
    let (columns, rows) = workspace.size();
    for j in 0..rows {
        for i in 0..columns {
            let [x, y] = workspace.point(i, j);
            let flag = u8::from(workspace.is_reachable(i, j));
            writeln!(out, "{},{},{flag}", fixed(x, 3), fixed(y, 3))?;
        }
    }
    Ok(())
}

fn write_text(
    out: &mut dyn Write,
    robot: &Robot,
    workspace: &Workspace,
    rectangle: &Rectangle,
) -> anyhow::Result<()> {
    writeln!(out, "workspace of {} (grid step {} mm)", robot.name, workspace.step())?;
    writeln!(
        out,
        "reachable area: {} mm² ({} grid points)",
        fixed(workspace.area_mm2(), 0),
        workspace.count()
    )?;
    writeln!(
        out,
        "largest rectangle: x {} .. {} mm, y {} .. {} mm ({} x {} mm, {} mm²)",
        fixed(rectangle.min[0], 3),
        fixed(rectangle.max[0], 3),
        fixed(rectangle.min[1], 3),
        fixed(rectangle.max[1], 3),
        fixed(rectangle.width(), 3),
        fixed(rectangle.height(), 3),
        fixed(rectangle.width() * rectangle.height(), 0)
    )?;
    Ok(())
}
