//! Inverse and forward kinematics of the five-bar + Z + rotary robot (docs/kinematics.md–§1.4).

use std::f64::consts::{PI, TAU};

use nalgebra as na;

use crate::{
    AssemblyMode, Chain, Joint, Joints, KinematicsError, Pose, Robot, RobotError, Shortfall, Sign,
    SingularityKind, WorkingMode,
};

/// The planar five-bar in one configuration: base joints, elbows and platform point, millimetres.
///
/// Both IK and FK produce one; the virtual robot draws it, and the singularity measures and the
/// Jacobian are computed from it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlanarConfiguration {
    /// The base joints `b1`, `b2`.
    pub bases: [na::Point2<f64>; 2],
    /// The elbows `E1`, `E2` (the passive joints between proximal and distal links).
    pub elbows: [na::Point2<f64>; 2],
    /// The platform point `P`, where the distal links meet.
    pub platform: na::Point2<f64>,
}

impl PlanarConfiguration {
    /// `E_i − b_i`, the proximal link of chain `chain` as a vector (length `l1`).
    pub fn proximal(&self, chain: Chain) -> na::Vector2<f64> {
        self.elbows[chain.index()] - self.bases[chain.index()]
    }

    /// `P − E_i`, the distal link of chain `chain` as a vector (length `l2`).
    pub fn distal(&self, chain: Chain) -> na::Vector2<f64> {
        self.platform - self.elbows[chain.index()]
    }

    /// The working mode of this configuration: `σ_i = sign((E_i − b_i) × (P − E_i))`.
    pub fn working_mode(&self) -> WorkingMode {
        let sigma = |chain| Sign::of(self.proximal(chain).perp(&self.distal(chain)));
        WorkingMode::new(sigma(Chain::One), sigma(Chain::Two))
    }

    /// The assembly mode of this configuration: `σ_a = sign((P − E2) × (P − E1))`.
    pub fn assembly_mode(&self) -> AssemblyMode {
        AssemblyMode(Sign::of(self.distal(Chain::Two).perp(&self.distal(Chain::One))))
    }

    /// The absolute angle `ψ_i = atan2(P − E_i)` of chain `chain`'s distal link, radians.
    pub fn distal_angle(&self, chain: Chain) -> f64 {
        let link = self.distal(chain);
        libm::atan2(link.y, link.x)
    }

    /// How far this configuration is from each singularity (docs/kinematics.md).
    pub fn singularity(&self) -> SingularityAngles {
        let type1 = |chain| line_angle(self.proximal(chain), self.distal(chain));
        SingularityAngles {
            type1: [type1(Chain::One), type1(Chain::Two)],
            type2: line_angle(self.distal(Chain::Two), self.distal(Chain::One)),
        }
    }
}

/// The angle between the lines along `a` and `b`, in [0, π/2]: 0 when they are collinear.
fn line_angle(a: na::Vector2<f64>, b: na::Vector2<f64>) -> f64 {
    a.perp(&b).abs().atan2(a.dot(&b).abs())
}

/// Distances from the singularities, as angles in radians (0 at the singularity, at most π/2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SingularityAngles {
    /// For each chain, the angle between its proximal and distal links' lines (type 1: 0 when
    /// the chain is stretched or folded), radians.
    pub type1: [f64; 2],
    /// The angle between the two distal links' lines (type 2: 0 when they are collinear), radians.
    pub type2: f64,
}

impl SingularityAngles {
    /// The smallest of the three angles and the singularity it belongs to.
    pub fn nearest(&self) -> (SingularityKind, f64) {
        let mut nearest = (SingularityKind::Type1(Chain::One), self.type1[0]);
        if self.type1[1] < nearest.1 {
            nearest = (SingularityKind::Type1(Chain::Two), self.type1[1]);
        }
        if self.type2 < nearest.1 {
            nearest = (SingularityKind::Type2, self.type2);
        }
        nearest
    }
}

/// The passive joint angles of the five-bar, radians, each zero at the home pose.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PassiveJoints {
    /// Rotation of chain 1's distal link relative to its proximal link, counter-clockwise about +Z.
    pub elbow1: f64,
    /// Rotation of chain 2's distal link relative to its proximal link, counter-clockwise about +Z.
    pub elbow2: f64,
    /// Rotation of chain 2's distal link relative to chain 1's, at the platform point.
    pub platform: f64,
}

/// The result of inverse kinematics: the joints and the five-bar configuration that reaches a pose.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IkSolution {
    /// The pose that was solved for.
    pub pose: Pose,
    /// The joint values: θ1, θ2 in (−π, π] and θ3 from the single-pose rule
    /// `φ − wrap(ψ1 − ψ1_home)`, each shifted by 2π into its limits when only that makes it fit;
    /// see [`crate::Theta3Unwrapper`] for paths.
    pub joints: Joints,
    /// The five-bar configuration.
    pub configuration: PlanarConfiguration,
    /// `ψ1 − ψ1_home` wrapped into (−π, π]: how far chain 1's distal link has turned from home.
    pub distal_rotation: f64,
}

impl IkSolution {
    /// The assembly mode this solution is in (which need not be the robot's).
    pub fn assembly_mode(&self) -> AssemblyMode {
        self.configuration.assembly_mode()
    }
}

/// The result of forward kinematics: the pose and every passive joint.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FkSolution {
    /// The joint values that were solved for.
    pub joints: Joints,
    /// The tool pose.
    pub pose: Pose,
    /// The five-bar configuration (elbows, platform point).
    pub configuration: PlanarConfiguration,
    /// The passive joint angles.
    pub passive: PassiveJoints,
}

/// The kinematic model of one robot, precomputed from a [`Robot`] in radians and millimetres.
///
/// Solving a pose allocates nothing; the struct is small and `Copy`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Kinematics {
    pub(crate) l1: f64,
    pub(crate) l2: f64,
    pub(crate) bases: [na::Point2<f64>; 2],
    pub(crate) lp: f64,
    pub(crate) working_mode: WorkingMode,
    pub(crate) assembly_mode: AssemblyMode,
    /// Limits in radians (θ) and millimetres (d4).
    pub(crate) limits: [[f64; 2]; 4],
    /// Limits in the user's units: degrees (θ) and millimetres (d4).
    pub(crate) limits_user: [[f64; 2]; 4],
    pub(crate) singularity_margin: f64,
    /// tan(singularity_margin), for the fast test.
    pub(crate) singularity_margin_tan: f64,
    /// ψ1 and ψ2 at the home pose.
    pub(crate) distal_home: [f64; 2],
}

impl Kinematics {
    /// Builds the model of `robot` after validating it.
    pub fn new(robot: &Robot) -> Result<Kinematics, RobotError> {
        robot.validate()?;
        let limits_user = robot.joint_limits.to_array();
        let mut limits = limits_user;
        for range in &mut limits[..3] {
            *range = range.map(f64::to_radians);
        }
        let mut model = Kinematics {
            l1: robot.links.l1,
            l2: robot.links.l2,
            bases: [na::Point2::new(robot.base.b1x, 0.0), na::Point2::new(robot.base.b2x, 0.0)],
            lp: robot.lp,
            working_mode: robot.working_mode,
            assembly_mode: robot.assembly_mode,
            limits,
            limits_user,
            singularity_margin: robot.singularity_margin.to_radians(),
            singularity_margin_tan: robot.singularity_margin.to_radians().tan(),
            distal_home: [0.0; 2],
        };
        // `validate` guarantees b1x − b2x < 2·l2, so the home pose assembles.
        let home = model.planar_forward(0.0, 0.0, robot.assembly_mode).map_err(|err| {
            RobotError::Invalid {
                line: None,
                column: None,
                key: "base".to_owned(),
                message: err.to_string(),
            }
        })?;
        model.distal_home = [home.distal_angle(Chain::One), home.distal_angle(Chain::Two)];
        Ok(model)
    }

    /// Proximal link length `l1`, millimetres.
    pub fn l1(&self) -> f64 {
        self.l1
    }

    /// Distal link length `l2`, millimetres.
    pub fn l2(&self) -> f64 {
        self.l2
    }

    /// The base joints `b1`, `b2`, millimetres.
    pub fn bases(&self) -> [na::Point2<f64>; 2] {
        self.bases
    }

    /// The working mode IK solves in.
    pub fn working_mode(&self) -> WorkingMode {
        self.working_mode
    }

    /// The assembly mode FK solves in and IK solutions must have.
    pub fn assembly_mode(&self) -> AssemblyMode {
        self.assembly_mode
    }

    /// The singularity margin, radians.
    pub fn singularity_margin(&self) -> f64 {
        self.singularity_margin
    }

    /// The limits of `joint`: radians for θ, millimetres for d4.
    pub fn limits(&self, joint: Joint) -> [f64; 2] {
        self.limits[joint as usize]
    }

    /// ψ1 at the home pose: the absolute angle of chain 1's distal link when `q = 0`, radians.
    pub fn distal_home(&self, chain: Chain) -> f64 {
        self.distal_home[chain.index()]
    }

    /// The same model in another working mode (the assembly mode is kept).
    pub fn with_working_mode(mut self, mode: WorkingMode) -> Kinematics {
        self.working_mode = mode;
        self
    }

    /// The same model in another assembly mode (the working mode is kept).
    pub fn with_assembly_mode(mut self, mode: AssemblyMode) -> Kinematics {
        self.assembly_mode = mode;
        self
    }

    /// Inverse kinematics in the robot's working mode, without limit, assembly-mode or
    /// singularity checks: fails only when a chain cannot reach the point.
    ///
    /// Each chain's root is chosen by its σ_i (docs/kinematics.md). The solution reports its
    /// assembly mode; use [`Kinematics::inverse_checked`] to refuse poses the robot cannot take.
    // Inlined so that the solution, returned in a `Result`, is not stored and loaded back:
    // `joints` on the engraving program 0.456 → 0.425 s.
    #[inline(always)]
    pub fn inverse(&self, pose: &Pose) -> Result<IkSolution, KinematicsError> {
        // v − v is 0 for a finite v and NaN otherwise: one test for the four coordinates, and
        // the one to name found only when it fails.
        let spread = finite_zero(pose.x) + finite_zero(pose.y) + finite_zero(pose.z);
        if spread + finite_zero(pose.phi) != 0.0 {
            return Err(not_finite(&[
                ("x", pose.x),
                ("y", pose.y),
                ("z", pose.z),
                ("c", pose.phi),
            ]));
        }
        let (direction1, elbow1) = self.chain_inverse(Chain::One, pose.x, pose.y)?;
        let (direction2, elbow2) = self.chain_inverse(Chain::Two, pose.x, pose.y)?;
        let theta1 = libm::atan2(direction1.y, direction1.x);
        let theta2 = libm::atan2(direction2.y, direction2.x);
        let configuration = PlanarConfiguration {
            bases: self.bases,
            elbows: [elbow1, elbow2],
            platform: pose.platform(),
        };
        let distal_rotation =
            wrap_difference(configuration.distal_angle(Chain::One), self.distal_home[0]);
        let joints = Joints {
            theta1: fit_into(theta1, self.limits[0]),
            theta2: fit_into(theta2, self.limits[1]),
            theta3: fit_into(pose.phi - distal_rotation, self.limits[2]),
            d4: self.lp - pose.z,
        };
        Ok(IkSolution { pose: *pose, joints, configuration, distal_rotation })
    }

    /// The five-bar configuration (elbows and platform) with the tool at `(x, y)` mm, in the
    /// working mode: what the Jacobian needs, without the joint angles and so without the three
    /// `atan2` of [`Kinematics::inverse`]. Fails only when a chain cannot reach the point.
    #[inline]
    pub fn configuration(&self, x: f64, y: f64) -> Result<PlanarConfiguration, KinematicsError> {
        for (what, value) in [("x", x), ("y", y)] {
            if !value.is_finite() {
                return Err(KinematicsError::NotFinite { what });
            }
        }
        let (_, elbow1) = self.chain_inverse(Chain::One, x, y)?;
        let (_, elbow2) = self.chain_inverse(Chain::Two, x, y)?;
        Ok(PlanarConfiguration {
            bases: self.bases,
            elbows: [elbow1, elbow2],
            platform: na::Point2::new(x, y),
        })
    }

    /// θ1 and θ2 (rad) of the tool point (x, y) (mm), as [`Kinematics::inverse`] gives them,
    /// bit for bit, without the rest of the solution (θ3 and the configuration): for callers
    /// that hold the configuration already and need the actuated angles alone.
    #[inline]
    pub fn actuated_angles(&self, x: f64, y: f64) -> Result<[f64; 2], KinematicsError> {
        for (what, value) in [("x", x), ("y", y)] {
            if !value.is_finite() {
                return Err(KinematicsError::NotFinite { what });
            }
        }
        let (direction1, _) = self.chain_inverse(Chain::One, x, y)?;
        let (direction2, _) = self.chain_inverse(Chain::Two, x, y)?;
        Ok([
            fit_into(libm::atan2(direction1.y, direction1.x), self.limits[0]),
            fit_into(libm::atan2(direction2.y, direction2.x), self.limits[1]),
        ])
    }

    /// Inverse kinematics with every check a running robot needs: reachable in the working mode,
    /// in the robot's assembly mode, inside the joint limits and outside the singularity margin.
    pub fn inverse_checked(&self, pose: &Pose) -> Result<IkSolution, KinematicsError> {
        let solution = self.inverse(pose)?;
        self.check_assembly(&solution)?;
        self.check_limits(&solution.joints)?;
        self.check_singularity(&solution.configuration)?;
        Ok(solution)
    }

    /// Fails with [`KinematicsError::BeyondType2`] when the solution is not in the robot's
    /// assembly mode.
    pub fn check_assembly(&self, solution: &IkSolution) -> Result<(), KinematicsError> {
        let found = solution.assembly_mode();
        if found == self.assembly_mode {
            Ok(())
        } else {
            Err(KinematicsError::BeyondType2 {
                x: solution.pose.x,
                y: solution.pose.y,
                found,
                expected: self.assembly_mode,
            })
        }
    }

    /// Whether every joint of `joints` is inside its limits ([`Kinematics::check_limits`]
    /// without the error).
    #[inline]
    pub fn within_limits(&self, joints: &Joints) -> bool {
        let inside = |value: f64, [min, max]: [f64; 2]| min <= value && value <= max;
        inside(joints.theta1, self.limits[0])
            && inside(joints.theta2, self.limits[1])
            && inside(joints.theta3, self.limits[2])
            && inside(joints.d4, self.limits[3])
    }

    /// Whether the platform point `(x, y)` (mm) counts as reachable in the workspace: IK in the
    /// working mode, in the robot's assembly mode, θ1 and θ2 inside their limits and outside
    /// the singularity margin. z and c are free: d4 and θ3 are taken at the middle of their
    /// ranges (some z and c always give that), so they never decide. The one definition the
    /// workspace, [`Kinematics::reachable_batch`] and the design sweeps count by.
    pub fn reachable(&self, x: f64, y: f64) -> bool {
        let middle = |[min, max]: [f64; 2]| 0.5 * (min + max);
        self.inverse(&Pose::new(x, y, 0.0, 0.0)).is_ok_and(|ik| {
            let joints =
                Joints { theta3: middle(self.limits[2]), d4: middle(self.limits[3]), ..ik.joints };
            self.check_assembly(&ik).is_ok()
                && self.check_limits(&joints).is_ok()
                && self.check_singularity(&ik.configuration).is_ok()
        })
    }

    /// Fails with [`KinematicsError::JointLimit`] for the first joint outside its limits.
    pub fn check_limits(&self, joints: &Joints) -> Result<(), KinematicsError> {
        for joint in Joint::ALL {
            let value = joints.get(joint);
            let [min, max] = self.limits[joint as usize];
            if !(min..=max).contains(&value) {
                let [min, max] = self.limits_user[joint as usize];
                let value = if joint.is_revolute() { value.to_degrees() } else { value };
                return Err(KinematicsError::JointLimit { joint, value, min, max });
            }
        }
        Ok(())
    }

    /// Fails with [`KinematicsError::NearSingular`] when the configuration lies within the
    /// singularity margin of a type-1 or type-2 singularity (the nearest one is reported).
    #[inline]
    pub fn check_singularity(
        &self,
        configuration: &PlanarConfiguration,
    ) -> Result<(), KinematicsError> {
        // angle = atan2(|cross|, |dot|) < margin ⇔ |cross| < tan(margin)·|dot|: test without
        // atan2 and compute the angles only to report a failure (IK + checks 141 → 108 ns/pose).
        let clear = |a: na::Vector2<f64>, b: na::Vector2<f64>| {
            a.perp(&b).abs() >= self.singularity_margin_tan * a.dot(&b).abs()
        };
        let z1 = configuration.distal(Chain::One);
        let z2 = configuration.distal(Chain::Two);
        if clear(configuration.proximal(Chain::One), z1)
            && clear(configuration.proximal(Chain::Two), z2)
            && clear(z2, z1)
        {
            return Ok(());
        }
        self.near_singularity(configuration)
    }

    /// [`Kinematics::check_singularity`] once the quick test has failed: the angles, out of line.
    #[cold]
    #[inline(never)]
    fn near_singularity(&self, configuration: &PlanarConfiguration) -> Result<(), KinematicsError> {
        let (kind, angle) = configuration.singularity().nearest();
        if angle < self.singularity_margin {
            Err(KinematicsError::NearSingular {
                kind,
                angle_deg: angle.to_degrees(),
                margin_deg: self.singularity_margin.to_degrees(),
            })
        } else {
            Ok(())
        }
    }

    /// Forward kinematics in the robot's assembly mode.
    pub fn forward(&self, joints: &Joints) -> Result<FkSolution, KinematicsError> {
        self.forward_in(joints, self.assembly_mode)
    }

    /// Forward kinematics in the given assembly mode: the pose, elbows and passive joints.
    ///
    /// Fails only when the distal links cannot meet; joint limits are not checked (use
    /// [`Kinematics::check_limits`]).
    pub fn forward_in(
        &self,
        joints: &Joints,
        assembly_mode: AssemblyMode,
    ) -> Result<FkSolution, KinematicsError> {
        for (what, value) in [
            ("theta1", joints.theta1),
            ("theta2", joints.theta2),
            ("theta3", joints.theta3),
            ("d4", joints.d4),
        ] {
            if !value.is_finite() {
                return Err(KinematicsError::NotFinite { what });
            }
        }
        let configuration = self.planar_forward(joints.theta1, joints.theta2, assembly_mode)?;
        let distal =
            [configuration.distal_angle(Chain::One), configuration.distal_angle(Chain::Two)];
        let distal_rotation = wrap_difference(distal[0], self.distal_home[0]);
        let passive = PassiveJoints {
            elbow1: wrap_angle(distal[0] - joints.theta1 - self.distal_home[0]),
            elbow2: wrap_angle(distal[1] - joints.theta2 - self.distal_home[1]),
            platform: wrap_angle(
                (distal[1] - distal[0]) - (self.distal_home[1] - self.distal_home[0]),
            ),
        };
        let pose = Pose {
            x: configuration.platform.x,
            y: configuration.platform.y,
            z: self.lp - joints.d4,
            phi: joints.theta3 + distal_rotation,
        };
        Ok(FkSolution { joints: *joints, pose, configuration, passive })
    }

    /// The five-bar's configuration (elbows and platform point, mm) for θ1, θ2 in the robot's
    /// assembly mode: the planar part of [`Kinematics::forward`] without the angles, for callers
    /// that need only the points (the inverse dynamics, once per sample).
    pub fn planar(&self, theta1: f64, theta2: f64) -> Result<PlanarConfiguration, KinematicsError> {
        self.planar_forward(theta1, theta2, self.assembly_mode)
    }

    /// The pose at `q = 0`.
    pub fn home(&self) -> Pose {
        // Kinematics::new has checked that the home pose assembles.
        self.forward(&Joints::default()).map(|fk| fk.pose).unwrap_or_default()
    }

    /// Solves `A cos θ + B sin θ = C` for one chain (docs/kinematics.md, the corrected eq. (7)),
    /// picking the root whose bend matches the working mode. Returns `(cos θ, sin θ)` times the
    /// reach `R` (θ is its `atan2`, in (−π, π]) and the elbow.
    #[inline(always)]
    fn chain_inverse(
        &self,
        chain: Chain,
        x: f64,
        y: f64,
    ) -> Result<(na::Vector2<f64>, na::Point2<f64>), KinematicsError> {
        let base = self.bases[chain.index()];
        let dx = x - base.x;
        let a = -y;
        let b = dx;
        let reach2 = dx * dx + y * y; // = A² + B²
        let c = (self.l2 * self.l2 - self.l1 * self.l1 - reach2) / (2.0 * self.l1);
        let discriminant = reach2 - c * c;
        if discriminant < 0.0 || reach2 == 0.0 {
            let reach = reach2.sqrt();
            let (shortfall_mm, side) = if reach > self.l1 + self.l2 {
                (reach - (self.l1 + self.l2), Shortfall::TooFar)
            } else {
                ((self.l1 - self.l2).abs() - reach, Shortfall::TooClose)
            };
            return Err(KinematicsError::Unreachable { chain, x, y, shortfall_mm, side });
        }
        // θ = γ + σ·δ with cos γ = A/R, sin γ = B/R, cos δ = C/R, sin δ = √disc/R: σ = + bends
        // the chain counter-clockwise ((E − b) × (P − E) ≥ 0), σ = − clockwise.
        let root = self.working_mode.of(chain).factor() * discriminant.sqrt();
        let cos_theta = a * c - b * root;
        let sin_theta = b * c + a * root;
        let scale = self.l1 / reach2;
        let elbow = na::Point2::new(base.x - scale * sin_theta, base.y + scale * cos_theta);
        Ok((na::Vector2::new(cos_theta, sin_theta), elbow))
    }

    /// The five-bar configuration for θ1, θ2 in the given assembly mode.
    fn planar_forward(
        &self,
        theta1: f64,
        theta2: f64,
        assembly_mode: AssemblyMode,
    ) -> Result<PlanarConfiguration, KinematicsError> {
        let elbow = |base: na::Point2<f64>, theta: f64| {
            let (sin, cos) = theta.sin_cos();
            na::Point2::new(base.x - self.l1 * sin, base.y + self.l1 * cos)
        };
        let elbows = [elbow(self.bases[0], theta1), elbow(self.bases[1], theta2)];
        let between = elbows[1] - elbows[0];
        let distance2 = between.norm_squared();
        let height2 = self.l2 * self.l2 - 0.25 * distance2;
        if height2 < 0.0 || distance2 == 0.0 {
            return Err(KinematicsError::NoAssembly {
                elbow_distance_mm: distance2.sqrt(),
                max_mm: 2.0 * self.l2,
            });
        }
        // With n = between rotated by +90°, (P − E2) × (P − E1) = −h·|E2 − E1| for P = M + h·n,
        // so assembly mode + takes the point on the −n side.
        let normal = na::Vector2::new(-between.y, between.x) / distance2.sqrt();
        let middle = na::center(&elbows[0], &elbows[1]);
        let platform = middle - assembly_mode.0.factor() * height2.sqrt() * normal;
        Ok(PlanarConfiguration { bases: self.bases, elbows, platform })
    }
}

impl Default for Kinematics {
    /// The kinematics of the default robot.
    fn default() -> Self {
        // The default robot is valid (tested), so this cannot fail.
        Kinematics::new(&Robot::default()).unwrap_or_else(|err| panic!("default robot: {err}"))
    }
}

/// Wraps an angle into (−π, π].
pub fn wrap_angle(angle: f64) -> f64 {
    let wrapped = angle.rem_euclid(TAU);
    if wrapped > PI { wrapped - TAU } else { wrapped }
}

/// 0 for a finite `value`, NaN for an infinite or NaN one.
#[inline(always)]
#[allow(clippy::eq_op)] // v − v: the point
fn finite_zero(value: f64) -> f64 {
    value - value
}

/// The error naming the first of `values` that is not a finite number (one of them is not).
#[cold]
#[inline(never)]
fn not_finite(values: &[(&'static str, f64)]) -> KinematicsError {
    let what = values.iter().find(|(_, value)| !value.is_finite()).map_or("x", |&(what, _)| what);
    KinematicsError::NotFinite { what }
}

/// `a − b` wrapped into (−π, π], for `a`, `b` already in [−π, π] (no division).
fn wrap_difference(a: f64, b: f64) -> f64 {
    let difference = a - b;
    if difference > PI {
        difference - TAU
    } else if difference <= -PI {
        difference + TAU
    } else {
        difference
    }
}

/// Moves a revolute angle (θ1, θ2, θ3) by ±2π when only that puts it inside `[min, max]` (an
/// angle just past ±180°, or a range that reaches past it); otherwise returns it unchanged, so
/// that a limit error reports the angle as solved.
fn fit_into(angle: f64, [min, max]: [f64; 2]) -> f64 {
    let inside = |angle: f64| (min..=max).contains(&angle);
    if angle < min && inside(angle + TAU) {
        angle + TAU
    } else if angle > max && inside(angle - TAU) {
        angle - TAU
    } else {
        angle
    }
}

/// The proximal link direction `a_i = (−sin θ, cos θ)` rotated by +90°: `d a_i / dθ`.
pub(crate) fn proximal_rate_direction(proximal: na::Vector2<f64>) -> na::Vector2<f64> {
    na::Vector2::new(-proximal.y, proximal.x)
}

#[cfg(test)]
mod tests {
    use approx::assert_relative_eq;

    use super::*;

    fn default_model() -> Kinematics {
        Kinematics::default()
    }

    proptest::proptest! {
        /// The actuated angles alone are the full IK's, bit for bit (the torque-limited planner
        /// relies on it to keep its plans), and fail where it fails.
        #[test]
        fn actuated_angles_are_the_inverses_bit_for_bit(
            x in -700.0f64..700.0,
            y in -300.0f64..800.0,
        ) {
            let model = default_model();
            match model.inverse(&Pose::from_degrees(x, y, 0.0, 0.0)) {
                Ok(solution) => {
                    let [theta1, theta2] = model.actuated_angles(x, y).unwrap();
                    proptest::prop_assert_eq!(theta1.to_bits(), solution.joints.theta1.to_bits());
                    proptest::prop_assert_eq!(theta2.to_bits(), solution.joints.theta2.to_bits());
                }
                Err(err) => proptest::prop_assert_eq!(model.actuated_angles(x, y), Err(err)),
            }
        }
    }

    #[test]
    fn inverse_names_the_first_coordinate_that_is_not_finite() {
        let model = default_model();
        let pose = Pose::from_degrees(10.0, 400.0, 50.0, 5.0);
        assert!(model.inverse(&pose).is_ok());
        let bad = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY];
        for (index, what) in ["x", "y", "z", "c"].into_iter().enumerate() {
            for value in bad {
                let mut broken = pose;
                match index {
                    0 => broken.x = value,
                    1 => broken.y = value,
                    2 => broken.z = value,
                    _ => broken.phi = value,
                }
                // A later coordinate broken too: the first is named.
                broken.phi = if index == 3 { value } else { f64::NAN };
                match model.inverse(&broken) {
                    Err(KinematicsError::NotFinite { what: named }) => assert_eq!(named, what),
                    other => panic!("{what} = {value}: {other:?}"),
                }
            }
        }
    }

    #[test]
    fn home_pose_of_the_default_robot() {
        let model = default_model();
        let home = model.forward(&Joints::default()).unwrap();
        assert_relative_eq!(home.pose.x, 0.0, epsilon = 1e-12);
        assert_relative_eq!(home.pose.y, 210.0 + (270.0f64.powi(2) - 100.0f64.powi(2)).sqrt());
        assert_relative_eq!(home.pose.y, 460.7987, epsilon = 1e-4);
        assert_relative_eq!(home.pose.z, 100.0);
        assert_relative_eq!(home.pose.phi, 0.0);
        assert_eq!(home.configuration.working_mode(), WorkingMode::default());
        assert_eq!(home.configuration.assembly_mode(), AssemblyMode(Sign::Plus));
        assert_eq!(home.passive, PassiveJoints { elbow1: 0.0, elbow2: 0.0, platform: 0.0 });

        let ik = model.inverse_checked(&home.pose).unwrap();
        for value in ik.joints.to_array() {
            assert_relative_eq!(value, 0.0, epsilon = 1e-12);
        }
    }

    #[test]
    fn unreachable_points_name_the_chain_and_the_shortfall() {
        let model = default_model();
        // (400, 300) is 583.095 mm from chain 2's base at (−100, 0): beyond l1 + l2 = 480.
        let err = model.inverse(&Pose::new(400.0, 300.0, 50.0, 0.0)).unwrap_err();
        match err {
            KinematicsError::Unreachable { chain, shortfall_mm, side, .. } => {
                assert_eq!(chain, Chain::Two);
                assert_relative_eq!(shortfall_mm, (500.0f64.hypot(300.0)) - 480.0, epsilon = 1e-9);
                assert_eq!(side, Shortfall::TooFar);
            }
            other => panic!("unexpected {other:?}"),
        }
        // 40 mm from chain 1's base: closer than |l1 − l2| = 60.
        let err = model.inverse(&Pose::new(100.0, 40.0, 50.0, 0.0)).unwrap_err();
        assert!(
            matches!(err, KinematicsError::Unreachable { chain: Chain::One, side: Shortfall::TooClose, shortfall_mm, .. } if (shortfall_mm - 20.0).abs() < 1e-9),
            "{err:?}"
        );
        assert_eq!(
            err.to_string(),
            "chain 1 cannot reach (x, y) = (100.000, 40.000): 20.000 mm too close to its base joint"
        );
    }

    #[test]
    fn pose_beyond_a_type2_singularity_is_refused() {
        let model = default_model();
        // Below the base line both chains reach in mode +-, but the distal links cross over.
        let pose = Pose::new(0.0, 60.0, 50.0, 0.0);
        let solution = model.inverse(&pose).unwrap();
        assert_eq!(solution.assembly_mode(), AssemblyMode(Sign::Minus));
        let err = model.inverse_checked(&pose).unwrap_err();
        assert!(matches!(err, KinematicsError::BeyondType2 { .. }), "{err:?}");
    }

    #[test]
    fn joint_limit_error_says_by_how_much() {
        let model = default_model();
        let err = model.check_limits(&Joints::from_degrees(0.0, -140.0, 0.0, 50.0)).unwrap_err();
        assert!(
            matches!(err, KinematicsError::JointLimit { joint: Joint::Theta2, value, min: -135.0, max: 135.0 } if (value + 140.0).abs() < 1e-9),
            "{err:?}"
        );
        assert_relative_eq!(err.excess(), 5.0, epsilon = 1e-9);
        assert_eq!(
            err.to_string(),
            "theta2 = -140.000° is outside its limits [-135, 135] by 5.000°"
        );
        let err = model.check_limits(&Joints::from_degrees(0.0, 0.0, 0.0, 101.5)).unwrap_err();
        assert_eq!(err.to_string(), "d4 = 101.500 mm is outside its limits [0, 100] by 1.500 mm");
    }

    #[test]
    fn near_singular_poses_are_refused() {
        let model = default_model();
        // Chain 1 almost stretched: 479.9 mm from its base (2.3° from straight), at 120° from +X.
        let angle = 120f64.to_radians();
        let pose = Pose::new(100.0 + 479.9 * angle.cos(), 479.9 * angle.sin(), 50.0, 0.0);
        let solution = model.inverse(&pose).unwrap();
        let err = model.check_singularity(&solution.configuration).unwrap_err();
        assert!(
            matches!(err, KinematicsError::NearSingular { kind: SingularityKind::Type1(Chain::One), angle_deg, .. } if angle_deg < 5.0),
            "{err:?}"
        );
    }

    #[test]
    fn fast_singularity_test_agrees_with_the_angles() {
        let model = default_model();
        let mut refused = 0;
        for i in 0..200 {
            for j in 0..200 {
                let pose =
                    Pose::new(-500.0 + 5.0 * f64::from(i), -300.0 + 5.0 * f64::from(j), 0.0, 0.0);
                let Ok(solution) = model.inverse(&pose) else { continue };
                let angle = solution.configuration.singularity().nearest().1;
                let fast = model.check_singularity(&solution.configuration).is_ok();
                assert_eq!(fast, angle >= model.singularity_margin(), "{pose:?}: {angle}");
                refused += usize::from(!fast);
            }
        }
        assert!(refused > 100, "the grid should cross the margin often, crossed {refused} times");
    }

    #[test]
    fn wrapping_helpers() {
        assert_relative_eq!(wrap_angle(3.0 * PI), PI);
        assert_relative_eq!(wrap_angle(-PI), PI);
        assert_relative_eq!(wrap_angle(0.5), 0.5);
        assert_relative_eq!(wrap_difference(3.0, -3.0), 6.0 - TAU);
        assert_relative_eq!(fit_into(-3.0, [0.0, 5.0]), TAU - 3.0);
        assert_relative_eq!(fit_into(-3.0, [-2.0, 2.0]), -3.0);
        assert_relative_eq!(fit_into(10.0, [-PI, PI]), 10.0);
        assert_relative_eq!(fit_into(4.0, [-PI, PI]), 4.0 - TAU);
    }
}
