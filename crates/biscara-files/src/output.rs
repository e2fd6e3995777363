//! Outputs: standard output, or a file written atomically.

use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::{Mutex, OnceLock};

use crate::{FileError, is_stdio, temporary_path};

/// Writes through `write` to `path`, or to standard output when `path` is `None` or `-`.
///
/// A regular file is written to a temporary file beside it, synced, and renamed over the target
/// only when `write` succeeds: a failed run leaves no partial file and an earlier good file
/// untouched, and an interrupt (SIGINT, SIGTERM, SIGHUP) removes the temporary file and ends the
/// process as the caller asked ([`on_interrupt`]). A path that exists and is not a regular file (`/dev/null`, a FIFO, a terminal) is written
/// in place: renaming over it would replace the device with a file.
pub fn write_output<E: From<FileError>>(
    path: Option<&Path>,
    write: impl FnOnce(&mut dyn Write) -> Result<(), E>,
) -> Result<(), E> {
    match path {
        Some(path) if !is_stdio(path) && is_special(path) => {
            let file = std::fs::OpenOptions::new()
                .write(true)
                .open(path)
                .map_err(|source| write_error(path, source))?;
            write_buffered(BufWriter::new(file), write).map(drop)
        }
        Some(path) if !is_stdio(path) => write_file_atomically(path, write),
        _ => write_buffered(BufWriter::new(io::stdout().lock()), write).map(drop),
    }
}

/// Whether `path` exists and is neither a regular file nor a folder.
fn is_special(path: &Path) -> bool {
    std::fs::metadata(path).is_ok_and(|metadata| !metadata.is_file() && !metadata.is_dir())
}

/// Runs `write` on `out` and flushes it; returns the inner writer.
fn write_buffered<W: Write, E: From<FileError>>(
    mut out: BufWriter<W>,
    write: impl FnOnce(&mut dyn Write) -> Result<(), E>,
) -> Result<W, E> {
    write(&mut out)?;
    out.into_inner().map_err(|err| E::from(FileError::Io(err.into_error())))
}

fn write_file_atomically<E: From<FileError>>(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> Result<(), E>,
) -> Result<(), E> {
    let temporary = temporary_path(path);
    register(&temporary);
    let result = (|| {
        let file = File::create(&temporary).map_err(|source| write_error(&temporary, source))?;
        let file = write_buffered(BufWriter::new(file), write)?;
        file.sync_all().map_err(FileError::Io)?;
        std::fs::rename(&temporary, path).map_err(|source| write_error(path, source))?;
        Ok(())
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&temporary);
    }
    unregister(&temporary);
    result
}

fn write_error(path: &Path, source: io::Error) -> FileError {
    FileError::Write { path: path.display().to_string(), source }
}

/// Temporary files being written right now, removed by the interrupt handler.
static TEMPORARIES: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// What the interrupt handler calls once the temporary files are removed: the caller's, set by
/// [`on_interrupt`].
static INTERRUPTED: OnceLock<fn() -> !> = OnceLock::new();

/// Makes SIGINT, SIGTERM and SIGHUP remove the temporary files of the outputs being written and
/// then call `interrupted`, which ends the process (the `biscara` binary exits with 130, as
/// shells report an interrupt). The handler is installed when the first output file is written:
/// runs that write no file keep the signals' default behaviour. Only the first call counts.
///
/// Without this call the signals are left alone, and an interrupted run may leave a temporary
/// file beside its output (never a partial output: the target is replaced only on success).
pub fn on_interrupt(interrupted: fn() -> !) {
    let _ = INTERRUPTED.set(interrupted);
}

/// Installs the handler of [`on_interrupt`] now, rather than when the first output file is
/// written: for a run that owns something outside the process (a controller it started) from
/// its start.
pub fn catch_interrupts() {
    remove_temporaries_on_interrupt();
}

/// Installs, once, the handler of SIGINT, SIGTERM and SIGHUP when the caller asked for one.
fn remove_temporaries_on_interrupt() {
    static INSTALLED: std::sync::Once = std::sync::Once::new();
    let Some(&interrupted) = INTERRUPTED.get() else { return };
    // Without the handler an interrupt would still leave the target untouched, only a stray
    // temporary file: not worth failing the run for.
    INSTALLED.call_once(|| {
        let _ = ctrlc::set_handler(move || {
            remove_temporaries();
            interrupted()
        });
    });
}

/// Removes the temporary files of the outputs being written.
fn remove_temporaries() {
    let temporaries = TEMPORARIES.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
    for path in temporaries.iter() {
        let _ = std::fs::remove_file(path);
    }
}

fn register(path: &Path) {
    remove_temporaries_on_interrupt();
    TEMPORARIES.lock().unwrap_or_else(|poisoned| poisoned.into_inner()).push(path.to_owned());
}

fn unregister(path: &Path) {
    TEMPORARIES.lock().unwrap_or_else(|poisoned| poisoned.into_inner()).retain(|p| p != path);
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch_dir(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("biscara-files-{}-{name}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn a_failed_write_leaves_the_earlier_file_and_no_temporary() {
        let dir = scratch_dir("failed");
        let path = dir.join("traj.csv");
        std::fs::write(&path, "good\n").unwrap();
        let result = write_output(Some(&path), |out| -> Result<(), FileError> {
            out.write_all(b"partial")?;
            Err(FileError::Io(io::Error::other("the pipeline failed")))
        });
        assert!(result.is_err());
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "good\n");
        let names: Vec<_> =
            std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().file_name()).collect();
        assert_eq!(names, [std::ffi::OsString::from("traj.csv")]);
        std::fs::remove_dir_all(dir).unwrap();
    }

    #[test]
    fn a_successful_write_replaces_the_file() {
        let dir = scratch_dir("success");
        let path = dir.join("out.txt");
        std::fs::write(&path, "old\n").unwrap();
        write_output(Some(&path), |out| -> Result<(), FileError> { Ok(out.write_all(b"new\n")?) })
            .unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "new\n");
        std::fs::remove_dir_all(dir).unwrap();
    }

    #[test]
    fn a_missing_folder_is_named() {
        let path = Path::new("/nonexistent-biscara/out.txt");
        let err = write_output(Some(path), |_| -> Result<(), FileError> { Ok(()) }).unwrap_err();
        assert!(
            err.to_string().starts_with("cannot write /nonexistent-biscara/.out.txt.tmp-"),
            "{err}"
        );
    }
}
