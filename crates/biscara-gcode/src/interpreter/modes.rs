//! Modes and offsets: path control, units, coordinate systems, G10 L2/L20, G92 and G52.

use super::*;

impl Machine {
    /// G61, G61.1 (exact stop) and G64 P… Q… (blending within P of the corners, in the program's
    /// length unit, kept in millimetres; no P, or a negative one, is LinuxCNC's tolerance 0: no
    /// tolerance given).
    ///
    /// Q is LinuxCNC's naive-CAM tolerance: its motion layer (not its interpreter) may merge
    /// nearly collinear feed moves into one when every point left out lies within Q of it. The
    /// interpreter keeps every move and marks the straight feed moves under G64 with a positive
    /// Q ([`Motion::naive_cam`], millimetres); the merging is `biscara-blend`'s `NaiveCam`, before
    /// the blends. (rs274 reads Q the same way: its canonical calls carry only P.)
    pub(super) fn set_path_control(&mut self, code: Code) -> Result<(), Fault> {
        if code.code != 640 {
            self.state.blend = None;
            self.state.naive_cam = None;
            return Ok(());
        }
        let scale = if self.state.metric { 1.0 } else { MM_PER_INCH };
        let p = self.syntax.block.word(b'p').map_or(0.0, |p| p.value.max(0.0));
        self.state.blend = Some(p * scale);
        let q = self.syntax.block.word(b'q').map_or(0.0, |q| q.value);
        self.state.naive_cam = (q > 0.0).then_some(q * scale);
        Ok(())
    }

    /// The naive-CAM tolerance a motion carries: G64 Q on a straight feed move under G64.
    pub(super) fn naive_cam(&self, kind: &MotionKind, blend: Option<f64>) -> Option<f64> {
        let straight = matches!(kind, MotionKind::Linear { .. });
        self.state.naive_cam.filter(|_| straight && blend.is_some())
    }

    pub(super) fn set_units(&mut self, metric: bool) {
        if self.state.metric == metric {
            return;
        }
        let scale = if metric { MM_PER_INCH } else { 1.0 / MM_PER_INCH };
        self.state.comp.scale(scale);
        for axis in 0..3 {
            self.state.current[axis] *= scale;
            self.state.origin[axis] *= scale;
            self.state.axis_offset[axis] *= scale;
            // rs274 keeps the tool length offset's number: it changes with the units.
        }
        self.state.metric = metric;
    }

    pub(super) fn select_system(&mut self, system: usize) {
        self.change_system(system, false);
    }

    /// G10 L2 and L20.
    pub(super) fn set_coordinate_data(&mut self, code: Code) -> Result<(), Fault> {
        let Some(l) = self.syntax.block.word(b'l') else {
            return Err(
                self.code_fault(code, "Line with G10 does not have L0, L1, L10, L11, L2, or L20")
            );
        };
        let l_value = l.value as i64;
        match l_value {
            2 | 20 => {}
            1 | 10 | 11 => return self.set_tool_data(code, l_value),
            0 => {
                // Reloading the tool table: rs274 keeps the table as the program changed it,
                // and refuses while a tool is in the spindle.
                let loaded = self.state.tools.spindle.tool;
                if loaded > 0 {
                    return Err(self.code_fault(
                        code,
                        format!("G10 L0 not allowed with loaded tool <{loaded}>"),
                    ));
                }
                return Ok(());
            }
            _ => {
                return Err(
                    self.word_fault(l, "Line with G10 does not have L0, L1, L10, L11, L2, or L20")
                );
            }
        }
        let system = match self.syntax.block.word(b'p') {
            Some(p) if (0.0..=9.0).contains(&p.value) && p.value.fract() == 0.0 => p.value as usize,
            // Grbl 1.1 wants P or L (`gc_execute_line`: "P/L word missing"), and its P defaults
            // to 0: the system in force (an OpenBuilds plasma post's `G10 L20 Z-2`).
            None if self.hooks.rules.g10_p_optional => 0,
            _ => {
                return Err(self
                    .code_fault(code, format!("P value out of range (0-9) with G10 L{l_value}")));
            }
        };
        if system == 0 || system == self.state.system {
            self.refuse_with_comp(
                (code.at, code.end),
                "Cannot change the active coordinate system with cutter radius compensation on",
            )?;
        }
        let r = self.syntax.block.word(b'r');
        if let Some(r) = r
            && l_value == 20
        {
            return Err(self.word_fault(r, "R not allowed in G10 L20"));
        }
        let system = if system == 0 { self.state.system } else { system };
        let base = coordinate_system_base(system);
        let rotated_l20 = if l_value == 20 { self.rotated_l20_origin(system) } else { None };
        for (axis, &letter) in AXES.iter().enumerate() {
            let Some(word) = self.syntax.block.word(letter) else { continue };
            let origin = match rotated_l20 {
                Some(xy) if axis < 2 => xy[axis],
                _ if l_value == 2 => word.value,
                _ => self.state.current[axis] + self.state.origin[axis] - word.value,
            };
            let value = self.state.to_mm(axis, origin);
            self.state.params.set(base + axis_slot(axis), value);
        }
        if let Some(xy) = rotated_l20 {
            // In a rotated system both X and Y change, whichever was given.
            for (axis, value) in xy.into_iter().enumerate() {
                let value = self.state.to_mm(axis, value);
                self.state.params.set(base + axis_slot(axis), value);
            }
        }
        if let Some(r) = r {
            self.state.params.set(rotation::rotation_parameter(system), r.value);
        }
        if system == self.state.system {
            self.change_system(system, true);
        }
        Ok(())
    }

    /// G92: offsets that make the current point have the given coordinates.
    pub(super) fn set_axis_offsets(&mut self, code: Code) -> Result<(), Fault> {
        if AXES.iter().all(|&letter| self.syntax.block.word(letter).is_none()) {
            return Err(self.code_fault(code, "All axes missing with g52 or g92"));
        }
        let mut offsets = self.state.axis_offset;
        for (axis, &letter) in AXES.iter().enumerate() {
            if let Some(word) = self.syntax.block.word(letter) {
                self.state.zeroed_at_start[axis] |= !self.output.moved;
                offsets[axis] =
                    self.state.current[axis] + self.state.axis_offset[axis] - word.value;
            }
        }
        self.apply_axis_offsets(offsets);
        for (axis, offset) in offsets.into_iter().enumerate() {
            let value = self.state.to_mm(axis, offset);
            self.state.params.set(G92_OFFSET + axis_slot(axis), value);
        }
        self.state.params.set(G92_ENABLED, 1.0);
        Ok(())
    }

    /// G52: local offsets, kept in G92's offsets (as LinuxCNC does): the given axes' offsets
    /// become the given values.
    pub(super) fn set_local_offsets(&mut self) {
        let mut offsets = self.state.axis_offset;
        for (axis, &letter) in AXES.iter().enumerate() {
            if let Some(word) = self.syntax.block.word(letter) {
                offsets[axis] = word.value;
            }
        }
        self.apply_axis_offsets(offsets);
        for (axis, offset) in offsets.into_iter().enumerate() {
            let value = self.state.to_mm(axis, offset);
            self.state.params.set(G92_OFFSET + axis_slot(axis), value);
        }
        self.state.params.set(G92_ENABLED, 1.0);
    }

    /// G92.3 (`on`: the offsets of parameters 5211–5219 in force again) or G92.2 (none in
    /// force, the parameters kept); 5210 says which, as in rs274.
    pub(super) fn apply_g92(&mut self, on: bool) {
        let offsets = std::array::from_fn(|axis| {
            let value = if on { self.state.params.get(G92_OFFSET + axis_slot(axis)) } else { 0.0 };
            self.state.mm_to_program(axis, value)
        });
        self.apply_axis_offsets(offsets);
        self.state.params.set(G92_ENABLED, if on { 1.0 } else { 0.0 });
    }

    pub(super) fn apply_axis_offsets(&mut self, offsets: [f64; 4]) {
        for (axis, offset) in offsets.into_iter().enumerate() {
            self.state.current[axis] += self.state.axis_offset[axis] - offset;
            self.state.axis_offset[axis] = offset;
        }
    }
}
