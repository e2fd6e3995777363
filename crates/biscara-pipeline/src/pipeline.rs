//! The stages wired once: program → motions → Cartesian samples → joint samples.

use std::path::PathBuf;
use std::sync::Arc;

use biscara_gcode::{Dialect, IniFile, Tool, ToolTable};
use biscara_interpolate::{
    CartesianSample, InterpolateError, InterpolationConfig, Interpolator, PathCsvReader, Profile,
    SlowDown, read_path_csv,
};
use biscara_joints::{
    JointSample, JointSpeedLimit, JointTrajectory, JointsError, cartesian_limits,
};
use biscara_kinematics::RobotModel;
use biscara_motion::Position;

use std::cell::{Cell, RefCell};
use std::rc::Rc;

use crate::motions::{MotionReader, NoteSink, Reading, Told, read_motions};
use crate::tool::{Recorder, SharedTool, ToolJointSamples, ToolSamples, Track};
use crate::{Note, PipelineError, ProgramKind, ProgramSource, place};

/// How a program is placed and sampled in time (docs/motion.md, docs/gcode.md).
#[derive(Debug, Clone, PartialEq)]
pub struct SamplingConfig {
    /// Time step, s (> 0).
    pub dt: f64,
    /// The velocity profile of every motion.
    pub profile: Profile,
    /// Seconds each pick and place holds the pose (0: they take no time).
    pub grip_time: f64,
    /// The G54 offset before a G-code program's first line, `[x, y, z, c]` (mm, degrees);
    /// `None` is zero.
    pub origin: Option<Position>,
    /// Centre the program's XY extent in the workspace rectangle (`--fit`).
    pub fit: bool,
    /// Whose G-code a G-code program is (docs/gcode.md); `Auto` decides from the program.
    pub dialect: Dialect,
    /// The tool the robot carries (`--tool`, docs/motion.md); `None`: the robot file's `tool.kind`,
    /// else inferred from the program (with a [`Note::Tool`]), else the gripper.
    pub tool: Option<Tool>,
    /// Folders where file subroutines (`o<name> call` → `name.ngc`) are looked for after the
    /// program's own folder (`--subroutine-path`).
    pub subroutine_path: Vec<PathBuf>,
    /// The corner tolerance of a G-code program that never says G61 or G64 (`--blend`, mm):
    /// `None` (the default) runs it with an exact stop at every corner, `Some(p)` as if it began
    /// with `G64 P{p}` (docs/motion.md).
    pub blend: Option<f64>,
    /// LinuxCNC's tool table for G-code programs (`--tool-table`); `None`: every tool has zero
    /// length and diameter.
    pub tool_table: Option<Arc<ToolTable>>,
    /// LinuxCNC's INI file for G-code programs (`--ini`): the values of their
    /// `#<_ini[SECTION]NAME>` names; `None`: those are global names like any other.
    pub ini: Option<Arc<IniFile>>,
    /// The most motions `--fit` reads to find the program's extent ([`MAX_FIT_MOTIONS`] by
    /// default): a program that loops forever while moving is an error there, not a hang.
    pub max_fit_motions: u64,
    /// Jumps back a G-code program may make without a motion before it is stopped as an
    /// endless loop (`--max-idle-jumps`; [`biscara_gcode::MAX_IDLE_JUMPS`] by default).
    pub max_idle_jumps: u64,
    /// The most motions one run of a G-code program may make before it is stopped as a
    /// program that never ends (`--max-motions`; [`biscara_gcode::MAX_MOTIONS`] by default).
    pub max_motions: u64,
    /// The most robot time, seconds, that `interpolate` and `joints` sample before they stop as
    /// with a program that never ends (`--time-limit`; [`DEFAULT_TIME_LIMIT`] by default).
    pub time_limit: f64,
}

/// The most robot time sampled, by default: four hours, 14.4 million samples at 1 ms (about
/// 0.7 GB of joint CSV).
pub const DEFAULT_TIME_LIMIT: f64 = 4.0 * 3600.0;

/// The most motions `--fit` reads to find a program's extent, by default: 100 million (a
/// program of ten million lines with loops; reading them takes about ten seconds).
pub const MAX_FIT_MOTIONS: u64 = 100_000_000;

impl Default for SamplingConfig {
    /// The defaults of the command line: 1 ms, the optimal profile, no grip time, no origin, no fit, the
    /// dialect decided from the program.
    fn default() -> SamplingConfig {
        SamplingConfig {
            dt: 0.001,
            profile: Profile::Optimal,
            grip_time: 0.0,
            origin: None,
            fit: false,
            dialect: Dialect::Auto,
            tool: None,
            subroutine_path: Vec::new(),
            blend: None,
            tool_table: None,
            ini: None,
            max_fit_motions: MAX_FIT_MOTIONS,
            max_idle_jumps: biscara_gcode::MAX_IDLE_JUMPS,
            max_motions: biscara_gcode::MAX_MOTIONS,
            time_limit: DEFAULT_TIME_LIMIT,
        }
    }
}

/// Where the interpolator reports slowed motions: into the notes (called once per slowed motion,
/// so a boxed function costs nothing measurable).
pub type SlowDownNotes = Box<dyn FnMut(&SlowDown)>;

/// A program's motions, placed, errors located.
pub type Motions = MotionReader;

/// One robot and one sampling configuration: the pipeline every command runs programs through.
#[derive(Debug, Clone)]
pub struct Pipeline<'m> {
    model: &'m RobotModel,
    config: SamplingConfig,
}

/// The tool `config`'s flag or else `model`'s robot file names (`None`: inferred from the
/// program).
pub(crate) fn configured_tool(model: &RobotModel, config: &SamplingConfig) -> Option<Tool> {
    config.tool.or(model.robot().tool.kind)
}

impl<'m> Pipeline<'m> {
    /// The pipeline of `model` sampling with `config`.
    pub fn new(model: &'m RobotModel, config: SamplingConfig) -> Pipeline<'m> {
        Pipeline { model, config }
    }

    /// The robot.
    pub fn model(&self) -> &'m RobotModel {
        self.model
    }

    /// The sampling configuration.
    pub fn config(&self) -> &SamplingConfig {
        &self.config
    }

    /// The tool when the flag or the robot file says which (`None`: inferred from the program).
    pub fn tool(&self) -> Option<Tool> {
        configured_tool(self.model, &self.config)
    }

    /// The program's motions, placed by the configuration's origin and `fit` (which reports a
    /// [`Note::Placed`]). A path CSV has no motions.
    pub fn motions(
        &self,
        source: &dyn ProgramSource,
        kind: ProgramKind,
        notes: impl FnMut(Note) + 'static,
    ) -> Result<Motions, PipelineError> {
        self.placed_motions(source, kind, &NoteSink::new(notes), Told::default())
    }

    fn placed_motions(
        &self,
        source: &dyn ProgramSource,
        kind: ProgramKind,
        notes: &NoteSink,
        told: Told,
    ) -> Result<Motions, PipelineError> {
        let placement = place(self.model, source, kind, &self.config, &mut |note| notes.say(note))?;
        let reading = Reading::of(&self.config, placement.origin, placement.start, self.tool());
        let motions = read_motions(self.model, source, kind, &reading, notes.clone(), told)?;
        Ok(match placement.transform {
            Some(transform) if !transform.is_identity() => {
                Box::new(motions.map(move |m| m.map(|m| transform.motion(m))))
            }
            _ => motions,
        })
    }

    /// The program's Cartesian samples: a path CSV read as it is, or the motions interpolated
    /// with the configuration's profile, the robot's Cartesian limits and its joint speed limit.
    /// Every slowed motion is reported to `notes` as a [`Note::SlowedDown`].
    pub fn samples(
        &self,
        source: &dyn ProgramSource,
        kind: ProgramKind,
        notes: impl FnMut(Note) + 'static,
    ) -> Result<Samples, PipelineError> {
        self.recorded_samples(source, kind, NoteSink::new(notes), None)
    }

    /// The program's Cartesian samples ([`Pipeline::samples`]) with the tool's state at each
    /// (`--events`, docs/motion.md): a wrapper over the motions records the tool's events as the
    /// interpolator reads them, and one over the samples gives each its state. Streaming. A path
    /// CSV has no tool events: its samples carry the gripper column it has. A sample past the
    /// configured [`time_limit`](SamplingConfig::time_limit) is a [`PipelineError::TimeLimit`].
    pub fn tool_samples(
        &self,
        source: &dyn ProgramSource,
        kind: ProgramKind,
        notes: impl FnMut(Note) + 'static,
    ) -> Result<ToolSamples, PipelineError> {
        let tool = Rc::new(Cell::new(self.tool()));
        let track: Rc<RefCell<Option<Track>>> = Rc::default();
        let recorder = (Rc::clone(&tool), Rc::clone(&track));
        let samples = self.recorded_samples(source, kind, NoteSink::new(notes), Some(recorder))?;
        let track = track.borrow_mut().take().unwrap_or_default();
        let limit = (source.name().to_owned(), self.config.time_limit);
        Ok(ToolSamples::new(samples, track, tool, limit))
    }

    fn recorded_samples(
        &self,
        source: &dyn ProgramSource,
        kind: ProgramKind,
        notes: NoteSink,
        recorder: Option<(SharedTool, Rc<RefCell<Option<Track>>>)>,
    ) -> Result<Samples, PipelineError> {
        let file = source.name().to_owned();
        if kind == ProgramKind::Path {
            if self.config.fit {
                return Err(PipelineError::unsupported(&file, crate::placement::FIT_NOT_PATH));
            }
            let input =
                source.open().map_err(|source| PipelineError::Io { file: file.clone(), source })?;
            return Ok(Samples::Path { reader: read_path_csv(input), file });
        }
        let told = Told { zeroed: None, tool: recorder.as_ref().map(|(tool, _)| Rc::clone(tool)) };
        let mut motions = self.placed_motions(source, kind, &notes, told)?;
        if let Some((tool, track)) = recorder {
            let recorder = Recorder::new(motions, self.model.home_position(), tool);
            *track.borrow_mut() = Some(recorder.track());
            motions = Box::new(recorder);
        }
        let robot = self.model.robot();
        let config = InterpolationConfig {
            dt: self.config.dt,
            profile: self.config.profile,
            start: self.model.home_position(),
            limits: cartesian_limits(robot),
            grip_time: self.config.grip_time,
        };
        let limit = JointSpeedLimit::new(self.model.kinematics(), robot).with_motors(self.model)?;
        let name = file.clone();
        let on_slow: SlowDownNotes =
            Box::new(move |slow| notes.say(Note::SlowedDown { file: name.clone(), slow: *slow }));
        let interpolator = Box::new(Interpolator::new(motions, config, limit, on_slow));
        Ok(Samples::Program { interpolator, file })
    }

    /// The program's joint samples: [`Pipeline::samples`] solved by IK in the robot's working
    /// and assembly mode, θ3 continuous, with velocities and accelerations; stops at the first
    /// sample the robot cannot take.
    pub fn joints(
        &self,
        source: &dyn ProgramSource,
        kind: ProgramKind,
        notes: impl FnMut(Note) + 'static,
    ) -> Result<JointSamples, PipelineError> {
        let file = source.name().to_owned();
        let samples = self.samples(source, kind, notes)?;
        Ok(JointSamples {
            trajectory: JointTrajectory::new(samples, self.model.kinematics()),
            file,
        })
    }

    /// The program's joint samples ([`Pipeline::joints`]) with the tool's state at each
    /// (`joints --events`, docs/motion.md): the states of [`Pipeline::tool_samples`] carried to
    /// the joint samples solved from them. Streaming.
    pub fn tool_joints(
        &self,
        source: &dyn ProgramSource,
        kind: ProgramKind,
        notes: impl FnMut(Note) + 'static,
    ) -> Result<ToolJointSamples, PipelineError> {
        let file = source.name().to_owned();
        let samples = self.tool_samples(source, kind, notes)?;
        Ok(ToolJointSamples::new(samples, self.model.kinematics(), file))
    }
}

/// A joint-trajectory error located in `file`.
pub(crate) fn locate(file: &str, err: JointsError<PipelineError>) -> PipelineError {
    match err {
        JointsError::Input(err) => err,
        JointsError::Pose(err) => PipelineError::program(file, err),
        other => PipelineError::program(file, other),
    }
}

/// The Cartesian samples of a program, read from a path CSV or interpolated from its motions.
///
/// A concrete type rather than a boxed iterator, so that `joints` can inline the step from one
/// sample to the next: a sample passed through a `dyn Iterator` and a `map` was stored and
/// loaded back twice, with a store-forwarding stall each time (with `Interpolator::next`
/// inlined as well: 0.429 → 0.423 s for `joints` on the engraving program).
pub enum Samples {
    /// A path CSV.
    Path {
        /// The reader.
        reader: PathCsvReader<Box<dyn std::io::BufRead>>,
        /// The program's name.
        file: String,
    },
    /// A program's motions, interpolated.
    Program {
        /// The interpolator.
        interpolator: Box<Interpolator<Motions, JointSpeedLimit, SlowDownNotes>>,
        /// The program's name.
        file: String,
    },
}

impl Iterator for Samples {
    type Item = Result<CartesianSample, PipelineError>;

    #[inline(always)]
    fn next(&mut self) -> Option<Self::Item> {
        match self {
            Samples::Path { reader, file } => {
                Some(reader.next()?.map_err(|err| PipelineError::program(file, err)))
            }
            Samples::Program { interpolator, file } => {
                Some(interpolator.next()?.map_err(|err| match err {
                    InterpolateError::Input(err) => err,
                    other => PipelineError::program(file, other),
                }))
            }
        }
    }
}

impl Samples {
    /// Calls `each` with every sample in turn, by reference, and stops at the first error of
    /// either. Equivalent to iterating, but a sample is never moved through an
    /// `Option<Result<…>>` (for `interpolate`, that copy through the stack was a store-forwarding
    /// stall per sample).
    pub fn try_for_each_sample<E: From<PipelineError>>(
        &mut self,
        mut each: impl FnMut(&CartesianSample) -> Result<(), E>,
    ) -> Result<(), E> {
        match self {
            Samples::Path { reader, file } => {
                for sample in reader {
                    each(&sample.map_err(|err| PipelineError::program(file, err))?)?;
                }
            }
            Samples::Program { interpolator, file } => {
                interpolator.try_for_each_sample(each, |err| match err {
                    InterpolateError::Input(err) => err.into(),
                    other => PipelineError::program(file, other).into(),
                })?;
            }
        }
        Ok(())
    }
}

/// A program's joint samples, errors located (see [`Pipeline::joints`]).
pub struct JointSamples {
    trajectory: JointTrajectory<Samples, PipelineError>,
    file: String,
}

impl JointSamples {
    /// The same samples with `velocity` and `acceleration` left at zero, not computed
    /// ([`JointTrajectory::without_derivatives`]): for a joint CSV without derivative columns.
    pub fn without_derivatives(mut self) -> Self {
        self.trajectory = self.trajectory.without_derivatives();
        self
    }

    /// The next sample, borrowed: [`Iterator::next`] without copying the sample out (returning
    /// the 152-byte sample inside an `Option<Result<…>>`, then moving it out, cost 5 % of
    /// `joints` on the engraving program).
    #[inline]
    pub fn next_sample(&mut self) -> Option<Result<&JointSample, PipelineError>> {
        let file = &self.file;
        Some(self.trajectory.next_sample()?.map_err(|err| locate(file, err)))
    }
}

impl Iterator for JointSamples {
    type Item = Result<JointSample, PipelineError>;

    fn next(&mut self) -> Option<Self::Item> {
        Some(self.next_sample()?.copied())
    }
}
