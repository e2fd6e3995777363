//! The G-code interpreter's environment on the command line: the file system, and `python3`.

use std::ffi::OsString;
use std::fs::File;
use std::io::{self, BufRead, BufReader, Write};
use std::path::Path;
use std::process::{Child, ChildStdin, ChildStdout, Command, Stdio};
use std::sync::Arc;

use biscara_gcode::{Environment, PythonProcess, Seekable};

/// The files a G-code program names (file subroutines, user M-code programs, tool tables, INI
/// files) read from the file system, and LinuxCNC's Python plug-ins run by `python3` from the
/// `PATH`, its standard error the terminal's.
#[derive(Debug, Clone, Copy, Default)]
pub struct FileSystem;

impl FileSystem {
    /// The file `path`, when one is given, read by `read` (a tool table's or an INI file's
    /// reader) from the file system, shared: what the interpreter's settings keep.
    pub fn read_shared<T, E>(
        path: Option<&Path>,
        read: fn(&dyn Environment, &Path) -> Result<T, E>,
    ) -> Result<Option<Arc<T>>, E> {
        Ok(path.map(|path| read(&FileSystem, path)).transpose()?.map(Arc::new))
    }
}

impl Environment for FileSystem {
    fn open(&self, path: &Path) -> io::Result<Box<dyn Seekable>> {
        Ok(Box::new(BufReader::new(File::open(path)?)))
    }

    fn is_file(&self, path: &Path) -> bool {
        path.is_file()
    }

    fn start_python(&self, arguments: &[OsString]) -> io::Result<Box<dyn PythonProcess>> {
        let mut child = Command::new("python3")
            .args(arguments)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit())
            .spawn()?;
        let (Some(to), Some(from)) = (child.stdin.take(), child.stdout.take()) else {
            let _ = child.kill();
            let _ = child.wait();
            return Err(io::Error::other("cannot talk to python3"));
        };
        Ok(Box::new(Python3 { child, to, from: BufReader::new(from) }))
    }
}

/// A running `python3`, its input and output piped.
#[derive(Debug)]
struct Python3 {
    child: Child,
    to: ChildStdin,
    from: BufReader<ChildStdout>,
}

impl PythonProcess for Python3 {
    fn input(&mut self) -> &mut dyn Write {
        &mut self.to
    }

    fn output(&mut self) -> &mut dyn BufRead {
        &mut self.from
    }

    fn wait(&mut self) -> String {
        self.child.wait().map(|status| status.to_string()).unwrap_or_default()
    }
}

impl Drop for Python3 {
    fn drop(&mut self) {
        // Python may be in a loop of its own: it is stopped, not waited for.
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn name_length(_: &dyn Environment, path: &Path) -> Result<usize, io::Error> {
        match path.to_str() {
            Some("missing") => Err(io::Error::other("missing")),
            _ => Ok(path.as_os_str().len()),
        }
    }

    #[test]
    fn a_file_is_read_only_when_given() {
        assert_eq!(FileSystem::read_shared(None, name_length).unwrap(), None);
        let read = FileSystem::read_shared(Some(Path::new("tools.tbl")), name_length).unwrap();
        assert_eq!(read.as_deref(), Some(&9));
        assert!(FileSystem::read_shared(Some(Path::new("missing")), name_length).is_err());
    }

    #[test]
    fn files_are_opened_from_the_file_system() {
        let dir = std::env::temp_dir().join(format!("biscara-files-env-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("a temporary folder");
        let path = dir.join("sub.ngc");
        std::fs::write(&path, "o<sub> sub\no<sub> endsub\n").expect("write");
        assert!(FileSystem.is_file(&path));
        assert!(!FileSystem.is_file(&dir));
        let mut line = String::new();
        FileSystem.open(&path).expect("open").read_line(&mut line).expect("a line");
        assert_eq!(line, "o<sub> sub\n");
        let missing = FileSystem.open(&dir.join("none.ngc")).err().map(|err| err.kind());
        assert_eq!(missing, Some(io::ErrorKind::NotFound));
        std::fs::remove_dir_all(&dir).expect("clean up");
    }
}
