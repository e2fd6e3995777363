//! proptest strategies: points files, valid and invalid.

use proptest::prelude::*;

/// Text that looks like a points file: keywords, numbers of every kind, separators and comments.
pub fn points_like() -> impl Strategy<Value = String> {
    let word = prop::sample::select(vec![
        "home", "HOME", "approach", "feed", "dwell", "pick", "place", "Pick", "move", "#", " ",
        "\t", ",", "\n", "\n", "\n", "NaN", "inf", "1e999", "1e300", "-0", "0", "10", "150",
        "-150", "320", "300", "0.3", "50", "100", "-45", "30",
    ]);
    let number = any::<f64>().prop_map(|value| value.to_string());
    prop::collection::vec(prop_oneof![4 => word.prop_map(str::to_owned), 1 => number], 0..80)
        .prop_map(|parts| parts.join(" "))
}
