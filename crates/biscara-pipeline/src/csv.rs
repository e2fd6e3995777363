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

impl Pipeline<'_> {
    /// An error once a sample's time `t` (s) is past the configured
    /// [`time_limit`](crate::SamplingConfig::time_limit): a program that never ends stops
    /// there, its partial output left to the caller to throw away.
    #[inline(always)]
    pub(crate) fn within_time_limit(
        &self,
        file: &str,
        t: f64,
        line: usize,
    ) -> Result<(), PipelineError> {
        if t > self.config().time_limit {
            return Err(PipelineError::TimeLimit {
                file: file.to_owned(),
                line,
                limit: self.config().time_limit,
            });
        }
        Ok(())
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
        let payload = dynamics.bodies().payload;
        let file = source.name();
        if events {
            let mut samples = self.tool_joints(source, kind, notes)?;
            let tool = samples.tool();
            let mut columns = TORQUE_COLUMNS.to_vec();
            columns.extend(ToolState::columns(tool));
            let mut writer = JointCsvWriter::with_columns(out, format, &columns)?;
            while let Some(row) = samples.next_sample() {
                let (row, state) = row?;
                let held = if tool == Tool::Gripper && state.gripper { payload } else { 0.0 };
                let [t1, t2, t3, f4] = sample_torques(dynamics, row, held, file)?;
                writer.write_with_array(row, [t1, t2, t3, f4, held, state.value(tool)])?;
            }
            writer.finish()?;
            return Ok(());
        }
        let mut samples = self.joints(source, kind, notes)?;
        let mut writer = JointCsvWriter::with_columns(out, format, &TORQUE_COLUMNS)?;
        while let Some(row) = samples.next_sample() {
            let row = row?;
            let held = if row.gripper { payload } else { 0.0 };
            let [t1, t2, t3, f4] = sample_torques(dynamics, row, held, file)?;
            writer.write_with_array(row, [t1, t2, t3, f4, held])?;
        }
        writer.finish()?;
        Ok(())
    }
}

/// The torques at one joint sample, an error located at its line and time.
#[inline]
pub(crate) fn sample_torques(
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
