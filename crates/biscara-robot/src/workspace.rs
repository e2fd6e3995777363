//! The reachable region in the XY plane (docs/virtual-robot.md) and the largest rectangle inside
//! it.

use biscara_kinematics::Kinematics;

use crate::VirtualRobotError;

/// Smallest grid step accepted, millimetres.
pub const MIN_STEP_MM: f64 = 0.1;
/// Largest grid step accepted, millimetres.
pub const MAX_STEP_MM: f64 = 100.0;

/// The workspace as a grid of points at multiples of `step` in X and Y, each reachable or not.
#[derive(Debug, Clone, PartialEq)]
pub struct Workspace {
    step: f64,
    /// Grid index of the first column and row: point (i, j) is at `((i0 + i)·step, (j0 + j)·step)`.
    i0: i64,
    j0: i64,
    columns: usize,
    rows: usize,
    /// Row-major, row 0 at the smallest y.
    reachable: Vec<bool>,
}

/// An axis-aligned rectangle of the grid: corners on grid points, every grid point inside it
/// (edges included) reachable.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rectangle {
    /// The corner with the smallest x and y, millimetres.
    pub min: [f64; 2],
    /// The corner with the largest x and y, millimetres.
    pub max: [f64; 2],
}

impl Rectangle {
    /// Width (X), millimetres.
    pub fn width(&self) -> f64 {
        self.max[0] - self.min[0]
    }

    /// Height (Y), millimetres.
    pub fn height(&self) -> f64 {
        self.max[1] - self.min[1]
    }

    /// The centre, millimetres.
    pub fn center(&self) -> [f64; 2] {
        [0.5 * (self.min[0] + self.max[0]), 0.5 * (self.min[1] + self.max[1])]
    }
}

impl Workspace {
    /// Fails with [`VirtualRobotError::Step`] unless `step` (mm) lies in
    /// [[`MIN_STEP_MM`], [`MAX_STEP_MM`]]: the grid steps a workspace is computed at.
    pub fn check_step(step: f64) -> Result<(), VirtualRobotError> {
        if (MIN_STEP_MM..=MAX_STEP_MM).contains(&step) {
            Ok(())
        } else {
            Err(VirtualRobotError::Step { step_mm: step, min_mm: MIN_STEP_MM, max_mm: MAX_STEP_MM })
        }
    }

    /// The workspace of `model` on a grid of `step` millimetres covering everything the chains
    /// can reach (each chain reaches at most `l1 + l2` from its base joint).
    pub fn compute(model: &Kinematics, step: f64) -> Result<Workspace, VirtualRobotError> {
        Workspace::check_step(step)?;
        let reach = model.l1() + model.l2();
        let [b1, b2] = model.bases();
        let index = |value: f64, up: bool| {
            let scaled = value / step;
            (if up { scaled.ceil() } else { scaled.floor() }) as i64
        };
        let (i0, i1) = (index(b2.x.min(b1.x) - reach, false), index(b1.x.max(b2.x) + reach, true));
        let (j0, j1) = (index(-reach, false), index(reach, true));
        let columns = usize::try_from(i1 - i0 + 1).unwrap_or(0);
        let rows = usize::try_from(j1 - j0 + 1).unwrap_or(0);
        // Row by row through the batch solver (vectorised; the same verdicts as `reachable`),
        // over the columns both chains can reach: a point farther than l1 + l2 from a base
        // joint has no IK solution, so the span where the two discs of that radius overlap,
        // widened by a step against rounding, holds every reachable point of the row.
        let xs: Vec<f64> = (0..columns).map(|i| (i0 + i as i64) as f64 * step).collect();
        let mut ys = vec![0.0; columns];
        let mut reachable = vec![false; columns * rows];
        for (j, row) in reachable.chunks_exact_mut(columns.max(1)).enumerate() {
            let y = (j0 + j as i64) as f64 * step;
            let half = (reach * reach - y * y).sqrt();
            if half.is_nan() {
                continue;
            }
            let low = b1.x.max(b2.x) - half - step;
            let high = b1.x.min(b2.x) + half + step;
            let first = xs.partition_point(|&x| x < low);
            let last = xs.partition_point(|&x| x <= high);
            if first >= last {
                continue;
            }
            ys[first..last].fill(y);
            model.reachable_batch(&xs[first..last], &ys[first..last], &mut row[first..last]);
        }
        Ok(Workspace { step, i0, j0, columns, rows, reachable })
    }

    /// The grid step, millimetres.
    pub fn step(&self) -> f64 {
        self.step
    }

    /// Number of grid columns (X) and rows (Y).
    pub fn size(&self) -> (usize, usize) {
        (self.columns, self.rows)
    }

    /// The position of grid point `(i, j)`, millimetres.
    pub fn point(&self, i: usize, j: usize) -> [f64; 2] {
        [(self.i0 + i as i64) as f64 * self.step, (self.j0 + j as i64) as f64 * self.step]
    }

    /// Whether grid point `(i, j)` is reachable (false outside the grid).
    pub fn is_reachable(&self, i: usize, j: usize) -> bool {
        i < self.columns && j < self.rows && self.reachable[j * self.columns + i]
    }

    /// The grid indices of the point at `(x, y)` when it lies on the grid.
    pub fn index_of(&self, x: f64, y: f64) -> Option<(usize, usize)> {
        let i = (x / self.step).round() as i64 - self.i0;
        let j = (y / self.step).round() as i64 - self.j0;
        let (i, j) = (usize::try_from(i).ok()?, usize::try_from(j).ok()?);
        (i < self.columns && j < self.rows).then_some((i, j))
    }

    /// Number of reachable grid points.
    pub fn count(&self) -> usize {
        self.reachable.iter().filter(|&&r| r).count()
    }

    /// The reachable area, mm²: each reachable point stands for one `step × step` cell.
    pub fn area_mm2(&self) -> f64 {
        self.count() as f64 * self.step * self.step
    }

    /// The runs of reachable points of row `j`: `(first column, last column)` inclusive.
    pub fn runs(&self, j: usize) -> Vec<(usize, usize)> {
        let mut runs = Vec::new();
        let mut start = None;
        for i in 0..=self.columns {
            match (self.is_reachable(i, j), start) {
                (true, None) => start = Some(i),
                (false, Some(first)) => {
                    runs.push((first, i - 1));
                    start = None;
                }
                _ => {}
            }
        }
        runs
    }

    /// The largest axis-aligned rectangle whose corners are grid points and whose grid points
    /// are all reachable, by area `(columns − 1)·(rows − 1)·step²`: exact on the grid (the
    /// maximal-rectangle algorithm over row histograms, O(columns·rows)). Ties go to the first
    /// found (lowest top row, then leftmost). Fails when no two-by-two block is reachable.
    pub fn largest_rectangle(&self) -> Result<Rectangle, VirtualRobotError> {
        let empty = VirtualRobotError::EmptyWorkspace { step_mm: self.step };
        // Only the rows and columns that hold a reachable point: the same blocks, less to scan.
        let used_rows: Vec<usize> = (0..self.rows)
            .filter(|&j| self.reachable[j * self.columns..(j + 1) * self.columns].contains(&true))
            .collect();
        let (Some(&top), Some(&bottom)) = (used_rows.first(), used_rows.last()) else {
            return Err(empty);
        };
        let mut left = self.columns;
        let mut right = 0;
        for j in top..=bottom {
            let row = &self.reachable[j * self.columns..(j + 1) * self.columns];
            if let (Some(first), Some(last)) =
                (row.iter().position(|&r| r), row.iter().rposition(|&r| r))
            {
                left = left.min(first);
                right = right.max(last);
            }
        }
        let columns = right + 1 - left;
        let cells: Vec<bool> = (top..=bottom)
            .flat_map(|j| &self.reachable[j * self.columns + left..=j * self.columns + right])
            .copied()
            .collect();
        let (i, j, w, h) = largest_block(&cells, columns, bottom + 1 - top).ok_or(empty)?;
        let (i, j) = (i + left, j + top);
        let min = self.point(i, j);
        let max = self.point(i + w - 1, j + h - 1);
        Ok(Rectangle { min, max })
    }
}

/// The block of `true` cells (`i`, `j`, width, height) maximising `(width − 1)·(height − 1)`,
/// among blocks at least 2 × 2. For each row the heights of the `true` runs ending there form a
/// histogram; a stack finds, for every bar, the widest span of bars at least as high. Every
/// maximal block is found that way, and the objective grows with width and height, so the best
/// block is among them.
fn largest_block(
    cells: &[bool],
    columns: usize,
    rows: usize,
) -> Option<(usize, usize, usize, usize)> {
    let mut heights = vec![0usize; columns];
    let mut best: Option<(usize, (usize, usize, usize, usize))> = None;
    let mut stack: Vec<usize> = Vec::with_capacity(columns + 1);
    for top in 0..rows {
        for i in 0..columns {
            heights[i] = if cells[top * columns + i] { heights[i] + 1 } else { 0 };
        }
        stack.clear();
        for i in 0..=columns {
            let current = if i < columns { heights[i] } else { 0 };
            while let Some(&last) = stack.last() {
                if heights[last] < current {
                    break;
                }
                stack.pop();
                let height = heights[last];
                let left = stack.last().map_or(0, |&k| k + 1);
                let width = i - left;
                if height >= 2 && width >= 2 {
                    let area = (width - 1) * (height - 1);
                    if best.is_none_or(|(value, _)| area > value) {
                        best = Some((area, (left, top + 1 - height, width, height)));
                    }
                }
            }
            stack.push(i);
        }
    }
    best.map(|(_, block)| block)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The best block by brute force over every block.
    fn brute_force(cells: &[bool], columns: usize, rows: usize) -> usize {
        let mut best = 0;
        for j0 in 0..rows {
            for i0 in 0..columns {
                for j1 in j0 + 1..rows {
                    for i1 in i0 + 1..columns {
                        let full = (j0..=j1).all(|j| (i0..=i1).all(|i| cells[j * columns + i]));
                        if full {
                            best = best.max((i1 - i0) * (j1 - j0));
                        }
                    }
                }
            }
        }
        best
    }

    #[test]
    fn largest_block_matches_brute_force() {
        let mut seed = 12345u64;
        for _ in 0..200 {
            let (columns, rows) = (7, 6);
            let cells: Vec<bool> = (0..columns * rows)
                .map(|_| {
                    seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
                    (seed >> 33) % 10 < 7
                })
                .collect();
            let expected = brute_force(&cells, columns, rows);
            let found = largest_block(&cells, columns, rows);
            match found {
                None => assert_eq!(expected, 0),
                Some((i, j, w, h)) => {
                    assert_eq!((w - 1) * (h - 1), expected);
                    assert!((j..j + h).all(|r| (i..i + w).all(|c| cells[r * columns + c])));
                }
            }
        }
    }

    #[test]
    fn the_grid_agrees_with_the_scalar_test() {
        let model = Kinematics::default();
        let workspace = Workspace::compute(&model, 5.0).unwrap();
        let (columns, rows) = workspace.size();
        for j in 0..rows {
            for i in 0..columns {
                let [x, y] = workspace.point(i, j);
                assert_eq!(workspace.is_reachable(i, j), model.reachable(x, y), "({x}, {y})");
            }
        }
        assert!(workspace.count() > 1000);
    }

    #[test]
    fn home_is_reachable_and_the_base_is_not() {
        let model = Kinematics::default();
        assert!(model.reachable(0.0, 400.0));
        assert!(!model.reachable(0.0, 0.0));
        assert!(!model.reachable(0.0, 600.0));
    }
}
