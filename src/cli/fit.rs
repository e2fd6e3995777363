//! `--fit`: placing a program in the workspace rectangle (SPEC §4.2, §8.2).

use std::path::Path;

use anyhow::anyhow;
use biscara::kinematics::{Kinematics, Robot};
use biscara::robot::{Bounds, fit};
use biscara::text::fixed;

use super::display_path;
use super::trajectory::{InputKind, motions};

/// Grid step of the workspace rectangle `--fit` centres programs in, millimetres (the default of
/// `biscara workspace`).
const FIT_STEP_MM: f64 = 2.0;

/// The XY offset that centres the program's bounding box in the workspace rectangle, reported on
/// stderr. Reads the program once (so it must be a file, not standard input); `origin` is the
/// G54 offset of a G-code program.
pub(crate) fn fit_offset(
    path: &Path,
    kind: InputKind,
    robot: &Robot,
    origin: [f64; 4],
) -> anyhow::Result<[f64; 2]> {
    let name = display_path(path);
    if path == Path::new("-") {
        return Err(anyhow!("--fit reads the program twice: give a file, not standard input"));
    }
    if kind == InputKind::Path {
        return Err(anyhow!("{name}: --fit places a program, not a path CSV"));
    }
    let home = Kinematics::new(robot)?.home().to_degrees();
    let mut bounds = Bounds::new(home);
    for motion in motions(path, kind, robot, origin)? {
        bounds.push(&motion?);
    }
    let (_, rectangle) = super::workspace::compute(robot, FIT_STEP_MM)?;
    let placed = fit(&bounds, &rectangle).map_err(|err| anyhow!("{name}: --fit: {err}"))?;
    let [dx, dy] = placed.offset;
    let f = |v: f64| fixed(v, 3);
    #[allow(clippy::print_stderr)]
    {
        eprintln!(
            "biscara: note: {name}: --fit: the program's XY extent x {}..{}, y {}..{} mm \
             ({} x {} mm) is centred in the workspace rectangle x {}..{}, y {}..{} mm by the \
             offset X{} Y{} (z and c unchanged)",
            f(bounds.min[0]),
            f(bounds.max[0]),
            f(bounds.min[1]),
            f(bounds.max[1]),
            f(bounds.width()),
            f(bounds.height()),
            f(rectangle.min[0]),
            f(rectangle.max[0]),
            f(rectangle.min[1]),
            f(rectangle.max[1]),
            f(dx),
            f(dy)
        );
    }
    Ok(placed.offset)
}

/// The G54 origin and the extra shift of a program's motions: with `fit`, a G-code program's
/// origin moves by the fit offset (so G28/G53 keep their machine meaning), an inter-file's
/// absolute motions are shifted instead.
pub(crate) fn placement(
    path: &Path,
    kind: InputKind,
    robot: &Robot,
    origin: Option<[f64; 4]>,
    fit: bool,
) -> anyhow::Result<([f64; 4], Option<[f64; 2]>)> {
    let mut origin = origin.unwrap_or([0.0; 4]);
    if !fit {
        return Ok((origin, None));
    }
    let offset = fit_offset(path, kind, robot, origin)?;
    if kind == InputKind::Gcode {
        origin[0] += offset[0];
        origin[1] += offset[1];
        Ok((origin, None))
    } else {
        Ok((origin, Some(offset)))
    }
}
