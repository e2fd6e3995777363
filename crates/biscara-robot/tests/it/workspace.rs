//! The workspace grid, its area and its largest rectangle (docs/virtual-robot.md).

use biscara_kinematics::{Kinematics, Robot};
use biscara_robot::Workspace;

fn default_model() -> Kinematics {
    Kinematics::new(&Robot::default()).expect("default robot")
}

#[test]
fn area_converges_as_the_step_shrinks() {
    let model = default_model();
    let coarse = Workspace::compute(&model, 2.0).unwrap().area_mm2();
    let fine = Workspace::compute(&model, 1.0).unwrap().area_mm2();
    let relative = (coarse - fine).abs() / fine;
    assert!(relative < 0.01, "2 mm: {coarse} mm², 1 mm: {fine} mm², {:.3} %", 100.0 * relative);
    // Not vacuous: a plausible size for l1 = 210, l2 = 270 (between a tenth and all of the
    // annulus both chains reach).
    assert!(fine > 100_000.0 && fine < std::f64::consts::PI * 480.0 * 480.0, "{fine}");
}

#[test]
fn the_rectangle_is_reachable_and_maximal_on_the_grid() {
    for robot in [
        Robot::default(),
        Robot::from_json(include_str!("../../../../data/robots/asymmetric.json")).unwrap(),
    ] {
        let model = Kinematics::new(&robot).unwrap();
        let workspace = Workspace::compute(&model, 2.0).unwrap();
        let rectangle = workspace.largest_rectangle().unwrap();
        assert!(rectangle.width() > 0.0 && rectangle.height() > 0.0);
        // Every corner reachable, by the grid and by an independent call.
        for x in [rectangle.min[0], rectangle.max[0]] {
            for y in [rectangle.min[1], rectangle.max[1]] {
                assert!(model.reachable(x, y), "corner ({x}, {y}) of {rectangle:?}");
            }
        }
        // Every grid point inside reachable.
        let (i0, j0) = workspace.index_of(rectangle.min[0], rectangle.min[1]).unwrap();
        let (i1, j1) = workspace.index_of(rectangle.max[0], rectangle.max[1]).unwrap();
        for j in j0..=j1 {
            for i in i0..=i1 {
                assert!(workspace.is_reachable(i, j), "({i}, {j}) inside {rectangle:?}");
            }
        }
        // It cannot grow by one step on any side: each side's next row or column has an
        // unreachable point.
        let column_blocked =
            |i: Option<usize>| i.is_none_or(|i| (j0..=j1).any(|j| !workspace.is_reachable(i, j)));
        let row_blocked =
            |j: Option<usize>| j.is_none_or(|j| (i0..=i1).any(|i| !workspace.is_reachable(i, j)));
        assert!(column_blocked(i0.checked_sub(1)), "can grow left: {rectangle:?}");
        assert!(column_blocked(Some(i1 + 1)), "can grow right: {rectangle:?}");
        assert!(row_blocked(j0.checked_sub(1)), "can grow down: {rectangle:?}");
        assert!(row_blocked(Some(j1 + 1)), "can grow up: {rectangle:?}");
    }
}

#[test]
fn default_robot_figures() {
    // The figures README quotes; a change in the kinematics or the grid shows here.
    let workspace = Workspace::compute(&default_model(), 2.0).unwrap();
    let rectangle = workspace.largest_rectangle().unwrap();
    assert_eq!(workspace.area_mm2(), 311_844.0);
    assert_eq!((rectangle.min, rectangle.max), ([-232.0, 136.0], [232.0, 346.0]));
}

#[test]
fn bad_steps_are_refused() {
    let model = default_model();
    for step in [0.0, -1.0, f64::NAN, f64::INFINITY, 0.01, 1000.0] {
        let err = Workspace::compute(&model, step).unwrap_err();
        assert!(err.to_string().contains("grid step"), "{err}");
    }
}
