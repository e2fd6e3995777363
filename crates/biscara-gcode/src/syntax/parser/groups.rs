//! LinuxCNC's modal groups of G and M codes (`gees` and `ems` in rs274ngc), and which codes
//! are implemented here.

/// Whether a code is implemented here.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Support {
    /// Implemented (or accepted as the no-op it is for this robot).
    Yes,
    /// Part of LinuxCNC's language, refused with "… is not supported yet".
    No(&'static str),
    /// Part of LinuxCNC's language that this robot cannot do (lathe, spindle-synchronised
    /// motion; docs/gcode.md): refused, with why.
    Cannot(&'static str),
}

/// Why spindle-synchronised motion is refused.
const NO_SPINDLE_SYNC: &str = "spindle-synchronised motion needs a spindle encoder and a rotating tool axis this robot has not";
/// Why lathe codes are refused.
const NO_LATHE: &str = "a lathe code; this robot is an X Y Z C arm, not a lathe";

/// The modal group of G code `code` (ten times the number: G59.3 = 593) and whether it is
/// implemented; `None` for a code LinuxCNC does not know.
pub(crate) fn g_group(code: u16) -> Option<(usize, Support)> {
    use Support::{Cannot, No, Yes};
    Some(match code {
        40 | 100 | 280 | 281 | 300 | 301 | 530 | 920 => (0, Yes),
        // LinuxCNC puts G92.1, G92.2 and G92.3 in a group of their own (they may stand with G28).
        921..=923 => (11, Yes),
        520 => (0, Yes),
        0 | 10 | 20 | 30 | 800 => (1, Yes),
        // G5 and G5.1: straight moves along the curve (interpreter/spline.rs).
        50 | 51 => (1, Yes),
        // rs274 hands G5.2/G5.3 NURBS to the motion planner without the points of their path.
        52 | 53 => (1, No("NURBS: LinuxCNC's rs274 passes it on without its path")),
        330 | 331 => (1, Cannot(NO_SPINDLE_SYNC)),
        760 => (1, Cannot(NO_LATHE)),
        // Probing runs as rs274 simulates it: no probe trips (interpreter/probe.rs).
        382..=385 => (1, Yes),
        730 | 740 | 810 | 820 | 830 | 840 | 850 | 860 | 870 | 880 | 890 => (1, Yes),
        700 | 710 | 711 | 712 | 720 | 721 | 722 => (1, Cannot(NO_LATHE)),
        170 | 180 | 190 => (2, Yes),
        171 | 181 | 191 => (2, No("UVW plane")),
        900 | 910 => (3, Yes),
        901 | 911 => (4, Yes),
        930 | 940 => (5, Yes),
        950 => (5, Cannot(NO_SPINDLE_SYNC)),
        200 | 210 => (6, Yes),
        400 => (7, Yes),
        410 | 420 | 411 | 421 => (7, Yes),
        490 => (8, Yes),
        430..=432 => (8, Yes),
        980 | 990 => (10, Yes),
        540 | 550 | 560 | 570 | 580 | 590 | 591 | 592 | 593 => (12, Yes),
        610 | 611 | 640 => (13, Yes),
        970 => (14, Yes),
        960 => (14, Cannot(NO_SPINDLE_SYNC)),
        70 | 80 => (15, Cannot(NO_LATHE)),
        _ => return None,
    })
}

/// The modal group of M code `code` and whether it is implemented; `None` when unknown.
pub(crate) fn m_group(code: u16) -> Option<(usize, Support)> {
    use Support::Yes;
    Some(match code {
        0 | 1 | 2 | 30 | 60 => (4, Yes),
        6 | 61 => (6, Yes),
        3..=5 => (7, Yes),
        // Spindle orientation: an event here (interpreter/io_codes.rs).
        19 => (7, Yes),
        7..=9 => (8, Yes),
        // Override switches: accepted, nothing to do in a simulation.
        48..=53 => (9, Yes),
        // Digital and analog outputs, waiting for an input: events here.
        62..=68 => (5, Yes),
        // rs274 refuses M70 with M3, M4 or M5: one group.
        70..=73 => (7, Yes),
        // User M codes: an event here (there is no external program to run).
        100..=199 => (10, Yes),
        _ => return None,
    })
}
