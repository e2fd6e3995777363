//! Motor torques as bounds of the time-optimal profile (docs/dynamics.md).
//!
//! Along a path q(s) with q′ = dq/ds and q″ = d²q/ds², the joints move with q̇ = q′ ṡ and
//! q̈ = q′ s̈ + q″ ṡ², and the rigid-body torques τ = M(q) q̈ + C(q, q̇) q̇ + g(q) become
//!
//! `τ = a · s̈ + b · ṡ² + c` with `a = M q′`, `b = M q″ + C(q, q′) q′`, `c = g`,
//!
//! the form of `biscara_timing::Constraint`. All three come from the inverse dynamics alone:
//! `c = τ(q, 0, 0)`, `a = τ(q, 0, q′) − c` and `b = τ(q, q′, q″) − c` (the velocity terms are
//! quadratic in q̇, so those at q′ are the ones at q̇ divided by ṡ²).
//!
//! Friction is bounded conservatively, off the motor's peak on both sides:
//! - Coulomb friction (its full value): along a path run forward it has the sign of q′, and so
//!   would be a term of `c`; but where a joint stops and turns back at a corner, its sign
//!   flips while the braking torque is still applied, and the central differences of the
//!   sampled trajectory (what `joints --torques` and `check` compute) see both at one sample —
//!   up to twice the Coulomb friction over the peak (measured: 3.8 % of θ2's peak on a corner
//!   of the random programs of `tests/it/torque.rs`). Taken off both sides, it bounds the
//!   torque whatever its sign.
//! - Viscous friction grows with |q̇| and so fits no such row: its value at the joint's
//!   velocity limit, which no planned motion exceeds.

use biscara_interpolate::Constraint;

/// The planner's bounds on one motor: its rigid-body torque within ±`peak` less its friction
/// (`coulomb` and `viscous_at_limit`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct MotorBound {
    /// Peak torque (N·m, N for d4), margin included.
    pub(crate) peak: f64,
    /// Coulomb friction (N·m, N).
    pub(crate) coulomb: f64,
    /// Viscous friction at the joint's velocity limit (N·m, N).
    pub(crate) viscous_at_limit: f64,
}

/// The torque rows at one point of a path into `out` (four rows: θ1, θ2, θ3, d4): `rigid`
/// is the rigid-body inverse dynamics `(q, q̇, q̈) → τ` (no friction) at the point, `at_rest`
/// its value at rest when known beforehand (else evaluated), `first` and `second` the joints' q′
/// and q″. `false` where `rigid` fails (the rows are then left as they were).
pub(crate) fn torque_rows(
    mut rigid: impl FnMut([f64; 4], [f64; 4]) -> Option<[f64; 4]>,
    at_rest: Option<[f64; 4]>,
    first: [f64; 4],
    second: [f64; 4],
    motors: &[MotorBound; 4],
    out: &mut [Constraint],
) -> bool {
    let Some(at_rest) = at_rest.or_else(|| rigid([0.0; 4], [0.0; 4])) else { return false };
    let Some(along) = rigid([0.0; 4], first) else { return false };
    let Some(curving) = rigid(first, second) else { return false };
    for (j, (row, motor)) in out.iter_mut().zip(motors).enumerate() {
        let c = at_rest[j];
        // Rest must stay allowed: a motor that can barely hold the slide against gravity holds
        // it (the model refuses one that cannot hold it at all).
        let bound = (motor.peak - motor.coulomb - motor.viscous_at_limit).max(c.abs());
        *row = Constraint { a: along[j] - c, b: curving[j] - c, c, lo: -bound, hi: bound };
    }
    true
}

#[cfg(test)]
mod tests {
    use approx::assert_relative_eq;

    use super::*;

    /// A stand-in model: a pose-dependent diagonal inertia, a velocity product term and a
    /// constant load on d4.
    fn model(q: [f64; 4], qd: [f64; 4], qdd: [f64; 4]) -> [f64; 4] {
        let m = [1.0 + q[1].cos(), 2.0, 0.5, 3.0];
        let mut tau = [0.0; 4];
        for j in 0..4 {
            tau[j] = m[j] * qdd[j];
        }
        tau[0] += 0.3 * qd[0] * qd[1];
        tau[3] -= 5.0;
        tau
    }

    #[test]
    fn rows_give_the_torques_of_the_timed_path() {
        let q = [0.2, 0.7, -0.1, 30.0];
        let (first, second) = ([0.5, -1.0, 0.25, 2.0], [0.1, 0.3, -0.2, 0.0]);
        let motors = [MotorBound { peak: 10.0, coulomb: 0.5, viscous_at_limit: 1.0 }; 4];
        let mut rows = [Constraint::default(); 4];
        assert!(torque_rows(
            |qd, qdd| Some(model(q, qd, qdd)),
            None,
            first,
            second,
            &motors,
            &mut rows
        ));
        // At ṡ = 1.5 /s and s̈ = −2 /s²: q̇ = q′ ṡ, q̈ = q′ s̈ + q″ ṡ².
        let (rate, accel) = (1.5, -2.0);
        let qd = first.map(|v| v * rate);
        let qdd: [f64; 4] = std::array::from_fn(|j| first[j] * accel + second[j] * rate * rate);
        let expected = model(q, qd, qdd);
        for j in 0..4 {
            let planned = rows[j].a * accel + rows[j].b * rate * rate + rows[j].c;
            assert_relative_eq!(planned, expected[j], epsilon = 1e-12);
            assert_eq!((rows[j].lo, rows[j].hi), (-8.5, 8.5));
        }
    }

    #[test]
    fn rest_stays_allowed_for_a_motor_that_barely_holds_its_load() {
        let motors = [MotorBound { peak: 5.5, coulomb: 0.5, viscous_at_limit: 0.5 }; 4];
        let mut rows = [Constraint::default(); 4];
        let q = [0.0; 4];
        assert!(torque_rows(
            |qd, qdd| Some(model(q, qd, qdd)),
            Some(model(q, [0.0; 4], [0.0; 4])),
            [1.0, 0.0, 0.0, 1.0],
            [0.0; 4],
            &motors,
            &mut rows
        ));
        assert_eq!((rows[0].c, rows[0].hi), (0.0, 4.5));
        assert_eq!((rows[3].c, rows[3].lo, rows[3].hi), (-5.0, -5.0, 5.0));
    }

    #[test]
    fn a_failing_model_gives_no_rows() {
        let motors = [MotorBound { peak: 1.0, coulomb: 0.0, viscous_at_limit: 0.0 }; 4];
        let mut rows = [Constraint::default(); 4];
        assert!(!torque_rows(|_, _| None, None, [1.0; 4], [0.0; 4], &motors, &mut rows));
    }
}
