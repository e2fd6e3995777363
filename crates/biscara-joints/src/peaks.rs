//! Peak joint velocities and accelerations against the robot's limits: the one running tracker,
//! for `check` and for LinuxCNC's recordings.

use std::fmt;

use biscara_kinematics::{Joint, Robot};

/// The slack of every limit test: one part in a million, so that a move planned exactly at a limit
/// (d4 at the rapid speed) does not fail by rounding, nor a recording by its resolution (1e-9
/// degree or mm a cycle).
pub const LIMIT_TOLERANCE: f64 = 1e-6;

/// The largest magnitude of one quantity over a trajectory, against its limit, with where it
/// occurs.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Peak {
    /// The magnitude: degrees/s (or /s²) for θ, mm/s (or /s²) for d4; N·m or N for a torque.
    pub value: f64,
    /// The robot's limit, same unit.
    pub limit: f64,
    /// Program line where it occurs (0 where the samples carry no line).
    pub line: usize,
    /// Time where it occurs, s.
    pub t: f64,
}

impl Peak {
    /// No peak yet (zero) against `limit`.
    pub fn against(limit: f64) -> Peak {
        Peak { limit, ..Peak::default() }
    }

    /// Takes `magnitude` (≥ 0) at `line` and `t` when it is larger than the peak so far; of
    /// equal magnitudes the first stays.
    pub fn offer(&mut self, magnitude: f64, line: usize, t: f64) {
        if magnitude > self.value {
            *self = Peak { value: magnitude, line, t, ..*self };
        }
    }

    /// The peak as a fraction of its limit (1 = at the limit).
    pub fn ratio(&self) -> f64 {
        self.value / self.limit
    }

    /// Whether the peak exceeds its limit by more than [`LIMIT_TOLERANCE`].
    pub fn exceeds(&self) -> bool {
        self.ratio() > 1.0 + LIMIT_TOLERANCE
    }
}

/// A joint's value in the robot file's unit: degrees for θ (from radians), mm for d4.
pub fn user_unit(joint: Joint, value: f64) -> f64 {
    if joint.is_revolute() { value.to_degrees() } else { value }
}

/// Running peaks of |velocity| and |acceleration| of the four joints against the robot's
/// `joint_max_velocity` and `joint_max_acceleration`, in the robot file's units (degrees or mm
/// per second, squared).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Peaks {
    /// Peak velocities, `[theta1, theta2, theta3, d4]`.
    pub velocity: [Peak; 4],
    /// Peak accelerations, `[theta1, theta2, theta3, d4]`.
    pub acceleration: [Peak; 4],
}

impl Peaks {
    /// No peaks yet, against `robot`'s limits.
    pub fn new(robot: &Robot) -> Peaks {
        Peaks {
            velocity: robot.joint_max_velocity.to_array().map(Peak::against),
            acceleration: robot.joint_max_acceleration.to_array().map(Peak::against),
        }
    }

    /// Takes one sample's velocities and accelerations (rad/s and mm/s, squared), at `line` and
    /// `t`.
    pub fn push(&mut self, line: usize, t: f64, velocity: &[f64; 4], acceleration: &[f64; 4]) {
        for (j, joint) in Joint::ALL.into_iter().enumerate() {
            self.velocity[j].offer(user_unit(joint, velocity[j].abs()), line, t);
            self.acceleration[j].offer(user_unit(joint, acceleration[j].abs()), line, t);
        }
    }

    /// Each joint's peaks.
    pub fn joints(&self) -> [JointPeaks; 4] {
        Joint::ALL.map(|joint| JointPeaks {
            joint,
            velocity: self.velocity[joint as usize],
            acceleration: self.acceleration[joint as usize],
        })
    }
}

/// Peak speed and acceleration of one joint against its limits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointPeaks {
    /// The joint.
    pub joint: Joint,
    /// Largest |velocity|: degrees/s or mm/s.
    pub velocity: Peak,
    /// Largest |acceleration|: degrees/s² or mm/s².
    pub acceleration: Peak,
}

impl JointPeaks {
    /// Whether the velocity or the acceleration exceeds its limit by more than
    /// [`LIMIT_TOLERANCE`].
    pub fn exceeds(&self) -> bool {
        self.velocity.exceeds() || self.acceleration.exceeds()
    }
}

impl fmt::Display for JointPeaks {
    /// `theta1: peak 120.0 °/s of 360 (33 %), 2400 °/s² of 7200 (33 %)`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let unit = if self.joint.is_revolute() { "°" } else { "mm" };
        let (velocity, acceleration) = (self.velocity, self.acceleration);
        write!(
            f,
            "{}: peak {:.1} {unit}/s of {} ({:.0} %), {:.0} {unit}/s² of {} ({:.0} %)",
            self.joint.name(),
            velocity.value,
            velocity.limit,
            100.0 * velocity.ratio(),
            acceleration.value,
            acceleration.limit,
            100.0 * acceleration.ratio()
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_peaks_are_the_largest_magnitudes_in_the_robot_files_units_where_they_occur() {
        let robot = Robot::default();
        let mut peaks = Peaks::new(&robot);
        assert_eq!(peaks.velocity[0], Peak::against(robot.joint_max_velocity.theta1));
        assert_eq!(peaks.acceleration[3].limit, robot.joint_max_acceleration.d4);
        let pi = std::f64::consts::PI;
        peaks.push(3, 0.5, &[pi, -pi / 2.0, 0.0, -40.0], &[-pi, 0.0, 0.0, 100.0]);
        peaks.push(4, 0.6, &[-pi / 2.0, pi, 0.0, 30.0], &[pi, 0.0, 0.0, -100.0]);
        // Radians become degrees, d4 keeps its millimetres; signs do not count.
        assert!((peaks.velocity[0].value - 180.0).abs() < 1e-12);
        assert_eq!((peaks.velocity[0].line, peaks.velocity[0].t), (3, 0.5));
        assert!((peaks.velocity[1].value - 180.0).abs() < 1e-12);
        assert_eq!((peaks.velocity[1].line, peaks.velocity[1].t), (4, 0.6));
        assert_eq!(peaks.velocity[2], Peak::against(robot.joint_max_velocity.theta3));
        assert_eq!(peaks.velocity[3].value, 40.0);
        // Of equal magnitudes the first stays.
        assert_eq!((peaks.acceleration[0].line, peaks.acceleration[3].line), (3, 3));
        assert_eq!(peaks.acceleration[3].value, 100.0);
    }

    #[test]
    fn the_ratio_is_against_the_limit_with_a_millionth_of_slack() {
        let at = |value: f64| Peak { value, limit: 200.0, line: 0, t: 0.0 };
        assert_eq!(at(50.0).ratio(), 0.25);
        assert!(!at(200.0).exceeds());
        assert!(!at(200.0 * (1.0 + 0.5e-6)).exceeds());
        assert!(at(200.0 * (1.0 + 2e-6)).exceeds());
        let joint = |velocity, acceleration| JointPeaks {
            joint: Joint::D4,
            velocity: at(velocity),
            acceleration: at(acceleration),
        };
        assert!(!joint(200.0, 10.0).exceeds());
        assert!(joint(201.0, 10.0).exceeds());
        assert!(joint(10.0, 201.0).exceeds());
    }

    #[test]
    fn a_joints_peaks_read_as_the_run_summary_prints_them() {
        let peaks = JointPeaks {
            joint: Joint::Theta1,
            velocity: Peak { value: 120.04, limit: 360.0, line: 0, t: 0.0 },
            acceleration: Peak { value: 2400.0, limit: 7200.0, line: 0, t: 0.0 },
        };
        assert_eq!(
            peaks.to_string(),
            "theta1: peak 120.0 °/s of 360 (33 %), 2400 °/s² of 7200 (33 %)"
        );
        let d4 = JointPeaks { joint: Joint::D4, ..peaks };
        assert!(d4.to_string().starts_with("d4: peak 120.0 mm/s of 360 (33 %), 2400 mm/s² "));
    }
}
