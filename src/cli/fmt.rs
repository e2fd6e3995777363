//! Number formatting for text outputs.

/// `value` with exactly `decimals` decimals, never printing a negative zero (`-0.000`).
pub(crate) fn fixed(value: f64, decimals: usize) -> String {
    let text = format!("{value:.decimals$}");
    match text.strip_prefix('-') {
        Some(magnitude) if magnitude.bytes().all(|byte| byte == b'0' || byte == b'.') => {
            magnitude.to_owned()
        }
        _ => text,
    }
}

/// `value` with negative zero turned into zero, for JSON outputs.
pub(crate) fn clean(value: f64) -> f64 {
    value + 0.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fixed_never_prints_negative_zero() {
        assert_eq!(fixed(-0.0000001, 6), "0.000000");
        assert_eq!(fixed(-0.0, 3), "0.000");
        assert_eq!(fixed(-1.5, 3), "-1.500");
        assert_eq!(fixed(2.0, 0), "2");
        assert_eq!(clean(-0.0).to_string(), "0");
    }
}
