//! Area, largest rectangle and GCI of random designs, against a brute-force scalar evaluation
//! written here: its own grid, the scalar IK test of each point (`Kinematics::reachable`, with
//! libm's atan2), every rectangle of the grid tried, and cond(J) from nalgebra's SVD.

use biscara_design::{Design, DesignStatus, Evaluator};
use biscara_kinematics::{Kinematics, PlanarJacobian, Robot};

/// xorshift64*, so every run draws the same designs.
struct Rng(u64);

impl Rng {
    fn unit(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
    }
}

struct Grid {
    i0: i64,
    j0: i64,
    columns: usize,
    rows: usize,
    cells: Vec<bool>,
}

/// The reachable grid over a box that surely holds the workspace.
fn brute_grid(model: &Kinematics, step: f64) -> Grid {
    let reach = model.l1() + model.l2() + model.bases()[0].x.abs() + step;
    let (i0, j0) = ((-reach / step).floor() as i64, (-reach / step).floor() as i64);
    let n = (2.0 * reach / step).ceil() as usize + 1;
    let mut cells = Vec::with_capacity(n * n);
    for j in 0..n {
        for i in 0..n {
            let (x, y) = ((i0 + i as i64) as f64 * step, (j0 + j as i64) as f64 * step);
            cells.push(model.reachable(x, y));
        }
    }
    Grid { i0, j0, columns: n, rows: n, cells }
}

/// The largest (columns − 1)·(rows − 1) of a block of reachable cells, trying every block
/// (prefix sums count a block's reachable cells).
fn brute_rectangle(grid: &Grid) -> usize {
    let (c, r) = (grid.columns, grid.rows);
    let mut sum = vec![0usize; (c + 1) * (r + 1)];
    for j in 0..r {
        for i in 0..c {
            sum[(j + 1) * (c + 1) + i + 1] = usize::from(grid.cells[j * c + i])
                + sum[j * (c + 1) + i + 1]
                + sum[(j + 1) * (c + 1) + i]
                - sum[j * (c + 1) + i];
        }
    }
    let count = |i0: usize, j0: usize, i1: usize, j1: usize| {
        sum[(j1 + 1) * (c + 1) + i1 + 1] + sum[j0 * (c + 1) + i0]
            - sum[j0 * (c + 1) + i1 + 1]
            - sum[(j1 + 1) * (c + 1) + i0]
    };
    let rows_used: Vec<usize> = (0..r).filter(|&j| (0..c).any(|i| grid.cells[j * c + i])).collect();
    let (Some(&first), Some(&last)) = (rows_used.first(), rows_used.last()) else { return 0 };
    let mut best = 0;
    for j0 in first..=last {
        for j1 in j0 + 1..=last {
            for i0 in 0..c {
                if !grid.cells[j0 * c + i0] {
                    continue;
                }
                for i1 in i0 + 1..c {
                    if count(i0, j0, i1, j1) != (i1 - i0 + 1) * (j1 - j0 + 1) {
                        break;
                    }
                    best = best.max((i1 - i0) * (j1 - j0));
                }
            }
        }
    }
    best
}

#[test]
fn random_designs_agree_with_a_brute_force_evaluation() {
    let mut rng = Rng(0x5eed_0000_2929);
    let step = 20.0;
    let evaluator = Evaluator::new(Robot::default(), step, None).expect("evaluator");
    let mut with_rectangle = 0;
    for index in 0..30 {
        let design = Design {
            index,
            l1: 120.0 + 180.0 * rng.unit(),
            l2: 150.0 + 200.0 * rng.unit(),
            base: 40.0 + 300.0 * rng.unit(),
        };
        let evaluation = evaluator.evaluate(design);
        let Ok(model) = Kinematics::new(&evaluator.robot_of(&design)) else {
            assert_eq!(evaluation.status, DesignStatus::Invalid, "{design:?}");
            continue;
        };
        let grid = brute_grid(&model, step);
        let count = grid.cells.iter().filter(|&&c| c).count();
        assert_eq!(evaluation.area_mm2, count as f64 * step * step, "{design:?}");
        let best = brute_rectangle(&grid);
        let Some(rectangle) = evaluation.rectangle else {
            assert_eq!(best, 0, "{design:?}: the brute force finds a rectangle");
            continue;
        };
        with_rectangle += 1;
        let cells = (rectangle.width() / step).round() * (rectangle.height() / step).round();
        assert_eq!(cells as usize, best, "{design:?}: {rectangle:?}");
        // Every grid point of the rectangle reachable, and the GCI and worst LCI by SVD.
        let (mut sum, mut worst, mut n) = (0.0, f64::INFINITY, 0.0);
        let to_index = |v: f64| (v / step).round() as i64;
        for j in to_index(rectangle.min[1])..=to_index(rectangle.max[1]) {
            for i in to_index(rectangle.min[0])..=to_index(rectangle.max[0]) {
                let (gi, gj) = ((i - grid.i0) as usize, (j - grid.j0) as usize);
                assert!(grid.cells[gj * grid.columns + gi], "{design:?}: ({i}, {j}) unreachable");
                let (x, y) = (i as f64 * step, j as f64 * step);
                let configuration = model.configuration(x, y).expect("reachable");
                let lci = 1.0 / PlanarJacobian::new(&configuration).condition_number();
                sum += lci;
                worst = f64::min(worst, lci);
                n += 1.0;
            }
        }
        assert!(
            (evaluation.gci - sum / n).abs() < 1e-9,
            "{design:?}: GCI {} vs {}",
            evaluation.gci,
            sum / n
        );
        assert!((evaluation.lci_min - worst).abs() < 1e-9, "{design:?}: worst LCI");
        let _ = grid.rows;
    }
    assert!(with_rectangle >= 15, "only {with_rectangle} designs had a rectangle");
}
