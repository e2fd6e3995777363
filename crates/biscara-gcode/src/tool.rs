//! What the robot carries, and so what M3, M4, M5 and S mean (SPEC §1.6).

/// The end effector the program drives. The interpreter turns M3/M4/M5 and S into the tool's
/// own events; it does not infer the tool (that is the caller's, from `robot.json`, a flag or
/// the program).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Tool {
    /// The paper's gripper: M3 pick, M4 place, M5 gripper off; S has no effect.
    #[default]
    Gripper,
    /// A laser: M3 on at constant power, M4 on at dynamic power (Grbl's laser mode), M5 off;
    /// S is the power, and a new S while on is a new power.
    Laser,
    /// A spindle: M3 clockwise, M4 counter-clockwise, M5 off; S is the speed in rpm.
    Spindle,
    /// An extruder: E words carry the filament on the moves; M3, M4 and M5 are recorded as
    /// codes with no effect.
    Extruder,
    /// A pen: M3 and M4 put it down, M5 lifts it; S has no effect.
    Pen,
}
