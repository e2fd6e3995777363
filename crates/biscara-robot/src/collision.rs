//! Collision tests of the body against itself and against the scene (docs/virtual-robot.md).

use std::fmt;

use nalgebra as na;

use crate::geometry::{Rect, interval_gap, point_rect, segment_rect, segment_segment};
use crate::{Body, Cylinder, LinkName, Scene, SceneBox};

/// A part of the body that can touch the scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum BodyPart {
    /// One of the four links.
    Link(LinkName),
    /// The Z column above the gripper.
    Column,
    /// The gripper.
    Gripper,
}

impl fmt::Display for BodyPart {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            BodyPart::Link(name) => name.fmt(f),
            BodyPart::Column => f.write_str("Z column"),
            BodyPart::Gripper => f.write_str("gripper"),
        }
    }
}

/// Two links that come closer than `link_width` (their capsules overlap).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SelfCollision {
    /// The first link.
    pub first: LinkName,
    /// The second link.
    pub second: LinkName,
    /// The distance between the links' centre lines, millimetres (below `link_width`).
    pub distance_mm: f64,
}

/// A part of the body that reaches into a box of the scene.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneCollision {
    /// The part of the body.
    pub part: BodyPart,
    /// The index of the box in the scene.
    pub box_index: usize,
    /// How deep the part reaches into the box's clearance, millimetres (> 0): the part's radius
    /// minus the distance from its axis to the box.
    pub depth_mm: f64,
}

/// The pairs of links that are not joined to each other: each is tested against `link_width`.
const NON_ADJACENT: [(LinkName, LinkName); 3] = [
    (LinkName::Proximal1, LinkName::Proximal2),
    (LinkName::Proximal1, LinkName::Distal2),
    (LinkName::Proximal2, LinkName::Distal1),
];

/// The self-collisions of a body: non-adjacent links whose centre lines are closer than
/// `link_width`, and the two distal links folded onto each other (their far ends, the elbows,
/// closer than `link_width`: the links would cross). Links joined at a common joint (a proximal
/// link and its distal link; the two distal links at the platform point) are not tested against
/// each other otherwise.
pub fn self_collisions(body: &Body) -> Vec<SelfCollision> {
    let width = body.geometry.link_width;
    let links = body.links();
    let link = |name: LinkName| links[name as usize];
    let mut found = Vec::new();
    for (first, second) in NON_ADJACENT {
        let (a, b) = (link(first), link(second));
        let distance_mm = segment_segment(&a.start, &a.end, &b.start, &b.end);
        if distance_mm < width {
            found.push(SelfCollision { first, second, distance_mm });
        }
    }
    let elbows = (body.configuration.elbows[0] - body.configuration.elbows[1]).norm();
    if elbows < width {
        found.push(SelfCollision {
            first: LinkName::Distal1,
            second: LinkName::Distal2,
            distance_mm: elbows,
        });
    }
    found
}

/// The parts of the body that come into a box of the scene: the links (capsules `link_width`
/// wide at `link_height`), the Z column and the gripper (vertical cylinders).
pub fn scene_collisions(body: &Body, scene: &Scene) -> Vec<SceneCollision> {
    let mut found = Vec::new();
    for (box_index, scene_box) in scene.boxes.iter().enumerate() {
        let rect = rect_of(scene_box);
        let height = body.geometry.link_height;
        let radius = 0.5 * body.geometry.link_width;
        let dz = interval_gap(height, height, scene_box.min[2], scene_box.max[2]);
        for link in body.links() {
            let distance = segment_rect(&link.start, &link.end, &rect).hypot(dz);
            if distance < radius {
                found.push(SceneCollision {
                    part: BodyPart::Link(link.name),
                    box_index,
                    depth_mm: radius - distance,
                });
            }
        }
        let parts = [(BodyPart::Column, body.column()), (BodyPart::Gripper, Some(body.gripper()))];
        for (part, cylinder) in parts {
            if let Some(depth_mm) = cylinder.and_then(|c| cylinder_depth(&c, scene_box, &rect)) {
                found.push(SceneCollision { part, box_index, depth_mm });
            }
        }
    }
    found
}

/// How far a vertical cylinder reaches into a box (`None` when it does not): the cylinder and
/// the box must overlap in z (touching faces do not count) and the axis must be closer to the
/// box's footprint than the radius.
fn cylinder_depth(cylinder: &Cylinder, scene_box: &SceneBox, rect: &Rect) -> Option<f64> {
    let overlap_z = cylinder.z_min < scene_box.max[2] && cylinder.z_max > scene_box.min[2];
    let distance = point_rect(&cylinder.center, rect);
    (overlap_z && distance < cylinder.radius).then_some(cylinder.radius - distance)
}

fn rect_of(scene_box: &SceneBox) -> Rect {
    Rect {
        min: na::Point2::new(scene_box.min[0], scene_box.min[1]),
        max: na::Point2::new(scene_box.max[0], scene_box.max[1]),
    }
}

#[cfg(test)]
mod tests {
    use biscara_kinematics::{Joints, RobotModel};

    use super::*;
    use crate::VirtualRobot;

    fn home_body() -> Body {
        VirtualRobot::new(&RobotModel::default()).body(&Joints::default()).unwrap()
    }

    fn scene(min: [f64; 3], max: [f64; 3]) -> Scene {
        Scene { boxes: vec![SceneBox { name: "b".to_owned(), min, max }] }
    }

    #[test]
    fn the_home_pose_is_free() {
        let body = home_body();
        assert!(self_collisions(&body).is_empty());
        assert!(scene_collisions(&body, &Scene::new()).is_empty());
    }

    #[test]
    fn a_box_under_the_gripper_is_hit_only_when_the_tool_goes_into_it() {
        let mut body = home_body(); // tool at (0, 460.8), z = 100
        let under = scene([-10.0, 450.0, 0.0], [10.0, 470.0, 50.0]);
        assert!(scene_collisions(&body, &under).is_empty());
        body.z = 50.0; // gripper bottom on the box's top face: touching, not colliding
        assert!(scene_collisions(&body, &under).is_empty());
        body.z = 40.0;
        let hits = scene_collisions(&body, &under);
        assert_eq!(hits.len(), 1, "{hits:?}");
        assert_eq!(hits[0].part, BodyPart::Gripper);
        assert_eq!(hits[0].depth_mm, 20.0);
    }

    #[test]
    fn a_tall_post_hits_the_links_and_the_column() {
        let body = home_body();
        // A post 5 mm beside proximal link 1 (x = 100, y 0..210), reaching above link height.
        let post = scene([110.0, 100.0, 0.0], [130.0, 120.0, 300.0]);
        let hits = scene_collisions(&body, &post);
        assert_eq!(hits.len(), 1, "{hits:?}");
        assert_eq!(hits[0].part, BodyPart::Link(LinkName::Proximal1));
        assert!((hits[0].depth_mm - 5.0).abs() < 1e-9);
        // A low post under the links touches nothing; under the column it hits the column.
        assert!(
            scene_collisions(&body, &scene([110.0, 100.0, 0.0], [130.0, 120.0, 200.0])).is_empty()
        );
        let column = scene_collisions(&body, &scene([-5.0, 455.0, 150.0], [5.0, 465.0, 160.0]));
        assert_eq!(column.len(), 1);
        assert_eq!(column[0].part, BodyPart::Column);
    }

    #[test]
    fn folded_links_collide() {
        let robot = VirtualRobot::new(&RobotModel::default());
        // θ1 = −θ2 ≈ 27° brings the elbows within 10 mm of each other: the proximal links meet.
        let t = (100.0f64 / 210.0).asin();
        let t = 0.95 * t;
        let body = robot.body(&Joints { theta1: t, theta2: -t, theta3: 0.0, d4: 0.0 }).unwrap();
        let found = self_collisions(&body);
        assert!(
            found.iter().any(|c| (c.first, c.second) == (LinkName::Proximal1, LinkName::Proximal2)),
            "{found:?}"
        );
        assert!(
            found.iter().any(|c| (c.first, c.second) == (LinkName::Distal1, LinkName::Distal2)),
            "{found:?}"
        );
    }
}
