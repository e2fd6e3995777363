//! Outputs are atomic even when the run is interrupted, and a closed pipe is not an error.

use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use crate::util::temp_dir;

/// A program long enough to keep `joints` busy for seconds: zig-zag moves, 1 mm each.
fn long_program(lines: usize) -> String {
    let mut text = String::from("G21 G90 G94\nG0 X-100 Y300 Z50 C0\n");
    for i in 0..lines {
        let (col, row) = (i % 200, (i / 200) % 100);
        let x = if row % 2 == 0 { -100.0 + col as f64 } else { 99.0 - col as f64 };
        text.push_str(&format!("G1 X{x:.3} Y{:.3} F6000\n", 300.0 + row as f64));
    }
    text.push_str("M2\n");
    text
}

#[test]
fn sigint_during_a_long_run_leaves_no_temporary_file_and_the_old_output() {
    let dir = temp_dir("sigint");
    std::fs::write(dir.join("long.ngc"), long_program(300_000)).expect("write program");
    std::fs::write(dir.join("traj.csv"), "the earlier good file\n").expect("write");
    let mut child = Command::new(env!("CARGO_BIN_EXE_biscara"))
        .args(["joints", "long.ngc", "-o", "traj.csv"])
        .current_dir(&dir)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("spawn biscara");
    let temporary = |dir: &std::path::Path| {
        std::fs::read_dir(dir)
            .expect("dir")
            .filter_map(Result::ok)
            .any(|entry| entry.file_name().to_string_lossy().starts_with(".traj.csv.tmp"))
    };
    let start = Instant::now();
    while !temporary(&dir) {
        assert!(start.elapsed() < Duration::from_secs(30), "no temporary file appeared");
        assert!(
            child.try_wait().expect("poll").is_none(),
            "joints ended before it was interrupted"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
    let status =
        Command::new("kill").args(["-INT", &child.id().to_string()]).status().expect("kill");
    assert!(status.success());
    let status = child.wait().expect("wait");
    assert_eq!(status.code(), Some(130), "interrupted runs exit with 130");
    assert!(!temporary(&dir), "the temporary file was left behind");
    assert_eq!(
        std::fs::read_to_string(dir.join("traj.csv")).expect("read"),
        "the earlier good file\n"
    );
}

#[test]
fn a_closed_pipe_ends_the_run_quietly_with_success() {
    let dir = temp_dir("broken-pipe");
    std::fs::write(dir.join("long.ngc"), long_program(20_000)).expect("write program");
    let mut child = Command::new(env!("CARGO_BIN_EXE_biscara"))
        .args(["joints", "long.ngc"])
        .current_dir(&dir)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn biscara");
    // Read one line, then close the pipe, as `biscara joints … | head -1` does.
    let mut stdout = child.stdout.take().expect("stdout");
    let mut first = [0u8; 64];
    let read = std::io::Read::read(&mut stdout, &mut first).expect("read");
    assert!(read > 0);
    drop(stdout);
    let output = child.wait_with_output().expect("wait");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(0), "stderr: {stderr}");
    assert!(!stderr.contains("error"), "a broken pipe is not reported: {stderr}");
}

/// A closed standard error (`biscara check … 2>&1 | head -1` once `head` has its line) loses
/// the notes and the error message, not the exit code: no panic (101).
#[test]
fn a_closed_stderr_keeps_the_exit_code() {
    let dir = temp_dir("closed-stderr");
    // Near a singularity: `check` reports problems (exit 1) after notes on stderr.
    std::fs::write(dir.join("edge.ngc"), "G0 X0 Y300 Z50\nG1 X0 Y480 F3000\nM2\n").expect("write");
    for (args, expected) in [(["check", "edge.ngc"], 1), (["joints", "edge.ngc"], 1)] {
        let mut child = Command::new(env!("CARGO_BIN_EXE_biscara"))
            .args(args)
            .current_dir(&dir)
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .expect("spawn biscara");
        drop(child.stderr.take());
        let status = child.wait().expect("wait");
        assert_eq!(status.code(), Some(expected), "biscara {args:?}");
    }
}

/// `-o` naming a FIFO (or `/dev/null`, a device) writes into it: renaming a temporary file over
/// it would replace the device or pipe with a regular file (as root, even `/dev/null`).
#[test]
fn an_output_that_is_not_a_regular_file_is_written_in_place() {
    let dir = temp_dir("fifo-output");
    std::fs::write(dir.join("job.ngc"), "G0 X0 Y400 Z50\nG1 X10 F600\nM2\n").expect("write");
    let fifo = dir.join("out.fifo");
    let made = Command::new("mkfifo").arg(&fifo).status().expect("mkfifo (coreutils)");
    assert!(made.success());
    let reader_path = fifo.clone();
    let reader = std::thread::spawn(move || std::fs::read_to_string(reader_path).expect("read"));
    let output = Command::new(env!("CARGO_BIN_EXE_biscara"))
        .args(["interpret", "job.ngc", "-o", "out.fifo"])
        .current_dir(&dir)
        .output()
        .expect("run biscara");
    assert_eq!(output.status.code(), Some(0), "{}", String::from_utf8_lossy(&output.stderr));
    // Checked before waiting for the reader, which would wait forever on a replaced FIFO.
    use std::os::unix::fs::FileTypeExt;
    let kind = std::fs::symlink_metadata(&fifo).expect("fifo").file_type();
    assert!(kind.is_fifo(), "the FIFO was replaced: {kind:?}");
    let written = reader.join().expect("reader");
    assert_eq!(written.lines().count(), 3, "{written}");
}

/// No input makes a command hang. A loop that comes back to the same state stops at its second
/// pass in every command; one that moves and changes stops at the bound on motions in every
/// command, and the commands that sample it in time at --time-limit too; one
/// that loops without moving stops at its bound of jumps everywhere. No output file is left.
#[test]
fn endless_programs_stop_with_an_error_naming_where() {
    let dir = temp_dir("endless");
    let repeating = "G21 G90\nG0 X0 Y400\no1 while [1]\nG1 X10 F6000\nG1 X0\no1 endwhile\nM2\n";
    std::fs::write(dir.join("repeating.ngc"), repeating).expect("write");
    let moving =
        "G21 G90\nG0 X0 Y400\no1 while [1]\n#1 = [#1 + 1]\nG1 X10 F6000\nG1 X0\no1 endwhile\nM2\n";
    std::fs::write(dir.join("moving.ngc"), moving).expect("write");
    let outputs = [
        ("interpret", "out.jsonl"),
        ("interpolate", "out.csv"),
        ("joints", "out.csv"),
        ("check", "out.json"),
        ("plot", "out.svg"),
        ("view", "out.html"),
    ];
    // `view` reads the program beside a joint trajectory.
    std::fs::write(dir.join("short.ngc"), "G21 G90\nG0 X0 Y400\nM2\n").expect("write");
    crate::util::biscara(&dir, &["joints", "short.ngc", "-o", "traj.csv"]).expect_code(0);
    for (command, output) in outputs {
        let program =
            |name| if command == "view" { vec!["traj.csv", "--program", name] } else { vec![name] };
        let mut args = vec![command];
        args.extend(program("repeating.ngc"));
        args.extend(["-o", output]);
        let run = crate::util::biscara(&dir, &args);
        run.expect_code(1);
        let message = "repeating.ngc:6:1: the loop at line 3 repeats forever";
        assert!(run.stderr.contains(message), "{run}");
        assert!(!dir.join(output).exists(), "{command} left {output}");
        if command == "view" {
            // `view` reads the program only as far as the trajectory goes.
            continue;
        }
        let mut bounded = vec![command, "--max-motions", "300"];
        bounded.extend(program("moving.ngc"));
        bounded.extend(["-o", output]);
        let run = crate::util::biscara(&dir, &bounded);
        run.expect_code(1);
        assert!(
            run.stderr.contains("moving.ngc:6:1: the program goes on past 300 motions"),
            "{run}"
        );
        assert!(run.stderr.contains("(--max-motions N allows more"), "{run}");
        assert!(!dir.join(output).exists(), "{command} left {output}");
    }
    for (command, output) in &outputs[1..5] {
        let limited = [*command, "--time-limit", "2", "moving.ngc", "-o", *output];
        let run = crate::util::biscara(&dir, &limited);
        run.expect_code(1);
        assert!(run.stderr.contains("s of robot time, past"), "{run}");
        assert!(run.stderr.contains("an endless loop that moves?"), "{run}");
        assert!(run.stderr.contains("(--time-limit SECONDS allows more"), "{run}");
        assert!(run.stderr.contains("moving.ngc:"), "{run}");
        assert!(!dir.join(output).exists(), "{command} left {output}");
    }
    let idle = "G21\no1 while [1]\n#1 = [#1 + 1]\no1 endwhile\nM2\n";
    std::fs::write(dir.join("idle.ngc"), idle).expect("write");
    for command in ["interpret", "joints", "check"] {
        let run = crate::util::biscara(&dir, &[command, "--max-idle-jumps", "1000", "idle.ngc"]);
        run.expect_code(1);
        assert!(run.stderr.contains("idle.ngc:4:1: the loop at line 2 has jumped back"), "{run}");
    }
}
