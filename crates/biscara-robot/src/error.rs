//! What can go wrong in the virtual robot.

use biscara_kinematics::{KinematicsError, RobotError};

/// A virtual-robot failure: a bad scene file, a robot file that cannot be modelled, a program
/// that does not fit the workspace, or a picture that cannot be drawn.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum VirtualRobotError {
    /// Occurs when a scene file is not JSON, has an unknown or missing key, a value of the wrong
    /// type, or an impossible box (`min` not below `max` on every axis).
    #[error("{line}:{column}: {key}: {message}")]
    Scene {
        /// 1-based line of the error.
        line: usize,
        /// 1-based column of the error.
        column: usize,
        /// Dotted path of the offending key (`boxes[1].max`), or `.` for the whole document.
        key: String,
        /// What is wrong and what would be right.
        message: String,
    },
    /// Occurs when a `check --json` report read back is not JSON, has no `problems` array, or
    /// a problem without a number `t_s` or with an unknown `kind`.
    #[error("{line}:{column}: not a check --json report: {key}: {message}")]
    CheckReport {
        /// 1-based line of the error.
        line: usize,
        /// 1-based column of the error.
        column: usize,
        /// Dotted path of the offending key (`problems[0].kind`), or `.` for the whole document.
        key: String,
        /// What is wrong.
        message: String,
    },
    /// Occurs when the robot file is invalid.
    #[error(transparent)]
    Robot(#[from] RobotError),
    /// Occurs when a pose needed to draw or place the robot cannot be solved.
    #[error(transparent)]
    Kinematics(#[from] KinematicsError),
    /// Occurs when the workspace grid step is not a positive finite number, or so small that the
    /// grid would be unreasonably large.
    #[error("the grid step must lie in [{min_mm}, {max_mm}] mm (got {step_mm})")]
    Step {
        /// The step asked for, millimetres.
        step_mm: f64,
        /// Smallest allowed step, millimetres.
        min_mm: f64,
        /// Largest allowed step, millimetres.
        max_mm: f64,
    },
    /// Occurs when no grid point of the workspace is reachable, so there is no rectangle.
    #[error("no point of the XY plane is reachable for this robot at a {step_mm} mm grid")]
    EmptyWorkspace {
        /// The grid step, millimetres.
        step_mm: f64,
    },
    /// Occurs when a program has no move away from its start pose's XY (none at all, or only
    /// along Z, as a resin printer's lifts), so it has no XY extent to place.
    #[error("the program has no move in X or Y away from its start: there is nothing to place")]
    NoMoves,
    /// Occurs when a program's XY extent is wider or taller than the workspace rectangle, as
    /// programmed and turned by 90° about Z.
    #[error(
        "the program's XY extent {width_mm:.3} x {height_mm:.3} mm does not fit the workspace \
         rectangle {rect_width_mm:.3} x {rect_height_mm:.3} mm: as programmed, {}; turned by 90° \
         about Z, {}",
        excess(*.width_mm, *.height_mm, *.rect_width_mm, *.rect_height_mm),
        excess(*.height_mm, *.width_mm, *.rect_width_mm, *.rect_height_mm)
    )]
    DoesNotFit {
        /// Width (X) of the program's bounding box, millimetres.
        width_mm: f64,
        /// Height (Y) of the program's bounding box, millimetres.
        height_mm: f64,
        /// Width of the workspace rectangle, millimetres.
        rect_width_mm: f64,
        /// Height of the workspace rectangle, millimetres.
        rect_height_mm: f64,
    },
}

fn excess(width: f64, height: f64, rect_width: f64, rect_height: f64) -> String {
    let mut parts = Vec::new();
    if width > rect_width {
        parts.push(format!("{:.3} mm too wide in X", width - rect_width));
    }
    if height > rect_height {
        parts.push(format!("{:.3} mm too tall in Y", height - rect_height));
    }
    parts.join(" and ")
}
