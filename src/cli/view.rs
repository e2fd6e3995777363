//! `biscara view` (the HTML viewer) and the pictures `biscara demo` adds to its folder.

use std::path::{Path, PathBuf};

use biscara::kinematics::Robot;

use super::run_command;

/// Writes the demo's model (`robot.xml` with the companion `robot.traj.csv`) from the demo's
/// joint trajectory `traj.csv` in `dir`; returns what it wrote, for the demo's summary.
pub(crate) fn demo_pictures(
    robot: &Robot,
    dir: &Path,
) -> anyhow::Result<Vec<(PathBuf, &'static str)>> {
    let text = |name: &str| dir.join(name).to_string_lossy().into_owned();
    run_command(robot, ["mjcf", "-o", &text("robot.xml"), "--traj", &text("traj.csv")])?;
    Ok(vec![
        (dir.join("robot.xml"), "MuJoCo model (biscara mjcf)"),
        (dir.join("robot.traj.csv"), "the trajectory in the model's joints (mjcf --traj)"),
    ])
}
