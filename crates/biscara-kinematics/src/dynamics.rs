//! The `dynamics` and `motors` sections of `robot.json` (docs/dynamics.md): the bodies' masses,
//! centres and inertias, and the motors at the joints. Read and checked here, with the rest of the
//! robot file; the model built from them is `biscara-dynamics`'.

use serde::{Deserialize, Serialize};

use crate::RobotError;
use crate::robot::{finite, invalid};

/// The rigid bodies of the robot (`robot.json`'s `dynamics`), SI units except `com` (mm).
///
/// Every key is optional: a body or value not written takes the value computed from `geometry`
/// (solid aluminium, docs/dynamics.md); `gravity` defaults to standard gravity and the payload
/// to none.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct DynamicsSpec {
    /// Gravitational acceleration along −z, m/s² (9.80665 when absent).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gravity: Option<f64>,
    /// Each proximal link: turns about its base joint with θi; `com` mm from the base joint
    /// toward the elbow.
    #[serde(skip_serializing_if = "BodySpec::is_empty")]
    #[serde(deserialize_with = "crate::object::object")]
    pub proximal: BodySpec,
    /// Each distal link: `com` mm from the elbow toward the tool point.
    #[serde(skip_serializing_if = "BodySpec::is_empty")]
    #[serde(deserialize_with = "crate::object::object")]
    pub distal: BodySpec,
    /// A point mass at the tool point moving in x and y only (the Z axis's frame and motors).
    #[serde(skip_serializing_if = "PointSpec::is_empty")]
    #[serde(deserialize_with = "crate::object::object")]
    pub carriage: PointSpec,
    /// A point mass at the tool point that also moves with d4.
    #[serde(skip_serializing_if = "PointSpec::is_empty")]
    #[serde(deserialize_with = "crate::object::object")]
    pub slide: PointSpec,
    /// The inertia about the tool axis, turning with the tool angle c.
    #[serde(skip_serializing_if = "ToolBodySpec::is_empty")]
    #[serde(deserialize_with = "crate::object::object")]
    pub tool: ToolBodySpec,
    /// A point mass at the tool point carried from each pick to its place.
    #[serde(skip_serializing_if = "PointSpec::is_empty")]
    #[serde(deserialize_with = "crate::object::object")]
    pub payload: PointSpec,
}

/// A link: mass kg, centre of mass mm along the link, inertia kg·m² about its centre of mass
/// (vertical axis).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct BodySpec {
    /// Mass, kg.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mass: Option<f64>,
    /// Centre of mass, mm from the link's first joint toward its second.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub com: Option<f64>,
    /// Moment of inertia about the vertical axis through the centre of mass, kg·m².
    #[serde(skip_serializing_if = "Option::is_none")]
    pub inertia: Option<f64>,
}

/// A point mass, kg.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PointSpec {
    /// Mass, kg.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mass: Option<f64>,
}

/// The tool's inertia about its axis, kg·m².
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ToolBodySpec {
    /// Moment of inertia about the tool axis, kg·m².
    #[serde(skip_serializing_if = "Option::is_none")]
    pub inertia: Option<f64>,
}

impl BodySpec {
    /// Whether no value is written.
    pub fn is_empty(&self) -> bool {
        *self == BodySpec::default()
    }
}

impl PointSpec {
    /// Whether no value is written.
    pub fn is_empty(&self) -> bool {
        *self == PointSpec::default()
    }
}

impl ToolBodySpec {
    /// Whether no value is written.
    pub fn is_empty(&self) -> bool {
        *self == ToolBodySpec::default()
    }
}

/// The four motors (`robot.json`'s `motors`), each at its joint (after any gear).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Motors {
    /// θ1's motor (N·m, kg·m²).
    #[serde(deserialize_with = "crate::object::object")]
    pub theta1: Motor,
    /// θ2's motor (N·m, kg·m²).
    #[serde(deserialize_with = "crate::object::object")]
    pub theta2: Motor,
    /// θ3's motor (N·m, kg·m²).
    #[serde(deserialize_with = "crate::object::object")]
    pub theta3: Motor,
    /// d4's motor (N, kg).
    #[serde(deserialize_with = "crate::object::object")]
    pub d4: Motor,
}

impl Motors {
    /// The motors in joint order θ1, θ2, θ3, d4.
    pub fn to_array(self) -> [Motor; 4] {
        [self.theta1, self.theta2, self.theta3, self.d4]
    }
}

/// One motor at its joint: torques N·m for θ1–θ3, forces N for d4.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Motor {
    /// The most torque (force) it gives, N·m (N).
    pub peak: f64,
    /// The torque (force) it gives continuously without overheating, N·m (N); at most `peak`.
    pub rated: f64,
    /// The rotor's inertia reflected to the joint, kg·m² (kg for d4); 0 when absent.
    #[serde(default)]
    pub rotor_inertia: f64,
    /// Viscous friction, N·m·s/rad (N·s/m for d4); 0 when absent.
    #[serde(default)]
    pub viscous: f64,
    /// Coulomb friction, N·m (N), against the motion; 0 when absent.
    #[serde(default)]
    pub coulomb: f64,
}

/// The names of the joints in the order of [`Motors::to_array`].
const JOINTS: [&str; 4] = ["theta1", "theta2", "theta3", "d4"];

/// The largest mass a body (or the payload) may have, kg: a five-bar SCARA-class arm's links,
/// carriage and payload weigh grams to tens of kilograms; a tonne is beyond any of them, and
/// bounding every input keeps the model's torques, and their squares summed over a cycle, finite.
pub const MAX_MASS_KG: f64 = 1e3;

/// The largest moment of inertia a body may have, kg·m²: a tonne at a metre's radius.
pub const MAX_INERTIA_KG_M2: f64 = 1e3;

/// The largest gravity, m/s²: about 10 g (the surface gravity of every planet of the solar system
/// is below 25 m/s²).
pub const MAX_GRAVITY: f64 = 100.0;

/// The largest `peak`, `rated`, `viscous` or `coulomb` of a motor, N·m or N (N·m·s/rad, N·s/m):
/// a meganewton(-metre), far beyond any motor and gear of this class of robot.
pub const MAX_MOTOR_EFFORT: f64 = 1e6;

/// The largest reflected rotor inertia, kg·m² (kg for d4): a rotor of 10⁻³ kg·m² through a 100:1
/// gear is 10 kg·m², through a 1 mm-lead screw ≈ 4·10⁴ kg; 10⁶ leaves room for both.
pub const MAX_ROTOR_INERTIA: f64 = 1e6;

fn non_negative(key: &str, value: Option<f64>) -> Result<(), RobotError> {
    let Some(value) = value else { return Ok(()) };
    finite(key, value)?;
    if value < 0.0 {
        return Err(invalid(key, format!("must not be negative (got {value})")));
    }
    Ok(())
}

/// [`non_negative`] and at most `max` (`unit`, named in the message with the bound's reason).
fn bounded(key: &str, value: Option<f64>, max: f64, unit: &str) -> Result<(), RobotError> {
    non_negative(key, value)?;
    match value {
        Some(value) if value > max => {
            // 1e308 as written, not as 309 digits.
            let value = if value >= 1e9 { format!("{value:e}") } else { value.to_string() };
            Err(invalid(
                key,
                format!(
                    "{value} {unit} is beyond any robot of this class: at most {max} {unit} \
                     (docs/dynamics.md)"
                ),
            ))
        }
        _ => Ok(()),
    }
}

fn within_link(key: &str, com: Option<f64>, link: &str, length: f64) -> Result<(), RobotError> {
    non_negative(key, com)?;
    match com {
        Some(com) if com > length => Err(invalid(
            key,
            format!(
                "the centre of mass lies beyond the link: {com} mm from its first joint, but \
                 {link} is {length} mm long"
            ),
        )),
        _ => Ok(()),
    }
}

impl DynamicsSpec {
    /// Checks every written value: finite, masses and inertias not negative, gravity positive,
    /// each link's centre of mass on the link (`l1`, `l2` mm long).
    pub fn validate(&self, l1: f64, l2: f64) -> Result<(), RobotError> {
        if let Some(gravity) = self.gravity {
            finite("dynamics.gravity", gravity)?;
            if gravity < 0.0 {
                return Err(invalid(
                    "dynamics.gravity",
                    format!("must not be negative (got {gravity}): gravity points along -z"),
                ));
            }
        }
        bounded("dynamics.gravity", self.gravity, MAX_GRAVITY, "m/s²")?;
        for (name, body, link, length) in
            [("proximal", &self.proximal, "l1", l1), ("distal", &self.distal, "l2", l2)]
        {
            bounded(&format!("dynamics.{name}.mass"), body.mass, MAX_MASS_KG, "kg")?;
            within_link(&format!("dynamics.{name}.com"), body.com, link, length)?;
            let inertia = body.inertia;
            bounded(&format!("dynamics.{name}.inertia"), inertia, MAX_INERTIA_KG_M2, "kg·m²")?;
        }
        for (name, point) in
            [("carriage", &self.carriage), ("slide", &self.slide), ("payload", &self.payload)]
        {
            bounded(&format!("dynamics.{name}.mass"), point.mass, MAX_MASS_KG, "kg")?;
        }
        bounded("dynamics.tool.inertia", self.tool.inertia, MAX_INERTIA_KG_M2, "kg·m²")
    }
}

impl Motors {
    /// Checks every motor: finite values, `peak` positive, `rated` positive and at most `peak`,
    /// the rest not negative.
    pub fn validate(&self) -> Result<(), RobotError> {
        for (name, motor) in JOINTS.iter().zip(self.to_array()) {
            let key = |field: &str| format!("motors.{name}.{field}");
            // Units as the motor's joint has them: a turning joint's, or d4's.
            let (effort, inertia) = if *name == "d4" { ("N", "kg") } else { ("N·m", "kg·m²") };
            for (field, value) in [("peak", motor.peak), ("rated", motor.rated)] {
                finite(&key(field), value)?;
                if value <= 0.0 {
                    return Err(invalid(&key(field), format!("must be positive (got {value})")));
                }
                bounded(&key(field), Some(value), MAX_MOTOR_EFFORT, effort)?;
            }
            if motor.rated > motor.peak {
                return Err(invalid(
                    &key("rated"),
                    format!(
                        "the continuous rating {} exceeds the peak {}: rated must be at most peak",
                        motor.rated, motor.peak
                    ),
                ));
            }
            bounded(&key("rotor_inertia"), Some(motor.rotor_inertia), MAX_ROTOR_INERTIA, inertia)?;
            let viscous_unit = if *name == "d4" { "N·s/m" } else { "N·m·s/rad" };
            bounded(&key("viscous"), Some(motor.viscous), MAX_MOTOR_EFFORT, viscous_unit)?;
            bounded(&key("coulomb"), Some(motor.coulomb), MAX_MOTOR_EFFORT, effort)?;
        }
        Ok(())
    }
}
