//! The joint CSV of `biscara joints`, with the motors' torques when asked for.

use std::io::Write;

use biscara_dynamics::Dynamics;
use biscara_joints::JointCsvFormat;

use crate::{Note, Pipeline, PipelineError, ProgramKind, ProgramSource};

impl Pipeline<'_> {
    /// Writes the joint CSV of `source` to `out`: [`Pipeline::write_joint_torque_csv`] with
    /// `dynamics` (the torques after the derivatives), else [`Pipeline::write_joint_csv`].
    #[allow(clippy::too_many_arguments)]
    pub fn write_joints(
        &self,
        source: &dyn ProgramSource,
        kind: ProgramKind,
        out: &mut dyn Write,
        format: JointCsvFormat,
        events: bool,
        dynamics: Option<&Dynamics>,
        notes: impl FnMut(Note) + 'static,
    ) -> Result<(), PipelineError> {
        match dynamics {
            Some(dynamics) => {
                self.write_joint_torque_csv(source, kind, out, format, events, dynamics, notes)
            }
            None => self.write_joint_csv(source, kind, out, format, events, notes),
        }
    }
}

#[cfg(test)]
mod tests {
    use biscara_joints::AngleUnit;
    use biscara_kinematics::RobotModel;

    use super::*;
    use crate::{SamplingConfig, TextSource};

    #[test]
    fn torques_are_written_only_with_the_dynamics() {
        let model = RobotModel::default();
        let pipeline = Pipeline::new(&model, SamplingConfig::default());
        let program = TextSource::new("job.ngc", "G0 X0 Y400 Z50\nG1 X10 F600\nM2\n");
        let format =
            JointCsvFormat { angle_unit: AngleUnit::Radians, derivatives: false, precision: 3 };
        let header = |dynamics: Option<&Dynamics>| {
            let mut out = Vec::new();
            pipeline
                .write_joints(
                    &program,
                    ProgramKind::Gcode,
                    &mut out,
                    format,
                    false,
                    dynamics,
                    |_| {},
                )
                .unwrap();
            String::from_utf8(out).unwrap().lines().next().unwrap().to_owned()
        };
        assert_eq!(header(None), "t_s,theta1_rad,theta2_rad,theta3_rad,d4_mm");
        let dynamics = Dynamics::new(&model).unwrap();
        let with = header(Some(&dynamics));
        assert!(with.contains(",dtheta1_rad_s,") && with.ends_with(",f_d4_N,payload_kg"), "{with}");
    }
}
