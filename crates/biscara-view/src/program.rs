//! A program sampled by the pipeline, overlaid on a picture or on the viewer's page.

use biscara_kinematics::{RobotModel, ToolKind};
use biscara_pipeline::{Note, Pipeline, PipelineError, ProgramKind, ProgramSource, SamplingConfig};

use crate::{MAX_WORK_POINTS, ProgramOverlay, ProgramTrace, ToolWork, Viewer};

/// A program traced for a picture ([`trace_program`]).
#[derive(Debug)]
pub struct TracedProgram {
    /// The path, the bodies at the wanted times and the joint curves.
    pub trace: ProgramTrace,
    /// The tool's work (for the gripper, the path without travel).
    pub work: ToolWork,
    /// The tool the program ran.
    pub tool: ToolKind,
}

/// Samples `source` with `pipeline` (stopping at its time limit) and traces it for `plot`: the
/// path, the robot's body at the times `at` (s), the joint curves, and the tool's work.
pub fn trace_program(
    model: &RobotModel,
    pipeline: &Pipeline<'_>,
    source: &dyn ProgramSource,
    kind: ProgramKind,
    at: &[f64],
    notes: impl FnMut(Note) + 'static,
) -> Result<TracedProgram, PipelineError> {
    let mut trace = ProgramTrace::new(model, at);
    let mut samples = pipeline.tool_samples(source, kind, notes)?;
    let tool = samples.tool();
    let max_power = model.robot().tool.max_power;
    let mut overlay = ProgramOverlay::new(tool, MAX_WORK_POINTS, 0, None);
    for sample in samples {
        let (sample, state) = sample?;
        trace.push(&sample);
        overlay.push(&sample, state.strength(tool, max_power));
    }
    Ok(TracedProgram { trace, work: overlay.into_work(), tool })
}

impl Viewer {
    /// Samples the program a trajectory was made from as `joints` sampled it, at the
    /// trajectory's time step (`config`'s otherwise), up to a second past the trajectory's
    /// end, and shows its path, events, lines and tool work; returns the program's end as
    /// sampled (s) when it is apart from the trajectory's duration by more than a time step
    /// (the trajectory was made with other settings).
    pub fn add_program(
        &mut self,
        model: &RobotModel,
        config: SamplingConfig,
        source: &dyn ProgramSource,
        kind: ProgramKind,
    ) -> Result<Option<f64>, PipelineError> {
        let dt = self.time_step().filter(|dt| *dt > 0.0).unwrap_or(0.001);
        let pipeline = Pipeline::new(model, SamplingConfig { dt, ..config });
        let mut samples = pipeline.tool_samples(source, kind, |_| {})?;
        let tool = samples.tool();
        let mut overlay = self.overlay(tool);
        let max_power = model.robot().tool.max_power;
        for sample in samples {
            let (sample, state) = sample?;
            if !overlay.push(&sample, state.strength(tool, max_power)) {
                break;
            }
            self.push_path_sample(sample.t, sample.pose, sample.line, sample.gripper);
        }
        let duration = self.duration().unwrap_or(0.0);
        let apart = overlay.ends_apart_from(duration, self.time_step().unwrap_or(0.0));
        let (end, file) = (overlay.end(), source.name().to_owned());
        self.set_overlay(overlay);
        if kind != ProgramKind::Path {
            let io = |source: std::io::Error| PipelineError::Io { file: file.clone(), source };
            self.read_line_texts(source.open().map_err(io)?).map_err(io)?;
        }
        Ok(apart.then_some(end))
    }
}

#[cfg(test)]
mod tests {
    use biscara_joints::JointCsvRow;
    use biscara_pipeline::TextSource;

    use super::*;
    use crate::ViewerOptions;

    const PROGRAM: &str = "G21 G90\nG0 X0 Y400\nG1 X20 F1200\nM2\n";

    #[test]
    fn a_traced_program_has_its_path_and_the_bodies_asked_for() {
        let model = RobotModel::default();
        let pipeline = Pipeline::new(&model, SamplingConfig::default());
        let source = TextSource::new("job.ngc", PROGRAM);
        let traced =
            trace_program(&model, &pipeline, &source, ProgramKind::Gcode, &[0.0, 1e6], |_| {})
                .expect("traced");
        assert_eq!(traced.tool, ToolKind::Gripper);
        assert_eq!(traced.trace.bodies.len(), 1, "the start only: 1e6 s is past the end");
        assert_eq!(traced.trace.missed_times(), [1e6]);
        let [x, y] = *traced.trace.path.last().expect("a path");
        // The path keeps points a spacing apart: its last is within one of the end.
        assert!((x - 20.0).abs() < 1.0 && (y - 400.0).abs() < 1e-6, "ends at ({x}, {y})");
    }

    #[test]
    fn a_program_overlaid_on_a_shorter_trajectory_reports_its_own_end() {
        let model = RobotModel::default();
        let mut viewer = Viewer::new(&model, Default::default(), ViewerOptions::default());
        for (index, t) in [0.0, 0.001, 0.002].into_iter().enumerate() {
            let row =
                JointCsvRow { t, line: index + 2, joints: Default::default(), velocity: None };
            viewer.push_row(&row).expect("a row");
        }
        let source = TextSource::new("job.ngc", PROGRAM);
        let config = SamplingConfig::default();
        let end =
            viewer.add_program(&model, config, &source, ProgramKind::Gcode).expect("overlaid");
        let end = end.expect("the program runs longer than 2 ms");
        assert!(end > 0.5, "the program's end as sampled: {end} s");
    }
}
