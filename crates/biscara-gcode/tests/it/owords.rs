//! O-word control flow through the library: the same motions from a file (jumps by byte offset)
//! and from an input read only forwards (lines kept), file subroutines, the bound on what an
//! input read only forwards keeps, and flat memory for long loops and long programs. (Each
//! feature and error is compared with LinuxCNC's `rs274` in `tests/conformance/oword_*.ngc`
//! and `error_oword_*.ngc`, `conformance.rs`.)

use std::fs::File;
use std::io::{BufReader, Cursor, Write};
use std::path::PathBuf;
use std::sync::Arc;

use biscara_gcode::{
    Config, Dialect, GcodeError, InMemory, Setting, interpret, interpret_seekable,
};
use biscara_motion::{Motion, MotionKind};

use crate::memory::{in_a_process_of_its_own, resident_kib};

/// A program with every construct: subroutines with arguments and values, loops, conditions,
/// a Fanuc-style subprogram found by reading on.
const PROGRAM: &str = "\
o<square> sub
  G1 X#1 Y#1 F600
  G1 X[#1 + #2]
  o1 if [#2 GT 5]
    o<square> return [#2]
  o1 endif
  G1 Y[#1 + #2]
o<square> endsub [#1 * #2]
#1 = 0
o10 while [#1 LT 3]
  o<square> call [#1] [#1 * 4]
  G0 Z#<_value>
  #1 = [#1 + 1]
o10 endwhile
o11 repeat [2]
  o12 do
    G0 C[#<_c> + 10]
  o12 while [#<_c> LT 25]
o11 endrepeat
M98 P100 L2
M2
O100
  G0 X[#<_x> + 1]
M99
";

fn ends(motions: &[Motion]) -> Vec<[f64; 4]> {
    motions.iter().filter_map(|motion| motion.kind.end()).collect()
}

#[test]
fn a_file_and_an_input_read_only_forwards_give_the_same_motions() {
    let config = Config::default();
    let seekable: Vec<Motion> = interpret_seekable(Cursor::new(PROGRAM), &config)
        .collect::<Result<_, _>>()
        .unwrap_or_else(|err| panic!("{err}"));
    let forwards: Vec<Motion> = interpret(PROGRAM.as_bytes(), &config)
        .collect::<Result<_, _>>()
        .unwrap_or_else(|err| panic!("{err}"));
    assert_eq!(seekable, forwards);
    let ends = ends(&seekable);
    // Three calls of the square (the third returns early), each followed by Z = its value.
    assert_eq!(ends[3], [0.0, 0.0, 0.0, 0.0], "Z = 0 * 0");
    assert_eq!(ends[7], [5.0, 5.0, 4.0, 0.0], "Z = 1 * 4");
    assert_eq!(ends[10], [10.0, 2.0, 8.0, 0.0], "returned early: Z = 8");
    // repeat 2 × (do … while C < 25): C = 10, 20, 30, then 40 (the do runs once).
    let c: Vec<f64> = ends[11..15].iter().map(|end| end[3]).collect();
    assert_eq!(c, [10.0, 20.0, 30.0, 40.0]);
    // M98 L2: X + 1 twice.
    assert_eq!((ends[15][0], ends[16][0]), (11.0, 12.0));
    assert_eq!(seekable.len(), 18);
    assert_eq!(seekable[17].kind, MotionKind::End);
    // Line numbers are those of the lines that made the motions.
    assert_eq!(seekable[0].line, 2);
    assert_eq!(seekable[15].line, 23);
    assert_eq!(seekable[17].line, 21);
}

#[test]
fn a_jump_to_a_line_not_kept_is_an_error_on_an_input_read_only_forwards() {
    // The subroutine is defined after the call, and the call's line is behind it: a file finds
    // it by reading on and comes back, standard input keeps the lines from the call on.
    let program = "o<later> call\nG0 X2\nM2\no<later> sub\nG0 Y1\no<later> endsub\n";
    let from_file: Vec<Motion> = interpret_seekable(Cursor::new(program), &Config::default())
        .collect::<Result<_, _>>()
        .unwrap_or_else(|err| panic!("{err}"));
    let forwards: Vec<Motion> = interpret(program.as_bytes(), &Config::default())
        .collect::<Result<_, _>>()
        .unwrap_or_else(|err| panic!("{err}"));
    assert_eq!(from_file, forwards);
    // More than 16 MiB of loop body: refused, with what to do.
    let mut big = String::from("#1=0\no1 while [#1 LT 2]\n");
    let comment = format!("({})\n", "x".repeat(200));
    while big.len() < 17 << 20 {
        big.push_str(&comment);
    }
    big.push_str("#1=[#1+1]\no1 endwhile\nM2\n");
    let err = interpret(big.as_bytes(), &Config::default())
        .find_map(Result::err)
        .expect("a loop body over the bound is refused");
    let message = err.to_string();
    assert!(message.contains("give the program as a file"), "{message}");
    assert!(message.contains("16 MiB"), "{message}");
    // The same from a file runs.
    let runs = interpret_seekable(Cursor::new(big), &Config::default()).all(|m| m.is_ok());
    assert!(runs);
}

/// A fresh folder under the system's temporary folder.
fn temp_folder(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("biscara-owords-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("create a temporary folder");
    dir
}

#[test]
fn file_subroutines_are_found_beside_the_program_then_on_the_path() {
    let files = Arc::new(
        InMemory::new()
            .with_file("prog/beside.ngc", "o<beside> sub\nG0 X#1\no<beside> endsub [7]\nM2\n")
            .with_file(
                "library/far.ngc",
                "%\no<far> sub\nG0 Y#1\no<deep> call [#1 + 1]\no<far> endsub\n%\n",
            )
            .with_file("library/deep.ngc", "o<deep> sub\no<deep> endsub\n"),
    );
    let program = PathBuf::from("prog/main.ngc");
    let run = |text: &str, dirs: Vec<PathBuf>| -> Result<Vec<Motion>, GcodeError> {
        interpret_seekable(Cursor::new(text.to_owned()), &Config::default())
            .with_subroutines(Some(program.clone()), dirs)
            .with_environment(files.clone())
            .collect()
    };
    let main = "o<beside> call [3]\no<far> call [#<_value>]\nG0 Z1\nM2\n";
    // Without the path, `far` is looked for in the program itself, to its end.
    let err = run(main, Vec::new()).expect_err("far.ngc is not beside the program");
    assert!(err.to_string().contains("seeking o-word: o<far> from line: 2"), "{err}");
    // It stands at the call, with its text (not at the program's last line, an empty one), and
    // says the subroutine path would help.
    let at = err.location().expect("located");
    assert_eq!((at.line, at.column, at.text.as_str()), (2, 1, "o<far> call [#<_value>]"), "{err}");
    assert_eq!(err.setting(), Some(Setting::SubroutinePath));
    // A subroutine file may call another one, and `%` lines in it do not end the program.
    let library = PathBuf::from("library");
    let motions = run(main, vec![library.clone()]).unwrap_or_else(|err| panic!("{err}"));
    let ends = ends(&motions);
    assert_eq!(ends[0][0], 3.0);
    assert_eq!(ends[1][1], 7.0);
    assert_eq!(ends[2][2], 1.0);
    assert_eq!(motions[1].line, 3, "the line in far.ngc");
    // A name with a path in it is refused, not looked up.
    let err = run("o<../main> call\nM2\n", vec![library.clone()]).expect_err("a name with ..");
    assert!(err.to_string().contains("a subroutine name with '/' or '..' is refused"), "{err}");
    assert!(!err.to_string().contains("--"), "no command-line flag in the library: {err}");
    assert_eq!(err.setting(), Some(Setting::SubroutinePath));
    // Without an environment there are no files: the subroutine is looked for in the program.
    let alone = interpret_seekable(Cursor::new(main.to_owned()), &Config::default())
        .with_subroutines(Some(program.clone()), vec![library])
        .collect::<Result<Vec<Motion>, GcodeError>>();
    let err = alone.expect_err("no files without an environment");
    assert!(err.to_string().contains("seeking o-word: o<beside> from line: 1"), "{err}");
}

#[test]
fn mach3_program_numbers_are_still_program_numbers() {
    let config = Config { dialect: Dialect::Mach3, ..Config::default() };
    let motions: Vec<Motion> = interpret("O0001 (PART)\nG0 X1\nM30\n".as_bytes(), &config)
        .collect::<Result<_, _>>()
        .unwrap_or_else(|err| panic!("{err}"));
    assert_eq!(ends(&motions), [[1.0, 0.0, 0.0, 0.0]]);
}

/// Runs `motions`, checking that resident memory stays flat; returns how many there were. Call
/// it from a test that runs [`in_a_process_of_its_own`].
pub(crate) fn count_in_flat_memory(
    motions: impl Iterator<Item = Result<Motion, GcodeError>>,
) -> usize {
    let start = resident_kib();
    let mut peak = start.unwrap_or(0);
    let mut count = 0usize;
    for motion in motions {
        motion.unwrap_or_else(|err| panic!("{err}"));
        count += 1;
        if count.is_multiple_of(100_000) {
            peak = peak.max(resident_kib().unwrap_or(0));
        }
    }
    if let Some(start) = start {
        let growth = peak.saturating_sub(start);
        assert!(growth < 16 * 1024, "resident memory grew by {growth} KiB over {count} motions");
    }
    count
}

#[test]
fn a_long_loop_runs_in_flat_memory_from_a_file_and_from_standard_input() {
    if !in_a_process_of_its_own(
        "owords::a_long_loop_runs_in_flat_memory_from_a_file_and_from_standard_input",
    ) {
        return;
    }
    // Ten million iterations with RUN_SLOW_TESTS (about 40 million lines read), one million
    // otherwise.
    let iterations =
        if std::env::var_os("RUN_SLOW_TESTS").is_some() { 10_000_000 } else { 1_000_000 };
    let program = format!(
        "#1=0\no1 while [#1 LT {iterations}]\n  G1 X[#1 MOD 100] F1000\n  #1=[#1+1]\no1 endwhile\nM2\n"
    );
    let count =
        count_in_flat_memory(interpret_seekable(Cursor::new(program.clone()), &Config::default()));
    assert_eq!(count, iterations + 1);
    let count = count_in_flat_memory(interpret(program.as_bytes(), &Config::default()));
    assert_eq!(count, iterations + 1);
}

#[test]
fn a_million_line_program_with_subroutines_streams_from_a_file() {
    if !in_a_process_of_its_own(
        "owords::a_million_line_program_with_subroutines_streams_from_a_file",
    ) {
        return;
    }
    let dir = temp_folder("million");
    let path = dir.join("million.ngc");
    let mut out = std::io::BufWriter::new(File::create(&path).expect("create"));
    writeln!(out, "o<step> sub\n  G1 X[#1 MOD 100] Y#2 F1000\no<step> endsub [#1 + 1]")
        .expect("write");
    writeln!(out, "#1=0").expect("write");
    const LINES: usize = 1_000_000;
    for line in 0..LINES / 2 {
        writeln!(out, "o<step> call [{line}] [{}]", line % 7).expect("write");
        writeln!(out, "G0 Z#<_value>").expect("write");
    }
    writeln!(out, "M2").expect("write");
    drop(out);
    let file = BufReader::new(File::open(&path).expect("open"));
    let count = count_in_flat_memory(
        interpret_seekable(file, &Config::default())
            .with_subroutines(Some(path.clone()), Vec::new()),
    );
    assert_eq!(count, LINES + 1);
    let _ = std::fs::remove_dir_all(&dir);
}
