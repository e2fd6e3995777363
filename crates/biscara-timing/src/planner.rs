//! TOPP-RA's two passes over windows of the grid, and s(t) from the plan.

use crate::polygon::Polygon;
use crate::{Constraint, PathConstraints, TimingError};

/// One interval of the plan: s̈ constant from `s_start` to `s_end`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Interval {
    /// Path parameter where it starts.
    pub s_start: f64,
    /// Path parameter where it ends.
    pub s_end: f64,
    /// ṡ² at the start, 1/s².
    pub x_start: f64,
    /// ṡ² at the end, 1/s².
    pub x_end: f64,
    /// s̈ over the interval, 1/s².
    pub u: f64,
    /// Time it takes, s.
    pub duration: f64,
}

impl Interval {
    /// The path parameter `tau` seconds after the interval starts (clamped to the interval).
    #[inline]
    pub fn s_after(&self, tau: f64) -> f64 {
        let tau = tau.clamp(0.0, self.duration);
        let s = self.s_start + self.x_start.sqrt() * tau + 0.5 * self.u * tau * tau;
        s.clamp(self.s_start, self.s_end)
    }
}

/// The grid points s_0 = 0 < s_1 < … < s_M = 1.
///
/// Without end parts (`ends` = 0): `intervals` equal intervals. With them: `ends` equal
/// intervals over [0, `end`], `intervals` equal ones over [`end`, 1 − `end`] and `ends` over
/// [1 − `end`, 1], so that `end` and 1 − `end` are grid points (where a caller expects the
/// ramps from and to rest to end). Either way the first and the last interval, of length Δ, are
/// then cut geometrically towards the path's end, at Δ·ratio, Δ·ratio², …, Δ·ratio^refine from
/// it (M = `intervals` + 2 · `ends` + 2 · `refine`), so that short ramps are resolved without a
/// fine grid all along.
///
/// TOPP-RA loses time in the interval where the optimum switches from accelerating to cruising
/// (x = ṡ² is linear in s there, below the optimum's corner): a fraction of that interval's
/// traversal time, and nothing when the switch falls on a grid point. A ramp shorter than one
/// interval of a uniform grid would lose most of an interval per stop; with the ends refined,
/// the switch falls in an interval of about (1/ratio − 1) times the ramp.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grid {
    /// Number of equal intervals of the middle part (≥ 1).
    pub intervals: usize,
    /// Number of points added between each end and its nearest equal interval's point.
    pub refine: u32,
    /// Ratio of consecutive refined points' distances to the end, in (0, 1).
    pub ratio: f64,
    /// Number of equal intervals of each end part (0: none).
    pub ends: usize,
    /// Length in s of each end part, in (0, ½) when `ends` > 0.
    pub end: f64,
}

impl Grid {
    /// `intervals` equal intervals.
    pub fn uniform(intervals: usize) -> Grid {
        Grid { intervals, refine: 0, ratio: 0.5, ends: 0, end: 0.0 }
    }

    /// `intervals` equal intervals, the first and last refined `refine` times by `ratio`.
    pub fn refined(intervals: usize, refine: u32, ratio: f64) -> Grid {
        Grid { refine, ratio, ..Grid::uniform(intervals) }
    }

    /// Number of intervals, M.
    pub fn len(&self) -> usize {
        self.base_len() + 2 * self.refine as usize
    }

    /// Whether it has no interval.
    pub fn is_empty(&self) -> bool {
        self.intervals == 0
    }

    /// Intervals before refinement.
    fn base_len(&self) -> usize {
        self.intervals + 2 * self.ends
    }

    /// Point `index` of the grid before refinement (0 ..= `base_len`).
    fn base(&self, index: usize) -> f64 {
        let last = self.base_len();
        let (ends, middle) = (self.ends, self.intervals);
        if index == 0 {
            0.0
        } else if index >= last {
            1.0
        } else if index < ends {
            index as f64 * self.end / ends as f64
        } else if index > ends + middle {
            1.0 - (last - index) as f64 * self.end / ends as f64
        } else {
            self.end + (index - ends) as f64 * (1.0 - 2.0 * self.end) / middle as f64
        }
    }

    /// Grid point `index` (0 ..= M).
    pub fn s(&self, index: usize) -> f64 {
        if self.refine == 0 {
            // The same points without the refined ends' arithmetic: base(0) = 0, base(M) = 1.
            return self.base(index);
        }
        let refine = self.refine as usize;
        let last = self.len();
        // From an end: 0, Δ·ratio^r, …, Δ·ratio, Δ at 0, 1, …, r + 1.
        let from_end = |k: usize, step: f64| {
            if k == 0 { 0.0 } else { step * self.ratio.powi((refine + 1 - k) as i32) }
        };
        if index <= refine {
            from_end(index, self.base(1))
        } else if index + refine >= last {
            1.0 - from_end(last - index, 1.0 - self.base(self.base_len() - 1))
        } else {
            self.base(index - refine)
        }
    }

    fn is_valid(&self) -> bool {
        let refined = self.refine == 0 || (self.base_len() >= 2 && self.refine <= 1000);
        let ends = self.ends == 0 || (self.end > 0.0 && self.end < 0.5);
        self.intervals > 0 && refined && ends && self.ratio > 0.0 && self.ratio < 1.0
    }
}

/// The time-optimal time scaling of a path under [`PathConstraints`] (see the crate's
/// documentation for the method), streamed: at most `2 · window + 1` grid points are held.
///
/// The same `path` must be passed to every call. One value can plan path after path
/// ([`plan`](Self::plan)) without allocating once its buffers have grown.
#[derive(Debug, Clone, Default)]
pub struct TimeOptimal {
    grid: Option<Grid>,
    /// Number of grid intervals.
    intervals: usize,
    window: usize,
    count: usize,
    /// The duration, once the window holding the path's end has been planned.
    duration: Option<f64>,
    /// Grid index of the first point held.
    first: usize,
    /// Path parameter of every point held.
    s: Vec<f64>,
    /// Largest ṡ² of every point held.
    x_max: Vec<f64>,
    /// `count` constraints of every point held.
    rows: Vec<Constraint>,
    /// Top of the controllable set of every point held (its bottom is 0: rest is allowed).
    k_max: Vec<f64>,
    /// The upper bounds on s̈ of every stage held, `stride` a stage, as the backward pass found
    /// them (see [`cut_stage`](Self::cut_stage)): what the forward pass reads.
    cuts: Vec<Cut>,
    stride: usize,
    /// ṡ² of the forward pass at every point held from `forward_from` on, and the duration of
    /// the interval ending there, once the window holds the path's end (the forward pass then
    /// runs to the end at once, to learn the duration).
    forward: Vec<[f64; 2]>,
    /// Local index of `forward[0]` (`usize::MAX` while the end is not held).
    forward_from: usize,
    polygon: Polygon,
    /// Grid index of the next interval's start, ṡ² there, and the plan's time there.
    index: usize,
    x: f64,
    time: f64,
    /// The interval `s_at` is in, and the time it starts.
    current: Option<Interval>,
    elapsed: f64,
    /// Whether the path gives its own grid points ([`plan_streamed`](Self::plan_streamed)).
    streamed: bool,
    /// The rows of a point a stage skips at its start and takes at its end: 0 and `count`, or
    /// for a sided path ([`PathConstraints::sided`]) `count / 2` and `count / 2`.
    skip: usize,
    take: usize,
}

impl TimeOptimal {
    /// Plans `path` over `grid`, holding windows of `window` intervals plus as many of
    /// look-ahead.
    pub fn new<P: PathConstraints + ?Sized>(
        path: &mut P,
        grid: Grid,
        window: usize,
    ) -> Result<TimeOptimal, TimingError> {
        let mut plan = TimeOptimal::default();
        plan.plan(path, grid, window)?;
        Ok(plan)
    }

    /// Plans `path` over `grid` in place of what was planned before, reusing the buffers: the
    /// first window's backward pass, and when that window holds the whole grid, the forward
    /// pass too (the [`duration`](Self::duration) is then known).
    pub fn plan<P: PathConstraints + ?Sized>(
        &mut self,
        path: &mut P,
        grid: Grid,
        window: usize,
    ) -> Result<(), TimingError> {
        self.grid = None;
        self.streamed = false;
        if !grid.is_valid() {
            return Err(TimingError::NoIntervals);
        }
        self.grid = Some(grid);
        self.intervals = grid.len();
        self.start(path, window)
    }

    /// Plans `path` over the grid points it gives itself ([`PathConstraints::point`]), whose
    /// number is not known in advance: a path of any length (a chain of blended moves, whose
    /// end is found as the windows reach it), planned in windows of `window` intervals plus as
    /// many of look-ahead, from rest to rest. The path parameter is the path's own (for
    /// example mm along it); [`s_at`](Self::s_at) returns the last point's after the end.
    pub fn plan_streamed<P: PathConstraints + ?Sized>(
        &mut self,
        path: &mut P,
        window: usize,
    ) -> Result<(), TimingError> {
        self.grid = None;
        self.streamed = true;
        self.intervals = usize::MAX;
        self.start(path, window)
    }

    fn start<P: PathConstraints + ?Sized>(
        &mut self,
        path: &mut P,
        window: usize,
    ) -> Result<(), TimingError> {
        self.window = window.max(1);
        self.count = path.count();
        let sided = path.sided() && self.count.is_multiple_of(2);
        (self.skip, self.take) =
            if sided { (self.count / 2, self.count / 2) } else { (0, self.count) };
        self.duration = None;
        self.first = 0;
        self.s.clear();
        self.x_max.clear();
        self.rows.clear();
        self.index = 0;
        self.x = 0.0;
        self.time = 0.0;
        self.current = None;
        self.elapsed = 0.0;
        let planned = self.fill(path, 0);
        if planned.is_err() {
            self.grid = None;
            self.streamed = false;
        }
        planned
    }

    /// The duration of the plan, s: known from [`plan`](Self::plan) on when the grid fits in
    /// one window, else once sampling has reached the last window (`None` until then). A path
    /// is planned once either way: a long one is sampled in its own time before its end is
    /// known.
    pub fn duration(&self) -> Option<f64> {
        self.duration
    }

    /// The grid (`None` before the first successful plan).
    pub fn grid(&self) -> Option<Grid> {
        self.grid
    }

    /// The path parameter at time `t` (s) from the start; `t` must not decrease from one call to
    /// the next. 1 from the end of the plan on.
    #[inline(always)]
    pub fn s_at<P: PathConstraints + ?Sized>(
        &mut self,
        path: &mut P,
        t: f64,
    ) -> Result<f64, TimingError> {
        // Most samples fall in the interval of the one before: inline, without a call.
        if let Some(interval) = self.current
            && t <= self.elapsed + interval.duration
        {
            return Ok(interval.s_after(t - self.elapsed));
        }
        self.s_at_next(path, t)
    }

    /// [`s_at`](Self::s_at) past the current interval: the plan's next intervals.
    #[inline(never)]
    fn s_at_next<P: PathConstraints + ?Sized>(
        &mut self,
        path: &mut P,
        t: f64,
    ) -> Result<f64, TimingError> {
        loop {
            if let Some(interval) = self.current {
                if t <= self.elapsed + interval.duration {
                    return Ok(interval.s_after(t - self.elapsed));
                }
                self.elapsed += interval.duration;
            }
            self.current = self.next_interval(path)?;
            if self.current.is_none() {
                return Ok(if self.streamed { self.s.last().copied().unwrap_or(0.0) } else { 1.0 });
            }
        }
    }

    /// The next interval of the plan (the forward pass, one step), or `None` at the end.
    pub fn next_interval<P: PathConstraints + ?Sized>(
        &mut self,
        path: &mut P,
    ) -> Result<Option<Interval>, TimingError> {
        if self.index >= self.intervals || (self.grid.is_none() && !self.streamed) {
            return Ok(None);
        }
        if self.forward_from == usize::MAX && self.index - self.first >= self.window {
            self.fill(path, self.index)?;
        }
        let local = self.index - self.first;
        let (s_start, s_end) = (self.s[local], self.s[local + 1]);
        let step = s_end - s_start;
        // The forward pass to the end kept each interval's ṡ² at its end and its duration.
        let [x_end, duration] = match local.checked_sub(self.forward_from) {
            Some(k) => self.forward[k + 1],
            None => {
                let x_end = self.forward_step(local);
                [x_end, 2.0 * step / (self.x.sqrt() + x_end.sqrt())]
            }
        };
        if !duration.is_finite() {
            return Err(TimingError::Stuck { s: s_start });
        }
        let interval = Interval {
            s_start,
            s_end,
            x_start: self.x,
            x_end,
            u: (x_end - self.x) / (2.0 * step),
            duration,
        };
        self.index += 1;
        self.x = x_end;
        self.time += duration;
        Ok(Some(interval))
    }

    /// ṡ² at the end of the interval from held point `local`, from ṡ² = `self.x` at its start:
    /// the largest s̈ that keeps the next point controllable.
    fn forward_step(&self, local: usize) -> f64 {
        self.forward_step_from(local, self.x)
    }

    fn forward_step_from(&self, local: usize, x: f64) -> f64 {
        let step = self.s[local + 1] - self.s[local];
        // The stage's upper bounds in the order `cut_stage` met them (the same minimum, signed
        // zeros included); a neutral cut gives +∞, which never replaces it.
        let mut u_max = f64::INFINITY;
        for cut in &self.cuts[local * self.stride..(local + 1) * self.stride] {
            let u = (cut.upper - cut.beta * x) * cut.inverse;
            if u < u_max {
                u_max = u;
            }
        }
        let x_end = (x + 2.0 * step * u_max).clamp(0.0, self.k_max[local + 1]);
        if self.first + local + 1 == self.intervals || x_end.is_nan() { 0.0 } else { x_end }
    }

    /// The range of s̈ the stage from held point `local` allows at ṡ² = `x`, and whether the
    /// bounds on x alone hold there: the stage's polygon (see [`build_stage`](Self::build_stage))
    /// cut at one x, with no polygon built. Each row whose s̈ coefficient α is not zero
    /// (relative to its ṡ² coefficient, as [`Polygon`] decides) bounds s̈ by
    /// `(bound − β·x) / α`; a row with α ≈ 0 bounds x alone. The upper bounds are kept in
    /// `cuts` for the forward pass, which then computes only `(bound − β·x) / α` at its x (once
    /// a stage, instead of sorting the rows again: a quarter of the planner's instructions).
    #[inline]
    fn cut_stage(&mut self, local: usize, x: f64) -> (f64, f64, bool) {
        let step = self.s[local + 1] - self.s[local];
        let (mut u_lo, mut u_hi, mut x_ok) = (f64::NEG_INFINITY, f64::INFINITY, true);
        let stride = self.stride;
        let mut cuts = self.cuts[local * stride..(local + 1) * stride].iter_mut();
        // Comparisons rather than `f64::max`/`min`, whose NaN handling costs five instructions
        // each, with the same results: the coefficients are never NaN (`evaluate` checks them
        // finite), u_lo and u_hi never become NaN, and a NaN bound leaves them as they are.
        let mut bound = |alpha: f64, beta: f64, lo: f64, hi: f64| {
            // [`Polygon`]'s test, |α| ≤ ZERO·max(|α|, |β|), is |α| ≤ ZERO·|β| for finite α: when
            // |β| ≤ |α| both hold only for α = 0. A zero row (α = β = 0, which [`Polygon`]
            // drops) takes the bound on x, which it meets: β·x = 0 and lo ≤ 0 ≤ hi (rest is
            // allowed, `evaluate` checks it).
            let cut = cuts.next().expect("a cut a row");
            if alpha.abs() <= crate::polygon::ZERO * beta.abs() {
                let value = beta * x;
                x_ok &= value <= hi && value >= lo;
                *cut = Cut::NONE;
                return;
            }
            // An infinite bound needs no test: it gives u = +∞ above (−∞ below), which changes
            // nothing, as its sign and the inverse's go together (x and β·x are finite where
            // the range is read).
            let (upper, lower) = if alpha > 0.0 { (hi, lo) } else { (lo, hi) };
            let inverse = 1.0 / alpha;
            *cut = Cut { upper, beta, inverse };
            let u = (upper - beta * x) * inverse;
            if u < u_hi {
                u_hi = u;
            }
            let u = (lower - beta * x) * inverse;
            if u > u_lo {
                u_lo = u;
            }
        };
        let (start, end) = stage_ranges(self.count, self.skip, self.take, local);
        for row in &self.rows[start] {
            bound(row.a, row.b, row.lo - row.c, row.hi - row.c);
        }
        for row in &self.rows[end] {
            bound(row.a + 2.0 * step * row.b, row.b, row.lo - row.c, row.hi - row.c);
        }
        bound(2.0 * step, 1.0, 0.0, self.k_max[local + 1]);
        (u_lo, u_hi, x_ok)
    }

    /// Holds grid points `from` to `from + 2·window` (or the end), evaluating those not held
    /// yet, and runs the backward pass over them; when they reach the end, the forward pass too.
    fn fill<P: PathConstraints + ?Sized>(
        &mut self,
        path: &mut P,
        from: usize,
    ) -> Result<(), TimingError> {
        let grid = self.grid.unwrap_or(Grid::uniform(1));
        let mut last = (from + 2 * self.window).min(self.intervals);
        let mut next = from;
        if !self.x_max.is_empty() && from >= self.first {
            let held_last = self.first + self.x_max.len() - 1;
            let drop = (from - self.first).min(self.x_max.len());
            self.s.drain(..drop);
            self.x_max.drain(..drop);
            self.rows.drain(..drop * self.count);
            next = held_last + 1;
        } else {
            self.s.clear();
            self.x_max.clear();
            self.rows.clear();
        }
        self.first = from;
        self.forward_from = usize::MAX;
        for index in next..=last {
            let s = if self.streamed {
                match path.point(index) {
                    Some(s) if index == 0 || s > self.s[self.s.len() - 1] => s,
                    Some(s) if s.is_nan() => return Err(TimingError::NotFinite { s }),
                    Some(s) => {
                        let previous = self.s[self.s.len() - 1];
                        return Err(TimingError::NotIncreasing { s, previous });
                    }
                    None if index < 2 => return Err(TimingError::NoIntervals),
                    None => {
                        self.intervals = index - 1;
                        last = index - 1;
                        break;
                    }
                }
            } else {
                grid.s(index)
            };
            self.evaluate(path, s)?;
        }
        self.backward()?;
        if last == self.intervals {
            self.forward_to_end()?;
        }
        Ok(())
    }

    /// The forward pass from the next interval to the path's end, kept; the duration.
    fn forward_to_end(&mut self) -> Result<(), TimingError> {
        let from = self.index - self.first;
        let mut forward = std::mem::take(&mut self.forward);
        forward.clear();
        forward.push([self.x, 0.0]);
        let mut x = self.x;
        let mut time = self.time;
        for local in from..self.x_max.len() - 1 {
            let x_end = self.forward_step_from(local, x);
            let step = self.s[local + 1] - self.s[local];
            let duration = 2.0 * step / (x.sqrt() + x_end.sqrt());
            if !duration.is_finite() {
                self.forward = forward;
                return Err(TimingError::Stuck { s: self.s[local] });
            }
            time += duration;
            forward.push([x_end, duration]);
            x = x_end;
        }
        self.forward = forward;
        self.forward_from = from;
        self.duration = Some(time);
        Ok(())
    }

    /// Evaluates the grid point at `s`, at the end of what is held.
    fn evaluate<P: PathConstraints + ?Sized>(
        &mut self,
        path: &mut P,
        s: f64,
    ) -> Result<(), TimingError> {
        let start = self.rows.len();
        self.rows.resize(start + self.count, Constraint::default());
        let x_max = path.evaluate(s, &mut self.rows[start..]);
        if x_max.is_nan() || x_max < 0.0 {
            return Err(TimingError::NotFinite { s });
        }
        // One test a row in the common case: the spread is 0 when a, b and c are finite (NaN
        // otherwise: ∞·0 is NaN), and a NaN bound fails the comparisons.
        let clean = self.rows[start..].iter().all(|row| {
            let spread = row.a * 0.0 + row.b * 0.0 + row.c * 0.0;
            spread == 0.0 && row.lo <= row.c && row.c <= row.hi
        });
        if !clean {
            return Err(Self::bad_row(&self.rows[start..], s));
        }
        self.s.push(s);
        self.x_max.push(x_max);
        Ok(())
    }

    /// Why the rows of the point at `s` were refused: the first row that is not finite or
    /// forbids rest.
    #[cold]
    #[inline(never)]
    fn bad_row(rows: &[Constraint], s: f64) -> TimingError {
        for (offset, row) in rows.iter().enumerate() {
            let finite = row.a.is_finite() && row.b.is_finite() && row.c.is_finite();
            if !finite || row.lo.is_nan() || row.hi.is_nan() {
                return TimingError::NotFinite { s };
            }
            if !(row.lo <= row.c && row.c <= row.hi) {
                return TimingError::RestForbidden { s, index: offset };
            }
        }
        TimingError::NotFinite { s }
    }

    /// The controllable sets of the points held, from rest at the last one.
    fn backward(&mut self) -> Result<(), TimingError> {
        let held = self.x_max.len();
        self.k_max.clear();
        self.k_max.resize(held, 0.0);
        self.stride = self.count - self.skip + self.take + 1;
        self.cuts.clear();
        self.cuts.resize((held - 1) * self.stride, Cut::NONE);
        for local in (0..held - 1).rev() {
            // Where the speed limit itself is controllable (cruising, far from a stop), it is the
            // top: the feasible x form an interval that holds 0, so one O(m) test settles it,
            // without building the polygon. (The stage's cuts are kept either way; at an
            // infinite x_max the range is meaningless and not read.)
            let x_max = self.x_max[local];
            let (u_lo, u_hi, x_ok) = self.cut_stage(local, x_max);
            if x_max.is_finite() && x_ok && u_lo <= u_hi {
                self.k_max[local] = x_max;
                continue;
            }
            self.build_stage(local, false);
            // (u, x) = (0, 0) is feasible (rest is allowed everywhere and 0 ∈ K_{i+1}): the
            // range runs from 0 to its top.
            let top = self.polygon.x_top(x_max);
            if top.is_infinite() {
                return Err(TimingError::Unbounded { s: self.s[local] });
            }
            self.k_max[local] = top.max(0.0);
        }
        Ok(())
    }

    /// Where in `rows` the constraints of the stage from held point `local` to the next are: at
    /// its start and at its end. A sided path's points carry the rows that hold before them
    /// (first half) and after them (second half): a stage takes the second half of its start's
    /// and the first half of its end's.
    #[inline]
    fn stage_ranges(&self, local: usize) -> (std::ops::Range<usize>, std::ops::Range<usize>) {
        stage_ranges(self.count, self.skip, self.take, local)
    }

    /// The half-planes in (u, x) of the stage from held point `local` to the next: every
    /// constraint at both ends of the interval, and the next point in its controllable set (only
    /// the upper bounds on u with `uppers_only`).
    fn build_stage(&mut self, local: usize, uppers_only: bool) {
        let step = self.s[local + 1] - self.s[local];
        self.polygon.reset(uppers_only);
        let (start, end) = self.stage_ranges(local);
        for row in &self.rows[start] {
            self.polygon.push_range(row.a, row.b, row.lo - row.c, row.hi - row.c);
        }
        // At the interval's end, x_{i+1} = x + 2Δu: a'·u + b'·(x + 2Δu).
        for row in &self.rows[end] {
            self.polygon.push_range(
                row.a + 2.0 * step * row.b,
                row.b,
                row.lo - row.c,
                row.hi - row.c,
            );
        }
        self.polygon.push_range(2.0 * step, 1.0, 0.0, self.k_max[local + 1]);
    }
}

/// [`TimeOptimal::stage_ranges`] of a path of `count` rows a point.
#[inline]
fn stage_ranges(
    count: usize,
    skip: usize,
    take: usize,
    local: usize,
) -> (std::ops::Range<usize>, std::ops::Range<usize>) {
    let (start, end) = (local * count, (local + 1) * count);
    (start + skip..end, end..end + take)
}

/// One upper bound on s̈ of a stage at ṡ² = x: `(upper − beta·x) · inverse`.
#[derive(Debug, Clone, Copy)]
struct Cut {
    upper: f64,
    beta: f64,
    inverse: f64,
}

impl Cut {
    /// A row that bounds s̈ from above by nothing: +∞ at every finite x.
    const NONE: Cut = Cut { upper: f64::INFINITY, beta: 0.0, inverse: 1.0 };
}

#[cfg(test)]
mod tests {
    use approx::assert_relative_eq;
    use proptest::prelude::*;

    use super::*;

    /// |s̈| ≤ `acceleration`, ṡ ≤ `rate`.
    struct Trapezoid {
        rate: f64,
        acceleration: f64,
        calls: usize,
    }

    impl PathConstraints for Trapezoid {
        fn count(&self) -> usize {
            1
        }
        fn evaluate(&mut self, _s: f64, out: &mut [Constraint]) -> f64 {
            self.calls += 1;
            let a = self.acceleration;
            out[0] = Constraint { a: 1.0, b: 0.0, c: 0.0, lo: -a, hi: a };
            self.rate * self.rate
        }
    }

    fn trapezoid(rate: f64, acceleration: f64) -> Trapezoid {
        Trapezoid { rate, acceleration, calls: 0 }
    }

    /// Runs the forward pass to the end: the sum of the intervals' durations, which must be
    /// the duration the plan then reports.
    fn run<P: PathConstraints>(plan: &mut TimeOptimal, path: &mut P) -> f64 {
        let mut total = 0.0;
        while let Some(interval) = plan.next_interval(path).unwrap() {
            total += interval.duration;
        }
        let duration = plan.duration().expect("known at the end");
        assert!((total - duration).abs() <= 1e-9 * total, "{total} against {duration}");
        duration
    }

    /// The closed-form shortest time of a trapezoid (or triangle) over s ∈ [0, 1].
    fn exact(rate: f64, acceleration: f64) -> f64 {
        if rate * rate >= acceleration {
            2.0 / acceleration.sqrt()
        } else {
            1.0 / rate + rate / acceleration
        }
    }

    #[test]
    fn a_box_gives_the_trapezoid() {
        for (rate, acceleration) in [(1.0, 4.0), (3.0, 4.0), (0.2, 50.0)] {
            let plan =
                TimeOptimal::new(&mut trapezoid(rate, acceleration), Grid::uniform(2000), 4096)
                    .unwrap();
            let duration = plan.duration().expect("one window");
            let shortest = exact(rate, acceleration);
            // The plan is feasible for the continuous problem, so never shorter; the switch from
            // accelerating to cruising falls on the grid, which costs at most a little.
            assert!(duration >= shortest * (1.0 - 1e-12), "{rate} {acceleration}");
            assert_relative_eq!(duration, shortest, max_relative = 2e-3);
        }
    }

    #[test]
    fn refined_ends_resolve_short_ramps() {
        // A ramp of s = 1/2000 (ṡ = 1 at 1000 /s²) on a grid of 10 intervals: uniform, each stop
        // costs most of an interval at cruise speed; refined, almost nothing.
        let shortest = exact(1.0, 1000.0);
        let uniform =
            TimeOptimal::new(&mut trapezoid(1.0, 1000.0), Grid::uniform(10), 4096).unwrap();
        let uniform = uniform.duration().unwrap();
        assert!(uniform > shortest + 0.1, "{uniform}");
        let grid = Grid::refined(10, 11, 0.5);
        assert_eq!(grid.s(0), 0.0);
        assert_eq!(grid.s(1), 0.1 / 2048.0);
        assert_eq!(grid.s(12), 0.1);
        assert_eq!(grid.s(13), 0.2);
        assert_relative_eq!(grid.s(grid.len() - 1), 1.0 - 0.1 / 2048.0, epsilon = 1e-15);
        assert_eq!(grid.s(grid.len()), 1.0);
        let refined = TimeOptimal::new(&mut trapezoid(1.0, 1000.0), grid, 4096).unwrap();
        let refined = refined.duration().unwrap();
        assert!(refined >= shortest * (1.0 - 1e-12));
        assert_relative_eq!(refined, shortest, max_relative = 2e-4);
    }

    #[test]
    fn end_parts_put_the_ramps_on_grid_points() {
        // Ramps of s = 1/8 (ṡ = 1 at 4 /s²): with grid points at 1/8 and 7/8, three intervals
        // give the exact trapezoid; the refined points and end parts are where they should be.
        let grid = Grid { ends: 1, end: 0.125, ..Grid::uniform(1) };
        assert_eq!((grid.len(), grid.s(1), grid.s(2), grid.s(3)), (3, 0.125, 0.875, 1.0));
        let plan = TimeOptimal::new(&mut trapezoid(1.0, 4.0), grid, 100).unwrap();
        assert_relative_eq!(plan.duration().unwrap(), exact(1.0, 4.0), max_relative = 1e-12);
        let grid = Grid { ends: 2, end: 0.2, ..Grid::refined(3, 2, 0.5) };
        let points: Vec<f64> = (0..=grid.len()).map(|index| grid.s(index)).collect();
        let expected = [0.0, 0.025, 0.05, 0.1, 0.2, 0.4, 0.6, 0.8, 0.9, 0.95, 0.975, 1.0];
        assert_eq!(points.len(), expected.len());
        for (point, expected) in points.iter().zip(expected) {
            assert_relative_eq!(*point, expected, epsilon = 1e-15);
        }
        assert!(TimeOptimal::new(&mut trapezoid(1.0, 4.0), Grid { end: 0.5, ..grid }, 9).is_err());
    }

    #[test]
    fn samples_follow_the_plan_and_end_at_one() {
        for window in [4096, 60] {
            let mut path = trapezoid(1.0, 4.0);
            let mut plan = TimeOptimal::new(&mut path, Grid::uniform(500), window).unwrap();
            // A plan longer than its window learns its duration as it is sampled.
            let known = plan.duration();
            assert_eq!(known.is_some(), window >= 500);
            let duration = exact(1.0, 4.0);
            let mut previous = 0.0;
            for k in 0..=1100 {
                let t = duration * f64::from(k) / 1000.0;
                let s = plan.s_at(&mut path, t).unwrap();
                assert!(s >= previous, "s went back at {k}");
                previous = s;
                // In the cruise, ṡ = 1: s(0.5) = 1/8 (the ramp, 0.25 s) + 0.25.
                if k == 400 {
                    assert_relative_eq!(s, 0.375, epsilon = 2e-3);
                }
            }
            assert_eq!(previous, 1.0);
            let learned = plan.duration().expect("known at the end");
            assert_relative_eq!(learned, duration, max_relative = 2e-3);
            if let Some(known) = known {
                assert_eq!(known, learned);
            }
            assert_eq!(plan.s_at(&mut path, duration * 2.0).unwrap(), 1.0);
        }
    }

    #[test]
    fn one_value_plans_path_after_path() {
        let mut plan = TimeOptimal::default();
        for (rate, acceleration) in [(1.0, 4.0), (3.0, 4.0), (0.2, 50.0)] {
            let mut path = trapezoid(rate, acceleration);
            plan.plan(&mut path, Grid::uniform(700), 100).unwrap();
            let mut fresh = TimeOptimal::new(&mut path, Grid::uniform(700), 100).unwrap();
            let fresh = run(&mut fresh, &mut path);
            assert_eq!(run(&mut plan, &mut path), fresh);
        }
        // A failed plan leaves nothing to sample.
        assert!(plan.plan(&mut Pushed, Grid::uniform(10), 100).is_err());
        assert_eq!(plan.next_interval(&mut Pushed).unwrap(), None);
    }

    #[test]
    fn short_windows_stay_feasible_and_long_ones_are_optimal() {
        // Braking from ṡ = 1 at 4 /s² takes s = 1/8: 125 of 1000 intervals.
        let mut path = trapezoid(1.0, 4.0);
        let whole = TimeOptimal::new(&mut path, Grid::uniform(1000), 4096).unwrap();
        let whole = whole.duration().unwrap();
        assert_eq!(path.calls, 1001);
        let mut path = trapezoid(1.0, 4.0);
        let mut long = TimeOptimal::new(&mut path, Grid::uniform(1000), 150).unwrap();
        assert_eq!(long.duration(), None);
        assert_relative_eq!(run(&mut long, &mut path), whole, max_relative = 1e-12);
        // Windows of 150 + 150 intervals: every grid point is evaluated once (planned once, not
        // once for the duration and again for the samples).
        assert_eq!(path.calls, 1001);
        let mut path = trapezoid(1.0, 4.0);
        let mut short = TimeOptimal::new(&mut path, Grid::uniform(1000), 20).unwrap();
        let mut total = 0.0;
        while let Some(interval) = short.next_interval(&mut path).unwrap() {
            assert!(interval.u.abs() <= 4.0 * (1.0 + 1e-9));
            assert!(interval.x_end <= 1.0 + 1e-12);
            total += interval.duration;
        }
        assert!(total > whole);
        assert_eq!(short.duration(), Some(total));
    }

    /// The trapezoid over the points 0, 1/n, …, 1 that it gives itself.
    struct Streamed {
        inner: Trapezoid,
        points: usize,
        asked: usize,
    }

    impl PathConstraints for Streamed {
        fn count(&self) -> usize {
            1
        }
        fn evaluate(&mut self, s: f64, out: &mut [Constraint]) -> f64 {
            self.inner.evaluate(s, out)
        }
        fn point(&mut self, index: usize) -> Option<f64> {
            assert_eq!(index, self.asked, "points are asked in order, once each");
            self.asked += 1;
            (index <= self.points).then(|| index as f64 / self.points as f64)
        }
    }

    #[test]
    fn a_streamed_path_plans_as_its_grid() {
        for window in [4096, 60, 7] {
            let mut grid_path = trapezoid(1.0, 4.0);
            let mut whole = TimeOptimal::new(&mut grid_path, Grid::uniform(1000), window).unwrap();
            let expected = run(&mut whole, &mut grid_path);
            let mut path = Streamed { inner: trapezoid(1.0, 4.0), points: 1000, asked: 0 };
            let mut plan = TimeOptimal::default();
            plan.plan_streamed(&mut path, window).unwrap();
            assert_eq!(plan.duration().is_some(), window >= 1000);
            let mut last = 0.0;
            let mut t = 0.0;
            while last < 1.0 {
                t += 1e-3;
                last = plan.s_at(&mut path, t).unwrap();
            }
            assert_eq!(path.inner.calls, 1001);
            assert_relative_eq!(plan.duration().unwrap(), expected, max_relative = 1e-12);
            assert_relative_eq!(t, expected, epsilon = 1.1e-3);
        }
        let mut one = Streamed { inner: trapezoid(1.0, 4.0), points: 0, asked: 0 };
        assert_eq!(
            TimeOptimal::default().plan_streamed(&mut one, 10),
            Err(TimingError::NoIntervals)
        );
    }

    /// The trapezoid over points whose third does not lie past its second.
    struct Stalled(Trapezoid);

    impl PathConstraints for Stalled {
        fn count(&self) -> usize {
            self.0.count()
        }
        fn evaluate(&mut self, s: f64, out: &mut [Constraint]) -> f64 {
            self.0.evaluate(s, out)
        }
        fn point(&mut self, index: usize) -> Option<f64> {
            [0.0, 0.5, 0.5, 1.0].get(index).copied()
        }
    }

    #[test]
    fn a_streamed_point_that_does_not_advance_is_an_error_saying_so() {
        let mut path = Stalled(trapezoid(1.0, 4.0));
        let err = TimeOptimal::default().plan_streamed(&mut path, 10).unwrap_err();
        assert_eq!(err, TimingError::NotIncreasing { s: 0.5, previous: 0.5 });
        assert_eq!(
            err.to_string(),
            "at s = 0.5: the grid point does not lie past the one before it, at 0.5"
        );
    }

    /// |s̈| ≤ 4 everywhere but on the side before s = 0.05 (in the ramp up), on which
    /// |s̈| ≤ `before`; with `sided`, each side holds only on its own interval.
    struct Switching {
        before: f64,
        sided: bool,
    }

    impl PathConstraints for Switching {
        fn count(&self) -> usize {
            2
        }
        fn evaluate(&mut self, s: f64, out: &mut [Constraint]) -> f64 {
            let row = |limit: f64| Constraint { a: 1.0, b: 0.0, c: 0.0, lo: -limit, hi: limit };
            let before = if s == 0.05 { self.before } else { 4.0 };
            out[0] = row(before);
            out[1] = row(4.0);
            1.0
        }
        fn sided(&self) -> bool {
            self.sided
        }
    }

    #[test]
    fn sided_rows_hold_on_their_own_side() {
        let duration = |before: f64, sided: bool| {
            let mut path = Switching { before, sided };
            TimeOptimal::new(&mut path, Grid::uniform(100), 4096).unwrap().duration().unwrap()
        };
        // The same rows on both sides: sided or not, the same plan.
        assert_eq!(duration(4.0, true), duration(4.0, false));
        // A tight bound only on the interval before s = 0.05: sided, the interval after it is
        // free to accelerate, so the plan is faster than with the bound on both sides; both
        // slower than without it.
        let (sided, both) = (duration(0.01, true), duration(0.01, false));
        assert!(sided < both, "{sided} {both}");
        assert!(sided > duration(4.0, true));
    }

    struct Blocked;
    impl PathConstraints for Blocked {
        fn count(&self) -> usize {
            1
        }
        fn evaluate(&mut self, s: f64, out: &mut [Constraint]) -> f64 {
            out[0] = Constraint { a: 1.0, b: 0.0, c: 0.0, lo: -1.0, hi: 1.0 };
            if (0.35..0.65).contains(&s) { 0.0 } else { 1.0 }
        }
    }

    struct Pushed;
    impl PathConstraints for Pushed {
        fn count(&self) -> usize {
            1
        }
        fn evaluate(&mut self, _s: f64, out: &mut [Constraint]) -> f64 {
            out[0] = Constraint { a: 1.0, b: 0.0, c: 2.0, lo: -1.0, hi: 1.0 };
            1.0
        }
    }

    #[test]
    fn paths_that_cannot_be_timed_are_errors() {
        // One point where ṡ must be 0 is a stop on the way; two in a row block the path.
        assert_eq!(
            TimeOptimal::new(&mut Blocked, Grid::uniform(10), 100).unwrap_err(),
            TimingError::Stuck { s: 0.4 }
        );
        assert_eq!(
            TimeOptimal::new(&mut Pushed, Grid::uniform(10), 100).unwrap_err(),
            TimingError::RestForbidden { s: 0.0, index: 0 }
        );
        assert_eq!(
            TimeOptimal::new(&mut trapezoid(1.0, 1.0), Grid::uniform(0), 100).unwrap_err(),
            TimingError::NoIntervals
        );
        assert!(matches!(
            TimeOptimal::new(&mut trapezoid(f64::INFINITY, f64::INFINITY), Grid::uniform(10), 100),
            Err(TimingError::Unbounded { .. })
        ));
    }

    /// Two "joints" q_j(s) with q′ and q″ from sums of sines, velocity and acceleration bounds.
    #[derive(Debug, Clone)]
    struct Joints {
        waves: Vec<[f64; 3]>,
        velocity: [f64; 2],
        acceleration: [f64; 2],
    }

    impl Joints {
        /// q′_j(s) and q″_j(s).
        fn derivatives(&self, s: f64) -> [[f64; 2]; 2] {
            let mut result = [[0.0; 2]; 2];
            for (k, &[amplitude, frequency, phase]) in self.waves.iter().enumerate() {
                let j = k % 2;
                let angle = frequency * s + phase;
                result[j][0] += amplitude * angle.cos() + 0.3;
                result[j][1] -= amplitude * frequency * angle.sin();
            }
            result
        }
    }

    impl PathConstraints for Joints {
        fn count(&self) -> usize {
            2
        }
        fn evaluate(&mut self, s: f64, out: &mut [Constraint]) -> f64 {
            let mut x_max = f64::INFINITY;
            for (j, [first, second]) in self.derivatives(s).into_iter().enumerate() {
                let a = self.acceleration[j];
                out[j] = Constraint { a: first, b: second, c: 0.0, lo: -a, hi: a };
                if first != 0.0 {
                    x_max = x_max.min((self.velocity[j] / first).powi(2));
                }
            }
            x_max
        }
    }

    fn joints() -> impl Strategy<Value = Joints> {
        (
            proptest::collection::vec((0.1..3.0f64, 0.5..20.0f64, 0.0..6.3f64), 2..6),
            (0.5..5.0f64, 0.5..5.0f64),
            (1.0..50.0f64, 1.0..50.0f64),
        )
            .prop_map(|(waves, velocity, acceleration)| Joints {
                waves: waves.into_iter().map(|(a, f, p)| [a, f, p]).collect(),
                velocity: [velocity.0, velocity.1],
                acceleration: [acceleration.0, acceleration.1],
            })
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

        /// Every bound holds at both ends of every interval, the plan starts and ends at rest,
        /// and a windowed plan is never faster than the whole one.
        #[test]
        fn plans_keep_every_bound(path in joints(), window in 5usize..300, refine in 0u32..12) {
            let grid = Grid::refined(400, refine, 0.7);
            let intervals = grid.len();
            let mut whole_path = path.clone();
            let whole = TimeOptimal::new(&mut whole_path, grid, 4096);
            prop_assume!(whole.is_ok());
            let whole = whole.unwrap().duration().expect("one window");
            let mut windowed_path = path.clone();
            let mut plan = TimeOptimal::new(&mut windowed_path, grid, window).unwrap();
            let mut total = 0.0;
            let mut count = 0;
            while let Some(interval) = plan.next_interval(&mut windowed_path).unwrap() {
                if count == 0 {
                    prop_assert_eq!(interval.x_start, 0.0);
                }
                for (s, x) in [(interval.s_start, interval.x_start), (interval.s_end, interval.x_end)] {
                    let mut rows = [Constraint::default(); 2];
                    let x_max = path.clone().evaluate(s, &mut rows);
                    prop_assert!(x <= x_max * (1.0 + 1e-9) + 1e-12, "ṡ² {x} > {x_max} at {s}");
                    for (j, row) in rows.iter().enumerate() {
                        let value = row.a * interval.u + row.b * x;
                        let slack = 1e-9 * (row.hi + (row.a * interval.u).abs() + (row.b * x).abs());
                        prop_assert!(value.abs() <= row.hi + slack, "joint {j} at {s}: {value} > {}", row.hi);
                    }
                }
                prop_assert_eq!(interval.s_start, grid.s(count));
                prop_assert_eq!(interval.s_end, grid.s(count + 1));
                prop_assert!(interval.s_end > interval.s_start);
                total += interval.duration;
                count += 1;
                if count == intervals {
                    prop_assert_eq!(interval.x_end, 0.0);
                }
            }
            prop_assert_eq!(count, intervals);
            let duration = plan.duration().expect("known at the end");
            prop_assert!((total - duration).abs() <= 1e-9 * total);
            prop_assert!(duration >= whole * (1.0 - 1e-9));
        }
    }
}
