//! Where a program runs: its G54 origin and, with `--fit`, the offset that centres it in the
//! workspace rectangle (docs/gcode.md, docs/virtual-robot.md).

use biscara_kinematics::RobotModel;
use biscara_motion::Position;
use std::cell::Cell;
use std::rc::Rc;

use biscara_robot::{Bounds, Transform, Workspace, fit};

use crate::motions::{NoteSink, Reading, Told, read_motions};
use crate::{Hint, Note, PipelineError, ProgramKind, ProgramSource, SamplingConfig};

/// Grid step of the workspace rectangle `--fit` centres programs in, millimetres (the default
/// of `biscara workspace`).
const FIT_STEP_MM: f64 = 2.0;

/// Why a path CSV cannot be fitted.
pub(crate) const FIT_NOT_PATH: &str =
    "a path CSV holds samples at their place: only a program can be fitted to the workspace";

/// Where a program's motions go.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Placement {
    /// The G54 offset in force before a G-code program's first line, `[x, y, z, c]` (mm, mm,
    /// mm, degrees).
    pub origin: Position,
    /// Where a G-code program starts when not at the robot's home pose: moved with the program
    /// when it made its start point its zero (`G92 X0 Y0`); `None` at home.
    pub start: Option<Position>,
    /// What is done to the motions as read: an inter-file's shift, and the 90° turn of a program
    /// that fits only turned; `None` when nothing.
    pub transform: Option<Transform>,
}

/// The placement of the program: the configuration's `origin` (zero when `None`), and with `fit` the offset
/// that centres the program's XY extent (arcs included) in the largest rectangle of the
/// workspace, turned by 90° about Z when it fits only that way, and its Z extent centred in the
/// Z stroke when it lies outside it; announced as a [`Note::Placed`]. A G-code program that
/// makes its start point its zero with G92 is placed by moving its start, any other by moving
/// its G54 origin, an inter-file by moving its motions. `fit` reads the program once more, so
/// its source must be re-readable; a path CSV holds samples and cannot be placed.
pub fn place(
    model: &RobotModel,
    source: &dyn ProgramSource,
    kind: ProgramKind,
    config: &SamplingConfig,
    notes: &mut dyn FnMut(Note),
) -> Result<Placement, PipelineError> {
    let tool = crate::pipeline::configured_tool(model, config);
    let mut origin = config.origin.unwrap_or([0.0; 4]);
    if !config.fit {
        return Ok(Placement { origin, start: None, transform: None });
    }
    let file = source.name();
    if !source.rereadable() {
        return Err(PipelineError::unsupported(
            file,
            "fitting a program to the workspace reads it twice: give a file, not standard input",
        ));
    }
    if kind == ProgramKind::Path {
        return Err(PipelineError::unsupported(file, FIT_NOT_PATH));
    }
    let home = model.home_position();
    let mut bounds = Bounds::new(home);
    let zeroed = Rc::new(Cell::new([false; 4]));
    let motions = read_motions(
        model,
        source,
        kind,
        &Reading::of(config, origin, None, tool),
        NoteSink::silent(),
        Told { zeroed: Some(zeroed.clone()), tool: None },
    )?;
    for (count, motion) in motions.enumerate() {
        let motion = motion?;
        if count as u64 >= config.max_fit_motions {
            return Err(PipelineError::Unsupported {
                file: file.to_owned(),
                message: format!(
                    "fitting a program to the workspace reads it whole to find its extent, and \
                     it goes on past {} motions (line {}): an endless loop that moves?",
                    config.max_fit_motions, motion.line
                ),
                hints: vec![Hint::PlaceByOrigin],
            });
        }
        bounds.push(&motion);
    }
    let zeroed = zeroed.get();
    let by_start = zeroed[0] || zeroed[1];
    if by_start {
        // X0 Y0 is the start point, and a point of the part.
        bounds.include_home();
    }
    if zeroed[2] {
        bounds.include_home_z();
    }
    let workspace =
        Workspace::compute(&model.kinematics(), FIT_STEP_MM).map_err(PipelineError::Workspace)?;
    let rectangle = workspace.largest_rectangle().map_err(PipelineError::Workspace)?;
    let placed = fit(&bounds, &rectangle)
        .map_err(|error| PipelineError::Fit { file: file.to_owned(), error })?;
    let stroke = z_stroke(model);
    let dz = z_shift(bounds.z, stroke);
    let mut transform = placed.transform();
    notes(Note::Placed {
        file: file.to_owned(),
        fit: placed,
        z: bounds.z,
        stroke,
        dz,
        by_start: by_start || zeroed[2],
    });
    if kind == ProgramKind::Gcode {
        // The interpreter moves the program before the turn: by R⁻¹ of the offset.
        let [ux, uy] = transform.unturn_vector(placed.offset);
        let mut start = None;
        if by_start || zeroed[2] {
            let mut moved = home;
            if by_start {
                moved[0] += ux;
                moved[1] += uy;
            }
            if zeroed[2] {
                moved[2] += dz;
            }
            start = Some(moved);
        }
        if !by_start {
            origin[0] += ux;
            origin[1] += uy;
        }
        if !zeroed[2] {
            origin[2] += dz;
        }
        let transform = transform.rotated.then_some(Transform { offset: [0.0; 3], ..transform });
        Ok(Placement { origin, start, transform })
    } else {
        transform.offset[2] = dz;
        Ok(Placement { origin, start: None, transform: Some(transform) })
    }
}

/// The Z range the tool point reaches, `[lowest, highest]` mm: `z = lp − d4` over the d4 limits.
fn z_stroke(model: &RobotModel) -> [f64; 2] {
    let robot = model.robot();
    let [d4_min, d4_max] = robot.joint_limits.d4;
    [robot.lp - d4_max, robot.lp - d4_min]
}

/// The Z shift that centres a program's Z extent `z` in `stroke` when it lies outside it (zero
/// when it is inside, or when the program has no Z extent).
fn z_shift(z: [f64; 2], stroke: [f64; 2]) -> f64 {
    if z[0] > z[1] || !z[0].is_finite() || (z[0] >= stroke[0] && z[1] <= stroke[1]) {
        return 0.0;
    }
    0.5 * (stroke[0] + stroke[1]) - 0.5 * (z[0] + z[1])
}
