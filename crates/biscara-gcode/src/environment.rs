//! What the interpreter reaches outside the program it is given: the files a program names
//! (file subroutines, user M-code programs, a tool table, an INI file) and LinuxCNC's Python
//! plug-ins. The library never opens a path or starts a process itself: the caller gives it an
//! [`Environment`] (the command line's reads the file system and runs `python3`; tests give an
//! [`InMemory`] one).

use std::collections::HashMap;
use std::ffi::OsString;
use std::fmt;
use std::io::{self, BufRead, Write};
use std::path::{Path, PathBuf};

use crate::syntax::lexer::Seekable;

/// The world outside the program: files by path, and a Python interpreter.
///
/// Paths are built by the interpreter as LinuxCNC builds them (`NAME.ngc` beside the program,
/// then in the subroutine folders; `M101` in the INI file's user M-code folders); the
/// environment only answers whether a path names a file and opens it.
pub trait Environment: fmt::Debug {
    /// Opens the file `path` from its start, as an input the interpreter can jump in (a file
    /// subroutine is read again from its labels).
    ///
    /// # Errors
    /// Why it cannot be opened (the interpreter quotes it in its message).
    fn open(&self, path: &Path) -> io::Result<Box<dyn Seekable>>;

    /// Whether `path` names a file (where file subroutines and user M-code programs are
    /// looked for).
    fn is_file(&self, path: &Path) -> bool;

    /// Starts `python3` with `arguments` (after the program's name), its standard input and
    /// output piped to the interpreter and its standard error the caller's. Refused by default:
    /// a program's Python then cannot run.
    ///
    /// # Errors
    /// Why Python cannot be started.
    fn start_python(&self, arguments: &[OsString]) -> io::Result<Box<dyn PythonProcess>> {
        let _ = arguments;
        Err(io::Error::new(io::ErrorKind::Unsupported, "no Python in this environment"))
    }
}

/// A running `python3` ([`Environment::start_python`]), stopped when dropped.
pub trait PythonProcess: fmt::Debug {
    /// Its standard input.
    fn input(&mut self) -> &mut dyn Write;

    /// Its standard output.
    fn output(&mut self) -> &mut dyn BufRead;

    /// Waits for it to end: how it ended (`exit status: 1`), for a message.
    fn wait(&mut self) -> String;
}

/// An environment with no files and no Python: what [`interpret`](crate::interpret) reads by
/// default (a file subroutine is then never found, a program's Python never runs).
#[derive(Debug, Clone, Copy, Default)]
pub struct NoEnvironment;

impl Environment for NoEnvironment {
    fn open(&self, path: &Path) -> io::Result<Box<dyn Seekable>> {
        Err(io::Error::new(io::ErrorKind::NotFound, format!("no file {}", path.display())))
    }

    fn is_file(&self, _path: &Path) -> bool {
        false
    }
}

/// Files held in memory, by path: for tests and for programs built in memory. It has no Python.
///
/// ```
/// use std::path::Path;
/// use biscara_gcode::{Environment, InMemory};
///
/// let files = InMemory::new().with_file("subs/square.ngc", "o<square> sub\no<square> endsub\n");
/// assert!(files.is_file(Path::new("subs/square.ngc")));
/// assert!(!files.is_file(Path::new("square.ngc")));
/// ```
#[derive(Debug, Clone, Default)]
pub struct InMemory {
    files: HashMap<PathBuf, Vec<u8>>,
}

impl InMemory {
    /// No files.
    pub fn new() -> InMemory {
        InMemory::default()
    }

    /// The same files and `path` holding `text`.
    #[must_use]
    pub fn with_file(mut self, path: impl Into<PathBuf>, text: impl Into<Vec<u8>>) -> InMemory {
        self.files.insert(path.into(), text.into());
        self
    }
}

impl Environment for InMemory {
    fn open(&self, path: &Path) -> io::Result<Box<dyn Seekable>> {
        match self.files.get(path) {
            Some(text) => Ok(Box::new(io::Cursor::new(text.clone()))),
            None => Err(io::Error::new(io::ErrorKind::NotFound, "no such file in memory")),
        }
    }

    fn is_file(&self, path: &Path) -> bool {
        self.files.contains_key(path)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn files_in_memory_open_and_jump() {
        let files = InMemory::new().with_file("a.ngc", "G0 X1\nM2\n");
        let mut input = files.open(Path::new("a.ngc")).expect("a.ngc is there");
        let mut line = String::new();
        input.read_line(&mut line).expect("a line");
        assert_eq!(line, "G0 X1\n");
        input.jump(6, 0).expect("jumps back");
        line.clear();
        input.read_line(&mut line).expect("the line again");
        assert_eq!(line, "G0 X1\n");
        assert_eq!(
            files.open(Path::new("b.ngc")).err().map(|err| err.kind()),
            Some(io::ErrorKind::NotFound)
        );
        assert!(NoEnvironment.open(Path::new("a.ngc")).is_err());
        assert!(!NoEnvironment.is_file(Path::new("a.ngc")));
        assert!(files.start_python(&[]).is_err());
    }
}
