//! The joint CSV (docs/motion.md).

use std::io::{self, BufRead, Write};

use biscara_kinematics::Joints;
use biscara_text::{CsvError, NumericCsvReader, RowBuffer};

use crate::{JointSample, Peaks};

/// The unit of the angle columns.
///
/// With the `clap` feature, `--angle-unit rad` or `deg`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
pub enum AngleUnit {
    /// Radians.
    ///
    /// The default, as Simulink wants them.
    #[default]
    #[cfg_attr(feature = "clap", value(name = "rad"))]
    Radians,
    /// Degrees.
    #[cfg_attr(feature = "clap", value(name = "deg"))]
    Degrees,
}

/// How a joint CSV is written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct JointCsvFormat {
    /// Unit of θ1–θ3 and their derivatives.
    pub angle_unit: AngleUnit,
    /// Add velocity and acceleration columns.
    pub derivatives: bool,
    /// Decimals of every number.
    pub precision: usize,
}

impl JointCsvFormat {
    /// The header line, without the newline: [`JointCsvFormat::columns`] joined by commas.
    pub fn header(&self) -> String {
        self.columns().join(",")
    }

    /// The names of the columns, in order: `t_s`, the joints, and with `derivatives` their
    /// velocities and accelerations (the values of [`JointCsvFormat::values`]).
    pub fn columns(&self) -> Vec<String> {
        let unit = match self.angle_unit {
            AngleUnit::Radians => "rad",
            AngleUnit::Degrees => "deg",
        };
        let mut columns = vec!["t_s".to_owned()];
        let angles = ["theta1", "theta2", "theta3"];
        columns.extend(angles.iter().map(|name| format!("{name}_{unit}")));
        columns.push("d4_mm".to_owned());
        if self.derivatives {
            columns.extend(angles.iter().map(|name| format!("d{name}_{unit}_s")));
            columns.push("dd4_mm_s".to_owned());
            columns.extend(angles.iter().map(|name| format!("dd{name}_{unit}_s2")));
            columns.push("ddd4_mm_s2".to_owned());
        }
        columns
    }

    /// The values of one sample in the order and units of [`JointCsvFormat::columns`], unrounded:
    /// what a row of the CSV holds, for callers that keep the numbers (the Python package).
    pub fn values(&self, sample: &JointSample) -> impl Iterator<Item = f64> + use<> {
        let (pose, derivatives) = self.scaled(sample);
        let derivatives = if self.derivatives { Some(derivatives) } else { None };
        pose.into_iter().chain(derivatives.into_iter().flatten())
    }

    /// `[t, θ1, θ2, θ3, d4]` and the velocities and accelerations in the format's angle unit.
    #[inline]
    fn scaled(&self, sample: &JointSample) -> ([f64; 5], [f64; 8]) {
        let scale = match self.angle_unit {
            AngleUnit::Radians => 1.0,
            AngleUnit::Degrees => 180.0 / std::f64::consts::PI,
        };
        let scaled = |[a, b, c, d]: [f64; 4]| [a * scale, b * scale, c * scale, d];
        let [theta1, theta2, theta3, d4] = scaled(sample.joints.to_array());
        let [v1, v2, v3, v4] = scaled(sample.velocity);
        let [a1, a2, a3, a4] = scaled(sample.acceleration);
        ([sample.t, theta1, theta2, theta3, d4], [v1, v2, v3, v4, a1, a2, a3, a4])
    }
}

/// Writes joint samples as CSV; rows reach the output in chunks of [`biscara_text::FLUSH_AT`] bytes
/// and at [`JointCsvWriter::finish`], which must be called.
#[derive(Debug)]
pub struct JointCsvWriter<W: Write> {
    out: W,
    format: JointCsvFormat,
    /// Rows not yet handed to `out`.
    row: RowBuffer,
}

impl<W: Write> JointCsvWriter<W> {
    /// A writer in `format`; writes the header at once.
    pub fn new(mut out: W, format: JointCsvFormat) -> io::Result<Self> {
        writeln!(out, "{}", format.header())?;
        Ok(JointCsvWriter { out, format, row: RowBuffer::new() })
    }

    /// A writer in `format` with the extra columns `columns` after the joints (the tool's,
    /// `joints --events`, docs/motion.md), whose values [`JointCsvWriter::write_with`] takes;
    /// writes the header at once.
    pub fn with_columns(mut out: W, format: JointCsvFormat, columns: &[&str]) -> io::Result<Self> {
        write!(out, "{}", format.header())?;
        for column in columns {
            write!(out, ",{column}")?;
        }
        out.write_all(b"\n")?;
        Ok(JointCsvWriter { out, format, row: RowBuffer::new() })
    }

    /// Writes one sample.
    pub fn write(&mut self, sample: &JointSample) -> io::Result<()> {
        self.write_with(sample, &[])
    }

    /// Writes one sample with the values of the extra columns (see
    /// [`JointCsvWriter::with_columns`]), with the format's decimals.
    pub fn write_with(&mut self, sample: &JointSample, values: &[f64]) -> io::Result<()> {
        self.push_joints(sample);
        for value in values {
            self.row.push(b',');
            self.row.push_fixed(*value, self.format.precision);
        }
        self.end_row()
    }

    /// [`JointCsvWriter::write_with`] for a fixed number of extra values, formatted together
    /// (faster, for the torque columns written at every row).
    pub fn write_with_array<const N: usize>(
        &mut self,
        sample: &JointSample,
        values: [f64; N],
    ) -> io::Result<()> {
        self.push_joints(sample);
        if N > 0 {
            self.row.push(b',');
            self.row.push_fixed_list(values, self.format.precision);
        }
        self.end_row()
    }

    /// The row's time, joints and (in the format) derivatives, without the newline.
    #[inline(always)]
    fn push_joints(&mut self, sample: &JointSample) {
        let decimals = self.format.precision;
        let (pose, derivatives) = self.format.scaled(sample);
        if self.format.derivatives {
            // The thirteen numbers in one list: one dispatch on the decimals and one check of
            // the buffer's room instead of two.
            let [t, q1, q2, q3, q4] = pose;
            let [v1, v2, v3, v4, a1, a2, a3, a4] = derivatives;
            let row = [t, q1, q2, q3, q4, v1, v2, v3, v4, a1, a2, a3, a4];
            self.row.push_fixed_list(row, decimals);
        } else {
            self.row.push_fixed_list(pose, decimals);
        }
    }

    /// Ends the row; hands the buffer to the output when it is full.
    #[inline(always)]
    fn end_row(&mut self) -> io::Result<()> {
        self.row.push(b'\n');
        if self.row.is_full() {
            self.row.write_to(&mut self.out)?;
        }
        Ok(())
    }

    /// Writes the rows still buffered, flushes and returns the underlying writer.
    pub fn finish(mut self) -> io::Result<W> {
        self.row.write_to(&mut self.out)?;
        self.out.flush()?;
        Ok(self.out)
    }
}

/// The tool columns `joints --events` may add after the joints (docs/motion.md), which the reader
/// reads past.
pub const TOOL_COLUMNS: [&str; 5] =
    ["gripper", "laser_power", "spindle_rpm", "extruded_mm", "pen_down"];

/// The columns `joints --torques` adds after the derivatives (docs/dynamics.md), which the
/// reader reads past: the torques of θ1–θ3 (N·m), d4's force (N) and the payload held (kg).
pub const TORQUE_COLUMNS: [&str; 5] =
    ["tau_theta1_Nm", "tau_theta2_Nm", "tau_theta3_Nm", "f_d4_N", "payload_kg"];

/// One row of a joint CSV read back: radians and millimetres whatever the file's angle unit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointCsvRow {
    /// Time, s.
    pub t: f64,
    /// 1-based line of the row in the CSV file.
    pub line: usize,
    /// Joint positions (radians, mm).
    pub joints: Joints,
    /// Joint velocities (rad/s, mm/s) when the file has derivative columns.
    pub velocity: Option<[f64; 4]>,
}

/// A joint CSV that cannot be read; `Display` starts with `LINE:COL: ` or `LINE: `.
pub type JointCsvError = CsvError;

/// Reads a joint CSV written by `biscara joints` (any angle unit, with or without derivatives),
/// streaming; rows come back in radians and millimetres. Lines longer than
/// [`biscara_text::MAX_LINE_BYTES`] are refused.
pub fn read_joint_csv<R: BufRead>(reader: R) -> JointCsvReader<R> {
    JointCsvReader {
        csv: NumericCsvReader::new(reader),
        format: None,
        tool_column: false,
        torque_columns: false,
        failed: false,
    }
}

/// The iterator returned by [`read_joint_csv`]; stops after the first error.
#[derive(Debug)]
pub struct JointCsvReader<R> {
    csv: NumericCsvReader<R>,
    /// Known once the header is read.
    format: Option<JointCsvFormat>,
    /// The header ends with a tool's column (read past).
    tool_column: bool,
    /// The header has the torque columns after the derivatives (read past).
    torque_columns: bool,
    failed: bool,
}

impl<R: BufRead> JointCsvReader<R> {
    fn read_format(&mut self) -> Result<JointCsvFormat, JointCsvError> {
        let header = self.csv.header()?.to_owned();
        // A tool's column (`joints --events`) after the joints is read past.
        let (header, tool_column) = match header.rsplit_once(',') {
            Some((joints, column)) if TOOL_COLUMNS.contains(&column) => (joints, true),
            _ => (header.as_str(), false),
        };
        self.tool_column = tool_column;
        // The torque columns (`joints --torques`) after the derivatives are read past.
        let torques = format!(",{}", TORQUE_COLUMNS.join(","));
        let (header, torque_columns) = match header.strip_suffix(torques.as_str()) {
            Some(joints) => (joints, true),
            None => (header, false),
        };
        self.torque_columns = torque_columns;
        for angle_unit in [AngleUnit::Radians, AngleUnit::Degrees] {
            for derivatives in [false, true] {
                let format = JointCsvFormat { angle_unit, derivatives, precision: 0 };
                if header == format.header() {
                    return Ok(format);
                }
            }
        }
        Err(self.csv.header_error(
            "a joint CSV header `t_s,theta1_rad,theta2_rad,theta3_rad,d4_mm` (or `_deg`, \
             optionally with derivative columns)",
        ))
    }

    fn next_row(&mut self) -> Result<Option<JointCsvRow>, JointCsvError> {
        let format = match self.format {
            Some(format) => format,
            None => {
                let format = self.read_format()?;
                *self.format.insert(format)
            }
        };
        let columns = if format.derivatives { 13 } else { 5 }
            + usize::from(self.tool_column)
            + if self.torque_columns { TORQUE_COLUMNS.len() } else { 0 };
        let Some((line, values)) = self.csv.row(columns)? else { return Ok(None) };
        let scale = match format.angle_unit {
            AngleUnit::Radians => 1.0,
            AngleUnit::Degrees => std::f64::consts::PI / 180.0,
        };
        let joints = Joints {
            theta1: values[1] * scale,
            theta2: values[2] * scale,
            theta3: values[3] * scale,
            d4: values[4],
        };
        let velocity = format
            .derivatives
            .then(|| [values[5] * scale, values[6] * scale, values[7] * scale, values[8]]);
        Ok(Some(JointCsvRow { t: values[0], line, joints, velocity }))
    }
}

biscara_text::record_reader!(JointCsvReader, JointCsvRow, JointCsvError, next_row, failed);

#[cfg(test)]
mod tests {
    use super::*;

    fn read(text: &[u8]) -> Result<Vec<JointCsvRow>, String> {
        read_joint_csv(text).collect::<Result<_, _>>().map_err(|err| err.to_string())
    }

    fn sample(t: f64, degrees: [f64; 4]) -> JointSample {
        JointSample {
            t,
            line: 3,
            pose: [0.0; 4],
            joints: Joints::from_degrees(degrees[0], degrees[1], degrees[2], degrees[3]),
            velocity: [0.5, -0.25, 1.0, 20.0],
            acceleration: [0.0; 4],
            gripper: false,
        }
    }

    #[test]
    fn columns_and_values_are_the_rows_the_writer_writes() {
        for angle_unit in [AngleUnit::Radians, AngleUnit::Degrees] {
            for derivatives in [false, true] {
                let format = JointCsvFormat { angle_unit, derivatives, precision: 6 };
                let s = sample(0.25, [10.0, -20.0, 30.0, 40.0]);
                let mut writer = JointCsvWriter::new(Vec::new(), format).unwrap();
                writer.write(&s).unwrap();
                let text = String::from_utf8(writer.finish().unwrap()).unwrap();
                let mut lines = text.lines();
                assert_eq!(lines.next().unwrap(), format.columns().join(","));
                let written: Vec<f64> =
                    lines.next().unwrap().split(',').map(|v| v.parse().unwrap()).collect();
                let values: Vec<f64> = format.values(&s).collect();
                assert_eq!(values.len(), format.columns().len());
                assert_eq!(written.len(), values.len());
                for (written, value) in written.iter().zip(&values) {
                    assert!((written - value).abs() <= 5e-7, "{written} vs {value}");
                }
            }
        }
    }

    #[test]
    fn what_the_writer_writes_reads_back_in_both_units() {
        for angle_unit in [AngleUnit::Radians, AngleUnit::Degrees] {
            for derivatives in [false, true] {
                let format = JointCsvFormat { angle_unit, derivatives, precision: 9 };
                let mut writer = JointCsvWriter::new(Vec::new(), format).unwrap();
                let samples = [sample(0.0, [10.0, -20.0, 30.0, 40.0]), sample(0.5, [0.0; 4])];
                for s in &samples {
                    writer.write(s).unwrap();
                }
                let text = writer.finish().unwrap();
                let rows = read(&text).unwrap();
                assert_eq!(rows.len(), 2);
                assert_eq!(rows[0].line, 2);
                assert_eq!(rows[1].t, 0.5);
                let got = rows[0].joints.to_array();
                for (got, want) in got.iter().zip(samples[0].joints.to_array()) {
                    assert!((got - want).abs() < 1e-8, "{angle_unit:?}: {got} vs {want}");
                }
                match rows[0].velocity {
                    Some(velocity) => {
                        assert!(derivatives);
                        assert!((velocity[1] + 0.25).abs() < 1e-8 && velocity[3] == 20.0);
                    }
                    None => assert!(!derivatives),
                }
            }
        }
    }

    #[test]
    fn a_tool_column_is_read_past_and_checked() {
        let format =
            JointCsvFormat { angle_unit: AngleUnit::Degrees, derivatives: true, precision: 6 };
        let mut writer = JointCsvWriter::with_columns(Vec::new(), format, &["pen_down"]).unwrap();
        writer.write_with(&sample(0.0, [10.0, -20.0, 30.0, 40.0]), &[1.0]).unwrap();
        let text = writer.finish().unwrap();
        assert!(String::from_utf8_lossy(&text).starts_with("t_s,theta1_deg,"));
        let rows = read(&text).unwrap();
        assert_eq!(rows.len(), 1);
        assert!((rows[0].joints.d4 - 40.0).abs() < 1e-9);
        let header = "t_s,theta1_rad,theta2_rad,theta3_rad,d4_mm";
        let cases = [
            (format!("{header},laser_power\n0,0,0,0,0\n"), "2:10: expected 6 fields, found 5"),
            (format!("{header},power\n0,0,0,0,0,1\n"), "1:1: expected a joint CSV header"),
            (format!("{header},extruded_mm\n0,0,0,0,0,x\n"), "2:11: `x` is not a"),
        ];
        for (input, expected) in cases {
            let message = read(input.as_bytes()).unwrap_err();
            assert!(message.starts_with(expected), "{message:?} should start with {expected:?}");
        }
    }

    #[test]
    fn the_torque_columns_are_read_past() {
        let format =
            JointCsvFormat { angle_unit: AngleUnit::Radians, derivatives: true, precision: 6 };
        let mut columns = TORQUE_COLUMNS.to_vec();
        columns.push("gripper");
        let mut writer = JointCsvWriter::with_columns(Vec::new(), format, &columns).unwrap();
        let values = [1.5, -2.0, 0.25, -7.0, 0.2, 1.0];
        writer.write_with_array(&sample(0.0, [10.0, -20.0, 30.0, 40.0]), values).unwrap();
        writer.write_with(&sample(0.5, [10.0, -20.0, 30.0, 40.0]), &values).unwrap();
        let text = writer.finish().unwrap();
        let rows = read(&text).unwrap();
        assert!((rows[0].joints.d4 - 40.0).abs() < 1e-9 && rows[0].velocity.is_some());
        let lines: Vec<&str> = std::str::from_utf8(&text).unwrap().lines().collect();
        let after_time = |line: &str| line.split_once(',').unwrap().1.to_owned();
        assert_eq!(after_time(lines[1]), after_time(lines[2]), "the same row either way");
        let short = String::from_utf8_lossy(&text).replace(",0.200000,1.000000", "");
        let message = read(short.as_bytes()).unwrap_err();
        assert!(message.starts_with("2:"), "{message}");
    }

    #[test]
    fn bad_input_names_line_and_column() {
        let header = "t_s,theta1_rad,theta2_rad,theta3_rad,d4_mm\n";
        let long = format!("{header}0,{}\n", "1".repeat(100_000)).into_bytes();
        let cases: [(Vec<u8>, &str); 8] = [
            (long, "2: the line is longer than 65536 bytes"),
            (b"".to_vec(), "1:1: expected a joint CSV header"),
            (b"\x00\xff\xfe garbage".to_vec(), "1: stream did not contain valid UTF-8"),
            (b"t_s,x_mm,y_mm,z_mm,c_deg\n0,0,0,0,0\n".to_vec(), "1:1: expected a joint CSV header"),
            (format!("{header}0,0,0,0\n").into_bytes(), "2:8: expected 5 fields, found 4"),
            (format!("{header}0,0,0,0,0,1\n").into_bytes(), "2:11: expected 5 fields, found more"),
            (format!("{header}0,0,NaN,0,0\n").into_bytes(), "2:5: `NaN` is not a finite number"),
            (
                format!("{header}0,0,0,0,0\n0,1,1,1,1\n").into_bytes(),
                "3:1: time 0 does not increase",
            ),
        ];
        for (input, expected) in cases {
            let message = read(&input).unwrap_err();
            assert!(message.starts_with(expected), "{message:?} should start with {expected:?}");
        }
    }
}

/// What a joint trajectory amounts to: its duration, its rows and the peak speed of each joint.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct TrajectorySummary {
    /// Time of the last row, s.
    pub duration: f64,
    /// Rows read.
    pub samples: usize,
    /// Peak |velocity| of θ1, θ2, θ3 (degrees/s) and d4 (mm/s); zero without derivative columns.
    pub peak_velocity: [f64; 4],
}

impl TrajectorySummary {
    /// Reads a joint CSV to its end and sums it up; the first bad row is the error.
    pub fn of<R: BufRead>(reader: R) -> Result<TrajectorySummary, JointCsvError> {
        let mut summary = TrajectorySummary::default();
        let mut peaks = Peaks::default();
        for row in read_joint_csv(reader) {
            let row = row?;
            summary.duration = row.t;
            summary.samples += 1;
            peaks.push(0, row.t, &row.velocity.unwrap_or([0.0; 4]), &[0.0; 4]);
        }
        summary.peak_velocity = peaks.velocity.map(|peak| peak.value);
        Ok(summary)
    }
}

#[cfg(test)]
mod summary_tests {
    use super::*;

    #[test]
    fn the_summary_takes_the_last_time_and_the_peak_speeds() {
        let csv = "t_s,theta1_deg,theta2_deg,theta3_deg,d4_mm,dtheta1_deg_s,dtheta2_deg_s,\
                   dtheta3_deg_s,dd4_mm_s,ddtheta1_deg_s2,ddtheta2_deg_s2,ddtheta3_deg_s2,ddd4_mm_s2\n\
                   0,0,0,0,0,10,-20,0,5,0,0,0,0\n0.5,1,1,1,1,-30,2,0,-1,0,0,0,0\n";
        let summary = TrajectorySummary::of(csv.as_bytes()).unwrap();
        assert_eq!(summary.samples, 2);
        assert_eq!(summary.duration, 0.5);
        let [t1, t2, t3, d4] = summary.peak_velocity;
        assert!((t1 - 30.0).abs() < 1e-9 && (t2 - 20.0).abs() < 1e-9 && t3 == 0.0 && d4 == 5.0);
    }
}
