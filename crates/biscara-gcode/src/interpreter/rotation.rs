//! G10 L2 R: a coordinate system rotated about Z, as LinuxCNC's `rs274` and canon do it.
//!
//! The rotation is the system's parameter 5230 (+20 per system) and applies while the system
//! is in force: a point `p` of the program is, on the machine, `rot(p + g92) + origin` in XY
//! (Z and C are not rotated; the tool length offset is added after the rotation). Arcs in the
//! XY plane turn with their centre; an arc in the XZ or YZ plane of a rotated system lies in a
//! tilted plane, which the inter-file (docs/motion.md) cannot describe: it runs as straight moves
//! within 0.001 mm of it ([`Machine::tilted_arc`]). Nothing here
//! runs while no system is rotated: [`State::rotation`] is zero and the plain sums are used.
//!
//! rs274's own bookkeeping is followed where it differs from that geometry: G10 L2 on the
//! system in force moves the current point as if no G92 offset were set.

use std::f64::consts::PI;

use biscara_motion::Feed;

use super::motion::find_turn;
use super::spline::{CHORD_TOLERANCE_MM, MAX_SEGMENTS};
use super::{Machine, State};
use crate::syntax::params::{COORDINATE_SYSTEM, G92_ENABLED, axis_slot, coordinate_system_base};

/// The parameter of a system's rotation, after its nine axes.
const ROTATION_SLOT: usize = 9;

/// `[x, y]` turned by `degrees` about the origin (LinuxCNC's `rotate`).
pub(super) fn rotate([x, y]: [f64; 2], degrees: f64) -> [f64; 2] {
    let t = degrees * PI / 180.0;
    let (sin, cos) = t.sin_cos();
    [x * cos - y * sin, x * sin + y * cos]
}

/// The parameter holding coordinate system `system`'s rotation, degrees.
pub(super) fn rotation_parameter(system: usize) -> usize {
    coordinate_system_base(system) + ROTATION_SLOT
}

impl State {
    /// [`State::absolute`] in a rotated system.
    pub(super) fn absolute_rotated(&self, position: [f64; 4]) -> [f64; 4] {
        let local = self.local(position);
        std::array::from_fn(|axis| {
            self.to_mm(axis, local[axis] + self.origin[axis]) + self.tool_offset_mm[axis]
        })
    }

    /// `position + g92`, turned by the system's rotation (program units).
    fn local(&self, position: [f64; 4]) -> [f64; 4] {
        let mut local: [f64; 4] =
            std::array::from_fn(|axis| position[axis] + self.axis_offset[axis]);
        [local[0], local[1]] = rotate([local[0], local[1]], self.rotation);
        local
    }

    /// The current position as coordinate system `system` (1–9) reads it, in program units
    /// (rs274's `find_current_in_system`, and with `with_tool` its
    /// `find_current_in_system_without_tlo`, which adds the tool length offset in force): the
    /// point turned into the machine's frame by the system in force, then read in `system`'s
    /// origin and rotation, less the G92 offset when one is in force.
    pub(super) fn position_in_system(&self, system: usize, with_tool: bool) -> [f64; 4] {
        let param = |index: usize, axis: usize| self.mm_to_program(axis, self.params.get(index));
        let mut at = self.local(self.current);
        let base = coordinate_system_base(system);
        for (axis, at) in at.iter_mut().enumerate() {
            let tool = if with_tool { self.tool_offset[axis] } else { 0.0 };
            *at += self.origin[axis] + tool - param(base + axis_slot(axis), axis);
        }
        [at[0], at[1]] = rotate([at[0], at[1]], -self.params.get(rotation_parameter(system)));
        if self.g92_in_force() {
            for (axis, at) in at.iter_mut().enumerate() {
                *at -= param(G92_ENABLED + 1 + axis_slot(axis), axis);
            }
        }
        at
    }

    /// A shift of the machine (a change of tool length offset) as seen in the program's
    /// coordinates: turned back by the rotation in XY.
    pub(super) fn program_shift(&self, shift: [f64; 4]) -> [f64; 4] {
        if self.rotation == 0.0 {
            return shift;
        }
        let [x, y] = rotate([shift[0], shift[1]], -self.rotation);
        [x, y, shift[2], shift[3]]
    }

    /// The machine position (program units, with the tool length offset) of `position`.
    pub(super) fn machine(&self, position: [f64; 4]) -> [f64; 4] {
        if self.rotation == 0.0 {
            return std::array::from_fn(|axis| {
                position[axis] + self.origin[axis] + self.axis_offset[axis] + self.tool_offset[axis]
            });
        }
        let local = self.local(position);
        std::array::from_fn(|axis| local[axis] + self.origin[axis] + self.tool_offset[axis])
    }

    /// The program position of machine position `machine` (program units, with the tool
    /// length offset), the inverse of [`State::machine`].
    pub(super) fn program_of(&self, machine: [f64; 4]) -> [f64; 4] {
        if self.rotation == 0.0 {
            return std::array::from_fn(|axis| {
                machine[axis] - self.origin[axis] - self.axis_offset[axis] - self.tool_offset[axis]
            });
        }
        let mut local: [f64; 4] =
            std::array::from_fn(|axis| machine[axis] - self.origin[axis] - self.tool_offset[axis]);
        [local[0], local[1]] = rotate([local[0], local[1]], -self.rotation);
        std::array::from_fn(|axis| local[axis] - self.axis_offset[axis])
    }
}

impl Machine {
    /// Makes `system` the one in force (its origin and rotation from the parameters), keeping
    /// the machine position. `g10`: rs274's G10 L2 on the system in force, which leaves the
    /// G92 offset out of the rotations.
    pub(super) fn change_system(&mut self, system: usize, g10: bool) {
        let base = coordinate_system_base(system);
        let origin: [f64; 4] = std::array::from_fn(|axis| {
            self.state.mm_to_program(axis, self.state.params.get(base + axis_slot(axis)))
        });
        let rotation = self.state.params.get(rotation_parameter(system));
        let state = &mut self.state;
        if rotation == 0.0 && state.rotation == 0.0 {
            for (axis, origin) in origin.into_iter().enumerate() {
                state.current[axis] += state.origin[axis] - origin;
                state.origin[axis] = origin;
            }
        } else {
            let offset = if g10 { [0.0; 2] } else { [state.axis_offset[0], state.axis_offset[1]] };
            let turned = rotate(
                [state.current[0] + offset[0], state.current[1] + offset[1]],
                state.rotation,
            );
            let [x, y] = rotate(
                [turned[0] + state.origin[0] - origin[0], turned[1] + state.origin[1] - origin[1]],
                -rotation,
            );
            state.current[0] = x - offset[0];
            state.current[1] = y - offset[1];
            for (axis, origin) in origin.into_iter().enumerate() {
                if axis >= 2 {
                    state.current[axis] += state.origin[axis] - origin;
                }
                state.origin[axis] = origin;
            }
            state.rotation = rotation;
        }
        state.system = system;
        state.params.set(COORDINATE_SYSTEM, system as f64);
    }

    /// G10 L20's XY origin for `system` when a rotation is involved (`None`: the plain sums
    /// do, or no X or Y word), as rs274's `convert_setup` computes it: the current point read
    /// in `system` ([`State::position_in_system`]) and the wanted one (a missing X or Y keeps
    /// its value) are both turned by `system`'s rotation, and the origin moves by their
    /// difference. In a rotated system both X and Y change, whichever was given.
    pub(super) fn rotated_l20_origin(&self, system: usize) -> Option<[f64; 2]> {
        let state = &self.state;
        let turn = state.params.get(rotation_parameter(system));
        let given =
            [b'x', b'y'].map(|letter| self.syntax.block.word(letter).map(|word| word.value));
        if (state.rotation == 0.0 && turn == 0.0) || given.iter().all(Option::is_none) {
            return None;
        }
        let at = state.position_in_system(system, false);
        let old = rotate([at[0], at[1]], turn);
        let new = rotate([given[0].unwrap_or(at[0]), given[1].unwrap_or(at[1])], turn);
        let base = coordinate_system_base(system);
        Some(std::array::from_fn(|axis| {
            old[axis] + state.mm_to_program(axis, state.params.get(base + axis_slot(axis)))
                - new[axis]
        }))
    }

    /// G53's X and Y in a rotated system (`None` without an X or Y word): the machine
    /// position of the current point with the given axes replaced, back in the program's
    /// coordinates.
    pub(super) fn rotated_g53_ends(&self) -> Option<[f64; 2]> {
        let given =
            [b'x', b'y'].map(|letter| self.syntax.block.word(letter).map(|word| word.value));
        if given.iter().all(Option::is_none) {
            return None;
        }
        let mut machine = self.state.machine(self.state.current);
        for (axis, value) in given.into_iter().enumerate() {
            if let Some(value) = value {
                machine[axis] = value;
            }
        }
        let program = self.state.program_of(machine);
        Some([program[0], program[1]])
    }

    /// An arc in the XZ or YZ plane of a rotated system, from `start` to `end` (program
    /// coordinates) about `center` (the plane's two axes), `turns` times round: LinuxCNC's canon
    /// turns the arc's basis vectors with the system, so the arc lies in a tilted plane, which
    /// the inter-file (docs/motion.md) cannot describe. It runs as straight moves within
    /// [`CHORD_TOLERANCE_MM`] of it: equal steps of the angle, the radius going from the start's
    /// to the end's (LinuxCNC's arcs may end a little off their radius), the normal axis and C
    /// in proportion (a helix's chords leave it only in the plane). `Err` with the message when
    /// it would take more than [`MAX_SEGMENTS`] moves.
    pub(super) fn tilted_arc(
        &mut self,
        [start, end]: [[f64; 4]; 2],
        center: [f64; 2],
        clockwise: bool,
        turns: u32,
        feed: Feed,
    ) -> Result<(), String> {
        use std::f64::consts::TAU;
        let [first, second, normal] = self.state.plane.axes();
        let radius = |point: [f64; 4]| (point[first] - center[0]).hypot(point[second] - center[1]);
        let in_plane = |point: [f64; 4]| [point[first], point[second]];
        let (radius0, radius1) = (radius(start), radius(end));
        let from = (start[second] - center[1]).atan2(start[first] - center[0]);
        // At least one part of a turn, then the whole turns (turns ≤ 1,000,000).
        let turn = if clockwise { -(turns as i32) } else { turns as i32 };
        let sweep = find_turn(in_plane(start), center, turn, in_plane(end));
        // A chord of angle φ on radius r stays r·(1 − cos(φ/2)) from the arc.
        let tolerance = CHORD_TOLERANCE_MM / self.state.factor();
        let largest = radius0.max(radius1);
        let step =
            if largest <= tolerance { TAU } else { 2.0 * (1.0 - tolerance / largest).acos() };
        let count = (sweep.abs() / step).ceil().max(1.0);
        if count > MAX_SEGMENTS as f64 {
            return Err(format!(
                "Arc too large in a rotated coordinate system: its plane is tilted, so it runs as \
                 straight moves within {CHORD_TOLERANCE_MM} mm of it, and more than \
                 {MAX_SEGMENTS} would be needed; split it into shorter arcs"
            ));
        }
        let count = count as usize;
        for index in 1..count {
            let t = index as f64 / count as f64;
            let (turned, r) = (from + sweep * t, radius0 + (radius1 - radius0) * t);
            let mut point = start;
            point[first] = center[0] + r * turned.cos();
            point[second] = center[1] + r * turned.sin();
            point[normal] = start[normal] + (end[normal] - start[normal]) * t;
            point[3] = start[3] + (end[3] - start[3]) * t;
            self.move_to(point, Some(feed));
        }
        self.move_to(end, Some(feed));
        Ok(())
    }
}
