//! What LinuxCNC's joints did: the recorder's lines read back, and their summary.

use biscara_joints::{JointPeaks, JointSample, Peaks, central_differences, end_derivatives};
use biscara_kinematics::{Joints, Robot};

use crate::LinuxcncError;

/// The servo period of the configuration, seconds: one recorded sample each.
pub const SERVO_PERIOD: f64 = 0.001;

/// The recorder's scale: positions are recorded times this, for halsampler's six decimals.
const RECORD_SCALE: f64 = 1000.0;

/// One servo cycle as recorded: LinuxCNC's units (degrees and mm), its joint order.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RecordedSample {
    /// The sampler's sample number (consecutive unless samples were lost).
    pub number: u64,
    /// Joint positions θ1, θ2 (degrees), d4 (mm), θ3 (degrees): LinuxCNC's joints 0–3.
    pub joints: [f64; 4],
    /// The commanded axis positions X, Y, Z (mm) and C (degrees).
    pub axes: [f64; 4],
    /// Whether the stream path was playing.
    pub streaming: bool,
}

impl RecordedSample {
    /// The joints in this project's order and units: θ1, θ2, θ3 (radians), d4 (mm).
    pub fn joints(&self) -> Joints {
        let [theta1, theta2, d4, theta3] = self.joints;
        Joints::from_degrees(theta1, theta2, theta3, d4)
    }
}

/// Reads one line of `halsampler -t` for the configuration's recorder: the sample number,
/// eight floats (θ1 θ2 d4 θ3 X Y Z C, times 1000) and the stream flag.
pub fn parse_recorded_line(line: &str) -> Result<RecordedSample, String> {
    let fields: Vec<&str> = line.split_whitespace().collect();
    if fields.len() != 10 {
        return Err(format!("expected 10 fields, found {}", fields.len()));
    }
    let number =
        fields[0].parse::<u64>().map_err(|_| format!("bad sample number {:?}", fields[0]))?;
    let mut values = [0.0; 8];
    for (value, field) in values.iter_mut().zip(&fields[1..9]) {
        let parsed = field.parse::<f64>().map_err(|_| format!("bad number {field:?}"))?;
        if !parsed.is_finite() {
            return Err(format!("not a finite number: {field:?}"));
        }
        *value = parsed / RECORD_SCALE;
    }
    let streaming = match fields[9] {
        "0" => false,
        "1" => true,
        other => return Err(format!("bad stream flag {other:?}")),
    };
    Ok(RecordedSample {
        number,
        joints: [values[0], values[1], values[2], values[3]],
        axes: [values[4], values[5], values[6], values[7]],
        streaming,
    })
}

/// Where a recording starts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RecordingStart {
    /// At the first sample the stream path played (`t = 0` is the stream's first sample).
    Stream,
    /// At the last sample before the joints first move (LinuxCNC takes some cycles between
    /// the start of a program and its first motion).
    FirstMotion,
}

/// What a recording held.
#[derive(Debug, Clone, PartialEq)]
pub struct RecordingSummary {
    /// Samples written.
    pub samples: usize,
    /// Time of the last sample, s.
    pub duration: f64,
    /// Samples the stream path played.
    pub streamed: usize,
    /// Peak joint velocity and acceleration against the limits.
    pub peaks: [JointPeaks; 4],
}

/// Reads the recorder's lines (`halsampler -t`) and hands every sample from `start` on to
/// `each` as a joint sample (t from 0, one servo period apart; velocity and acceleration by
/// central differences and the end-sample rule of `biscara joints`) with the recorded
/// sample; streaming, three samples at a time. Fails on a malformed line or a gap in the sample
/// numbers (a lost sample).
pub fn read_recording<R: std::io::BufRead, E: From<LinuxcncError>>(
    reader: R,
    start: RecordingStart,
    robot: &Robot,
    mut each: impl FnMut(&JointSample, &RecordedSample) -> Result<(), E>,
) -> Result<RecordingSummary, E> {
    let mut window: Vec<(RecordedSample, [f64; 4])> = Vec::with_capacity(3);
    let mut peaks = Peaks::new(robot);
    let mut summary =
        RecordingSummary { samples: 0, duration: 0.0, streamed: 0, peaks: peaks.joints() };
    let mut last_number: Option<u64> = None;
    let mut started = false;
    // Emits one sample with its derivatives.
    let mut emit = |entry: &(RecordedSample, [f64; 4]),
                    (velocity, acceleration): ([f64; 4], [f64; 4]),
                    summary: &mut RecordingSummary|
     -> Result<(), E> {
        let t = summary.samples as f64 * SERVO_PERIOD;
        let q = entry.1;
        let sample = JointSample {
            t,
            line: 0,
            pose: entry.0.axes,
            joints: Joints { theta1: q[0], theta2: q[1], theta3: q[2], d4: q[3] },
            velocity,
            acceleration,
            gripper: false,
        };
        peaks.push(sample.line, t, &sample.velocity, &sample.acceleration);
        summary.samples += 1;
        summary.duration = t;
        summary.streamed += usize::from(entry.0.streaming);
        each(&sample, &entry.0)
    };
    // The last central acceleration, for the last sample's end rule.
    let mut last_acceleration = [0.0; 4];
    for (index, line) in reader.lines().enumerate() {
        let line_number = index + 1;
        let line = line.map_err(|err| LinuxcncError::Recording {
            line: line_number,
            message: err.to_string(),
        })?;
        if line.trim().is_empty() {
            continue;
        }
        let sample = parse_recorded_line(&line)
            .map_err(|message| LinuxcncError::Recording { line: line_number, message })?;
        if let Some(last) = last_number
            && sample.number != last + 1
        {
            return Err(LinuxcncError::Recording {
                line: line_number,
                message: format!(
                    "samples {} to {} were lost (the recorder's FIFO overran)",
                    last + 1,
                    sample.number.saturating_sub(1)
                ),
            }
            .into());
        }
        last_number = Some(sample.number);
        let entry = (sample, sample.joints().to_array());
        if !started {
            match start {
                RecordingStart::Stream if !sample.streaming => continue,
                RecordingStart::FirstMotion => {
                    // Keep only the last sample of the still lead-in.
                    if let Some(first) = window.first()
                        && first.1 == entry.1
                    {
                        window[0] = entry;
                        continue;
                    }
                    if window.is_empty() {
                        window.push(entry);
                        continue;
                    }
                }
                RecordingStart::Stream => {}
            }
            started = true;
        }
        window.push(entry);
        if window.len() == 3 {
            let t = |k: usize| k as f64 * SERVO_PERIOD;
            let (q0, q1, q2) = (&window[0].1, &window[1].1, &window[2].1);
            let middle = central_differences((t(0), q0), (t(1), q1), (t(2), q2));
            if summary.samples == 0 {
                emit(&window[0], end_derivatives((t(0), q0), (t(1), q1), middle.1), &mut summary)?;
            }
            emit(&window[1], middle, &mut summary)?;
            last_acceleration = middle.1;
            window.remove(0);
        }
    }
    // What is left: the last sample (after at least three), or all of a recording of one or two.
    let step = SERVO_PERIOD;
    match window.len() {
        1 => emit(&window[0], ([0.0; 4], [0.0; 4]), &mut summary)?,
        2 if summary.samples == 0 => {
            let (q0, q1) = (&window[0].1, &window[1].1);
            emit(&window[0], end_derivatives((0.0, q0), (step, q1), [0.0; 4]), &mut summary)?;
            emit(&window[1], end_derivatives((step, q1), (0.0, q0), [0.0; 4]), &mut summary)?;
        }
        2 => {
            let (q0, q1) = (&window[0].1, &window[1].1);
            let end = end_derivatives((step, q1), (0.0, q0), last_acceleration);
            emit(&window[1], end, &mut summary)?;
        }
        _ => {}
    }
    summary.peaks = peaks.joints();
    Ok(summary)
}

/// Writes one line of a stream file for the configuration's stream path: θ1 θ2 d4 θ3 in
/// LinuxCNC's joint order and units (degrees, mm), each number exact (the shortest decimal that
/// reads back as the same `f64`).
pub fn write_stream_sample(out: &mut impl std::io::Write, joints: &Joints) -> std::io::Result<()> {
    writeln!(
        out,
        "{} {} {} {}",
        joints.theta1.to_degrees(),
        joints.theta2.to_degrees(),
        joints.d4,
        joints.theta3.to_degrees()
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line(number: u64, joints: [f64; 4], streaming: bool) -> String {
        let scaled = joints.map(|value| format!("{:.6}", value * RECORD_SCALE));
        format!(
            "{number} {} 0.000000 460798.724080 100000.000000 0.000000 {}\n",
            scaled.join(" "),
            u8::from(streaming)
        )
    }

    fn read(
        text: &str,
        start: RecordingStart,
    ) -> Result<(RecordingSummary, Vec<JointSample>), LinuxcncError> {
        let mut samples = Vec::new();
        let summary = read_recording(text.as_bytes(), start, &Robot::default(), |sample, _| {
            samples.push(*sample);
            Ok::<(), LinuxcncError>(())
        })?;
        Ok((summary, samples))
    }

    #[test]
    fn a_recorded_line_reads_back_in_linuxcncs_units_and_order() {
        let sample = parse_recorded_line(
            "7 -19767.034576 19767.034576 17843.444434 -17563.853064 \
                                          0.000000 406328.615948 82081.825250 0.000000 1",
        )
        .unwrap();
        assert_eq!(sample.number, 7);
        assert!((sample.joints[2] - 17.843444434).abs() < 1e-12);
        assert!((sample.axes[1] - 406.328615948).abs() < 1e-12);
        assert!(sample.streaming);
        let joints = sample.joints();
        assert!((joints.d4 - 17.843444434).abs() < 1e-12, "d4 is LinuxCNC's joint 2");
        assert!((joints.theta3.to_degrees() + 17.563853064).abs() < 1e-9, "θ3 is its joint 3");
    }

    #[test]
    fn malformed_lines_and_lost_samples_are_errors_naming_the_line() {
        for (text, expected) in [
            ("1 2 3\n", "line 1: expected 10 fields"),
            ("1 a 0 0 0 0 0 0 0 0\n", "line 1: bad number"),
            ("1 nan 0 0 0 0 0 0 0 0\n", "line 1: not a finite number"),
            ("1 0 0 0 0 0 0 0 0 2\n", "line 1: bad stream flag"),
            ("x 0 0 0 0 0 0 0 0 0\n", "line 1: bad sample number"),
        ] {
            let err = read(text, RecordingStart::FirstMotion).unwrap_err().to_string();
            assert!(err.contains(expected), "{text:?}: {err}");
        }
        let text =
            [line(1, [0.0; 4], false), line(2, [1.0; 4], false), line(5, [2.0; 4], false)].concat();
        let err = read(&text, RecordingStart::FirstMotion).unwrap_err().to_string();
        assert!(err.contains("line 3: samples 3 to 4 were lost"), "{err}");
    }

    #[test]
    fn a_program_recording_starts_at_the_last_still_sample_with_differences() {
        let mut text = String::new();
        for number in 0..5 {
            text += &line(number, [0.0; 4], false);
        }
        // θ1 = t² (degrees, t in cycles) from cycle 5 on.
        for number in 5..10 {
            let t = (number - 4) as f64;
            text += &line(number, [t * t, 0.0, 0.0, 0.0], false);
        }
        let (summary, samples) = read(&text, RecordingStart::FirstMotion).unwrap();
        assert_eq!(samples.len(), 6, "the last still sample and the five moving ones");
        assert_eq!(summary.samples, 6);
        assert!((summary.duration - 0.005).abs() < 1e-12);
        assert_eq!(samples[0].joints.theta1, 0.0);
        // The ends as `biscara joints` has them: the slope to the neighbour (1° in a cycle) and
        // the neighbour's acceleration.
        let first = samples[0].velocity[0].to_degrees();
        assert!((first - 1000.0).abs() < 1e-6, "{first}");
        assert_eq!(samples[0].acceleration, samples[1].acceleration);
        // The last: 25° after 16°, 9° in the last cycle.
        let last = samples[5].velocity[0].to_degrees();
        assert!((last - 9000.0).abs() < 1e-6, "{last}");
        assert_eq!(samples[5].acceleration, samples[4].acceleration);
        // q = t² degrees per cycle²: 2 degrees per cycle² = 2e6 degrees/s².
        let acceleration = samples[2].acceleration[0].to_degrees();
        assert!((acceleration - 2e6).abs() < 1e-3, "{acceleration}");
        assert!((summary.peaks[0].acceleration.value - 2e6).abs() < 1e-3);
        assert_eq!(summary.peaks[0].acceleration.limit, 7200.0);
    }

    #[test]
    fn a_stream_recording_starts_at_the_first_streamed_sample() {
        let text = [
            line(1, [5.0; 4], false),
            line(2, [0.0; 4], true),
            line(3, [0.1; 4], true),
            line(4, [0.2; 4], false),
        ]
        .concat();
        let (summary, samples) = read(&text, RecordingStart::Stream).unwrap();
        assert_eq!(samples.len(), 3);
        assert_eq!(summary.streamed, 2);
        assert_eq!(samples[0].joints.d4, 0.0);
    }

    #[test]
    fn a_stream_line_is_linuxcncs_order_and_degrees() {
        let mut out = Vec::new();
        write_stream_sample(&mut out, &Joints::from_degrees(10.0, -20.0, 30.0, 40.5)).unwrap();
        let text = String::from_utf8(out).unwrap();
        let values: Vec<f64> = text.split_whitespace().map(|v| v.parse().unwrap()).collect();
        assert_eq!(values.len(), 4);
        assert!((values[0] - 10.0).abs() < 1e-12 && (values[1] + 20.0).abs() < 1e-12);
        assert_eq!(values[2], 40.5, "d4 third");
        assert!((values[3] - 30.0).abs() < 1e-12, "θ3 last");
    }
}
