//! The motion types.

use serde::{Deserialize, Serialize};

/// One entry of a program: a move or an event, with the 1-based line of the block that made it.
///
/// Its file form is one flat JSON object (docs/motion.md); see [`crate::write_jsonl`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(into = "Record", try_from = "Record")]
pub struct Motion {
    /// 1-based line of the G-code file (or inter-file entry) this motion comes from.
    pub line: usize,
    /// What to do.
    pub kind: MotionKind,
    /// Filament the extruder feeds during this move, millimetres (negative: a retraction);
    /// `None` when the block had no E word. Only moves carry it (docs/motion.md).
    pub extrude: Option<f64>,
    /// The path-control mode the move was programmed under (docs/motion.md): `Some(p)` under
    /// G64, the corner at the move's end may be blended within `p` millimetres of it (`p = 0`: G64 with
    /// no P, the canon's "no tolerance given"); `None` under G61/G61.1, an exact stop. Only moves
    /// carry it.
    pub blend: Option<f64>,
    /// G64 Q, LinuxCNC's naive-CAM tolerance, mm: `Some(q)` on a straight feed move (G1)
    /// programmed under G64 with a positive Q, which may be merged with the G1 moves around it
    /// while every end point left out lies within `q` of the merged move (`biscara-blend`'s
    /// `NaiveCam`); `None` otherwise.
    pub naive_cam: Option<f64>,
}

impl Motion {
    /// A motion with no extrusion, under exact stop.
    pub fn new(line: usize, kind: MotionKind) -> Motion {
        Motion { line, kind, extrude: None, blend: None, naive_cam: None }
    }
}

/// The name of a code with no motion that a dialect accepts (`M104`, `G29`, `$H`): printable
/// ASCII, 1 to [`CodeName::MAX`] bytes, stored inline so that motions stay `Copy`.
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct CodeName {
    bytes: [u8; CodeName::MAX],
    len: u8,
}

impl CodeName {
    /// The longest name, bytes.
    pub const MAX: usize = 31;

    /// `name` as a code name; `None` when it is empty, longer than [`CodeName::MAX`] bytes or
    /// holds anything but printable ASCII without spaces.
    pub fn new(name: &str) -> Option<CodeName> {
        let bytes = name.as_bytes();
        if bytes.is_empty()
            || bytes.len() > CodeName::MAX
            || !bytes.iter().all(u8::is_ascii_graphic)
        {
            return None;
        }
        let mut stored = [0; CodeName::MAX];
        stored[..bytes.len()].copy_from_slice(bytes);
        Some(CodeName { bytes: stored, len: bytes.len() as u8 })
    }

    /// The name.
    pub fn as_str(&self) -> &str {
        // Only printable ASCII is ever stored.
        std::str::from_utf8(&self.bytes[..usize::from(self.len)]).unwrap_or("?")
    }
}

impl std::fmt::Debug for CodeName {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{:?}", self.as_str())
    }
}

impl std::fmt::Display for CodeName {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// The plane of an arc, with its axes in LinuxCNC's canonical order `(first, second)` and the
/// normal `first × second`: `xy` → (X, Y) about +Z, `xz` → (Z, X) about +Y, `yz` → (Y, Z) about +X.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Plane {
    /// G17: the XY plane; centre `[x, y]`; helical along Z.
    Xy,
    /// G18: the XZ plane; centre `[z, x]`; helical along Y.
    Xz,
    /// G19: the YZ plane; centre `[y, z]`; helical along X.
    Yz,
}

impl Plane {
    /// Indices into `[x, y, z]` of the plane's first axis, second axis and normal axis.
    pub fn axes(self) -> [usize; 3] {
        match self {
            Plane::Xy => [0, 1, 2],
            Plane::Xz => [2, 0, 1],
            Plane::Yz => [1, 2, 0],
        }
    }
}

/// A feed rate, always in mm/min along the XYZ path (degrees/min of C for a move with no XYZ
/// length, LinuxCNC's rule).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Feed {
    /// Millimetres (or degrees) per minute.
    pub mm_per_min: f64,
    /// Whether the program gave it in G93 inverse-time mode (converted to the equivalent mm/min).
    pub inverse_time: bool,
}

/// What one motion does.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum MotionKind {
    /// G0: move to `end` at the rapid limits.
    Rapid {
        /// End pose `[x, y, z, c]`, mm and degrees.
        end: [f64; 4],
    },
    /// G1: straight move to `end` at `feed`.
    Linear {
        /// End pose `[x, y, z, c]`, mm and degrees.
        end: [f64; 4],
        /// Feed rate.
        feed: Feed,
    },
    /// G2/G3: circular or helical move to `end` about `center` in `plane`.
    Arc {
        /// End pose `[x, y, z, c]`, mm and degrees.
        end: [f64; 4],
        /// Centre in the plane's axes (see [`Plane`]), mm.
        center: [f64; 2],
        /// The plane.
        plane: Plane,
        /// G2 (true) or G3 (false): clockwise seen from the plane's positive normal.
        clockwise: bool,
        /// The P word: 1 ends at the first pass through `end`, each more adds a full turn.
        turns: u32,
        /// Feed rate.
        feed: Feed,
    },
    /// G4: hold the pose.
    Dwell {
        /// Seconds.
        seconds: f64,
    },
    /// M3: close the gripper (grip).
    Pick,
    /// M4: open the gripper (release).
    Place,
    /// M5: gripper off.
    GripperOff,
    /// M0, M1 or M60: a program pause.
    Pause,
    /// M2 or M30: end of program.
    End,
    /// A laser tool switched on (M3: constant power; M4: dynamic power, Grbl's laser mode), or
    /// its power changed while on (an S word). Takes no time.
    LaserOn {
        /// The S value: power, 0 … the tool's maximum.
        power: f64,
        /// M4: power scaled with the actual speed (Grbl laser mode).
        dynamic: bool,
    },
    /// A laser tool switched off (M5). Takes no time.
    LaserOff,
    /// A spindle switched on (M3 clockwise, M4 counter-clockwise), or its speed changed while
    /// on. Takes no time.
    SpindleOn {
        /// The S value, revolutions per minute.
        rpm: f64,
        /// M3 (true) or M4 (false).
        clockwise: bool,
    },
    /// A spindle switched off (M5). Takes no time.
    SpindleOff,
    /// A pen put down on the paper (M3 or M4). Takes no time.
    PenDown,
    /// A pen lifted (M5). Takes no time.
    PenUp,
    /// A code with no motion that the program's dialect accepts (a temperature, fan, progress
    /// or settings code, a Grbl `$` line, …): recorded, not acted on. Takes no time. A probe
    /// code (`G38.2`) marks the probe move that follows it.
    Code {
        /// The code as the program wrote it, upper case (`M104`, `G29`, `$H`).
        code: CodeName,
    },
}

impl MotionKind {
    /// The end pose of a move; `None` for events.
    pub fn end(&self) -> Option<[f64; 4]> {
        match *self {
            MotionKind::Rapid { end }
            | MotionKind::Linear { end, .. }
            | MotionKind::Arc { end, .. } => Some(end),
            _ => None,
        }
    }

    /// The `kind` string of the file form.
    pub fn name(&self) -> &'static str {
        self.tag().name()
    }

    fn tag(&self) -> Tag {
        match self {
            MotionKind::Rapid { .. } => Tag::Rapid,
            MotionKind::Linear { .. } => Tag::Linear,
            MotionKind::Arc { .. } => Tag::Arc,
            MotionKind::Dwell { .. } => Tag::Dwell,
            MotionKind::Pick => Tag::Pick,
            MotionKind::Place => Tag::Place,
            MotionKind::GripperOff => Tag::GripperOff,
            MotionKind::Pause => Tag::Pause,
            MotionKind::End => Tag::End,
            MotionKind::LaserOn { .. } => Tag::LaserOn,
            MotionKind::LaserOff => Tag::LaserOff,
            MotionKind::SpindleOn { .. } => Tag::SpindleOn,
            MotionKind::SpindleOff => Tag::SpindleOff,
            MotionKind::PenDown => Tag::PenDown,
            MotionKind::PenUp => Tag::PenUp,
            MotionKind::Code { .. } => Tag::Code,
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
enum Tag {
    Rapid,
    Linear,
    Arc,
    Dwell,
    Pick,
    Place,
    GripperOff,
    Pause,
    End,
    LaserOn,
    LaserOff,
    SpindleOn,
    SpindleOff,
    PenDown,
    PenUp,
    Code,
}

impl Tag {
    fn name(self) -> &'static str {
        match self {
            Tag::Rapid => "rapid",
            Tag::Linear => "linear",
            Tag::Arc => "arc",
            Tag::Dwell => "dwell",
            Tag::Pick => "pick",
            Tag::Place => "place",
            Tag::GripperOff => "gripper_off",
            Tag::Pause => "pause",
            Tag::End => "end",
            Tag::LaserOn => "laser_on",
            Tag::LaserOff => "laser_off",
            Tag::SpindleOn => "spindle_on",
            Tag::SpindleOff => "spindle_off",
            Tag::PenDown => "pen_down",
            Tag::PenUp => "pen_up",
            Tag::Code => "code",
        }
    }
}

/// The flat file form of a motion: every key any kind may have, in the order they are written.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct Record {
    line: usize,
    kind: Tag,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    end: Option<[f64; 4]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    center: Option<[f64; 2]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    plane: Option<Plane>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    clockwise: Option<bool>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    turns: Option<u32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    feed: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    inverse_time: Option<bool>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    seconds: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    extrude: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    blend: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    naive_cam: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    power: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    dynamic: Option<bool>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    rpm: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    code: Option<String>,
}

impl From<Motion> for Record {
    fn from(motion: Motion) -> Record {
        let mut record = Record {
            line: motion.line,
            kind: motion.kind.tag(),
            end: motion.kind.end(),
            center: None,
            plane: None,
            clockwise: None,
            turns: None,
            feed: None,
            inverse_time: None,
            seconds: None,
            extrude: motion.extrude,
            blend: motion.blend,
            naive_cam: motion.naive_cam,
            power: None,
            dynamic: None,
            rpm: None,
            code: None,
        };
        match motion.kind {
            MotionKind::Linear { feed, .. } => record.set_feed(feed),
            MotionKind::Arc { center, plane, clockwise, turns, feed, .. } => {
                record.center = Some(center);
                record.plane = Some(plane);
                record.clockwise = Some(clockwise);
                record.turns = Some(turns);
                record.set_feed(feed);
            }
            MotionKind::Dwell { seconds } => record.seconds = Some(seconds),
            MotionKind::LaserOn { power, dynamic } => {
                record.power = Some(power);
                record.dynamic = Some(dynamic);
            }
            MotionKind::SpindleOn { rpm, clockwise } => {
                record.rpm = Some(rpm);
                record.clockwise = Some(clockwise);
            }
            MotionKind::Code { code } => record.code = Some(code.as_str().to_owned()),
            _ => {}
        }
        record
    }
}

impl Record {
    fn set_feed(&mut self, feed: Feed) {
        self.feed = Some(feed.mm_per_min);
        self.inverse_time = feed.inverse_time.then_some(true);
    }
}

impl TryFrom<Record> for Motion {
    type Error = String;

    fn try_from(record: Record) -> Result<Motion, String> {
        let kind_name = record.kind.name();
        let missing = |key: &str| format!("missing field `{key}` for a {kind_name} motion");
        let mut used = vec!["line", "kind"];
        let mut take = |key: &'static str| used.push(key);
        let kind = match record.kind {
            Tag::Rapid => {
                take("end");
                take("extrude");
                take("blend");
                MotionKind::Rapid { end: record.end.ok_or_else(|| missing("end"))? }
            }
            Tag::Linear => {
                take("end");
                take("extrude");
                take("feed");
                take("inverse_time");
                take("blend");
                take("naive_cam");
                MotionKind::Linear {
                    end: record.end.ok_or_else(|| missing("end"))?,
                    feed: Feed {
                        mm_per_min: record.feed.ok_or_else(|| missing("feed"))?,
                        inverse_time: record.inverse_time.unwrap_or(false),
                    },
                }
            }
            Tag::Arc => {
                for key in [
                    "end",
                    "center",
                    "plane",
                    "clockwise",
                    "turns",
                    "feed",
                    "inverse_time",
                    "extrude",
                    "blend",
                ] {
                    take(key);
                }
                MotionKind::Arc {
                    end: record.end.ok_or_else(|| missing("end"))?,
                    center: record.center.ok_or_else(|| missing("center"))?,
                    plane: record.plane.ok_or_else(|| missing("plane"))?,
                    clockwise: record.clockwise.ok_or_else(|| missing("clockwise"))?,
                    turns: record.turns.unwrap_or(1),
                    feed: Feed {
                        mm_per_min: record.feed.ok_or_else(|| missing("feed"))?,
                        inverse_time: record.inverse_time.unwrap_or(false),
                    },
                }
            }
            Tag::Dwell => {
                take("seconds");
                MotionKind::Dwell { seconds: record.seconds.ok_or_else(|| missing("seconds"))? }
            }
            Tag::Pick => MotionKind::Pick,
            Tag::Place => MotionKind::Place,
            Tag::GripperOff => MotionKind::GripperOff,
            Tag::Pause => MotionKind::Pause,
            Tag::End => MotionKind::End,
            Tag::LaserOn => {
                take("power");
                take("dynamic");
                MotionKind::LaserOn {
                    power: record.power.ok_or_else(|| missing("power"))?,
                    dynamic: record.dynamic.unwrap_or(false),
                }
            }
            Tag::LaserOff => MotionKind::LaserOff,
            Tag::SpindleOn => {
                take("rpm");
                take("clockwise");
                MotionKind::SpindleOn {
                    rpm: record.rpm.ok_or_else(|| missing("rpm"))?,
                    clockwise: record.clockwise.unwrap_or(true),
                }
            }
            Tag::SpindleOff => MotionKind::SpindleOff,
            Tag::PenDown => MotionKind::PenDown,
            Tag::PenUp => MotionKind::PenUp,
            Tag::Code => {
                take("code");
                let name = record.code.as_deref().ok_or_else(|| missing("code"))?;
                let code = CodeName::new(name).ok_or_else(|| {
                    format!(
                        "\"code\" must be 1 to {} printable ASCII characters without spaces, got \
                         {name:?}",
                        CodeName::MAX
                    )
                })?;
                MotionKind::Code { code }
            }
        };
        let present = [
            ("end", record.end.is_some()),
            ("center", record.center.is_some()),
            ("plane", record.plane.is_some()),
            ("clockwise", record.clockwise.is_some()),
            ("turns", record.turns.is_some()),
            ("feed", record.feed.is_some()),
            ("inverse_time", record.inverse_time.is_some()),
            ("seconds", record.seconds.is_some()),
            ("extrude", record.extrude.is_some()),
            ("blend", record.blend.is_some()),
            ("naive_cam", record.naive_cam.is_some()),
            ("power", record.power.is_some()),
            ("dynamic", record.dynamic.is_some()),
            ("rpm", record.rpm.is_some()),
            ("code", record.code.is_some()),
        ];
        if let Some((key, _)) = present.iter().find(|(key, here)| *here && !used.contains(key)) {
            return Err(format!("field `{key}` does not belong to a {kind_name} motion"));
        }
        Ok(Motion {
            line: record.line,
            kind,
            extrude: record.extrude,
            blend: record.blend,
            naive_cam: record.naive_cam,
        })
    }
}
