//! The command line's files: the program as the pipeline's source, the scene, and the
//! input/output functions of `biscara-files` with the binary's error type.

use std::io::{self, BufRead, Write};
use std::path::{Path, PathBuf};
use std::sync::Arc;

use biscara::gcode::{Environment, Seekable};
use biscara::kinematics::Robot;
use biscara::pipeline::{ProgramKind, ProgramSource};
use biscara::robot::Scene;
use biscara::view::{ImageFormat, MAX_MESH_TRIANGLES, StlError, Viewer, read_stl};
pub(crate) use biscara_files::{display_path, file_name};

use super::diag::located;

/// A program file (or standard input for `-`) as the pipeline's source.
pub(crate) struct FileSource {
    path: PathBuf,
    name: String,
}

impl FileSource {
    pub(crate) fn new(path: &Path) -> FileSource {
        FileSource { path: path.to_owned(), name: display_path(path) }
    }

    /// The program's kind: `from` when given, else from its name and first bytes.
    pub(crate) fn kind(&self, from: Option<ProgramKind>) -> anyhow::Result<ProgramKind> {
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
        biscara_files::open_input(&self.path).map_err(io_error)
    }

    fn open_seekable(&self) -> io::Result<Option<Box<dyn Seekable>>> {
        if self.path == Path::new("-") {
            return Ok(None);
        }
        Ok(Some(Box::new(biscara_files::open_file(&self.path).map_err(io_error)?)))
    }

    fn path(&self) -> Option<&Path> {
        (self.path != Path::new("-")).then_some(self.path.as_path())
    }

    fn rereadable(&self) -> bool {
        self.path != Path::new("-")
    }

    fn environment(&self) -> Arc<dyn Environment> {
        Arc::new(biscara_files::FileSystem)
    }
}

/// The scene of `--scene FILE` (`-`: standard input), or an empty one; errors as
/// `FILE:LINE:COL: key: message`.
pub(crate) fn load_scene(path: Option<&Path>) -> anyhow::Result<Scene> {
    let Some(path) = path else { return Ok(Scene::new()) };
    Scene::from_json(&biscara_files::read_bytes(path)?).map_err(|err| located(path, err))
}

/// The picture format a path asks for: PNG for `.png`, else SVG (also on standard output).
pub(crate) fn format_of(path: Option<&Path>) -> ImageFormat {
    match path.and_then(|p| p.extension()).and_then(|e| e.to_str()) {
        Some(ext) if ext.eq_ignore_ascii_case("png") => ImageFormat::Png,
        _ => ImageFormat::Svg,
    }
}

/// Opens a text input: a file, or standard input for `-`.
pub(crate) fn open_input(path: &Path) -> anyhow::Result<Box<dyn BufRead>> {
    Ok(biscara_files::open_input(path)?)
}

/// Writes through `write` to `path` (atomically), or to standard output for `None` or `-`.
pub(crate) fn write_output(
    path: Option<&Path>,
    write: impl FnOnce(&mut dyn Write) -> anyhow::Result<()>,
) -> anyhow::Result<()> {
    biscara_files::write_output(path, write)
}

/// A read error as the pipeline's sources report it: the system's error, the file named by the
/// pipeline.
fn io_error(err: biscara_files::FileError) -> io::Error {
    match err {
        biscara_files::FileError::Read { source, .. } => source,
        other => io::Error::other(other),
    }
}

/// Makes the robot's mesh files absolute, each relative to the robot file's folder (the current
/// folder for standard input), so that the robot in force names them wherever it is used or
/// written; a file that cannot be found is an error at its key: `ROBOT:LINE:COL: meshes.PART: …`.
pub(crate) fn resolve_meshes(robot: &mut Robot, path: &Path, text: &str) -> anyhow::Result<()> {
    let folder = match path.parent() {
        Some(folder) if path != Path::new("-") => folder.to_owned(),
        _ => PathBuf::new(),
    };
    for (part, spec) in robot.meshes.parts_mut() {
        let key = format!("meshes.{part}");
        let file = folder.join(&spec.file);
        let resolved = file.canonicalize().and_then(|resolved| {
            if resolved.is_file() { Ok(resolved) } else { Err(io::Error::other("not a file")) }
        });
        match resolved {
            Ok(resolved) => spec.file = resolved.to_string_lossy().into_owned(),
            Err(err) => {
                let at = Robot::locate_key(text, &key)
                    .map_or_else(String::new, |(line, column)| format!("{line}:{column}: "));
                return Err(anyhow::anyhow!(
                    "{}:{at}{key}: cannot read the STL file {}: {err}",
                    display_path(path),
                    file.display()
                ));
            }
        }
    }
    Ok(())
}

/// Reads the robot's mesh files (already resolved by [`resolve_meshes`]) into the viewer;
/// errors as `STL_FILE:LINE:COL: …` or `STL_FILE: byte N: …`.
pub(crate) fn load_meshes(robot: &Robot, viewer: &mut Viewer) -> anyhow::Result<()> {
    for (part, spec) in robot.meshes.parts() {
        let path = Path::new(&spec.file);
        let mesh = read_stl(open_input(path)?, MAX_MESH_TRIANGLES).map_err(|err| match err {
            // A byte offset reads better after a space: `part.stl: byte 84: …`.
            StlError::Binary { .. } => located(path, format_args!(" {err}")),
            _ => located(path, err),
        })?;
        viewer.add_mesh(part, spec, &mesh).map_err(|err| located(path, format_args!(" {err}")))?;
    }
    Ok(())
}
