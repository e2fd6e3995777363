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
    #[error("{line}: {fault}")]
    Csv {
        /// The line, from 1.
        line: usize,
        /// What is wrong with it.
        fault: CsvFault,
    },
    /// A line of one of several design CSVs (`design merge`) that cannot be taken.
    #[error("{file}:{line}: {fault}")]
    Merge {
        /// The file's name.
        file: String,
        /// The line, from 1.
        line: usize,
        /// What is wrong with it.
        fault: MergeFault,
    },
    /// Merged shards that leave a design out.
    #[error("design {index} is in none of the files: a shard is missing")]
    Missing {
        /// The first index missing.
        index: u64,
    },
    /// The time objective without programs to time.
    #[error("--objective time needs --programs")]
    NoPrograms,
    /// No design meets what the best must: a rectangle, the task covered (`task`), the
    /// programs or the cycle run (by `objective`).
    #[error(
        "no design has a rectangle{}{}",
        if *task { " and covers the task" } else { "" },
        match objective {
            crate::Objective::Time => " and runs the programs",
            crate::Objective::Cycle => " and runs the Adept cycle",
            _ => "",
        }
    )]
    NoneChosen {
        /// Whether the designs had to cover a task rectangle.
        task: bool,
        /// What the best design maximises.
        objective: crate::Objective,
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

/// What is wrong with a line of a design CSV ([`DesignError::Csv`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum CsvFault {
    /// Occurs when the first line is not a design CSV's header.
    #[error("not a design CSV: the header is not '{expected}'")]
    Header {
        /// The header of a sweep without optional columns.
        expected: String,
    },
    /// Occurs when a row has another number of fields than the header.
    #[error("{found} fields, the header has {expected}")]
    FieldCount {
        /// The row's fields.
        found: usize,
        /// The header's.
        expected: usize,
    },
    /// Occurs when a field that holds a number does not.
    #[error("{column} '{text}' is no number")]
    NotANumber {
        /// The column.
        column: &'static str,
        /// The field.
        text: String,
    },
    /// Occurs when a number is infinite or NaN.
    #[error("{column} '{text}' is not finite")]
    NotFinite {
        /// The column.
        column: &'static str,
        /// The field.
        text: String,
    },
    /// Occurs when the index is not a design number.
    #[error("index '{text}' is no design number")]
    Index {
        /// The field.
        text: String,
    },
    /// Occurs when the status is not one a sweep writes.
    #[error("status '{text}' is not ok, empty or invalid")]
    Status {
        /// The field.
        text: String,
    },
    /// Occurs when task_ok is neither 0 nor 1.
    #[error("task_ok '{text}' is not 0 or 1")]
    TaskOk {
        /// The field.
        text: String,
    },
}

/// Why a line of one of the merged CSVs cannot be taken ([`DesignError::Merge`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum MergeFault {
    /// Occurs when the line cannot be read.
    #[error(transparent)]
    Row(#[from] CsvFault),
    /// Occurs when a file's header differs from the first file's.
    #[error("its header differs from the first file's")]
    HeaderDiffers,
    /// Occurs when a design is in two files.
    #[error("design {index} is in another file too")]
    Repeated {
        /// The design.
        index: u64,
    },
    /// Occurs when a file's rows do not rise.
    #[error("design {index} follows design {previous}: rows out of order or repeated")]
    OutOfOrder {
        /// The design on this line.
        index: u64,
        /// The design on the line before.
        previous: u64,
    },
}
