//! One job on LinuxCNC, from the command line's choices to its outputs: the configuration and
//! its robot, the stream, the run, LinuxCNC's refusals as errors with the program's line, and
//! the recording written as a joint CSV or a path CSV.

use std::fmt;
use std::fs;
use std::io::{BufReader, BufWriter, Write};
use std::path::{Path, PathBuf};

use biscara_files::{FileError, FileSource, Level, display_path, write_output};
use biscara_interpolate::Profile;
use biscara_joints::{JointCsvFormat, JointCsvWriter};
use biscara_kinematics::{Joints, RobotModel, ToolKind};
use biscara_pipeline::{Note, Pipeline, PipelineError, ProgramKind, ProgramSource, SamplingConfig};
use biscara_robot::{Bounds, Rectangle};

use crate::config::check_region;
use crate::runner::{self, ComponentStatus, RunRequest, TempFolder};
use crate::{
    AxisLimitSource, ConfigOptions, Configuration, INI_FILE, LinuxcncError, ROBOT_FILE,
    RecordingStart, RecordingSummary, Region, SERVO_PERIOD, configuration, configuration_robot,
    grow, ini_value, read_recording, write_stream_sample,
};

/// What a run plays through the stream path before any G-code.
pub enum Stream<'a> {
    /// A program's joint trajectory (`biscara joints`), computed for the configuration's robot.
    Program {
        /// The program.
        source: &'a dyn ProgramSource,
        /// Its kind.
        kind: ProgramKind,
        /// How it is sampled (the profile, the origin); the time step is the servo period.
        sampling: SamplingConfig,
    },
    /// A joint CSV with the columns and units `biscara joints` writes, checked against the
    /// robot's joint limits before it plays.
    Csv {
        /// The file.
        path: &'a Path,
    },
}

impl<'a> Stream<'a> {
    /// The stream a command line asks for: the joint CSV `csv`, else with `stream` the
    /// trajectory of `program` sampled with `profile` from `origin`; `None` runs the program on
    /// LinuxCNC's planner.
    pub fn of(
        csv: Option<&'a Path>,
        stream: bool,
        program: &'a FileSource,
        profile: Profile,
        origin: Option<[f64; 4]>,
    ) -> Result<Option<Stream<'a>>, FileError> {
        Ok(match csv {
            Some(path) => Some(Stream::Csv { path }),
            None if stream => Some(Stream::Program {
                source: program,
                kind: program.kind(None)?,
                sampling: SamplingConfig { profile, origin, ..SamplingConfig::default() },
            }),
            None => None,
        })
    }
}

/// One run of `biscara linuxcnc run`.
pub struct Job<'a> {
    /// The configuration folder (`None`: one written for the robot in force with `options`).
    pub config: Option<&'a Path>,
    /// The robot file given on the command line (`--robot`), when one was: it must be the
    /// configuration's robot.
    pub robot_file: Option<&'a Path>,
    /// How the configuration is written when none is given.
    pub options: ConfigOptions,
    /// The program, as named on the command line (run on LinuxCNC's planner unless streamed).
    pub program: &'a Path,
    /// The stream to play instead of running `program`.
    pub stream: Option<Stream<'a>>,
    /// A program to run on LinuxCNC's planner after the stream.
    pub then: Option<&'a Path>,
    /// A G54 offset before the program.
    pub origin: Option<[f64; 4]>,
    /// How long the program or the stream may take, s.
    pub timeout: f64,
    /// A commissioning event: E-stop or machine off this long after the start, s.
    pub event: Option<(runner::Event, f64)>,
}

/// Where `linuxcnc run` writes what the joints did.
#[derive(Debug, Clone, Copy)]
pub struct Outputs<'a> {
    /// The joint CSV's file; `None` or `-`: standard output.
    pub joints: Option<&'a Path>,
    /// The path CSV's file (LinuxCNC's commanded poses), when asked for.
    pub path: Option<&'a Path>,
    /// How the joint CSV is written; the path CSV takes its decimals.
    pub format: JointCsvFormat,
}

/// A finished job: LinuxCNC's recording, and the robot it ran.
#[derive(Debug)]
pub struct Finished {
    run: runner::Run,
    model: RobotModel,
    start: RecordingStart,
    /// What the run played: `PROGRAM` or the stream path's (`--stream`, `--stream-csv`).
    program: PathBuf,
}

impl Finished {
    /// What stopped the stream or the program early (an E-stop, the machine switched off, a
    /// following error), when something did: the recording still holds what the joints did.
    pub fn stop(&self) -> Option<&runner::Stop> {
        self.run.stop.as_ref()
    }

    /// The robot the job ran (the configuration's).
    pub fn model(&self) -> &RobotModel {
        &self.model
    }

    /// The note on what was recorded: `LinuxCNC ran|streamed PROGRAM: D s, N samples of 1 ms`.
    pub fn note(&self, summary: &RecordingSummary) -> String {
        let what = if self.streamed() { "streamed" } else { "ran" };
        format!(
            "LinuxCNC {what} {}: {:.3} s, {} samples of 1 ms",
            display_path(&self.program),
            summary.duration,
            summary.samples
        )
    }

    /// Whether the job played a stream (its recording starts at the stream's first sample).
    fn streamed(&self) -> bool {
        self.start == RecordingStart::Stream
    }

    /// The error of a run [stopped](Self::stop) early, when it was: what stopped it, when, and
    /// where the joints held (`summary`: what [`write_joints`](Self::write_joints) returned).
    pub fn stopped(&self, summary: Option<&RecordingSummary>) -> Option<LinuxcncError> {
        let stop = self.stop()?;
        let held = match summary {
            Some(summary) if self.streamed() => format!(
                "the stream's last sample played at {:.3} s, the joints held from there",
                summary.streamed.saturating_sub(1) as f64 * SERVO_PERIOD
            ),
            _ => "the joints held where LinuxCNC stopped them".to_owned(),
        };
        Some(LinuxcncError::Stopped {
            program: display_path(&self.program),
            what: stop.what.clone(),
            time: stop.time,
            held,
        })
    }

    /// Writes the recording as `outputs` asks, each file atomically, and tells `report` what
    /// the run amounts to: LinuxCNC's own notes first, then (after the files) the duration and
    /// each joint's peaks against its limits (a [`Level::Warning`] for a peak over its limit).
    /// What stopped the run early is the error, once the files are written.
    pub fn write_outputs<E>(
        &self,
        outputs: &Outputs<'_>,
        report: &mut dyn FnMut(Level, &dyn fmt::Display),
    ) -> Result<(), E>
    where
        E: From<LinuxcncError> + From<std::io::Error> + From<FileError>,
    {
        for note in self.notes() {
            report(Level::Note, &format_args!("LinuxCNC: {note}"));
        }
        let mut summary = None;
        write_output(outputs.joints, |out| {
            summary = Some(self.write_joints::<E>(out, outputs.format)?);
            Ok::<(), E>(())
        })?;
        if let Some(path) = outputs.path {
            write_output(Some(path), |out| self.write_path::<E>(out, outputs.format.precision))?;
        }
        if let Some(summary) = &summary {
            report(Level::Note, &self.note(summary));
            for peak in summary.peaks {
                report(if peak.exceeds() { Level::Warning } else { Level::Note }, &peak);
            }
        }
        match self.stopped(summary.as_ref()) {
            Some(stop) => Err(stop.into()),
            None => Ok(()),
        }
    }

    /// LinuxCNC's messages that were not errors.
    pub fn notes(&self) -> impl Iterator<Item = &str> {
        self.run.messages.iter().filter(|message| !message.error).map(|m| m.text.as_str())
    }

    fn recording(&self) -> Result<BufReader<fs::File>, LinuxcncError> {
        let path = self.run.samples();
        fs::File::open(&path).map(BufReader::new).map_err(|err| LinuxcncError::io(&path, err))
    }

    /// Writes what the joints did as a joint CSV (the columns of `biscara joints`), and returns
    /// the recording's summary.
    pub fn write_joints<E: From<LinuxcncError> + From<std::io::Error>>(
        &self,
        out: &mut dyn Write,
        format: JointCsvFormat,
    ) -> Result<RecordingSummary, E> {
        let mut joints = JointCsvWriter::new(out, format)?;
        let summary = read_recording(self.recording()?, self.start, self.model.robot(), |s, _| {
            joints.write(s).map_err(E::from)
        })?;
        joints.finish()?;
        Ok(summary)
    }

    /// Writes LinuxCNC's commanded Cartesian position every cycle as a path CSV
    /// (`t_s,x_mm,y_mm,z_mm,c_deg`) with `decimals` decimals.
    pub fn write_path<E: From<LinuxcncError> + From<std::io::Error>>(
        &self,
        out: &mut dyn Write,
        decimals: usize,
    ) -> Result<(), E> {
        writeln!(out, "t_s,x_mm,y_mm,z_mm,c_deg")?;
        read_recording(self.recording()?, self.start, self.model.robot(), |sample, recorded| {
            let [x, y, z, c] = recorded.axes;
            let t = sample.t;
            writeln!(
                out,
                "{t:.decimals$},{x:.decimals$},{y:.decimals$},{z:.decimals$},{c:.decimals$}"
            )
            .map_err(E::from)
        })?;
        Ok(())
    }
}

/// Where a configuration's region comes from, as the command line chooses it.
pub enum RegionChoice<'a> {
    /// None: the workspace rectangle, soft limits at the robot's reach.
    Workspace,
    /// A program's extent plus a margin ([`program_region`]).
    Program {
        /// The program file (its kind from its name and first bytes).
        program: &'a Path,
        /// How it is placed (its origin, or fitted).
        sampling: SamplingConfig,
        /// The margin around its extent, mm (0 or more).
        margin: f64,
    },
    /// A rectangle `[x0, x1, y0, y1]` (mm), the robot parked at its centre.
    Rectangle([f64; 4]),
}

impl<'a> RegionChoice<'a> {
    /// The region a command line's flags choose: the extent of `program` (placed by `origin`
    /// or fitted with `fit`) plus `margin`, else `rectangle`, else the workspace.
    pub fn of(
        program: Option<&'a Path>,
        margin: f64,
        rectangle: Option<[f64; 4]>,
        origin: Option<[f64; 4]>,
        fit: bool,
    ) -> RegionChoice<'a> {
        match (program, rectangle) {
            (Some(program), _) => RegionChoice::Program {
                program,
                sampling: SamplingConfig { origin, fit, ..SamplingConfig::default() },
                margin,
            },
            (None, Some(rectangle)) => RegionChoice::Rectangle(rectangle),
            (None, None) => RegionChoice::Workspace,
        }
    }
}

/// How a configuration is made, as `linuxcnc config` and `linuxcnc run` choose it.
pub struct ConfigRequest<'a> {
    /// The tool whose codes the HAL wires (`None`: the robot file's, else the gripper).
    pub tool: Option<ToolKind>,
    /// Where the axis limits come from.
    pub limits: AxisLimitSource,
    /// The region the job stays in.
    pub region: RegionChoice<'a>,
}

impl ConfigRequest<'_> {
    /// The configuration's options for `model`; a program's region is measured with the
    /// pipeline (its notes to `notes`).
    pub fn options<E: From<LinuxcncError> + From<PipelineError>>(
        self,
        model: &RobotModel,
        notes: impl FnMut(Note) + 'static,
    ) -> Result<ConfigOptions, E> {
        let tool = self.tool.or(model.robot().tool.kind).unwrap_or(ToolKind::Gripper);
        let region = match self.region {
            RegionChoice::Workspace => None,
            RegionChoice::Program { margin, .. } if !(margin >= 0.0 && margin.is_finite()) => {
                return Err(LinuxcncError::Usage {
                    message: format!("--margin must be a number of mm, 0 or more (got {margin})"),
                }
                .into());
            }
            RegionChoice::Program { program, sampling, margin } => {
                let source = FileSource::new(program);
                let kind = source.kind(None).map_err(LinuxcncError::from)?;
                Some(program_region::<E>(model, &source, kind, sampling, margin, notes)?)
            }
            RegionChoice::Rectangle([x0, x1, y0, y1]) => {
                let [_, _, z, _] = model.home_position();
                Some(Region {
                    rectangle: Rectangle { min: [x0, y0], max: [x1, y1] },
                    origin: format!("--region {x0}:{x1},{y0}:{y1}"),
                    park: Some([0.5 * (x0 + x1), 0.5 * (y0 + y1), z, 0.0]),
                })
            }
        };
        Ok(ConfigOptions { tool, limits: self.limits, region, ..ConfigOptions::default() })
    }
}

/// Reads a region `X0:X1,Y0:Y1` (mm) as `[x0, x1, y0, y1]`, each range from its smaller end.
pub fn parse_region(text: &str) -> Result<[f64; 4], String> {
    let bad = || format!("expected X0:X1,Y0:Y1 (mm), found `{text}`");
    let (x, y) = text.split_once(',').ok_or_else(bad)?;
    let range = |range: &str| -> Result<[f64; 2], String> {
        let (a, b) = range.split_once(':').ok_or_else(bad)?;
        let number = |value: &str| {
            value
                .trim()
                .parse::<f64>()
                .ok()
                .filter(|value| value.is_finite())
                .ok_or_else(|| format!("`{}` is not a finite number", value.trim()))
        };
        let (a, b) = (number(a)?, number(b)?);
        if a >= b {
            return Err(format!("the range {a}:{b} is empty: give its smaller end first"));
        }
        Ok([a, b])
    };
    let ([x0, x1], [y0, y1]) = (range(x)?, range(y)?);
    Ok([x0, x1, y0, y1])
}

/// The note on a configuration written into `folder`: its files, its axis limits and how to
/// install its kinematics component.
pub fn written_note(configuration: &Configuration, folder: &Path) -> String {
    let limits = &configuration.limits;
    format!(
        "wrote {} files into {}; axis limits: X and Y {:.1} mm/s, {:.1} mm/s², Z {:.1} mm/s, \
         C {:.1} °/s; install the kinematics once with `halcompile --install {}`",
        configuration.files.len(),
        display_path(folder),
        limits.xy_velocity,
        limits.xy_acceleration,
        limits.z_velocity,
        limits.c_velocity,
        display_path(&folder.join("biscarakins.comp")),
    )
}

/// Writes `configuration` into `folder` (created if missing; its files replaced, each whole or
/// not at all).
pub fn write_configuration(
    configuration: &Configuration,
    folder: &Path,
) -> Result<(), LinuxcncError> {
    fs::create_dir_all(folder).map_err(|err| LinuxcncError::io(folder, err))?;
    for file in &configuration.files {
        let path = folder.join(file.name);
        write_output(Some(&path), |out| {
            out.write_all(file.contents.as_bytes()).map_err(FileError::Io)
        })?;
        if file.executable {
            use std::os::unix::fs::PermissionsExt as _;
            fs::set_permissions(&path, fs::Permissions::from_mode(0o755))
                .map_err(|err| LinuxcncError::io(&path, err))?;
        }
    }
    Ok(())
}

/// The robot of the configuration in `folder` (its `robot.json`, checked against its INI and
/// HAL); when the command line named a robot file too, it must be the same robot.
pub fn folder_robot(
    folder: &Path,
    model: &RobotModel,
    robot_file: Option<&Path>,
) -> Result<RobotModel, LinuxcncError> {
    let name = display_path(folder);
    let read = |file: &str| {
        let path = folder.join(file);
        fs::read_to_string(&path).map_err(|err| match err.kind() {
            std::io::ErrorKind::NotFound if file == ROBOT_FILE => LinuxcncError::Robot {
                message: format!(
                    "{name} has no {ROBOT_FILE}: not a configuration of this version of biscara \
                     (write it again with `biscara linuxcnc config`)"
                ),
            },
            _ => LinuxcncError::io(&path, err),
        })
    };
    let robot_json = read(ROBOT_FILE)?;
    let configured =
        configuration_robot(&name, &robot_json, &read(INI_FILE)?, &read("biscara.hal")?)?;
    if let Some(file) = robot_file
        && configured.robot() != model.robot()
    {
        return Err(LinuxcncError::Robot {
            message: format!(
                "the configuration {name} was written for the robot \"{}\" ({name}/{ROBOT_FILE}), \
                 not for --robot {} (\"{}\"): run without --robot to use the configuration's, or \
                 write a configuration for {} with `biscara --robot {} linuxcnc config`",
                configured.robot().name,
                display_path(file),
                model.robot().name,
                display_path(file),
                display_path(file),
            ),
        });
    }
    Ok(configured)
}

/// The region a program works in, and where the robot parks for it.
///
/// The robot's home pose (all joints 0) is at the edge of its reach, where no useful axis
/// limit holds; a program's moves to and from it are left out, as `--fit` leaves them out. The
/// region is the XY extent of the program's moves (placed as `sampling` says, arcs included)
/// grown by `margin` mm on every side, or by less where the margin would leave the workspace;
/// the park pose is the end of the program's first move away from home.
pub fn program_region<E: From<PipelineError>>(
    model: &RobotModel,
    source: &dyn ProgramSource,
    kind: ProgramKind,
    sampling: SamplingConfig,
    margin: f64,
    notes: impl FnMut(Note) + 'static,
) -> Result<Region, E> {
    let pipeline = Pipeline::new(model, sampling);
    let home = model.home_position();
    let mut bounds = Bounds::new(home);
    let mut park = None;
    for motion in pipeline.motions(source, kind, notes)? {
        let motion = motion?;
        bounds.push(&motion);
        if park.is_none()
            && let Some(end) = motion.kind.end()
            && (end[0] - home[0]).hypot(end[1] - home[1]) > 1e-6
        {
            park = Some(end);
        }
    }
    let extent = if bounds.is_empty() {
        Rectangle { min: [home[0], home[1]], max: [home[0], home[1]] }
    } else {
        Rectangle { min: bounds.min, max: bounds.max }
    };
    let name = source.name().to_owned();
    let region = |margin: f64| Region {
        rectangle: grow(&extent, margin),
        origin: format!("{name} (its extent plus {margin} mm)"),
        park,
    };
    // Where the margin would reach beyond the workspace, a smaller one (to 0.1 mm).
    let step = ConfigOptions::default().step;
    let fits = |margin: f64| check_region(model, &region(margin), step).is_ok();
    if margin > 0.0 && !fits(margin) && fits(0.0) {
        let (mut low, mut high) = (0.0, margin);
        while high - low > 0.1 {
            let middle = 0.5 * (low + high);
            if fits(middle) {
                low = middle;
            } else {
                high = middle;
            }
        }
        return Ok(region((low * 10.0).floor() / 10.0));
    }
    Ok(region(margin))
}

/// Writes the stream file of `stream` for `model` into `path`; returns the first sample's
/// joints and the number of samples.
fn write_stream<E: From<LinuxcncError> + From<PipelineError>>(
    model: &RobotModel,
    stream: &Stream<'_>,
    path: &Path,
    notes: impl FnMut(Note) + 'static,
) -> Result<(Joints, usize), E> {
    let file = fs::File::create(path).map_err(|err| LinuxcncError::io(path, err))?;
    let mut out = BufWriter::new(file);
    let (first, count) = match stream {
        Stream::Program { source, kind, sampling } => {
            let mut sampling = sampling.clone();
            sampling.dt = SERVO_PERIOD;
            let pipeline = Pipeline::new(model, sampling);
            let mut samples = pipeline.joints(*source, *kind, notes)?.without_derivatives();
            let mut first = None;
            let mut count = 0;
            while let Some(sample) = samples.next_sample() {
                let joints = sample?.joints;
                first.get_or_insert(joints);
                write_stream_sample(&mut out, &joints)
                    .map_err(|err| LinuxcncError::io(path, err))?;
                count += 1;
            }
            (first.unwrap_or_default(), count)
        }
        Stream::Csv { path: csv } => {
            let name = display_path(csv);
            let reader = fs::File::open(csv)
                .map(BufReader::new)
                .map_err(|err| LinuxcncError::io(csv, err))?;
            crate::stream::check_joint_csv(&name, reader, model.robot(), &mut out)?
        }
    };
    out.flush().map_err(|err| LinuxcncError::io(path, err))?;
    Ok((first, count))
}

/// Where the joints stand after homing: `[JOINT_n] HOME` of the configuration's INI (θ1 θ2 d4
/// θ3, degrees and mm; 0 where it says nothing).
fn homed_joints(config: &Path) -> Result<[f64; 4], LinuxcncError> {
    let path = config.join(INI_FILE);
    let ini = fs::read_to_string(&path).map_err(|err| LinuxcncError::io(&path, err))?;
    Ok(std::array::from_fn(|joint| {
        ini_value(&ini, &format!("JOINT_{joint}"), "HOME")
            .and_then(|value| value.parse().ok())
            .unwrap_or(0.0)
    }))
}

/// Runs `job` on LinuxCNC: resolves the configuration and its robot, builds and installs the
/// kinematics component when needed, writes the stream, runs LinuxCNC headless and turns its
/// refusals into [`LinuxcncError::Refused`]. `notes` receives the pipeline's notes, `say`
/// this function's (the component installed, the samples streamed).
pub fn run_job<E: From<LinuxcncError> + From<PipelineError>>(
    model: &RobotModel,
    job: &Job<'_>,
    notes: impl FnMut(Note) + 'static,
    say: &mut dyn FnMut(String),
) -> Result<Finished, E> {
    if let Some((_, at)) = job.event
        && !(at >= 0.0 && at.is_finite())
    {
        return Err(LinuxcncError::Usage {
            message: format!(
                "--estop-at and --machine-off-at take a time in seconds, 0 or more (got {at})"
            ),
        }
        .into());
    }
    if !(job.timeout > 0.0 && job.timeout.is_finite()) {
        return Err(LinuxcncError::Usage {
            message: format!(
                "--timeout must be a positive number of seconds (got {})",
                job.timeout
            ),
        }
        .into());
    }
    for program in std::iter::once(&job.program).chain(&job.then) {
        fs::File::open(program).map_err(|err| LinuxcncError::io(program, err))?;
    }
    runner::check_installed()?;
    let work = TempFolder::new("biscara-linuxcnc-run")?;
    let (config, model) = match job.config {
        Some(folder) => (folder.to_owned(), folder_robot(folder, model, job.robot_file)?),
        None => {
            let folder = work.path().join("config");
            write_configuration(&configuration(model, &job.options)?, &folder)?;
            (folder, model.clone())
        }
    };
    if runner::ensure_component(&config)? == ComponentStatus::Updated {
        say("built and installed the kinematics component biscarakins".to_owned());
    }
    let stream = match &job.stream {
        Some(stream) => {
            let path = work.path().join("stream.txt");
            let (first, samples) = write_stream::<E>(&model, stream, &path, notes)?;
            let homed = homed_joints(&config)?;
            if homed != [0.0; 4] {
                return Err(LinuxcncError::Usage {
                    message: format!(
                        "{} parks the robot away from its home pose (a configuration made for a \
                         region): stream with a configuration for the whole workspace",
                        display_path(&config)
                    ),
                }
                .into());
            }
            crate::stream::check_start(&first, homed)?;
            let what = match stream {
                Stream::Program { .. } => "`biscara joints`".to_owned(),
                Stream::Csv { path } => display_path(path),
            };
            say(format!("streaming {samples} samples of {what}"));
            Some(path)
        }
        None => None,
    };
    let program: Option<PathBuf> =
        if stream.is_some() { job.then.map(Path::to_owned) } else { Some(job.program.to_owned()) };
    let start = if stream.is_some() { RecordingStart::Stream } else { RecordingStart::FirstMotion };
    let request = RunRequest {
        config,
        program: program.clone(),
        origin: if stream.is_some() { None } else { job.origin },
        stream,
        timeout: job.timeout,
        event: job.event,
    };
    let run = runner::run(&request)?;
    if !run.ok && run.stop.is_none() {
        let errors: Vec<&str> =
            run.messages.iter().filter(|m| m.error).map(|m| m.text.as_str()).collect();
        let message = if errors.is_empty() {
            run.failure.clone().unwrap_or_else(|| "stopped".to_owned())
        } else {
            errors.join("; ")
        };
        let line = line_of(&errors).unwrap_or(run.line);
        let name = display_path(program.as_deref().unwrap_or(job.program));
        return Err(LinuxcncError::Refused { program: name, line, message }.into());
    }
    let program = job.program.to_owned();
    Ok(Finished { run, model, start, program })
}

/// The program line a LinuxCNC message names (`… on line 12 …`).
pub fn line_of(messages: &[&str]) -> Option<usize> {
    messages.iter().find_map(|text| {
        let rest = &text[text.find("line ")? + 5..];
        let digits: String = rest.chars().take_while(char::is_ascii_digit).collect();
        digits.parse().ok()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_program_wins_over_the_rectangle_and_carries_its_placement() {
        let program = Path::new("job.ngc");
        let rectangle = Some([0.0, 10.0, 300.0, 310.0]);
        let origin = Some([1.0, 2.0, 3.0, 4.0]);
        match RegionChoice::of(Some(program), 5.0, rectangle, origin, false) {
            RegionChoice::Program { program: p, sampling, margin } => {
                assert_eq!(
                    (p, sampling.origin, sampling.fit, margin),
                    (program, origin, false, 5.0)
                );
            }
            _ => panic!("the program's region"),
        }
        let chosen = RegionChoice::of(None, 10.0, rectangle, None, false);
        assert!(matches!(chosen, RegionChoice::Rectangle(r) if Some(r) == rectangle));
        assert!(matches!(RegionChoice::of(None, 10.0, None, None, true), RegionChoice::Workspace));
        let dir = std::env::temp_dir().join(format!("biscara-stream-of-{}", std::process::id()));
        fs::create_dir_all(&dir).unwrap();
        fs::write(dir.join("job.ngc"), "G0 X0 Y300\n").unwrap();
        let source = FileSource::new(&dir.join("job.ngc"));
        let csv = Stream::of(Some(Path::new("t.csv")), true, &source, Profile::Optimal, None);
        assert!(matches!(csv, Ok(Some(Stream::Csv { path })) if path == Path::new("t.csv")));
        let origin = Some([0.0, 300.0, 0.0, 0.0]);
        match Stream::of(None, true, &source, Profile::Trapezoid, origin) {
            Ok(Some(Stream::Program { kind, sampling, .. })) => {
                assert_eq!(kind, ProgramKind::Gcode);
                assert_eq!((sampling.profile, sampling.origin), (Profile::Trapezoid, origin));
            }
            _ => panic!("the program's trajectory"),
        }
        assert!(matches!(Stream::of(None, false, &source, Profile::Optimal, None), Ok(None)));
        fs::remove_dir_all(&dir).unwrap();
        let event = runner::Event::at(Some(1.5), Some(2.0));
        assert_eq!(event, Some((runner::Event::Estop, 1.5)));
        let event = runner::Event::at(None, Some(2.0));
        assert_eq!(event, Some((runner::Event::MachineOff, 2.0)));
        assert_eq!(runner::Event::at(None, None), None);
    }

    #[test]
    fn a_region_reads_two_ranges_each_from_its_smaller_end() {
        assert_eq!(parse_region("-100:100, 250:400"), Ok([-100.0, 100.0, 250.0, 400.0]));
        assert_eq!(parse_region("0:1"), Err("expected X0:X1,Y0:Y1 (mm), found `0:1`".to_owned()));
        assert_eq!(parse_region("0:x,1:2"), Err("`x` is not a finite number".to_owned()));
        let empty = parse_region("5:5,1:2").expect_err("empty");
        assert_eq!(empty, "the range 5:5 is empty: give its smaller end first");
    }

    /// Either error of [`ConfigRequest::options`].
    #[derive(Debug)]
    #[allow(dead_code, reason = "read by Debug when a test fails")]
    enum Failed {
        Linuxcnc(LinuxcncError),
        Pipeline(PipelineError),
    }

    impl From<LinuxcncError> for Failed {
        fn from(err: LinuxcncError) -> Failed {
            Failed::Linuxcnc(err)
        }
    }

    impl From<PipelineError> for Failed {
        fn from(err: PipelineError) -> Failed {
            Failed::Pipeline(err)
        }
    }

    #[test]
    fn a_config_request_sets_the_tool_and_the_region() {
        let model = RobotModel::default();
        let request = |region| ConfigRequest {
            tool: Some(ToolKind::Laser),
            limits: AxisLimitSource::Cartesian,
            region,
        };
        let options: ConfigOptions = request(RegionChoice::Rectangle([-10.0, 10.0, 300.0, 320.0]))
            .options::<Failed>(&model, |_| {})
            .expect("options");
        assert_eq!((options.tool, options.limits), (ToolKind::Laser, AxisLimitSource::Cartesian));
        let region = options.region.expect("a region");
        assert_eq!(region.rectangle, Rectangle { min: [-10.0, 300.0], max: [10.0, 320.0] });
        assert_eq!(region.origin, "--region -10:10,300:320");
        assert_eq!(region.park.map(|p| [p[0], p[1], p[3]]), Some([0.0, 310.0, 0.0]));
        let options: ConfigOptions =
            request(RegionChoice::Workspace).options::<Failed>(&model, |_| {}).expect("ok");
        assert_eq!(options.region, None);
    }

    #[test]
    fn the_line_is_the_first_line_number_a_message_names() {
        assert_eq!(line_of(&["joint 0 on limit switch error"]), None);
        assert_eq!(line_of(&["no line", "Can't move on line 12 of the program"]), Some(12));
        assert_eq!(line_of(&["on line x", "line 3"]), Some(3));
        assert_eq!(line_of(&[]), None);
    }

    #[test]
    fn a_region_is_the_program_extent_plus_the_margin_without_the_moves_home() {
        let model = RobotModel::default();
        let source = biscara_pipeline::TextSource::new(
            "job.ngc",
            "G21 G90\nG0 X-50 Y250 Z50\nG1 X50 Y300 F3000\nG2 X50 Y200 J-50\nG28\nM2\n",
        );
        let sampling = SamplingConfig::default();
        let region = program_region::<PipelineError>(
            &model,
            &source,
            ProgramKind::Gcode,
            sampling,
            10.0,
            |_| {},
        )
        .unwrap();
        let r = region.rectangle;
        // The arc from (50, 300) around (50, 250) clockwise reaches x = 100.
        for (got, want) in
            [(r.min[0], -60.0), (r.max[0], 110.0), (r.min[1], 190.0), (r.max[1], 310.0)]
        {
            assert!((got - want).abs() < 1e-3, "{r:?}");
        }
        assert_eq!(region.origin, "job.ngc (its extent plus 10 mm)");
        assert_eq!(region.park, Some([-50.0, 250.0, 50.0, 0.0]));
    }
}
