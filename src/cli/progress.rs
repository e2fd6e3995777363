//! A progress bar on stderr for long runs on a terminal.

use std::fs::File;
use std::io::{self, BufRead, BufReader, IsTerminal};
use std::path::Path;

use anyhow::Context;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressFinish, ProgressStyle};

/// Inputs smaller than this get no progress bar: they are done before it would show.
const MIN_BYTES_FOR_PROGRESS: u64 = 4 << 20;

/// `path` opened for buffered reading (standard input for `-`). When stderr is a terminal and
/// the file is large, reading it advances a progress bar on stderr, cleared at the end.
pub(crate) fn open_with_progress(path: &Path) -> anyhow::Result<Box<dyn BufRead>> {
    if path == Path::new("-") {
        return Ok(Box::new(io::stdin().lock()));
    }
    let file = File::open(path).with_context(|| format!("cannot read {}", path.display()))?;
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
