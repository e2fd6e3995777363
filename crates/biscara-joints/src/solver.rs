//! The per-sample joint solver: the one place a Cartesian sample becomes joint values.

use biscara_interpolate::CartesianSample;
use biscara_kinematics::{
    BatchStatus, IkSolution, Joint, Joints, Kinematics, KinematicsError, Pose, PoseColumns,
    SolutionColumns, Theta3Unwrapper,
};
use biscara_motion::Position;

/// Why the robot cannot take one sample, located in the program and in time.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error(
    "{line}: at t = {t:.3} s the pose (x, y, z, c) = ({}) cannot be taken: {source}",
    format_pose(pose)
)]
pub struct SampleError {
    /// 1-based line of the motion the sample belongs to.
    pub line: usize,
    /// Time of the sample, s.
    pub t: f64,
    /// The pose `[x, y, z, c]`, mm and degrees.
    pub pose: Position,
    /// Why the robot cannot take it: unreachable, beyond a type-2 singularity, outside the joint
    /// limits or near a singularity.
    pub source: KinematicsError,
}

fn format_pose(pose: &[f64; 4]) -> String {
    format!("{:.3}, {:.3}, {:.3}, {:.3}", pose[0], pose[1], pose[2], pose[3])
}

/// A joint outside its position limits, in the robot file's units (degrees, mm).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LimitViolation {
    /// The joint.
    pub joint: Joint,
    /// Its value: degrees for θ, millimetres for d4.
    pub value: f64,
    /// Its limits `[min, max]`, same unit.
    pub limits: [f64; 2],
}

impl LimitViolation {
    /// How far outside the limits, same unit (positive).
    pub fn excess(&self) -> f64 {
        let [min, max] = self.limits;
        if self.value < min { min - self.value } else { self.value - max }
    }
}

/// Solves the samples of one path in order: IK in the robot's working mode, the assembly-mode
/// check (docs/kinematics.md), θ3 kept continuous ([`Theta3Unwrapper`]), then the joint limits and
/// the singularity margin on the unwrapped values.
///
/// Every consumer of samples uses it: `joints` ([`crate::JointTrajectory`]) stops at the first
/// error, `check` collects them all, the pictures skip what cannot be drawn. A failed sample does
/// not stop the solver: the next one is solved as if the failed one had not been there.
#[derive(Debug, Clone, Copy)]
pub struct JointSolver {
    model: Kinematics,
    theta3: Theta3Unwrapper,
}

impl JointSolver {
    /// A solver for a new path of the robot `model`.
    pub fn new(model: Kinematics) -> JointSolver {
        JointSolver { model, theta3: Theta3Unwrapper::new() }
    }

    /// The robot's kinematics.
    pub fn model(&self) -> &Kinematics {
        &self.model
    }

    /// The configuration the robot takes at `pose` (`[x, y, z, c]`, mm and degrees): IK in the
    /// working mode, refused beyond a type-2 singularity, θ3 continuous with the previous
    /// solution. Limits and the singularity margin are not checked: see
    /// [`JointSolver::limit_violations`] and [`Kinematics::check_singularity`].
    #[inline(always)]
    pub fn reach(&mut self, pose: &Position) -> Result<IkSolution, KinematicsError> {
        let [x, y, z, c] = *pose;
        let mut solution = self.model.inverse(&Pose::from_degrees(x, y, z, c))?;
        self.model.check_assembly(&solution)?;
        self.theta3.apply(&mut solution);
        Ok(solution)
    }

    /// The sample solved with every check a running robot needs ([`JointSolver::reach`], the
    /// joint limits, the singularity margin), or the first reason it cannot be taken, located.
    #[inline(always)]
    pub fn solve(&mut self, sample: &CartesianSample) -> Result<IkSolution, SampleError> {
        let fail =
            |source| SampleError { line: sample.line, t: sample.t, pose: sample.pose, source };
        let solution = self.reach(&sample.pose).map_err(fail)?;
        self.model.check_limits(&solution.joints).map_err(fail)?;
        self.model.check_singularity(&solution.configuration).map_err(fail)?;
        Ok(solution)
    }

    /// Solves `samples` ahead by batch IK ([`Kinematics::inverse_columns`]) into `batch`, for
    /// [`JointSolver::solve_prepared`] to take one at a time, in order. The solver is not
    /// changed.
    pub fn prepare(&self, samples: &[CartesianSample], batch: &mut PreparedSamples) {
        batch.resize(samples.len());
        for (k, sample) in samples.iter().enumerate() {
            let [x, y, z, c] = sample.pose;
            let pose = Pose::from_degrees(x, y, z, c);
            (batch.x[k], batch.y[k], batch.z[k], batch.phi[k]) = (pose.x, pose.y, pose.z, pose.phi);
        }
        self.model.inverse_columns(
            PoseColumns { x: &batch.x, y: &batch.y, z: &batch.z, phi: &batch.phi },
            SolutionColumns::new(&mut batch.solved, &mut batch.status),
        );
    }

    /// [`JointSolver::solve`] of `sample`, the sample `k` of the last [`JointSolver::prepare`]
    /// into `batch`, the samples before it taken in order: the same joints, bit for bit, or the
    /// same error. A pose the batch found clean needs only θ3 made continuous and the limits
    /// tested on it; any other is solved again by [`JointSolver::solve`], which gives the
    /// error (or, when only the batch's θ3 was outside its limits, the joints).
    #[inline(always)]
    pub fn solve_prepared(
        &mut self,
        sample: &CartesianSample,
        batch: &PreparedSamples,
        k: usize,
    ) -> Result<Joints, SampleError> {
        if batch.status[k] == BatchStatus::Ok {
            let [theta1, theta2, theta3, d4, rotation] = batch.solved.each_ref().map(|q| q[k]);
            let mut unwrapper = self.theta3;
            let theta3 = unwrapper.theta3(batch.phi[k], rotation, theta3);
            // The batch found θ1, θ2 and d4 inside their limits (these values, the same
            // comparisons); θ3, made continuous, may have moved by a turn: only it is tested.
            let [min, max] = self.model.limits(Joint::Theta3);
            if min <= theta3 && theta3 <= max {
                self.theta3 = unwrapper;
                return Ok(Joints::new(theta1, theta2, theta3, d4));
            }
        }
        self.solve(sample).map(|solution| solution.joints)
    }

    /// Every joint of `joints` outside its limits, in the robot file's units.
    pub fn limit_violations(&self, joints: &Joints) -> impl Iterator<Item = LimitViolation> {
        let model = self.model;
        let joints = *joints;
        Joint::ALL.into_iter().filter_map(move |joint| {
            let value = joints.get(joint);
            let [min, max] = model.limits(joint);
            if (min..=max).contains(&value) {
                return None;
            }
            let user = |v: f64| if joint.is_revolute() { v.to_degrees() } else { v };
            Some(LimitViolation { joint, value: user(value), limits: [user(min), user(max)] })
        })
    }
}

/// Samples solved ahead by [`JointSolver::prepare`]: the poses and their batch solutions, as
/// columns. Reused from one batch to the next.
#[derive(Debug, Clone, Default)]
pub struct PreparedSamples {
    x: Vec<f64>,
    y: Vec<f64>,
    z: Vec<f64>,
    phi: Vec<f64>,
    /// θ1, θ2, θ3 (fitted as [`Kinematics::inverse`] does), d4 and the distal rotation.
    solved: [Vec<f64>; 5],
    status: Vec<BatchStatus>,
}

impl PreparedSamples {
    /// Room for `n` samples.
    fn resize(&mut self, n: usize) {
        for column in [&mut self.x, &mut self.y, &mut self.z, &mut self.phi] {
            column.resize(n, 0.0);
        }
        for column in &mut self.solved {
            column.resize(n, 0.0);
        }
        self.status.resize(n, BatchStatus::Ok);
    }
}

#[cfg(test)]
mod tests {
    use biscara_kinematics::Robot;

    use super::*;

    fn sample(t: f64, pose: [f64; 4]) -> CartesianSample {
        CartesianSample { t, pose, line: 7, gripper: false }
    }

    #[test]
    fn theta3_stays_continuous_across_a_failed_sample() {
        let mut solver = JointSolver::new(Kinematics::default());
        let first = solver.solve(&sample(0.0, [0.0, 400.0, 50.0, 170.0])).expect("reachable");
        let err = solver.solve(&sample(0.1, [0.0, 2000.0, 50.0, 175.0])).expect_err("too far");
        assert_eq!((err.line, err.t), (7, 0.1));
        assert!(matches!(err.source, KinematicsError::Unreachable { .. }));
        let next = solver.solve(&sample(0.2, [0.0, 400.0, 50.0, 190.0])).expect("reachable");
        let step = next.joints.theta3 - first.joints.theta3;
        assert!((step - 20f64.to_radians()).abs() < 1e-9, "θ3 jumped by {step} rad");
    }

    #[test]
    fn limit_violations_name_every_joint_outside_in_user_units() {
        let solver = JointSolver::new(Kinematics::new(&Robot::default()).expect("robot"));
        let joints = Joints::new(140f64.to_radians(), 0.0, 0.0, 120.0);
        let found: Vec<_> = solver.limit_violations(&joints).collect();
        assert_eq!(found.len(), 2);
        assert_eq!(found[0].joint, Joint::Theta1);
        assert!((found[0].excess() - 5.0).abs() < 1e-9);
        assert_eq!((found[1].joint, found[1].excess()), (Joint::D4, 20.0));
    }
}
