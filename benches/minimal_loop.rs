//! The minimal end-to-end loop (docs/performance.md), the reference `joints` is measured against: G-code
//! in, joint CSV out, doing the same work with no checks — read G0/G1/G2/G3 with X Y Z C I J F
//! (absolute millimetres), time every move with a trapezoid at the default robot's limits (exact
//! stop, duration rounded up to whole 1 ms steps), solve IK with the branch-free closed form of
//! `benches/kinematics.rs` (no reachability, mode, limit or singularity check), and print
//! `t_s,theta1_rad,theta2_rad,theta3_rad,d4_mm` with six fixed decimals.
//!
//! No joint-speed limit, no profile choice, no error reporting, no dialects: a lower bound on the
//! cost of the work, not a usable program. `benches/pipeline.sh` runs it beside `joints` on the
//! same generated programs.
//!
//! Run: `cargo run --release --example minimal_loop -- PROGRAM.ngc > out.csv`.

#![allow(missing_docs)]

use std::f64::consts::{PI, TAU};
use std::io::{self, BufRead, Write};

use biscara::kinematics::{Chain, Kinematics};

const DT: f64 = 0.001;
/// The default robot (`data/robots/default.json`).
const L1: f64 = 210.0;
const L2: f64 = 270.0;
const BASE: f64 = 100.0;
const LP: f64 = 100.0;
const RAPID: f64 = 500.0;
const RAPID_ROTATION: f64 = 360.0;
const ACCELERATION: f64 = 5000.0;

/// IK of the five-bar in its working mode (+, −), θ3 and d4.
#[inline(always)]
fn ik(x: f64, y: f64, z: f64, c_rad: f64, psi1_home: f64) -> [f64; 4] {
    let chain = |bx: f64, sigma: f64| {
        let b = x - bx;
        let a = -y;
        let r2 = b * b + y * y;
        let c = (L2 * L2 - L1 * L1 - r2) / (2.0 * L1);
        let root = sigma * (r2 - c * c).max(0.0).sqrt();
        let (ct, st) = (a * c - b * root, b * c + a * root);
        let scale = L1 / r2;
        (libm::atan2(st, ct), bx - scale * st, scale * ct)
    };
    let (theta1, ex, ey) = chain(BASE, 1.0);
    let (theta2, _, _) = chain(-BASE, -1.0);
    let mut rotation = libm::atan2(y - ey, x - ex) - psi1_home;
    rotation -= TAU * ((rotation + PI) / TAU).floor();
    [theta1, theta2, c_rad - rotation, LP - z]
}

/// Appends `value` with six decimals.
#[inline(always)]
fn push_fixed(out: &mut Vec<u8>, value: f64) {
    let scaled = (value * 1e6).round() as i64;
    if scaled < 0 {
        out.push(b'-');
    }
    let magnitude = scaled.unsigned_abs();
    let (whole, fraction) = (magnitude / 1_000_000, magnitude % 1_000_000);
    let mut digits = [0u8; 20];
    let mut n = 0;
    let mut rest = whole;
    loop {
        digits[n] = b'0' + (rest % 10) as u8;
        n += 1;
        rest /= 10;
        if rest == 0 {
            break;
        }
    }
    out.extend(digits[..n].iter().rev());
    out.push(b'.');
    let mut frac = [0u8; 6];
    let mut rest = fraction;
    for slot in frac.iter_mut().rev() {
        *slot = b'0' + (rest % 10) as u8;
        rest /= 10;
    }
    out.extend_from_slice(&frac);
}

struct Writer {
    out: io::StdoutLock<'static>,
    buffer: Vec<u8>,
    step: u64,
    psi1_home: f64,
}

impl Writer {
    fn row(&mut self, pose: [f64; 4]) {
        let q = ik(pose[0], pose[1], pose[2], pose[3].to_radians(), self.psi1_home);
        push_fixed(&mut self.buffer, self.step as f64 * DT);
        for value in q {
            self.buffer.push(b',');
            push_fixed(&mut self.buffer, value);
        }
        self.buffer.push(b'\n');
        self.step += 1;
        if self.buffer.len() > 60_000 {
            self.out.write_all(&self.buffer).expect("stdout");
            self.buffer.clear();
        }
    }
}

/// Samples one move: `point(s)` along it, at `rate` (1/s) and `acceleration` (1/s²) in s.
fn sample(writer: &mut Writer, rate: f64, acceleration: f64, point: impl Fn(f64) -> [f64; 4]) {
    // Trapezoid (or triangle) in s over [0, 1], stretched to whole steps.
    let (rate, ramp) = if rate * rate / acceleration >= 1.0 {
        let peak = acceleration.sqrt();
        (peak, 1.0 / peak)
    } else {
        (rate, rate / acceleration)
    };
    let duration = 1.0 / rate + ramp;
    let steps = (duration / DT).ceil().max(1.0) as u64;
    let scale = duration / (steps as f64 * DT);
    for k in 1..=steps {
        let t = k as f64 * DT * scale;
        let s = if t < ramp {
            0.5 * acceleration * t * t
        } else if t < duration - ramp {
            0.5 * rate * ramp + rate * (t - ramp)
        } else {
            let left = duration - t;
            1.0 - 0.5 * acceleration * left * left
        };
        writer.row(point(s.min(1.0)));
    }
}

fn main() {
    let path = std::env::args().nth(1).expect("usage: minimal_loop PROGRAM");
    let file = std::fs::File::open(path).expect("program");
    let model = Kinematics::default();
    let mut pose = model.home().to_degrees();
    let stdout: &'static io::Stdout = Box::leak(Box::new(io::stdout()));
    let mut writer = Writer {
        out: stdout.lock(),
        buffer: Vec::with_capacity(65_536),
        step: 0,
        psi1_home: model.distal_home(Chain::One),
    };
    writer.buffer.extend_from_slice(b"t_s,theta1_rad,theta2_rad,theta3_rad,d4_mm\n");
    writer.row(pose);
    let (mut motion, mut feed) = (0u32, 1000.0f64);
    for line in io::BufReader::with_capacity(1 << 16, file).lines() {
        let line = line.expect("read");
        let mut end = pose;
        let (mut center, mut moved) = ([0.0f64; 2], false);
        let mut words = line.split(|c: char| c.is_ascii_whitespace()).filter(|w| !w.is_empty());
        for word in words.by_ref() {
            let (letter, number) = word.split_at(1);
            let Ok(value) = number.parse::<f64>() else { break };
            match letter {
                "G" if value < 4.0 => motion = value as u32,
                "X" | "Y" | "Z" | "C" => {
                    end["XYZC".find(letter).unwrap_or(0)] = value;
                    moved = true;
                }
                "I" => center[0] = value,
                "J" => center[1] = value,
                "F" => feed = value,
                _ => {}
            }
        }
        if !moved {
            continue;
        }
        let start = pose;
        let delta = [end[0] - start[0], end[1] - start[1], end[2] - start[2], end[3] - start[3]];
        if motion >= 2 {
            let (cx, cy) = (start[0] + center[0], start[1] + center[1]);
            let radius = center[0].hypot(center[1]);
            let from = (start[1] - cy).atan2(start[0] - cx);
            let to = (end[1] - cy).atan2(end[0] - cx);
            let mut sweep = to - from;
            if motion == 2 {
                sweep = -(-sweep).rem_euclid(TAU);
            } else {
                sweep = sweep.rem_euclid(TAU);
            }
            if sweep == 0.0 {
                sweep = if motion == 2 { -TAU } else { TAU };
            }
            let length = (radius * sweep.abs()).hypot(delta[2]);
            let rate = feed / 60.0 / length;
            sample(&mut writer, rate, ACCELERATION / length, |s| {
                let (sin, cos) = (from + s * sweep).sin_cos();
                [
                    cx + radius * cos,
                    cy + radius * sin,
                    start[2] + s * delta[2],
                    start[3] + s * delta[3],
                ]
            });
        } else {
            let length = (delta[0] * delta[0] + delta[1] * delta[1] + delta[2] * delta[2]).sqrt();
            let rotation = delta[3].abs();
            let rate = if motion == 0 {
                (RAPID / length).min(RAPID_ROTATION / rotation)
            } else {
                feed / 60.0 / if length > 0.0 { length } else { rotation }
            };
            if length == 0.0 && rotation == 0.0 {
                continue;
            }
            let acceleration = (ACCELERATION / length).min(7200.0 / rotation);
            sample(&mut writer, rate, acceleration, |s| {
                [
                    start[0] + s * delta[0],
                    start[1] + s * delta[1],
                    start[2] + s * delta[2],
                    start[3] + s * delta[3],
                ]
            });
        }
        pose = end;
    }
    let Writer { mut out, buffer, .. } = writer;
    out.write_all(&buffer).expect("stdout");
    out.flush().expect("stdout");
}
