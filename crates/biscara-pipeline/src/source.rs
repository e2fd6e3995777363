//! Where a program's text comes from.

use std::io::{self, BufRead};
use std::path::Path;
use std::sync::Arc;

use biscara_gcode::{Environment, NoEnvironment, Seekable};

/// A program's text, opened by the caller: the pipeline never touches a path.
pub trait ProgramSource {
    /// How the program is named in messages: its path, or `<stdin>`.
    fn name(&self) -> &str;

    /// The text from its start. Called twice when the program is placed with `--fit`.
    fn open(&self) -> io::Result<Box<dyn BufRead>>;

    /// Whether [`ProgramSource::open`] may be called more than once (false for standard input).
    fn rereadable(&self) -> bool {
        true
    }

    /// The text from its start as an input the interpreter can jump in (O-word loops and
    /// subroutine calls go back by byte offset); `None` (the default) when it can only be read
    /// forwards, as standard input.
    fn open_seekable(&self) -> io::Result<Option<Box<dyn Seekable>>> {
        Ok(None)
    }

    /// The program's file, when it is one: file subroutines (`o<name> call`) are looked for
    /// beside it, and it names the program in LinuxCNC's messages. `None` by default.
    fn path(&self) -> Option<&Path> {
        None
    }

    /// Where the files a G-code program names (file subroutines, user M-code programs) are
    /// found, and how its Python starts: none of them by default ([`NoEnvironment`]).
    fn environment(&self) -> Arc<dyn Environment> {
        Arc::new(NoEnvironment)
    }
}

/// A program held in a string: for tests, benchmarks and programs built in memory.
#[derive(Debug, Clone)]
pub struct TextSource {
    name: String,
    text: String,
}

impl TextSource {
    /// The program `text`, named `name` in messages.
    pub fn new(name: impl Into<String>, text: impl Into<String>) -> TextSource {
        TextSource { name: name.into(), text: text.into() }
    }
}

impl ProgramSource for TextSource {
    fn name(&self) -> &str {
        &self.name
    }

    fn open(&self) -> io::Result<Box<dyn BufRead>> {
        Ok(Box::new(io::Cursor::new(self.text.clone().into_bytes())))
    }

    fn open_seekable(&self) -> io::Result<Option<Box<dyn Seekable>>> {
        Ok(Some(Box::new(io::Cursor::new(self.text.clone().into_bytes()))))
    }
}
