//! Joint samples from Cartesian samples: IK of every sample, θ3 continuous, derivatives.

use biscara_interpolate::CartesianSample;
use biscara_kinematics::{Joints, Kinematics, KinematicsError, Pose, Theta3Unwrapper};

/// One row of the joint trajectory: radians and millimetres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointSample {
    /// Time, s.
    pub t: f64,
    /// 1-based line of the motion (G-code, inter-file or path CSV) this sample belongs to.
    pub line: usize,
    /// The Cartesian pose it was solved from, `[x, y, z, c]` (mm, degrees).
    pub pose: [f64; 4],
    /// Joint positions.
    pub joints: Joints,
    /// Joint velocities (rad/s, mm/s), by finite differences of the positions.
    pub velocity: [f64; 4],
    /// Joint accelerations (rad/s², mm/s²), by finite differences of the positions.
    pub acceleration: [f64; 4],
    /// Whether the gripper is closed.
    pub gripper: bool,
}

/// A joint-trajectory failure.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum JointsError<E> {
    /// Occurs when the sample source fails (G-code, interpolation or CSV errors).
    #[error(transparent)]
    Input(E),
    /// Occurs when a sample cannot be taken by the robot: unreachable, beyond a type-2
    /// singularity, outside the joint limits or near a singularity.
    #[error("line {line}: at t = {t:.3} s, pose ({}): {source}", format_pose(pose))]
    Pose {
        /// 1-based line of the motion.
        line: usize,
        /// Time of the sample, s.
        t: f64,
        /// The pose `[x, y, z, c]`, mm and degrees.
        pose: [f64; 4],
        /// Why the robot cannot take it.
        source: KinematicsError,
    },
}

fn format_pose(pose: &[f64; 4]) -> String {
    format!("{:.3}, {:.3}, {:.3}, {:.3}", pose[0], pose[1], pose[2], pose[3])
}

/// Solves every Cartesian sample in the robot's working and assembly mode, keeps θ3 continuous,
/// and attaches velocities and accelerations from finite differences of the positions (central
/// in the interior; at the first and last sample the one-sided difference for velocity and the
/// neighbouring sample's acceleration). Fails at the first sample the robot cannot take.
///
/// Holds three samples at a time: memory does not grow with the trajectory.
pub struct JointTrajectory<I> {
    samples: I,
    model: Kinematics,
    theta3: Theta3Unwrapper,
    /// The sample before `current`, solved, waiting for `current`'s successor to be emitted.
    previous: Option<JointSample>,
    /// The newest solved sample.
    current: Option<JointSample>,
    emitted_any: bool,
    finished: bool,
}

impl<I, E> JointTrajectory<I>
where
    I: Iterator<Item = Result<CartesianSample, E>>,
{
    /// A trajectory over `samples` for the robot `model`.
    pub fn new(samples: I, model: Kinematics) -> Self {
        JointTrajectory {
            samples,
            model,
            theta3: Theta3Unwrapper::new(),
            previous: None,
            current: None,
            emitted_any: false,
            finished: false,
        }
    }

    fn solve(&mut self, sample: &CartesianSample) -> Result<JointSample, JointsError<E>> {
        let [x, y, z, c] = sample.pose;
        let pose = Pose::from_degrees(x, y, z, c);
        let fail = |source| JointsError::Pose {
            line: sample.line,
            t: sample.t,
            pose: sample.pose,
            source,
        };
        let mut solution = self.model.inverse(&pose).map_err(fail)?;
        self.model.check_assembly(&solution).map_err(fail)?;
        self.theta3.apply(&mut solution);
        self.model.check_limits(&solution.joints).map_err(fail)?;
        self.model.check_singularity(&solution.configuration).map_err(fail)?;
        Ok(JointSample {
            t: sample.t,
            line: sample.line,
            pose: sample.pose,
            joints: solution.joints,
            velocity: [0.0; 4],
            acceleration: [0.0; 4],
            gripper: sample.gripper,
        })
    }

    /// Emits what is left once the input has ended.
    fn flush(&mut self) -> Option<JointSample> {
        let Some(mut previous) = self.previous.take() else {
            return self.current.take();
        };
        let mut last = self.current.take()?;
        last.velocity = slope(&previous, &last);
        if !self.emitted_any {
            // Only two samples in all.
            previous.velocity = last.velocity;
        }
        last.acceleration = previous.acceleration;
        self.current = Some(last);
        self.emitted_any = true;
        Some(previous)
    }

    /// Takes in the next solved sample; returns a sample whose differences are now complete.
    fn push(&mut self, next: JointSample) -> Option<JointSample> {
        let mut current = self.current.replace(next)?;
        let Some(mut previous) = self.previous.take() else {
            self.previous = Some(current);
            return None;
        };
        // `current` has both neighbours now: central differences.
        let (back, ahead) = (slope(&previous, &current), slope(&current, &next));
        let span = next.t - previous.t;
        let (q_before, q_after) = (previous.joints.to_array(), next.joints.to_array());
        for j in 0..4 {
            current.velocity[j] = (q_after[j] - q_before[j]) / span;
            current.acceleration[j] = 2.0 * (ahead[j] - back[j]) / span;
        }
        if !self.emitted_any {
            // The first sample: forward difference, and the acceleration of its neighbour.
            previous.velocity = back;
            previous.acceleration = current.acceleration;
            self.emitted_any = true;
        }
        self.previous = Some(current);
        Some(previous)
    }
}

/// First differences `(b − a) / (t_b − t_a)` per joint.
fn slope(a: &JointSample, b: &JointSample) -> [f64; 4] {
    let (qa, qb) = (a.joints.to_array(), b.joints.to_array());
    let dt = b.t - a.t;
    [0, 1, 2, 3].map(|j| (qb[j] - qa[j]) / dt)
}

impl<I, E> Iterator for JointTrajectory<I>
where
    I: Iterator<Item = Result<CartesianSample, E>>,
{
    type Item = Result<JointSample, JointsError<E>>;

    fn next(&mut self) -> Option<Self::Item> {
        loop {
            if self.finished {
                return self.flush().map(Ok);
            }
            let failure = match self.samples.next() {
                None => {
                    self.finished = true;
                    continue;
                }
                Some(Err(err)) => JointsError::Input(err),
                Some(Ok(sample)) => match self.solve(&sample) {
                    Ok(solved) => match self.push(solved) {
                        Some(ready) => return Some(Ok(ready)),
                        None => continue,
                    },
                    Err(err) => err,
                },
            };
            self.finished = true;
            self.previous = None;
            self.current = None;
            return Some(Err(failure));
        }
    }
}
