//! Quoting input and numbers in error messages.

/// `text` cut to at most 40 characters, with `…` when cut, for quoting input in messages.
pub fn shorten(text: &str) -> String {
    let mut chars = text.chars();
    let head: String = chars.by_ref().take(40).collect();
    if chars.next().is_some() { format!("{head}…") } else { head }
}

/// `value` as written by a person: plain for ordinary magnitudes, `1e300` for huge or tiny ones.
pub fn compact(value: f64) -> String {
    let magnitude = value.abs();
    if magnitude != 0.0 && !(1e-4..1e7).contains(&magnitude) {
        format!("{value:e}")
    } else {
        format!("{value}")
    }
}

/// A serde_json message without the " at line L column C" serde_json appends to it: readers
/// report the position apart, as `LINE:COL: `.
pub fn strip_position(message: &str) -> String {
    match message.rfind(" at line ") {
        Some(index) => message[..index].to_owned(),
        None => message.to_owned(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_quote_input_briefly() {
        assert_eq!(shorten("GOTO/1,2,3"), "GOTO/1,2,3");
        assert_eq!(shorten(&"x".repeat(41)), format!("{}…", "x".repeat(40)));
        assert_eq!(compact(0.0), "0");
        assert_eq!(compact(-1.5), "-1.5");
        assert_eq!(compact(1e300), "1e300");
        assert_eq!(compact(1e-5), "1e-5");
        assert_eq!(strip_position("expected value at line 1 column 3"), "expected value");
        assert_eq!(strip_position("EOF while parsing"), "EOF while parsing");
    }
}
