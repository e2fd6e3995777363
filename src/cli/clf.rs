//! `biscara clf`: points file → CL file.

use std::path::PathBuf;

use biscara::kinematics::RobotModel;
use biscara::pnp::write_cl;
use biscara_files::{located_at, open_input};
use clap::Args;

use super::files::write_output;

/// Turns a pick-and-place points file into an APT-style CL file.
///
/// From home, for each pick/place pair: a rapid above the pick (approach height, with the pick's
/// rotation), feed down, PICK, dwell, feed up; the same for the place; finally a rapid home, END,
/// FINI. Every pose and every approach pose is checked with the robot's inverse kinematics
/// (reach, assembly mode, joint limits, singularity margin): on any problem the command exits with
/// 1, names the line of the points file and writes nothing.
#[derive(Debug, Args)]
#[command(
    about = "Points file → CL file (pick-and-place program)",
    after_long_help = "Example:\n  $ biscara clf data/jobs/pick_place.txt -o job.cl\n  \
                       $ biscara --robot my-robot.json clf pallet.txt > pallet.cl"
)]
pub(crate) struct ClfArgs {
    /// The points file: home, approach, feed, dwell, then pick/place lines; `-` reads
    /// standard input.
    #[arg(value_name = "POINTS")]
    points: PathBuf,
    /// Write to FILE instead of standard output.
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,
}

pub(crate) fn clf(robot: &RobotModel, args: &ClfArgs) -> anyhow::Result<()> {
    let model = robot.kinematics();
    let input = open_input(&args.points)?;
    write_output(args.output.as_deref(), |out| {
        write_cl(input, &model, out).map_err(|err| located_at(&args.points, err.line(), err).into())
    })
}
