//! Inputs: a file or standard input, read line by line or whole.

use std::fs::File;
use std::io::{self, BufRead, BufReader, IsTerminal, Read, Seek};
use std::path::{Path, PathBuf};

use indicatif::{ProgressBar, ProgressBarIter, ProgressDrawTarget, ProgressFinish, ProgressStyle};

use crate::{FileError, display_path, is_stdio};

/// Inputs smaller than this get no progress bar: they are done before it would show.
const MIN_BYTES_FOR_PROGRESS: u64 = 4 << 20;

/// `path` opened for buffered reading (standard input for `-`); a file as [`open_file`] opens it.
pub fn open_input(path: &Path) -> Result<Box<dyn BufRead>, FileError> {
    if is_stdio(path) {
        return Ok(Box::new(io::stdin().lock()));
    }
    Ok(Box::new(open_file(path)?))
}

/// A file opened for reading: buffered, seekable (so that a reader may jump back, as G-code
/// loops do), and advancing a progress bar on stderr when stderr is a terminal and the file is
/// large (cleared at the end).
pub fn open_file(path: &Path) -> Result<BufReader<ProgressFile>, FileError> {
    let file = File::open(path).map_err(|source| read_error(path, source))?;
    let length = file.metadata().map(|metadata| metadata.len()).unwrap_or(0);
    let bar = if length < MIN_BYTES_FOR_PROGRESS || !io::stderr().is_terminal() {
        ProgressBar::hidden()
    } else {
        ProgressBar::with_draw_target(Some(length), ProgressDrawTarget::stderr())
            .with_style(
                ProgressStyle::with_template("{bar:40} {bytes}/{total_bytes} {elapsed} eta {eta}")
                    .unwrap_or_else(|_| ProgressStyle::default_bar()),
            )
            .with_finish(ProgressFinish::AndClear)
    };
    Ok(BufReader::with_capacity(1 << 16, ProgressFile(bar.wrap_read(file))))
}

/// A progress bar on stderr counting `length` items named `unit` (e.g. "designs"), drawn only
/// when stderr is a terminal; the caller advances it and clears it at the end.
pub fn progress(length: u64, unit: &str) -> ProgressBar {
    if !io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let template = format!("{{bar:40}} {{pos}}/{{len}} {unit} {{elapsed}} eta {{eta}}");
    ProgressBar::with_draw_target(Some(length), ProgressDrawTarget::stderr())
        .with_style(
            ProgressStyle::with_template(&template)
                .unwrap_or_else(|_| ProgressStyle::default_bar()),
        )
        .with_finish(ProgressFinish::AndClear)
}

/// A file whose reads and seeks move its progress bar: what [`open_file`] reads through.
#[derive(Debug)]
pub struct ProgressFile(ProgressBarIter<File>);

impl Read for ProgressFile {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        self.0.read(buf)
    }
}

impl Seek for ProgressFile {
    fn seek(&mut self, to: io::SeekFrom) -> io::Result<u64> {
        self.0.seek(to)
    }
}

/// The whole content of `path` (standard input for `-`).
pub fn read_bytes(path: &Path) -> Result<Vec<u8>, FileError> {
    let bytes = if is_stdio(path) {
        let mut bytes = Vec::new();
        io::stdin().read_to_end(&mut bytes).map(|_| bytes)
    } else {
        std::fs::read(path)
    };
    bytes.map_err(|source| read_error(path, source))
}

/// The whole content of `path` as text; bytes that are not UTF-8 are an error naming their line.
pub fn read_text(path: &Path) -> Result<String, FileError> {
    String::from_utf8(read_bytes(path)?).map_err(|err| {
        let valid = &err.as_bytes()[..err.utf8_error().valid_up_to()];
        let line = valid.iter().filter(|&&byte| byte == b'\n').count() + 1;
        FileError::NotUtf8 { path: display_path(path), line }
    })
}

fn read_error(path: &Path, source: io::Error) -> FileError {
    FileError::Read { path: display_path(path), source }
}

/// Every file of `paths` as [`read_text`] reads it, named as messages name it
/// ([`display_path`]): programs a library reads by name.
pub fn read_texts(paths: &[PathBuf]) -> Result<Vec<(String, String)>, FileError> {
    paths.iter().map(|path| Ok((display_path(path), read_text(path)?))).collect()
}

/// An input and its name as messages name it ([`display_path`]).
pub type NamedInput = (String, Box<dyn BufRead>);

/// Every file of `paths` opened as [`open_input`] opens it, named as messages name it.
pub fn open_inputs(paths: &[PathBuf]) -> Result<Vec<NamedInput>, FileError> {
    paths.iter().map(|path| Ok((display_path(path), open_input(path)?))).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str, content: &[u8]) -> std::path::PathBuf {
        let path =
            std::env::temp_dir().join(format!("biscara-files-{}-{name}", std::process::id()));
        std::fs::write(&path, content).unwrap();
        path
    }

    #[test]
    fn text_that_is_not_utf8_names_its_line() {
        let path = scratch("latin1", b"G0 X1\nG1 X2 (\xe9)\n");
        let err = read_text(&path).unwrap_err();
        assert_eq!(err.to_string(), format!("{}:2: the file is not UTF-8 text", path.display()));
        std::fs::remove_file(path).unwrap();
    }

    #[test]
    fn a_missing_file_is_named() {
        let Err(err) = open_input(Path::new("/nonexistent/biscara.ngc")) else {
            panic!("a missing file opened")
        };
        assert!(err.to_string().starts_with("cannot read /nonexistent/biscara.ngc: "), "{err}");
    }

    #[test]
    fn inputs_read_back_what_was_written() {
        let path = scratch("lines", b"a\nb\n");
        let lines: Vec<String> = open_input(&path).unwrap().lines().map(Result::unwrap).collect();
        assert_eq!(lines, ["a", "b"]);
        assert_eq!(read_text(&path).unwrap(), "a\nb\n");
        let texts = read_texts(std::slice::from_ref(&path)).unwrap();
        assert_eq!(texts, [(path.display().to_string(), "a\nb\n".to_owned())]);
        let mut inputs = open_inputs(&[path.clone(), path.clone()]).unwrap();
        assert_eq!(inputs.len(), 2);
        assert_eq!(io::read_to_string(inputs.pop().unwrap().1).unwrap(), "a\nb\n");
        let missing = PathBuf::from("/nonexistent/biscara.ngc");
        assert!(read_texts(&[path.clone(), missing.clone()]).is_err());
        assert!(open_inputs(&[missing]).is_err());
        let mut file = open_file(&path).unwrap();
        file.seek(io::SeekFrom::Start(2)).unwrap();
        assert_eq!(io::read_to_string(file).unwrap(), "b\n");
        std::fs::remove_file(path).unwrap();
    }
}
