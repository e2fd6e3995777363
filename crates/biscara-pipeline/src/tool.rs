//! What the tool does at every sample (docs/motion.md `--events`): a wrapper over the sample
//! stream that follows the tool's events as the interpolator reads the motions, streaming.

use std::cell::{Cell, RefCell};
use std::collections::VecDeque;
use std::rc::Rc;

use biscara_gcode::Tool;
use biscara_interpolate::CartesianSample;
use biscara_joints::{JointSample, JointTrajectory};
use biscara_kinematics::Kinematics;
use biscara_motion::{Motion, MotionKind};

use crate::pipeline::locate;
use crate::{PipelineError, Samples};

/// The tool's state at one sample.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ToolState {
    /// The gripper is closed (from a pick to the next place).
    pub gripper: bool,
    /// The laser's programmed power (S) while it is on, 0 while off.
    pub laser_power: f64,
    /// The spindle's speed while it runs, rpm (negative: counter-clockwise), 0 while off.
    pub spindle_rpm: f64,
    /// Filament fed since the start, mm (retractions subtract), proportional along each move.
    pub extruded_mm: f64,
    /// The pen is down.
    pub pen_down: bool,
    /// The sample belongs to a rapid (G0) move.
    pub rapid: bool,
    /// Filament the sample's move feeds, mm (0 when none).
    pub move_extrude_mm: f64,
}

impl ToolState {
    /// The `--events` column names of `tool`.
    pub fn columns(tool: Tool) -> &'static [&'static str] {
        match tool {
            Tool::Gripper => &["gripper"],
            Tool::Laser => &["laser_power"],
            Tool::Spindle => &["spindle_rpm"],
            Tool::Extruder => &["extruded_mm"],
            Tool::Pen => &["pen_down"],
        }
    }

    /// The value of `tool`'s column.
    pub fn value(&self, tool: Tool) -> f64 {
        let flag = |on: bool| if on { 1.0 } else { 0.0 };
        match tool {
            Tool::Gripper => flag(self.gripper),
            Tool::Laser => self.laser_power,
            Tool::Spindle => self.spindle_rpm,
            Tool::Extruder => self.extruded_mm,
            Tool::Pen => flag(self.pen_down),
        }
    }

    /// How strongly `tool` works at this sample, 0 … 1 (a laser's power over `max_power`, 1 for
    /// the other tools); `None` while it does not work (docs/motion.md): a laser off, an extruder
    /// not feeding, a pen up, a spindle off or on a rapid, a gripper always.
    pub fn strength(&self, tool: Tool, max_power: f64) -> Option<f64> {
        match tool {
            Tool::Laser if self.laser_power > 0.0 => Some(self.laser_power / max_power),
            Tool::Extruder if self.move_extrude_mm > 0.0 => Some(1.0),
            Tool::Pen if self.pen_down => Some(1.0),
            Tool::Spindle if self.spindle_rpm != 0.0 && !self.rapid => Some(1.0),
            _ => None,
        }
    }

    /// What only `tool` can get wrong at this sample (docs/motion.md), for `check`: a laser burning
    /// during a rapid move, as the subject, the detail and how much (the power). (An extruder
    /// cannot feed during one: E words are Marlin's, whose G0 is a G1.)
    pub fn problem(&self, tool: Tool) -> Option<(&'static str, String, f64)> {
        if !self.rapid {
            return None;
        }
        match tool {
            Tool::Laser if self.laser_power > 0.0 => Some((
                "laser on during a rapid move",
                format!("the laser burns at power S{} during a G0 move", self.laser_power),
                self.laser_power,
            )),
            _ => None,
        }
    }

    /// The state after `kind` (an event; moves change nothing).
    pub fn after(mut self, kind: &MotionKind) -> ToolState {
        match *kind {
            MotionKind::Pick => self.gripper = true,
            MotionKind::Place | MotionKind::GripperOff => self.gripper = false,
            MotionKind::LaserOn { power, .. } => self.laser_power = power,
            MotionKind::LaserOff => self.laser_power = 0.0,
            MotionKind::SpindleOn { rpm, clockwise } => {
                self.spindle_rpm = if clockwise { rpm } else { -rpm }
            }
            MotionKind::SpindleOff => self.spindle_rpm = 0.0,
            MotionKind::PenDown => self.pen_down = true,
            MotionKind::PenUp => self.pen_down = false,
            _ => {}
        }
        self
    }
}

/// One motion as the tool sees it: the state during it, and the extrusion it carries.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Entry {
    line: usize,
    start: [f64; 4],
    end: [f64; 4],
    state: ToolState,
    extrude: f64,
    rapid: bool,
}

/// The tool the program drives, once known, shared by the reader that learns it and the
/// samples that need it.
pub(crate) type SharedTool = Rc<Cell<Option<Tool>>>;

/// The motions read so far and not yet sampled, shared by the two ends.
pub(crate) type Track = Rc<RefCell<VecDeque<Entry>>>;

/// Wraps the motions the interpolator reads: records each one with the tool's state.
pub(crate) struct Recorder<M> {
    motions: M,
    track: Track,
    state: ToolState,
    position: [f64; 4],
    tool: Rc<Cell<Option<Tool>>>,
}

impl<M> Recorder<M> {
    /// Records `motions`, starting at `start`; the tool is guessed from the events when the
    /// caller did not know it.
    pub(crate) fn new(motions: M, start: [f64; 4], tool: Rc<Cell<Option<Tool>>>) -> Self {
        let track = Rc::new(RefCell::new(VecDeque::new()));
        Recorder { motions, track, state: ToolState::default(), position: start, tool }
    }

    /// The shared record, for the [`ToolSamples`] at the other end.
    pub(crate) fn track(&self) -> Track {
        Rc::clone(&self.track)
    }
}

impl<M: Iterator<Item = Result<Motion, PipelineError>>> Iterator for Recorder<M> {
    type Item = Result<Motion, PipelineError>;

    fn next(&mut self) -> Option<Self::Item> {
        let motion = self.motions.next()?;
        if let Ok(motion) = &motion {
            let shown = match motion.kind {
                MotionKind::LaserOn { .. } | MotionKind::LaserOff => Some(Tool::Laser),
                MotionKind::SpindleOn { .. } | MotionKind::SpindleOff => Some(Tool::Spindle),
                MotionKind::PenDown | MotionKind::PenUp => Some(Tool::Pen),
                _ if motion.extrude.is_some() => Some(Tool::Extruder),
                _ => None,
            };
            if self.tool.get().is_none() {
                self.tool.set(shown);
            }
            self.state = self.state.after(&motion.kind);
            let end = motion.kind.end().unwrap_or(self.position);
            let extrude = motion.extrude.unwrap_or(0.0);
            let rapid = matches!(motion.kind, MotionKind::Rapid { .. });
            let (line, start, state) = (motion.line, self.position, self.state);
            let entry = Entry { line, start, end, state, extrude, rapid };
            self.track.borrow_mut().push_back(entry);
            self.state.extruded_mm += extrude;
            self.position = end;
        }
        Some(motion)
    }
}

/// A program's Cartesian samples with the tool's state at each (see [`crate::Pipeline::tool_samples`]).
pub struct ToolSamples {
    samples: Samples,
    track: Track,
    tool: Rc<Cell<Option<Tool>>>,
    current: Option<Entry>,
    peeked: VecDeque<Result<CartesianSample, PipelineError>>,
    /// The program's name and the configured time limit, s: the first sample past it is an
    /// error.
    limit: (String, f64),
}

impl ToolSamples {
    pub(crate) fn new(
        samples: Samples,
        track: Track,
        tool: Rc<Cell<Option<Tool>>>,
        limit: (String, f64),
    ) -> Self {
        ToolSamples { samples, track, tool, current: None, peeked: VecDeque::new(), limit }
    }

    /// The tool: the flag's or the robot file's, else the one the program's events show (read
    /// ahead to the first sample), else the gripper.
    pub fn tool(&mut self) -> Tool {
        // The second sample reads the first move, and the events before it.
        while self.tool.get().is_none() && self.peeked.len() < 2 {
            match self.samples.next() {
                Some(sample) => self.peeked.push_back(sample),
                None => break,
            }
        }
        self.tool.get().unwrap_or_default()
    }

    fn state(&mut self, sample: &CartesianSample) -> ToolState {
        let mut track = self.track.borrow_mut();
        if self.current.is_none_or(|entry| entry.line != sample.line)
            && let Some(at) = track.iter().position(|entry| entry.line == sample.line)
        {
            track.drain(..at);
            self.current = track.pop_front();
        }
        let Some(entry) = self.current else {
            return ToolState { gripper: sample.gripper, ..ToolState::default() };
        };
        let mut state = ToolState {
            gripper: sample.gripper,
            rapid: entry.rapid,
            move_extrude_mm: entry.extrude,
            ..entry.state
        };
        let length = distance(entry.start, entry.end);
        if entry.extrude != 0.0 {
            // A move with no XYZ length (a retraction) feeds all of it at once.
            let along = if length > 0.0 {
                (distance(entry.start, sample.pose) / length).clamp(0.0, 1.0)
            } else {
                1.0
            };
            state.extruded_mm += entry.extrude * along;
        }
        state
    }
}

fn distance(a: [f64; 4], b: [f64; 4]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

impl Iterator for ToolSamples {
    type Item = Result<(CartesianSample, ToolState), PipelineError>;

    fn next(&mut self) -> Option<Self::Item> {
        let sample = match self.peeked.pop_front() {
            Some(sample) => sample,
            None => self.samples.next()?,
        };
        Some(sample.and_then(|sample| {
            let (file, limit) = &self.limit;
            crate::csv::within_limit(file, sample.t, sample.line, *limit)?;
            let state = self.state(&sample);
            Ok((sample, state))
        }))
    }
}

/// The states of the samples handed to the joint solver and not yet out of it, oldest first.
type Stash = Rc<RefCell<VecDeque<ToolState>>>;

/// The Cartesian samples of a [`ToolSamples`], their states set aside in order for the joint
/// samples solved from them.
pub(crate) struct Stashed {
    samples: ToolSamples,
    states: Stash,
}

impl Iterator for Stashed {
    type Item = Result<CartesianSample, PipelineError>;

    fn next(&mut self) -> Option<Self::Item> {
        Some(self.samples.next()?.map(|(sample, state)| {
            self.states.borrow_mut().push_back(state);
            sample
        }))
    }
}

/// A program's joint samples with the tool's state at each (see
/// [`crate::Pipeline::tool_joints`]); the solver holds a batch of samples and three more, so do
/// the states.
pub struct ToolJointSamples {
    trajectory: JointTrajectory<Stashed, PipelineError>,
    states: Stash,
    tool: Tool,
    file: String,
}

impl ToolJointSamples {
    pub(crate) fn new(mut samples: ToolSamples, model: Kinematics, file: String) -> Self {
        let tool = samples.tool();
        let states = Stash::default();
        let stashed = Stashed { samples, states: Rc::clone(&states) };
        ToolJointSamples { trajectory: JointTrajectory::new(stashed, model), states, tool, file }
    }

    /// The tool (see [`ToolSamples::tool`]).
    pub fn tool(&self) -> Tool {
        self.tool
    }

    /// The next joint sample, borrowed, with the tool's state at it.
    pub fn next_sample(&mut self) -> Option<Result<(&JointSample, ToolState), PipelineError>> {
        let file = &self.file;
        match self.trajectory.next_sample()? {
            Ok(sample) => {
                let state = self.states.borrow_mut().pop_front().unwrap_or_default();
                Some(Ok((sample, state)))
            }
            Err(err) => Some(Err(locate(file, err))),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_sample_past_the_time_limit_is_the_pipeline_s_time_limit_error() {
        use biscara_kinematics::RobotModel;

        use crate::{Pipeline, ProgramKind, SamplingConfig, TextSource};
        let model = RobotModel::default();
        let config = SamplingConfig { time_limit: 0.05, ..SamplingConfig::default() };
        let pipeline = Pipeline::new(&model, config);
        let program = TextSource::new("long.ngc", "G21 G90\nG0 X0 Y400\nG1 X100 F600\nM2\n");
        let samples = pipeline.tool_samples(&program, ProgramKind::Gcode, |_| {}).expect("open");
        let mut last = None;
        let err = samples
            .map(|sample| sample.map(|(sample, _)| last = Some(sample)))
            .find_map(Result::err)
            .expect("past the limit");
        let last = last.expect("samples before the limit");
        assert!(last.t <= 0.05, "{last:?}");
        // The one error `within_time_limit` makes, at the sample after the last one given.
        let expected = pipeline.within_time_limit("long.ngc", 0.051, 2).expect_err("past it");
        assert_eq!(err.to_string(), expected.to_string());
    }

    #[test]
    fn each_tool_works_only_while_it_acts_on_the_part() {
        let off = ToolState::default();
        for tool in [Tool::Gripper, Tool::Laser, Tool::Spindle, Tool::Extruder, Tool::Pen] {
            assert_eq!(off.strength(tool, 1000.0), None, "{tool:?}");
        }
        let laser = ToolState { laser_power: 250.0, ..off };
        assert_eq!(laser.strength(Tool::Laser, 1000.0), Some(0.25));
        let cutting = ToolState { spindle_rpm: -12000.0, ..off };
        assert_eq!(cutting.strength(Tool::Spindle, 1000.0), Some(1.0));
        assert_eq!(ToolState { rapid: true, ..cutting }.strength(Tool::Spindle, 1000.0), None);
        let feeding = ToolState { move_extrude_mm: 0.1, extruded_mm: 5.0, ..off };
        assert_eq!(feeding.strength(Tool::Extruder, 1000.0), Some(1.0));
        // Filament fed before does not make a travel move a track.
        assert_eq!(ToolState { extruded_mm: 5.0, ..off }.strength(Tool::Extruder, 1000.0), None);
        assert_eq!(ToolState { pen_down: true, ..off }.strength(Tool::Pen, 1000.0), Some(1.0));
    }

    #[test]
    fn only_a_laser_on_during_a_rapid_is_a_tool_problem() {
        let rapid = ToolState { rapid: true, ..ToolState::default() };
        let burning = ToolState { laser_power: 300.0, ..rapid };
        let (subject, detail, severity) = burning.problem(Tool::Laser).unwrap();
        assert_eq!(subject, "laser on during a rapid move");
        assert!(detail.contains("S300"), "{detail}");
        assert_eq!(severity, 300.0);
        assert_eq!(ToolState { rapid: false, ..burning }.problem(Tool::Laser), None);
        assert_eq!(rapid.problem(Tool::Laser), None);
        // A spindle or pen on during a rapid is how those tools travel.
        let on = ToolState { spindle_rpm: 9000.0, pen_down: true, move_extrude_mm: 0.2, ..rapid };
        assert_eq!(on.problem(Tool::Extruder), None);
        assert_eq!(on.problem(Tool::Spindle), None);
        assert_eq!(on.problem(Tool::Pen), None);
    }
}
