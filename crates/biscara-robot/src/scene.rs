//! The scene: boxes around the robot that no part of it may touch (docs/virtual-robot.md).

use biscara_text::strip_position;
use serde::{Deserialize, Serialize};

use crate::VirtualRobotError;

/// The robot's surroundings: a list of axis-aligned boxes.
///
/// The file form is `{"boxes":[{"name":"pallet","min":[x,y,z],"max":[x,y,z]}]}` (millimetres,
/// base frame); unknown keys are errors, `name` is optional (`box N` by default).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// The boxes.
    pub boxes: Vec<SceneBox>,
}

/// One axis-aligned box of the scene, millimetres.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "RawBox")]
pub struct SceneBox {
    /// A name for reports (`box N`, 1-based, when the file gives none).
    pub name: String,
    /// The corner with the smallest x, y, z.
    pub min: [f64; 3],
    /// The corner with the largest x, y, z.
    pub max: [f64; 3],
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawBox {
    #[serde(default)]
    name: Option<String>,
    min: [f64; 3],
    max: [f64; 3],
}

impl TryFrom<RawBox> for SceneBox {
    type Error = String;

    fn try_from(raw: RawBox) -> Result<SceneBox, String> {
        for (axis, (low, high)) in ["x", "y", "z"].iter().zip(raw.min.iter().zip(&raw.max)) {
            if !low.is_finite() || !high.is_finite() {
                return Err(format!("{axis}: the corners must be finite numbers"));
            }
            if low >= high {
                return Err(format!(
                    "max must exceed min on every axis, but on {axis} min = {low} and max = \
                     {high} (write the smaller corner as min)"
                ));
            }
        }
        if matches!(&raw.name, Some(name) if name.trim().is_empty()) {
            return Err("name: must not be empty".to_owned());
        }
        Ok(SceneBox { name: raw.name.unwrap_or_default(), min: raw.min, max: raw.max })
    }
}

impl Scene {
    /// An empty scene.
    pub fn new() -> Scene {
        Scene::default()
    }

    /// Reads and validates a scene from the bytes of a JSON file.
    ///
    /// Errors carry the 1-based line and column and the key they are about (`boxes[0].max`).
    pub fn from_json(bytes: &[u8]) -> Result<Scene, VirtualRobotError> {
        let mut scene: Scene = read_json(bytes).map_err(|error| VirtualRobotError::Scene {
            line: error.line,
            column: error.column,
            key: error.key,
            message: error.message,
        })?;
        for (index, scene_box) in scene.boxes.iter_mut().enumerate() {
            if scene_box.name.is_empty() {
                scene_box.name = format!("box {}", index + 1);
            }
        }
        Ok(scene)
    }
}

/// Where and why a JSON document could not be read ([`read_json`]).
pub(crate) struct JsonError {
    /// 1-based line.
    pub(crate) line: usize,
    /// 1-based column.
    pub(crate) column: usize,
    /// Dotted path of the offending key (`boxes[1].max`), or `.` for the whole document.
    pub(crate) key: String,
    /// What is wrong, without serde's position.
    pub(crate) message: String,
}

/// Reads `bytes` as one JSON document of `T`: the reader of the scene and of `check`'s report.
pub(crate) fn read_json<T: serde::de::DeserializeOwned>(bytes: &[u8]) -> Result<T, JsonError> {
    let error = |key: String, inner: serde_json::Error| JsonError {
        line: inner.line().max(1),
        column: inner.column().max(1),
        key,
        message: strip_position(&inner.to_string()),
    };
    let mut deserializer = serde_json::Deserializer::from_slice(bytes);
    let value = serde_path_to_error::deserialize(&mut deserializer).map_err(|err| {
        let path = err.path().to_string();
        error(path, err.into_inner())
    })?;
    deserializer.end().map_err(|inner| error(".".to_owned(), inner))?;
    Ok(value)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[track_caller]
    fn rejected(json: &str, expected: &str) {
        let err = Scene::from_json(json.as_bytes()).expect_err("scene must be rejected");
        assert_eq!(err.to_string(), expected);
    }

    #[test]
    fn a_scene_reads_with_default_names() {
        let scene = Scene::from_json(
            br#"{"boxes":[{"name":"pallet","min":[-1,2,0],"max":[1,3,4]},{"min":[0,0,0],"max":[1,1,1]}]}"#,
        )
        .unwrap();
        assert_eq!(scene.boxes.len(), 2);
        assert_eq!(scene.boxes[0].name, "pallet");
        assert_eq!(scene.boxes[1].name, "box 2");
        assert_eq!(scene.boxes[0].min, [-1.0, 2.0, 0.0]);
        assert_eq!(Scene::from_json(br#"{"boxes":[]}"#).unwrap(), Scene::new());
    }

    #[test]
    fn bad_scenes_name_line_column_and_key() {
        rejected("", "1:1: .: EOF while parsing a value");
        rejected("\u{1}\u{2}garbage", "1:1: .: expected value");
        rejected(
            "{\n  \"boxes\": [{\"min\": [0,0,0], \"max\": [1,1,1], \"colour\": 1}]\n}",
            "2:53: boxes[0].colour: unknown field `colour`, expected one of `name`, `min`, `max`",
        );
        rejected(r#"{"box": []}"#, "1:6: box: unknown field `box`, expected `boxes`");
        rejected(
            "{\"boxes\": [\n {\"min\": [0,0,5], \"max\": [1,1,1]}]}",
            "2:34: boxes[0]: max must exceed min on every axis, but on z min = 5 and max = 1 \
             (write the smaller corner as min)",
        );
        rejected(
            r#"{"boxes": [{"min": [0,0,NaN], "max": [1,1,1]}]}"#,
            "1:25: boxes[0].min[2]: expected value",
        );
        rejected(
            r#"{"boxes": [{"min": [0,0,1e999], "max": [1,1,1]}]}"#,
            "1:29: boxes[0].min[2]: number out of range",
        );
        rejected(
            r#"{"boxes": [{"min": [0,0], "max": [1,1,1]}]}"#,
            "1:24: boxes[0].min: invalid length 2, expected an array of length 3",
        );
        rejected(r#"{"boxes": [{"max": [1,1,1]}]}"#, "1:27: boxes[0]: missing field `min`");
        rejected(r#"{"boxes": []} []"#, "1:15: .: trailing characters");
    }
}
