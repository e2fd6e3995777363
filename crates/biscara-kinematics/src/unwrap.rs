//! Keeping angles continuous along a path.

use std::f64::consts::{PI, TAU};

use crate::IkSolution;

/// Unwraps a sequence of angles: each value is moved by a whole number of turns to lie within
/// half a turn of the previous output. The first value passes unchanged.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct AngleUnwrapper {
    /// The previous result and the raw angle it came from.
    previous: Option<(f64, f64)>,
}

impl AngleUnwrapper {
    /// An unwrapper with no history.
    pub fn new() -> AngleUnwrapper {
        AngleUnwrapper::default()
    }

    /// The angle (radians) shifted by whole turns to be nearest to the previous result.
    pub fn unwrap(&mut self, angle: f64) -> f64 {
        let continuous = match self.previous {
            // Along a path consecutive angles are close: add the step from the previous raw angle,
            // brought into (−π, π] by at most one turn, instead of dividing and rounding (`round`
            // is a library call on baseline x86-64). Raw angles may come unwrapped too: then the
            // step is reduced by whole turns the slow way.
            Some((previous, previous_raw)) => {
                let mut step = angle - previous_raw;
                if step.abs() > 3.0 * PI {
                    step -= TAU * (step / TAU).round();
                }
                if step > PI {
                    step -= TAU;
                } else if step <= -PI {
                    step += TAU;
                }
                previous + step
            }
            None => angle,
        };
        self.previous = Some((continuous, angle));
        continuous
    }
}

/// Makes θ3 continuous along a path (docs/kinematics.md): `θ3 = φ − (ψ1 − ψ1_home)` with ψ1
/// unwrapped, never wrapped into (−180°, 180°].
///
/// Feed it the IK solutions of a path in order.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Theta3Unwrapper {
    distal_rotation: AngleUnwrapper,
}

impl Theta3Unwrapper {
    /// An unwrapper for a new path.
    pub fn new() -> Theta3Unwrapper {
        Theta3Unwrapper::default()
    }

    /// Rewrites `solution.joints.theta3` so that it continues the previous solutions' θ3.
    ///
    /// The first solution keeps the θ3 [`crate::Kinematics::inverse`] gave it (shifted by a turn
    /// into the limits when only that makes it fit), so that a path starts where `ik` says.
    pub fn apply(&mut self, solution: &mut IkSolution) {
        solution.joints.theta3 =
            self.theta3(solution.pose.phi, solution.distal_rotation, solution.joints.theta3);
    }

    /// [`Theta3Unwrapper::apply`] on the parts of a solution it reads: the pose's φ, the
    /// solution's distal rotation and θ3; returns the continuous θ3.
    #[inline]
    pub fn theta3(&mut self, phi: f64, distal_rotation: f64, theta3: f64) -> f64 {
        let raw = distal_rotation;
        if self.distal_rotation.previous.is_some() {
            let rotation = self.distal_rotation.unwrap(raw);
            phi - rotation
        } else {
            // The single-pose θ3 is `φ − raw` or a turn from it: the rotation starts at that turn.
            let unshifted = phi - raw;
            let rotation = if theta3 > unshifted + PI {
                raw - TAU
            } else if theta3 < unshifted - PI {
                raw + TAU
            } else {
                raw
            };
            self.distal_rotation.previous = Some((rotation, raw));
            theta3
        }
    }
}

#[cfg(test)]
mod tests {
    use std::f64::consts::PI;

    use approx::assert_relative_eq;

    use super::*;

    #[test]
    fn unwrapper_follows_a_turning_angle() {
        let mut unwrapper = AngleUnwrapper::new();
        let mut outputs = Vec::new();
        for step in 0..40 {
            let true_angle = 0.3 * f64::from(step);
            let wrapped = crate::wrap_angle(true_angle);
            outputs.push((unwrapper.unwrap(wrapped), true_angle));
        }
        for (output, expected) in outputs {
            assert_relative_eq!(output, expected, epsilon = 1e-12);
        }
    }

    #[test]
    fn many_turns_and_unwrapped_inputs() {
        let mut unwrapper = AngleUnwrapper::new();
        let mut last = 0.0;
        for step in 0..=100_000 {
            last = unwrapper.unwrap(crate::wrap_angle(0.3 * f64::from(step)));
        }
        assert_relative_eq!(last, 30_000.0, epsilon = 1e-6);
        let mut unwrapper = AngleUnwrapper::new();
        unwrapper.unwrap(0.0);
        assert_relative_eq!(unwrapper.unwrap(10.0 * PI + 0.1), 0.1, epsilon = 1e-12);
    }

    /// Issue 13: in working mode `-+`, assembly mode `-`, θ3 = 204.198° is outside [−180°, 180°]
    /// but −155.802° reaches the same pose; IK and the start of a path both take it.
    #[test]
    fn theta3_is_shifted_into_its_limits() {
        let robot: crate::Robot =
            crate::Robot::from_json(r#"{"working_mode": "-+", "assembly_mode": "-"}"#).unwrap();
        let model = crate::Kinematics::new(&robot).unwrap();
        let pose = crate::Pose::from_degrees(-71.220188, 203.375603, 94.088431, 39.89336);
        let mut ik = model.inverse_checked(&pose).expect("the pose is reachable");
        assert_relative_eq!(ik.joints.theta3.to_degrees(), -155.802, epsilon = 1e-3);
        let single = ik.joints.theta3;
        let mut unwrapper = Theta3Unwrapper::new();
        unwrapper.apply(&mut ik);
        assert_eq!(ik.joints.theta3, single);
        // The path goes on from there, continuously.
        let next = crate::Pose::from_degrees(-71.0, 203.5, 94.0, 40.0);
        let mut ik = model.inverse(&next).unwrap();
        unwrapper.apply(&mut ik);
        assert_relative_eq!(ik.joints.theta3, single, epsilon = 0.01);
    }

    #[test]
    fn first_value_is_kept() {
        let mut unwrapper = AngleUnwrapper::new();
        assert_eq!(unwrapper.unwrap(PI), PI);
        assert_relative_eq!(unwrapper.unwrap(-PI + 0.1), PI + 0.1, epsilon = 1e-12);
    }
}
