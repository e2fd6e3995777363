//! M70–M73: saving and restoring the modal state, as LinuxCNC's `rs274` does it.
//!
//! M70 saves, M71 forgets, M72 restores, M73 saves for restoring when a subroutine returns
//! (at the program's level it only saves). Each call level has its own saved state: a
//! subroutine starts with none, and what it saved is forgotten (M70) or restored (M73) when it
//! returns. Saved and restored: the length units, the plane, the distance and arc distance
//! modes, the feed mode and rate, the spindle speed and direction (a change of direction is the
//! tool's event, as M3/M4/M5), the coolant, the coordinate system, the canned cycles' retract
//! mode, the tool length offset (G43 or G49, as rs274 saves it: G43 comes back as the offset of
//! the tool in the spindle), whether the G92 offsets are in force (G92.3 or G92.2) and the
//! path-control mode (G61, G61.1, G64 P Q); cutter compensation back off (back on is refused
//! as not supported). Not the motion mode. As in rs274, the feed comes back with one decimal
//! and the speed with none, and an M72 that changes anything loses the rest of its line (see
//! [`Machine::modal_state`]).

use biscara_motion::Plane;

use super::Machine;
use crate::syntax::lexer::Fault;
use crate::syntax::parser::Code;

/// The modal state M70 saves.
#[derive(Debug, Clone, Copy)]
pub(super) struct SavedModes {
    metric: bool,
    incremental: bool,
    ijk_absolute: bool,
    plane: Plane,
    inverse_time: bool,
    feed_rate: f64,
    speed: f64,
    spindle: u16,
    mist: bool,
    flood: bool,
    system: usize,
    retract_to_old: bool,
    /// G43 (an offset in force) rather than G49: what rs274 saves of the tool length offset.
    tool_offset_on: bool,
    /// G92.3 (the G92 offsets in force, parameter 5210) rather than G92.2.
    g92_on: bool,
    blend: Option<f64>,
    naive_cam: Option<f64>,
    /// Cutter radius compensation's code: 400 (G40), 410 (left) or 420 (right).
    comp: f64,
}

/// The saved state, if any, and whether M73 asked for it to be restored on return.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct ModalStack {
    pub saved: Option<SavedModes>,
    /// M73: restore when the subroutine returns.
    pub auto_restore: bool,
}

impl Machine {
    /// M70, M71, M72 or M73. `Ok(true)` when M72 restored a state that differs from the one in
    /// force: rs274 then runs the restoring codes as blocks of their own, read into the place of
    /// the current one, so that the rest of the M72's line (what comes after M70–M73 in the
    /// order of execution: coolant, dwell, G-codes, the motion, a stop) is lost; the caller skips
    /// it. When nothing differs, nothing is run and the line goes on.
    pub(super) fn modal_state(&mut self, code: Code) -> Result<bool, Fault> {
        match code.code {
            70 | 73 => {
                let state = &self.state;
                self.state.modal_stack = ModalStack {
                    saved: Some(SavedModes {
                        metric: state.metric,
                        incremental: state.incremental,
                        ijk_absolute: state.ijk_absolute,
                        plane: state.plane,
                        inverse_time: state.inverse_time,
                        feed_rate: state.feed_rate,
                        speed: state.speed,
                        spindle: state.spindle,
                        mist: state.mist,
                        flood: state.flood,
                        system: state.system,
                        retract_to_old: state.cycle.retract_to_old,
                        tool_offset_on: state.tools.offset_active,
                        g92_on: state.g92_in_force(),
                        blend: state.blend,
                        naive_cam: state.naive_cam,
                        comp: state.comp.code(),
                    }),
                    auto_restore: code.code == 73,
                };
            }
            71 => self.state.modal_stack = ModalStack::default(),
            _ => {
                let Some(saved) = self.state.modal_stack.saved else {
                    return Err(self.code_fault(
                        code,
                        "Cannot restore context from invalid stack frame - missing M70/M73?",
                    ));
                };
                let span = self.span(code.at, code.end);
                return self.restore_modes(saved, span);
            }
        }
        Ok(false)
    }

    /// The return from a subroutine: the state M73 saved at its level, if M71 did not forget
    /// it. Each call level has its own saved state (M70 in a subroutine is forgotten when it
    /// returns; M72 finds only what its own level saved).
    pub(super) fn restore_on_return(&mut self) -> Result<(), Fault> {
        let stack = std::mem::take(&mut self.state.modal_stack);
        if stack.auto_restore
            && let Some(saved) = stack.saved
        {
            // (The line is the return's: the whole of it is shown.)
            self.restore_modes(saved, (0, self.syntax.raw_len.max(1)))?;
        }
        Ok(())
    }

    /// M72 (on `span` of its line): the saved state back, in rs274's order; whether it differed
    /// from the state in force (in what rs274's `gen_settings` and `gen_m_codes` compare).
    /// rs274 writes the feed back as `F%.1f` and the speed as `S%.0f`: both come back rounded
    /// so.
    fn restore_modes(&mut self, saved: SavedModes, span: (usize, usize)) -> Result<bool, Fault> {
        let state = &self.state;
        if saved.comp != state.comp.code() && saved.comp != 400.0 {
            // rs274 would run a G41 or G42 with no D word (or G41.1 with none: an error).
            return Err(Fault::not_supported(
                span.0,
                span.1,
                "M72 or a return under M73 turning cutter compensation back on".to_owned(),
                "rs274 runs G41 or G42 again without their D word",
            ));
        }
        let differs = saved.metric != state.metric
            || saved.incremental != state.incremental
            || saved.ijk_absolute != state.ijk_absolute
            || saved.plane != state.plane
            || saved.inverse_time != state.inverse_time
            || saved.feed_rate != state.feed_rate
            || saved.speed != state.speed
            || saved.spindle != state.spindle
            || saved.mist != state.mist
            || saved.flood != state.flood
            || saved.system != state.system
            || saved.retract_to_old != state.cycle.retract_to_old
            || saved.tool_offset_on != state.tools.offset_active
            || saved.g92_on != state.g92_in_force()
            || saved.blend != state.blend
            || saved.naive_cam != state.naive_cam
            || saved.comp != state.comp.code();
        let rounded = |value: f64, decimals: usize| {
            format!("{value:.decimals$}").parse::<f64>().unwrap_or(value)
        };
        self.set_units(saved.metric);
        // rs274 sets F again only when it differs from the F in force before the feed mode
        // is restored (and G94 zeroes the feed rate).
        let feed_differs = saved.feed_rate != self.state.feed_rate;
        if saved.inverse_time != self.state.inverse_time {
            self.state.inverse_time = saved.inverse_time;
            if !saved.inverse_time {
                self.state.feed_rate = 0.0;
                self.state.feed_mm = 0.0;
            }
        }
        if feed_differs {
            self.state.feed_rate = rounded(saved.feed_rate, 1);
            self.state.feed_mm = self.state.feed_rate * self.state.factor();
        }
        if saved.speed != self.state.speed {
            self.state.speed = rounded(saved.speed, 0);
        }
        self.state.blend = saved.blend;
        self.state.naive_cam = saved.naive_cam;
        if saved.spindle != self.state.spindle {
            self.state.spindle = saved.spindle;
            self.tool_event(saved.spindle);
        }
        self.state.plane = saved.plane;
        if saved.comp != self.state.comp.code() {
            self.cutter_comp_off()?;
        }
        if saved.system != self.state.system {
            self.select_system(saved.system);
        }
        self.state.incremental = saved.incremental;
        self.state.ijk_absolute = saved.ijk_absolute;
        self.state.mist = saved.mist;
        self.state.flood = saved.flood;
        self.state.cycle.retract_to_old = saved.retract_to_old;
        // rs274 saves G43 or G49, not the offset: restoring G43 runs `G43` (the tool in the
        // spindle), and when both are G43 the offset in force stays.
        if saved.tool_offset_on != self.state.tools.offset_active {
            let new = if saved.tool_offset_on { self.spindle_tool_offset() } else { [0.0; 4] };
            self.set_tool_offset(new);
        }
        // G92.2 or G92.3, which rs274 does not run while compensation is on.
        if saved.g92_on != self.state.g92_in_force() && !self.state.comp.on() {
            self.apply_g92(saved.g92_on);
        }
        Ok(differs)
    }
}
