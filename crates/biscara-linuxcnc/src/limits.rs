//! Axis velocity and acceleration limits for LinuxCNC's Cartesian planner, derived from the joint
//! limits so that no joint can exceed its own anywhere in the workspace rectangle.
//!
//! LinuxCNC's trajectory planner limits each axis (X, Y, Z, C) separately and knows nothing of
//! the joints under non-trivial kinematics. With every axis velocity within `|vx|, |vy| ≤ V`
//! and acceleration within `|ax|, |ay| ≤ A`, a joint angle θ(x, y) moves at
//! `θ̇ = ∇θ · v` and accelerates at `θ̈ = ∇θ · a + vᵀ H v` (H the Hessian of θ), so
//!
//! ```text
//! |θ̇| ≤ G V            with G = |∂θ/∂x| + |∂θ/∂y|
//! |θ̈| ≤ G A + S V²     with S = max |uᵀ H u| over |ux|, |uy| ≤ 1
//! ```
//!
//! for every direction of motion. V and A are chosen so that both bounds hold for θ1 and θ2 at
//! every grid point of the rectangle; θ3 = φ − ψ1 + const (ψ1 the angle of chain 1's distal
//! link) gives C's limits the same way, and d4 = lp − z gives Z the limits of d4.

use biscara_kinematics::{Chain, Kinematics, Robot};
use biscara_robot::Rectangle;

/// The fraction of a joint's acceleration limit that the velocity term `S V²` may take at
/// most; the rest is left for the path's own acceleration.
const CURVATURE_SHARE: f64 = 0.5;

/// The fraction of θ3's velocity and acceleration limits that the rotation of chain 1's
/// distal link may take at most; the rest is left for C itself.
const DISTAL_SHARE: f64 = 0.75;

/// The derived limits are this share of the bounds found on the grid, for what lies between
/// its points (the bounds vary by well under 3 % from one point to the next at 2 mm).
const GRID_MARGIN: f64 = 0.97;

/// Steps of the finite differences, millimetres: the gradient's and the Hessian's.
const GRADIENT_STEP: f64 = 1e-3;
const HESSIAN_STEP: f64 = 0.05;

/// Axis limits for LinuxCNC's `[AXIS_*]` sections and how each was found.
#[derive(Debug, Clone, PartialEq)]
pub struct AxisLimits {
    /// X's and Y's velocity limit, mm/s (each axis; √2 times that diagonally).
    pub xy_velocity: f64,
    /// X's and Y's acceleration limit, mm/s².
    pub xy_acceleration: f64,
    /// Z's velocity limit, mm/s.
    pub z_velocity: f64,
    /// Z's acceleration limit, mm/s².
    pub z_acceleration: f64,
    /// C's velocity limit, degrees/s.
    pub c_velocity: f64,
    /// C's acceleration limit, degrees/s².
    pub c_acceleration: f64,
    /// Where the numbers came from, for the INI's comments.
    pub derivation: Derivation,
}

/// The figures behind [`AxisLimits`]: the rectangle, the worst gradients and curvatures found
/// on it, what bound each limit, and what the limits cost.
#[derive(Debug, Clone, PartialEq)]
pub struct Derivation {
    /// The rectangle the limits hold on.
    pub rectangle: Rectangle,
    /// The grid step, millimetres.
    pub step: f64,
    /// Number of grid points evaluated.
    pub points: usize,
    /// Largest `G` of θ1 and θ2, degrees per mm.
    pub gradient: [f64; 2],
    /// Largest `S` of θ1 and θ2, degrees per mm².
    pub curvature: [f64; 2],
    /// Largest `G` and `S` of ψ1 (chain 1's distal link), degrees per mm and per mm².
    pub distal: [f64; 2],
    /// What bounds the XY velocity: a joint's velocity limit, its acceleration limit (through
    /// `S V²`), θ3, or the robot's own Cartesian `rapid_velocity`.
    pub velocity_bound: &'static str,
    /// What bounds the XY acceleration.
    pub acceleration_bound: &'static str,
    /// The XY speed along X that θ1's and θ2's velocity limits alone allow at the rectangle's
    /// centre, mm/s: what the uniform limit gives up there.
    pub centre_speed: f64,
}

/// The error of [`derive_axis_limits`].
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum LimitsError {
    /// Occurs when a grid point of the rectangle cannot be solved (it should be reachable).
    #[error("the workspace rectangle's point ({x:.3}, {y:.3}) mm cannot be solved")]
    Unsolvable {
        /// x, millimetres.
        x: f64,
        /// y, millimetres.
        y: f64,
    },
    /// Occurs when the grid step is not a positive number.
    #[error("the grid step must be a positive number of millimetres (got {0})")]
    Step(f64),
}

/// θ1, θ2 and ψ1 at (x, y), radians, in the robot's working mode.
fn angles(model: &Kinematics, x: f64, y: f64) -> Option<[f64; 3]> {
    let configuration = model.configuration(x, y).ok()?;
    let angle = |chain: Chain| {
        let proximal = configuration.proximal(chain);
        // θ from +Y counter-clockwise: the proximal direction is (−sin θ, cos θ).
        (-proximal.x).atan2(proximal.y)
    };
    Some([angle(Chain::One), angle(Chain::Two), configuration.distal_angle(Chain::One)])
}

/// The difference of two angles, wrapped into (−π, π].
fn angle_difference(a: f64, b: f64) -> f64 {
    biscara_kinematics::wrap_angle(a - b)
}

/// `G` and `S` of θ1, θ2 and ψ1 at (x, y): radians per mm and per mm².
fn gradient_and_curvature(model: &Kinematics, x: f64, y: f64) -> Option<[[f64; 2]; 3]> {
    let centre = angles(model, x, y)?;
    let at = |dx: f64, dy: f64| angles(model, x + dx, y + dy);
    let (g, h) = (GRADIENT_STEP, HESSIAN_STEP);
    let (gx_plus, gx_minus, gy_plus, gy_minus) =
        (at(g, 0.0)?, at(-g, 0.0)?, at(0.0, g)?, at(0.0, -g)?);
    let (hx_plus, hx_minus, hy_plus, hy_minus) =
        (at(h, 0.0)?, at(-h, 0.0)?, at(0.0, h)?, at(0.0, -h)?);
    let (pp, pm, mp, mm) = (at(h, h)?, at(h, -h)?, at(-h, h)?, at(-h, -h)?);
    let mut result = [[0.0; 2]; 3];
    for k in 0..3 {
        let dx = angle_difference(gx_plus[k], gx_minus[k]) / (2.0 * g);
        let dy = angle_difference(gy_plus[k], gy_minus[k]) / (2.0 * g);
        let second = |plus: f64, minus: f64| {
            (angle_difference(plus, centre[k]) + angle_difference(minus, centre[k])) / (h * h)
        };
        let dxx = second(hx_plus[k], hx_minus[k]);
        let dyy = second(hy_plus[k], hy_minus[k]);
        let dxy = (angle_difference(pp[k], pm[k]) - angle_difference(mp[k], mm[k])) / (4.0 * h * h);
        result[k] = [dx.abs() + dy.abs(), box_maximum(dxx, dxy, dyy)];
    }
    Some(result)
}

/// The largest `|vᵀ H v|` over the box `|vx|, |vy| ≤ 1`, H = [[xx, xy], [xy, yy]]: at a corner,
/// or where it is stationary along an edge (v = (±1, t) or (t, ±1)).
fn box_maximum(xx: f64, xy: f64, yy: f64) -> f64 {
    let form = |vx: f64, vy: f64| (xx * vx * vx + 2.0 * xy * vx * vy + yy * vy * vy).abs();
    let mut maximum = form(1.0, 1.0).max(form(1.0, -1.0));
    if yy != 0.0 && (xy / yy).abs() <= 1.0 {
        maximum = maximum.max(form(1.0, -xy / yy));
    }
    if xx != 0.0 && (xy / xx).abs() <= 1.0 {
        maximum = maximum.max(form(-xy / xx, 1.0));
    }
    maximum
}

/// Derives LinuxCNC's axis limits from `robot`'s joint limits over `rectangle` (a grid of
/// `step` mm, edges included): the largest uniform XY velocity and acceleration, and C's and
/// Z's limits, such that no joint exceeds its velocity or acceleration limit at any grid point
/// for any direction of motion, and none exceeds the robot's own Cartesian limits (`motion`).
pub fn derive_axis_limits(
    robot: &Robot,
    model: &Kinematics,
    rectangle: &Rectangle,
    step: f64,
) -> Result<AxisLimits, LimitsError> {
    if !(step > 0.0 && step.is_finite()) {
        return Err(LimitsError::Step(step));
    }
    let columns = ((rectangle.width() / step).round() as usize).max(1);
    let rows = ((rectangle.height() / step).round() as usize).max(1);
    // Per grid point: G and S of θ1, θ2, ψ1.
    let mut points = Vec::with_capacity((columns + 1) * (rows + 1));
    for i in 0..=columns {
        for j in 0..=rows {
            let x = rectangle.min[0] + rectangle.width() * i as f64 / columns as f64;
            let y = rectangle.min[1] + rectangle.height() * j as f64 / rows as f64;
            points
                .push(gradient_and_curvature(model, x, y).ok_or(LimitsError::Unsolvable { x, y })?);
        }
    }
    let velocity = robot.joint_max_velocity.to_array().map(f64::to_radians);
    let acceleration = robot.joint_max_acceleration.to_array().map(f64::to_radians);
    let max_of = |k: usize, part: usize| points.iter().map(|p| p[k][part]).fold(0.0, f64::max);
    let gradient = [max_of(0, 0), max_of(1, 0)];
    let curvature = [max_of(0, 1), max_of(1, 1)];
    let distal = [max_of(2, 0), max_of(2, 1)];

    // The XY velocity: the smallest of what each bound allows.
    let mut candidates = vec![
        (velocity[0] / gradient[0], "theta1's velocity limit"),
        (velocity[1] / gradient[1], "theta2's velocity limit"),
        (DISTAL_SHARE * velocity[2] / distal[0], "theta3's velocity limit (the distal link turns)"),
        (robot.motion.rapid_velocity, "the robot's rapid_velocity"),
    ];
    for (k, name) in [(0, "theta1's acceleration limit"), (1, "theta2's acceleration limit")] {
        if curvature[k] > 0.0 {
            candidates.push(((CURVATURE_SHARE * acceleration[k] / curvature[k]).sqrt(), name));
        }
    }
    if distal[1] > 0.0 {
        let share = CURVATURE_SHARE * DISTAL_SHARE * acceleration[2] / distal[1];
        candidates.push((share.sqrt(), "theta3's acceleration limit (the distal link turns)"));
    }
    let (xy_velocity, velocity_bound) = smallest(&candidates);
    let xy_velocity = GRID_MARGIN * xy_velocity;

    // The XY acceleration: what is left of each joint's acceleration limit at every point.
    let mut candidates = vec![(robot.motion.acceleration, "the robot's acceleration")];
    for (k, name) in [(0, "theta1's acceleration limit"), (1, "theta2's acceleration limit")] {
        let allowed = points
            .iter()
            .map(|p| (acceleration[k] - p[k][1] * xy_velocity * xy_velocity) / p[k][0])
            .fold(f64::INFINITY, f64::min);
        candidates.push((allowed, name));
    }
    let allowed = points
        .iter()
        .map(|p| (DISTAL_SHARE * acceleration[2] - p[2][1] * xy_velocity * xy_velocity) / p[2][0])
        .fold(f64::INFINITY, f64::min);
    candidates.push((allowed, "theta3's acceleration limit (the distal link turns)"));
    let (xy_acceleration, acceleration_bound) = smallest(&candidates);
    let xy_acceleration = GRID_MARGIN * xy_acceleration;

    // C: what θ3's limits leave after the distal link's own turning at those XY limits.
    let distal_rate = distal[0] * xy_velocity;
    let distal_acceleration = points
        .iter()
        .map(|p| p[2][0] * xy_acceleration + p[2][1] * xy_velocity * xy_velocity)
        .fold(0.0, f64::max);
    let c_velocity = (velocity[2] - distal_rate).to_degrees().min(robot.motion.rapid_rotation);
    let c_acceleration = (acceleration[2] - distal_acceleration)
        .to_degrees()
        .min(robot.motion.rotation_acceleration);

    let centre = rectangle.center();
    let centre_speed = gradient_and_curvature(model, centre[0], centre[1])
        .map_or(f64::NAN, |p| (velocity[0] / p[0][0]).min(velocity[1] / p[1][0]));
    let to_degrees = |values: [f64; 2]| values.map(f64::to_degrees);
    Ok(AxisLimits {
        xy_velocity,
        xy_acceleration,
        z_velocity: robot.joint_max_velocity.d4,
        z_acceleration: robot.joint_max_acceleration.d4,
        c_velocity,
        c_acceleration,
        derivation: Derivation {
            rectangle: *rectangle,
            step,
            points: points.len(),
            gradient: to_degrees(gradient),
            curvature: to_degrees(curvature),
            distal: to_degrees(distal),
            velocity_bound,
            acceleration_bound,
            centre_speed,
        },
    })
}

/// The smallest value and its name.
fn smallest(candidates: &[(f64, &'static str)]) -> (f64, &'static str) {
    candidates
        .iter()
        .copied()
        .fold((f64::INFINITY, ""), |best, next| if next.0 < best.0 { next } else { best })
}

#[cfg(test)]
mod tests {
    use biscara_kinematics::{Joints, Pose, RobotModel};
    use biscara_robot::Workspace;

    use super::*;

    fn default_limits() -> (RobotModel, Rectangle, AxisLimits) {
        let model = RobotModel::default();
        let kinematics = model.kinematics();
        let rectangle = Workspace::compute(&kinematics, 4.0).unwrap().largest_rectangle().unwrap();
        let limits = derive_axis_limits(model.robot(), &kinematics, &rectangle, 4.0).unwrap();
        (model, rectangle, limits)
    }

    /// Joint angles (θ1, θ2, θ3) of the pose, radians, θ3 for C = 0.
    fn joints_at(model: &Kinematics, x: f64, y: f64) -> Joints {
        model.inverse(&Pose::new(x, y, 50.0, 0.0)).unwrap().joints
    }

    #[test]
    fn box_maximum_is_the_largest_form_on_the_box() {
        for (xx, xy, yy) in [(1.0, 0.3, -2.0), (0.5, -0.9, 0.2), (-1.0, 0.0, -1.0), (2.0, 2.0, 2.0)]
        {
            let mut brute = 0.0_f64;
            for i in 0..=200 {
                for j in 0..=200 {
                    let (vx, vy) = (-1.0 + 0.01 * f64::from(i), -1.0 + 0.01 * f64::from(j));
                    brute = brute.max((xx * vx * vx + 2.0 * xy * vx * vy + yy * vy * vy).abs());
                }
            }
            let exact = box_maximum(xx, xy, yy);
            assert!(exact >= brute - 1e-12 && exact <= brute * 1.001 + 1e-12, "{exact} {brute}");
        }
    }

    /// Independent of the derivation: moves at the limits in many directions, from many points
    /// of the rectangle, measured by finite differences of IK along the move over 1 ms, never
    /// exceed a joint's velocity or acceleration limit.
    #[test]
    fn no_joint_exceeds_its_limits_at_the_derived_axis_limits() {
        let (model, rectangle, limits) = default_limits();
        let kinematics = model.kinematics();
        let robot = model.robot();
        let velocity_limit = robot.joint_max_velocity.to_array().map(f64::to_radians);
        let acceleration_limit = robot.joint_max_acceleration.to_array().map(f64::to_radians);
        let (v, a) = (limits.xy_velocity, limits.xy_acceleration);
        let dt = 1e-3;
        let mut worst = [0.0_f64; 2];
        for i in 0..=20 {
            for j in 0..=10 {
                let x = rectangle.min[0] + rectangle.width() * f64::from(i) / 20.0;
                let y = rectangle.min[1] + rectangle.height() * f64::from(j) / 10.0;
                // Velocity and acceleration on the box's corners and edges, both signs.
                for (vx, vy) in [(1.0, 1.0), (1.0, -1.0), (1.0, 0.0), (0.0, 1.0), (1.0, 0.5)] {
                    for (ax, ay) in [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)] {
                        let at = |t: f64| {
                            joints_at(
                                &kinematics,
                                x + v * vx * t + 0.5 * a * ax * t * t,
                                y + v * vy * t + 0.5 * a * ay * t * t,
                            )
                            .to_array()
                        };
                        let (before, middle, after) = (at(-dt), at(0.0), at(dt));
                        for k in 0..2 {
                            let speed = (after[k] - before[k]).abs() / (2.0 * dt);
                            let accel = (after[k] - 2.0 * middle[k] + before[k]).abs() / (dt * dt);
                            worst[0] = worst[0].max(speed / velocity_limit[k]);
                            worst[1] = worst[1].max(accel / acceleration_limit[k]);
                        }
                    }
                }
            }
        }
        assert!(worst[0] <= 1.0 && worst[1] <= 1.0, "peak shares of the limits: {worst:?}");
        // And the bound is not vacuous: some move comes near a limit.
        assert!(worst[0] > 0.2 || worst[1] > 0.5, "{worst:?}");
    }

    #[test]
    fn the_limits_are_bounded_by_the_robots_cartesian_limits_and_say_why() {
        let (model, _, limits) = default_limits();
        let motion = model.robot().motion;
        assert!(limits.xy_velocity > 0.0 && limits.xy_velocity <= motion.rapid_velocity);
        assert!(limits.xy_acceleration > 0.0 && limits.xy_acceleration <= motion.acceleration);
        assert!(limits.c_velocity > 0.0 && limits.c_velocity <= motion.rapid_rotation);
        assert!(limits.c_acceleration > 0.0);
        assert_eq!(limits.z_velocity, model.robot().joint_max_velocity.d4);
        // The symmetric default robot's θ1 and θ2 bend alike: their acceleration limits through
        // the path's curvature bound the speed (θ2 by rounding), and the speed is what it gives.
        let derivation = &limits.derivation;
        assert_eq!(derivation.velocity_bound, "theta2's acceleration limit");
        let acceleration = model.robot().joint_max_acceleration.theta2;
        let bound = (CURVATURE_SHARE * acceleration / derivation.curvature[1]).sqrt();
        assert!((limits.xy_velocity - GRID_MARGIN * bound).abs() < 1e-9, "{limits:?}");
        assert!(limits.derivation.centre_speed > limits.xy_velocity);
    }

    #[test]
    fn a_bad_step_is_refused() {
        let model = RobotModel::default();
        let rectangle = Rectangle { min: [-10.0, 300.0], max: [10.0, 320.0] };
        let err = derive_axis_limits(model.robot(), &model.kinematics(), &rectangle, 0.0);
        assert_eq!(err.unwrap_err(), LimitsError::Step(0.0));
    }
}
