//! Where a program's text comes from.

use std::io::{self, BufRead};

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
}
