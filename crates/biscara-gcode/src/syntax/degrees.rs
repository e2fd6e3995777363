//! LinuxCNC's trigonometry in degrees, to the last bit rs274 computes on x86-64.
//!
//! rs274 converts with `M_PIl`, the 64-bit-significand π of the x87 long double: `SIN[a]` is
//! `sinl((a · π_ld) / 180)`, both operations rounded to long double, and `ASIN[x]`, `ACOS[x]`,
//! `ATAN[y]/[x]` are `(f(x) · 180) / π_ld`, `f` in double, the product in double and the
//! division in long double; the result is rounded to double. The difference from plain `f64`
//! shows where it matters: `COS[90]` is −2.5e-20 in rs274 (π_ld is above π), 6.1e-17 in `f64`,
//! so `COS[90] LT 0` is true there; `TAN[90]` is −4e19, not +1.6e16; `ACOS[0.5]` is exactly 60,
//! not 60.00000000000001. Signed zeros keep their sign (ATAN of −0 and +0 differ by 360°).
//!
//! Long double values are emulated as unevaluated sums of two doubles ("double-double", about
//! 106 bits), rounded to 64 significant bits after each operation as the x87 unit does; sin, cos
//! and tan are evaluated in double-double (reduction by π/2 in three parts, then Taylor series)
//! and their long double result rounded to double, as rs274 rounds it. The conformance test
//! `trigonometry_agrees_to_the_last_bit` compares every value with rs274's to the last bit: all
//! of 803 ASIN, ACOS and ATAN agree, and 598 of 604 SIN, COS and TAN (where the others differ,
//! glibc's `sinl`/`cosl`/`tanl` round the other way).

/// π_ld, the long double nearest π (significand 0xC90FDAA22168C235), as `PI_HI + PI_LO` exactly.
const PI_HI: f64 = std::f64::consts::PI;
const PI_LO: f64 = 1.225_148_454_908_62e-16;

/// `a + b` as a double and its rounding error (exact).
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let sum = a + b;
    let b_part = sum - a;
    let error = (a - (sum - b_part)) + (b - b_part);
    (sum, error)
}

/// `a · b` as a double and its rounding error (exact, by a fused multiply-add).
fn two_product(a: f64, b: f64) -> (f64, f64) {
    let product = a * b;
    (product, a.mul_add(b, -product))
}

/// `hi + lo` (with `|lo|` small next to `|hi|`) rounded to 64 significant bits, ties to even:
/// the rounding of every x87 long double operation.
fn round_to_extended(hi: f64, lo: f64) -> DoubleDouble {
    let (hi, lo) = two_sum(hi, lo);
    // Below about 1e-270 the grid's spacing would underflow; left as it is (zeros, with their
    // sign, are handled by the callers).
    if lo == 0.0 || !hi.is_finite() || hi.abs() < 1e-270 {
        return DoubleDouble { hi: hi + lo, lo: 0.0 };
    }
    // The 64-bit grid in hi's binade is 2^11 times finer than hi's own; hi is on it. Just below a
    // power of two (hi = 2^k, lo < 0) the grid is twice finer again.
    let exponent = ((hi.to_bits() >> 52) & 0x7ff) as i32 - 1023;
    let power_of_two = hi.to_bits() & ((1 << 52) - 1) == 0;
    let shift = if power_of_two && (lo < 0.0) == (hi > 0.0) { 64 } else { 63 };
    let spacing = 2f64.powi(exponent - shift);
    let lo = (lo / spacing).round_ties_even() * spacing;
    DoubleDouble::new(hi, lo)
}

/// `(degrees · π_ld) / 180` in long double arithmetic.
fn to_radians(degrees: f64) -> DoubleDouble {
    let (product, error) = two_product(degrees, PI_HI);
    let product = round_to_extended(product, error + degrees * PI_LO);
    let quotient = product.hi / 180.0;
    // The remainder of the double division is exact; what is left is divided in double.
    let remainder = (-quotient).mul_add(180.0, product.hi) + product.lo;
    round_to_extended(quotient, remainder / 180.0)
}

/// `(radians · 180) / π_ld` as rs274 writes it: `radians · 180.0` is a double product (rounded
/// to double), the division by `M_PIl` is in long double; the result is rounded to double.
fn to_degrees(radians: f64) -> f64 {
    let product = radians * 180.0;
    if product == 0.0 || !product.is_finite() {
        // ±0 keeps its sign (ATAN tells them apart), as the long double division does.
        return product / PI_HI;
    }
    let quotient = DoubleDouble::new(product, 0.0).div(DoubleDouble::new(PI_HI, PI_LO));
    quotient.to_f64()
}

/// A double-double `hi + lo` with `|lo| ≤ ulp(hi) / 2`; a long double when on the 64-bit grid
/// ([`round_to_extended`]).
#[derive(Debug, Clone, Copy, PartialEq)]
struct DoubleDouble {
    hi: f64,
    lo: f64,
}

impl DoubleDouble {
    fn new(hi: f64, lo: f64) -> DoubleDouble {
        let (hi, lo) = two_sum(hi, lo);
        DoubleDouble { hi, lo }
    }

    fn add(self, other: DoubleDouble) -> DoubleDouble {
        let (sum, error) = two_sum(self.hi, other.hi);
        DoubleDouble::new(sum, error + self.lo + other.lo)
    }

    fn mul(self, other: DoubleDouble) -> DoubleDouble {
        let (product, error) = two_product(self.hi, other.hi);
        DoubleDouble::new(product, error + self.hi * other.lo + self.lo * other.hi)
    }

    fn div(self, other: DoubleDouble) -> DoubleDouble {
        let quotient = self.hi / other.hi;
        let remainder = self.add(other.mul(DoubleDouble::new(-quotient, 0.0)));
        DoubleDouble::new(quotient, remainder.hi / other.hi)
    }

    fn scale(self, factor: f64) -> DoubleDouble {
        self.mul(DoubleDouble::new(factor, 0.0))
    }

    fn negate(self) -> DoubleDouble {
        DoubleDouble { hi: -self.hi, lo: -self.lo }
    }

    /// The long double result rounded to double, as rs274 stores it.
    fn to_f64(self) -> f64 {
        let extended = round_to_extended(self.hi, self.lo);
        extended.hi + extended.lo
    }
}

/// π/2 in three doubles, for reducing an angle by whole quarter turns.
const HALF_PI: [f64; 3] =
    [std::f64::consts::FRAC_PI_2, 6.123_233_995_736_766e-17, -1.497_384_904_859_169_8e-33];

/// `sin` and `cos` of a long double angle, in double-double: `angle = k·π/2 + r` with
/// `|r| ≤ π/4`, Taylor series of `r`, then the quarter turns.
fn sin_cos(angle: DoubleDouble) -> (DoubleDouble, DoubleDouble) {
    let turns = (angle.hi / HALF_PI[0]).round();
    if !turns.is_finite() || turns.abs() > 1e15 {
        // Huge angles: sin(h + l) from f64's exactly reduced sin and cos of both parts (l is
        // itself large here, and decides the result as much as h).
        let (sin_hi, cos_hi) = angle.hi.sin_cos();
        let (sin_lo, cos_lo) = angle.lo.sin_cos();
        let sin = sin_hi.mul_add(cos_lo, cos_hi * sin_lo);
        let cos = cos_hi.mul_add(cos_lo, -(sin_hi * sin_lo));
        return (DoubleDouble { hi: sin, lo: 0.0 }, DoubleDouble { hi: cos, lo: 0.0 });
    }
    // turns · π/2, each part's product exact or far below the result's precision.
    let mut reduced = angle;
    for part in HALF_PI {
        let (product, error) = two_product(turns, part);
        reduced = reduced.add(DoubleDouble::new(-product, -error));
    }
    let square = reduced.mul(reduced);
    // sin r = r − r³/3! + …, cos r = 1 − r²/2! + …: 14 terms each reach 2⁻¹⁰⁶ for |r| ≤ π/4.
    let (mut sin, mut cos) = (reduced, DoubleDouble::new(1.0, 0.0));
    let (mut sin_term, mut cos_term) = (reduced, DoubleDouble::new(1.0, 0.0));
    for n in 1..15 {
        let n = f64::from(n);
        sin_term = sin_term.mul(square).scale(-1.0 / ((2.0 * n) * (2.0 * n + 1.0)));
        cos_term = cos_term.mul(square).scale(-1.0 / ((2.0 * n - 1.0) * (2.0 * n)));
        sin = sin.add(sin_term);
        cos = cos.add(cos_term);
    }
    match (turns as i64).rem_euclid(4) {
        0 => (sin, cos),
        1 => (cos, sin.negate()),
        2 => (sin.negate(), cos.negate()),
        _ => (cos.negate(), sin),
    }
}

/// `SIN[degrees]`.
pub(crate) fn sin(degrees: f64) -> f64 {
    if degrees == 0.0 {
        // ±0, as `sinl` returns it (the double-double sums would lose the sign).
        return degrees;
    }
    sin_cos(to_radians(degrees)).0.to_f64()
}

/// `COS[degrees]`.
pub(crate) fn cos(degrees: f64) -> f64 {
    sin_cos(to_radians(degrees)).1.to_f64()
}

/// `TAN[degrees]` (at 90°, π_ld/2 lies past the pole: −4e19).
pub(crate) fn tan(degrees: f64) -> f64 {
    if degrees == 0.0 {
        return degrees;
    }
    let (sin, cos) = sin_cos(to_radians(degrees));
    sin.div(cos).to_f64()
}

/// `ASIN[x]` in degrees (`x` in [−1, 1]): the double `asin`, converted as [`to_degrees`] does
/// (`ASIN[0.5]` is exactly 30).
pub(crate) fn asin(x: f64) -> f64 {
    to_degrees(x.asin())
}

/// `ACOS[x]` in degrees (`x` in [−1, 1]), as [`asin`]: `ACOS[0.5]` is exactly 60.
pub(crate) fn acos(x: f64) -> f64 {
    to_degrees(x.acos())
}

/// `ATAN[y]/[x]` in degrees, in [−180, 180], as [`asin`].
pub(crate) fn atan2(y: f64, x: f64) -> f64 {
    to_degrees(y.atan2(x))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Values rs274 (LinuxCNC 2.9, Debian amd64) prints for these expressions, scaled so that
    /// its four decimals show them: `[SIN[180]] * 1e18` → −0.0502 and so on.
    #[test]
    fn tiny_results_have_rs274s_sign_and_size() {
        assert!((sin(180.0) * 1e18 + 0.0502).abs() < 5e-5, "{}", sin(180.0));
        assert!((cos(90.0) * 1e18 + 0.0251).abs() < 5e-5, "{}", cos(90.0));
        assert!((cos(270.0) * 1e18 - 0.1837).abs() < 5e-5, "{}", cos(270.0));
        assert!(tan(90.0) < -3.9e19 && tan(90.0) > -4.1e19, "{}", tan(90.0));
    }

    #[test]
    fn exact_angles_are_exact() {
        assert_eq!(cos(60.0), 0.5);
        assert_eq!(sin(30.0), 0.5);
        assert_eq!(tan(45.0), 1.0);
        assert_eq!(acos(0.5), 60.0);
        assert_eq!(asin(0.5), 30.0);
        assert_eq!(asin(1.0), 90.0);
        assert_eq!(asin(-1.0), -90.0);
        assert_eq!(acos(-1.0), 180.0);
        assert_eq!(acos(1.0), 0.0);
        assert_eq!(atan2(1.0, 1.0), 45.0);
        assert_eq!(atan2(-0.0, -1.0), -180.0);
        assert_eq!(atan2(0.0, -1.0), 180.0);
        assert_eq!(sin(0.0), 0.0);
        // Signed zeros survive, as in rs274: ATAN of them gives ±180.
        assert!(sin(-0.0).is_sign_negative() && tan(-0.0).is_sign_negative());
        assert!(asin(-0.0).is_sign_negative() && atan2(-0.0, 1.0).is_sign_negative());
        assert_eq!(cos(0.0), 1.0);
    }

    #[test]
    fn elsewhere_as_f64_to_its_rounding() {
        // f64's own conversion to radians is off by up to an ulp of the angle.
        let mut degrees: f64 = -1000.0;
        while degrees < 1000.0 {
            let radians = degrees.to_radians();
            let tolerance = 4e-16 * (1.0 + radians.abs());
            assert!((sin(degrees) - radians.sin()).abs() <= tolerance, "sin {degrees}");
            assert!((cos(degrees) - radians.cos()).abs() <= tolerance, "cos {degrees}");
            let plain = radians.tan();
            let slope = 1.0 + plain * plain;
            assert!((tan(degrees) - plain).abs() <= tolerance * slope, "tan {degrees}");
            degrees += 0.37;
        }
        for x in [-1.0, -0.7, -0.2, 0.0, 1e-9, 0.3, 0.9, 1.0 - 1e-12, 1.0] {
            assert!((asin(x) - x.asin().to_degrees()).abs() <= 1e-13, "asin {x}");
            assert!((acos(x) - x.acos().to_degrees()).abs() <= 1e-13, "acos {x}");
            for y in [-3.0, -0.0, 0.0, 0.5, 7.0] {
                let plain = x.atan2(y).to_degrees();
                assert!((atan2(x, y) - plain).abs() <= 1e-13, "atan2 {x} {y}");
            }
        }
    }

    #[test]
    fn extreme_arguments_give_numbers_or_nan_never_a_panic() {
        // Beyond 5.7e307 degrees the product by π overflows a double (not a long double): NaN,
        // which the interpreter refuses as not finite.
        assert!(sin(f64::MAX).is_nan());
        for value in [0.0, -0.0, 1e-320, -1e-300, 1e-200, 1e15, 1e300, f64::MIN_POSITIVE] {
            for result in [sin(value), cos(value), tan(value)] {
                assert!(result.is_finite(), "{value}: {result}");
            }
        }
        for value in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert!(sin(value).is_nan() && cos(value).is_nan() && tan(value).is_nan());
        }
        assert!(sin(1e-320) > 1.7e-322 && sin(1e-320) < 1.8e-322);
        assert!(asin(1e-320).abs() < 1e-300 && atan2(1e-320, 1.0).abs() < 1e-300);
        assert_eq!(atan2(f64::INFINITY, 1.0), 90.0);
    }

    #[test]
    fn rounding_to_64_bits() {
        // 1 + 2⁻⁶⁴ is below half a step of the 64-bit grid (2⁻⁶³): it rounds to 1.
        assert_eq!(round_to_extended(1.0, 2f64.powi(-64)), DoubleDouble { hi: 1.0, lo: 0.0 });
        // 1 + 3·2⁻⁶⁵ rounds up to 1 + 2⁻⁶³.
        let rounded = round_to_extended(1.0, 3.0 * 2f64.powi(-65));
        assert_eq!(rounded, DoubleDouble { hi: 1.0, lo: 2f64.powi(-63) });
        // Just below 2 the grid is 2⁻⁶³; just below 1, 2⁻⁶⁴.
        let below_one = round_to_extended(1.0, -3.0 * 2f64.powi(-66));
        assert_eq!(below_one, DoubleDouble { hi: 1.0, lo: -2f64.powi(-64) });
    }
}
