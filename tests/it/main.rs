//! Integration tests of the `biscara` binary: one test binary, one module per feature.

mod cli_kinematics;
mod golden;
mod linuxcnc;
mod motion_cli;
mod programming;
mod util;
