//! Slowing moves down so that no joint exceeds its velocity limit (SPEC §6, §7).

use biscara_interpolate::{CartesianLimits, RateLimit, Segment, SpeedLimit};
use biscara_kinematics::{Joint, Kinematics, PlanarConfiguration, Robot};

/// Probes per millimetre of XYZ path and per degree of C when bounding a move's joint rates.
const PROBES_PER_MM: f64 = 1.0;
const PROBES_PER_DEGREE: f64 = 1.0;
/// Bounds on the number of probe intervals of one move: a move shorter than 1 mm and 1° is probed
/// at its two ends only.
const MIN_PROBES: f64 = 1.0;
const MAX_PROBES: f64 = 4096.0;
/// The rate found at the probes of a revolute joint is lowered by this factor, for peaks between
/// probes (probes at most 1 mm or 1° apart miss a peak by far less). d4 = lp − z is linear in the
/// path, so its bound is exact.
const REVOLUTE_PROBE_SAFETY: f64 = 0.998;

/// A [`SpeedLimit`] from the robot's `joint_max_velocity`: the largest path rate at which no joint
/// exceeds its limit, found by evaluating the joint rates `dq/ds = J⁻¹ · dx/ds` along the move
/// (at least one probe per mm of path and per degree of C), with a 0.2 % margin for revolute
/// joints.
///
/// Probes where IK fails are skipped: the joint-trajectory stage reports those poses.
///
/// A probe needs the five-bar's configuration, not the joint angles
/// ([`Kinematics::configuration`], no `atan2`), and a move's first probe is usually the last
/// probe of the move before: its configuration is kept. On the engraving program of
/// `scripts/gen-program.sh` (moves of 0.05–0.4 mm), with two probes instead of three on moves
/// under 1 mm, they took `joints` from 0.411 to 0.373 s (median of 10).
#[derive(Debug, Clone, Copy)]
pub struct JointSpeedLimit {
    model: Kinematics,
    /// θ limits in rad/s, d4 in mm/s.
    max_velocity: [f64; 4],
    /// The last probe: its point (x, y) and configuration, if IK found one.
    last_probe: Option<([f64; 2], Option<PlanarConfiguration>)>,
}

impl JointSpeedLimit {
    /// The limiter for `robot` (whose kinematics `model` is).
    pub fn new(model: Kinematics, robot: &Robot) -> JointSpeedLimit {
        let [t1, t2, t3, d4] = robot.joint_max_velocity.to_array();
        JointSpeedLimit {
            model,
            max_velocity: [t1.to_radians(), t2.to_radians(), t3.to_radians(), d4],
            last_probe: None,
        }
    }
}

impl SpeedLimit for JointSpeedLimit {
    fn max_rate(&mut self, segment: &Segment) -> Option<RateLimit> {
        let probes = (segment.length() * PROBES_PER_MM
            + segment.rotation().abs() * PROBES_PER_DEGREE)
            .clamp(MIN_PROBES, MAX_PROBES) as u32;
        let mut best: Option<RateLimit> = None;
        for k in 0..=probes {
            let s = f64::from(k) / f64::from(probes);
            let [x, y, ..] = segment.point(s);
            let configuration = match self.last_probe {
                Some((point, configuration)) if point == [x, y] => configuration,
                _ => {
                    let configuration = self.model.configuration(x, y).ok();
                    self.last_probe = Some(([x, y], configuration));
                    configuration
                }
            };
            let Some(configuration) = configuration else { continue };
            let [dx, dy, dz, dc] = segment.derivative(s);
            let Some(rates) =
                self.model.joint_velocity(&configuration, [dx, dy, dz, dc.to_radians()])
            else {
                continue;
            };
            for joint in Joint::ALL {
                let per_s = rates.get(joint).abs();
                if per_s == 0.0 {
                    continue;
                }
                let safety = if joint.is_revolute() { REVOLUTE_PROBE_SAFETY } else { 1.0 };
                let rate = safety * self.max_velocity[joint as usize] / per_s;
                if best.is_none_or(|best| rate < best.rate) {
                    best = Some(RateLimit { rate, cause: joint.name() });
                }
            }
        }
        best
    }
}

/// The interpolator's Cartesian limits from `robot.json`'s `motion` section.
pub fn cartesian_limits(robot: &Robot) -> CartesianLimits {
    CartesianLimits {
        rapid_velocity: robot.motion.rapid_velocity,
        rapid_rotation: robot.motion.rapid_rotation,
        acceleration: robot.motion.acceleration,
        rotation_acceleration: robot.motion.rotation_acceleration,
    }
}
