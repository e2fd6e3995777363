//! Values typed as text by a user (a command line's flags): a number within a range, a time, a
//! list of numbers, sizes. Each parser is a plain function (or makes one), so a command line
//! parser such as clap takes it as it is; the errors say what was typed and what is expected.

use std::ops::RangeInclusive;

/// A typed value that does not parse.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ValueError {
    /// Occurs when the text is no number at all.
    #[error("`{text}` is not a number")]
    NotANumber {
        /// The text typed.
        text: String,
    },
    /// Occurs when a number lies outside the range [`number_in`] allows.
    #[error("{what} must lie in {shown}, got {text}")]
    OutOfRange {
        /// What the number is ("the time step").
        what: &'static str,
        /// The range as shown to the user, with its unit ("[0, 100] mm").
        shown: &'static str,
        /// The text typed.
        text: String,
    },
    /// Occurs when a number [`non_negative`] reads is not finite and ≥ 0.
    #[error("{what} must be a number ≥ 0, got {text}")]
    Negative {
        /// What the number is ("the tolerance").
        what: &'static str,
        /// The text typed.
        text: String,
    },
    /// Occurs when a list of numbers has another count than [`numbers`] expects.
    #[error("expected {expected}, found {found}")]
    Count {
        /// The numbers expected, in words ("four numbers X,Y,Z,C").
        expected: &'static str,
        /// How many were given.
        found: usize,
    },
    /// Occurs when an item of a list of numbers is not a finite number.
    #[error("`{text}` is not a finite number")]
    NotFinite {
        /// The item typed.
        text: String,
    },
    /// Occurs when [`parse_seconds`] reads no finite number ≥ 0.
    #[error("`{text}` is not a time in seconds (a number ≥ 0)")]
    NotSeconds {
        /// The text typed.
        text: String,
    },
    /// Occurs when [`parse_sizes`] reads something other than three numbers joined by `x`.
    #[error("`{text}` is not WxLxH (three sizes in mm, e.g. 30x20x15)")]
    NotSizes {
        /// The text typed.
        text: String,
    },
    /// Occurs when [`parse_sizes`] reads three numbers that are not all finite and positive.
    #[error("`{text}` is not WxLxH (three positive sizes in mm, e.g. 30x20x15)")]
    NotPositiveSizes {
        /// The text typed.
        text: String,
    },
}

/// A parser of a number within `range` (ends included), typed as Rust reads an `f64`; `what`
/// and `shown` word the error: "`{what}` must lie in `{shown}`, got …".
pub fn number_in(
    range: RangeInclusive<f64>,
    what: &'static str,
    shown: &'static str,
) -> impl Fn(&str) -> Result<f64, ValueError> + Clone + Send + Sync + 'static {
    move |text| {
        let value: f64 =
            text.parse().map_err(|_| ValueError::NotANumber { text: text.to_owned() })?;
        if range.contains(&value) {
            Ok(value)
        } else {
            Err(ValueError::OutOfRange { what, shown, text: text.to_owned() })
        }
    }
}

/// A parser of a finite number ≥ 0; `what` words the error.
pub fn non_negative(
    what: &'static str,
) -> impl Fn(&str) -> Result<f64, ValueError> + Clone + Send + Sync + 'static {
    move |text| match text.parse::<f64>() {
        Ok(value) if value.is_finite() && value >= 0.0 => Ok(value),
        _ => Err(ValueError::Negative { what, text: text.to_owned() }),
    }
}

/// A time in seconds: a finite number ≥ 0, blanks around it allowed.
pub fn parse_seconds(text: &str) -> Result<f64, ValueError> {
    match text.trim().parse::<f64>() {
        Ok(value) if value.is_finite() && value >= 0.0 => Ok(value),
        _ => Err(ValueError::NotSeconds { text: text.to_owned() }),
    }
}

/// `N` comma-separated finite numbers (blanks around each allowed); `expected` names them in
/// the error ("four numbers X,Y,Z,C").
pub fn numbers<const N: usize>(text: &str, expected: &'static str) -> Result<[f64; N], ValueError> {
    let values: Vec<&str> = text.split(',').map(str::trim).collect();
    if values.len() != N {
        return Err(ValueError::Count { expected, found: values.len() });
    }
    let mut numbers = [0.0; N];
    for (slot, value) in numbers.iter_mut().zip(values) {
        *slot = value
            .parse::<f64>()
            .ok()
            .filter(|number| number.is_finite())
            .ok_or_else(|| ValueError::NotFinite { text: value.to_owned() })?;
    }
    Ok(numbers)
}

/// `X,Y,Z,C`: four finite numbers (a pose or an offset: mm, mm, mm, degrees).
pub fn parse_xyzc(text: &str) -> Result<[f64; 4], ValueError> {
    numbers(text, "four numbers X,Y,Z,C")
}

/// `X,Y`: two finite numbers (a point, mm).
pub fn parse_xy(text: &str) -> Result<[f64; 2], ValueError> {
    numbers(text, "two numbers X,Y")
}

/// `WxLxH`: three positive sizes (mm), joined by `x` or `X`, e.g. `30x20x15`.
pub fn parse_sizes(text: &str) -> Result<[f64; 3], ValueError> {
    let sizes: Vec<f64> = text
        .split(['x', 'X'])
        .map(|part| part.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|_| ValueError::NotSizes { text: text.to_owned() })?;
    match sizes[..] {
        [w, l, h] if [w, l, h].iter().all(|v| v.is_finite() && *v > 0.0) => Ok([w, l, h]),
        _ => Err(ValueError::NotPositiveSizes { text: text.to_owned() }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[track_caller]
    fn check_error<T: std::fmt::Debug>(result: Result<T, ValueError>, expected: &str) {
        assert_eq!(result.unwrap_err().to_string(), expected);
    }

    #[test]
    fn numbers_in_a_range_include_both_ends() {
        let step = number_in(1e-6..=10.0, "the time step", "[0.000001, 10] s");
        assert_eq!(step("1e-6"), Ok(1e-6));
        assert_eq!(step("10"), Ok(10.0));
        check_error(step("0"), "the time step must lie in [0.000001, 10] s, got 0");
        check_error(step("NaN"), "the time step must lie in [0.000001, 10] s, got NaN");
        check_error(step(" 1"), "` 1` is not a number");
        check_error(step("abc"), "`abc` is not a number");
    }

    #[test]
    fn non_negative_numbers_and_times() {
        let tolerance = non_negative("the tolerance");
        assert_eq!(tolerance("0"), Ok(0.0));
        check_error(tolerance("-1e-9"), "the tolerance must be a number ≥ 0, got -1e-9");
        check_error(tolerance("inf"), "the tolerance must be a number ≥ 0, got inf");
        assert_eq!(parse_seconds(" 2.5 "), Ok(2.5));
        check_error(parse_seconds("-2"), "`-2` is not a time in seconds (a number ≥ 0)");
        check_error(parse_seconds("x"), "`x` is not a time in seconds (a number ≥ 0)");
    }

    #[test]
    fn lists_of_numbers_have_their_count_and_are_finite() {
        assert_eq!(parse_xyzc("1, -2,3.5 ,4"), Ok([1.0, -2.0, 3.5, 4.0]));
        assert_eq!(parse_xy("-0,250"), Ok([-0.0, 250.0]));
        check_error(parse_xyzc("1,2,3"), "expected four numbers X,Y,Z,C, found 3");
        check_error(parse_xy("1"), "expected two numbers X,Y, found 1");
        check_error(parse_xyzc("1,2,nan,4"), "`nan` is not a finite number");
        check_error(parse_xy("1,"), "`` is not a finite number");
    }

    #[test]
    fn sizes_are_three_positive_numbers() {
        assert_eq!(parse_sizes("30x20X 15"), Ok([30.0, 20.0, 15.0]));
        check_error(parse_sizes("axb"), "`axb` is not WxLxH (three sizes in mm, e.g. 30x20x15)");
        let positive = "(three positive sizes in mm, e.g. 30x20x15)";
        check_error(parse_sizes("1x2"), &format!("`1x2` is not WxLxH {positive}"));
        check_error(parse_sizes("1x2x0"), &format!("`1x2x0` is not WxLxH {positive}"));
        check_error(parse_sizes("1x2xinf"), &format!("`1x2xinf` is not WxLxH {positive}"));
    }
}
