//! Inverse kinematics and reachability over many poses at once, vectorised with runtime CPU
//! dispatch.
//!
//! The poses are solved in blocks of [`LANES`] with no branches, as vectors of pulp's [`Simd`]
//! trait: from columns ([`Kinematics::inverse_columns`]) as they are, from [`Pose`]s
//! ([`Kinematics::inverse_batch`]) copied into columns first. [`pulp::Arch`] detects the CPU
//! once per call and runs the code compiled for x86-64-v4 (AVX-512, eight lanes) or x86-64-v3
//! (AVX2 + FMA, four lanes) when the CPU has it, one lane at a time elsewhere: the same source,
//! and no `unsafe` here (pulp holds it).
//!
//! The results are the scalar path's, bit for bit ([`Kinematics::inverse`] and its checks;
//! tested on grids and random poses in every working and assembly mode, with every dispatch):
//! the formulas are the same operation for operation, and `atan2`, which the scalar path takes
//! from libm, is libm's algorithm in lanes ([`atan2`]: the same reduction, constants and
//! operations, no fused multiply-add). A lane on which libm takes one of its special cases
//! (a zero or a ratio of the arguments past 2⁶²) is solved again by the scalar path.
//!
//! Reachability ([`Kinematics::reachable_batch`]) tests θ1's and θ2's limits on the directions
//! of the proximal links (a dot product against the limits' arc, no `atan2`), and falls back to
//! the angles, as the scalar path compares them, for a vector in which a direction lies within
//! 1e-9 of a limit: grid points fall exactly on limits (θ2 = −135° at (20, 120) mm for the
//! default bases, a 45° line from a base joint), and there only the same comparison gives the
//! same verdict.

use std::f64::consts::{PI, TAU};

use pulp::{Simd, WithSimd};

use crate::{Joints, Kinematics, KinematicsError, Pose};

/// How many poses one block of the batch loops solves together: enough vectors for the CPU to
/// overlap their long chains of dependent steps.
pub const LANES: usize = 32;

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
/// Not a status: the pose is solved again by the scalar path (see [`atan2_simd`]).
const SCALAR: u8 = 6;

/// 2⁵²: a code from 0 to 6 plus this is a double whose low bits are the code.
const CODE_BIAS: f64 = 4_503_599_627_370_496.0;

/// The code of a status [`Lanes::solve_block`] wrote (biased by [`CODE_BIAS`]).
#[inline(always)]
fn code_of(biased: f64) -> u8 {
    (biased.to_bits() & 0xff) as u8
}

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
    /// The best the CPU offers, detected at run time: AVX-512 (x86-64-v4), else AVX2 + FMA
    /// (x86-64-v3), else the portable code.
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
    /// Whether θ1's and θ2's limits reach ±π, where `fit_into` can move an angle of `atan2`
    /// (in [−π, π]) by 2π; inside (−π, π) it never does (θ + 2π ≥ π > max, θ − 2π ≤ −π < min),
    /// and the angle is kept as it is, as the scalar path keeps it.
    wraps: [bool; 2],
}

/// [`Lanes::solve_block`]'s working space: the arguments of the three angles of a block, θ1's,
/// θ2's and ψ1's blocks one after the other, then the angles in their place. Kept from one block
/// to the next rather than cleared for each.
struct Scratch {
    angle_y: [f64; 3 * LANES],
    angle_x: [f64; 3 * LANES],
}

impl Scratch {
    fn new() -> Scratch {
        Scratch { angle_y: [0.0; 3 * LANES], angle_x: [0.0; 3 * LANES] }
    }
}

/// What [`Lanes::chains`] finds for a vector of poses.
struct Chains<S: Simd> {
    /// Chain 1's `(cos θ1, sin θ1)` times the reach squared, and the reach squared.
    d1: [S::f64s; 3],
    /// The same for chain 2.
    d2: [S::f64s; 3],
    /// Chain 1's distal link, P − E1 (its angle is ψ1).
    distal: [S::f64s; 2],
    /// The status code of every check but the joint limits.
    status: S::f64s,
    /// Finite, and both chains reach.
    solvable: S::m64s,
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
            wraps: [0, 1].map(|j| !(model.limits[j][0] > -PI && model.limits[j][1] < PI)),
        }
    }

    /// What a vector of poses gives without an angle, branch-free. No closures here or below:
    /// every helper is an `#[inline(always)]` function, so that all of it is compiled with the
    /// CPU features pulp enables.
    #[inline(always)]
    fn chains<S: Simd>(&self, s: S, pose: [S::f64s; 4]) -> Chains<S> {
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
        let wrong_assembly =
            if self.assembly_minus { s.not_m64s(assembly_minus) } else { assembly_minus };
        let reaches = s.and_m64s(reaches1, reaches2);
        // The first check failed, the limits aside: the checks applied from the last to the
        // first.
        let mut status = s.select_f64s(clear_all, code(s, OK), code(s, NEAR_SINGULAR));
        status = s.select_f64s(wrong_assembly, code(s, BEYOND_TYPE2), status);
        status = s.select_f64s(reaches, status, code(s, UNREACHABLE));
        status = s.select_f64s(finite, status, code(s, NOT_FINITE));
        Chains { d1, d2, distal: z1, status, solvable: s.and_m64s(finite, reaches) }
    }

    /// The status code of a vector of platform points for [`Kinematics::reachable_batch`]: `OK`
    /// when reachable.
    #[inline(always)]
    fn reachable<S: Simd>(&self, s: S, x: S::f64s, y: S::f64s) -> S::f64s {
        let zero = s.splat_f64s(0.0);
        let Chains { d1, d2, status, solvable, .. } = self.chains(s, [x, y, zero, zero]);
        // Reachability needs no angle unless a direction lies within rounding of a limit (grid
        // points do, exactly): θ is in its limits when its direction is in their arc.
        let (in1, near1) = self.arc[0].test(s, d1);
        let (in2, near2) = self.arc[1].test(s, d2);
        let near = s.and_m64s(s.or_m64s(near1, near2), solvable);
        let (within, other) = if s.first_true_m64s(near) < S::F64_LANES {
            // Decide by the angles, as the scalar path does.
            let (theta1, other1) = atan2_simd(s, d1[1], d1[0]);
            let (theta2, other2) = atan2_simd(s, d2[1], d2[0]);
            let theta1 = self.fit_angle(s, 0, theta1);
            let theta2 = self.fit_angle(s, 1, theta2);
            let within =
                s.and_m64s(inside(s, theta1, self.limits[0]), inside(s, theta2, self.limits[1]));
            (within, s.and_m64s(near, s.or_m64s(other1, other2)))
        } else {
            (s.and_m64s(in1, in2), near) // near: no lane
        };
        let status = s.select_f64s(within, status, code(s, JOINT_LIMIT));
        s.select_f64s(other, code(s, SCALAR), status)
    }

    /// One block of poses, `[x, y, z, φ]`: the joints and the status code of each, in three
    /// passes over the block: everything but the angles, the angles, then the joints and the
    /// limits. Each pass is a loop over vectors with short, independent iterations, which the
    /// CPU overlaps; one pass for all of it, each iteration one long chain of dependent steps
    /// (two divisions and a square root before the first `atan2`, two divisions in each), ran
    /// at the latency of that chain.
    #[inline(always)]
    fn solve_block<S: Simd>(
        &self,
        s: S,
        pose: [&[f64; LANES]; 4],
        joints: [&mut [f64; LANES]; 5],
        status: &mut [f64; LANES],
        scratch: &mut Scratch,
    ) -> bool {
        let [x, y, z, phi] = pose.map(|block| S::as_simd_f64s(block).0);
        let Scratch { angle_y, angle_x } = scratch;
        {
            let (ay, ax) = (S::as_mut_simd_f64s(angle_y).0, S::as_mut_simd_f64s(angle_x).0);
            let codes = S::as_mut_simd_f64s(status).0;
            let n = codes.len();
            for v in 0..n {
                let chains = self.chains(s, [x[v], y[v], z[v], phi[v]]);
                (ay[v], ax[v]) = (chains.d1[1], chains.d1[0]);
                (ay[n + v], ax[n + v]) = (chains.d2[1], chains.d2[0]);
                (ay[2 * n + v], ax[2 * n + v]) = (chains.distal[1], chains.distal[0]);
                codes[v] = chains.status;
            }
        }
        {
            let ax = S::as_simd_f64s(angle_x).0;
            let ay = S::as_mut_simd_f64s(angle_y).0;
            let nan = s.splat_f64s(f64::NAN);
            for v in 0..ay.len() {
                // NaN marks a lane libm must compute (the arguments of a solvable pose are
                // finite, so its angles are not NaN otherwise).
                let (angle, other) = atan2_simd(s, ay[v], ax[v]);
                ay[v] = s.select_f64s(other, nan, angle);
            }
        }
        let angles = S::as_simd_f64s(angle_y).0;
        let [q0, q1, q2, q3, q4] = joints;
        let q4 = S::as_mut_simd_f64s(q4).0;
        let mut any_other = s.less_than_f64s(s.splat_f64s(1.0), s.splat_f64s(0.0));
        let (q0, q1) = (S::as_mut_simd_f64s(q0).0, S::as_mut_simd_f64s(q1).0);
        let (q2, q3) = (S::as_mut_simd_f64s(q2).0, S::as_mut_simd_f64s(q3).0);
        let codes = S::as_mut_simd_f64s(status).0;
        let n = codes.len();
        for v in 0..n {
            let (theta1, theta2, psi1) = (angles[v], angles[n + v], angles[2 * n + v]);
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
            let q = [
                self.fit_angle(s, 0, theta1),
                self.fit_angle(s, 1, theta2),
                fit_into(s, s.sub_f64s(phi[v], rotation), self.limits[2]),
                s.sub_f64s(s.splat_f64s(self.lp), z[v]),
            ];
            let within = s.and_m64s(
                s.and_m64s(inside(s, q[0], self.limits[0]), inside(s, q[1], self.limits[1])),
                s.and_m64s(inside(s, q[2], self.limits[2]), inside(s, q[3], self.limits[3])),
            );
            let mut status = codes[v];
            // The limits come after the assembly mode and before the singularity margin.
            let late = s.or_m64s(
                s.equal_f64s(status, code(s, OK)),
                s.equal_f64s(status, code(s, NEAR_SINGULAR)),
            );
            status =
                s.select_f64s(s.and_m64s(late, s.not_m64s(within)), code(s, JOINT_LIMIT), status);
            // An angle libm computes by one of its special cases: the pose the scalar way.
            let sum = s.add_f64s(s.add_f64s(theta1, theta2), psi1);
            let solvable = s.not_m64s(s.or_m64s(
                s.equal_f64s(status, code(s, NOT_FINITE)),
                s.equal_f64s(status, code(s, UNREACHABLE)),
            ));
            let other = s.and_m64s(solvable, s.not_m64s(s.equal_f64s(sum, sum)));
            any_other = s.or_m64s(any_other, other);
            // Plus 2⁵²: the code in the low bits of the double, read back by `code_of` (a
            // move, no conversion).
            let status = s.select_f64s(other, code(s, SCALAR), status);
            codes[v] = s.add_f64s(status, s.splat_f64s(CODE_BIAS));
            (q0[v], q1[v], q2[v], q3[v], q4[v]) = (q[0], q[1], q[2], q[3], rotation);
        }
        s.first_true_m64s(any_other) < S::F64_LANES
    }

    /// θ1 (`j` = 0) or θ2 (`j` = 1) from `atan2` fitted into its limits ([`fit_into`]).
    #[inline(always)]
    fn fit_angle<S: Simd>(&self, s: S, j: usize, angle: S::f64s) -> S::f64s {
        if self.wraps[j] { fit_into(s, angle, self.limits[j]) } else { angle }
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

/// Poses as columns (struct of arrays): pose `k` is `(x[k], y[k], z[k], phi[k])`, millimetres
/// and radians as in [`Pose`]. [`Kinematics::inverse_columns`] loads them into vectors as they
/// are, with no copy into lanes.
#[derive(Debug, Clone, Copy)]
pub struct PoseColumns<'a> {
    /// x, mm.
    pub x: &'a [f64],
    /// y, mm.
    pub y: &'a [f64],
    /// z, mm.
    pub z: &'a [f64],
    /// The tool's angle φ, radians.
    pub phi: &'a [f64],
}

/// Where [`Kinematics::inverse_columns`] writes pose `k`'s solution: its joints (as
/// [`BatchSolution::joints`]) and its status.
#[derive(Debug)]
pub struct SolutionColumns<'a> {
    /// θ1, radians.
    pub theta1: &'a mut [f64],
    /// θ2, radians.
    pub theta2: &'a mut [f64],
    /// θ3, radians.
    pub theta3: &'a mut [f64],
    /// d4, mm.
    pub d4: &'a mut [f64],
    /// The distal rotation ψ1 − ψ1_home in (−π, π] ([`crate::IkSolution::distal_rotation`]),
    /// radians: what [`crate::Theta3Unwrapper::theta3`] reads.
    pub distal_rotation: &'a mut [f64],
    /// Whether the robot can take the pose, or the first reason it cannot.
    pub status: &'a mut [BatchStatus],
}

impl<'a> SolutionColumns<'a> {
    /// The columns `[theta1, theta2, theta3, d4, distal_rotation]` (in the fields' order, as
    /// [`Joints::to_array`] then the distal rotation) and `status`.
    pub fn new(joints: &'a mut [Vec<f64>; 5], status: &'a mut [BatchStatus]) -> Self {
        let [theta1, theta2, theta3, d4, distal_rotation] = joints;
        SolutionColumns { theta1, theta2, theta3, d4, distal_rotation, status }
    }
}

impl Kinematics {
    /// [`Kinematics::inverse_checked`] for every pose of `poses`, written into `out` (as long as
    /// `poses`): the joints [`Kinematics::inverse`] gives, the same bits, and the first check
    /// failed, without the error's numbers. Vectorised, with the CPU detected at run time.
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
        dispatch.arch().dispatch(InverseOp { model: self, lanes: Lanes::new(self), poses, out });
    }

    /// [`Kinematics::inverse_batch`] on poses given as columns, the solutions written as
    /// columns: the same results, without gathering each pose's coordinates into lanes (the
    /// faster entry point when the poses can be kept that way).
    ///
    /// # Panics
    /// When the columns differ in length.
    pub fn inverse_columns(&self, poses: PoseColumns<'_>, out: SolutionColumns<'_>) {
        self.inverse_columns_with(Dispatch::Detect, poses, out);
    }

    /// [`Kinematics::inverse_columns`] with the machine code chosen by `dispatch`.
    ///
    /// # Panics
    /// When the columns differ in length.
    pub fn inverse_columns_with(
        &self,
        dispatch: Dispatch,
        poses: PoseColumns<'_>,
        out: SolutionColumns<'_>,
    ) {
        let n = poses.x.len();
        let lengths = [poses.y.len(), poses.z.len(), poses.phi.len(), out.theta1.len()];
        let more = [out.theta2.len(), out.theta3.len(), out.d4.len(), out.distal_rotation.len()];
        let more = more.into_iter().chain([out.status.len()]);
        assert!(
            lengths.into_iter().chain(more).all(|length| length == n),
            "inverse_columns: the columns differ in length"
        );
        dispatch.arch().dispatch(ColumnsOp { model: self, lanes: Lanes::new(self), poses, out });
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
        dispatch.arch().dispatch(ReachableOp { model: self, lanes: Lanes::new(self), x, y, out });
    }

    /// One pose the scalar way, for the lanes the vector code leaves to libm's `atan2`.
    #[cold]
    #[inline(never)]
    fn solve_scalar(&self, pose: &Pose) -> (BatchSolution, f64) {
        let solution = match self.inverse(pose) {
            Ok(solution) => solution,
            Err(KinematicsError::NotFinite { .. }) => {
                return (failure(BatchStatus::NotFinite), 0.0);
            }
            Err(_) => return (failure(BatchStatus::Unreachable), 0.0),
        };
        let status = if self.check_assembly(&solution).is_err() {
            BatchStatus::BeyondType2
        } else if self.check_limits(&solution.joints).is_err() {
            BatchStatus::JointLimit
        } else if self.check_singularity(&solution.configuration).is_err() {
            BatchStatus::NearSingular
        } else {
            BatchStatus::Ok
        };
        (BatchSolution { joints: solution.joints, status }, solution.distal_rotation)
    }

    /// [`Kinematics::reachable_batch`] for one point the scalar way (see
    /// [`Kinematics::solve_scalar`]).
    #[cold]
    #[inline(never)]
    fn reachable_scalar(&self, x: f64, y: f64) -> bool {
        self.reachable(x, y)
    }
}

/// A pose that fails with `status` before its joints are known.
fn failure(status: BatchStatus) -> BatchSolution {
    BatchSolution { joints: Joints::default(), status }
}

/// `values` as one block: itself when it holds [`LANES`] values, else copied into `padding`
/// (whose other values are left as they are).
#[inline(always)]
fn block<'a>(values: &'a [f64], padding: &'a mut [f64; LANES]) -> &'a [f64; LANES] {
    match values.try_into() {
        Ok(full) => full,
        Err(_) => {
            padding[..values.len()].copy_from_slice(values);
            padding
        }
    }
}

/// [`Kinematics::inverse_batch`] as pulp runs it, with the vector type of the CPU.
struct InverseOp<'a> {
    model: &'a Kinematics,
    lanes: Lanes,
    poses: &'a [Pose],
    out: &'a mut [BatchSolution],
}

impl WithSimd for InverseOp<'_> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: Simd>(self, s: S) {
        let mut scratch = Scratch::new();
        // Struct of arrays; a short last block is padded with the previous block's poses (and
        // dropped).
        let mut pose = [[0.0; LANES]; 4];
        let mut q = [[0.0; LANES]; 5];
        let mut status = [0.0; LANES];
        for (poses, out) in self.poses.chunks(LANES).zip(self.out.chunks_mut(LANES)) {
            for (k, p) in poses.iter().enumerate() {
                (pose[0][k], pose[1][k], pose[2][k], pose[3][k]) = (p.x, p.y, p.z, p.phi);
            }
            let [x, y, z, phi] = &pose;
            let [q0, q1, q2, q3, rotation] = &mut q;
            let joints = [q0, q1, q2, q3, rotation];
            let other =
                self.lanes.solve_block(s, [x, y, z, phi], joints, &mut status, &mut scratch);
            // Field by field: a whole `BatchSolution` was built on the stack and copied with
            // its padding, a load over the status byte just stored that waited for it (29 % of
            // the time, 20 → 14 ns per pose). No branch per pose: the poses the scalar path
            // solves again are found after, in the rare blocks that have one.
            for (k, solution) in out.iter_mut().enumerate() {
                solution.joints = Joints::new(q[0][k], q[1][k], q[2][k], q[3][k]);
                solution.status = status_of(code_of(status[k]));
            }
            if other {
                for (k, &code) in status[..out.len()].iter().enumerate() {
                    if code_of(code) == SCALAR {
                        out[k] = self.model.solve_scalar(&poses[k]).0;
                    }
                }
            }
        }
    }
}

/// [`Kinematics::inverse_columns`] as pulp runs it, with the vector type of the CPU.
struct ColumnsOp<'a> {
    model: &'a Kinematics,
    lanes: Lanes,
    poses: PoseColumns<'a>,
    out: SolutionColumns<'a>,
}

impl WithSimd for ColumnsOp<'_> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: Simd>(self, s: S) {
        let PoseColumns { x, y, z, phi } = self.poses;
        let SolutionColumns { theta1, theta2, theta3, d4, distal_rotation, status } = self.out;
        let columns = x.chunks(LANES).zip(y.chunks(LANES)).zip(z.chunks(LANES));
        let columns = columns.zip(phi.chunks(LANES)).zip(theta1.chunks_mut(LANES));
        let columns = columns.zip(theta2.chunks_mut(LANES)).zip(theta3.chunks_mut(LANES));
        let columns = columns.zip(d4.chunks_mut(LANES)).zip(distal_rotation.chunks_mut(LANES));
        let columns = columns.zip(status.chunks_mut(LANES));
        // A short last block is padded with the origin (and dropped).
        let mut padding = [[0.0; LANES]; 4];
        let mut scratch = Scratch::new();
        let mut codes = [0.0; LANES];
        let mut tail = [[0.0; LANES]; 5];
        for (((((((((x, y), z), phi), theta1), theta2), theta3), d4), distal_rotation), status) in
            columns
        {
            let [px, py, pz, pphi] = &mut padding;
            let pose = [block(x, px), block(y, py), block(z, pz), block(phi, pphi)];
            let joints =
                [&mut *theta1, &mut *theta2, &mut *theta3, &mut *d4, &mut *distal_rotation];
            let other = match joints.map(<&mut [f64; LANES]>::try_from) {
                // A whole block: the joints written in place.
                [Ok(q0), Ok(q1), Ok(q2), Ok(q3), Ok(q4)] => {
                    let joints = [q0, q1, q2, q3, q4];
                    self.lanes.solve_block(s, pose, joints, &mut codes, &mut scratch)
                }
                _ => {
                    let [q0, q1, q2, q3, q4] = &mut tail;
                    let joints = [q0, q1, q2, q3, q4];
                    let other = self.lanes.solve_block(s, pose, joints, &mut codes, &mut scratch);
                    let n = status.len();
                    theta1.copy_from_slice(&tail[0][..n]);
                    theta2.copy_from_slice(&tail[1][..n]);
                    theta3.copy_from_slice(&tail[2][..n]);
                    d4.copy_from_slice(&tail[3][..n]);
                    distal_rotation.copy_from_slice(&tail[4][..n]);
                    other
                }
            };
            for (slot, code) in status.iter_mut().zip(codes) {
                *slot = status_of(code_of(code));
            }
            if other {
                for (k, &code) in codes[..status.len()].iter().enumerate() {
                    if code_of(code) == SCALAR {
                        let pose = Pose::new(pose[0][k], pose[1][k], pose[2][k], pose[3][k]);
                        let (solution, rotation) = self.model.solve_scalar(&pose);
                        [theta1[k], theta2[k], theta3[k], d4[k]] = solution.joints.to_array();
                        distal_rotation[k] = rotation;
                        status[k] = solution.status;
                    }
                }
            }
        }
    }
}

/// [`Kinematics::reachable_batch`] as pulp runs it, with the vector type of the CPU.
struct ReachableOp<'a> {
    model: &'a Kinematics,
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
        let mut padding = [[0.0; LANES]; 2];
        for ((xs, ys), out) in blocks {
            let [px, py] = &mut padding;
            let (x, y) = (block(xs, px), block(ys, py));
            let mut status = [0.0; LANES];
            {
                let (xv, yv) = (S::as_simd_f64s(x).0, S::as_simd_f64s(y).0);
                let codes = S::as_mut_simd_f64s(&mut status).0;
                for v in 0..codes.len() {
                    codes[v] = self.lanes.reachable(s, xv[v], yv[v]);
                }
            }
            for (k, (reachable, code)) in out.iter_mut().zip(status).enumerate() {
                *reachable = match code as u8 {
                    OK => true,
                    SCALAR => self.model.reachable_scalar(x[k], y[k]),
                    _ => false,
                };
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

// The arctangent of fdlibm (Sun Microsystems, 1993: "Permission to use, copy, modify, and
// distribute this software is freely granted, provided that this notice is preserved"), as the
// `libm` crate computes it for the scalar path: its reduction of the argument to five intervals,
// its constants (written as their bits) and its polynomial, operation for operation (no fused
// multiply-add), so that a lane rounds exactly as the scalar code does.

/// atan(1/2), atan(1), atan(3/2) and atan(∞) = π/2, each as a high part and a low part.
const ATAN_HIGH: [f64; 4] = [
    f64::from_bits(0x3FDD_AC67_0561_BB4F),
    f64::from_bits(0x3FE9_21FB_5444_2D18),
    f64::from_bits(0x3FEF_730B_D281_F69B),
    f64::from_bits(0x3FF9_21FB_5444_2D18),
];
const ATAN_LOW: [f64; 4] = [
    f64::from_bits(0x3C7A_2B7F_222F_65E2),
    f64::from_bits(0x3C81_A626_3314_5C07),
    f64::from_bits(0x3C70_0788_7AF0_CBBD),
    f64::from_bits(0x3C91_A626_3314_5C07),
];
/// atan t ≈ t − t·(Σ Pₖ t²⁽ᵏ⁺¹⁾), split into the odd and even k.
const ATAN_POLY: [f64; 11] = [
    f64::from_bits(0x3FD5_5555_5555_550D),
    f64::from_bits(0xBFC9_9999_9998_EBC4),
    f64::from_bits(0x3FC2_4924_9200_83FF),
    f64::from_bits(0xBFBC_71C6_FE23_1671),
    f64::from_bits(0x3FB7_45CD_C54C_206E),
    f64::from_bits(0xBFB3_B0F2_AF74_9A6D),
    f64::from_bits(0x3FB1_0D66_A0D0_3D51),
    f64::from_bits(0xBFAD_DE2D_52DE_FD9A),
    f64::from_bits(0x3FA9_7B4B_2476_0DEB),
    f64::from_bits(0xBFA2_B444_2C6A_6C2F),
    f64::from_bits(0x3F90_AD3A_E322_DA11),
];
/// π − the double nearest π.
const PI_LOW: f64 = f64::from_bits(0x3CA1_A626_3314_5C07);
/// Where the argument's interval changes: 7/16, 11/16, 19/16, 39/16.
const ATAN_BOUNDS: [f64; 4] = [0.4375, 0.6875, 1.1875, 2.4375];
/// Below 2⁻²⁷, atan q rounds to q.
const ATAN_TINY: f64 = 1.0 / 134_217_728.0;
/// The lanes [`atan2_simd`] leaves to libm: |y/x| at least 2⁶² or at most 2⁻⁶² (zeros
/// included), where libm takes its special cases, and NaN or infinite arguments.
const ATAN_RATIO: f64 = 4_611_686_018_427_387_904.0;

/// `atan2(y, x)` with the same bits as `libm::atan2` (the scalar path's), for any arguments.
#[inline(always)]
pub fn atan2(y: f64, x: f64) -> f64 {
    let (angle, other) = atan2_simd(pulp::Scalar, y, x);
    if other { libm::atan2(y, x) } else { angle }
}

/// `atan2(y, x)` on every lane without branches, the same bits as `libm::atan2`, except on the
/// lanes of the returned mask (see [`ATAN_RATIO`]), whose value is meaningless: the caller
/// takes libm's there.
///
/// libm computes q = |y/x| and atan q by fdlibm's method: q below 7/16 directly, else
/// atan q = atan c + atan((q − c)/(1 + q·c)) for c = 1/2, 1, 3/2, or π/2 + atan(−1/q) beyond
/// 39/16; then π − atan q for x < 0, and y's sign. Here every lane takes the same path: the
/// fraction is selected per lane (q/1 below 7/16, where the constants are 0), one division.
#[inline(always)]
fn atan2_simd<S: Simd>(s: S, y: S::f64s, x: S::f64s) -> (S::f64s, S::m64s) {
    let q = s.abs_f64s(s.div_f64s(y, x));
    // 2⁻⁶² < q < 2⁶²: the exponents of y and x differ by less than 64, so libm takes none of
    // its special cases (zeros, infinities and NaN give q = 0, ∞ or NaN, outside).
    let handled = s.and_m64s(
        s.less_than_f64s(q, s.splat_f64s(ATAN_RATIO)),
        s.less_than_f64s(s.splat_f64s(1.0 / ATAN_RATIO), q),
    );
    let one = s.splat_f64s(1.0);
    let (mut numerator, mut denominator) = (q, one);
    let (mut high, mut low) = (s.splat_f64s(0.0), s.splat_f64s(0.0));
    let candidates = [
        (s.sub_f64s(s.mul_f64s(s.splat_f64s(2.0), q), one), s.add_f64s(s.splat_f64s(2.0), q)),
        (s.sub_f64s(q, one), s.add_f64s(q, one)),
        (s.sub_f64s(q, s.splat_f64s(1.5)), s.add_f64s(one, s.mul_f64s(s.splat_f64s(1.5), q))),
        (s.splat_f64s(-1.0), q),
    ];
    for (k, (n, d)) in candidates.into_iter().enumerate() {
        let past = s.greater_than_or_equal_f64s(q, s.splat_f64s(ATAN_BOUNDS[k]));
        numerator = s.select_f64s(past, n, numerator);
        denominator = s.select_f64s(past, d, denominator);
        high = s.select_f64s(past, s.splat_f64s(ATAN_HIGH[k]), high);
        low = s.select_f64s(past, s.splat_f64s(ATAN_LOW[k]), low);
    }
    let t = s.div_f64s(numerator, denominator);
    let z = s.mul_f64s(t, t);
    let w = s.mul_f64s(z, z);
    let mut odd = s.splat_f64s(ATAN_POLY[10]);
    for k in [8, 6, 4, 2, 0] {
        odd = s.add_f64s(s.splat_f64s(ATAN_POLY[k]), s.mul_f64s(w, odd));
    }
    let mut even = s.splat_f64s(ATAN_POLY[9]);
    for k in [7, 5, 3, 1] {
        even = s.add_f64s(s.splat_f64s(ATAN_POLY[k]), s.mul_f64s(w, even));
    }
    let sum = s.add_f64s(s.mul_f64s(z, odd), s.mul_f64s(w, even));
    // high − ((t·sum − low) − t), which is t − t·sum below 7/16 (high = low = 0).
    let atan = s.sub_f64s(high, s.sub_f64s(s.sub_f64s(s.mul_f64s(t, sum), low), t));
    let atan = s.select_f64s(s.less_than_f64s(q, s.splat_f64s(ATAN_TINY)), q, atan);
    // x < 0: π − (atan − π_low); −0 is a lane left to libm.
    let left = s.less_than_f64s(x, s.splat_f64s(0.0));
    let angle = s.select_f64s(
        left,
        s.sub_f64s(s.splat_f64s(PI), s.sub_f64s(atan, s.splat_f64s(PI_LOW))),
        atan,
    );
    // angle > 0 here: y's sign bit makes it −angle, as libm's (atan − π_low) − π is.
    (s.or_f64s(angle, s.and_f64s(y, s.splat_f64s(-0.0))), s.not_m64s(handled))
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;
    use std::f64::consts::TAU;

    use crate::{Chain, Joint, KinematicsError, Robot, Sign, WorkingMode, na};

    /// Whether two angles are the same double (NaN equal to NaN).
    fn same(a: f64, b: f64) -> bool {
        a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
    }

    #[test]
    fn atan2_gives_the_bits_of_libm() {
        let mut values = vec![0.0, 1e-300, 5e-324, 1e-20, 1e-9, 0.3, 0.7, 1.0, 2.5, 1e6, 1e20];
        values.extend([1e300, f64::MAX, f64::INFINITY, f64::NAN, 0.1 + 0.2, 3.0, 7.0, 11.0]);
        // Ratios on and next to the edges of libm's intervals (7/16, 11/16, 19/16, 39/16, 2⁻²⁷)
        // and of its special cases (2⁶⁴).
        for edge in [0.4375, 0.6875, 1.1875, 2.4375, ATAN_TINY, 2f64.powi(64), 2f64.powi(62)] {
            values.extend([edge, edge.next_up(), edge.next_down(), 1.0 / edge]);
        }
        let signed: Vec<f64> = values.iter().flat_map(|&v| [v, -v]).collect();
        for &y in &signed {
            for &x in &signed {
                let (ours, libm) = (atan2(y, x), libm::atan2(y, x));
                assert!(same(ours, libm), "atan2({y:e}, {x:e}) = {ours:e}, libm {libm:e}");
            }
        }
        let mut rng = 0x2545_f491_4f6c_dd1d_u64;
        let mut unit = || {
            rng ^= rng << 13;
            rng ^= rng >> 7;
            rng ^= rng << 17;
            (rng >> 11) as f64 / (1u64 << 53) as f64
        };
        // Ratios from 2⁻⁶² to 2⁻²², where libm returns the ratio itself below 2⁻²⁷ and the
        // lanes take the polynomial all the same.
        for _ in 0..50_000 {
            let q = 2f64.powf(-62.0 + 40.0 * unit());
            for x in [1.0f64, -1.0, 3.7, -0.2, 1e-5] {
                for y in [q * x.abs(), -q * x.abs()] {
                    let (ours, libm) = (atan2(y, x), libm::atan2(y, x));
                    assert!(same(ours, libm), "atan2({y:e}, {x:e}) = {ours:e}, libm {libm:e}");
                }
            }
        }
        for i in 0..400_000 {
            let angle = -PI + TAU * f64::from(i) / 400_000.0;
            let length = 10f64.powf(12.0 * unit() - 6.0);
            let (y, x) = (length * angle.sin(), length * angle.cos());
            assert!(same(atan2(y, x), libm::atan2(y, x)), "atan2({y:e}, {x:e})");
        }
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

    /// Whether `(x, y)` is reachable as the workspace counts it, from the five-bar's geometry
    /// alone, apart from `inverse`: each elbow where the circles of radius l1 about its base and
    /// l2 about the point meet, on the working mode's side; θ its direction from +Y, moved by 2π into
    /// the limits when that fits; the assembly mode the sign of distal 2 × distal 1; the
    /// singularity angles those between the lines of each proximal and distal link, and of the
    /// two distal links. Also returns how clear the verdict is: the least distance of a deciding
    /// quantity from its threshold (mm, radians or a sine).
    fn reachable_by_geometry(model: &Kinematics, x: f64, y: f64) -> (bool, f64) {
        type V = na::Vector2<f64>;
        let cross = |a: V, b: V| a.x * b.y - a.y * b.x;
        let line_angle = |a: V, b: V| cross(a, b).abs().atan2(a.dot(&b).abs());
        let (l1, l2) = (model.l1(), model.l2());
        let p = na::Point2::new(x, y);
        let mut clear = f64::INFINITY;
        let mut verdict = true;
        let mut links = Vec::new();
        for (chain, joint) in [(Chain::One, Joint::Theta1), (Chain::Two, Joint::Theta2)] {
            let base = model.bases()[chain.index()];
            let v = p - base;
            let d = v.norm();
            clear = clear.min((d - (l1 + l2)).abs()).min((d - (l1 - l2).abs()).abs());
            if d > l1 + l2 || d < (l1 - l2).abs() {
                return (false, clear);
            }
            let a = (l1 * l1 - l2 * l2 + d * d) / (2.0 * d);
            let h = (l1 * l1 - a * a).max(0.0).sqrt();
            let (u, n) = (v / d, V::new(-v.y / d, v.x / d));
            let sigma = model.working_mode().of(chain);
            let elbow = [base + a * u + h * n, base + a * u - h * n]
                .into_iter()
                .find(|e| Sign::of(cross(e - base, p - e)) == sigma)
                .expect("one elbow bends each way");
            let (proximal, distal) = (elbow - base, p - elbow);
            let [min, max] = model.limits(joint);
            // The proximal link points along (−sin θ, cos θ): θ = 0 along +Y.
            let mut theta = (-proximal.x).atan2(proximal.y);
            if theta < min && theta + TAU <= max {
                theta += TAU;
            } else if theta > max && theta - TAU >= min {
                theta -= TAU;
            }
            clear = clear.min((theta - min).abs()).min((max - theta).abs());
            verdict &= min <= theta && theta <= max;
            links.push((proximal, distal));
        }
        let (distal1, distal2) = (links[0].1, links[1].1);
        let assembly = cross(distal2, distal1);
        clear = clear.min(assembly.abs() / (l2 * l2));
        verdict &= Sign::of(assembly) == model.assembly_mode().0;
        let margin = model.singularity_margin();
        for angle in [
            line_angle(links[0].0, distal1),
            line_angle(links[1].0, distal2),
            line_angle(distal2, distal1),
        ] {
            clear = clear.min((angle - margin).abs());
            verdict &= angle >= margin;
        }
        (verdict, clear)
    }

    #[test]
    fn reachability_agrees_with_the_five_bars_geometry() {
        let (mut all_inside, mut all_outside) = (0, 0);
        for mode in ["++", "+-", "-+", "--"] {
            for assembly in ["+", "-"] {
                let model = model_in(mode, assembly);
                let (mut compared, mut inside, mut total) = (0, 0, 0);
                for i in 0..161 {
                    for j in 0..101 {
                        // Off the grid's round numbers, so that no point sits on a boundary.
                        let x = -640.0 + 8.0 * f64::from(i) + 0.123;
                        let y = -400.0 + 10.0 * f64::from(j) + 0.0456;
                        total += 1;
                        let (expected, clear) = reachable_by_geometry(&model, x, y);
                        if clear < 1e-9 {
                            continue;
                        }
                        compared += 1;
                        inside += usize::from(expected);
                        assert_eq!(model.reachable(x, y), expected, "{mode}{assembly} ({x}, {y})");
                    }
                }
                assert!(compared * 100 >= total * 99, "{mode}{assembly}: {compared} of {total}");
                (all_inside, all_outside) = (all_inside + inside, all_outside + compared - inside);
            }
        }
        // (Some modes reach little within these limits; together both verdicts are many.)
        assert!(all_inside > 10_000 && all_outside > 10_000, "{all_inside}, {all_outside}");
    }

    fn check_against_scalar(model: &Kinematics, poses: &[Pose]) {
        for dispatch in [Dispatch::Detect, Dispatch::Portable] {
            let mut out = vec![BatchSolution::default(); poses.len()];
            model.inverse_batch_with(dispatch, poses, &mut out);
            let xs: Vec<f64> = poses.iter().map(|p| p.x).collect();
            let ys: Vec<f64> = poses.iter().map(|p| p.y).collect();
            let mut reachable = vec![false; poses.len()];
            model.reachable_batch_with(dispatch, &xs, &ys, &mut reachable);
            let mut columns = [(); 5].map(|()| vec![0.0; poses.len()]);
            let mut status = vec![BatchStatus::Ok; poses.len()];
            let phis: Vec<f64> = poses.iter().map(|p| p.phi).collect();
            let zs: Vec<f64> = poses.iter().map(|p| p.z).collect();
            model.inverse_columns_with(
                dispatch,
                PoseColumns { x: &xs, y: &ys, z: &zs, phi: &phis },
                SolutionColumns::new(&mut columns, &mut status),
            );
            for (k, solution) in out.iter().enumerate() {
                assert_eq!(status[k], solution.status, "{:?} {dispatch:?}", poses[k]);
                let joints = solution.joints.to_array();
                for (column, value) in columns.iter().zip(joints) {
                    assert!(same(column[k], value), "{:?} {dispatch:?}", poses[k]);
                }
                if let Ok(ik) = model.inverse(&poses[k]) {
                    assert!(same(columns[4][k], ik.distal_rotation), "{:?}", poses[k]);
                }
            }
            for ((pose, solution), reachable) in poses.iter().zip(&out).zip(&reachable) {
                assert_eq!(solution.status, scalar_status(model, pose), "{pose:?} {dispatch:?}");
                if let Ok(ik) = model.inverse(pose) {
                    for (batch, scalar) in
                        solution.joints.to_array().iter().zip(ik.joints.to_array())
                    {
                        assert!(same(*batch, scalar), "{pose:?}: {batch} vs {scalar}");
                    }
                }
                let scalar = model.reachable(pose.x, pose.y);
                assert_eq!(*reachable, scalar, "{pose:?} {dispatch:?}");
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
