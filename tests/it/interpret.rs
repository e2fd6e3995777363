//! `biscara interpret`: golden inter-files for the programs in `data/programs/`, the pipeline
//! from `gen`, `--origin`, standard input, bad input (exit 1, a `FILE:LINE:COL` message with the
//! line and a caret, no output file, no panic), and the help text.

use std::path::Path;

use crate::golden::check_golden;
use crate::util::{Run, biscara, biscara_with_input, repo_root, skip_or_fail, temp_dir};

fn path_arg(path: &Path) -> &str {
    path.to_str().expect("UTF-8 path")
}

#[test]
fn programs_in_data_match_their_golden_inter_files() {
    let dir = temp_dir("interpret-golden");
    let mut programs: Vec<_> = std::fs::read_dir(repo_root().join("data/programs"))
        .expect("data/programs")
        .map(|entry| entry.expect("entry").path())
        .filter(|path| path.extension().is_some_and(|e| e == "ngc" || e == "gcode"))
        .collect();
    programs.sort();
    assert!(!programs.is_empty());
    for program in programs {
        let name = program.file_stem().and_then(|s| s.to_str()).expect("name").to_owned();
        let run = biscara(&dir, &["interpret", path_arg(&program), "-o", "out.jsonl"]);
        assert_eq!(run.success().stdout, "", "{run}");
        let written = std::fs::read_to_string(dir.join("out.jsonl")).expect("output");
        check_golden(&format!("interpret/{name}.jsonl"), &written);
    }
}

#[test]
fn generated_programs_interpret_from_standard_input() {
    let dir = temp_dir("interpret-gen");
    let job = repo_root().join("data/jobs/pick_place.txt");
    let gcode = biscara(&dir, &["gen", path_arg(&job)]);
    let run =
        biscara_with_input(&dir, &["interpret", "-"], Some(gcode.success().stdout.as_bytes()));
    let lines: Vec<&str> = run.success().stdout.lines().collect();
    // The bundled job's program: first a rapid to the job's home pose, last the end.
    assert_eq!(lines[0], r#"{"line":4,"kind":"rapid","end":[0.0,400.0,100.0,0.0]}"#, "{run}");
    assert!(lines.contains(&r#"{"line":7,"kind":"pick"}"#), "{run}");
    assert!(lines.contains(&r#"{"line":8,"kind":"dwell","seconds":0.3}"#), "{run}");
    assert_eq!(lines.last().copied(), Some(r#"{"line":26,"kind":"end"}"#), "{run}");
}

#[test]
fn the_program_starts_at_the_robots_home_pose_and_origin_shifts_it() {
    let dir = temp_dir("interpret-origin");
    let program = b"G28\nG91 G1 X10 F100\nG90 G0 X0 Y0 Z0 C0\nM2\n";
    let run = biscara_with_input(&dir, &["interpret", "-"], Some(program));
    let lines: Vec<&str> = run.success().stdout.lines().collect();
    // G28 with no G28.1 goes to the home pose: first through the intermediate point (here the
    // current point, the home pose itself), then home.
    assert_eq!(lines[0], r#"{"line":1,"kind":"rapid","end":[0.0,460.798724079689,100.0,0.0]}"#);
    assert_eq!(
        lines[2],
        r#"{"line":2,"kind":"linear","end":[10.0,460.798724079689,100.0,0.0],"feed":100.0}"#
    );
    assert_eq!(lines[3], r#"{"line":3,"kind":"rapid","end":[0.0,0.0,0.0,0.0]}"#);
    let shifted =
        biscara_with_input(&dir, &["interpret", "--origin", "-5,350,20,90", "-"], Some(program));
    let lines: Vec<&str> = shifted.success().stdout.lines().collect();
    assert_eq!(lines[3], r#"{"line":3,"kind":"rapid","end":[-5.0,350.0,20.0,90.0]}"#);
    biscara(&dir, &["interpret", "--origin", "1,2,3", "-"])
        .expect_code(2)
        .stderr_has("expected four numbers X,Y,Z,C");
    biscara(&dir, &["interpret", "--origin", "1,2,NaN,4", "-"])
        .expect_code(2)
        .stderr_has("`NaN` is not a finite number");
}

/// Runs `biscara interpret job.ngc -o out.jsonl` on `content`: exit 1, `message` on stderr, no
/// output file, no temporary file, no panic.
#[track_caller]
/// LinuxCNC's refusals (`--dialect linuxcnc`: `auto` reads some of these programs as another
/// firmware would, see `tests/it/dialects.rs`).
fn check_rejected(content: &[u8], message: &str) -> Run {
    let dir = temp_dir("interpret-bad");
    std::fs::write(dir.join("job.ngc"), content).expect("write");
    let run = biscara(&dir, &["interpret", "--dialect", "linuxcnc", "job.ngc", "-o", "out.jsonl"]);
    run.expect_code(1).stderr_has(message);
    assert!(!run.stderr.contains("panicked"), "{run}");
    let left: Vec<_> =
        std::fs::read_dir(&dir).expect("dir").map(|e| e.expect("entry").file_name()).collect();
    assert_eq!(left, vec![std::ffi::OsString::from("job.ngc")], "no output file\n{run}");
    run
}

#[test]
fn errors_name_file_line_and_column_and_show_a_caret() {
    let run = check_rejected(
        b"G21\nG1 X10 F100\nG2 X20 Y0\nM2\n",
        "job.ngc:3:1: R i j k words all missing for arc",
    );
    assert!(run.stderr.contains("\n    G2 X20 Y0\n    ^^\n"), "{run}");
    let run =
        check_rejected(b"G0 X1\nG0 X[1 + 2 / 0]\nM2\n", "job.ngc:2:12: Attempt to divide by zero");
    assert!(run.stderr.contains("\n    G0 X[1 + 2 / 0]\n               ^\n"), "{run}");
}

#[test]
fn bad_programs_get_a_clear_error_and_no_output() {
    let cases: Vec<(Vec<u8>, &str)> = vec![
        (b"".to_vec(), "job.ngc:1:1: File ended with no percent sign or program end"),
        (b"G0 X1\n".to_vec(), "job.ngc:1:1: File ended with no percent sign or program end"),
        (b"G0 X1 (open\nM2\n".to_vec(), "job.ngc:1:7: Unclosed comment found"),
        (b"G0 G1 X2\nM2\n".to_vec(), "job.ngc:1:4: Two g codes used from same modal group"),
        (b"G1 X0 Y0 F10\nG2 X10 Y0\nM2\n".to_vec(), "job.ngc:2:1: R i j k words all missing"),
        (
            b"G1 F100\nG2 X10.03 Y0 I5\nM2\n".to_vec(),
            "job.ngc:2:1: Radius to end of arc differs from radius to start",
        ),
        (b"G0 X\nM2\n".to_vec(), "job.ngc:1:5: No characters found in reading real value"),
        (
            b"G0 X1e999\nM2\n".to_vec(),
            "job.ngc:1:6: E word with no G70, G76, M66, M67 or M68 to use it",
        ),
        (b"G0 A1\nM2\n".to_vec(), "job.ngc:1:4: A axis word: this robot has the axes X Y Z C only"),
        (b"G0 X1 B2\nM2\n".to_vec(), "job.ngc:1:7: B axis word"),
        (b"G0 U1\nM2\n".to_vec(), "job.ngc:1:4: U axis word"),
        (b"G0 V1\nM2\n".to_vec(), "V axis word"),
        (b"G0 W1\nM2\n".to_vec(), "W axis word"),
        (b"G0 X[1/0]\nM2\n".to_vec(), "job.ngc:1:7: Attempt to divide by zero"),
        (b"G7.5\nM2\n".to_vec(), "job.ngc:1:1: Unknown g code used"),
        (b"M223\nM2\n".to_vec(), "job.ngc:1:1: M-code greater than 199: M223"),
        (b"G1 X1\nM2\n".to_vec(), "job.ngc:1:1: Cannot do g1 with zero feed rate"),
        (b"G0 X1 NaN\nM2\n".to_vec(), "job.ngc:1:7: Bad character 'n' used"),
        (b"G0 Xinf\nM2\n".to_vec(), "job.ngc:1:5: Unknown word where unary operation could be"),
        (
            format!("G0 X1{}\nM2\n", "0".repeat(240)).into_bytes(),
            "job.ngc:1:4: 1e240 is out of range: positions must lie within ±1e6 mm",
        ),
        (b"G0 X[10**400]\nM2\n".to_vec(), "job.ngc:1:5: Calculation resulted in 'infinity'"),
        (b"G0 X1 \x00\nM2\n".to_vec(), "job.ngc:1:7: Bad character byte 0x00 used"),
        (b"G0 X1\n\xff\xfe\x00\x01\nM2\n".to_vec(), "job.ngc:2:1: Bad character byte 0xff used"),
        (b"\x7fELF\x02\x01\x01\x00".to_vec(), "job.ngc:1:1: Bad character byte 0x7f used"),
        (b"G0 X1 Q2\nM2\n".to_vec(), "job.ngc:1:7: Q word with no"),
        (b"G5.2 X1 Y1 P1 L3 F10\nM2\n".to_vec(), "job.ngc:1:1: G5.2 is not supported yet"),
        (b"G18 G5 X1 Y1 I0 J1 P1 Q0 F10\nM2\n".to_vec(), "job.ngc:1:5: Splines must be in the XY"),
        (b"G5.1 X1 Y1 I0 F10\nM2\n".to_vec(), "job.ngc:1:1: Must specify both I and J with G5.1"),
        (
            b"G41.1 D4 F10\nG1 X1\nM2\n".to_vec(),
            "job.ngc:2:1: Length of cutter compensation entry move is not greater than the tool \
             radius",
        ),
        (b"G81 X1 Z-1 R1\nM2\n".to_vec(), "job.ngc:1:1: Cannot feed with zero feed rate"),
        (b"G33 Z-1 K1\nM2\n".to_vec(), "G33 is refused: spindle-synchronised motion"),
        (b"G76 P1 Z-1\nM2\n".to_vec(), "G76 is refused: a lathe code"),
        (b"o100 endsub\nM2\n".to_vec(), "job.ngc:1:1: 1: not in a subroutine definition"),
        (
            format!("G0 X1 ({})\nM2\n", "x".repeat(10 * 1024 * 1024)).into_bytes(),
            "job.ngc:1:253: Command too long",
        ),
    ];
    for (content, message) in &cases {
        check_rejected(content, message);
    }
    let binary: Vec<u8> = (0..=255u8).cycle().take(2000).collect();
    check_rejected(&binary, "job.ngc:1:1: Bad character byte 0x00 used");
}

#[test]
fn a_failed_run_keeps_the_earlier_good_file() {
    let dir = temp_dir("interpret-keep");
    std::fs::write(dir.join("good.ngc"), "G0 X1\nM2\n").expect("write");
    std::fs::write(dir.join("bad.ngc"), "G0 X1\nG1 X2\nM2\n").expect("write");
    biscara(&dir, &["interpret", "good.ngc", "-o", "out.jsonl"]).success();
    let good = std::fs::read_to_string(dir.join("out.jsonl")).expect("read");
    biscara(&dir, &["interpret", "bad.ngc", "-o", "out.jsonl"])
        .expect_code(1)
        .stderr_has("bad.ngc:2:1: Cannot do g1 with zero feed rate");
    assert_eq!(std::fs::read_to_string(dir.join("out.jsonl")).expect("read"), good);
    biscara(&dir, &["interpret", "missing.ngc"])
        .expect_code(1)
        .stderr_has("cannot read missing.ngc");
    biscara(&dir, &["interpret"]).expect_code(2);
}

#[test]
fn interpret_help_text_is_pinned() {
    let dir = temp_dir("interpret-help");
    let run = biscara(&dir, &["interpret", "--help"]);
    run.success();
    assert!(run.stdout.contains("Example:"), "{run}");
    check_golden("help/interpret.txt", &run.stdout);
}

#[test]
fn file_subroutines_come_from_beside_the_program_or_the_subroutine_path() {
    let dir = temp_dir("interpret-subroutines");
    std::fs::create_dir_all(dir.join("lib")).expect("mkdir");
    std::fs::write(dir.join("lib/hop.ngc"), "o<hop> sub\nG0 X#1\no<hop> endsub\n").expect("write");
    std::fs::write(dir.join("main.ngc"), "o<hop> call [3]\nG0 Y400\nM2\n").expect("write");
    // Not beside the program and no path: LinuxCNC's message, exit 1, nothing written.
    let run = biscara(&dir, &["interpret", "main.ngc", "-o", "out.jsonl"]);
    run.expect_code(1);
    assert!(
        run.stderr.contains("EOF in file:main.ngc seeking o-word: o<hop> from line: 1"),
        "{run}"
    );
    assert!(!dir.join("out.jsonl").exists(), "{run}");
    let run = biscara(&dir, &["interpret", "main.ngc", "--subroutine-path", "lib"]);
    let lines: Vec<&str> = run.success().stdout.lines().collect();
    assert_eq!(lines[0], r#"{"line":2,"kind":"rapid","end":[3.0,460.798724079689,100.0,0.0]}"#);
    assert_eq!(lines.len(), 3, "{run}");
    // From standard input: the same with the path; a loop runs from the lines kept.
    let program =
        b"o<hop> call [3]\n#1=0\no1 while [#1 LT 3]\nG0 Y[400 + #1]\n#1=[#1+1]\no1 endwhile\nM2\n";
    let run =
        biscara_with_input(&dir, &["interpret", "-", "--subroutine-path", "lib"], Some(program));
    assert_eq!(run.success().stdout.lines().count(), 5, "{run}");
}

#[test]
fn ini_file_variables_are_read_with_ini_and_joints_takes_it_too() {
    let dir = temp_dir("interpret-ini");
    std::fs::write(dir.join("machine.ini"), "[VARS]\nCHANGE_X = 12.5\nCHANGE_Y = 300\n")
        .expect("write the INI file");
    let program = "G0 X#<_ini[vars]change_x> Y#<_INI[VARS]CHANGE_Y> Z50\nM2\n";
    std::fs::write(dir.join("change.ngc"), program).expect("write the program");
    let run = biscara(&dir, &["interpret", "change.ngc", "--ini", "machine.ini"]);
    let first = run.success().stdout.lines().next().expect("a motion").to_owned();
    assert_eq!(first, r#"{"line":1,"kind":"rapid","end":[12.5,300.0,50.0,0.0]}"#);
    // Every command that reads G-code takes it; without it the name is not defined.
    let joints = biscara(&dir, &["joints", "change.ngc", "--ini", "machine.ini", "-o", "j.csv"]);
    joints.success();
    let without = biscara(&dir, &["interpret", "change.ngc"]);
    assert_eq!(without.code, 1, "{without}");
    assert!(without.stderr.contains("change.ngc:1:5: Named parameter #<_ini[vars]change_x> not"));
}

/// `--ini`'s `[RS274NGC] SUBROUTINE_PATH` is read as LinuxCNC reads it, relative to the INI
/// file's folder (LinuxCNC runs in it): a subroutine calling another there is found (LinuxCNC's
/// own interpreter tests need it; "EOF … seeking o-word o<caller>" before). `USER_M_PATH` says
/// where the user M-codes' programs are: one that is not there is LinuxCNC's unknown M code.
#[test]
fn ini_subroutine_path_and_user_m_path_start_from_the_ini_files_folder() {
    let dir = temp_dir("interpret-ini-paths");
    for folder in ["machine/subs", "machine/mcodes", "job"] {
        std::fs::create_dir_all(dir.join(folder)).expect("mkdir");
    }
    let ini = "[RS274NGC]\nSUBROUTINE_PATH = subs\nUSER_M_PATH = mcodes\n";
    std::fs::write(dir.join("machine/m.ini"), ini).expect("write the INI file");
    let caller = "o<caller> sub\nG0 X1 Y400\no<callee> call\no<caller> endsub\nM2\n";
    std::fs::write(dir.join("machine/subs/caller.ngc"), caller).expect("write");
    let callee = "o<callee> sub\nG1 X3 F100\no<callee> endsub\nM2\n";
    std::fs::write(dir.join("machine/subs/callee.ngc"), callee).expect("write");
    std::fs::write(dir.join("machine/mcodes/M101"), "#!/bin/sh\n").expect("write");
    std::fs::write(dir.join("job/main.ngc"), "G21\no<caller> call\nM101\nM2\n").expect("write");
    let run = biscara(&dir, &["interpret", "job/main.ngc", "--ini", "machine/m.ini"]);
    let lines: Vec<&str> = run.success().stdout.lines().collect();
    assert_eq!(lines.len(), 4, "{run}");
    assert!(lines[1].contains(r#""end":[3.0,400.0,100.0,0.0]"#), "{run}");
    let without = biscara(&dir, &["interpret", "job/main.ngc"]);
    without.expect_code(1);
    assert!(without.stderr.contains("seeking o-word: o<caller>"), "{without}");
    std::fs::write(dir.join("job/m102.ngc"), "G21\nM102\nM2\n").expect("write");
    let unknown = biscara(&dir, &["interpret", "job/m102.ngc", "--ini", "machine/m.ini"]);
    unknown.expect_code(1);
    assert!(unknown.stderr.contains("m102.ngc:2:1: Unknown M code used: M102"), "{unknown}");
}

#[test]
fn an_error_in_a_file_subroutine_names_that_file_and_its_line() {
    let dir = temp_dir("interpret-sub-error");
    std::fs::create_dir_all(dir.join("subs")).expect("subs folder");
    std::fs::write(dir.join("main.ngc"), "G21 G90 F100\nG1 X1\no<bad> call\nM2\n")
        .expect("write the program");
    std::fs::write(dir.join("subs/bad.ngc"), "o<bad> sub\nG1 X2\nG1 X[1/0]\no<bad> endsub\nM2\n")
        .expect("write the subroutine");
    let run = biscara(&dir, &["interpret", "main.ngc", "--subroutine-path", "subs"]);
    assert_eq!(run.code, 1, "{run}");
    assert!(
        run.stderr.starts_with("biscara: error: subs/bad.ngc:3:7: Attempt to divide by zero\n"),
        "{run}"
    );
    assert!(run.stderr.contains("G1 X[1/0]"), "{run}");
    // An error of the program's own lines still names the program.
    std::fs::write(dir.join("main.ngc"), "G21 G90 F100\no<bad> call\nG1 X[2/0]\nM2\n")
        .expect("write the program");
    std::fs::write(dir.join("subs/bad.ngc"), "o<bad> sub\nG1 X2\no<bad> endsub\nM2\n")
        .expect("write the subroutine");
    let run = biscara(&dir, &["interpret", "main.ngc", "--subroutine-path", "subs"]);
    assert!(
        run.stderr.starts_with("biscara: error: main.ngc:3:7: Attempt to divide by zero"),
        "{run}"
    );
}

#[test]
fn a_probing_program_runs_with_a_note_on_how_probing_is_simulated() {
    let dir = temp_dir("interpret-probe");
    let program = "G21 G90 F200\nG0 X0 Y400 Z60\nG38.2 Z40\nG0 Z[#5063 + 5]\nG38.2 Z30\nM2\n";
    std::fs::write(dir.join("probe.ngc"), program).expect("write the program");
    let run = biscara(&dir, &["interpret", "probe.ngc"]);
    let lines: Vec<&str> = run.success().stdout.lines().collect();
    assert_eq!(lines[1], r#"{"line":3,"kind":"code","code":"G38.2"}"#, "{run}");
    assert_eq!(lines[2], r#"{"line":3,"kind":"linear","end":[0.0,400.0,40.0,0.0],"feed":200.0}"#);
    assert_eq!(lines[4], r#"{"line":4,"kind":"rapid","end":[0.0,400.0,45.0,0.0]}"#, "{run}");
    assert!(
        run.stderr.contains("probe.ngc: probe moves run as LinuxCNC's rs274 simulates them")
            && run.stderr.contains("G38.2 ×2"),
        "{run}"
    );
    // The joints follow it like any move.
    biscara(&dir, &["joints", "probe.ngc", "-o", "probe.csv"]).success();
}

#[test]
fn python_plug_ins_run_with_an_ini_file_and_their_errors_fail_cleanly() {
    let python3 = std::process::Command::new("python3").arg("--version").output();
    if !python3.is_ok_and(|out| out.status.success()) {
        skip_or_fail("Python plug-ins", "python3", "");
        return;
    }
    let dir = temp_dir("interpret-python");
    std::fs::create_dir_all(dir.join("config")).expect("config folder");
    // The INI file's relative paths start from its own folder.
    let ini = "[PYTHON]\nPATH_PREPEND = .\nTOPLEVEL = toplevel.py\n";
    std::fs::write(dir.join("config/machine.ini"), ini).expect("write the INI file");
    std::fs::write(dir.join("config/toplevel.py"), "import oword\n").expect("write TOPLEVEL");
    let oword = "import emccanon\n\ndef corner(self, x):\n    emccanon.STRAIGHT_TRAVERSE(\
                 1, x, 300, 50, 0, 0, 0, 0, 0, 0)\n    return x * 2.0\n\ndef boom(self):\n    \
                 return 1 / 0\n";
    std::fs::write(dir.join("config/oword.py"), oword).expect("write oword.py");
    std::fs::write(dir.join("main.ngc"), "G21 G90\no<corner> call [10]\nG0 X#<_value>\nM2\n")
        .expect("write the program");
    let run = biscara(&dir, &["interpret", "main.ngc", "--ini", "config/machine.ini"]);
    let ends: Vec<&str> = run.success().stdout.lines().take(2).collect();
    assert_eq!(
        ends,
        [
            r#"{"line":2,"kind":"rapid","end":[10.0,300.0,50.0,0.0]}"#,
            r#"{"line":3,"kind":"rapid","end":[20.0,460.798724079689,100.0,0.0]}"#
        ]
    );
    // An exception in Python: the line that called it, exit 1, no output file.
    std::fs::write(dir.join("boom.ngc"), "G21 G90\nG0 X1\no<boom> call\nM2\n")
        .expect("write the program");
    let args = ["interpret", "boom.ngc", "--ini", "config/machine.ini", "-o", "boom.jsonl"];
    let run = biscara(&dir, &args);
    assert_eq!(run.code, 1, "{run}");
    assert!(
        run.stderr.starts_with(
            "biscara: error: boom.ngc:3:1: Python subroutine o<boom> failed: ZeroDivisionError: \
             division by zero (at oword.py:8, in boom)\n"
        ),
        "{run}"
    );
    assert!(!dir.join("boom.jsonl").exists(), "a partial output file");
    // Without python3 on the PATH: said so, at the first line that needs it.
    let empty = dir.join("no-python");
    std::fs::create_dir_all(&empty).expect("an empty folder");
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_biscara"))
        .args(["interpret", "main.ngc", "--ini", "config/machine.ini"])
        .current_dir(&dir)
        .env("PATH", &empty)
        .output()
        .expect("run biscara");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.starts_with(
            "biscara: error: main.ngc:2:1: the INI file's Python plug-ins ([PYTHON]) cannot be \
             loaded: cannot run python3 for them"
        ),
        "{stderr}"
    );
}
