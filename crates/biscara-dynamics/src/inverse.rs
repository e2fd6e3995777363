//! The inverse dynamics: virtual work in the actuated joints, the passive elbows eliminated
//! through the loop closure (docs/dynamics.md, "The derivation").

use biscara_kinematics::{Chain, Kinematics, Motor, RobotModel};

use crate::{Bodies, DynamicsError};

/// The robot's rigid-body model and motors, built once from a validated robot
/// (docs/dynamics.md); computes the torques one sample at a time, allocating nothing.
#[derive(Debug, Clone, PartialEq)]
pub struct Dynamics {
    kinematics: Kinematics,
    bodies: Bodies,
    motors: Option<[Motor; 4]>,
    /// Link lengths, m.
    l1: f64,
    l2: f64,
    /// 1/l1 and 1/l2 in 1/mm (to turn the links into unit vectors) and 1/l2 in 1/m.
    inverse_l1_mm: f64,
    inverse_l2_mm: f64,
    inverse_l2: f64,
    /// The proximal link's inertia about its joint, kg·m².
    proximal_about_joint: f64,
    /// The distal link's centre of mass as a fraction of `l2`.
    distal_fraction: f64,
    /// Each motor's rotor inertia at its joint (kg·m², kg), zero without motors.
    rotor: [f64; 4],
}

/// The rigid torques along a path, `τ = a·s̈ + b·ṡ² + c` ([`Dynamics::path_coefficients`]),
/// joint by joint (N·m, N).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathCoefficients {
    /// The coefficient of s̈: M·q′.
    pub a: [f64; 4],
    /// The coefficient of ṡ²: M·q″ + the velocity terms of q′.
    pub b: [f64; 4],
    /// The constant: gravity.
    pub c: [f64; 4],
}

/// The five-bar solved at one pose θ1, θ2 ([`Dynamics::linkage`]): the links' directions and the
/// loop closure's matrix, for evaluating the inverse dynamics at that pose for several rates
/// ([`Dynamics::linkage_torques`]) with one forward solve.
#[derive(Debug, Clone, Copy)]
pub struct Linkage {
    /// Unit vectors along the proximal (`e`) and distal (`u`) links of chains 1 and 2.
    e1: V2,
    u1: V2,
    e2: V2,
    u2: V2,
    /// 1 / det A, A the loop closure's matrix with rows u1, u2.
    inverse_det: f64,
}

/// A 2-vector, for the planar arithmetic done by hand (this runs per sample).
#[derive(Debug, Clone, Copy)]
struct V2(f64, f64);

impl V2 {
    fn dot(self, other: V2) -> f64 {
        self.0 * other.0 + self.1 * other.1
    }
    /// Turned by +90° about +z.
    fn perp(self) -> V2 {
        V2(-self.1, self.0)
    }
    fn scale(self, factor: f64) -> V2 {
        V2(self.0 * factor, self.1 * factor)
    }
    fn add(self, other: V2) -> V2 {
        V2(self.0 + other.0, self.1 + other.1)
    }
    fn sub(self, other: V2) -> V2 {
        V2(self.0 - other.0, self.1 - other.1)
    }
}

impl Dynamics {
    /// The model of `robot`: its bodies ([`Bodies::of`]) and motors. Fails when d4's motor
    /// cannot hold the slide and the robot's payload against gravity.
    pub fn new(robot: &RobotModel) -> Result<Dynamics, DynamicsError> {
        let bodies = Bodies::of(robot.robot());
        let motors = robot.robot().motors.map(|motors| motors.to_array());
        if let Some(motors) = &motors {
            let needed_n = (bodies.slide + bodies.payload) * bodies.gravity;
            if motors[3].peak < needed_n {
                return Err(DynamicsError::WeakSlideMotor {
                    peak_n: motors[3].peak,
                    needed_n,
                    slide_kg: bodies.slide,
                    payload_kg: bodies.payload,
                    gravity: bodies.gravity,
                });
            }
        }
        let kinematics = robot.kinematics();
        let (l1, l2) = (kinematics.l1() / 1000.0, kinematics.l2() / 1000.0);
        let proximal = bodies.proximal;
        Ok(Dynamics {
            kinematics,
            bodies,
            motors,
            l1,
            l2,
            inverse_l1_mm: 1.0 / kinematics.l1(),
            inverse_l2_mm: 1.0 / kinematics.l2(),
            inverse_l2: 1.0 / l2,
            proximal_about_joint: proximal.inertia + proximal.mass * proximal.com * proximal.com,
            distal_fraction: bodies.distal.com / l2,
            rotor: motors.map_or([0.0; 4], |motors| motors.map(|motor| motor.rotor_inertia)),
        })
    }

    /// The bodies in force (SI units).
    pub fn bodies(&self) -> &Bodies {
        &self.bodies
    }

    /// The payload the robot carries, kg: the robot file's `dynamics.payload` while the gripper
    /// holds it (`gripping`: closed, from a pick to its place), else none.
    pub fn held_payload(&self, gripping: bool) -> f64 {
        if gripping { self.bodies.payload } else { 0.0 }
    }

    /// The motors in joint order θ1, θ2, θ3, d4, when robot.json has `motors`.
    pub fn motors(&self) -> Option<&[Motor; 4]> {
        self.motors.as_ref()
    }

    /// Rigid-body inverse dynamics with gravity and the motors' rotor inertia, no friction.
    /// q = [θ1, θ2, θ3 (rad), d4 (mm)], qd in rad/s and mm/s, qdd in rad/s² and mm/s².
    /// Returns [τ1, τ2, τ3 (N·m), f_d4 (N)]. Error when the pose cannot be assembled.
    ///
    /// The same as [`Dynamics::linkage`] of θ1, θ2 followed by [`Dynamics::linkage_torques`],
    /// bit for bit: callers that evaluate one pose at several rates solve it once that way.
    pub fn rigid_torques(
        &self,
        q: [f64; 4],
        qd: [f64; 4],
        qdd: [f64; 4],
        payload_kg: f64,
    ) -> Result<[f64; 4], DynamicsError> {
        let sum: f64 = q.iter().chain(&qd).chain(&qdd).sum::<f64>() + payload_kg;
        if !sum.is_finite() {
            return Err(not_finite(q, qd, qdd, payload_kg));
        }
        let linkage = self.solve(q[0], q[1])?;
        Ok(self.evaluate(&linkage, qd, qdd, payload_kg))
    }

    /// The five-bar solved at θ1, θ2 (rad): the forward solve and the loop closure's matrix, what
    /// [`Dynamics::linkage_torques`] needs of the pose. Error when the pose cannot be assembled
    /// or is a parallel singularity.
    #[inline]
    pub fn linkage(&self, theta1: f64, theta2: f64) -> Result<Linkage, DynamicsError> {
        for (what, value) in [("theta1", theta1), ("theta2", theta2)] {
            if !value.is_finite() {
                return Err(DynamicsError::NotFinite { what });
            }
        }
        self.solve(theta1, theta2)
    }

    /// [`Dynamics::linkage`] without checking θ1 and θ2 (its callers have).
    #[inline(always)]
    fn solve(&self, theta1: f64, theta2: f64) -> Result<Linkage, DynamicsError> {
        let degrees = || (theta1.to_degrees(), theta2.to_degrees());
        let planar = self.kinematics.planar(theta1, theta2).map_err(|source| {
            let (theta1_deg, theta2_deg) = degrees();
            DynamicsError::Assembly { theta1_deg, theta2_deg, source }
        })?;
        // Unit vectors: e_i along the proximal link, u_i along the distal link.
        let unit = |chain: Chain| {
            let proximal = planar.proximal(chain) * self.inverse_l1_mm;
            let distal = planar.distal(chain) * self.inverse_l2_mm;
            (V2(proximal.x, proximal.y), V2(distal.x, distal.y))
        };
        let (e1, u1) = unit(Chain::One);
        let (e2, u2) = unit(Chain::Two);
        // Loop closure: u_i · Ṗ = u_i · Ė_i, i.e. A·Ṗ = diag(b)·θ̇ with A's rows u1, u2.
        let det = u1.0 * u2.1 - u1.1 * u2.0;
        if det.abs() < 1e-9 {
            let (theta1_deg, theta2_deg) = degrees();
            return Err(DynamicsError::Singular { theta1_deg, theta2_deg });
        }
        Ok(Linkage { e1, u1, e2, u2, inverse_det: 1.0 / det })
    }

    /// [`Dynamics::rigid_torques`] at the pose `linkage` was solved at ([`Dynamics::linkage`]
    /// of its θ1, θ2; θ3 and d4 play no part in the torques): no forward solve. Error when a
    /// rate or the payload is not finite.
    #[inline]
    pub fn linkage_torques(
        &self,
        linkage: &Linkage,
        qd: [f64; 4],
        qdd: [f64; 4],
        payload_kg: f64,
    ) -> Result<[f64; 4], DynamicsError> {
        let sum: f64 = qd.iter().chain(&qdd).sum::<f64>() + payload_kg;
        if !sum.is_finite() {
            return Err(not_finite([0.0; 4], qd, qdd, payload_kg));
        }
        Ok(self.evaluate(linkage, qd, qdd, payload_kg))
    }

    /// [`Dynamics::linkage_torques`] without checking the rates (its callers have).
    #[inline(always)]
    fn evaluate(
        &self,
        linkage: &Linkage,
        qd: [f64; 4],
        qdd: [f64; 4],
        payload_kg: f64,
    ) -> [f64; 4] {
        let (l1, l2) = (self.l1, self.l2);
        let Linkage { e1, u1, e2, u2, inverse_det } = *linkage;
        // e'_i and n_i are e_i and u_i turned by +90° (the directions in which the elbow and
        // the tool point move when the link turns).
        let (e1p, e2p, n1, n2) = (e1.perp(), e2.perp(), u1.perp(), u2.perp());
        let solve = |r1: f64, r2: f64| {
            V2((u2.1 * r1 - u1.1 * r2) * inverse_det, (u1.0 * r2 - u2.0 * r1) * inverse_det)
        };
        let b = [l1 * u1.dot(e1p), l1 * u2.dot(e2p)];
        // Velocities.
        let pd = solve(b[0] * qd[0], b[1] * qd[1]);
        let ed1 = e1p.scale(l1 * qd[0]);
        let ed2 = e2p.scale(l1 * qd[1]);
        let inverse_l2 = self.inverse_l2;
        let psid1 = n1.dot(pd.sub(ed1)) * inverse_l2;
        let psid2 = n2.dot(pd.sub(ed2)) * inverse_l2;
        // Accelerations: u_i · P̈ = u_i · Ë_i − l2·ψ̇_i².
        let c1 = -l1 * qd[0] * qd[0] * u1.dot(e1) - l2 * psid1 * psid1;
        let c2 = -l1 * qd[1] * qd[1] * u2.dot(e2) - l2 * psid2 * psid2;
        let pdd = solve(b[0] * qdd[0] + c1, b[1] * qdd[1] + c2);
        let edd1 = e1p.scale(l1 * qdd[0]).sub(e1.scale(l1 * qd[0] * qd[0]));
        let edd2 = e2p.scale(l1 * qdd[1]).sub(e2.scale(l1 * qd[1] * qd[1]));
        let psidd1 = n1.dot(pdd.sub(edd1)) * inverse_l2;
        let psidd2 = n2.dot(pdd.sub(edd2)) * inverse_l2;
        // Inertial forces and moments of the bodies.
        let bodies = &self.bodies;
        let k = self.distal_fraction;
        let distal_mass = bodies.distal.mass;
        let acd1 = edd1.scale(1.0 - k).add(pdd.scale(k));
        let acd2 = edd2.scale(1.0 - k).add(pdd.scale(k));
        let tool_acceleration = psidd1 + qdd[2];
        let tool_moment = bodies.tool_inertia * tool_acceleration;
        let moment1 = bodies.distal.inertia * psidd1 + tool_moment;
        let moment2 = bodies.distal.inertia * psidd2;
        let platform_mass = bodies.carriage + bodies.slide + payload_kg;
        // Everything that moves with the tool point's virtual displacement: τ gets Jᵀ·w.
        let w = pdd
            .scale(platform_mass)
            .add(acd1.add(acd2).scale(k * distal_mass))
            .add(n1.scale(moment1 * inverse_l2))
            .add(n2.scale(moment2 * inverse_l2));
        let v =
            V2((u2.1 * w.0 - u2.0 * w.1) * inverse_det, (u1.0 * w.1 - u1.1 * w.0) * inverse_det);
        let own = self.proximal_about_joint;
        let tau1 = b[0] * v.0 + (1.0 - k) * distal_mass * l1 * acd1.dot(e1p)
            - moment1 * l1 * n1.dot(e1p) * inverse_l2
            + (own + self.rotor[0]) * qdd[0];
        let tau2 = b[1] * v.1 + (1.0 - k) * distal_mass * l1 * acd2.dot(e2p)
            - moment2 * l1 * n2.dot(e2p) * inverse_l2
            + (own + self.rotor[1]) * qdd[1];
        let tau3 = tool_moment + self.rotor[2] * qdd[2];
        let vertical_mass = bodies.slide + payload_kg;
        let f_d4 = (vertical_mass + self.rotor[3]) * qdd[3] * 1e-3 - vertical_mass * bodies.gravity;
        [tau1, tau2, tau3, f_d4]
    }

    /// The rigid torques along a path q(s) in the form time-optimal planning takes:
    /// `τ = a·s̈ + b·ṡ² + c` (no friction), at the path's point `q` with `dq_ds` = q′ and
    /// `d2q_ds2` = q″ (units per unit of s, as q): a = M·q′, b = M·q″ + the velocity terms of
    /// q′, c = gravity. (With q̇ = q′·ṡ and q̈ = q′·s̈ + q″·ṡ²,
    /// the inverse dynamics is linear in q̈ and quadratic in q̇.)
    pub fn path_coefficients(
        &self,
        q: [f64; 4],
        dq_ds: [f64; 4],
        d2q_ds2: [f64; 4],
        payload_kg: f64,
    ) -> Result<PathCoefficients, DynamicsError> {
        let sum: f64 = q.iter().chain(&dq_ds).chain(&d2q_ds2).sum::<f64>() + payload_kg;
        if !sum.is_finite() {
            return Err(not_finite(q, dq_ds, d2q_ds2, payload_kg));
        }
        // One forward solve for the three evaluations.
        let linkage = self.solve(q[0], q[1])?;
        let c = self.evaluate(&linkage, [0.0; 4], [0.0; 4], payload_kg);
        let a = self.evaluate(&linkage, [0.0; 4], dq_ds, payload_kg);
        let b = self.evaluate(&linkage, dq_ds, d2q_ds2, payload_kg);
        Ok(PathCoefficients {
            a: std::array::from_fn(|joint| a[joint] - c[joint]),
            b: std::array::from_fn(|joint| b[joint] - c[joint]),
            c,
        })
    }

    /// Viscous + Coulomb friction at joint velocity qd (Coulomb is 0 at rest).
    pub fn friction(&self, qd: [f64; 4]) -> [f64; 4] {
        let Some(motors) = &self.motors else { return [0.0; 4] };
        let mut friction = [0.0; 4];
        for (joint, (motor, rate)) in motors.iter().zip(qd).enumerate() {
            // d4's viscous friction is per m/s; its velocity is in mm/s.
            let rate_si = if joint == 3 { rate * 1e-3 } else { rate };
            let coulomb = if rate > 0.0 {
                motor.coulomb
            } else if rate < 0.0 {
                -motor.coulomb
            } else {
                0.0
            };
            friction[joint] = motor.viscous * rate_si + coulomb;
        }
        friction
    }

    /// rigid_torques + friction: what the motors must give.
    pub fn torques(
        &self,
        q: [f64; 4],
        qd: [f64; 4],
        qdd: [f64; 4],
        payload_kg: f64,
    ) -> Result<[f64; 4], DynamicsError> {
        let rigid = self.rigid_torques(q, qd, qdd, payload_kg)?;
        let friction = self.friction(qd);
        let torques: [f64; 4] = std::array::from_fn(|joint| rigid[joint] + friction[joint]);
        // Finite inputs within the robot file's bounds can still overflow at absurd rates: an
        // error, never an infinite torque.
        const TORQUES: [&str; 4] =
            ["theta1's torque", "theta2's torque", "theta3's torque", "d4's force"];
        match torques.iter().position(|torque| !torque.is_finite()) {
            Some(joint) => Err(DynamicsError::NotFinite { what: TORQUES[joint] }),
            None => Ok(torques),
        }
    }
}

/// The error naming the first value that is not finite.
fn not_finite(q: [f64; 4], qd: [f64; 4], qdd: [f64; 4], payload_kg: f64) -> DynamicsError {
    const NAMES: [[&str; 4]; 3] = [
        ["theta1", "theta2", "theta3", "d4"],
        ["theta1's velocity", "theta2's velocity", "theta3's velocity", "d4's velocity"],
        [
            "theta1's acceleration",
            "theta2's acceleration",
            "theta3's acceleration",
            "d4's acceleration",
        ],
    ];
    for (names, values) in NAMES.iter().zip([q, qd, qdd]) {
        for (name, value) in names.iter().zip(values) {
            if !value.is_finite() {
                return DynamicsError::NotFinite { what: name };
            }
        }
    }
    let _ = payload_kg;
    DynamicsError::NotFinite { what: "the payload" }
}

#[cfg(test)]
mod tests {
    use biscara_kinematics::{DynamicsSpec, Joints, Motors, Robot};
    use proptest::prelude::*;

    use super::*;

    const G: f64 = 9.80665;

    fn motor(peak: f64, rotor_inertia: f64, viscous: f64, coulomb: f64) -> Motor {
        Motor { peak, rated: peak / 3.0, rotor_inertia, viscous, coulomb }
    }

    /// The demo robot with the example bodies and motors of docs/dynamics.md.
    fn example_robot() -> RobotModel {
        let dynamics: DynamicsSpec = serde_json::from_str(
            r#"{"proximal": {"mass": 0.62, "com": 98.0, "inertia": 0.0023},
                "distal": {"mass": 0.71, "com": 121.0, "inertia": 0.0043},
                "carriage": {"mass": 1.3}, "slide": {"mass": 0.55},
                "tool": {"inertia": 0.00021}, "payload": {"mass": 0.2}}"#,
        )
        .unwrap();
        let motors = Motors {
            theta1: motor(9.0, 0.006, 0.02, 0.15),
            theta2: motor(9.0, 0.006, 0.02, 0.15),
            theta3: motor(1.0, 0.0004, 0.001, 0.02),
            d4: motor(120.0, 0.4, 5.0, 3.0),
        };
        RobotModel::new(Robot {
            dynamics: Some(dynamics),
            motors: Some(motors),
            ..Robot::default()
        })
        .unwrap()
    }

    /// A robot with only the bodies given (all others massless) and no motors.
    fn only(json: &str) -> Dynamics {
        let zero: DynamicsSpec = serde_json::from_str(
            r#"{"proximal": {"mass": 0, "com": 0, "inertia": 0},
                "distal": {"mass": 0, "com": 0, "inertia": 0},
                "carriage": {"mass": 0}, "slide": {"mass": 0}, "tool": {"inertia": 0}}"#,
        )
        .unwrap();
        let given: DynamicsSpec = serde_json::from_str(json).unwrap();
        let pick = |a: Option<f64>, b: Option<f64>| a.or(b);
        let spec = DynamicsSpec {
            gravity: given.gravity,
            proximal: biscara_kinematics::BodySpec {
                mass: pick(given.proximal.mass, zero.proximal.mass),
                com: pick(given.proximal.com, zero.proximal.com),
                inertia: pick(given.proximal.inertia, zero.proximal.inertia),
            },
            distal: biscara_kinematics::BodySpec {
                mass: pick(given.distal.mass, zero.distal.mass),
                com: pick(given.distal.com, zero.distal.com),
                inertia: pick(given.distal.inertia, zero.distal.inertia),
            },
            carriage: biscara_kinematics::PointSpec {
                mass: pick(given.carriage.mass, zero.carriage.mass),
            },
            slide: biscara_kinematics::PointSpec { mass: pick(given.slide.mass, zero.slide.mass) },
            tool: biscara_kinematics::ToolBodySpec {
                inertia: pick(given.tool.inertia, zero.tool.inertia),
            },
            payload: given.payload,
        };
        Dynamics::new(&RobotModel::new(Robot { dynamics: Some(spec), ..Robot::default() }).unwrap())
            .unwrap()
    }

    #[test]
    fn at_rest_only_the_slide_feels_gravity() {
        let dynamics = Dynamics::new(&example_robot()).unwrap();
        for q in [[0.0, 0.0, 0.0, 0.0], [0.4, -0.3, 2.0, 55.0], [-0.8, 0.9, -1.0, 100.0]] {
            let [t1, t2, t3, f] = dynamics.torques(q, [0.0; 4], [0.0; 4], 0.2).unwrap();
            assert_eq!((t1, t2, t3), (0.0, 0.0, 0.0));
            approx::assert_relative_eq!(f, -(0.55 + 0.2) * G, max_relative = 1e-12);
        }
        assert!(dynamics.friction([0.0; 4]) == [0.0; 4], "no Coulomb friction at rest");
    }

    #[test]
    fn a_proximal_link_alone_is_a_pendulum_without_gravity() {
        // I about the joint = I_com + m·c², whatever the velocity (no centripetal torque).
        let dynamics = only(r#"{"proximal": {"mass": 0.5, "com": 100, "inertia": 0.002}}"#);
        let torques = dynamics.torques(
            [0.3, -0.2, 0.0, 20.0],
            [2.0, -1.0, 5.0, 10.0],
            [7.0, -3.0, 0.0, 0.0],
            0.0,
        );
        let [t1, t2, t3, f] = torques.unwrap();
        let about_joint = 0.002 + 0.5 * 0.01;
        approx::assert_relative_eq!(t1, about_joint * 7.0, max_relative = 1e-12);
        approx::assert_relative_eq!(t2, about_joint * -3.0, max_relative = 1e-12);
        assert_eq!((t3, f), (0.0, 0.0));
    }

    #[test]
    fn the_tool_alone_turns_with_the_first_distal_link() {
        // Only θ3 moving: τ3 = I·θ̈3, and the planar motors hold the reaction through ψ1.
        let dynamics = only(r#"{"tool": {"inertia": 0.001}}"#);
        let [_, _, t3, _] =
            dynamics.torques([0.2, 0.1, 0.0, 0.0], [0.0; 4], [0.0, 0.0, 40.0, 0.0], 0.0).unwrap();
        approx::assert_relative_eq!(t3, 0.04, max_relative = 1e-12);
    }

    #[test]
    fn a_point_mass_at_the_tool_point_feels_its_acceleration() {
        // One body alone by hand: a point mass m at P with θ2 held, θ1 turning at θ̇1 from rest
        // (θ̈1 only). Then τ1 = m·(∂P/∂θ1)·P̈ = m·|∂P/∂θ1|²·θ̈1, ∂P/∂θ1 by finite differences.
        let dynamics = only(r#"{"carriage": {"mass": 2.0}}"#);
        let model = RobotModel::default().kinematics();
        let (theta1, theta2, h) = (0.3, -0.25, 1e-6);
        let at = |theta1: f64| model.planar(theta1, theta2).unwrap().platform;
        let dp = (at(theta1 + h) - at(theta1 - h)) / (2.0 * h) / 1000.0;
        let [t1, t2, _, _] = dynamics
            .torques([theta1, theta2, 0.0, 0.0], [0.0; 4], [5.0, 0.0, 0.0, 0.0], 0.0)
            .unwrap();
        approx::assert_relative_eq!(t1, 2.0 * dp.norm_squared() * 5.0, max_relative = 1e-7);
        // θ2's motor holds the reaction: m·(∂P/∂θ2)·P̈.
        let at2 = |theta2: f64| model.planar(theta1, theta2).unwrap().platform;
        let dp2 = (at2(theta2 + h) - at2(theta2 - h)) / (2.0 * h) / 1000.0;
        approx::assert_relative_eq!(t2, 2.0 * dp.dot(&dp2) * 5.0, max_relative = 1e-6);
    }

    #[test]
    fn the_path_coefficients_give_the_torques_at_any_speed_along_the_path() {
        let dynamics = Dynamics::new(&example_robot()).unwrap();
        let (q, dq, ddq) =
            ([0.3, -0.2, 1.0, 40.0], [0.8, -1.1, 2.0, 30.0], [-2.0, 0.5, 1.0, -80.0]);
        let PathCoefficients { a, b, c } = dynamics.path_coefficients(q, dq, ddq, 0.3).unwrap();
        for (sd, sdd) in [(0.0, 0.0), (1.5, -4.0), (3.0, 10.0)] {
            let qd: [f64; 4] = std::array::from_fn(|i| dq[i] * sd);
            let qdd: [f64; 4] = std::array::from_fn(|i| dq[i] * sdd + ddq[i] * sd * sd);
            let torques = dynamics.rigid_torques(q, qd, qdd, 0.3).unwrap();
            for joint in 0..4 {
                let form = a[joint] * sdd + b[joint] * sd * sd + c[joint];
                approx::assert_relative_eq!(
                    torques[joint],
                    form,
                    epsilon = 1e-9,
                    max_relative = 1e-9
                );
            }
        }
    }

    #[test]
    fn friction_opposes_the_motion_in_si_units() {
        let dynamics = Dynamics::new(&example_robot()).unwrap();
        let friction = dynamics.friction([1.0, -2.0, 0.0, 100.0]);
        approx::assert_relative_eq!(friction[0], 0.02 + 0.15);
        approx::assert_relative_eq!(friction[1], -0.04 - 0.15);
        assert_eq!(friction[2], 0.0);
        approx::assert_relative_eq!(friction[3], 5.0 * 0.1 + 3.0);
        assert_eq!(Dynamics::new(&RobotModel::default()).unwrap().friction([1.0; 4]), [0.0; 4]);
    }

    #[test]
    fn a_weak_slide_motor_is_refused_with_both_figures() {
        let mut robot = example_robot().robot().clone();
        if let Some(motors) = &mut robot.motors {
            motors.d4.peak = 5.0;
            motors.d4.rated = 1.0;
        }
        let err = Dynamics::new(&RobotModel::new(robot).unwrap()).unwrap_err();
        assert_eq!(err.key(), Some("motors.d4.peak"));
        let text = err.to_string();
        // (0.55 + 0.2) kg × G = 7.3549875 N, rounded to the µN.
        assert!(text.contains("force 5 N") && text.contains("= 7.354988 N"), "{text}");
    }

    #[test]
    fn bad_values_are_errors_not_numbers() {
        let dynamics = Dynamics::new(&RobotModel::default()).unwrap();
        let err = dynamics.torques([0.0; 4], [0.0, f64::NAN, 0.0, 0.0], [0.0; 4], 0.0);
        assert_eq!(err, Err(DynamicsError::NotFinite { what: "theta2's velocity" }));
        // Rates that overflow the torques: an error, not an infinity.
        let err = dynamics.torques([0.2, 0.1, 0.0, 0.0], [1e200, 0.0, 0.0, 0.0], [0.0; 4], 0.0);
        assert_eq!(err, Err(DynamicsError::NotFinite { what: "theta1's torque" }));
        let err = dynamics.torques([0.2, 0.1, 0.0, 0.0], [0.0; 4], [0.0, 0.0, 0.0, 1e308], 1e3);
        assert_eq!(err, Err(DynamicsError::NotFinite { what: "d4's force" }));
        // Proximal links pointing apart: the elbows are over 600 mm apart, the distal links 540 mm.
        let err = dynamics.torques([-1.6, 1.6, 0.0, 0.0], [0.0; 4], [0.0; 4], 0.0);
        assert!(matches!(err, Err(DynamicsError::Assembly { .. })), "{err:?}");
    }

    /// The kinetic + potential energy (J) at q, q̇, from the kinematics alone: each body's
    /// velocity by central differences of the forward kinematics along q̇.
    fn energy(dynamics: &Dynamics, q: [f64; 4], qd: [f64; 4], payload: f64) -> f64 {
        let model = RobotModel::default().kinematics();
        let h = 1e-7;
        let fk = |sign: f64| {
            let joints: [f64; 4] = std::array::from_fn(|i| q[i] + sign * h * qd[i]);
            model.forward(&Joints::new(joints[0], joints[1], joints[2], joints[3])).unwrap()
        };
        let (plus, minus) = (fk(1.0), fk(-1.0));
        let rate = |a: f64, b: f64| (a - b) / (2.0 * h);
        let bodies = dynamics.bodies();
        let l2 = model.l2() / 1000.0;
        let mut kinetic = 0.0;
        for chain in Chain::BOTH {
            let i = chain.index();
            let (cp, cm) = (plus.configuration, minus.configuration);
            let psi_rate = rate(cp.distal_angle(chain), cm.distal_angle(chain));
            let k = bodies.distal.com / l2;
            let centre = |c: &biscara_kinematics::PlanarConfiguration| {
                (c.elbows[i].coords * (1.0 - k) + c.platform.coords * k) / 1000.0
            };
            let vc = (centre(&cp) - centre(&cm)) / (2.0 * h);
            let proximal =
                bodies.proximal.inertia + bodies.proximal.mass * bodies.proximal.com.powi(2);
            kinetic += 0.5 * proximal * qd[i] * qd[i]
                + 0.5 * bodies.distal.mass * vc.norm_squared()
                + 0.5 * bodies.distal.inertia * psi_rate * psi_rate;
        }
        let vp = (plus.configuration.platform - minus.configuration.platform) / (2.0 * h) / 1000.0;
        let vz = rate(plus.pose.z, minus.pose.z) / 1000.0;
        let tool_rate = rate(plus.pose.phi, minus.pose.phi);
        kinetic += 0.5 * (bodies.carriage + bodies.slide + payload) * vp.norm_squared()
            + 0.5 * (bodies.slide + payload) * vz * vz
            + 0.5 * bodies.tool_inertia * tool_rate * tool_rate;
        if let Some(motors) = dynamics.motors() {
            for (joint, motor) in motors.iter().enumerate() {
                let rate = if joint == 3 { qd[3] / 1000.0 } else { qd[joint] };
                kinetic += 0.5 * motor.rotor_inertia * rate * rate;
            }
        }
        let z = 0.5 * (plus.pose.z + minus.pose.z) / 1000.0;
        kinetic + (bodies.slide + payload) * bodies.gravity * z
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        /// The five-bar solved once and evaluated at several rates gives `rigid_torques`'s
        /// torques bit for bit (the planner relies on it to keep its plans).
        #[test]
        fn linkage_torques_are_rigid_torques_bit_for_bit(
            theta in prop::array::uniform2(-0.9f64..0.9),
            q34 in prop::array::uniform2(-100.0f64..100.0),
            qd in prop::array::uniform4(-20.0f64..20.0),
            qdd in prop::array::uniform4(-500.0f64..500.0),
            payload in 0.0f64..2.0,
        ) {
            let dynamics = Dynamics::new(&example_robot()).unwrap();
            let q = [theta[0], theta[1], q34[0], q34[1]];
            match dynamics.linkage(q[0], q[1]) {
                Ok(linkage) => {
                    let bits = |tau: [f64; 4]| tau.map(f64::to_bits);
                    let once = dynamics.linkage_torques(&linkage, qd, qdd, payload).unwrap();
                    let full = dynamics.rigid_torques(q, qd, qdd, payload).unwrap();
                    prop_assert_eq!(bits(once), bits(full));
                }
                Err(err) => prop_assert_eq!(dynamics.rigid_torques(q, qd, qdd, payload), Err(err)),
            }
        }

        /// Statics anywhere: at rest, gravity (along −z) loads only d4, which holds
        /// −(slide + payload)·g; the θ motors give nothing, and there is no friction.
        #[test]
        fn at_rest_anywhere_only_d4_holds_the_slide_and_payload(
            theta in prop::array::uniform2(-0.7f64..0.7),
            theta3 in -3.0f64..3.0,
            d4 in 0.0f64..100.0,
            payload in 0.0f64..2.0,
        ) {
            let dynamics = Dynamics::new(&example_robot()).unwrap();
            let q = [theta[0], theta[1], theta3, d4];
            let [t1, t2, t3, f] = dynamics.torques(q, [0.0; 4], [0.0; 4], payload).unwrap();
            prop_assert_eq!((t1, t2, t3), (0.0, 0.0, 0.0));
            let hold = -(0.55 + payload) * G;
            prop_assert!((f - hold).abs() <= 1e-12 * hold.abs(), "{} N against {} N", f, hold);
        }

        /// Power balance with friction off: Σ τ·q̇ = dE/dt along a smooth joint trajectory
        /// q(t) = q0 + a·sin(ω t + φ), compared at random instants.
        #[test]
        fn the_motors_power_is_the_energys_rate(
            q0 in prop::array::uniform4(-0.4f64..0.4),
            amplitude in prop::array::uniform4(-0.3f64..0.3),
            omega in prop::array::uniform4(0.5f64..6.0),
            phase in prop::array::uniform4(0.0f64..6.3),
            t in 0.0f64..2.0,
            payload in 0.0f64..1.0,
        ) {
            let dynamics = Dynamics::new(&example_robot()).unwrap();
            let scale = [1.0, 1.0, 3.0, 100.0];
            let offset = [0.0, 0.0, 0.0, 50.0];
            let q_at = |t: f64| -> [f64; 4] { std::array::from_fn(|i| offset[i] + scale[i] * (q0[i] + amplitude[i] * (omega[i] * t + phase[i]).sin())) };
            let qd_at = |t: f64| -> [f64; 4] { std::array::from_fn(|i| scale[i] * amplitude[i] * omega[i] * (omega[i] * t + phase[i]).cos()) };
            let qdd_at = |t: f64| -> [f64; 4] { std::array::from_fn(|i| -scale[i] * amplitude[i] * omega[i] * omega[i] * (omega[i] * t + phase[i]).sin()) };
            let (q, qd, qdd) = (q_at(t), qd_at(t), qdd_at(t));
            let tau = dynamics.rigid_torques(q, qd, qdd, payload).unwrap();
            let power = tau[0] * qd[0] + tau[1] * qd[1] + tau[2] * qd[2] + tau[3] * qd[3] / 1000.0;
            let h = 1e-4;
            let rate = (energy(&dynamics, q_at(t + h), qd_at(t + h), payload)
                - energy(&dynamics, q_at(t - h), qd_at(t - h), payload)) / (2.0 * h);
            let size: f64 = tau.iter().zip(qd).map(|(tau, qd)| (tau * qd).abs()).sum::<f64>() + 1e-3;
            prop_assert!((power - rate).abs() <= 1e-4 * size + 1e-6, "power {power} W, dE/dt {rate} W");
        }
    }
}
