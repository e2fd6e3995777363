//! The interpolator: an iterator of motions in, an iterator of Cartesian samples out.

use biscara_motion::{Motion, MotionKind, Position};

use crate::{Profile, Segment, Timing};

/// Cartesian motion limits (SPEC §1.3 `motion`), in mm, degrees and seconds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CartesianLimits {
    /// Speed of G0 moves along the XYZ path, mm/s.
    pub rapid_velocity: f64,
    /// Speed of C during G0 moves, and the cap of C's speed in every move, degrees/s.
    pub rapid_rotation: f64,
    /// Path acceleration of the trapezoid profile, mm/s².
    pub acceleration: f64,
    /// Acceleration of C, degrees/s².
    pub rotation_acceleration: f64,
}

/// Settings of one interpolation run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InterpolationConfig {
    /// Time step, s (> 0).
    pub dt: f64,
    /// The velocity profile of every motion.
    pub profile: Profile,
    /// The pose before the first motion (the robot's home pose), `[x, y, z, c]`.
    pub start: Position,
    /// Cartesian limits.
    pub limits: CartesianLimits,
    /// Seconds each pick and place holds the pose (0: they take no time).
    pub grip_time: f64,
}

/// One sample of the Cartesian path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CartesianSample {
    /// Time since the start, s (a whole number of steps).
    pub t: f64,
    /// The pose `[x, y, z, c]`, mm and degrees.
    pub pose: Position,
    /// 1-based line of the motion this sample belongs to (0 for the start sample).
    pub line: usize,
    /// Whether the gripper is closed (from a pick to the next place).
    pub gripper: bool,
}

/// A bound on how fast a move may be traversed, from outside the Cartesian world (the joint
/// velocity limits, computed by the joint-trajectory stage).
pub trait SpeedLimit {
    /// The largest path-parameter rate ds/dt (1/s) allowed on `segment`, with what limits it;
    /// `None` when nothing does.
    fn max_rate(&mut self, segment: &Segment) -> Option<RateLimit>;
}

/// A rate bound and its cause.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RateLimit {
    /// Largest ds/dt, 1/s.
    pub rate: f64,
    /// What sets it (a joint name such as `theta1`).
    pub cause: &'static str,
}

/// No bound beyond the Cartesian limits.
#[derive(Debug, Clone, Copy, Default)]
pub struct NoSpeedLimit;

impl SpeedLimit for NoSpeedLimit {
    fn max_rate(&mut self, _segment: &Segment) -> Option<RateLimit> {
        None
    }
}

/// A motion that was slowed below its programmed speed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SlowDown {
    /// 1-based line of the motion.
    pub line: usize,
    /// What slowed it: `C rotation` or a joint name.
    pub cause: &'static str,
    /// The speed it runs at as a fraction of the programmed one (< 1).
    pub factor: f64,
}

/// An interpolation failure.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum InterpolateError<E> {
    /// Occurs when the motion source fails (a G-code or inter-file error).
    #[error(transparent)]
    Input(E),
    /// Occurs when a motion cannot be timed: a feed that is not positive, a non-finite position,
    /// or a duration too long to count in steps.
    #[error("{line}: {message}")]
    Motion {
        /// 1-based line of the motion.
        line: usize,
        /// What is wrong.
        message: String,
    },
}

/// Below this, a length (mm) or rotation (degrees) counts as no movement.
const NO_MOVEMENT: f64 = 1e-12;

/// Turns motions into Cartesian samples at a fixed time step (SPEC §6).
///
/// The first sample is the start pose at t = 0; every programmed end point is hit exactly by a
/// sample. Memory does not depend on the program length. `on_slow` hears of every motion that
/// runs slower than programmed.
pub struct Interpolator<I, L, F> {
    motions: I,
    limit: L,
    on_slow: F,
    config: InterpolationConfig,
    pose: [f64; 4],
    gripper: bool,
    step: u64,
    active: Option<Active>,
    started: bool,
    finished: bool,
}

#[derive(Debug, Clone, Copy)]
enum Active {
    Move { segment: Segment, timing: Timing, done: u64, line: usize },
    Hold { remaining: u64, line: usize },
}

impl<I, E, L, F> Interpolator<I, L, F>
where
    I: Iterator<Item = Result<Motion, E>>,
    L: SpeedLimit,
    F: FnMut(&SlowDown),
{
    /// An interpolator over `motions`, bounded by `limit`, reporting slowed motions to `on_slow`.
    pub fn new(motions: I, config: InterpolationConfig, limit: L, on_slow: F) -> Self {
        Interpolator {
            motions,
            limit,
            on_slow,
            config,
            pose: config.start,
            gripper: false,
            step: 0,
            active: None,
            started: false,
            finished: false,
        }
    }

    fn sample(&self, pose: [f64; 4], line: usize) -> CartesianSample {
        CartesianSample { t: self.step as f64 * self.config.dt, pose, line, gripper: self.gripper }
    }

    /// Starts the next motion.
    #[inline(never)]
    fn begin(&mut self, motion: Motion) -> Result<(), InterpolateError<E>> {
        let line = motion.line;
        let fail = |message: String| InterpolateError::Motion { line, message };
        let hold_steps = |seconds: f64| -> Result<u64, InterpolateError<E>> {
            if seconds <= 0.0 {
                return Ok(0);
            }
            let steps = seconds / self.config.dt;
            if steps.is_nan() || steps >= 1e15 {
                return Err(fail(format!("a hold of {seconds} s is too long")));
            }
            Ok(crate::profile::steps_for(seconds, self.config.dt))
        };
        match motion.kind {
            MotionKind::Rapid { .. } | MotionKind::Linear { .. } | MotionKind::Arc { .. } => {
                let segment = self.segment(&motion.kind);
                if segment.end().iter().any(|value| !value.is_finite()) {
                    return Err(fail("the end point is not a finite number".to_owned()));
                }
                if let Some(timing) = self.plan(line, &motion.kind, &segment)? {
                    self.active = Some(Active::Move { segment, timing, done: 0, line });
                }
                self.pose = segment.end();
            }
            MotionKind::Dwell { seconds } => {
                let remaining = hold_steps(seconds)?;
                self.active = Some(Active::Hold { remaining, line });
            }
            MotionKind::Pick | MotionKind::Place => {
                self.gripper = matches!(motion.kind, MotionKind::Pick);
                let remaining = hold_steps(self.config.grip_time)?;
                self.active = Some(Active::Hold { remaining, line });
            }
            MotionKind::GripperOff => self.gripper = false,
            MotionKind::Pause => {}
            MotionKind::End => self.finished = true,
            // Tool events and recorded codes take no time and do not move the robot.
            _ => {}
        }
        Ok(())
    }

    fn segment(&self, kind: &MotionKind) -> Segment {
        match *kind {
            MotionKind::Arc { end, center, plane, clockwise, turns, .. } => {
                Segment::arc(self.pose, end, center, plane, clockwise, turns)
            }
            _ => Segment::line(self.pose, kind.end().unwrap_or(self.pose)),
        }
    }

    /// The timing of a move, or `None` when it does not move.
    fn plan(
        &mut self,
        line: usize,
        kind: &MotionKind,
        segment: &Segment,
    ) -> Result<Option<Timing>, InterpolateError<E>> {
        let length = segment.length();
        let rotation = segment.rotation().abs();
        if length < NO_MOVEMENT && rotation < NO_MOVEMENT {
            return Ok(None);
        }
        let limits = self.config.limits;
        // Bounds on ds/dt and d²s/dt²: a zero length or rotation divides to infinity and so
        // bounds nothing.
        let acceleration =
            (limits.acceleration / length).min(limits.rotation_acceleration / rotation);
        let (programmed, is_feed) = match *kind {
            MotionKind::Linear { feed, .. } | MotionKind::Arc { feed, .. } => {
                let per_second = feed.mm_per_min / 60.0;
                if !(per_second.is_finite() && per_second > 0.0) {
                    return Err(InterpolateError::Motion {
                        line,
                        message: format!("the feed {} mm/min is not positive", feed.mm_per_min),
                    });
                }
                // LinuxCNC: a move with no XYZ length runs its feed in degrees/min of C.
                let along = if length >= NO_MOVEMENT { length } else { rotation };
                (per_second / along, true)
            }
            _ => ((limits.rapid_velocity / length).min(limits.rapid_rotation / rotation), false),
        };
        let mut rate = programmed;
        if self.config.profile != Profile::Constant {
            let mut cause = None;
            if is_feed {
                let cap = limits.rapid_rotation / rotation;
                if cap < rate {
                    rate = cap;
                    cause = Some("C rotation");
                }
            }
            if let Some(limit) = self.limit.max_rate(segment)
                && limit.rate < rate
            {
                rate = limit.rate;
                cause = Some(limit.cause);
            }
            if let Some(cause) = cause {
                (self.on_slow)(&SlowDown { line, cause, factor: rate / programmed });
            }
        }
        let timing = Timing::new(self.config.profile, rate, acceleration, self.config.dt);
        if timing.duration() / self.config.dt > 1e15 || !timing.duration().is_finite() {
            return Err(InterpolateError::Motion {
                line,
                message: "the move is too slow to count in time steps".to_owned(),
            });
        }
        Ok(Some(timing))
    }
}

impl<I, E, L, F> Iterator for Interpolator<I, L, F>
where
    I: Iterator<Item = Result<Motion, E>>,
    L: SpeedLimit,
    F: FnMut(&SlowDown),
{
    type Item = Result<CartesianSample, InterpolateError<E>>;

    #[inline]
    fn next(&mut self) -> Option<Self::Item> {
        if !self.started {
            self.started = true;
            return Some(Ok(self.sample(self.pose, 0)));
        }
        loop {
            match &mut self.active {
                Some(Active::Move { segment, timing, done, line }) if *done < timing.steps() => {
                    *done += 1;
                    let pose = if *done == timing.steps() {
                        segment.end()
                    } else {
                        segment.point(timing.s_at(*done as f64 * self.config.dt))
                    };
                    let line = *line;
                    self.step += 1;
                    return Some(Ok(self.sample(pose, line)));
                }
                Some(Active::Hold { remaining, line }) if *remaining > 0 => {
                    *remaining -= 1;
                    let line = *line;
                    self.step += 1;
                    return Some(Ok(self.sample(self.pose, line)));
                }
                _ => self.active = None,
            }
            if self.finished {
                return None;
            }
            match self.motions.next() {
                None => {
                    self.finished = true;
                    return None;
                }
                Some(Err(err)) => {
                    self.finished = true;
                    return Some(Err(InterpolateError::Input(err)));
                }
                Some(Ok(motion)) => {
                    if let Err(err) = self.begin(motion) {
                        self.finished = true;
                        return Some(Err(err));
                    }
                }
            }
        }
    }
}
