//! The paper's equations against docs/kinematics.md: eq. (7) corrected, eq. (8)'s roots at home, and
//! eq. (14) equal to θ3 in the default mode only.

use std::f64::consts::{FRAC_PI_2, TAU};

use approx::assert_relative_eq;
use biscara_kinematics::{Joints, Kinematics, Pose, Robot, Sign, WorkingMode, wrap_angle};

const L1: f64 = 210.0;
const L2: f64 = 270.0;
const HOME_Y: f64 = 460.7987;

/// Eq. (8): `t = (B ± √(A² + B² − C²)) / (A + C)`, θ = 2·atan(t), with A, B of eq. (7).
fn eq8_theta(x: f64, y: f64, bx: f64, c: f64, sign: f64) -> f64 {
    let (a, b) = (-y, x - bx);
    let t = (b + sign * (a * a + b * b - c * c).sqrt()) / (a + c);
    2.0 * t.atan()
}

/// C of eq. (7) as docs/kinematics.md corrects it: `(l2² − l1² − (x − b)² − y²) / (2 l1)`.
fn corrected_c(x: f64, y: f64, bx: f64) -> f64 {
    (L2 * L2 - L1 * L1 - (x - bx).powi(2) - y * y) / (2.0 * L1)
}

/// C of eq. (7) as the paper prints it: `(l1² − l2² − x² − y² − b² + 2 x b) / (2 l1)`.
fn printed_c(x: f64, y: f64, bx: f64) -> f64 {
    (L1 * L1 - L2 * L2 - x * x - y * y - bx * bx + 2.0 * x * bx) / (2.0 * L1)
}

#[test]
fn home_pose_is_q_zero() {
    let model = Kinematics::default();
    let home = model.home();
    assert_relative_eq!(home.x, 0.0, epsilon = 1e-12);
    assert_relative_eq!(home.y, HOME_Y, epsilon = 1e-4);
    assert_relative_eq!(home.z, 100.0);
    let ik = model.inverse_checked(&Pose::new(0.0, HOME_Y, 100.0, 0.0)).expect("home");
    for value in ik.joints.to_array() {
        assert!(value.abs() < 1e-5, "{:?}", ik.joints);
    }
}

#[test]
fn corrected_eq7_reaches_home_through_the_plus_root_for_chain1_and_minus_for_chain2() {
    let y = L1 + (L2 * L2 - 100.0f64.powi(2)).sqrt();
    let theta1 = eq8_theta(0.0, y, 100.0, corrected_c(0.0, y, 100.0), 1.0);
    let theta2 = eq8_theta(0.0, y, -100.0, corrected_c(0.0, y, -100.0), -1.0);
    assert_relative_eq!(theta1, 0.0, epsilon = 1e-12);
    assert_relative_eq!(theta2, 0.0, epsilon = 1e-12);
    // The other roots are not home.
    assert!(eq8_theta(0.0, y, 100.0, corrected_c(0.0, y, 100.0), -1.0).abs() > 0.1);
    assert!(eq8_theta(0.0, y, -100.0, corrected_c(0.0, y, -100.0), 1.0).abs() > 0.1);
}

#[test]
fn printed_eq7_does_not_give_home() {
    let y = L1 + (L2 * L2 - 100.0f64.powi(2)).sqrt();
    // With the printed sign, C² > A² + B² at home: eq. (8) has no real root at all.
    let (a, b, c) = (-y, -100.0, printed_c(0.0, y, 100.0));
    assert!(a * a + b * b - c * c < 0.0);
    for sign in [1.0, -1.0] {
        let theta1 = eq8_theta(0.0, y, 100.0, c, sign);
        assert!(theta1.is_nan() || theta1.abs() >= 1e-3, "printed C gives θ1 = {theta1}");
    }
}

/// Our IK's root choice agrees with eq. (8)'s roots (which one depends on chain and region).
#[test]
fn ik_agrees_with_one_of_the_eq8_roots() {
    let model = Kinematics::default();
    for (x, y) in [(150.0, 320.0), (-150.0, 300.0), (120.0, 250.0), (0.0, 400.0), (-60.0, 420.0)] {
        let ik = model.inverse(&Pose::new(x, y, 50.0, 0.0)).expect("reachable");
        for (theta, bx) in [(ik.joints.theta1, 100.0), (ik.joints.theta2, -100.0)] {
            let c = corrected_c(x, y, bx);
            let closest = [1.0, -1.0]
                .map(|sign| wrap_angle(eq8_theta(x, y, bx, c, sign) - theta).abs())
                .into_iter()
                .fold(f64::INFINITY, f64::min);
            assert!(closest < 1e-9, "({x}, {y}) base {bx}: θ = {theta}");
        }
    }
}

/// Eqs. (10)–(14): θ3 = φ − θ1 − θ_p − α + 90°, θ_p unsigned.
fn eq14_theta3(x: f64, y: f64, phi: f64, theta1: f64, b1x: f64) -> f64 {
    let alpha = (L2 * L2 - b1x * b1x).sqrt().atan2(b1x);
    let c_theta_p = ((b1x - x).powi(2) + y * y - L1 * L1 - L2 * L2) / (2.0 * L1 * L2);
    let theta_p = (1.0 - c_theta_p * c_theta_p).sqrt().atan2(c_theta_p);
    phi - theta1 - theta_p - alpha + FRAC_PI_2
}

#[test]
fn eq14_equals_theta3_in_the_default_mode() {
    let model = Kinematics::default();
    let mut checked = 0;
    for i in 0..40 {
        for j in 0..40 {
            let x = -300.0 + 15.0 * f64::from(i);
            let y = 100.0 + 10.0 * f64::from(j);
            let phi = (f64::from(i * 7 + j * 3) - 100.0).to_radians();
            let Ok(ik) = model.inverse_checked(&Pose::new(x, y, 50.0, phi)) else { continue };
            let paper = eq14_theta3(x, y, phi, ik.joints.theta1, 100.0);
            assert_relative_eq!(wrap_angle(paper - ik.joints.theta3), 0.0, epsilon = 1e-9);
            checked += 1;
        }
    }
    assert!(checked > 300, "only {checked} reachable grid poses");
}

#[test]
fn eq14_is_wrong_when_chain1_bends_the_other_way() {
    let model = Kinematics::default().with_working_mode(WorkingMode::new(Sign::Minus, Sign::Minus));
    let (x, y, phi) = (-40.0, 380.0, 0.3);
    let ik = model.inverse(&Pose::new(x, y, 50.0, phi)).expect("reachable");
    let paper = eq14_theta3(x, y, phi, ik.joints.theta1, 100.0);
    let difference = wrap_angle(paper - ik.joints.theta3);
    assert!(difference.abs() > 1e-3, "eq. (14) should differ in mode --, differs by {difference}");
    // Our θ3 (docs/kinematics.md) still closes the round trip there.
    let fk = model.forward_in(&ik.joints, ik.assembly_mode()).expect("FK");
    assert_relative_eq!(wrap_angle(fk.pose.phi - phi), 0.0, epsilon = 1e-12);
}

#[test]
fn theta3_turns_with_the_distal_link_along_a_path() {
    // Driving c by whole turns at a fixed point keeps θ3 continuous (never wrapped).
    let model = Kinematics::default();
    let mut unwrapper = biscara_kinematics::Theta3Unwrapper::new();
    let mut previous = None;
    for step in 0..=720 {
        let phi = f64::from(step).to_radians();
        let mut ik = model.inverse(&Pose::new(0.0, 400.0, 50.0, phi)).expect("reachable");
        unwrapper.apply(&mut ik);
        if let Some(previous) = previous {
            let delta: f64 = ik.joints.theta3 - previous;
            assert!(delta.abs() < 0.1, "θ3 jumped by {delta} at step {step}");
        }
        previous = Some(ik.joints.theta3);
    }
    let first = model.inverse(&Pose::new(0.0, 400.0, 50.0, 0.0)).expect("reachable").joints.theta3;
    assert_relative_eq!(previous.unwrap_or_default() - first, 2.0 * TAU, epsilon = 1e-9);
}

#[test]
fn theta3_stays_continuous_when_the_distal_link_crosses_180_degrees() {
    // Chain 1's distal link points near −X far left: sweeping y moves ψ1 across ±180°.
    let mut robot = Robot::default();
    robot.joint_limits.theta1 = [-180.0, 180.0];
    let model = Kinematics::new(&robot).expect("robot");
    let mut unwrapper = biscara_kinematics::Theta3Unwrapper::new();
    let mut previous: Option<f64> = None;
    let mut crossed = false;
    let mut last_psi: Option<f64> = None;
    for step in 0..=200 {
        let y = -60.0 + f64::from(step);
        let Ok(mut ik) = model.inverse(&Pose::new(-330.0, y, 50.0, 0.0)) else { continue };
        let psi = ik.configuration.distal_angle(biscara_kinematics::Chain::One);
        if let Some(last) = last_psi {
            crossed |= (psi - last).abs() > 3.0;
        }
        last_psi = Some(psi);
        unwrapper.apply(&mut ik);
        if let Some(previous) = previous {
            assert!((ik.joints.theta3 - previous).abs() < 0.1, "θ3 jumped at y = {y}");
        }
        previous = Some(ik.joints.theta3);
    }
    assert!(crossed, "the sweep should carry ψ1 across ±180°");
}

#[test]
fn joints_default_is_home() {
    assert_eq!(Joints::default().to_array(), [0.0; 4]);
}
