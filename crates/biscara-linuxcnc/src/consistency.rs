//! A configuration folder's robot: read from its `robot.json`, and checked against the numbers
//! its INI and HAL hold (a file edited by hand must not run another robot's kinematics or
//! limits).

use biscara_kinematics::{Robot, RobotModel};

use crate::LinuxcncError;
use crate::config::{HAL, INI, ROBOT_FILE, fill, robot_values};

/// The value of `KEY` in `[SECTION]` of an INI file (its first occurrence, trimmed).
pub fn ini_value<'a>(ini: &'a str, section: &str, key: &str) -> Option<&'a str> {
    let mut current = "";
    for line in ini.lines() {
        let line = line.trim();
        if let Some(name) = line.strip_prefix('[').and_then(|rest| rest.strip_suffix(']')) {
            current = name.trim();
        } else if current == section
            && let Some((name, value)) = line.split_once('=')
            && name.trim() == key
        {
            return Some(value.trim());
        }
    }
    None
}

/// The `setp NAME VALUE` lines of a HAL file, in order (comments and other commands skipped).
pub fn hal_parameters(hal: &str) -> Vec<(&str, &str)> {
    hal.lines()
        .filter_map(|line| {
            let line = line.split('#').next().unwrap_or("");
            let mut words = line.split_whitespace();
            (words.next()? == "setp").then_some(())?;
            let (name, value) = (words.next()?, words.next()?);
            words.next().is_none().then_some((name, value))
        })
        .collect()
}

/// The INI keys of each joint that carry the robot's numbers.
const JOINT_KEYS: [&str; 4] = ["MIN_LIMIT", "MAX_LIMIT", "MAX_VELOCITY", "MAX_ACCELERATION"];

/// Whether two numbers written as text are the same number (`180` and `180.0` are).
fn same_number(a: &str, b: &str) -> bool {
    match (a.parse::<f64>(), b.parse::<f64>()) {
        (Ok(a), Ok(b)) => a == b,
        _ => a == b,
    }
}

/// Reads the robot a configuration was written for from its `robot.json` text, and checks that
/// its INI (`ini`) and HAL (`hal`, `biscara.hal`) hold that robot's numbers: the kinematics'
/// geometry and modes and θ1's and θ2's limits (`setp biscarakins.*`), the stream path's joint
/// limits (`setp limit-*`) and each joint's `[JOINT_n]` limits. `folder` names the
/// configuration in messages.
pub fn configuration_robot(
    folder: &str,
    robot_json: &str,
    ini: &str,
    hal: &str,
) -> Result<RobotModel, LinuxcncError> {
    let robot = Robot::from_json(robot_json)
        .and_then(RobotModel::new)
        .map_err(|err| LinuxcncError::Robot { message: format!("{folder}/{ROBOT_FILE}: {err}") })?;
    let values = robot_values(robot.robot());
    let expected_hal = fill(HAL, &values);
    let expected_ini = fill(INI, &values);
    let disagree = |file: &str, what: &str, found: &str, want: &str| LinuxcncError::Robot {
        message: format!(
            "{folder}/{file} and {folder}/{ROBOT_FILE} disagree: {what} is {found} in {file} and \
             {want} for the robot of {ROBOT_FILE}; write the configuration again with `biscara \
             linuxcnc config` instead of editing it"
        ),
    };
    let found = hal_parameters(hal);
    for (name, want) in hal_parameters(&expected_hal) {
        let robot_number = name.starts_with("biscarakins.") || name.starts_with("limit-");
        if !robot_number {
            continue;
        }
        match found.iter().rev().find(|(found, _)| *found == name) {
            Some((_, value)) if same_number(value, want) => {}
            Some((_, value)) => return Err(disagree("biscara.hal", name, value, want)),
            None => return Err(disagree("biscara.hal", name, "not set", want)),
        }
    }
    for joint in 0..4 {
        let section = format!("JOINT_{joint}");
        for key in JOINT_KEYS {
            let want = ini_value(&expected_ini, &section, key).unwrap_or("");
            let what = format!("[{section}] {key}");
            match ini_value(ini, &section, key) {
                Some(value) if same_number(value, want) => {}
                Some(value) => return Err(disagree("biscara.ini", &what, value, want)),
                None => return Err(disagree("biscara.ini", &what, "missing", want)),
            }
        }
    }
    Ok(robot)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{ConfigOptions, configuration};

    fn files(model: &RobotModel) -> (String, String, String) {
        let config = configuration(model, &ConfigOptions::default()).unwrap();
        let file = |name: &str| {
            config.files.iter().find(|file| file.name == name).unwrap().contents.clone()
        };
        (file(ROBOT_FILE), file("biscara.ini"), file("biscara.hal"))
    }

    #[test]
    fn ini_values_are_found_in_their_section() {
        let ini = "[A]\nX = 1\n[B]\n  X=2 \nY = three\n[ C ]\nX = 4\n";
        assert_eq!(ini_value(ini, "A", "X"), Some("1"));
        assert_eq!(ini_value(ini, "B", "X"), Some("2"));
        assert_eq!(ini_value(ini, "B", "Y"), Some("three"));
        assert_eq!(ini_value(ini, "C", "X"), Some("4"));
        assert_eq!(ini_value(ini, "A", "Y"), None);
        assert_eq!(ini_value(ini, "D", "X"), None);
    }

    #[test]
    fn hal_parameters_are_the_setp_lines() {
        let hal = "# setp a.b 1\nsetp a.b 2\nsetp  c.d  -3.5 # comment\nsets x 1\nsetp bad\n";
        assert_eq!(hal_parameters(hal), vec![("a.b", "2"), ("c.d", "-3.5")]);
    }

    #[test]
    fn a_written_configuration_carries_its_robot() {
        let robot = Robot::from_json(r#"{"links": {"l1": 180, "l2": 260}}"#).unwrap();
        let model = RobotModel::new(robot).unwrap();
        let (json, ini, hal) = files(&model);
        let read = configuration_robot("cfg", &json, &ini, &hal).unwrap();
        assert_eq!(read.robot(), model.robot());
    }

    #[test]
    fn a_hand_edited_ini_or_hal_is_refused_naming_both() {
        let model = RobotModel::default();
        let (json, ini, hal) = files(&model);
        let edited = hal.replacen("setp biscarakins.l1 ", "setp biscarakins.l1 1", 1);
        let err = configuration_robot("cfg", &json, &ini, &edited).unwrap_err().to_string();
        assert!(err.contains("cfg/biscara.hal and cfg/robot.json disagree"), "{err}");
        assert!(err.contains("biscarakins.l1"), "{err}");
        let edited = hal.replace("setp limit-theta2.maxv", "# setp limit-theta2.maxv");
        let err = configuration_robot("cfg", &json, &ini, &edited).unwrap_err().to_string();
        assert!(err.contains("limit-theta2.maxv is not set"), "{err}");
        let section = ini.find("[JOINT_1]").unwrap();
        let at = section + ini[section..].find("MAX_VELOCITY = ").unwrap() + 15;
        let edited = format!("{}9{}", &ini[..at], &ini[at..]);
        let err = configuration_robot("cfg", &json, &edited, &hal).unwrap_err().to_string();
        assert!(err.contains("[JOINT_1] MAX_VELOCITY is 9"), "{err}");
        let err = configuration_robot("cfg", "{", &ini, &hal).unwrap_err().to_string();
        assert!(err.starts_with("cfg/robot.json: "), "{err}");
    }
}
