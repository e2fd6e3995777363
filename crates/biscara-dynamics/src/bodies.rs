//! The robot's rigid bodies in SI units: `robot.json`'s `dynamics`, with what it leaves out
//! computed from `geometry` as solid aluminium (the one place these values are made: the inverse
//! dynamics and the MuJoCo model both take them from here).

use std::f64::consts::PI;

use biscara_kinematics::{BodySpec, DynamicsSpec, Robot};

/// Standard gravity, m/s²: `dynamics.gravity` when absent.
pub const STANDARD_GRAVITY: f64 = 9.80665;

/// Density of the bodies computed from `geometry`, kg/m³ (aluminium).
pub const ALUMINIUM_DENSITY: f64 = 2700.0;

/// A link turning in the plane: mass, centre of mass along the link and inertia about it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Link {
    /// Mass, kg.
    pub mass: f64,
    /// Centre of mass, m from the link's first joint toward its second.
    pub com: f64,
    /// Moment of inertia about the vertical axis through the centre of mass, kg·m².
    pub inertia: f64,
}

/// Every body of the robot, resolved: the values in force (SI units; `com` in metres).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bodies {
    /// Gravitational acceleration along −z, m/s².
    pub gravity: f64,
    /// Each proximal link (both legs).
    pub proximal: Link,
    /// Each distal link (both legs).
    pub distal: Link,
    /// Point mass at the tool point moving in x and y, kg.
    pub carriage: f64,
    /// Point mass at the tool point moving in x, y and with d4, kg.
    pub slide: f64,
    /// Inertia about the tool axis, turning with the tool angle, kg·m².
    pub tool_inertia: f64,
    /// The payload's mass while the gripper holds it, kg.
    pub payload: f64,
}

/// A solid capsule along a link: its mass and inertia about its centre (vertical axis, across
/// the capsule), for radius `radius` and length `length` between the centres of its caps.
fn capsule(radius: f64, length: f64) -> (f64, f64) {
    let cylinder = ALUMINIUM_DENSITY * PI * radius * radius * length;
    let cap = ALUMINIUM_DENSITY * 2.0 / 3.0 * PI * radius.powi(3);
    // Each hemisphere about its own centre of mass (3r/8 from its flat face), then moved.
    let cap_inertia = 83.0 / 320.0 * cap * radius * radius;
    let offset = 0.5 * length + 3.0 / 8.0 * radius;
    let inertia = cylinder * (3.0 * radius * radius + length * length) / 12.0
        + 2.0 * (cap_inertia + cap * offset * offset);
    (cylinder + 2.0 * cap, inertia)
}

impl Bodies {
    /// The bodies of `robot`: its `dynamics` where written, the rest from its `geometry`.
    ///
    /// The bodies from geometry, the shapes `biscara mjcf` draws, all solid aluminium: each
    /// proximal link a capsule `link_width` wide and `l1` long plus its motor hub (a cylinder
    /// 1.6 × `link_width` across and `link_width` high on the joint's axis); each distal link a
    /// capsule 0.8 × `link_width` wide and `l2` long; the slide the column (a cylinder
    /// `link_width`/2 across, from the gripper up to the links' height), the gripper cylinder
    /// and its finger; the tool the gripper cylinder and finger turning about the tool axis; no
    /// carriage and no payload.
    pub fn of(robot: &Robot) -> Bodies {
        let spec = robot.dynamics.unwrap_or_default();
        let geometry = &robot.geometry;
        let mm = |value: f64| value / 1000.0;
        let radius = mm(geometry.link_width) / 2.0;
        let (l1, l2) = (mm(robot.links.l1), mm(robot.links.l2));

        let (arm, arm_inertia) = capsule(radius, l1);
        let hub_radius = 1.6 * radius;
        let hub = ALUMINIUM_DENSITY * PI * hub_radius * hub_radius * 2.0 * radius;
        let proximal_mass = arm + hub;
        let proximal_com = arm * 0.5 * l1 / proximal_mass;
        let proximal = Link {
            mass: proximal_mass,
            com: proximal_com,
            inertia: arm_inertia
                + arm * (0.5 * l1 - proximal_com).powi(2)
                + 0.5 * hub * hub_radius * hub_radius
                + hub * proximal_com * proximal_com,
        };
        let (distal_mass, distal_inertia) = capsule(0.8 * radius, l2);
        let distal = Link { mass: distal_mass, com: 0.5 * l2, inertia: distal_inertia };

        let gripper_radius = mm(geometry.gripper_radius);
        let gripper_length = mm(geometry.gripper_length);
        let column_length = (mm(geometry.link_height) - gripper_length).max(0.0);
        let column = ALUMINIUM_DENSITY * PI * 0.25 * radius * radius * column_length;
        let gripper = ALUMINIUM_DENSITY * PI * gripper_radius * gripper_radius * gripper_length;
        // The finger: a box gripper_radius × gripper_radius/2 × gripper_length/2, its centre
        // gripper_radius from the tool axis.
        let finger =
            ALUMINIUM_DENSITY * gripper_radius * 0.5 * gripper_radius * 0.5 * gripper_length;
        let tool_inertia = 0.5 * gripper * gripper_radius * gripper_radius
            + finger * (1.25 * gripper_radius * gripper_radius) / 12.0
            + finger * gripper_radius * gripper_radius;

        let link = |spec: &BodySpec, default: Link| Link {
            mass: spec.mass.unwrap_or(default.mass),
            com: spec.com.map_or(default.com, mm),
            inertia: spec.inertia.unwrap_or(default.inertia),
        };
        Bodies {
            gravity: spec.gravity.unwrap_or(STANDARD_GRAVITY),
            proximal: link(&spec.proximal, proximal),
            distal: link(&spec.distal, distal),
            carriage: spec.carriage.mass.unwrap_or(0.0),
            slide: spec.slide.mass.unwrap_or(column + gripper + finger),
            tool_inertia: spec.tool.inertia.unwrap_or(tool_inertia),
            payload: spec.payload.mass.unwrap_or(0.0),
        }
    }

    /// The values as `robot.json`'s `dynamics` section, every key written (`com` in mm), each
    /// to 6 significant digits: what `biscara robot` prints (printed again once read back, the
    /// same text).
    pub fn to_spec(&self) -> DynamicsSpec {
        let link = |link: &Link| BodySpec {
            mass: Some(significant(link.mass)),
            com: Some(significant(link.com * 1000.0)),
            inertia: Some(significant(link.inertia)),
        };
        let point = |mass: f64| biscara_kinematics::PointSpec { mass: Some(significant(mass)) };
        DynamicsSpec {
            gravity: Some(significant(self.gravity)),
            proximal: link(&self.proximal),
            distal: link(&self.distal),
            carriage: point(self.carriage),
            slide: point(self.slide),
            tool: biscara_kinematics::ToolBodySpec {
                inertia: Some(significant(self.tool_inertia)),
            },
            payload: point(self.payload),
        }
    }
}

/// `value` to 6 significant digits.
fn significant(value: f64) -> f64 {
    format!("{value:.5e}").parse().unwrap_or(value)
}

/// `robot` with its `dynamics` section written out in full: the values in force, what
/// `biscara robot` prints (reading it back gives the same model).
pub fn robot_in_force(robot: &Robot) -> Robot {
    Robot { dynamics: Some(Bodies::of(robot).to_spec()), ..robot.clone() }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_capsule_of_no_radius_is_a_rod() {
        let (mass, inertia) = capsule(1e-6, 0.3);
        let rod = ALUMINIUM_DENSITY * PI * 1e-12 * 0.3;
        approx::assert_relative_eq!(mass, rod, max_relative = 1e-4);
        approx::assert_relative_eq!(inertia, rod * 0.09 / 12.0, max_relative = 1e-4);
    }

    #[test]
    fn a_capsule_of_no_length_is_a_sphere() {
        let (mass, inertia) = capsule(0.02, 0.0);
        let sphere = ALUMINIUM_DENSITY * 4.0 / 3.0 * PI * 0.02f64.powi(3);
        approx::assert_relative_eq!(mass, sphere, max_relative = 1e-12);
        approx::assert_relative_eq!(inertia, 0.4 * sphere * 0.0004, max_relative = 1e-12);
    }

    #[test]
    fn written_values_replace_the_geometry_ones_key_by_key() {
        let robot = Robot::from_json(
            r#"{"dynamics": {"proximal": {"mass": 0.62, "com": 98}, "payload": {"mass": 0.2}}}"#,
        )
        .unwrap();
        let bodies = Bodies::of(&robot);
        let default = Bodies::of(&Robot::default());
        assert_eq!(bodies.proximal.mass, 0.62);
        assert_eq!(bodies.proximal.com, 0.098);
        assert_eq!(bodies.proximal.inertia, default.proximal.inertia);
        assert_eq!(bodies.distal, default.distal);
        assert_eq!((bodies.payload, default.payload), (0.2, 0.0));
        assert_eq!(default.gravity, STANDARD_GRAVITY);
        // Printed and read back, the values are the same to 6 digits and print the same.
        let again = Bodies::of(&Robot { dynamics: Some(bodies.to_spec()), ..robot });
        approx::assert_relative_eq!(
            again.proximal.inertia,
            bodies.proximal.inertia,
            max_relative = 1e-5
        );
        assert_eq!(again.to_spec(), bodies.to_spec());
    }
}
