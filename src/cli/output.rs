//! Writing outputs: standard output, or a file replaced atomically.

use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use anyhow::Context;

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
        Some(path) => write_file_atomically(path, write),
    }
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
