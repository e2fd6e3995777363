//! Design sweeps: one workspace grid by the scalar IK path and by the batch path, and a
//! 1,000-design sweep (`biscara design`'s library), per design.
//!
//! Run: `cargo bench --bench design`. The README's *Performance* section quotes the figures as
//! ratios: batch grid against scalar grid, and sweep cost per design against one `biscara
//! workspace` run.

#![allow(missing_docs)]

use std::hint::black_box;

use biscara::design::{DesignGrid, Evaluator, ParamRange, Shard, Sweep, SweepOptions};
use biscara::kinematics::{Kinematics, Robot};
use biscara::robot::Workspace;
use criterion::{Criterion, Throughput, criterion_group, criterion_main};

/// The default robot's reachable grid at `step`, one scalar IK per point after a quick test of
/// the distance to the base joints (the path `workspace` took before the batch IK): the count of
/// reachable points.
fn scalar_grid(model: &Kinematics, step: f64) -> usize {
    let reach = model.l1() + model.l2();
    let [b1, b2] = model.bases();
    let (i0, i1) = (((b2.x - reach) / step).floor() as i64, ((b1.x + reach) / step).ceil() as i64);
    let (j0, j1) = ((-reach / step).floor() as i64, (reach / step).ceil() as i64);
    let mut count = 0;
    for j in j0..=j1 {
        for i in i0..=i1 {
            let (x, y) = (i as f64 * step, j as f64 * step);
            let far = |b: biscara::kinematics::na::Point2<f64>| (x - b.x).hypot(y - b.y) > reach;
            count += usize::from(!far(b1) && !far(b2) && model.reachable(x, y));
        }
    }
    count
}

fn design(c: &mut Criterion) {
    let model = Kinematics::default();
    let points = {
        let workspace = Workspace::compute(&model, 2.0).expect("workspace");
        let (columns, rows) = workspace.size();
        (columns * rows) as u64
    };
    let mut group = c.benchmark_group("workspace_grid_2mm");
    group.throughput(Throughput::Elements(points));
    group.sample_size(20);
    group.bench_function("scalar_ik_per_point", |b| b.iter(|| scalar_grid(black_box(&model), 2.0)));
    group.bench_function("batch_ik", |b| {
        b.iter(|| Workspace::compute(black_box(&model), 2.0).map(|w| w.count()))
    });
    group.finish();

    let mut group = c.benchmark_group("design_sweep");
    group.sample_size(10);
    let range = |what, text| ParamRange::parse(what, text).expect("range");
    for (name, step, grid) in [
        (
            "1000_designs_step_5mm",
            5.0,
            [
                range("--l1", "150:270:10"),
                range("--l2", "210:330:10"),
                range("--base", "100:300:10"),
            ],
        ),
        (
            "180_designs_step_2mm",
            2.0,
            [range("--l1", "170:250:6"), range("--l2", "230:310:6"), range("--base", "150:250:5")],
        ),
    ] {
        let grid = DesignGrid::new(grid[0], grid[1], grid[2]).expect("grid");
        let evaluator = Evaluator::new(Robot::default(), step, None).expect("evaluator");
        let sweep = Sweep::new(evaluator, grid, Shard::ALL);
        group.throughput(Throughput::Elements(sweep.count()));
        for threads in [1, 0] {
            let label = format!("{name}_{}", if threads == 1 { "1_thread" } else { "all_cores" });
            group.bench_function(label, |b| {
                b.iter(|| {
                    let mut sum = 0.0;
                    sweep
                        .run(
                            &SweepOptions { threads, ..SweepOptions::default() },
                            |e| -> Result<(), biscara::design::DesignError> {
                                sum += e.gci;
                                Ok(())
                            },
                        )
                        .expect("sweep");
                    sum
                });
            });
        }
    }
    group.finish();
}

criterion_group!(benches, design);
criterion_main!(benches);
