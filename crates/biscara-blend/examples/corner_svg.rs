//! Draws a blended corner as SVG on stdout: the programmed polyline (grey), the blended path
//! (blue, fillets red) and the tolerance band around the corners.
//!
//! `cargo run -p biscara-blend --example corner_svg > docs/blended-corner.svg`

use std::fmt::Write as _;
use std::io::Write as _;

use biscara_blend::{Blended, Blender};
use biscara_motion::{Feed, Motion, MotionKind};

fn main() -> std::io::Result<()> {
    let feed = Feed { mm_per_min: 6000.0, inverse_time: false };
    let tolerance = 0.5;
    // A square corner, a sharp one, and a run of short chords (the half-move rule).
    let vertices: [[f64; 4]; 9] = [
        [0.0, 0.0, 0.0, 0.0],
        [20.0, 0.0, 0.0, 0.0],
        [20.0, 20.0, 0.0, 0.0],
        [30.0, 2.0, 0.0, 0.0],
        [32.0, 3.0, 0.0, 0.0],
        [33.5, 5.0, 0.0, 0.0],
        [34.3, 7.0, 0.0, 0.0],
        [34.6, 9.0, 0.0, 0.0],
        [34.6, 20.0, 0.0, 0.0],
    ];
    let motions = vertices[1..].iter().enumerate().map(|(k, &end)| {
        Ok::<_, ()>(Motion {
            blend: Some(tolerance),
            ..Motion::new(k + 1, MotionKind::Linear { end, feed })
        })
    });
    let scale = 20.0;
    let (width, height) = (40.0 * scale, 25.0 * scale);
    let at = |p: [f64; 4]| ((p[0] + 2.0) * scale, height - (p[1] + 2.0) * scale);
    let mut svg = String::new();
    let _ = writeln!(
        svg,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{height}\" \
         viewBox=\"0 0 {width} {height}\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>"
    );
    let _ = writeln!(
        svg,
        "<text x=\"10\" y=\"20\" font-family=\"sans-serif\" font-size=\"14\">G64 P{tolerance}: \
         programmed path (grey), blended straight pieces (blue), fillets (red), circles of radius \
         P about the corners (dashed)</text>"
    );
    let mut points = String::new();
    for &v in &vertices {
        let (x, y) = at(v);
        let _ = write!(points, "{x:.2},{y:.2} ");
    }
    let _ = writeln!(
        svg,
        "<polyline points=\"{points}\" fill=\"none\" stroke=\"#999\" stroke-width=\"6\"/>"
    );
    for &v in &vertices[1..vertices.len() - 1] {
        let (x, y) = at(v);
        let _ = writeln!(
            svg,
            "<circle cx=\"{x:.2}\" cy=\"{y:.2}\" r=\"{:.2}\" fill=\"none\" stroke=\"#555\" \
             stroke-dasharray=\"3,3\"/>",
            tolerance * scale
        );
    }
    for item in Blender::new(motions, vertices[0]) {
        let Ok(Blended::Piece(piece)) = item else { continue };
        let colour = if piece.radius().is_some() { "#d22" } else { "#27c" };
        let mut points = String::new();
        for k in 0..=32 {
            let (x, y) = at(piece.point(f64::from(k) / 32.0));
            let _ = write!(points, "{x:.2},{y:.2} ");
        }
        let _ = writeln!(
            svg,
            "<polyline points=\"{points}\" fill=\"none\" stroke=\"{colour}\" stroke-width=\"2\"/>"
        );
    }
    svg.push_str("</svg>\n");
    std::io::stdout().lock().write_all(svg.as_bytes())
}
