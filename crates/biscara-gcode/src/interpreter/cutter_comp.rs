//! Cutter radius compensation — G40, G41, G42, G41.1, G42.1 — as LinuxCNC's rs274 does it.
//!
//! The tool is kept one radius to the left (G41) or right (G42) of the programmed path, in the
//! XY plane (G17) or the XZ plane (G18). Like rs274, this works on a look-ahead of one motion:
//! the compensated move of a block is held back until the next block's move shows whether the
//! corner between them is convex (an arc around the corner is inserted, or nothing when the
//! path goes straight on) or concave (the held move is shortened to where the tool touches
//! both sides, or the block is refused as gouging). What the program does meanwhile without
//! moving (a dwell, the gripper) is held behind the move, in order. At most one motion and the
//! events after it are ever held: memory does not grow with the program.
//!
//! Positions here are in program units and the current coordinate system, in the plane's
//! canonical axes `(first, second)` — `(x, y)` for G17, `(z, x)` for G18 — with the third
//! axis the plane's normal. The formulas follow LinuxCNC's `convert_straight_comp1/2`,
//! `convert_arc_comp1/2` and `move_endpoint_and_flush`, so that the motions and the refusals
//! (with LinuxCNC's wording) are rs274's.

use std::collections::VecDeque;
use std::f64::consts::{FRAC_PI_2, PI};

use biscara_motion::{Feed, Motion, MotionKind, Plane};

use super::Machine;
use super::motion::find_turn;
use crate::syntax::lexer::Fault;
use crate::syntax::parser::Word;

/// LinuxCNC's `TOLERANCE_CONCAVE_CORNER` (radians): below it a corner is straight on.
const TOLERANCE_CONCAVE_CORNER: f64 = 0.05;
/// LinuxCNC's `TOLERANCE_EQUAL`.
const TOLERANCE_EQUAL: f64 = 0.0001;

/// Which side of the path the tool keeps to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Side {
    /// G41, G41.1.
    Left,
    /// G42, G42.1.
    Right,
}

/// The compensation state and the held-back motions.
#[derive(Debug)]
pub(super) struct CutterComp {
    side: Option<Side>,
    /// The tool radius, program units, never negative.
    radius: f64,
    /// No compensated move yet since compensation was turned on.
    first_move: bool,
    /// The programmed (uncompensated) point, `[x, y, z, c]` in program units.
    programmed: [f64; 4],
    /// G40 just ended compensation: the next move must be straight.
    arc_not_allowed: bool,
    queue: VecDeque<Held>,
    /// Where the held moves start (LinuxCNC's `endpoint`), plane coordinates.
    endpoint: [f64; 2],
    endpoint_valid: bool,
}

/// A held-back entry: an event, or a compensated move whose end may still move.
#[derive(Debug)]
enum Held {
    Event(Motion),
    Move(HeldMove),
}

#[derive(Debug)]
struct HeldMove {
    line: usize,
    extrude: Option<f64>,
    /// The path-control mode when the move was programmed ([`Motion::blend`]).
    blend: Option<f64>,
    /// G64 Q when the move was programmed ([`Motion::naive_cam`]).
    naive_cam: Option<f64>,
    plane: Plane,
    /// `[x, y, z, c]`, program units.
    end: [f64; 4],
    shape: Shape,
}

#[derive(Debug, Clone, Copy)]
enum Shape {
    /// A rapid (`feed` None) or a feed move; `direction` is the one LinuxCNC records to catch
    /// a move reversed by a concave corner.
    Straight { feed: Option<Feed>, direction: [f64; 2] },
    /// An arc about `center` (plane coordinates), `turn` > 0 counterclockwise; `sweep` is the
    /// programmed arc's angle (0: its end never moves).
    Arc { feed: Feed, center: [f64; 2], turn: i32, sweep: f64 },
}

impl CutterComp {
    pub(super) fn new() -> CutterComp {
        CutterComp {
            side: None,
            radius: 0.0,
            first_move: true,
            programmed: [0.0; 4],
            arc_not_allowed: false,
            queue: VecDeque::new(),
            endpoint: [0.0; 2],
            endpoint_valid: false,
        }
    }

    /// Whether G41/G42 is in force (even with a zero radius).
    pub(super) fn on(&self) -> bool {
        self.side.is_some()
    }

    /// Whether moves are being compensated (on, with a radius).
    pub(super) fn active(&self) -> bool {
        self.side.is_some() && self.radius > 0.0
    }

    /// Whether motions are being held back (events must queue behind them).
    pub(super) fn holding(&self) -> bool {
        !self.queue.is_empty()
    }

    /// Holds an event behind the held moves.
    pub(super) fn hold(&mut self, motion: Motion) {
        self.queue.push_back(Held::Event(motion));
    }

    /// `#<_ccomp>`: 400 (off), 410 (left), 420 (right), whichever code turned it on.
    pub(super) fn code(&self) -> f64 {
        match self.side {
            None => 400.0,
            Some(Side::Left) => 410.0,
            Some(Side::Right) => 420.0,
        }
    }

    /// The base of an axis that the block does not give, or of an incremental move: the
    /// programmed point while compensating (LinuxCNC's `find_ends`), else `None`.
    pub(super) fn base(&self, axis: usize, plane: Plane) -> Option<f64> {
        let middle = self.side.is_some() && !self.first_move;
        let affected = match axis {
            0 => true,
            1 => plane == Plane::Xy,
            2 => plane == Plane::Xz,
            _ => false,
        };
        (middle && affected).then_some(self.programmed[axis])
    }

    /// G20/G21 while on: LinuxCNC rescales the radius, the programmed point and the held
    /// moves (`qc_scale`, which scales `endpoint` once per held entry).
    pub(super) fn scale(&mut self, factor: f64) {
        self.radius *= factor;
        for value in &mut self.programmed[..3] {
            *value *= factor;
        }
        for held in &mut self.queue {
            self.endpoint[0] *= factor;
            self.endpoint[1] *= factor;
            if let Held::Move(held) = held {
                for value in &mut held.end[..3] {
                    *value *= factor;
                }
                if let Shape::Arc { center, .. } = &mut held.shape {
                    center[0] *= factor;
                    center[1] *= factor;
                }
            }
        }
    }

    /// The program ends at `%`: rs274 never sends what it holds.
    pub(super) fn discard(&mut self) {
        self.queue.clear();
    }
}

/// Whether the tool is inside an arc turning `turn` (LinuxCNC's `TOOL_INSIDE_ARC`).
fn inside(side: Side, turn: i32) -> bool {
    (side == Side::Left && turn > 0) || (side == Side::Right && turn < 0)
}

fn polar(from: [f64; 2], length: f64, angle: f64) -> [f64; 2] {
    [from[0] + length * angle.cos(), from[1] + length * angle.sin()]
}

fn direction(from: [f64; 2], to: [f64; 2]) -> f64 {
    (to[1] - from[1]).atan2(to[0] - from[0])
}

fn distance(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// A compensated arc, ready to hold: plane coordinates.
pub(super) struct CompArc {
    /// The programmed arc's start (the programmed point, or the tool for the entry arc).
    pub start: [f64; 4],
    /// The programmed end, `[x, y, z, c]`.
    pub end: [f64; 4],
    /// The programmed centre, plane coordinates.
    pub center: [f64; 2],
    /// Turns, > 0 counterclockwise.
    pub turn: i32,
    pub feed: Feed,
}

impl Machine {
    /// Refuses a code that LinuxCNC refuses while compensation is on.
    pub(super) fn refuse_with_comp(&self, at: (usize, usize), message: &str) -> Result<(), Fault> {
        if self.state.comp.on() { Err(self.fault_at(at.0, at.1, message)) } else { Ok(()) }
    }

    /// The diameter of tool `tool` (the D word of G41/G42; 0: the tool in the spindle), in
    /// program units, from the tool table as the program has changed it. Without a table every
    /// tool has diameter 0 (and the note about tools used without a table is due).
    /// Also the tool's orientation (lathe tools: 1–8).
    fn tool_diameter(&mut self, tool: u32, d: Option<Word>) -> Result<(f64, i32), Fault> {
        let tools = &self.state.tools;
        let (mm, orientation) = if tool == 0 {
            (tools.spindle.diameter, tools.spindle.orientation)
        } else {
            match tools.table.get(tool) {
                Some(entry) => (entry.diameter, entry.orientation),
                None if !tools.has_table => (0.0, 0),
                None => {
                    let (start, end) = d.map_or((0, 1), |d| (d.at, d.end));
                    return Err(self.fault_at(
                        start,
                        end,
                        format!("Requested tool {tool} not found in the tool table"),
                    ));
                }
            }
        };
        if !self.state.tools.has_table {
            self.state.tools.used_without_table = true;
        }
        Ok((mm / self.state.factor(), orientation))
    }

    /// G40, G41, G42, G41.1, G42.1 (execution step 17).
    /// G40: compensation off; the move held back ends where the programmed path is.
    pub(super) fn cutter_comp_off(&mut self) -> Result<(), Fault> {
        let comp = &self.state.comp;
        if comp.active() && !comp.first_move {
            let current = self.plane_point(self.state.current);
            self.move_endpoint_and_flush(current)?;
            self.dequeue();
            let programmed = self.state.comp.programmed;
            let [first, second, normal] = self.state.plane.axes();
            for axis in [first, second, normal] {
                self.state.current[axis] = programmed[axis];
            }
            self.state.comp.arc_not_allowed = true;
        }
        self.state.comp.side = None;
        self.state.comp.first_move = true;
        Ok(())
    }

    pub(super) fn set_cutter_comp(&mut self) -> Result<(), Fault> {
        let Some(code) = self.syntax.block.g[7] else { return Ok(()) };
        let fail = |this: &Self, message: String| this.code_fault(code, message);
        if code.code == 400 {
            return self.cutter_comp_off();
        }
        if self.state.plane == Plane::Yz {
            return Err(fail(
                self,
                "Cutter radius compensation allowed only in XY, XZ planes".into(),
            ));
        }
        if self.state.comp.on() {
            return Err(fail(self, "Cannot turn cutter radius comp on when on".into()));
        }
        let whole = code.code / 10;
        let mut side = if whole == 41 { Side::Left } else { Side::Right };
        let d = self.syntax.block.word(b'd');
        let radius = if code.code % 10 == 1 {
            let Some(d) = d else {
                return Err(fail(self, format!("G{whole}.1 with no D word")));
            };
            if let Some(l) = self.syntax.block.word(b'l') {
                if self.state.plane != Plane::Xz {
                    return Err(
                        self.word_fault(l, format!("G{whole}.1 with L word, but plane is not G18"))
                    );
                }
                let (first, last) = self.span(l.at, l.end);
                return Err(Fault::not_supported(
                    first,
                    last,
                    format!("G{whole}.1 L"),
                    "lathe tool orientation",
                ));
            }
            d.value / 2.0
        } else if self.hooks.rules.comp_radius_in_p
            && let Some(p) = self.syntax.block.word(b'p')
        {
            // Mach3's G41/G42 P: the radius itself, program units, instead of the tool table's
            // (a Fusion 360 Mach3 post writes P1.587 for its 3.175 mm cutter).
            p.value
        } else {
            let tool = match d {
                None => 0,
                Some(d) => {
                    // LinuxCNC's is_near_int: (int)(value + 0.5) within 0.0001.
                    let near = (d.value + 0.5).trunc();
                    if (near - d.value).abs() >= 0.0001
                        || !(0.0..=f64::from(u32::MAX)).contains(&near)
                    {
                        return Err(self.word_fault(
                            d,
                            format!("G{whole} requires D word to be a whole number"),
                        ));
                    }
                    near as u32
                }
            };
            let (diameter, orientation) = self.tool_diameter(tool, d)?;
            if !matches!(orientation, 0 | 9) {
                if self.state.plane != Plane::Xz {
                    return Err(fail(
                        self,
                        format!("G{whole} with lathe tool, but plane is not G18"),
                    ));
                }
                let (first, last) = self.span(code.at, code.end);
                return Err(Fault::not_supported(
                    first,
                    last,
                    format!("G{whole} with a lathe tool"),
                    "lathe tool orientation",
                ));
            }
            diameter / 2.0
        };
        let radius = if radius < 0.0 {
            side = if side == Side::Left { Side::Right } else { Side::Left };
            -radius
        } else {
            radius
        };
        if self.state.rotation != 0.0 && self.state.plane != Plane::Xy {
            let (first, last) = self.span(code.at, code.end);
            return Err(Fault::not_supported(
                first,
                last,
                format!("G{whole} in the XZ plane of a rotated coordinate system"),
                "its corner arcs would lie in a tilted plane",
            ));
        }
        let comp = &mut self.state.comp;
        comp.radius = radius;
        comp.side = Some(side);
        Ok(())
    }

    /// The plane coordinates of a point.
    fn plane_point(&self, point: [f64; 4]) -> [f64; 2] {
        let [first, second, _] = self.state.plane.axes();
        [point[first], point[second]]
    }

    /// `point` with its plane coordinates replaced.
    fn with_plane(&self, mut point: [f64; 4], plane_xy: [f64; 2]) -> [f64; 4] {
        let [first, second, _] = self.state.plane.axes();
        point[first] = plane_xy[0];
        point[second] = plane_xy[1];
        point
    }

    /// Sends every held entry on, in order (LinuxCNC's `dequeue_canons`).
    fn dequeue(&mut self) {
        self.state.comp.endpoint_valid = false;
        while let Some(held) = self.state.comp.queue.pop_front() {
            let motion = match held {
                Held::Event(motion) => motion,
                Held::Move(held) => {
                    let end = self.state.absolute(held.end);
                    let kind = match held.shape {
                        Shape::Straight { feed: None, .. } => MotionKind::Rapid { end },
                        Shape::Straight { feed: Some(feed), .. } => {
                            MotionKind::Linear { end, feed }
                        }
                        Shape::Arc { feed, center, turn, .. } => {
                            let [first, second, _] = held.plane.axes();
                            let mut point = held.end;
                            point[first] = center[0];
                            point[second] = center[1];
                            let center = self.state.absolute(point);
                            MotionKind::Arc {
                                end,
                                center: [center[first], center[second]],
                                plane: held.plane,
                                clockwise: turn < 0,
                                turns: turn.unsigned_abs(),
                                feed,
                            }
                        }
                    };
                    // (Only a straight feed move carries Q; comp may turn one into an arc.)
                    let straight = matches!(kind, MotionKind::Linear { .. });
                    let naive_cam = held.naive_cam.filter(|_| straight && held.blend.is_some());
                    Motion {
                        line: held.line,
                        kind,
                        extrude: held.extrude,
                        blend: held.blend,
                        naive_cam,
                    }
                }
            };
            self.output.queue.push_back(motion);
        }
    }

    fn set_endpoint(&mut self, point: [f64; 2]) {
        self.state.comp.endpoint = point;
        self.state.comp.endpoint_valid = true;
    }

    fn enqueue(&mut self, end: [f64; 4], shape: Shape) {
        self.output.moved = true;
        let extrude = self.hooks.pending_extrude.take();
        let held = HeldMove {
            line: self.state.line,
            extrude,
            blend: self.state.blend,
            naive_cam: self.state.naive_cam,
            plane: self.state.plane,
            end,
            shape,
        };
        self.state.comp.queue.push_back(Held::Move(held));
    }

    /// Moves the end of every held move to `point`, refusing a move that this reverses (a
    /// concave corner the tool cannot reach), then sends them on (`move_endpoint_and_flush`).
    fn move_endpoint_and_flush(&mut self, point: [f64; 2]) -> Result<(), Fault> {
        if self.state.comp.queue.is_empty() {
            return Ok(());
        }
        let [first, second, _] = self.state.plane.axes();
        // LinuxCNC's slack for an arc that the corner makes longer: 0.0254 radians in mm
        // programs, 0.001 in inch programs.
        let sweep_tolerance = if self.state.metric { 0.0254 } else { 0.001 };
        let comp = &self.state.comp;
        let mut problem = None;
        for held in &comp.queue {
            let Held::Move(held) = held else { continue };
            match held.shape {
                Shape::Arc { center, turn, sweep, .. } => {
                    let old = distance([held.end[first], held.end[second]], center);
                    let new = distance(point, center);
                    let swept = find_turn(comp.endpoint, center, turn, point);
                    if (old - new).abs() > 0.01 {
                        problem = Some(format!(
                            "BUG: cutter compensation has generated an invalid arc with \
                             mismatched radii r1 {old:.6} r2 {new:.6}"
                        ));
                    } else if sweep != 0.0
                        && comp.endpoint_valid
                        && swept.abs() > sweep.abs() + sweep_tolerance
                    {
                        problem = Some(
                            "Arc move in concave corner cannot be reached by the tool without \
                             gouging"
                                .to_owned(),
                        );
                    }
                }
                Shape::Straight { feed, direction } => {
                    let moved = [point[0] - comp.endpoint[0], point[1] - comp.endpoint[1]];
                    let dot = direction[0] * moved[0] + direction[1] * moved[1];
                    if comp.endpoint_valid && dot < 0.0 {
                        let what =
                            if feed.is_some() { "Straight feed" } else { "Straight traverse" };
                        problem = Some(format!(
                            "{what} in concave corner cannot be reached by the tool without \
                             gouging"
                        ));
                    }
                }
            }
            if problem.is_some() {
                break;
            }
        }
        if let Some(message) = problem {
            return Err(self.motion_fault(message));
        }
        for held in &mut self.state.comp.queue {
            if let Held::Move(held) = held {
                held.end[first] = point[0];
                held.end[second] = point[1];
            }
        }
        self.dequeue();
        self.set_endpoint(point);
        Ok(())
    }

    /// Sends the held moves on where they are (before M0, M1, M2, M30, M60).
    pub(super) fn flush_cutter_comp(&mut self) -> Result<(), Fault> {
        let current = self.plane_point(self.state.current);
        self.move_endpoint_and_flush(current)?;
        self.dequeue();
        Ok(())
    }

    /// A G0 or G1 to the programmed `end` while compensating (`convert_straight_comp1/2`).
    pub(super) fn comp_straight(
        &mut self,
        rapid: bool,
        end: [f64; 4],
        feed: Option<Feed>,
        g53: bool,
    ) -> Result<(), Fault> {
        if g53 {
            return Err(self.motion_fault("Cannot use g53 with cutter radius comp"));
        }
        let [_, _, normal] = self.state.plane.axes();
        let side = self.state.comp.side.unwrap_or(Side::Left);
        let radius = self.state.comp.radius;
        let feed = if rapid { None } else { feed };
        let current = self.state.current;
        let c = self.plane_point(current);
        let p = self.plane_point(end);
        let tool_end = if self.state.comp.first_move {
            if distance(p, c) <= radius {
                return Err(self.motion_fault(
                    "Length of cutter compensation entry move is not greater than the tool radius",
                ));
            }
            let alpha = direction(c, p) + if side == Side::Left { FRAC_PI_2 } else { -FRAC_PI_2 };
            let tool = polar(p, radius, alpha);
            self.set_endpoint(c);
            let shape = Shape::Straight { feed, direction: [alpha.cos(), alpha.sin()] };
            self.enqueue(self.with_plane(end, tool), shape);
            self.state.comp.first_move = false;
            tool
        } else {
            let programmed = self.state.comp.programmed;
            let op = self.plane_point(programmed);
            let moved = [p[0] - op[0], p[1] - op[1]];
            if moved == [0.0, 0.0] {
                let shape = Shape::Straight { feed, direction: moved };
                self.enqueue(self.with_plane(end, c), shape);
                c
            } else {
                self.comp_corner_to_line(rapid, side, radius, c, op, p, current, end, feed)?
            }
        };
        let mut now = self.with_plane(end, tool_end);
        now[normal] = end[normal];
        self.state.current = now;
        self.state.comp.programmed = end;
        Ok(())
    }

    /// The corner before a straight move (not the first): returns the tool's end.
    #[allow(clippy::too_many_arguments)]
    fn comp_corner_to_line(
        &mut self,
        rapid: bool,
        side: Side,
        radius: f64,
        c: [f64; 2],
        op: [f64; 2],
        p: [f64; 2],
        current: [f64; 4],
        end: [f64; 4],
        feed: Option<Feed>,
    ) -> Result<[f64; 2], Fault> {
        let small = TOLERANCE_CONCAVE_CORNER;
        let mut theta = direction(op, c);
        let mut alpha = direction(op, p);
        let (beta, gamma) = match side {
            Side::Left => {
                if theta < alpha {
                    theta += 2.0 * PI;
                }
                (theta - alpha - FRAC_PI_2, FRAC_PI_2)
            }
            Side::Right => {
                if alpha < theta {
                    alpha += 2.0 * PI;
                }
                (alpha - theta - FRAC_PI_2, -FRAC_PI_2)
            }
        };
        let tool_end = polar(p, radius, alpha + gamma);
        let mid = polar(op, radius, alpha + gamma);
        let front_arc_turn = self.state.comp.queue.front().and_then(|held| match held {
            Held::Move(HeldMove { shape: Shape::Arc { turn, .. }, .. }) => Some(*turn),
            _ => None,
        });
        let concave = beta < -small
            || beta > PI + small
            || (beta > PI - small
                && front_arc_turn.is_some_and(|turn| {
                    (side == Side::Right && turn > 0) || (side == Side::Left && turn < 0)
                }));
        let [_, _, normal] = self.state.plane.axes();
        if !concave && beta > small {
            // A convex corner: around it on an arc about the programmed corner (a rapid
            // goes straight to where the arc would end).
            self.move_endpoint_and_flush(c)?;
            let mut corner = self.with_plane(end, mid);
            corner[normal] = current[normal];
            match feed {
                Some(feed) if !rapid => {
                    let turn = if side == Side::Left { -1 } else { 1 };
                    self.enqueue(corner, Shape::Arc { feed, center: op, turn, sweep: 0.0 });
                }
                _ => self.enqueue(corner, Shape::Straight { feed: None, direction: [0.0; 2] }),
            }
            self.dequeue();
            self.set_endpoint(mid);
        } else if concave {
            match self.front_arc() {
                None => {
                    // line → line: back along the held move until the tool touches both.
                    let half_corner = (beta + PI) / 2.0;
                    if half_corner == 0.0 {
                        return Err(self.motion_fault(
                            "Zero degree inside corner is invalid for cutter compensation",
                        ));
                    }
                    let retreat = radius / half_corner.tan();
                    let meet = polar(c, retreat, theta + gamma);
                    self.move_endpoint_and_flush(meet)?;
                }
                Some((center, turn, old_end)) => {
                    // arc → line: where the held (compensated) arc meets the new offset line.
                    let old_radius = distance(center, old_end);
                    let base = direction(op, p);
                    let theta = if turn > 0 { base + FRAC_PI_2 } else { base - FRAC_PI_2 };
                    let phi = direction(op, center);
                    let tool_inside = inside(side, turn);
                    let programmed_radius =
                        if tool_inside { old_radius + radius } else { old_radius - radius };
                    let d = programmed_radius * (theta - phi).cos();
                    let l = if tool_inside { d - radius } else { d + radius } / old_radius;
                    if !(-1.0..=1.0).contains(&l) {
                        return Err(self.motion_fault(
                            "Arc to straight motion makes a corner the compensated tool can't \
                             fit in without gouging",
                        ));
                    }
                    let clockwise_sign = if (turn > 0) == tool_inside { -1.0 } else { 1.0 };
                    let angle = clockwise_sign * l.acos() + theta + PI;
                    let meet = polar(center, old_radius, angle);
                    self.move_endpoint_and_flush(meet)?;
                }
            }
        } else {
            self.dequeue();
            self.set_endpoint(c);
        }
        let mut target = self.with_plane(end, tool_end);
        target[normal] = end[normal];
        let moved = [p[0] - op[0], p[1] - op[1]];
        self.enqueue(
            target,
            Shape::Straight { feed: if rapid { None } else { feed }, direction: moved },
        );
        Ok(tool_end)
    }

    /// The first held move if it is an arc: its centre, turn and end (plane coordinates).
    fn front_arc(&self) -> Option<([f64; 2], i32, [f64; 2])> {
        let [first, second, _] = self.state.plane.axes();
        match self.state.comp.queue.front() {
            Some(Held::Move(HeldMove { shape: Shape::Arc { center, turn, .. }, end, .. })) => {
                Some((*center, *turn, [end[first], end[second]]))
            }
            _ => None,
        }
    }

    /// The start of the programmed move while compensating (for an arc's centre and for
    /// inverse-time rates): the programmed point after the first move, else `None` (the
    /// current point).
    pub(super) fn comp_start(&self) -> Option<[f64; 4]> {
        let comp = &self.state.comp;
        if !comp.active() || comp.first_move || self.state.plane == Plane::Yz {
            return None;
        }
        let programmed = self.plane_point(comp.programmed);
        Some(self.with_plane(self.state.current, programmed))
    }

    /// Whether arcs are compensated now (on with a radius, in XY or XZ).
    pub(super) fn comp_arcs(&self) -> bool {
        self.state.comp.active() && self.state.plane != Plane::Yz
    }

    /// LinuxCNC's checks of an arc before its centre is found: the move after G40 is
    /// straight; an entry arc is longer than the radius; an R arc the tool is inside is larger
    /// than the tool (`arc_data_comp_r`).
    pub(super) fn comp_arc_checks(
        &self,
        clockwise: bool,
        end: [f64; 4],
        r: Option<f64>,
    ) -> Result<(), Fault> {
        let comp = &self.state.comp;
        if !self.comp_arcs() || !comp.first_move {
            return Ok(());
        }
        let c = self.plane_point(self.state.current);
        if distance(self.plane_point(end), c) <= comp.radius {
            return Err(self.motion_fault(
                "Radius of cutter compensation entry arc is not greater than the tool radius",
            ));
        }
        let side = comp.side.unwrap_or(Side::Left);
        let turn = if clockwise { -1 } else { 1 };
        if let Some(r) = r
            && r.abs() <= comp.radius
            && inside(side, turn)
        {
            return Err(self.motion_fault("Tool radius not less than arc radius with comp"));
        }
        Ok(())
    }

    /// The move after G40 must be straight.
    pub(super) fn comp_arc_allowed(&self) -> Result<(), Fault> {
        if self.state.comp.arc_not_allowed {
            return Err(self.motion_fault(
                "The move just after exiting cutter compensation mode must be straight, not an arc",
            ));
        }
        Ok(())
    }

    /// A G0 or G1 resets the "straight after G40" rule.
    pub(super) fn comp_straight_seen(&mut self) {
        self.state.comp.arc_not_allowed = false;
    }

    /// A G2 or G3 while compensating (`convert_arc_comp1/2`).
    pub(super) fn comp_arc(&mut self, arc: CompArc) -> Result<(), Fault> {
        let [_, _, normal] = self.state.plane.axes();
        let side = self.state.comp.side.unwrap_or(Side::Left);
        let radius = self.state.comp.radius;
        let turn = arc.turn;
        let center = arc.center;
        let p = self.plane_point(arc.end);
        let current = self.state.current;
        let c = self.plane_point(current);
        let feed = arc.feed;
        if self.state.comp.first_move {
            // The entry arc: tangent to the tool where it is, through the offset end.
            if inside(side, turn) && distance(center, c) <= radius {
                return Err(self.motion_fault("Tool radius not less than arc radius with comp"));
            }
            let gamma =
                if inside(side, turn) { direction(p, center) } else { direction(center, p) };
            self.state.comp.first_move = false;
            self.state.comp.programmed = arc.end;
            let tool = polar(p, radius, gamma);
            let half = distance(c, tool) / 2.0;
            let to_center = direction(tool, center);
            let a_angle = direction(tool, c) - to_center;
            if a_angle.cos().abs() < TOLERANCE_EQUAL {
                return Err(self.motion_fault("Tool radius not less than arc radius with comp"));
            }
            let new_center = polar(tool, half / a_angle.cos(), to_center);
            let spiral = if self.state.metric {
                super::CENTER_ARC_RADIUS_TOLERANCE_MM
            } else {
                super::CENTER_ARC_RADIUS_TOLERANCE_INCH
            };
            if (distance(new_center, tool) - distance(new_center, c)).abs() > spiral {
                return Err(self.motion_fault("Bug in tool radius comp"));
            }
            let sweep = find_turn(c, new_center, turn, tool);
            self.enqueue(
                self.with_plane(arc.end, tool),
                Shape::Arc { feed, center: new_center, turn, sweep },
            );
            self.state.current = self.with_plane(arc.end, tool);
            return Ok(());
        }
        let op = self.plane_point(arc.start);
        let small = TOLERANCE_CONCAVE_CORNER;
        let arc_radius = distance(center, p);
        let theta = direction(op, c) + if side == Side::Left { -FRAC_PI_2 } else { FRAC_PI_2 };
        let mut delta = direction(op, center);
        let alpha = if turn > 0 { delta - FRAC_PI_2 } else { delta + FRAC_PI_2 };
        let beta = if side == Side::Left { theta - alpha } else { alpha - theta };
        let beta = if beta > 1.5 * PI {
            beta - 2.0 * PI
        } else if beta < -FRAC_PI_2 {
            beta + 2.0 * PI
        } else {
            beta
        };
        let gamma = if inside(side, turn) {
            if arc_radius <= radius {
                return Err(self.motion_fault("Tool radius not less than arc radius with comp"));
            }
            direction(p, center)
        } else {
            delta += PI;
            direction(center, p)
        };
        let tool_end = polar(p, radius, gamma);
        let sweep = find_turn(op, center, turn, p);
        let main = Shape::Arc { feed, center, turn, sweep };
        let concave = beta < -small
            || beta > PI + small
            || ((beta - PI).abs() < small && !inside(side, turn));
        if concave {
            match self.front_arc() {
                None => {
                    // line → arc
                    let across = arc_radius * (beta - FRAC_PI_2).sin();
                    let (from_center, toward) = if inside(side, turn) {
                        (arc_radius - radius, across + radius)
                    } else {
                        (arc_radius + radius, across - radius)
                    };
                    let l = toward / from_center;
                    if !(-1.0..=1.0).contains(&l) {
                        return Err(self.motion_fault(
                            "Arc move in concave corner cannot be reached by the tool without \
                             gouging",
                        ));
                    }
                    let angle = match (inside(side, turn), turn > 0) {
                        (true, true) => theta + l.asin(),
                        (true, false) => theta - l.asin(),
                        (false, true) => theta + PI - l.asin(),
                        (false, false) => theta + PI + l.asin(),
                    };
                    let meet = polar(center, from_center, angle);
                    self.move_endpoint_and_flush(meet)?;
                }
                Some((old_center, old_turn, old_end)) => {
                    // arc → arc
                    let old_radius = distance(old_center, old_end);
                    let new_radius =
                        if inside(side, turn) { arc_radius - radius } else { arc_radius + radius };
                    let centers = distance(old_center, center);
                    if old_radius == 0.0 || centers == 0.0 {
                        return Err(self.motion_fault(
                            "Arc to arc motion is invalid because the arcs have the same center",
                        ));
                    }
                    let a = (old_radius * old_radius + centers * centers - new_radius * new_radius)
                        / (2.0 * old_radius * centers);
                    if !(-1.0..=1.0).contains(&a) {
                        return Err(self.motion_fault(
                            "Arc to arc motion makes a corner the compensated tool can't fit in \
                             without gouging",
                        ));
                    }
                    let pullback = a.acos();
                    let across = direction(old_center, center);
                    let toward = if inside(side, old_turn) == (turn > 0) {
                        across + pullback
                    } else {
                        across - pullback
                    };
                    let meet = polar(old_center, old_radius, toward);
                    self.move_endpoint_and_flush(meet)?;
                }
            }
        } else if beta > small {
            // convex: first around the programmed corner
            let mid = polar(op, radius, delta);
            self.dequeue();
            let mut corner = self.with_plane(arc.end, mid);
            corner[normal] = current[normal];
            let turn = if side == Side::Left { -1 } else { 1 };
            self.enqueue(corner, Shape::Arc { feed, center: op, turn, sweep: 0.0 });
            self.dequeue();
            self.set_endpoint(mid);
        } else {
            self.dequeue();
            self.set_endpoint(c);
        }
        self.enqueue(self.with_plane(arc.end, tool_end), main);
        self.state.comp.programmed = arc.end;
        self.state.current = self.with_plane(arc.end, tool_end);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn turns_sweep_the_right_way() {
        let quarter = find_turn([1.0, 0.0], [0.0, 0.0], 1, [0.0, 1.0]);
        assert!((quarter - FRAC_PI_2).abs() < 1e-12);
        let back = find_turn([1.0, 0.0], [0.0, 0.0], -1, [0.0, 1.0]);
        assert!((back + 3.0 * FRAC_PI_2).abs() < 1e-12);
        assert_eq!(find_turn([1.0, 0.0], [0.0, 0.0], 0, [0.0, 1.0]), 0.0);
    }

    #[test]
    fn the_tool_is_inside_a_left_counterclockwise_arc() {
        assert!(inside(Side::Left, 1));
        assert!(inside(Side::Right, -1));
        assert!(!inside(Side::Left, -1));
        assert!(!inside(Side::Right, 1));
    }
}
