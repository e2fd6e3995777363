//! `biscara demo`'s bundled job and the report of what it wrote.

use std::fmt;
use std::path::PathBuf;

use biscara_joints::TrajectorySummary;

/// The bundled pick-and-place job: the example points file (also `data/jobs/pick_place.txt`).
pub const EXAMPLE_JOB: &str = include_str!("../../../data/jobs/pick_place.txt");

/// What the demo wrote into its folder and the joint trajectory's summary; `Display` is the
/// demo's report: one line per file, then the duration, the samples and every joint's peak
/// speed.
#[derive(Debug, Clone, PartialEq)]
pub struct DemoReport {
    /// The folder written into.
    pub dir: PathBuf,
    /// Whether the robot has motors (the trajectory then holds their torques).
    pub motors: bool,
    /// The joint trajectory's summary.
    pub summary: TrajectorySummary,
}

impl DemoReport {
    /// Every file the demo writes, by name, and what it is.
    pub fn written(&self) -> [(&'static str, &'static str); 14] {
        let traj = if self.motors {
            "joint trajectory with velocities, accelerations and torques (biscara joints)"
        } else {
            "joint trajectory with velocities and accelerations (biscara joints)"
        };
        [
            ("robot.json", "the robot in force"),
            ("job.txt", "the pick-and-place points"),
            ("job.cl", "CL file (biscara clf)"),
            ("job.ngc", "G-code for LinuxCNC (biscara post)"),
            ("job.jsonl", "motions, the inter-file (biscara interpret)"),
            ("path.csv", "Cartesian samples at 1 ms (biscara interpolate)"),
            ("traj.csv", traj),
            ("check.json", "the virtual robot's report (biscara check --json)"),
            ("workspace.txt", "the workspace's area and largest rectangle (biscara workspace)"),
            ("workspace.svg", "the workspace and its largest rectangle (biscara workspace --svg)"),
            ("plot.svg", "workspace, path and robot in top view (biscara plot)"),
            ("view.html", "the robot in motion, open in a browser (biscara view)"),
            ("robot.xml", "MuJoCo model (biscara mjcf)"),
            ("robot.traj.csv", "the trajectory in the model's joints (mjcf --traj)"),
        ]
    }
}

impl fmt::Display for DemoReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "biscara demo: the bundled pick-and-place job through the whole pipeline")?;
        for (name, what) in self.written() {
            let path = self.dir.join(name).display().to_string();
            writeln!(f, "  wrote {path:<24} {what}")?;
        }
        let [t1, t2, t3, d4] = self.summary.peak_velocity;
        writeln!(
            f,
            "duration {:.3} s, {} samples; peak joint speeds: theta1 {t1:.1} °/s, theta2 {t2:.1} \
             °/s, theta3 {t3:.1} °/s, d4 {d4:.1} mm/s",
            self.summary.duration, self.summary.samples,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_report_lists_every_file_and_the_peaks() {
        let summary = TrajectorySummary {
            duration: 2.5,
            samples: 2501,
            peak_velocity: [1.0, 2.0, 3.04, 4.0],
        };
        let report = DemoReport { dir: PathBuf::from("out"), motors: true, summary };
        let text = report.to_string();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 16);
        assert_eq!(lines[1], "  wrote out/robot.json           the robot in force");
        assert!(lines[7].ends_with("velocities, accelerations and torques (biscara joints)"));
        assert_eq!(
            lines[15],
            "duration 2.500 s, 2501 samples; peak joint speeds: theta1 1.0 °/s, theta2 2.0 °/s, \
             theta3 3.0 °/s, d4 4.0 mm/s"
        );
        assert!(EXAMPLE_JOB.lines().count() > 3);
    }
}
