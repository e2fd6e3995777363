//! World poses, joint vectors and the names of chains and joints.

use std::fmt;

use nalgebra as na;

/// A tool pose in the base frame: millimetres and radians.
///
/// `x`, `y` are the platform point P, `z` the tool height, `phi` the tool rotation about +Z
/// (G-code's `C`, in radians here).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Pose {
    /// X of the tool point, millimetres.
    pub x: f64,
    /// Y of the tool point, millimetres.
    pub y: f64,
    /// Z of the tool point, millimetres.
    pub z: f64,
    /// Rotation of the tool about +Z, radians.
    pub phi: f64,
}

impl Pose {
    /// A pose from millimetres and radians.
    pub const fn new(x: f64, y: f64, z: f64, phi: f64) -> Pose {
        Pose { x, y, z, phi }
    }

    /// A pose from millimetres and the rotation `c` in degrees (the user-facing unit).
    pub fn from_degrees(x: f64, y: f64, z: f64, c_deg: f64) -> Pose {
        Pose::new(x, y, z, c_deg.to_radians())
    }

    /// `[x, y, z, c]` in millimetres and degrees.
    pub fn to_degrees(self) -> [f64; 4] {
        [self.x, self.y, self.z, self.phi.to_degrees()]
    }

    /// The platform point P = (x, y).
    pub fn platform(self) -> na::Point2<f64> {
        na::Point2::new(self.x, self.y)
    }
}

/// The joint coordinates `q = [θ1, θ2, θ3, d4]`: radians and millimetres.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Joints {
    /// θ1, chain 1's actuated base joint, radians, from +Y counter-clockwise.
    pub theta1: f64,
    /// θ2, chain 2's actuated base joint, radians, from +Y counter-clockwise.
    pub theta2: f64,
    /// θ3, the rotary joint at the platform, radians; continuous along a path.
    pub theta3: f64,
    /// d4, the prismatic joint, millimetres: `d4 = lp − z`.
    pub d4: f64,
}

impl Joints {
    /// Joints from radians and millimetres.
    pub const fn new(theta1: f64, theta2: f64, theta3: f64, d4: f64) -> Joints {
        Joints { theta1, theta2, theta3, d4 }
    }

    /// Joints from degrees and millimetres (the user-facing units).
    pub fn from_degrees(theta1: f64, theta2: f64, theta3: f64, d4: f64) -> Joints {
        Joints::new(theta1.to_radians(), theta2.to_radians(), theta3.to_radians(), d4)
    }

    /// `[θ1, θ2, θ3, d4]` in radians and millimetres.
    pub fn to_array(self) -> [f64; 4] {
        [self.theta1, self.theta2, self.theta3, self.d4]
    }

    /// `[θ1, θ2, θ3, d4]` in degrees and millimetres.
    pub fn to_degrees(self) -> [f64; 4] {
        [self.theta1.to_degrees(), self.theta2.to_degrees(), self.theta3.to_degrees(), self.d4]
    }

    /// The value of one joint: radians for θ, millimetres for d4.
    pub fn get(self, joint: Joint) -> f64 {
        self.to_array()[joint as usize]
    }
}

/// One of the two kinematic chains of the five-bar.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Chain {
    /// Chain 1: base joint at `b1x`, actuated by θ1, carries the rotary joint θ3.
    One,
    /// Chain 2: base joint at `b2x`, actuated by θ2.
    Two,
}

impl Chain {
    /// Both chains, in order.
    pub const BOTH: [Chain; 2] = [Chain::One, Chain::Two];

    /// 0 for chain 1, 1 for chain 2.
    pub fn index(self) -> usize {
        self as usize
    }
}

impl fmt::Display for Chain {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "chain {}", self.index() + 1)
    }
}

/// One of the four actuated joints.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Joint {
    /// θ1 (revolute).
    Theta1,
    /// θ2 (revolute).
    Theta2,
    /// θ3 (revolute).
    Theta3,
    /// d4 (prismatic).
    D4,
}

impl Joint {
    /// All four joints, in the order of `q`.
    pub const ALL: [Joint; 4] = [Joint::Theta1, Joint::Theta2, Joint::Theta3, Joint::D4];

    /// The joint's name as in files: `theta1`, `theta2`, `theta3`, `d4`.
    pub fn name(self) -> &'static str {
        match self {
            Joint::Theta1 => "theta1",
            Joint::Theta2 => "theta2",
            Joint::Theta3 => "theta3",
            Joint::D4 => "d4",
        }
    }

    /// Whether the joint is revolute (its user-facing unit is degrees) rather than prismatic (mm).
    pub fn is_revolute(self) -> bool {
        self != Joint::D4
    }

    /// The user-facing unit symbol: `°` or ` mm`.
    pub fn unit(self) -> &'static str {
        if self.is_revolute() { "°" } else { " mm" }
    }
}

impl fmt::Display for Joint {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}
