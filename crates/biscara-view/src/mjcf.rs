//! The MuJoCo model (MJCF) of a robot, and the companion file that plays a trajectory on it.

use std::fmt::Write as _;
use std::io::Write;

use biscara_dynamics::{Bodies, Dynamics};
use biscara_joints::JointCsvRow;
use biscara_kinematics::{Chain, Joints, Kinematics, RobotModel};

use crate::{Scene, ViewError};

/// The header of the companion trajectory file written by [`QposWriter`]: the six joints of the
/// model in MuJoCo's units (radians, metres), then the tool pose our forward kinematics gives.
pub const QPOS_HEADER: &str =
    "t_s,theta1,theta2,theta3,d4,elbow1,elbow2,tool_x_m,tool_y_m,tool_z_m,tool_phi_rad";

/// Settings of the model that are not in `robot.json`: the simulation and the servo loops.
///
/// The defaults were tuned on the demo job (`tests/mujoco/check_model.py`): stiff enough that the
/// tool follows the path within a fraction of a millimetre, stable with the implicit integrator.
/// The bodies' masses and inertias and the motors' rotor inertias are the robot's
/// ([`biscara_dynamics::Bodies`], docs/dynamics.md), not settings.
#[derive(Debug, Clone, PartialEq)]
pub struct MjcfOptions {
    /// Simulation time step, s.
    pub timestep: f64,
    /// Natural frequency of the position servos, rad/s (kp = ω²·inertia, kv = 2·ω·inertia).
    pub servo_frequency: f64,
    /// File name of the companion trajectory file (written by [`QposWriter`]), recorded in the
    /// model as the custom text `biscara_trajectory`.
    pub trajectory_file: Option<String>,
}

impl Default for MjcfOptions {
    fn default() -> Self {
        MjcfOptions { timestep: 0.0005, servo_frequency: 300.0, trajectory_file: None }
    }
}

/// The least mass (kg) and inertia (kg·m²) written for a moving body: MuJoCo refuses less
/// (`mjMINVAL`, 1e-15), and a robot file may say 0.
const MUJOCO_FLOOR: f64 = 1e-12;

/// Millimetres to metres.
fn m(mm: f64) -> f64 {
    mm / 1000.0
}

/// `w x y z` of a rotation by `angle` radians about +Z.
fn quat_z(angle: f64) -> String {
    let (sin, cos) = (0.5 * angle).sin_cos();
    format!("{cos} 0 0 {sin}")
}

/// Text safe inside an XML attribute.
fn escape(text: &str) -> String {
    let mut escaped = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => escaped.push_str("&amp;"),
            '<' => escaped.push_str("&lt;"),
            '>' => escaped.push_str("&gt;"),
            '"' => escaped.push_str("&quot;"),
            '\'' => escaped.push_str("&apos;"),
            c if c.is_control() => escaped.push(' '),
            c => escaped.push(c),
        }
    }
    escaped
}

/// Writes the MJCF model of `robot` with the `scene`'s boxes as static geoms
/// (docs/virtual-robot.md).
///
/// Names: hinges `theta1`, `theta2`, `theta3`, slide `d4` (radians, metres), each driven by a
/// position actuator of the same name with the joint's limits as its control range; passive hinges
/// `elbow1`, `elbow2` (the distal link relative to its proximal link, counter-clockwise about +Z,
/// zero at home); the site `tool`. The base frame is the world frame and every joint is zero at
/// the home pose, so qpos0 is the home pose, assembled. Chain 1's distal link carries the Z slide
/// and the rotary joint; chain 2 is closed on it by an equality `connect` at the platform point.
///
/// The masses, centres and inertias are `dynamics`' bodies (docs/dynamics.md), written as each
/// body's `inertial` (the geoms only draw): the proximal and distal links, the carriage at the
/// platform, the slide's mass and the tool's inertia on the gripper; gravity is
/// `dynamics.gravity`. The motors' rotor inertias are the joints' `armature` (0 without motors);
/// with motors, their viscous friction is the joints' `damping`, their Coulomb friction the
/// joints' `frictionloss`, and each actuator's `forcerange` is ±`peak`.
pub fn write_mjcf(
    out: &mut dyn Write,
    model: &RobotModel,
    dynamics: &Dynamics,
    scene: &Scene,
    options: &MjcfOptions,
) -> Result<(), ViewError> {
    let robot = model.robot();
    let model = model.kinematics();
    let bodies = dynamics.bodies();
    let motors = dynamics.motors();
    let armature = |joint: usize| motors.map_or(0.0, |motors| motors[joint].rotor_inertia);
    // The motors' friction: viscous as the joint's damping, Coulomb as its friction loss.
    let friction = |joint: usize| {
        motors.map_or(String::new(), |motors| {
            let motor = &motors[joint];
            format!(" damping=\"{}\" frictionloss=\"{}\"", motor.viscous, motor.coulomb)
        })
    };
    let forcerange = |joint: usize| {
        motors.map_or(String::new(), |motors| {
            format!(" forcerange=\"{} {}\"", -motors[joint].peak, motors[joint].peak)
        })
    };
    // An inertia about the vertical axis, the same about the others (they never turn). MuJoCo
    // refuses a moving body without mass or inertia: values below 1e-12 are written as 1e-12.
    let inertial = |pos: String, mass: f64, inertia: f64| {
        let (mass, inertia) = (mass.max(MUJOCO_FLOOR), inertia.max(MUJOCO_FLOOR));
        format!(
            "<inertial pos=\"{pos}\" mass=\"{mass}\" diaginertia=\"{inertia} {inertia} {inertia}\"/>"
        )
    };
    let geometry = &robot.geometry;
    let (l1, l2) = (m(robot.links.l1), m(robot.links.l2));
    let height = m(geometry.link_height);
    let radius = m(geometry.link_width) / 2.0;
    let limits = &robot.joint_limits;
    let rad = |range: [f64; 2]| format!("{} {}", range[0].to_radians(), range[1].to_radians());
    let d4_range = format!("{} {}", m(limits.d4[0]), m(limits.d4[1]));
    let psi = [model.distal_home(Chain::One), model.distal_home(Chain::Two)];
    let bases = model.bases();
    let column_length = height - m(geometry.gripper_length);
    let mut x = String::new();
    // Writing to a String cannot fail.
    let _ = (|| -> std::fmt::Result {
        writeln!(
            x,
            "<!-- The BiSCARA as a MuJoCo model, written by `biscara mjcf` (docs/virtual-robot.md)."
        )?;
        writeln!(x, "     Robot: {}. Units: metres, radians, kilograms.", escape(&robot.name))?;
        writeln!(x, "     Open it: python -m mujoco.viewer --mjcf robot.xml -->")?;
        writeln!(x, "<mujoco model=\"biscara\">")?;
        writeln!(
            x,
            "  <compiler angle=\"radian\" autolimits=\"true\" inertiafromgeom=\"false\"/>"
        )?;
        writeln!(
            x,
            "  <option timestep=\"{}\" integrator=\"implicitfast\" gravity=\"0 0 {}\"/>",
            options.timestep, -bodies.gravity
        )?;
        writeln!(x, "  <visual><global offwidth=\"1280\" offheight=\"960\"/></visual>")?;
        if let Some(file) = &options.trajectory_file {
            writeln!(x, "  <custom>")?;
            writeln!(x, "    <text name=\"biscara_trajectory\" data=\"{}\"/>", escape(file))?;
            writeln!(x, "  </custom>")?;
        }
        writeln!(x, "  <default>")?;
        writeln!(x, "    <geom contype=\"0\" conaffinity=\"0\"/>")?;
        writeln!(x, "    <joint axis=\"0 0 1\"/>")?;
        writeln!(x, "  </default>")?;
        writeln!(x, "  <asset>")?;
        writeln!(x, "    <material name=\"proximal\" rgba=\"0.20 0.45 0.80 1\"/>")?;
        writeln!(x, "    <material name=\"distal\" rgba=\"0.95 0.55 0.15 1\"/>")?;
        writeln!(x, "    <material name=\"column\" rgba=\"0.6 0.6 0.65 1\"/>")?;
        writeln!(x, "    <material name=\"gripper\" rgba=\"0.85 0.2 0.2 1\"/>")?;
        writeln!(x, "    <material name=\"base\" rgba=\"0.3 0.3 0.33 1\"/>")?;
        writeln!(x, "    <material name=\"scene\" rgba=\"0.45 0.7 0.45 0.6\"/>")?;
        writeln!(
            x,
            "    <texture name=\"grid\" type=\"2d\" builtin=\"checker\" rgb1=\"0.9 0.9 0.9\" rgb2=\"0.8 0.8 0.8\" width=\"256\" height=\"256\"/>"
        )?;
        writeln!(x, "    <material name=\"floor\" texture=\"grid\" texrepeat=\"10 10\"/>")?;
        writeln!(
            x,
            "    <texture name=\"sky\" type=\"skybox\" builtin=\"gradient\" rgb1=\"0.93 0.95 0.98\" rgb2=\"0.75 0.8 0.88\" width=\"32\" height=\"512\"/>"
        )?;
        writeln!(x, "  </asset>")?;
        writeln!(x, "  <worldbody>")?;
        writeln!(x, "    <light pos=\"0 0.3 1.5\" dir=\"0 0 -1\"/>")?;
        writeln!(
            x,
            "    <geom name=\"floor\" type=\"plane\" size=\"1 1 0.01\" material=\"floor\"/>"
        )?;
        // The base: a pillar between the two base joints, up to just below the links.
        let half_x = 0.5 * (bases[0].x - bases[1].x) / 1000.0 + 2.0 * radius;
        let centre_x = 0.5 * (bases[0].x + bases[1].x) / 1000.0;
        let pillar = height - 2.0 * radius;
        writeln!(
            x,
            "    <geom name=\"base\" type=\"box\" pos=\"{centre_x} 0 {}\" size=\"{half_x} {} {}\" material=\"base\"/>",
            pillar / 2.0,
            2.0 * radius,
            pillar / 2.0
        )?;
        for scene_box in &scene.boxes {
            let centre: Vec<String> = (0..3)
                .map(|i| m(0.5 * (scene_box.min[i] + scene_box.max[i])).to_string())
                .collect();
            let half: Vec<String> = (0..3)
                .map(|i| m(0.5 * (scene_box.max[i] - scene_box.min[i])).to_string())
                .collect();
            writeln!(
                x,
                "    <geom name=\"scene_{}\" type=\"box\" pos=\"{}\" size=\"{}\" material=\"scene\"/>",
                escape(&scene_box.name),
                centre.join(" "),
                half.join(" ")
            )?;
        }
        for (index, chain) in [(1, Chain::One), (2, Chain::Two)] {
            let base = bases[chain.index()];
            let (joint, range) = match chain {
                Chain::One => ("theta1", limits.theta1),
                Chain::Two => ("theta2", limits.theta2),
            };
            writeln!(x, "    <body name=\"proximal{index}\" pos=\"{} 0 {height}\">", m(base.x))?;
            let proximal = bodies.proximal;
            writeln!(
                x,
                "      {}",
                inertial(format!("0 {} 0", proximal.com), proximal.mass, proximal.inertia)
            )?;
            writeln!(
                x,
                "      <joint name=\"{joint}\" type=\"hinge\" range=\"{}\" armature=\"{}\"{}/>",
                rad(range),
                armature(chain.index()),
                friction(chain.index())
            )?;
            writeln!(
                x,
                "      <geom name=\"motor{index}\" type=\"cylinder\" pos=\"0 0 {}\" size=\"{} {}\" material=\"base\"/>",
                -radius,
                1.6 * radius,
                radius
            )?;
            writeln!(
                x,
                "      <geom name=\"proximal{index}\" type=\"capsule\" fromto=\"0 0 0 0 {l1} 0\" size=\"{radius}\" material=\"proximal\"/>"
            )?;
            writeln!(
                x,
                "      <body name=\"distal{index}\" pos=\"0 {l1} 0\" quat=\"{}\">",
                quat_z(psi[chain.index()])
            )?;
            let distal = bodies.distal;
            writeln!(
                x,
                "        {}",
                inertial(format!("{} 0 0", distal.com), distal.mass, distal.inertia)
            )?;
            writeln!(x, "        <joint name=\"elbow{index}\" type=\"hinge\"/>")?;
            writeln!(
                x,
                "        <geom name=\"distal{index}\" type=\"capsule\" fromto=\"0 0 0 {l2} 0 0\" size=\"{}\" material=\"distal\"/>",
                0.8 * radius
            )?;
            if chain == Chain::One {
                writeln!(
                    x,
                    "        <body name=\"platform\" pos=\"{l2} 0 0\" quat=\"{}\">",
                    quat_z(-psi[0])
                )?;
                if bodies.carriage > 0.0 {
                    writeln!(
                        x,
                        "          {}",
                        inertial("0 0 0".to_owned(), bodies.carriage, 0.0)
                    )?;
                }
                writeln!(
                    x,
                    "          <site name=\"platform\" size=\"{}\" rgba=\"0 0 0 1\"/>",
                    0.3 * radius
                )?;
                // The slide and the tool in one body, d4 then θ3: MuJoCo wants mass and inertia
                // in every moving body, and the slide's is a point mass on the tool axis (turning
                // with θ3 without effect), the tool's an inertia about that axis.
                writeln!(
                    x,
                    "          <body name=\"gripper\" pos=\"0 0 {}\">",
                    m(robot.lp) - height
                )?;
                writeln!(
                    x,
                    "            {}",
                    inertial("0 0 0".to_owned(), bodies.slide, bodies.tool_inertia)
                )?;
                writeln!(
                    x,
                    "            <joint name=\"d4\" type=\"slide\" axis=\"0 0 -1\" range=\"{d4_range}\" armature=\"{}\"{}/>",
                    armature(3),
                    friction(3)
                )?;
                writeln!(
                    x,
                    "            <joint name=\"theta3\" type=\"hinge\" range=\"{}\" armature=\"{}\"{}/>",
                    rad(limits.theta3),
                    armature(2),
                    friction(2)
                )?;
                writeln!(
                    x,
                    "            <geom name=\"column\" type=\"cylinder\" fromto=\"0 0 {} 0 0 {}\" size=\"{}\" material=\"column\"/>",
                    m(geometry.gripper_length),
                    m(geometry.gripper_length) + column_length,
                    0.5 * radius
                )?;
                let gripper_radius = m(geometry.gripper_radius);
                let gripper_length = m(geometry.gripper_length);
                writeln!(
                    x,
                    "            <geom name=\"gripper\" type=\"cylinder\" fromto=\"0 0 0 0 0 {gripper_length}\" size=\"{gripper_radius}\" material=\"gripper\"/>"
                )?;
                writeln!(
                    x,
                    "            <geom name=\"finger\" type=\"box\" pos=\"{} 0 {}\" size=\"{} {} {}\" material=\"gripper\"/>",
                    gripper_radius,
                    0.5 * gripper_length,
                    0.5 * gripper_radius,
                    0.25 * gripper_radius,
                    0.25 * gripper_length
                )?;
                writeln!(
                    x,
                    "            <site name=\"tool\" size=\"{}\" rgba=\"1 1 0 1\"/>",
                    0.3 * radius
                )?;
                writeln!(x, "          </body>")?;
                writeln!(x, "        </body>")?;
            }
            writeln!(x, "      </body>")?;
            writeln!(x, "    </body>")?;
        }
        writeln!(x, "  </worldbody>")?;
        writeln!(x, "  <equality>")?;
        writeln!(
            x,
            "    <connect name=\"platform\" body1=\"distal2\" body2=\"distal1\" anchor=\"{l2} 0 0\" solref=\"{} 1\"/>",
            4.0 * options.timestep
        )?;
        writeln!(x, "  </equality>")?;
        writeln!(x, "  <actuator>")?;
        // Each servo: kp = ω²·I, kv = 2·ω·I (critically damped) for the inertia it moves.
        let omega = options.servo_frequency;
        let inertia = actuated_inertia(bodies, model.l1() / 1000.0, model.l2() / 1000.0, armature);
        let joints = [
            ("theta1", rad(limits.theta1)),
            ("theta2", rad(limits.theta2)),
            ("theta3", rad(limits.theta3)),
            ("d4", d4_range.clone()),
        ];
        for (joint, ((name, range), inertia)) in joints.iter().zip(inertia).enumerate() {
            writeln!(
                x,
                "    <position name=\"{name}\" joint=\"{name}\" kp=\"{}\" kv=\"{}\" ctrlrange=\"{range}\"{}/>",
                omega * omega * inertia,
                2.0 * omega * inertia,
                forcerange(joint)
            )?;
        }
        writeln!(x, "  </actuator>")?;
        writeln!(x, "</mujoco>")
    })();
    out.write_all(x.as_bytes())?;
    Ok(())
}

/// A generous estimate of the inertia each actuator moves (kg·m² for the revolute joints, kg for
/// the slide), for the servos' gains: the bodies at the tool point counted at full reach on both
/// planar chains, plus each joint's armature.
fn actuated_inertia(
    bodies: &Bodies,
    l1: f64,
    l2: f64,
    armature: impl Fn(usize) -> f64,
) -> [f64; 4] {
    let proximal = bodies.proximal.inertia + bodies.proximal.mass * bodies.proximal.com.powi(2);
    let reach = (l1 + l2) * (l1 + l2);
    let planar = proximal
        + (bodies.distal.mass + bodies.carriage + bodies.slide) * reach
        + bodies.tool_inertia;
    [
        planar + armature(0),
        planar + armature(1),
        bodies.tool_inertia + armature(2),
        bodies.slide + armature(3),
    ]
}

/// Writes the companion trajectory file of a model: one row per joint-CSV row, the model's six
/// joints (radians, metres; the elbows from forward kinematics) and the tool pose FK gives.
#[derive(Debug)]
pub struct QposWriter<W: Write> {
    out: W,
    model: Kinematics,
    row: String,
}

impl<W: Write> QposWriter<W> {
    /// A writer for the robot `model`; writes the header at once.
    pub fn new(mut out: W, model: &RobotModel) -> Result<Self, ViewError> {
        writeln!(out, "{QPOS_HEADER}")?;
        Ok(QposWriter { out, model: model.kinematics(), row: String::new() })
    }

    /// Writes one row; fails when its joints do not assemble.
    pub fn write(&mut self, row: &JointCsvRow) -> Result<(), ViewError> {
        let joints: Joints = row.joints;
        let fk = self
            .model
            .forward(&joints)
            .map_err(|source| ViewError::Assembly { t: row.t, source })?;
        self.row.clear();
        let values = [
            joints.theta1,
            joints.theta2,
            joints.theta3,
            m(joints.d4),
            fk.passive.elbow1,
            fk.passive.elbow2,
            m(fk.pose.x),
            m(fk.pose.y),
            m(fk.pose.z),
            fk.pose.phi,
        ];
        let _ = write!(self.row, "{}", row.t);
        for value in values {
            let _ = write!(self.row, ",{value:.12}");
        }
        self.row.push('\n');
        self.out.write_all(self.row.as_bytes())?;
        Ok(())
    }

    /// Flushes and returns the underlying writer.
    pub fn finish(mut self) -> Result<W, ViewError> {
        self.out.flush()?;
        Ok(self.out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn model_text(scene: &Scene) -> String {
        let mut out = Vec::new();
        let model = RobotModel::default();
        let dynamics = Dynamics::new(&model).unwrap();
        write_mjcf(&mut out, &model, &dynamics, scene, &MjcfOptions::default()).unwrap();
        String::from_utf8(out).unwrap()
    }

    #[test]
    fn the_model_has_the_names_of_spec_8_3() {
        let text = model_text(&Scene::default());
        for name in [
            "<joint name=\"theta1\" type=\"hinge\"",
            "<joint name=\"theta2\" type=\"hinge\"",
            "<joint name=\"theta3\" type=\"hinge\"",
            "<joint name=\"d4\" type=\"slide\"",
            "<joint name=\"elbow1\" type=\"hinge\"",
            "<joint name=\"elbow2\" type=\"hinge\"",
            "<site name=\"tool\"",
            "<position name=\"theta1\" joint=\"theta1\"",
            "<position name=\"d4\" joint=\"d4\"",
            "<connect name=\"platform\"",
        ] {
            assert!(text.contains(name), "missing {name}");
        }
        // Limits in radians and metres.
        assert!(text.contains(&format!(
            "range=\"{} {}\"",
            (-135f64).to_radians(),
            135f64.to_radians()
        )));
        assert!(text.contains("range=\"0 0.1\""));
    }

    #[test]
    fn scene_boxes_become_static_geoms_with_escaped_names() {
        let scene = Scene {
            boxes: vec![crate::SceneBox {
                name: "a<b>".to_owned(),
                min: [100.0, 200.0, 0.0],
                max: [200.0, 300.0, 50.0],
            }],
        };
        let text = model_text(&scene);
        assert!(text.contains(
            "<geom name=\"scene_a&lt;b&gt;\" type=\"box\" pos=\"0.15 0.25 0.025\" size=\"0.05 0.05 0.025\""
        ));
    }

    #[test]
    fn the_companion_rows_hold_fk_in_metres() {
        let mut writer = QposWriter::new(Vec::new(), &RobotModel::default()).unwrap();
        let row = JointCsvRow { t: 0.0, line: 2, joints: Joints::default(), velocity: None };
        writer.write(&row).unwrap();
        let text = String::from_utf8(writer.finish().unwrap()).unwrap();
        let mut lines = text.lines();
        assert_eq!(lines.next(), Some(QPOS_HEADER));
        let values: Vec<f64> =
            lines.next().unwrap().split(',').map(|v| v.parse().unwrap()).collect();
        assert_eq!(values.len(), 11);
        approx::assert_abs_diff_eq!(values[8], 0.460798724079689, epsilon = 1e-12);
        approx::assert_abs_diff_eq!(values[9], 0.1, epsilon = 1e-12);
    }
}
