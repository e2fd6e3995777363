//! `biscara design`: sweeps link lengths and base distance, `design merge` joins shards,
//! `design atlas` draws a sweep.

use std::path::{Path, PathBuf};

use anyhow::Context as _;
use biscara::design::{
    Objective, ParamRange, Shard, SweepOptions, SweepOutcome, SweepRequest, Task, merge,
};
use biscara::kinematics::RobotModel;
use biscara_files::{Level, display_path, image_format, located, open_input, report};
use clap::{Args, Subcommand};

use super::files::write_output;

/// Sweeps the robot's design: every combination of proximal link l1, distal link l2 and base
/// distance (the two base joints at ±base/2; everything else from the robot file) is measured as
/// `biscara workspace` measures the robot: the grid of reachable points (working and assembly
/// mode, joint limits, singularity margin), its area and the largest axis-aligned rectangle; and
/// over the rectangle's grid points the local conditioning index LCI = 1/cond(J) of the Jacobian
/// J = ∂(x, y)/∂(θ1, θ2): its mean, the GCI, and its worst value.
///
/// Each range is MIN:MAX:N, N values from MIN to MAX inclusive (mm). Writes one CSV row per
/// design, as the designs are done (columns index, l1, l2, base, area_mm2, rect_w_mm, rect_h_mm,
/// rect_x0_mm, rect_y0_mm, gci, lci_min, status: ok, empty (no rectangle) or invalid (the base
/// wider than two distal links), task_ok with --task, time_s with --programs, cycle_s with
/// --objective cycle: the time of `biscara cycle` at the centre of the design's rectangle, its
/// bodies scaled with the links unless the robot file's `dynamics` gives them, its motors
/// fixed; empty where the cycle cannot run, and the note on standard error counts those designs
/// and says why for the first). --best writes the
/// robot file of the best design (largest rectangle, or --objective), among those covering
/// --task; --pareto the designs no other beats in both rectangle area and GCI; --atlas a picture
/// of one index over l1 × l2 for each base.
///
/// The designs run on every core (--threads); --shard K/N evaluates every N-th design from the
/// K-th, so N jobs of a batch system (a Slurm array, GNU parallel) share a sweep, and `biscara
/// design merge` joins their CSVs into the CSV one run writes.
#[derive(Debug, Args)]
#[command(
    about = "Sweep link lengths and base distance: workspace, rectangle, GCI per design",
    args_conflicts_with_subcommands = true,
    subcommand_negates_reqs = true,
    after_long_help = "Example:\n  \
        $ biscara design --l1 150:270:7 --l2 210:330:7 --base 100:300:5 -o designs.csv \\\n      \
        --best robot.json --atlas atlas.svg\n  \
        $ biscara design --l1 150:270:7 --l2 210:330:7 --base 100:300:5 --objective gci \\\n      \
        --task -150,300,150,450 --best robot.json -o designs.csv\n  \
        one job of eight (e.g. a Slurm array), then the join:\n  \
        $ biscara design --l1 150:270:61 --l2 210:330:61 --base 100:300:21 --shard 3/8 -o part3.csv\n  \
        $ biscara design merge part*.csv -o designs.csv"
)]
pub(crate) struct DesignArgs {
    #[command(subcommand)]
    command: Option<DesignCommand>,
    #[command(flatten)]
    sweep: SweepArgs,
}

#[derive(Debug, Subcommand)]
enum DesignCommand {
    Merge(MergeArgs),
    Atlas(AtlasArgs),
}

#[derive(Debug, Args)]
struct SweepArgs {
    /// Proximal link lengths, mm: MIN:MAX:N.
    #[arg(long, value_name = "MIN:MAX:N", required = true, value_parser = ParamRange::parser("l1"))]
    l1: Option<ParamRange>,
    /// Distal link lengths, mm: MIN:MAX:N.
    #[arg(long, value_name = "MIN:MAX:N", required = true, value_parser = ParamRange::parser("l2"))]
    l2: Option<ParamRange>,
    /// Distances between the two base joints, mm: MIN:MAX:N.
    #[arg(long, value_name = "MIN:MAX:N", required = true, value_parser = ParamRange::parser("base"))]
    base: Option<ParamRange>,
    /// Workspace grid step, mm (as `biscara workspace --step`).
    #[arg(long, value_name = "MM", default_value = "2")]
    step: f64,
    /// Write the CSV to FILE instead of standard output.
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,
    /// Write the robot file (robot.json) of the best design to FILE.
    #[arg(long, value_name = "FILE")]
    best: Option<PathBuf>,
    /// What --best and the atlas's ring choose: the largest rectangle, GCI, reachable area or
    /// worst LCI, or the shortest total time of --programs, or the shortest Adept cycle.
    #[arg(long, value_enum, default_value = "rect")]
    objective: Objective,
    /// A task rectangle X0,Y0,X1,Y1 (mm) every chosen design must cover: all its grid points
    /// reachable. Adds the task_ok column.
    #[arg(long, value_name = "X0,Y0,X1,Y1", allow_hyphen_values = true)]
    task: Option<Task>,
    /// Time these programs (G-code, inter-file or path CSV) on every design, as `joints` runs
    /// them (1 ms, the optimal profile, every joint limit), summed: the time_s column (empty
    /// when a program cannot run on the design).
    #[arg(long, value_name = "FILE", num_args = 1..)]
    programs: Vec<PathBuf>,
    /// Centre each of --programs in each design's workspace rectangle first (as `joints --fit`).
    #[arg(long, requires = "programs")]
    fit: bool,
    /// Write the Pareto front (rectangle area against GCI) to FILE, as CSV rows.
    #[arg(long, value_name = "FILE")]
    pareto: Option<PathBuf>,
    /// Draw the atlas of the objective's index to FILE (SVG, or PNG by its extension).
    #[arg(long, value_name = "FILE")]
    atlas: Option<PathBuf>,
    /// Worker threads (0: one per core).
    #[arg(long, value_name = "N", default_value = "0")]
    threads: usize,
    /// Evaluate part K of N of the sweep: the designs whose index is K − 1 modulo N.
    #[arg(long, value_name = "K/N", default_value = "1/1")]
    shard: Shard,
}

/// Joins the CSVs of a sharded sweep (`biscara design --shard K/N`) into the CSV of the whole
/// sweep, rows in design order; a design missing or in two files is an error.
#[derive(Debug, Args)]
#[command(
    about = "Join the CSVs of a sharded sweep into the whole sweep's CSV",
    after_long_help = "Example:\n  $ biscara design merge part1.csv part2.csv part3.csv -o designs.csv"
)]
struct MergeArgs {
    /// The shards' CSVs.
    #[arg(value_name = "CSV", required = true)]
    inputs: Vec<PathBuf>,
    /// Write the joined CSV to FILE instead of standard output.
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,
}

/// Draws the atlas of a design CSV: one index over l1 × l2, a panel per base distance.
#[derive(Debug, Args)]
#[command(
    about = "Draw a design CSV's atlas: one index over l1 × l2 per base (SVG/PNG)",
    after_long_help = "Example:\n  $ biscara design atlas designs.csv --index gci -o atlas.png"
)]
struct AtlasArgs {
    /// The design CSV (`biscara design -o`, or merged).
    #[arg(value_name = "CSV")]
    input: PathBuf,
    /// The index drawn, and the design ringed (its best).
    #[arg(long, value_enum, default_value = "gci")]
    index: Objective,
    /// The picture: SVG, or PNG by its extension.
    #[arg(short, long, value_name = "FILE", required = true)]
    output: PathBuf,
}

pub(crate) fn design(model: &RobotModel, args: &DesignArgs) -> anyhow::Result<()> {
    match &args.command {
        Some(DesignCommand::Merge(merge)) => merge_shards(merge),
        Some(DesignCommand::Atlas(atlas)) => draw(atlas),
        None => sweep(model, &args.sweep),
    }
}

fn sweep(model: &RobotModel, args: &SweepArgs) -> anyhow::Result<()> {
    let (Some(l1), Some(l2), Some(base)) = (args.l1, args.l2, args.base) else {
        anyhow::bail!("--l1, --l2 and --base are required");
    };
    let programs = biscara_files::read_texts(&args.programs)?;
    let objective = args.objective;
    let (step, task, fit, shard) = (args.step, args.task, args.fit, args.shard);
    let request = SweepRequest { l1, l2, base, step, task, objective, programs, fit, shard };
    let sweep = request.sweep(model.robot().clone())?;
    let options = SweepOptions { threads: args.threads, objective, cells: args.atlas.is_some() };
    let progress = biscara_files::progress(sweep.count(), "designs");
    let mut outcome = None;
    write_output(args.output.as_deref(), |out| {
        outcome = Some(sweep.write_csv::<anyhow::Error>(&options, out, || progress.inc(1))?);
        Ok(())
    })?;
    let outcome = outcome.expect("the sweep ran");
    progress.finish_and_clear();
    report(Level::Note, &outcome);
    if let Some(path) = &args.pareto {
        write_output(
            Some(path),
            |out| Ok(outcome.write_pareto(out, sweep.evaluator().columns())?),
        )?;
    }
    if let Some(path) = &args.atlas {
        write_atlas(path, &outcome)?;
    }
    if let Some(path) = &args.best {
        let robot = outcome
            .best_robot(&sweep, args.task.is_some())
            .map_err(|err| anyhow::anyhow!("{err}: {} not written", display_path(path)))?;
        write_output(Some(path), |out| Ok(writeln!(out, "{}", robot.to_json_pretty())?))?;
    }
    Ok(())
}

/// Draws the atlas of `outcome`'s cells, the best design ringed, to `path` (SVG or PNG).
fn write_atlas(path: &Path, outcome: &SweepOutcome) -> anyhow::Result<()> {
    let bytes = outcome
        .draw_atlas(image_format(Some(path)))
        .with_context(|| format!("drawing {}", display_path(path)))?;
    write_output(Some(path), |out| Ok(out.write_all(&bytes)?))
}

fn merge_shards(args: &MergeArgs) -> anyhow::Result<()> {
    let inputs = biscara_files::open_inputs(&args.inputs)?;
    write_output(args.output.as_deref(), |out| {
        let rows = merge(inputs, out)?;
        report(Level::Note, format!("{rows} designs merged"));
        Ok(())
    })
}

fn draw(args: &AtlasArgs) -> anyhow::Result<()> {
    let outcome = SweepOutcome::read(open_input(&args.input)?, args.index)
        .map_err(|err| located(&args.input, err))?;
    if outcome.cells.is_empty() {
        anyhow::bail!("{}: no designs to draw", display_path(&args.input));
    }
    write_atlas(&args.output, &outcome)
}
