//! G10 L2 R: a coordinate system rotated about Z, as LinuxCNC's `rs274` and canon do it.
//!
//! The rotation is the system's parameter 5230 (+20 per system) and applies while the system
//! is in force: a point `p` of the program is, on the machine, `rot(p + g92) + origin` in XY
//! (Z and C are not rotated; the tool length offset is added after the rotation). Arcs in the
//! XY plane turn with their centre; an arc in the XZ or YZ plane of a rotated system would lie
//! in a tilted plane, which the inter-file (SPEC §5) cannot describe: refused. Nothing here
//! runs while no system is rotated: [`State::rotation`] is zero and the plain sums are used.
//!
//! rs274's own bookkeeping is followed where it differs from that geometry: G10 L2 on the
//! system in force moves the current point as if no G92 offset were set.

use std::f64::consts::PI;
use std::io::BufRead;

use biscara_motion::Plane;

use super::{Interpreter, State};
use crate::lexer::Fault;
use crate::params::{COORDINATE_SYSTEM, axis_slot, coordinate_system_base};
use crate::parser::Code;

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
    pub(super) fn local(&self, position: [f64; 4]) -> [f64; 4] {
        let mut local: [f64; 4] =
            std::array::from_fn(|axis| position[axis] + self.axis_offset[axis]);
        [local[0], local[1]] = rotate([local[0], local[1]], self.rotation);
        local
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

impl<R: BufRead> Interpreter<R> {
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
    /// do, or no X or Y word). The point is placed on the machine as rs274 does for G10 L20,
    /// `rot(current) + origin` (without G92). The system in force, rotated: its origin
    /// becomes `origin + rot(current − given)` (a missing X or Y keeps its value, both
    /// change). Another system, not rotated: the given axes' origins become that point's
    /// coordinates less the given values. Another system, rotated: refused (rs274's result
    /// there has not been worked out).
    pub(super) fn rotated_l20_origin(
        &self,
        code: Code,
        system: usize,
    ) -> Result<Option<[f64; 2]>, Fault> {
        let state = &self.state;
        let target_rotation = state.params.get(rotation_parameter(system));
        let given = [b'x', b'y'].map(|letter| self.block.word(letter).map(|word| word.value));
        if (state.rotation == 0.0 && target_rotation == 0.0) || given.iter().all(Option::is_none) {
            return Ok(None);
        }
        let target = [given[0].unwrap_or(state.current[0]), given[1].unwrap_or(state.current[1])];
        if system == state.system {
            let [dx, dy] = rotate(
                [state.current[0] - target[0], state.current[1] - target[1]],
                state.rotation,
            );
            return Ok(Some([state.origin[0] + dx, state.origin[1] + dy]));
        }
        if target_rotation != 0.0 {
            let (first, last) = self.span(code.at, code.end);
            return Err(Fault::not_supported(
                first,
                last,
                "G10 L20 of a rotated coordinate system other than the one in force",
                "rs274's result there has not been worked out",
            ));
        }
        let turned = rotate([state.current[0], state.current[1]], state.rotation);
        let base = coordinate_system_base(system);
        Ok(Some(std::array::from_fn(|axis| match given[axis] {
            Some(value) => turned[axis] + state.origin[axis] - value,
            None => state.mm_to_program(axis, state.params.get(base + axis_slot(axis))),
        })))
    }

    /// G53's X and Y in a rotated system (`None` without an X or Y word): the machine
    /// position of the current point with the given axes replaced, back in the program's
    /// coordinates.
    pub(super) fn rotated_g53_ends(&self) -> Option<[f64; 2]> {
        let given = [b'x', b'y'].map(|letter| self.block.word(letter).map(|word| word.value));
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

    /// An arc outside the XY plane of a rotated system.
    pub(super) fn check_rotated_arc(&self, at: (usize, usize)) -> Result<(), Fault> {
        if self.state.rotation == 0.0 || self.state.plane == Plane::Xy {
            return Ok(());
        }
        let (first, last) = self.span(at.0, at.1);
        Err(Fault::not_supported(
            first,
            last,
            "an XZ or YZ arc in a rotated coordinate system",
            "its plane is tilted, which the inter-file cannot describe",
        ))
    }
}
