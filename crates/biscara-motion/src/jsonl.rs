//! Reading and writing the inter-file: one JSON object per line.

use std::io::{self, BufRead, Write};

use biscara_text::{Located, read_bounded_line, strip_position};

use serde_json::ser::{CompactFormatter, Formatter};

use crate::{Motion, MotionKind, Plane};

/// An inter-file that cannot be read, at its line (and column).
pub type InterFileError = Located<InterFileErrorKind>;

/// What is wrong in an inter-file.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum InterFileErrorKind {
    /// Occurs when the underlying reader fails (including text that is not UTF-8).
    #[error("{0}")]
    Io(#[source] io::Error),
    /// Occurs when a line is not a motion object: bad JSON, an unknown kind or key, a missing
    /// field, a wrong type (with the column where the JSON reader stopped).
    #[error("{0}")]
    Syntax(String),
    /// Occurs when a motion holds a number that is not finite, a negative dwell or feed, or zero
    /// turns.
    #[error("{0}")]
    Invalid(String),
}

/// Writes every motion of `motions` as the inter-file's lines ([`write_jsonl`]) to `out`,
/// through a buffer of 64 KiB (a motion is written in many small pieces, which `dyn Write`
/// would pass on one by one); stops at the first error of `motions` or of `out`.
pub fn write_motions<E: From<io::Error>>(
    out: &mut dyn Write,
    motions: impl IntoIterator<Item = Result<Motion, E>>,
) -> Result<(), E> {
    let mut out = io::BufWriter::with_capacity(64 * 1024, out);
    for motion in motions {
        write_jsonl(&mut out, &motion?)?;
    }
    out.flush()?;
    Ok(())
}

/// Writes one motion as one line of JSON.
///
/// The bytes are those of `serde_json::to_writer(out, motion)` and a newline (the keys of the
/// flat record in their order, numbers formatted by serde_json's formatter), written directly:
/// `interpret` writes one per line of its program, and serde's generic path (a record built
/// field by field, every key escaped as a string) cost more than the interpreter's own work on
/// a line.
pub fn write_jsonl(out: &mut impl Write, motion: &Motion) -> io::Result<()> {
    out.write_all(b"{\"line\":")?;
    CompactFormatter.write_u64(out, motion.line as u64)?;
    out.write_all(b",\"kind\":\"")?;
    out.write_all(motion.kind.name().as_bytes())?;
    out.write_all(b"\"")?;
    let feed = match motion.kind {
        MotionKind::Rapid { end } => {
            write_end(out, &end)?;
            None
        }
        MotionKind::Linear { end, feed } => {
            write_end(out, &end)?;
            Some(feed)
        }
        MotionKind::Arc { end, center, plane, clockwise, turns, feed } => {
            write_end(out, &end)?;
            out.write_all(b",\"center\":[")?;
            write_f64(out, center[0])?;
            out.write_all(b",")?;
            write_f64(out, center[1])?;
            out.write_all(match plane {
                Plane::Xy => b"],\"plane\":\"xy\"",
                Plane::Xz => b"],\"plane\":\"xz\"",
                Plane::Yz => b"],\"plane\":\"yz\"",
            })?;
            write_bool(out, b",\"clockwise\":", clockwise)?;
            out.write_all(b",\"turns\":")?;
            CompactFormatter.write_u32(out, turns)?;
            Some(feed)
        }
        MotionKind::Dwell { seconds } => {
            out.write_all(b",\"seconds\":")?;
            write_f64(out, seconds)?;
            None
        }
        MotionKind::SpindleOn { clockwise, .. } => {
            write_bool(out, b",\"clockwise\":", clockwise)?;
            None
        }
        _ => None,
    };
    if let Some(feed) = feed {
        out.write_all(b",\"feed\":")?;
        write_f64(out, feed.mm_per_min)?;
        if feed.inverse_time {
            out.write_all(b",\"inverse_time\":true")?;
        }
    }
    if let Some(extrude) = motion.extrude {
        out.write_all(b",\"extrude\":")?;
        write_f64(out, extrude)?;
    }
    if let Some(blend) = motion.blend {
        out.write_all(b",\"blend\":")?;
        write_f64(out, blend)?;
    }
    if let Some(q) = motion.naive_cam {
        out.write_all(b",\"naive_cam\":")?;
        write_f64(out, q)?;
    }
    match motion.kind {
        MotionKind::LaserOn { power, dynamic } => {
            out.write_all(b",\"power\":")?;
            write_f64(out, power)?;
            write_bool(out, b",\"dynamic\":", dynamic)?;
        }
        MotionKind::SpindleOn { rpm, .. } => {
            out.write_all(b",\"rpm\":")?;
            write_f64(out, rpm)?;
        }
        MotionKind::Code { code } => {
            out.write_all(b",\"code\":")?;
            // Printable ASCII, but `"` and `\` are printable: serde_json escapes.
            serde_json::to_writer(&mut *out, code.as_str()).map_err(io::Error::from)?;
        }
        _ => {}
    }
    out.write_all(b"}\n")
}

fn write_end(out: &mut impl Write, end: &[f64; 4]) -> io::Result<()> {
    out.write_all(b",\"end\":[")?;
    write_f64(out, end[0])?;
    for &value in &end[1..] {
        out.write_all(b",")?;
        write_f64(out, value)?;
    }
    out.write_all(b"]")
}

/// A number as serde_json writes it: `null` when it is not finite.
fn write_f64(out: &mut impl Write, value: f64) -> io::Result<()> {
    let mut buffer = [0; SHORT_DECIMAL_BYTES];
    if let Some(text) = short_decimal(value, &mut buffer) {
        out.write_all(text)
    } else if value.is_finite() {
        CompactFormatter.write_f64(out, value)
    } else {
        out.write_all(b"null")
    }
}

/// Room for a sign, nine digits, a point and three decimals.
const SHORT_DECIMAL_BYTES: usize = 16;

/// `value` written as serde_json writes it, when that is at most nine digits, a point and at
/// most three decimals (`-89.85`, `300.0`): most positions and feeds of a program. `None` for
/// any other number.
///
/// serde_json writes the shortest decimal that reads back as `value`. Below 10⁹ the decimals
/// with `k ≤ 3` places are 10⁻ᵏ apart, far more than the spacing of doubles, so at most one
/// of them reads back as `value`: `d / 10ᵏ` with `d = round(|value| · 10ᵏ)`, and it does when
/// the division (correctly rounded, of an integer and a power of ten both exact) gives `value`
/// back. The first `k` that works gives the shortest.
fn short_decimal(value: f64, buffer: &mut [u8; SHORT_DECIMAL_BYTES]) -> Option<&[u8]> {
    const SCALES: [f64; 4] = [1.0, 10.0, 100.0, 1000.0];
    let magnitude = value.abs();
    if magnitude.is_nan() || magnitude >= 1e9 {
        return None;
    }
    let (places, digits) = SCALES.iter().enumerate().find_map(|(places, &scale)| {
        // Below 10¹², exact as a double and as a u64.
        let digits = (magnitude * scale + 0.5) as u64;
        (digits as f64 / scale == magnitude).then_some((places, digits))
    })?;
    // Written from the end: the decimals (or `0` after the point), the point, the integer part.
    let mut at = buffer.len();
    let mut rest = digits;
    let mut put = |byte: u8| {
        at -= 1;
        buffer[at] = byte;
    };
    if places == 0 {
        put(b'0');
    }
    for _ in 0..places {
        put(b'0' + (rest % 10) as u8);
        rest /= 10;
    }
    put(b'.');
    loop {
        put(b'0' + (rest % 10) as u8);
        rest /= 10;
        if rest == 0 {
            break;
        }
    }
    if value.is_sign_negative() {
        put(b'-');
    }
    Some(&buffer[at..])
}

fn write_bool(out: &mut impl Write, key: &[u8], value: bool) -> io::Result<()> {
    out.write_all(key)?;
    out.write_all(if value { b"true" } else { b"false" })
}

/// Reads motions from an inter-file, one per non-blank line, streaming.
pub fn read_jsonl<R: BufRead>(reader: R) -> JsonlReader<R> {
    JsonlReader { reader, line: 0, buffer: String::new(), failed: false }
}

/// The iterator returned by [`read_jsonl`]; stops after the first error.
#[derive(Debug)]
pub struct JsonlReader<R> {
    reader: R,
    line: usize,
    buffer: String,
    failed: bool,
}

impl<R: BufRead> JsonlReader<R> {
    /// The next motion, skipping blank lines; `Ok(None)` at the end.
    fn read_motion(&mut self) -> Result<Option<Motion>, InterFileError> {
        loop {
            self.buffer.clear();
            self.line += 1;
            let line = self.line;
            let read = read_bounded_line(&mut self.reader, &mut self.buffer);
            if !read.map_err(|source| Located::at_line(line, InterFileErrorKind::Io(source)))? {
                return Ok(None);
            }
            if !self.buffer.trim().is_empty() {
                return parse_line(&self.buffer, line).map(Some);
            }
        }
    }
}

biscara_text::record_reader!(JsonlReader, Motion, InterFileError, read_motion, failed);

fn parse_line(text: &str, line: usize) -> Result<Motion, InterFileError> {
    let mut motion: Motion = serde_json::from_str(text).map_err(|err| {
        let message = strip_position(&err.to_string());
        match err.column() {
            // Errors found after the whole object was read (a missing or misplaced key).
            0 => Located::at_line(line, InterFileErrorKind::Invalid(message)),
            column => Located::at(line, column, InterFileErrorKind::Syntax(message)),
        }
    })?;
    let invalid = |message: String| Located::at_line(line, InterFileErrorKind::Invalid(message));
    let finite = |values: &[f64]| values.iter().all(|value| value.is_finite());
    match motion.kind {
        MotionKind::Rapid { end }
        | MotionKind::Linear { end, .. }
        | MotionKind::Arc { end, .. }
            if !finite(&end) =>
        {
            return Err(invalid("\"end\" holds a number that is not finite".to_owned()));
        }
        MotionKind::Arc { center, .. } if !finite(&center) => {
            return Err(invalid("\"center\" holds a number that is not finite".to_owned()));
        }
        MotionKind::Arc { turns: 0, .. } => {
            return Err(invalid("\"turns\" must be at least 1".to_owned()));
        }
        MotionKind::Dwell { seconds } if !(seconds.is_finite() && seconds >= 0.0) => {
            return Err(invalid(format!("\"seconds\" must be a finite number ≥ 0, got {seconds}")));
        }
        MotionKind::LaserOn { power, .. } if !(power.is_finite() && power >= 0.0) => {
            return Err(invalid(format!("\"power\" must be a finite number ≥ 0, got {power}")));
        }
        MotionKind::SpindleOn { rpm, .. } if !(rpm.is_finite() && rpm >= 0.0) => {
            return Err(invalid(format!("\"rpm\" must be a finite number ≥ 0, got {rpm}")));
        }
        _ => {}
    }
    if let Some(extrude) = motion.extrude.filter(|extrude| !extrude.is_finite()) {
        return Err(invalid(format!("\"extrude\" must be a finite number, got {extrude}")));
    }
    if let Some(blend) = motion.blend.filter(|blend| !(blend.is_finite() && *blend >= 0.0)) {
        return Err(invalid(format!("\"blend\" must be a finite number ≥ 0, got {blend}")));
    }
    if let Some(q) = motion.naive_cam.filter(|q| !(q.is_finite() && *q > 0.0)) {
        return Err(invalid(format!("\"naive_cam\" must be a finite number > 0, got {q}")));
    }
    if let MotionKind::Linear { feed, .. } | MotionKind::Arc { feed, .. } = motion.kind
        && !(feed.mm_per_min.is_finite() && feed.mm_per_min > 0.0)
    {
        return Err(invalid(format!("\"feed\" must be positive, got {}", feed.mm_per_min)));
    }
    if motion.line == 0 {
        motion.line = line;
    }
    Ok(motion)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{CodeName, Feed, Plane};

    #[test]
    fn motions_are_written_in_order_until_the_first_error() {
        let motion = |line| Motion::new(line, MotionKind::Rapid { end: [0.0, 300.0, 10.0, 0.0] });
        let mut out = Vec::new();
        write_motions::<io::Error>(&mut out, [Ok(motion(1)), Ok(motion(2))]).unwrap();
        let mut expected = Vec::new();
        write_jsonl(&mut expected, &motion(1)).unwrap();
        write_jsonl(&mut expected, &motion(2)).unwrap();
        assert_eq!(out, expected);
        let failing = [Ok(motion(1)), Err(io::Error::other("line 2")), Ok(motion(3))];
        let mut out = Vec::new();
        assert_eq!(write_motions(&mut out, failing).unwrap_err().to_string(), "line 2");
    }

    fn round_trip(motion: Motion) -> String {
        let mut text = Vec::new();
        write_jsonl(&mut text, &motion).unwrap();
        let text = String::from_utf8(text).unwrap();
        let back: Vec<Motion> = read_jsonl(text.as_bytes()).collect::<Result<_, _>>().unwrap();
        assert_eq!(back, [motion]);
        text
    }

    #[test]
    fn every_kind_has_the_spec_form() {
        let feed = Feed { mm_per_min: 1200.0, inverse_time: false };
        let cases = [
            (
                MotionKind::Rapid { end: [0.0, 400.0, 100.0, 0.0] },
                r#"{"line":3,"kind":"rapid","end":[0.0,400.0,100.0,0.0]}"#,
            ),
            (
                MotionKind::Linear {
                    end: [150.0, 320.0, 10.0, 30.0],
                    feed: Feed { mm_per_min: 3000.0, inverse_time: false },
                },
                r#"{"line":3,"kind":"linear","end":[150.0,320.0,10.0,30.0],"feed":3000.0}"#,
            ),
            (
                MotionKind::Linear {
                    end: [1.0, 2.0, 3.0, 4.0],
                    feed: Feed { mm_per_min: 60.0, inverse_time: true },
                },
                r#"{"line":3,"kind":"linear","end":[1.0,2.0,3.0,4.0],"feed":60.0,"inverse_time":true}"#,
            ),
            (
                MotionKind::Arc {
                    end: [1.0, 2.0, 3.0, 4.0],
                    center: [5.0, 6.0],
                    plane: Plane::Xy,
                    clockwise: true,
                    turns: 1,
                    feed,
                },
                r#"{"line":3,"kind":"arc","end":[1.0,2.0,3.0,4.0],"center":[5.0,6.0],"plane":"xy","clockwise":true,"turns":1,"feed":1200.0}"#,
            ),
            (MotionKind::Dwell { seconds: 0.3 }, r#"{"line":3,"kind":"dwell","seconds":0.3}"#),
            (MotionKind::Pick, r#"{"line":3,"kind":"pick"}"#),
            (MotionKind::Place, r#"{"line":3,"kind":"place"}"#),
            (MotionKind::GripperOff, r#"{"line":3,"kind":"gripper_off"}"#),
            (MotionKind::Pause, r#"{"line":3,"kind":"pause"}"#),
            (MotionKind::End, r#"{"line":3,"kind":"end"}"#),
            (
                MotionKind::LaserOn { power: 300.0, dynamic: true },
                r#"{"line":3,"kind":"laser_on","power":300.0,"dynamic":true}"#,
            ),
            (MotionKind::LaserOff, r#"{"line":3,"kind":"laser_off"}"#),
            (
                MotionKind::SpindleOn { rpm: 12000.0, clockwise: false },
                r#"{"line":3,"kind":"spindle_on","clockwise":false,"rpm":12000.0}"#,
            ),
            (MotionKind::SpindleOff, r#"{"line":3,"kind":"spindle_off"}"#),
            (MotionKind::PenDown, r#"{"line":3,"kind":"pen_down"}"#),
            (MotionKind::PenUp, r#"{"line":3,"kind":"pen_up"}"#),
            (
                MotionKind::Code { code: CodeName::new("M104").unwrap() },
                r#"{"line":3,"kind":"code","code":"M104"}"#,
            ),
        ];
        for (kind, expected) in cases {
            assert_eq!(round_trip(Motion::new(3, kind)).trim_end(), expected);
        }
    }

    #[test]
    fn moves_carry_their_extrusion() {
        let feed = Feed { mm_per_min: 1800.0, inverse_time: false };
        let linear = Motion {
            line: 7,
            kind: MotionKind::Linear { end: [1.0, 2.0, 3.0, 0.0], feed },
            extrude: Some(0.5),
            blend: None,
            naive_cam: None,
        };
        assert_eq!(
            round_trip(linear).trim_end(),
            r#"{"line":7,"kind":"linear","end":[1.0,2.0,3.0,0.0],"feed":1800.0,"extrude":0.5}"#
        );
        let retract = Motion {
            line: 8,
            kind: MotionKind::Rapid { end: [0.0; 4] },
            extrude: Some(-2.0),
            blend: None,
            naive_cam: None,
        };
        assert!(round_trip(retract).contains(r#""extrude":-2.0"#));
    }

    #[test]
    fn moves_carry_their_blend_tolerance() {
        let feed = Feed { mm_per_min: 600.0, inverse_time: false };
        let kinds = [
            MotionKind::Rapid { end: [1.0, 2.0, 3.0, 0.0] },
            MotionKind::Linear { end: [1.0, 2.0, 3.0, 0.0], feed },
            MotionKind::Arc {
                end: [1.0, 2.0, 3.0, 0.0],
                center: [0.0, 0.0],
                plane: Plane::Xy,
                clockwise: false,
                turns: 1,
                feed,
            },
        ];
        for kind in kinds {
            let motion = Motion { blend: Some(0.05), ..Motion::new(4, kind) };
            assert!(round_trip(motion).trim_end().ends_with(r#","blend":0.05}"#));
            let no_tolerance = Motion { blend: Some(0.0), ..Motion::new(4, kind) };
            assert!(round_trip(no_tolerance).contains(r#""blend":0.0"#));
            assert!(!round_trip(Motion::new(4, kind)).contains("blend"));
        }
    }

    #[test]
    fn straight_feed_moves_carry_their_naive_cam_tolerance() {
        let feed = Feed { mm_per_min: 600.0, inverse_time: false };
        let linear = MotionKind::Linear { end: [1.0, 2.0, 3.0, 0.0], feed };
        let motion = Motion { blend: Some(0.0), naive_cam: Some(0.05), ..Motion::new(4, linear) };
        assert!(round_trip(motion).trim_end().ends_with(r#","blend":0.0,"naive_cam":0.05}"#));
        assert!(!round_trip(Motion::new(4, linear)).contains("naive_cam"));
        check_error(
            "{\"line\":1,\"kind\":\"rapid\",\"end\":[0,0,0,0],\"naive_cam\":0.1}",
            "1: field `naive_cam` does not belong to a rapid motion",
        );
        check_error(
            "{\"line\":1,\"kind\":\"linear\",\"end\":[0,0,0,0],\"feed\":1,\"naive_cam\":0}",
            "1: \"naive_cam\" must be a finite number > 0, got 0",
        );
    }

    #[track_caller]
    fn check_error(text: &str, expected: &str) {
        let results: Vec<_> = read_jsonl(text.as_bytes()).collect();
        let err = results.into_iter().find_map(Result::err).expect("an error");
        assert_eq!(err.to_string(), expected);
    }

    #[test]
    fn bad_lines_are_reported_with_their_position() {
        check_error(
            "\n{\"line\":1,\"kind\":\"fly\"}\n",
            "2:22: unknown variant `fly`, expected one of `rapid`, `linear`, `arc`, `dwell`, `pick`, `place`, `gripper_off`, `pause`, `end`, `laser_on`, `laser_off`, `spindle_on`, `spindle_off`, `pen_down`, `pen_up`, `code`",
        );
        check_error("{\"line\":1,\"kind\":\"rapid\"}", "1: missing field `end` for a rapid motion");
        check_error(
            "{\"line\":1,\"kind\":\"rapid\",\"end\":[1,2,3]}",
            "1:38: invalid length 3, expected an array of length 4",
        );
        check_error(
            "{\"line\":1,\"kind\":\"dwell\",\"seconds\":-1}",
            "1: \"seconds\" must be a finite number ≥ 0, got -1",
        );
        check_error(
            "{\"line\":1,\"kind\":\"linear\",\"end\":[0,0,0,0],\"feed\":0}",
            "1: \"feed\" must be positive, got 0",
        );
        check_error(
            "{\"line\":1,\"kind\":\"pick\",\"extra\":1}",
            "1:31: unknown field `extra`, expected one of `line`, `kind`, `end`, `center`, `plane`, `clockwise`, `turns`, `feed`, `inverse_time`, `seconds`, `extrude`, `blend`, `naive_cam`, `power`, `dynamic`, `rpm`, `code`",
        );
        check_error(
            "{\"line\":1,\"kind\":\"pick\",\"extrude\":1}",
            "1: field `extrude` does not belong to a pick motion",
        );
        check_error(
            "{\"line\":1,\"kind\":\"rapid\",\"end\":[0,0,0,0],\"extrude\":\"a\"}",
            "1:54: invalid type: string \"a\", expected f64",
        );
        check_error(
            "{\"line\":1,\"kind\":\"laser_on\"}",
            "1: missing field `power` for a laser_on motion",
        );
        check_error(
            "{\"line\":1,\"kind\":\"laser_on\",\"power\":-5}",
            "1: \"power\" must be a finite number ≥ 0, got -5",
        );
        check_error(
            "{\"line\":1,\"kind\":\"spindle_on\",\"rpm\":-1}",
            "1: \"rpm\" must be a finite number ≥ 0, got -1",
        );
        check_error(
            "{\"line\":1,\"kind\":\"laser_off\",\"power\":5}",
            "1: field `power` does not belong to a laser_off motion",
        );
        check_error("{\"line\":1,\"kind\":\"code\"}", "1: missing field `code` for a code motion");
        check_error(
            "{\"line\":1,\"kind\":\"code\",\"code\":\"M 104\"}",
            "1: \"code\" must be 1 to 31 printable ASCII characters without spaces, got \"M 104\"",
        );
        check_error(
            "{\"line\":1,\"kind\":\"code\",\"code\":\"M104\",\"end\":[0,0,0,0]}",
            "1: field `end` does not belong to a code motion",
        );
        check_error(
            "{\"line\":1,\"kind\":\"rapid\",\"end\":[0,0,0,0],\"blend\":-0.1}",
            "1: \"blend\" must be a finite number ≥ 0, got -0.1",
        );
        check_error(
            "{\"line\":1,\"kind\":\"dwell\",\"seconds\":1,\"blend\":0.1}",
            "1: field `blend` does not belong to a dwell motion",
        );
        check_error("not json", "1:2: expected ident");
    }

    #[test]
    fn reading_stops_after_the_first_error() {
        let text = "{\"line\":1,\"kind\":\"pick\"}\nbad\n{\"line\":3,\"kind\":\"place\"}\n";
        let results: Vec<_> = read_jsonl(text.as_bytes()).collect();
        assert_eq!(results.len(), 2);
        assert!(results[1].is_err());
    }

    mod writer {
        use proptest::prelude::*;

        use super::*;

        /// Any number, with the ones serde_json writes as `null` and the ones with long forms.
        fn number() -> impl Strategy<Value = f64> {
            prop_oneof![
                any::<f64>(),
                (-1000i32..1000).prop_map(|value| f64::from(value) / 8.0),
                Just(f64::NAN),
                Just(f64::INFINITY),
                Just(-0.0),
                Just(1e300),
                Just(5e-324),
            ]
        }

        fn pose() -> impl Strategy<Value = [f64; 4]> {
            [number(), number(), number(), number()]
        }

        fn feed() -> impl Strategy<Value = Feed> {
            (number(), any::<bool>())
                .prop_map(|(mm_per_min, inverse_time)| Feed { mm_per_min, inverse_time })
        }

        fn kind() -> impl Strategy<Value = MotionKind> {
            let plane = prop_oneof![Just(Plane::Xy), Just(Plane::Xz), Just(Plane::Yz)];
            prop_oneof![
                pose().prop_map(|end| MotionKind::Rapid { end }),
                (pose(), feed()).prop_map(|(end, feed)| MotionKind::Linear { end, feed }),
                (pose(), [number(), number()], plane, any::<bool>(), any::<u32>(), feed())
                    .prop_map(|(end, center, plane, clockwise, turns, feed)| {
                        MotionKind::Arc { end, center, plane, clockwise, turns, feed }
                    }),
                number().prop_map(|seconds| MotionKind::Dwell { seconds }),
                Just(MotionKind::Pick),
                Just(MotionKind::Place),
                Just(MotionKind::GripperOff),
                Just(MotionKind::Pause),
                Just(MotionKind::End),
                (number(), any::<bool>())
                    .prop_map(|(power, dynamic)| MotionKind::LaserOn { power, dynamic }),
                Just(MotionKind::LaserOff),
                (number(), any::<bool>())
                    .prop_map(|(rpm, clockwise)| MotionKind::SpindleOn { rpm, clockwise }),
                Just(MotionKind::SpindleOff),
                Just(MotionKind::PenDown),
                Just(MotionKind::PenUp),
                // Printable ASCII, quotes and backslashes included.
                "[!-~]{1,15}".prop_map(|name| MotionKind::Code {
                    code: CodeName::new(&name).expect("a code name"),
                }),
            ]
        }

        /// Numbers of at most three decimals, and their neighbours (which are not).
        fn decimal() -> impl Strategy<Value = f64> {
            (-999_999_999_999i64..=999_999_999_999, 0..4i32, -2i64..=2).prop_map(
                |(digits, places, ulps)| {
                    let value = digits as f64 / 10f64.powi(places);
                    f64::from_bits(value.to_bits().wrapping_add_signed(ulps))
                },
            )
        }

        proptest! {
            /// Numbers are written as serde_json writes them: short decimals by the fast path,
            /// the others by serde_json's formatter.
            #[test]
            fn numbers_are_written_as_serde_json_writes_them(
                value in prop_oneof![decimal(), number(), -1e10..1e10f64],
            ) {
                let mut written = Vec::new();
                write_f64(&mut written, value).unwrap();
                let expected = serde_json::to_vec(&value).unwrap();
                prop_assert_eq!(String::from_utf8(written), String::from_utf8(expected));
            }

            /// The hand-written writer gives serde_json's bytes for every motion.
            #[test]
            fn writes_what_serde_json_writes(
                line in any::<usize>(),
                kind in kind(),
                extrude in proptest::option::of(number()),
                blend in proptest::option::of(number()),
                naive_cam in proptest::option::of(number()),
            ) {
                let motion = Motion { line, kind, extrude, blend, naive_cam };
                let mut written = Vec::new();
                write_jsonl(&mut written, &motion).unwrap();
                let mut expected = serde_json::to_vec(&motion).unwrap();
                expected.push(b'\n');
                prop_assert_eq!(String::from_utf8(written), String::from_utf8(expected));
            }
        }
    }
}
