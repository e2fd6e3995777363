//! LinuxCNC itself, headless: `biscara linuxcnc config` and `biscara linuxcnc run`.
//!
//! These tests start the real LinuxCNC (Debian's `linuxcnc-uspace`, with `linuxcnc-uspace-dev`
//! for `halcompile`; `.ci/run` installs both). LinuxCNC runs one instance per machine, so they
//! take turns through one lock, and after every run (passed or failed) they check that nothing
//! of LinuxCNC is left: no process, no lock file, no shared-memory segment. When LinuxCNC is
//! missing they print why and pass, except under `CI=true`, where they fail.

use std::path::Path;
use std::sync::{Mutex, MutexGuard};

use biscara::kinematics::{Joints, Pose, RobotModel, Theta3Unwrapper};
use biscara::linuxcnc::runner::{LOCK_FILE, leftover_processes, leftover_shared_memory};

use crate::util::{Run, biscara, repo_root, skip_or_fail, temp_dir};

/// One LinuxCNC per machine: the tests take turns.
static LINUXCNC: Mutex<()> = Mutex::new(());

/// The lock when LinuxCNC is installed, else `None` after saying why (a failure under CI).
fn linuxcnc_or_skip(checks: &str) -> Option<MutexGuard<'static, ()>> {
    if biscara::linuxcnc::runner::check_installed().is_err() {
        skip_or_fail(
            checks,
            "LinuxCNC (linuxcnc, halcompile)",
            " (apt-get install --no-install-recommends linuxcnc-uspace linuxcnc-uspace-dev)",
        );
        return None;
    }
    Some(LINUXCNC.lock().unwrap_or_else(|poisoned| poisoned.into_inner()))
}

/// Fails when anything of LinuxCNC is left after a run.
#[track_caller]
fn assert_nothing_left(after: &Run) {
    let processes = leftover_processes();
    let memory = leftover_shared_memory();
    assert!(processes.is_empty(), "LinuxCNC processes left: {processes:?}\n{after}");
    assert!(memory.is_empty(), "shared memory left: {memory:?}\n{after}");
    assert!(!Path::new(LOCK_FILE).exists(), "{LOCK_FILE} left\n{after}");
}

/// Waits (at most 10 minutes) while a LinuxCNC started outside these tests runs: another test
/// process on the same machine, whose instance would make this run's "another LinuxCNC is
/// running" and its leftovers look like ours.
fn wait_for_other_linuxcnc() {
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(600);
    while (Path::new(LOCK_FILE).exists() || !leftover_processes().is_empty())
        && std::time::Instant::now() < deadline
    {
        std::thread::sleep(std::time::Duration::from_millis(500));
    }
}

/// Runs `biscara ARGS` and checks that LinuxCNC left nothing behind.
fn run_linuxcnc(dir: &Path, args: &[&str]) -> Run {
    wait_for_other_linuxcnc();
    let run = biscara(dir, args);
    assert_nothing_left(&run);
    run
}

/// The numbers of a CSV with a header: one row a line.
fn read_csv(path: &Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = std::fs::read_to_string(path).expect("read CSV");
    let mut lines = text.lines();
    let header = lines.next().expect("header").split(',').map(str::to_owned).collect();
    let rows = lines
        .map(|line| line.split(',').map(|value| value.parse().expect("number")).collect())
        .collect();
    (header, rows)
}

/// A program inside the workspace rectangles of the default and the asymmetric robot: lines,
/// arcs both ways, Z and C moves, a dwell.
const PARITY_PROGRAM: &str = "\
G21 G90 G17 G64
G0 X-100 Y250 Z80 C0
G1 X100 Y300 Z60 C45 F2400
G2 X150 Y250 I0 J-50 F1800
G3 X0 Y220 R90
G1 X-120 Y320 C-30 F3000
G4 P0.2
G0 X0 Y300 Z90 C10
M2
";

/// Forward and inverse kinematics on LinuxCNC against this project's: every recorded joint
/// sample against IK of LinuxCNC's commanded Cartesian positions through its cubic
/// interpolator (two servo cycles late, smoothed), at rest and while moving, to 1e-6 degree or
/// mm; at rest, FK of LinuxCNC's joints against its commanded pose to 1e-6 mm.
fn check_parity(dir: &Path, robot_file: Option<&Path>) {
    let mut args: Vec<String> = Vec::new();
    if let Some(robot) = robot_file {
        args.extend(["--robot".to_owned(), robot.display().to_string()]);
    }
    let robot = match robot_file {
        Some(path) => RobotModel::from_json(&std::fs::read_to_string(path).expect("robot"))
            .expect("robot file"),
        None => RobotModel::default(),
    };
    let model = robot.kinematics();
    std::fs::write(dir.join("parity.ngc"), PARITY_PROGRAM).expect("write program");
    args.extend(
        [
            "linuxcnc",
            "run",
            "parity.ngc",
            "--limits",
            "cartesian",
            "--angle-unit",
            "deg",
            "--precision",
            "10",
            "-o",
            "run.csv",
            "--path",
            "path.csv",
        ]
        .map(str::to_owned),
    );
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let run = run_linuxcnc(dir, &args);
    run.success();
    let (header, joints) = read_csv(&dir.join("run.csv"));
    assert_eq!(header.join(","), "t_s,theta1_deg,theta2_deg,theta3_deg,d4_mm");
    let (_, path) = read_csv(&dir.join("path.csv"));
    assert_eq!(joints.len(), path.len());
    assert!(joints.len() > 1000, "a few seconds of motion: {} samples", joints.len());
    // IK of every commanded pose, θ3 continuous along the path.
    let mut unwrapper = Theta3Unwrapper::new();
    let ik: Vec<[f64; 4]> = path
        .iter()
        .map(|row| {
            let [_, x, y, z, c] = row[..] else { panic!("path row {row:?}") };
            let mut ik = model.inverse_checked(&Pose::from_degrees(x, y, z, c)).expect("reachable");
            unwrapper.apply(&mut ik);
            ik.joints.to_array()
        })
        .collect();
    let (mut moving, mut worst_mm) = (0, 0.0_f64);
    for k in 3..joints.len() {
        // LinuxCNC's cubic interpolator: the joint command of cycle k is the B-spline
        // (1, 4, 1) / 6 of the inverse kinematics at cycles k − 3, k − 2, k − 1.
        let expected: [f64; 4] =
            std::array::from_fn(|j| (ik[k - 3][j] + 4.0 * ik[k - 2][j] + ik[k - 1][j]) / 6.0);
        let row = &joints[k];
        let actual = Joints::from_degrees(row[1], row[2], row[3], row[4]);
        let got = actual.to_array();
        for j in 0..4 {
            let difference = got[j] - expected[j];
            let difference = if j == 3 { difference } else { difference.to_degrees() };
            assert!(
                difference.abs() < 1e-6,
                "t = {}: joint {j}: {got:?} against IK {expected:?}",
                row[0]
            );
        }
        // At rest (the same pose for three cycles): FK of LinuxCNC's joints is its pose.
        if path[k - 1][1..] == path[k - 3][1..] && path[k - 2][1..] == path[k - 3][1..] {
            let [_, x, y, z, _] = path[k - 2][..] else { unreachable!() };
            let fk = model.forward(&actual).expect("FK");
            let error = (fk.pose.x - x).hypot(fk.pose.y - y).max((fk.pose.z - z).abs());
            worst_mm = worst_mm.max(error);
        } else {
            moving += 1;
        }
    }
    assert!(worst_mm < 1e-6, "FK of LinuxCNC's joints is {worst_mm} mm from its pose");
    assert!(moving > 1000, "the parity was checked while moving: {moving} samples");
}

#[test]
fn linuxcnc_kinematics_equal_ik_and_fk_on_two_robots() {
    let Some(_lock) = linuxcnc_or_skip("LinuxCNC kinematics parity") else { return };
    let dir = temp_dir("linuxcnc-parity");
    check_parity(&dir, None);
    check_parity(&dir, Some(&repo_root().join("data/robots/asymmetric.json")));
}

/// The stream path plays `biscara joints`' trajectory of the configuration's robot sample for
/// sample, without `--robot` (the configuration carries its robot); LinuxCNC's G-code then
/// continues from where the stream ended, starting from LinuxCNC's forward kinematics of the
/// last streamed joints. A different `--robot`, or a configuration edited by hand, is refused.
#[test]
fn the_stream_replays_joints_of_the_configurations_robot_and_gcode_continues_after_it() {
    let Some(_lock) = linuxcnc_or_skip("LinuxCNC stream path") else { return };
    let dir = temp_dir("linuxcnc-stream");
    let robot_file = repo_root().join("data/robots/asymmetric.json");
    let robot_file = robot_file.display().to_string();
    std::fs::write(dir.join("job.ngc"), PARITY_PROGRAM).expect("write program");
    std::fs::write(dir.join("then.ngc"), "G91 G1 Z-10 F600\nG90\nM2\n").expect("write program");
    biscara(&dir, &["--robot", &robot_file, "linuxcnc", "config", "-o", "cfg"]).success();
    let deg = ["--angle-unit", "deg", "--precision", "10"];
    biscara(
        &dir,
        &[&["--robot", &robot_file, "joints", "job.ngc", "-o", "traj.csv"][..], &deg].concat(),
    )
    .success();
    let run =
        run_linuxcnc(
            &dir,
            &[
                &[
                    "linuxcnc", "run", "job.ngc", "--config", "cfg", "--stream", "--then",
                    "then.ngc",
                ][..],
                &["-o", "run.csv", "--path", "path.csv"],
                &deg,
            ]
            .concat(),
        );
    run.success().stderr_has("LinuxCNC streamed job.ngc");
    let (_, expected) = read_csv(&dir.join("traj.csv"));
    let (_, actual) = read_csv(&dir.join("run.csv"));
    let (_, path) = read_csv(&dir.join("path.csv"));
    assert!(actual.len() > expected.len(), "the G-code after the stream was recorded too");
    for (want, got) in expected.iter().zip(&actual) {
        assert!((want[0] - got[0]).abs() < 1e-9, "time {want:?} against {got:?}");
        for j in 1..5 {
            assert!(
                (want[j] - got[j]).abs() < 1e-6,
                "sample at t = {}: {want:?} against {got:?}",
                want[0]
            );
        }
    }
    // After the stream, LinuxCNC's position is its forward kinematics of the last streamed
    // joints: this project's FK of the configuration's robot to 1e-6 mm.
    let model = RobotModel::from_json(&std::fs::read_to_string(&robot_file).expect("robot"))
        .expect("robot file");
    let last = &expected[expected.len() - 1];
    let fk = model
        .kinematics()
        .forward(&Joints::from_degrees(last[1], last[2], last[3], last[4]))
        .expect("FK");
    // (With the machine on during the stream LinuxCNC takes up where the joints are once it
    // ended: its pose before the G-code moves the joints again, which follow its commanded pose
    // a few cycles late.)
    let moves_again = (expected.len() + 1..actual.len())
        .find(|&k| actual[k][1..] != actual[k - 1][1..])
        .expect("the G-code moved");
    let after = &path[moves_again - 5];
    let want = [fk.pose.x, fk.pose.y, fk.pose.z, fk.pose.phi.to_degrees()];
    for (got, want) in after[1..].iter().zip(want) {
        assert!(
            (got - want).abs() < 1e-6,
            "LinuxCNC's pose after the stream {after:?}, FK {want:?}"
        );
    }
    // Then the G-code: 10 mm down from there, d4 10 mm longer.
    let end = &actual[actual.len() - 1];
    assert!((end[4] - (last[4] + 10.0)).abs() < 1e-6, "{end:?} after {last:?}");
    for j in 1..4 {
        assert!((end[j] - last[j]).abs() < 1e-6, "only Z moved: {end:?} after {last:?}");
    }
    // The same trajectory as a joint CSV (`--stream-csv`), checked and played sample for sample.
    let run =
        run_linuxcnc(
            &dir,
            &[
                &[
                    "linuxcnc",
                    "run",
                    "--stream-csv",
                    "traj.csv",
                    "--config",
                    "cfg",
                    "-o",
                    "csv.csv",
                ][..],
                &deg,
            ]
            .concat(),
        );
    run.success().stderr_has("LinuxCNC streamed traj.csv");
    let (_, played) = read_csv(&dir.join("csv.csv"));
    // (The recording goes on for the few cycles the display takes to stop it: standing still.)
    assert!(played.len() >= expected.len(), "{} of {} samples", played.len(), expected.len());
    let last = expected.last().expect("samples");
    for (k, got) in played.iter().enumerate() {
        let want = expected.get(k).unwrap_or(last);
        for j in 1..5 {
            assert!((want[j] - got[j]).abs() < 1e-6, "{want:?} against {got:?}");
        }
    }
    // Another robot than the configuration's is refused before LinuxCNC starts, naming both.
    let default = repo_root().join("data/robots/default.json").display().to_string();
    let run = run_linuxcnc(
        &dir,
        &["--robot", &default, "linuxcnc", "run", "job.ngc", "--config", "cfg", "-o", "x.csv"],
    );
    run.expect_code(1)
        .stderr_has("the configuration cfg was written for the robot \"asymmetric")
        .stderr_has("not for --robot")
        .stderr_has("default.json");
    // The same robot named again is fine (checked here without running: a missing program).
    biscara(
        &dir,
        &["--robot", &robot_file, "linuxcnc", "run", "none.ngc", "--config", "cfg", "-o", "x.csv"],
    )
    .expect_code(1)
    .stderr_has("none.ngc");
    // A configuration whose HAL no longer holds its robot's numbers is refused.
    let hal = std::fs::read_to_string(dir.join("cfg/biscara.hal")).expect("hal");
    let edited = hal.replace("setp biscarakins.l2 ", "setp biscarakins.l2 1");
    std::fs::write(dir.join("cfg/biscara.hal"), edited).expect("write hal");
    let run = run_linuxcnc(&dir, &["linuxcnc", "run", "job.ngc", "--config", "cfg", "-o", "x.csv"]);
    run.expect_code(1).stderr_has("cfg/biscara.hal and cfg/robot.json disagree");
    assert!(!dir.join("x.csv").exists());
}

/// LinuxCNC's refusals are errors: exit 1, LinuxCNC's message with the program's line, no
/// output file, nothing of LinuxCNC left.
#[test]
fn linuxcnc_refusals_are_errors_with_the_line() {
    let Some(_lock) = linuxcnc_or_skip("LinuxCNC refusals") else { return };
    let dir = temp_dir("linuxcnc-refusals");
    // θ1 would be −140.4° at (300, 100): beyond its limit of −135°.
    std::fs::write(dir.join("limit.ngc"), "G21 G90\nG0 X0 Y300 Z50\nG0 X300 Y100\nM2\n")
        .expect("write");
    let run = run_linuxcnc(&dir, &["linuxcnc", "run", "limit.ngc", "-o", "run.csv"]);
    run.expect_code(1).stderr_has("limit.ngc:3: LinuxCNC: ").stderr_has("joint 0");
    assert!(!dir.join("run.csv").exists());
    // (420, 100) is 49.5 mm beyond chain 2's reach: the inverse kinematics fail.
    std::fs::write(dir.join("reach.ngc"), "G21 G90\nG0 X0 Y300 Z50\nG1 X420 Y100 F3000\nM2\n")
        .expect("write");
    let run = run_linuxcnc(&dir, &["linuxcnc", "run", "reach.ngc", "-o", "run.csv"]);
    run.expect_code(1).stderr_has("reach.ngc:3: LinuxCNC: ");
    assert!(!dir.join("run.csv").exists());
    // A configuration for a region: LinuxCNC's own soft limit refuses a move out of it.
    biscara(&dir, &["linuxcnc", "config", "--region=-50:50,250:350", "-o", "region"]).success();
    std::fs::write(dir.join("out.ngc"), "G21 G90\nG0 X0 Y300 Z50\nG1 X80 Y300 F3000\nM2\n")
        .expect("write");
    let run =
        run_linuxcnc(&dir, &["linuxcnc", "run", "out.ngc", "--config", "region", "-o", "run.csv"]);
    run.expect_code(1).stderr_has("out.ngc:3: LinuxCNC: ").stderr_has("X's positive limit");
    assert!(!dir.join("run.csv").exists());
}

/// A joint CSV that does not start where the joints stand, or that breaks a joint limit, is
/// refused before LinuxCNC moves (LinuxCNC is not even started): exit 1, the file and its line,
/// nothing written.
#[test]
fn a_stream_csv_away_from_the_joints_or_beyond_a_limit_is_refused() {
    let Some(_lock) = linuxcnc_or_skip("LinuxCNC stream CSV refusals") else { return };
    let dir = temp_dir("linuxcnc-stream-csv");
    let header = "t_s,theta1_deg,theta2_deg,theta3_deg,d4_mm\n";
    let write = |name: &str, rows: &str| {
        std::fs::write(dir.join(name), format!("{header}{rows}")).expect("write CSV");
    };
    // Starts 10° from where θ1 stands after homing (0°).
    write("away.csv", "0,10,0,0,0\n0.001,10,0,0,0\n");
    // 500 °/s on θ1 against its 360.
    write("fast.csv", "0,0,0,0,0\n0.001,0.5,0,0,0\n0.002,1,0,0,0\n");
    // θ2 at 300 °/s from the start, beyond its 135° at row 451 (line 453).
    let ramp: String = (0..460)
        .map(|k| format!("{:.3},0,{:.1},0,0\n", f64::from(k) * 1e-3, 0.3 * f64::from(k)))
        .collect();
    write("far.csv", &ramp);
    // Rows 2 ms apart, and a malformed row.
    write("slow.csv", "0,0,0,0,0\n0.002,0,0,0,0\n");
    write("bad.csv", "0,0,0,0,0\n0.001,0,x,0,0\n");
    for (name, expected) in [
        ("away.csv", "the stream starts at θ1 10.0000°"),
        ("fast.csv", "fast.csv:3: theta1 moves at 500.000000°/s over its velocity limit"),
        ("far.csv", "far.csv:453: theta2 at 135.300000° is outside its limits -135 to 135"),
        ("slow.csv", "slow.csv:3: t = 0.002 s where the next servo cycle is"),
        ("bad.csv", "bad.csv:3:"),
    ] {
        let run = run_linuxcnc(&dir, &["linuxcnc", "run", "--stream-csv", name, "-o", "run.csv"]);
        run.expect_code(1).stderr_has(expected);
        assert!(!run.stderr.contains("LinuxCNC streamed") && !run.stderr.contains("panicked"));
        assert!(!dir.join("run.csv").exists(), "{run}");
    }
}

/// Starts `biscara ARGS` in `dir` without waiting for it: its standard error piped.
fn spawn_biscara(dir: &Path, args: &[&str]) -> std::process::Child {
    std::process::Command::new(env!("CARGO_BIN_EXE_biscara"))
        .args(args)
        .current_dir(dir)
        .stdin(std::process::Stdio::null())
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("start biscara")
}

/// The recorded time of the stream's last sample, from the run's error message.
fn stream_end(stderr: &str) -> f64 {
    let needle = "the stream's last sample played at ";
    let rest = &stderr[stderr.find(needle).expect(stderr) + needle.len()..];
    rest[..rest.find(" s").expect(stderr)].parse().expect(stderr)
}

/// E-stop and machine off during a stream (commissioning in simulation): the stream stops at
/// once and the joints hold (after the stop plus two servo cycles no recorded joint moves), the
/// samples before it are the streamed ones, the recording is written, exit 1 names the event
/// and its time; a following error injected on the simulated machine stops it too.
#[test]
fn estop_machine_off_and_a_following_error_stop_the_stream() {
    let Some(_lock) = linuxcnc_or_skip("LinuxCNC stream stops") else { return };
    let dir = temp_dir("linuxcnc-stream-stop");
    std::fs::write(dir.join("job.ngc"), PARITY_PROGRAM).expect("write program");
    let deg = ["--angle-unit", "deg", "--precision", "9"];
    biscara(&dir, &[&["joints", "job.ngc", "-o", "traj.csv"][..], &deg].concat()).success();
    let (_, expected) = read_csv(&dir.join("traj.csv"));
    // The recording against the trajectory: equal up to the stream's last sample, still after.
    let check = |run: &Run, what: &str, at: Option<f64>| {
        run.expect_code(1).stderr_has(what);
        let end = stream_end(&run.stderr);
        if let Some(at) = at {
            assert!(run.stderr.contains(&format!("{what} at {at}")), "{run}");
            assert!(end >= at && end < at + 0.2, "stopped at {end} s for {at} s\n{run}");
        }
        let (_, recorded) = read_csv(&dir.join("run.csv"));
        let last = (end * 1000.0).round() as usize;
        assert!(recorded.len() > last + 100, "the joints after the stop are recorded too");
        for (k, row) in recorded.iter().enumerate() {
            let want = if k <= last { &expected[k] } else { &recorded[last + 2] };
            for j in 1..5 {
                assert!(
                    (row[j] - want[j]).abs() < 1e-6,
                    "{what}: sample {k} (stream's end {last}): {row:?} against {want:?}"
                );
            }
        }
        // (The two cycles after the last sample: the hold takes effect.)
        assert!(expected.len() > last + 100, "the stream was stopped before its end");
        std::fs::remove_file(dir.join("run.csv")).expect("remove");
    };
    for (flag, what, at) in [
        ("--estop-at", "E-stop", "0.5"),
        ("--machine-off-at", "machine off", "1.7"),
        ("--estop-at", "E-stop", "3.2"),
    ] {
        let run = run_linuxcnc(
            &dir,
            &[&["linuxcnc", "run", "job.ngc", "--stream", flag, at, "-o", "run.csv"][..], &deg]
                .concat(),
        );
        check(&run, what, Some(at.parse().expect("time")));
    }
    // A following error of 10° on θ1's simulated feedback (its FERROR is 5°), injected while
    // the stream plays.
    wait_for_other_linuxcnc();
    let child = spawn_biscara(
        &dir,
        &[&["linuxcnc", "run", "job.ngc", "--stream", "-o", "run.csv"][..], &deg].concat(),
    );
    let playing = || {
        std::process::Command::new("halcmd")
            .args(["gets", "stream-play"])
            .output()
            .is_ok_and(|out| String::from_utf8_lossy(&out.stdout).trim() == "TRUE")
    };
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(60);
    while !playing() && std::time::Instant::now() < deadline {
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    std::thread::sleep(std::time::Duration::from_millis(800));
    let status = std::process::Command::new("halcmd")
        .args(["sets", "sim-theta1-error", "10"])
        .status()
        .expect("halcmd");
    assert!(status.success(), "could not inject the following error");
    let output = child.wait_with_output().expect("wait");
    let run = Run {
        command: "biscara linuxcnc run job.ngc --stream (following error)".to_owned(),
        code: output.status.code().unwrap_or(-1),
        stdout: String::new(),
        stderr: String::from_utf8_lossy(&output.stderr).into_owned(),
    };
    assert_nothing_left(&run);
    check(&run, "following error", None);
}

/// SIGINT, SIGTERM and SIGHUP during a run stop LinuxCNC and remove the temporary folders:
/// exit 130, no output, nothing of LinuxCNC left.
#[test]
#[allow(clippy::print_stderr)]
fn an_interrupted_run_leaves_nothing_behind() {
    let Some(_lock) = linuxcnc_or_skip("LinuxCNC interrupted") else { return };
    let dir = temp_dir("linuxcnc-interrupt");
    let program = repo_root().join("data/programs/arcs_and_offsets.ngc");
    let program = program.display().to_string();
    for signal in ["INT", "TERM", "HUP"] {
        wait_for_other_linuxcnc();
        let child = spawn_biscara(&dir, &["linuxcnc", "run", &program, "-o", "run.csv"]);
        // Mid-run: LinuxCNC is up (its lock file) and has run for a while.
        let deadline = std::time::Instant::now() + std::time::Duration::from_secs(60);
        while !Path::new(LOCK_FILE).exists() && std::time::Instant::now() < deadline {
            std::thread::sleep(std::time::Duration::from_millis(50));
        }
        assert!(Path::new(LOCK_FILE).exists(), "LinuxCNC did not start");
        std::thread::sleep(std::time::Duration::from_secs(4));
        let folders = run_folders(child.id());
        assert!(!folders.is_empty(), "no run folder while running");
        let status = std::process::Command::new("kill")
            .args(["-s", signal, &child.id().to_string()])
            .status()
            .expect("kill");
        assert!(status.success());
        let output = child.wait_with_output().expect("wait");
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(130), "SIG{signal}: {stderr}");
        assert!(stderr.contains("interrupted"), "SIG{signal}: {stderr}");
        let left = Run {
            command: format!("biscara linuxcnc run … (SIG{signal})"),
            code: output.status.code().unwrap_or(-1),
            stdout: String::new(),
            stderr: stderr.clone().into_owned(),
        };
        assert_nothing_left(&left);
        for folder in folders {
            assert!(!folder.exists(), "SIG{signal}: {} left", folder.display());
        }
        assert!(!dir.join("run.csv").exists(), "SIG{signal}: an output was written");
        eprintln!("SIG{signal}: exit 130, nothing of LinuxCNC left");
    }
}

/// The temporary folders of the biscara process `pid`.
fn run_folders(pid: u32) -> Vec<std::path::PathBuf> {
    std::fs::read_dir(std::env::temp_dir())
        .expect("temporary folder")
        .flatten()
        .map(|entry| entry.path())
        .filter(|path| {
            let name = path.file_name().map(|name| name.to_string_lossy().into_owned());
            name.is_some_and(|name| {
                name.starts_with("biscara-") && name.contains(&format!("-{pid}-"))
            })
        })
        .collect()
}

/// LinuxCNC's own planner on a configuration made for each data program (`config --for`: the
/// axis limits derived over the program's region, its soft limits at that region) stays within
/// every joint's velocity and acceleration limit, and takes at most 1.5 times the time-optimal
/// duration of `biscara joints` (the ratio is printed).
#[test]
#[allow(clippy::print_stderr)]
fn linuxcnc_planner_on_job_limits_stays_within_every_joint_limit_and_is_fast() {
    let Some(_lock) = linuxcnc_or_skip("LinuxCNC planner on job limits") else { return };
    let dir = temp_dir("linuxcnc-job");
    let robot = RobotModel::default();
    let velocity = robot.robot().joint_max_velocity.to_array();
    let acceleration = robot.robot().joint_max_acceleration.to_array();
    // Every G-code program of data/ in LinuxCNC's dialect, placed as its header says.
    let programs = [
        ("arcs_and_offsets.ngc", None),
        ("pick_place_inch.ngc", None),
        ("pen_plot.ngc", Some("-30,280,10,0")),
        ("laser_engraving.ngc", Some("-30,250,0,0")),
        ("engraving_arcs.ngc", Some("-75,300,20,0")),
    ];
    let listed = std::fs::read_dir(repo_root().join("data/programs"))
        .expect("data/programs")
        .filter(|entry| {
            entry.as_ref().expect("entry").path().extension().is_some_and(|e| e == "ngc")
        })
        .count();
    assert_eq!(listed, programs.len(), "a data program is missing here");
    for (name, origin) in programs {
        let program = repo_root().join("data/programs").join(name).display().to_string();
        let origin = origin.map(|origin| ["--origin", origin]);
        let origin = origin.as_ref().map_or(&[][..], |origin| &origin[..]);
        biscara(
            &dir,
            &[&["linuxcnc", "config", "--for", &program, "-o", "cfg"][..], origin].concat(),
        )
        .success();
        let ini = std::fs::read_to_string(dir.join("cfg/biscara.ini")).expect("ini");
        assert!(ini.contains(&format!("# Where: the region of {program}")), "{ini}");
        biscara(&dir, &[&["joints", &program, "-o", "optimal.csv"][..], origin].concat()).success();
        let run = run_linuxcnc(
            &dir,
            &[
                &["linuxcnc", "run", &program, "--config", "cfg", "--derivatives"][..],
                &["--angle-unit", "deg", "--precision", "9", "-o", "run.csv"],
                origin,
            ]
            .concat(),
        );
        run.success();
        let (header, rows) = read_csv(&dir.join("run.csv"));
        assert_eq!(header.len(), 13, "{header:?}");
        assert!(rows.len() > 1000, "{program}: {} samples", rows.len());
        // Columns: t, 4 positions, 4 velocities, 4 accelerations (θ1 θ2 θ3 d4).
        let mut shares = Vec::new();
        for j in 0..4 {
            let peak = |column: usize| rows.iter().map(|row| row[column].abs()).fold(0.0, f64::max);
            let (v, a) = (peak(5 + j), peak(9 + j));
            // The CSV's nine decimals (±0.5e-9) allow 1e-6/s in a velocity by differences over
            // 1 ms and 2e-3/s² in an acceleration.
            assert!(
                v <= velocity[j] + 2e-6,
                "{program}: joint {j} at {v} of {}\n{run}",
                velocity[j]
            );
            assert!(
                a <= acceleration[j] + 5e-3,
                "{program}: joint {j} at {a}/s² of {}\n{run}",
                acceleration[j]
            );
            shares.push(format!(
                "{:.0} % / {:.0} %",
                100.0 * v / velocity[j],
                100.0 * a / acceleration[j]
            ));
        }
        let (_, optimal) = read_csv(&dir.join("optimal.csv"));
        let duration = |rows: &[Vec<f64>]| rows.last().expect("a sample")[0];
        let ratio = duration(&rows) / duration(&optimal);
        eprintln!(
            "{name}: LinuxCNC on job limits {:.3} s, time-optimal {:.3} s, ratio {ratio:.2}; \
             joints' peak velocity / acceleration: {}",
            duration(&rows),
            duration(&optimal),
            shares.join(", ")
        );
        assert!(ratio <= 1.5, "{name}: LinuxCNC takes {ratio:.2} times the time-optimal duration");
    }
}

/// `biscara linuxcnc config` writes a whole configuration with the robot file's numbers, and
/// refuses what it cannot configure; needs no LinuxCNC.
#[test]
fn config_writes_the_robots_configuration() {
    let dir = temp_dir("linuxcnc-config");
    let robot = repo_root().join("data/robots/asymmetric.json");
    let robot = robot.display().to_string();
    biscara(&dir, &["--robot", &robot, "linuxcnc", "config", "-o", "cfg"])
        .success()
        .stderr_has("halcompile --install");
    let read = |name: &str| std::fs::read_to_string(dir.join("cfg").join(name)).expect(name);
    let ini = read("biscara.ini");
    for line in [
        "KINEMATICS = biscarakins",
        "JOINTS = 4",
        "COORDINATES = X Y Z C",
        "SERVO_PERIOD = 1000000",
    ] {
        assert!(ini.contains(line), "{line}\n{ini}");
    }
    // The asymmetric robot's joint limits and geometry.
    assert!(ini.contains("MIN_LIMIT = -270") && ini.contains("MAX_LIMIT = 150\n"), "{ini}");
    let hal = read("biscara.hal");
    for line in
        ["setp biscarakins.l1 180\n", "setp biscarakins.b2x -90\n", "setp biscarakins.lp 150\n"]
    {
        assert!(hal.contains(line), "{line}\n{hal}");
    }
    for name in [
        "biscarakins.comp",
        "biscara.hal",
        "sim.hal",
        "hardware.hal",
        "biscara_run.py",
        "README.md",
    ] {
        let text = read(name);
        assert!(!text.contains("@NAME@") && !text.contains("@L1@"), "{name} has a placeholder");
    }
    // The configuration carries its robot.
    let carried = RobotModel::from_json(&read("robot.json")).expect("robot.json");
    let given = RobotModel::from_json(&std::fs::read_to_string(&robot).expect("robot"))
        .expect("robot file");
    assert_eq!(carried.robot(), given.robot());
    use std::os::unix::fs::PermissionsExt as _;
    let mode =
        std::fs::metadata(dir.join("cfg/biscara_run.py")).expect("runner").permissions().mode();
    assert!(mode & 0o111 != 0, "the headless display is executable");
    // The robot's Cartesian limits as they are, on request.
    biscara(
        &dir,
        &["linuxcnc", "config", "--limits", "cartesian", "--tool", "laser", "-o", "cart"],
    )
    .success();
    let ini = std::fs::read_to_string(dir.join("cart/biscara.ini")).expect("ini");
    assert!(ini.contains("[AXIS_X]\nMAX_VELOCITY = 500\nMAX_ACCELERATION = 5000\n"), "{ini}");
    let hal = std::fs::read_to_string(dir.join("cart/biscara.hal")).expect("hal");
    assert!(hal.contains("net laser-power spindle.0.speed-out"), "{hal}");
}

/// The default robot's INI and HAL, pinned: a change to them is reviewed like code.
#[test]
fn the_default_configuration_is_pinned() {
    let dir = temp_dir("linuxcnc-config-golden");
    biscara(&dir, &["linuxcnc", "config", "-o", "cfg"]).success();
    for name in ["biscara.ini", "biscara.hal", "sim.hal", "hardware.hal"] {
        let text = std::fs::read_to_string(dir.join("cfg").join(name)).expect(name);
        crate::golden::check_golden(&format!("linuxcnc/{name}"), &text);
    }
    for command in [
        &["linuxcnc", "--help"][..],
        &["linuxcnc", "config", "--help"],
        &["linuxcnc", "run", "--help"],
    ] {
        let run = biscara(&dir, command);
        run.success();
        assert!(run.stdout.contains("Example:"), "{run}");
        crate::golden::check_golden(
            &format!("help/{}.txt", command[..command.len() - 1].join("-")),
            &run.stdout,
        );
    }
}

/// Bad input to `biscara linuxcnc`: a clear error, exit 1 (2 for wrong usage), no output file.
#[test]
fn linuxcnc_bad_input_is_refused() {
    let dir = temp_dir("linuxcnc-bad");
    std::fs::write(dir.join("job.ngc"), "G0 X0 Y300\nM2\n").expect("write");
    std::fs::write(dir.join("extruder.json"), r#"{"tool": {"kind": "extruder"}}"#).expect("write");
    biscara(&dir, &["linuxcnc", "config", "--tool", "extruder", "-o", "cfg"])
        .expect_code(1)
        .stderr_has("no extruder");
    biscara(&dir, &["linuxcnc", "config", "--tool", "drill", "-o", "cfg"]).expect_code(2);
    for region in ["--region=1:2", "--region=a:2,3:4", "--region=5:1,0:1", "--region=0:inf,0:1"] {
        biscara(&dir, &["linuxcnc", "config", region, "-o", "cfg"]).expect_code(2);
    }
    biscara(&dir, &["linuxcnc", "config", "--margin", "5", "-o", "cfg"]).expect_code(2);
    biscara(&dir, &["linuxcnc", "config", "--region=-50:50,400:500", "-o", "cfg"])
        .expect_code(1)
        .stderr_has("the region of --region -50:50,400:500: ")
        .stderr_has("outside the workspace");
    biscara(&dir, &["linuxcnc", "config", "--for", "missing.ngc", "-o", "cfg"])
        .expect_code(1)
        .stderr_has("missing.ngc");
    biscara(&dir, &["linuxcnc", "config", "--for", "job.ngc", "--margin=-1", "-o", "cfg"])
        .expect_code(1)
        .stderr_has("--margin");
    std::fs::write(dir.join("far.ngc"), "G0 X0 Y300\nG0 X300 Y100\nM2\n").expect("write");
    biscara(&dir, &["linuxcnc", "config", "--for", "far.ngc", "-o", "cfg"])
        .expect_code(1)
        .stderr_has("the region of far.ngc (its extent plus 10 mm): ");
    biscara(&dir, &["linuxcnc", "config"]).expect_code(2);
    biscara(&dir, &["--robot", "extruder.json", "linuxcnc", "config", "-o", "cfg"])
        .expect_code(1)
        .stderr_has("no extruder");
    assert!(!dir.join("cfg").exists());
    biscara(&dir, &["linuxcnc", "run", "job.ngc", "--then", "job.ngc"]).expect_code(2);
    biscara(&dir, &["linuxcnc", "run", "-o", "run.csv"]).expect_code(2);
    biscara(&dir, &["linuxcnc", "run", "job.ngc", "--stream-csv", "t.csv"]).expect_code(2);
    biscara(&dir, &["linuxcnc", "run", "job.ngc", "--estop-at", "1", "--machine-off-at", "2"])
        .expect_code(2);
    biscara(&dir, &["linuxcnc", "run", "job.ngc", "--estop-at", "-1", "-o", "run.csv"])
        .expect_code(1)
        .stderr_has("--estop-at");
    for args in [
        &["linuxcnc", "run", "missing.ngc", "-o", "run.csv"][..],
        &["linuxcnc", "run", "job.ngc", "--config", "no-such-folder", "-o", "run.csv"],
        &["linuxcnc", "run", "job.ngc", "--timeout", "0", "-o", "run.csv"],
    ] {
        let run = biscara(&dir, args);
        run.expect_code(1);
        assert!(!run.stderr.contains("panicked"), "{run}");
        // A file's I/O error is said once, not again as the error's cause.
        assert!(run.stderr.matches("(os error").count() <= 1, "{run}");
        assert!(!dir.join("run.csv").exists(), "{run}");
    }
}
