//! The BiSCARA on LinuxCNC: the bridge from this project's robot to the controller the
//! research planned for it.
//!
//! - [`configuration`]: a complete LinuxCNC 2.9 configuration for a robot file: the kinematics
//!   component (`biscarakins.comp`, forward and inverse kinematics identical to
//!   [`biscara_kinematics::Kinematics`], the robot's numbers as HAL pins), the INI, the HAL of a
//!   simulated machine that runs headless, a commented hardware template, the tool's codes, the
//!   stream path (streamer → limit3 → mux2 per joint) and the headless display.
//! - [`derive_axis_limits`]: axis velocity and acceleration limits such that LinuxCNC's
//!   Cartesian planner, which knows nothing of the joints, cannot exceed any joint's limit in
//!   the workspace rectangle.
//! - [`read_recording`]: what LinuxCNC's joints did, every servo cycle, as joint samples.
//! - [`runner`]: the one part that touches the outside world: builds and installs the
//!   component, runs LinuxCNC headless in a fresh folder, and leaves nothing of it behind.
//!
//! It knows nothing of G-code text: LinuxCNC reads the program itself.
//!
//! ```
//! use biscara_kinematics::RobotModel;
//! use biscara_linuxcnc::{ConfigOptions, configuration};
//!
//! let config = configuration(&RobotModel::default(), &ConfigOptions::default())?;
//! let ini = config.files.iter().find(|file| file.name == "biscara.ini").unwrap();
//! assert!(ini.contents.contains("KINEMATICS = biscarakins"));
//! // No joint can exceed its limit: the XY axes move slower than the robot's rapid speed.
//! assert!(config.limits.xy_velocity < 500.0);
//! # Ok::<(), biscara_linuxcnc::LinuxcncError>(())
//! ```

mod config;
mod consistency;
mod error;
pub mod job;
mod limits;
pub mod runner;
mod samples;
pub mod stream;

pub use config::{
    AxisLimitSource, COMPONENT_NAME, COMPONENT_SOURCE, ConfigFile, ConfigOptions, Configuration,
    INI_FILE, ROBOT_FILE, Region, configuration, grow,
};
pub use consistency::{configuration_robot, hal_parameters, ini_value};
pub use error::LinuxcncError;
pub use limits::{AxisLimits, Derivation, LimitsError, derive_axis_limits};
pub use samples::{
    RecordedSample, RecordingStart, RecordingSummary, SERVO_PERIOD, parse_recorded_line,
    read_recording, write_stream_sample,
};
