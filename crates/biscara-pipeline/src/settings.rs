//! The sampling settings of [`SamplingConfig`](crate::SamplingConfig) as a user types them (a
//! command line's flags): each parser holds the range a user may give, and its error says it.

use biscara_text::{ValueError, number_in};

/// The time step `dt`, seconds: in [0.000001, 10].
pub fn parse_time_step(text: &str) -> Result<f64, ValueError> {
    number_in(1e-6..=10.0, "the time step", "[0.000001, 10] s")(text)
}

/// A pick's or place's hold (`grip_time`), seconds: in [0, 3600].
pub fn parse_grip_time(text: &str) -> Result<f64, ValueError> {
    number_in(0.0..=3600.0, "the time", "[0, 3600] s")(text)
}

/// The default corner tolerance `blend` (G64 P), mm: in [0, 100] (0: G64 with no P).
pub fn parse_blend(text: &str) -> Result<f64, ValueError> {
    number_in(0.0..=100.0, "the blend tolerance", "[0, 100] mm")(text)
}

/// The most robot time to sample (`time_limit`), seconds: in [0, 1e9].
pub fn parse_time_limit(text: &str) -> Result<f64, ValueError> {
    number_in(0.0..=1e9, "the time limit", "[0, 1e9] s")(text)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_setting_takes_its_range_and_names_it() {
        assert_eq!(parse_time_step("0.000001"), Ok(1e-6));
        assert_eq!(parse_grip_time("3600"), Ok(3600.0));
        assert_eq!(parse_blend("0"), Ok(0.0));
        assert_eq!(parse_time_limit("1e9"), Ok(1e9));
        let refused = [
            (parse_time_step("0"), "the time step must lie in [0.000001, 10] s, got 0"),
            (parse_grip_time("3601"), "the time must lie in [0, 3600] s, got 3601"),
            (parse_blend("100.5"), "the blend tolerance must lie in [0, 100] mm, got 100.5"),
            (parse_time_limit("-1"), "the time limit must lie in [0, 1e9] s, got -1"),
            (parse_time_step("x"), "`x` is not a number"),
        ];
        for (result, message) in refused {
            assert_eq!(result.unwrap_err().to_string(), message);
        }
    }
}
