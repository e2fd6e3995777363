//! Resident memory, for the tests that check that the interpreter streams.
//!
//! The workspace forbids `unsafe`, so there is no counting global allocator: the tests sample the
//! process's resident memory (`VmRSS` in `/proc/self/status`). The test harness runs tests in
//! parallel threads of one process, whose allocations would count too, so a memory test runs by
//! itself in a child process of this test binary ([`in_a_process_of_its_own`]).

use std::process::Command;

/// Set in the child process that runs one memory test alone.
const ALONE: &str = "BISCARA_GCODE_MEMORY_TEST_ALONE";

/// Resident memory of this process in KiB (Linux), if known.
pub(crate) fn resident_kib() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|line| line.starts_with("VmRSS:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

/// Whether the test `name` (its full path, `module::test`) should run its body here: true in a
/// child process of this test binary that runs only that test; false in the parent, after
/// asserting that the child passed.
pub(crate) fn in_a_process_of_its_own(name: &str) -> bool {
    if std::env::var_os(ALONE).is_some() {
        return true;
    }
    let binary = std::env::current_exe().expect("the test binary's path");
    let status = Command::new(binary)
        .args([name, "--exact", "--test-threads=1"])
        .env(ALONE, "1")
        .status()
        .expect("run the test binary again");
    assert!(status.success(), "{name} failed in a process of its own (its output is above)");
    false
}
