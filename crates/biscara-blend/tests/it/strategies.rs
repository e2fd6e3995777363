//! Strategies: random polylines, from CAM-like runs of short chords to long zig-zags.

use proptest::prelude::*;

/// 2 to 40 vertices `[x, y, z, c]`, consecutive ones at least 1 µm apart in XYZ.
pub fn polyline() -> impl Strategy<Value = Vec<[f64; 4]>> {
    let step = (
        prop_oneof![0.01..2.0f64, 2.0..100.0f64],
        -std::f64::consts::PI..std::f64::consts::PI,
        prop_oneof![Just(0.0), -5.0..5.0f64],
        prop_oneof![Just(0.0), -30.0..30.0f64],
    );
    (prop::collection::vec(step, 1..40), -100.0..100.0f64).prop_map(|(steps, x0)| {
        let mut vertices = vec![[x0, 400.0, 50.0, 0.0]];
        for (length, heading, dz, dc) in steps {
            let last = vertices[vertices.len() - 1];
            vertices.push([
                last[0] + length * heading.cos(),
                last[1] + length * heading.sin(),
                last[2] + dz,
                last[3] + dc,
            ]);
        }
        vertices
    })
}
