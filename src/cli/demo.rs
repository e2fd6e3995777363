//! `biscara demo`: the bundled example, end to end as far as the pipeline exists.

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::Context;
use biscara::kinematics::{Kinematics, Pose, Robot};
use clap::Args;

use super::fmt::fixed;
use super::output::write_output;

/// Runs the bundled example and writes its files into DIR.
///
/// For now the pipeline stops at the kinematics: the demo solves IK and FK for every pose of the
/// bundled pick-and-place job (SPEC §2: home, each pick and place and the approach point above
/// it), checks the round trip, and writes `robot.json` and `poses.csv` into DIR.
#[derive(Debug, Args)]
#[command(
    about = "Run the bundled example and write its files (default folder out/)",
    after_long_help = "Example:\n  $ biscara demo\n  $ biscara demo /tmp/biscara-demo"
)]
pub(crate) struct DemoArgs {
    /// Folder to write into; created when missing.
    #[arg(value_name = "DIR", default_value = "out")]
    dir: PathBuf,
}

/// The bundled example job of SPEC §2: `(label, x, y, z, c)` in mm and degrees.
const EXAMPLE_JOB: [(&str, [f64; 4]); 5] = [
    ("home", [0.0, 400.0, 100.0, 0.0]),
    ("pick 1", [150.0, 320.0, 10.0, 30.0]),
    ("place 1", [-150.0, 300.0, 20.0, 0.0]),
    ("pick 2", [120.0, 250.0, 10.0, -45.0]),
    ("place 2", [-150.0, 340.0, 20.0, 0.0]),
];

/// Height of the approach points above each pick and place, mm (the points file's default).
const APPROACH_MM: f64 = 50.0;

struct DemoRow {
    label: String,
    pose: [f64; 4],
    joints: [f64; 4],
    round_trip_mm: f64,
}

pub(crate) fn demo(robot: &Robot, args: &DemoArgs) -> anyhow::Result<()> {
    let model = Kinematics::new(robot)?;
    let rows = solve_example(&model)?;
    std::fs::create_dir_all(&args.dir)
        .with_context(|| format!("cannot create {}", args.dir.display()))?;
    let robot_path = args.dir.join("robot.json");
    write_output(Some(&robot_path), |out| Ok(writeln!(out, "{}", robot.to_json_pretty())?))?;
    let poses_path = args.dir.join("poses.csv");
    write_output(Some(&poses_path), |out| write_poses_csv(out, &rows))?;
    print_summary(&rows, &[&robot_path, &poses_path])
}

fn solve_example(model: &Kinematics) -> anyhow::Result<Vec<DemoRow>> {
    let mut rows = Vec::new();
    for (label, [x, y, z, c]) in EXAMPLE_JOB {
        let mut poses = vec![(label.to_owned(), [x, y, z, c])];
        if label != "home" {
            poses.insert(0, (format!("above {label}"), [x, y, z + APPROACH_MM, c]));
        }
        for (label, pose) in poses {
            let [x, y, z, c] = pose;
            let ik = model
                .inverse_checked(&Pose::from_degrees(x, y, z, c))
                .with_context(|| format!("example pose {label}"))?;
            let fk = model.forward(&ik.joints)?;
            let back = fk.pose.to_degrees();
            let round_trip_mm = (back[0] - x).hypot(back[1] - y).hypot(back[2] - z);
            rows.push(DemoRow { label, pose, joints: ik.joints.to_degrees(), round_trip_mm });
        }
    }
    Ok(rows)
}

fn write_poses_csv(out: &mut dyn Write, rows: &[DemoRow]) -> anyhow::Result<()> {
    writeln!(
        out,
        "label,x_mm,y_mm,z_mm,c_deg,theta1_deg,theta2_deg,theta3_deg,d4_mm,round_trip_mm"
    )?;
    for row in rows {
        let numbers: Vec<String> =
            row.pose.iter().chain(&row.joints).map(|&value| fixed(value, 6)).collect();
        writeln!(out, "{},{},{}", row.label, numbers.join(","), fixed(row.round_trip_mm, 9))?;
    }
    Ok(())
}

#[allow(clippy::print_stdout)]
fn print_summary(rows: &[DemoRow], written: &[&Path]) -> anyhow::Result<()> {
    println!("biscara demo: IK and FK of the bundled pick-and-place job's poses");
    println!("(the full pipeline — points, CL, G-code, joints — arrives with later stages)");
    println!();
    println!(
        "{:<14} {:>9} {:>9} {:>8} {:>8}   {:>9} {:>9} {:>9} {:>8}",
        "pose", "x", "y", "z", "c", "theta1", "theta2", "theta3", "d4"
    );
    let mut worst = 0.0f64;
    for row in rows {
        let [x, y, z, c] = row.pose.map(|value| fixed(value, 1));
        let [t1, t2, t3, d4] = row.joints.map(|value| fixed(value, 3));
        println!("{:<14} {x:>9} {y:>9} {z:>8} {c:>8}   {t1:>9} {t2:>9} {t3:>9} {d4:>8}", row.label);
        worst = worst.max(row.round_trip_mm);
    }
    println!();
    println!("largest FK(IK(x)) round-trip error: {worst:.1e} mm");
    for path in written {
        println!("wrote {}", path.display());
    }
    Ok(())
}
