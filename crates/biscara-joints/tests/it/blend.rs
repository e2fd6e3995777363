//! Corner blending under G64 P (issue 17): on random polylines (CAM-style, sharp and shallow
//! corners, short and long segments, rapids among feeds, C and Z moving) and on random chains of
//! lines and arcs, the blended trajectory keeps every joint limit in its own central
//! differences, FK of every row lies within P of the programmed path, the program ends on its
//! last programmed point, and it is never slower than the same program with exact stops (up to
//! the planner's grid).

use biscara_blend::NO_TOLERANCE_CAP_MM;
use biscara_interpolate::Profile;
use biscara_kinematics::{Kinematics, Robot};
use biscara_motion::{Motion, MotionKind};
use proptest::prelude::*;

use crate::optimal::{TOLERANCE, feed, motions, peak_ratios, robot, segments, step, trajectory};

/// One polyline vertex: turn from the previous heading (degrees), length (mm), Z and C changes,
/// feed (mm/min), whether it is a rapid.
type Vertex = (f64, f64, f64, f64, f64, bool);

fn vertex() -> impl Strategy<Value = Vertex> {
    (
        prop_oneof![-179.0..179.0f64, -5.0..5.0f64],
        prop_oneof![0.2..2.0f64, 2.0..25.0f64],
        -1.0..1.0f64,
        -5.0..5.0f64,
        300.0..12000.0f64,
        prop::bool::weighted(0.15),
    )
}

/// G64 P: 0.01, 0.05, 0.1 mm, or 0 (G64 with no P).
fn tolerance() -> impl Strategy<Value = f64> {
    prop_oneof![Just(0.01), Just(0.05), Just(0.1), Just(0.0)]
}

/// The polyline's motions from a start in the workspace's middle, turning back at the edges of
/// a 160 × 100 mm box; every motion under `blend`.
fn polyline(vertices: &[Vertex], blend: Option<f64>) -> Vec<Motion> {
    let mut pose = [0.0, 340.0, 50.0, 0.0];
    let mut heading = 0.0f64;
    let mut motions = vec![Motion { blend, ..Motion::new(1, MotionKind::Rapid { end: pose }) }];
    for (index, &(turn, length, dz, dc, f, rapid)) in vertices.iter().enumerate() {
        heading += turn.to_radians();
        let end = |heading: f64| {
            [
                pose[0] + length * heading.cos(),
                pose[1] + length * heading.sin(),
                pose[2] + dz,
                pose[3] + dc,
            ]
        };
        let mut next = end(heading);
        if next[0].abs() > 80.0 || !(290.0..390.0).contains(&next[1]) {
            heading += std::f64::consts::PI;
            next = end(heading);
        }
        let kind = if rapid {
            MotionKind::Rapid { end: next }
        } else {
            MotionKind::Linear { end: next, feed: feed(f) }
        };
        motions.push(Motion { blend, ..Motion::new(index + 2, kind) });
        pose = next;
    }
    motions
}

/// The same motions under exact stop.
fn exact(motions: &[Motion]) -> Vec<Motion> {
    motions.iter().map(|motion| Motion { blend: None, ..*motion }).collect()
}

/// Runs `blended` and its exact-stop twin and checks the properties of the module's doc; `None`
/// when the robot cannot follow the exact-stop program (such programs are `check`'s).
fn check_blended(blended: &[Motion], robot: &Robot, tolerance: f64) -> Result<(), TestCaseError> {
    let model = Kinematics::new(robot).expect("robot");
    let home = model.home().to_degrees();
    let stopping = trajectory(&exact(blended), robot, Profile::Optimal);
    prop_assume!(stopping.is_some());
    let stopping = stopping.unwrap_or_default();
    let rows = trajectory(blended, robot, Profile::Optimal);
    prop_assert!(rows.is_some(), "the exact-stop program runs, the blended one does not");
    let rows = rows.unwrap_or_default();
    let (velocity, acceleration) = peak_ratios(&rows, robot);
    for j in 0..4 {
        prop_assert!(velocity[j] <= 1.0 + TOLERANCE, "joint {j} velocity at {}", velocity[j]);
        prop_assert!(
            acceleration[j] <= 1.0 + TOLERANCE,
            "joint {j} acceleration at {}",
            acceleration[j]
        );
    }
    let allowed = if tolerance > 0.0 { tolerance } else { NO_TOLERANCE_CAP_MM };
    let path = segments(blended, home);
    for (index, row) in rows.iter().enumerate() {
        let fk = model.forward(&row.joints).expect("FK").pose;
        let distance = path
            .iter()
            .map(|(_, segment)| segment.distance_to([fk.x, fk.y, fk.z]))
            .fold(f64::INFINITY, f64::min);
        prop_assert!(
            distance <= allowed + 1e-6,
            "row {index} (t = {}) is {distance} mm off the path",
            row.t
        );
    }
    let last = rows.last().expect("rows");
    let end = path.last().expect("motions").1.end();
    prop_assert_eq!(last.pose, end);
    // TOPP-RA loses part of an interval's time where a switch of the optimum (from
    // accelerating to cruising, say) falls between grid points, which the blended chain and the
    // exact-stop moves do on different grids where a joint bound binds: up to a millisecond a
    // move either way, as between the optimal and the trapezoid profiles.
    let (blended_time, stopping_time) = (last.t, stopping.last().map_or(0.0, |row| row.t));
    let grid = blended.len() as f64 * 0.001;
    prop_assert!(
        blended_time <= stopping_time + grid + 1e-9,
        "blended {blended_time} s, exact stop {stopping_time} s"
    );
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 32,
        max_global_rejects: 10_000,
        ..ProptestConfig::default()
    })]

    /// Random CAM-style polylines on the strong and the weak robot.
    #[test]
    fn blended_polylines_keep_the_tolerance_and_the_limits(
        vertices in proptest::collection::vec(vertex(), 1..40),
        tolerance in tolerance(),
        weak: bool,
    ) {
        let robot = robot(weak);
        check_blended(&polyline(&vertices, Some(tolerance)), &robot, tolerance)?;
    }

    /// Random chains of lines, tight arcs, C rotations and moves near the workspace's edge: arcs
    /// and moves without XYZ length stop, the lines between them blend.
    #[test]
    fn blended_arc_chains_keep_the_tolerance_and_the_limits(
        steps in proptest::collection::vec(step(), 1..8),
        tolerance in tolerance(),
        weak: bool,
    ) {
        let robot = robot(weak);
        let model = Kinematics::new(&robot).expect("robot");
        let blended: Vec<Motion> = motions(&steps, model.home().to_degrees(), &model)
            .into_iter()
            .map(|motion| Motion { blend: Some(tolerance), ..motion })
            .collect();
        check_blended(&blended, &robot, tolerance)?;
    }
}
