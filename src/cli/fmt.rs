//! Number formatting for text outputs (fixed decimals are `biscara::text::fixed`).

/// `value` with negative zero turned into zero, for JSON outputs.
pub(crate) fn clean(value: f64) -> f64 {
    value + 0.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clean_removes_negative_zero() {
        assert_eq!(clean(-0.0).to_string(), "0");
    }
}
