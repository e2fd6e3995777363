//! The interpolator: an iterator of motions in, an iterator of Cartesian samples out.

use biscara_blend::{Blended, Blender, NaiveCam, Piece};
use biscara_motion::{Motion, MotionKind, Position};
use biscara_timing::{Constraint, Grid, PathConstraints, TimeOptimal, TimingError};

use crate::chain::{Chain, ChainBounds};
use crate::{Profile, Segment, Timing};

/// Cartesian motion limits (docs/kinematics.md `motion`), in mm, degrees and seconds.
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
/// limits, computed by the joint-trajectory stage).
///
/// The trapezoid profile asks for one rate per move ([`max_rate`](Self::max_rate)); the optimal
/// profile asks for the joints' limits ([`joint_bounds`](Self::joint_bounds)) and their
/// derivatives along the move ([`joint_derivatives`](Self::joint_derivatives)).
pub trait SpeedLimit {
    /// The largest path-parameter rate ds/dt (1/s) allowed on `segment`, with what limits it;
    /// `None` when nothing does.
    fn max_rate(&mut self, segment: &Segment) -> Option<RateLimit>;

    /// The joints whose velocity and acceleration the optimal profile keeps within bounds (at
    /// most [`MAX_JOINTS`]; the first `MAX_JOINTS` are used). None by default.
    fn joint_bounds(&self) -> &[JointBound] {
        &[]
    }

    /// Writes `dq/ds` into `first` and `d²q/ds²` into `second` for every joint of
    /// [`joint_bounds`](Self::joint_bounds), at path parameter `s` of `segment`; `false` where
    /// the robot cannot take the pose (no joint bound applies there: the joint-trajectory stage
    /// reports such poses). `false` by default.
    fn joint_derivatives(
        &mut self,
        segment: &Segment,
        s: f64,
        first: &mut [f64],
        second: &mut [f64],
    ) -> bool {
        let _ = (segment, s, first, second);
        false
    }

    /// Rows of further bounds at every grid point beyond the joints' velocity and acceleration
    /// (a robot's motor torques: [`torque_constraints`](Self::torque_constraints)). None by
    /// default.
    fn torque_rows(&self) -> usize {
        0
    }

    /// Fills `out` (`torque_rows()` long) with bounds `lo ≤ a · s̈ + b · ṡ² + c ≤ hi` at the
    /// point of the last [`joint_derivatives`](Self::joint_derivatives) call that returned
    /// `true`, from the joints' `first` and `second` derivatives along the path parameter the
    /// planner uses (those of `joint_derivatives`, rescaled to it); `false` where they cannot be
    /// computed (no bound applies there). `false` by default.
    fn torque_constraints(
        &mut self,
        first: &[f64],
        second: &[f64],
        out: &mut [Constraint],
    ) -> bool {
        let _ = (first, second, out);
        false
    }

    /// Whether the gripper holds its payload in the moves planned from now on (told at every
    /// pick, place and gripper release). Ignored by default.
    fn set_holding(&mut self, holding: bool) {
        let _ = holding;
    }
}

/// Most joints a [`SpeedLimit`] may bound for the optimal profile.
pub const MAX_JOINTS: usize = 8;

/// One joint's limits for the optimal profile, in the units of
/// [`SpeedLimit::joint_derivatives`] (radians or mm, seconds), margins included.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointBound {
    /// Name, for reports (`theta1`, …).
    pub name: &'static str,
    /// Largest |dq/dt|.
    pub max_velocity: f64,
    /// Largest |d²q/dt²|.
    pub max_acceleration: f64,
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

/// The optimal profile's grid along a move: an interval per 0.5 mm of path and per 7.5° the
/// path turns, and at least [`MIN_INTERVALS`]. C needs none: it moves in proportion to s, so it
/// adds a constant to θ3's q′ and nothing to any q″. TOPP-RA keeps every bound at the grid
/// points; between them a joint's q′ and q″ change by a little, which the margins of the
/// [`SpeedLimit`] cover (see the property tests of `biscara-joints`). The excess inside an
/// interval grows with the square of the turn it spans, largest where the robot brakes hard on
/// a tight arc (q″'s change times the change of ṡ²): on such an arc, braking to rest on the weak
/// robot, an interval per 10° reached 1.01 % over the planned bound (above the 1 % margin), per
/// 7.5° 0.57 %. On the arcs of 1 mm radius of `scripts/gen-program.sh mixed`, 7.5° costs `joints`
/// 3.5 % more instructions than 10° (2,000 lines, callgrind); lines are unchanged.
pub(crate) const GRID_MM: f64 = 0.5;
pub(crate) const GRID_TURN_DEGREES: f64 = 7.5;
const MIN_INTERVALS: f64 = 2.0;
/// The refined grid's ratio and most points (see [`optimal_grid`]).
pub(crate) const REFINE_RATIO: f64 = 0.7;
pub(crate) const MAX_REFINE: f64 = 100.0;
/// Intervals planned at a time (and as many of look-ahead): 512 mm at 0.5 mm, far more than the
/// braking distance from any speed a robot file allows (500 mm/s at 5000 mm/s² brakes in
/// 25 mm). Holds 2049 grid points of at most 9 constraints: about 200 KB.
pub(crate) const WINDOW: usize = 1024;

/// How a move advances in time.
#[derive(Debug, Clone)]
enum Schedule {
    /// Constant or trapezoid: a closed form.
    Closed(Timing),
    /// The optimal profile, planned by the interpolator's [`TimeOptimal`] as it is sampled.
    Optimal(OptimalSchedule),
}

#[derive(Debug, Clone, Copy)]
struct OptimalSchedule {
    /// `u64::MAX` until the duration is known (a move longer than one window).
    steps: u64,
    /// Plan time per sampled time (≤ 1: the duration rounded up to whole steps).
    scale: f64,
    /// The Cartesian bounds of the move: largest ds/dt and |d²s/dt²|.
    rate: f64,
    acceleration: f64,
    /// The programmed rate, and what slows the move below it (reported once the whole move is
    /// planned).
    programmed: f64,
    cause: Option<RateLimit>,
}

impl Schedule {
    fn steps(&self) -> u64 {
        match self {
            Schedule::Closed(timing) => timing.steps(),
            Schedule::Optimal(optimal) => optimal.steps,
        }
    }
}

/// The bounds of one move for [`TimeOptimal`]: |d²s/dt²| (the path and C accelerations), the
/// largest ds/dt (feed, rapid speed, C), and every joint's velocity and acceleration.
struct MoveBounds<'a, L> {
    segment: &'a Segment,
    limit: &'a mut L,
    rate: f64,
    acceleration: f64,
    /// The lowest rate a joint velocity allows at a grid point, and that joint.
    slowest: &'a mut Option<RateLimit>,
}

impl<L: SpeedLimit> PathConstraints for MoveBounds<'_, L> {
    fn count(&self) -> usize {
        1 + self.limit.joint_bounds().len().min(MAX_JOINTS) + self.limit.torque_rows()
    }

    fn evaluate(&mut self, s: f64, out: &mut [Constraint]) -> f64 {
        let acceleration = self.acceleration;
        out[0] = Constraint { a: 1.0, b: 0.0, c: 0.0, lo: -acceleration, hi: acceleration };
        let joints = self.limit.joint_bounds().len().min(MAX_JOINTS);
        let (mut first, mut second) = ([0.0; MAX_JOINTS], [0.0; MAX_JOINTS]);
        let known = self.limit.joint_derivatives(
            self.segment,
            s,
            &mut first[..joints],
            &mut second[..joints],
        ) && {
            // Finite, all of them: x·0 is 0 for a finite x, NaN otherwise.
            let spread = first[..joints].iter().zip(&second[..joints]);
            spread.fold(0.0, |sum, (a, b)| sum + a * 0.0 + b * 0.0) == 0.0
        };
        let mut rate = self.rate;
        for (j, bound) in self.limit.joint_bounds()[..joints].iter().enumerate() {
            if !known {
                // Nothing bounds the joints where the robot cannot be (an unbounded row).
                out[1 + j] = Constraint { lo: f64::NEG_INFINITY, hi: f64::INFINITY, ..out[0] };
                continue;
            }
            let a = bound.max_acceleration;
            out[1 + j] = Constraint { a: first[j], b: second[j], c: 0.0, lo: -a, hi: a };
            let joint_rate = bound.max_velocity / first[j].abs();
            if joint_rate < rate {
                rate = joint_rate;
            }
            if self.slowest.is_none_or(|slowest| joint_rate < slowest.rate) {
                *self.slowest = Some(RateLimit { rate: joint_rate, cause: bound.name });
            }
        }
        fill_torque_rows(
            self.limit,
            known,
            &first[..joints],
            &second[..joints],
            &mut out[1 + joints..],
        );
        rate * rate
    }
}

/// Fills a grid point's torque rows (`out`, after the path and joint rows) from the joints'
/// derivatives along the path: the speed limit's rows where the derivatives are `known` and
/// it gives them, else rows that bound nothing. For a single move and for a chain alike.
pub(crate) fn fill_torque_rows<L: SpeedLimit>(
    limit: &mut L,
    known: bool,
    first: &[f64],
    second: &[f64],
    out: &mut [Constraint],
) {
    let filled = out.is_empty() || (known && limit.torque_constraints(first, second, out));
    if !filled {
        out.fill(UNBOUNDED);
    }
}

/// A row that bounds nothing.
pub(crate) const UNBOUNDED: Constraint =
    Constraint { a: 0.0, b: 0.0, c: 0.0, lo: f64::NEG_INFINITY, hi: f64::INFINITY };

/// Turns motions into Cartesian samples at a fixed time step (docs/motion.md).
///
/// The first sample is the start pose at t = 0; every programmed end point is hit exactly by a
/// sample. Memory does not depend on the program length. `on_slow` hears of every motion that
/// runs slower than programmed.
pub struct Interpolator<I: Iterator, L, F> {
    /// The motions, nearly collinear G1 moves merged under G64 Q (LinuxCNC's naive-CAM
    /// detector), their corners blended where they ask for it (optimal profile only).
    motions: Blender<NaiveCam<I>>,
    /// Whether corners under G64 are blended (the optimal profile).
    blending: bool,
    limit: L,
    /// The optimal profile's planner, reused from move to move (no allocation per move).
    planner: TimeOptimal,
    on_slow: F,
    config: InterpolationConfig,
    pose: [f64; 4],
    gripper: bool,
    step: u64,
    active: Option<Active>,
    started: bool,
    finished: bool,
}

// One per interpolator, never in a collection: boxing the move would cost an allocation per move.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone)]
enum Active {
    Move {
        segment: Segment,
        schedule: Schedule,
        done: u64,
        line: usize,
    },
    Hold {
        remaining: u64,
        line: usize,
    },
    /// A chain of blended moves (G64), timed as one path; `steps` is `u64::MAX` until its
    /// duration is known.
    Chain {
        chain: Chain,
        steps: u64,
        scale: f64,
        done: u64,
    },
}

impl<I, E, L, F> Interpolator<I, L, F>
where
    I: Iterator<Item = Result<Motion, E>>,
    L: SpeedLimit,
    F: FnMut(&SlowDown),
{
    /// An interpolator over `motions`, bounded by `limit`, reporting slowed motions to `on_slow`.
    pub fn new(motions: I, config: InterpolationConfig, limit: L, on_slow: F) -> Self {
        let blending = config.profile == Profile::Optimal;
        Interpolator {
            motions: Blender::new(NaiveCam::new(motions, config.start), config.start)
                .blending(blending),
            blending,
            limit,
            planner: TimeOptimal::default(),
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
                if let Some(schedule) = self.plan(line, &motion.kind, &segment)? {
                    self.active = Some(Active::Move { segment, schedule, done: 0, line });
                }
                self.pose = segment.end();
            }
            MotionKind::Dwell { seconds } => {
                let remaining = hold_steps(seconds)?;
                self.active = Some(Active::Hold { remaining, line });
            }
            MotionKind::Pick | MotionKind::Place => {
                self.gripper = matches!(motion.kind, MotionKind::Pick);
                self.limit.set_holding(self.gripper);
                let remaining = hold_steps(self.config.grip_time)?;
                self.active = Some(Active::Hold { remaining, line });
            }
            MotionKind::GripperOff => {
                self.gripper = false;
                self.limit.set_holding(false);
            }
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

    /// Plans one move on the optimal profile over `grid` (the planner's first window) under its
    /// Cartesian bounds and the joints', noting the slowest joint rate met in `slowest`.
    fn plan_move(
        &mut self,
        segment: &Segment,
        grid: Grid,
        rate: f64,
        acceleration: f64,
        slowest: &mut Option<RateLimit>,
    ) -> Result<(), TimingError> {
        let mut bounds =
            MoveBounds { segment, limit: &mut self.limit, rate, acceleration, slowest };
        self.planner.plan(&mut bounds, grid, WINDOW)
    }

    /// The timing of a move, or `None` when it does not move.
    fn plan(
        &mut self,
        line: usize,
        kind: &MotionKind,
        segment: &Segment,
    ) -> Result<Option<Schedule>, InterpolateError<E>> {
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
        let mut cause = None;
        if self.config.profile != Profile::Constant && is_feed {
            let cap = limits.rapid_rotation / rotation;
            if cap < rate {
                rate = cap;
                cause = Some("C rotation");
            }
        }
        let too_long = || InterpolateError::Motion {
            line,
            message: "the move is too slow to count in time steps".to_owned(),
        };
        if self.config.profile == Profile::Optimal {
            let grid = optimal_grid(length, segment.turning(), rate, acceleration, false)
                .ok_or_else(too_long)?;
            let mut slowest = cause.map(|cause| RateLimit { rate, cause });
            if self.plan_move(segment, grid, rate, acceleration, &mut slowest).is_err() {
                return self.fallback(line, segment, rate, acceleration, programmed);
            }
            // Slower than the Cartesian trapezoid: a joint bound binds, and the switches need
            // not fall on the grid's points.
            let cartesian = if rate * rate >= acceleration {
                2.0 / acceleration.sqrt()
            } else {
                1.0 / rate + rate / acceleration
            };
            if self.planner.duration().is_some_and(|duration| duration > cartesian * (1.0 + 1e-9)) {
                let refined = optimal_grid(length, segment.turning(), rate, acceleration, true)
                    .ok_or_else(too_long)?;
                if self.plan_move(segment, refined, rate, acceleration, &mut slowest).is_err() {
                    return self.fallback(line, segment, rate, acceleration, programmed);
                }
            }
            let mut optimal = OptimalSchedule {
                steps: u64::MAX,
                scale: 1.0,
                rate,
                acceleration,
                programmed,
                cause: slowest,
            };
            if let Some(duration) = self.planner.duration() {
                self.finish_optimal(line, &mut optimal, duration, 0)?;
            }
            return Ok(Some(Schedule::Optimal(optimal)));
        }
        if self.config.profile != Profile::Constant {
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
            return Err(too_long());
        }
        Ok(Some(Schedule::Closed(timing)))
    }
}

impl<I, E, L, F> Interpolator<I, L, F>
where
    I: Iterator<Item = Result<Motion, E>>,
    L: SpeedLimit,
    F: FnMut(&SlowDown),
{
    /// A move the time-optimal planner cannot time (its bounds admit no motion somewhere along
    /// it): timed instead with the trapezoid profile at the rate the joints' speed
    /// limit allows ([`SpeedLimit::max_rate`], below the Cartesian `rate`), which is feasible
    /// and slower, with a note ([`PLANNER_FALLBACK`]) — never an error.
    #[cold]
    fn fallback(
        &mut self,
        line: usize,
        segment: &Segment,
        rate: f64,
        acceleration: f64,
        programmed: f64,
    ) -> Result<Option<Schedule>, InterpolateError<E>> {
        let rate = self.limit.max_rate(segment).map_or(rate, |limit| limit.rate.min(rate));
        (self.on_slow)(&SlowDown { line, cause: PLANNER_FALLBACK, factor: rate / programmed });
        let timing = Timing::new(Profile::Trapezoid, rate, acceleration, self.config.dt);
        if timing.duration() / self.config.dt > 1e15 || !timing.duration().is_finite() {
            return Err(InterpolateError::Motion {
                line,
                message: "the move is too slow to count in time steps".to_owned(),
            });
        }
        Ok(Some(Schedule::Closed(timing)))
    }
}

/// The [`SlowDown::cause`] of a move the time-optimal planner could not time, timed with the
/// trapezoid profile at the joints' speed limit instead.
pub const PLANNER_FALLBACK: &str = "time-optimal planner";

/// The optimal profile's grid along a move of `length` mm turning by `turning` degrees, with the
/// Cartesian bounds `rate` (ds/dt) and `acceleration` (d²s/dt²); `None` when it would be too
/// fine to count.
///
/// About an interval per [`GRID_MM`] of path and per [`GRID_TURN_DEGREES`] of turning, at least
/// [`MIN_INTERVALS`]. TOPP-RA loses time in the interval where the profile switches from
/// accelerating to cruising, and nothing when the switch falls on a grid point:
/// - first try (`refined` false): where the Cartesian bounds bind — on most moves — the switches
///   are at the ends of the Cartesian ramps, `ṡ²/2s̈` in s from either end, and those are grid
///   points (`Grid::end`); where the ramps reach the middle there is no cruise, and a symmetric
///   ramp up and down switches at s = ½, which an even grid holds;
/// - where the plan comes out slower than the Cartesian trapezoid, a joint binds and the
///   switches can be anywhere: the caller plans again (`refined` true) on the uniform grid with
///   its first and last interval cut geometrically by [`REFINE_RATIO`] down to an eighth of the
///   Cartesian ramp, so that a switch falls in an interval of about 0.4 ramps (at most
///   [`MAX_REFINE`] points).
fn optimal_grid(
    length: f64,
    turning: f64,
    rate: f64,
    acceleration: f64,
    refined: bool,
) -> Option<Grid> {
    let per_unit = (length / GRID_MM + turning / GRID_TURN_DEGREES).max(MIN_INTERVALS);
    if per_unit.is_nan() || per_unit >= 1e12 {
        return None;
    }
    let ramp = rate * rate / (2.0 * acceleration);
    let grid = if refined {
        let intervals = per_unit.ceil();
        let refine =
            ((ramp * intervals / 8.0).ln() / REFINE_RATIO.ln()).ceil().clamp(0.0, MAX_REFINE);
        Grid::refined(intervals as usize, refine as u32, REFINE_RATIO)
    } else if ramp.is_nan() || ramp >= 0.5 {
        let intervals = per_unit.ceil();
        Grid::uniform((intervals + intervals % 2.0) as usize)
    } else {
        let ends = (ramp * per_unit).ceil().max(1.0) as usize;
        let middle = ((1.0 - 2.0 * ramp) * per_unit).ceil().max(1.0) as usize;
        Grid { ends, end: ramp, ..Grid::uniform(middle) }
    };
    Some(grid)
}

impl<I, E, L, F> Interpolator<I, L, F>
where
    I: Iterator<Item = Result<Motion, E>>,
    L: SpeedLimit,
    F: FnMut(&SlowDown),
{
    /// Once a move's plan knows its `duration` (at `done` steps into the move): its steps
    /// (rounded up, never fewer than `done`), the time scale, and the report of a slow-down.
    fn finish_optimal(
        &mut self,
        line: usize,
        optimal: &mut OptimalSchedule,
        duration: f64,
        done: u64,
    ) -> Result<(), InterpolateError<E>> {
        if !duration.is_finite() || duration / self.config.dt > 1e15 {
            return Err(InterpolateError::Motion {
                line,
                message: "the move is too slow to count in time steps".to_owned(),
            });
        }
        if let Some(cause) = optimal.cause.filter(|cause| cause.rate < optimal.programmed) {
            let factor = cause.rate / optimal.programmed;
            (self.on_slow)(&SlowDown { line, cause: cause.cause, factor });
        }
        let steps = crate::profile::steps_for(duration, self.config.dt);
        if done == 0 {
            // Known before the first sample: the whole move is slowed to end on a step.
            optimal.scale = duration / (steps as f64 * self.config.dt);
            optimal.steps = steps;
        } else {
            // Sampled in its own time so far: it rests at its end for what is left of a step.
            optimal.steps = steps.max(done);
        }
        Ok(())
    }
}

impl<I, E, L, F> Interpolator<I, L, F>
where
    I: Iterator<Item = Result<Motion, E>>,
    L: SpeedLimit,
    F: FnMut(&SlowDown),
{
    /// Starts a chain of blended moves with its first piece: plans its first window.
    fn begin_chain(&mut self, piece: Piece) -> Result<(), InterpolateError<E>> {
        let line = piece.line;
        let mut chain = Chain::new(piece, self.config.limits)?;
        let mut error = None;
        let mut bounds = ChainBounds {
            chain: &mut chain,
            source: &mut self.motions,
            limit: &mut self.limit,
            limits: self.config.limits,
            error: &mut error,
        };
        let planned = self.planner.plan_streamed(&mut bounds, WINDOW);
        if let Some(err) = error {
            return Err(err);
        }
        planned.map_err(|err| InterpolateError::Motion {
            line,
            message: format!("cannot time the blended moves: {err}"),
        })?;
        let (mut steps, mut scale) = (u64::MAX, 1.0);
        if let Some(duration) = self.planner.duration() {
            steps = self.chain_steps(line, duration)?;
            scale = duration / (steps as f64 * self.config.dt);
        }
        self.active = Some(Active::Chain { chain, steps, scale, done: 0 });
        Ok(())
    }

    /// A chain's duration in whole steps.
    fn chain_steps(&self, line: usize, duration: f64) -> Result<u64, InterpolateError<E>> {
        if !duration.is_finite() || duration / self.config.dt > 1e15 {
            return Err(InterpolateError::Motion {
                line,
                message: "the move is too slow to count in time steps".to_owned(),
            });
        }
        Ok(crate::profile::steps_for(duration, self.config.dt))
    }

    /// The next sample of the active chain. Known before the first sample, the chain's
    /// duration is rounded up to whole steps by slowing it down; learned on the way (a chain
    /// longer than a window), the chain rests at its end for what is left of a step.
    fn chain_sample(&mut self) -> Result<CartesianSample, InterpolateError<E>> {
        let dt = self.config.dt;
        let Some(Active::Chain { chain, steps, scale, done }) = &mut self.active else {
            unreachable!("a chain is active");
        };
        *done += 1;
        let t = *done as f64 * dt;
        let mut error = None;
        let mut bounds = ChainBounds {
            chain,
            source: &mut self.motions,
            limit: &mut self.limit,
            limits: self.config.limits,
            error: &mut error,
        };
        let s = self.planner.s_at(&mut bounds, t * *scale);
        if let Some(err) = error {
            return Err(err);
        }
        let (mut pose, line) = chain.pose(*s.as_ref().unwrap_or(&0.0));
        let s = s.map_err(|err| InterpolateError::Motion {
            line,
            message: format!("cannot time the blended moves: {err}"),
        });
        s?;
        if *steps == u64::MAX
            && let Some(duration) = self.planner.duration()
        {
            let dt = self.config.dt;
            if !duration.is_finite() || duration / dt > 1e15 {
                return Err(InterpolateError::Motion {
                    line,
                    message: "the move is too slow to count in time steps".to_owned(),
                });
            }
            *steps = crate::profile::steps_for(duration, dt).max(*done);
        }
        if *done == *steps {
            pose = chain.end.unwrap_or(pose);
            chain.finish();
        }
        for report in chain.reports.drain(..) {
            (self.on_slow)(&report);
        }
        self.step += 1;
        Ok(self.sample(pose, line))
    }
}

impl<I, E, L, F> Interpolator<I, L, F>
where
    I: Iterator<Item = Result<Motion, E>>,
    L: SpeedLimit,
    F: FnMut(&SlowDown),
{
    /// Calls `each` with every sample in turn, by reference, and stops at the first error:
    /// `each`'s own, or the interpolator's turned into `G` by `error`. The same samples as
    /// iterating, but the inner samples of a move with a closed-form schedule (the constant and
    /// trapezoid profiles) come from a tight loop, without a pass through [`Iterator::next`]'s
    /// dispatch and its `Option<Result<…>>` each.
    pub fn try_for_each_sample<G>(
        &mut self,
        mut each: impl FnMut(&CartesianSample) -> Result<(), G>,
        error: impl FnOnce(InterpolateError<E>) -> G,
    ) -> Result<(), G> {
        loop {
            if let Some(Active::Move { segment, schedule: Schedule::Closed(timing), done, line }) =
                &mut self.active
            {
                // Every step but the last, which `next` ends exactly on the segment's end.
                let (dt, last) = (self.config.dt, timing.steps());
                while *done + 1 < last {
                    *done += 1;
                    self.step += 1;
                    let pose = segment.point(timing.s_at(*done as f64 * dt));
                    let t = self.step as f64 * dt;
                    each(&CartesianSample { t, pose, line: *line, gripper: self.gripper })?;
                }
            }
            match self.next() {
                None => return Ok(()),
                Some(Ok(sample)) => each(&sample)?,
                Some(Err(err)) => return Err(error(err)),
            }
        }
    }
}

#[cfg(test)]
impl<I: Iterator, L, F> Interpolator<I, L, F> {
    /// Number of blended pieces held (0 outside a chain).
    pub(crate) fn held_pieces(&self) -> usize {
        match &self.active {
            Some(Active::Chain { chain, .. }) => chain.held(),
            _ => 0,
        }
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
                Some(Active::Move { segment, schedule, done, line })
                    if *done < schedule.steps() =>
                {
                    *done += 1;
                    let t = *done as f64 * self.config.dt;
                    let line = *line;
                    let pose = match schedule {
                        Schedule::Closed(timing) => {
                            if *done == timing.steps() {
                                segment.end()
                            } else {
                                segment.point(timing.s_at(t))
                            }
                        }
                        Schedule::Optimal(optimal) => {
                            let known = optimal.steps != u64::MAX;
                            let s = if *done == optimal.steps {
                                1.0
                            } else {
                                let mut bounds = MoveBounds {
                                    segment,
                                    limit: &mut self.limit,
                                    rate: optimal.rate,
                                    acceleration: optimal.acceleration,
                                    slowest: &mut optimal.cause,
                                };
                                match self.planner.s_at(&mut bounds, t * optimal.scale) {
                                    Ok(s) => s,
                                    Err(err) => {
                                        self.finished = true;
                                        return Some(Err(InterpolateError::Motion {
                                            line,
                                            message: format!("cannot time the move: {err}"),
                                        }));
                                    }
                                }
                            };
                            if !known && let Some(duration) = self.planner.duration() {
                                let (mut optimal, done) = (*optimal, *done);
                                let finished =
                                    self.finish_optimal(line, &mut optimal, duration, done);
                                if let Err(err) = finished {
                                    self.finished = true;
                                    return Some(Err(err));
                                }
                                if let Some(Active::Move {
                                    schedule: Schedule::Optimal(kept),
                                    ..
                                }) = &mut self.active
                                {
                                    *kept = optimal;
                                }
                            }
                            match &self.active {
                                Some(Active::Move { segment, schedule, done, .. })
                                    if *done == schedule.steps() =>
                                {
                                    segment.end()
                                }
                                Some(Active::Move { segment, .. }) => segment.point(s),
                                _ => unreachable!("a move is active"),
                            }
                        }
                    };
                    self.step += 1;
                    return Some(Ok(self.sample(pose, line)));
                }
                Some(Active::Hold { remaining, line }) if *remaining > 0 => {
                    *remaining -= 1;
                    let line = *line;
                    self.step += 1;
                    return Some(Ok(self.sample(self.pose, line)));
                }
                Some(Active::Chain { done, steps, .. }) if *done < *steps => {
                    let sample = self.chain_sample();
                    if sample.is_err() {
                        self.finished = true;
                    }
                    return Some(sample);
                }
                Some(Active::Chain { chain, .. }) => {
                    self.pose = chain.end.unwrap_or(self.pose);
                    let deferred = chain.deferred.take();
                    self.active = None;
                    if let Some(motion) = deferred
                        && let Err(err) = self.begin(motion)
                    {
                        self.finished = true;
                        return Some(Err(err));
                    }
                    continue;
                }
                _ => self.active = None,
            }
            if self.finished {
                return None;
            }
            // Motions that are not blended go straight from the source: the blender sees only
            // those under G64 (and what follows them until their chain ends).
            if self.motions.is_idle() {
                match self.motions.source().next() {
                    None => {
                        self.finished = true;
                        return None;
                    }
                    Some(Err(err)) => {
                        self.finished = true;
                        return Some(Err(InterpolateError::Input(err)));
                    }
                    Some(Ok(motion)) if motion.blend.is_none() || !self.blending => {
                        if let Err(err) = self.begin(motion) {
                            self.finished = true;
                            return Some(Err(err));
                        }
                    }
                    Some(Ok(motion)) => self.motions.take_from(motion, self.pose),
                }
                continue;
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
                Some(Ok(Blended::Motion(motion))) => {
                    if let Err(err) = self.begin(motion) {
                        self.finished = true;
                        return Some(Err(err));
                    }
                }
                Some(Ok(Blended::Piece(piece))) => {
                    if let Err(err) = self.begin_chain(piece) {
                        self.finished = true;
                        return Some(Err(err));
                    }
                }
            }
        }
    }
}
