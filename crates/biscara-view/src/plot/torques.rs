//! The motors' torques against time (docs/dynamics.md), with their ratings: what choosing
//! motors looks at.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::{FAMILY, ImageFormat, ROBOT_COLOURS, encode_png, plot_error, register_font};
use crate::ViewError;

/// The torque curves: each motor's torque (N·m, N for d4) against time.
#[derive(Debug, Clone, Copy)]
pub struct TorqueCurves<'a> {
    /// A title above the picture.
    pub title: &'a str,
    /// Times, s.
    pub t: &'a [f64],
    /// `[theta1, theta2, theta3, d4]` at each time: N·m and N.
    pub torques: &'a [[f64; 4]],
    /// Each motor's `[peak, rated]`, drawn as ± lines, when the robot has motors.
    pub ratings: Option<[[f64; 2]; 4]>,
}

const PEAK_COLOUR: RGBColor = RGBColor(200, 30, 30);
const RATED_COLOUR: RGBColor = RGBColor(230, 140, 20);

/// The torque curves as SVG or PNG bytes: four panels, τ1, τ2, τ3 (N·m) and d4's force (N)
/// against time, with ±`peak` as red dashed lines and ±`rated` as orange dashed lines.
pub fn draw_torques(curves: &TorqueCurves<'_>, format: ImageFormat) -> Result<Vec<u8>, ViewError> {
    super::render_with!((1000, 900), format, torques_on, curves)
}

fn torques_on<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    curves: &TorqueCurves<'_>,
) -> Result<(), String> {
    let e = |err: DrawingAreaErrorKind<DB::ErrorType>| err.to_string();
    root.fill(&WHITE).map_err(e)?;
    let title = match curves.ratings {
        Some(_) => format!("{} (dashed: ±peak red, ±rated orange)", curves.title),
        None => curves.title.to_owned(),
    };
    let root = root.titled(&title, (FAMILY, 20)).map_err(e)?;
    let panels = root.split_evenly((4, 1));
    let names = ["τ1 (N·m)", "τ2 (N·m)", "τ3 (N·m)", "f d4 (N)"];
    let t_end = curves.t.last().copied().unwrap_or(1.0).max(1e-3);
    for (j, panel) in panels.iter().enumerate() {
        let (mut min, mut max) = (0.0f64, 0.0f64);
        for torque in curves.torques {
            min = min.min(torque[j]);
            max = max.max(torque[j]);
        }
        if let Some(ratings) = curves.ratings {
            min = min.min(-ratings[j][0]);
            max = max.max(ratings[j][0]);
        }
        let pad = 0.08 * (max - min).max(1e-3);
        let mut chart = ChartBuilder::on(panel)
            .margin(8)
            .x_label_area_size(if j == 3 { 35 } else { 20 })
            .y_label_area_size(60)
            .build_cartesian_2d(0.0..t_end, (min - pad)..(max + pad))
            .map_err(e)?;
        let mut mesh = chart.configure_mesh();
        mesh.y_desc(names[j]).label_style((FAMILY, 13)).light_line_style(WHITE.mix(0.0));
        if j == 3 {
            mesh.x_desc("t (s)");
        }
        mesh.draw().map_err(e)?;
        if let Some(ratings) = curves.ratings {
            let [peak, rated] = ratings[j];
            for (level, colour) in [
                (peak, PEAK_COLOUR),
                (-peak, PEAK_COLOUR),
                (rated, RATED_COLOUR),
                (-rated, RATED_COLOUR),
            ] {
                chart
                    .draw_series(DashedLineSeries::new(
                        [(0.0, level), (t_end, level)],
                        8,
                        5,
                        colour.stroke_width(2),
                    ))
                    .map_err(e)?;
            }
        }
        chart
            .draw_series(LineSeries::new(
                curves.t.iter().zip(curves.torques).map(|(&t, torque)| (t, torque[j])),
                ROBOT_COLOURS[0].stroke_width(2),
            ))
            .map_err(e)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn torque_curves_draw_with_their_ratings() {
        let t: Vec<f64> = (0..100).map(|k| f64::from(k) * 0.01).collect();
        let torques: Vec<[f64; 4]> =
            t.iter().map(|t| [t.sin(), -t.sin(), 0.1 * t, -5.0 - t]).collect();
        let ratings = Some([[2.0, 1.0], [2.0, 1.0], [0.5, 0.2], [20.0, 10.0]]);
        let curves = TorqueCurves { title: "torques", t: &t, torques: &torques, ratings };
        let svg = String::from_utf8(draw_torques(&curves, ImageFormat::Svg).unwrap()).unwrap();
        assert!(svg.contains("τ1 (N·m)") && svg.contains("±peak"), "{svg}");
        // The dashed ratings (four per panel) in their colours.
        assert!(svg.matches("#C81E1E").count() >= 8, "peak lines");
        assert!(svg.matches("#E68C14").count() >= 8, "rated lines");
        let png =
            draw_torques(&TorqueCurves { ratings: None, ..curves }, ImageFormat::Png).unwrap();
        assert_eq!(&png[1..4], b"PNG");
    }
}
