//! `biscara gen`: points file → G-code in one streaming pass (clf + post).

use std::io::Write;
use std::path::{Path, PathBuf};

use biscara::kinematics::RobotModel;
use biscara::pipeline::{GenerateError, generate as generate_gcode};
use biscara::post::PostOptions;
use biscara_files::{located, located_at, open_input};
use clap::error::ErrorKind;
use clap::{Args, CommandFactory};

use super::Cli;
use super::files::write_output;

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
    /// The points file; `-` reads standard input.
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

pub(crate) fn generate(robot: &RobotModel, args: &GenArgs) -> anyhow::Result<()> {
    let is_stdout = |path: Option<&Path>| path.is_none_or(|path| path == Path::new("-"));
    if args.clf.as_deref().is_some_and(|path| path == Path::new("-"))
        && is_stdout(args.output.as_deref())
    {
        let message = "--clf - and the G-code cannot both go to standard output: give -o FILE";
        Cli::command().error(ErrorKind::ArgumentConflict, message).exit();
    }
    let model = robot.kinematics();
    let input = open_input(&args.points)?;
    let options = PostOptions { line_numbers: args.line_numbers };
    let cl_name = args.clf.as_deref().unwrap_or(Path::new("<generated CL>"));
    let run = |out: &mut dyn Write, cl_out: Option<&mut dyn Write>| {
        generate_gcode(input, &model, out, cl_out, options).map_err(|err| match err {
            GenerateError::Points(err) => located(&args.points, err).into(),
            GenerateError::Post(err) => located_at(cl_name, err.line(), err).into(),
            other => anyhow::Error::from(other),
        })
    };
    match args.clf.as_deref() {
        Some(clf_path) => write_output(Some(clf_path), |cl_out| {
            write_output(args.output.as_deref(), |out| run(out, Some(cl_out)))
        }),
        None => write_output(args.output.as_deref(), |out| run(out, None)),
    }
}
