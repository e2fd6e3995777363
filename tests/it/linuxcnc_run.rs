//! LinuxCNC itself, headless (issue 27): `biscara linuxcnc config` and `biscara linuxcnc run`.
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
    let installed = ["linuxcnc", "halcompile"].iter().all(|program| {
        std::env::var_os("PATH").is_some_and(|path| {
            std::env::split_paths(&path).any(|dir| dir.join(program).is_file())
        })
    });
    if !installed {
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

/// Runs `biscara ARGS` and checks that LinuxCNC left nothing behind.
fn run_linuxcnc(dir: &Path, args: &[&str]) -> Run {
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
            "linuxcnc", "run", "parity.ngc", "--limits", "cartesian", "--angle-unit", "deg",
            "--precision", "10", "-o", "run.csv", "--path", "path.csv",
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
