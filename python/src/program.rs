//! The functions that run a program: `interpret`, `interpolate`, `joints` and `check`, through
//! the library's pipeline, with the GIL released and signals checked between chunks.

use std::cell::RefCell;
use std::io::Write as _;
use std::path::PathBuf;
use std::rc::Rc;
use std::sync::Arc;

use biscara_dynamics::Dynamics;
use biscara_files::FileSystem;
use biscara_gcode::{Dialect, IniFile, Tool, ToolTable};
use biscara_interpolate::{PATH_HEADER, Profile};
use biscara_joints::{AngleUnit, JointCsvFormat, JointSample, TORQUE_COLUMNS};
use biscara_motion::write_jsonl;
use biscara_pipeline::{Note, Pipeline, SamplingConfig, ToolState, torque_columns};
use biscara_robot::{Checker, Scene};
use numpy::PyArray1;
use pyo3::prelude::*;

use crate::error::{Failure, check_signals};
use crate::robot::PyRobot;
use crate::source::Program;

/// Samples between two checks for signals (Ctrl-C).
const CHUNK: usize = 1 << 16;

/// Slowed motions reported one by one before they are only counted (as on the command line).
const SLOWED_SHOWN: usize = 20;

/// How a program is read and sampled: the command line's options, as the Python layer passes
/// them (a dict, already checked there).
#[derive(Debug, FromPyObject)]
#[pyo3(from_item_all)]
pub(crate) struct Options {
    /// `gcode`, `jsonl`, `path` or None (from the name and first bytes).
    kind: Option<String>,
    dialect: String,
    tool: Option<String>,
    origin: Option<[f64; 4]>,
    fit: bool,
    profile: String,
    dt: f64,
    grip_time: f64,
    blend: Option<f64>,
    subroutine_path: Vec<PathBuf>,
    tool_table: Option<PathBuf>,
    ini: Option<PathBuf>,
    max_idle_jumps: u64,
    max_motions: u64,
    time_limit: f64,
}

impl Options {
    /// The pipeline's configuration.
    fn config(&self) -> Result<SamplingConfig, Failure> {
        let dialect: Dialect =
            self.dialect.parse().map_err(|err| Failure::Value(format!("dialect: {err}")))?;
        let tool = match &self.tool {
            Some(name) => Some(Tool::from_name(name).ok_or_else(|| {
                Failure::Value(format!(
                    "tool: {name:?} is not a tool: gripper, laser, spindle, extruder or pen"
                ))
            })?),
            None => None,
        };
        let profile = match self.profile.as_str() {
            "constant" => Profile::Constant,
            "trapezoid" => Profile::Trapezoid,
            "optimal" => Profile::Optimal,
            other => {
                return Err(Failure::Value(format!(
                    "profile must be \"constant\", \"trapezoid\" or \"optimal\", got {other:?}"
                )));
            }
        };
        let tool_table = match &self.tool_table {
            Some(path) => Some(Arc::new(
                ToolTable::read(&FileSystem, path).map_err(|err| Failure::of(&err, None))?,
            )),
            None => None,
        };
        let ini = match &self.ini {
            Some(path) => Some(Arc::new(
                IniFile::read(&FileSystem, path).map_err(|err| Failure::of(&err, None))?,
            )),
            None => None,
        };
        Ok(SamplingConfig {
            dt: self.dt,
            profile,
            grip_time: self.grip_time,
            origin: self.origin,
            fit: self.fit,
            dialect,
            tool,
            subroutine_path: self.subroutine_path.clone(),
            blend: self.blend,
            tool_table,
            ini,
            max_idle_jumps: self.max_idle_jumps,
            max_motions: self.max_motions,
            time_limit: self.time_limit,
            ..SamplingConfig::default()
        })
    }
}

/// The pipeline's notes, kept as text (the command line prints them on stderr; the Python layer
/// logs them): slowed motions one by one up to [`SLOWED_SHOWN`], then counted.
#[derive(Default, Clone)]
struct Notes {
    kept: Rc<RefCell<(Vec<String>, usize)>>,
}

impl Notes {
    fn sink(&self) -> impl FnMut(Note) + 'static {
        let kept = Rc::clone(&self.kept);
        move |note| {
            let mut kept = kept.borrow_mut();
            if let Note::SlowedDown { .. } = note {
                kept.1 += 1;
                if kept.1 > SLOWED_SHOWN {
                    return;
                }
            }
            kept.0.push(note.to_string());
        }
    }

    fn finish(self) -> Vec<String> {
        let (mut notes, slowed) = self.kept.take();
        if slowed > SLOWED_SHOWN {
            notes.push(format!("{slowed} motions slowed in all"));
        }
        notes
    }
}

/// Columns of numbers, filled row by row.
struct Columns {
    names: Vec<String>,
    values: Vec<Vec<f64>>,
    rows: usize,
}

impl Columns {
    fn new(names: Vec<String>) -> Columns {
        let values = names.iter().map(|_| Vec::new()).collect();
        Columns { names, values, rows: 0 }
    }

    /// Appends one row (as many values as columns), checking for signals now and then.
    fn push(&mut self, row: impl IntoIterator<Item = f64>) -> Result<(), Failure> {
        for (column, value) in self.values.iter_mut().zip(row) {
            column.push(value);
        }
        self.rows += 1;
        if self.rows.is_multiple_of(CHUNK) {
            check_signals()?;
        }
        Ok(())
    }

    /// The columns as a list of (name, 1-D array) pairs, in order.
    fn into_py(self, py: Python<'_>) -> Vec<(String, Bound<'_, PyArray1<f64>>)> {
        self.names
            .into_iter()
            .zip(self.values)
            .map(|(name, values)| (name, PyArray1::from_vec(py, values)))
            .collect()
    }
}

/// The (name, array) pairs of a sampled program and its notes.
type Table<'py> = (Vec<(String, Bound<'py, PyArray1<f64>>)>, Vec<String>);

/// `interpret`: the program's motions as the inter-file's JSON Lines records, gathered into one
/// JSON array (the Python layer parses it), and the notes.
#[pyfunction]
#[pyo3(signature = (robot, path, source, options))]
pub(crate) fn interpret(
    py: Python<'_>,
    robot: &Bound<'_, PyRobot>,
    path: Option<PathBuf>,
    source: Option<String>,
    options: Options,
) -> PyResult<(String, Vec<String>)> {
    let model = &robot.get().model;
    py.detach(|| -> Result<_, Failure> {
        let program = Program::new(path, source)?;
        let config = options.config()?;
        let notes = Notes::default();
        let kind = program.kind(options.kind.as_deref().or(Some("gcode")))?;
        let motions = Pipeline::new(model, config).motions(program.source(), kind, notes.sink())?;
        let mut out = Vec::with_capacity(64 * 1024);
        out.push(b'[');
        for (count, motion) in motions.enumerate() {
            if count > 0 {
                out.push(b',');
            }
            write_jsonl(&mut out, &motion?).map_err(Failure::plain)?;
            if out.last() == Some(&b'\n') {
                out.pop();
            }
            if count % CHUNK == CHUNK - 1 {
                check_signals()?;
            }
        }
        out.push(b']');
        let text = String::from_utf8(out).map_err(Failure::plain)?;
        Ok((text, notes.finish()))
    })
    .map_err(|failure| failure.into_py(py))
}

/// `joints`: the joint trajectory's columns, named as the joint CSV's, and the notes.
#[pyfunction]
#[pyo3(signature = (robot, path, source, options, derivatives, radians, events, torques))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn joints<'py>(
    py: Python<'py>,
    robot: &Bound<'py, PyRobot>,
    path: Option<PathBuf>,
    source: Option<String>,
    options: Options,
    derivatives: bool,
    radians: bool,
    events: bool,
    torques: bool,
) -> PyResult<Table<'py>> {
    let model = &robot.get().model;
    let (columns, notes) = py
        .detach(|| -> Result<_, Failure> {
            let program = Program::new(path, source)?;
            let kind = program.kind(options.kind.as_deref())?;
            let pipeline = Pipeline::new(model, options.config()?);
            let notes = Notes::default();
            let angle_unit = if radians { AngleUnit::Radians } else { AngleUnit::Degrees };
            // The torques are those of each row's own derivatives, so they come with them.
            let derivatives = derivatives || torques;
            let format = JointCsvFormat { angle_unit, derivatives, precision: 6 };
            let dynamics = if torques { Some(Dynamics::new(model)?) } else { None };
            let file = program.source().name().to_owned();
            let mut names = format.columns();
            if torques {
                names.extend(TORQUE_COLUMNS.iter().map(|name| (*name).to_owned()));
            }
            // [τ1, τ2, τ3, f_d4, payload] of a row, when asked for.
            let torques_of = |row: &JointSample, tool: Option<Tool>| -> Result<Vec<f64>, Failure> {
                let Some(dynamics) = &dynamics else { return Ok(Vec::new()) };
                Ok(torque_columns(dynamics, row, tool, &file)?.to_vec())
            };
            if events {
                let mut samples = pipeline.tool_joints(program.source(), kind, notes.sink())?;
                let tool = samples.tool();
                names.extend(ToolState::columns(tool).iter().map(|name| (*name).to_owned()));
                let mut columns = Columns::new(names);
                while let Some(row) = samples.next_sample() {
                    let (row, state) = row?;
                    pipeline.within_time_limit(&file, row.t, row.line)?;
                    let extra = torques_of(row, Some(tool))?;
                    columns.push(format.values(row).chain(extra).chain([state.value(tool)]))?;
                }
                return Ok((columns, notes.finish()));
            }
            let mut samples = pipeline.joints(program.source(), kind, notes.sink())?;
            if !derivatives {
                samples = samples.without_derivatives();
            }
            let mut columns = Columns::new(names);
            while let Some(row) = samples.next_sample() {
                let row = row?;
                pipeline.within_time_limit(&file, row.t, row.line)?;
                let extra = torques_of(row, None)?;
                columns.push(format.values(row).chain(extra))?;
            }
            Ok((columns, notes.finish()))
        })
        .map_err(|failure| failure.into_py(py))?;
    Ok((columns.into_py(py), notes))
}

/// `interpolate`: the Cartesian path's columns, named as the path CSV's, and the notes.
#[pyfunction]
#[pyo3(signature = (robot, path, source, options, events))]
pub(crate) fn interpolate<'py>(
    py: Python<'py>,
    robot: &Bound<'py, PyRobot>,
    path: Option<PathBuf>,
    source: Option<String>,
    options: Options,
    events: bool,
) -> PyResult<Table<'py>> {
    let model = &robot.get().model;
    let (columns, notes) = py
        .detach(|| -> Result<_, Failure> {
            let program = Program::new(path, source)?;
            let kind = program.kind(options.kind.as_deref())?;
            if kind == biscara_pipeline::ProgramKind::Path {
                let name = program.file().unwrap_or(crate::error::SOURCE_NAME);
                let message = format!(
                    "{name}: a path CSV holds samples already: give G-code or an inter-file"
                );
                return Err(Failure::message_in(message, Some(name)));
            }
            let pipeline = Pipeline::new(model, options.config()?);
            let notes = Notes::default();
            let mut names: Vec<String> = PATH_HEADER.split(',').map(str::to_owned).collect();
            let mut samples = pipeline.tool_samples(program.source(), kind, notes.sink())?;
            let tool = samples.tool();
            if events {
                names.extend(ToolState::columns(tool).iter().map(|name| (*name).to_owned()));
            }
            let mut columns = Columns::new(names);
            let file = program.source().name().to_owned();
            for sample in samples {
                let (sample, state) = sample?;
                pipeline.within_time_limit(&file, sample.t, sample.line)?;
                let [x, y, z, c] = sample.pose;
                let tool_value = events.then(|| state.value(tool));
                columns.push([sample.t, x, y, z, c].into_iter().chain(tool_value))?;
            }
            Ok((columns, notes.finish()))
        })
        .map_err(|failure| failure.into_py(py))?;
    Ok((columns.into_py(py), notes))
}

/// `check`: the report as `check --json` prints it (JSON text), and the notes; an error once the
/// program has run the options' `time_limit` s of robot time (`--time-limit`).
#[pyfunction]
#[pyo3(signature = (robot, path, source, options, scene_path, scene_text))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn check(
    py: Python<'_>,
    robot: &Bound<'_, PyRobot>,
    path: Option<PathBuf>,
    source: Option<String>,
    options: Options,
    scene_path: Option<PathBuf>,
    scene_text: Option<String>,
) -> PyResult<(String, Vec<String>)> {
    let model = &robot.get().model;
    py.detach(|| -> Result<_, Failure> {
        let scene = match (&scene_path, &scene_text) {
            (Some(path), _) => {
                let name = path.display().to_string();
                let bytes = std::fs::read(path)
                    .map_err(|err| Failure::in_file(format!("cannot read {name}: {err}"), &name))?;
                Scene::from_json(&bytes).map_err(|err| Failure::located(&err, Some(&name)))?
            }
            (None, Some(text)) => {
                Scene::from_json(text.as_bytes()).map_err(|err| Failure::located(&err, None))?
            }
            (None, None) => Scene::new(),
        };
        let program = Program::new(path, source)?;
        let kind = program.kind(options.kind.as_deref())?;
        let notes = Notes::default();
        let mut checker = Checker::new(model, scene);
        let mut samples = Pipeline::new(model, options.config()?).tool_samples(
            program.source(),
            kind,
            notes.sink(),
        )?;
        let tool = samples.tool();
        for (count, sample) in samples.by_ref().enumerate() {
            let (sample, state) = sample?;
            checker.push(&sample);
            if let Some((subject, detail, severity)) = state.problem(tool) {
                checker.push_tool_problem(&sample, subject, detail, severity);
            }
            if count % CHUNK == CHUNK - 1 {
                check_signals()?;
            }
        }
        let report = checker.finish();
        let mut text = Vec::new();
        write!(text, "{}", report.to_json()).map_err(Failure::plain)?;
        Ok((String::from_utf8(text).map_err(Failure::plain)?, notes.finish()))
    })
    .map_err(|failure| failure.into_py(py))
}
