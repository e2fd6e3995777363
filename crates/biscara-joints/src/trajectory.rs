//! Joint samples from Cartesian samples: IK of every sample, θ3 continuous, derivatives.

use biscara_interpolate::CartesianSample;
use biscara_kinematics::{Joints, Kinematics};
use biscara_motion::Position;

use crate::differences::{central_differences, end_derivatives};
use crate::solver::{JointSolver, PreparedSamples, SampleError};

/// How many Cartesian samples [`JointTrajectory`] reads ahead and solves together by batch IK
/// ([`JointSolver::prepare`]): `joints` on the 20,000-line engraving program counts 0.6 % fewer
/// instructions than with 64.
pub const BATCH_SAMPLES: usize = 256;

/// One row of the joint trajectory: radians and millimetres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointSample {
    /// Time, s.
    pub t: f64,
    /// 1-based line of the motion (G-code, inter-file or path CSV) this sample belongs to.
    pub line: usize,
    /// The Cartesian pose it was solved from, `[x, y, z, c]` (mm, degrees).
    pub pose: Position,
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
    #[error(transparent)]
    Pose(SampleError),
}

/// Solves every Cartesian sample in the robot's working and assembly mode, keeps θ3 continuous,
/// and attaches velocities and accelerations from finite differences of the positions (central
/// in the interior; at the first and last sample the one-sided difference for velocity and the
/// neighbouring sample's acceleration). Fails at the first sample the robot cannot take.
///
/// Reads the samples [`BATCH_SAMPLES`] at a time and solves them together by batch IK, then
/// takes them in order as one at a time: the same rows, bit for bit, and the same first error
/// (the input's error, too, comes after the samples before it). Holds that batch and three
/// solved samples: memory does not grow with the trajectory.
pub struct JointTrajectory<I, E> {
    samples: I,
    solver: JointSolver,
    /// The samples read ahead, solved into `prepared`; `next` is the next one to take.
    batch: Vec<CartesianSample>,
    prepared: PreparedSamples,
    next: usize,
    /// How the input stopped after the batch, when it has: `Some(None)` at its end.
    stop: Option<Option<E>>,
    /// Solved samples in a ring, solved and differenced in place: each sample is copied once,
    /// when it is emitted (moving them through `Option`s cost 9 % of `joints` in `memcpy`).
    ring: [JointSample; 3],
    /// Index in `ring` of the oldest sample not yet emitted.
    head: usize,
    /// Samples solved and not yet emitted (0, 1 or 2 between calls).
    held: usize,
    emitted_any: bool,
    finished: bool,
    /// Whether velocities and accelerations are computed ([`JointTrajectory::without_derivatives`]).
    derivatives: bool,
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

impl<I, E> JointTrajectory<I, E>
where
    I: Iterator<Item = Result<CartesianSample, E>>,
{
    /// A trajectory over `samples` for the robot `model`.
    pub fn new(samples: I, model: Kinematics) -> Self {
        JointTrajectory {
            samples,
            solver: JointSolver::new(model),
            batch: Vec::with_capacity(BATCH_SAMPLES),
            prepared: PreparedSamples::default(),
            next: 0,
            stop: None,
            ring: [EMPTY_SAMPLE; 3],
            head: 0,
            held: 0,
            emitted_any: false,
            finished: false,
            derivatives: true,
        }
    }

    /// The same trajectory with `velocity` and `acceleration` left at zero: for a reader that does
    /// not use them (a joint CSV without derivative columns), the finite differences are not
    /// computed (`joints` on the 20,000-line engraving program: 642.3 → 630.2 M instructions).
    pub fn without_derivatives(mut self) -> Self {
        self.derivatives = false;
        self
    }

    /// Solves the sample `k` of the batch into `slot`.
    #[inline(always)]
    fn solve(
        solver: &mut JointSolver,
        sample: &CartesianSample,
        prepared: &PreparedSamples,
        k: usize,
        slot: &mut JointSample,
    ) -> Result<(), JointsError<E>> {
        let joints = solver.solve_prepared(sample, prepared, k).map_err(JointsError::Pose)?;
        slot.t = sample.t;
        slot.line = sample.line;
        slot.pose = sample.pose;
        slot.joints = joints;
        slot.velocity = [0.0; 4];
        slot.acceleration = [0.0; 4];
        slot.gripper = sample.gripper;
        Ok(())
    }

    /// Reads the next batch of samples and solves them, up to the input's end or error (kept
    /// in `stop` for when the batch has been taken).
    fn read_batch(&mut self) {
        self.batch.clear();
        self.next = 0;
        while self.batch.len() < BATCH_SAMPLES {
            match self.samples.next() {
                Some(Ok(sample)) => self.batch.push(sample),
                Some(Err(err)) => {
                    self.stop = Some(Some(err));
                    break;
                }
                None => {
                    self.stop = Some(None);
                    break;
                }
            }
        }
        self.solver.prepare(&self.batch, &mut self.prepared);
    }

    /// Ring index `offset` (at most 2) places after the head: a comparison, not a `% 3` (a
    /// multiplication and a shift, four times a sample).
    #[inline(always)]
    fn at(&self, offset: usize) -> usize {
        let index = self.head + offset;
        if index >= 3 { index - 3 } else { index }
    }

    /// With three samples held, completes the middle one's differences (and the first sample's,
    /// at the start) and emits the oldest: returns its ring index.
    fn emit_oldest_of_three(&mut self) -> usize {
        let (previous, current, next) = (self.at(0), self.at(1), self.at(2));
        if !self.derivatives {
            self.head = current;
            self.held -= 1;
            return previous;
        }
        let q = [previous, current, next].map(|index| self.ring[index].joints.to_array());
        let t = [previous, current, next].map(|index| self.ring[index].t);
        let (velocity, acceleration) =
            central_differences((t[0], &q[0]), (t[1], &q[1]), (t[2], &q[2]));
        let middle = &mut self.ring[current];
        middle.velocity = velocity;
        middle.acceleration = acceleration;
        if !self.emitted_any {
            // The first sample: forward difference, and the acceleration of its neighbour.
            let first = end_derivatives((t[0], &q[0]), (t[1], &q[1]), acceleration);
            (self.ring[previous].velocity, self.ring[previous].acceleration) = first;
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
            _ if !self.derivatives => {
                let (previous, last) = (self.at(0), self.at(1));
                self.head = last;
                self.held = 1;
                Some(previous)
            }
            _ => {
                let (previous, last) = (self.at(0), self.at(1));
                let (a, b) = (&self.ring[previous], &self.ring[last]);
                let (qa, qb) = (a.joints.to_array(), b.joints.to_array());
                let (velocity, acceleration) =
                    end_derivatives((b.t, &qb), (a.t, &qa), a.acceleration);
                if !self.emitted_any {
                    // Only two samples in all.
                    self.ring[previous].velocity = velocity;
                    self.emitted_any = true;
                }
                self.ring[last].velocity = velocity;
                self.ring[last].acceleration = acceleration;
                self.head = last;
                self.held = 1;
                Some(previous)
            }
        }
    }
}

impl<I, E> JointTrajectory<I, E>
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
            if self.next == self.batch.len() {
                match self.stop.take() {
                    None => {
                        self.read_batch();
                        continue;
                    }
                    Some(None) => {
                        self.finished = true;
                        continue;
                    }
                    Some(Some(err)) => {
                        self.finished = true;
                        self.held = 0;
                        return Some(Err(JointsError::Input(err)));
                    }
                }
            }
            let k = self.next;
            self.next += 1;
            let slot = self.at(self.held);
            let sample = &self.batch[k];
            match Self::solve(&mut self.solver, sample, &self.prepared, k, &mut self.ring[slot]) {
                Ok(()) => {
                    self.held += 1;
                    if self.held == 3 {
                        return Some(Ok(self.emit_oldest_of_three()));
                    }
                }
                Err(err) => {
                    self.finished = true;
                    self.held = 0;
                    return Some(Err(err));
                }
            }
        }
    }
}

impl<I, E> Iterator for JointTrajectory<I, E>
where
    I: Iterator<Item = Result<CartesianSample, E>>,
{
    type Item = Result<JointSample, JointsError<E>>;

    fn next(&mut self) -> Option<Self::Item> {
        Some(self.next_sample()?.copied())
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;

    /// A row: t, line and the bits of the joints.
    type Row = (f64, usize, [u64; 4]);
    /// The rows of a trajectory and the error it ends with.
    type Outcome = (Vec<Row>, Option<String>);

    /// The trajectory one sample at a time, as before batches: each sample by
    /// [`JointSolver::solve`], stopping at the first error, the input's included.
    fn one_at_a_time(samples: &[Result<CartesianSample, String>], model: Kinematics) -> Outcome {
        let mut solver = JointSolver::new(model);
        let mut rows = Vec::new();
        for sample in samples {
            let sample = match sample {
                Ok(sample) => sample,
                Err(err) => return (rows, Some(format!("input {err}"))),
            };
            match solver.solve(sample) {
                Ok(solution) => {
                    let bits = solution.joints.to_array().map(f64::to_bits);
                    rows.push((sample.t, sample.line, bits));
                }
                Err(err) => return (rows, Some(err.to_string())),
            }
        }
        (rows, None)
    }

    fn batched(
        samples: &[Result<CartesianSample, String>],
        model: Kinematics,
        derivatives: bool,
    ) -> Outcome {
        let trajectory = JointTrajectory::new(samples.iter().cloned(), model);
        let mut trajectory =
            if derivatives { trajectory } else { trajectory.without_derivatives() };
        let mut rows = Vec::new();
        while let Some(row) = trajectory.next_sample() {
            match row {
                Ok(row) => {
                    rows.push((row.t, row.line, row.joints.to_array().map(f64::to_bits)));
                }
                Err(JointsError::Input(err)) => return (rows, Some(format!("input {err}"))),
                Err(JointsError::Pose(err)) => return (rows, Some(err.to_string())),
            }
        }
        (rows, None)
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        /// Batches change nothing: the same rows, bit for bit, and the same first error, for
        /// paths that leave the workspace, turn the tool by whole turns and have input errors,
        /// anywhere in a batch or across batches.
        #[test]
        fn batches_give_the_rows_and_the_error_of_one_sample_at_a_time(
            steps in prop::collection::vec(
                (-8.0..8.0f64, -8.0..8.0f64, -5.0..5.0f64, -40.0..40.0f64, 0u16..1500), 1..800),
            derivatives in any::<bool>(),
        ) {
            let mut pose = [0.0, 400.0, 50.0, 0.0];
            let samples: Vec<Result<CartesianSample, String>> = steps
                .iter()
                .enumerate()
                .map(|(k, &(dx, dy, dz, dc, event))| {
                    pose = [pose[0] + dx, pose[1] + dy, (pose[2] + dz).clamp(0.0, 100.0), pose[3] + dc];
                    let mut at = pose;
                    match event {
                        // Out of reach, or a bad input line, now and then.
                        0 => at[1] = 2000.0,
                        1 => return Err(format!("bad line {k}")),
                        2 => at[0] = f64::NAN,
                        _ => {}
                    }
                    Ok(CartesianSample { t: k as f64 * 1e-3, pose: at, line: k + 1, gripper: false })
                })
                .collect();
            let model = Kinematics::default();
            let (expected_rows, expected_error) = one_at_a_time(&samples, model);
            let (rows, error) = batched(&samples, model, derivatives);
            let failed = expected_error.is_some();
            prop_assert_eq!(error, expected_error);
            // At an error, the two samples held for the differences are dropped, as before.
            let solved = expected_rows.len();
            let emitted = if failed { solved.max(2) - 2 } else { solved };
            prop_assert_eq!(&rows[..], &expected_rows[..emitted]);
        }
    }
}
