//! `biscara.Robot`: the robot file, batch inverse and forward kinematics, the workspace.

use std::path::PathBuf;

use biscara_design::{Design, Evaluator};
use biscara_kinematics::{BatchSolution, BatchStatus, Joints, Kinematics, Pose, Robot, RobotModel};
use biscara_robot::Workspace;
use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::error::{Failure, check_signals};

/// Poses solved between two checks for signals (Ctrl-C), and per call of the batch solver.
const CHUNK: usize = 1 << 16;

/// A robot: its description (robot.json) validated and modelled once.
#[pyclass(name = "Robot", module = "biscara._biscara", frozen)]
pub(crate) struct PyRobot {
    pub(crate) model: RobotModel,
}

impl PyRobot {
    fn of(robot: Robot, path: Option<&str>, text: &str) -> Result<PyRobot, Failure> {
        let model = RobotModel::new(robot).map_err(|err| located(&err, path, text))?;
        Ok(PyRobot { model })
    }
}

/// A robot-file error (`LINE:COL: key: …`, or `key: …` from validation, located by its key).
fn located(err: &biscara_kinematics::RobotError, path: Option<&str>, _text: &str) -> Failure {
    let name = path.unwrap_or("<json>");
    let failure = Failure::message_in(format!("{name}:{err}"), Some(name));
    match (failure, path) {
        (Failure::Located { message, line, column, .. }, None) => {
            Failure::Located { message, path: None, line, column }
        }
        (failure, _) => failure,
    }
}

/// The row and message of a pose `inverse_batch` could not solve: the message of
/// [`Kinematics::inverse_checked`], as `biscara ik` prints it.
fn failed_pose(
    kinematics: &Kinematics,
    row: usize,
    given: &[f64],
    pose: &Pose,
    status: BatchStatus,
) -> (usize, String) {
    let p = &given[..4];
    let why = match kinematics.inverse_checked(pose) {
        Err(err) => err.to_string(),
        Ok(_) => format!("{status:?}"),
    };
    let message = format!(
        "row {row}: pose (x, y, z, c) = ({}, {}, {}, {}) is unreachable: {why}",
        p[0], p[1], p[2], p[3]
    );
    (row, message)
}

/// An angle conversion.
type Convert = fn(f64) -> f64;

/// What `ik` and `fk` return: the (N, 4) values, the mask of rows solved, the first row that
/// failed with its message, and the first row that is not finite (`ik` only: `fk`'s caller
/// checks).
type Solved<'py> = (Bound<'py, PyAny>, Bound<'py, PyAny>, Option<(usize, String)>, Option<usize>);

/// Conversions of the caller's angles to radians and back: degrees as the command line converts
/// them (`to_radians`, `to_degrees`), or none.
fn angle_units(radians: bool) -> (Convert, Convert) {
    if radians { (|v| v, |v| v) } else { (f64::to_radians, f64::to_degrees) }
}

#[pymethods]
impl PyRobot {
    /// The built-in robot.
    #[new]
    fn new() -> PyRobot {
        PyRobot { model: RobotModel::default() }
    }

    /// The robot described by the file `path` (robot.json).
    #[staticmethod]
    fn from_file(py: Python<'_>, path: PathBuf) -> PyResult<PyRobot> {
        let name = path.display().to_string();
        let text = std::fs::read_to_string(&path).map_err(|err| {
            Failure::in_file(format!("cannot read {name}: {err}"), &name).into_py(py)
        })?;
        let robot =
            Robot::from_json(&text).map_err(|err| located(&err, Some(&name), &text).into_py(py))?;
        PyRobot::of(robot, Some(&name), &text).map_err(|failure| failure.into_py(py))
    }

    /// The robot described by the JSON text `text`.
    #[staticmethod]
    fn from_json(py: Python<'_>, text: &str) -> PyResult<PyRobot> {
        let robot = Robot::from_json(text).map_err(|err| located(&err, None, text).into_py(py))?;
        PyRobot::of(robot, None, text).map_err(|failure| failure.into_py(py))
    }

    /// The robot as JSON, as `biscara robot` prints it.
    fn to_json(&self) -> String {
        biscara_dynamics::robot_in_force(self.model.robot()).to_json_pretty()
    }

    /// The robot's name.
    #[getter]
    fn name(&self) -> String {
        self.model.robot().name.clone()
    }

    /// The robot with other link lengths and base distance, as a design sweep builds it.
    fn with_design(&self, py: Python<'_>, l1: f64, l2: f64, base: f64) -> PyResult<PyRobot> {
        let evaluator = Evaluator::new(self.model.robot().clone(), 2.0, None)
            .map_err(|err| Failure::from(err).into_py(py))?;
        let robot = evaluator.robot_of(&Design { index: 0, l1, l2, base });
        let text = robot.to_json_pretty();
        PyRobot::of(robot, None, &text).map_err(|failure| failure.into_py(py))
    }

    /// Batch inverse kinematics of the C-contiguous (N, 4) float64 array `poses` (x, y, z mm,
    /// c in degrees, or radians with `radians`): the (N, 4) joints (θ1, θ2, θ3, d4), a boolean
    /// mask of the poses solved, the first row that failed with its message (None when all
    /// were solved), and the first row that is not finite.
    fn ik<'py>(
        &self,
        py: Python<'py>,
        poses: PyReadonlyArray2<'py, f64>,
        radians: bool,
    ) -> PyResult<Solved<'py>> {
        let input = poses.as_slice()?;
        let n = input.len() / 4;
        let kinematics = self.model.kinematics();
        let result = py.detach(|| -> Result<_, Failure> {
            let mut joints = Vec::with_capacity(4 * n);
            let mut mask = Vec::with_capacity(n);
            let mut first: Option<(usize, String)> = None;
            let mut not_finite = None;
            let mut batch = Vec::with_capacity(CHUNK.min(n));
            let mut out = Vec::with_capacity(CHUNK.min(n));
            let (to_rad, from_rad) = angle_units(radians);
            for (chunk, rows) in input.chunks(4 * CHUNK).enumerate() {
                batch.clear();
                batch.extend(
                    rows.chunks_exact(4).map(|p| Pose::new(p[0], p[1], p[2], to_rad(p[3]))),
                );
                out.clear();
                out.resize(batch.len(), BatchSolution::default());
                kinematics.inverse_batch(&batch, &mut out);
                for (k, solution) in out.iter().enumerate() {
                    let ok = solution.status == BatchStatus::Ok;
                    mask.push(ok);
                    if ok {
                        let [t1, t2, t3, d4] = solution.joints.to_array();
                        joints.extend([from_rad(t1), from_rad(t2), from_rad(t3), d4]);
                        continue;
                    }
                    joints.extend([f64::NAN; 4]);
                    if solution.status == BatchStatus::NotFinite {
                        not_finite.get_or_insert(chunk * CHUNK + k);
                    } else if first.is_none() {
                        first = Some(failed_pose(
                            &kinematics,
                            chunk * CHUNK + k,
                            &rows[4 * k..],
                            &batch[k],
                            solution.status,
                        ));
                    }
                }
                if n > CHUNK {
                    check_signals()?;
                }
            }
            Ok((joints, mask, first, not_finite))
        });
        let (joints, mask, first, not_finite) = result.map_err(|failure| failure.into_py(py))?;
        let joints = PyArray1::from_vec(py, joints).reshape([n, 4])?.into_any();
        let mask = PyArray1::from_vec(py, mask).into_any();
        Ok((joints, mask, first, not_finite))
    }

    /// Forward kinematics of the C-contiguous (N, 4) float64 array `joints` (θ1, θ2, θ3 in
    /// degrees, or radians with `radians`, d4 mm): the (N, 4) poses, a mask of the rows solved,
    /// and the first row that failed with its message.
    fn fk<'py>(
        &self,
        py: Python<'py>,
        joints: PyReadonlyArray2<'py, f64>,
        radians: bool,
    ) -> PyResult<Solved<'py>> {
        let input = joints.as_slice()?;
        let n = input.len() / 4;
        let kinematics = self.model.kinematics();
        let result = py.detach(|| -> Result<_, Failure> {
            let mut poses = vec![f64::NAN; 4 * n];
            let mut mask = vec![false; n];
            let mut first = None;
            let (to_rad, from_rad) = angle_units(radians);
            for (row, (q, slot)) in input.chunks_exact(4).zip(poses.chunks_exact_mut(4)).enumerate() {
                let joints = Joints::new(to_rad(q[0]), to_rad(q[1]), to_rad(q[2]), q[3]);
                match kinematics.forward(&joints) {
                    Ok(solution) => {
                        let pose = solution.pose;
                        slot.copy_from_slice(&[pose.x, pose.y, pose.z, from_rad(pose.phi)]);
                        mask[row] = true;
                    }
                    Err(err) if first.is_none() => {
                        first = Some((
                            row,
                            format!(
                                "row {row}: joints (θ1, θ2, θ3, d4) = ({}, {}, {}, {}) have no pose: {err}",
                                q[0], q[1], q[2], q[3]
                            ),
                        ));
                    }
                    Err(_) => {}
                }
                if row % CHUNK == CHUNK - 1 {
                    check_signals()?;
                }
            }
            Ok((poses, mask, first))
        });
        let (poses, mask, first) = result.map_err(|failure| failure.into_py(py))?;
        let poses = PyArray1::from_vec(py, poses).reshape([n, 4])?.into_any();
        let mask = PyArray1::from_vec(py, mask).into_any();
        Ok((poses, mask, first, None))
    }

    /// The reachable XY grid at multiples of `step` (mm): a dict with `area_mm2`, `step_mm`,
    /// `rect` (x0, x1, y0, y1), `grid` (bool, rows along y), `x_mm` and `y_mm`.
    fn workspace<'py>(&self, py: Python<'py>, step: f64) -> PyResult<Bound<'py, PyDict>> {
        let kinematics = self.model.kinematics();
        let computed = py.detach(|| -> Result<_, Failure> {
            let workspace =
                Workspace::compute(&kinematics, step).map_err(|err| Failure::of(&err, None))?;
            let rectangle = workspace.largest_rectangle().ok();
            Ok((workspace, rectangle))
        });
        let (workspace, rectangle) = computed.map_err(|failure| failure.into_py(py))?;
        let (columns, rows) = workspace.size();
        let mut grid = Vec::with_capacity(columns * rows);
        for j in 0..rows {
            grid.extend((0..columns).map(|i| workspace.is_reachable(i, j)));
        }
        let x: Vec<f64> = (0..columns).map(|i| workspace.point(i, 0)[0]).collect();
        let y: Vec<f64> = (0..rows).map(|j| workspace.point(0, j)[1]).collect();
        let dict = PyDict::new(py);
        dict.set_item("area_mm2", workspace.area_mm2())?;
        dict.set_item("step_mm", workspace.step())?;
        dict.set_item("rect", rectangle.map(|r| (r.min[0], r.max[0], r.min[1], r.max[1])))?;
        dict.set_item("grid", PyArray1::from_vec(py, grid).reshape([rows, columns])?)?;
        dict.set_item("x_mm", PyArray1::from_vec(py, x))?;
        dict.set_item("y_mm", PyArray1::from_vec(py, y))?;
        Ok(dict)
    }
}
