//! The files of a command-line run, the one place that opens paths: inputs (a file, or standard
//! input for `-`, with a progress bar on a terminal for large files), whole text files checked
//! for UTF-8, and outputs written atomically (a temporary file beside the target, renamed over it
//! only on success, removed when the run is interrupted), and the G-code interpreter's
//! [`FileSystem`] (its file subroutines, tool tables and INI files, and `python3` for LinuxCNC's
//! Python plug-ins); and the command line's diagnostics on stderr ([`report`], [`NoteReporter`],
//! [`error_message`] with the pipeline's hints worded as flags).
//!
//! The stage crates never open a path: they read `impl BufRead` and write `impl Write`. This crate
//! gives the binary those readers and writers with the guarantees users rely on: a failed or
//! interrupted run leaves no partial file and an earlier good file untouched; an output that is
//! not a regular file (`/dev/null`, a FIFO) is written in place, never replaced.
//!
//! ```
//! use std::io::{BufRead, Write};
//!
//! let dir = std::env::temp_dir().join(format!("biscara-files-doc-{}", std::process::id()));
//! std::fs::create_dir_all(&dir)?;
//! let path = dir.join("out.txt");
//! biscara_files::write_output(Some(&path), |out| -> Result<(), biscara_files::FileError> {
//!     writeln!(out, "G0 X1")?;
//!     Ok(())
//! })?;
//! let mut first = String::new();
//! biscara_files::open_input(&path)?.read_line(&mut first)?;
//! assert_eq!(first, "G0 X1\n");
//! # std::fs::remove_dir_all(&dir)?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod diag;
mod environment;
mod input;
mod output;
mod robot;
mod source;
mod trajectory;

use std::path::{Path, PathBuf};

use biscara_view::ImageFormat;

pub use diag::{Level, NoteReporter, error_message, is_broken_pipe, located, located_at, report};
pub use environment::FileSystem;
pub use indicatif::ProgressBar;
pub use input::{
    NamedInput, ProgressFile, open_file, open_input, open_inputs, progress, read_bytes, read_text,
    read_texts,
};
pub use output::{catch_interrupts, on_interrupt, write_output};
pub use robot::{load_meshes, load_robot, load_scene, resolve_meshes};
pub use source::FileSource;
pub use trajectory::read_joint_rows;

/// What went wrong with a file, and which file.
#[derive(Debug, thiserror::Error)]
pub enum FileError {
    /// The file (or standard input) could not be read.
    #[error("cannot read {path}: {source}")]
    Read {
        /// The path as shown to users ([`display_path`]).
        path: String,
        /// What the system said.
        source: std::io::Error,
    },
    /// A whole text file holds bytes that are not UTF-8; `line` is where the first one is.
    #[error("{path}:{line}: the file is not UTF-8 text")]
    NotUtf8 {
        /// The path as shown to users.
        path: String,
        /// The 1-based line of the first byte that is not UTF-8.
        line: usize,
    },
    /// An output (or its temporary file) could not be created or renamed into place.
    #[error("cannot write {path}: {source}")]
    Write {
        /// The path of the output or of its temporary file.
        path: String,
        /// What the system said.
        source: std::io::Error,
    },
    /// A file's content is wrong: `message` starts with the line (and column) when it has one.
    #[error("{path}:{message}")]
    Located {
        /// The path as shown to users.
        path: String,
        /// What is wrong, from the reader of the content.
        message: String,
    },
    /// A joint trajectory file holds no rows ([`read_joint_rows`]).
    #[error("{path}: the trajectory has no rows")]
    NoRows {
        /// The path as shown to users.
        path: String,
    },
    /// Writing the content failed (a full disk, a closed pipe).
    #[error(transparent)]
    Io(#[from] std::io::Error),
    /// Another error, as it is: a reader's error with no line to locate ([`located_at`]).
    #[error(transparent)]
    Other(Box<dyn std::error::Error + Send + Sync>),
}

/// How a path is named in messages: `<stdin>` for `-`.
pub fn display_path(path: &Path) -> String {
    if is_stdio(path) { "<stdin>".to_owned() } else { path.display().to_string() }
}

/// The last component of a path, for titles (the whole path when it has none).
pub fn file_name(path: &Path) -> String {
    path.file_name().map_or_else(|| display_path(path), |name| name.to_string_lossy().into_owned())
}

/// The picture format a path asks for: PNG for `.png`, else SVG (also on standard output).
pub fn image_format(path: Option<&Path>) -> ImageFormat {
    match path.and_then(|p| p.extension()).and_then(|e| e.to_str()) {
        Some(ext) if ext.eq_ignore_ascii_case("png") => ImageFormat::Png,
        _ => ImageFormat::Svg,
    }
}

/// Whether `path` is `-`: standard input or output.
fn is_stdio(path: &Path) -> bool {
    path == Path::new("-")
}

/// `dir/.name.tmp-PID` beside `path`.
fn temporary_path(path: &Path) -> PathBuf {
    let name = path.file_name().map(|name| name.to_string_lossy().into_owned()).unwrap_or_default();
    path.with_file_name(format!(".{name}.tmp-{}", std::process::id()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn standard_input_is_named_stdin() {
        assert_eq!(display_path(Path::new("-")), "<stdin>");
        assert_eq!(display_path(Path::new("a/b.ngc")), "a/b.ngc");
        assert_eq!(file_name(Path::new("a/b.ngc")), "b.ngc");
        assert_eq!(image_format(Some(Path::new("a.PNG"))), ImageFormat::Png);
        assert_eq!(image_format(Some(Path::new("a.png.svg"))), ImageFormat::Svg);
        assert_eq!(image_format(None), ImageFormat::Svg);
    }

    #[test]
    fn the_temporary_file_sits_beside_the_target() {
        let temporary = temporary_path(Path::new("out/traj.csv"));
        assert_eq!(temporary.parent(), Some(Path::new("out")));
        assert!(temporary.file_name().unwrap().to_string_lossy().starts_with(".traj.csv.tmp-"));
    }
}
