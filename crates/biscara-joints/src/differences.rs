//! Joint velocities and accelerations by finite differences of the positions: the one place
//! that computes them, for the joint CSV (`JointTrajectory`) and for `check`.

/// First differences `(q_b − q_a) / (t_b − t_a)` per joint: the velocity between two samples.
#[inline(always)]
pub fn slope(t_a: f64, q_a: &[f64; 4], t_b: f64, q_b: &[f64; 4]) -> [f64; 4] {
    let dt = t_b - t_a;
    [0, 1, 2, 3].map(|j| (q_b[j] - q_a[j]) / dt)
}

/// Central differences at the middle of three samples `(t, q)`: the velocity
/// `(q₂ − q₀) / (t₂ − t₀)` and the acceleration `2 (v₁₂ − v₀₁) / (t₂ − t₀)`, where `v₀₁` and `v₁₂`
/// are the [`slope`]s on either side (exact for a parabola, also with unequal steps).
#[inline(always)]
pub fn central_differences(
    before: (f64, &[f64; 4]),
    middle: (f64, &[f64; 4]),
    after: (f64, &[f64; 4]),
) -> ([f64; 4], [f64; 4]) {
    let back = slope(before.0, before.1, middle.0, middle.1);
    let ahead = slope(middle.0, middle.1, after.0, after.1);
    let span = after.0 - before.0;
    let mut velocity = [0.0; 4];
    let mut acceleration = [0.0; 4];
    for j in 0..4 {
        velocity[j] = (after.1[j] - before.1[j]) / span;
        acceleration[j] = 2.0 * (ahead[j] - back[j]) / span;
    }
    (velocity, acceleration)
}

/// The end-sample rule of every joint trajectory here (the joint CSV, LinuxCNC's recordings): a
/// first or last sample takes the slope between it and its one neighbour as its velocity, and
/// its neighbour's acceleration (zero when the neighbour has none: two samples in all).
#[inline(always)]
pub fn end_derivatives(
    end: (f64, &[f64; 4]),
    neighbour: (f64, &[f64; 4]),
    neighbour_acceleration: [f64; 4],
) -> ([f64; 4], [f64; 4]) {
    (slope(end.0, end.1, neighbour.0, neighbour.1), neighbour_acceleration)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn central_differences_are_exact_on_a_parabola_with_unequal_steps() {
        // q = 3 t² − 2 t + 1 in every joint: q' = 6 t − 2, q'' = 6.
        let q = |t: f64| [3.0 * t * t - 2.0 * t + 1.0; 4];
        let (t0, t1, t2) = (0.5, 0.6, 0.85);
        let (velocity, acceleration) =
            central_differences((t0, &q(t0)), (t1, &q(t1)), (t2, &q(t2)));
        for j in 0..4 {
            // The central velocity is the chord's slope: exact at the middle of the span.
            assert!((velocity[j] - (6.0 * 0.5 * (t0 + t2) - 2.0)).abs() < 1e-12);
            assert!((acceleration[j] - 6.0).abs() < 1e-9);
        }
    }

    #[test]
    fn slope_is_the_chord() {
        assert_eq!(
            slope(1.0, &[0.0, 1.0, 2.0, 3.0], 1.5, &[1.0, 1.0, 0.0, 4.0]),
            [2.0, 0.0, -4.0, 2.0]
        );
    }
}
