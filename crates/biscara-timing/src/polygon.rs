//! The two-variable linear programmes of one TOPP-RA stage, in (u, x) = (s̈, ṡ²), solved exactly.

/// Below this, a half-plane's coefficient of u, relative to the larger of its two coefficients,
/// counts as zero.
pub(crate) const ZERO: f64 = 1e-12;

/// The half-planes of one stage, kept as what they say: bounds on x alone, constant bounds on
/// u, and bounds `u ≤ p + r·x` (upper) or `u ≥ p + r·x` (lower).
#[derive(Debug, Clone)]
pub(crate) struct Polygon {
    x_lo: f64,
    x_hi: f64,
    u_lo: f64,
    u_hi: f64,
    uppers: Vec<(f64, f64)>,
    lowers: Vec<(f64, f64)>,
    /// Keep only the upper bounds on u (all the forward pass needs).
    uppers_only: bool,
}

impl Default for Polygon {
    fn default() -> Polygon {
        Polygon {
            x_lo: f64::NEG_INFINITY,
            x_hi: f64::INFINITY,
            u_lo: f64::NEG_INFINITY,
            u_hi: f64::INFINITY,
            uppers: Vec::new(),
            lowers: Vec::new(),
            uppers_only: false,
        }
    }
}

impl Polygon {
    /// Empties it; with `uppers_only`, it then keeps only the upper bounds on u: `u_range`'s
    /// upper end stays right, nothing else does.
    pub(crate) fn reset(&mut self, uppers_only: bool) {
        self.clear();
        self.uppers_only = uppers_only;
    }

    /// Empties it.
    pub(crate) fn clear(&mut self) {
        self.x_lo = f64::NEG_INFINITY;
        self.x_hi = f64::INFINITY;
        self.u_lo = f64::NEG_INFINITY;
        self.u_hi = f64::INFINITY;
        self.uppers.clear();
        self.lowers.clear();
    }

    /// Adds `alpha · u + beta · x ≤ gamma`; a bound of +∞ bounds nothing, and a zero row is
    /// dropped (its feasibility is the caller's to check).
    pub(crate) fn push(&mut self, alpha: f64, beta: f64, gamma: f64) {
        if gamma == f64::INFINITY || self.uppers_only && alpha <= 0.0 {
            return;
        }
        let scale = alpha.abs().max(beta.abs());
        if scale == 0.0 {
            return;
        }
        if alpha.abs() <= ZERO * scale {
            if beta > 0.0 {
                self.x_hi = self.x_hi.min(gamma / beta);
            } else {
                self.x_lo = self.x_lo.max(gamma / beta);
            }
            return;
        }
        let (p, r) = (gamma / alpha, -beta / alpha);
        match (alpha > 0.0, r == 0.0) {
            (true, true) => self.u_hi = self.u_hi.min(p),
            (false, true) => self.u_lo = self.u_lo.max(p),
            (true, false) => self.uppers.push((p, r)),
            (false, false) => self.lowers.push((p, r)),
        }
    }

    /// Adds `lo ≤ alpha · u + beta · x ≤ hi`: one division for both sides.
    pub(crate) fn push_range(&mut self, alpha: f64, beta: f64, lo: f64, hi: f64) {
        // |α| ≤ ZERO·max(|α|, |β|) (with α = β = 0) is |α| ≤ ZERO·|β| for finite α.
        if alpha.abs() <= ZERO * beta.abs() {
            self.push(alpha, beta, hi);
            self.push(-alpha, -beta, -lo);
            return;
        }
        let inverse = 1.0 / alpha;
        let r = -beta * inverse;
        // α > 0: u ≤ (hi − βx)/α and u ≥ (lo − βx)/α; α < 0: the other way round.
        let (upper, lower) = if alpha > 0.0 { (hi, lo) } else { (lo, hi) };
        if upper.is_finite() {
            let p = upper * inverse;
            if r == 0.0 {
                self.u_hi = self.u_hi.min(p);
            } else {
                self.uppers.push((p, r));
            }
        }
        if lower.is_finite() && !self.uppers_only {
            let p = lower * inverse;
            if r == 0.0 {
                self.u_lo = self.u_lo.max(p);
            } else {
                self.lowers.push((p, r));
            }
        }
    }

    /// The range of x over the polygon intersected with `lo ≤ x ≤ hi`, by Fourier–Motzkin
    /// elimination of u: `None` when it is empty.
    ///
    /// u exists iff every lower bound `p_l + r_l·x` is at most every upper bound `p_u + r_u·x`,
    /// a linear condition on x per pair: with m half-planes, at most m²/4 pairs of a
    /// multiplication and a comparison (a division only where the range shrinks). The planner
    /// takes [`x_top`](Self::x_top), the same top for its polygons (tested against this).
    #[cfg(test)]
    pub(crate) fn x_range(&self, lo: f64, hi: f64) -> Option<(f64, f64)> {
        let (mut lo, mut hi) = (lo.max(self.x_lo), hi.min(self.x_hi));
        let constant_upper = (self.u_hi < f64::INFINITY).then_some((self.u_hi, 0.0));
        let constant_lower = (self.u_lo > f64::NEG_INFINITY).then_some((self.u_lo, 0.0));
        // The pairs in the order of the bounds (the slanted ones, then the constant one), over
        // plain slices: the chained iterators cost a third of the loop's instructions.
        let lowers = self.lowers.as_slice();
        let mut pair = |(p_upper, r_upper): (f64, f64)| -> bool {
            let mut one = |(p_lower, r_lower): (f64, f64)| -> bool {
                // p_lower + r_lower·x ≤ p_upper + r_upper·x
                let coefficient = r_lower - r_upper;
                let bound = p_upper - p_lower;
                if coefficient > 0.0 {
                    if bound < hi * coefficient {
                        hi = bound / coefficient;
                    }
                } else if coefficient < 0.0 {
                    if bound < lo * coefficient {
                        lo = bound / coefficient;
                    }
                } else if bound < 0.0 {
                    return false;
                }
                true
            };
            for &lower in lowers {
                if !one(lower) {
                    return false;
                }
            }
            constant_lower.is_none_or(&mut one)
        };
        for &upper in &self.uppers {
            if !pair(upper) {
                return None;
            }
        }
        if !constant_upper.is_none_or(&mut pair) || self.u_lo > self.u_hi {
            return None;
        }
        (lo <= hi).then_some((lo, hi))
    }

    /// `x_range(0, hi)`'s top, for a polygon that holds rest, (u, x) = (0, 0): every bound
    /// `γ ≥ 0` (the planner's stages: each row allows rest, and the next point's set holds 0).
    ///
    /// The same pairs in the same order with the same arithmetic, so the same bits, but only
    /// the pairs that can act are tested: each upper's p is ≥ 0 and each lower's ≤ 0, so a
    /// pair's `bound` is ≥ 0; then a pair of coefficient ≤ 0 can neither raise the bottom
    /// (which stays 0, the x-only bounds being ≤ 0 below and ≥ 0 above) nor empty the range,
    /// and only the top moves. One comparison a pair instead of three branches (the polygon is
    /// the planner's largest cost on short moves).
    pub(crate) fn x_top(&self, hi: f64) -> f64 {
        let mut hi = hi.min(self.x_hi);
        let constant_upper = (self.u_hi < f64::INFINITY).then_some((self.u_hi, 0.0));
        let constant_lower = (self.u_lo > f64::NEG_INFINITY).then_some((self.u_lo, 0.0));
        let lowers = self.lowers.as_slice();
        // A pair acts (coefficient > 0 and bound < hi·coefficient) only where, at x = hi, the
        // lower line p_l + r_l·x lies above the upper one, up to rounding (a few ulps of the
        // terms' sizes). So an upper whose line lies clearly above every lower's at hi (by far
        // more than rounding: 1e-12 of the sizes) is skipped, as no pair of it would act; the
        // others are tested pair by pair as before. The lowers' highest line and largest size
        // at hi are computed again only when hi moves (twice a polygon, on average).
        let highest = |hi: f64| {
            let (mut line, mut size) = (f64::NEG_INFINITY, 0.0f64);
            // Comparisons, not `f64::max` (five instructions each for its NaN rule): a NaN
            // line (hi = ∞) is left out here, and the test below takes every pair at hi = ∞.
            for &(p, r) in lowers.iter().chain(&constant_lower) {
                let (value, value_size) = (p + hi * r, p.abs() + hi * r.abs());
                if value > line {
                    line = value;
                }
                if value_size > size {
                    size = value_size;
                }
            }
            (line, size)
        };
        let mut lines = highest(hi);
        let mut pair = |(p_upper, r_upper): (f64, f64)| {
            let (line, size) = lines;
            let upper = p_upper + hi * r_upper;
            let slack = 1e-12 * (p_upper.abs() + hi * r_upper.abs() + size) + 1e-300;
            // (NaN, at hi = ∞, takes the pairs.)
            if upper - line > slack {
                return;
            }
            let before = hi;
            let mut one = |(p_lower, r_lower): (f64, f64)| {
                let coefficient = r_lower - r_upper;
                let bound = p_upper - p_lower;
                debug_assert!(bound >= 0.0 || bound.is_nan(), "a bound below rest: {bound}");
                if (coefficient > 0.0) & (bound < hi * coefficient) {
                    hi = bound / coefficient;
                }
            };
            for &lower in lowers {
                one(lower);
            }
            if let Some(lower) = constant_lower {
                one(lower);
            }
            if hi != before {
                lines = highest(hi);
            }
        };
        for &upper in &self.uppers {
            pair(upper);
        }
        if let Some(upper) = constant_upper {
            pair(upper);
        }
        hi
    }

    /// Whether some u satisfies every half-plane at `x` (O(m), against `x_range`'s O(m²)); the
    /// planner computes the same without building the polygon (`TimeOptimal::cut_stage`).
    #[cfg(test)]
    pub(crate) fn contains_x(&self, x: f64) -> bool {
        let (lo, hi) = self.u_range(x);
        x >= self.x_lo && x <= self.x_hi && lo <= hi
    }

    /// The largest u at the given x (`+∞` when nothing bounds it from above) and the smallest
    /// (`−∞` likewise).
    #[cfg(test)]
    pub(crate) fn u_range(&self, x: f64) -> (f64, f64) {
        let hi = self.uppers.iter().fold(self.u_hi, |hi, &(p, r)| hi.min(p + r * x));
        let lo = self.lowers.iter().fold(self.u_lo, |lo, &(p, r)| lo.max(p + r * x));
        (lo, hi)
    }
}

#[cfg(test)]
mod tests {
    use approx::assert_relative_eq;
    use proptest::prelude::*;

    use super::*;

    #[test]
    fn a_box_and_a_slanted_bound() {
        // |u| ≤ 2, x + u ≤ 3 → largest x is 5 (u = −2), and x ≤ 10 from the caller.
        let mut polygon = Polygon::default();
        polygon.push_range(1.0, 0.0, -2.0, 2.0);
        polygon.push(1.0, 1.0, 3.0);
        let (lo, hi) = polygon.x_range(0.0, 10.0).unwrap();
        assert_eq!(lo, 0.0);
        assert_relative_eq!(hi, 5.0, epsilon = 1e-12);
        let (u_lo, u_hi) = polygon.u_range(4.0);
        assert_relative_eq!(u_lo, -2.0, epsilon = 1e-12);
        assert_relative_eq!(u_hi, -1.0, epsilon = 1e-12);
    }

    #[test]
    fn an_empty_polygon_is_reported() {
        let mut polygon = Polygon::default();
        polygon.push(1.0, 1.0, -1.0); // u + x ≤ −1
        polygon.push(-1.0, 0.0, 0.0); // u ≥ 0
        assert_eq!(polygon.x_range(0.0, 10.0), None);
    }

    proptest! {
        /// The exact range matches a brute-force scan of (u, x) on a fine grid: every scanned
        /// feasible point lies within it, and its ends are feasible for some scanned u.
        #[test]
        fn range_matches_a_scan(
            planes in proptest::collection::vec((-3.0..3.0f64, -3.0..3.0f64, 0.1..4.0f64), 1..6),
        ) {
            let mut polygon = Polygon::default();
            // A box keeps u bounded, and every γ > 0 keeps (0, 0) feasible.
            polygon.push_range(1.0, 0.0, -5.0, 5.0);
            for &(alpha, beta, gamma) in &planes {
                polygon.push(alpha, beta, gamma);
            }
            let (lo, hi) = polygon.x_range(0.0, 8.0).expect("(0, 0) is feasible");
            // The planner's shortcut: the same top, bit for bit.
            prop_assert_eq!(polygon.x_top(8.0).to_bits(), hi.to_bits());
            let feasible = |u: f64, x: f64| {
                u.abs() <= 5.0 + 1e-9
                    && planes.iter().all(|&(a, b, g)| a * u + b * x <= g + 1e-9)
            };
            let mut seen_hi = 0.0f64;
            for i in 0..=200 {
                let x = 8.0 * f64::from(i) / 200.0;
                for j in 0..=200 {
                    let u = -5.0 + 10.0 * f64::from(j) / 200.0;
                    if feasible(u, x) {
                        prop_assert!(x >= lo - 1e-9 && x <= hi + 1e-9, "x {x} outside [{lo}, {hi}]");
                        seen_hi = seen_hi.max(x);
                    }
                }
            }
            // The top is feasible for some u, and a little above it none is: u's bounds from
            // each half-plane directly, at the midpoint of the range u_range gives.
            let u_bounds = |x: f64| {
                let (mut low, mut high) = (-5.0f64, 5.0f64);
                for &(a, b, g) in &planes {
                    if a > 1e-9 {
                        high = high.min((g - b * x) / a);
                    } else if a < -1e-9 {
                        low = low.max((g - b * x) / a);
                    } else if b * x > g + 1e-9 {
                        return (1.0, -1.0);
                    }
                }
                (low, high)
            };
            let (u_lo, u_hi) = polygon.u_range(hi);
            prop_assert!(feasible(0.5 * (u_lo.max(-5.0) + u_hi.min(5.0)), hi));
            prop_assert!(hi >= seen_hi - 1e-9);
            if hi < 8.0 - 1e-3 {
                let (low, high) = u_bounds(hi + 1e-3);
                prop_assert!(low > high, "x = {} is still feasible", hi + 1e-3);
                prop_assert!(!polygon.contains_x(hi + 1e-3));
            }
            prop_assert!(polygon.contains_x(0.0));
            prop_assert!(polygon.contains_x((hi - 1e-6).max(0.0)));
        }
    }
}
