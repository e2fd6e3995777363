//! The planar Jacobian of the five-bar from its loop-closure equations, and joint rates.

use nalgebra as na;

use crate::kinematics::proximal_rate_direction;
use crate::{Chain, Joints, PlanarConfiguration};

/// The planar Jacobian `Ṗ = J(q)·[θ̇1, θ̇2]` at one configuration.
///
/// From the loop closure `|P − E_i(θ_i)|² = l2²`: `z_i · Ṗ = l1 (a_i × z_i) θ̇_i` with
/// `z_i = P − E_i`, i.e. `A·Ṗ = B·θ̇` with `A = [z1ᵀ; z2ᵀ]` and `B = diag((E_i − b_i) × z_i)`.
/// `A` is singular at a type-2 singularity (`det A = z1 × z2`), `B` at a type-1 singularity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlanarJacobian {
    /// `A`: rows are the distal link vectors `z_i`, millimetres.
    a: na::Matrix2<f64>,
    /// The diagonal of `B`: `(E_i − b_i) × z_i`, mm².
    b: [f64; 2],
}

impl PlanarJacobian {
    /// The Jacobian at `configuration`.
    pub fn new(configuration: &PlanarConfiguration) -> PlanarJacobian {
        let z1 = configuration.distal(Chain::One);
        let z2 = configuration.distal(Chain::Two);
        let bend = |chain| configuration.proximal(chain).perp(&configuration.distal(chain));
        PlanarJacobian {
            a: na::Matrix2::new(z1.x, z1.y, z2.x, z2.y),
            b: [bend(Chain::One), bend(Chain::Two)],
        }
    }

    /// `J`, mapping joint rates (rad/s) to platform velocity (mm/s); `None` at a type-2
    /// singularity, where it does not exist.
    pub fn forward(&self) -> Option<na::Matrix2<f64>> {
        let a_inverse = self.a.try_inverse()?;
        Some(a_inverse * na::Matrix2::from_diagonal(&na::Vector2::from(self.b)))
    }

    /// `J⁻¹`, mapping platform velocity (mm/s) to joint rates (rad/s); `None` at a type-1
    /// singularity, where it does not exist.
    pub fn inverse(&self) -> Option<na::Matrix2<f64>> {
        if self.b[0] == 0.0 || self.b[1] == 0.0 {
            return None;
        }
        let mut inverse = self.a;
        inverse.row_mut(0).scale_mut(1.0 / self.b[0]);
        inverse.row_mut(1).scale_mut(1.0 / self.b[1]);
        Some(inverse)
    }

    /// The 2-norm condition number of `J` (σ_max / σ_min): 1 is isotropic, infinite at either
    /// singularity type.
    pub fn condition_number(&self) -> f64 {
        match self.forward() {
            Some(jacobian) => {
                let singular = jacobian.singular_values();
                let (max, min) = (singular.max(), singular.min());
                if min == 0.0 { f64::INFINITY } else { max / min }
            }
            None => f64::INFINITY,
        }
    }
}

impl crate::Kinematics {
    /// Joint rates for a tool velocity at one configuration: `velocity` holds ẋ, ẏ, ż (mm/s) and
    /// φ̇ (rad/s); the result holds θ̇1, θ̇2, θ̇3 (rad/s) and ḋ4 (mm/s). `None` at a type-1
    /// singularity.
    pub fn joint_velocity(
        &self,
        configuration: &PlanarConfiguration,
        velocity: [f64; 4],
    ) -> Option<Joints> {
        let [vx, vy, vz, phi_rate] = velocity;
        let platform_velocity = na::Vector2::new(vx, vy);
        let rates = PlanarJacobian::new(configuration).inverse()? * platform_velocity;
        // θ3 = φ − (ψ1 − ψ1_home), and ψ̇1 = (z1 × ż1) / l2² with ż1 = Ṗ − Ė1.
        let z1 = configuration.distal(Chain::One);
        let elbow_velocity = rates.x * proximal_rate_direction(configuration.proximal(Chain::One));
        let distal_rate = z1.perp(&(platform_velocity - elbow_velocity)) / z1.norm_squared();
        Some(Joints::new(rates.x, rates.y, phi_rate - distal_rate, -vz))
    }

    /// The first and second derivatives of the joints along a path through `configuration`:
    /// `first` holds dx/ds, dy/ds, dz/ds (mm) and dφ/ds (rad), `second` their derivatives; the
    /// result is `(dq/ds, d²q/ds²)` (rad and mm per unit of s and per unit of s²). `None` at a
    /// type-1 singularity.
    ///
    /// Chain i, with `a = E − b` (length l1), `z = P − E` and `a⊥` = a turned by +90°: the loop
    /// closure `|z|² = l2²` gives `z · P′ = θ′ (a × z)`; differentiated once more along s, with
    /// `z′ = P′ − θ′ a⊥` and `(a × z)′ = a × P′ − θ′ (a · z + l1²)`,
    ///
    /// `θ″ (a × z) = z′ · P′ + z · P″ − θ′ (a × z)′`.
    ///
    /// θ3 = φ − ψ1 + const with ψ1 the angle of z1: `ψ1′ = (z1 × z1′) / l2²` and, |z1| being
    /// constant, `ψ1″ = (z1 × z1″) / l2²` with `z1″ = P″ − θ1″ a1⊥ + θ1′² a1`. d4 = lp − z.
    /// Exact where [`joint_velocity`](Self::joint_velocity) is (tested against differences of
    /// IK along curved paths); one configuration per point, where differences of the Jacobian
    /// need two.
    pub fn joint_derivatives(
        &self,
        configuration: &PlanarConfiguration,
        first: [f64; 4],
        second: [f64; 4],
    ) -> Option<(Joints, Joints)> {
        let velocity = na::Vector2::new(first[0], first[1]);
        let acceleration = na::Vector2::new(second[0], second[1]);
        let mut rates = [0.0; 2];
        let mut curvature = [0.0; 2];
        let mut distal_first = [na::Vector2::zeros(); 2];
        let mut distal_second = [na::Vector2::zeros(); 2];
        for chain in [Chain::One, Chain::Two] {
            let i = chain.index();
            let a = configuration.proximal(chain);
            let z = configuration.distal(chain);
            let bend = a.perp(&z);
            if bend == 0.0 {
                return None;
            }
            let a_perp = proximal_rate_direction(a);
            let rate = z.dot(&velocity) / bend;
            let z_rate = velocity - rate * a_perp;
            let bend_rate = a.perp(&velocity) - rate * (a.dot(&z) + a.norm_squared());
            let second_rate =
                (z_rate.dot(&velocity) + z.dot(&acceleration) - rate * bend_rate) / bend;
            rates[i] = rate;
            curvature[i] = second_rate;
            distal_first[i] = z_rate;
            distal_second[i] = acceleration - second_rate * a_perp + rate * rate * a;
        }
        let z1 = configuration.distal(Chain::One);
        let length_squared = z1.norm_squared();
        let distal_rate = z1.perp(&distal_first[0]) / length_squared;
        let distal_curvature = z1.perp(&distal_second[0]) / length_squared;
        Some((
            Joints::new(rates[0], rates[1], first[3] - distal_rate, -first[2]),
            Joints::new(curvature[0], curvature[1], second[3] - distal_curvature, -second[2]),
        ))
    }
}

#[cfg(test)]
mod tests {
    use approx::assert_relative_eq;

    use super::*;
    use crate::{Kinematics, Pose};

    #[test]
    fn jacobian_matches_finite_differences_of_fk() {
        let model = Kinematics::default();
        let q = Joints::from_degrees(20.0, -35.0, 10.0, 40.0);
        let fk = model.forward(&q).unwrap();
        let jacobian = PlanarJacobian::new(&fk.configuration).forward().unwrap();
        let h = 1e-7;
        for (column, dq) in [(0, Joints::new(h, 0.0, 0.0, 0.0)), (1, Joints::new(0.0, h, 0.0, 0.0))]
        {
            let plus = Joints::new(q.theta1 + dq.theta1, q.theta2 + dq.theta2, q.theta3, q.d4);
            let minus = Joints::new(q.theta1 - dq.theta1, q.theta2 - dq.theta2, q.theta3, q.d4);
            let p1 = model.forward(&plus).unwrap().pose;
            let p0 = model.forward(&minus).unwrap().pose;
            assert_relative_eq!(jacobian[(0, column)], (p1.x - p0.x) / (2.0 * h), epsilon = 1e-4);
            assert_relative_eq!(jacobian[(1, column)], (p1.y - p0.y) / (2.0 * h), epsilon = 1e-4);
        }
        let inverse = PlanarJacobian::new(&fk.configuration).inverse().unwrap();
        assert_relative_eq!(jacobian * inverse, na::Matrix2::identity(), epsilon = 1e-9);
    }

    #[test]
    fn joint_velocity_matches_finite_differences_of_ik() {
        let model = Kinematics::default();
        let pose = Pose::from_degrees(80.0, 330.0, 40.0, 25.0);
        let velocity = [120.0, -75.0, 30.0, 1.5];
        let h = 1e-6;
        let step = |sign: f64| {
            let moved = Pose::new(
                pose.x + sign * h * velocity[0],
                pose.y + sign * h * velocity[1],
                pose.z + sign * h * velocity[2],
                pose.phi + sign * h * velocity[3],
            );
            model.inverse(&moved).unwrap().joints.to_array()
        };
        let (after, before) = (step(1.0), step(-1.0));
        let solution = model.inverse(&pose).unwrap();
        let rates = model.joint_velocity(&solution.configuration, velocity).unwrap().to_array();
        for joint in 0..4 {
            let expected = (after[joint] - before[joint]) / (2.0 * h);
            assert_relative_eq!(rates[joint], expected, epsilon = 1e-5, max_relative = 1e-6);
        }
    }

    /// Along a curved path (a circle with z and φ moving), the analytic derivatives match
    /// central differences of IK, at several places of the workspace.
    #[test]
    fn joint_derivatives_match_differences_of_ik() {
        let model = Kinematics::default();
        for (cx, cy, radius, speed) in
            [(80.0, 330.0, 25.0, 0.7), (-120.0, 260.0, 3.0, 2.5), (40.0, 420.0, 60.0, 0.2)]
        {
            // x(s) = c + r (cos ωs, sin ωs), z = 40 − 7s + 3s², φ = 0.4 + 0.3s − 0.2s².
            let pose = |s: f64| {
                let angle = speed * s;
                Pose::new(
                    cx + radius * angle.cos(),
                    cy + radius * angle.sin(),
                    40.0 - 7.0 * s + 3.0 * s * s,
                    0.4 + 0.3 * s - 0.2 * s * s,
                )
            };
            for s in [0.1, 0.5, 0.9] {
                let angle = speed * s;
                let (sin, cos) = angle.sin_cos();
                let first =
                    [-radius * speed * sin, radius * speed * cos, -7.0 + 6.0 * s, 0.3 - 0.4 * s];
                let w2 = radius * speed * speed;
                let second = [-w2 * cos, -w2 * sin, 6.0, -0.4];
                let solution = model.inverse(&pose(s)).unwrap();
                let (rates, curvature) =
                    model.joint_derivatives(&solution.configuration, first, second).unwrap();
                let ik = |s: f64| model.inverse(&pose(s)).unwrap().joints.to_array();
                let h = 1e-4;
                let (before, here, after) = (ik(s - h), ik(s), ik(s + h));
                let (rates, curvature) = (rates.to_array(), curvature.to_array());
                let velocity = model.joint_velocity(&solution.configuration, first).unwrap();
                for joint in 0..4 {
                    let expected_rate = (after[joint] - before[joint]) / (2.0 * h);
                    let expected_curvature =
                        (after[joint] - 2.0 * here[joint] + before[joint]) / (h * h);
                    assert_relative_eq!(
                        rates[joint],
                        expected_rate,
                        epsilon = 1e-6,
                        max_relative = 1e-6
                    );
                    assert_relative_eq!(
                        rates[joint],
                        velocity.to_array()[joint],
                        epsilon = 1e-12,
                        max_relative = 1e-12
                    );
                    assert_relative_eq!(
                        curvature[joint],
                        expected_curvature,
                        epsilon = 1e-4,
                        max_relative = 1e-4
                    );
                }
            }
        }
    }

    #[test]
    fn condition_number_grows_near_a_singularity() {
        let model = Kinematics::default();
        let home = model.forward(&Joints::default()).unwrap();
        let angle = 120f64.to_radians();
        let point = Pose::new(100.0 + 479.9 * angle.cos(), 479.9 * angle.sin(), 0.0, 0.0);
        let stretched = model.inverse(&point).unwrap();
        let near = PlanarJacobian::new(&stretched.configuration).condition_number();
        let far = PlanarJacobian::new(&home.configuration).condition_number();
        assert!(near > 10.0 * far, "near {near}, far {far}");
    }
}
