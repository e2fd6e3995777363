//! `interpret` throughput (the goal, docs/performance.md: at least 50 MB/s of G-code on one
//! core) on a generated 1,000,000-line program of mixed G0/G1/G2/G3 moves, with parameters and an
//! expression every few lines, interpreted into motions (no output formatting).
//!
//! Run: `cargo bench -p biscara-gcode --bench interpret`; criterion's "thrpt" line gives MiB/s
//! of G-code; lines/s = 1e6 / time.
//!
//! Measured 2026-11-22 on the 2-core development machine (x86_64, rustc 1.95, release profile,
//! load 3.5–6 from other builds): 205–215 ms per pass over the 1,000,000 lines (23.8 MB), i.e.
//! 106–110 MiB/s (111–116 MB/s) and 4.7–4.9 M lines/s. End to end, `biscara interpret` writing
//! the inter-file takes 0.47–0.49 s on the same program (49–51 MB/s, 2.1 M lines/s, peak RSS
//! 4.6 MiB): the JSON writer's float formatting is then the larger half.
//!
//! 2026-11-23, with the dialects (docs/gcode.md) in, `linuxcnc` dialect: wall time could not be
//! compared (load 8 on 2 cores: passes of 0.5–1.5 s for both builds, interleaved), so the
//! interpreter's instructions were counted with callgrind on this program, one pass, the
//! program's generation subtracted: 2,913 M before, 2,986 M after (+2.5 %).

#![allow(missing_docs)]

use std::fmt::Write;
use std::hint::black_box;

use biscara_gcode::{Config, interpret};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};

const LINES: usize = 1_000_000;

/// The benchmark program: feed moves, arcs in both directions and both forms, rapids with C.
fn program() -> String {
    let mut text = String::with_capacity(LINES * 24);
    text.push_str("%\nG21 G17 G90 G94\nG0 X0 Y300 Z50 C0\nF3000\n");
    let (mut px, mut py) = (0.0_f64, 300.0_f64);
    for i in 0..LINES - 6 {
        let x = (i % 200) as f64 * 0.5 - 50.0;
        let y = 300.0 + (i / 200 % 100) as f64 * 0.5;
        let _ = match i % 8 {
            0 | 4 | 7 => {
                (px, py) = (x, y);
                if i % 8 == 7 {
                    writeln!(text, "G1 X{x:.3} Y{y:.3} Z[#<_z> - 1]")
                } else {
                    writeln!(text, "G1 X{x:.3} Y{y:.3}")
                }
            }
            1 => {
                px += 0.5;
                writeln!(text, "G2 X{px:.3} Y{py:.3} I0.25 J0")
            }
            2 => {
                px -= 0.5;
                writeln!(text, "G3 X{px:.3} Y{py:.3} R0.25")
            }
            3 => writeln!(text, "G0 Z{:.3} C{:.1}", 40.0 + (i % 10) as f64, (i % 90) as f64),
            5 => writeln!(text, "G1 Z30.000 F[2000 + #1]"),
            _ => writeln!(text, "#1=[#1 + 1 MOD 100]"),
        };
    }
    text.push_str("M2\n%\n");
    text
}

fn bench(c: &mut Criterion) {
    let text = program();
    let config = Config::default();
    let motions = interpret(text.as_bytes(), &config).filter(Result::is_ok).count();
    assert!(motions > LINES / 2, "the benchmark program interprets ({motions} motions)");
    let mut group = c.benchmark_group("interpret");
    group.sample_size(10);
    group.throughput(Throughput::Bytes(text.len() as u64));
    group.bench_function("mixed_1M_lines", |b| {
        b.iter(|| interpret(black_box(text.as_bytes()), &config).count())
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
