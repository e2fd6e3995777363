//! Golden files: `tests/golden/NAME` holds the expected output; `UPDATE_GOLDEN=1` rewrites it.
//! A missing golden file is written and the test fails, so that it gets reviewed.

use crate::util::{biscara, repo_root, temp_dir};

/// Compares `actual` with the golden file `name`, or rewrites it under `UPDATE_GOLDEN=1`.
#[track_caller]
pub fn check_golden(name: &str, actual: &str) {
    let path = repo_root().join("tests/golden").join(name);
    let update = std::env::var_os("UPDATE_GOLDEN").is_some_and(|value| value != "0");
    let expected = std::fs::read_to_string(&path).ok();
    if update || expected.is_none() {
        std::fs::create_dir_all(path.parent().expect("golden folder")).expect("create golden dir");
        std::fs::write(&path, actual).expect("write golden file");
        assert!(
            update,
            "golden file {} was missing and has been written: review it",
            path.display()
        );
        return;
    }
    let expected = expected.unwrap_or_default();
    if expected != actual && !numerically_equal(&expected, actual) {
        let first = expected
            .lines()
            .zip(actual.lines())
            .position(|(e, a)| e != a)
            .unwrap_or_else(|| expected.lines().count().min(actual.lines().count()));
        panic!(
            "output differs from {} at line {} (UPDATE_GOLDEN=1 rewrites it)\n--- expected ---\n{}\n--- actual ---\n{}",
            path.display(),
            first + 1,
            expected.lines().nth(first).unwrap_or("<end of file>"),
            actual.lines().nth(first).unwrap_or("<end of file>"),
        );
    }
}

/// Tolerance of numeric golden comparisons: one unit in the sixth decimal, so that a last-digit
/// rounding difference of another machine's libm does not fail a golden test.
const GOLDEN_TOLERANCE: f64 = 1.5e-6;

/// Whether two CSV or JSON Lines texts agree number by number (the comparison `biscara diff`
/// makes); texts of other kinds never do.
fn numerically_equal(expected: &str, actual: &str) -> bool {
    let options = biscara::diff::DiffOptions { tolerance: GOLDEN_TOLERANCE };
    biscara::diff::diff(expected.as_bytes(), actual.as_bytes(), options)
        .is_ok_and(|report| report.is_equal())
}

/// Every robot in `data/robots/` reads back to itself through `biscara robot`.
#[test]
fn robots_in_data_print_as_their_golden_files() {
    let dir = temp_dir("golden-robots");
    let mut robots: Vec<_> = std::fs::read_dir(repo_root().join("data/robots"))
        .expect("data/robots")
        .map(|entry| entry.expect("entry").path())
        .collect();
    robots.sort();
    assert!(!robots.is_empty());
    for robot in robots {
        let name = robot.file_name().and_then(|n| n.to_str()).expect("name").to_owned();
        let run = biscara(&dir, &["--robot", robot.to_str().expect("path"), "robot"]);
        run.success();
        check_golden(&format!("robots/{name}"), &run.stdout);
    }
}

/// Every `step`-th data row of a CSV, with its header: a small golden that still follows the
/// whole trajectory.
pub fn decimate(csv: &str, step: usize) -> String {
    let mut lines = csv.lines();
    let mut kept = String::new();
    if let Some(header) = lines.next() {
        kept.push_str(header);
        kept.push('\n');
    }
    let rows: Vec<&str> = lines.collect();
    for (index, row) in rows.iter().enumerate() {
        if index % step == 0 || index + 1 == rows.len() {
            kept.push_str(row);
            kept.push('\n');
        }
    }
    kept
}

/// The demo with a robot that has motors writes the torques they must give in traj.csv
/// (docs/dynamics.md).
#[test]
fn demo_with_motors_writes_the_torques() {
    let dir = temp_dir("golden-demo-motors");
    let robot = repo_root().join("data/robots/servo-example.json");
    let run = biscara(&dir, &["--robot", robot.to_str().expect("path"), "demo", "out"]);
    run.success();
    assert!(run.stdout.contains("accelerations and torques"), "{run}");
    let written = std::fs::read_to_string(dir.join("out/traj.csv")).expect("demo output");
    check_golden("demo/servo-example/traj.csv.every-250th-row", &decimate(&written, 250));
}

/// The demo runs the whole pipeline and writes every stage's file.
#[test]
fn demo_writes_its_golden_files() {
    let dir = temp_dir("golden-demo");
    let run = biscara(&dir, &["demo", "out"]);
    run.success();
    assert!(run.stdout.contains("peak joint speeds"), "{run}");
    for name in ["robot.json", "job.txt", "job.cl", "job.ngc", "job.jsonl"] {
        let written = std::fs::read_to_string(dir.join("out").join(name)).expect("demo output");
        check_golden(&format!("demo/{name}"), &written);
    }
    for name in ["path.csv", "traj.csv"] {
        let written = std::fs::read_to_string(dir.join("out").join(name)).expect("demo output");
        check_golden(&format!("demo/{name}.every-250th-row"), &decimate(&written, 250));
    }
}
