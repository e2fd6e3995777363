//! The self-contained HTML viewer (`biscara view`, docs/virtual-robot.md).

use std::collections::BTreeMap;
use std::io::BufRead;
use std::io::Write;

use biscara_joints::JointCsvRow;
use biscara_kinematics::{Kinematics, MeshSpec, Part, Robot, RobotModel, ToolKind};
use biscara_robot::ReportedProblem;
use biscara_text::round_to;

use crate::decimate::Decimator;
use crate::{MAX_MESH_TRIANGLES, ProgramOverlay, Scene, StlMesh, ToolWork, ViewError};

/// The page: HTML, CSS and hand-written JavaScript; `/*BISCARA_DATA*/` is replaced by the data,
/// `/*BISCARA_FRAMES*/` by the frames (base64 of little-endian `f32`s) and `/*BISCARA_THREE*/`
/// by the three.js bundle.
const TEMPLATE: &str = include_str!("viewer.html");
const DATA_MARKER: &str = "/*BISCARA_DATA*/";
const FRAMES_MARKER: &str = "/*BISCARA_FRAMES*/";
const THREE_MARKER: &str = "/*BISCARA_THREE*/";
/// three.js (and its OrbitControls), minified by `scripts/bundle-three.sh` (MIT licence beside it).
const THREE: &str = include_str!("../assets/three.min.js");
/// Numbers per frame: t (s), θ1, θ2, θ3 (degrees), d4 (mm), tool x, y, z (mm), c (degrees).
const FRAME_WIDTH: usize = 9;

/// Limits on what the page holds: at most about 51 MB however long the program (1 048 576
/// frames of 48 bytes as base64, and the bounded path, lines, events and work).
#[derive(Debug, Clone, PartialEq)]
pub struct ViewerOptions {
    /// Title shown at the top of the page.
    pub title: String,
    /// Most robot frames kept (each 48 bytes of the page); beyond it every other frame is
    /// dropped. The default keeps 1 048 576 (17 minutes at 1 ms) so the time slider reaches
    /// every sample.
    pub max_frames: usize,
    /// Most points of the programmed path kept.
    pub max_path_points: usize,
    /// Most program-line changes kept (for the G-code line shown while playing).
    pub max_line_changes: usize,
    /// Most pick/place events kept (and as many changes of the tool's work).
    pub max_events: usize,
    /// Most points of the tool's work kept (the burnt trace, the track, the strokes).
    pub max_process_points: usize,
}

impl Default for ViewerOptions {
    fn default() -> Self {
        ViewerOptions {
            title: "biscara view".to_owned(),
            max_frames: 1 << 20,
            max_path_points: 20_000,
            max_line_changes: 20_000,
            max_events: 5_000,
            max_process_points: crate::MAX_WORK_POINTS,
        }
    }
}

/// One robot frame: t, θ1, θ2, θ3, d4, and the tool pose x, y, z, c from forward kinematics
/// (s, degrees, mm). The page puts each elbow at its base plus `l1` along θ1 or θ2 and draws
/// the distal links from the elbows to the tool point, so every passive joint follows from FK.
type Frame = [f32; FRAME_WIDTH];

/// A pick or a place: time, kind, where.
#[derive(Debug, Clone, Copy)]
struct Event {
    t: f64,
    pick: bool,
    at: [f64; 3],
}

/// Gathers a joint trajectory, the programmed path and a scene, and writes the viewer page.
///
/// Push the trajectory's rows with [`Viewer::push_row`], optionally the program's Cartesian
/// samples with [`Viewer::push_path_sample`] (they give the programmed path, the pick/place events
/// and the program line at each moment) and the text of program lines with
/// [`Viewer::set_line_text`], then [`Viewer::write_html`]. Memory stays bounded: frames, path
/// points and line changes are decimated as they arrive.
#[derive(Debug)]
pub struct Viewer {
    robot: Robot,
    model: Kinematics,
    scene: Scene,
    options: ViewerOptions,
    frames: Decimator<Frame>,
    path: Decimator<[f64; 4]>,
    lines: Decimator<(f64, usize)>,
    current_line: Option<usize>,
    events: Vec<Event>,
    gripper: bool,
    line_text: BTreeMap<usize, String>,
    time_step: Option<f64>,
    previous_t: Option<f64>,
    /// The tool whose work is shown, and the work.
    tool: Option<ToolKind>,
    process: ToolWork,
    /// `check`'s problems (messages shortened to 200 characters).
    problems: Vec<ReportedProblem>,
    /// The objects' size (width x, length y, height z; mm), when given.
    object: Option<[f64; 3]>,
    /// The parts' meshes: the part and its triangles' corners in the part's frame (mm).
    meshes: Vec<(Part, Vec<f32>)>,
}

impl Viewer {
    /// A viewer of the robot `model` in `scene`.
    pub fn new(model: &RobotModel, scene: Scene, options: ViewerOptions) -> Viewer {
        Viewer {
            robot: model.robot().clone(),
            model: model.kinematics(),
            scene,
            frames: Decimator::new(options.max_frames),
            path: Decimator::new(options.max_path_points),
            lines: Decimator::new(options.max_line_changes),
            tool: None,
            process: ToolWork::new(options.max_process_points, options.max_events),
            options,
            current_line: None,
            events: Vec::new(),
            gripper: false,
            line_text: BTreeMap::new(),
            time_step: None,
            previous_t: None,
            problems: Vec::new(),
            object: None,
            meshes: Vec::new(),
        }
    }

    /// Draws `mesh` in place of the box or cylinder of `part`, placed in the part's frame by
    /// `spec` (scale, rotation, offset; the file is not read here). Fails for a part given twice,
    /// or when the meshes together would hold more than [`MAX_MESH_TRIANGLES`] triangles.
    pub fn add_mesh(
        &mut self,
        part: Part,
        spec: &MeshSpec,
        mesh: &StlMesh,
    ) -> Result<(), ViewError> {
        if self.meshes.iter().any(|(other, _)| *other == part) {
            return Err(ViewError::MeshTwice { part });
        }
        if self.mesh_triangles() + mesh.triangles() > MAX_MESH_TRIANGLES {
            return Err(ViewError::TooManyTriangles { max: MAX_MESH_TRIANGLES });
        }
        let m = spec.transform();
        let mut corners = Vec::with_capacity(mesh.positions().len());
        for corner in mesh.positions().chunks_exact(3) {
            let v = [0, 1, 2].map(|k| f64::from(corner[k]));
            for row in &m {
                corners.push((row[0] * v[0] + row[1] * v[1] + row[2] * v[2] + row[3]) as f32);
            }
        }
        self.meshes.push((part, corners));
        Ok(())
    }

    /// The triangles of the meshes added so far.
    pub fn mesh_triangles(&self) -> usize {
        self.meshes.iter().map(|(_, corners)| corners.len() / 9).sum()
    }

    /// The size of the objects picked (width along x, length along y, height; mm). Without it
    /// the page uses 1.6 × 1.6 gripper radii by 0.8 gripper lengths.
    pub fn set_object_size(&mut self, size: [f64; 3]) {
        self.object = Some(size);
    }

    /// Adds one of `check`'s problems (README.md's `check --json`, read by
    /// [`biscara_robot::Report::read_problems`]). The page marks it in the scene, where the tool
    /// is at that time, and on the timeline. At most `max_events` are kept.
    pub fn add_problem(&mut self, problem: &ReportedProblem) {
        if self.problems.len() < self.options.max_events {
            let message: String = problem.message.chars().take(200).collect();
            self.problems.push(ReportedProblem { message, ..problem.clone() });
        }
    }

    /// Adds one trajectory row; fails when its joints do not assemble.
    pub fn push_row(&mut self, row: &JointCsvRow) -> Result<(), ViewError> {
        let fk = self
            .model
            .forward(&row.joints)
            .map_err(|source| ViewError::Assembly { t: row.t, source })?;
        if self.time_step.is_none() {
            self.time_step = self.previous_t.map(|previous| row.t - previous);
        }
        self.previous_t = Some(row.t);
        let [t1, t2, t3, d4] = row.joints.to_degrees();
        let [x, y, z, c] = fk.pose.to_degrees();
        // f32: 0.1 µm at 1 m, 0.06 ms after 17 minutes.
        self.frames.push([row.t, t1, t2, t3, d4, x, y, z, c].map(|value| value as f32));
        Ok(())
    }

    /// The time step of the trajectory (the first two rows' difference), s.
    pub fn time_step(&self) -> Option<f64> {
        self.time_step
    }

    /// The time of the last row pushed, s.
    pub fn duration(&self) -> Option<f64> {
        self.previous_t
    }

    /// Adds one sample of the programmed path: time (s), pose `[x, y, z, c]` (mm, degrees), the
    /// program line it belongs to and whether the gripper is closed.
    pub fn push_path_sample(&mut self, t: f64, pose: [f64; 4], line: usize, gripper: bool) {
        self.path.push(pose);
        if self.current_line != Some(line) {
            self.current_line = Some(line);
            self.lines.push((t, line));
        }
        if gripper != self.gripper && self.events.len() < self.options.max_events {
            self.events.push(Event { t, pick: gripper, at: [pose[0], pose[1], pose[2]] });
        }
        self.gripper = gripper;
    }

    /// A [`ProgramOverlay`] of `tool`'s work within this page's bounds, sampled up to a second
    /// past the trajectory's last row: push the program's samples into it, then
    /// [`Viewer::set_overlay`].
    pub fn overlay(&self, tool: ToolKind) -> ProgramOverlay {
        let options = &self.options;
        ProgramOverlay::new(tool, options.max_process_points, options.max_events, self.duration())
    }

    /// Shows the tool's work of `overlay` (docs/motion.md: for a laser, an extruder, a pen, a
    /// spindle; the gripper leaves none): the burnt trace, the deposited track layer by layer,
    /// the pen's strokes, the cuts, apart from travel.
    pub fn set_overlay(&mut self, overlay: ProgramOverlay) {
        self.tool = Some(overlay.tool()).filter(|&tool| tool != ToolKind::Gripper);
        self.process = overlay.work().clone();
    }

    /// The program lines the page refers to (those of the kept line changes), ascending.
    pub fn referenced_lines(&self) -> Vec<usize> {
        let mut lines: Vec<usize> =
            self.lines.items().map(|&(_, line)| line).filter(|&line| line > 0).collect();
        lines.sort_unstable();
        lines.dedup();
        lines
    }

    /// The text of one program line (shortened to 100 characters on the page).
    pub fn set_line_text(&mut self, line: usize, text: &str) {
        let text: String = text.trim_end().chars().take(100).collect();
        self.line_text.insert(line, text);
    }

    /// Reads the program's text and keeps the lines the page refers to
    /// ([`Viewer::referenced_lines`]); stops reading after the last of them.
    pub fn read_line_texts(&mut self, program: impl BufRead) -> std::io::Result<()> {
        let mut wanted = self.referenced_lines().into_iter().peekable();
        for (index, line) in program.lines().enumerate() {
            let Some(&next) = wanted.peek() else { break };
            if index + 1 == next {
                self.set_line_text(next, &line?);
                wanted.next();
            }
        }
        Ok(())
    }

    /// Writes the page: one HTML file with the data and the JavaScript inside.
    pub fn write_html(&self, out: &mut dyn Write) -> Result<(), ViewError> {
        if self.frames.seen == 0 {
            return Err(ViewError::EmptyTrajectory);
        }
        let data = self.data_json();
        let (head, rest) = TEMPLATE.split_once(THREE_MARKER).unwrap_or((TEMPLATE, ""));
        let (middle, rest) = rest.split_once(DATA_MARKER).unwrap_or((rest, ""));
        let (between, tail) = rest.split_once(FRAMES_MARKER).unwrap_or((rest, ""));
        out.write_all(head.as_bytes())?;
        out.write_all(THREE.as_bytes())?;
        out.write_all(middle.as_bytes())?;
        out.write_all(data.as_bytes())?;
        out.write_all(between.as_bytes())?;
        let mut bytes = Vec::with_capacity(3 * 4096);
        let mut text = Vec::with_capacity(4 * 4096 + 4);
        for frame in self.frames.items() {
            bytes.extend(frame.iter().flat_map(|value| value.to_le_bytes()));
            if bytes.len() >= 3 * 4096 {
                let whole = bytes.len() / 3 * 3;
                base64(&bytes[..whole], &mut text);
                out.write_all(&text)?;
                text.clear();
                bytes.drain(..whole);
            }
        }
        base64(&bytes, &mut text);
        out.write_all(&text)?;
        out.write_all(tail.as_bytes())?;
        Ok(())
    }

    /// The page's data as one JSON object (numbers with fixed decimals, `<` and `>` escaped so
    /// the text cannot close the script element).
    fn data_json(&self) -> String {
        let robot = &self.robot;
        let bases = self.model.bases();
        let limits = robot.joint_limits.to_array().map(|limit| limit.map(Num::<15>));
        let flat = |values: &mut dyn Iterator<Item = f64>| values.map(Num::<4>).collect();
        let data = PageData {
            title: &self.options.title,
            robot: RobotData {
                name: &robot.name,
                l1: Num(robot.links.l1),
                l2: Num(robot.links.l2),
                bases: bases.map(|base| [Num(base.x), Num(base.y)]),
                lp: Num(robot.lp),
                link_width: Num(robot.geometry.link_width),
                link_height: Num(robot.geometry.link_height),
                gripper_radius: Num(robot.geometry.gripper_radius),
                gripper_length: Num(robot.geometry.gripper_length),
                limits,
            },
            frames: FramesData {
                count: self.frames.items().count(),
                width: FRAME_WIDTH,
                stride: self.frames.stride,
                rows: self.frames.seen,
                dt: Num(self.time_step.unwrap_or(0.0)),
            },
            path: self.path.items().flat_map(|p| [p[0], p[1], p[2]]).map(Num::<2>).collect(),
            lines: flat(&mut self.lines.items().flat_map(|&(t, line)| [t, line as f64])),
            line_text: &self.line_text,
            events: self
                .events
                .iter()
                .map(|e| (Num(e.t), u8::from(e.pick), e.at.map(Num::<2>)))
                .map(|(t, pick, [x, y, z])| (t, pick, x, y, z))
                .collect(),
            tool: self.tool.map(|tool| ToolData { kind: tool.name(), label: tool.legend() }),
            process: flat(&mut self.process.points().flat_map(|p| {
                [p.t, p.at[0], p.at[1], p.at[2], p.strength, f64::from(u8::from(p.start))]
            })),
            work: flat(&mut self.process.changes().iter().flat_map(|&(t, s)| [t, s])),
            problems: self
                .problems
                .iter()
                .map(|problem| (Num(problem.t), problem.kind.name(), problem.message.as_str()))
                .collect(),
            object: self.object.map(|size| size.map(Num::<15>)),
            meshes: self
                .meshes
                .iter()
                .map(|(part, corners)| {
                    let bytes: Vec<u8> = corners.iter().flat_map(|v| v.to_le_bytes()).collect();
                    let mut text = Vec::with_capacity(bytes.len() / 3 * 4 + 4);
                    base64(&bytes, &mut text);
                    let data = String::from_utf8_lossy(&text).into_owned();
                    MeshData { part: part.name(), triangles: corners.len() / 9, data }
                })
                .collect(),
            scene: self
                .scene
                .boxes
                .iter()
                .map(|b| SceneData { name: &b.name, min: b.min.map(Num), max: b.max.map(Num) })
                .collect(),
        };
        let json = serde_json::to_string(&data).unwrap_or_default();
        json.replace('<', "\\u003c").replace('>', "\\u003e")
    }
}

/// A number of the page: rounded to `D` decimals, written without trailing zeros (an integer
/// without a decimal point) and never as `-0`. `Num<15>` keeps a robot file's numbers as given.
#[derive(Debug, Clone, Copy)]
struct Num<const D: usize>(f64);

impl<const D: usize> serde::Serialize for Num<D> {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let value = if D >= 15 { self.0 + 0.0 } else { round_to(self.0, D) };
        if value == value.trunc() && value.abs() < 1e15 {
            serializer.serialize_i64(value as i64)
        } else {
            serializer.serialize_f64(value)
        }
    }
}

/// The page's data (`D` in viewer.html).
#[derive(serde::Serialize)]
struct PageData<'a> {
    title: &'a str,
    robot: RobotData<'a>,
    frames: FramesData,
    /// x, y, z of each kept point, in a row.
    path: Vec<Num<2>>,
    /// t, line of each kept line change, in a row.
    lines: Vec<Num<4>>,
    line_text: &'a BTreeMap<usize, String>,
    /// t, pick (1) or place (0), x, y, z.
    events: Vec<(Num<4>, u8, Num<2>, Num<2>, Num<2>)>,
    tool: Option<ToolData>,
    /// t, x, y, z, strength, start of each point of the tool's work, in a row.
    process: Vec<Num<4>>,
    /// t, strength (−1: stops) of each change of the tool's work, in a row.
    work: Vec<Num<4>>,
    /// t, kind, message of each of `check`'s problems.
    problems: Vec<(Num<4>, &'static str, &'a str)>,
    object: Option<[Num<15>; 3]>,
    meshes: Vec<MeshData>,
    scene: Vec<SceneData<'a>>,
}

/// The robot's sizes the page draws (mm) and its joint limits (degrees, mm).
#[derive(serde::Serialize)]
struct RobotData<'a> {
    name: &'a str,
    l1: Num<15>,
    l2: Num<15>,
    bases: [[Num<15>; 2]; 2],
    lp: Num<15>,
    link_width: Num<15>,
    link_height: Num<15>,
    gripper_radius: Num<15>,
    gripper_length: Num<15>,
    limits: [[Num<15>; 2]; 4],
}

/// How the frames (base64 after the data) are laid out.
#[derive(serde::Serialize)]
struct FramesData {
    count: usize,
    width: usize,
    stride: usize,
    rows: usize,
    dt: Num<15>,
}

/// The tool whose work is shown.
#[derive(serde::Serialize)]
struct ToolData {
    kind: &'static str,
    label: &'static str,
}

/// One part's mesh: its triangles' corners as base64 of little-endian `f32`s.
#[derive(serde::Serialize)]
struct MeshData {
    part: &'static str,
    triangles: usize,
    data: String,
}

/// One box of the scene (mm).
#[derive(serde::Serialize)]
struct SceneData<'a> {
    name: &'a str,
    min: [Num<15>; 3],
    max: [Num<15>; 3],
}

/// Appends the base64 text of `bytes` (standard alphabet, `=` padding) to `text`.
fn base64(bytes: &[u8], text: &mut Vec<u8>) {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    for chunk in bytes.chunks(3) {
        let b = [chunk[0], *chunk.get(1).unwrap_or(&0), *chunk.get(2).unwrap_or(&0)];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                text.push(ALPHABET[((n >> (18 - 6 * k)) & 63) as usize]);
            } else {
                text.push(b'=');
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use biscara_kinematics::Joints;

    use super::*;

    fn row(t: f64, theta1_deg: f64) -> JointCsvRow {
        JointCsvRow {
            t,
            line: 2,
            joints: Joints::from_degrees(theta1_deg, 0.0, 0.0, 10.0),
            velocity: None,
        }
    }

    #[test]
    fn the_page_holds_frames_path_events_and_no_raw_angle_brackets_in_data() {
        let mut viewer = Viewer::new(
            &RobotModel::default(),
            Scene {
                boxes: vec![crate::SceneBox {
                    name: "</script>".to_owned(),
                    min: [0.0; 3],
                    max: [1.0; 3],
                }],
            },
            ViewerOptions::default(),
        );
        for step in 0..5 {
            viewer.push_row(&row(f64::from(step) * 0.5, f64::from(step))).unwrap();
            viewer.push_path_sample(f64::from(step) * 0.5, [0.0, 400.0, 50.0, 0.0], 7, step >= 2);
        }
        viewer.set_line_text(7, "G1 Z10 (pick)");
        viewer.add_problem(&ReportedProblem {
            t: 1.5,
            kind: biscara_robot::ProblemKind::SceneCollision,
            message: "the tool hits <pallet>".to_owned(),
        });
        assert_eq!(viewer.referenced_lines(), [7]);
        assert_eq!(viewer.time_step(), Some(0.5));
        let mut page = Vec::new();
        viewer.write_html(&mut page).unwrap();
        let page = String::from_utf8(page).unwrap();
        assert!(page.starts_with("<!DOCTYPE html>"));
        assert!(!page.contains(DATA_MARKER));
        assert!(page.contains("\"frames\":{\"count\":5,\"width\":9,"), "frames");
        let (_, frames) = page.split_once("id=\"frames\">").unwrap();
        let frames = frames.split_once('<').unwrap().0;
        assert_eq!(frames.len(), (5 * 9 * 4usize).div_ceil(3) * 4, "base64 of 45 f32");
        // The first frame's t = 0 and θ1 = 0: eight zero bytes, "AAAAAAAAAAA".
        assert!(frames.starts_with("AAAAAAAAAAA"), "{}", &frames[..20]);
        assert!(page.contains("\"events\":[[1,1,0,400,50]]"));
        assert!(page.contains("\"7\":\"G1 Z10 (pick)\""));
        assert!(page.contains(
            "\"problems\":[[1.5,\"scene_collision\",\"the tool hits \\u003cpallet\\u003e\"]]"
        ));
        assert_eq!(page.matches("</script>").count(), 4, "the scene name must not end a script");
        // The only address is the XHTML namespace three.js names (never fetched).
        let addresses = page.replace("http://www.w3.org/1999/xhtml", "");
        assert!(!addresses.contains("http://") && !addresses.contains("https://"), "no network");
    }

    #[test]
    fn meshes_are_placed_in_their_parts_frame_and_refused_when_unknown_twice_or_too_big() {
        let ascii = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 0.001 0 0\n\
                     vertex 0 0.002 0\nendloop\nendfacet\nendsolid t\n";
        let mesh = crate::read_stl(ascii.as_bytes(), 10).unwrap();
        let mut viewer =
            Viewer::new(&RobotModel::default(), Scene::default(), ViewerOptions::default());
        let spec = MeshSpec {
            scale: 1000.0,
            offset: [5.0, 0.0, 1.0],
            rotation: [0.0, 0.0, 90.0],
            ..MeshSpec::new("t.stl")
        };
        viewer.add_mesh(Part::Distal2, &spec, &mesh).unwrap();
        let corners = &viewer.meshes[0].1;
        // (1, 0, 0) mm turned to (0, 1, 0), (0, 2, 0) to (-2, 0, 0), then moved by the offset.
        let expected = [5.0, 0.0, 1.0, 5.0, 1.0, 1.0, 3.0, 0.0, 1.0];
        assert!(corners.iter().zip(expected).all(|(a, b)| (a - b).abs() < 1e-5), "{corners:?}");
        assert_eq!(viewer.mesh_triangles(), 1);
        let err = viewer.add_mesh(Part::Distal2, &spec, &mesh).unwrap_err();
        assert!(matches!(err, ViewError::MeshTwice { part: Part::Distal2 }), "{err}");
        assert_eq!(err.to_string(), "part `distal2` has a mesh already");
        let big = StlMesh::from_positions(vec![0.0; 9 * MAX_MESH_TRIANGLES]);
        let err = viewer.add_mesh(Part::Tool, &spec, &big).unwrap_err();
        assert!(matches!(err, ViewError::TooManyTriangles { max: MAX_MESH_TRIANGLES }), "{err}");
        assert!(err.to_string().contains("more than 200000 triangles"), "{err}");
        viewer.push_row(&row(0.0, 0.0)).unwrap();
        let mut page = Vec::new();
        viewer.write_html(&mut page).unwrap();
        let page = String::from_utf8(page).unwrap();
        assert!(page.contains("\"meshes\":[{\"part\":\"distal2\",\"triangles\":1,\"data\":\""));
    }

    #[test]
    fn base64_matches_the_standard_alphabet_and_padding() {
        for (bytes, expected) in [
            (&b""[..], ""),
            (b"f", "Zg=="),
            (b"fo", "Zm8="),
            (b"foo", "Zm9v"),
            (b"foob", "Zm9vYg=="),
        ] {
            let mut text = Vec::new();
            base64(bytes, &mut text);
            assert_eq!(String::from_utf8(text).unwrap(), expected);
        }
    }

    #[test]
    fn an_hour_stays_small() {
        // An hour at 10 ms with room for 40 000 frames: the page has reached its bound.
        let options = ViewerOptions { max_frames: 40_000, ..ViewerOptions::default() };
        let mut viewer = Viewer::new(&RobotModel::default(), Scene::default(), options);
        let rows = 360_000;
        for step in 0..rows {
            let t = f64::from(step) * 0.01;
            let angle = 30.0 * (t * 0.7).sin();
            viewer.push_row(&row(t, angle)).unwrap();
            let line = 10 + usize::try_from(step / 50).unwrap();
            viewer.push_path_sample(t, [angle, 400.0, 50.0, 0.0], line, step % 400 < 200);
        }
        let mut page = Vec::new();
        viewer.write_html(&mut page).unwrap();
        assert!(viewer.frames.stride >= 8 && viewer.frames.kept.len() <= 40_000);
        assert!(page.len() < 10_000_000, "{} bytes", page.len());
    }
}
