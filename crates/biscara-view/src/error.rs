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
    /// Occurs when a part is given a second mesh.
    #[error("part `{part}` has a mesh already")]
    MeshTwice {
        /// The part.
        part: biscara_kinematics::Part,
    },
    /// Occurs when the meshes together hold more triangles than the viewer takes.
    #[error(
        "the meshes hold more than {max} triangles, what the viewer takes: simplify them first"
    )]
    TooManyTriangles {
        /// The most the viewer takes ([`crate::MAX_MESH_TRIANGLES`]).
        max: usize,
    },
    /// Occurs when a plot cannot be drawn (the plotting backend failed).
    #[error("cannot draw the plot: {message}")]
    Plot {
        /// What the plotting backend said.
        message: String,
    },
}
