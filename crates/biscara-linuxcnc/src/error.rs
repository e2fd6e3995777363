//! What can go wrong between this project and LinuxCNC.

use std::path::{Path, PathBuf};

use biscara_robot::VirtualRobotError;

use crate::limits::LimitsError;

/// A LinuxCNC configuration that cannot be written, or a run that cannot be made.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum LinuxcncError {
    /// Occurs when the robot's workspace has no rectangle to derive the limits on.
    #[error(transparent)]
    Workspace(#[from] VirtualRobotError),
    /// Occurs when the axis limits cannot be derived.
    #[error(transparent)]
    Limits(#[from] LimitsError),
    /// Occurs when the configuration is asked for an extruder, which LinuxCNC does not drive
    /// (its E words are no axis of this robot).
    #[error(
        "LinuxCNC has no extruder axis: a configuration is written for a gripper, laser, \
         spindle or pen"
    )]
    Extruder,
    /// Occurs when the region a configuration is made for is not a rectangle of the workspace.
    #[error("the region of {region}: {message}")]
    Region {
        /// Where the region comes from.
        region: String,
        /// What is wrong.
        message: String,
    },
    /// Occurs when a configuration folder's robot file and its INI or HAL disagree, or the
    /// robot in force is not the configuration's.
    #[error("{message}")]
    Robot {
        /// What disagrees, naming both.
        message: String,
    },
    /// Occurs when LinuxCNC refused the program or stopped it (a soft limit, an unreachable
    /// move): its message, and the program's line when LinuxCNC named one.
    #[error("{program}:{}LinuxCNC: {message}", if *line > 0 { format!("{line}: ") } else { " ".to_owned() })]
    Refused {
        /// The program, as named on the command line.
        program: String,
        /// Its 1-based line (0: LinuxCNC named none).
        line: usize,
        /// LinuxCNC's messages.
        message: String,
    },
    /// Occurs when a run is asked for something it cannot do (a timeout that is not a positive
    /// number of seconds).
    #[error("{message}")]
    Usage {
        /// What is wrong.
        message: String,
    },
    /// Occurs when a run was stopped early (an E-stop, the machine switched off, a following
    /// error): what the joints did is still written.
    #[error("{program}: {what} at {time:.3} s: {held} (what they did is written)")]
    Stopped {
        /// The program (or stream) run.
        program: String,
        /// What stopped it.
        what: String,
        /// When, s after the start.
        time: f64,
        /// Where the joints held.
        held: String,
    },
    /// Occurs when a joint CSV to stream breaks a rule: `FILE:LINE: what`.
    #[error("{file}:{line}: {message}")]
    StreamCsv {
        /// The CSV, as named on the command line.
        file: String,
        /// 1-based line of the CSV.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// Occurs when a joint CSV to stream cannot be read: `FILE:LINE:COL: what`.
    #[error("{file}:{message}")]
    StreamCsvFormat {
        /// The CSV, as named on the command line.
        file: String,
        /// The reader's message.
        message: String,
    },
    /// Occurs when a stream does not start where the joints stand.
    #[error(
        "the stream starts at {stream} but the joints stand at {joints} (after homing): a \
         stream must start where the joints are, within 0.001° and 0.001 mm"
    )]
    StartPosition {
        /// The stream's first sample.
        stream: String,
        /// Where the joints are.
        joints: String,
    },
    /// Occurs when a run was interrupted (SIGINT, SIGTERM, SIGHUP): LinuxCNC was stopped and
    /// nothing of it is left.
    #[error("interrupted: LinuxCNC was stopped and its temporary folders removed")]
    Interrupted,
    /// Occurs when a program LinuxCNC needs is not installed.
    #[error(
        "LinuxCNC is not installed ({program} not found): apt-get install \
         --no-install-recommends linuxcnc-uspace linuxcnc-uspace-dev"
    )]
    NotInstalled {
        /// The program not found.
        program: &'static str,
    },
    /// Occurs when the kinematics component must be installed and this process is not root.
    #[error(
        "the kinematics component must be installed into LinuxCNC's module folder, which needs \
         root: run `sudo halcompile --install {}` once", component.display()
    )]
    NeedsRoot {
        /// The component's source.
        component: PathBuf,
    },
    /// Occurs when the kinematics component cannot be built or installed, or a configuration
    /// folder was not written by this project.
    #[error("{message}")]
    Component {
        /// What went wrong.
        message: String,
    },
    /// Occurs when another LinuxCNC is running (LinuxCNC runs one instance per machine).
    #[error("another LinuxCNC is running on this machine (/tmp/linuxcnc.lock exists)")]
    Busy,
    /// Occurs when a file or folder cannot be read or written, or a program cannot be started.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file, folder or program.
        path: PathBuf,
        /// The error.
        source: std::io::Error,
    },
    /// Occurs when LinuxCNC ends without a result (it did not start, or did not finish in time).
    #[error("LinuxCNC {why}; its log:\n{log}")]
    Failed {
        /// What happened.
        why: String,
        /// LinuxCNC's output.
        log: String,
    },
    /// Occurs when a configuration file cannot be written.
    #[error(transparent)]
    File(#[from] biscara_files::FileError),
    /// Occurs when the recorder's file holds a line that is not a sample, or lost samples.
    #[error("the recording's line {line}: {message}")]
    Recording {
        /// 1-based line of the recorder's file.
        line: usize,
        /// What is wrong.
        message: String,
    },
}

impl LinuxcncError {
    /// An I/O error on `path`.
    pub(crate) fn io(path: &Path, source: std::io::Error) -> LinuxcncError {
        LinuxcncError::Io { path: path.to_owned(), source }
    }

    /// Whether `err` or one of its sources is a run's [`LinuxcncError::Interrupted`] (the
    /// command line then ends with 130, as an interrupt while writing a file does).
    pub fn is_interrupted(err: &(dyn std::error::Error + 'static)) -> bool {
        std::iter::successors(Some(err), |&cause| cause.source())
            .any(|cause| matches!(cause.downcast_ref(), Some(LinuxcncError::Interrupted)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, thiserror::Error)]
    #[error("running job.ngc")]
    struct Context(#[source] LinuxcncError);

    #[test]
    fn an_interrupt_is_found_among_the_causes() {
        assert!(LinuxcncError::is_interrupted(&LinuxcncError::Interrupted));
        assert!(LinuxcncError::is_interrupted(&Context(LinuxcncError::Interrupted)));
        let other = LinuxcncError::Usage { message: "no".to_owned() };
        assert!(!LinuxcncError::is_interrupted(&Context(other)));
    }
}
