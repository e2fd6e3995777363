//! `biscara cycle`: the Adept cycle on the virtual robot, its motors against their ratings.

use std::path::PathBuf;

use biscara::kinematics::RobotModel;
use biscara::robot::{CycleConfig, adept_cycle};
use biscara::text::parse_xy;
use clap::Args;

use super::files::write_output;

/// The Adept cycle, the industry's pick-and-place benchmark: from a point, 25 mm up, 305 mm
/// across along x, 25 mm down, and back the same way, carrying the payload all the way.
///
/// Each segment is a rapid (G0) under the time-optimal profile: the joint limits, the rapid
/// speed and path acceleration, and with `motors` in the robot file every motor's peak torque
/// bound it; an exact stop at each corner unless --blend. Prints the cycle time, each motor's
/// peak and RMS torque (inverse dynamics of the sampled trajectory) against its `peak` and
/// `rated` torque, and the highest cycle rate the motors sustain: the cycle repeated with the
/// shortest dwell at its start point (holding the slide and payload) that keeps every motor's
/// RMS torque within its rating. Without `motors` the torques are printed without ratings.
///
/// The cycle is centred at --at (default: the centre of the largest workspace rectangle, as
/// `biscara workspace` prints it); a corner out of reach is an error naming it.
#[derive(Debug, Args)]
#[command(
    about = "The Adept cycle: cycle time, motor torques against their ratings, sustained rate",
    after_long_help = "Example:\n  $ biscara cycle\n  \
                       $ biscara --robot robot.json cycle --at 0,250 --z 30 --payload 2 --json\n  \
                       $ biscara cycle --blend 5"
)]
pub(crate) struct CycleArgs {
    /// The cycle's centre X,Y, millimetres (default: the largest workspace rectangle's centre).
    #[arg(long, value_name = "X,Y", value_parser = parse_xy, allow_hyphen_values = true)]
    at: Option<[f64; 2]>,
    /// Height of the cycle's low points, millimetres.
    #[arg(long, value_name = "MM", default_value = "40", allow_hyphen_values = true)]
    z: f64,
    /// Payload carried all the way, kilograms (default: the robot file's `dynamics.payload`).
    #[arg(long, value_name = "KG", allow_hyphen_values = true)]
    payload: Option<f64>,
    /// Blend the corners within MM millimetres (G64 P) instead of stopping at each; 0 is
    /// G64 with no P, as LinuxCNC reads G64 P0 (the corners rounded by at most 1 mm).
    #[arg(long, value_name = "MM", allow_hyphen_values = true)]
    blend: Option<f64>,
    /// Print `{"cycle_s","at":[x,y],"z","payload_kg","peak":{…},"rms":{…},"dwell_s","sustained_cycles_per_min"}`.
    #[arg(long)]
    json: bool,
    /// Write the report to FILE instead of standard output.
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,
}

pub(crate) fn cycle(model: &RobotModel, args: &CycleArgs) -> anyhow::Result<()> {
    let config = CycleConfig {
        at: args.at,
        z: args.z,
        payload_kg: args.payload,
        blend_mm: args.blend,
        ..CycleConfig::default()
    };
    let report = adept_cycle(model, &config)?;
    write_output(args.output.as_deref(), |out| {
        if args.json {
            writeln!(out, "{}", report.to_json())?;
        } else {
            write!(out, "{report}")?;
        }
        Ok(())
    })
}
