//! Integration tests of the `biscara` binary: one test binary, one module per feature.

mod architecture;
mod bad_input;
mod blending;
mod browser;
mod cli_kinematics;
mod conformance;
mod cycle;
mod design;
mod dialects;
mod dynamics;
mod golden;
mod interpret;
mod linuxcnc;
mod linuxcnc_run;
mod motion_cli;
mod mujoco;
mod optimal_profile;
mod programming;
mod python;
/// The recorded rs274 results of the conformance programs, shared with biscara-gcode's tests.
#[path = "../../crates/biscara-gcode/tests/it/rs274_record.rs"]
mod record;
mod robustness;
mod rs274;
mod tool;
mod toppra;
mod util;
mod view_cli;
mod virtual_robot;
