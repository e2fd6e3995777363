//! A program file (or standard input) as the pipeline's source.

use std::io::{self, BufRead};
use std::path::{Path, PathBuf};
use std::sync::Arc;

use biscara_gcode::{Environment, Seekable};
use biscara_pipeline::{ProgramKind, ProgramSource};

use crate::{FileError, FileSystem, display_path, open_file, open_input};

/// A program file (or standard input for `-`) as the pipeline's source.
#[derive(Debug, Clone)]
pub struct FileSource {
    path: PathBuf,
    name: String,
}

impl FileSource {
    /// The program at `path`, named as [`display_path`] names it.
    pub fn new(path: &Path) -> FileSource {
        FileSource { path: path.to_owned(), name: display_path(path) }
    }

    /// The program's kind: `from` when given, else from its name and first 64 bytes.
    pub fn kind(&self, from: Option<ProgramKind>) -> Result<ProgramKind, FileError> {
        if let Some(kind) = from {
            return Ok(kind);
        }
        let mut input = open_input(&self.path)?;
        let head = input.fill_buf()?;
        Ok(ProgramKind::detect(&self.name, &head[..head.len().min(64)]))
    }
}

impl ProgramSource for FileSource {
    fn name(&self) -> &str {
        &self.name
    }

    fn open(&self) -> io::Result<Box<dyn BufRead>> {
        open_input(&self.path).map_err(io_error)
    }

    fn open_seekable(&self) -> io::Result<Option<Box<dyn Seekable>>> {
        if self.path == Path::new("-") {
            return Ok(None);
        }
        Ok(Some(Box::new(open_file(&self.path).map_err(io_error)?)))
    }

    fn path(&self) -> Option<&Path> {
        (self.path != Path::new("-")).then_some(self.path.as_path())
    }

    fn rereadable(&self) -> bool {
        self.path != Path::new("-")
    }

    fn environment(&self) -> Arc<dyn Environment> {
        Arc::new(FileSystem)
    }
}

/// A read error as the pipeline's sources report it: the system's error, the file named by the
/// pipeline.
fn io_error(err: FileError) -> io::Error {
    match err {
        FileError::Read { source, .. } => source,
        other => io::Error::other(other),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_source_detects_its_kind_and_names_standard_input() {
        let dir = std::env::temp_dir().join(format!("biscara-source-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("a folder");
        let path = dir.join("program");
        std::fs::write(&path, "{\"kind\":\"rapid\"}\n").expect("written");
        let source = FileSource::new(&path);
        assert_eq!(source.kind(None).expect("a kind"), ProgramKind::Jsonl);
        assert_eq!(source.kind(Some(ProgramKind::Gcode)).expect("given"), ProgramKind::Gcode);
        assert!(source.rereadable() && source.path() == Some(path.as_path()));
        let stdin = FileSource::new(Path::new("-"));
        assert_eq!((stdin.name(), stdin.path(), stdin.rereadable()), ("<stdin>", None, false));
        std::fs::remove_dir_all(&dir).expect("removed");
    }
}
