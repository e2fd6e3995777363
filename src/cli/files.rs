//! The command line's outputs: `biscara-files`' atomic writer with the binary's error type.

use std::io::Write;
use std::path::Path;

/// Writes through `write` to `path` (atomically), or to standard output for `None` or `-`.
pub(crate) fn write_output(
    path: Option<&Path>,
    write: impl FnOnce(&mut dyn Write) -> anyhow::Result<()>,
) -> anyhow::Result<()> {
    biscara_files::write_output(path, write)
}
