//! A program run on the virtual robot: `biscara check`.

use biscara_robot::{Checker, Report, Scene};

use crate::{Note, Pipeline, PipelineError, ProgramKind, ProgramSource};

impl Pipeline<'_> {
    /// Runs the program on the virtual robot among `scene`'s boxes and reports every problem
    /// (the robot's, and what only the tool can get wrong), without stopping at the first;
    /// stops at the configured time limit. Streaming.
    pub fn check(
        &self,
        source: &dyn ProgramSource,
        kind: ProgramKind,
        scene: Scene,
        notes: impl FnMut(Note) + 'static,
    ) -> Result<Report, PipelineError> {
        let mut checker = Checker::new(self.model(), scene);
        let mut samples = self.tool_samples(source, kind, notes)?;
        let tool = samples.tool();
        for sample in samples {
            let (sample, state) = sample?;
            checker.push(&sample);
            if let Some((subject, detail, severity)) = state.problem(tool) {
                checker.push_tool_problem(&sample, subject, detail, severity);
            }
        }
        Ok(checker.finish())
    }
}

#[cfg(test)]
mod tests {
    use biscara_kinematics::RobotModel;

    use crate::{SamplingConfig, TextSource};

    use super::*;

    #[test]
    fn a_program_out_of_reach_is_reported_and_a_good_one_is_not() {
        let model = RobotModel::default();
        let pipeline = Pipeline::new(&model, SamplingConfig::default());
        let good = TextSource::new("good.ngc", "G21 G90\nG0 X0 Y400\nM2\n");
        let report = pipeline.check(&good, ProgramKind::Gcode, Scene::new(), |_| {}).expect("run");
        assert!(report.ok(), "{:?}", report.problems);
        let far = TextSource::new("far.ngc", "G21 G90\nG0 X0 Y400\nG1 X0 Y2000 F6000\nM2\n");
        let report = pipeline.check(&far, ProgramKind::Gcode, Scene::new(), |_| {}).expect("run");
        assert!(!report.ok());
        assert!(report.problems.iter().any(|problem| problem.line == 3), "{:?}", report.problems);
    }
}
