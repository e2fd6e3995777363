//! Running LinuxCNC headless on a configuration: the crate's one edge with the outside world.
//!
//! It builds and installs the kinematics component when the installed module was built from
//! another source, copies the configuration into a fresh run folder with the headless display,
//! starts `linuxcnc` in its own process group, waits for it, and afterwards makes sure nothing
//! of it is left: no process, no lock file, no shared-memory segment.

use std::fs;
use std::io::Read as _;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::Mutex;
use std::time::{Duration, Instant};

use crate::LinuxcncError;
use crate::config::{COMPONENT_NAME, INI_FILE, RUNNER_FILE};

/// Where `rtapi_app` loads realtime modules from (Debian's `linuxcnc-uspace`).
pub const MODULE_DIR: &str = "/usr/lib/linuxcnc/modules";

/// LinuxCNC's lock file: one LinuxCNC per machine.
pub const LOCK_FILE: &str = "/tmp/linuxcnc.lock";

/// The programs LinuxCNC starts, which must all be gone after a run.
pub const LINUXCNC_PROCESSES: [&str; 7] =
    ["rtapi_app", "milltask", "io", "linuxcncsvr", "halsampler", "halstreamer", "biscara_run.py"];

/// The text in the kinematics module that names the source it was built from.
const SOURCE_MARK: &str = "biscara-kinematics-source ";

/// What the kinematics component needed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ComponentStatus {
    /// The installed module was built from this source.
    Installed,
    /// It was missing or built from another source, and has been built and installed.
    Updated,
}

/// One run: what LinuxCNC is to do.
#[derive(Debug, Clone, PartialEq)]
pub struct RunRequest {
    /// The configuration folder (`biscara linuxcnc config`'s output).
    pub config: PathBuf,
    /// A G-code program to run (after the stream, if there is one).
    pub program: Option<PathBuf>,
    /// A stream file to play first: one line per servo cycle, `theta1 theta2 d4 theta3`
    /// (degrees, mm).
    pub stream: Option<PathBuf>,
    /// A G54 offset `[x, y, z, c]` (mm, degrees) set before the program.
    pub origin: Option<[f64; 4]>,
    /// How long the program or the stream may take, seconds.
    pub timeout: f64,
    /// A commissioning event: E-stop or machine off this many seconds after the stream (or the
    /// program) started.
    pub event: Option<(Event, f64)>,
}

/// What a commissioning run does to the machine ([`RunRequest::event`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Event {
    /// Press E-stop.
    Estop,
    /// Switch the machine off.
    MachineOff,
}

impl Event {
    /// The event a command line asks for at its time (seconds after the start): E-stop when
    /// `estop_at` is given, else the machine off when `machine_off_at` is.
    pub fn at(estop_at: Option<f64>, machine_off_at: Option<f64>) -> Option<(Event, f64)> {
        match (estop_at, machine_off_at) {
            (Some(at), _) => Some((Event::Estop, at)),
            (None, Some(at)) => Some((Event::MachineOff, at)),
            (None, None) => None,
        }
    }
}

/// What stopped a run early: an event the run was asked for, or one of the enable chain's.
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
pub struct Stop {
    /// What happened: `E-stop`, `machine off`, `following error` or `joint fault`.
    pub what: String,
    /// When, seconds after the stream (or the program) started, by the display's clock.
    pub time: f64,
}

/// One message of LinuxCNC's.
#[derive(Debug, Clone, PartialEq, Eq, serde::Deserialize)]
pub struct Message {
    /// Whether LinuxCNC reported it as an error.
    pub error: bool,
    /// Its text.
    pub text: String,
}

/// What the headless display reported.
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
struct Outcome {
    ok: bool,
    messages: Vec<Message>,
    #[serde(default)]
    line: usize,
    #[serde(default)]
    failure: Option<String>,
    #[serde(default)]
    overruns: u64,
    #[serde(default)]
    event: Option<Stop>,
}

/// A finished run.
#[derive(Debug)]
pub struct Run {
    /// The run folder (removed when this is dropped).
    folder: TempFolder,
    /// Whether LinuxCNC ran everything without an error.
    pub ok: bool,
    /// LinuxCNC's messages, in order.
    pub messages: Vec<Message>,
    /// The program's line LinuxCNC was at last (0 when unknown).
    pub line: usize,
    /// Why the run stopped early, when it did.
    pub failure: Option<String>,
    /// What stopped the stream or the program, when something did (the recording goes on).
    pub stop: Option<Stop>,
}

impl Run {
    /// The recorder's file (`halsampler -t`'s lines).
    pub fn samples(&self) -> PathBuf {
        self.folder.path().join("samples.txt")
    }

    /// LinuxCNC's own output (its log).
    pub fn log(&self) -> String {
        fs::read_to_string(self.folder.path().join("linuxcnc.log")).unwrap_or_default()
    }
}

/// Whether `program` is on the PATH.
fn on_path(program: &str) -> bool {
    std::env::var_os("PATH")
        .is_some_and(|path| std::env::split_paths(&path).any(|dir| dir.join(program).is_file()))
}

/// Fails unless LinuxCNC and halcompile are installed.
pub fn check_installed() -> Result<(), LinuxcncError> {
    for program in ["linuxcnc", "halcompile", "halsampler", "halstreamer", "halcmd"] {
        if !on_path(program) {
            return Err(LinuxcncError::NotInstalled { program });
        }
    }
    Ok(())
}

/// A short hex digest (FNV-1a, 64 bits) of `text`: the component source's mark.
pub fn source_id(text: &str) -> String {
    let hash = text.bytes().fold(0xcbf2_9ce4_8422_2325_u64, |hash, byte| {
        (hash ^ u64::from(byte)).wrapping_mul(0x0100_0000_01b3)
    });
    format!("{hash:016x}")
}

/// Whether this process runs as root (the owner of `/proc/self`).
fn is_root() -> bool {
    use std::os::unix::fs::MetadataExt as _;
    fs::metadata("/proc/self").is_ok_and(|meta| meta.uid() == 0)
}

/// Builds and installs the kinematics component of `config` when the installed module is
/// missing or was built from another source.
pub fn ensure_component(config: &Path) -> Result<ComponentStatus, LinuxcncError> {
    let source_path = config.join(format!("{COMPONENT_NAME}.comp"));
    let source =
        fs::read_to_string(&source_path).map_err(|err| LinuxcncError::io(&source_path, err))?;
    let mark = source
        .find(SOURCE_MARK)
        .map(|start| &source[start..start + SOURCE_MARK.len() + 16])
        .ok_or_else(|| LinuxcncError::Component {
            message: format!(
                "{} has no source mark: not written by biscara",
                source_path.display()
            ),
        })?;
    let module = Path::new(MODULE_DIR).join(format!("{COMPONENT_NAME}.so"));
    if fs::read(&module).is_ok_and(|bytes| contains(&bytes, mark.as_bytes())) {
        return Ok(ComponentStatus::Installed);
    }
    if !is_root() {
        return Err(LinuxcncError::NeedsRoot { component: source_path });
    }
    // `halcompile --install` overwrites the module in place: never under a running LinuxCNC.
    if Path::new(LOCK_FILE).exists() {
        return Err(LinuxcncError::Busy);
    }
    let build = TempFolder::new("biscara-halcompile")?;
    let copy = build.path().join(format!("{COMPONENT_NAME}.comp"));
    fs::write(&copy, &source).map_err(|err| LinuxcncError::io(&copy, err))?;
    let output = Command::new("halcompile")
        .arg("--install")
        .arg(&copy)
        .current_dir(build.path())
        .stdin(Stdio::null())
        .output()
        .map_err(|err| LinuxcncError::io(Path::new("halcompile"), err))?;
    if !output.status.success() {
        return Err(LinuxcncError::Component {
            message: format!(
                "halcompile --install failed:\n{}{}",
                String::from_utf8_lossy(&output.stdout),
                String::from_utf8_lossy(&output.stderr)
            ),
        });
    }
    Ok(ComponentStatus::Updated)
}

fn contains(haystack: &[u8], needle: &[u8]) -> bool {
    haystack.windows(needle.len()).any(|window| window == needle)
}

/// A fresh, empty folder under the system's temporary folder, removed with what it holds when
/// dropped: the run folder, the component's build folder, the command line's work folder.
#[derive(Debug)]
pub struct TempFolder(PathBuf);

impl TempFolder {
    /// Creates `PREFIX-PID-N` under the system's temporary folder.
    pub fn new(prefix: &str) -> Result<TempFolder, LinuxcncError> {
        use std::sync::atomic::{AtomicUsize, Ordering};
        static COUNTER: AtomicUsize = AtomicUsize::new(0);
        let folder = std::env::temp_dir().join(format!(
            "{prefix}-{}-{}",
            std::process::id(),
            COUNTER.fetch_add(1, Ordering::Relaxed)
        ));
        let _ = fs::remove_dir_all(&folder);
        fs::create_dir_all(&folder).map_err(|err| LinuxcncError::io(&folder, err))?;
        lock(&FOLDERS).push(folder.clone());
        Ok(TempFolder(folder))
    }

    /// The folder.
    pub fn path(&self) -> &Path {
        &self.0
    }
}

impl Drop for TempFolder {
    fn drop(&mut self) {
        let _ = fs::remove_dir_all(&self.0);
        lock(&FOLDERS).retain(|folder| folder != &self.0);
    }
}

/// The temporary folders that exist: removed by [`interrupt`] when the process is about to end.
static FOLDERS: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// Whether a LinuxCNC runs ([`run`] is waiting for it), and whether it was interrupted.
static RUNNING: Mutex<RunState> = Mutex::new(RunState { running: false, interrupted: false });

#[derive(Debug)]
struct RunState {
    running: bool,
    interrupted: bool,
}

fn lock<T>(mutex: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    mutex.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// What the process's interrupt handler (SIGINT, SIGTERM, SIGHUP) calls, from its own thread.
///
/// While a LinuxCNC runs, this asks [`run`] to stop it (its display first, so that LinuxCNC's
/// own shutdown runs, then its process group), remove its folders and fail with
/// [`LinuxcncError::Interrupted`], and returns `true`: the caller must then leave the ending to
/// the main thread. Otherwise it removes every temporary folder of this crate and returns
/// `false`: the caller may end the process.
pub fn interrupt() -> bool {
    {
        let mut state = lock(&RUNNING);
        if state.running {
            state.interrupted = true;
            return true;
        }
    }
    for folder in lock(&FOLDERS).drain(..) {
        let _ = fs::remove_dir_all(folder);
    }
    false
}

/// Marks a run as started; an interrupt that came before fails it at once.
fn start_running() -> Result<(), LinuxcncError> {
    let mut state = lock(&RUNNING);
    if state.interrupted {
        return Err(LinuxcncError::Interrupted);
    }
    state.running = true;
    Ok(())
}

/// Whether the run was interrupted.
fn interrupted() -> bool {
    lock(&RUNNING).interrupted
}

/// Marks the run as ended.
fn stop_running() {
    lock(&RUNNING).running = false;
}

/// The processes of process group `group`: (pid, command line's first two words).
fn group_members(group: u32) -> Vec<(u32, String)> {
    let Ok(entries) = fs::read_dir("/proc") else { return Vec::new() };
    entries
        .flatten()
        .filter_map(|entry| {
            let pid: u32 = entry.file_name().to_str()?.parse().ok()?;
            let stat = fs::read_to_string(entry.path().join("stat")).ok()?;
            (process_group(&stat)? == group).then_some(())?;
            let cmdline = fs::read(entry.path().join("cmdline")).ok()?;
            let words: Vec<String> = cmdline
                .split(|&b| b == 0)
                .take(2)
                .map(|word| String::from_utf8_lossy(word).into_owned())
                .collect();
            Some((pid, words.join(" ")))
        })
        .collect()
}

/// The process group in a `/proc/PID/stat` line: "PID (COMMAND) STATE PPID PGRP …", the
/// command possibly holding spaces and parentheses.
fn process_group(stat: &str) -> Option<u32> {
    let rest = &stat[stat.rfind(')')? + 1..];
    rest.split_whitespace().nth(2)?.parse().ok()
}

/// Stops a running LinuxCNC as its user would: ends its display (the headless runner), which
/// makes LinuxCNC's script shut everything down, and waits up to `grace` for that.
fn stop_display(child: &mut Child, grace: Duration) {
    for (pid, command) in group_members(child.id()) {
        if command.contains(RUNNER_FILE) {
            let _ = Command::new("kill")
                .args(["-s", "TERM", &pid.to_string()])
                .stderr(Stdio::null())
                .status();
        }
    }
    let deadline = Instant::now() + grace;
    while Instant::now() < deadline {
        if matches!(child.try_wait(), Ok(Some(_))) {
            return;
        }
        std::thread::sleep(Duration::from_millis(50));
    }
}

/// Copies the configuration into `folder`, with the headless display in the INI.
fn prepare(config: &Path, folder: &Path) -> Result<(), LinuxcncError> {
    let entries = fs::read_dir(config).map_err(|err| LinuxcncError::io(config, err))?;
    for entry in entries {
        let entry = entry.map_err(|err| LinuxcncError::io(config, err))?;
        let path = entry.path();
        if path.is_file() {
            let target = folder.join(entry.file_name());
            fs::copy(&path, &target).map_err(|err| LinuxcncError::io(&path, err))?;
        }
    }
    let ini_path = folder.join(INI_FILE);
    let ini = fs::read_to_string(&ini_path).map_err(|err| LinuxcncError::io(&ini_path, err))?;
    fs::write(&ini_path, with_display(&ini)).map_err(|err| LinuxcncError::io(&ini_path, err))?;
    let runner = folder.join(RUNNER_FILE);
    if !runner.is_file() {
        return Err(LinuxcncError::Component {
            message: format!(
                "{} has no {RUNNER_FILE}: not a biscara configuration",
                config.display()
            ),
        });
    }
    use std::os::unix::fs::PermissionsExt as _;
    fs::set_permissions(&runner, fs::Permissions::from_mode(0o755))
        .map_err(|err| LinuxcncError::io(&runner, err))?;
    // LinuxCNC's non-realtime threads run as RTAPI_UID, which must write its FIFO here.
    let fifo = folder.join("fifo");
    fs::create_dir_all(&fifo).map_err(|err| LinuxcncError::io(&fifo, err))?;
    fs::set_permissions(&fifo, fs::Permissions::from_mode(0o777))
        .map_err(|err| LinuxcncError::io(&fifo, err))?;
    Ok(())
}

/// The INI with `[DISPLAY] DISPLAY` set to the headless display.
fn with_display(ini: &str) -> String {
    let mut section = String::new();
    let mut out = String::with_capacity(ini.len());
    for line in ini.lines() {
        let trimmed = line.trim();
        if trimmed.starts_with('[') {
            section = trimmed.to_owned();
        }
        let is_display = section == "[DISPLAY]"
            && trimmed.split('=').next().is_some_and(|key| key.trim() == "DISPLAY");
        if is_display {
            out.push_str(&format!("DISPLAY = ./{RUNNER_FILE}"));
        } else {
            out.push_str(line);
        }
        out.push('\n');
    }
    out
}

/// The names of LinuxCNC's processes still running.
pub fn leftover_processes() -> Vec<String> {
    let Ok(entries) = fs::read_dir("/proc") else { return Vec::new() };
    let mut found = Vec::new();
    for entry in entries.flatten() {
        let name = entry.file_name();
        if !name.to_string_lossy().bytes().all(|b| b.is_ascii_digit()) {
            continue;
        }
        let Ok(cmdline) = fs::read(entry.path().join("cmdline")) else { continue };
        for argument in cmdline.split(|&b| b == 0).take(2) {
            let argument = String::from_utf8_lossy(argument);
            let base = argument.rsplit('/').next().unwrap_or("");
            if LINUXCNC_PROCESSES.contains(&base) {
                found.push(format!("{base} (pid {})", name.to_string_lossy()));
            }
        }
    }
    found
}

/// The System V shared-memory segments of HAL and RTAPI still present (`/proc/sysvipc/shm`).
pub fn leftover_shared_memory() -> Vec<String> {
    let Ok(text) = fs::read_to_string("/proc/sysvipc/shm") else { return Vec::new() };
    text.lines()
        .skip(1)
        .filter_map(|line| {
            let key: i64 = line.split_whitespace().next()?.parse().ok()?;
            let key = key as u32;
            is_linuxcnc_key(key).then(|| format!("key 0x{key:08x}"))
        })
        .collect()
}

/// LinuxCNC's System V shared-memory keys: its NML buffers (1001-1010 in `linuxcnc.nml`), the
/// motion controller's (100) and HAL's and its components' (`HAL2`, `HHL4`, `HST0`, `HSA0`: all
/// starting with `H`).
fn is_linuxcnc_key(key: u32) -> bool {
    (1001..=1010).contains(&key) || key == 100 || key >> 24 == u32::from(b'H')
}

/// Whether a process of process group `group` is still running.
fn group_alive(group: u32) -> bool {
    !group_members(group).is_empty()
}

/// Kills what is left of a LinuxCNC: its process group (LinuxCNC's script, started in a group
/// of its own, and everything it started), then `halrun -U`, and removes the lock file.
fn clean_up(child: &mut Child) {
    let group = child.id();
    if child.try_wait().ok().flatten().is_none() {
        let _ = child.kill();
    }
    let _ = child.wait();
    if group_alive(group) {
        // `--`: a negative number after it is a process group, never an option.
        let _ = Command::new("kill")
            .args(["-s", "KILL", "--", &format!("-{group}")])
            .stderr(Stdio::null())
            .status();
    }
    if !leftover_processes().is_empty() || Path::new(LOCK_FILE).exists() {
        let _ = Command::new("halrun")
            .arg("-U")
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .status();
        let _ = fs::remove_file(LOCK_FILE);
    }
}

/// Runs LinuxCNC headless on `request`: the program and/or the stream, recorded every servo
/// cycle. Fails before starting when LinuxCNC is missing or already running.
pub fn run(request: &RunRequest) -> Result<Run, LinuxcncError> {
    check_installed()?;
    if Path::new(LOCK_FILE).exists() {
        return Err(LinuxcncError::Busy);
    }
    let temporary = TempFolder::new("biscara-linuxcnc")?;
    let folder = temporary.path().to_owned();
    let mut run = Run {
        folder: temporary,
        ok: false,
        messages: Vec::new(),
        line: 0,
        failure: None,
        stop: None,
    };
    prepare(&request.config, &folder)?;
    let log_path = folder.join("linuxcnc.log");
    let log = fs::File::create(&log_path).map_err(|err| LinuxcncError::io(&log_path, err))?;
    let log_err = log.try_clone().map_err(|err| LinuxcncError::io(&log_path, err))?;
    let mut command = Command::new("linuxcnc");
    command
        .arg("-r")
        .arg(INI_FILE)
        .current_dir(&folder)
        .stdin(Stdio::null())
        .stdout(log)
        .stderr(log_err)
        // The script copies its logs into $HOME on an error: keep them in the run folder.
        .env("HOME", &folder)
        .env("BISCARA_SAMPLES", run.samples())
        .env("BISCARA_RESULT", folder.join("result.json"))
        .env("BISCARA_TIMEOUT", format!("{}", request.timeout));
    if is_root() {
        // As root, LinuxCNC's non-realtime threads run as RTAPI_UID (any user: `nobody` unless
        // the caller says), which must be able to write its FIFO (a folder open to all).
        let uid = std::env::var("RTAPI_UID").unwrap_or_else(|_| "65534".to_owned());
        command.env("RTAPI_UID", uid).env("RTAPI_FIFO_PATH", folder.join("fifo").join("fifo"));
    }
    if let Some(program) = &request.program {
        let program = fs::canonicalize(program).map_err(|err| LinuxcncError::io(program, err))?;
        command.env("BISCARA_PROGRAM", program);
    }
    if let Some(stream) = &request.stream {
        let stream = fs::canonicalize(stream).map_err(|err| LinuxcncError::io(stream, err))?;
        command.env("BISCARA_STREAM", stream);
    }
    if let Some((event, at)) = request.event {
        let kind = match event {
            Event::Estop => "estop",
            Event::MachineOff => "machine-off",
        };
        command.env("BISCARA_EVENT", format!("{kind}:{at}"));
    }
    if let Some([x, y, z, c]) = request.origin {
        command.env("BISCARA_ORIGIN", format!("{x},{y},{z},{c}"));
    }
    use std::os::unix::process::CommandExt as _;
    command.process_group(0);
    start_running()?;
    let mut child = match command.spawn() {
        Ok(child) => child,
        Err(err) => {
            stop_running();
            return Err(LinuxcncError::io(Path::new("linuxcnc"), err));
        }
    };
    // The display waits `timeout` for the program; LinuxCNC takes seconds to start and stop.
    let deadline = Instant::now() + Duration::from_secs_f64(request.timeout + 60.0);
    let status = loop {
        if interrupted() {
            stop_display(&mut child, Duration::from_secs(20));
            break None;
        }
        match child.try_wait() {
            Ok(Some(status)) => break Some(status),
            Ok(None) if Instant::now() < deadline => std::thread::sleep(Duration::from_millis(20)),
            _ => break None,
        }
    };
    clean_up(&mut child);
    stop_running();
    if interrupted() {
        return Err(LinuxcncError::Interrupted);
    }
    let result_path = folder.join("result.json");
    let mut text = String::new();
    let outcome = fs::File::open(&result_path)
        .and_then(|mut file| file.read_to_string(&mut text))
        .ok()
        .and_then(|_| serde_json::from_str::<Outcome>(&text).ok());
    let Some(outcome) = outcome else {
        let why = match status {
            None => "did not finish in time".to_owned(),
            Some(status) => format!("exited ({status}) without a result"),
        };
        return Err(LinuxcncError::Failed { why, log: run.log() });
    };
    if outcome.overruns > 0 {
        return Err(LinuxcncError::Failed {
            why: format!("the recorder lost {} samples (its FIFO overran)", outcome.overruns),
            log: run.log(),
        });
    }
    run.ok = outcome.ok;
    run.messages = outcome.messages;
    run.line = outcome.line;
    run.failure = outcome.failure;
    run.stop = outcome.event;
    Ok(run)
}
