//! Velocity profiles in path-parameter space: how s ∈ [0, 1] advances with time.

/// How a motion's speed varies along it (docs/motion.md).
///
/// The first paragraph of each variant's documentation is the help of `--profile`'s values (the
/// `clap` feature).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
pub enum Profile {
    /// Constant speed from a motion's first sample to its last (the paper).
    ///
    /// The paper's: velocity jumps at corners.
    Constant,
    /// Accelerate, cruise, decelerate: an exact stop at every corner.
    ///
    /// From rest to rest.
    Trapezoid,
    /// Time-optimal under every joint's velocity and acceleration limits (TOPP-RA), with an
    /// exact stop at every corner.
    ///
    /// The fastest time scaling of each motion under the path speed and acceleration, C's
    /// limits and every joint's velocity and acceleration limits (from the [`SpeedLimit`]),
    /// from rest to rest (TOPP-RA, `biscara-timing`). Not a closed form: the interpolator plans
    /// it; [`Timing`] times it as a trapezoid.
    ///
    /// The default (docs/motion.md).
    ///
    /// [`SpeedLimit`]: crate::SpeedLimit
    #[default]
    Optimal,
}

/// Relative slack when rounding a duration up to whole steps, so that a duration that is a whole
/// number of steps up to rounding noise (0.3 s at 1 ms) is not given one step more.
const STEP_ROUNDING_SLACK: f64 = 1e-9;

/// The timing of one motion: a whole number of steps, and s(t).
///
/// `max_rate` (1/s) and `max_acceleration` (1/s²) bound ds/dt and d²s/dt². The duration is the
/// profile's shortest one, rounded up to whole steps; the speed is then lowered so that the motion
/// ends exactly on the last step (never raised).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Timing {
    steps: u64,
    duration: f64,
    rate: f64,
    acceleration: f64,
    accelerating_for: f64,
    profile: Profile,
}

impl Timing {
    /// The timing of a motion under `profile` at step `dt` (s) ([`Profile::Optimal`] is timed as
    /// a trapezoid here).
    pub fn new(profile: Profile, max_rate: f64, max_acceleration: f64, dt: f64) -> Timing {
        let shortest = match profile {
            Profile::Constant => 1.0 / max_rate,
            Profile::Trapezoid | Profile::Optimal => {
                if max_rate * max_rate >= max_acceleration {
                    // Triangle: accelerate over half the path, decelerate over the other half.
                    2.0 / max_acceleration.sqrt()
                } else {
                    1.0 / max_rate + max_rate / max_acceleration
                }
            }
        };
        let steps = steps_for(shortest, dt);
        let duration = steps as f64 * dt;
        let (rate, accelerating_for) = match profile {
            Profile::Constant => (1.0 / duration, 0.0),
            Profile::Trapezoid | Profile::Optimal => {
                // Cruise rate v with acceleration a covering s = 1 in T: v² − aTv + a = 0.
                let a = max_acceleration;
                let discriminant = (a * a * duration * duration - 4.0 * a).max(0.0);
                let rate = 0.5 * (a * duration - discriminant.sqrt());
                (rate, rate / a)
            }
        };
        Timing { steps, duration, rate, acceleration: max_acceleration, accelerating_for, profile }
    }

    /// Number of whole time steps the motion takes (≥ 1).
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// Duration, s: `steps · dt`.
    pub fn duration(&self) -> f64 {
        self.duration
    }

    /// Cruise rate ds/dt, 1/s (after rounding the duration up).
    pub fn rate(&self) -> f64 {
        self.rate
    }

    /// The path parameter at time `t` (s) since the motion's start, in [0, 1].
    pub fn s_at(&self, t: f64) -> f64 {
        if t >= self.duration {
            return 1.0;
        }
        match self.profile {
            Profile::Constant => t * self.rate,
            Profile::Trapezoid | Profile::Optimal => {
                let ramp = self.accelerating_for;
                if t < ramp {
                    0.5 * self.acceleration * t * t
                } else if t <= self.duration - ramp {
                    0.5 * self.acceleration * ramp * ramp + self.rate * (t - ramp)
                } else {
                    let left = self.duration - t;
                    1.0 - 0.5 * self.acceleration * left * left
                }
            }
        }
    }
}

/// `duration` in whole steps of `dt`, rounded up (at least 1).
pub(crate) fn steps_for(duration: f64, dt: f64) -> u64 {
    let exact = duration / dt;
    let steps = (exact * (1.0 - STEP_ROUNDING_SLACK)).ceil();
    // Durations are bounded by the caller's checks; saturate rather than wrap.
    (steps as u64).max(1)
}

#[cfg(test)]
mod tests {
    use approx::assert_relative_eq;

    use super::*;

    #[test]
    fn constant_profile_rounds_up_and_slows_down() {
        // 1 s at 1/s, dt 0.3 → 4 steps, 1.2 s.
        let timing = Timing::new(Profile::Constant, 1.0, f64::INFINITY, 0.3);
        assert_eq!(timing.steps(), 4);
        assert_relative_eq!(timing.duration(), 1.2);
        assert_relative_eq!(timing.s_at(0.6), 0.5);
        assert_eq!(timing.s_at(1.2), 1.0);
    }

    #[test]
    fn whole_durations_get_no_extra_step() {
        let timing = Timing::new(Profile::Constant, 1.0 / 0.3, f64::INFINITY, 0.001);
        assert_eq!(timing.steps(), 300);
    }

    #[test]
    fn trapezoid_reaches_the_end_at_rest_and_is_continuous() {
        let timing = Timing::new(Profile::Trapezoid, 2.0, 10.0, 0.001);
        // Shortest: 1/2 + 2/10 = 0.7 s.
        assert_eq!(timing.steps(), 700);
        assert!(timing.rate() <= 2.0 + 1e-12);
        let mut previous = 0.0;
        for k in 1..=timing.steps() {
            let s = timing.s_at(k as f64 * 0.001);
            assert!(s >= previous - 1e-15, "s decreased at step {k}");
            assert!(s - previous <= timing.rate() * 0.001 + 1e-12);
            previous = s;
        }
        assert_eq!(previous, 1.0);
        let last = timing.s_at(0.699);
        assert_relative_eq!(1.0 - last, 0.5 * 10.0 * 0.001 * 0.001, epsilon = 1e-9);
    }

    #[test]
    fn short_moves_are_triangles() {
        let timing = Timing::new(Profile::Trapezoid, 100.0, 4.0, 0.01);
        assert_eq!(timing.steps(), 100); // 2/√4 = 1 s
        assert_relative_eq!(timing.s_at(0.5), 0.5, epsilon = 1e-9);
    }

    #[test]
    fn rounding_up_lowers_the_trapezoid_rate() {
        let exact = Timing::new(Profile::Trapezoid, 2.0, 10.0, 0.7);
        let rounded = Timing::new(Profile::Trapezoid, 2.0, 10.0, 0.4);
        assert_eq!(rounded.steps(), 2);
        assert!(rounded.rate() < exact.rate());
        assert_relative_eq!(
            rounded.s_at(0.4),
            0.5 * 10.0 * rounded.accelerating_for.powi(2)
                + rounded.rate() * (0.4 - rounded.accelerating_for),
            epsilon = 1e-12
        );
    }
}
