//! `biscara diff`: numeric comparison of two outputs, for golden-file checks.

use std::path::PathBuf;

use anyhow::anyhow;
use biscara::diff::{DiffError, DiffOptions, Side, diff as compare};
use biscara::text::non_negative;
use clap::Args;

use biscara_files::{display_path, open_input};

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
    let (name_a, name_b) = (display_path(&args.a), display_path(&args.b));
    let name = |side| if side == Side::A { name_a.clone() } else { name_b.clone() };
    let report =
        compare(open_input(&args.a)?, open_input(&args.b)?, DiffOptions { tolerance: args.tol })
            .map_err(|err| match err {
                DiffError::Io { side, line, source } => anyhow!("{}:{line}: {source}", name(side)),
                DiffError::Json { side, line, message } => {
                    anyhow!("{}:{line}: not JSON: {message}", name(side))
                }
                other => anyhow!("{name_a} and {name_b}: {other}"),
            })?;
    match report.first {
        None => {
            #[allow(clippy::print_stdout)]
            {
                println!(
                    "equal within {}: {} rows, largest difference {:e}",
                    args.tol, report.rows, report.largest_difference
                );
            }
            Ok(())
        }
        Some(first) => Err(anyhow!(
            "{name_b}:{}: `{}` differs: {name_a} has {}, {name_b} has {}; {} of {} rows differ \
             (tolerance {})",
            first.line,
            first.column,
            first.a,
            first.b,
            report.differing_rows,
            report.rows,
            args.tol
        )),
    }
}
