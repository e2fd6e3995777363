//! The bad-input catalogue: every file in `tests/bad_input/READER/` must make its command fail
//! with exit code 1, the error message in `NAME.expected` (a golden: `UPDATE_GOLDEN=1` rewrites
//! it), no panic and no output file. Beside the files, each reader also gets generated cases:
//! binary garbage and a line far longer than any limit.

use std::path::Path;

use crate::util::{biscara, repo_root, temp_dir};

/// Each reader: its folder, its file extension, and the command that reads it (`{}` is the
/// file, `{out}` the output that must not appear; `check` gets a good program, [`PROGRAM`]).
const READERS: [(&str, &str, &[&str]); 9] = [
    ("points", "txt", &["clf", "{}", "-o", "{out}"]),
    ("cl", "cl", &["post", "{}", "-o", "{out}"]),
    ("gcode", "ngc", &["interpret", "{}", "-o", "{out}"]),
    ("robot", "json", &["--robot", "{}", "robot", "-o", "{out}"]),
    ("path", "csv", &["joints", "--from", "path", "{}", "-o", "{out}"]),
    ("jsonl", "jsonl", &["interpolate", "--from", "jsonl", "{}", "-o", "{out}"]),
    ("scene", "json", &["check", "--scene", "{}", "program.jsonl", "-o", "{out}"]),
    ("tool_table", "tbl", &["check", "--tool-table", "{}", "program.jsonl", "-o", "{out}"]),
    ("ini", "ini", &["interpret", "--ini", "{}", "program.ngc", "-o", "{out}"]),
];

/// A clean program, for the commands that read a bad file beside a good program.
const PROGRAM: &str = "{\"line\":1,\"kind\":\"rapid\",\"end\":[0.0,400.0,80.0,0.0]}\n";

/// A G-code program that reads `[VARS] X` of its INI file, for the bad INI files.
const INI_PROGRAM: &str = "G0 X#<_ini[vars]x> Y300\nM2\n";

/// The generated cases: the same for every reader.
fn generated_cases() -> Vec<(&'static str, Vec<u8>)> {
    let mut garbage = Vec::new();
    let mut state = 0x9e37_79b9u32;
    for _ in 0..4096 {
        state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
        garbage.push((state >> 24) as u8);
    }
    let mut huge = vec![b'7'; 200_000];
    huge.push(b'\n');
    vec![("binary_garbage", garbage), ("huge_line", huge)]
}

/// Compares `stderr` with the expected message of one case, or writes it under UPDATE_GOLDEN.
fn check_expected(expected_path: &Path, stderr: &str) -> Result<(), String> {
    let update = std::env::var_os("UPDATE_GOLDEN").is_some_and(|value| value != "0");
    match std::fs::read_to_string(expected_path) {
        Ok(expected) if !update => {
            if expected == stderr {
                Ok(())
            } else {
                Err(format!("{}: expected\n{expected}\ngot\n{stderr}", expected_path.display()))
            }
        }
        _ => {
            std::fs::write(expected_path, stderr).expect("write the expected message");
            if update {
                Ok(())
            } else {
                Err(format!("{} was missing: written, review it", expected_path.display()))
            }
        }
    }
}

#[test]
fn every_bad_input_fails_cleanly_with_its_expected_message() {
    let mut failures = Vec::new();
    let mut cases = 0;
    for (reader, extension, command) in READERS {
        let catalogue = repo_root().join("tests/bad_input").join(reader);
        let dir = temp_dir(&format!("bad-input-{reader}"));
        std::fs::write(dir.join("program.jsonl"), PROGRAM).expect("write the good program");
        std::fs::write(dir.join("program.ngc"), INI_PROGRAM).expect("write the INI program");
        let mut inputs: Vec<(String, Vec<u8>)> = Vec::new();
        for entry in std::fs::read_dir(&catalogue).expect("catalogue folder") {
            let path = entry.expect("entry").path();
            if path.extension().and_then(|e| e.to_str()) == Some(extension) {
                let name = path.file_name().and_then(|n| n.to_str()).expect("name").to_owned();
                inputs.push((name, std::fs::read(&path).expect("read case")));
            }
        }
        for (name, bytes) in generated_cases() {
            inputs.push((format!("{name}.{extension}"), bytes));
        }
        inputs.sort();
        assert!(inputs.len() >= 10, "{reader}: only {} cases", inputs.len());
        for (name, bytes) in inputs {
            cases += 1;
            std::fs::write(dir.join(&name), bytes).expect("write case");
            let out = format!("out-of-{name}");
            let args: Vec<String> =
                command.iter().map(|arg| arg.replace("{}", &name).replace("{out}", &out)).collect();
            let args: Vec<&str> = args.iter().map(String::as_str).collect();
            let run = biscara(&dir, &args);
            if run.code != 1 {
                failures.push(format!("{reader}/{name}: exit code {} (want 1)\n{run}", run.code));
                continue;
            }
            if !run.stderr.starts_with("biscara: error: ") {
                failures.push(format!("{reader}/{name}: not a one-error message\n{run}"));
            }
            if dir.join(&out).exists() {
                failures.push(format!("{reader}/{name}: an output file was written"));
            }
            let stem = name.rsplit_once('.').map_or(name.as_str(), |(stem, _)| stem);
            if let Err(message) =
                check_expected(&catalogue.join(format!("{stem}.expected")), &run.stderr)
            {
                failures.push(message);
            }
        }
        let leftovers: Vec<_> = std::fs::read_dir(&dir)
            .expect("dir")
            .filter_map(Result::ok)
            .filter(|entry| entry.file_name().to_string_lossy().starts_with(".out"))
            .collect();
        assert!(leftovers.is_empty(), "{reader}: temporary files left: {leftovers:?}");
    }
    assert!(cases >= 60, "only {cases} cases");
    assert!(
        failures.is_empty(),
        "{} of {cases} bad inputs misbehaved:\n{}",
        failures.len(),
        failures.join("\n\n")
    );
}
