//! The time a design takes to run programs: `joints`' trajectory of each, under the default
//! (time-optimal) profile, summed.

use biscara_kinematics::{Robot, RobotModel};
use biscara_pipeline::{Pipeline, ProgramKind, SamplingConfig, TextSource};

/// Programs to time on every design.
#[derive(Debug, Clone, Default)]
pub struct ProgramTimer {
    programs: Vec<(TextSource, ProgramKind)>,
    fit: bool,
}

impl ProgramTimer {
    /// Programs given as `(name, text)`; each one's kind (G-code, inter-file, path CSV) comes
    /// from its name and first bytes, as the command line decides it. With `fit`, each program
    /// is centred in each design's workspace rectangle first (`joints --fit`).
    pub fn new(programs: impl IntoIterator<Item = (String, String)>, fit: bool) -> ProgramTimer {
        let programs = programs
            .into_iter()
            .map(|(name, text)| {
                let head = &text.as_bytes()[..text.len().min(64)];
                let kind = ProgramKind::detect(&name, head);
                (TextSource::new(name, text), kind)
            })
            .collect();
        ProgramTimer { programs, fit }
    }

    /// Whether there is no program.
    pub fn is_empty(&self) -> bool {
        self.programs.is_empty()
    }

    /// The total duration, seconds, of every program's joint trajectory on `robot` with the
    /// default sampling (1 ms, the optimal profile, every joint limit, `--fit` if asked); `None`
    /// when the robot file is invalid or a program cannot run on it (a pose unreachable, a limit
    /// or the singularity margin crossed).
    pub fn time(&self, robot: &Robot) -> Option<f64> {
        let model = RobotModel::new(robot.clone()).ok()?;
        let config = SamplingConfig { fit: self.fit, ..SamplingConfig::default() };
        let pipeline = Pipeline::new(&model, config);
        let mut total = 0.0;
        for (source, kind) in &self.programs {
            let mut samples = pipeline.joints(source, *kind, |_| {}).ok()?.without_derivatives();
            let mut end = 0.0;
            while let Some(sample) = samples.next_sample() {
                end = sample.ok()?.t;
            }
            total += end;
        }
        Some(total)
    }
}
