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
    /// Solved samples in a ring, solved and differenced in place: each sample is copied once,
    /// when it is emitted (moving them through `Option`s cost 9 % of `joints` in `memcpy`).
    ring: [JointSample; 3],
    /// Index in `ring` of the oldest sample not yet emitted.
    head: usize,
    /// Samples solved and not yet emitted (0, 1 or 2 between calls).
    held: usize,
    emitted_any: bool,
    finished: bool,
}

const EMPTY_SAMPLE: JointSample = JointSample {
    t: 0.0,
    line: 0,
    pose: [0.0; 4],
    joints: Joints::new(0.0, 0.0, 0.0, 0.0),
    velocity: [0.0; 4],
    acceleration: [0.0; 4],
    gripper: false,
};

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
            ring: [EMPTY_SAMPLE; 3],
            head: 0,
            held: 0,
            emitted_any: false,
            finished: false,
        }
    }

    /// Solves `sample` into `slot`.
    fn solve(
        model: &Kinematics,
        theta3: &mut Theta3Unwrapper,
        sample: &CartesianSample,
        slot: &mut JointSample,
    ) -> Result<(), JointsError<E>> {
        let [x, y, z, c] = sample.pose;
        let pose = Pose::from_degrees(x, y, z, c);
        let fail = |source| JointsError::Pose {
            line: sample.line,
            t: sample.t,
            pose: sample.pose,
            source,
        };
        let mut solution = model.inverse(&pose).map_err(fail)?;
        model.check_assembly(&solution).map_err(fail)?;
        theta3.apply(&mut solution);
        model.check_limits(&solution.joints).map_err(fail)?;
        model.check_singularity(&solution.configuration).map_err(fail)?;
        slot.t = sample.t;
        slot.line = sample.line;
        slot.pose = sample.pose;
        slot.joints = solution.joints;
        slot.velocity = [0.0; 4];
        slot.acceleration = [0.0; 4];
        slot.gripper = sample.gripper;
        Ok(())
    }

    /// Ring index `offset` places after the head.
    fn at(&self, offset: usize) -> usize {
        (self.head + offset) % 3
    }

    /// With three samples held, completes the middle one's differences (and the first sample's,
    /// at the start) and emits the oldest: returns its ring index.
    fn emit_oldest_of_three(&mut self) -> usize {
        let (previous, current, next) = (self.at(0), self.at(1), self.at(2));
        let back = slope(&self.ring[previous], &self.ring[current]);
        let ahead = slope(&self.ring[current], &self.ring[next]);
        let span = self.ring[next].t - self.ring[previous].t;
        let (q_before, q_after) =
            (self.ring[previous].joints.to_array(), self.ring[next].joints.to_array());
        let middle = &mut self.ring[current];
        for j in 0..4 {
            middle.velocity[j] = (q_after[j] - q_before[j]) / span;
            middle.acceleration[j] = 2.0 * (ahead[j] - back[j]) / span;
        }
        let acceleration = middle.acceleration;
        if !self.emitted_any {
            // The first sample: forward difference, and the acceleration of its neighbour.
            self.ring[previous].velocity = back;
            self.ring[previous].acceleration = acceleration;
            self.emitted_any = true;
        }
        self.head = current;
        self.held -= 1;
        previous
    }

    /// Emits what is left once the input has ended: the ring index of the next sample.
    fn flush(&mut self) -> Option<usize> {
        match self.held {
            0 => None,
            1 => {
                self.held = 0;
                Some(self.head)
            }
            _ => {
                let (previous, last) = (self.at(0), self.at(1));
                let velocity = slope(&self.ring[previous], &self.ring[last]);
                if !self.emitted_any {
                    // Only two samples in all.
                    self.ring[previous].velocity = velocity;
                    self.emitted_any = true;
                }
                self.ring[last].velocity = velocity;
                self.ring[last].acceleration = self.ring[previous].acceleration;
                self.head = last;
                self.held = 1;
                Some(previous)
            }
        }
    }
}

/// First differences `(b − a) / (t_b − t_a)` per joint.
fn slope(a: &JointSample, b: &JointSample) -> [f64; 4] {
    let (qa, qb) = (a.joints.to_array(), b.joints.to_array());
    let dt = b.t - a.t;
    [0, 1, 2, 3].map(|j| (qb[j] - qa[j]) / dt)
}

impl<I, E> JointTrajectory<I>
where
    I: Iterator<Item = Result<CartesianSample, E>>,
{
    /// The next sample, borrowed: [`Iterator::next`] without copying the sample out. For the
    /// CLI's writer: returning the 152-byte sample inside an `Option<Result<…>>`, then moving it
    /// out, cost 5 % of `joints` on the engraving program (0.563 → 0.524 s).
    #[inline]
    pub fn next_sample(&mut self) -> Option<Result<&JointSample, JointsError<E>>> {
        match self.advance()? {
            Ok(index) => Some(Ok(&self.ring[index])),
            Err(err) => Some(Err(err)),
        }
    }

    /// Solves samples until one can be emitted; returns its ring index.
    fn advance(&mut self) -> Option<Result<usize, JointsError<E>>> {
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
                Some(Ok(sample)) => {
                    let slot = self.at(self.held);
                    match Self::solve(&self.model, &mut self.theta3, &sample, &mut self.ring[slot])
                    {
                        Ok(()) => {
                            self.held += 1;
                            if self.held == 3 {
                                return Some(Ok(self.emit_oldest_of_three()));
                            }
                            continue;
                        }
                        Err(err) => err,
                    }
                }
            };
            self.finished = true;
            self.held = 0;
            return Some(Err(failure));
        }
    }
}

impl<I, E> Iterator for JointTrajectory<I>
where
    I: Iterator<Item = Result<CartesianSample, E>>,
{
    type Item = Result<JointSample, JointsError<E>>;

    fn next(&mut self) -> Option<Self::Item> {
        Some(self.next_sample()?.copied())
    }
}
