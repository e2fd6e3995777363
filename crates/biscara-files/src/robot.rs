//! The robot file, its meshes and the scene, read from the file system.

use std::io;
use std::path::{Path, PathBuf};

use biscara_dynamics::Dynamics;
use biscara_kinematics::{Robot, RobotModel};
use biscara_robot::Scene;
use biscara_view::{MAX_MESH_TRIANGLES, StlError, Viewer, read_stl};

use crate::{FileError, display_path, open_input, read_bytes, read_text};

/// The robot in force, validated and modelled once: the built-in one, or the robot file `path`
/// read (`-`: standard input), its meshes resolved ([`resolve_meshes`]) and its dynamics
/// checked; errors as `ROBOT:LINE:COL: key: message`.
pub fn load_robot(path: Option<&Path>) -> Result<RobotModel, FileError> {
    let Some(path) = path else {
        return Ok(RobotModel::default());
    };
    let text = read_text(path)?;
    let mut robot = Robot::from_json(&text).map_err(|err| located(path, err))?;
    resolve_meshes(&mut robot, path, &text)?;
    let model = RobotModel::new(robot).map_err(|err| located(path, err))?;
    // The dynamics' own check (d4's motor against the slide's weight), before anything runs.
    if let Err(err) = Dynamics::new(&model) {
        let (line, column) =
            err.key().and_then(|key| Robot::locate_key(&text, key)).unwrap_or((1, 1));
        return Err(located(path, format_args!("{line}:{column}: {err}")));
    }
    Ok(model)
}

/// An error whose `Display` starts with `LINE[:COL]:`, located in `path`.
fn located(path: &Path, err: impl std::fmt::Display) -> FileError {
    FileError::Located { path: display_path(path), message: err.to_string() }
}

/// Makes the robot's mesh files absolute, each relative to the robot file's folder (the current
/// folder for standard input), so that the robot in force names them wherever it is used or
/// written; a file that cannot be found is an error at its key: `ROBOT:LINE:COL: meshes.PART: …`.
pub fn resolve_meshes(robot: &mut Robot, path: &Path, text: &str) -> Result<(), FileError> {
    let folder = match path.parent() {
        Some(folder) if path != Path::new("-") => folder.to_owned(),
        _ => PathBuf::new(),
    };
    for (part, spec) in robot.meshes.parts_mut() {
        let key = format!("meshes.{part}");
        let file = folder.join(&spec.file);
        let resolved = file.canonicalize().and_then(|resolved| {
            if resolved.is_file() { Ok(resolved) } else { Err(io::Error::other("not a file")) }
        });
        match resolved {
            Ok(resolved) => spec.file = resolved.to_string_lossy().into_owned(),
            Err(err) => {
                let at = Robot::locate_key(text, &key)
                    .map_or_else(String::new, |(line, column)| format!("{line}:{column}: "));
                let message =
                    format!("{at}{key}: cannot read the STL file {}: {err}", file.display());
                return Err(located(path, message));
            }
        }
    }
    Ok(())
}

/// Reads the robot's mesh files (already resolved by [`resolve_meshes`]) into the viewer;
/// errors as `STL_FILE:LINE:COL: …` or `STL_FILE: byte N: …`.
pub fn load_meshes(robot: &Robot, viewer: &mut Viewer) -> Result<(), FileError> {
    for (part, spec) in robot.meshes.parts() {
        let path = Path::new(&spec.file);
        let mesh = read_stl(open_input(path)?, MAX_MESH_TRIANGLES).map_err(|err| match err {
            // A byte offset reads better after a space: `part.stl: byte 84: …`.
            StlError::Binary { .. } => located(path, format_args!(" {err}")),
            _ => located(path, err),
        })?;
        viewer.add_mesh(part, spec, &mesh).map_err(|err| located(path, format_args!(" {err}")))?;
    }
    Ok(())
}

/// The scene of `--scene FILE` (`-`: standard input), or an empty one; errors as
/// `FILE:LINE:COL: key: message`.
pub fn load_scene(path: Option<&Path>) -> Result<Scene, FileError> {
    let Some(path) = path else { return Ok(Scene::new()) };
    Scene::from_json(&read_bytes(path)?).map_err(|err| located(path, err))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_robot_file_is_read_and_its_faults_are_located() {
        let dir = std::env::temp_dir().join(format!("biscara-robot-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("a folder");
        let path = dir.join("robot.json");
        std::fs::write(&path, Robot::default().to_json_pretty()).expect("written");
        let model = load_robot(Some(&path)).expect("the robot");
        assert_eq!(model.robot(), RobotModel::default().robot());
        std::fs::write(&path, "{\n  \"links\": 3\n}\n").expect("written");
        let err = load_robot(Some(&path)).expect_err("not a robot").to_string();
        assert!(err.starts_with(&format!("{}:2:", path.display())), "{err}");
        // A mesh file that is not there: an error at its key.
        let json = Robot::default().to_json_pretty();
        let json =
            json.replacen('{', "{\n  \"meshes\": {\"base\": {\"file\": \"missing.stl\"}},", 1);
        std::fs::write(&path, json).expect("written");
        let err = load_robot(Some(&path)).expect_err("no such mesh").to_string();
        assert!(
            err.contains("robot.json:2:")
                && err.contains(": meshes.base: cannot read the STL file")
        );
        assert_eq!(load_scene(None).expect("empty"), Scene::new());
        std::fs::remove_dir_all(&dir).expect("removed");
    }
}
