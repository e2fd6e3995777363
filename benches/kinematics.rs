//! IK and FK throughput over 1 M random reachable poses, against a hand-written scalar loop of
//! the same formulas (docs/performance.md: IK within 1.5× of it).
//!
//! Run: `cargo bench --bench kinematics`. Figures are ns per pose (criterion reports the time of
//! one pass over 1 M poses; divide by 1e6, or read the "thrpt" line in Melem/s).
//!
//! Measured 2026-11-22 on the 2-core development machine (Intel Xeon, x86_64, rustc 1.95,
//! release profile), per pose: reference scalar IK 71.8 ns, `inverse` 79.6 ns (1.11×),
//! `inverse_checked` 108.4 ns, `forward` 95.2 ns.
//!
//! Measured 2026-11-26 on the 2-core development machine of that day (AMD EPYC, AVX2 and
//! AVX-512, shared with other builds), per pose: reference 83.8 ns, `inverse` 77.0 ns,
//! `inverse_checked` 91.3 ns, the batch path (`inverse_batch`, the same checks) 23.0 ns with
//! run-time dispatch (x86-64-v3) and 42.2 ns forced portable, `forward` 81.7 ns.
//!
//! Measured 2026-11-27, same machine kind, at a load of about 2: reference 82.6 ns, `inverse`
//! 73.0 ns, `inverse_checked` 82.5 ns, the batch path (now the scalar path's bits, AVX-512)
//! 16.9 ns through `inverse_batch` and 15.5 ns through `inverse_columns` (52.0 and 44.8 ns
//! forced portable), `forward` 81.2 ns. docs/performance.md quotes these.
//!
//! Measured 2026-11-27 later, the solutions black-boxed instead of summed after each call, at
//! a load of 0.4–0.9: reference 90.1 ns, `inverse` 78.8 ns, `inverse_checked` 85.7 ns, the
//! batch path 15.3 ns through `inverse_batch` and 14.7 ns through `inverse_columns` (48.4 and
//! 47.5 ns forced portable), `forward` 84.9 ns.
//!
//! Measured 2026-11-27 after `inverse_batch`'s status codes became bits (no f64 → u8
//! conversion) and its write-back lost its branch per pose, at a load of 2.3–3: 14.7 and
//! 14.9 ns through `inverse_batch`, 13.7 and 15.3 ns through `inverse_columns` (main's binary,
//! interleaved: 15.2 and 14.7 ns, 14.2 and 13.9 ns). docs/performance.md has the runs.

#![allow(missing_docs)]

use std::f64::consts::PI;
use std::hint::black_box;

use biscara::kinematics::{
    BatchSolution, BatchStatus, Dispatch, Joints, Kinematics, Pose, PoseColumns, SolutionColumns,
};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};

const POSES: usize = 1_000_000;

/// xorshift64*: a tiny deterministic generator, so every run solves the same poses.
struct Rng(u64);

impl Rng {
    fn next_unit(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let bits = self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11;
        bits as f64 / (1u64 << 53) as f64
    }
}

/// 1 M poses the default robot can take (reachable, in its modes and limits, off singularities).
fn reachable_poses(model: &Kinematics) -> Vec<Pose> {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let mut poses = Vec::with_capacity(POSES);
    while poses.len() < POSES {
        let pose = Pose::from_degrees(
            -400.0 + 800.0 * rng.next_unit(),
            100.0 + 400.0 * rng.next_unit(),
            100.0 * rng.next_unit(),
            -90.0 + 180.0 * rng.next_unit(),
        );
        if model.inverse_checked(&pose).is_ok() {
            poses.push(pose);
        }
    }
    poses
}

/// The reference: docs/kinematics.md's inverse formulas as one plain scalar function, no types, no checks
/// beyond the reach test, with the same `atan2` (libm's) as the library. Default robot, working
/// mode "+-".
#[inline(never)]
fn reference_ik(x: f64, y: f64, z: f64, phi: f64, psi1_home: f64) -> Option<[f64; 4]> {
    const L1: f64 = 210.0;
    const L2: f64 = 270.0;
    let chain = |bx: f64, sigma: f64| -> Option<(f64, f64, f64)> {
        let b = x - bx;
        let a = -y;
        let r2 = b * b + y * y;
        let c = (L2 * L2 - L1 * L1 - r2) / (2.0 * L1);
        let disc = r2 - c * c;
        if disc < 0.0 {
            return None;
        }
        let root = sigma * disc.sqrt();
        let (ct, st) = (a * c - b * root, b * c + a * root);
        let scale = L1 / r2;
        Some((libm::atan2(st, ct), bx - scale * st, scale * ct))
    };
    let (theta1, ex, ey) = chain(100.0, 1.0)?;
    let (theta2, _, _) = chain(-100.0, -1.0)?;
    let mut rotation = libm::atan2(y - ey, x - ex) - psi1_home;
    if rotation > PI {
        rotation -= 2.0 * PI;
    } else if rotation <= -PI {
        rotation += 2.0 * PI;
    }
    Some([theta1, theta2, phi - rotation, 100.0 - z])
}

fn kinematics(c: &mut Criterion) {
    let model = Kinematics::default();
    let poses = reachable_poses(&model);
    let joints: Vec<Joints> = poses
        .iter()
        .map(|pose| model.inverse(pose).map(|ik| ik.joints).unwrap_or_default())
        .collect();
    let psi1_home = model.distal_home(biscara::kinematics::Chain::One);

    let mut group = c.benchmark_group("kinematics_1M_poses");
    group.throughput(Throughput::Elements(POSES as u64));
    group.sample_size(20);
    group.bench_function("reference_scalar_ik", |b| {
        b.iter(|| {
            let mut sum = 0.0;
            for pose in &poses {
                let pose = black_box(pose);
                if let Some(q) = reference_ik(pose.x, pose.y, pose.z, pose.phi, psi1_home) {
                    sum += q[0] + q[1] + q[2] + q[3];
                }
            }
            sum
        });
    });
    group.bench_function("ik_inverse", |b| {
        b.iter(|| {
            let mut sum = 0.0;
            for pose in &poses {
                if let Ok(ik) = model.inverse(black_box(pose)) {
                    let q = ik.joints;
                    sum += q.theta1 + q.theta2 + q.theta3 + q.d4;
                }
            }
            sum
        });
    });
    group.bench_function("ik_inverse_checked", |b| {
        b.iter(|| {
            let mut sum = 0.0;
            for pose in &poses {
                if let Ok(ik) = model.inverse_checked(black_box(pose)) {
                    let q = ik.joints;
                    sum += q.theta1 + q.theta2 + q.theta3 + q.d4;
                }
            }
            sum
        });
    });
    // The batch path (IK + assembly, limit and singularity checks, as `inverse_checked`), once
    // with the CPU detected at run time and once forced to the portable build. The solutions
    // go to `black_box` (until 2026-11-27 they were summed after each call: a chain of 1 M
    // dependent additions, about 1 ns a pose on top of the call).
    let mut solved = vec![BatchSolution::default(); POSES];
    for (name, dispatch) in [
        ("ik_batch_checked_dispatch", Dispatch::Detect),
        ("ik_batch_checked_portable", Dispatch::Portable),
    ] {
        group.bench_function(name, |b| {
            b.iter(|| {
                model.inverse_batch_with(dispatch, black_box(&poses), &mut solved);
                black_box(&mut solved);
            });
        });
    }
    // The same, the poses given and the solutions written as columns (no gathering into lanes).
    let column = |f: fn(&Pose) -> f64| poses.iter().map(f).collect::<Vec<f64>>();
    let (xs, ys, zs, phis) = (column(|p| p.x), column(|p| p.y), column(|p| p.z), column(|p| p.phi));
    let mut q = [(); 5].map(|()| vec![0.0; POSES]);
    let mut status = vec![BatchStatus::Ok; POSES];
    for (name, dispatch) in [
        ("ik_columns_checked_dispatch", Dispatch::Detect),
        ("ik_columns_checked_portable", Dispatch::Portable),
    ] {
        group.bench_function(name, |b| {
            b.iter(|| {
                model.inverse_columns_with(
                    dispatch,
                    PoseColumns { x: black_box(&xs), y: &ys, z: &zs, phi: &phis },
                    SolutionColumns::new(&mut q, &mut status),
                );
                black_box(&mut q);
            });
        });
    }
    group.bench_function("fk_forward", |b| {
        b.iter(|| {
            let mut sum = 0.0;
            for q in &joints {
                if let Ok(fk) = model.forward(black_box(q)) {
                    sum += fk.pose.x + fk.pose.y + fk.pose.z + fk.pose.phi;
                }
            }
            sum
        });
    });
    group.finish();
}

criterion_group!(benches, kinematics);
criterion_main!(benches);
