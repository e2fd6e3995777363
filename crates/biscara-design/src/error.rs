//! What can go wrong in a design sweep.

/// An error of a design sweep, a shard or a design CSV.
#[derive(Debug, thiserror::Error)]
pub enum DesignError {
    /// A `MIN:MAX:N` range that cannot be read or is impossible.
    #[error("'{text}' {reason} (expected MIN:MAX:N, e.g. 180:260:5)")]
    Range {
        /// The parameter, e.g. `l1` (the caller names it: the command line's own error names
        /// its flag).
        what: &'static str,
        /// The text given.
        text: String,
        /// What is wrong with it.
        reason: String,
    },
    /// A `K/N` shard that cannot be read or is impossible.
    #[error("'{text}' {reason} (expected K/N with 1 ≤ K ≤ N, e.g. 2/8)")]
    Shard {
        /// The text given.
        text: String,
        /// What is wrong with it.
        reason: String,
    },
    /// A task rectangle `X0,Y0,X1,Y1` that cannot be read.
    #[error("'{text}' {reason} (expected X0,Y0,X1,Y1 in mm, e.g. -100,300,100,400)")]
    Task {
        /// The text given.
        text: String,
        /// What is wrong with it.
        reason: String,
    },
    /// A grid too large to index.
    #[error("the sweep has {count} designs, more than {max}")]
    TooManyDesigns {
        /// How many designs the ranges make.
        count: u128,
        /// The most accepted.
        max: u64,
    },
    /// A line of a design CSV that cannot be read.
    #[error("{line}: {message}")]
    Csv {
        /// The line, from 1.
        line: usize,
        /// What is wrong with it.
        message: String,
    },
    /// A line of one of several design CSVs (`design merge`) that cannot be taken.
    #[error("{file}:{line}: {message}")]
    Merge {
        /// The file's name.
        file: String,
        /// The line, from 1.
        line: usize,
        /// What is wrong with it.
        message: String,
    },
    /// Merged shards that leave a design out.
    #[error("design {index} is in none of the files: a shard is missing")]
    Missing {
        /// The first index missing.
        index: u64,
    },
    /// Reading or writing failed.
    #[error(transparent)]
    Io(#[from] std::io::Error),
    /// The worker threads could not be started.
    #[error("cannot start {threads} worker threads: {message}")]
    Threads {
        /// How many were asked for.
        threads: usize,
        /// Why not.
        message: String,
    },
    /// The workspace grid step is out of range.
    #[error(transparent)]
    Workspace(#[from] biscara_robot::VirtualRobotError),
    /// The robot the designs start from is invalid.
    #[error(transparent)]
    Robot(#[from] biscara_kinematics::RobotError),
}
