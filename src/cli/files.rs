//! Inputs and outputs: opening programs (with a progress bar on a terminal), and writing
//! outputs to standard output or atomically to a file.

use std::fs::File;
use std::io::{self, BufRead, BufReader, BufWriter, IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use anyhow::Context;
use biscara::gcode::Seekable;
use biscara::pipeline::{ProgramKind, ProgramSource};
use biscara::robot::Scene;
use biscara::view::ImageFormat;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressFinish, ProgressStyle};

use super::args::InputKind;
use super::diag::located;

/// How a path is named in messages: `<stdin>` for `-`.
pub(crate) fn display_path(path: &Path) -> String {
    if path == Path::new("-") { "<stdin>".to_owned() } else { path.display().to_string() }
}

/// The last component of a path, for titles.
pub(crate) fn file_name(path: &Path) -> String {
    path.file_name().map_or_else(|| display_path(path), |name| name.to_string_lossy().into_owned())
}

/// A program file (or standard input for `-`) as the pipeline's source.
pub(crate) struct FileSource {
    path: PathBuf,
    name: String,
}

impl FileSource {
    pub(crate) fn new(path: &Path) -> FileSource {
        FileSource { path: path.to_owned(), name: display_path(path) }
    }

    /// The program's kind: `from` when given, else from its name and first bytes.
    pub(crate) fn kind(&self, from: Option<InputKind>) -> anyhow::Result<ProgramKind> {
        if let Some(kind) = from {
            return Ok(kind.into());
        }
        let mut input = self.open().with_context(|| format!("cannot read {}", self.name))?;
        let head = input.fill_buf()?;
        Ok(ProgramKind::detect(&self.name, &head[..head.len().min(64)]))
    }
}

impl ProgramSource for FileSource {
    fn name(&self) -> &str {
        &self.name
    }

    fn open(&self) -> io::Result<Box<dyn BufRead>> {
        if self.path == Path::new("-") {
            return Ok(Box::new(io::stdin().lock()));
        }
        Ok(open_with_progress(&self.path)?)
    }

    fn open_seekable(&self) -> io::Result<Option<Box<dyn Seekable>>> {
        if self.path == Path::new("-") {
            return Ok(None);
        }
        open_with_progress(&self.path).map(Some)
    }

    fn path(&self) -> Option<&Path> {
        (self.path != Path::new("-")).then_some(self.path.as_path())
    }

    fn rereadable(&self) -> bool {
        self.path != Path::new("-")
    }
}

/// The scene of `--scene FILE` (`-`: standard input), or an empty one; errors as
/// `FILE:LINE:COL: key: message`.
pub(crate) fn load_scene(path: Option<&Path>) -> anyhow::Result<Scene> {
    let Some(path) = path else { return Ok(Scene::new()) };
    let bytes = if path == Path::new("-") {
        let mut bytes = Vec::new();
        io::Read::read_to_end(&mut io::stdin(), &mut bytes)?;
        bytes
    } else {
        std::fs::read(path).with_context(|| format!("cannot read {}", path.display()))?
    };
    Scene::from_json(&bytes).map_err(|err| located(path, err))
}

/// The picture format a path asks for: PNG for `.png`, else SVG (also on standard output).
pub(crate) fn format_of(path: Option<&Path>) -> ImageFormat {
    match path.and_then(|p| p.extension()).and_then(|e| e.to_str()) {
        Some(ext) if ext.eq_ignore_ascii_case("png") => ImageFormat::Png,
        _ => ImageFormat::Svg,
    }
}

/// Opens a text input: a file, or standard input for `-`.
pub(crate) fn open_input(path: &Path) -> anyhow::Result<Box<dyn BufRead>> {
    if path == Path::new("-") {
        return Ok(Box::new(io::stdin().lock()));
    }
    let file = File::open(path).with_context(|| format!("cannot read {}", path.display()))?;
    Ok(Box::new(BufReader::new(file)))
}

/// Inputs smaller than this get no progress bar: they are done before it would show.
const MIN_BYTES_FOR_PROGRESS: u64 = 4 << 20;

/// `path` opened for buffered reading (standard input for `-`). When stderr is a terminal and
/// the file is large, reading it advances a progress bar on stderr, cleared at the end.
fn open_with_progress(path: &Path) -> io::Result<Box<dyn Seekable>> {
    let file = File::open(path)?;
    let length = file.metadata().map(|metadata| metadata.len()).unwrap_or(0);
    if length < MIN_BYTES_FOR_PROGRESS || !io::stderr().is_terminal() {
        return Ok(Box::new(BufReader::with_capacity(1 << 16, file)));
    }
    let bar = ProgressBar::with_draw_target(Some(length), ProgressDrawTarget::stderr())
        .with_style(
            ProgressStyle::with_template("{bar:40} {bytes}/{total_bytes} {elapsed} eta {eta}")
                .unwrap_or_else(|_| ProgressStyle::default_bar()),
        )
        .with_finish(ProgressFinish::AndClear);
    Ok(Box::new(BufReader::with_capacity(1 << 16, bar.wrap_read(file))))
}

/// Temporary files being written right now, removed by the interrupt handler.
static TEMPORARIES: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// Exit code after SIGINT, SIGTERM or SIGHUP: 128 + SIGINT, as shells report an interrupt.
const INTERRUPTED: i32 = 130;

/// Installs, once, the handler of SIGINT, SIGTERM and SIGHUP: it removes the temporary files of
/// outputs being written (so an interrupted run leaves neither a partial file nor a temporary one,
/// and an earlier good file untouched) and exits with 130. Runs that write no file keep the
/// default behaviour.
fn remove_temporaries_on_interrupt() {
    static INSTALLED: std::sync::Once = std::sync::Once::new();
    // Without the handler an interrupt would still leave the target untouched, only a stray
    // temporary file: not worth failing the run for.
    INSTALLED.call_once(|| {
        let _ = ctrlc::set_handler(remove_temporaries_and_exit);
    });
}

fn remove_temporaries_and_exit() {
    {
        let temporaries = TEMPORARIES.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
        for path in temporaries.iter() {
            let _ = std::fs::remove_file(path);
        }
    }
    std::process::exit(INTERRUPTED);
}

fn register(path: &Path) {
    remove_temporaries_on_interrupt();
    TEMPORARIES.lock().unwrap_or_else(|poisoned| poisoned.into_inner()).push(path.to_owned());
}

fn unregister(path: &Path) {
    TEMPORARIES.lock().unwrap_or_else(|poisoned| poisoned.into_inner()).retain(|p| p != path);
}

/// Writes through `write` to `path`, or to standard output when `path` is `None` or `-`.
///
/// A file is written to a temporary file beside it and renamed over the target only when `write`
/// succeeds, so a failed run leaves no partial file and an earlier good file untouched.
pub(crate) fn write_output(
    path: Option<&Path>,
    write: impl FnOnce(&mut dyn Write) -> anyhow::Result<()>,
) -> anyhow::Result<()> {
    match path {
        None => write_stdout(write),
        Some(path) if path == Path::new("-") => write_stdout(write),
        Some(path) if is_special(path) => write_special(path, write),
        Some(path) => write_file_atomically(path, write),
    }
}

/// Whether `path` exists and is not a regular file (`/dev/null`, a FIFO, a terminal): renaming a
/// temporary file over it would replace the device with a file, so it is written in place.
fn is_special(path: &Path) -> bool {
    std::fs::metadata(path).is_ok_and(|metadata| !metadata.is_file() && !metadata.is_dir())
}

fn write_special(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> anyhow::Result<()>,
) -> anyhow::Result<()> {
    let file = std::fs::OpenOptions::new()
        .write(true)
        .open(path)
        .with_context(|| format!("cannot write {}", path.display()))?;
    let mut out = BufWriter::new(file);
    write(&mut out)?;
    out.flush()?;
    Ok(())
}

fn write_stdout(write: impl FnOnce(&mut dyn Write) -> anyhow::Result<()>) -> anyhow::Result<()> {
    let stdout = io::stdout();
    let mut out = BufWriter::new(stdout.lock());
    write(&mut out)?;
    out.flush()?;
    Ok(())
}

fn write_file_atomically(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> anyhow::Result<()>,
) -> anyhow::Result<()> {
    let temporary = temporary_path(path);
    register(&temporary);
    let result = (|| {
        let file = File::create(&temporary)
            .with_context(|| format!("cannot create {}", temporary.display()))?;
        let mut out = BufWriter::new(file);
        write(&mut out)?;
        let file = out.into_inner().map_err(io::IntoInnerError::into_error)?;
        file.sync_all()?;
        std::fs::rename(&temporary, path)
            .with_context(|| format!("cannot write {}", path.display()))
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&temporary);
    }
    unregister(&temporary);
    result
}

/// `dir/.name.tmp-PID` beside `path`.
fn temporary_path(path: &Path) -> PathBuf {
    let name = path.file_name().map(|name| name.to_string_lossy().into_owned()).unwrap_or_default();
    path.with_file_name(format!(".{name}.tmp-{}", std::process::id()))
}
