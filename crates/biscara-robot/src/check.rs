//! `check`: a program's samples run on the virtual robot, every problem collected and grouped.

use std::fmt;

use biscara_dynamics::Dynamics;
use biscara_interpolate::CartesianSample;
use biscara_joints::{JointSolver, LIMIT_TOLERANCE, Peak, Peaks, central_differences, user_unit};
use biscara_kinematics::{Joint, Joints, KinematicsError, RobotModel, Shortfall};

use crate::collision::{scene_collisions, self_collisions};
use crate::{Scene, VirtualRobot};

/// The kinds of problem of docs/virtual-robot.md, in the order reports list them at equal times.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum ProblemKind {
    /// A pose no configuration of the robot reaches (or only beyond a type-2 singularity).
    Unreachable,
    /// A joint outside its position limits.
    JointLimit,
    /// A joint faster than `joint_max_velocity`.
    VelocityLimit,
    /// A joint accelerating harder than `joint_max_acceleration`.
    AccelerationLimit,
    /// A pose within `singularity_margin` of a type-1 or type-2 singularity.
    Singularity,
    /// Two links closer than `link_width`, or the distal links folded onto each other.
    SelfCollision,
    /// A part of the body inside a box of the scene.
    SceneCollision,
    /// What only the tool can get wrong (docs/motion.md): a laser burning during a rapid (G0)
    /// move.
    Tool,
    /// A motor's torque (force for d4) beyond its `peak` (docs/dynamics.md).
    TorqueLimit,
    /// A motor's RMS torque over the whole program beyond its `rated` torque: the program
    /// cannot be repeated without a pause (docs/dynamics.md).
    RmsTorque,
}

impl ProblemKind {
    /// Every kind, in the order reports list them at equal times.
    pub const ALL: [ProblemKind; 10] = [
        ProblemKind::Unreachable,
        ProblemKind::JointLimit,
        ProblemKind::VelocityLimit,
        ProblemKind::AccelerationLimit,
        ProblemKind::Singularity,
        ProblemKind::SelfCollision,
        ProblemKind::SceneCollision,
        ProblemKind::Tool,
        ProblemKind::TorqueLimit,
        ProblemKind::RmsTorque,
    ];

    /// The kind whose [`ProblemKind::name`] is `name`.
    pub fn from_name(name: &str) -> Option<ProblemKind> {
        ProblemKind::ALL.into_iter().find(|kind| kind.name() == name)
    }

    /// The `kind` string of `check --json` (README.md).
    pub fn name(self) -> &'static str {
        match self {
            ProblemKind::Unreachable => "unreachable",
            ProblemKind::JointLimit => "joint_limit",
            ProblemKind::VelocityLimit => "velocity_limit",
            ProblemKind::AccelerationLimit => "acceleration_limit",
            ProblemKind::Singularity => "singularity",
            ProblemKind::SelfCollision => "self_collision",
            ProblemKind::SceneCollision => "scene_collision",
            ProblemKind::Tool => "tool",
            ProblemKind::TorqueLimit => "torque_limit",
            ProblemKind::RmsTorque => "rms_torque",
        }
    }

    fn is_derivative(self) -> bool {
        matches!(
            self,
            ProblemKind::VelocityLimit | ProblemKind::AccelerationLimit | ProblemKind::TorqueLimit
        )
    }
}

impl fmt::Display for ProblemKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// One problem: a run of consecutive samples with the same kind of problem on the same subject
/// (joint, chain, link pair, part and box), reported once with its time span.
#[derive(Debug, Clone, PartialEq)]
pub struct Problem {
    /// What kind of problem.
    pub kind: ProblemKind,
    /// What it concerns: `theta1`, `chain 1`, `proximal link 1 and distal link 2`,
    /// `gripper in pallet`, ….
    pub subject: String,
    /// 1-based program line of the first sample with the problem.
    pub line: usize,
    /// Program line of the last sample with the problem.
    pub line_end: usize,
    /// Time of the first sample with the problem, s.
    pub t_start: f64,
    /// Time of the last sample with the problem, s.
    pub t_end: f64,
    /// Number of samples with the problem.
    pub samples: u64,
    /// The pose `[x, y, z, c]` (mm, degrees) at the first sample.
    pub pose: [f64; 4],
    /// Time of the worst sample, s.
    pub t_worst: f64,
    /// Program line of the worst sample.
    pub line_worst: usize,
    /// The pose at the worst sample.
    pub pose_worst: [f64; 4],
    /// What is wrong at the worst sample, with its numbers.
    pub detail: String,
}

impl Problem {
    /// A one-line description: the worst sample's detail and the time span.
    pub fn message(&self) -> String {
        if self.samples == 1 {
            format!("{} at t = {:.3} s", self.detail, self.t_start)
        } else {
            format!(
                "{} (worst at t = {:.3} s, line {}); {} samples from t = {:.3} to {:.3} s",
                self.detail, self.t_worst, self.line_worst, self.samples, self.t_start, self.t_end
            )
        }
    }
}

/// The smallest singularity angle met along the program.
#[derive(Debug, Clone, PartialEq)]
pub struct SingularityDistance {
    /// The angle of docs/kinematics.md, degrees (0 at the singularity).
    pub angle_deg: f64,
    /// Which singularity (`type-2 singularity`, `type-1 singularity of chain 1`).
    pub kind: String,
    /// Program line where it occurs.
    pub line: usize,
    /// Time where it occurs, s.
    pub t: f64,
}

/// One motor's torques over the program (docs/dynamics.md): N·m for θ1–θ3, N for d4.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MotorTorque {
    /// The largest |torque|, with the motor's `peak` as its limit, its line and time.
    pub peak: Peak,
    /// The root mean square of the torque over the program's duration.
    pub rms: f64,
    /// The motor's `rated` (continuous) torque.
    pub rated: f64,
}

/// Figures of the whole program.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Summary {
    /// Number of samples.
    pub samples: u64,
    /// Time of the last sample, s.
    pub duration_s: f64,
    /// Length of the XYZ path (sum of the distances between samples), mm.
    pub path_length_mm: f64,
    /// Peak joint velocities and accelerations (central differences), each on the line of the
    /// later of its three samples.
    pub peaks: Peaks,
    /// The smallest singularity angle over the reachable samples; `None` when none was.
    pub min_singularity: Option<SingularityDistance>,
    /// Each motor's peak and RMS torque, `[theta1, theta2, theta3, d4]` (inverse dynamics of the
    /// central differences, with the payload while the gripper holds it), when the robot has
    /// `motors`.
    pub torques: Option<[MotorTorque; 4]>,
}

/// What `check` found: the problems in time order and the summary.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Report {
    /// Every problem, ordered by start time (then kind and subject).
    pub problems: Vec<Problem>,
    /// Figures of the whole program.
    pub summary: Summary,
}

impl Report {
    /// Whether the program is clean.
    pub fn ok(&self) -> bool {
        self.problems.is_empty()
    }
}

struct Finding {
    kind: ProblemKind,
    subject: String,
    /// How bad, in the finding's own measure (larger is worse).
    severity: f64,
    detail: String,
}

#[derive(Clone, Copy)]
struct SampleInfo {
    index: u64,
    t: f64,
    line: usize,
    pose: [f64; 4],
    gripper: bool,
}

/// The motors' model and what is summed over the program for the RMS torques.
struct MotorCheck {
    dynamics: Dynamics,
    /// Each motor's ∫ τ² dt over the samples with central differences, and that time.
    squares: [f64; 4],
    time: f64,
    /// The first sample, where the RMS problems are reported.
    first: Option<SampleInfo>,
    last: Option<SampleInfo>,
}

struct Open {
    problem: Problem,
    severity: f64,
    last_index: u64,
}

#[derive(Clone, Copy)]
struct Solved {
    info: SampleInfo,
    q: [f64; 4],
}

/// Runs samples on the virtual robot and collects every problem (docs/virtual-robot.md), without
/// stopping at the first: unreachable poses, joint position, velocity and acceleration limits,
/// near-singular poses, self-collisions and collisions with the scene. Consecutive samples with the
/// same problem on the same subject become one [`Problem`] with its time span.
///
/// Feed the samples in order with [`Checker::push`], then call [`Checker::finish`]. Memory holds
/// three samples and the open problems, not the trajectory.
///
/// Velocities and accelerations are central finite differences of the joint positions over
/// three consecutive reachable samples, as in the joint CSV; they are reported on the line of
/// the later sample (the same motion, except at a corner, where the difference measures the
/// start of the next motion).
pub struct Checker {
    robot: VirtualRobot,
    scene: Scene,
    solver: JointSolver,
    /// Velocity and acceleration limits, radians or mm per second (squared).
    max_velocity: [f64; 4],
    max_acceleration: [f64; 4],
    /// The same in user units, for reports.
    max_velocity_user: [f64; 4],
    max_acceleration_user: [f64; 4],
    window: [Option<Solved>; 2],
    open: Vec<Open>,
    closed: Vec<Problem>,
    summary: Summary,
    previous_pose: Option<[f64; 4]>,
    count: u64,
    motors: Option<Box<MotorCheck>>,
}

fn unit(joint: Joint) -> &'static str {
    if joint.is_revolute() { "°" } else { " mm" }
}

impl Checker {
    /// A checker for `model` in `scene`.
    pub fn new(model: &RobotModel, scene: Scene) -> Checker {
        let robot = model.robot();
        let to_internal = |values: [f64; 4]| {
            let mut values = values;
            for value in &mut values[..3] {
                *value = value.to_radians();
            }
            values
        };
        let velocity = robot.joint_max_velocity.to_array();
        let acceleration = robot.joint_max_acceleration.to_array();
        let mut summary = Summary { peaks: Peaks::new(robot), ..Summary::default() };
        // A robot whose model cannot be built has been refused where it was loaded.
        let dynamics = Dynamics::new(model).ok().filter(|dynamics| dynamics.motors().is_some());
        if let Some(motors) = dynamics.as_ref().and_then(Dynamics::motors) {
            summary.torques = Some(std::array::from_fn(|j| MotorTorque {
                peak: Peak::against(motors[j].peak),
                rms: 0.0,
                rated: motors[j].rated,
            }));
        }
        let motors = dynamics.map(|dynamics| {
            Box::new(MotorCheck { dynamics, squares: [0.0; 4], time: 0.0, first: None, last: None })
        });
        Checker {
            robot: VirtualRobot::new(model),
            scene,
            solver: JointSolver::new(model.kinematics()),
            max_velocity: to_internal(velocity),
            max_acceleration: to_internal(acceleration),
            max_velocity_user: velocity,
            max_acceleration_user: acceleration,
            window: [None, None],
            open: Vec::new(),
            closed: Vec::new(),
            summary,
            previous_pose: None,
            count: 0,
            motors,
        }
    }

    /// Checks the next sample.
    pub fn push(&mut self, sample: &CartesianSample) {
        let info = SampleInfo {
            index: self.count,
            t: sample.t,
            line: sample.line,
            pose: sample.pose,
            gripper: sample.gripper,
        };
        if let Some(motors) = &mut self.motors {
            // The RMS problems are reported at the program's first motion (the start sample
            // has line 0).
            if motors.first.is_none_or(|first| first.line == 0) {
                motors.first = Some(info);
            }
            motors.last = Some(info);
        }
        self.count += 1;
        self.summary.samples = self.count;
        self.summary.duration_s = sample.t;
        if let Some(previous) = self.previous_pose {
            let d: f64 = (0..3).map(|i| (sample.pose[i] - previous[i]).powi(2)).sum();
            self.summary.path_length_mm += d.sqrt();
        }
        self.previous_pose = Some(sample.pose);

        let mut findings = Vec::new();
        let solved = self.solve(&info, &mut findings);
        for finding in findings {
            self.record(info, finding);
        }
        match solved {
            Some(joints) => {
                let current = Solved { info, q: joints.to_array() };
                if let [Some(before), Some(middle)] = self.window {
                    let mut findings = Vec::new();
                    self.derivatives(&before, &middle, &current, &mut findings);
                    // At the last sample of a motion the differences measure the start of
                    // the next one: report them on its line.
                    let mut info = middle.info;
                    info.line = current.info.line;
                    for finding in findings {
                        self.record(info, finding);
                    }
                }
                self.window = [self.window[1], Some(current)];
            }
            None => self.window = [None, None],
        }
        let now = info.index;
        self.close_where(|open| {
            let seen = open.last_index;
            // Derivatives and the tool are recorded after the sample is pushed.
            let late = open.problem.kind.is_derivative() || open.problem.kind == ProblemKind::Tool;
            if late { seen + 1 < now } else { seen < now }
        });
    }

    /// Reports a tool problem (docs/motion.md) at the sample last [`Checker::push`]ed: `subject`
    /// names it (`laser on during a rapid move`), `detail` gives its numbers, `severity` ranks
    /// the samples of one run (the worst is shown).
    pub fn push_tool_problem(
        &mut self,
        sample: &CartesianSample,
        subject: &str,
        detail: String,
        severity: f64,
    ) {
        let info = SampleInfo {
            index: self.count.saturating_sub(1),
            t: sample.t,
            line: sample.line,
            pose: sample.pose,
            gripper: sample.gripper,
        };
        let finding =
            Finding { kind: ProblemKind::Tool, subject: subject.to_owned(), severity, detail };
        self.record(info, finding);
    }

    /// Ends the run: the problems in time order and the summary.
    pub fn finish(mut self) -> Report {
        self.close_where(|_| true);
        self.rms_torques();
        let mut problems = self.closed;
        problems.sort_by(|a, b| {
            a.t_start
                .total_cmp(&b.t_start)
                .then(a.kind.cmp(&b.kind))
                .then_with(|| a.subject.cmp(&b.subject))
        });
        Report { problems, summary: self.summary }
    }

    /// IK, limits, singularity and collisions of one sample; the joints when it is reachable.
    fn solve(&mut self, info: &SampleInfo, findings: &mut Vec<Finding>) -> Option<Joints> {
        let solution = match self.solver.reach(&info.pose) {
            Ok(solution) => solution,
            Err(err) => {
                findings.push(unreachable(&err));
                return None;
            }
        };
        let model = *self.solver.model();
        let joints = solution.joints;
        for violation in self.solver.limit_violations(&joints) {
            let excess = violation.excess();
            let joint = violation.joint;
            let [min, max] = violation.limits;
            findings.push(Finding {
                kind: ProblemKind::JointLimit,
                subject: joint.name().to_owned(),
                severity: excess,
                detail: format!(
                    "{joint} = {:.3}{u} is outside its limits [{}, {}]{u} by {excess:.3}{u}",
                    violation.value,
                    round(min),
                    round(max),
                    u = unit(joint),
                ),
            });
        }
        let angles = solution.configuration.singularity();
        let (kind, angle) = angles.nearest();
        let angle_deg = angle.to_degrees();
        let closer = self
            .summary
            .min_singularity
            .as_ref()
            .is_none_or(|nearest| angle_deg < nearest.angle_deg);
        if closer {
            self.summary.min_singularity = Some(SingularityDistance {
                angle_deg,
                kind: kind.to_string(),
                line: info.line,
                t: info.t,
            });
        }
        if let Err(KinematicsError::NearSingular { kind, angle_deg, margin_deg }) =
            model.check_singularity(&solution.configuration)
        {
            findings.push(Finding {
                kind: ProblemKind::Singularity,
                subject: kind.to_string(),
                severity: margin_deg - angle_deg,
                detail: format!(
                    "{angle_deg:.3}° from a {kind}, closer than the margin of {margin_deg}°"
                ),
            });
        }
        let pose = solution.pose;
        let body = self.robot.body_at(solution.configuration, pose.z, pose.phi);
        let width = body.geometry.link_width;
        for hit in self_collisions(&body) {
            findings.push(Finding {
                kind: ProblemKind::SelfCollision,
                subject: format!("{} and {}", hit.first, hit.second),
                severity: width - hit.distance_mm,
                detail: if (hit.first, hit.second)
                    == (crate::LinkName::Distal1, crate::LinkName::Distal2)
                {
                    format!(
                        "the distal links fold onto each other: the elbows are {:.3} mm apart, \
                         closer than the link width {} mm",
                        hit.distance_mm, width
                    )
                } else {
                    format!(
                        "{} and {} are {:.3} mm apart, closer than the link width {} mm",
                        hit.first, hit.second, hit.distance_mm, width
                    )
                },
            });
        }
        for hit in scene_collisions(&body, &self.scene) {
            let name = &self.scene.boxes[hit.box_index].name;
            findings.push(Finding {
                kind: ProblemKind::SceneCollision,
                subject: format!("{} in {name}", hit.part),
                severity: hit.depth_mm,
                detail: format!("the {} reaches {:.3} mm into {name}", hit.part, hit.depth_mm),
            });
        }
        Some(joints)
    }

    /// Velocity and acceleration at `middle` from its neighbours.
    fn derivatives(
        &mut self,
        before: &Solved,
        middle: &Solved,
        after: &Solved,
        findings: &mut Vec<Finding>,
    ) {
        let span = after.info.t - before.info.t;
        let (dt_back, dt_ahead) = (middle.info.t - before.info.t, after.info.t - middle.info.t);
        if !(span > 0.0 && dt_back > 0.0 && dt_ahead > 0.0) {
            return;
        }
        let (velocities, accelerations) = central_differences(
            (before.info.t, &before.q),
            (middle.info.t, &middle.q),
            (after.info.t, &after.q),
        );
        self.torques(middle, span / 2.0, velocities, accelerations, findings, after.info.line);
        self.summary.peaks.push(after.info.line, middle.info.t, &velocities, &accelerations);
        for (j, joint) in Joint::ALL.into_iter().enumerate() {
            let (velocity, acceleration) = (velocities[j], accelerations[j]);
            let checks = [
                (
                    velocity,
                    self.max_velocity[j],
                    self.max_velocity_user[j],
                    ProblemKind::VelocityLimit,
                    "velocity",
                    "/s",
                ),
                (
                    acceleration,
                    self.max_acceleration[j],
                    self.max_acceleration_user[j],
                    ProblemKind::AccelerationLimit,
                    "acceleration",
                    "/s²",
                ),
            ];
            for (value, limit, limit_user, kind, what, per) in checks {
                if value.abs() > limit * (1.0 + LIMIT_TOLERANCE) {
                    let magnitude = user_unit(joint, value.abs());
                    findings.push(Finding {
                        kind,
                        subject: joint.name().to_owned(),
                        severity: magnitude / limit_user,
                        detail: format!(
                            "{joint} {what} {magnitude:.3}{u}{per} exceeds its limit {}{u}{per}",
                            round(limit_user),
                            u = unit(joint),
                        ),
                    });
                }
            }
        }
    }

    /// The motors' torques at `middle` from its velocity and acceleration: the peaks, the sums
    /// of the RMS and the problems beyond a peak (reported on `line`).
    fn torques(
        &mut self,
        middle: &Solved,
        weight: f64,
        velocity: [f64; 4],
        acceleration: [f64; 4],
        findings: &mut Vec<Finding>,
        line: usize,
    ) {
        let Some(motors) = &mut self.motors else { return };
        let Some(figures) = &mut self.summary.torques else { return };
        let dynamics = &motors.dynamics;
        let payload = dynamics.held_payload(middle.info.gripper);
        // At a parallel singularity the torques are unbounded: the singularity is reported.
        let Ok(torques) = dynamics.torques(middle.q, velocity, acceleration, payload) else {
            return;
        };
        motors.time += weight;
        for (j, joint) in Joint::ALL.into_iter().enumerate() {
            let (torque, figure) = (torques[j], &mut figures[j]);
            motors.squares[j] += torque * torque * weight;
            let magnitude = torque.abs();
            figure.peak.offer(magnitude, line, middle.info.t);
            let peak = figure.peak.limit;
            if magnitude > peak * (1.0 + LIMIT_TOLERANCE) {
                let unit = torque_unit(joint);
                findings.push(Finding {
                    kind: ProblemKind::TorqueLimit,
                    subject: joint.name().to_owned(),
                    severity: magnitude / peak,
                    detail: format!(
                        "{joint}'s motor needs {} {unit}, beyond its peak {} {unit}",
                        fixed_torque(torque),
                        round(peak)
                    ),
                });
            }
        }
    }

    /// The RMS torques of the program, and a problem for each motor beyond its `rated` torque.
    fn rms_torques(&mut self) {
        let (Some(motors), Some(figures)) = (&self.motors, &mut self.summary.torques) else {
            return;
        };
        let (Some(first), Some(last)) = (motors.first, motors.last) else { return };
        if motors.time <= 0.0 {
            return;
        }
        for (j, joint) in Joint::ALL.into_iter().enumerate() {
            let figure = &mut figures[j];
            figure.rms = (motors.squares[j] / motors.time).sqrt();
            if figure.rms <= figure.rated * (1.0 + LIMIT_TOLERANCE) {
                continue;
            }
            let unit = torque_unit(joint);
            let peak = figure.peak;
            self.closed.push(Problem {
                kind: ProblemKind::RmsTorque,
                subject: joint.name().to_owned(),
                line: first.line,
                line_end: last.line,
                t_start: first.t,
                t_end: last.t,
                samples: self.count,
                pose: first.pose,
                t_worst: peak.t,
                line_worst: peak.line,
                pose_worst: first.pose,
                detail: format!(
                    "{joint}'s motor's RMS torque over the program {} {unit} exceeds its rated \
                     {} {unit}: the program cannot be repeated without a pause",
                    fixed_torque(figure.rms),
                    round(figure.rated)
                ),
            });
        }
    }

    fn record(&mut self, info: SampleInfo, finding: Finding) {
        let open = self.open.iter_mut().find(|open| {
            open.problem.kind == finding.kind && open.problem.subject == finding.subject
        });
        match open {
            Some(open) => {
                let problem = &mut open.problem;
                problem.t_end = info.t;
                problem.line_end = info.line;
                problem.samples += 1;
                open.last_index = info.index;
                if finding.severity > open.severity {
                    open.severity = finding.severity;
                    problem.t_worst = info.t;
                    problem.line_worst = info.line;
                    problem.pose_worst = info.pose;
                    problem.detail = finding.detail;
                }
            }
            None => self.open.push(Open {
                problem: Problem {
                    kind: finding.kind,
                    subject: finding.subject,
                    line: info.line,
                    line_end: info.line,
                    t_start: info.t,
                    t_end: info.t,
                    samples: 1,
                    pose: info.pose,
                    t_worst: info.t,
                    line_worst: info.line,
                    pose_worst: info.pose,
                    detail: finding.detail,
                },
                severity: finding.severity,
                last_index: info.index,
            }),
        }
    }

    fn close_where(&mut self, stale: impl Fn(&Open) -> bool) {
        let mut index = 0;
        while index < self.open.len() {
            if stale(&self.open[index]) {
                let open = self.open.swap_remove(index);
                self.closed.push(open.problem);
            } else {
                index += 1;
            }
        }
    }
}

/// The finding for a pose the robot cannot reach (or only beyond a type-2 singularity).
fn unreachable(err: &KinematicsError) -> Finding {
    let (subject, severity) = match *err {
        KinematicsError::Unreachable { chain, shortfall_mm, side, .. } => (
            format!(
                "{chain} {}",
                match side {
                    Shortfall::TooFar => "too far",
                    Shortfall::TooClose => "too close",
                }
            ),
            shortfall_mm,
        ),
        KinematicsError::BeyondType2 { .. } => ("assembly mode".to_owned(), 0.0),
        _ => ("pose".to_owned(), 0.0),
    };
    Finding { kind: ProblemKind::Unreachable, subject, severity, detail: err.to_string() }
}

/// The unit of a motor's torque: N·m, or N for d4's force.
pub(crate) fn torque_unit(joint: Joint) -> &'static str {
    if joint.is_revolute() { "N·m" } else { "N" }
}

/// A torque for a message, to the mN·m.
fn fixed_torque(value: f64) -> String {
    biscara_text::fixed(value, 3)
}

/// A limit as written in the robot file: without trailing zeros.
fn round(value: f64) -> f64 {
    (value * 1e6).round() / 1e6
}
