//! What a program looks like on the robot, gathered for a picture: the path, the robot's body
//! at chosen times and the joint curves, bounded in memory however long the program is.

use biscara_joints::{CartesianSample, JointSolver};
use biscara_kinematics::RobotModel;
use biscara_robot::{Body, VirtualRobot};

use crate::decimate::thin;

/// Most points a trace keeps of the path and of the joint curves: past it every other point is
/// dropped and the spacing doubled.
const MAX_POINTS: usize = 20_000;

/// A program's samples reduced to what its pictures need (`biscara plot`, the demo).
///
/// Every sample is solved by the [`JointSolver`] (so a picture never shows a pose that `joints`
/// and `check` refuse for its assembly mode); samples the robot cannot reach are on the path
/// but have no joint values and no body.
#[derive(Debug)]
pub struct ProgramTrace {
    robot: VirtualRobot,
    solver: JointSolver,
    /// The XY path, points at least `path_spacing` apart, millimetres.
    pub path: Vec<[f64; 2]>,
    /// The robot's body at each wanted time that the program reached, in time order.
    pub bodies: Vec<(f64, Body)>,
    /// Times of the joint curves' points, seconds.
    pub t: Vec<f64>,
    /// Joint values at those times: degrees for θ, millimetres for d4.
    pub q: Vec<[f64; 4]>,
    wanted: Vec<f64>,
    next_wanted: usize,
    path_spacing: f64,
    time_spacing: f64,
    last_t: f64,
}

impl ProgramTrace {
    /// A trace for `model` that draws the body at the times `at` (seconds, any order).
    pub fn new(model: &RobotModel, at: &[f64]) -> ProgramTrace {
        let mut wanted = at.to_vec();
        wanted.sort_by(f64::total_cmp);
        ProgramTrace {
            robot: VirtualRobot::new(model),
            solver: JointSolver::new(model.kinematics()),
            path: Vec::new(),
            bodies: Vec::new(),
            t: Vec::new(),
            q: Vec::new(),
            wanted,
            next_wanted: 0,
            // Path points 0.5 mm apart and joint points 5 ms apart: plenty for a picture.
            path_spacing: 0.5,
            time_spacing: 0.005,
            last_t: 0.0,
        }
    }

    /// Adds the next sample.
    pub fn push(&mut self, sample: &CartesianSample) {
        self.last_t = sample.t;
        let [x, y, ..] = sample.pose;
        if self.path.last().is_none_or(|p| (p[0] - x).hypot(p[1] - y) >= self.path_spacing) {
            self.path.push([x, y]);
            if self.path.len() > MAX_POINTS {
                thin(&mut self.path, |_, _| false);
                self.path_spacing *= 2.0;
            }
        }
        let Ok(solution) = self.solver.reach(&sample.pose) else { return };
        if self.t.last().is_none_or(|&t| sample.t - t >= self.time_spacing) {
            self.t.push(sample.t);
            self.q.push(solution.joints.to_degrees());
            if self.t.len() > MAX_POINTS {
                thin(&mut self.t, |_, _| false);
                thin(&mut self.q, |_, _| false);
                self.time_spacing *= 2.0;
            }
        }
        while self.wanted.get(self.next_wanted).is_some_and(|&t| t <= sample.t + 1e-9) {
            let pose = solution.pose;
            let body = self.robot.body_at(solution.configuration, pose.z, pose.phi);
            self.bodies.push((self.wanted[self.next_wanted], body));
            self.next_wanted += 1;
        }
    }

    /// The wanted times after the program's end, which have no body.
    pub fn missed_times(&self) -> &[f64] {
        &self.wanted[self.next_wanted..]
    }

    /// Time of the last sample, seconds.
    pub fn duration(&self) -> f64 {
        self.last_t
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_long_program_keeps_a_bounded_trace_and_bodies_at_the_wanted_times() {
        let mut trace = ProgramTrace::new(&RobotModel::default(), &[2.0, 0.0, 500.0]);
        for step in 0..200_000 {
            let t = f64::from(step) * 0.001;
            let x = 100.0 * (t * 0.3).sin();
            trace.push(&CartesianSample {
                t,
                pose: [x, 400.0, 50.0, 0.0],
                line: 1,
                gripper: false,
            });
        }
        assert!(trace.path.len() <= MAX_POINTS && trace.t.len() <= MAX_POINTS);
        assert_eq!(trace.t.len(), trace.q.len());
        let times: Vec<f64> = trace.bodies.iter().map(|(t, _)| *t).collect();
        assert_eq!(times, [0.0, 2.0]);
        assert_eq!(trace.missed_times(), [500.0]);
    }
}
