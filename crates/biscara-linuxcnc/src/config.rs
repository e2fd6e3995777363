//! The configuration's files, rendered from the templates with a robot's numbers.

use biscara_kinematics::{Pose, Robot, RobotModel, Sign, ToolKind};
use biscara_robot::{Rectangle, Workspace};

use crate::LinuxcncError;
use crate::limits::{AxisLimits, derive_axis_limits};

/// The kinematics component's source (LinuxCNC 2.9's API, built with `halcompile`).
pub const COMPONENT_SOURCE: &str = include_str!("../templates/biscarakins.comp");
/// The kinematics component's name: the module LinuxCNC loads and the file `halcompile` builds.
pub const COMPONENT_NAME: &str = "biscarakins";
/// The configuration's INI file name.
pub const INI_FILE: &str = "biscara.ini";
/// The headless display's file name.
pub const RUNNER_FILE: &str = "biscara_run.py";
/// The robot file a configuration carries: the robot its files were written for.
pub const ROBOT_FILE: &str = "robot.json";

/// The INI's template.
pub(crate) const INI: &str = include_str!("../templates/biscara.ini");
/// `biscara.hal`'s template.
pub(crate) const HAL: &str = include_str!("../templates/biscara.hal");
const SIM_HAL: &str = include_str!("../templates/sim.hal");
const HARDWARE_HAL: &str = include_str!("../templates/hardware.hal");
const RUNNER: &str = include_str!("../templates/biscara_run.py");
const README: &str = include_str!("../templates/README.md");

/// Where LinuxCNC's axis limits come from.
///
/// The first paragraph of each variant's documentation is the help of `--limits`'s values (the
/// `clap` feature).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
pub enum AxisLimitSource {
    /// Derived from the joint limits: LinuxCNC's planner cannot exceed a joint's limit in the
    /// workspace rectangle.
    ///
    /// Derived over the workspace rectangle (or the configuration's region), so that LinuxCNC's
    /// planner cannot exceed any joint's velocity or acceleration limit there.
    #[default]
    Derived,
    /// The robot file's Cartesian motion limits as they are (LinuxCNC's planner then exceeds the
    /// joints' limits; for comparison).
    ///
    /// The robot's `motion` limits (`rapid_velocity`, `acceleration`, `rapid_rotation`,
    /// `rotation_acceleration`): what an integrator would write without thinking of the joints.
    Cartesian,
}

/// The region of the XY plane a configuration is made for: its axis limits are derived over it
/// and LinuxCNC's soft limits keep the robot inside it.
#[derive(Debug, Clone, PartialEq)]
pub struct Region {
    /// The rectangle, millimetres.
    pub rectangle: Rectangle,
    /// Where it comes from, for the INI's comments (`the extent of job.ngc plus 10 mm`).
    pub origin: String,
    /// The pose `[x, y, z, c]` (mm, degrees) the robot parks at inside the region: where
    /// homing ends (each joint moves there in joint space) and where G28 and G30 go. `None`:
    /// the robot's home pose (all joints 0), which must then lie inside the region.
    pub park: Option<[f64; 4]>,
}

/// What a configuration is made for.
#[derive(Debug, Clone, PartialEq)]
pub struct ConfigOptions {
    /// The tool whose codes the HAL wires (M3/M4/M5 and S).
    pub tool: ToolKind,
    /// Where the axis limits come from.
    pub limits: AxisLimitSource,
    /// The workspace grid step the rectangle and the derived limits are computed on, mm.
    pub step: f64,
    /// The region the job stays in (`None`: the workspace rectangle, and soft limits at the
    /// robot's reach).
    pub region: Option<Region>,
}

impl Default for ConfigOptions {
    fn default() -> Self {
        ConfigOptions {
            tool: ToolKind::Gripper,
            limits: AxisLimitSource::Derived,
            step: 2.0,
            region: None,
        }
    }
}

/// The rectangle `[x0, x1] × [y0, y1]` grown by `margin` mm on every side.
pub fn grow(rectangle: &Rectangle, margin: f64) -> Rectangle {
    Rectangle {
        min: [rectangle.min[0] - margin, rectangle.min[1] - margin],
        max: [rectangle.max[0] + margin, rectangle.max[1] + margin],
    }
}

/// Fails unless every point of `region` (a grid of at most `step` mm, edges included) is
/// reachable: inside the joint limits and away from the singularities.
pub(crate) fn check_region(
    model: &RobotModel,
    region: &Region,
    step: f64,
) -> Result<(), LinuxcncError> {
    let rectangle = &region.rectangle;
    let finite = rectangle.min.iter().chain(&rectangle.max).all(|value| value.is_finite());
    if !finite || rectangle.width() < 0.0 || rectangle.height() < 0.0 {
        return Err(LinuxcncError::Region {
            region: region.origin.clone(),
            message: "not a rectangle".to_owned(),
        });
    }
    let kinematics = model.kinematics();
    let [x, y, z, c] = region.park.unwrap_or_else(|| model.home_position());
    let inside = (rectangle.min[0]..=rectangle.max[0]).contains(&x)
        && (rectangle.min[1]..=rectangle.max[1]).contains(&y);
    if !inside || kinematics.inverse_checked(&Pose::from_degrees(x, y, z, c)).is_err() {
        let what = if region.park.is_some() { "park" } else { "home" };
        return Err(LinuxcncError::Region {
            region: region.origin.clone(),
            message: format!(
                "the robot's {what} pose ({x:.3}, {y:.3}, {z:.3}, {c:.3}) is not a reachable \
                 pose inside it"
            ),
        });
    }
    let columns = ((rectangle.width() / step).ceil() as usize).max(1);
    let rows = ((rectangle.height() / step).ceil() as usize).max(1);
    for i in 0..=columns {
        for j in 0..=rows {
            let x = rectangle.min[0] + rectangle.width() * i as f64 / columns as f64;
            let y = rectangle.min[1] + rectangle.height() * j as f64 / rows as f64;
            if !kinematics.reachable(x, y) {
                return Err(LinuxcncError::Region {
                    region: region.origin.clone(),
                    message: format!(
                        "({x:.1}, {y:.1}) mm is outside the workspace (a joint limit or a \
                         singularity): `biscara workspace` shows where the robot reaches"
                    ),
                });
            }
        }
    }
    Ok(())
}

/// One file of a configuration.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ConfigFile {
    /// File name inside the configuration folder.
    pub name: &'static str,
    /// Contents.
    pub contents: String,
    /// Whether the file must be executable (the headless display).
    pub executable: bool,
}

/// A complete LinuxCNC configuration for one robot: its files and the axis limits in them.
#[derive(Debug, Clone, PartialEq)]
pub struct Configuration {
    /// The files, in the order they are listed in the configuration's README.
    pub files: Vec<ConfigFile>,
    /// The axis limits written into the INI.
    pub limits: AxisLimits,
}

/// Writes a number the way LinuxCNC reads it back exactly: the shortest decimal that parses to
/// the same `f64`.
fn number(value: f64) -> String {
    format!("{value}")
}

/// A number rounded down to 3 significant decimals (a limit never rounds up).
fn limit(value: f64) -> String {
    number((value * 1000.0).floor() / 1000.0)
}

/// Replaces every `@KEY@` of `template` with its value.
///
/// # Panics
/// When a placeholder is left without a value: the templates and this crate disagree, a bug
/// that the tests catch.
fn render(template: &str, values: &[(String, String)]) -> String {
    let text = fill(template, values);
    if let Some(start) = text.find('@') {
        let rest = &text[start + 1..];
        if let Some(end) = rest.find('@') {
            let key = &rest[..end];
            assert!(
                !key.chars().all(|c| c.is_ascii_uppercase() || c.is_ascii_digit() || c == '_'),
                "template placeholder @{key}@ has no value"
            );
        }
    }
    text
}

/// Replaces every `@KEY@` of `template` that has a value in `values`; the others stay.
pub(crate) fn fill(template: &str, values: &[(String, String)]) -> String {
    let mut text = template.to_owned();
    for (key, value) in values {
        text = text.replace(&format!("@{key}@"), value);
    }
    text
}

/// The HAL lines of the tool: `(biscara.hal's nets, hardware.hal's commented examples)`.
fn tool_nets(tool: ToolKind) -> Result<(String, String), LinuxcncError> {
    let (nets, hardware) = match tool {
        ToolKind::Gripper => (
            "# M3 picks (closes the gripper), M4 places (opens it), M5 switches it off. The\n\
             # pick/place dwell is the program's G4 after M3/M4, as `biscara post` writes it.\n\
             net gripper-close spindle.0.forward\n\
             net gripper-open spindle.0.reverse\n\
             net gripper-on spindle.0.on",
            "# net gripper-close => IO.gripper-close-out\n\
             # net gripper-open  => IO.gripper-open-out",
        ),
        ToolKind::Laser => (
            "# M3 (constant power) and M4 switch the laser on, M5 off; S is the power, 0 to the\n\
             # robot file's max_power (LinuxCNC holds S constant: Grbl's M4 dynamic power, which\n\
             # scales with speed, is not emulated).\n\
             net laser-on spindle.0.on\n\
             net laser-power spindle.0.speed-out",
            "# net laser-on    => IO.laser-enable-out\n\
             # net laser-power => IO.laser-pwm-value (scaled to your PWM generator)",
        ),
        ToolKind::Spindle => (
            "# M3 clockwise, M4 counter-clockwise, M5 off; S in rpm.\n\
             net spindle-cw spindle.0.forward\n\
             net spindle-ccw spindle.0.reverse\n\
             net spindle-rpm spindle.0.speed-out",
            "# net spindle-cw  => IO.spindle-forward-out\n\
             # net spindle-ccw => IO.spindle-reverse-out\n\
             # net spindle-rpm => IO.spindle-speed-value",
        ),
        ToolKind::Pen => (
            "# M3 and M4 put the pen down, M5 lifts it.\n\
             net pen-down spindle.0.on",
            "# net pen-down => IO.pen-solenoid-out",
        ),
        ToolKind::Extruder => return Err(LinuxcncError::Extruder),
    };
    Ok((nets.to_owned(), hardware.to_owned()))
}

/// The configuration of `model`'s robot: every file, with the axis limits of `options`.
pub fn configuration(
    model: &RobotModel,
    options: &ConfigOptions,
) -> Result<Configuration, LinuxcncError> {
    let robot = model.robot();
    let kinematics = model.kinematics();
    let rectangle = match &options.region {
        Some(region) => {
            check_region(model, region, options.step)?;
            region.rectangle
        }
        None => Workspace::compute(&kinematics, options.step)?.largest_rectangle()?,
    };
    let mut limits = derive_axis_limits(robot, &kinematics, &rectangle, options.step)?;
    if options.limits == AxisLimitSource::Cartesian {
        limits.xy_velocity = robot.motion.rapid_velocity;
        limits.xy_acceleration = robot.motion.acceleration;
        limits.z_velocity = robot.motion.rapid_velocity;
        limits.z_acceleration = robot.motion.acceleration;
        limits.c_velocity = robot.motion.rapid_rotation;
        limits.c_acceleration = robot.motion.rotation_acceleration;
    }
    let (tool_nets, tool_hardware) = tool_nets(options.tool)?;
    let park = options.region.as_ref().and_then(|region| region.park);
    let home = match park {
        Some([x, y, z, c]) => {
            let joints =
                kinematics.inverse_checked(&Pose::from_degrees(x, y, z, c)).map_err(|err| {
                    LinuxcncError::Region {
                        region: String::from("the park pose"),
                        message: err.to_string(),
                    }
                })?;
            let [theta1, theta2, theta3, d4] = joints.joints.to_array();
            [theta1.to_degrees(), theta2.to_degrees(), d4, theta3.to_degrees()]
        }
        None => [0.0; 4],
    };
    let park = park.unwrap_or_else(|| model.home_position());
    let mut values = values(robot, &limits, options, tool_nets, tool_hardware);
    for (joint, value) in home.into_iter().enumerate() {
        values.push((format!("HOME_{joint}"), number(value)));
    }
    let file = |name, template, executable| ConfigFile {
        name,
        contents: render(template, &values),
        executable,
    };
    Ok(Configuration {
        files: vec![
            file("biscarakins.comp", COMPONENT_SOURCE, false),
            file(INI_FILE, INI, false),
            file("biscara.hal", HAL, false),
            file("sim.hal", SIM_HAL, false),
            file("hardware.hal", HARDWARE_HAL, false),
            file(RUNNER_FILE, RUNNER, true),
            ConfigFile { name: "biscara.tbl", contents: tool_table(), executable: false },
            ConfigFile { name: "biscara.var", contents: parameters(park), executable: false },
            ConfigFile { name: ROBOT_FILE, contents: robot_file(robot), executable: false },
            file("README.md", README, false),
        ],
        limits,
    })
}

/// The robot file the configuration carries: `robot` as JSON, every number exact.
fn robot_file(robot: &Robot) -> String {
    let mut text = serde_json::to_string_pretty(robot).unwrap_or_default();
    text.push('\n');
    text
}

/// The tool table: tools 1 to 99 in pockets 1 to 99, of zero length and diameter (what
/// `biscara interpret` assumes without a tool table), so that a program's `T1 M6` runs; replace
/// it with the real tools' lengths for G43.
fn tool_table() -> String {
    (1..=99).map(|tool| format!("T{tool} P{tool} Z0 D0 ;tool {tool}\n")).collect()
}

/// The parameter file: G28's and G30's positions (parameters 5161–5169 and 5181–5189, in
/// machine coordinates) at `park` (the robot's home pose unless the configuration is made for a
/// region), so that G28 and G30 go home as they do in `biscara interpret`; G54 in force (5220).
fn parameters(park: [f64; 4]) -> String {
    let [x, y, z, c] = park;
    let mut text = String::new();
    for start in [5161, 5181] {
        for (offset, value) in [x, y, z, 0.0, 0.0, c, 0.0, 0.0, 0.0].into_iter().enumerate() {
            text += &format!("{} {}\n", start + offset, number(value));
        }
    }
    text += "5220 1\n";
    text
}

/// The INI's comment block on where the axis limits come from.
fn limits_comment(
    robot: &Robot,
    limits: &AxisLimits,
    source: AxisLimitSource,
    region: Option<&Region>,
) -> (String, String) {
    let d = &limits.derivation;
    if source == AxisLimitSource::Cartesian {
        let title = "The robot file's Cartesian motion limits, unchanged.".to_owned();
        let comment =
            "# LinuxCNC's planner limits each axis and knows nothing of the joints: with \
                       these limits\n# it can exceed the joints' velocity and acceleration limits \
                       (use the derived limits,\n# the default of `biscara linuxcnc config`)."
                .to_owned();
        return (title, comment);
    }
    let [x0, y0] = d.rectangle.min;
    let [x1, y1] = d.rectangle.max;
    let title = "Derived from the joint limits so that LinuxCNC's planner, which limits \
                 each axis\n# and knows nothing of the joints, cannot exceed any joint's limit."
        .to_owned();
    let comment = format!(
        "# Where: {place} x {x0:.1} .. {x1:.1} mm, y {y0:.1} .. {y1:.1} mm \
         ({points} grid points,\n\
         # {step} mm apart). {outside}\n\
         # How: with |vx|, |vy| <= V and |ax|, |ay| <= A, a joint angle theta(x, y) has\n\
         #   |theta'| <= G V and |theta''| <= G A + S V^2, G = |dtheta/dx| + |dtheta/dy|,\n\
         #   S = the largest |u' H u| over |ux|, |uy| <= 1 (H: theta's second derivatives),\n\
         # for every direction of motion. Largest on the rectangle: theta1 G = {g1:.4} deg/mm,\n\
         # S = {s1:.5} deg/mm^2; theta2 G = {g2:.4} deg/mm, S = {s2:.5} deg/mm^2; chain 1's distal\n\
         # link (theta3 = C - its turn) G = {g3:.4} deg/mm, S = {s3:.5} deg/mm^2.\n\
         # V = {v:.3} mm/s, bound by {vb};\n\
         # A = {a:.3} mm/s^2, bound by {ab}\n\
         # (the velocity term S V^2 may take at most half of a joint's acceleration limit;\n\
         # V and A are 97 % of these bounds, for what lies between the grid points).\n\
         # C: what theta3's limits ({w3} deg/s, {al3} deg/s^2) leave after the distal link's turn.\n\
         # Z: d4's limits. Cost: at the rectangle's centre theta1's and theta2's velocity limits\n\
         # alone would allow {centre:.1} mm/s along X; LinuxCNC's planner here moves at most\n\
         # {v:.1} mm/s per axis ({diag:.1} mm/s diagonally). `biscara joints` (the time-optimal\n\
         # profile under the joint limits themselves) is faster: `biscara linuxcnc run --stream`\n\
         # plays its trajectory.",
        place = match region {
            Some(region) => format!("the region of {},\n#", region.origin),
            None => "the workspace rectangle".to_owned(),
        },
        outside = if region.is_some() {
            "LinuxCNC's soft limits\n# ([AXIS_X], [AXIS_Y] MIN_LIMIT/MAX_LIMIT) keep the robot inside it."
        } else {
            "Outside it these numbers promise nothing."
        },
        points = d.points,
        step = d.step,
        g1 = d.gradient[0],
        s1 = d.curvature[0],
        g2 = d.gradient[1],
        s2 = d.curvature[1],
        g3 = d.distal[0],
        s3 = d.distal[1],
        v = limits.xy_velocity,
        vb = d.velocity_bound,
        a = limits.xy_acceleration,
        ab = d.acceleration_bound,
        w3 = robot.joint_max_velocity.theta3,
        al3 = robot.joint_max_acceleration.theta3,
        centre = d.centre_speed,
        diag = limits.xy_velocity * std::f64::consts::SQRT_2,
    );
    (title, comment)
}

/// Every placeholder's value.
fn values(
    robot: &Robot,
    limits: &AxisLimits,
    options: &ConfigOptions,
    tool_nets: String,
    tool_hardware: String,
) -> Vec<(String, String)> {
    let joint_limits = robot.joint_limits.to_array();
    let reach = robot.links.l1 + robot.links.l2 + robot.base.b1x.abs().max(robot.base.b2x.abs());
    let (title, comment) = limits_comment(robot, limits, options.limits, options.region.as_ref());
    let [x_min, y_min, x_max, y_max] = match &options.region {
        Some(region) => {
            let r = &region.rectangle;
            [r.min[0], r.min[1], r.max[0], r.max[1]]
        }
        None => [-reach, -reach, reach, reach],
    };
    let traj_velocity = (2.0 * limits.xy_velocity * limits.xy_velocity
        + limits.z_velocity * limits.z_velocity)
        .sqrt();
    let traj_acceleration = (2.0 * limits.xy_acceleration * limits.xy_acceleration
        + limits.z_acceleration * limits.z_acceleration)
        .sqrt();
    let values: Vec<(&str, String)> = vec![
        ("NAME", robot.name.replace(['\n', '\r', '"'], " ")),
        ("XY_VELOCITY", limit(limits.xy_velocity)),
        ("XY_ACCELERATION", limit(limits.xy_acceleration)),
        ("Z_VELOCITY", limit(limits.z_velocity)),
        ("Z_ACCELERATION", limit(limits.z_acceleration)),
        ("C_VELOCITY", limit(limits.c_velocity)),
        ("C_ACCELERATION", limit(limits.c_acceleration)),
        ("TRAJ_VELOCITY", limit(traj_velocity)),
        ("TRAJ_ACCELERATION", limit(traj_acceleration)),
        ("DEFAULT_VELOCITY", limit(limits.xy_velocity / 4.0)),
        ("X_MIN", number(x_min)),
        ("X_MAX", number(x_max)),
        ("Y_MIN", number(y_min)),
        ("Y_MAX", number(y_max)),
        ("Z_MIN", number(robot.lp - joint_limits[3][1])),
        ("Z_MAX", number(robot.lp - joint_limits[3][0])),
        ("LIMITS_TITLE", title),
        ("LIMITS_COMMENT", comment),
        ("MACHINE_HAL", "sim.hal".to_owned()),
        ("STREAM_DEPTH", "4000".to_owned()),
        ("SAMPLER_DEPTH", "16000".to_owned()),
        ("TOOL", options.tool.name().to_owned()),
        ("SOURCE_ID", crate::runner::source_id(COMPONENT_SOURCE)),
        ("TOOL_NETS", tool_nets),
        ("TOOL_HARDWARE", tool_hardware),
    ];
    let mut values: Vec<(String, String)> =
        values.into_iter().map(|(key, value)| (key.to_owned(), value)).collect();
    values.extend(robot_values(robot));
    values
}

/// The placeholders that hold the robot's own numbers: its geometry, modes and joint limits.
pub(crate) fn robot_values(robot: &Robot) -> Vec<(String, String)> {
    let joint_limits = robot.joint_limits.to_array();
    let velocity = robot.joint_max_velocity.to_array();
    let acceleration = robot.joint_max_acceleration.to_array();
    let sign = |sign: Sign| number(sign.factor());
    let mut values: Vec<(String, String)> = [
        ("L1", number(robot.links.l1)),
        ("L2", number(robot.links.l2)),
        ("B1X", number(robot.base.b1x)),
        ("B2X", number(robot.base.b2x)),
        ("LP", number(robot.lp)),
        ("SIGMA1", sign(robot.working_mode.chain1)),
        ("SIGMA2", sign(robot.working_mode.chain2)),
        ("SIGMAA", sign(robot.assembly_mode.0)),
        ("MARGIN", number(robot.singularity_margin)),
    ]
    .into_iter()
    .map(|(key, value)| (key.to_owned(), value))
    .collect();
    for (index, name) in ["THETA1", "THETA2", "THETA3", "D4"].into_iter().enumerate() {
        values.push((format!("{name}_MIN"), number(joint_limits[index][0])));
        values.push((format!("{name}_MAX"), number(joint_limits[index][1])));
        values.push((format!("{name}_VELOCITY"), number(velocity[index])));
        values.push((format!("{name}_ACCELERATION"), number(acceleration[index])));
    }
    values
}
