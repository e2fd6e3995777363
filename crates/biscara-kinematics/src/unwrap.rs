//! Keeping angles continuous along a path.

use std::f64::consts::TAU;

use crate::IkSolution;

/// Unwraps a sequence of angles: each value is moved by a whole number of turns to lie within
/// half a turn of the previous output. The first value passes unchanged.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct AngleUnwrapper {
    previous: Option<f64>,
}

impl AngleUnwrapper {
    /// An unwrapper with no history.
    pub fn new() -> AngleUnwrapper {
        AngleUnwrapper::default()
    }

    /// The angle (radians) shifted by whole turns to be nearest to the previous result.
    pub fn unwrap(&mut self, angle: f64) -> f64 {
        let continuous = match self.previous {
            Some(previous) => angle + TAU * ((previous - angle) / TAU).round(),
            None => angle,
        };
        self.previous = Some(continuous);
        continuous
    }
}

/// Makes θ3 continuous along a path (SPEC §1.1): `θ3 = φ − (ψ1 − ψ1_home)` with ψ1 unwrapped,
/// never wrapped into (−180°, 180°].
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
    pub fn apply(&mut self, solution: &mut IkSolution) {
        let rotation = self.distal_rotation.unwrap(solution.distal_rotation);
        solution.joints.theta3 = solution.pose.phi - rotation;
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
    fn first_value_is_kept() {
        let mut unwrapper = AngleUnwrapper::new();
        assert_eq!(unwrapper.unwrap(PI), PI);
        assert_relative_eq!(unwrapper.unwrap(-PI + 0.1), PI + 0.1, epsilon = 1e-12);
    }
}
