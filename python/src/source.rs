//! Where a program comes from: a file, or text given as `source=`.

use std::fs::File;
use std::io::{self, BufRead, BufReader, Read};
use std::path::{Path, PathBuf};
use std::sync::Arc;

use biscara_files::FileSystem;
use biscara_gcode::{Environment, Seekable};
use biscara_pipeline::{ProgramKind, ProgramSource, TextSource};

use crate::error::{Failure, SOURCE_NAME};

/// A program file, read from the file system; its file subroutines, tool table, INI file and
/// Python plug-ins too, as on the command line.
pub(crate) struct FileSource {
    path: PathBuf,
    name: String,
}

impl ProgramSource for FileSource {
    fn name(&self) -> &str {
        &self.name
    }

    fn open(&self) -> io::Result<Box<dyn BufRead>> {
        Ok(Box::new(BufReader::with_capacity(64 * 1024, File::open(&self.path)?)))
    }

    fn open_seekable(&self) -> io::Result<Option<Box<dyn Seekable>>> {
        FileSystem.open(&self.path).map(Some)
    }

    fn path(&self) -> Option<&Path> {
        Some(&self.path)
    }

    fn environment(&self) -> Arc<dyn Environment> {
        Arc::new(FileSystem)
    }
}

/// A program: a file or text.
pub(crate) enum Program {
    /// A file.
    File(FileSource),
    /// Text, named `<source>` in messages.
    Text(TextSource, String),
}

impl Program {
    /// The program of `path` or `text` (exactly one is given: the Python layer checks).
    pub(crate) fn new(path: Option<PathBuf>, text: Option<String>) -> Result<Program, Failure> {
        match (path, text) {
            (Some(path), None) => {
                let name = path.display().to_string();
                Ok(Program::File(FileSource { path, name }))
            }
            (None, Some(text)) => {
                Ok(Program::Text(TextSource::new(SOURCE_NAME, text.clone()), text))
            }
            _ => Err(Failure::plain("give either a path or source=, not both")),
        }
    }

    /// The pipeline's source.
    pub(crate) fn source(&self) -> &dyn ProgramSource {
        match self {
            Program::File(file) => file,
            Program::Text(text, _) => text,
        }
    }

    /// The file's name in messages (`None` for text).
    pub(crate) fn file(&self) -> Option<&str> {
        match self {
            Program::File(file) => Some(&file.name),
            Program::Text(..) => None,
        }
    }

    /// The whole input as a reader (for the points and CL readers).
    pub(crate) fn reader(&self) -> Result<Box<dyn BufRead + '_>, Failure> {
        match self {
            Program::File(file) => file.open().map_err(|err| {
                Failure::in_file(format!("cannot read {}: {err}", file.name), &file.name)
            }),
            Program::Text(_, text) => Ok(Box::new(text.as_bytes())),
        }
    }

    /// The program's kind: `from` when given (`gcode`, `jsonl`, `path`), else from its name
    /// and first bytes, as the command line decides.
    pub(crate) fn kind(&self, from: Option<&str>) -> Result<ProgramKind, Failure> {
        match from {
            Some("gcode") => return Ok(ProgramKind::Gcode),
            Some("jsonl") => return Ok(ProgramKind::Jsonl),
            Some("path") => return Ok(ProgramKind::Path),
            Some(other) => {
                return Err(Failure::Value(format!(
                    "kind must be \"gcode\", \"jsonl\" or \"path\", got {other:?}"
                )));
            }
            None => {}
        }
        let mut head = Vec::with_capacity(64);
        match self {
            Program::File(file) => {
                let input = File::open(&file.path).map_err(|err| {
                    Failure::in_file(format!("cannot read {}: {err}", file.name), &file.name)
                })?;
                input.take(64).read_to_end(&mut head).map_err(|err| {
                    Failure::in_file(format!("cannot read {}: {err}", file.name), &file.name)
                })?;
                Ok(ProgramKind::detect(&file.name, &head))
            }
            Program::Text(_, text) => {
                let bytes = text.as_bytes();
                Ok(ProgramKind::detect(SOURCE_NAME, &bytes[..bytes.len().min(64)]))
            }
        }
    }
}
