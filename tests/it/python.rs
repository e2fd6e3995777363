//! The Python package's pytest suite (python/tests), run against the package installed in a
//! virtual environment: `.ci/run` builds it (`python3 -m venv`, `pip install ./python pytest`)
//! and names it in `BISCARA_PYTHON_VENV`. Without it the test is skipped with a message on a
//! developer machine and fails under `CI=true`.

use std::path::PathBuf;
use std::process::Command;

use crate::util::{repo_root, skip_or_fail};

#[test]
fn pytest_suite_passes_against_the_command_line() {
    let Some(venv) = std::env::var_os("BISCARA_PYTHON_VENV") else {
        skip_or_fail(
            "the Python package's pytest suite",
            "a virtual environment with the package (BISCARA_PYTHON_VENV)",
            ": python3 -m venv DIR && DIR/bin/pip install ./python pytest, then \
             BISCARA_PYTHON_VENV=DIR",
        );
        return;
    };
    let pytest = PathBuf::from(venv).join("bin").join("pytest");
    let output = Command::new(&pytest)
        .args(["-q", "-p", "no:cacheprovider"])
        .arg(repo_root().join("python").join("tests"))
        .env("BISCARA_BIN", env!("CARGO_BIN_EXE_biscara"))
        .current_dir(repo_root())
        .output()
        .unwrap_or_else(|err| panic!("cannot run {}: {err}", pytest.display()));
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    );
    match output.status.code() {
        Some(0) => {}
        // pytest's "no tests collected": the suite was not found, which must not pass.
        Some(5) => panic!("pytest collected no tests from python/tests:\n{text}"),
        _ => panic!("the Python package's tests failed ({}):\n{text}", output.status),
    }
    assert!(text.contains(" passed"), "pytest printed no passed tests:\n{text}");
}
