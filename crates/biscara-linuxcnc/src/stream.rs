//! A joint CSV made into a stream file: checked against the robot's joint limits row by row
//! before anything moves, and against where the joints stand.

use std::io::{BufRead, Write};

use biscara_joints::{central_differences, read_joint_csv};
use biscara_kinematics::{Joint, Joints, Robot};

use crate::{LinuxcncError, SERVO_PERIOD, write_stream_sample};

/// How far a stream's first sample may be from where the joints stand: degrees or mm.
pub const START_TOLERANCE: f64 = 1e-3;

/// The positions in LinuxCNC's units: θ1 θ2 θ3 in degrees, d4 in mm, this project's order.
fn degrees(joints: &Joints) -> [f64; 4] {
    let [theta1, theta2, theta3, d4] = joints.to_array();
    [theta1.to_degrees(), theta2.to_degrees(), theta3.to_degrees(), d4]
}

/// A joint's value with its unit.
fn with_unit(joint: Joint, value: f64, per: &str) -> String {
    let unit = if joint.is_revolute() { "°" } else { " mm" };
    format!("{value:.6}{unit}{per}")
}

/// Reads the joint CSV `reader` (the columns and units of `biscara joints`: any angle unit,
/// with or without derivative columns) and writes it to `out` as a stream file, checking every
/// row before the stream is played: one row per servo period (t = t₀ + k·1 ms), every position
/// within the robot's joint limits, and every row's velocity and acceleration (by differences
/// over its neighbours, as `biscara joints` computes them) within the limits. The numbers are
/// checked as written, which is what the joints will follow: a file written with few decimals
/// carries their rounding into its accelerations (six decimals of radians: up to 115 °/s² at
/// 1 ms), and is refused where that crosses a limit. Returns the first row's joints and the row
/// count; the first offending row is the error, with its line.
pub fn check_joint_csv<R: BufRead>(
    name: &str,
    reader: R,
    robot: &Robot,
    out: &mut impl Write,
) -> Result<(Joints, usize), LinuxcncError> {
    let refused = |line: usize, message: String| LinuxcncError::StreamCsv {
        file: name.to_owned(),
        line,
        message,
    };
    let format_error =
        |message: String| LinuxcncError::StreamCsvFormat { file: name.to_owned(), message };
    let limits = robot.joint_limits.to_array();
    let velocity_limits = robot.joint_max_velocity.to_array();
    let acceleration_limits = robot.joint_max_acceleration.to_array();
    // Only a floating-point rounding's worth of slack: 1e-9 of each limit.
    let slack = |limit: f64| limit * (1.0 + 1e-9);
    let hint = " (a CSV written with more decimals, `biscara joints --precision 9`, carries less \
                rounding)";
    let mut window: Vec<(usize, f64, [f64; 4])> = Vec::with_capacity(3);
    let mut first: Option<(f64, Joints)> = None;
    let mut count = 0usize;
    for row in read_joint_csv(reader) {
        let row = row.map_err(|err| format_error(err.to_string()))?;
        let (t0, _) = *first.get_or_insert((row.t, row.joints));
        let expected = t0 + count as f64 * SERVO_PERIOD;
        if (row.t - expected).abs() > 1e-6 {
            return Err(refused(
                row.line,
                format!(
                    "t = {} s where the next servo cycle is t = {expected:.6} s: a stream plays one \
                     row per servo cycle of 1 ms (write it with `biscara joints --dt 0.001`)",
                    row.t
                ),
            ));
        }
        let q = degrees(&row.joints);
        for joint in Joint::ALL {
            let k = joint as usize;
            let [min, max] = limits[k];
            if q[k] < min - 1e-9 || q[k] > max + 1e-9 {
                return Err(refused(
                    row.line,
                    format!(
                        "{} at {} is outside its limits {min} to {max}",
                        joint.name(),
                        with_unit(joint, q[k], "")
                    ),
                ));
            }
        }
        window.push((row.line, row.t, q));
        if window.len() == 3 {
            let [(_, t0, q0), (line, t1, q1), (_, t2, q2)] = [window[0], window[1], window[2]];
            let (velocity, acceleration) = central_differences((t0, &q0), (t1, &q1), (t2, &q2));
            for joint in Joint::ALL {
                let k = joint as usize;
                if velocity[k].abs() > slack(velocity_limits[k]) {
                    return Err(refused(
                        line,
                        format!(
                            "{} moves at {} over its velocity limit {}",
                            joint.name(),
                            with_unit(joint, velocity[k].abs(), "/s"),
                            with_unit(joint, velocity_limits[k], "/s")
                        ),
                    ));
                }
                if acceleration[k].abs() > slack(acceleration_limits[k]) {
                    return Err(refused(
                        line,
                        format!(
                            "{} accelerates at {} over its acceleration limit {}{hint}",
                            joint.name(),
                            with_unit(joint, acceleration[k].abs(), "/s²"),
                            with_unit(joint, acceleration_limits[k], "/s²")
                        ),
                    ));
                }
            }
            window.remove(0);
        }
        write_stream_sample(out, &row.joints).map_err(|err| format_error(err.to_string()))?;
        count += 1;
    }
    let Some((_, joints)) = first else {
        return Err(refused(1, "no rows: nothing to stream".to_owned()));
    };
    Ok((joints, count))
}

/// Fails unless a stream starting at `first` starts where the joints stand (`home`: θ1 θ2 d4 θ3
/// in degrees and mm, LinuxCNC's order, as `[JOINT_n] HOME` holds them after homing), within
/// [`START_TOLERANCE`].
pub fn check_start(first: &Joints, home: [f64; 4]) -> Result<(), LinuxcncError> {
    let [theta1, theta2, theta3, d4] = degrees(first);
    let start = [theta1, theta2, d4, theta3];
    if start.iter().zip(&home).all(|(a, b)| (a - b).abs() <= START_TOLERANCE) {
        return Ok(());
    }
    let show = |[theta1, theta2, d4, theta3]: [f64; 4]| {
        format!("θ1 {theta1:.4}°, θ2 {theta2:.4}°, θ3 {theta3:.4}°, d4 {d4:.4} mm")
    };
    Err(LinuxcncError::StartPosition { stream: show(start), joints: show(home) })
}

#[cfg(test)]
mod tests {
    use super::*;

    const HEADER: &str = "t_s,theta1_deg,theta2_deg,theta3_deg,d4_mm\n";

    fn check(text: &str) -> Result<(Joints, usize), String> {
        let mut out = Vec::new();
        check_joint_csv("t.csv", text.as_bytes(), &Robot::default(), &mut out)
            .map_err(|err| err.to_string())
    }

    /// Rows 1 ms apart with θ1 = f(k), the others still.
    fn rows(theta1: impl Fn(usize) -> f64, count: usize) -> String {
        let mut text = HEADER.to_owned();
        for k in 0..count {
            text += &format!(
                "{:.9},{:.9},0.000000000,0.000000000,0.000000000\n",
                k as f64 * 1e-3,
                theta1(k)
            );
        }
        text
    }

    #[test]
    fn a_trajectory_within_the_limits_becomes_a_stream_file() {
        // 100 °/s, no acceleration.
        let text = rows(|k| 0.1 * k as f64, 50);
        let mut out = Vec::new();
        let (first, count) =
            check_joint_csv("t.csv", text.as_bytes(), &Robot::default(), &mut out).unwrap();
        assert_eq!(count, 50);
        assert_eq!(first.theta1, 0.0);
        let stream = String::from_utf8(out).unwrap();
        assert_eq!(stream.lines().count(), 50);
        let second: Vec<f64> =
            stream.lines().nth(1).unwrap().split(' ').map(|v| v.parse().unwrap()).collect();
        assert!((second[0] - 0.1).abs() < 1e-9, "{second:?}");
    }

    #[test]
    fn the_first_offending_row_is_named() {
        // θ1 beyond 135°.
        let err = check(&rows(|k| 134.99 + 0.004 * k as f64, 10)).unwrap_err();
        assert!(
            err.starts_with("t.csv:5: theta1 at 135.002000° is outside its limits -135 to 135"),
            "{err}"
        );
        // 400 °/s against 360.
        let err = check(&rows(|k| 0.4 * k as f64, 10)).unwrap_err();
        assert!(
            err.starts_with("t.csv:3: theta1 moves at 400.000000°/s over its velocity limit"),
            "{err}"
        );
        // A step of acceleration: 8000 °/s² against 7200, from row 5 on.
        let err = check(&rows(|k| if k < 4 { 0.0 } else { 4e-3 * ((k - 4) * (k - 4)) as f64 }, 10))
            .unwrap_err();
        assert!(err.starts_with("t.csv:7: theta1 accelerates at 8000.000000°/s²"), "{err}");
        let err = check(&rows(|k| if k < 4 { 0.0 } else { 4e-3 * ((k - 3) * (k - 3)) as f64 }, 10))
            .unwrap_err();
        assert!(err.contains("over its acceleration limit 7200.000000°/s²"), "{err}");
        // Rows not 1 ms apart.
        let text = format!("{HEADER}0.000,0,0,0,0\n0.002,0,0,0,0\n");
        let err = check(&text).unwrap_err();
        assert!(
            err.starts_with("t.csv:3: t = 0.002 s where the next servo cycle is t = 0.001000 s"),
            "{err}"
        );
        // No rows, a bad header, a bad number.
        assert!(check(HEADER).unwrap_err().contains("no rows"));
        assert!(check("t,x\n0,0\n").unwrap_err().starts_with("t.csv:1:"));
        let err = check(&format!("{HEADER}0,0,x,0,0\n")).unwrap_err();
        assert!(err.starts_with("t.csv:2:"), "{err}");
    }

    #[test]
    fn the_numbers_are_checked_as_written() {
        // 7000 °/s² written in radians: with six decimals the 1 ms differences of the rounded
        // positions scatter by up to 115 °/s² and cross 7200; with ten they do not.
        let csv = |decimals: usize| {
            let mut text = "t_s,theta1_rad,theta2_rad,theta3_rad,d4_mm\n".to_owned();
            for k in 0..45 {
                let t = k as f64 * 1e-3;
                let q = (0.5 * 7150.0 * t * t).to_radians();
                text += &format!("{t:.6},{q:.decimals$},0,0,0\n");
            }
            text
        };
        let err = check(&csv(6)).unwrap_err();
        assert!(
            err.contains("over its acceleration limit") && err.contains("--precision 9"),
            "{err}"
        );
        check(&csv(10)).unwrap();
        // Half a degree a millisecond is 500 °/s.
        let text = format!("{HEADER}0,0,0,0,0\n0.001,0.5,0,0,0\n0.002,1,0,0,0\n");
        assert!(check(&text).unwrap_err().starts_with("t.csv:3: theta1 moves at 500.000000°/s"));
    }

    #[test]
    fn a_stream_must_start_where_the_joints_stand() {
        let first = Joints::from_degrees(0.0, 0.0005, 0.0, 0.0);
        check_start(&first, [0.0; 4]).unwrap();
        let first = Joints::from_degrees(10.0, -20.0, 30.0, 40.0);
        let err = check_start(&first, [10.0, -20.0, 40.0, 30.002]).unwrap_err().to_string();
        assert!(err.contains("θ1 10.0000°, θ2 -20.0000°, θ3 30.0000°, d4 40.0000 mm"), "{err}");
        assert!(err.contains("θ3 30.0020°, d4 40.0000 mm"), "{err}");
    }
}
