//! The motors' torques along a program, sample by sample (`plot --torques`).

use biscara_dynamics::Dynamics;
use biscara_joints::JointSample;

use crate::csv::{PayloadWatch, torque_columns};
use crate::{Note, Pipeline, PipelineError, ProgramKind, ProgramSource};

impl Pipeline<'_> {
    /// Calls `each` with every joint sample of the program ([`Pipeline::joints`]) and its
    /// motors' torques `[τ1, τ2, τ3 (N·m), f_d4 (N)]`: `dynamics`' inverse dynamics of the
    /// sample's own position, velocity and acceleration, with the payload while the gripper
    /// holds it, as `joints --torques` writes them. Streaming; stops at the first error,
    /// `each`'s included, and at the first sample past the configured time limit.
    pub fn for_each_torque(
        &self,
        source: &dyn ProgramSource,
        kind: ProgramKind,
        dynamics: &Dynamics,
        notes: impl FnMut(Note) + 'static,
        mut each: impl FnMut(&JointSample, [f64; 4]) -> Result<(), PipelineError>,
    ) -> Result<(), PipelineError> {
        let file = source.name().to_owned();
        let mut payload = PayloadWatch::new(kind, dynamics.bodies().payload, &file, notes);
        let mut samples = self.joints(source, kind, payload.forward())?;
        while let Some(row) = samples.next_sample() {
            let row = row?;
            self.within_time_limit(&file, row.t, row.line)?;
            let [t1, t2, t3, f4, _] = torque_columns(dynamics, row, None, &file)?;
            payload.saw(row);
            each(row, [t1, t2, t3, f4])?;
        }
        payload.finish();
        Ok(())
    }
}
