//! `biscara diff`: numeric comparison of two outputs, for golden-file checks.

use std::path::PathBuf;

use anyhow::anyhow;
use biscara::diff::{DiffOptions, diff as compare};
use biscara::text::non_negative;
use biscara_files::{display_path, open_input};
use clap::Args;

use super::files::write_output;

/// Compares two outputs of the same kind (joint or path CSV, inter-file) number by number.
///
/// Exit 0 when every value agrees within the tolerance; exit 1 naming the first differing line,
/// column and both values, and the count of differing rows. Meant for regression checks of your
/// own programs in CI: keep a reviewed output, regenerate it, compare.
#[derive(Debug, Args)]
#[command(
    about = "Compare two outputs numerically (exit 1 when they differ)",
    after_long_help = "Example:\n  $ biscara joints job.ngc -o new.csv\n  \
                       $ biscara diff expected.csv new.csv --tol 1e-6"
)]
pub(crate) struct DiffArgs {
    /// The expected file.
    #[arg(value_name = "A")]
    a: PathBuf,
    /// The file to check.
    #[arg(value_name = "B")]
    b: PathBuf,
    /// Largest absolute difference of two numbers that still counts as equal.
    #[arg(long, value_name = "X", default_value = "1e-6", value_parser = non_negative("the tolerance"))]
    tol: f64,
}

pub(crate) fn diff(args: &DiffArgs) -> anyhow::Result<()> {
    let (a, b) = (display_path(&args.a), display_path(&args.b));
    let options = DiffOptions { tolerance: args.tol };
    let report = compare(open_input(&args.a)?, open_input(&args.b)?, options)
        .map_err(|err| anyhow!(err.named(&a, &b)))?;
    let agreement = report.verdict(&a, &b, args.tol)?;
    write_output(None, |out| Ok(writeln!(out, "{agreement}")?))
}
