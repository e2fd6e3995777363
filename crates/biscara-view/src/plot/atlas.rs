//! The design atlas: one index of a design sweep over l1 × l2, one panel per base distance, as
//! the five-bar literature draws its performance atlases.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::{FAMILY, ImageFormat, encode_png, plot_error, register_font};
use crate::ViewError;

/// Most panels drawn; a sweep over more base distances shows this many, evenly chosen.
pub const ATLAS_MAX_PANELS: usize = 12;

/// One design's value in an atlas.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AtlasCell {
    /// Proximal link length, mm.
    pub l1: f64,
    /// Distal link length, mm.
    pub l2: f64,
    /// Base distance, mm.
    pub base: f64,
    /// The index drawn; `None` for a design without one (invalid or no rectangle): grey.
    pub value: Option<f64>,
}

/// What an atlas shows.
#[derive(Debug, Clone)]
pub struct Atlas<'a> {
    /// The picture's title.
    pub title: &'a str,
    /// The index's name and unit, for the colour scale, e.g. "GCI".
    pub index: &'a str,
    /// Every design's value (any order).
    pub cells: &'a [AtlasCell],
    /// The chosen design `(l1, l2, base)`, ringed in its panel.
    pub chosen: Option<[f64; 3]>,
}

/// Draws `atlas` as SVG or PNG bytes: a heat map over l1 (x) × l2 (y) per base distance, with a
/// shared colour scale from the smallest to the largest value.
pub fn draw_atlas(atlas: &Atlas<'_>, format: ImageFormat) -> Result<Vec<u8>, ViewError> {
    let bases = panel_bases(atlas.cells);
    let columns = bases.len().clamp(1, 4);
    let rows = bases.len().div_ceil(columns).max(1);
    let size = (360 * columns as u32 + 40, 330 * rows as u32 + 130);
    super::render_with!(size, format, atlas_on, atlas, &bases, columns, rows)
}

/// The base distances that get a panel, sorted.
fn panel_bases(cells: &[AtlasCell]) -> Vec<f64> {
    let mut bases: Vec<f64> = cells.iter().map(|c| c.base).collect();
    bases.sort_by(f64::total_cmp);
    bases.dedup();
    if bases.len() > ATLAS_MAX_PANELS {
        let n = bases.len() - 1;
        bases = (0..ATLAS_MAX_PANELS).map(|k| bases[k * n / (ATLAS_MAX_PANELS - 1)]).collect();
    }
    bases
}

/// The colour of `t` in [0, 1]: dark blue through teal and green to yellow (a viridis-like
/// ramp, readable in grey and by colour-blind readers).
fn ramp(t: f64) -> RGBColor {
    const STOPS: [(f64, [f64; 3]); 5] = [
        (0.0, [68.0, 1.0, 84.0]),
        (0.25, [59.0, 82.0, 139.0]),
        (0.5, [33.0, 145.0, 140.0]),
        (0.75, [94.0, 201.0, 98.0]),
        (1.0, [253.0, 231.0, 37.0]),
    ];
    let t = t.clamp(0.0, 1.0);
    let k = STOPS.iter().rposition(|(s, _)| *s <= t).unwrap_or(0).min(STOPS.len() - 2);
    let (s0, c0) = STOPS[k];
    let (s1, c1) = STOPS[k + 1];
    let f = (t - s0) / (s1 - s0);
    let mix = |i: usize| (c0[i] + f * (c1[i] - c0[i])).round() as u8;
    RGBColor(mix(0), mix(1), mix(2))
}

/// The sorted distinct values of one coordinate and the half gap around each.
fn axis(values: impl Iterator<Item = f64>) -> (Vec<f64>, f64) {
    let mut values: Vec<f64> = values.collect();
    values.sort_by(f64::total_cmp);
    values.dedup();
    let gap = values.windows(2).map(|w| w[1] - w[0]).fold(f64::INFINITY, f64::min);
    let half = if gap.is_finite() { 0.5 * gap } else { 5.0 };
    (values, half)
}

fn atlas_on<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    atlas: &Atlas<'_>,
    bases: &[f64],
    columns: usize,
    rows: usize,
) -> Result<(), String> {
    let e = |err: DrawingAreaErrorKind<DB::ErrorType>| err.to_string();
    root.fill(&WHITE).map_err(e)?;
    let (height, width) = (root.dim_in_pixel().1, root.dim_in_pixel().0);
    let root = root.titled(atlas.title, (FAMILY, 22)).map_err(e)?;
    let (body, scale_area) = root.split_vertically(height - 100);
    let values = atlas.cells.iter().filter_map(|c| c.value);
    let (low, high) =
        values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(v), hi.max(v)));
    let span = if high > low { high - low } else { 1.0 };
    let colour = |value: Option<f64>| match value {
        Some(v) if low.is_finite() => ramp((v - low) / span),
        _ => RGBColor(200, 200, 200),
    };
    let (l1s, h1) = axis(atlas.cells.iter().map(|c| c.l1));
    let (l2s, h2) = axis(atlas.cells.iter().map(|c| c.l2));
    let x_range = l1s.first().copied().unwrap_or(0.0) - h1..l1s.last().copied().unwrap_or(1.0) + h1;
    let y_range = l2s.first().copied().unwrap_or(0.0) - h2..l2s.last().copied().unwrap_or(1.0) + h2;
    for (panel, &base) in body.split_evenly((rows, columns)).iter().zip(bases) {
        let mut chart = ChartBuilder::on(panel)
            .caption(format!("base {base} mm"), (FAMILY, 16))
            .margin(8)
            .x_label_area_size(36)
            .y_label_area_size(48)
            .build_cartesian_2d(x_range.clone(), y_range.clone())
            .map_err(e)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc("l1 (mm)")
            .y_desc("l2 (mm)")
            .x_labels(5)
            .y_labels(5)
            .label_style((FAMILY, 12))
            .draw()
            .map_err(e)?;
        let cells = atlas.cells.iter().filter(|c| c.base == base).map(|c| {
            Rectangle::new(
                [(c.l1 - h1, c.l2 - h2), (c.l1 + h1, c.l2 + h2)],
                colour(c.value).filled(),
            )
        });
        chart.draw_series(cells).map_err(e)?;
        if let Some([l1, l2, b]) = atlas.chosen
            && b == base
        {
            chart
                .draw_series(std::iter::once(Rectangle::new(
                    [(l1 - h1, l2 - h2), (l1 + h1, l2 + h2)],
                    RED.stroke_width(3),
                )))
                .map_err(e)?;
        }
    }
    // The colour scale.
    let bar = scale_area.margin(30, 40, 60, 60);
    let (bar_width, _) = bar.dim_in_pixel();
    let steps = 100;
    for k in 0..steps {
        let x0 = (bar_width as i32 * k) / steps;
        let x1 = (bar_width as i32 * (k + 1)) / steps;
        let t = (f64::from(k) + 0.5) / f64::from(steps);
        bar.draw(&Rectangle::new([(x0, 0), (x1, 18)], ramp(t).filled())).map_err(e)?;
    }
    let label = |v: f64| if v.abs() >= 100.0 { format!("{v:.0}") } else { format!("{v:.3}") };
    let style = (FAMILY, 14).into_font().color(&BLACK);
    if low.is_finite() {
        bar.draw_text(&label(low), &style, (0, 22)).map_err(e)?;
        let text = label(high);
        let right = bar_width as i32 - 8 * text.len() as i32;
        bar.draw_text(&text, &style, (right, 22)).map_err(e)?;
    }
    let note = format!("{} (grey: no rectangle; red: the chosen design)", atlas.index);
    bar.draw_text(&note, &style, (bar_width as i32 / 2 - 4 * note.len() as i32, 22)).map_err(e)?;
    let _ = width;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_ramp_runs_from_dark_to_light() {
        let luminance =
            |c: RGBColor| 0.3 * f64::from(c.0) + 0.6 * f64::from(c.1) + 0.1 * f64::from(c.2);
        let values: Vec<f64> = (0..=10).map(|k| luminance(ramp(f64::from(k) / 10.0))).collect();
        assert!(values.windows(2).all(|w| w[1] > w[0]), "{values:?}");
    }

    /// The centre (x, y pixels) and count of the PNG's pixels of colour `rgb`.
    fn pixels_of(png: &[u8], rgb: [u8; 3]) -> ([f64; 2], usize) {
        let mut reader = png::Decoder::new(std::io::Cursor::new(png)).read_info().unwrap();
        let mut buffer = vec![0; reader.output_buffer_size().unwrap()];
        let info = reader.next_frame(&mut buffer).unwrap();
        let (mut sum, mut count) = ([0.0, 0.0], 0);
        for (index, pixel) in buffer[..info.buffer_size()].chunks(3).enumerate() {
            if pixel == rgb {
                let index = index as u32;
                sum[0] += f64::from(index % info.width);
                sum[1] += f64::from(index / info.width);
                count += 1;
            }
        }
        ([sum[0] / count.max(1) as f64, sum[1] / count.max(1) as f64], count)
    }

    #[test]
    fn each_design_is_drawn_in_its_values_colour_where_its_links_put_it() {
        // One base, l1 ∈ {200, 300} across, l2 ∈ {250, 350} up: the lowest value at (200, 250),
        // the highest at (300, 350), the middle one at (200, 350), no rectangle at (300, 250).
        let cell = |l1, l2, value| AtlasCell { l1, l2, base: 150.0, value };
        let cells = [
            cell(200.0, 250.0, Some(0.2)),
            cell(300.0, 250.0, None),
            cell(200.0, 350.0, Some(0.5)),
            cell(300.0, 350.0, Some(0.8)),
        ];
        let atlas = Atlas {
            title: "atlas",
            index: "GCI",
            cells: &cells,
            chosen: Some([300.0, 350.0, 150.0]),
        };
        let png = draw_atlas(&atlas, ImageFormat::Png).unwrap();
        let RGBColor(r, g, b) = ramp(0.0);
        let (low, low_count) = pixels_of(&png, [r, g, b]);
        let RGBColor(r, g, b) = ramp(0.5);
        let (middle, middle_count) = pixels_of(&png, [r, g, b]);
        let RGBColor(r, g, b) = ramp(1.0);
        let (high, high_count) = pixels_of(&png, [r, g, b]);
        let (grey, grey_count) = pixels_of(&png, [200, 200, 200]);
        let (ring, ring_count) = pixels_of(&png, [255, 0, 0]);
        for count in [low_count, middle_count, high_count, grey_count] {
            assert!(count > 5_000, "a cell of {count} pixels");
        }
        assert!(ring_count > 500, "the chosen design's ring: {ring_count} pixels");
        let close =
            |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).abs() < 3.0 && (a[1] - b[1]).abs() < 3.0;
        // Columns by l1, rows by l2 (up: smaller pixel y).
        assert!(close([low[0], 0.0], [middle[0], 0.0]) && close([grey[0], 0.0], [high[0], 0.0]));
        assert!(close([0.0, low[1]], [0.0, grey[1]]) && close([0.0, middle[1]], [0.0, high[1]]));
        assert!(high[0] > low[0] + 50.0 && low[1] > high[1] + 50.0, "{low:?} {high:?}");
        assert!(close(ring, high), "the ring {ring:?} around the best {high:?}");
    }

    #[test]
    fn an_atlas_draws_a_panel_per_base() {
        let mut cells = Vec::new();
        for base in [100.0, 200.0] {
            for l1 in [150.0, 200.0, 250.0] {
                for l2 in [200.0, 300.0] {
                    let value = (l1 < 250.0).then_some(l1 / l2 + base / 1000.0);
                    cells.push(AtlasCell { l1, l2, base, value });
                }
            }
        }
        let atlas = Atlas {
            title: "GCI atlas",
            index: "GCI",
            cells: &cells,
            chosen: Some([200.0, 200.0, 200.0]),
        };
        let svg = String::from_utf8(draw_atlas(&atlas, ImageFormat::Svg).unwrap()).unwrap();
        assert!(svg.contains("base 100 mm") && svg.contains("base 200 mm"), "panels");
        assert!(svg.contains("GCI (grey"), "scale");
        let png = draw_atlas(&atlas, ImageFormat::Png).unwrap();
        assert_eq!(&png[1..4], b"PNG");
    }
}
