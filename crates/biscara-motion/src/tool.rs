//! What the robot carries, and so what a program's M3, M4, M5, S and E words mean.

use serde::{Deserialize, Serialize};

/// The kind of end effector the robot carries: `robot.json`'s `tool.kind`, `--tool`, and what
/// the G-code interpreter turns M3/M4/M5 and S into (the tool events of [`MotionKind`]).
///
/// One enum for every crate: the kinematics crate names it `ToolKind` (the robot's file), the
/// G-code crate `Tool` (what the interpreter drives).
///
/// [`MotionKind`]: crate::MotionKind
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Tool {
    /// The paper's gripper: M3 pick, M4 place, M5 gripper off; S has no effect.
    #[default]
    Gripper,
    /// A laser: M3 on at constant power, M4 on at dynamic power (Grbl's laser mode), M5 off;
    /// S is the power, and a new S while on is a new power.
    Laser,
    /// A spindle: M3 clockwise, M4 counter-clockwise, M5 off; S is the speed in rpm.
    Spindle,
    /// A 3D printer's extruder: E words carry the filament on the moves; M3, M4 and M5 are
    /// recorded as codes with no effect.
    Extruder,
    /// A pen: M3 and M4 put it down, M5 lifts it; S has no effect.
    Pen,
}

impl Tool {
    /// Every kind, in the order `robot.json`'s errors list them.
    pub const ALL: [Tool; 5] =
        [Tool::Gripper, Tool::Laser, Tool::Spindle, Tool::Extruder, Tool::Pen];

    /// The name of `robot.json` and `--tool`: `gripper`, `laser`, `spindle`, `extruder`, `pen`.
    pub fn name(self) -> &'static str {
        match self {
            Tool::Gripper => "gripper",
            Tool::Laser => "laser",
            Tool::Spindle => "spindle",
            Tool::Extruder => "extruder",
            Tool::Pen => "pen",
        }
    }

    /// What a picture calls this tool's work in its legend ("" for the gripper, which leaves
    /// none).
    pub fn legend(self) -> &'static str {
        match self {
            Tool::Laser => "laser: burnt trace (darker: more power)",
            Tool::Extruder => "extruder: deposited track",
            Tool::Pen => "pen: strokes (pen down)",
            Tool::Spindle => "spindle: cutting moves",
            Tool::Gripper => "",
        }
    }

    /// The kind named `name` (see [`Tool::name`]); `None` for any other name.
    pub fn from_name(name: &str) -> Option<Tool> {
        Tool::ALL.into_iter().find(|tool| tool.name() == name)
    }
}

/// A tool name that is not one of [`Tool::ALL`]'s.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("`{0}` is not a tool: gripper, laser, spindle, extruder or pen")]
pub struct UnknownTool(pub String);

impl std::str::FromStr for Tool {
    type Err = UnknownTool;

    /// The kind named `name` exactly (see [`Tool::name`]).
    fn from_str(name: &str) -> Result<Tool, UnknownTool> {
        Tool::from_name(name).ok_or_else(|| UnknownTool(name.to_owned()))
    }
}

impl std::fmt::Display for Tool {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_unknown_name_is_refused_with_the_names_known() {
        let err = "Laser".parse::<Tool>().unwrap_err();
        assert_eq!(
            err.to_string(),
            "`Laser` is not a tool: gripper, laser, spindle, extruder or pen"
        );
    }

    #[test]
    fn names_are_those_of_the_robot_file() {
        for tool in Tool::ALL {
            assert_eq!(Tool::from_name(tool.name()), Some(tool));
            assert_eq!(tool.name().parse::<Tool>(), Ok(tool));
            let json = serde_json::to_string(&tool).unwrap();
            assert_eq!(json, format!("\"{}\"", tool.name()));
            assert_eq!(serde_json::from_str::<Tool>(&json).unwrap(), tool);
        }
        assert_eq!(Tool::from_name("torch"), None);
        assert_eq!(Tool::Gripper.legend(), "");
        assert!(Tool::ALL[1..].iter().all(|tool| tool.legend().starts_with(tool.name())));
        assert_eq!(Tool::default(), Tool::Gripper);
    }
}
