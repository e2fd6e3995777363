//! Time-optimal path parameterisation: the fastest time scaling s(t) of a path s ∈ [0, 1] under
//! velocity and acceleration bounds, starting and ending at rest.
//!
//! # Method
//!
//! TOPP-RA, the reachability analysis of H. Pham and Q.-C. Pham, "A New Approach to
//! Time-Optimal Path Parameterization Based on Reachability Analysis", IEEE Transactions on
//! Robotics 34(3), 2018. The path is cut into intervals of s by a [`Grid`]: equal ones, with the
//! first and last refined geometrically towards the ends. The unknowns are x = ṡ² at each grid point and u = s̈, constant over each
//! interval, so that x_{i+1} = x_i + 2 Δ_i u_i with Δ_i = s_{i+1} − s_i. Every bound is a [`Constraint`]
//! of the form
//!
//! `lo ≤ a(s) · s̈ + b(s) · ṡ² + c(s) ≤ hi`
//!
//! (a joint with q(s): velocity bounds are folded into the largest ṡ² allowed at each point,
//! acceleration bounds have a = q′(s), b = q″(s), c = 0). This crate enforces each constraint at
//! **both ends** of every interval (at s_{i+1} with x_{i+1} = x_i + 2 Δ_i u_i, which is still
//! linear in (u_i, x_i)), so that the piecewise-constant s̈ meets the bounds on either side of
//! each grid point, not only where the interval starts as in the paper's collocation.
//!
//! 1. **Backward pass**: the controllable sets K_i (the ṡ² at s_i from which the end can be
//!    reached at rest) from K_N = {0}: K_i is the projection on x of the polygon
//!    {(u, x) : the constraints at stage i hold and x + 2 Δ_i u ∈ K_{i+1}}. With two unknowns
//!    that linear programme is solved exactly, in closed form, by Fourier–Motzkin elimination of
//!    u (every pair of an upper and a lower bound on u gives a bound on x): no LP solver.
//! 2. **Forward pass**: from x_0 = 0, the greedy choice of the largest u_i that keeps
//!    x_{i+1} in K_{i+1} — optimal by the paper's Theorem 2.
//!
//! The time of each interval is 2 Δ_i / (√x_i + √x_{i+1}), and s(t) is a parabola inside it.
//!
//! # Streaming
//!
//! Memory does not grow with `N`: the passes run over windows of at most
//! `2 · window + 1` grid points. A window's backward pass ends at rest at its last point
//! (K = {0} there: a stop the robot can make, not one it must), and its forward pass commits
//! only the first `window` intervals; the next window starts where the commitment ended. Since
//! rest is feasible everywhere (checked), a state from which the robot can stop within the
//! first window can also stop within the next, longer one: the plan stays feasible. It is
//! optimal whenever stopping from full speed takes fewer than `window` intervals, i.e. unless
//! the look-ahead is too short for the braking distance. Every grid point is evaluated once
//! and every stage planned once: a grid that fits one window is planned whole by
//! [`TimeOptimal::plan`], which then knows the duration; a longer one is planned window by
//! window as [`TimeOptimal::s_at`] advances, and its duration is known once the window holding
//! its end is planned (the forward pass then runs to the end at once).
//!
//! It knows nothing of kinematics or of G-code: the caller evaluates the coefficients through
//! [`PathConstraints`].
//!
//! ```
//! use biscara_timing::{Constraint, Grid, PathConstraints, TimeOptimal};
//!
//! /// s̈ within ±4 /s², ṡ at most 1 /s: a trapezoid of 1/1 + 1/4 = 1.25 s.
//! struct Box;
//! impl PathConstraints for Box {
//!     fn count(&self) -> usize { 1 }
//!     fn evaluate(&mut self, _s: f64, out: &mut [Constraint]) -> f64 {
//!         out[0] = Constraint { a: 1.0, b: 0.0, c: 0.0, lo: -4.0, hi: 4.0 };
//!         1.0
//!     }
//! }
//! let plan = TimeOptimal::new(&mut Box, Grid::uniform(1000), 4096)?;
//! assert!((plan.duration().expect("one window") - 1.25).abs() < 0.01);
//! # Ok::<(), biscara_timing::TimingError>(())
//! ```

#![warn(missing_docs)]

mod planner;
mod polygon;

pub use planner::{Grid, Interval, TimeOptimal};

/// One bound along the path: `lo ≤ a · s̈ + b · ṡ² + c ≤ hi` at one grid point.
///
/// `a`, `b` and `c` must be finite; `lo` and `hi` may be infinite. Rest (ṡ = s̈ = 0) must be
/// allowed: `lo ≤ c ≤ hi`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Constraint {
    /// Coefficient of s̈ (a joint's q′(s)).
    pub a: f64,
    /// Coefficient of ṡ² (a joint's q″(s)).
    pub b: f64,
    /// Constant term (0 for a robot without gravity or friction terms).
    pub c: f64,
    /// Lower bound.
    pub lo: f64,
    /// Upper bound.
    pub hi: f64,
}

/// The bounds along a path, evaluated at grid points.
pub trait PathConstraints {
    /// Number of [`Constraint`]s at every grid point (the same everywhere).
    fn count(&self) -> usize;

    /// Fills `out` (`count()` long) with the constraints at path parameter `s` ∈ [0, 1] and
    /// returns the largest ṡ² allowed there (the velocity bounds: `+∞` when none).
    ///
    /// Called for the grid points in increasing order, each once per pass (see the crate's
    /// documentation on streaming), so it may keep state between calls.
    fn evaluate(&mut self, s: f64, out: &mut [Constraint]) -> f64;

    /// For a path planned by [`TimeOptimal::plan_streamed`]: grid point `index`'s path
    /// parameter, increasing with `index`, or `None` past the last point (a path has at least
    /// two). Called for 0, 1, 2, … in order, once each, each call followed by the
    /// [`evaluate`](Self::evaluate) of that point, so that the path may keep only the points
    /// ahead of its sampling. Never called for a path planned over a [`Grid`]; `None` by
    /// default.
    fn point(&mut self, index: usize) -> Option<f64> {
        let _ = index;
        None
    }

    /// Whether each point's rows come in two halves: the first holds on the interval before
    /// the point, the second on the interval after it (where the path's curvature jumps, such
    /// as where a line meets an arc, the two differ). `false` by default: every row holds on
    /// both sides. `count()` must then be even.
    fn sided(&self) -> bool {
        false
    }
}

/// A path that cannot be timed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum TimingError {
    /// Occurs when a grid has no interval.
    #[error("a path needs at least one grid interval")]
    NoIntervals,
    /// Occurs when a coefficient is not finite, a bound is NaN, or the largest ṡ² is negative or
    /// NaN.
    #[error("at s = {s}: a constraint coefficient is not a finite number")]
    NotFinite {
        /// Path parameter of the grid point.
        s: f64,
    },
    /// Occurs when a streamed path gives a grid point that does not lie past the one before it
    /// (a piece of the path too short for its parameter to tell its ends apart).
    #[error("at s = {s}: the grid point does not lie past the one before it, at {previous}")]
    NotIncreasing {
        /// Path parameter of the grid point.
        s: f64,
        /// Path parameter of the grid point before it.
        previous: f64,
    },
    /// Occurs when a constraint forbids rest (`c` outside `[lo, hi]`).
    #[error("at s = {s}: constraint {index} does not allow rest")]
    RestForbidden {
        /// Path parameter of the grid point.
        s: f64,
        /// Index of the constraint.
        index: usize,
    },
    /// Occurs when the path cannot be traversed at all near `s`: the bounds allow no positive
    /// speed there.
    #[error("at s = {s}: the bounds allow no motion along the path")]
    Stuck {
        /// Path parameter of the grid point.
        s: f64,
    },
    /// Occurs when nothing bounds the speed near `s` (no velocity bound and no acceleration
    /// bound that would stop the motion).
    #[error("at s = {s}: nothing bounds the speed along the path")]
    Unbounded {
        /// Path parameter of the grid point.
        s: f64,
    },
}
