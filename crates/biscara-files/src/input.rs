//! Inputs: a file or standard input, read line by line or whole.

use std::fs::File;
use std::io::{self, BufRead, BufReader, IsTerminal, Read};
use std::path::Path;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressFinish, ProgressStyle};

use crate::{FileError, display_path, is_stdio};

/// Inputs smaller than this get no progress bar: they are done before it would show.
const MIN_BYTES_FOR_PROGRESS: u64 = 4 << 20;

/// `path` opened for buffered reading (standard input for `-`). When stderr is a terminal and the
/// file is large, reading it advances a progress bar on stderr, cleared at the end.
pub fn open_input(path: &Path) -> Result<Box<dyn BufRead>, FileError> {
    if is_stdio(path) {
        return Ok(Box::new(io::stdin().lock()));
    }
    let file = File::open(path).map_err(|source| read_error(path, source))?;
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

/// The whole content of `path` (standard input for `-`).
pub fn read_bytes(path: &Path) -> Result<Vec<u8>, FileError> {
    let mut bytes = Vec::new();
    let result = if is_stdio(path) {
        io::stdin().read_to_end(&mut bytes).map(drop)
    } else {
        std::fs::read(path).map(|content| bytes = content)
    };
    result.map_err(|source| read_error(path, source))?;
    Ok(bytes)
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
        std::fs::remove_file(path).unwrap();
    }
}
