//! The robot description, `robot.json` (docs/kinematics.md): reading, validation, defaults.

use serde::{Deserialize, Serialize};

use crate::{AssemblyMode, DynamicsSpec, Meshes, Motors, WorkingMode};

/// A robot as described by `robot.json`, in the file's units: millimetres and degrees
/// (velocities per second, accelerations per second squared).
///
/// Every key is optional: a missing key takes the default robot's value. An unknown key is an
/// error, so that a typo never falls back silently to a default. Build one with
/// [`Robot::from_json`] (which validates) or from [`Robot::default`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Robot {
    /// A free-form name, shown in reports.
    pub name: String,
    /// Link lengths of the five-bar.
    #[serde(deserialize_with = "crate::object::object")]
    pub links: Links,
    /// Positions of the two actuated base joints on the X axis.
    #[serde(deserialize_with = "crate::object::object")]
    pub base: Base,
    /// Length of the prismatic axis, millimetres: `d4 = lp − z`.
    pub lp: f64,
    /// The working mode the robot runs in (`"+-"` by default).
    pub working_mode: WorkingMode,
    /// The assembly mode the robot is built in (`"+"` by default).
    pub assembly_mode: AssemblyMode,
    /// Position limits of the four joints, `[min, max]`.
    #[serde(deserialize_with = "crate::object::object")]
    pub joint_limits: JointLimits,
    /// Velocity limits of the four joints, degrees per second (θ) and mm/s (d4).
    #[serde(deserialize_with = "crate::object::object")]
    pub joint_max_velocity: JointValues,
    /// Acceleration limits of the four joints, degrees/s² (θ) and mm/s² (d4).
    #[serde(deserialize_with = "crate::object::object")]
    pub joint_max_acceleration: JointValues,
    /// Cartesian motion limits used by the interpolator.
    #[serde(deserialize_with = "crate::object::object")]
    pub motion: MotionLimits,
    /// Angle, degrees, below which a pose counts as near a singularity.
    pub singularity_margin: f64,
    /// Body dimensions used by the virtual robot (collisions, pictures).
    #[serde(deserialize_with = "crate::object::object")]
    pub geometry: Geometry,
    /// The end effector (docs/motion.md): what the program's M3, M4, M5, S and E words drive.
    #[serde(deserialize_with = "crate::object::object")]
    pub tool: ToolSpec,
    /// STL files drawn by the viewer in place of the parts' boxes and cylinders (none by default).
    #[serde(skip_serializing_if = "Meshes::is_empty")]
    #[serde(deserialize_with = "crate::object::object")]
    pub meshes: Meshes,
    /// The bodies' masses and inertias (docs/dynamics.md); absent: solid aluminium bodies of the
    /// `geometry`'s size.
    #[serde(skip_serializing_if = "Option::is_none")]
    #[serde(deserialize_with = "crate::object::optional_object")]
    pub dynamics: Option<DynamicsSpec>,
    /// The motors at the four joints (docs/dynamics.md); absent: torques are computed but bound
    /// nothing.
    #[serde(skip_serializing_if = "Option::is_none")]
    #[serde(deserialize_with = "crate::object::optional_object")]
    pub motors: Option<Motors>,
}

/// The end effector the robot carries (docs/motion.md).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ToolSpec {
    /// Its kind; absent (`None`): inferred from each program, the gripper when nothing tells.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub kind: Option<ToolKind>,
    /// A laser's full power: the S value of 100 % (Grbl's `$30`, 1000 by default).
    pub max_power: f64,
}

impl Default for ToolSpec {
    fn default() -> ToolSpec {
        ToolSpec { kind: None, max_power: 1000.0 }
    }
}

/// The kinds of end effector: the one tool kind every crate shares, named here as `robot.json`
/// has it (`tool.kind`).
pub use biscara_motion::Tool as ToolKind;

/// Link lengths of the five-bar, millimetres.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Links {
    /// Proximal (actuated) link length, millimetres.
    pub l1: f64,
    /// Distal link length, millimetres.
    pub l2: f64,
}

/// The actuated base joints at `(b1x, 0)` and `(b2x, 0)`, millimetres.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Base {
    /// X of chain 1's base joint, millimetres; must be greater than `b2x`.
    pub b1x: f64,
    /// X of chain 2's base joint, millimetres.
    pub b2x: f64,
}

/// `[min, max]` position limits: degrees for θ1–θ3, millimetres for d4.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct JointLimits {
    /// θ1 range, degrees.
    pub theta1: [f64; 2],
    /// θ2 range, degrees.
    pub theta2: [f64; 2],
    /// θ3 range, degrees.
    pub theta3: [f64; 2],
    /// d4 range, millimetres.
    pub d4: [f64; 2],
}

/// One positive value per joint: degrees-based for θ1–θ3, millimetre-based for d4.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JointValues {
    /// θ1 value (degrees per second or per second squared).
    pub theta1: f64,
    /// θ2 value (degrees per second or per second squared).
    pub theta2: f64,
    /// θ3 value (degrees per second or per second squared).
    pub theta3: f64,
    /// d4 value (millimetres per second or per second squared).
    pub d4: f64,
}

/// Cartesian motion limits.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct MotionLimits {
    /// Speed of G0 moves along the XYZ path, mm/s.
    pub rapid_velocity: f64,
    /// Speed of C during G0 moves (and the cap for every move), degrees/s.
    pub rapid_rotation: f64,
    /// Path acceleration of the trapezoid profile, mm/s².
    pub acceleration: f64,
    /// Acceleration of C, degrees/s².
    pub rotation_acceleration: f64,
}

/// Body dimensions of the virtual robot, millimetres.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Geometry {
    /// Width (diameter) of the link capsules.
    pub link_width: f64,
    /// Height of the links above the table.
    pub link_height: f64,
    /// Radius of the gripper cylinder.
    pub gripper_radius: f64,
    /// Length of the gripper cylinder, from the tool point up.
    pub gripper_length: f64,
}

impl Default for Robot {
    /// The robot of docs/kinematics.md: the paper's link lengths and Z stroke, our base, limits and
    /// geometry.
    fn default() -> Self {
        Robot {
            name: "BiSCARA 4-axis (FME Transactions 50, 2022)".to_owned(),
            links: Links::default(),
            base: Base::default(),
            lp: 100.0,
            working_mode: WorkingMode::default(),
            assembly_mode: AssemblyMode::default(),
            joint_limits: JointLimits::default(),
            joint_max_velocity: JointValues {
                theta1: 360.0,
                theta2: 360.0,
                theta3: 720.0,
                d4: 500.0,
            },
            joint_max_acceleration: JointValues {
                theta1: 7200.0,
                theta2: 7200.0,
                theta3: 14400.0,
                d4: 10000.0,
            },
            motion: MotionLimits::default(),
            singularity_margin: 5.0,
            geometry: Geometry::default(),
            tool: ToolSpec::default(),
            meshes: Meshes::default(),
            dynamics: None,
            motors: None,
        }
    }
}

impl Default for Links {
    fn default() -> Self {
        Links { l1: 210.0, l2: 270.0 }
    }
}

impl Default for Base {
    fn default() -> Self {
        Base { b1x: 100.0, b2x: -100.0 }
    }
}

impl Default for JointLimits {
    fn default() -> Self {
        JointLimits {
            theta1: [-135.0, 135.0],
            theta2: [-135.0, 135.0],
            theta3: [-180.0, 180.0],
            d4: [0.0, 100.0],
        }
    }
}

impl Default for MotionLimits {
    fn default() -> Self {
        MotionLimits {
            rapid_velocity: 500.0,
            rapid_rotation: 360.0,
            acceleration: 5000.0,
            rotation_acceleration: 7200.0,
        }
    }
}

impl Default for Geometry {
    fn default() -> Self {
        Geometry {
            link_width: 30.0,
            link_height: 250.0,
            gripper_radius: 20.0,
            gripper_length: 40.0,
        }
    }
}

/// A robot file that cannot be used.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum RobotError {
    /// Occurs when the text is not JSON, a value has the wrong type, a key is unknown or repeated,
    /// or a mode string is not one of the allowed ones.
    #[error("{}{}{message}", position_prefix(*.line, *.column), key_prefix(key))]
    Syntax {
        /// 1-based line of the error.
        line: usize,
        /// 1-based column of the error.
        column: usize,
        /// Dotted path of the offending key (`links.l1`), or `.` for the whole document.
        key: String,
        /// What is wrong.
        message: String,
    },
    /// Occurs when a value is well-formed but impossible: a non-positive length, `b1x ≤ b2x`, an
    /// empty limit range, a non-finite number, or a base too wide for the home pose to assemble.
    #[error("{}{key}: {message}", location_prefix(*.line, *.column))]
    Invalid {
        /// 1-based line of the key in the file, when the robot was read from one.
        line: Option<usize>,
        /// 1-based column of the key in the file, when the robot was read from one.
        column: Option<usize>,
        /// Dotted path of the offending key (`joint_limits.theta1`).
        key: String,
        /// What is wrong and what would be right.
        message: String,
    },
}

/// `LINE:COL: `, or `LINE: ` when serde_json knows no column (an error at the very end).
fn position_prefix(line: usize, column: usize) -> String {
    if column == 0 { format!("{line}: ") } else { format!("{line}:{column}: ") }
}

/// `key: `, or nothing for an error about the document as a whole (`.` or `?`).
fn key_prefix(key: &str) -> String {
    if key == "." || key == "?" || key.is_empty() { String::new() } else { format!("{key}: ") }
}

fn location_prefix(line: Option<usize>, column: Option<usize>) -> String {
    match (line, column) {
        (Some(line), Some(column)) => format!("{line}:{column}: "),
        _ => String::new(),
    }
}

impl RobotError {
    /// The dotted path of the key this error is about.
    pub fn key(&self) -> &str {
        match self {
            RobotError::Syntax { key, .. } | RobotError::Invalid { key, .. } => key,
        }
    }
}

impl Robot {
    /// Reads and validates a robot from the text of a `robot.json` file.
    ///
    /// Errors carry the 1-based line and column and the dotted key they are about.
    pub fn from_json(text: &str) -> Result<Robot, RobotError> {
        let syntax = |key: String, inner: serde_json::Error| RobotError::Syntax {
            line: inner.line(),
            column: inner.column(),
            key,
            message: biscara_text::strip_position(&inner.to_string()),
        };
        // A JSON array would deserialise as the struct's fields in order: only an object is a
        // robot file.
        let first = text.trim_start().chars().next();
        if first.is_some_and(|first| first != '{') {
            let offset = text.len() - text.trim_start().len();
            let line = text[..offset].matches('\n').count() + 1;
            let column = offset - text[..offset].rfind('\n').map_or(0, |newline| newline + 1) + 1;
            return Err(RobotError::Syntax {
                line,
                column,
                key: ".".to_owned(),
                message: "a robot file is one JSON object: `{ \"links\": …, … }`".to_owned(),
            });
        }
        let mut deserializer = serde_json::Deserializer::from_str(text);
        let robot: Robot = serde_path_to_error::deserialize(&mut deserializer)
            .map_err(|err| syntax(err.path().to_string(), err.into_inner()))?;
        deserializer.end().map_err(|inner| syntax(".".to_owned(), inner))?;
        robot.validate().map_err(|err| match err {
            RobotError::Invalid { key, message, .. } => {
                let (line, column) = locate_key(text, &key).unzip();
                RobotError::Invalid { line, column, key, message }
            }
            other => other,
        })?;
        Ok(robot)
    }

    /// The robot as pretty-printed JSON: a complete template to edit.
    pub fn to_json_pretty(&self) -> String {
        // Serialising plain numbers, strings and arrays cannot fail.
        serde_json::to_string_pretty(self).unwrap_or_default()
    }

    /// Checks that every value is possible; the error names the first offending key.
    pub fn validate(&self) -> Result<(), RobotError> {
        positive("links.l1", self.links.l1)?;
        positive("tool.max_power", self.tool.max_power)?;
        positive("links.l2", self.links.l2)?;
        finite("base.b1x", self.base.b1x)?;
        finite("base.b2x", self.base.b2x)?;
        if self.base.b1x <= self.base.b2x {
            return Err(invalid(
                "base.b1x",
                format!(
                    "must be greater than base.b2x (got b1x = {}, b2x = {}): chain 1's base joint \
                     lies on +X of chain 2's",
                    self.base.b1x, self.base.b2x
                ),
            ));
        }
        let base_width = self.base.b1x - self.base.b2x;
        if base_width >= 2.0 * self.links.l2 {
            return Err(invalid(
                "base",
                format!(
                    "the base joints are {base_width} mm apart, so the home pose (all joints 0) \
                     cannot close the loop: it needs b1x - b2x < 2*l2 = {}",
                    2.0 * self.links.l2
                ),
            ));
        }
        finite("lp", self.lp)?;
        let limits = &self.joint_limits;
        range("joint_limits.theta1", limits.theta1)?;
        range("joint_limits.theta2", limits.theta2)?;
        range("joint_limits.theta3", limits.theta3)?;
        range("joint_limits.d4", limits.d4)?;
        for (section, values) in [
            ("joint_max_velocity", &self.joint_max_velocity),
            ("joint_max_acceleration", &self.joint_max_acceleration),
        ] {
            positive(&format!("{section}.theta1"), values.theta1)?;
            positive(&format!("{section}.theta2"), values.theta2)?;
            positive(&format!("{section}.theta3"), values.theta3)?;
            positive(&format!("{section}.d4"), values.d4)?;
        }
        positive("motion.rapid_velocity", self.motion.rapid_velocity)?;
        positive("motion.rapid_rotation", self.motion.rapid_rotation)?;
        positive("motion.acceleration", self.motion.acceleration)?;
        positive("motion.rotation_acceleration", self.motion.rotation_acceleration)?;
        let margin = self.singularity_margin;
        if !(0.0..90.0).contains(&margin) {
            return Err(invalid(
                "singularity_margin",
                format!("must be at least 0 and below 90 degrees (got {margin})"),
            ));
        }
        positive("geometry.link_width", self.geometry.link_width)?;
        positive("geometry.link_height", self.geometry.link_height)?;
        positive("geometry.gripper_radius", self.geometry.gripper_radius)?;
        positive("geometry.gripper_length", self.geometry.gripper_length)?;
        for (part, mesh) in self.meshes.parts() {
            let key = format!("meshes.{part}");
            if mesh.file.trim().is_empty() {
                return Err(invalid(&key, "names no file: write the STL file's path".to_owned()));
            }
            positive(&format!("{key}.scale"), mesh.scale)?;
            for (name, values) in [("offset", mesh.offset), ("rotation", mesh.rotation)] {
                for value in values {
                    finite(&format!("{key}.{name}"), value)?;
                }
            }
        }
        if let Some(dynamics) = &self.dynamics {
            dynamics.validate(self.links.l1, self.links.l2)?;
        }
        if let Some(motors) = &self.motors {
            motors.validate()?;
        }
        Ok(())
    }
}

impl JointValues {
    /// The values as `[theta1, theta2, theta3, d4]`.
    pub fn to_array(self) -> [f64; 4] {
        [self.theta1, self.theta2, self.theta3, self.d4]
    }
}

impl JointLimits {
    /// The ranges as `[theta1, theta2, theta3, d4]`.
    pub fn to_array(self) -> [[f64; 2]; 4] {
        [self.theta1, self.theta2, self.theta3, self.d4]
    }
}

pub(crate) fn invalid(key: &str, message: String) -> RobotError {
    RobotError::Invalid { line: None, column: None, key: key.to_owned(), message }
}

pub(crate) fn finite(key: &str, value: f64) -> Result<(), RobotError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(invalid(key, format!("must be a finite number (got {value})")))
    }
}

fn positive(key: &str, value: f64) -> Result<(), RobotError> {
    finite(key, value)?;
    if value > 0.0 { Ok(()) } else { Err(invalid(key, format!("must be positive (got {value})"))) }
}

fn range(key: &str, [min, max]: [f64; 2]) -> Result<(), RobotError> {
    finite(key, min)?;
    finite(key, max)?;
    if min < max {
        Ok(())
    } else {
        Err(invalid(
            key,
            format!("the range [{min}, {max}] is empty: write [min, max] with min < max"),
        ))
    }
}

impl Robot {
    /// The 1-based line and column of the dotted key `a.b.c` in the text of a robot file (`None`
    /// when the key is not written): where a caller points the user at a value it found wrong
    /// later, such as a mesh file that cannot be read.
    pub fn locate_key(text: &str, dotted_key: &str) -> Option<(usize, usize)> {
        locate_key(text, dotted_key)
    }
}

/// Finds the 1-based line and column of the key `a.b.c` in a JSON text, by looking for each quoted
/// key (followed by a colon) after the previous one. Good enough to point a user at a valid file's
/// offending value; `None` when the key is not written (a default was used).
fn locate_key(text: &str, dotted_key: &str) -> Option<(usize, usize)> {
    let mut from = 0;
    for part in dotted_key.split('.') {
        let quoted = format!("\"{part}\"");
        let mut search = from;
        loop {
            let found = search + text[search..].find(&quoted)?;
            let after = found + quoted.len();
            if text[after..].trim_start().starts_with(':') {
                from = found;
                break;
            }
            search = after;
        }
    }
    let line_start = text[..from].rfind('\n').map_or(0, |index| index + 1);
    let line = text[..from].matches('\n').count() + 1;
    let column = text[line_start..from].chars().count() + 1;
    Some((line, column))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[track_caller]
    fn check_rejected(json: &str, key: &str, message_part: &str) {
        let err = Robot::from_json(json).expect_err("robot file must be rejected");
        assert_eq!(err.key(), key, "{err}");
        let text = err.to_string();
        // Errors about the document as a whole (key ".") name no key.
        assert!(key == "." || text.contains(key), "message does not name the key: {text}");
        assert!(text.contains(message_part), "message {text:?} lacks {message_part:?}");
    }

    #[test]
    fn default_robot_is_valid_and_round_trips_through_json() {
        let robot = Robot::default();
        robot.validate().unwrap();
        assert_eq!(Robot::from_json(&robot.to_json_pretty()).unwrap(), robot);
    }

    #[test]
    fn missing_keys_take_the_defaults() {
        let robot = Robot::from_json(r#"{"links": {"l1": 180}}"#).unwrap();
        assert_eq!(robot.links.l1, 180.0);
        assert_eq!(robot.links.l2, 270.0);
        assert_eq!(robot.base, Base::default());
    }

    #[test]
    fn unknown_key_is_named_with_its_position() {
        let err = Robot::from_json("{\n  \"links\": {\"l1\": 210, \"l3\": 5}\n}").unwrap_err();
        assert!(matches!(err, RobotError::Syntax { line: 2, .. }), "{err:?}");
        assert!(err.to_string().contains("unknown field `l3`"), "{err}");
        assert!(err.to_string().starts_with("2:"), "{err}");
        check_rejected(r#"{"lenghts": {}}"#, "lenghts", "unknown field `lenghts`");
        check_rejected("[210, 270]", ".", "a robot file is one JSON object");
    }

    #[test]
    fn non_positive_lengths_are_rejected() {
        check_rejected(r#"{"links": {"l1": 0}}"#, "links.l1", "must be positive");
        check_rejected(r#"{"links": {"l2": -270}}"#, "links.l2", "must be positive");
        check_rejected(r#"{"geometry": {"link_width": 0}}"#, "geometry.link_width", "positive");
        check_rejected(
            r#"{"joint_max_velocity": {"theta1": 1, "theta2": 1, "theta3": 0, "d4": 1}}"#,
            "joint_max_velocity.theta3",
            "positive",
        );
    }

    #[test]
    fn base_order_is_checked() {
        check_rejected(r#"{"base": {"b1x": -100, "b2x": 100}}"#, "base.b1x", "greater than");
        check_rejected(r#"{"base": {"b1x": 10, "b2x": 10}}"#, "base.b1x", "greater than");
        check_rejected(r#"{"base": {"b1x": 300, "b2x": -300}}"#, "base", "cannot close the loop");
    }

    #[test]
    fn empty_limit_ranges_are_rejected() {
        check_rejected(r#"{"joint_limits": {"theta2": [10, 10]}}"#, "joint_limits.theta2", "empty");
        check_rejected(r#"{"joint_limits": {"d4": [100, 0]}}"#, "joint_limits.d4", "empty");
    }

    #[test]
    fn bad_mode_strings_are_rejected() {
        check_rejected(r#"{"working_mode": "+x"}"#, "working_mode", "unknown working mode");
        check_rejected(r#"{"assembly_mode": "++"}"#, "assembly_mode", "unknown assembly mode");
    }

    #[test]
    fn wrong_types_and_bad_json_are_rejected() {
        check_rejected(r#"{"lp": "100"}"#, "lp", "invalid type");
        check_rejected(r#"{"joint_limits": {"theta1": [1, 2, 3]}}"#, "joint_limits.theta1", "");
        check_rejected(r#"{"links": {"l1": 1, "l1": 2}}"#, "links", "duplicate field `l1`");
        check_rejected("", ".", "EOF");
        check_rejected(r#"{"lp": 100} x"#, ".", "trailing characters");
    }

    #[test]
    fn a_list_where_an_object_belongs_is_refused_at_its_key() {
        let object = "invalid type: sequence, expected a JSON object";
        check_rejected(r#"{"links": [300, 400]}"#, "links", object);
        check_rejected(r#"{"joint_max_velocity": [1, 2, 3, 4]}"#, "joint_max_velocity", object);
        check_rejected(r#"{"dynamics": [9.8]}"#, "dynamics", object);
        check_rejected(r#"{"dynamics": {"proximal": [1, 2]}}"#, "dynamics.proximal", object);
        check_rejected(r#"{"motors": {"theta1": [1, 1]}}"#, "motors.theta1", object);
        check_rejected(r#"{"tool": 3}"#, "tool", "invalid type: integer `3`, expected a JSON");
        // No Rust type name in any message.
        let err = Robot::from_json(r#"{"dynamics": {"distal": [1, 2]}}"#).unwrap_err();
        assert!(!err.to_string().contains("struct"), "{err}");
        assert_eq!((err.to_string().split(':').next()), Some("1"), "{err}");
        // A section may still be null (absent), and an object still reads.
        let robot = Robot::from_json(r#"{"dynamics": null, "links": {"l1": 210}}"#).unwrap();
        assert_eq!((robot.dynamics, robot.links.l1), (None, 210.0));
    }

    #[test]
    fn meshes_name_parts_files_and_placements() {
        let json = r#"{"meshes": {"base": "base.stl",
            "proximal1": {"file": "arm.stl", "scale": 1000, "offset": [0, 0, -5], "rotation": [0, 0, 90]}}}"#;
        let robot = Robot::from_json(json).unwrap();
        let parts: Vec<&str> = robot.meshes.parts().map(|(part, _)| part.name()).collect();
        assert_eq!(parts, ["base", "proximal1"]);
        // Each part's name is its key in the file.
        for part in crate::Part::ALL {
            let json = format!(r#"{{"meshes": {{"{part}": "{part}.stl"}}}}"#);
            let meshes = Robot::from_json(&json).unwrap().meshes;
            let found: Vec<_> =
                meshes.parts().map(|(found, spec)| (found, spec.file.clone())).collect();
            assert_eq!(found, [(part, format!("{part}.stl"))]);
        }
        assert_eq!(robot.meshes.base, Some(crate::MeshSpec::new("base.stl")));
        let arm = robot.meshes.proximal1.as_ref().unwrap();
        assert_eq!(
            (arm.scale, arm.offset, arm.rotation),
            (1000.0, [0.0, 0.0, -5.0], [0.0, 0.0, 90.0])
        );
        assert_eq!(Robot::from_json(&robot.to_json_pretty()).unwrap(), robot);
        assert!(!Robot::default().to_json_pretty().contains("meshes"), "no meshes, no key");
    }

    #[test]
    fn bad_meshes_are_located_and_named() {
        let err = Robot::from_json("{\"meshes\": {\n  \"elbow\": \"e.stl\"}}").unwrap_err();
        assert!(
            err.to_string()
                .starts_with("2:9: meshes.elbow: unknown field `elbow`, expected one of `base`"),
            "{err}"
        );
        let err =
            Robot::from_json("{\"meshes\": {\"tool\": {\"file\": \"t.stl\", \"units\": \"m\"}}}")
                .unwrap_err();
        assert!(err.to_string().contains("meshes.tool"), "{err}");
        assert!(err.to_string().contains("unknown field `units`"), "{err}");
        check_rejected(r#"{"meshes": {"tool": 5}}"#, "meshes.tool", "an STL file name");
        check_rejected(
            r#"{"meshes": {"tool": {"scale": 2}}}"#,
            "meshes.tool",
            "missing field `file`",
        );
        check_rejected(r#"{"meshes": {"tool": ""}}"#, "meshes.tool", "names no file");
        check_rejected(
            r#"{"meshes": {"column": {"file": "c.stl", "scale": 0}}}"#,
            "meshes.column.scale",
            "must be positive",
        );
        let err =
            Robot::from_json("{\"meshes\": {\n \"tool\": {\"file\": \"t.stl\", \"scale\": -1}}}")
                .unwrap_err();
        assert_eq!(err.to_string(), "2:28: meshes.tool.scale: must be positive (got -1)");
        assert_eq!(
            Robot::locate_key("{\n  \"meshes\": {\"tool\": \"t.stl\"}}", "meshes.tool"),
            Some((2, 14))
        );
    }

    #[test]
    fn dynamics_and_motors_are_checked_key_by_key() {
        let json = r#"{"dynamics": {"gravity": 9.81, "proximal": {"mass": 0.62, "com": 98.0},
            "payload": {"mass": 0.2}},
            "motors": {"theta1": {"peak": 9, "rated": 3}, "theta2": {"peak": 9, "rated": 3},
            "theta3": {"peak": 1, "rated": 0.5}, "d4": {"peak": 120, "rated": 45, "coulomb": 3}}}"#;
        let robot = Robot::from_json(json).unwrap();
        let dynamics = robot.dynamics.unwrap();
        assert_eq!((dynamics.proximal.mass, dynamics.proximal.inertia), (Some(0.62), None));
        assert_eq!(robot.motors.unwrap().d4.coulomb, 3.0);
        assert_eq!(robot.motors.unwrap().theta1.viscous, 0.0);
        assert_eq!(Robot::from_json(&robot.to_json_pretty()).unwrap(), robot);
        check_rejected(
            r#"{"dynamics": {"distal": {"mass": -1}}}"#,
            "dynamics.distal.mass",
            "must not be negative",
        );
        check_rejected(
            r#"{"dynamics": {"proximal": {"com": 211}}}"#,
            "dynamics.proximal.com",
            "l1 is 210 mm long",
        );
        check_rejected(r#"{"dynamics": {"tool": {"mass": 1}}}"#, "dynamics.tool.mass", "unknown");
        let motors = r#"{"motors": {"theta1": {"peak": 9, "rated": 10}, "theta2": {"peak": 9,
            "rated": 3}, "theta3": {"peak": 1, "rated": 0.5}, "d4": {"peak": 120, "rated": 45}}}"#;
        check_rejected(motors, "motors.theta1.rated", "exceeds the peak 9");
        check_rejected(r#"{"motors": {"theta1": {"peak": 9}}}"#, "motors.theta1", "`rated`");
    }

    #[test]
    fn absurd_magnitudes_in_dynamics_and_motors_are_refused_with_the_bound() {
        let beyond = "is beyond any robot of this class: at most";
        check_rejected(
            r#"{"dynamics": {"proximal": {"mass": 1e308}}}"#,
            "dynamics.proximal.mass",
            beyond,
        );
        check_rejected(
            r#"{"dynamics": {"payload": {"mass": 1001}}}"#,
            "dynamics.payload.mass",
            "at most 1000 kg",
        );
        check_rejected(
            r#"{"dynamics": {"distal": {"inertia": 1e200}}}"#,
            "dynamics.distal.inertia",
            beyond,
        );
        check_rejected(
            r#"{"dynamics": {"tool": {"inertia": 2e3}}}"#,
            "dynamics.tool.inertia",
            "kg·m²",
        );
        check_rejected(r#"{"dynamics": {"gravity": 1e9}}"#, "dynamics.gravity", "at most 100 m/s²");
        let motor = |theta1: &str| {
            format!(
                r#"{{"motors": {{"theta1": {theta1}, "theta2": {{"peak": 9, "rated": 3}},
                "theta3": {{"peak": 1, "rated": 0.5}}, "d4": {{"peak": 120, "rated": 45}}}}}}"#
            )
        };
        check_rejected(&motor(r#"{"peak": 1e300, "rated": 3}"#), "motors.theta1.peak", "N·m");
        check_rejected(
            &motor(r#"{"peak": 9, "rated": 3, "rotor_inertia": 1e7}"#),
            "motors.theta1.rotor_inertia",
            beyond,
        );
        check_rejected(
            &motor(r#"{"peak": 9, "rated": 3, "viscous": 1e7}"#),
            "motors.theta1.viscous",
            beyond,
        );
        check_rejected(
            &motor(r#"{"peak": 9, "rated": 3, "coulomb": 1e7}"#),
            "motors.theta1.coulomb",
            beyond,
        );
        // The bounds themselves are accepted.
        let json = r#"{"dynamics": {"gravity": 100, "proximal": {"mass": 1000, "inertia": 1000},
            "payload": {"mass": 1000}}}"#;
        Robot::from_json(json).unwrap();
        Robot::from_json(&motor(r#"{"peak": 1e6, "rated": 1e6, "rotor_inertia": 1e6}"#)).unwrap();
    }

    #[test]
    fn validation_errors_point_at_the_key() {
        let json = "{\n  \"links\": {\n    \"l1\": 210,\n    \"l2\": -1\n  }\n}";
        let err = Robot::from_json(json).unwrap_err();
        assert_eq!(err.to_string(), "4:5: links.l2: must be positive (got -1)");
    }
}
