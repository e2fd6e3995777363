//! Tools: T, M6, M61, the tool length offset (G43, G43.1, G43.2, G49), G10 L1/L10/L11 and the
//! tool parameters (5400–5413, `#<_current_tool>`, …), as LinuxCNC's standalone `rs274` does
//! them (docs/gcode.md tier 3).
//!
//! The table is LinuxCNC's `.tbl` ([`ToolTable`], millimetres). Without one, every tool exists
//! with zero offsets and diameter, and [`Interpreter::tools_without_table`] says whether the
//! program used them. The tool in the spindle is a copy of its table entry (LinuxCNC's pocket
//! 0), taken by M6; as in `rs274`, M61 changes the current pocket but not that copy, and a
//! G10 L1 of the tool in the current pocket updates it.

use super::rotation::{rotate, rotation_parameter};
use super::{AXES, Machine};
use crate::syntax::lexer::Fault;
use crate::syntax::params::{G92_ENABLED, axis_slot};
use crate::syntax::parser::Code;
use crate::tool_table::{ToolEntry, ToolTable};

/// First of the current tool's parameters: 5400 tool, 5401–5409 offsets (x y z a b c u v w),
/// 5410 diameter, 5411 front angle, 5412 back angle, 5413 orientation.
const TOOL_PARAMETERS: usize = 5400;

/// The tools' state.
#[derive(Debug, Clone)]
pub(super) struct Tools {
    /// The table, changed by G10 L1/L10/L11.
    pub table: ToolTable,
    /// Whether a table was given (without one, every tool exists with zero offsets).
    pub has_table: bool,
    /// The tool in the spindle (LinuxCNC's pocket 0).
    pub spindle: ToolEntry,
    /// The pocket of the tool in the spindle (`#<_current_pocket>`).
    pub current_pocket: f64,
    /// The pocket of the selected tool (`#<_selected_pocket>`; −1 before any T).
    pub selected_pocket: f64,
    /// The tool selected by T (`#<_selected_tool>`).
    pub selected_tool: f64,
    /// Whether a tool length offset other than zero is in force (`#<_tool_offset>`).
    pub offset_active: bool,
    /// Whether the program used a tool's offsets or diameter while there was no table.
    pub used_without_table: bool,
    /// The tool in the spindle before an M61 of this block: rs274 puts M61's tool in pocket 0
    /// for the rest of the block (a G43 there takes its offsets) and takes pocket 0 back from
    /// its canon, which M61 does not change, as it reads the next line.
    pub before_m61: Option<ToolEntry>,
}

impl Tools {
    pub(super) fn new(table: Option<&ToolTable>) -> Tools {
        Tools {
            table: table.cloned().unwrap_or_default(),
            has_table: table.is_some(),
            spindle: ToolEntry::default(),
            current_pocket: 1.0,
            selected_pocket: -1.0,
            selected_tool: 0.0,
            offset_active: false,
            used_without_table: false,
            before_m61: None,
        }
    }

    /// Tool `tool`'s entry: the table's, or (without a table) zero offsets; `None` when a
    /// table is given and lacks it.
    fn entry(&self, tool: u32) -> Option<ToolEntry> {
        match self.table.get(tool) {
            Some(entry) => Some(*entry),
            None if !self.has_table => {
                Some(ToolEntry { tool, pocket: tool, ..ToolEntry::default() })
            }
            None => None,
        }
    }

    /// Parameters 5400–5413 from the tool in the spindle (values in mm and degrees).
    pub(super) fn publish(&self, params: &mut crate::syntax::params::Params) {
        let spindle = &self.spindle;
        params.set(TOOL_PARAMETERS, f64::from(spindle.tool));
        for axis in 0..4 {
            params.set(TOOL_PARAMETERS + 1 + axis_slot(axis), spindle.offset[axis]);
        }
        params.set(TOOL_PARAMETERS + 10, spindle.diameter);
        params.set(TOOL_PARAMETERS + 11, spindle.front_angle);
        params.set(TOOL_PARAMETERS + 12, spindle.back_angle);
        params.set(TOOL_PARAMETERS + 13, f64::from(spindle.orientation));
    }
}

/// LinuxCNC's message for a tool the table lacks.
fn not_found(tool: impl std::fmt::Display) -> String {
    format!("Requested tool {tool} not found in the tool table")
}

impl Machine {
    fn note_no_table(&mut self) {
        if !self.state.tools.has_table {
            self.state.tools.used_without_table = true;
        }
    }

    /// T: selects a tool (LinuxCNC's `convert_tool_select`).
    pub(super) fn select_tool(&mut self) -> Result<(), Fault> {
        let Some(t) = self.syntax.block.word(b't') else { return Ok(()) };
        // Not negative: the reader refuses that; an integer: the reader rounds it.
        let tool = t.value as u32;
        let spindle = self.state.tools.spindle;
        let pocket = if tool == 0 {
            // rs274: the pocket of the tool in the spindle.
            if spindle.tool != 0 {
                f64::from(spindle.pocket)
            } else {
                self.state.tools.current_pocket
            }
        } else {
            match self.state.tools.entry(tool) {
                Some(entry) => f64::from(entry.pocket),
                None => return Err(self.word_fault(t, not_found(tool))),
            }
        };
        self.state.tools.selected_tool = t.value;
        self.state.tools.selected_pocket = pocket;
        Ok(())
    }

    /// M6: the selected tool goes into the spindle (the offset in force is not changed). As
    /// in rs274, the current point is then taken back from the last move: a tool length offset
    /// set since that move no longer shifts it.
    pub(super) fn change_tool(&mut self) {
        self.state.resync = true;
        let tools = &mut self.state.tools;
        let tool = tools.selected_tool as u32;
        if tool != 0
            && let Some(entry) = tools.entry(tool)
        {
            tools.spindle = entry;
        }
        if tools.selected_pocket >= 0.0 {
            tools.current_pocket = tools.selected_pocket;
        }
        self.state.tools.publish(&mut self.state.params);
    }

    /// rs274 after M6 and M61, as it reads the next line: the current point taken back from
    /// the last move (so a G43 in the tool change's own block moves no current point).
    pub(super) fn resync_position(&mut self) {
        self.state.resync = false;
        if let Some(spindle) = self.state.tools.before_m61.take() {
            self.state.tools.spindle = spindle;
        }
        for axis in 0..4 {
            self.state.current[axis] -= self.state.tool_shift[axis];
        }
        self.state.tool_shift = [0.0; 4];
    }

    /// M61 Q: says which tool is in the spindle. As in `rs274`, the current pocket changes,
    /// the tool's entry stands in the spindle for the rest of the block only
    /// ([`Tools::before_m61`]), and the current point is taken back from the last move as the
    /// next line is read, as after M6.
    pub(super) fn set_current_tool(&mut self, code: Code) -> Result<(), Fault> {
        let q = self.syntax.block.word(b'q').filter(|q| q.value >= 0.0);
        let Some(q) = q else {
            return Err(
                self.code_fault(code, "Need non-negative Q-word to specify tool number with M61")
            );
        };
        let tool = q.value.round() as u32;
        let Some(entry) = self.state.tools.entry(tool) else {
            return Err(self.word_fault(q, not_found(tool)));
        };
        self.note_no_table();
        self.state.resync = true;
        let tools = &mut self.state.tools;
        tools.before_m61.get_or_insert(tools.spindle);
        tools.spindle = entry;
        self.state.tools.current_pocket = f64::from(entry.pocket);
        Ok(())
    }

    /// The tool an H word names (`find_tool_pocket`): H0 is pocket 0, the spindle's tool; a
    /// positive H a tool of the table; `None` when there is none.
    fn h_tool(&self, h: f64) -> Option<ToolEntry> {
        if h == 0.0 {
            Some(self.state.tools.spindle)
        } else {
            (h > 0.0).then(|| self.state.tools.entry(h as u32)).flatten()
        }
    }

    /// G43, G43.1, G43.2 and G49 (`convert_tool_length_offset`).
    pub(super) fn tool_length_offset(&mut self, code: Code) -> Result<(), Fault> {
        let h = self.syntax.block.word(b'h');
        let axes: [Option<f64>; 4] =
            std::array::from_fn(|axis| self.syntax.block.word(AXES[axis]).map(|word| word.value));
        let any_axis = axes.iter().any(Option::is_some);
        let old = self.state.tool_offset;
        let new = match code.code {
            490 => [0.0; 4],
            430 => match h {
                None => self.spindle_tool_offset(),
                Some(h) => match self.h_tool(h.value) {
                    Some(entry) => {
                        self.note_no_table();
                        self.state.offsets_in_program_units(&entry)
                    }
                    None => return Err(self.word_fault(h, not_found(h.value))),
                },
            },
            431 => {
                let mut offset = old;
                for (axis, value) in axes.iter().enumerate() {
                    if let Some(value) = value {
                        offset[axis] = *value;
                    }
                }
                offset
            }
            _ => {
                if h.is_some() && any_axis {
                    return Err(self.code_fault(code, "G43.2: Can not have both H and axis words"));
                }
                let mut offset = old;
                if let Some(h) = h {
                    let Some(entry) = self.h_tool(h.value) else {
                        return Err(self.word_fault(h, not_found(h.value)));
                    };
                    self.note_no_table();
                    let add = self.state.offsets_in_program_units(&entry);
                    for axis in 0..4 {
                        offset[axis] += add[axis];
                    }
                } else if any_axis {
                    // LinuxCNC 2.9's rs274 takes the missing H for H-1.
                    return Err(self.code_fault(
                        code,
                        "Requested tool -1 not found in the tool table (G43.2 with axis words \
                         needs an H word in LinuxCNC 2.9)",
                    ));
                } else {
                    return Err(
                        self.code_fault(code, "G43.2: No axes specified and H word missing")
                    );
                }
                offset
            }
        };
        self.set_tool_offset(new);
        Ok(())
    }

    /// The tool length offset `new` (program units) in force: the current point moves by the
    /// change, as the machine keeps the tool's tip where it was.
    pub(super) fn set_tool_offset(&mut self, new: [f64; 4]) {
        let old = self.state.tool_offset;
        let shift = self.state.program_shift(std::array::from_fn(|axis| old[axis] - new[axis]));
        for (axis, shift) in shift.into_iter().enumerate() {
            self.state.current[axis] += shift;
            self.state.tool_shift[axis] += shift;
        }
        self.state.tool_offset = new;
        self.state.tool_offset_mm = std::array::from_fn(|axis| self.state.to_mm(axis, new[axis]));
        // `#<_tool_offset>` in rs274: whether any offset is not zero.
        self.state.tools.offset_active = new.iter().any(|&value| value != 0.0);
    }

    /// G43 with no H: the offsets of the tool in the spindle, in program units.
    pub(super) fn spindle_tool_offset(&mut self) -> [f64; 4] {
        self.note_no_table();
        self.state.offsets_in_program_units(&self.state.tools.spindle)
    }

    /// G10 L10's and L11's offsets of tool `entry`, as rs274's `convert_setup_tool` computes
    /// them: the offsets that make the current position read the given coordinates in the
    /// system in force (L10) or in G59.3 (L11, G92 left out). X and Y are turned by that
    /// system's rotation into the machine's frame, where tool offsets apply; an axis of the
    /// two not given keeps the entry's component along it.
    fn offsets_from_position(&self, entry: &mut ToolEntry, l: i64) {
        let state = &self.state;
        let system = if l == 11 { 9 } else { state.system };
        let mut at = state.position_in_system(system, true);
        if l == 11 && state.g92_in_force() {
            for (axis, at) in at.iter_mut().enumerate() {
                *at +=
                    state.mm_to_program(axis, state.params.get(G92_ENABLED + 1 + axis_slot(axis)));
            }
        }
        let turn = state.params.get(rotation_parameter(system));
        let given =
            [b'x', b'y'].map(|letter| self.syntax.block.word(letter).map(|word| word.value));
        let old = [0, 1].map(|axis| state.mm_to_program(axis, entry.offset[axis]));
        let xy = match given {
            [None, None] => None,
            [Some(x), Some(y)] => Some(rotate([at[0] - x, at[1] - y], turn)),
            [x, y] => {
                // Only one: keep the old offset's component along the other (turned) axis.
                let mut kept = rotate(old, -turn);
                let mut new = [0.0; 2];
                if let Some(x) = x {
                    kept[0] = 0.0;
                    new[0] = at[0] - x;
                }
                if let Some(y) = y {
                    kept[1] = 0.0;
                    new[1] = at[1] - y;
                }
                let [kept, new] = [rotate(kept, turn), rotate(new, turn)];
                Some([new[0] + kept[0], new[1] + kept[1]])
            }
        };
        if let Some(xy) = xy {
            for (axis, value) in xy.into_iter().enumerate() {
                entry.offset[axis] = state.to_mm(axis, value);
            }
        }
        for axis in [2, 3] {
            if let Some(word) = self.syntax.block.word(AXES[axis]) {
                entry.offset[axis] = state.to_mm(axis, at[axis] - word.value);
            }
        }
    }

    /// G10 L1, L10 and L11: writes tool P's entry (`convert_setup_tool`).
    pub(super) fn set_tool_data(&mut self, code: Code, l: i64) -> Result<(), Fault> {
        let p = self.syntax.block.word(b'p').filter(|p| p.value > 0.0);
        let Some(p) = p else {
            return Err(self.code_fault(code, format!("P value out of range with G10 L{l}")));
        };
        let tool = p.value.round() as u32;
        let Some(mut entry) = self.state.tools.entry(tool) else {
            return Err(self.word_fault(p, not_found(tool)));
        };
        let words = [b'x', b'y', b'z', b'c', b'r', b'i', b'j', b'q'];
        if words.iter().all(|&letter| self.syntax.block.word(letter).is_none()) {
            return Err(self.code_fault(code, "G10 L1 without offsets has no effect"));
        }
        self.note_no_table();
        if l == 1 {
            for (axis, &letter) in AXES.iter().enumerate() {
                if let Some(word) = self.syntax.block.word(letter) {
                    entry.offset[axis] = self.state.to_mm(axis, word.value);
                }
            }
        } else {
            self.offsets_from_position(&mut entry, l);
        }
        if let Some(r) = self.syntax.block.word(b'r') {
            entry.diameter = 2.0 * self.state.to_mm(0, r.value);
        }
        if let Some(i) = self.syntax.block.word(b'i') {
            entry.front_angle = i.value;
        }
        if let Some(j) = self.syntax.block.word(b'j') {
            entry.back_angle = j.value;
        }
        if let Some(q) = self.syntax.block.word(b'q') {
            entry.orientation = q.value as i32;
        }
        let tools = &mut self.state.tools;
        tools.table.insert(entry);
        if f64::from(entry.pocket) == tools.current_pocket {
            tools.spindle = entry;
        }
        self.state.tools.publish(&mut self.state.params);
        Ok(())
    }
}
