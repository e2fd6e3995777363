//! Slowing moves down so that no joint exceeds its velocity limit (docs/motion.md).

use biscara_dynamics::{Dynamics, DynamicsError};
use biscara_interpolate::{
    CartesianLimits, Constraint, JointBound, RateLimit, Segment, SpeedLimit,
};
use biscara_kinematics::{Joint, Kinematics, PlanarConfiguration, Robot, RobotModel};

use crate::torque::{MotorBound, torque_rows};

/// Probes per millimetre of XYZ path and per degree of C when bounding a move's joint rates.
const PROBES_PER_MM: f64 = 1.0;
const PROBES_PER_DEGREE: f64 = 1.0;
/// Probes per degree an arc turns: its direction changes by at most 5° between probes, so that a
/// joint rate peaking between two probes exceeds the nearer one by at most 1 − cos 2.5° = 0.1 %
/// from the turning (the rate is linear in the direction). Without it, a tight arc (5 mm radius,
/// 33 mm long, 33 probes 11° apart) let θ2 exceed its limit by 0.07 % (the test below).
const PROBES_PER_DEGREE_OF_TURN: f64 = 0.2;
/// Bounds on the number of probe intervals of one move: a move shorter than 1 mm and 1° is probed
/// at its two ends only.
const MIN_PROBES: f64 = 1.0;
const MAX_PROBES: f64 = 4096.0;
/// The rate found at the probes of a revolute joint is lowered by this factor, for peaks between
/// probes (probes at most 1 mm or 1° apart miss a peak by far less). d4 = lp − z is linear in the
/// path, so its bound is exact.
const REVOLUTE_PROBE_SAFETY: f64 = 0.998;
/// The optimal profile's margins on the revolute joints' limits: it meets them exactly at its
/// grid points, and between them (at most 0.5 mm and 2° of turning apart) q′ and q″ change a
/// little. The velocity margin is the trapezoid's probe margin; the acceleration
/// margin is 1 %. d4 = lp − z is linear in the path: its limits are exact.
const OPTIMAL_VELOCITY_MARGIN: f64 = REVOLUTE_PROBE_SAFETY;
const OPTIMAL_ACCELERATION_MARGIN: f64 = 0.99;
/// The optimal profile's margin on the motors' peak torques, for the same reason as the
/// acceleration margin: the torque rows hold exactly at the grid points, and between them the
/// pose, q′ and q″ change a little (the torque-limited tests of `biscara-joints` measure the
/// excess of the sampled trajectory).
const OPTIMAL_TORQUE_MARGIN: f64 = 0.99;

/// A [`SpeedLimit`] from the robot's `joint_max_velocity`: the largest path rate at which no joint
/// exceeds its limit, found by evaluating the joint rates `dq/ds = J⁻¹ · dx/ds` along the move
/// (at least one probe per mm of path, per degree of C and per 5° an arc turns, and one at each
/// end), with a 0.2 % margin for revolute joints.
///
/// Probes where IK fails are skipped: the joint-trajectory stage reports those poses.
///
/// A probe needs the five-bar's configuration, not the joint angles
/// ([`Kinematics::configuration`], no `atan2`), and a move's first probe is usually the last
/// probe of the move before: its configuration is kept. On the engraving program of
/// `scripts/gen-program.sh` (moves of 0.05–0.4 mm), with two probes instead of three on moves
/// under 1 mm, they took `joints` from 0.411 to 0.373 s (median of 10).
///
/// With the robot's motors ([`with_motors`](Self::with_motors)), the optimal profile also keeps
/// every motor's torque within its peak (docs/dynamics.md).
#[derive(Debug, Clone)]
pub struct JointSpeedLimit {
    model: Kinematics,
    /// θ limits in rad/s, d4 in mm/s.
    max_velocity: [f64; 4],
    /// The last probe or grid point: its point (x, y) and configuration, if IK found one.
    last_probe: Option<([f64; 2], Option<PlanarConfiguration>)>,
    /// The optimal profile's bounds, margins included.
    bounds: [JointBound; 4],
    /// The motors' torques, when the robot has motors.
    torques: Option<Box<TorqueLimit>>,
}

/// The motors' torque bounds of the optimal profile.
#[derive(Debug, Clone)]
struct TorqueLimit {
    dynamics: Dynamics,
    motors: [MotorBound; 4],
    /// The payload's mass while the gripper holds it, kg.
    payload_kg: f64,
    holding: bool,
    /// The torques at rest, without and with the payload: the same in every pose, since gravity
    /// is along −z and the revolute joints turn about vertical axes (only d4 carries the
    /// weight; `tests/it/torque.rs` checks it on random poses). One evaluation of the inverse
    /// dynamics saved per grid point.
    at_rest: [[f64; 4]; 2],
    /// The pose `[x, y, z, c]` of the last grid point whose derivatives are known.
    pose: [f64; 4],
}

impl JointSpeedLimit {
    /// The limiter for `robot` (whose kinematics `model` is).
    pub fn new(model: Kinematics, robot: &Robot) -> JointSpeedLimit {
        let [t1, t2, t3, d4] = robot.joint_max_velocity.to_array();
        let max_velocity = [t1.to_radians(), t2.to_radians(), t3.to_radians(), d4];
        let [a1, a2, a3, a4] = robot.joint_max_acceleration.to_array();
        let max_acceleration = [a1.to_radians(), a2.to_radians(), a3.to_radians(), a4];
        let bounds = Joint::ALL.map(|joint| {
            let j = joint as usize;
            let (velocity, acceleration) = if joint.is_revolute() {
                (OPTIMAL_VELOCITY_MARGIN, OPTIMAL_ACCELERATION_MARGIN)
            } else {
                (1.0, 1.0)
            };
            JointBound {
                name: joint.name(),
                max_velocity: velocity * max_velocity[j],
                max_acceleration: acceleration * max_acceleration[j],
            }
        });
        JointSpeedLimit { model, max_velocity, last_probe: None, bounds, torques: None }
    }

    /// The limiter that also bounds the motors' torques by their peaks (less a 1 % margin, and
    /// less the viscous friction at each joint's velocity limit), with the inverse dynamics of
    /// `robot`; unchanged when the robot has no `motors`. Fails when the model cannot be built
    /// (d4's motor too weak to hold the slide and payload).
    pub fn with_motors(mut self, robot: &RobotModel) -> Result<JointSpeedLimit, DynamicsError> {
        if robot.robot().motors.is_none() {
            return Ok(self);
        }
        let dynamics = Dynamics::new(robot)?;
        let Some(motors) = dynamics.motors().copied() else { return Ok(self) };
        // Viscous + Coulomb at the velocity limits, less Coulomb: the viscous part.
        let at_limit = dynamics.friction(self.max_velocity);
        let motors = std::array::from_fn(|j| {
            let motor = motors[j];
            let margin = if j == 3 { 1.0 } else { OPTIMAL_TORQUE_MARGIN };
            MotorBound {
                peak: margin * motor.peak,
                coulomb: motor.coulomb,
                viscous_at_limit: (at_limit[j] - motor.coulomb).max(0.0),
            }
        });
        let payload_kg = dynamics.bodies().payload;
        // At the home pose (q = 0), which every robot model assembles.
        let [free, held] = [0.0, payload_kg]
            .map(|payload| dynamics.rigid_torques([0.0; 4], [0.0; 4], [0.0; 4], payload));
        let at_rest = [free?, held?];
        self.torques = Some(Box::new(TorqueLimit {
            dynamics,
            motors,
            payload_kg,
            holding: false,
            at_rest,
            pose: [f64::NAN; 4],
        }));
        Ok(self)
    }
}

impl SpeedLimit for JointSpeedLimit {
    fn max_rate(&mut self, segment: &Segment) -> Option<RateLimit> {
        let probes = (segment.length() * PROBES_PER_MM
            + segment.rotation().abs() * PROBES_PER_DEGREE
            + segment.turning() * PROBES_PER_DEGREE_OF_TURN)
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

    fn joint_bounds(&self) -> &[JointBound] {
        &self.bounds
    }

    /// `dq/ds` and `d²q/ds²` in closed form from the loop closure differentiated twice
    /// ([`Kinematics::joint_derivatives`], tested against differences of IK in
    /// `biscara-kinematics`), from the pose and its first two derivatives along the move: one
    /// IK configuration per grid point. (The first version took central differences of the
    /// Jacobian 1 µm apart: two configurations per point and a truncation error of ~1e-10.)
    fn joint_derivatives(
        &mut self,
        segment: &Segment,
        s: f64,
        first: &mut [f64],
        second: &mut [f64],
    ) -> bool {
        let [point, along, curve] = segment.derivatives(s);
        if let Some(torques) = &mut self.torques {
            torques.pose = point;
        }
        // A move's first grid point is the last one's of the move before (the same bits):
        // its configuration is the probe kept from there.
        let configuration = match self.last_probe {
            Some(([x, y], configuration))
                if x.to_bits() == point[0].to_bits() && y.to_bits() == point[1].to_bits() =>
            {
                configuration
            }
            _ => {
                let configuration = self.model.configuration(point[0], point[1]).ok();
                self.last_probe = Some(([point[0], point[1]], configuration));
                configuration
            }
        };
        let Some(configuration) = configuration else {
            return false;
        };
        let (along, curve) = (
            [along[0], along[1], along[2], along[3].to_radians()],
            [curve[0], curve[1], curve[2], curve[3].to_radians()],
        );
        let Some((rates, curvature)) = self.model.joint_derivatives(&configuration, along, curve)
        else {
            return false;
        };
        let (rates, curvature) = (rates.to_array(), curvature.to_array());
        let joints = first.len().min(4);
        first[..joints].copy_from_slice(&rates[..joints]);
        second[..joints].copy_from_slice(&curvature[..joints]);
        true
    }

    fn torque_rows(&self) -> usize {
        if self.torques.is_some() { 4 } else { 0 }
    }

    /// The motors' torques along the path (`biscara_joints`' `torque` module): the pose's θ1
    /// and θ2 by IK, the five-bar solved there once ([`Dynamics::linkage`]), the rows from two
    /// evaluations of the rigid-body inverse dynamics (the third, at rest, is known).
    fn torque_constraints(
        &mut self,
        first: &[f64],
        second: &[f64],
        out: &mut [Constraint],
    ) -> bool {
        let Some(torques) = &self.torques else { return false };
        if first.len() < 4 || second.len() < 4 {
            return false;
        }
        // θ1 and θ2 alone (the torques do not depend on θ3 or d4), and the five-bar solved at
        // them once for the two evaluations: bit for bit what `rigid_torques` of the pose's IK
        // gives, without computing θ3 or solving the five-bar twice.
        let [x, y, z, c] = torques.pose;
        if !(z.is_finite() && c.is_finite()) {
            return false;
        }
        let Ok([theta1, theta2]) = self.model.actuated_angles(x, y) else { return false };
        let dynamics = &torques.dynamics;
        let Ok(linkage) = dynamics.linkage(theta1, theta2) else { return false };
        let payload = if torques.holding { torques.payload_kg } else { 0.0 };
        let rigid = |qd, qdd| dynamics.linkage_torques(&linkage, qd, qdd, payload).ok();
        let first = [first[0], first[1], first[2], first[3]];
        let second = [second[0], second[1], second[2], second[3]];
        let at_rest = torques.at_rest[usize::from(torques.holding)];
        torque_rows(rigid, Some(at_rest), first, second, &torques.motors, out)
    }

    fn set_holding(&mut self, holding: bool) {
        if let Some(torques) = &mut self.torques {
            torques.holding = holding;
        }
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

#[cfg(test)]
mod tests {
    use biscara_interpolate::Segment;
    use biscara_kinematics::{Pose, Robot};
    use biscara_motion::Plane;
    use proptest::prelude::*;

    use super::*;

    /// The joint rates `dq/ds` at `s`, or `None` where the robot cannot take the pose.
    fn rates(model: &Kinematics, segment: &Segment, s: f64) -> Option<[f64; 4]> {
        let [x, y, z, c] = segment.point(s);
        let solution = model.inverse_checked(&Pose::from_degrees(x, y, z, c)).ok()?;
        let [dx, dy, dz, dc] = segment.derivative(s);
        let rates = model.joint_velocity(&solution.configuration, [dx, dy, dz, dc.to_radians()])?;
        Some(rates.to_array())
    }

    proptest! {
        #![proptest_config(ProptestConfig {
            cases: 400,
            max_global_rejects: 100_000,
            ..ProptestConfig::default()
        })]

        /// At the rate the limiter allows, no joint exceeds its limit anywhere along the move,
        /// checked at 400 points: the margin covers the peaks between probes, on moves probed
        /// at their ends only (under 1 mm and 1°) as on longer ones.
        #[test]
        fn no_joint_exceeds_its_limit_between_probes(
            x in -200.0..200.0f64,
            y in 150.0..450.0f64,
            heading in 0.0..std::f64::consts::TAU,
            length in prop_oneof![0.01..1.0f64, 1.0..30.0f64],
            rotation in prop_oneof![Just(0.0), -0.9..0.9f64, -40.0..40.0f64],
            bulge in prop_oneof![Just(0.0), 0.6..5.0f64],
            clockwise: bool,
        ) {
            let robot = Robot::default();
            let model = Kinematics::new(&robot).expect("robot");
            let start = [x, y, 50.0, 0.0];
            let end = [x + length * heading.cos(), y + length * heading.sin(), 40.0, rotation];
            let segment = if bulge > 0.0 {
                // The centre off the chord's midpoint by `bulge` chords.
                let (mx, my) = ((start[0] + end[0]) / 2.0, (start[1] + end[1]) / 2.0);
                let centre = [mx - bulge * length * heading.sin(), my + bulge * length * heading.cos()];
                Segment::arc(start, end, centre, Plane::Xy, clockwise, 1)
            } else {
                Segment::line(start, end)
            };
            let dense: Option<Vec<[f64; 4]>> =
                (0..=400).map(|k| rates(&model, &segment, f64::from(k) / 400.0)).collect();
            // Moves the robot cannot take, or that come near a singularity, are the trajectory
            // stage's to refuse.
            prop_assume!(dense.is_some());
            let limit = JointSpeedLimit::new(model, &robot).max_rate(&segment);
            let limit = limit.expect("a moving segment has a rate limit");
            let max_velocity = JointSpeedLimit::new(model, &robot).max_velocity;
            for rates in dense.unwrap_or_default() {
                for joint in 0..4 {
                    let speed = rates[joint].abs() * limit.rate;
                    prop_assert!(
                        speed <= max_velocity[joint] * (1.0 + 1e-9),
                        "joint {joint}: {speed} > {} at the allowed rate {}",
                        max_velocity[joint],
                        limit.rate
                    );
                }
            }
        }
    }
}
