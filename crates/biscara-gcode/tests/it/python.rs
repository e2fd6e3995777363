//! LinuxCNC's Python plug-ins through the library: O-word subroutines written in Python,
//! `;py,` lines and `(py,…)` comments with an INI file's `[PYTHON]` section, refused without
//! one; Python's moves streamed in flat memory. (Each feature is compared with LinuxCNC's
//! `rs274` in `tests/conformance/python_*.ngc`, `conformance.rs`.)
//!
//! These tests need `python3`: without it they are skipped, saying so, except under `CI=true`,
//! where they fail.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::Arc;

use biscara_files::FileSystem;
use biscara_gcode::{Config, GcodeError, InMemory, IniFile, Interpreter, Setting, interpret};
use biscara_motion::{Motion, MotionKind};

use crate::memory::in_a_process_of_its_own;
use crate::owords::count_in_flat_memory;

/// Whether `python3` runs; when it does not, `test` is skipped (a failure under `CI=true`).
fn python3_available(test: &str) -> bool {
    let runs =
        Command::new("python3").arg("--version").output().is_ok_and(|out| out.status.success());
    if !runs {
        let ci = std::env::var("CI").is_ok_and(|value| value == "true");
        assert!(!ci, "{test}: python3 is missing under CI=true");
        #[allow(clippy::print_stderr)]
        {
            eprintln!("{test}: skipped: python3 is not installed");
        }
    }
    runs
}

/// A folder of its own with `files` (name, text) written in it.
fn folder_with(name: &str, files: &[(&str, &str)]) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("biscara-python-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("create a temporary folder");
    for (file, text) in files {
        std::fs::write(dir.join(file), text).expect("write a file");
    }
    dir
}

/// The configuration with the INI file `name` of `dir`.
fn config_with_ini(dir: &Path, name: &str) -> Config {
    let ini = IniFile::read(&FileSystem, &dir.join(name)).expect("read the INI file");
    Config { ini: Some(Arc::new(ini)), ..Config::default() }
}

/// `program` interpreted with `config` in the file system, where `python3` runs.
fn run<'a>(program: &'a str, config: &Config) -> Interpreter<&'a [u8]> {
    interpret(program.as_bytes(), config).with_environment(Arc::new(FileSystem))
}

const INI: &str = "[PYTHON]\nPATH_PREPEND = .\nTOPLEVEL = toplevel.py\n";
const TOPLEVEL: &str = "import oword\n";
const OWORD: &str = "\
import emccanon

def zigzag(self, count, step):
    for i in range(int(count)):
        emccanon.STRAIGHT_FEED(1, i * step, (i % 2) * step, 0, 0, 0, 0, 0, 0, 0)
    return count * step

def missing_canon(self):
    emccanon.ARC_FEED(1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0)
";

fn ends(motions: &[Motion]) -> Vec<[f64; 4]> {
    motions.iter().filter_map(|motion| motion.kind.end()).collect()
}

#[test]
fn a_python_subroutine_moves_between_the_programs_moves() {
    if !python3_available("a_python_subroutine_moves_between_the_programs_moves") {
        return;
    }
    let dir =
        folder_with("moves", &[("test.ini", INI), ("toplevel.py", TOPLEVEL), ("oword.py", OWORD)]);
    let program = "G21 F600\nG0 X-1\no<zigzag> call [3] [2]\nG1 Y#<_value>\nM2\n";
    let motions: Vec<Motion> = run(program, &config_with_ini(&dir, "test.ini"))
        .collect::<Result<_, _>>()
        .unwrap_or_else(|err| panic!("{err}"));
    assert_eq!(
        ends(&motions),
        [
            [-1.0, 0.0, 0.0, 0.0],
            [0.0, 0.0, 0.0, 0.0],
            [2.0, 2.0, 0.0, 0.0],
            [4.0, 0.0, 0.0, 0.0],
            [-1.0, 6.0, 0.0, 0.0]
        ],
        "the G1 after the call starts from the program's own current point, X-1"
    );
    assert!(motions[1..4].iter().all(|motion| motion.line == 3), "{motions:?}");
    assert!(matches!(motions[2].kind, MotionKind::Linear { feed, .. } if feed.mm_per_min == 600.0));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn python_errors_point_at_the_line_that_ran_it() {
    if !python3_available("python_errors_point_at_the_line_that_ran_it") {
        return;
    }
    let dir = folder_with(
        "errors",
        &[
            ("test.ini", INI),
            ("toplevel.py", TOPLEVEL),
            ("oword.py", OWORD),
            ("broken.ini", "[PYTHON]\nTOPLEVEL = not_there.py\n"),
        ],
    );
    let error = |ini: &str, program: &str| {
        let result: Result<Vec<Motion>, GcodeError> =
            run(program, &config_with_ini(&dir, ini)).collect();
        result.expect_err("an error").to_string()
    };
    let canon = error("test.ini", "G0 X1\no<missing_canon> call\nM2\n");
    assert!(
        canon.starts_with("2:1: Python subroutine o<missing_canon> failed: AttributeError"),
        "{canon}"
    );
    assert!(canon.contains("ARC_FEED") && canon.contains("oword.py:9"), "{canon}");
    let line = error("test.ini", "G0 X1\n;py,import no_such_module\nM2\n");
    assert!(line.starts_with("2:1: this line's Python failed: ModuleNotFoundError"), "{line}");
    let load = error("broken.ini", "G0 X1\n;py,x = 1\nM2\n");
    assert!(
        load.contains("2:1: the INI file's Python plug-ins ([PYTHON]) cannot be loaded"),
        "{load}"
    );
    assert!(load.contains("not_there.py"), "{load}");
    // A subroutine Python does not have is looked for in the program, as without plug-ins.
    let missing = error("test.ini", "o<nowhere> call\nM2\n");
    assert!(missing.contains("seeking o-word: o<nowhere> from line: 1"), "{missing}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_programs_python_is_refused_without_a_python_section() {
    // No python3 needed: nothing is run.
    for program in [";py,print('hello')\nM2\n", "G0 X1 (py,x = 1)\nM2\n", "(pyreload)\nM2\n"] {
        let result: Result<Vec<Motion>, GcodeError> =
            interpret(program.as_bytes(), &Config::default()).collect();
        let err = result.expect_err("refused");
        assert_eq!(err.setting(), Some(Setting::Ini));
        let message = err.to_string();
        assert!(message.contains("runs only with LinuxCNC's Python plug-ins"), "{message}");
        assert!(!message.contains("--"), "no command-line flag in the library: {message}");
    }
    // Not Python: `;PY,` (LinuxCNC's check is case-sensitive), `; py,` and `(pyx)`.
    let program = ";PY,print('hello')\n; py,x\nG0 X1 (pyx)\nM2\n";
    let motions: Result<Vec<Motion>, GcodeError> =
        interpret(program.as_bytes(), &Config::default()).collect();
    assert_eq!(motions.map(|motions| motions.len()).ok(), Some(2));
}

#[test]
fn python_needs_an_environment_that_starts_it() {
    // No python3 needed: the environment has none (the library never starts a process itself).
    let ini = IniFile::read(&InMemory::new().with_file("m.ini", INI), Path::new("m.ini"))
        .expect("read the INI file from memory");
    let config = Config { ini: Some(Arc::new(ini)), ..Config::default() };
    let program = "G0 X1\n;py,x = 1\nM2\n";
    let result: Result<Vec<Motion>, GcodeError> = interpret(program.as_bytes(), &config)
        .with_environment(Arc::new(InMemory::new()))
        .collect();
    let message = result.expect_err("refused").to_string();
    assert_eq!(
        message,
        "2:1: the INI file's Python plug-ins ([PYTHON]) cannot be loaded: cannot run python3 for \
         them: no Python in this environment"
    );
}

#[test]
fn a_python_subroutines_moves_stream_in_flat_memory() {
    if !in_a_process_of_its_own("python::a_python_subroutines_moves_stream_in_flat_memory") {
        return;
    }
    if !python3_available("a_python_subroutines_moves_stream_in_flat_memory") {
        return;
    }
    let dir =
        folder_with("flat", &[("test.ini", INI), ("toplevel.py", TOPLEVEL), ("oword.py", OWORD)]);
    // 200,000 moves held take some 25 MiB (measured with the pause taken out); streamed, none.
    let program = "G21 F600\no<zigzag> call [200000] [0.001]\nM2\n";
    let config = config_with_ini(&dir, "test.ini");
    let count = count_in_flat_memory(run(program, &config));
    assert_eq!(count, 200_001);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn pyrun_runs_a_file_and_pyreload_runs_toplevel_again() {
    if !python3_available("pyrun_runs_a_file_and_pyreload_runs_toplevel_again") {
        return;
    }
    let toplevel = "import oword\nloads = globals().get('loads', 0) + 1\n";
    let extra = "import interpreter\ninterpreter.this.params['_from_file'] = 3.5\n";
    let dir = folder_with(
        "pyrun",
        &[("test.ini", INI), ("toplevel.py", toplevel), ("oword.py", OWORD), ("extra.py", extra)],
    );
    let program = format!(
        "(pyrun,{})\nG0 X#<_from_file>\n(PyReload)\n;py,import interpreter\n\
         ;py,interpreter.this.params['_loads'] = loads\nG0 Y#<_loads>\nM2\n",
        dir.join("extra.py").display()
    );
    let motions: Vec<Motion> = run(&program, &config_with_ini(&dir, "test.ini"))
        .collect::<Result<_, _>>()
        .unwrap_or_else(|err| panic!("{err}"));
    assert_eq!(ends(&motions), [[3.5, 0.0, 0.0, 0.0], [3.5, 2.0, 0.0, 0.0]]);
    let _ = std::fs::remove_dir_all(&dir);
}
