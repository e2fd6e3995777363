//! Interpolation (docs/motion.md): end points hit exactly, durations in whole steps, speeds never above the programmed
//! ones, the paper's constant profile, the trapezoid, dwells, grip time and events.

use std::convert::Infallible;

use approx::assert_relative_eq;
use biscara_interpolate::{
    CartesianLimits, CartesianSample, Constraint, InterpolationConfig, Interpolator, JointBound,
    NoSpeedLimit, PLANNER_FALLBACK, Profile, RateLimit, Segment, SlowDown, SpeedLimit,
};
use biscara_motion::{Feed, Motion, MotionKind, Plane};
use proptest::prelude::*;

use crate::strategies::program;

const START: [f64; 4] = [0.0, 400.0, 50.0, 0.0];

fn config(profile: Profile, dt: f64) -> InterpolationConfig {
    InterpolationConfig {
        dt,
        profile,
        start: START,
        limits: CartesianLimits {
            rapid_velocity: 500.0,
            rapid_rotation: 360.0,
            acceleration: 5000.0,
            rotation_acceleration: 7200.0,
        },
        grip_time: 0.0,
    }
}

fn run(motions: &[Motion], config: InterpolationConfig) -> (Vec<CartesianSample>, Vec<SlowDown>) {
    let mut slow = Vec::new();
    let samples = Interpolator::new(
        motions.iter().map(|m| Ok::<_, Infallible>(*m)),
        config,
        NoSpeedLimit,
        |s: &SlowDown| slow.push(*s),
    )
    .collect::<Result<Vec<_>, _>>()
    .expect("interpolation");
    (samples, slow)
}

fn feed(mm_per_min: f64) -> Feed {
    Feed { mm_per_min, inverse_time: false }
}

fn linear(line: usize, end: [f64; 4], mm_per_min: f64) -> Motion {
    Motion::new(line, MotionKind::Linear { end, feed: feed(mm_per_min) })
}

#[test]
fn constant_profile_is_the_papers() {
    // 30 mm at 1800 mm/min = 30 mm/s: 1 s, 1000 steps of exactly 0.03 mm.
    let motions = [linear(1, [30.0, 400.0, 50.0, 0.0], 1800.0)];
    let (samples, _) = run(&motions, config(Profile::Constant, 0.001));
    assert_eq!(samples.len(), 1001);
    assert_eq!(samples[0].t, 0.0);
    assert_eq!(samples[0].pose, START);
    for pair in samples.windows(2) {
        assert_relative_eq!(pair[1].pose[0] - pair[0].pose[0], 0.03, epsilon = 1e-9);
        assert_relative_eq!(pair[1].t - pair[0].t, 0.001, epsilon = 1e-12);
    }
    assert_eq!(samples[1000].pose, [30.0, 400.0, 50.0, 0.0]);
    assert_relative_eq!(samples[1000].t, 1.0, epsilon = 1e-12);
}

#[test]
fn durations_round_up_to_whole_steps_and_speed_drops() {
    // 10 mm at 600 mm/min = 1 s; with dt = 0.3 s that is 4 steps (1.2 s).
    let motions = [linear(1, [10.0, 400.0, 50.0, 0.0], 600.0)];
    let (samples, _) = run(&motions, config(Profile::Constant, 0.3));
    assert_eq!(samples.len(), 5);
    assert_relative_eq!(samples[4].t, 1.2, epsilon = 1e-12);
    assert_relative_eq!(samples[1].pose[0], 2.5, epsilon = 1e-12);
}

#[test]
fn rapids_use_the_rapid_limits() {
    // 250 mm at 500 mm/s = 0.5 s; a C turn of 270° at 360°/s = 0.75 s wins.
    let motions = [
        Motion::new(1, MotionKind::Rapid { end: [250.0, 400.0, 50.0, 0.0] }),
        Motion::new(2, MotionKind::Rapid { end: [250.0, 400.0, 50.0, 270.0] }),
    ];
    let (samples, slow) = run(&motions, config(Profile::Constant, 0.001));
    assert_eq!(samples.len(), 1 + 500 + 750);
    assert!(slow.is_empty(), "rapids are not slowed, they define their speed");
}

#[test]
fn rotation_only_feed_is_degrees_per_minute() {
    // LinuxCNC: G1 C90 F600 turns at 600°/min = 10°/s: 9 s.
    let motions = [linear(1, [0.0, 400.0, 50.0, 90.0], 600.0)];
    let (samples, _) = run(&motions, config(Profile::Constant, 0.01));
    assert_eq!(samples.len(), 901);
}

#[test]
fn fast_rotation_is_capped_and_reported_except_in_the_constant_profile() {
    // 10 mm at 6000 mm/min (0.1 s) while C turns 180°: 500 °/s would exceed rapid_rotation.
    let motions = [linear(7, [10.0, 400.0, 50.0, 180.0], 6000.0)];
    let (samples, slow) = run(&motions, config(Profile::Trapezoid, 0.001));
    assert_eq!(slow.len(), 1);
    assert_eq!(slow[0].line, 7);
    assert_eq!(slow[0].cause, "C rotation");
    for pair in samples.windows(2) {
        let rate = (pair[1].pose[3] - pair[0].pose[3]) / 0.001;
        assert!(rate <= 360.0 + 1e-6, "C at {rate} °/s");
    }
    let (_, slow) = run(&motions, config(Profile::Constant, 0.001));
    assert!(slow.is_empty());
}

#[test]
fn trapezoid_starts_and_stops_at_rest_and_respects_speed_and_acceleration() {
    let motions = [
        linear(1, [100.0, 400.0, 50.0, 0.0], 6000.0),
        linear(2, [100.0, 300.0, 50.0, 0.0], 3000.0),
    ];
    let dt = 0.001;
    let (samples, _) = run(&motions, config(Profile::Trapezoid, dt));
    let speeds: Vec<f64> = samples
        .windows(2)
        .map(|p| {
            let d: f64 = (0..3).map(|i| (p[1].pose[i] - p[0].pose[i]).powi(2)).sum();
            d.sqrt() / dt
        })
        .collect();
    assert!(speeds[0] < 5000.0 * dt * 1.01, "first step from rest: {}", speeds[0]);
    assert!(speeds.iter().all(|&v| v <= 100.0 + 1e-6), "never above 6000 mm/min");
    for pair in speeds.windows(2) {
        assert!((pair[1] - pair[0]).abs() / dt <= 5000.0 * 1.01, "acceleration within the limit");
    }
    let corner =
        samples.iter().position(|s| s.pose == [100.0, 400.0, 50.0, 0.0]).expect("corner hit");
    assert_eq!(samples[corner].line, 1);
    assert_eq!(samples[corner + 1].line, 2);
}

#[test]
fn arcs_follow_the_circle() {
    let motions = [
        linear(1, [50.0, 400.0, 50.0, 0.0], 6000.0),
        Motion {
            line: 2,
            kind: MotionKind::Arc {
                end: [0.0, 450.0, 60.0, 0.0],
                center: [0.0, 400.0],
                plane: Plane::Xy,
                clockwise: false,
                turns: 1,
                feed: feed(1200.0),
            },
            extrude: None,
            blend: None,
            naive_cam: None,
        },
    ];
    let (samples, _) = run(&motions, config(Profile::Trapezoid, 0.001));
    let arc = Segment::arc(
        [50.0, 400.0, 50.0, 0.0],
        [0.0, 450.0, 60.0, 0.0],
        [0.0, 400.0],
        Plane::Xy,
        false,
        1,
    );
    for sample in samples.iter().filter(|s| s.line == 2) {
        let radius = sample.pose[0].hypot(sample.pose[1] - 400.0);
        assert_relative_eq!(radius, 50.0, epsilon = 1e-9);
        assert!(arc.distance_to([sample.pose[0], sample.pose[1], sample.pose[2]]) < 1e-6);
    }
    assert_eq!(samples.last().expect("samples").pose, [0.0, 450.0, 60.0, 0.0]);
}

#[test]
fn dwell_grip_time_and_gripper_events() {
    let motions = [
        Motion::new(1, MotionKind::Pick),
        Motion::new(2, MotionKind::Dwell { seconds: 0.3 }),
        linear(3, [1.0, 400.0, 50.0, 0.0], 60.0),
        Motion::new(4, MotionKind::Place),
        Motion::new(5, MotionKind::Pause),
        Motion::new(6, MotionKind::End),
        linear(7, [99.0, 400.0, 50.0, 0.0], 60.0),
    ];
    let mut settings = config(Profile::Constant, 0.1);
    settings.grip_time = 0.25;
    let (samples, _) = run(&motions, settings);
    // start + pick 3 (0.25 s → 3 steps) + dwell 3 + move 10 + place 3; nothing after M2.
    assert_eq!(samples.len(), 1 + 3 + 3 + 10 + 3);
    assert!(!samples[0].gripper);
    assert!(samples[1..17].iter().all(|s| s.gripper));
    assert!(samples[17..].iter().all(|s| !s.gripper));
    assert_eq!(samples.last().expect("samples").pose, [1.0, 400.0, 50.0, 0.0]);
    // Without grip time, events take no time.
    let (samples, _) = run(&motions, config(Profile::Constant, 0.1));
    assert_eq!(samples.len(), 1 + 3 + 10);
}

#[test]
fn a_speed_limit_slows_a_move_and_is_reported() {
    struct HalfSpeed;
    impl SpeedLimit for HalfSpeed {
        fn max_rate(&mut self, _segment: &Segment) -> Option<RateLimit> {
            Some(RateLimit { rate: 0.5, cause: "theta2" })
        }
    }
    let motions = [linear(3, [10.0, 400.0, 50.0, 0.0], 1200.0)]; // 0.5 s at 1 /s... → 2 s at 0.5/s
    let mut slow = Vec::new();
    let samples: Vec<_> = Interpolator::new(
        motions.iter().map(|m| Ok::<_, Infallible>(*m)),
        config(Profile::Trapezoid, 0.01),
        HalfSpeed,
        |s: &SlowDown| slow.push(*s),
    )
    .collect::<Result<_, _>>()
    .expect("interpolation");
    assert_eq!(slow.len(), 1);
    assert_eq!((slow[0].line, slow[0].cause), (3, "theta2"));
    assert!(samples.last().expect("samples").t >= 2.0);
}

/// A move along which the bounds admit no motion for the time-optimal planner (a joint whose
/// rate along the path is so large in the middle of the move that the largest ṡ² rounds to
/// zero, "the bounds allow no motion along the path" — what a GRBL-Plotter program met with
/// `check --fit`) is timed with the trapezoid at the joints' speed limit instead, with a note,
/// never an error; the end point is still hit.
#[test]
fn a_move_the_optimal_planner_cannot_time_falls_back_to_a_slower_trapezoid() {
    struct Wall([JointBound; 1]);
    impl SpeedLimit for Wall {
        fn max_rate(&mut self, _segment: &Segment) -> Option<RateLimit> {
            Some(RateLimit { rate: 0.25, cause: "theta1" })
        }
        fn joint_bounds(&self) -> &[JointBound] {
            &self.0
        }
        fn joint_derivatives(
            &mut self,
            _segment: &Segment,
            s: f64,
            first: &mut [f64],
            second: &mut [f64],
        ) -> bool {
            first[0] = if (0.4..0.7).contains(&s) { 1e200 } else { 1.0 };
            second[0] = 0.0;
            true
        }
    }
    let bound = JointBound { name: "theta1", max_velocity: 1.0, max_acceleration: 10.0 };
    let end = [10.0, 400.0, 50.0, 0.0];
    let motions = [linear(7, end, 1200.0)];
    let mut slow = Vec::new();
    let samples: Vec<_> = Interpolator::new(
        motions.iter().map(|m| Ok::<_, Infallible>(*m)),
        config(Profile::Optimal, 0.01),
        Wall([bound]),
        |s: &SlowDown| slow.push(*s),
    )
    .collect::<Result<_, _>>()
    .expect("timed, not an error");
    assert_eq!(slow.len(), 1, "{slow:?}");
    assert_eq!((slow[0].line, slow[0].cause), (7, PLANNER_FALLBACK));
    assert_relative_eq!(slow[0].factor, 0.25 / 2.0);
    let last = samples.last().expect("samples");
    assert_eq!(last.pose, end);
    // At a quarter of the move per second: at least 4 s.
    assert!(last.t >= 4.0, "{}", last.t);
}

/// A motor that pushes a mass along the path: its force `mass · s̈` (mm/s², kg·mm/s² = mN)
/// within ±`peak`, the mass 4× while the gripper holds.
struct Pusher {
    bound: [JointBound; 1],
    holding: bool,
}

impl Pusher {
    const PEAK: f64 = 1000.0;

    fn new() -> Pusher {
        let bound =
            JointBound { name: "x", max_velocity: f64::INFINITY, max_acceleration: f64::INFINITY };
        Pusher { bound: [bound], holding: false }
    }
}

impl SpeedLimit for Pusher {
    fn max_rate(&mut self, _segment: &Segment) -> Option<RateLimit> {
        None
    }
    fn joint_bounds(&self) -> &[JointBound] {
        &self.bound
    }
    /// The one "joint" is the distance along the path.
    fn joint_derivatives(
        &mut self,
        segment: &Segment,
        _s: f64,
        first: &mut [f64],
        second: &mut [f64],
    ) -> bool {
        (first[0], second[0]) = (segment.length(), 0.0);
        true
    }
    fn torque_rows(&self) -> usize {
        1
    }
    fn torque_constraints(
        &mut self,
        first: &[f64],
        second: &[f64],
        out: &mut [Constraint],
    ) -> bool {
        let mass = if self.holding { 4.0 } else { 1.0 };
        let peak = Pusher::PEAK;
        out[0] =
            Constraint { a: mass * first[0], b: mass * second[0], c: 0.0, lo: -peak, hi: peak };
        true
    }
    fn set_holding(&mut self, holding: bool) {
        self.holding = holding;
    }
}

/// The largest acceleration along the path between samples (mm/s²), from second differences
/// of the distance travelled.
fn peak_path_acceleration(samples: &[CartesianSample], dt: f64) -> f64 {
    let distance = |a: &CartesianSample, b: &CartesianSample| {
        (0..3).map(|k| (b.pose[k] - a.pose[k]).powi(2)).sum::<f64>().sqrt()
    };
    samples
        .windows(3)
        .map(|w| (distance(&w[1], &w[2]) - distance(&w[0], &w[1])).abs() / (dt * dt))
        .fold(0.0, f64::max)
}

/// Rows beyond the joints' (a motor's torque) bound the optimal profile, in single moves and in
/// blended chains, with the payload the gripper holds.
#[test]
fn torque_rows_bound_the_optimal_profile_with_the_payload() {
    let dt = 0.001;
    let run_with = |motions: &[Motion]| -> Vec<CartesianSample> {
        Interpolator::new(
            motions.iter().map(|m| Ok::<_, Infallible>(*m)),
            config(Profile::Optimal, dt),
            Pusher::new(),
            |_: &SlowDown| {},
        )
        .collect::<Result<_, _>>()
        .expect("interpolation")
    };
    // 100 mm at up to 1000 mm/s² (well below the path's 5000): a triangle of 2·√(0.1 s²).
    let free = run_with(&[linear(1, [100.0, 400.0, 50.0, 0.0], 60_000.0)]);
    let duration = free.last().expect("samples").t;
    assert_relative_eq!(duration, 2.0 * 0.1f64.sqrt(), max_relative = 0.01);
    assert!(peak_path_acceleration(&free, dt) <= Pusher::PEAK * 1.001);
    // Holding four times the mass: a quarter of the acceleration, twice the time.
    let held = run_with(&[
        Motion::new(1, MotionKind::Pick),
        linear(2, [100.0, 400.0, 50.0, 0.0], 60_000.0),
    ]);
    assert_relative_eq!(held.last().expect("samples").t, 2.0 * duration, max_relative = 0.01);
    assert!(peak_path_acceleration(&held, dt) <= Pusher::PEAK / 4.0 * 1.001);
    // A blended chain: the same bound along its pieces.
    let chain: Vec<_> = [[50.0, 400.0], [50.0, 450.0], [100.0, 450.0]]
        .iter()
        .enumerate()
        .map(|(k, [x, y])| Motion {
            blend: Some(1.0),
            ..linear(k + 1, [*x, *y, 50.0, 0.0], 60_000.0)
        })
        .collect();
    let blended = run_with(&chain);
    assert!(blended.last().expect("samples").t > 2.0 * (0.15f64).sqrt() * 0.99);
    assert!(peak_path_acceleration(&blended, dt) <= Pusher::PEAK * 1.01);
}

#[test]
fn input_errors_and_bad_feeds_stop_the_stream() {
    let motions = [linear(1, [10.0, 400.0, 50.0, 0.0], 0.0)];
    let results: Vec<_> = Interpolator::new(
        motions.iter().map(|m| Ok::<_, Infallible>(*m)),
        config(Profile::Trapezoid, 0.01),
        NoSpeedLimit,
        |_: &SlowDown| {},
    )
    .collect();
    assert_eq!(results.len(), 2);
    let err = results[1].as_ref().expect_err("zero feed");
    assert_eq!(err.to_string(), "1: the feed 0 mm/min is not positive");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    /// Every programmed end point is hit exactly by a sample, times are whole steps,
    /// and no step moves faster than the programmed speed allows.
    #[test]
    fn every_end_point_is_hit(
        motions in program(12),
        profile in prop_oneof![Just(Profile::Constant), Just(Profile::Trapezoid), Just(Profile::Optimal)],
    ) {
        let dt = 0.002;
        let (samples, _) = run(&motions, config(profile, dt));
        for (index, sample) in samples.iter().enumerate() {
            prop_assert!((sample.t - index as f64 * dt).abs() < 1e-9);
        }
        let mut cursor = 0;
        for motion in &motions {
            let Some(end) = motion.kind.end() else { continue };
            let found = samples[cursor..].iter().position(|s| s.pose == end && s.line == motion.line);
            prop_assert!(found.is_some() || samples[cursor].pose == end, "end of line {} not hit", motion.line);
            if let Some(offset) = found {
                cursor += offset;
            }
        }
        for pair in samples.windows(2) {
            let Some(motion) = motions.iter().find(|m| m.line == pair[1].line) else { continue };
            let step: f64 = (0..3).map(|i| (pair[1].pose[i] - pair[0].pose[i]).powi(2)).sum::<f64>().sqrt();
            let limit = match motion.kind {
                MotionKind::Linear { feed, .. } | MotionKind::Arc { feed, .. } => feed.mm_per_min / 60.0,
                MotionKind::Rapid { .. } => 500.0,
                _ => 0.0,
            };
            // A chord is never longer than the arc it cuts, so this bounds arcs too.
            prop_assert!(step <= limit * dt * (1.0 + 1e-6) + 1e-9, "line {}: {} mm in one step", motion.line, step);
        }
    }
}

/// Feed moves of a random program with their start poses, for the profile properties.
fn feed_moves(motions: &[Motion]) -> Vec<(Motion, Segment)> {
    let mut pose = START;
    let mut moves = Vec::new();
    for motion in motions {
        let segment = match motion.kind {
            MotionKind::Arc { end, center, plane, clockwise, turns, .. } => {
                Segment::arc(pose, end, center, plane, clockwise, turns)
            }
            kind => match kind.end() {
                Some(end) => Segment::line(pose, end),
                None => continue,
            },
        };
        pose = segment.end();
        moves.push((*motion, segment));
    }
    moves
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(100))]

    /// `--profile constant` is the paper's rule: a motion of length L at speed v takes
    /// N = ceil(L / (v·dt)) equal steps.
    #[test]
    fn constant_profile_takes_ceil_l_over_v_dt_equal_steps(motions in program(8)) {
        let dt = 0.002;
        let (samples, _) = run(&motions, config(Profile::Constant, dt));
        for (motion, segment) in feed_moves(&motions) {
            let MotionKind::Linear { feed, .. } = motion.kind else { continue };
            let length = segment.length();
            if length < 1e-6 {
                continue;
            }
            let expected = (length / (feed.mm_per_min / 60.0 * dt) * (1.0 - 1e-9)).ceil() as usize;
            let rows: Vec<_> = samples.iter().filter(|s| s.line == motion.line).collect();
            prop_assert_eq!(rows.len(), expected.max(1), "line {}", motion.line);
            let step = length / expected as f64;
            let mut previous = segment.start();
            for row in rows {
                let d: f64 = (0..3).map(|i| (row.pose[i] - previous[i]).powi(2)).sum::<f64>().sqrt();
                prop_assert!((d - step).abs() < 1e-9, "line {}: step {} instead of {}", motion.line, d, step);
                previous = row.pose;
            }
        }
    }

    /// `--profile trapezoid` and `optimal`: the path acceleration never exceeds
    /// `motion.acceleration`, and every motion starts and ends at rest.
    #[test]
    fn trapezoid_acceleration_never_exceeds_the_limit(motions in program(8), optimal in any::<bool>()) {
        let dt = 0.002;
        let profile = if optimal { Profile::Optimal } else { Profile::Trapezoid };
        let (samples, _) = run(&motions, config(profile, dt));
        let moves = feed_moves(&motions);
        let segment_of = |line: usize| moves.iter().find(|(m, _)| m.line == line).map(|(_, s)| *s);
        // Path speed of each step, from the path parameter of the samples of one motion.
        for triple in samples.windows(3) {
            let line = triple[1].line;
            if triple[0].line != line && triple[0].line != 0 || triple[2].line != line {
                continue;
            }
            let Some(segment) = segment_of(line) else { continue };
            let length = segment.length();
            if length < 1e-6 {
                continue;
            }
            let chord = |a: &[f64; 4], b: &[f64; 4]| (0..3).map(|i| (a[i] - b[i]).powi(2)).sum::<f64>().sqrt();
            let v1 = chord(&triple[1].pose, &triple[0].pose) / dt;
            let v2 = chord(&triple[2].pose, &triple[1].pose) / dt;
            // Chords of an arc are shorter than the arc: allow for it with the sagitta ratio.
            prop_assert!((v2 - v1).abs() / dt <= 5000.0 * 1.001 + 1e-6, "line {line}: {} mm/s²", (v2 - v1).abs() / dt);
        }
    }

    /// Without joint limits, the optimal profile solves the trapezoid's problem (bounded path
    /// speed and acceleration, rest to rest), whose exact optimum is the trapezoid: every motion
    /// takes at least as many steps, and at most one more plus 0.2 % (the grid's loss where the
    /// ramps end).
    #[test]
    fn optimal_without_joint_limits_is_the_trapezoid(motions in program(8)) {
        let dt = 0.001;
        let steps = |profile| {
            let (samples, _) = run(&motions, config(profile, dt));
            let mut per_line = std::collections::BTreeMap::new();
            for sample in &samples[1..] {
                *per_line.entry(sample.line).or_insert(0usize) += 1;
            }
            per_line
        };
        let (trapezoid, optimal) = (steps(Profile::Trapezoid), steps(Profile::Optimal));
        prop_assert_eq!(trapezoid.len(), optimal.len());
        for (line, &n) in &trapezoid {
            let m = optimal[line];
            prop_assert!(m >= n && m <= n + 1 + n / 500, "line {line}: trapezoid {n} steps, optimal {m}");
        }
    }
}

/// The samples of `motions` through [`Interpolator::try_for_each_sample`], up to the first error.
fn run_by_reference(
    motions: &[Motion],
    config: InterpolationConfig,
) -> (Vec<CartesianSample>, Option<String>) {
    let mut samples = Vec::new();
    let outcome = Interpolator::new(
        motions.iter().map(|m| Ok::<_, Infallible>(*m)),
        config,
        NoSpeedLimit,
        |_: &SlowDown| {},
    )
    .try_for_each_sample(
        |sample| {
            samples.push(*sample);
            Ok::<(), String>(())
        },
        |err| err.to_string(),
    );
    (samples, outcome.err())
}

#[test]
fn sampling_by_reference_stops_at_errors_and_at_the_callers_error() {
    let motions =
        [linear(1, [10.0, 400.0, 50.0, 0.0], 600.0), linear(2, [10.0, 410.0, 50.0, 0.0], 0.0)];
    let (samples, err) = run_by_reference(&motions, config(Profile::Trapezoid, 0.01));
    assert_eq!(err.as_deref(), Some("2: the feed 0 mm/min is not positive"));
    assert_eq!(samples.last().map(|s| s.pose), Some([10.0, 400.0, 50.0, 0.0]));
    // The caller's error stops the stream in the middle of a move.
    let mut seen = 0;
    let stopped = Interpolator::new(
        motions.iter().map(|m| Ok::<_, Infallible>(*m)),
        config(Profile::Trapezoid, 0.01),
        NoSpeedLimit,
        |_: &SlowDown| {},
    )
    .try_for_each_sample(
        |_| {
            seen += 1;
            if seen == 5 { Err("enough") } else { Ok(()) }
        },
        |_| "interpolation",
    );
    assert_eq!((stopped, seen), (Err("enough"), 5));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    /// Sampling by reference (the closed-form schedules' tight loop) gives exactly the samples
    /// of iterating, in every profile.
    #[test]
    fn sampling_by_reference_is_iterating(
        motions in program(12),
        profile in prop_oneof![Just(Profile::Constant), Just(Profile::Trapezoid), Just(Profile::Optimal)],
    ) {
        let (iterated, _) = run(&motions, config(profile, 0.002));
        let (by_reference, err) = run_by_reference(&motions, config(profile, 0.002));
        prop_assert_eq!(err, None);
        prop_assert_eq!(iterated, by_reference);
    }
}
