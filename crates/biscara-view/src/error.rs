//! The errors of this crate.

use std::io;

/// What can go wrong while building a picture, a plot or a model.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ViewError {
    /// Occurs when a trajectory row's joints do not assemble (the distal links cannot meet).
    #[error("at t = {t:.3} s the joints do not assemble: {source}")]
    Assembly {
        /// Time of the row, s.
        t: f64,
        /// Why forward kinematics failed.
        source: biscara_kinematics::KinematicsError,
    },
    /// Occurs when the robot description is impossible (see [`biscara_kinematics::Robot::validate`]).
    #[error(transparent)]
    Robot(#[from] biscara_kinematics::RobotError),
    /// Occurs when the trajectory has no rows.
    #[error("the trajectory has no rows")]
    EmptyTrajectory,
    /// Occurs when writing the output fails.
    #[error(transparent)]
    Io(#[from] io::Error),
    /// Occurs when a mesh is given for a part the viewer does not draw (see
    /// [`biscara_kinematics::Meshes::PART_NAMES`]), or the meshes together hold more than
    /// [`crate::MAX_MESH_TRIANGLES`] triangles.
    #[error("{message}")]
    Mesh {
        /// What is wrong.
        message: String,
    },
    /// Occurs when a plot cannot be drawn (the plotting backend failed).
    #[error("cannot draw the plot: {message}")]
    Plot {
        /// What the plotting backend said.
        message: String,
    },
}
