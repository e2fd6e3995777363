//! Inverse kinematics and reachability over many poses at once, vectorised with runtime CPU
//! dispatch.
//!
//! The poses are solved in blocks of [`LANES`], each block as struct-of-arrays loops with no
//! branches, which the compiler turns into SIMD code. [`pulp::Arch`] detects the CPU once per
//! call and runs the loops compiled for x86-64-v3 (AVX2 + FMA) when the CPU has it, the plain
//! build elsewhere: the same source, no `unsafe` here.
//!
//! `atan2` is the one function the scalar path takes from `libm`, which does not vectorise; the
//! batch path has its own branch-free [`atan2`] (range reduction to |t| ≤ tan(π/16) and the
//! series of atan to the 21st power), within two units in the last place of libm's. Every
//! other operation is the scalar path's, in the same order, so elbows, assembly modes and
//! singularity tests agree bit for bit and the joint angles within 1e-12 rad (tested).

use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, FRAC_PI_8, PI, TAU};

use crate::{Joints, Kinematics, Pose};

/// How many poses one block of the batch loops solves together.
pub const LANES: usize = 8;

/// The outcome of one pose of [`Kinematics::inverse_batch`]: the first check of
/// [`Kinematics::inverse_checked`] it fails, in that function's order.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum BatchStatus {
    /// Reachable, in the assembly mode, inside every joint limit and outside the singularity
    /// margin.
    #[default]
    Ok,
    /// A coordinate is NaN or infinite.
    NotFinite,
    /// A chain cannot reach the point.
    Unreachable,
    /// The solution is in the other assembly mode.
    BeyondType2,
    /// A joint is outside its limits.
    JointLimit,
    /// The pose lies within the singularity margin.
    NearSingular,
}

/// One pose solved by [`Kinematics::inverse_batch`].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct BatchSolution {
    /// The joints [`Kinematics::inverse`] returns (θ1, θ2, θ3 fitted into their limits as it
    /// does); meaningless when the status is [`BatchStatus::NotFinite`] or
    /// [`BatchStatus::Unreachable`].
    pub joints: Joints,
    /// Whether the robot can take the pose, or the first reason it cannot.
    pub status: BatchStatus,
}

/// Status codes (carried as f64 inside the loops, an enum would not vectorise).
const OK: u8 = 0;
const NOT_FINITE: u8 = 1;
const UNREACHABLE: u8 = 2;
const BEYOND_TYPE2: u8 = 3;
const JOINT_LIMIT: u8 = 4;
const NEAR_SINGULAR: u8 = 5;

fn status_of(code: u8) -> BatchStatus {
    match code {
        OK => BatchStatus::Ok,
        NOT_FINITE => BatchStatus::NotFinite,
        UNREACHABLE => BatchStatus::Unreachable,
        BEYOND_TYPE2 => BatchStatus::BeyondType2,
        JOINT_LIMIT => BatchStatus::JointLimit,
        _ => BatchStatus::NearSingular,
    }
}

/// Which machine code runs the batch loops.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Dispatch {
    /// The best the CPU offers, detected at run time (x86-64-v3 when present).
    #[default]
    Detect,
    /// The portable build, whatever the CPU (for comparisons and benchmarks).
    Portable,
}

impl Dispatch {
    fn arch(self) -> pulp::Arch {
        match self {
            Dispatch::Detect => pulp::Arch::new(),
            Dispatch::Portable => pulp::Arch::Scalar,
        }
    }
}

/// The constants of one model that the lane code reads.
#[derive(Debug, Clone, Copy)]
struct Lanes {
    l1: f64,
    /// `l2² − l1²`, as the scalar path computes it.
    l2_l1: f64,
    two_l1: f64,
    bx: [f64; 2],
    by: [f64; 2],
    factor: [f64; 2],
    assembly_minus: bool,
    limits: [[f64; 2]; 4],
    lp: f64,
    margin_tan: f64,
    psi1_home: f64,
}

impl Lanes {
    fn new(model: &Kinematics) -> Lanes {
        let chain = |i: usize| model.bases[i];
        Lanes {
            l1: model.l1,
            l2_l1: model.l2 * model.l2 - model.l1 * model.l1,
            two_l1: 2.0 * model.l1,
            bx: [chain(0).x, chain(1).x],
            by: [chain(0).y, chain(1).y],
            factor: [
                model.working_mode.of(crate::Chain::One).factor(),
                model.working_mode.of(crate::Chain::Two).factor(),
            ],
            assembly_minus: model.assembly_mode.0 == crate::Sign::Minus,
            limits: model.limits,
            lp: model.lp,
            margin_tan: model.singularity_margin_tan,
            psi1_home: model.distal_home[0],
        }
    }

    /// One pose, branch-free: the joints and the status code. `full` adds θ3 and d4 to the
    /// limit test (reachability takes them at the middle of their ranges, where they pass).
    #[inline(always)]
    fn solve(&self, x: f64, y: f64, z: f64, phi: f64, full: bool) -> ([f64; 4], f64) {
        let finite = (x - x) + (y - y) + (z - z) + (phi - phi) == 0.0;
        let chain = |i: usize| {
            let dx = x - self.bx[i];
            let a = -y;
            let b = dx;
            let reach2 = dx * dx + y * y;
            let c = (self.l2_l1 - reach2) / self.two_l1;
            let discriminant = reach2 - c * c;
            let reaches = (discriminant >= 0.0) & (reach2 != 0.0);
            let root = self.factor[i] * discriminant.max(0.0).sqrt();
            let cos_theta = a * c - b * root;
            let sin_theta = b * c + a * root;
            let scale = self.l1 / reach2;
            let elbow = [self.bx[i] - scale * sin_theta, self.by[i] + scale * cos_theta];
            (atan2(sin_theta, cos_theta), elbow, reaches)
        };
        let (theta1, e1, reaches1) = chain(0);
        let (theta2, e2, reaches2) = chain(1);
        let z1 = [x - e1[0], y - e1[1]];
        let z2 = [x - e2[0], y - e2[1]];
        let a1 = [e1[0] - self.bx[0], e1[1] - self.by[0]];
        let a2 = [e2[0] - self.bx[1], e2[1] - self.by[1]];
        let perp = |a: [f64; 2], b: [f64; 2]| a[0] * b[1] - a[1] * b[0];
        let dot = |a: [f64; 2], b: [f64; 2]| a[0] * b[0] + a[1] * b[1];
        let assembly_minus = perp(z2, z1) < 0.0;
        let clear = |a, b| perp(a, b).abs() >= self.margin_tan * dot(a, b).abs();
        let singular = !(clear(a1, z1) & clear(a2, z2) & clear(z2, z1));

        let psi1 = atan2(z1[1], z1[0]);
        let difference = psi1 - self.psi1_home;
        let rotation = select(
            difference > PI,
            difference - TAU,
            select(difference <= -PI, difference + TAU, difference),
        );
        let joints = [
            fit_into(theta1, self.limits[0]),
            fit_into(theta2, self.limits[1]),
            fit_into(phi - rotation, self.limits[2]),
            self.lp - z,
        ];
        let inside = |k: usize| (self.limits[k][0] <= joints[k]) & (joints[k] <= self.limits[k][1]);
        let mut within = inside(0) & inside(1);
        if full {
            within &= inside(2) & inside(3);
        }
        // Codes as f64, so that every lane of the loops is one width.
        let code = select(
            !finite,
            f64::from(NOT_FINITE),
            select(
                !(reaches1 & reaches2),
                f64::from(UNREACHABLE),
                select(
                    assembly_minus != self.assembly_minus,
                    f64::from(BEYOND_TYPE2),
                    select(
                        !within,
                        f64::from(JOINT_LIMIT),
                        select(singular, f64::from(NEAR_SINGULAR), f64::from(OK)),
                    ),
                ),
            ),
        );
        (joints, code)
    }
}

impl Kinematics {
    /// [`Kinematics::inverse_checked`] for every pose of `poses`, written into `out` (as long as
    /// `poses`): the joints as [`Kinematics::inverse`] gives them (within 1e-12 rad) and the first
    /// check failed, without the error's numbers. Vectorised, with the CPU detected at run time.
    ///
    /// # Panics
    /// When `out` and `poses` differ in length.
    pub fn inverse_batch(&self, poses: &[Pose], out: &mut [BatchSolution]) {
        self.inverse_batch_with(Dispatch::Detect, poses, out);
    }

    /// [`Kinematics::inverse_batch`] with the machine code chosen by `dispatch`.
    ///
    /// # Panics
    /// When `out` and `poses` differ in length.
    pub fn inverse_batch_with(
        &self,
        dispatch: Dispatch,
        poses: &[Pose],
        out: &mut [BatchSolution],
    ) {
        assert_eq!(poses.len(), out.len(), "inverse_batch: as many solutions as poses");
        let lanes = Lanes::new(self);
        dispatch.arch().dispatch(
            #[inline(always)]
            || {
                let mut poses = poses.chunks_exact(LANES);
                let mut out = out.chunks_exact_mut(LANES);
                for (block, solved) in (&mut poses).zip(&mut out) {
                    let mut x = [0.0; LANES];
                    let mut y = [0.0; LANES];
                    let mut z = [0.0; LANES];
                    let mut phi = [0.0; LANES];
                    for (k, pose) in block.iter().enumerate() {
                        (x[k], y[k], z[k], phi[k]) = (pose.x, pose.y, pose.z, pose.phi);
                    }
                    let mut q = [[0.0; 4]; LANES];
                    let mut code = [0.0; LANES];
                    for k in 0..LANES {
                        (q[k], code[k]) = lanes.solve(x[k], y[k], z[k], phi[k], true);
                    }
                    for (k, solution) in solved.iter_mut().enumerate() {
                        *solution = BatchSolution {
                            joints: Joints::new(q[k][0], q[k][1], q[k][2], q[k][3]),
                            status: status_of(code[k] as u8),
                        };
                    }
                }
                let rest = poses.remainder().iter().zip(out.into_remainder());
                for (pose, solution) in rest {
                    let (q, code) = lanes.solve(pose.x, pose.y, pose.z, pose.phi, true);
                    *solution = BatchSolution {
                        joints: Joints::new(q[0], q[1], q[2], q[3]),
                        status: status_of(code as u8),
                    };
                }
            },
        );
    }

    /// Whether each platform point `(x[k], y[k])` is reachable as the workspace counts it: IK in
    /// the working mode, in the robot's assembly mode, θ1 and θ2 inside their limits and outside
    /// the singularity margin (z and c are free). Vectorised, with the CPU detected at run time.
    ///
    /// # Panics
    /// When `x`, `y` and `out` differ in length.
    pub fn reachable_batch(&self, x: &[f64], y: &[f64], out: &mut [bool]) {
        self.reachable_batch_with(Dispatch::Detect, x, y, out);
    }

    /// [`Kinematics::reachable_batch`] with the machine code chosen by `dispatch`.
    ///
    /// # Panics
    /// When `x`, `y` and `out` differ in length.
    pub fn reachable_batch_with(&self, dispatch: Dispatch, x: &[f64], y: &[f64], out: &mut [bool]) {
        assert!(x.len() == out.len() && y.len() == out.len(), "reachable_batch: lengths differ");
        let lanes = Lanes::new(self);
        dispatch.arch().dispatch(
            #[inline(always)]
            || {
                let mut xs = x.chunks_exact(LANES);
                let mut ys = y.chunks_exact(LANES);
                let mut out = out.chunks_exact_mut(LANES);
                for ((xb, yb), ob) in (&mut xs).zip(&mut ys).zip(&mut out) {
                    let mut code = [0.0; LANES];
                    for k in 0..LANES {
                        code[k] = lanes.solve(xb[k], yb[k], 0.0, 0.0, false).1;
                    }
                    for k in 0..LANES {
                        ob[k] = code[k] == f64::from(OK);
                    }
                }
                let rest = xs.remainder().iter().zip(ys.remainder()).zip(out.into_remainder());
                for ((&x, &y), reachable) in rest {
                    *reachable = lanes.solve(x, y, 0.0, 0.0, false).1 == f64::from(OK);
                }
            },
        );
    }
}

#[inline(always)]
fn select(condition: bool, a: f64, b: f64) -> f64 {
    if condition { a } else { b }
}

/// The scalar path's `fit_into`, branch-free: ±2π when only that puts the angle inside.
#[inline(always)]
fn fit_into(angle: f64, [min, max]: [f64; 2]) -> f64 {
    let up = angle + TAU;
    let down = angle - TAU;
    let inside = |a: f64| (min <= a) & (a <= max);
    select((angle < min) & inside(up), up, select((angle > max) & inside(down), down, angle))
}

/// tan(π/16) and tan(3π/16): where the reduction switches centre.
const TAN_PI_16: f64 = 0.198_912_367_379_658;
const TAN_3PI_16: f64 = 0.668_178_637_919_298_9;
/// tan(π/8) = √2 − 1.
const TAN_PI_8: f64 = 0.414_213_562_373_095_03;

/// The coefficients of the series of atan t / t in powers of t²: (−1)ᵏ / (2k + 1).
const ATAN_SERIES: [f64; 11] = [
    1.0,
    -1.0 / 3.0,
    1.0 / 5.0,
    -1.0 / 7.0,
    1.0 / 9.0,
    -1.0 / 11.0,
    1.0 / 13.0,
    -1.0 / 15.0,
    1.0 / 17.0,
    -1.0 / 19.0,
    1.0 / 21.0,
];

/// `atan2(y, x)` in (−π, π] without branches, for finite arguments, within a few ulp of libm's.
///
/// The ratio of the smaller to the larger magnitude, a ∈ [0, 1], is moved to t = (a − c)/(1 + a·c)
/// with c = tan 0, tan(π/8) or tan(π/4) nearest, so |t| ≤ tan(π/16) ≈ 0.199, where the series of
/// atan t to t²¹ leaves less than 4e-18. Then the octant: π/2 − r, π − r, the sign of y.
#[inline(always)]
pub fn atan2(y: f64, x: f64) -> f64 {
    let (ax, ay) = (x.abs(), y.abs());
    let (large, small) = (ax.max(ay), ax.min(ay));
    let a = select(large == 0.0, 0.0, small / large);
    let high = a > TAN_3PI_16;
    let middle = a > TAN_PI_16;
    let c = select(high, 1.0, select(middle, TAN_PI_8, 0.0));
    let base = select(high, FRAC_PI_4, select(middle, FRAC_PI_8, 0.0));
    let t = (a - c) / (1.0 + a * c);
    let t2 = t * t;
    // atan t = t·(1 − t²/3 + t⁴/5 − … + t²⁰/21), by Horner in t².
    let mut series = ATAN_SERIES[10];
    for k in (0..10).rev() {
        series = ATAN_SERIES[k] + t2 * series;
    }
    let mut r = base + t * series;
    r = select(ay > ax, FRAC_PI_2 - r, r);
    r = select(x.is_sign_negative(), PI - r, r);
    r.copysign(y)
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;
    use crate::{KinematicsError, Robot, WorkingMode};

    #[test]
    fn atan2_agrees_with_libm() {
        let mut worst: f64 = 0.0;
        let values = [0.0, -0.0, 1e-300, -1e-300, 1e-9, 0.3, -0.7, 1.0, -1.0, 2.5, -1e6, 1e300];
        for &y in &values {
            for &x in &values {
                let (ours, libm) = (atan2(y, x), libm::atan2(y, x));
                assert!((ours - libm).abs() <= 9e-16, "atan2({y}, {x}) = {ours}, libm {libm}");
                assert_eq!(ours.is_sign_negative(), libm.is_sign_negative(), "atan2({y}, {x})");
            }
        }
        for i in 0..200_000 {
            let angle = -PI + TAU * f64::from(i) / 200_000.0;
            let (y, x) = (3.7 * angle.sin(), 3.7 * angle.cos());
            worst = worst.max((atan2(y, x) - libm::atan2(y, x)).abs());
        }
        assert!(worst <= 9e-16, "worst difference {worst}");
    }

    /// The batch status of the scalar path's verdict on one pose.
    fn scalar_status(model: &Kinematics, pose: &Pose) -> BatchStatus {
        match model.inverse_checked(pose) {
            Ok(_) => BatchStatus::Ok,
            Err(KinematicsError::NotFinite { .. }) => BatchStatus::NotFinite,
            Err(KinematicsError::Unreachable { .. }) => BatchStatus::Unreachable,
            Err(KinematicsError::BeyondType2 { .. }) => BatchStatus::BeyondType2,
            Err(KinematicsError::JointLimit { .. }) => BatchStatus::JointLimit,
            Err(KinematicsError::NearSingular { .. }) => BatchStatus::NearSingular,
            Err(other) => panic!("unexpected {other}"),
        }
    }

    fn model_in(mode: &str, assembly: &str) -> Kinematics {
        let mut robot = Robot::default();
        robot.working_mode = mode.parse::<WorkingMode>().unwrap();
        robot.assembly_mode = assembly.parse().unwrap();
        // Limits that bind somewhere in the sampled region.
        robot.joint_limits.theta1 = [-100.0, 150.0];
        robot.joint_limits.theta3 = [-90.0, 200.0];
        Kinematics::new(&robot).unwrap()
    }

    fn check_against_scalar(model: &Kinematics, poses: &[Pose]) {
        for dispatch in [Dispatch::Detect, Dispatch::Portable] {
            let mut out = vec![BatchSolution::default(); poses.len()];
            model.inverse_batch_with(dispatch, poses, &mut out);
            let xs: Vec<f64> = poses.iter().map(|p| p.x).collect();
            let ys: Vec<f64> = poses.iter().map(|p| p.y).collect();
            let mut reachable = vec![false; poses.len()];
            model.reachable_batch_with(dispatch, &xs, &ys, &mut reachable);
            for ((pose, solution), reachable) in poses.iter().zip(&out).zip(&reachable) {
                assert_eq!(solution.status, scalar_status(model, pose), "{pose:?} {dispatch:?}");
                if let Ok(ik) = model.inverse(pose) {
                    for (batch, scalar) in
                        solution.joints.to_array().iter().zip(ik.joints.to_array())
                    {
                        assert!((batch - scalar).abs() <= 1e-12, "{pose:?}: {batch} vs {scalar}");
                    }
                }
                let workspace = model.inverse(pose).is_ok_and(|ik| {
                    let middle = |[min, max]: [f64; 2]| 0.5 * (min + max);
                    let joints = Joints {
                        theta3: middle(model.limits[2]),
                        d4: middle(model.limits[3]),
                        ..ik.joints
                    };
                    model.check_assembly(&ik).is_ok()
                        && model.check_limits(&joints).is_ok()
                        && model.check_singularity(&ik.configuration).is_ok()
                });
                assert_eq!(*reachable, workspace, "{pose:?} {dispatch:?}");
            }
        }
    }

    #[test]
    fn a_grid_over_every_mode_agrees_with_the_scalar_path() {
        for mode in ["++", "+-", "-+", "--"] {
            for assembly in ["+", "-"] {
                let model = model_in(mode, assembly);
                let poses: Vec<Pose> = (0..121)
                    .flat_map(|i| {
                        (0..61).map(move |j| {
                            let (x, y) =
                                (-600.0 + 10.0 * f64::from(i), -600.0 + 20.0 * f64::from(j));
                            Pose::new(x, y, -20.0 + f64::from(j), 0.05 * f64::from(i) - 3.0)
                        })
                    })
                    .collect();
                check_against_scalar(&model, &poses);
            }
        }
    }

    #[test]
    fn coordinates_that_are_not_finite_are_flagged() {
        let model = Kinematics::default();
        let poses = [
            Pose::new(f64::NAN, 400.0, 0.0, 0.0),
            Pose::new(0.0, 400.0, f64::INFINITY, 0.0),
            Pose::new(0.0, 400.0, 0.0, 0.0),
        ];
        let mut out = [BatchSolution::default(); 3];
        model.inverse_batch(&poses, &mut out);
        let status: Vec<_> = out.iter().map(|s| s.status).collect();
        assert_eq!(status, [BatchStatus::NotFinite, BatchStatus::NotFinite, BatchStatus::Ok]);
    }

    proptest! {
        #[test]
        fn random_poses_agree_with_the_scalar_path(
            mode in 0usize..4,
            assembly in 0usize..2,
            poses in prop::collection::vec(
                (-700.0..700.0f64, -700.0..700.0f64, -50.0..150.0f64, -7.0..7.0f64), 1..40),
        ) {
            let model = model_in(["++", "+-", "-+", "--"][mode], ["+", "-"][assembly]);
            let poses: Vec<Pose> =
                poses.into_iter().map(|(x, y, z, phi)| Pose::new(x, y, z, phi)).collect();
            check_against_scalar(&model, &poses);
        }
    }
}
