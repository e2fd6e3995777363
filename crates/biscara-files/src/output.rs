//! Outputs: standard output, or a file written atomically.

use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use crate::{FileError, is_stdio, temporary_path};

/// Writes through `write` to `path`, or to standard output when `path` is `None` or `-`.
///
/// A regular file is written to a temporary file beside it, synced, and renamed over the target
/// only when `write` succeeds: a failed run leaves no partial file and an earlier good file
/// untouched, and an interrupt (SIGINT, SIGTERM, SIGHUP) removes the temporary file and exits with
/// 130. A path that exists and is not a regular file (`/dev/null`, a FIFO, a terminal) is written
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

/// Exit code after SIGINT, SIGTERM or SIGHUP: 128 + SIGINT, as shells report an interrupt.
const INTERRUPTED: i32 = 130;

/// Installs, once, the handler of SIGINT, SIGTERM and SIGHUP: it removes the temporary files of
/// outputs being written and exits with 130. Runs that write no file keep the default behaviour.
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
