//! The report of `check` as the user reads it: JSON (README.md) and text.

use biscara_kinematics::Joint;
use biscara_text::{fixed, round_to};
use serde_json::{Value, json};

use std::io::Write;

use crate::check::torque_unit;
use crate::scene::read_json;
use crate::{Peak, Problem, ProblemKind, Rectangle, Report, VirtualRobotError, Workspace};

/// Where a figure of the summary was found: `line N`, or `the home pose` for line 0, the first
/// sample (t = 0), which is the robot's home pose before the program's first line.
fn at_line(line: usize) -> String {
    if line == 0 { "the home pose".to_owned() } else { format!("line {line}") }
}

/// A number rounded to 6 decimals, negative zero cleaned, for JSON.
fn round6(value: f64) -> Value {
    json!(round_to(value, 6))
}

fn pose_json(pose: &[f64; 4]) -> Value {
    Value::Array(pose.iter().map(|&v| round6(v)).collect())
}

fn problem_json(problem: &Problem) -> Value {
    json!({
        "kind": problem.kind.name(),
        "line": problem.line,
        "t_s": round6(problem.t_start),
        "t_end_s": round6(problem.t_end),
        "line_end": problem.line_end,
        "samples": problem.samples,
        "subject": problem.subject,
        "pose": pose_json(&problem.pose),
        "worst": {
            "t_s": round6(problem.t_worst),
            "line": problem.line_worst,
            "pose": pose_json(&problem.pose_worst),
        },
        "message": problem.message(),
    })
}

/// One problem of a `check --json` report read back ([`Report::read_problems`]).
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
pub struct ReportedProblem {
    /// When it starts, s.
    #[serde(rename = "t_s")]
    pub t: f64,
    /// What kind of problem.
    pub kind: ProblemKind,
    /// What it is, as the report says it (empty when the report has none).
    #[serde(default)]
    pub message: String,
}

/// The part of a `check --json` report the viewer reads.
#[derive(serde::Deserialize)]
struct ReportedProblems {
    problems: Vec<ReportedProblem>,
}

impl<'de> serde::Deserialize<'de> for ProblemKind {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let name = String::deserialize(deserializer)?;
        ProblemKind::from_name(&name).ok_or_else(|| {
            let names: Vec<&str> = ProblemKind::ALL.iter().map(|kind| kind.name()).collect();
            serde::de::Error::custom(format!(
                "unknown kind `{name}`, expected one of {}",
                names.join(", ")
            ))
        })
    }
}

impl Report {
    /// Reads the problems of a `check --json` report ([`Report::to_json`]) back: each one's
    /// start time, kind and message; the other keys are not read. Fails with the line, column
    /// and key of what is not such a report.
    pub fn read_problems(json: &[u8]) -> Result<Vec<ReportedProblem>, VirtualRobotError> {
        let report: ReportedProblems =
            read_json(json).map_err(|error| VirtualRobotError::CheckReport {
                line: error.line,
                column: error.column,
                key: error.key,
                message: error.message,
            })?;
        Ok(report.problems)
    }

    /// The report as README.md's `{"ok":…,"problems":[…],"summary":{…}}` (`check --json`).
    pub fn to_json(&self) -> Value {
        let report = self;
        let summary = &report.summary;
        let peaks = |peaks: &[Peak; 4], per: &str| {
            let mut map = serde_json::Map::new();
            for (joint, peak) in Joint::ALL.into_iter().zip(peaks) {
                let unit = if joint.is_revolute() { "deg" } else { "mm" };
                map.insert(
                    joint.name().to_owned(),
                    json!({
                        "value": round6(peak.value),
                        "limit": round6(peak.limit),
                        "unit": format!("{unit}{per}"),
                        "line": peak.line,
                        "t_s": round6(peak.t),
                    }),
                );
            }
            Value::Object(map)
        };
        let mut value = json!({
            "ok": report.ok(),
            "problems": report.problems.iter().map(problem_json).collect::<Vec<_>>(),
            "summary": {
                "samples": summary.samples,
                "duration_s": round6(summary.duration_s),
                "path_length_mm": round6(summary.path_length_mm),
                "peak_velocity": peaks(&summary.peaks.velocity, "/s"),
                "peak_acceleration": peaks(&summary.peaks.acceleration, "/s2"),
                "min_singularity": summary.min_singularity.as_ref().map(|nearest| json!({
                    "angle_deg": round6(nearest.angle_deg),
                    "kind": nearest.kind,
                    "line": nearest.line,
                    "t_s": round6(nearest.t),
                })),
            },
        });
        if let Some(torques) = &summary.torques {
            let (mut peak, mut rms) = (serde_json::Map::new(), serde_json::Map::new());
            for (joint, figure) in Joint::ALL.into_iter().zip(torques) {
                let unit = torque_unit(joint);
                peak.insert(
                    joint.name().to_owned(),
                    json!({
                        "value": round6(figure.peak.value),
                        "limit": round6(figure.peak.limit),
                        "unit": unit,
                        "line": figure.peak.line,
                        "t_s": round6(figure.peak.t),
                    }),
                );
                rms.insert(
                    joint.name().to_owned(),
                    json!({
                        "value": round6(figure.rms),
                        "limit": round6(figure.rated),
                        "unit": unit,
                    }),
                );
            }
            value["summary"]["peak_torque"] = Value::Object(peak);
            value["summary"]["rms_torque"] = Value::Object(rms);
        }
        value
    }

    /// The report as text (`check`): the problems of `name`, one a line, then the summary.
    pub fn write_text(&self, out: &mut dyn std::io::Write, name: &str) -> std::io::Result<()> {
        let report = self;
        let count = report.problems.len();
        if report.ok() {
            writeln!(out, "{name}: clean: no problem found")?;
        } else {
            writeln!(out, "{name}: {count} problem{}", if count == 1 { "" } else { "s" })?;
        }
        for problem in &report.problems {
            let [x, y, z, c] = problem.pose.map(|v| fixed(v, 3));
            // A problem at the home pose (line 0) has no line to name: `FILE: home pose: …`.
            let line =
                if problem.line == 0 { " home pose".to_owned() } else { problem.line.to_string() };
            writeln!(
                out,
                "{name}:{line}: {} ({}) at t = {} s, pose (x, y, z, c) = ({x}, {y}, {z}, {c}): {}",
                problem.kind,
                problem.subject,
                fixed(problem.t_start, 3),
                problem.message()
            )?;
        }
        let summary = &report.summary;
        writeln!(out, "summary:")?;
        writeln!(
            out,
            "  duration {} s ({} sample{}), path length {} mm",
            fixed(summary.duration_s, 3),
            summary.samples,
            if summary.samples == 1 { "" } else { "s" },
            fixed(summary.path_length_mm, 3)
        )?;
        for (what, peaks, per) in [
            ("velocity", &summary.peaks.velocity, "/s"),
            ("acceleration", &summary.peaks.acceleration, "/s²"),
        ] {
            writeln!(out, "  peak joint {what}:")?;
            for (joint, peak) in Joint::ALL.into_iter().zip(peaks) {
                let unit = if joint.is_revolute() { "°" } else { "mm" };
                writeln!(
                    out,
                    "    {:<7} {:>12} {unit}{per} (limit {}; {}, t = {} s)",
                    joint.name(),
                    fixed(peak.value, 3),
                    peak.limit,
                    at_line(peak.line),
                    fixed(peak.t, 3)
                )?;
            }
        }
        if let Some(torques) = &summary.torques {
            writeln!(out, "  motor torques (peak against peak, RMS against rated):")?;
            for (joint, figure) in Joint::ALL.into_iter().zip(torques) {
                let unit = torque_unit(joint);
                writeln!(
                    out,
                    "    {:<7} peak {:>10} {unit} (peak {}; {}, t = {} s), RMS {:>10} {unit} \
                     (rated {})",
                    joint.name(),
                    fixed(figure.peak.value, 3),
                    figure.peak.limit,
                    at_line(figure.peak.line),
                    fixed(figure.peak.t, 3),
                    fixed(figure.rms, 3),
                    figure.rated
                )?;
            }
        }
        match &summary.min_singularity {
            Some(nearest) => writeln!(
                out,
                "  nearest singularity: {}° from the {} ({}, t = {} s)",
                fixed(nearest.angle_deg, 3),
                nearest.kind,
                at_line(nearest.line),
                fixed(nearest.t, 3)
            )?,
            None => writeln!(out, "  nearest singularity: no reachable sample")?,
        }
        Ok(())
    }
}

/// The workspace and its largest rectangle, as `workspace --json` prints them.
#[derive(serde::Serialize)]
struct WorkspaceJson {
    area_mm2: f64,
    step_mm: f64,
    rectangle: RectangleJson,
}

#[derive(serde::Serialize)]
struct RectangleJson {
    min: [f64; 2],
    max: [f64; 2],
}

impl Workspace {
    /// `{"area_mm2":…,"step_mm":…,"rectangle":{"min":[x,y],"max":[x,y]}}` (README.md).
    pub fn to_json(&self, rectangle: &Rectangle) -> String {
        let workspace = self;
        let r = |v: f64| round_to(v, 6);
        let value = WorkspaceJson {
            area_mm2: r(workspace.area_mm2()),
            step_mm: workspace.step(),
            rectangle: RectangleJson { min: rectangle.min.map(r), max: rectangle.max.map(r) },
        };
        serde_json::to_string(&value).unwrap_or_default()
    }

    /// The grid as CSV, `x_mm,y_mm,reachable` (1 or 0), one row per grid point.
    pub fn write_csv(&self, out: &mut dyn Write) -> std::io::Result<()> {
        let workspace = self;
        writeln!(out, "x_mm,y_mm,reachable")?;
        let (columns, rows) = workspace.size();
        for j in 0..rows {
            for i in 0..columns {
                let [x, y] = workspace.point(i, j);
                let flag = u8::from(workspace.is_reachable(i, j));
                writeln!(out, "{},{},{flag}", fixed(x, 3), fixed(y, 3))?;
            }
        }
        Ok(())
    }

    /// The area and the rectangle as text, for the robot named `name`.
    pub fn write_text(
        &self,
        out: &mut dyn Write,
        name: &str,
        rectangle: &Rectangle,
    ) -> std::io::Result<()> {
        let workspace = self;
        writeln!(out, "workspace of {name} (grid step {} mm)", workspace.step())?;
        writeln!(
            out,
            "reachable area: {} mm² ({} grid points)",
            fixed(workspace.area_mm2(), 0),
            workspace.count()
        )?;
        writeln!(
            out,
            "largest rectangle: x {} .. {} mm, y {} .. {} mm ({} x {} mm, {} mm²)",
            fixed(rectangle.min[0], 3),
            fixed(rectangle.max[0], 3),
            fixed(rectangle.min[1], 3),
            fixed(rectangle.max[1], 3),
            fixed(rectangle.width(), 3),
            fixed(rectangle.height(), 3),
            fixed(rectangle.width() * rectangle.height(), 0)
        )?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_problems_written_are_read_back() {
        let json = br#"{"ok":false,"problems":[{"kind":"joint_limit","line":3,"t_s":1.25,
            "message":"theta1 beyond its limit"},{"kind":"tool","t_s":2}],"summary":{}}"#;
        let problems = Report::read_problems(json).unwrap();
        assert_eq!(
            problems,
            [
                ReportedProblem {
                    t: 1.25,
                    kind: ProblemKind::JointLimit,
                    message: "theta1 beyond its limit".to_owned()
                },
                ReportedProblem { t: 2.0, kind: ProblemKind::Tool, message: String::new() },
            ]
        );
        for kind in ProblemKind::ALL {
            assert_eq!(ProblemKind::from_name(kind.name()), Some(kind));
        }
    }

    #[test]
    fn what_is_not_a_report_is_refused_at_its_line_column_and_key() {
        // (Each message starts so; the list of kinds goes on.)
        for (json, expected) in [
            (
                "{\"problems\": [\n  {\"kind\": }]}",
                "2:12: not a check --json report: problems[0].kind: expected value",
            ),
            ("{\"ok\": true}", "1:12: not a check --json report: .: missing field `problems`"),
            (
                "{\"problems\":[{\"kind\":\"tool\"}]}",
                "1:28: not a check --json report: problems[0]: missing field `t_s`",
            ),
            (
                "{\"problems\":[{\"kind\":\"limit\",\"t_s\":1}]}",
                "1:28: not a check --json report: problems[0].kind: unknown kind `limit`, \
                 expected one of unreachable, joint_limit, ",
            ),
            ("{\"problems\":[]} x", "1:17: not a check --json report: .: trailing characters"),
        ] {
            let err = Report::read_problems(json.as_bytes()).unwrap_err();
            assert!(err.to_string().starts_with(expected), "{json}: {err}");
        }
    }
}
