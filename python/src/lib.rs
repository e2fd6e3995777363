//! biscara for Python: the extension module `biscara._biscara`, which the Python package
//! `biscara` (python/biscara/__init__.py) wraps. Every function runs the library the command line
//! runs, with the GIL released, and builds its results straight into NumPy arrays.

mod error;
mod program;
mod robot;
mod source;

use std::path::PathBuf;

use biscara_design::{
    DesignGrid, Evaluator, Objective, ParamRange, ProgramTimer, Shard, Sweep, SweepOptions, Task,
};
use biscara_pipeline::{GenerateError, generate};
use biscara_post::{PostOptions, post as post_cl};
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::error::{Failure, check_signals};
use crate::robot::PyRobot;
use crate::source::Program;

/// `design`: the sweep's columns (named as the design CSV's) as a dict of 1-D arrays, and the
/// row of the best design by `objective` (None when no design qualifies); with `programs`, each
/// design's total time of them (`time_s`, NaN where one cannot run).
#[pyfunction]
#[pyo3(signature = (robot, l1, l2, base, step, task, objective, threads, programs, fit))]
#[allow(clippy::too_many_arguments)]
fn design<'py>(
    py: Python<'py>,
    robot: &Bound<'py, PyRobot>,
    l1: &str,
    l2: &str,
    base: &str,
    step: f64,
    task: Option<&str>,
    objective: &str,
    threads: usize,
    programs: Vec<PathBuf>,
    fit: bool,
) -> PyResult<(Bound<'py, PyDict>, Option<usize>)> {
    let robot = robot.get().model.robot().clone();
    let swept = py
        .detach(|| -> Result<_, Failure> {
            let objective = match objective {
                "rect" => Objective::Rectangle,
                "gci" => Objective::Gci,
                "area" => Objective::Area,
                "lci_min" => Objective::LciMin,
                "time" => Objective::Time,
                "cycle" => Objective::Cycle,
                other => {
                    return Err(Failure::Value(format!(
                        "objective must be \"rect\", \"gci\", \"area\", \"lci_min\", \"time\" or \
                         \"cycle\", got {other:?}"
                    )));
                }
            };
            let range = |what, text| ParamRange::parse(what, text).map_err(Failure::from);
            let grid = DesignGrid::new(range("l1", l1)?, range("l2", l2)?, range("base", base)?)?;
            let task: Option<Task> = task.map(str::parse).transpose()?;
            let mut evaluator = Evaluator::new(robot, step, task)?;
            if !programs.is_empty() {
                let mut texts = Vec::with_capacity(programs.len());
                for path in &programs {
                    let name = path.display().to_string();
                    let text = std::fs::read_to_string(path).map_err(|err| {
                        Failure::in_file(format!("cannot read {name}: {err}"), &name)
                    })?;
                    texts.push((name, text));
                }
                evaluator = evaluator.with_programs(ProgramTimer::new(texts, fit));
            } else if objective == Objective::Time {
                return Err(Failure::Value("objective \"time\" needs programs".to_owned()));
            }
            if objective == Objective::Cycle {
                evaluator = evaluator.with_cycle();
            }
            let with_cycle = objective == Objective::Cycle;
            let sweep = Sweep::new(evaluator, grid, Shard::ALL);
            let mut rows = Vec::new();
            let options = SweepOptions { threads, objective, cells: false };
            let outcome = sweep.run(&options, |evaluation| -> Result<(), Failure> {
                rows.push(*evaluation);
                if rows.len() % 256 == 0 {
                    check_signals()?;
                }
                Ok(())
            })?;
            let chosen = outcome.best.map(|chosen| chosen.design.index);
            Ok((rows, chosen, task.is_some(), !programs.is_empty(), with_cycle))
        })
        .map_err(|failure| failure.into_py(py))?;
    let (rows, chosen, with_task, with_time, with_cycle) = swept;
    let column = |value: fn(&biscara_design::Evaluation) -> f64| {
        PyArray1::from_vec(py, rows.iter().map(value).collect())
    };
    let dict = PyDict::new(py);
    let index: Vec<u64> = rows.iter().map(|e| e.design.index).collect();
    dict.set_item("index", PyArray1::from_vec(py, index))?;
    dict.set_item("l1", column(|e| e.design.l1))?;
    dict.set_item("l2", column(|e| e.design.l2))?;
    dict.set_item("base", column(|e| e.design.base))?;
    dict.set_item("area_mm2", column(|e| e.area_mm2))?;
    dict.set_item("rect_w_mm", column(|e| e.rectangle.map_or(0.0, |r| r.width())))?;
    dict.set_item("rect_h_mm", column(|e| e.rectangle.map_or(0.0, |r| r.height())))?;
    dict.set_item("rect_x0_mm", column(|e| e.rectangle.map_or(0.0, |r| r.min[0])))?;
    dict.set_item("rect_y0_mm", column(|e| e.rectangle.map_or(0.0, |r| r.min[1])))?;
    dict.set_item("gci", column(|e| e.gci))?;
    dict.set_item("lci_min", column(|e| e.lci_min))?;
    let status: Vec<&str> = rows.iter().map(|e| e.status.as_str()).collect();
    dict.set_item("status", status)?;
    if with_task {
        let task_ok: Vec<bool> = rows.iter().map(|e| e.task_ok == Some(true)).collect();
        dict.set_item("task_ok", PyArray1::from_vec(py, task_ok))?;
    }
    if with_time {
        dict.set_item("time_s", column(|e| e.time_s.unwrap_or(f64::NAN)))?;
    }
    if with_cycle {
        dict.set_item("cycle_s", column(|e| e.cycle_s.unwrap_or(f64::NAN)))?;
    }
    let best = chosen.and_then(|index| rows.iter().position(|e| e.design.index == index));
    Ok((dict, best))
}

/// `gen`: a points file (or its text) → G-code text.
#[pyfunction]
#[pyo3(signature = (robot, path, source, line_numbers))]
#[pyo3(name = "gen")]
fn generate_gcode(
    py: Python<'_>,
    robot: &Bound<'_, PyRobot>,
    path: Option<PathBuf>,
    source: Option<String>,
    line_numbers: bool,
) -> PyResult<String> {
    let kinematics = robot.get().model.kinematics();
    py.detach(|| -> Result<_, Failure> {
        let program = Program::new(path, source)?;
        let file = program.file().map(str::to_owned);
        let mut out = Vec::new();
        let options = PostOptions { line_numbers };
        generate(program.reader()?, &kinematics, &mut out, None, options).map_err(
            |err| match err {
                GenerateError::Points(err) => Failure::located(&err, file.as_deref()),
                GenerateError::Post(err) if err.line().is_some() => {
                    Failure::located(&err, Some("<generated CL>"))
                }
                other => Failure::of(&other, None),
            },
        )?;
        String::from_utf8(out).map_err(Failure::plain)
    })
    .map_err(|failure| failure.into_py(py))
}

/// `post`: a CL file (or its text) → G-code text.
#[pyfunction]
#[pyo3(signature = (path, source, line_numbers))]
fn post(
    py: Python<'_>,
    path: Option<PathBuf>,
    source: Option<String>,
    line_numbers: bool,
) -> PyResult<(String, Option<String>)> {
    py.detach(|| -> Result<_, Failure> {
        let program = Program::new(path, source)?;
        let file = program.file().map(str::to_owned);
        let mut out = Vec::new();
        let summary =
            post_cl(program.reader()?, &mut out, PostOptions { line_numbers }).map_err(|err| {
                if err.line().is_some() {
                    Failure::located(&err, file.as_deref())
                } else {
                    Failure::of(&err, None)
                }
            })?;
        let text = String::from_utf8(out).map_err(Failure::plain)?;
        Ok((text, summary.ignored_note()))
    })
    .map_err(|failure| failure.into_py(py))
}

/// The module `biscara._biscara`.
#[pymodule]
fn _biscara(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("Error", m.py().get_type::<error::Error>())?;
    m.add_class::<PyRobot>()?;
    m.add_function(wrap_pyfunction!(program::interpret, m)?)?;
    m.add_function(wrap_pyfunction!(program::joints, m)?)?;
    m.add_function(wrap_pyfunction!(program::interpolate, m)?)?;
    m.add_function(wrap_pyfunction!(program::check, m)?)?;
    m.add_function(wrap_pyfunction!(design, m)?)?;
    m.add_function(wrap_pyfunction!(generate_gcode, m)?)?;
    m.add_function(wrap_pyfunction!(post, m)?)?;
    Ok(())
}
