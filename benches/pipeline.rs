//! The `joints` pipeline stage by stage, on one core (docs/performance.md: 5 M samples/s end to end):
//! interpreting G-code, interpolating, IK (joint trajectory) and formatting the CSV, each timed
//! on its own over the same generated program, and the whole chain into `io::sink()`.
//!
//! Run: `cargo bench --bench pipeline`. Throughput lines read in samples/s (elements) except
//! `interpret`, which reads in bytes/s of G-code.
//!
//! Measured 2026-11-22 on the 2-core development machine (Intel Xeon, x86_64, rustc 1.95), see
//! the README's performance table for the figures.

#![allow(missing_docs)]

use std::convert::Infallible;
use std::hint::black_box;
use std::io;

use biscara::gcode::{Config, interpret};
use biscara::interpolate::{
    CartesianSample, InterpolationConfig, Interpolator, NoSpeedLimit, Profile, SlowDown,
};
use biscara::joints::{
    AngleUnit, JointCsvFormat, JointCsvWriter, JointSample, JointSpeedLimit, JointTrajectory,
    cartesian_limits,
};
use biscara::kinematics::{Kinematics, Robot};
use biscara::motion::Motion;
use biscara::pipeline::{Pipeline, ProgramKind, RobotModel, SamplingConfig, TextSource};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};

/// Lines of the generated program (the same shape as `scripts/gen-program.sh`).
const LINES: usize = 20_000;

fn program() -> String {
    let mut text = String::from("%\nG21 G17 G90 G94\nG0 X-100 Y300 Z50 C0\n");
    for i in 0..LINES {
        let (col, row) = (i % 200, (i / 200) % 100);
        let x = if row % 2 == 0 { -100.0 + col as f64 } else { 99.0 - col as f64 };
        text.push_str(&format!(
            "G1 X{x:.3} Y{:.3} C{:.3} F6000\n",
            300.0 + row as f64,
            (i % 90) as f64 - 45.0
        ));
    }
    text.push_str("M2\n%\n");
    text
}

fn interpolation_config(robot: &Robot, model: &Kinematics) -> InterpolationConfig {
    InterpolationConfig {
        dt: 0.001,
        profile: Profile::Trapezoid,
        start: model.home().to_degrees(),
        limits: cartesian_limits(robot),
        grip_time: 0.0,
    }
}

fn pipeline(c: &mut Criterion) {
    let robot = Robot::default();
    let model = Kinematics::new(&robot).expect("default robot");
    let text = program();
    let gcode_config = Config { home: model.home().to_degrees(), ..Config::default() };
    let motions: Vec<Motion> = interpret(text.as_bytes(), &gcode_config)
        .collect::<Result<_, _>>()
        .expect("the benchmark program interprets");
    let config = interpolation_config(&robot, &model);
    let samples: Vec<CartesianSample> = Interpolator::new(
        motions.iter().map(|m| Ok::<_, Infallible>(*m)),
        config,
        JointSpeedLimit::new(model, &robot),
        |_: &SlowDown| {},
    )
    .collect::<Result<_, _>>()
    .expect("interpolation");
    let rows: Vec<JointSample> =
        JointTrajectory::new(samples.iter().map(|s| Ok::<_, Infallible>(*s)), model)
            .collect::<Result<_, _>>()
            .expect("joint trajectory");
    let format =
        JointCsvFormat { angle_unit: AngleUnit::Radians, derivatives: false, precision: 6 };

    let mut group = c.benchmark_group("joints_pipeline");
    group.sample_size(10);

    group.throughput(Throughput::Bytes(text.len() as u64));
    group.bench_function("interpret_gcode", |b| {
        b.iter(|| interpret(black_box(text.as_bytes()), &gcode_config).count())
    });

    group.throughput(Throughput::Elements(samples.len() as u64));
    group.bench_function("interpolate_no_joint_limit", |b| {
        b.iter(|| {
            Interpolator::new(
                motions.iter().map(|m| Ok::<_, Infallible>(*m)),
                config,
                NoSpeedLimit,
                |_: &SlowDown| {},
            )
            .count()
        })
    });
    group.bench_function("interpolate_with_joint_speed_limit", |b| {
        b.iter(|| {
            Interpolator::new(
                motions.iter().map(|m| Ok::<_, Infallible>(*m)),
                config,
                JointSpeedLimit::new(model, &robot),
                |_: &SlowDown| {},
            )
            .count()
        })
    });
    group.bench_function("ik_joint_trajectory", |b| {
        b.iter(|| {
            JointTrajectory::new(samples.iter().map(|s| Ok::<_, Infallible>(*black_box(s))), model)
                .count()
        })
    });
    group.bench_function("format_joint_csv", |b| {
        b.iter(|| {
            let mut writer = JointCsvWriter::new(io::sink(), format).expect("sink");
            for row in &rows {
                writer.write(black_box(row)).expect("sink");
            }
            writer.finish().expect("sink");
        })
    });
    // The whole chain as the `joints` command runs it: through the pipeline library.
    let robot_model = RobotModel::default();
    let pipeline = Pipeline::new(&robot_model, SamplingConfig::default());
    let source = TextSource::new("bench.ngc", text.clone());
    group.bench_function("end_to_end_gcode_to_csv", |b| {
        b.iter(|| {
            pipeline
                .write_joint_csv(
                    &source,
                    ProgramKind::Gcode,
                    &mut io::sink(),
                    format,
                    false,
                    |_| {},
                )
                .expect("reachable");
        })
    });
    group.finish();
}

criterion_group!(benches, pipeline);
criterion_main!(benches);
