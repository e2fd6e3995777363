//! The robot's whole body at one instant: base, links, elbows, platform, Z column and gripper.

use std::fmt;

use biscara_kinematics::{
    Chain, Geometry, Joints, Kinematics, KinematicsError, PlanarConfiguration, RobotModel,
};
use nalgebra as na;

/// One of the four links of the five-bar.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum LinkName {
    /// Chain 1's proximal (actuated) link, from `b1` to `E1`.
    Proximal1,
    /// Chain 1's distal link, from `E1` to `P`.
    Distal1,
    /// Chain 2's proximal (actuated) link, from `b2` to `E2`.
    Proximal2,
    /// Chain 2's distal link, from `E2` to `P`.
    Distal2,
}

impl LinkName {
    /// The four links, in the order of [`Body::links`].
    pub const ALL: [LinkName; 4] =
        [LinkName::Proximal1, LinkName::Distal1, LinkName::Proximal2, LinkName::Distal2];
}

impl fmt::Display for LinkName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            LinkName::Proximal1 => "proximal link 1",
            LinkName::Distal1 => "distal link 1",
            LinkName::Proximal2 => "proximal link 2",
            LinkName::Distal2 => "distal link 2",
        })
    }
}

/// One link as a segment in the XY plane (its capsule is `link_width` wide, at `link_height`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Link {
    /// Which link.
    pub name: LinkName,
    /// The joint it starts at (a base joint or an elbow), millimetres.
    pub start: na::Point2<f64>,
    /// The joint it ends at (an elbow or the platform point), millimetres.
    pub end: na::Point2<f64>,
}

/// A vertical cylinder: the gripper or the Z column, millimetres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cylinder {
    /// Its axis, in the XY plane.
    pub center: na::Point2<f64>,
    /// Radius.
    pub radius: f64,
    /// Height of its bottom.
    pub z_min: f64,
    /// Height of its top.
    pub z_max: f64,
}

/// The whole body of the robot in one pose, millimetres and radians.
///
/// The five-bar's links lie in the plane `z = link_height` as capsules `link_width` wide; the
/// platform point carries the Z column and, below it, the gripper: a cylinder of
/// `gripper_radius` from the tool point `z` up `gripper_length`. The column continues from the
/// gripper's top to `link_height`, `link_width` wide.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Body {
    /// The five-bar: base joints, elbows and platform point.
    pub configuration: PlanarConfiguration,
    /// Height of the tool point, millimetres.
    pub z: f64,
    /// Orientation of the tool about Z (the pose's c), radians.
    pub phi: f64,
    /// The body dimensions.
    pub geometry: Geometry,
}

impl Body {
    /// The body of a five-bar configuration with the tool at height `z` and orientation `phi`.
    pub fn new(configuration: PlanarConfiguration, z: f64, phi: f64, geometry: Geometry) -> Body {
        Body { configuration, z, phi, geometry }
    }

    /// The four links, in the order of [`LinkName::ALL`].
    pub fn links(&self) -> [Link; 4] {
        let c = &self.configuration;
        let link = |name, start, end| Link { name, start, end };
        [
            link(LinkName::Proximal1, c.bases[0], c.elbows[0]),
            link(LinkName::Distal1, c.elbows[0], c.platform),
            link(LinkName::Proximal2, c.bases[1], c.elbows[1]),
            link(LinkName::Distal2, c.elbows[1], c.platform),
        ]
    }

    /// The gripper: from the tool point up `gripper_length`.
    pub fn gripper(&self) -> Cylinder {
        Cylinder {
            center: self.configuration.platform,
            radius: self.geometry.gripper_radius,
            z_min: self.z,
            z_max: self.z + self.geometry.gripper_length,
        }
    }

    /// The Z column from the gripper's top up to the links, `link_width` wide; `None` when the
    /// gripper reaches the links' height.
    pub fn column(&self) -> Option<Cylinder> {
        let bottom = self.z + self.geometry.gripper_length;
        (bottom < self.geometry.link_height).then_some(Cylinder {
            center: self.configuration.platform,
            radius: 0.5 * self.geometry.link_width,
            z_min: bottom,
            z_max: self.geometry.link_height,
        })
    }

    /// The elbow of `chain`.
    pub fn elbow(&self, chain: Chain) -> na::Point2<f64> {
        self.configuration.elbows[chain.index()]
    }
}

/// The virtual robot: the kinematic model and the body dimensions of one `robot.json`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VirtualRobot {
    model: Kinematics,
    geometry: Geometry,
    lp: f64,
}

impl VirtualRobot {
    /// The virtual robot of a validated robot.
    pub fn new(model: &RobotModel) -> VirtualRobot {
        let robot = model.robot();
        VirtualRobot { model: model.kinematics(), geometry: robot.geometry, lp: robot.lp }
    }

    /// The kinematic model.
    pub fn model(&self) -> &Kinematics {
        &self.model
    }

    /// The body dimensions.
    pub fn geometry(&self) -> Geometry {
        self.geometry
    }

    /// The body at joint values `joints` (radians, millimetres), by forward kinematics in the
    /// robot's assembly mode. Joint limits are not checked.
    pub fn body(&self, joints: &Joints) -> Result<Body, KinematicsError> {
        let fk = self.model.forward(joints)?;
        Ok(Body::new(fk.configuration, fk.pose.z, fk.pose.phi, self.geometry))
    }

    /// The body of a five-bar configuration (from IK) with the tool at `z`, `phi`.
    pub fn body_at(&self, configuration: PlanarConfiguration, z: f64, phi: f64) -> Body {
        Body::new(configuration, z, phi, self.geometry)
    }

    /// Length of the prismatic axis, `d4 = lp − z`, millimetres.
    pub fn lp(&self) -> f64 {
        self.lp
    }
}

#[cfg(test)]
mod tests {
    use approx::assert_relative_eq;

    use super::*;

    #[test]
    fn home_body_of_the_default_robot() {
        let robot = VirtualRobot::new(&RobotModel::default());
        let body = robot.body(&Joints::default()).unwrap();
        let links = body.links();
        assert_eq!(links[0].start, na::Point2::new(100.0, 0.0));
        assert_relative_eq!(links[0].end, na::Point2::new(100.0, 210.0), epsilon = 1e-9);
        assert_relative_eq!(links[1].end.y, 460.798724079689, epsilon = 1e-9);
        assert_relative_eq!(links[3].end, links[1].end, epsilon = 1e-12);
        for link in links {
            let expected = if matches!(link.name, LinkName::Proximal1 | LinkName::Proximal2) {
                210.0
            } else {
                270.0
            };
            assert_relative_eq!((link.end - link.start).norm(), expected, epsilon = 1e-9);
        }
        let gripper = body.gripper();
        assert_eq!((gripper.z_min, gripper.z_max, gripper.radius), (100.0, 140.0, 20.0));
        let column = body.column().unwrap();
        assert_eq!((column.z_min, column.z_max, column.radius), (140.0, 250.0, 15.0));
    }

    #[test]
    fn no_column_when_the_gripper_reaches_the_links() {
        let robot = VirtualRobot::new(&RobotModel::default());
        let mut body = robot.body(&Joints::default()).unwrap();
        body.z = 215.0;
        assert!(body.column().is_none());
    }
}
