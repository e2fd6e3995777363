//! The pipeline's two CSV outputs written whole: the path CSV of `interpolate` and the joint CSV
//! of `joints`, with the tool's column after `--events` (docs/motion.md).
//! The commands and the benchmarks write them through here, so that what is measured is what
//! runs.

use std::io::Write;

use biscara_dynamics::{Dynamics, DynamicsError};
use biscara_gcode::Tool;
use biscara_interpolate::PathCsvWriter;
use biscara_joints::{JointCsvFormat, JointCsvWriter, JointSample, TORQUE_COLUMNS};

use crate::{Note, Pipeline, PipelineError, ProgramKind, ProgramSource, ToolState};

/// [`Pipeline::within_time_limit`] against `limit` (s), for the stages that hold the limit
/// without the pipeline ([`crate::ToolSamples`]).
#[inline(always)]
pub(crate) fn within_limit(
    file: &str,
    t: f64,
    line: usize,
    limit: f64,
) -> Result<(), PipelineError> {
    if t > limit {
        return Err(PipelineError::TimeLimit { file: file.to_owned(), line, limit });
    }
    Ok(())
}

impl Pipeline<'_> {
    /// An error once a sample's time `t` (s) is past the configured
    /// [`time_limit`](crate::SamplingConfig::time_limit): a program that never ends stops
    /// there, its partial output left to the caller to throw away.
    #[inline(always)]
    pub fn within_time_limit(&self, file: &str, t: f64, line: usize) -> Result<(), PipelineError> {
        within_limit(file, t, line, self.config().time_limit)
    }

    /// Writes the program's Cartesian samples ([`Pipeline::samples`]) to `out` as a path CSV
    /// with `decimals` decimals; with `events`, the tool's column after the pose
    /// ([`ToolState::columns`]: `gripper`, `laser_power`, …). Nothing is written when the
    /// program cannot be opened or placed; at the first error in the program the rows so far
    /// have been written.
    pub fn write_path_csv(
        &self,
        source: &dyn ProgramSource,
        kind: ProgramKind,
        out: &mut dyn Write,
        decimals: usize,
        events: bool,
        notes: impl FnMut(Note) + 'static,
    ) -> Result<(), PipelineError> {
        if kind == ProgramKind::Path {
            return Err(PipelineError::unsupported(
                source.name(),
                "a path CSV holds samples already: give G-code or an inter-file",
            ));
        }
        if !events {
            let mut samples = self.samples(source, kind, notes)?;
            let mut writer = PathCsvWriter::new(out, decimals, false)?;
            samples.try_for_each_sample(|sample| {
                self.within_time_limit(source.name(), sample.t, sample.line)?;
                writer.write(sample).map_err(PipelineError::from)
            })?;
            writer.finish()?;
            return Ok(());
        }
        let mut samples = self.tool_samples(source, kind, notes)?;
        let tool = samples.tool();
        let mut writer = if tool == Tool::Gripper {
            PathCsvWriter::new(out, decimals, true)?
        } else {
            PathCsvWriter::with_columns(out, decimals, ToolState::columns(tool))?
        };
        for sample in samples {
            let (sample, state) = sample?;
            self.within_time_limit(source.name(), sample.t, sample.line)?;
            if tool == Tool::Gripper {
                writer.write(&sample)?;
            } else {
                writer.write_with(&sample, &[state.value(tool)])?;
            }
        }
        writer.finish()?;
        Ok(())
    }

    /// Writes the program's joint samples ([`Pipeline::joints`]) to `out` as a joint CSV in
    /// `format` (its velocity and acceleration are computed only when it has their columns);
    /// with `events`, the tool's column after the joints. Nothing is written when the program
    /// cannot be opened or placed; at the first sample the robot cannot take, the rows so far
    /// have been written.
    pub fn write_joint_csv(
        &self,
        source: &dyn ProgramSource,
        kind: ProgramKind,
        out: &mut dyn Write,
        format: JointCsvFormat,
        events: bool,
        notes: impl FnMut(Note) + 'static,
    ) -> Result<(), PipelineError> {
        if events {
            let mut samples = self.tool_joints(source, kind, notes)?;
            let tool = samples.tool();
            let mut writer = JointCsvWriter::with_columns(out, format, ToolState::columns(tool))?;
            while let Some(row) = samples.next_sample() {
                let (row, state) = row?;
                self.within_time_limit(source.name(), row.t, row.line)?;
                writer.write_with(row, &[state.value(tool)])?;
            }
            writer.finish()?;
            return Ok(());
        }
        let mut samples = self.joints(source, kind, notes)?;
        if !format.derivatives {
            samples = samples.without_derivatives();
        }
        let mut writer = JointCsvWriter::new(out, format)?;
        while let Some(row) = samples.next_sample() {
            let row = row?;
            self.within_time_limit(source.name(), row.t, row.line)?;
            writer.write(row)?;
        }
        writer.finish()?;
        Ok(())
    }

    /// Writes the program's joint samples as [`Pipeline::write_joint_csv`] does, with the
    /// derivative columns whatever `format` says and, after them, the torques the motors must
    /// give ([`TORQUE_COLUMNS`]: `tau_theta1_Nm,tau_theta2_Nm,tau_theta3_Nm,f_d4_N,payload_kg`):
    /// each row's inverse dynamics ([`Dynamics::torques`]) of its own joints, velocities and
    /// accelerations, with the robot's payload while the gripper holds it (from each pick to its
    /// place), else none. With `events`, the tool's column comes last.
    #[allow(clippy::too_many_arguments)]
    pub fn write_joint_torque_csv(
        &self,
        source: &dyn ProgramSource,
        kind: ProgramKind,
        out: &mut dyn Write,
        format: JointCsvFormat,
        events: bool,
        dynamics: &Dynamics,
        notes: impl FnMut(Note) + 'static,
    ) -> Result<(), PipelineError> {
        let format = JointCsvFormat { derivatives: true, ..format };
        let file = source.name();
        let mut payload = PayloadWatch::new(kind, dynamics.bodies().payload, file, notes);
        let notes = payload.forward();
        if events {
            let mut samples = self.tool_joints(source, kind, notes)?;
            let tool = samples.tool();
            let mut columns = TORQUE_COLUMNS.to_vec();
            columns.extend(ToolState::columns(tool));
            let mut writer = JointCsvWriter::with_columns(out, format, &columns)?;
            while let Some(row) = samples.next_sample() {
                let (row, state) = row?;
                self.within_time_limit(file, row.t, row.line)?;
                let [t1, t2, t3, f4, held] = torque_columns(dynamics, row, Some(tool), file)?;
                payload.saw(row);
                writer.write_with_array(row, [t1, t2, t3, f4, held, state.value(tool)])?;
            }
            writer.finish()?;
            payload.finish();
            return Ok(());
        }
        let mut samples = self.joints(source, kind, notes)?;
        let mut writer = JointCsvWriter::with_columns(out, format, &TORQUE_COLUMNS)?;
        while let Some(row) = samples.next_sample() {
            let row = row?;
            self.within_time_limit(file, row.t, row.line)?;
            payload.saw(row);
            writer.write_with_array(row, torque_columns(dynamics, row, None, file)?)?;
        }
        writer.finish()?;
        payload.finish();
        Ok(())
    }
}

/// Whether a path CSV's samples ever hold the payload: a path CSV without its `gripper`
/// column never does, and its torques would silently leave the robot's payload out; at the
/// end, a [`Note::NoPayloadCarried`] says so. The caller's notes pass through it.
pub(crate) struct PayloadWatch<N> {
    notes: std::rc::Rc<std::cell::RefCell<N>>,
    /// The program's name and the robot's payload (kg), for a path CSV of a robot with one.
    watch: Option<(String, f64)>,
    held: bool,
}

impl<N: FnMut(Note) + 'static> PayloadWatch<N> {
    /// Watches the samples of a program of `kind` for the robot's `payload` (kg).
    pub(crate) fn new(kind: ProgramKind, payload: f64, file: &str, notes: N) -> Self {
        let watch =
            (kind == ProgramKind::Path && payload > 0.0).then(|| (file.to_owned(), payload));
        PayloadWatch { notes: std::rc::Rc::new(std::cell::RefCell::new(notes)), watch, held: false }
    }

    /// The caller's notes, for the stages that run the program.
    pub(crate) fn forward(&self) -> impl FnMut(Note) + 'static {
        let notes = std::rc::Rc::clone(&self.notes);
        move |note| (notes.borrow_mut())(note)
    }

    /// One sample written.
    #[inline]
    pub(crate) fn saw(&mut self, sample: &JointSample) {
        self.held(sample.gripper);
    }

    /// One sample, with the gripper closed or not.
    #[inline]
    pub(crate) fn held(&mut self, gripper: bool) {
        self.held |= gripper;
    }

    /// The end of the program: the note, when no sample held the payload.
    pub(crate) fn finish(self) {
        if let Some((file, payload_kg)) = self.watch.filter(|_| !self.held) {
            (self.notes.borrow_mut())(Note::NoPayloadCarried { file, payload_kg });
        }
    }
}

/// The payload (kg) held at one joint sample ([`Dynamics::held_payload`]): while the gripper is
/// closed (from a pick to its place) and the program's `tool`, when known, is a gripper.
#[inline]
pub fn held_payload(dynamics: &Dynamics, sample: &JointSample, tool: Option<Tool>) -> f64 {
    dynamics.held_payload(sample.gripper && tool.is_none_or(|tool| tool == Tool::Gripper))
}

/// The [`TORQUE_COLUMNS`] of one joint sample: its motors' torques ([`sample_torques`]) with the
/// payload it holds ([`held_payload`] of `tool`), then that payload, kg.
#[inline]
pub fn torque_columns(
    dynamics: &Dynamics,
    sample: &JointSample,
    tool: Option<Tool>,
    file: &str,
) -> Result<[f64; 5], PipelineError> {
    let held = held_payload(dynamics, sample, tool);
    let [t1, t2, t3, f4] = sample_torques(dynamics, sample, held, file)?;
    Ok([t1, t2, t3, f4, held])
}

/// The torques at one joint sample ([`Dynamics::torques`] of its joints, velocities and
/// accelerations with `payload` kg held), an error located at its line and time in `file`.
#[inline]
pub fn sample_torques(
    dynamics: &Dynamics,
    sample: &JointSample,
    payload: f64,
    file: &str,
) -> Result<[f64; 4], PipelineError> {
    dynamics
        .torques(sample.joints.to_array(), sample.velocity, sample.acceleration, payload)
        .map_err(|source| {
            PipelineError::program(file, TorqueError { line: sample.line, t: sample.t, source })
        })
}

/// A sample whose torques cannot be computed (in practice never: the trajectory refuses the
/// poses that would fail first).
#[derive(Debug, thiserror::Error)]
#[error("{line}: at t = {t} s: {source}")]
struct TorqueError {
    line: usize,
    t: f64,
    source: DynamicsError,
}

#[cfg(test)]
mod tests {
    use biscara_kinematics::{DynamicsSpec, Joints, PointSpec, Robot, RobotModel};

    use super::*;

    fn dynamics(payload: f64) -> Dynamics {
        let spec =
            DynamicsSpec { payload: PointSpec { mass: Some(payload) }, ..Default::default() };
        Dynamics::new(&RobotModel::new(Robot { dynamics: Some(spec), ..Robot::default() }).unwrap())
            .unwrap()
    }

    fn sample(gripper: bool) -> JointSample {
        JointSample {
            t: 0.25,
            line: 7,
            pose: [0.0, 460.798724079689, 100.0, 0.0],
            joints: Joints { theta1: 0.0, theta2: 0.0, theta3: 0.0, d4: 0.0 },
            velocity: [0.0; 4],
            acceleration: [0.0; 4],
            gripper,
        }
    }

    #[test]
    fn the_payload_is_held_while_a_gripper_is_closed() {
        let dynamics = dynamics(0.7);
        assert_eq!(held_payload(&dynamics, &sample(true), None), 0.7);
        assert_eq!(held_payload(&dynamics, &sample(true), Some(Tool::Gripper)), 0.7);
        assert_eq!(held_payload(&dynamics, &sample(false), None), 0.0);
        assert_eq!(held_payload(&dynamics, &sample(false), Some(Tool::Gripper)), 0.0);
        assert_eq!(held_payload(&dynamics, &sample(true), Some(Tool::Laser)), 0.0);
    }

    #[test]
    fn the_torque_columns_carry_the_payload_in_d4s_force_and_last() {
        let dynamics = dynamics(0.7);
        let [.., free_d4, free] =
            torque_columns(&dynamics, &sample(false), None, "job.ngc").unwrap();
        let [.., held_d4, held] =
            torque_columns(&dynamics, &sample(true), None, "job.ngc").unwrap();
        assert_eq!((free, held), (0.0, 0.7));
        // At rest, d4 holds the payload's weight more.
        let gravity = dynamics.bodies().gravity;
        assert!(((held_d4 - free_d4).abs() - 0.7 * gravity).abs() < 1e-9, "{free_d4} {held_d4}");
    }

    /// A path CSV without its `gripper` column never holds the payload: its torques say so in a
    /// note, not silently; with the column (a pick in it), or with no payload, there is none.
    #[test]
    fn a_path_csv_that_never_holds_the_payload_says_so() {
        use std::cell::RefCell;
        use std::rc::Rc;

        use crate::{SamplingConfig, TextSource};
        let rows = |gripper: &[u8]| -> String {
            let header = if gripper.is_empty() { "" } else { ",gripper" };
            let mut text = format!("t_s,x_mm,y_mm,z_mm,c_deg{header}\n");
            for (i, y) in [400.0, 400.001, 400.003].into_iter().enumerate() {
                let column = gripper.get(i).map_or(String::new(), |g| format!(",{g}"));
                text.push_str(&format!("{}.00{i},0,{y},50,0{column}\n", 0));
            }
            text
        };
        let notes_of = |payload: f64, text: String| -> Vec<String> {
            let model = RobotModel::new(Robot {
                dynamics: Some(DynamicsSpec {
                    payload: PointSpec { mass: Some(payload) },
                    ..Default::default()
                }),
                ..Robot::default()
            })
            .unwrap();
            let dynamics = Dynamics::new(&model).unwrap();
            let pipeline = Pipeline::new(&model, SamplingConfig::default());
            let notes = Rc::new(RefCell::new(Vec::new()));
            let sink = Rc::clone(&notes);
            let source = TextSource::new("path.csv", text);
            let format = JointCsvFormat {
                angle_unit: biscara_joints::AngleUnit::Radians,
                derivatives: true,
                precision: 6,
            };
            pipeline
                .write_joint_torque_csv(
                    &source,
                    ProgramKind::Path,
                    &mut Vec::new(),
                    format,
                    false,
                    &dynamics,
                    move |note| sink.borrow_mut().push(note.to_string()),
                )
                .unwrap();
            notes.take()
        };
        let without = notes_of(0.5, rows(&[]));
        assert_eq!(without.len(), 1, "{without:?}");
        assert!(
            without[0].starts_with("path.csv: no sample has the gripper closed"),
            "{without:?}"
        );
        assert!(without[0].contains("0.5 kg payload"), "{without:?}");
        assert_eq!(notes_of(0.5, rows(&[0, 1, 1])), Vec::<String>::new());
        assert_eq!(notes_of(0.0, rows(&[])), Vec::<String>::new());
    }
}
