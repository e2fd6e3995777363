//! Proptest strategies: G-code text, from arbitrary bytes to plausible programs.

use proptest::prelude::*;

/// Arbitrary bytes, with line breaks sprinkled in.
pub fn bytes() -> impl Strategy<Value = Vec<u8>> {
    prop::collection::vec(prop_oneof![8 => any::<u8>(), 1 => Just(b'\n')], 0..400)
}

/// One token of the language, or something close to one.
fn token() -> impl Strategy<Value = String> {
    let words = prop::sample::select(vec![
        "G0",
        "G1",
        "G2",
        "G3",
        "G4",
        "G10",
        "G17",
        "G18",
        "G19",
        "G20",
        "G21",
        "G28",
        "G28.1",
        "G30",
        "G40",
        "G53",
        "G54",
        "G55",
        "G59.3",
        "G80",
        "G90",
        "G91",
        "G90.1",
        "G91.1",
        "G92",
        "G92.1",
        "G92.2",
        "G92.3",
        "G93",
        "G94",
        "G41",
        "G81",
        "M0",
        "M2",
        "M3",
        "M4",
        "M5",
        "M6",
        "M30",
        "M60",
        "L2",
        "L20",
        "P",
        "R",
        "I",
        "J",
        "K",
        "F",
        "S",
        "T",
        "X",
        "Y",
        "Z",
        "C",
        "A",
        "N10",
        "O100",
        "#1=",
        "#<a>=",
        "#<_x>",
        "#5161",
        "[",
        "]",
        "+",
        "-",
        "*",
        "/",
        "**",
        "MOD",
        "EQ",
        "AND",
        "SIN[",
        "ATAN[1]/[",
        "SQRT[",
        "EXISTS[#<a>]",
        "(",
        ")",
        "(MSG,hi)",
        ";",
        "%",
        " ",
        "\n",
        "\t",
        "\r\n",
        ".",
        "1e9",
        "\0",
    ]);
    prop_oneof![
        4 => words.prop_map(str::to_owned),
        2 => (-1e7f64..1e7).prop_map(|value| format!("{value}")),
        2 => (0u32..400).prop_map(|value| value.to_string()),
        1 => Just("0.0001".to_owned()),
    ]
}

/// A soup of tokens: mostly words and numbers, in any order.
pub fn token_soup() -> impl Strategy<Value = String> {
    prop::collection::vec(token(), 0..120).prop_map(|tokens| tokens.concat())
}

/// A valid-looking program: moves with numbers, then an end.
pub fn program() -> impl Strategy<Value = String> {
    let line = prop_oneof![
        (-500.0f64..500.0, -500.0f64..500.0).prop_map(|(x, y)| format!("G0 X{x:.3} Y{y:.3}")),
        (-500.0f64..500.0, 1.0f64..5000.0).prop_map(|(z, f)| format!("G1 Z{z:.3} F{f:.1}")),
        (0.1f64..50.0, 1u32..4).prop_map(|(i, p)| format!("G2 I{i:.3} P{p} F100")),
        (-50.0f64..50.0, 1.0f64..60.0)
            .prop_map(|(x, r)| format!("G3 X[#<_x>+{x:.3}] R{r:.3} F100")),
        Just("G91".to_owned()),
        Just("G90".to_owned()),
        Just("G20".to_owned()),
        Just("G21".to_owned()),
        Just("G18".to_owned()),
        Just("G17".to_owned()),
        (-100.0f64..100.0).prop_map(|x| format!("G92 X{x:.3}")),
        Just("G92.1".to_owned()),
        (1u32..10, -100.0f64..100.0).prop_map(|(p, x)| format!("G10 L2 P{p} X{x:.3}")),
        Just("G28".to_owned()),
        Just("G93 G1 X1 F2".to_owned()),
        Just("G94".to_owned()),
    ];
    prop::collection::vec(line, 0..40).prop_map(|lines| lines.join("\n") + "\nM2\n")
}
