//! `biscara gen`: points file → G-code in one streaming pass (clf + post).

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{Context, anyhow};
use biscara::cl::write_statement;
use biscara::kinematics::{Kinematics, Robot};
use biscara::pnp::ClProgram;
use biscara::post::{PostOptions, Postprocessor};
use clap::error::ErrorKind;
use clap::{Args, CommandFactory};

use super::input::open_input;
use super::output::write_output;
use super::post::post_error;
use super::{Cli, display_path};

/// Turns a pick-and-place points file straight into G-code: `biscara clf` and `biscara post` in
/// one pass, with the same checks and the same output.
///
/// With --clf the intermediate CL file is written too. On any error nothing is written: the exit
/// code is 1 and the message names the line of the points file.
#[derive(Debug, Args)]
#[command(
    about = "Points file → G-code (clf + post in one pass)",
    after_long_help = "Example:\n  $ biscara gen data/jobs/pick_place.txt > job.ngc\n  \
                       $ biscara gen data/jobs/pallet_3x3.txt -o pallet.ngc --clf pallet.cl"
)]
pub(crate) struct GenArgs {
    /// The points file (SPEC §2); `-` reads standard input.
    #[arg(value_name = "POINTS")]
    points: PathBuf,
    /// Write the G-code to FILE instead of standard output.
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,
    /// Also write the CL file to FILE.
    #[arg(long, value_name = "FILE")]
    clf: Option<PathBuf>,
    /// Number the G-code blocks N10, N20, …
    #[arg(long)]
    line_numbers: bool,
}

pub(crate) fn generate(robot: &Robot, args: &GenArgs) -> anyhow::Result<()> {
    let is_stdout = |path: Option<&Path>| path.is_none_or(|path| path == Path::new("-"));
    if args.clf.as_deref().is_some_and(|path| path == Path::new("-"))
        && is_stdout(args.output.as_deref())
    {
        let message = "--clf - and the G-code cannot both go to standard output: give -o FILE";
        Cli::command().error(ErrorKind::ArgumentConflict, message).exit();
    }
    let model = Kinematics::new(robot)?;
    let input = open_input(&args.points)?;
    let options = PostOptions { line_numbers: args.line_numbers };
    match args.clf.as_deref() {
        Some(clf_path) => write_output(Some(clf_path), |clf_out| {
            write_output(args.output.as_deref(), |out| {
                run(&model, input, out, Some(clf_out), options, &args.points, clf_path)
            })
        }),
        None => write_output(args.output.as_deref(), |out| {
            run(&model, input, out, None, options, &args.points, Path::new("<generated CL>"))
        }),
    }
}

fn run(
    model: &Kinematics,
    input: Box<dyn std::io::BufRead>,
    out: &mut dyn Write,
    mut clf_out: Option<&mut dyn Write>,
    options: PostOptions,
    points_path: &Path,
    clf_path: &Path,
) -> anyhow::Result<()> {
    let mut post = Postprocessor::new(out, options);
    let mut cl_line = 0;
    for statement in ClProgram::new(input, model) {
        let statement = statement.map_err(|err| anyhow!("{}:{err}", display_path(points_path)))?;
        cl_line += 1;
        if let Some(clf_out) = clf_out.as_mut() {
            write_statement(clf_out, &statement).context("cannot write the CL file")?;
        }
        post.apply(cl_line, &statement).map_err(|err| post_error(clf_path, err))?;
    }
    post.finish(cl_line).map_err(|err| post_error(clf_path, err))?;
    if let Some(clf_out) = clf_out {
        clf_out.flush().context("cannot write the CL file")?;
    }
    Ok(())
}
