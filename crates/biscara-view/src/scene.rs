//! Scenes: the static boxes around the robot (SPEC §8.1), as the viewer and the model show them.

use serde::Deserialize;

use crate::ViewError;

/// The robot's surroundings: axis-aligned boxes in the base frame.
#[derive(Debug, Clone, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// The boxes, in file order.
    pub boxes: Vec<SceneBox>,
}

/// One axis-aligned box of a scene.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneBox {
    /// Its name (shown by the viewer, the geom's name in the model).
    pub name: String,
    /// The corner with the smallest coordinates, `[x, y, z]`, millimetres.
    pub min: [f64; 3],
    /// The corner with the largest coordinates, `[x, y, z]`, millimetres.
    pub max: [f64; 3],
}

impl Scene {
    /// Reads a scene file `{"boxes":[{"name":…,"min":[x,y,z],"max":[x,y,z]}]}`: unknown keys,
    /// non-finite numbers and boxes with `min ≥ max` on an axis are errors.
    pub fn from_json(text: &str) -> Result<Scene, ViewError> {
        let scene: Scene = serde_json::from_str(text).map_err(|err| ViewError::Scene {
            line: err.line().max(1),
            column: err.column().max(1),
            message: err.to_string().split(" at line ").next().unwrap_or_default().to_owned(),
        })?;
        for (index, scene_box) in scene.boxes.iter().enumerate() {
            let finite = scene_box.min.iter().chain(&scene_box.max).all(|v| v.is_finite());
            let ordered = (0..3).all(|axis| scene_box.min[axis] < scene_box.max[axis]);
            if !finite || !ordered {
                return Err(ViewError::Scene {
                    line: 1,
                    column: 1,
                    message: format!(
                        "box {index} (`{}`): every coordinate of `min` must be finite and smaller \
                         than the same coordinate of `max`",
                        scene_box.name
                    ),
                });
            }
        }
        Ok(scene)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_boxes_and_rejects_bad_ones() {
        let scene = Scene::from_json(
            r#"{"boxes":[{"name":"pallet","min":[100,250,0],"max":[200,350,10]}]}"#,
        )
        .unwrap();
        assert_eq!(scene.boxes[0].max, [200.0, 350.0, 10.0]);
        let unknown = Scene::from_json("{\"boxes\":[],\n \"colour\":1}").unwrap_err().to_string();
        assert!(unknown.starts_with("2:") && unknown.contains("colour"), "{unknown}");
        let flat = Scene::from_json(r#"{"boxes":[{"name":"a","min":[0,0,0],"max":[1,1,0]}]}"#);
        assert!(flat.unwrap_err().to_string().contains("`a`"));
    }
}
