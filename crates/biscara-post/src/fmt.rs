//! Number formatting for the text outputs.

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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fixed_never_prints_negative_zero() {
        assert_eq!(fixed(-0.0001, 3), "0.000");
        assert_eq!(fixed(-1.5, 3), "-1.500");
        assert_eq!(fixed(460.79872, 4), "460.7987");
    }
}
