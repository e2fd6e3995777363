//! The command line's files: the program as the pipeline's source, the scene, and the
//! input/output functions of `biscara-files` with the binary's error type.

use std::io::{BufRead, Write};
use std::path::Path;

use biscara::view::ImageFormat;
pub(crate) use biscara_files::{FileSource, display_path, file_name, load_meshes, load_scene};

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
