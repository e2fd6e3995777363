//! A small driver for the batch IK: `cargo run --release -p biscara-kinematics --example
//! batch_driver -- [batch|columns] [PASSES] [POSES]` solves POSES (default 1 M) reachable poses
//! PASSES times through `inverse_batch` or `inverse_columns` and prints the best pass in ns per
//! pose. Under `valgrind --tool=callgrind` with 1 pass it counts the instructions of the call.

#![allow(missing_docs, clippy::print_stdout)]

use std::hint::black_box;
use std::time::Instant;

use biscara_kinematics::{
    BatchSolution, BatchStatus, Kinematics, Pose, PoseColumns, SolutionColumns,
};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let which = args.get(1).map_or("batch", String::as_str).to_owned();
    let passes: usize = args.get(2).map_or(20, |a| a.parse().expect("PASSES"));
    let count: usize = args.get(3).map_or(1_000_000, |a| a.parse().expect("POSES"));
    let model = Kinematics::default();
    // The benchmark's generator (xorshift64*) and region.
    let mut state = 0x9e37_79b9_7f4a_7c15_u64;
    let mut unit = || {
        state ^= state >> 12;
        state ^= state << 25;
        state ^= state >> 27;
        (state.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut poses = Vec::with_capacity(count);
    while poses.len() < count {
        let pose = Pose::from_degrees(
            -400.0 + 800.0 * unit(),
            100.0 + 400.0 * unit(),
            100.0 * unit(),
            -90.0 + 180.0 * unit(),
        );
        if model.inverse_checked(&pose).is_ok() {
            poses.push(pose);
        }
    }
    let mut best = f64::INFINITY;
    if which == "columns" {
        let column = |f: fn(&Pose) -> f64| poses.iter().map(f).collect::<Vec<f64>>();
        let (xs, ys, zs, phis) =
            (column(|p| p.x), column(|p| p.y), column(|p| p.z), column(|p| p.phi));
        let mut q = [(); 5].map(|()| vec![0.0; count]);
        let mut status = vec![BatchStatus::Ok; count];
        for _ in 0..passes {
            let start = Instant::now();
            model.inverse_columns(
                PoseColumns { x: black_box(&xs), y: &ys, z: &zs, phi: &phis },
                SolutionColumns::new(&mut q, &mut status),
            );
            black_box(&mut q);
            best = best.min(start.elapsed().as_secs_f64());
        }
    } else {
        let mut out = vec![BatchSolution::default(); count];
        for _ in 0..passes {
            let start = Instant::now();
            model.inverse_batch(black_box(&poses), &mut out);
            black_box(&mut out);
            best = best.min(start.elapsed().as_secs_f64());
        }
    }
    println!("{which}: best of {passes} passes {:.2} ns per pose", best * 1e9 / count as f64);
}
