//! `biscara mjcf`: the MuJoCo model of the robot, and the companion file that plays a trajectory.

use std::path::{Path, PathBuf};

use biscara::kinematics::RobotModel;
use biscara::view::{MjcfOptions, QposWriter, write_mjcf};
use biscara_files::{load_scene, open_input, read_joint_rows};
use clap::Args;

use super::files::write_output;

/// Writes a MuJoCo model (MJCF) of the robot.
///
/// The two chains are bodies with hinge joints, the loop is closed by an equality `connect` at
/// the platform point, and chain 1's distal link carries the Z slide and the rotary joint. Joints
/// and position actuators `theta1`, `theta2`, `theta3`, `d4` (radians, metres; control ranges from
/// the robot's joint limits), passive hinges `elbow1`, `elbow2`, the site `tool`; the base frame is
/// the world frame and qpos0 the assembled home pose. Link sizes come from robot.json `geometry`;
/// the masses, centres and inertias from its `dynamics` (or from `geometry` as solid aluminium),
/// the same values `joints --torques` uses; with `motors`, each joint's armature is its motor's
/// rotor inertia and each actuator's force range ±its `peak`. Scene boxes become static geoms.
///
/// With --traj, the joint trajectory is written beside the model as `NAME.traj.csv` (for
/// `-o robot.xml`: `robot.traj.csv`): every row's six joints in MuJoCo's units, the elbows from
/// forward kinematics, and the tool pose FK gives; the model names it in the custom text
/// `biscara_trajectory`. Open the model with `python -m mujoco.viewer --mjcf robot.xml`.
#[derive(Debug, Args)]
#[command(
    about = "MuJoCo model of the robot (MJCF), optionally with a trajectory to play",
    after_long_help = "Example:\n  $ biscara mjcf -o robot.xml\n  \
                       $ biscara mjcf -o robot.xml --traj traj.csv --scene scene.json\n  \
                       $ python -m mujoco.viewer --mjcf robot.xml"
)]
pub(crate) struct MjcfArgs {
    /// Write to FILE instead of standard output.
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,
    /// A joint CSV (from `biscara joints`) to write beside the model as NAME.traj.csv.
    #[arg(
        long,
        value_name = "TRAJ",
        requires = "output",
        help = "Joint trajectory to play (needs -o)"
    )]
    traj: Option<PathBuf>,
    /// A scene file: `{"boxes":[{"name":…,"min":[x,y,z],"max":[x,y,z]}]}` (mm).
    #[arg(long, value_name = "FILE", help = "Scene boxes to add as static geoms")]
    scene: Option<PathBuf>,
}

/// The scene in `path`, or an empty one.
fn companion_path(output: &Path) -> PathBuf {
    let stem = output.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
    output.with_file_name(format!("{stem}.traj.csv"))
}

pub(crate) fn mjcf(robot: &RobotModel, args: &MjcfArgs) -> anyhow::Result<()> {
    let scene = load_scene(args.scene.as_deref())?;
    let mut options = MjcfOptions::default();
    if let (Some(traj), Some(output)) = (&args.traj, &args.output) {
        let companion = companion_path(output);
        write_companion(robot, traj, &companion)?;
        options.trajectory_file =
            companion.file_name().map(|name| name.to_string_lossy().into_owned());
    }
    let dynamics = biscara::dynamics::Dynamics::new(robot)?;
    write_output(args.output.as_deref(), |out| {
        Ok(write_mjcf(out, robot, &dynamics, &scene, &options)?)
    })
}

/// Reads the joint CSV `traj` and writes the companion file `companion`.
fn write_companion(robot: &RobotModel, traj: &Path, companion: &Path) -> anyhow::Result<()> {
    let input = open_input(traj)?;
    write_output(Some(companion), |out| {
        let mut writer = QposWriter::new(out, robot)?;
        read_joint_rows(traj, input, |row| writer.write(row))?;
        writer.finish()?;
        Ok(())
    })
}
