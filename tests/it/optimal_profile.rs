//! `--profile optimal` (issue 16) end to end: on the programs of `data/programs/` and the demo
//! job, on the default and the weak-motor robot, `check` finds no velocity or acceleration
//! problem in the optimal trajectory, while it still flags the trapezoid's on the weak robot
//! (`check`'s `acceleration_limit` stays: a trajectory made with another profile can break it).

use crate::util::{biscara, repo_root, temp_dir};

/// Whether `check`'s report names a velocity or acceleration problem.
fn has_derivative_problem(report: &str) -> bool {
    report.contains("velocity_limit") || report.contains("acceleration_limit")
}

#[test]
fn check_finds_no_joint_speed_problem_in_optimal_trajectories() {
    let dir = temp_dir("optimal-profile");
    let root = repo_root();
    biscara(&dir, &["demo", "demo"]).success();
    let demo = dir.join("demo/job.ngc");
    let programs = [
        (root.join("data/programs/arcs_and_offsets.ngc"), None),
        (root.join("data/programs/engraving_arcs.ngc"), Some("-75,300,20,0")),
        (root.join("data/programs/pick_place_inch.ngc"), None),
        (demo, None),
    ];
    let mut trapezoid_problems = 0;
    for robot in ["default", "weak-motors"] {
        let robot_file = root.join(format!("data/robots/{robot}.json"));
        for (program, origin) in &programs {
            for profile in ["optimal", "trapezoid"] {
                let mut args = vec![
                    "--robot",
                    robot_file.to_str().expect("path"),
                    "check",
                    "--profile",
                    profile,
                    program.to_str().expect("path"),
                ];
                if let Some(origin) = origin {
                    args.extend(["--origin", origin]);
                }
                let run = biscara(&dir, &args);
                let report = format!("{}{}", run.stdout, run.stderr);
                if profile == "optimal" {
                    assert!(
                        !has_derivative_problem(&report),
                        "{} on {robot}: {report}",
                        program.display()
                    );
                    run.success();
                } else if has_derivative_problem(&report) {
                    trapezoid_problems += 1;
                    assert_eq!(robot, "weak-motors", "{report}");
                }
            }
        }
    }
    // The weak motors cannot follow the trapezoid's accelerations on any of the four programs.
    assert_eq!(trapezoid_problems, 4);
}
