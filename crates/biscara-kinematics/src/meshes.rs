//! `meshes` in `robot.json`: STL files drawn in place of the viewer's boxes and cylinders.
//!
//! This crate only holds and checks the names and placements; it never opens the files (the
//! command line resolves the paths against the robot file's folder and reads them).

use std::fmt;

use serde::de::{self, MapAccess, Visitor};
use serde::{Deserialize, Deserializer, Serialize};

/// The STL meshes of the robot's parts, each optional: a part without one is drawn as a box or a
/// cylinder of `geometry`'s sizes. The part names are the viewer's; each part's frame is given
/// in its field's documentation (millimetres, +Z up in every frame).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Meshes {
    /// The fixed base (pillars and beam): in the base frame itself.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub base: Option<MeshSpec>,
    /// Chain 1's proximal link: origin on its base joint's axis at `link_height`, +X along the
    /// link toward the elbow (turns with θ1).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub proximal1: Option<MeshSpec>,
    /// Chain 2's proximal link: as `proximal1`, on chain 2's base joint (turns with θ2).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub proximal2: Option<MeshSpec>,
    /// Chain 1's distal link: origin on elbow 1's axis at `link_height`, +X along the link toward
    /// the platform point (the tool's x, y).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub distal1: Option<MeshSpec>,
    /// Chain 2's distal link: as `distal1`, from elbow 2.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub distal2: Option<MeshSpec>,
    /// The Z column (the part that moves with z): origin at the tool point, axes parallel to the
    /// base frame's (not turned by c).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub column: Option<MeshSpec>,
    /// The tool with its flange: origin at the tool point, turned by c about +Z.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tool: Option<MeshSpec>,
}

/// A part of the robot the viewer draws, and so may have a mesh (see [`Meshes`]'s fields for
/// each part's frame).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Part {
    /// The fixed base (pillars and beam).
    Base,
    /// Chain 1's proximal link.
    Proximal1,
    /// Chain 2's proximal link.
    Proximal2,
    /// Chain 1's distal link.
    Distal1,
    /// Chain 2's distal link.
    Distal2,
    /// The Z column.
    Column,
    /// The tool with its flange.
    Tool,
}

impl Part {
    /// Every part, in the order of `robot.json`'s `meshes`.
    pub const ALL: [Part; 7] = [
        Part::Base,
        Part::Proximal1,
        Part::Proximal2,
        Part::Distal1,
        Part::Distal2,
        Part::Column,
        Part::Tool,
    ];

    /// The part's key in `robot.json`'s `meshes` and the viewer's name for it.
    pub fn name(self) -> &'static str {
        match self {
            Part::Base => "base",
            Part::Proximal1 => "proximal1",
            Part::Proximal2 => "proximal2",
            Part::Distal1 => "distal1",
            Part::Distal2 => "distal2",
            Part::Column => "column",
            Part::Tool => "tool",
        }
    }
}

impl fmt::Display for Part {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl Meshes {
    /// The mesh of `part`, if it has one.
    pub fn get(&self, part: Part) -> Option<&MeshSpec> {
        match part {
            Part::Base => self.base.as_ref(),
            Part::Proximal1 => self.proximal1.as_ref(),
            Part::Proximal2 => self.proximal2.as_ref(),
            Part::Distal1 => self.distal1.as_ref(),
            Part::Distal2 => self.distal2.as_ref(),
            Part::Column => self.column.as_ref(),
            Part::Tool => self.tool.as_ref(),
        }
    }

    /// The parts that have a mesh, in the order of [`Part::ALL`].
    pub fn parts(&self) -> impl Iterator<Item = (Part, &MeshSpec)> {
        Part::ALL.into_iter().filter_map(|part| Some((part, self.get(part)?)))
    }

    /// The parts that have a mesh, mutably (to resolve their paths).
    pub fn parts_mut(&mut self) -> impl Iterator<Item = (Part, &mut MeshSpec)> {
        let Meshes { base, proximal1, proximal2, distal1, distal2, column, tool } = self;
        Part::ALL
            .into_iter()
            .zip([base, proximal1, proximal2, distal1, distal2, column, tool])
            .filter_map(|(part, spec)| Some((part, spec.as_mut()?)))
    }

    /// Whether no part has a mesh.
    pub fn is_empty(&self) -> bool {
        self.parts().next().is_none()
    }
}

/// One part's mesh: an STL file and where it sits in the part's frame. In `robot.json` either a
/// file name (`"proximal.stl"`: millimetres, placed as drawn) or an object with `file` and any of
/// `scale`, `offset` and `rotation`.
///
/// A vertex `v` of the file lands at `offset + Rz(rz)·Ry(ry)·Rx(rx)·(scale·v)` in the part's
/// frame: scaled, turned about the frame's X, then Y, then Z axes (fixed axes), then moved.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MeshSpec {
    /// The STL file (binary or ASCII); a relative path is relative to the robot file's folder.
    pub file: String,
    /// Millimetres per STL unit: 1 for files in millimetres (the default), 1000 for metres, 25.4
    /// for inches.
    pub scale: f64,
    /// Where the file's origin lands in the part's frame, millimetres.
    pub offset: [f64; 3],
    /// Turns about the part frame's X, Y and Z axes, applied in that order, degrees.
    pub rotation: [f64; 3],
}

impl MeshSpec {
    /// A mesh in millimetres, placed as drawn.
    pub fn new(file: impl Into<String>) -> MeshSpec {
        MeshSpec { file: file.into(), scale: 1.0, offset: [0.0; 3], rotation: [0.0; 3] }
    }

    /// The affine map from the file's coordinates to the part's frame (millimetres), as a 3×4
    /// row-major matrix `[R·scale | offset]`.
    pub fn transform(&self) -> [[f64; 4]; 3] {
        let [rx, ry, rz] = self.rotation.map(f64::to_radians);
        let (sx, cx) = rx.sin_cos();
        let (sy, cy) = ry.sin_cos();
        let (sz, cz) = rz.sin_cos();
        // Rz·Ry·Rx.
        let r = [
            [cz * cy, cz * sy * sx - sz * cx, cz * sy * cx + sz * sx],
            [sz * cy, sz * sy * sx + cz * cx, sz * sy * cx - cz * sx],
            [-sy, cy * sx, cy * cx],
        ];
        let s = self.scale;
        let o = self.offset;
        [0, 1, 2].map(|i| [r[i][0] * s, r[i][1] * s, r[i][2] * s, o[i]])
    }
}

/// The object form of a mesh entry, as written.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct MeshObject {
    file: String,
    #[serde(default = "one")]
    scale: f64,
    #[serde(default)]
    offset: [f64; 3],
    #[serde(default)]
    rotation: [f64; 3],
}

fn one() -> f64 {
    1.0
}

impl<'de> Deserialize<'de> for MeshSpec {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<MeshSpec, D::Error> {
        struct SpecVisitor;
        impl<'de> Visitor<'de> for SpecVisitor {
            type Value = MeshSpec;

            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str(
                    "an STL file name, or {\"file\": …, \"scale\": …, \"offset\": [x, y, z], \
                     \"rotation\": [rx, ry, rz]}",
                )
            }

            fn visit_str<E: de::Error>(self, file: &str) -> Result<MeshSpec, E> {
                Ok(MeshSpec::new(file))
            }

            fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<MeshSpec, A::Error> {
                let object = MeshObject::deserialize(de::value::MapAccessDeserializer::new(map))?;
                Ok(MeshSpec {
                    file: object.file,
                    scale: object.scale,
                    offset: object.offset,
                    rotation: object.rotation,
                })
            }
        }
        deserializer.deserialize_any(SpecVisitor)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_transform_scales_turns_then_moves() {
        let spec = MeshSpec {
            file: "a.stl".to_owned(),
            scale: 1000.0,
            offset: [10.0, 0.0, 5.0],
            rotation: [0.0, 0.0, 90.0],
        };
        let m = spec.transform();
        // (0.001, 0, 0) m → 1 mm along x → turned to +y → moved.
        let v = [0.001, 0.0, 0.0];
        let p: Vec<f64> =
            (0..3).map(|i| m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2] + m[i][3]).collect();
        assert!((p[0] - 10.0).abs() < 1e-9 && (p[1] - 1.0).abs() < 1e-9 && p[2] == 5.0, "{p:?}");
        // X first, then Z: +y turned 90° about X is +z, which Z leaves alone.
        let spec = MeshSpec { rotation: [90.0, 0.0, 90.0], ..MeshSpec::new("b.stl") };
        let m = spec.transform();
        assert!(m[2][1] > 0.999 && m[0][1].abs() < 1e-12 && m[1][1].abs() < 1e-12, "{m:?}");
    }
}
