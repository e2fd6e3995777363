//! Pictures (docs/virtual-robot.md): the workspace, the programmed path and the robot in top view,
//! and the joint curves against time, as SVG or PNG, drawn with plotters.
//!
//! PNG text is rendered with DejaVu Sans embedded in the library (plotters' `ab_glyph`
//! backend), so pictures come out the same on machines without system fonts.

use std::sync::Once;

use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::FontStyle;

use biscara_robot::{Body, Rectangle as WorkspaceRectangle, Scene, Workspace};

use crate::{ToolWork, ViewError, WorkPoint};

/// DejaVu Sans (Bitstream Vera licence, see `fonts/DejaVuSans-LICENSE.txt`).
static FONT: &[u8] = include_bytes!("../fonts/DejaVuSans.ttf");
static REGISTER_FONT: Once = Once::new();

const FAMILY: &str = "sans-serif";

fn register_font() {
    REGISTER_FONT.call_once(|| {
        // The embedded font is valid; a failure would only leave PNG text out.
        let _ = plotters::style::register_font(FAMILY, FontStyle::Normal, FONT);
    });
}

/// The file format of a picture.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ImageFormat {
    /// Scalable vector graphics (text).
    Svg,
    /// Portable network graphics (RGB, 8 bits).
    Png,
}

/// What the top view shows. Every part is optional.
#[derive(Debug, Clone, Copy)]
pub struct TopView<'a> {
    /// A title above the picture.
    pub title: &'a str,
    /// The workspace grid, drawn as a filled region.
    pub workspace: Option<&'a Workspace>,
    /// The largest rectangle, outlined.
    pub rectangle: Option<&'a WorkspaceRectangle>,
    /// The programmed path in XY, millimetres (a polyline).
    pub path: &'a [[f64; 2]],
    /// What the tool did (docs/motion.md): the laser's burnt trace, the extruded track, the pen's
    /// strokes, the cut; drawn over the path, which then shows the travel. `None` or empty for
    /// the gripper.
    pub process: Option<&'a ToolWork>,
    /// The legend of the process strokes (`laser: burnt trace, darker for more power`).
    pub process_label: &'a str,
    /// The robot at chosen times: `(t, body)`.
    pub bodies: &'a [(f64, Body)],
    /// The scene's boxes, drawn as footprints.
    pub scene: Option<&'a Scene>,
    /// The region drawn, `((x_min, x_max), (y_min, y_max))` in millimetres; `None`: everything
    /// (workspace, path, robot, scene) with a margin.
    pub region: Option<((f64, f64), (f64, f64))>,
}

/// The region a zoomed picture shows, `((x_min, x_max), (y_min, y_max))`: the tool's `work`,
/// else the `path` but its first and last points (the travel from and back to the home pose),
/// with a margin of a tenth (at least 5 mm); `None` when there is nothing to show.
pub fn zoom_region(work: &ToolWork, path: &[[f64; 2]]) -> Option<((f64, f64), (f64, f64))> {
    let points: Vec<[f64; 2]> = if work.is_empty() {
        path.get(1..path.len().saturating_sub(1)).unwrap_or_default().to_vec()
    } else {
        work.points().map(|point| [point.at[0], point.at[1]]).collect()
    };
    let mut min = [f64::INFINITY; 2];
    let mut max = [f64::NEG_INFINITY; 2];
    for point in &points {
        for axis in 0..2 {
            min[axis] = min[axis].min(point[axis]);
            max[axis] = max[axis].max(point[axis]);
        }
    }
    if !min[0].is_finite() {
        return None;
    }
    let margin = (0.1 * (max[0] - min[0]).max(max[1] - min[1])).max(5.0);
    Some(((min[0] - margin, max[0] + margin), (min[1] - margin, max[1] + margin)))
}

/// The colour of a process stroke of `strength` (0 … 1): light brown to near black.
fn process_colour(strength: f64) -> RGBColor {
    let s = strength.clamp(0.0, 1.0);
    let lerp = |light: f64, dark: f64| (light + (dark - light) * s).round() as u8;
    RGBColor(lerp(225.0, 30.0), lerp(190.0, 15.0), lerp(140.0, 5.0))
}

/// The joint curves: positions in user units (degrees for θ, millimetres for d4) against time.
#[derive(Debug, Clone, Copy)]
pub struct JointCurves<'a> {
    /// A title above the picture.
    pub title: &'a str,
    /// Times, s.
    pub t: &'a [f64],
    /// `[theta1, theta2, theta3, d4]` at each time: degrees and millimetres.
    pub q: &'a [[f64; 4]],
    /// The joint limits, `[min, max]` per joint, same units.
    pub limits: [[f64; 2]; 4],
}

fn plot_error(err: impl std::fmt::Display) -> ViewError {
    ViewError::Plot { message: err.to_string() }
}

macro_rules! render_with {
    ($size:expr, $format:expr, $draw:ident, $($arg:expr),*) => {{
        register_font();
        let (width, height) = $size;
        match $format {
            ImageFormat::Svg => {
                let mut text = String::new();
                {
                    let root = SVGBackend::with_string(&mut text, (width, height)).into_drawing_area();
                    $draw(&root, $($arg),*).map_err(plot_error)?;
                    root.present().map_err(plot_error)?;
                }
                Ok(text.into_bytes())
            }
            ImageFormat::Png => {
                let mut pixels = vec![0u8; width as usize * height as usize * 3];
                {
                    let root =
                        BitMapBackend::with_buffer(&mut pixels, (width, height)).into_drawing_area();
                    $draw(&root, $($arg),*).map_err(plot_error)?;
                    root.present().map_err(plot_error)?;
                }
                encode_png(&pixels, width, height)
            }
        }
    }};
}

pub(crate) use render_with;

mod atlas;
pub use atlas::{ATLAS_MAX_PANELS, Atlas, AtlasCell, draw_atlas};
mod torques;
pub use torques::{TorqueCurves, draw_torques};

fn encode_png(pixels: &[u8], width: u32, height: u32) -> Result<Vec<u8>, ViewError> {
    let mut bytes = Vec::new();
    {
        let mut encoder = png::Encoder::new(&mut bytes, width, height);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        let mut writer = encoder.write_header().map_err(plot_error)?;
        writer.write_image_data(pixels).map_err(plot_error)?;
        writer.finish().map_err(plot_error)?;
    }
    Ok(bytes)
}

/// Colours of the robots drawn at successive times.
const ROBOT_COLOURS: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
];
const WORKSPACE_FILL: RGBColor = RGBColor(205, 225, 245);
const RECTANGLE_COLOUR: RGBColor = RGBColor(0, 110, 60);
const PATH_COLOUR: RGBColor = RGBColor(200, 30, 30);
const SCENE_FILL: RGBColor = RGBColor(170, 170, 170);

/// The top view as SVG or PNG bytes.
pub fn draw_top_view(view: &TopView<'_>, format: ImageFormat) -> Result<Vec<u8>, ViewError> {
    let (x_range, y_range) = top_view_extent(view);
    let width = 1000u32;
    let plot_height = (f64::from(width - 90) * (y_range.1 - y_range.0) / (x_range.1 - x_range.0))
        .clamp(200.0, 2000.0);
    let height = plot_height as u32 + 110;
    render_with!((width, height), format, top_view_on, view, x_range, y_range)
}

fn top_view_extent(view: &TopView<'_>) -> ((f64, f64), (f64, f64)) {
    if let Some(region) = view.region {
        return region;
    }
    let mut min = [f64::INFINITY; 2];
    let mut max = [f64::NEG_INFINITY; 2];
    let mut include = |p: [f64; 2]| {
        for axis in 0..2 {
            min[axis] = min[axis].min(p[axis]);
            max[axis] = max[axis].max(p[axis]);
        }
    };
    if let Some(workspace) = view.workspace {
        let (columns, rows) = workspace.size();
        for j in 0..rows {
            for (first, last) in workspace.runs(j) {
                include(workspace.point(first, j));
                include(workspace.point(last, j));
            }
        }
        let _ = columns;
    }
    for &point in view.path {
        include(point);
    }
    for (_, body) in view.bodies {
        let c = &body.configuration;
        for p in c.bases.iter().chain(&c.elbows).chain(std::iter::once(&c.platform)) {
            include([p.x, p.y]);
        }
    }
    if let Some(scene) = view.scene {
        for b in &scene.boxes {
            include([b.min[0], b.min[1]]);
            include([b.max[0], b.max[1]]);
        }
    }
    if !min[0].is_finite() {
        return ((-500.0, 500.0), (-100.0, 500.0));
    }
    // Always show the base joints' line.
    min[1] = min[1].min(-20.0);
    let margin = 0.05 * (max[0] - min[0]).max(max[1] - min[1]).max(100.0);
    ((min[0] - margin, max[0] + margin), (min[1] - margin, max[1] + margin))
}

/// The top view's chart: x and y in millimetres.
type TopChart<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

fn top_view_on<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    view: &TopView<'_>,
    x_range: (f64, f64),
    y_range: (f64, f64),
) -> Result<(), String> {
    let e = |err: DrawingAreaErrorKind<DB::ErrorType>| err.to_string();
    root.fill(&WHITE).map_err(e)?;
    let mut chart = ChartBuilder::on(root)
        .caption(view.title, (FAMILY, 22))
        .margin(15)
        .x_label_area_size(40)
        .y_label_area_size(55)
        .build_cartesian_2d(x_range.0..x_range.1, y_range.0..y_range.1)
        .map_err(e)?;
    chart
        .configure_mesh()
        .x_desc("x (mm)")
        .y_desc("y (mm)")
        .label_style((FAMILY, 14))
        .light_line_style(WHITE.mix(0.0))
        .bold_line_style(BLACK.mix(0.08))
        .draw()
        .map_err(e)?;
    if let Some(workspace) = view.workspace {
        workspace_layer(&mut chart, workspace)?;
    }
    if let Some(scene) = view.scene {
        scene_layer(&mut chart, scene)?;
    }
    if let Some(rectangle) = view.rectangle {
        rectangle_layer(&mut chart, rectangle)?;
    }
    path_and_work_layers(&mut chart, view)?;
    bodies_layer(&mut chart, view.bodies)?;
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK.mix(0.3))
        .label_font((FAMILY, 13))
        .draw()
        .map_err(e)?;
    Ok(())
}

/// The reachable region, filled, run by run of each grid row.
fn workspace_layer<DB: DrawingBackend>(
    chart: &mut TopChart<'_, DB>,
    workspace: &Workspace,
) -> Result<(), String> {
    let e = |err: DrawingAreaErrorKind<DB::ErrorType>| err.to_string();
    let half = 0.5 * workspace.step();
    let (_, rows) = workspace.size();
    let mut cells = Vec::new();
    for j in 0..rows {
        for (first, last) in workspace.runs(j) {
            let [x0, y] = workspace.point(first, j);
            let [x1, _] = workspace.point(last, j);
            cells.push(Rectangle::new(
                [(x0 - half, y - half), (x1 + half, y + half)],
                WORKSPACE_FILL.filled(),
            ));
        }
    }
    chart
        .draw_series(cells)
        .map_err(e)?
        .label(format!("reachable ({:.0} mm²)", workspace.area_mm2()))
        .legend(|(x, y)| Rectangle::new([(x, y - 6), (x + 16, y + 6)], WORKSPACE_FILL.filled()));
    Ok(())
}

/// The scene's boxes as footprints, with their names.
fn scene_layer<DB: DrawingBackend>(
    chart: &mut TopChart<'_, DB>,
    scene: &Scene,
) -> Result<(), String> {
    let e = |err: DrawingAreaErrorKind<DB::ErrorType>| err.to_string();
    let boxes = scene.boxes.iter().map(|b| {
        Rectangle::new([(b.min[0], b.min[1]), (b.max[0], b.max[1])], SCENE_FILL.mix(0.7).filled())
    });
    chart.draw_series(boxes).map_err(e)?;
    let names = scene.boxes.iter().map(|b| {
        Text::new(b.name.clone(), (b.min[0], b.max[1]), (FAMILY, 13).into_font().color(&BLACK))
    });
    chart.draw_series(names).map_err(e)?;
    Ok(())
}

/// The largest rectangle, outlined, its size and place in the legend.
fn rectangle_layer<DB: DrawingBackend>(
    chart: &mut TopChart<'_, DB>,
    r: &WorkspaceRectangle,
) -> Result<(), String> {
    let e = |err: DrawingAreaErrorKind<DB::ErrorType>| err.to_string();
    let corners = [
        (r.min[0], r.min[1]),
        (r.max[0], r.min[1]),
        (r.max[0], r.max[1]),
        (r.min[0], r.max[1]),
        (r.min[0], r.min[1]),
    ];
    chart
        .draw_series(LineSeries::new(corners, RECTANGLE_COLOUR.stroke_width(2)))
        .map_err(e)?
        .label(format!(
            "largest rectangle {:.0} x {:.0} mm, x {:.0}..{:.0}, y {:.0}..{:.0}",
            r.width(),
            r.height(),
            r.min[0],
            r.max[0],
            r.min[1],
            r.max[1]
        ))
        .legend(|(x, y)| PathElement::new([(x, y), (x + 16, y)], RECTANGLE_COLOUR.stroke_width(2)));
    Ok(())
}

/// The programmed path and, over it, the tool's work.
fn path_and_work_layers<DB: DrawingBackend>(
    chart: &mut TopChart<'_, DB>,
    view: &TopView<'_>,
) -> Result<(), String> {
    let e = |err: DrawingAreaErrorKind<DB::ErrorType>| err.to_string();
    let work = view.process.filter(|work| !work.is_empty());
    if !view.path.is_empty() {
        // With the tool's work drawn over it, the path shows the travel: thin.
        let (width, label) = if work.is_none() { (2, "programmed path") } else { (1, "travel") };
        chart
            .draw_series(LineSeries::new(
                view.path.iter().map(|p| (p[0], p[1])),
                PATH_COLOUR.stroke_width(width),
            ))
            .map_err(e)?
            .label(label)
            .legend(move |(x, y)| {
                PathElement::new([(x, y), (x + 16, y)], PATH_COLOUR.stroke_width(width))
            });
    }
    if let Some(work) = work {
        // A segment from each point to the next of its stroke, unless it is vertical (a
        // plunge, a point in top view).
        let points: Vec<&WorkPoint> = work.points().collect();
        let drawn = |pair: &&[&WorkPoint]| !pair[1].start && pair[0].at[..2] != pair[1].at[..2];
        let segments = points.windows(2).filter(drawn).map(|pair| {
            let [from, to] = [pair[0].at, pair[1].at];
            PathElement::new(
                [(from[0], from[1]), (to[0], to[1])],
                process_colour(pair[0].strength).stroke_width(3),
            )
        });
        chart.draw_series(segments).map_err(e)?.label(view.process_label).legend(|(x, y)| {
            PathElement::new([(x, y), (x + 16, y)], process_colour(1.0).stroke_width(3))
        });
    }
    Ok(())
}

/// The robot at each wanted time: links, joints, base joints, the gripper with a tick for c.
fn bodies_layer<DB: DrawingBackend>(
    chart: &mut TopChart<'_, DB>,
    bodies: &[(f64, Body)],
) -> Result<(), String> {
    let e = |err: DrawingAreaErrorKind<DB::ErrorType>| err.to_string();
    for (index, (t, body)) in bodies.iter().enumerate() {
        let colour = ROBOT_COLOURS[index % ROBOT_COLOURS.len()];
        let width_px = 5;
        for link in body.links() {
            chart
                .draw_series(LineSeries::new(
                    [(link.start.x, link.start.y), (link.end.x, link.end.y)],
                    colour.mix(0.85).stroke_width(width_px),
                ))
                .map_err(e)?;
        }
        let c = &body.configuration;
        let joints = c.elbows.iter().chain(std::iter::once(&c.platform));
        chart.draw_series(joints.map(|p| Circle::new((p.x, p.y), 4, BLACK.filled()))).map_err(e)?;
        chart
            .draw_series(c.bases.iter().map(|p| {
                Rectangle::new([(p.x - 10.0, p.y - 10.0), (p.x + 10.0, p.y + 10.0)], BLACK.filled())
            }))
            .map_err(e)?;
        // The gripper, with a tick showing c.
        let gripper = body.gripper();
        let tip = (
            c.platform.x + gripper.radius * body.phi.cos(),
            c.platform.y + gripper.radius * body.phi.sin(),
        );
        chart
            .draw_series(std::iter::once(PathElement::new(
                [(c.platform.x, c.platform.y), tip],
                BLACK.stroke_width(2),
            )))
            .map_err(e)?;
        chart
            .draw_series(std::iter::once(Text::new(
                format!("t = {t} s"),
                (c.platform.x + 12.0, c.platform.y + 12.0),
                (FAMILY, 14).into_font().color(&colour),
            )))
            .map_err(e)?
            .label(format!("robot at t = {t} s"))
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 16, y)], colour.stroke_width(4)));
    }
    Ok(())
}

/// The joint curves as SVG or PNG bytes: four panels, θ1, θ2, θ3 (degrees) and d4 (mm) against
/// time, with their limits as dashed lines.
pub fn draw_joints(curves: &JointCurves<'_>, format: ImageFormat) -> Result<Vec<u8>, ViewError> {
    render_with!((1000, 900), format, joints_on, curves)
}

fn joints_on<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    curves: &JointCurves<'_>,
) -> Result<(), String> {
    let names = ["θ1 (°)", "θ2 (°)", "θ3 (°)", "d4 (mm)"];
    let panels = std::array::from_fn(|j| {
        let [low, high] = curves.limits[j];
        TimePanel {
            name: names[j],
            shows: (low, high),
            min_span: 1.0,
            levels: vec![(low, RED), (high, RED)],
        }
    });
    time_panels(root, (curves.title, 22), curves.t, curves.q, panels)
}

/// One of the four panels of [`time_panels`].
struct TimePanel<'a> {
    /// The value axis' name, with its unit.
    name: &'a str,
    /// The range `(min, max)` the value axis shows whatever the curve (the limits).
    shows: (f64, f64),
    /// The smallest span of the value axis, padded by 8 % of its span above and below.
    min_span: f64,
    /// Dashed lines across the panel, `(value, colour)`, drawn in order under the curve.
    levels: Vec<(f64, RGBColor)>,
}

/// Four panels of a quantity per joint against time, one above the other under `title` (its
/// text and size): each its value axis, dashed levels and the curve of `values[k][j]` at `t[k]`;
/// the time axis, from 0 to the last time, named on the last.
fn time_panels<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    (title, title_size): (&str, u32),
    t: &[f64],
    values: &[[f64; 4]],
    panels: [TimePanel<'_>; 4],
) -> Result<(), String> {
    let e = |err: DrawingAreaErrorKind<DB::ErrorType>| err.to_string();
    root.fill(&WHITE).map_err(e)?;
    let root = root.titled(title, (FAMILY, title_size)).map_err(e)?;
    let areas = root.split_evenly((4, 1));
    let t_end = t.last().copied().unwrap_or(1.0).max(1e-3);
    for (j, (area, panel)) in areas.iter().zip(panels).enumerate() {
        let (mut min, mut max) = panel.shows;
        for value in values {
            min = min.min(value[j]);
            max = max.max(value[j]);
        }
        let pad = 0.08 * (max - min).max(panel.min_span);
        let mut chart = ChartBuilder::on(area)
            .margin(8)
            .x_label_area_size(if j == 3 { 35 } else { 20 })
            .y_label_area_size(60)
            .build_cartesian_2d(0.0..t_end, (min - pad)..(max + pad))
            .map_err(e)?;
        let mut mesh = chart.configure_mesh();
        mesh.y_desc(panel.name).label_style((FAMILY, 13)).light_line_style(WHITE.mix(0.0));
        if j == 3 {
            mesh.x_desc("t (s)");
        }
        mesh.draw().map_err(e)?;
        for (level, colour) in panel.levels {
            chart
                .draw_series(DashedLineSeries::new(
                    [(0.0, level), (t_end, level)],
                    8,
                    5,
                    colour.stroke_width(2),
                ))
                .map_err(e)?;
        }
        chart
            .draw_series(LineSeries::new(
                t.iter().zip(values).map(|(&t, value)| (t, value[j])),
                ROBOT_COLOURS[0].stroke_width(2),
            ))
            .map_err(e)?;
    }
    Ok(())
}

/// The workspace and its rectangle, with the robot at home: the paper's Fig. 5.
pub fn draw_workspace(
    workspace: &Workspace,
    rectangle: &WorkspaceRectangle,
    home: Option<&Body>,
    title: &str,
    format: ImageFormat,
) -> Result<Vec<u8>, ViewError> {
    let bodies: Vec<(f64, Body)> = home.map(|body| (0.0, *body)).into_iter().collect();
    let view = TopView {
        process: None,
        process_label: "",
        region: None,
        title,
        workspace: Some(workspace),
        rectangle: Some(rectangle),
        path: &[],
        bodies: &bodies,
        scene: None,
    };
    draw_top_view(&view, format)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_zoom_region_holds_the_work_with_a_margin() {
        let mut work = ToolWork::new(100, 10);
        work.push(0.0, [0.0, 0.0, 0.0, 0.0], 1, Some(1.0));
        work.push(1.0, [100.0, 20.0, 0.0, 0.0], 1, Some(1.0));
        assert_eq!(zoom_region(&work, &[]), Some(((-10.0, 110.0), (-10.0, 30.0))));
        // Without work: the path but its travel from and back to home, at least 5 mm around.
        let none = ToolWork::new(100, 10);
        let path = [[500.0, 500.0], [1.0, 1.0], [2.0, 2.0], [500.0, 500.0]];
        assert_eq!(zoom_region(&none, &path), Some(((-4.0, 7.0), (-4.0, 7.0))));
        assert_eq!(zoom_region(&none, &path[..2]), None);
    }
}
