//! Executing one block in LinuxCNC's order of execution (`execute_block`).

use super::*;

/// What the checks of a block found, for its execution.
#[derive(Debug, Clone, Copy)]
pub(super) struct Plan {
    /// Its group 1 code (G0–G3, G80, cycles, …).
    motion_code: Option<Code>,
    /// Its group 0 code (G4, G10, G28, G53, G92, …).
    group0: Option<Code>,
    /// The motion it makes: its own, or the modal one when it has axis words.
    motion_to_be: Option<u16>,
}

impl Machine {
    /// Checks the block just read (not empty) and stores its parameter settings: LinuxCNC's
    /// order of execution up to its comment.
    pub(super) fn execute_settings(&mut self) -> Result<Plan, Fault> {
        self.check_support()?;
        if self.syntax.block.extra.is_some() {
            self.check_polar_words()?;
        }
        let plan = self.plan_motion()?;
        self.check_group_zero()?;
        if let Some(zero) = plan.group0.filter(|zero| zero.code == 530) {
            if !matches!(plan.motion_to_be, Some(0 | 10)) {
                return Err(self.code_fault(zero, "Must use g0 or g1 with g53"));
            }
            let incremental = match self.syntax.block.g[3] {
                Some(code) => code.code == 910,
                None => self.state.incremental,
            };
            if incremental {
                return Err(self.code_fault(zero, "Cannot use g53 incremental"));
            }
        }
        self.check_other_words(plan.motion_to_be)?;
        self.store_parameters()?;
        Ok(plan)
    }

    /// The motion the block makes, checked against its axis words (`enhance_block`,
    /// `check_g_codes`).
    fn plan_motion(&self) -> Result<Plan, Fault> {
        let motion_code = self.syntax.block.g[1];
        let group0 = self.syntax.block.g[0];
        let axis_words = AXES.iter().any(|&letter| self.syntax.block.word(letter).is_some())
            || self.syntax.block.polar();
        // rs274 checks the axis words of a motion other than G0–G3 first of all
        // (`enhance_block`).
        if let Some(code) = motion_code
            && !matches!(code.code, 0 | 10 | 20 | 30 | 800)
            && !axis_words
        {
            return Err(self.code_fault(code, "All axes missing with motion code"));
        }
        let uses_axes = |code: u16| matches!(code, 100 | 280 | 300 | 520 | 920);
        // check_g_codes / check_other_codes
        if let (Some(zero), Some(_)) = (group0, motion_code)
            && uses_axes(zero.code)
        {
            return Err(self.code_fault(zero, "Cannot use two g codes that both use axis values"));
        }
        // G43.1 and G43.2 use the axis words too (without making the modal motion move).
        let group0_uses_axes = group0.is_some_and(|zero| uses_axes(zero.code))
            || self.syntax.block.g[8].is_some_and(|code| matches!(code.code, 431 | 432));
        let modal_motion = match motion_code {
            Some(code) => Some(code.code),
            None => self.state.motion,
        };
        if axis_words && !group0_uses_axes {
            if motion_code.is_some_and(|code| code.code == 800) {
                let word = self.first_axis_word().unwrap_or(Word { value: 0.0, at: 0, end: 1 });
                return Err(self.word_fault(word, "Cannot use axis values with g80"));
            }
            if modal_motion.is_none() {
                let word = self.first_axis_word().unwrap_or(Word { value: 0.0, at: 0, end: 1 });
                return Err(
                    self.word_fault(word, "Cannot use axis values without a g code that uses them")
                );
            }
        }
        let motion_to_be = match motion_code {
            Some(code) if code.code != 800 => Some(code.code),
            Some(_) => None,
            None if axis_words && !group0_uses_axes => self.state.motion,
            None => None,
        };
        Ok(Plan { motion_code, group0, motion_to_be })
    }

    /// Stores the block's parameter settings, which take effect after the whole line is read.
    /// Read-only names are refused here, after the block's checks (rs274 reports an unused E
    /// word on `#<_x>=1 E1`, not the assignment).
    fn store_parameters(&mut self) -> Result<(), Fault> {
        for &(start, end, _) in &self.syntax.block.named {
            let name = &self.syntax.compact.bytes()[start..end];
            if name.first() == Some(&b'_') && self.state.predefined(name).is_some() {
                return Err(self.fault_at(
                    start.saturating_sub(2),
                    end + 1,
                    format!(
                        "Cannot assign to read-only parameter #<{}>",
                        String::from_utf8_lossy(name)
                    ),
                ));
            }
        }
        for index in 0..self.syntax.block.numbered.len() {
            let (number, value) = self.syntax.block.numbered[index];
            self.state.params.set(number, value);
        }
        for index in 0..self.syntax.block.named.len() {
            let (start, end, value) = self.syntax.block.named[index];
            self.state.params.set_named(&self.syntax.compact.bytes()[start..end], value);
        }
        Ok(())
    }

    /// Executes the rest of the block, after its comment, in LinuxCNC's order of execution
    /// (`execute_block`'s numbered steps); `user_m_missing`: its user M-code has no program
    /// where the INI file says they are.
    pub(super) fn execute(&mut self, plan: Plan, user_m_missing: bool) -> Result<(), Fault> {
        self.execute_feed_and_tool()?;
        if self.execute_m_codes(user_m_missing)? {
            // rs274 read the restoring codes into this block's place: the rest is lost.
            self.state.publish_position();
            return Ok(());
        }
        self.execute_dwell(plan.group0)?;
        self.execute_modes()?;
        self.execute_group_zero(plan.group0)?;
        // 22. retract mode
        if let Some(code) = self.syntax.block.g[10] {
            self.state.cycle.retract_to_old = code.code == 980;
        }
        self.execute_motion(plan)?;
        self.check_range()?;
        self.execute_stop()?;
        self.state.publish_position();
        Ok(())
    }

    /// Steps 3–6: feed mode, feed rate, spindle speed, tool selection.
    fn execute_feed_and_tool(&mut self) -> Result<(), Fault> {
        // 3. feed mode
        if let Some(code) = self.syntax.block.g[5] {
            if code.code == 930 {
                self.state.inverse_time = true;
            } else {
                self.state.inverse_time = false;
                self.state.feed_rate = 0.0;
                self.state.feed_mm = 0.0;
            }
        }
        // 4. feed rate
        if let Some(f) = self.syntax.block.word(b'f')
            && !self.state.inverse_time
        {
            self.state.feed_rate = f.value;
            self.state.feed_mm = f.value * self.state.factor();
        }
        if self.syntax.block.extra.is_some() {
            self.check_spindle_number()?;
        }
        // 5, 6. spindle speed, tool selection: no effect on motion (a new power or speed
        // for a laser or spindle that is on).
        if let Some(s) = self.syntax.block.word(b's') {
            let changed = s.value != self.state.speed;
            self.state.speed = s.value;
            let powered = matches!(self.hooks.tool, Tool::Laser | Tool::Spindle);
            if changed && powered && self.hooks.tool_on && self.syntax.block.m[7].is_none() {
                self.tool_event(self.state.spindle);
            }
        }
        // (Calls into the tier-3 modules only when the block has their words: every line
        // passes here.)
        if self.syntax.block.word(b't').is_some() {
            self.select_tool()?;
        }
        Ok(())
    }

    /// Steps 7–12: outputs and inputs, tool change, spindle, coolant, overrides, user M-codes;
    /// `Ok(true)` when M72 or M73 restored the modal state (the rest of the block is lost).
    fn execute_m_codes(&mut self, user_m_missing: bool) -> Result<bool, Fault> {
        // 7. digital and analog outputs and inputs
        if self.syntax.block.m[5].is_some() {
            self.io_output()?;
        }
        // 8. tool change: LinuxCNC stops the spindle first (here: gripper off); M61 says which
        // tool is in the spindle.
        if let Some(code) = self.syntax.block.m[6] {
            if code.code == 61 {
                self.set_current_tool(code)?;
            } else {
                self.refuse_with_comp(
                    (code.at, code.end),
                    "Cannot change tools with cutter radius compensation on",
                )?;
                self.change_tool();
                self.state.spindle = 5;
                self.tool_event(5);
            }
        }
        // 9. spindle: the gripper (or the tool)
        if let Some(code) = self.syntax.block.m[7].filter(|code| code.code >= 70) {
            if self.modal_state(code)? {
                return Ok(true);
            }
        } else if self.syntax.block.m[7].is_some_and(|code| code.code == 19) {
            self.orient_spindle()?;
        } else if let Some(code) = self.syntax.block.m[7] {
            self.state.spindle = code.code;
            self.tool_event(code.code);
        }
        // 11. coolant
        if let Some(code) = self.syntax.block.m[8] {
            match code.code {
                7 => self.state.mist = true,
                8 => self.state.flood = true,
                _ => (self.state.mist, self.state.flood) = (false, false),
            }
        }
        // overrides
        if self.syntax.block.m[9].is_some() {
            self.overrides()?;
        }
        // 12. user M codes: LinuxCNC runs an external program; here an event, with a note.
        // With an INI file that says where the programs are, one that is not there is
        // LinuxCNC's unknown M code.
        if let Some(code) = self.syntax.block.m[10] {
            let name = format!("M{}", code.code);
            if user_m_missing {
                return Err(self.code_fault(
                    code,
                    format!(
                        "Unknown M code used: {name} (no program {name} in the INI file's \
                         USER_M_PATH or PROGRAM_PREFIX)"
                    ),
                ));
            }
            self.record(&name, true);
        }
        Ok(false)
    }

    /// Step 14: dwell (G4 P).
    fn execute_dwell(&mut self, group0: Option<Code>) -> Result<(), Fault> {
        if group0.is_some_and(|zero| zero.code == 40)
            && let Some(p) = self.syntax.block.word(b'p')
        {
            if p.value < 0.0 {
                return Err(
                    self.word_fault(p, format!("a dwell time must not be negative: P{}", p.value))
                );
            }
            self.emit(MotionKind::Dwell { seconds: p.value });
        }
        Ok(())
    }

    /// Steps 15–21: plane, length units, cutter radius compensation, tool length offset,
    /// coordinate system, path control, distance modes.
    fn execute_modes(&mut self) -> Result<(), Fault> {
        // 15. plane
        if let Some(code) = self.syntax.block.g[2] {
            let plane = match code.code {
                170 => Plane::Xy,
                180 => Plane::Xz,
                _ => Plane::Yz,
            };
            if plane != self.state.plane {
                self.refuse_with_comp(
                    (code.at, code.end),
                    "Cannot change planes with cutter radius compensation on",
                )?;
            }
            self.state.plane = plane;
        }
        // 16. length units
        if let Some(code) = self.syntax.block.g[6] {
            self.set_units(code.code == 210);
        }
        // 17. cutter radius compensation
        if self.syntax.block.g[7].is_some() {
            self.set_cutter_comp()?;
        }
        // 18. tool length offset
        if let Some(code) = self.syntax.block.g[8] {
            self.tool_length_offset(code)?;
        }
        // 19. coordinate system
        if let Some(code) = self.syntax.block.g[12] {
            let system = match code.code {
                540 => 1,
                550 => 2,
                560 => 3,
                570 => 4,
                580 => 5,
                590 => 6,
                591 => 7,
                592 => 8,
                _ => 9,
            };
            self.refuse_with_comp(
                (code.at, code.end),
                "Cannot change coordinate systems with cutter radius compensation on",
            )?;
            self.select_system(system);
        }
        // 20. path control mode
        if let Some(code) = self.syntax.block.g[13] {
            self.set_path_control(code)?;
        }
        // 21. distance modes
        if let Some(code) = self.syntax.block.g[3] {
            self.state.incremental = code.code == 910;
        }
        if let Some(code) = self.syntax.block.g[4] {
            self.state.ijk_absolute = code.code == 901;
        }
        Ok(())
    }

    /// Step 23: G10, G28, G30, G28.1, G30.1, G52, G92, then G92.1, G92.2, G92.3.
    fn execute_group_zero(&mut self, group0: Option<Code>) -> Result<(), Fault> {
        if let Some(zero) = group0 {
            match zero.code {
                100 => self.set_coordinate_data(zero)?,
                280 | 300 => {
                    self.refuse_with_comp(
                        (zero.at, zero.end),
                        "Cannot use g28 or g30 with cutter radius comp",
                    )?;
                    self.go_home(zero)?;
                }
                281 | 301 => {
                    self.refuse_with_comp(
                        (zero.at, zero.end),
                        "Cannot set reference point with cutter compensation in effect",
                    )?;
                    let base = if zero.code == 281 { G28_HOME } else { G30_HOME };
                    let machine = self.state.machine(self.state.current);
                    for (axis, machine) in machine.into_iter().enumerate() {
                        let value = self.state.to_mm(axis, machine);
                        self.state.params.set(base + axis_slot(axis), value);
                    }
                }
                920 | 520 => {
                    self.refuse_with_comp(
                        (zero.at, zero.end),
                        "Cannot change axis offsets with cutter radius comp",
                    )?;
                    if zero.code == 920 {
                        self.set_axis_offsets(zero)?;
                    } else {
                        self.set_local_offsets();
                    }
                }
                _ => {}
            }
        }
        // (rs274 ignores G92.1, G92.2 and G92.3 while cutter compensation is on)
        if let Some(code) = self.syntax.block.g[11].filter(|_| !self.state.comp.on()) {
            self.apply_g92(code.code == 923);
            if code.code == 921 {
                for slot in 0..10 {
                    self.state.params.set(G92_ENABLED + slot, 0.0);
                }
            }
        }
        Ok(())
    }

    /// Step 24: the motion mode, and the block's motion.
    fn execute_motion(&mut self, plan: Plan) -> Result<(), Fault> {
        let Plan { motion_code, group0, motion_to_be } = plan;
        let previous_motion = self.state.motion;
        // A spline leaves the modal motion as it was.
        if let Some(code) = motion_code.filter(|code| !spline::is_spline(code.code)) {
            self.state.motion = if code.code == 800 { None } else { Some(code.code) };
            if !canned::is_cycle(code.code) {
                self.state.cycle.initial_level = None;
            }
        }
        let Some(motion) = motion_to_be else { return Ok(()) };
        let g53 = group0.is_some_and(|zero| zero.code == 530);
        if self.syntax.block.extra.is_some() {
            self.apply_polar(motion, g53)?;
        }
        match motion {
            0 | 10 => self.straight(motion, g53),
            20 | 30 => self.arc(motion == 20),
            50 | 51 => self.spline(motion),
            code if probe::is_probe(code) => self.probe(code),
            _ => self.canned_cycle(motion, previous_motion == Some(motion)),
        }
    }

    /// Step 25: stop (M0, M1, M60) or end (M2, M30).
    fn execute_stop(&mut self) -> Result<(), Fault> {
        if let Some(code) = self.syntax.block.m[4] {
            self.flush_cutter_comp()?;
            match code.code {
                2 | 30 => {
                    self.state.comp = cutter_comp::CutterComp::new();
                    self.emit(MotionKind::End);
                    self.output.finished = true;
                }
                _ => self.emit(MotionKind::Pause),
            }
        }
        Ok(())
    }
}
