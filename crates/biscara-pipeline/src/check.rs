//! A program run on the virtual robot: `biscara check`.

use biscara_robot::{Checker, Report, Scene};

use crate::csv::PayloadWatch;
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
        let payload = biscara_dynamics::Bodies::of(self.model().robot()).payload;
        let mut payload = PayloadWatch::new(kind, payload, source.name(), notes);
        let mut samples = self.tool_samples(source, kind, payload.forward())?;
        let tool = samples.tool();
        for sample in samples {
            let (sample, state) = sample?;
            payload.held(sample.gripper);
            checker.push(&sample);
            if let Some((subject, detail, severity)) = state.problem(tool) {
                checker.push_tool_problem(&sample, subject, detail, severity);
            }
        }
        payload.finish();
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

    /// A path CSV without its gripper column, for a robot with a payload: the report's torques
    /// carry none, and a note says so.
    #[test]
    fn a_path_csv_that_never_holds_the_payload_says_so() {
        use std::cell::RefCell;
        use std::rc::Rc;

        use biscara_kinematics::{DynamicsSpec, PointSpec, Robot};
        let spec = DynamicsSpec { payload: PointSpec { mass: Some(0.5) }, ..Default::default() };
        let model = RobotModel::new(Robot { dynamics: Some(spec), ..Robot::default() }).unwrap();
        let pipeline = Pipeline::new(&model, SamplingConfig::default());
        let path = "t_s,x_mm,y_mm,z_mm,c_deg\n0.000,0,400,50,0\n0.001,0,400.001,50,0\n";
        let notes = Rc::new(RefCell::new(Vec::new()));
        let sink = Rc::clone(&notes);
        let source = TextSource::new("path.csv", path);
        let push = move |note: Note| sink.borrow_mut().push(note.to_string());
        pipeline.check(&source, ProgramKind::Path, Scene::new(), push).expect("run");
        let notes = notes.take();
        assert_eq!(notes.len(), 1, "{notes:?}");
        assert!(notes[0].contains("carry none of the robot's 0.5 kg payload"), "{notes:?}");
    }
}
