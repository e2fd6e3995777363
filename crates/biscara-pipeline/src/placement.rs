//! Where a program runs: its G54 origin and, with `--fit`, the offset that centres it in the
//! workspace rectangle (SPEC §4.2, §8.2).

use biscara_kinematics::RobotModel;
use biscara_motion::Position;
use biscara_robot::{Bounds, Workspace, fit};

use crate::motions::{NoteSink, Reading, read_motions};
use crate::{Note, PipelineError, ProgramKind, ProgramSource, SamplingConfig};

/// Grid step of the workspace rectangle `--fit` centres programs in, millimetres (the default
/// of `biscara workspace`).
const FIT_STEP_MM: f64 = 2.0;

/// Where a program's motions go.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Placement {
    /// The G54 offset in force before a G-code program's first line, `[x, y, z, c]` (mm, mm,
    /// mm, degrees).
    pub origin: Position,
    /// An XY shift added to an inter-file's absolute motions (mm); `None` for G-code, whose
    /// origin moves instead (so that G28 and G53 keep their machine meaning).
    pub shift: Option<[f64; 2]>,
}

/// The placement of the program: the configuration's `origin` as given (zero when `None`), and
/// with its `fit` the offset that centres the program's XY extent (arcs included) in the largest rectangle of the
/// workspace, announced as a [`Note::Placed`]. `fit` reads the program once more, so its source
/// must be re-readable; a path CSV holds samples and cannot be placed.
pub fn place(
    model: &RobotModel,
    source: &dyn ProgramSource,
    kind: ProgramKind,
    config: &SamplingConfig,
    notes: &mut dyn FnMut(Note),
) -> Result<Placement, PipelineError> {
    let mut origin = config.origin.unwrap_or([0.0; 4]);
    if !config.fit {
        return Ok(Placement { origin, shift: None });
    }
    let file = source.name();
    if !source.rereadable() {
        return Err(PipelineError::Unsupported {
            file: file.to_owned(),
            message: "--fit reads the program twice: give a file, not standard input".to_owned(),
        });
    }
    if kind == ProgramKind::Path {
        return Err(PipelineError::Unsupported {
            file: file.to_owned(),
            message: "--fit places a program, not a path CSV".to_owned(),
        });
    }
    let mut bounds = Bounds::new(model.home_position());
    let reading = Reading {
        dialect: config.dialect,
        subroutine_path: &config.subroutine_path,
        blend: config.blend,
    };
    for motion in read_motions(model, source, kind, origin, &reading, NoteSink::silent())? {
        bounds.push(&motion?);
    }
    let workspace =
        Workspace::compute(&model.kinematics(), FIT_STEP_MM).map_err(PipelineError::Workspace)?;
    let rectangle = workspace.largest_rectangle().map_err(PipelineError::Workspace)?;
    let placed = fit(&bounds, &rectangle)
        .map_err(|error| PipelineError::Fit { file: file.to_owned(), error })?;
    notes(Note::Placed { file: file.to_owned(), fit: placed });
    if kind == ProgramKind::Gcode {
        origin[0] += placed.offset[0];
        origin[1] += placed.offset[1];
        Ok(Placement { origin, shift: None })
    } else {
        Ok(Placement { origin, shift: Some(placed.offset) })
    }
}
