//! `biscara workspace`: the reachable XY region, its area and largest rectangle.

use std::path::PathBuf;

use biscara::kinematics::{Joints, RobotModel};
use biscara::robot::{VirtualRobot, Workspace};
use biscara::view::draw_workspace;
use biscara_files::image_format;
use clap::Args;

use super::files::write_output;

/// The reachable region of the XY plane and the largest axis-aligned rectangle inside it
/// (the paper's "reduced workspace", Fig. 5).
///
/// A grid of points at multiples of --step is tested: a point is reachable when IK solves it in
/// the robot's working mode and assembly mode, θ1 and θ2 lie within their limits, and the pose
/// is outside the singularity margin. z and c are free (d4 and θ3 are taken at the middle of
/// their ranges), so they never decide. The area counts each reachable point as one step × step
/// cell. The rectangle is exact on the grid: its corners are grid points, every grid point in it
/// is reachable, and no larger one exists (maximal-rectangle algorithm).
///
/// Prints text by default, `--json` one JSON object, `--csv` the grid (`x_mm,y_mm,reachable`);
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

pub(crate) fn workspace(model: &RobotModel, args: &WorkspaceArgs) -> anyhow::Result<()> {
    let robot = model.robot();
    let workspace = Workspace::compute(&model.kinematics(), args.step)?;
    let rectangle = workspace.largest_rectangle()?;
    for path in [&args.svg, &args.png].into_iter().flatten() {
        let home = VirtualRobot::new(model).body(&Joints::default())?;
        let title = format!("Workspace of {} (grid {} mm)", robot.name, workspace.step());
        let bytes =
            draw_workspace(&workspace, &rectangle, Some(&home), &title, image_format(Some(path)))?;
        write_output(Some(path), |out| Ok(out.write_all(&bytes)?))?;
    }
    write_output(args.output.as_deref(), |out| {
        if args.json {
            writeln!(out, "{}", workspace.to_json(&rectangle))?;
        } else if args.csv {
            workspace.write_csv(out)?;
        } else {
            workspace.write_text(out, &robot.name, &rectangle)?;
        }
        Ok(())
    })
}
