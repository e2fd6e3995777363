//! `--fit` on programs as CAM systems write them: G92 zeros, programs that fit only turned, Z
//! outside the stroke, and every program of `../shared/realworld`.

use std::cell::RefCell;
use std::path::PathBuf;
use std::rc::Rc;

use biscara_kinematics::RobotModel;
use biscara_motion::{Motion, MotionKind, Plane};
use biscara_pipeline::{
    Hint, Note, Pipeline, PipelineError, ProgramKind, SamplingConfig, TextSource,
};
use biscara_robot::Rectangle;

/// The motions of `program` placed by `--fit`, with the notes.
fn placed(name: &str, program: &str) -> (Result<Vec<Motion>, PipelineError>, Vec<Note>) {
    let model = RobotModel::default();
    let config = SamplingConfig { fit: true, ..SamplingConfig::default() };
    let source = TextSource::new(name, program);
    run(&model, config, &source)
}

fn run(
    model: &RobotModel,
    config: SamplingConfig,
    source: &dyn biscara_pipeline::ProgramSource,
) -> (Result<Vec<Motion>, PipelineError>, Vec<Note>) {
    let notes = Rc::new(RefCell::new(Vec::new()));
    let heard = Rc::clone(&notes);
    let kind = ProgramKind::Gcode;
    let motions = Pipeline::new(model, config)
        .motions(source, kind, move |note| heard.borrow_mut().push(note))
        .and_then(|motions| motions.collect::<Result<Vec<_>, _>>());
    let notes = notes.borrow().clone();
    (motions, notes)
}

/// The rectangle, whether the program was turned, and the Z shift of the placement note.
fn placement(notes: &[Note]) -> (Rectangle, bool, f64) {
    for note in notes {
        if let Note::Placed { fit, dz, .. } = note {
            return (fit.rectangle, fit.rotated, *dz);
        }
    }
    panic!("no placement note in {notes:?}");
}

fn inside(rectangle: &Rectangle, [x, y, ..]: [f64; 4]) -> bool {
    const MM: f64 = 1e-6;
    x >= rectangle.min[0] - MM
        && x <= rectangle.max[0] + MM
        && y >= rectangle.min[1] - MM
        && y <= rectangle.max[1] + MM
}

const HOME: [f64; 4] = [0.0, 460.798724079689, 100.0, 0.0];

fn at_home_xy(end: [f64; 4]) -> bool {
    (end[0] - HOME[0]).abs() < 1e-9 && (end[1] - HOME[1]).abs() < 1e-9
}

#[test]
fn a_program_that_zeroes_itself_with_g92_moves_with_its_start() {
    // SuperCam's way: the tool is where the part's zero is, G92 says so. A 40 x 30 mm
    // rectangle with a corner at the zero, cut 2 mm deep.
    let program = "G92 X0 Y0 Z0\nG0 Z5\nG0 X0 Y0\nG1 Z-2 F300\nG1 X40\nG1 Y30\nG1 X0\nG1 Y0\n\
                   G0 Z5\nM2\n";
    let (motions, notes) = placed("g92.ngc", program);
    let motions = motions.unwrap();
    let (rectangle, rotated, dz) = placement(&notes);
    assert!(!rotated);
    let ends: Vec<_> = motions.iter().filter_map(|m| m.kind.end()).collect();
    // Every corner of the part is inside the rectangle, and the part is centred in it.
    for end in &ends {
        assert!(inside(&rectangle, *end), "{end:?} outside {rectangle:?}");
        assert!(!at_home_xy(*end), "{end:?} left at home");
    }
    let xs: Vec<f64> = ends.iter().map(|e| e[0]).collect();
    let ys: Vec<f64> = ends.iter().map(|e| e[1]).collect();
    let (min_x, max_x) =
        (xs.iter().cloned().fold(f64::MAX, f64::min), xs.iter().cloned().fold(f64::MIN, f64::max));
    let (min_y, max_y) =
        (ys.iter().cloned().fold(f64::MAX, f64::min), ys.iter().cloned().fold(f64::MIN, f64::max));
    assert!((max_x - min_x - 40.0).abs() < 1e-9 && (max_y - min_y - 30.0).abs() < 1e-9);
    let centre = rectangle.center();
    assert!((0.5 * (min_x + max_x) - centre[0]).abs() < 1e-9);
    assert!((0.5 * (min_y + max_y) - centre[1]).abs() < 1e-9);
    // Z: zeroed at the home pose's Z (the top of the stroke), Z5 is above it: the range
    // −2..5 (98..105 mm) is centred in the stroke 0..100, at 46.5..53.5 mm.
    assert!((dz - (50.0 - (HOME[2] + 1.5))).abs() < 1e-9, "{dz}");
    let zs: Vec<f64> = ends.iter().map(|e| e[2]).collect();
    assert!(zs.iter().all(|&z| (46.5 - 1e-9..=53.5 + 1e-9).contains(&z)), "{zs:?}");
    assert!(notes.iter().any(|n| n.to_string().contains("zeroes itself with G92")), "{notes:?}");
}

#[test]
fn a_program_that_fits_only_turned_is_turned_with_its_arcs_and_c() {
    // 100 mm wide, 300 mm tall: taller than the 210 mm rectangle, narrower than its 464 mm.
    // A half circle of radius 50 on top, in XY; a quarter arc in XZ at the bottom.
    let program = "G0 X0 Y0 Z-20 C10\nG1 Y250 F1000\nG2 X100 Y250 I50 J0\nG1 Y0\n\
                   G18 G2 X90 Z-10 I-10 K0\nM2\n";
    let (motions, notes) = placed("tall.ngc", program);
    let motions = motions.unwrap();
    let (rectangle, rotated, _) = placement(&notes);
    assert!(rotated, "{notes:?}");
    assert!(notes[0].to_string().contains("turned by 90°"), "{}", notes[0]);
    let model = RobotModel::default();
    let mut start = model.home_position();
    for motion in &motions {
        let Some(end) = motion.kind.end() else { continue };
        assert!(inside(&rectangle, end), "{end:?} outside {rectangle:?}");
        // C turns with the program.
        assert_eq!(end[3], 100.0);
        if let MotionKind::Arc { center, plane, .. } = motion.kind {
            // The centre is as far from the start as from the end: still the same circle.
            let [a, b, _] = plane.axes();
            let radius = |p: [f64; 4]| (p[a] - center[0]).hypot(p[b] - center[1]);
            assert!((radius(start) - radius(end)).abs() < 1e-9, "{motion:?} from {start:?}");
            match motion.line {
                3 => assert_eq!(plane, Plane::Xy),
                // The XZ arc (in the plane y = 0) turned by 90° lies in a plane x = const.
                5 => assert_eq!(plane, Plane::Yz),
                _ => unreachable!(),
            }
        }
        start = end;
    }
    // The samples follow the turned arcs: the program runs.
    let config = SamplingConfig { fit: true, ..SamplingConfig::default() };
    let source = TextSource::new("tall.ngc", program);
    let samples = Pipeline::new(&model, config).samples(&source, ProgramKind::Gcode, |_| {});
    assert!(samples.unwrap().all(|s| s.is_ok_and(|s| inside(&rectangle, s.pose) || at_home_xy(s.pose) || s.t < 1.0)));
}

#[test]
fn an_inter_file_is_turned_and_placed_as_its_g_code_is() {
    let program = "G0 X0 Y0 Z-20 C10\nG1 Y250 F1000\nG2 X100 Y250 I50 J0\nG1 Y0\n\
                   G18 G2 X90 Z-10 I-10 K0\nM2\n";
    let model = RobotModel::default();
    let gcode = TextSource::new("tall.ngc", program);
    let mut jsonl = Vec::new();
    let unplaced = Pipeline::new(&model, SamplingConfig::default());
    for motion in unplaced.motions(&gcode, ProgramKind::Gcode, |_| {}).unwrap() {
        biscara_motion::write_jsonl(&mut jsonl, &motion.unwrap()).unwrap();
    }
    let jsonl = TextSource::new("tall.jsonl", String::from_utf8(jsonl).unwrap());
    let config = SamplingConfig { fit: true, ..SamplingConfig::default() };
    let pipeline = Pipeline::new(&model, config);
    let from_gcode: Vec<_> =
        pipeline.motions(&gcode, ProgramKind::Gcode, |_| {}).unwrap().map(Result::unwrap).collect();
    let from_jsonl: Vec<_> =
        pipeline.motions(&jsonl, ProgramKind::Jsonl, |_| {}).unwrap().map(Result::unwrap).collect();
    assert_eq!(from_gcode.len(), from_jsonl.len());
    for (a, b) in from_gcode.iter().zip(&from_jsonl) {
        let (Some(ea), Some(eb)) = (a.kind.end(), b.kind.end()) else { continue };
        for axis in 0..4 {
            assert!((ea[axis] - eb[axis]).abs() < 1e-9, "{a:?} vs {b:?}");
        }
        if let (
            MotionKind::Arc { center: ca, plane: pa, .. },
            MotionKind::Arc { center: cb, plane: pb, .. },
        ) = (a.kind, b.kind)
        {
            assert_eq!(pa, pb);
            assert!((ca[0] - cb[0]).abs() < 1e-9 && (ca[1] - cb[1]).abs() < 1e-9, "{a:?} vs {b:?}");
        }
    }
}

#[test]
fn a_program_that_fits_neither_way_says_by_how_much_in_each() {
    let (motions, _) = placed("big.ngc", "G0 X0 Y0 Z50\nG1 X500 Y300 F1000\nM2\n");
    let err = motions.unwrap_err().to_string();
    assert!(
        err.starts_with("big.ngc: cannot fit the program to the workspace: the program's XY extent 500.000 x 300.000 mm"),
        "{err}"
    );
    assert!(
        err.contains("as programmed, 36.000 mm too wide in X and 90.000 mm too tall in Y; turned by 90° about Z, 290.000 mm too tall in Y"),
        "{err}"
    );
}

#[test]
fn z_outside_the_stroke_is_centred_in_it_and_inside_it_is_left() {
    let (motions, notes) = placed("deep.ngc", "G0 X0 Y0 Z-10\nG1 Z-50 F300\nG1 X20\nG0 Z-10\nM2\n");
    let (_, _, dz) = placement(&notes);
    assert_eq!(dz, 80.0);
    let zs: Vec<f64> = motions.unwrap().iter().filter_map(|m| m.kind.end()).map(|e| e[2]).collect();
    assert_eq!(zs, [70.0, 30.0, 30.0, 70.0]);
    let (motions, notes) = placed("inside.ngc", "G0 X0 Y0 Z60\nG1 Z40 F300\nG1 X20\nM2\n");
    assert_eq!(placement(&notes).2, 0.0);
    let zs: Vec<f64> = motions.unwrap().iter().filter_map(|m| m.kind.end()).map(|e| e[2]).collect();
    assert_eq!(zs, [60.0, 40.0, 40.0]);
    assert!(notes[0].to_string().ends_with("(z and c unchanged)"), "{}", notes[0]);
}

/// `../shared/realworld`, beside the clone or beside the folder of worktrees.
fn realworld() -> Option<PathBuf> {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..");
    for relative in ["../shared/realworld", "../../shared/realworld"] {
        let folder = root.join(relative);
        if folder.join("SOURCES.tsv").is_file() {
            return Some(folder);
        }
    }
    let in_ci = std::env::var("CI").is_ok_and(|value| value == "true");
    assert!(!in_ci, "../shared/realworld is missing, and CI=true requires it");
    None
}

/// What `--fit` does with a real program.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Fits {
    /// Placed as programmed; `g92`: it zeroes itself with G92, so its start moved.
    Placed { g92: bool, z_moved: bool },
    /// Placed turned by 90°.
    Turned,
    /// Larger than the rectangle both ways.
    TooLarge,
    /// Not read (a refusal or a LinuxCNC feature not there yet): the dialect tests name why.
    Unread,
}

/// Placed by its G54 origin, its Z range inside the stroke.
const PLACED: Fits = Fits::Placed { g92: false, z_moved: false };
/// Placed by its G54 origin; its Z zero is the stock top (or the paper), so it cuts below
/// z = 0 and its Z range is moved into the stroke.
const CUT: Fits = Fits::Placed { g92: false, z_moved: true };

/// What `--fit` does with each program of `../shared/realworld`.
const TABLE: &[(&str, Fits)] = &[
    ("laser/fabtotum-laser-cardboard.gcode", PLACED),
    ("laser/inkscape-lasertools-qr.gcode", PLACED),
    ("laser/lasergrbl-vector-snowflake.nc", PLACED),
    ("laser/laserweb4-lasercut-crlf.gcode", PLACED),
    ("mill/cambam-2008-smile-inch.nc", CUT),
    ("mill/cambam-birthday.nc", CUT),
    ("mill/dxf2gcode-b02-erin7.ngc", CUT),
    ("mill/estlcam10-spool.nc", CUT),
    ("mill/fengrave-140-text.ngc", CUT),
    ("mill/freecad-grbl-ecscentric-cut.nc", CUT),
    ("mill/fusion-grbl-clamp-base.nc", CUT),
    ("mill/fusion-linuxcnc-inch-hema-p030.ngc", CUT),
    ("mill/fusion-mach3-eccentric-g41p.tap", CUT),
    ("mill/fusion-mach3-heatsink-bottom.tap", CUT),
    ("mill/gcodetools-puzzle03.gcode", CUT),
    ("mill/jscut-jsdc-engrave.gcode", CUT),
    ("mill/openvoronoi-ttt-vcarve.ngc", CUT),
    ("mill/partkam-plate.nc", CUT),
    ("mill/pycam-tiny-cat-outline.ngc", CUT),
    ("mill/solidworkscam-motor-offset-g41d.tap", CUT),
    ("mill/supercam-girl-inch.gcode", Fits::Placed { g92: true, z_moved: false }),
    ("mill/viaconstructor-all.ngc", CUT),
    ("other/camotics-tpl-cds.gcode", Fits::TooLarge),
    ("other/flatcam-inferred-bcnc-sample.gcode", CUT),
    ("other/gcode-exporter-pcb-reprap.gcode", CUT),
    ("other/gmax-4axis-rotation-a.ngc", Fits::Unread),
    ("other/handwritten-linuxcnc-external-subs.ngc", Fits::Unread),
    ("other/handwritten-linuxcnc-spool-owords-b.nc", Fits::Unread),
    ("other/millmasterpro-mastercam-hdr-g70.nc", Fits::Unread),
    ("other/pcb2gcode-autolevel-linuxcnc-back.ngc", CUT),
    ("plotter/estlcam10-crown-plotter.gcode", Fits::Placed { g92: true, z_moved: true }),
    ("plotter/gcodeplot-3rect.gcode", PLACED),
    ("plotter/rotrics-studio-dexarm-quote.gcode", CUT),
    ("plotter/svg2gcode-smooth-curves-arcs.gcode", PLACED),
];

#[test]
fn every_real_program_is_placed_in_the_rectangle_or_says_why_not() {
    let Some(folder) = realworld() else { return };
    let model = RobotModel::default();
    let config = SamplingConfig { fit: true, ..SamplingConfig::default() };
    let [lowest, highest] = {
        let robot = model.robot();
        [robot.lp - robot.joint_limits.d4[1], robot.lp - robot.joint_limits.d4[0]]
    };
    let mut failures = Vec::new();
    let mut printers = 0;
    let mut names: Vec<String> = Vec::new();
    for group in ["laser", "mill", "other", "plotter", "printer"] {
        let mut files: Vec<_> = std::fs::read_dir(folder.join(group))
            .unwrap()
            .map(|entry| entry.unwrap().file_name().into_string().unwrap())
            .collect();
        files.sort();
        names.extend(files.into_iter().map(|file| format!("{group}/{file}")));
    }
    for name in &names {
        // Slicer output: placed as programmed, Z from the bed up (checked below like the rest).
        let expected = match TABLE.iter().find(|(file, _)| file == name) {
            Some((_, fits)) => *fits,
            None if name.starts_with("printer/") => {
                printers += 1;
                PLACED
            }
            None => panic!("{name} is not in the table"),
        };
        let text = std::fs::read_to_string(folder.join(name)).unwrap();
        let source = TextSource::new(name, text);
        let (motions, notes) = run(&model, config.clone(), &source);
        let found = match &motions {
            Err(PipelineError::Fit { .. }) => Fits::TooLarge,
            Err(_) => Fits::Unread,
            Ok(_) => {
                let Some(Note::Placed { fit, by_start, dz, .. }) =
                    notes.iter().find(|n| matches!(n, Note::Placed { .. }))
                else {
                    panic!("{name}: no placement note")
                };
                if fit.rotated {
                    Fits::Turned
                } else {
                    Fits::Placed { g92: *by_start, z_moved: *dz != 0.0 }
                }
            }
        };
        if found != expected {
            failures.push(format!(
                "{name}: expected {expected:?}, found {found:?}: {:?}",
                motions.err().map(|e| e.to_string())
            ));
            continue;
        }
        let Ok(motions) = motions else { continue };
        let (rectangle, ..) = placement(&notes);
        // Every move that the placement moved is inside the rectangle and the stroke.
        for motion in &motions {
            let Some(end) = motion.kind.end() else { continue };
            if at_home_xy(end) {
                continue;
            }
            if !inside(&rectangle, end) || end[2] < lowest - 1e-6 || end[2] > highest + 1e-6 {
                failures.push(format!(
                    "{name}:{}: {end:?} outside the rectangle or stroke",
                    motion.line
                ));
                break;
            }
        }
    }
    assert!(printers >= 9, "{printers} printer programs");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// `--fit` reads the whole program: one that loops forever while moving (and counting) stops at
/// a bound of motions with an error that says so, instead of reading on forever; one whose loop
/// comes back to the same state is refused at its second pass.
#[test]
fn fit_stops_an_endless_program_at_its_bound() {
    let model = RobotModel::default();
    let repeating = "G21 G90\no1 while [1]\nG0 X0 Y0\nG0 X10 Y10\no1 endwhile\nM2\n";
    let config = SamplingConfig { fit: true, ..SamplingConfig::default() };
    let (motions, _) = run(&model, config, &TextSource::new("endless.ngc", repeating));
    let message = motions.expect_err("endless").to_string();
    assert!(message.contains("endless.ngc:5:1: the loop at line 2 repeats forever"), "{message}");
    let program = "G21 G90\no1 while [1]\n#1 = [#1 + 1]\nG0 X0 Y0\nG0 X10 Y10\no1 endwhile\nM2\n";
    let config = SamplingConfig { fit: true, max_fit_motions: 1000, ..SamplingConfig::default() };
    let (motions, _) = run(&model, config, &TextSource::new("endless.ngc", program));
    let err = motions.expect_err("endless");
    let message = err.to_string();
    assert!(message.contains("past 1000 motions") && message.contains("endless"), "{message}");
    // The remedy is the caller's to word (the command line names its flags).
    assert_eq!(err.hints(), [Hint::PlaceByOrigin]);
    assert!(!message.contains("--"), "{message}");
}

/// `interpolate` and `joints` stop a program that never ends at the time limit, naming its line,
/// with the remedy for the caller to word.
#[test]
fn sampling_stops_at_the_time_limit() {
    let model = RobotModel::default();
    let program = "G21 G90\nG0 X0 Y400\no1 while [1]\n#1 = [#1 + 1]\nG1 X10 F6000\nG1 X0\n\
                   o1 endwhile\nM2\n";
    let source = TextSource::new("endless.ngc", program);
    let config = SamplingConfig { time_limit: 2.0, ..SamplingConfig::default() };
    let pipeline = Pipeline::new(&model, config);
    let mut out = Vec::new();
    let err = pipeline
        .write_path_csv(&source, ProgramKind::Gcode, &mut out, 3, false, |_| {})
        .expect_err("endless");
    let message = err.to_string();
    assert!(message.starts_with("endless.ngc:"), "{message}");
    assert!(message.contains("has run 2 s of robot time, past the time limit"), "{message}");
    assert_eq!(err.hints(), [Hint::MoreTime]);
    let format = biscara_joints::JointCsvFormat {
        angle_unit: biscara_joints::AngleUnit::Radians,
        derivatives: false,
        precision: 3,
    };
    let err = pipeline
        .write_joint_csv(&source, ProgramKind::Gcode, &mut Vec::new(), format, true, |_| {})
        .expect_err("endless");
    assert!(err.to_string().contains("past the time limit"), "{err}");
    // `check` and `plot` read the tool's samples, and `plot --torques` the torques: the same
    // limit, at the first sample past it.
    let samples = pipeline.tool_samples(&source, ProgramKind::Gcode, |_| {}).expect("samples");
    let mut last = 0.0;
    let err = samples
        .map(|sample| sample.map(|(sample, _)| last = sample.t))
        .collect::<Result<Vec<()>, _>>()
        .expect_err("endless");
    assert!(matches!(err, PipelineError::TimeLimit { limit: 2.0, .. }), "{err}");
    assert!((last - 2.0).abs() < 1e-9, "the last sample within the limit is at {last} s");
    let dynamics = biscara_dynamics::Dynamics::new(&model).expect("dynamics");
    let mut rows = 0;
    let err = pipeline
        .for_each_torque(
            &source,
            ProgramKind::Gcode,
            &dynamics,
            |_| {},
            |_, _| {
                rows += 1;
                Ok(())
            },
        )
        .expect_err("endless");
    assert!(err.to_string().contains("past the time limit"), "{err}");
    assert_eq!(rows, 2001, "the rows from 0 to 2 s");
}
