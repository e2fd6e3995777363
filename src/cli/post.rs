//! `biscara post`: CL file → G-code.

use std::path::PathBuf;

use biscara::post::{PostOptions, PostSummary, post as post_file};
use biscara_files::{Level, display_path, located_at, open_input, report};
use clap::Args;

use super::files::write_output;

/// Turns a CL file into G-code that runs unchanged on LinuxCNC.
///
/// Reads the CL files `biscara clf` writes and those of 3-axis CAM systems: GOTO with 3, 4 or 6
/// values (the tool axis must be 0,0,1), FEDRAT in MMPM or IPM (either order), UNITS/INCHES
/// (converted to mm), CIRCLE + GOTO (→ G2/G3), DELAY (→ G4), PICK (→ M3), PLACE (→ M4), PPRINT
/// and PARTNO (→ comments), END, FINI, `$` continuations and `$$` comments. Post words with no
/// meaning for this robot (SPINDL, COOLNT, LOADTL, CUTTER, MULTAX, TLAXIS, …) become comments and
/// are listed once on stderr. Anything else is an error naming the line, with exit code 1.
#[derive(Debug, Args)]
#[command(
    about = "CL file → G-code for LinuxCNC",
    after_long_help = "Example:\n  $ biscara post job.cl -o job.ngc\n  \
                       $ biscara post --line-numbers data/cl/bracket.cl > bracket.ngc"
)]
pub(crate) struct PostArgs {
    /// The CL file; `-` reads standard input.
    #[arg(value_name = "CL")]
    cl: PathBuf,
    /// Write to FILE instead of standard output.
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,
    /// Number the blocks N10, N20, …
    #[arg(long)]
    line_numbers: bool,
}

pub(crate) fn post(args: &PostArgs) -> anyhow::Result<()> {
    let input = open_input(&args.cl)?;
    let options = PostOptions { line_numbers: args.line_numbers };
    let mut summary = PostSummary::default();
    write_output(args.output.as_deref(), |out| {
        summary =
            post_file(input, out, options).map_err(|err| located_at(&args.cl, err.line(), err))?;
        Ok(())
    })?;
    if let Some(note) = summary.ignored_note() {
        report(Level::Note, format_args!("{}: {note}", display_path(&args.cl)));
    }
    Ok(())
}
