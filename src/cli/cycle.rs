//! `biscara cycle`: the Adept cycle on the virtual robot, its motors against their ratings.

use std::path::PathBuf;

use biscara::kinematics::{Joint, RobotModel};
use biscara::robot::{CycleConfig, CycleReport, adept_cycle};
use biscara::text::{fixed, round_to};
use clap::Args;
use serde_json::{Value, json};

use super::args::parse_point;
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
    #[arg(long, value_name = "X,Y", value_parser = parse_point, allow_hyphen_values = true)]
    at: Option<[f64; 2]>,
    /// Height of the cycle's low points, millimetres.
    #[arg(long, value_name = "MM", default_value = "40", allow_hyphen_values = true)]
    z: f64,
    /// Payload carried all the way, kilograms (default: the robot file's `dynamics.payload`).
    #[arg(long, value_name = "KG")]
    payload: Option<f64>,
    /// Blend the corners within MM millimetres (G64 P) instead of stopping at each.
    #[arg(long, value_name = "MM")]
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
            writeln!(out, "{}", to_json(&report))?;
        } else {
            write_text(out, &report)?;
        }
        Ok(())
    })
}

/// A number rounded to 6 decimals, for JSON.
fn round6(value: f64) -> Value {
    json!(round_to(value, 6))
}

fn unit(joint: Joint) -> &'static str {
    if joint.is_revolute() { "N·m" } else { "N" }
}

fn to_json(report: &CycleReport) -> Value {
    let (mut peak, mut rms) = (serde_json::Map::new(), serde_json::Map::new());
    for (joint, motor) in Joint::ALL.into_iter().zip(&report.motors) {
        let [peak_limit, rated] = match motor.ratings {
            Some([peak, rated]) => [round6(peak), round6(rated)],
            None => [Value::Null, Value::Null],
        };
        let name = joint.name().to_owned();
        peak.insert(
            name.clone(),
            json!({"value": round6(motor.peak), "limit": peak_limit, "unit": unit(joint)}),
        );
        rms.insert(name, json!({"value": round6(motor.rms), "limit": rated, "unit": unit(joint)}));
    }
    json!({
        "cycle_s": round6(report.cycle_s),
        "at": [round6(report.at[0]), round6(report.at[1])],
        "z": round6(report.z),
        "payload_kg": round6(report.payload_kg),
        "peak": peak,
        "rms": rms,
        "dwell_s": report.dwell_s.map(round6),
        "sustained_cycles_per_min": report.sustained_cycles_per_min().map(round6),
    })
}

fn write_text(out: &mut dyn std::io::Write, report: &CycleReport) -> std::io::Result<()> {
    writeln!(
        out,
        "Adept cycle at ({}, {}) mm, z {} mm, payload {} kg: 25 mm up, 305 mm across, 25 mm \
         down and back",
        fixed(report.at[0], 3),
        fixed(report.at[1], 3),
        fixed(report.z, 3),
        report.payload_kg
    )?;
    writeln!(out, "cycle time: {} s", fixed(report.cycle_s, 3))?;
    writeln!(out, "motor torques (peak against peak, RMS against rated):")?;
    for (joint, motor) in Joint::ALL.into_iter().zip(&report.motors) {
        let unit = unit(joint);
        let (peak_limit, rated) = match motor.ratings {
            Some([peak, rated]) => (format!(" (peak {peak})"), format!(" (rated {rated})")),
            None => (String::new(), String::new()),
        };
        writeln!(
            out,
            "  {:<7} peak {:>10} {unit}{peak_limit}, RMS {:>10} {unit}{rated}",
            joint.name(),
            fixed(motor.peak, 3),
            fixed(motor.rms, 3),
        )?;
    }
    match (report.dwell_s, report.sustained_cycles_per_min()) {
        (Some(dwell), Some(rate)) if dwell > 0.0 => writeln!(
            out,
            "sustained: {} cycles/min, with a dwell of {} s after each cycle (RMS within rated)",
            fixed(rate, 1),
            fixed(dwell, 3)
        ),
        (Some(_), Some(rate)) => writeln!(
            out,
            "sustained: {} cycles/min, back to back (RMS within rated)",
            fixed(rate, 1)
        ),
        _ if report.motors[0].ratings.is_none() => {
            writeln!(out, "sustained: unknown: the robot file has no motors")
        }
        _ => writeln!(
            out,
            "sustained: none: a motor's torque holding the robot at rest is beyond its rating"
        ),
    }
}
