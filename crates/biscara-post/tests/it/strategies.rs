//! proptest strategies: CL text, valid and invalid.

use proptest::prelude::*;

/// Text that looks like CL data: known and unknown words, numbers of every kind, separators,
/// continuations and comments, in random order.
pub fn cl_like() -> impl Strategy<Value = String> {
    let word = prop::sample::select(vec![
        "GOTO", "goto", "RAPID", "FEDRAT", "CIRCLE", "DELAY", "PICK", "PLACE", "PPRINT", "PARTNO",
        "UNITS", "END", "FINI", "SPINDL", "COOLNT", "TLAXIS", "CYCLE", "MMPM", "IPM", "INCHES",
        "MM", "/", ",", " , ", "$", "$$", "\n", "\n", "\n", "(", ")", "NaN", "inf", "-inf",
        "1e999", "1e300", "-0", "0", "1", "-1", "25.4", ".5", "1.", "0,0,1", "0,0,-1",
    ]);
    let number = any::<f64>().prop_map(|value| value.to_string());
    prop::collection::vec(prop_oneof![3 => word.prop_map(str::to_owned), 1 => number], 0..80)
        .prop_map(|parts| parts.concat())
}

/// A valid CL program: statements in any order after a FEDRAT, ending with END and FINI.
pub fn valid_program() -> impl Strategy<Value = String> {
    let coordinate = || -1000.0..1000.0f64;
    let statement = prop_oneof![
        Just("RAPID".to_owned()),
        (coordinate(), coordinate(), coordinate())
            .prop_map(|(x, y, z)| format!("GOTO/{x},{y},{z}")),
        (coordinate(), coordinate(), coordinate(), -720.0..720.0f64)
            .prop_map(|(x, y, z, c)| format!("goto / {x} , {y} , {z} , {c}")),
        (coordinate(), coordinate(), coordinate())
            .prop_map(|(x, y, z)| format!("GOTO/{x},{y},$\n {z},0,0,1")),
        (0.1..1e4f64).prop_map(|f| format!("FEDRAT / {f}, MMPM")),
        (0.1..100.0f64).prop_map(|f| format!("FEDRAT/IPM,{f}")),
        (0.0..10.0f64).prop_map(|s| format!("DELAY/{s}")),
        Just("PICK".to_owned()),
        Just("PLACE".to_owned()),
        "[a-zA-Z0-9 ,.()/]{0,30}".prop_map(|text| format!("PPRINT/{text}")),
        Just("SPINDL/ON".to_owned()),
        Just("UNITS/INCHES".to_owned()),
        Just("UNITS/MM".to_owned()),
        Just("$$ a comment".to_owned()),
    ];
    prop::collection::vec(statement, 0..40)
        .prop_map(|statements| format!("FEDRAT/100\n{}\nEND\nFINI\n", statements.join("\n")))
}
