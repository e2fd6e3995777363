//! The joint CSV (SPEC §7).

use std::io::{self, Write};

use biscara_interpolate::{FLUSH_AT, push_fixed};

use crate::JointSample;

/// The unit of the angle columns.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum AngleUnit {
    /// Radians (the default, as Simulink wants them).
    #[default]
    Radians,
    /// Degrees.
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
    /// The header line, without the newline.
    pub fn header(&self) -> String {
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
        columns.join(",")
    }
}

/// Writes joint samples as CSV; rows reach the output in chunks of [`FLUSH_AT`] bytes and at
/// [`JointCsvWriter::finish`], which must be called.
#[derive(Debug)]
pub struct JointCsvWriter<W: Write> {
    out: W,
    format: JointCsvFormat,
    /// Rows not yet handed to `out`.
    row: Vec<u8>,
}

impl<W: Write> JointCsvWriter<W> {
    /// A writer in `format`; writes the header at once.
    pub fn new(mut out: W, format: JointCsvFormat) -> io::Result<Self> {
        writeln!(out, "{}", format.header())?;
        Ok(JointCsvWriter { out, format, row: Vec::with_capacity(FLUSH_AT + 512) })
    }

    /// Writes one sample.
    pub fn write(&mut self, sample: &JointSample) -> io::Result<()> {
        let decimals = self.format.precision;
        let scale = match self.format.angle_unit {
            AngleUnit::Radians => 1.0,
            AngleUnit::Degrees => 180.0 / std::f64::consts::PI,
        };
        let scales = [scale, scale, scale, 1.0];
        push_fixed(&mut self.row, sample.t, decimals);
        let push_all = |row: &mut Vec<u8>, values: [f64; 4]| {
            for (value, scale) in values.into_iter().zip(scales) {
                row.push(b',');
                push_fixed(row, value * scale, decimals);
            }
        };
        push_all(&mut self.row, sample.joints.to_array());
        if self.format.derivatives {
            push_all(&mut self.row, sample.velocity);
            push_all(&mut self.row, sample.acceleration);
        }
        self.row.push(b'\n');
        if self.row.len() >= FLUSH_AT {
            self.out.write_all(&self.row)?;
            self.row.clear();
        }
        Ok(())
    }

    /// Writes the rows still buffered, flushes and returns the underlying writer.
    pub fn finish(mut self) -> io::Result<W> {
        self.out.write_all(&self.row)?;
        self.out.flush()?;
        Ok(self.out)
    }
}
