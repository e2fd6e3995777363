//! `biscara joints --torques` (docs/dynamics.md): each row's torques are the inverse dynamics of
//! that row's own columns, the payload is held from each pick to its place, and the columns
//! read back.

use biscara::dynamics::Dynamics;
use biscara::kinematics::RobotModel;

use crate::util::{biscara, repo_root, temp_dir};

fn parse(csv: &str) -> (Vec<String>, Vec<Vec<f64>>) {
    let mut lines = csv.lines();
    let header = lines.next().expect("header").split(',').map(str::to_owned).collect();
    let rows = lines
        .map(|line| line.split(',').map(|value| value.parse().expect("number")).collect())
        .collect();
    (header, rows)
}

#[test]
fn each_rows_torques_are_its_own_inverse_dynamics_and_the_gripper_holds_the_payload() {
    let dir = temp_dir("joints-torques");
    let robot = repo_root().join("data/robots/servo-example.json");
    let robot = robot.to_str().expect("path");
    biscara(&dir, &["demo", "out"]).success();
    biscara(
        &dir,
        &["--robot", robot, "joints", "out/job.ngc", "--torques", "--events", "-o", "t.csv"],
    )
    .success();
    let (header, rows) = parse(&std::fs::read_to_string(dir.join("t.csv")).expect("csv"));
    let tail: Vec<&str> = header[13..].iter().map(String::as_str).collect();
    assert_eq!(
        tail,
        ["tau_theta1_Nm", "tau_theta2_Nm", "tau_theta3_Nm", "f_d4_N", "payload_kg", "gripper"]
    );
    let model = RobotModel::from_json(&std::fs::read_to_string(robot).expect("robot")).unwrap();
    let dynamics = Dynamics::new(&model).expect("dynamics");
    let (mut held, mut free) = (0, 0);
    for row in &rows {
        let q = [row[1], row[2], row[3], row[4]];
        let qd = [row[5], row[6], row[7], row[8]];
        let qdd = [row[9], row[10], row[11], row[12]];
        let payload = row[17];
        // From each pick to its place the gripper holds the payload, else nothing.
        if row[18] == 1.0 {
            assert_eq!(payload, 0.5, "t = {}", row[0]);
            held += 1;
        } else {
            assert_eq!(payload, 0.0, "t = {}", row[0]);
            free += 1;
        }
        let torques = dynamics.torques(q, qd, qdd, payload).expect("torques");
        for (joint, torque) in torques.iter().enumerate() {
            let printed = row[13 + joint];
            // The row's values are printed to 6 decimals: the torques agree to that rounding.
            assert!(
                (printed - torque).abs() <= 1e-5 * (1.0 + torque.abs()),
                "t = {}: joint {joint}: printed {printed}, recomputed {torque}",
                row[0]
            );
        }
    }
    assert!(held > 1000 && free > 1000, "held {held}, free {free}");
    // The trajectory with torques reads back where joint CSVs are read.
    biscara(&dir, &["--robot", robot, "mjcf", "-o", "m.xml", "--traj", "t.csv"]).success();
}

#[test]
fn torques_imply_the_derivatives_and_the_slide_is_held_at_rest() {
    let dir = temp_dir("joints-torques-rest");
    std::fs::write(dir.join("rest.ngc"), "G0 X0 Y400 Z50\nG4 P0.2\nM2\n").expect("write");
    let run = biscara(&dir, &["joints", "rest.ngc", "--torques"]);
    let (header, rows) = parse(&run.success().stdout);
    assert_eq!(header.len(), 18);
    assert_eq!(header[9], "ddtheta1_rad_s2");
    let slide = Dynamics::new(&RobotModel::default()).expect("dynamics").bodies().slide;
    let last = rows.last().expect("rows");
    // At rest (the dwell's end): no θ torque, d4 holds the slide: −m·g.
    assert_eq!(&last[5..13], &[0.0; 8]);
    assert_eq!(&last[13..16], &[0.0; 3]);
    assert!((last[16] + slide * 9.80665).abs() < 1e-6, "{last:?}");
}
