//! The pipeline run as a library, without a process: the same stages as the commands.

use biscara_interpolate::Profile;
use biscara_kinematics::{Pose, RobotModel};
use biscara_pipeline::{
    Note, Pipeline, PipelineError, ProgramKind, ProgramSource, SamplingConfig, TextSource,
};

const PROGRAM: &str = "G21 G90\nG0 X-20 Y380 Z60 C0\nG1 X20 F3000\nG2 X40 Y400 I0 J20\nM2\n";

fn pipeline(model: &RobotModel, config: SamplingConfig) -> Pipeline<'_> {
    Pipeline::new(model, config)
}

#[test]
fn gcode_and_its_inter_file_give_the_same_samples() {
    let model = RobotModel::default();
    let pipeline = pipeline(&model, SamplingConfig::default());
    let gcode = TextSource::new("job.ngc", PROGRAM);
    let mut jsonl = Vec::new();
    for motion in pipeline.motions(&gcode, ProgramKind::Gcode, |_| {}).unwrap() {
        biscara_motion::write_jsonl(&mut jsonl, &motion.unwrap()).unwrap();
    }
    let jsonl = TextSource::new("job.jsonl", String::from_utf8(jsonl).unwrap());
    let from_gcode: Vec<_> =
        pipeline.samples(&gcode, ProgramKind::Gcode, |_| {}).unwrap().map(Result::unwrap).collect();
    let from_jsonl: Vec<_> =
        pipeline.samples(&jsonl, ProgramKind::Jsonl, |_| {}).unwrap().map(Result::unwrap).collect();
    assert_eq!(from_gcode.len(), from_jsonl.len());
    assert!(from_gcode.len() > 1000);
    for (a, b) in from_gcode.iter().zip(&from_jsonl) {
        assert_eq!(a.t, b.t);
        for axis in 0..4 {
            assert!((a.pose[axis] - b.pose[axis]).abs() < 1e-9);
        }
    }
}

#[test]
fn each_sample_by_reference_is_the_iterator_and_stops_at_its_error() {
    let model = RobotModel::default();
    let pipeline = pipeline(&model, SamplingConfig::default());
    let source = TextSource::new("job.ngc", PROGRAM);
    let iterated: Vec<_> = pipeline
        .samples(&source, ProgramKind::Gcode, |_| {})
        .unwrap()
        .map(Result::unwrap)
        .collect();
    let mut each = Vec::new();
    let mut samples = pipeline.samples(&source, ProgramKind::Gcode, |_| {}).unwrap();
    samples
        .try_for_each_sample(|sample| {
            each.push(*sample);
            Ok::<_, PipelineError>(())
        })
        .unwrap();
    assert_eq!(each, iterated);
    // The program's error ends it, located; samples before it were passed on.
    let bad = TextSource::new("bad.ngc", "G0 X0 Y400 Z50\nG2 X10 Y400 F100\n");
    let mut seen = 0;
    let mut samples = pipeline.samples(&bad, ProgramKind::Gcode, |_| {}).unwrap();
    let err = samples
        .try_for_each_sample(|_| {
            seen += 1;
            Ok::<_, PipelineError>(())
        })
        .unwrap_err();
    assert!(seen > 1, "{seen}");
    assert!(err.to_string().starts_with("bad.ngc:2:1: "), "{err}");
    // And so does the caller's.
    let mut samples = pipeline.samples(&source, ProgramKind::Gcode, |_| {}).unwrap();
    let mut kept = 0;
    let stop = samples.try_for_each_sample(|sample| {
        kept += 1;
        if sample.t >= 0.01 {
            Err(PipelineError::Unsupported {
                file: "x".into(),
                message: "enough".into(),
                hints: vec![],
            })
        } else {
            Ok(())
        }
    });
    assert_eq!(kept, 11);
    assert!(stop.unwrap_err().to_string().ends_with("enough"));
}

#[test]
fn every_joint_row_lies_on_the_path_and_starts_at_home() {
    let model = RobotModel::default();
    let config = SamplingConfig { dt: 0.002, profile: Profile::Constant, ..Default::default() };
    let source = TextSource::new("job.ngc", PROGRAM);
    let mut rows = pipeline(&model, config).joints(&source, ProgramKind::Gcode, |_| {}).unwrap();
    let first = rows.next().unwrap().unwrap();
    assert_eq!(first.t, 0.0);
    assert_eq!(first.pose, model.home_position());
    for row in rows {
        let row = row.unwrap();
        let fk = model.kinematics().forward(&row.joints).unwrap();
        let [x, y, z, c] = row.pose;
        let expected = Pose::from_degrees(x, y, z, c);
        assert!((fk.pose.x - expected.x).hypot(fk.pose.y - expected.y) < 1e-6, "t = {}", row.t);
    }
}

#[test]
fn errors_are_located_in_the_program_with_a_caret() {
    let model = RobotModel::default();
    let source = TextSource::new("bad.ngc", "G0 X0 Y400\nG2 X10 Y400 F100\n");
    let err = pipeline(&model, SamplingConfig::default())
        .samples(&source, ProgramKind::Gcode, |_| {})
        .unwrap()
        .find_map(Result::err)
        .unwrap();
    let text = err.to_string();
    assert!(text.starts_with("bad.ngc:2:1: "), "{text}");
    assert!(text.ends_with("\n    G2 X10 Y400 F100\n    ^^"), "{text}");
}

#[test]
fn an_unreachable_sample_names_the_file_line_and_time() {
    let model = RobotModel::default();
    let source = TextSource::new("far.ngc", "G0 X0 Y400 Z50\nG1 Y900 F6000\n");
    let err = pipeline(&model, SamplingConfig::default())
        .joints(&source, ProgramKind::Gcode, |_| {})
        .unwrap()
        .find_map(Result::err)
        .unwrap();
    let text = err.to_string();
    assert!(text.starts_with("far.ngc:2: at t = "), "{text}");
    assert!(text.contains("cannot be taken"), "{text}");
}

#[test]
fn fit_places_the_program_and_says_so() {
    let model = RobotModel::default();
    // A part drawn about its own zero: (0, 0) is not reachable by the robot.
    let part = "G0 X0 Y0 Z50\nG1 X40 F3000\nG1 Y30\nG1 X0\nG1 Y0\nM2\n";
    let source = TextSource::new("part.ngc", part);
    let notes = std::rc::Rc::new(std::cell::RefCell::new(Vec::new()));
    let heard = std::rc::Rc::clone(&notes);
    let config = SamplingConfig { fit: true, ..SamplingConfig::default() };
    let rows: Vec<_> = pipeline(&model, config)
        .joints(&source, ProgramKind::Gcode, move |note| heard.borrow_mut().push(note))
        .unwrap()
        .collect::<Result<_, _>>()
        .unwrap();
    assert!(rows.len() > 100);
    let notes = notes.borrow();
    let [Note::Placed { file, fit, .. }] = notes.as_slice() else { panic!("{notes:?}") };
    assert_eq!(file, "part.ngc");
    assert!(fit.offset[1] > 100.0, "{fit:?}");
}

/// Standard input: readable once.
struct Once(TextSource);

impl ProgramSource for Once {
    fn name(&self) -> &str {
        "<stdin>"
    }

    fn open(&self) -> std::io::Result<Box<dyn std::io::BufRead>> {
        self.0.open()
    }

    fn rereadable(&self) -> bool {
        false
    }
}

#[test]
fn fit_refuses_a_source_it_cannot_read_twice_and_a_path_csv() {
    let model = RobotModel::default();
    let config = SamplingConfig { fit: true, ..SamplingConfig::default() };
    let stdin = Once(TextSource::new("-", PROGRAM));
    let err =
        pipeline(&model, config.clone()).samples(&stdin, ProgramKind::Gcode, |_| {}).err().unwrap();
    assert!(matches!(err, PipelineError::Unsupported { .. }), "{err}");
    assert!(err.to_string().contains("not standard input"), "{err}");
    let csv = TextSource::new("path.csv", "t_s,x_mm,y_mm,z_mm,c_deg\n0,0,400,50,0\n");
    let err = pipeline(&model, config).samples(&csv, ProgramKind::Path, |_| {}).err().unwrap();
    assert_eq!(
        err.to_string(),
        "path.csv: a path CSV holds samples at their place: only a program can be fitted to \
         the workspace"
    );
}

#[test]
fn a_path_csv_is_read_as_it_is() {
    let model = RobotModel::default();
    let csv =
        TextSource::new("path.csv", "t_s,x_mm,y_mm,z_mm,c_deg\n0,0,400,50,0\n0.5,10,400,50,0\n");
    let samples: Vec<_> = pipeline(&model, SamplingConfig::default())
        .samples(&csv, ProgramKind::Path, |_| {})
        .unwrap()
        .collect::<Result<_, _>>()
        .unwrap();
    assert_eq!(samples.len(), 2);
    assert_eq!(samples[1].pose, [10.0, 400.0, 50.0, 0.0]);
    assert_eq!(samples[1].line, 3);
}

mod placement;

/// The kinds of the motions of `program` read with `tool` and the robot file `robot`, and the
/// notes.
fn tool_kinds(
    robot: &str,
    tool: Option<biscara_gcode::Tool>,
    program: &str,
) -> (Vec<&'static str>, Vec<Note>) {
    let model = RobotModel::from_json(robot).unwrap();
    let notes = std::rc::Rc::new(std::cell::RefCell::new(Vec::new()));
    let heard = std::rc::Rc::clone(&notes);
    let config = SamplingConfig { tool, ..SamplingConfig::default() };
    let source = TextSource::new("job.nc", program);
    let kinds = pipeline(&model, config)
        .motions(&source, ProgramKind::Gcode, move |note| heard.borrow_mut().push(note))
        .unwrap()
        .map(|m| m.unwrap().kind.name())
        .filter(|name| !matches!(*name, "rapid" | "linear"))
        .collect();
    let notes = notes.borrow().clone();
    (kinds, notes)
}

#[test]
fn the_tool_comes_from_the_flag_then_the_robot_file_then_the_program() {
    use biscara_gcode::Tool;
    let laser = "M3 S0\nG1 X10 Y400 F600\nS300\nG1 X20\nM5\nM2\n";
    // Inferred, with a note that says why.
    let (kinds, notes) = tool_kinds("{}", None, laser);
    assert_eq!(kinds, ["laser_on", "laser_on", "laser_off", "end"]);
    let said: Vec<String> = notes.iter().map(ToString::to_string).collect();
    assert!(
        said.iter()
            .any(|n| n.starts_with("job.nc:1: tool: laser (M3/M4 with S power and no Z move")),
        "{said:?}"
    );
    // The robot file says: no inference, no note.
    let (kinds, notes) = tool_kinds(r#"{"tool":{"kind":"spindle"}}"#, None, laser);
    assert_eq!(kinds, ["spindle_on", "spindle_on", "spindle_off", "end"]);
    assert!(!notes.iter().any(|n| matches!(n, Note::Tool { .. })), "{notes:?}");
    // The flag wins over the robot file.
    let (kinds, _) = tool_kinds(r#"{"tool":{"kind":"spindle"}}"#, Some(Tool::Gripper), laser);
    assert_eq!(kinds, ["pick", "gripper_off", "end"]);
    // The paper's pick and place stays the gripper's, with no note.
    let (kinds, notes) = tool_kinds("{}", None, "G0 X0 Y400 Z5\nM3\nG0 Z20\nM4\nM2\n");
    assert_eq!(kinds, ["pick", "place", "end"]);
    assert!(!notes.iter().any(|n| matches!(n, Note::Tool { .. })), "{notes:?}");
}

#[test]
fn a_robot_file_with_a_bad_tool_is_refused_naming_the_key() {
    let err = RobotModel::from_json(r#"{"tool":{"kind":"torch"}}"#).unwrap_err().to_string();
    assert!(err.contains("tool.kind") && err.contains("torch"), "{err}");
    let err = RobotModel::from_json(r#"{"tool":{"max_power":0}}"#).unwrap_err().to_string();
    assert!(err.contains("tool.max_power"), "{err}");
}

#[test]
fn tool_offsets_come_from_the_table_or_a_note_says_there_is_none() {
    let model = RobotModel::default();
    let program = "G21 G90\nT1 M6\nG43 H1\nG0 X0 Y400 Z10\nM2\n";
    let source = TextSource::new("tools.ngc", program);
    let run = |config: SamplingConfig| {
        let notes = std::rc::Rc::new(std::cell::RefCell::new(Vec::new()));
        let heard = std::rc::Rc::clone(&notes);
        let motions: Vec<_> = pipeline(&model, config)
            .motions(&source, ProgramKind::Gcode, move |note| heard.borrow_mut().push(note))
            .unwrap()
            .collect::<Result<_, _>>()
            .unwrap();
        let end = motions.iter().find_map(|motion| motion.kind.end()).unwrap();
        let notes = notes.borrow().clone();
        (end, notes)
    };
    let (end, notes) = run(SamplingConfig::default());
    assert_eq!(end[2], 10.0);
    assert!(
        notes
            .iter()
            .any(|note| matches!(note, Note::ToolsWithoutTable { file } if file == "tools.ngc")),
        "{notes:?}"
    );
    let table = biscara_gcode::ToolTable::parse("T1 P1 Z25 D6\n".as_bytes(), "t.tbl").unwrap();
    let config = SamplingConfig {
        tool_table: Some(std::sync::Arc::new(table)),
        ..SamplingConfig::default()
    };
    let (end, notes) = run(config);
    assert_eq!(end[2], 35.0, "the machine holds the tool's tip at Z10");
    assert!(!notes.iter().any(|note| matches!(note, Note::ToolsWithoutTable { .. })), "{notes:?}");
}

#[test]
fn a_grbl_program_is_told_what_grbl_itself_refuses() {
    let model = RobotModel::default();
    let notes_of = |name: &str, program: &str| {
        let source = TextSource::new(name, program);
        let notes = std::rc::Rc::new(std::cell::RefCell::new(Vec::new()));
        let heard = std::rc::Rc::clone(&notes);
        let config =
            SamplingConfig { dialect: biscara_gcode::Dialect::Grbl, ..SamplingConfig::default() };
        let motions = pipeline(&model, config)
            .motions(&source, ProgramKind::Gcode, move |note| heard.borrow_mut().push(note))
            .unwrap();
        assert!(motions.collect::<Result<Vec<_>, _>>().is_ok());
        notes.borrow().iter().map(ToString::to_string).collect::<Vec<_>>()
    };
    let notes = notes_of(
        "peck.nc",
        "G21 G90 F100
G0 X0 Y400 Z10
G83 X1 Y400 Z5 R8 Q1
G80
",
    );
    let note = notes.iter().find(|note| note.contains("itself refuses")).expect("a note");
    assert_eq!(
        note,
        "peck.nc: grbl itself refuses these (its error 20, unsupported command); read here as \
         LinuxCNC reads them, so the program runs here but not on that machine: G83 ×1"
    );
    let notes = notes_of(
        "plain.nc",
        "G21 G90 F100
G0 X0 Y400 Z10
G1 X1
",
    );
    assert!(!notes.iter().any(|note| note.contains("itself refuses")), "{notes:?}");
}

/// A writer that refuses every byte, as a full disk does.
struct FullDisk;

impl std::io::Write for FullDisk {
    fn write(&mut self, _: &[u8]) -> std::io::Result<usize> {
        Err(std::io::Error::new(std::io::ErrorKind::StorageFull, "no space left"))
    }

    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

#[test]
fn the_csv_outputs_have_a_row_per_sample_and_the_tool_column_asked_for() {
    let model = RobotModel::default();
    let pipeline = pipeline(&model, SamplingConfig::default());
    let source = TextSource::new("job.ngc", PROGRAM);
    let samples = pipeline.samples(&source, ProgramKind::Gcode, |_| {}).unwrap().count();
    let mut path = Vec::new();
    pipeline.write_path_csv(&source, ProgramKind::Gcode, &mut path, 3, false, |_| {}).unwrap();
    let path = String::from_utf8(path).unwrap();
    assert_eq!(path.lines().next(), Some("t_s,x_mm,y_mm,z_mm,c_deg"));
    assert_eq!(path.lines().count(), samples + 1);
    let [x, y, z, c] = model.home_position();
    let home = format!("0.000,{x:.3},{y:.3},{z:.3},{c:.3}").replace("-0.000", "0.000");
    assert_eq!(path.lines().nth(1), Some(home.as_str()), "the home pose");
    let laser =
        TextSource::new("laser.nc", "G21 G90\nM4 S500\nG1 X-20 Y380 Z60 F3000\nM5\nG0 X-30\nM2\n");
    let config = SamplingConfig { tool: Some(biscara_gcode::Tool::Laser), ..Default::default() };
    let mut joints = Vec::new();
    let format = biscara_joints::JointCsvFormat {
        angle_unit: biscara_joints::AngleUnit::Degrees,
        derivatives: false,
        precision: 2,
    };
    Pipeline::new(&model, config)
        .write_joint_csv(&laser, ProgramKind::Gcode, &mut joints, format, true, |_| {})
        .unwrap();
    let joints = String::from_utf8(joints).unwrap();
    let header = joints.lines().next().unwrap();
    assert!(header.starts_with("t_s,theta1_deg,") && header.ends_with(",laser_power"), "{header}");
    let powers: Vec<&str> =
        joints.lines().skip(1).map(|row| row.rsplit(',').next().unwrap()).collect();
    let burning = powers.iter().filter(|power| **power == "500.00").count();
    assert!(burning > 100 && burning < powers.len(), "{burning} of {}", powers.len());
    assert_eq!(powers.last(), Some(&"0.00"), "off during the last G0");
}

#[test]
fn the_csv_outputs_say_why_they_stop() {
    let model = RobotModel::default();
    let pipeline = pipeline(&model, SamplingConfig::default());
    let source = TextSource::new("job.ngc", PROGRAM);
    let err = pipeline
        .write_path_csv(&source, ProgramKind::Gcode, &mut FullDisk, 6, false, |_| {})
        .unwrap_err();
    assert!(matches!(err, PipelineError::Write(_)), "{err:?}");
    // A path CSV is already a path: nothing to interpolate, nothing written.
    let csv = TextSource::new("path.csv", "t_s,x_mm,y_mm,z_mm,c_deg\n0,0,400,50,0\n");
    let mut out = Vec::new();
    let err =
        pipeline.write_path_csv(&csv, ProgramKind::Path, &mut out, 6, false, |_| {}).unwrap_err();
    assert_eq!(
        err.to_string(),
        "path.csv: a path CSV holds samples already: give G-code or an inter-file"
    );
    assert!(out.is_empty());
    // A program that cannot be placed writes nothing, not even the header.
    let far = TextSource::new("far.ngc", "G0 X0 Y0 Z50\nG1 X5000 F3000\nM2\n");
    let fit = Pipeline::new(&model, SamplingConfig { fit: true, ..Default::default() });
    let format = biscara_joints::JointCsvFormat {
        angle_unit: biscara_joints::AngleUnit::Radians,
        derivatives: true,
        precision: 6,
    };
    let err =
        fit.write_joint_csv(&far, ProgramKind::Gcode, &mut out, format, false, |_| {}).unwrap_err();
    assert!(
        err.to_string().starts_with("far.ngc: cannot fit the program to the workspace: "),
        "{err}"
    );
    assert!(out.is_empty());
}
