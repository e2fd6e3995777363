//! Inverse kinematics and reachability over many poses at once, vectorised with runtime CPU
//! dispatch.
//!
//! The poses are solved in blocks of [`LANES`], copied into struct-of-arrays form and solved
//! with no branches as vectors of pulp's [`Simd`] trait. [`pulp::Arch`] detects the CPU once per
//! call and runs the code compiled for x86-64-v3 (AVX2 + FMA, four lanes) when the CPU has it,
//! one lane at a time elsewhere: the same source, and no `unsafe` here (pulp holds it).
//!
//! The formulas are the scalar path's ([`Kinematics::inverse`] and its checks), operation for
//! operation, so the elbows, and with them the reach, assembly-mode and singularity verdicts,
//! are the same bits (a grid point at a chain's full stretch stays exactly at it); only `atan2`,
//! which the scalar path takes from libm and which does not vectorise, is the branch-free
//! [`atan2`] here, within two units in the last place of libm's. Joint angles agree with the
//! scalar path's within 1e-12 rad (tested on grids and random poses in every working and
//! assembly mode).
//!
//! Reachability ([`Kinematics::reachable_batch`]) tests θ1's and θ2's limits on the directions
//! of the proximal links (a dot product against the limits' arc, no `atan2`), and falls back to
//! the angles, as the scalar path compares them, for a vector in which a direction lies within
//! 1e-9 of a limit: grid points fall exactly on limits (θ2 = −135° at (20, 120) mm for the
//! default bases, a 45° line from a base joint), and there only the same comparison gives the
//! same verdict.

use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI, TAU};

use pulp::{Simd, WithSimd};

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

/// Status codes (carried as f64 inside the vectors).
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
    /// θ1's and θ2's limits as arcs of directions.
    arc: [Arc; 2],
}

/// A joint's limits `[min, max]` as an arc of directions: centre (cos m, sin m) with
/// m = (min + max)/2, and cos h with h = (max − min)/2. A direction at angle θ is inside when
/// cos(θ − m) ≥ cos h, which is the scalar test (θ, or θ ± 2π, within the limits) for limits of
/// less than a turn inside (−3π, 3π]; other limits always take the angles (`exact` false).
#[derive(Debug, Clone, Copy)]
struct Arc {
    centre: [f64; 2],
    cos_half: f64,
    exact: bool,
}

impl Arc {
    /// How close to the arc's edge, relative to the direction's length, counts as on it: far
    /// above the rounding of the directions (1e-15), far below any grid's spacing.
    const NEAR: f64 = 1e-9;

    fn new([min, max]: [f64; 2]) -> Arc {
        let (middle, half) = (0.5 * (min + max), 0.5 * (max - min));
        let exact = half < PI && min >= -3.0 * PI && max <= 3.0 * PI;
        Arc { centre: [middle.cos(), middle.sin()], cos_half: half.cos(), exact }
    }

    /// Whether `direction` (x, y and its length, as the chains compute it) lies in the arc, and
    /// whether it lies so close to its edge (or the arc is not exact) that the angle must decide.
    #[inline(always)]
    fn test<S: Simd>(&self, s: S, direction: [S::f64s; 3]) -> (S::m64s, S::m64s) {
        let along = s.add_f64s(
            s.mul_f64s(direction[0], s.splat_f64s(self.centre[0])),
            s.mul_f64s(direction[1], s.splat_f64s(self.centre[1])),
        );
        // |direction|² = (A² + B²)(C² + A² + B² − C²) = reach2².
        let length = direction[2];
        let margin = s.sub_f64s(along, s.mul_f64s(length, s.splat_f64s(self.cos_half)));
        let near = s.less_than_or_equal_f64s(
            s.abs_f64s(margin),
            s.mul_f64s(length, s.splat_f64s(Self::NEAR)),
        );
        let near = if self.exact { near } else { s.or_m64s(near, s.not_m64s(near)) };
        (s.greater_than_or_equal_f64s(margin, s.splat_f64s(0.0)), near)
    }
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
            arc: [Arc::new(model.limits[0]), Arc::new(model.limits[1])],
        }
    }

    /// A vector of poses, branch-free: the joints and the status code of each lane. `full` adds
    /// θ3 and d4 to the limit test (reachability takes them at the middle of their ranges, where
    /// they pass). No closures: every helper is an `#[inline(always)]` function, so that all of it is
    /// compiled with the CPU features pulp enables.
    #[inline(always)]
    fn solve<S: Simd>(&self, s: S, pose: [S::f64s; 4], full: bool) -> ([S::f64s; 4], S::f64s) {
        let [x, y, z, phi] = pose;
        let zero = s.splat_f64s(0.0);
        let spread = s.add_f64s(
            s.add_f64s(s.sub_f64s(x, x), s.sub_f64s(y, y)),
            s.add_f64s(s.sub_f64s(z, z), s.sub_f64s(phi, phi)),
        );
        let finite = s.equal_f64s(spread, zero);
        let (d1, e1, reaches1) = self.chain(s, 0, x, y);
        let (d2, e2, reaches2) = self.chain(s, 1, x, y);
        let z1 = minus(s, [x, y], e1);
        let z2 = minus(s, [x, y], e2);
        let a1 = minus(s, e1, [s.splat_f64s(self.bx[0]), s.splat_f64s(self.by[0])]);
        let a2 = minus(s, e2, [s.splat_f64s(self.bx[1]), s.splat_f64s(self.by[1])]);
        let assembly_minus = s.less_than_f64s(perp(s, z2, z1), zero);
        let tan = s.splat_f64s(self.margin_tan);
        let clear_all = s.and_m64s(
            s.and_m64s(clear(s, tan, a1, z1), clear(s, tan, a2, z2)),
            clear(s, tan, z2, z1),
        );

        let (joints, within) = if full {
            let psi1 = atan2_simd(s, z1[1], z1[0]);
            let difference = s.sub_f64s(psi1, s.splat_f64s(self.psi1_home));
            let rotation = s.select_f64s(
                s.greater_than_f64s(difference, s.splat_f64s(PI)),
                s.sub_f64s(difference, s.splat_f64s(TAU)),
                s.select_f64s(
                    s.less_than_or_equal_f64s(difference, s.splat_f64s(-PI)),
                    s.add_f64s(difference, s.splat_f64s(TAU)),
                    difference,
                ),
            );
            let joints = [
                fit_into(s, atan2_simd(s, d1[1], d1[0]), self.limits[0]),
                fit_into(s, atan2_simd(s, d2[1], d2[0]), self.limits[1]),
                fit_into(s, s.sub_f64s(phi, rotation), self.limits[2]),
                s.sub_f64s(s.splat_f64s(self.lp), z),
            ];
            let within = s.and_m64s(
                s.and_m64s(
                    inside(s, joints[0], self.limits[0]),
                    inside(s, joints[1], self.limits[1]),
                ),
                s.and_m64s(
                    inside(s, joints[2], self.limits[2]),
                    inside(s, joints[3], self.limits[3]),
                ),
            );
            (joints, within)
        } else {
            // Reachability needs no angle unless a direction lies within rounding of a limit
            // (grid points do, exactly): θ is in its limits when its direction is in their arc.
            let (in1, near1) = self.arc[0].test(s, d1);
            let (in2, near2) = self.arc[1].test(s, d2);
            let near = s.and_m64s(s.or_m64s(near1, near2), s.and_m64s(reaches1, reaches2));
            let within = if s.first_true_m64s(near) < S::F64_LANES {
                // Decide by the angles, as the scalar path does.
                let theta1 = fit_into(s, atan2_simd(s, d1[1], d1[0]), self.limits[0]);
                let theta2 = fit_into(s, atan2_simd(s, d2[1], d2[0]), self.limits[1]);
                s.and_m64s(inside(s, theta1, self.limits[0]), inside(s, theta2, self.limits[1]))
            } else {
                s.and_m64s(in1, in2)
            };
            ([zero; 4], within)
        };
        let wrong_assembly =
            if self.assembly_minus { s.not_m64s(assembly_minus) } else { assembly_minus };
        // The first check failed: the checks applied from the last to the first.
        let mut status = s.select_f64s(clear_all, code(s, OK), code(s, NEAR_SINGULAR));
        status = s.select_f64s(within, status, code(s, JOINT_LIMIT));
        status = s.select_f64s(wrong_assembly, code(s, BEYOND_TYPE2), status);
        status = s.select_f64s(s.and_m64s(reaches1, reaches2), status, code(s, UNREACHABLE));
        status = s.select_f64s(finite, status, code(s, NOT_FINITE));
        (joints, status)
    }

    /// Chain `i`'s IK (the scalar `chain_inverse`): `(cos θ, sin θ)` times the reach squared and
    /// the reach squared (the direction's length), the elbow, and whether it reaches.
    #[inline(always)]
    fn chain<S: Simd>(
        &self,
        s: S,
        i: usize,
        x: S::f64s,
        y: S::f64s,
    ) -> ([S::f64s; 3], [S::f64s; 2], S::m64s) {
        let zero = s.splat_f64s(0.0);
        let dx = s.sub_f64s(x, s.splat_f64s(self.bx[i]));
        let a = s.neg_f64s(y);
        let b = dx;
        let reach2 = s.add_f64s(s.mul_f64s(dx, dx), s.mul_f64s(y, y));
        let c = s.div_f64s(s.sub_f64s(s.splat_f64s(self.l2_l1), reach2), s.splat_f64s(self.two_l1));
        let discriminant = s.sub_f64s(reach2, s.mul_f64s(c, c));
        let reaches = s.and_m64s(
            s.greater_than_or_equal_f64s(discriminant, zero),
            s.not_m64s(s.equal_f64s(reach2, zero)),
        );
        let root =
            s.mul_f64s(s.splat_f64s(self.factor[i]), s.sqrt_f64s(s.max_f64s(discriminant, zero)));
        let cos_theta = s.sub_f64s(s.mul_f64s(a, c), s.mul_f64s(b, root));
        let sin_theta = s.add_f64s(s.mul_f64s(b, c), s.mul_f64s(a, root));
        let scale = s.div_f64s(s.splat_f64s(self.l1), reach2);
        let elbow = [
            s.sub_f64s(s.splat_f64s(self.bx[i]), s.mul_f64s(scale, sin_theta)),
            s.add_f64s(s.splat_f64s(self.by[i]), s.mul_f64s(scale, cos_theta)),
        ];
        ([cos_theta, sin_theta, reach2], elbow, reaches)
    }
}

/// A status code on every lane.
#[inline(always)]
fn code<S: Simd>(s: S, code: u8) -> S::f64s {
    s.splat_f64s(f64::from(code))
}

/// `a − b` of two vectors of 2-D vectors.
#[inline(always)]
fn minus<S: Simd>(s: S, a: [S::f64s; 2], b: [S::f64s; 2]) -> [S::f64s; 2] {
    [s.sub_f64s(a[0], b[0]), s.sub_f64s(a[1], b[1])]
}

/// The 2-D cross product `a × b` (nalgebra's `perp`).
#[inline(always)]
fn perp<S: Simd>(s: S, a: [S::f64s; 2], b: [S::f64s; 2]) -> S::f64s {
    s.sub_f64s(s.mul_f64s(a[0], b[1]), s.mul_f64s(a[1], b[0]))
}

/// The dot product `a · b`.
#[inline(always)]
fn dot<S: Simd>(s: S, a: [S::f64s; 2], b: [S::f64s; 2]) -> S::f64s {
    s.add_f64s(s.mul_f64s(a[0], b[0]), s.mul_f64s(a[1], b[1]))
}

/// The scalar path's singularity test: |a × b| ≥ tan(margin)·|a · b|.
#[inline(always)]
fn clear<S: Simd>(s: S, tan: S::f64s, a: [S::f64s; 2], b: [S::f64s; 2]) -> S::m64s {
    s.greater_than_or_equal_f64s(
        s.abs_f64s(perp(s, a, b)),
        s.mul_f64s(tan, s.abs_f64s(dot(s, a, b))),
    )
}

/// `min ≤ value ≤ max` on every lane.
#[inline(always)]
fn inside<S: Simd>(s: S, value: S::f64s, [min, max]: [f64; 2]) -> S::m64s {
    s.and_m64s(
        s.less_than_or_equal_f64s(s.splat_f64s(min), value),
        s.less_than_or_equal_f64s(value, s.splat_f64s(max)),
    )
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
        dispatch.arch().dispatch(InverseOp { lanes: Lanes::new(self), poses, out });
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
        dispatch.arch().dispatch(ReachableOp { lanes: Lanes::new(self), x, y, out });
    }
}

/// One block of [`LANES`] values of one coordinate, as vectors of `S`.
#[inline(always)]
fn load<S: Simd>(block: &[f64; LANES]) -> &[S::f64s] {
    S::as_simd_f64s(block).0
}

/// [`Kinematics::inverse_batch`] as pulp runs it, with the vector type of the CPU.
struct InverseOp<'a> {
    lanes: Lanes,
    poses: &'a [Pose],
    out: &'a mut [BatchSolution],
}

impl WithSimd for InverseOp<'_> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: Simd>(self, s: S) {
        for (poses, out) in self.poses.chunks(LANES).zip(self.out.chunks_mut(LANES)) {
            // Struct of arrays; a short last block is padded with the origin (and dropped).
            let mut x = [0.0; LANES];
            let mut y = [0.0; LANES];
            let mut z = [0.0; LANES];
            let mut phi = [0.0; LANES];
            for (k, pose) in poses.iter().enumerate() {
                (x[k], y[k], z[k], phi[k]) = (pose.x, pose.y, pose.z, pose.phi);
            }
            let mut q = [[0.0; LANES]; 4];
            let mut status = [0.0; LANES];
            {
                let (xv, yv, zv, pv) =
                    (load::<S>(&x), load::<S>(&y), load::<S>(&z), load::<S>(&phi));
                let [q0, q1, q2, q3] = &mut q;
                let (q0, q1) = (S::as_mut_simd_f64s(q0).0, S::as_mut_simd_f64s(q1).0);
                let (q2, q3) = (S::as_mut_simd_f64s(q2).0, S::as_mut_simd_f64s(q3).0);
                let codes = S::as_mut_simd_f64s(&mut status).0;
                for v in 0..codes.len() {
                    let (joints, code) = self.lanes.solve(s, [xv[v], yv[v], zv[v], pv[v]], true);
                    (q0[v], q1[v], q2[v], q3[v]) = (joints[0], joints[1], joints[2], joints[3]);
                    codes[v] = code;
                }
            }
            for (k, solution) in out.iter_mut().enumerate() {
                *solution = BatchSolution {
                    joints: Joints::new(q[0][k], q[1][k], q[2][k], q[3][k]),
                    status: status_of(status[k] as u8),
                };
            }
        }
    }
}

/// [`Kinematics::reachable_batch`] as pulp runs it, with the vector type of the CPU.
struct ReachableOp<'a> {
    lanes: Lanes,
    x: &'a [f64],
    y: &'a [f64],
    out: &'a mut [bool],
}

impl WithSimd for ReachableOp<'_> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: Simd>(self, s: S) {
        let blocks = self.x.chunks(LANES).zip(self.y.chunks(LANES)).zip(self.out.chunks_mut(LANES));
        for ((xs, ys), out) in blocks {
            let mut x = [0.0; LANES];
            let mut y = [0.0; LANES];
            x[..xs.len()].copy_from_slice(xs);
            y[..ys.len()].copy_from_slice(ys);
            let mut status = [0.0; LANES];
            {
                let (xv, yv) = (load::<S>(&x), load::<S>(&y));
                let zero = s.splat_f64s(0.0);
                let codes = S::as_mut_simd_f64s(&mut status).0;
                for v in 0..codes.len() {
                    codes[v] = self.lanes.solve(s, [xv[v], yv[v], zero, zero], false).1;
                }
            }
            for (reachable, code) in out.iter_mut().zip(status) {
                *reachable = code == f64::from(OK);
            }
        }
    }
}

/// The scalar path's `fit_into`, branch-free: ±2π when only that puts the angle inside.
#[inline(always)]
fn fit_into<S: Simd>(s: S, angle: S::f64s, limits: [f64; 2]) -> S::f64s {
    let (min, max) = (s.splat_f64s(limits[0]), s.splat_f64s(limits[1]));
    let up = s.add_f64s(angle, s.splat_f64s(TAU));
    let down = s.sub_f64s(angle, s.splat_f64s(TAU));
    let raise = s.and_m64s(s.less_than_f64s(angle, min), inside(s, up, limits));
    let lower = s.and_m64s(s.greater_than_f64s(angle, max), inside(s, down, limits));
    s.select_f64s(raise, up, s.select_f64s(lower, down, angle))
}

/// The reduction's centres: angles kπ/16 (k = 0…4), their tangents, and the tangents of the
/// midpoints (2k + 1)π/32 where it switches from one centre to the next.
const CENTRE_ANGLE: [f64; 5] = [0.0, PI / 16.0, PI / 8.0, 3.0 * PI / 16.0, FRAC_PI_4];
const CENTRE_TAN: [f64; 5] =
    [0.0, 0.198_912_367_379_658, 0.414_213_562_373_095_03, 0.668_178_637_919_298_9, 1.0];
const SWITCH_TAN: [f64; 4] = [
    0.098_491_403_357_164_25,
    0.303_346_683_607_342_4,
    0.534_511_135_950_791_6,
    0.820_678_790_828_660_3,
];

/// The coefficients of the series of atan t / t in powers of t²: (−1)ᵏ / (2k + 1).
const ATAN_SERIES: [f64; 8] =
    [1.0, -1.0 / 3.0, 1.0 / 5.0, -1.0 / 7.0, 1.0 / 9.0, -1.0 / 11.0, 1.0 / 13.0, -1.0 / 15.0];

/// `atan2(y, x)` in (−π, π] without branches, for finite arguments, within two units in the
/// last place of libm's (tested).
///
/// With `small ≤ large` the magnitudes of x and y, a = small/large ∈ [0, 1] lies within π/32 of
/// the angle of one centre c = tan(kπ/16), and atan a = kπ/16 + atan t with
/// t = (a − c)/(1 + a·c) = (small − c·large)/(large + c·small): one division. |t| ≤ tan(π/32)
/// ≈ 0.0985, where the series of atan t to t¹⁵ leaves less than 1e-17. Then the octant: π/2 − r,
/// π − r, the sign of y.
#[inline(always)]
pub fn atan2(y: f64, x: f64) -> f64 {
    atan2_simd(pulp::Scalar, y, x)
}

/// [`atan2`] on every lane of a vector.
#[inline(always)]
fn atan2_simd<S: Simd>(s: S, y: S::f64s, x: S::f64s) -> S::f64s {
    let (ax, ay) = (s.abs_f64s(x), s.abs_f64s(y));
    let (large, small) = (s.max_f64s(ax, ay), s.min_f64s(ax, ay));
    let zero = s.splat_f64s(0.0);
    let mut c = zero;
    let mut base = zero;
    for k in 0..4 {
        // small/large > tan((2k + 1)π/32), without the division.
        let past = s.greater_than_f64s(small, s.mul_f64s(s.splat_f64s(SWITCH_TAN[k]), large));
        c = s.select_f64s(past, s.splat_f64s(CENTRE_TAN[k + 1]), c);
        base = s.select_f64s(past, s.splat_f64s(CENTRE_ANGLE[k + 1]), base);
    }
    let numerator = s.sub_f64s(small, s.mul_f64s(c, large));
    let denominator = s.add_f64s(large, s.mul_f64s(c, small));
    // large = 0 only at the origin, where atan2 is ±0 or ±π: t = 0 there.
    let t = s.select_f64s(s.equal_f64s(large, zero), zero, s.div_f64s(numerator, denominator));
    let t2 = s.mul_f64s(t, t);
    // atan t = t·(1 − t²/3 + t⁴/5 − … − t¹⁴/15), by Horner in t².
    let mut series = s.splat_f64s(ATAN_SERIES[7]);
    for k in (0..7).rev() {
        series = s.mul_add_e_f64s(t2, series, s.splat_f64s(ATAN_SERIES[k]));
    }
    let mut r = s.mul_add_e_f64s(t, series, base);
    r = s.select_f64s(s.greater_than_f64s(ay, ax), s.sub_f64s(s.splat_f64s(FRAC_PI_2), r), r);
    // x's sign, −0 included: ±1 with the sign bit of x.
    let sign_of_x = s.or_f64s(s.splat_f64s(1.0), s.and_f64s(x, s.splat_f64s(-0.0)));
    r = s.select_f64s(s.less_than_f64s(sign_of_x, zero), s.sub_f64s(s.splat_f64s(PI), r), r);
    // r ≥ 0 here: copysign(r, y) sets its sign bit from y's.
    s.or_f64s(r, s.and_f64s(y, s.splat_f64s(-0.0)))
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
        let mut robot = Robot {
            working_mode: mode.parse::<WorkingMode>().unwrap(),
            assembly_mode: assembly.parse().unwrap(),
            ..Robot::default()
        };
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

    #[test]
    fn limits_of_every_shape_agree_with_the_scalar_path() {
        for (theta1, theta2) in [
            ([-190.0, 190.0], [-135.0, 135.0]),
            ([100.0, 300.0], [-300.0, -100.0]),
            ([-45.0, 45.0], [0.0, 1.0]),
            ([-540.0, 540.0], [-10.0, 350.0]),
        ] {
            let mut robot = Robot::default();
            robot.joint_limits.theta1 = theta1;
            robot.joint_limits.theta2 = theta2;
            let model = Kinematics::new(&robot).unwrap();
            let poses: Vec<Pose> = (0..101)
                .flat_map(|i| {
                    (0..101).map(move |j| {
                        Pose::new(
                            -500.0 + 10.0 * f64::from(i),
                            -500.0 + 10.0 * f64::from(j),
                            0.0,
                            0.0,
                        )
                    })
                })
                .collect();
            check_against_scalar(&model, &poses);
        }
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
