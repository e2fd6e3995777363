//! The motors' torques against time (docs/dynamics.md), with their ratings: what choosing
//! motors looks at.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::{ImageFormat, TimePanel, encode_png, plot_error, register_font, time_panels};
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
    let title = match curves.ratings {
        Some(_) => format!("{} (dashed: ±peak red, ±rated orange)", curves.title),
        None => curves.title.to_owned(),
    };
    let names = ["τ1 (N·m)", "τ2 (N·m)", "τ3 (N·m)", "f d4 (N)"];
    // The axis shows 0 and ±peak whatever the curve.
    let panels = std::array::from_fn(|j| match curves.ratings {
        Some(ratings) => {
            let [peak, rated] = ratings[j];
            TimePanel {
                name: names[j],
                shows: ((-peak).min(0.0), peak.max(0.0)),
                min_span: 1e-3,
                levels: vec![
                    (peak, PEAK_COLOUR),
                    (-peak, PEAK_COLOUR),
                    (rated, RATED_COLOUR),
                    (-rated, RATED_COLOUR),
                ],
            }
        }
        None => TimePanel { name: names[j], shows: (0.0, 0.0), min_span: 1e-3, levels: Vec::new() },
    });
    time_panels(root, (&title, 20), curves.t, curves.torques, panels)
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
