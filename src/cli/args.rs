//! Arguments and value parsers shared by the commands that run a program.

use std::path::PathBuf;

use biscara::gcode::{Dialect, IniFile, Tool, ToolTable};
use biscara::interpolate::Profile;
use biscara::pipeline::{
    ProgramKind, SamplingConfig, parse_blend, parse_grip_time, parse_time_limit, parse_time_step,
};
use biscara::text::parse_xyzc;
use biscara_files::{FileSource, FileSystem};
use clap::Args;

/// The program a command runs, and its kind.
#[derive(Debug, Args)]
pub(crate) struct ProgramArgs {
    /// The program (G-code, inter-file or path CSV); `-` reads standard input.
    #[arg(value_name = "PROGRAM")]
    program: PathBuf,
    /// The program's kind (default: from the extension, else from its first bytes).
    #[arg(long, value_enum, value_name = "KIND")]
    from: Option<ProgramKind>,
}

impl ProgramArgs {
    /// The program as the pipeline's source, and its kind.
    pub(crate) fn open(&self) -> anyhow::Result<(FileSource, ProgramKind)> {
        let source = FileSource::new(&self.program);
        let kind = source.kind(self.from)?;
        Ok((source, kind))
    }
}

/// Where a G-code program is placed: its G54 origin, or centred in the workspace.
#[derive(Debug, Args)]
pub(crate) struct PlacementArgs {
    /// Shift a G-code program by X,Y,Z,C (mm, mm, mm, degrees): the G54 offset in force before
    /// its first line, as `biscara interpret --origin`.
    #[arg(
        long,
        value_name = "X,Y,Z,C",
        allow_hyphen_values = true,
        value_parser = parse_xyzc,
        help = "G54 offset before the first line of a G-code program"
    )]
    pub(crate) origin: Option<[f64; 4]>,
    /// Place the program in the workspace: shift it in X and Y so that its bounding box (arcs
    /// included) is centred in the largest rectangle of `biscara workspace`, turned by 90° about
    /// Z when it fits only that way, and its Z range centred in the Z stroke when it lies outside.
    /// Programs that zero themselves with G92 at their start are placed too. The placement is
    /// reported on stderr; a program that fits neither way is an error that says by how much.
    #[arg(
        long,
        help = "Centre the program in the workspace rectangle, turned by 90° if only that fits, \
                Z into the stroke (placement on stderr)"
    )]
    pub(crate) fit: bool,
}

/// Whose G-code a program is.
#[derive(Debug, Args)]
pub(crate) struct DialectArgs {
    /// Whose G-code the program is: `linuxcnc` (RS274/NGC exactly), `grbl` (Grbl 1.1), `marlin`
    /// (Marlin and RepRap printer firmware), `makerbot` (MakerBot's flavour of Marlin: the A
    /// word is the extruder), `mach3`, `fanuc` (Fanuc and Haas controls), or `auto` to decide
    /// from the program (the choice and its reason are noted on stderr).
    #[arg(
        long,
        value_name = "DIALECT",
        default_value = "auto",
        help = "auto, linuxcnc, grbl, marlin, makerbot, mach3 or fanuc (auto: decided from the program)"
    )]
    pub(crate) dialect: Dialect,
    /// What the robot carries, over the robot file's `tool.kind`: what M3, M4, M5,
    /// S and E mean. Without either, the tool is inferred from the program (noted on stderr),
    /// the gripper when nothing tells.
    #[arg(
        long,
        value_name = "KIND",
        help = "gripper, laser, spindle, extruder or pen (default: the robot file's, else inferred)"
    )]
    pub(crate) tool: Option<Tool>,
}

/// The files a G-code program may read besides itself.
#[derive(Debug, Args)]
pub(crate) struct GcodeFilesArgs {
    /// A folder where file subroutines are looked for: `o<name> call` of a subroutine the
    /// program does not define runs `name.ngc`, from the program's own folder or else from these
    /// folders, in order (LinuxCNC's SUBROUTINE_PATH). May be given more than once.
    #[arg(long, value_name = "DIR", help = "Folder of file subroutines (o<name> call → name.ngc)")]
    pub(crate) subroutine_path: Vec<PathBuf>,
    /// LinuxCNC's tool table (`.tbl`, millimetres): the tools' lengths for G43 and diameters.
    /// Without it, every tool has zero length and diameter, and a note says so when the program
    /// uses them.
    #[arg(
        long,
        value_name = "FILE",
        help = "LinuxCNC tool table (.tbl, mm) for G43 tool lengths and tool diameters"
    )]
    pub(crate) tool_table: Option<PathBuf>,
    /// LinuxCNC's INI file of the machine: G-code reads its values as `#<_ini[SECTION]NAME>`
    /// (LinuxCNC's INI_VARS; read-only), and its `[PYTHON]` section loads LinuxCNC's Python
    /// plug-ins (Python O-word subroutines, `;py,` lines), run with `python3`. Without it, such
    /// names are global names like any other, as in LinuxCNC without an INI file, and a
    /// program's Python is refused. Nothing else of the INI file is used.
    #[arg(
        long,
        value_name = "FILE",
        help = "LinuxCNC INI file: #<_ini[SECTION]NAME> values, [PYTHON] plug-ins"
    )]
    pub(crate) ini: Option<PathBuf>,
    /// How many times a program may jump back (an O-word loop's turn, a subroutine call, a
    /// Fanuc GOTO) without a motion in between before it is stopped as an endless loop, with
    /// an error naming the loop's line.
    #[arg(
        long,
        value_name = "N",
        default_value = "100000",
        help = "Jumps back without a motion before a loop is an endless one (error)"
    )]
    pub(crate) max_idle_jumps: u64,
    /// How many motions one run of a G-code program may make: the motion after them is an
    /// error naming its line, so that a program that never ends (a loop that moves and
    /// changes something at every pass) stops within seconds instead of writing without end.
    /// (A loop that comes back to the same state is stopped at its second pass, whatever
    /// this says.)
    #[arg(
        long,
        value_name = "N",
        default_value = "10000000",
        help = "Most motions one run of a G-code program may make (error past them)"
    )]
    pub(crate) max_motions: u64,
}

/// The bound on robot time of the commands that sample a program (interpolate, joints, check,
/// plot).
#[derive(Debug, Args)]
pub(crate) struct TimeLimitArgs {
    /// Stop with an error once the program has run this long in robot time (seconds; 4 h by
    /// default, 14.4 million samples at 1 ms): a program that loops forever while moving never
    /// ends, and this bounds what one run writes.
    #[arg(
        long,
        value_name = "SECONDS",
        default_value = "14400",
        value_parser = parse_time_limit,
        help = "Most robot time to sample, s (default 4 h): an endless program stops here"
    )]
    pub(crate) time_limit: f64,
}

/// Options shared by the commands that sample a program in time.
#[derive(Debug, Args)]
pub(crate) struct SamplingArgs {
    /// Time step, seconds.
    #[arg(long, value_name = "SECONDS", default_value = "0.001", value_parser = parse_time_step)]
    dt: f64,
    /// Velocity profile of every motion.
    #[arg(long, value_enum, default_value = "optimal")]
    profile: Profile,
    /// Seconds each pick (M3) and place (M4) holds the pose; by default they take no time.
    #[arg(long, value_name = "SECONDS", default_value = "0", value_parser = parse_grip_time)]
    grip_time: f64,
    #[command(flatten)]
    pub(crate) blend: BlendArgs,
    #[command(flatten)]
    pub(crate) placement: PlacementArgs,
    #[command(flatten)]
    pub(crate) dialect: DialectArgs,
    #[command(flatten)]
    pub(crate) files: GcodeFilesArgs,
    /// Decimals of every number in the CSV.
    #[arg(long, value_name = "N", default_value = "6", value_parser = clap::value_parser!(u8).range(0..=12))]
    pub(crate) precision: u8,
}

impl SamplingArgs {
    /// The pipeline's sampling configuration, bounded by `limit`.
    pub(crate) fn config(&self, limit: &TimeLimitArgs) -> anyhow::Result<SamplingConfig> {
        Ok(SamplingConfig {
            time_limit: limit.time_limit,
            dt: self.dt,
            profile: self.profile,
            grip_time: self.grip_time,
            blend: self.blend.blend,
            ..placed_reading(&self.placement, &self.dialect, &self.files)?
        })
    }
}

/// The default configuration but where and how a program is read: its placement, dialect and
/// tool, its file subroutines and tool table.
pub(crate) fn placed_reading(
    placement: &PlacementArgs,
    dialect: &DialectArgs,
    files: &GcodeFilesArgs,
) -> anyhow::Result<SamplingConfig> {
    Ok(SamplingConfig {
        origin: placement.origin,
        fit: placement.fit,
        dialect: dialect.dialect,
        tool: dialect.tool,
        subroutine_path: files.subroutine_path.clone(),
        tool_table: FileSystem::read_shared(files.tool_table.as_deref(), ToolTable::read)?,
        ini: FileSystem::read_shared(files.ini.as_deref(), IniFile::read)?,
        max_idle_jumps: files.max_idle_jumps,
        max_motions: files.max_motions,
        ..SamplingConfig::default()
    })
}

/// The default corner tolerance of a G-code program.
#[derive(Debug, Args)]
pub(crate) struct BlendArgs {
    /// Blend the corners of a program that never says G61 or G64 as if it began with `G64 P`
    /// TOL (mm): consecutive straight moves are joined by arcs within TOL of the corner and
    /// timed through without stopping. Off by default (an exact stop at every
    /// corner); a program's own G61 or G64 always wins.
    #[arg(
        long,
        value_name = "TOL",
        value_parser = parse_blend,
        help = "Default G64 P (mm) for programs that never say G61/G64 (default: exact stop)"
    )]
    pub(crate) blend: Option<f64>,
}
