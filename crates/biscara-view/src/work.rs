//! The tool's work along a program, as the viewer and the pictures draw it: [`ToolWork`], the
//! strokes, and [`ProgramOverlay`], a program's samples laid over a trajectory or a picture.

use biscara_joints::CartesianSample;
use biscara_kinematics::ToolKind;

use crate::decimate::thin;

/// One point of the tool's work.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WorkPoint {
    /// Time, s.
    pub t: f64,
    /// Where, mm.
    pub at: [f64; 3],
    /// How strongly the tool works, 0 … 1 (a laser's power over its maximum; 1 for the other
    /// tools): drawn darker when stronger. Constant along a stroke.
    pub strength: f64,
    /// Whether a stroke starts here (the previous point, if any, ends another).
    pub start: bool,
}

/// The tool's work (docs/motion.md: the laser's burnt trace, the extruded track, the pen's
/// strokes, the cut) as strokes of points at least 0.5 mm apart and at every corner (the last
/// sample of a program line), a new stroke where the strength changes, and the times its state
/// changes. Bounded: when full, the spacing doubles and every other inner point goes (a stroke's
/// ends stay). The one stroke type of the viewer and the pictures.
#[derive(Debug, Clone)]
pub struct ToolWork {
    points: Vec<WorkPoint>,
    /// The last point kept and the latest sample not kept, of the stroke being drawn.
    last: Option<WorkPoint>,
    pending: Option<WorkPoint>,
    spacing: f64,
    capacity: usize,
    /// The previous sample's program line.
    line: Option<usize>,
    /// (time, strength; −1 when the tool stops working).
    changes: Vec<(f64, f64)>,
    max_changes: usize,
}

impl ToolWork {
    /// No work yet; at most `capacity` points (at least 4) and `max_changes` changes are kept.
    pub fn new(capacity: usize, max_changes: usize) -> ToolWork {
        ToolWork {
            points: Vec::new(),
            last: None,
            pending: None,
            spacing: 0.5,
            capacity: capacity.max(4),
            line: None,
            changes: Vec::new(),
            max_changes,
        }
    }

    /// Adds the sample at time `t` (s) and pose `[x, y, z, c]` (mm, degrees) of program line
    /// `line`, where the tool works with `strength` (`None`: it does not work there: travel).
    pub fn push(&mut self, t: f64, pose: [f64; 4], line: usize, strength: Option<f64>) {
        let at = [pose[0], pose[1], pose[2]];
        // A corner: the previous sample ended a move; keep it.
        let corner = self.line.replace(line).is_some_and(|previous| previous != line);
        let was = self.last.map(|point| point.strength);
        if was != strength && self.changes.len() < self.max_changes {
            self.changes.push((t, strength.unwrap_or(-1.0)));
        }
        let Some(strength) = strength else {
            self.end_stroke();
            return;
        };
        let point = WorkPoint { t, at, strength, start: false };
        match self.last {
            Some(mut last) if last.strength == strength => {
                if corner && let Some(pending) = self.pending {
                    self.keep(pending);
                    last = pending;
                }
                let far = (0..3).map(|k| (at[k] - last.at[k]).powi(2)).sum::<f64>().sqrt()
                    >= self.spacing;
                if far {
                    self.keep(point);
                } else {
                    self.pending = Some(point);
                }
            }
            _ => {
                self.end_stroke();
                self.keep(WorkPoint { start: true, ..point });
            }
        }
    }

    /// Keeps the stroke's last sample, so that it ends where the tool stopped.
    pub fn end_stroke(&mut self) {
        if let Some(pending) = self.pending.take() {
            self.keep(pending);
        }
        self.last = None;
    }

    fn keep(&mut self, point: WorkPoint) {
        self.pending = None;
        self.last = Some(point);
        self.points.push(point);
        if self.points.len() > self.capacity {
            // A stroke's first and last points stay.
            thin(&mut self.points, |points, index| {
                points[index].start || points.get(index + 1).is_none_or(|next| next.start)
            });
            self.spacing *= 2.0;
        }
    }

    /// The points kept, with the latest sample of the stroke being drawn.
    pub fn points(&self) -> impl Iterator<Item = &WorkPoint> {
        self.points.iter().chain(&self.pending)
    }

    /// When the tool's state changed: time (s) and strength, −1 when it stopped working.
    pub fn changes(&self) -> &[(f64, f64)] {
        &self.changes
    }

    /// Whether no point of work is kept.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty() && self.pending.is_none()
    }
}

/// Most points of the tool's work a picture keeps (as [`crate::ViewerOptions`]'s default).
pub const MAX_WORK_POINTS: usize = 40_000;

/// A program's samples laid over a trajectory (`biscara view`) or a picture (`biscara plot`):
/// the tool's work and where the program ends, sampled no further than a second past the end of
/// what it is laid over (a program that loops forever while moving ends there).
#[derive(Debug, Clone)]
pub struct ProgramOverlay {
    tool: ToolKind,
    work: ToolWork,
    until: Option<f64>,
    end: f64,
}

impl ProgramOverlay {
    /// How far past `until` a program is still sampled, s.
    pub const GRACE_S: f64 = 1.0;

    /// The work of `tool`, at most `max_points` points and `max_changes` changes, sampled up to
    /// [`ProgramOverlay::GRACE_S`] past `until` (s; `None`: to the program's end).
    pub fn new(
        tool: ToolKind,
        max_points: usize,
        max_changes: usize,
        until: Option<f64>,
    ) -> ProgramOverlay {
        ProgramOverlay { tool, work: ToolWork::new(max_points, max_changes), until, end: 0.0 }
    }

    /// Adds the next sample, where the tool works with `strength` (`None`: it does not). Returns
    /// `false`, taking nothing but its time, for a sample past the cut-off: sample no further.
    pub fn push(&mut self, sample: &CartesianSample, strength: Option<f64>) -> bool {
        self.end = sample.t;
        if self.until.is_some_and(|until| sample.t > until + Self::GRACE_S) {
            return false;
        }
        self.work.push(sample.t, sample.pose, sample.line, strength);
        true
    }

    /// The time of the last sample pushed, s.
    pub fn end(&self) -> f64 {
        self.end
    }

    /// Whether the program, as sampled, ends more than `tolerance` (s, plus 1 µs) away from
    /// `duration`: a sign it was sampled otherwise than what it is laid over.
    pub fn ends_apart_from(&self, duration: f64, tolerance: f64) -> bool {
        (duration - self.end).abs() > 1e-6 + tolerance
    }

    /// The tool.
    pub fn tool(&self) -> ToolKind {
        self.tool
    }

    /// The tool's work so far.
    pub fn work(&self) -> &ToolWork {
        &self.work
    }

    /// The tool's work, its last stroke ended.
    pub fn into_work(mut self) -> ToolWork {
        self.work.end_stroke();
        self.work
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_process_is_kept_as_strokes_apart_from_travel_and_stays_bounded() {
        let mut process = ToolWork::new(100, 10);
        // Burn along x from 0 to 10 mm (0.1 mm a sample), travel, burn at half power.
        for step in 0..=100 {
            process.push(f64::from(step), [f64::from(step) * 0.1, 0.0, 0.0, 0.0], 1, Some(1.0));
        }
        process.push(101.0, [20.0, 0.0, 0.0, 0.0], 2, None);
        for step in 0..=10 {
            process.push(200.0 + f64::from(step), [0.0, f64::from(step), 0.0, 0.0], 3, Some(0.5));
        }
        process.end_stroke();
        let starts: Vec<f64> = process.points.iter().filter(|p| p.start).map(|p| p.t).collect();
        assert_eq!(starts, [0.0, 200.0], "two strokes");
        // Points 0.5 mm apart, each stroke ending where the tool stopped.
        let first: Vec<&WorkPoint> = process.points.iter().filter(|p| p.t < 150.0).collect();
        assert_eq!(first.len(), 21);
        assert_eq!(first.last().map(|p| p.at[0]), Some(10.0));
        assert!(process.points.iter().all(|p| p.at[0] <= 10.0), "travel is not work");
        assert_eq!(process.changes, [(0.0, 1.0), (101.0, -1.0), (200.0, 0.5)]);
        // A corner is kept: the last sample of a line, however close to the last point.
        let mut corner = ToolWork::new(100, 10);
        for step in 0..=34 {
            let x = (f64::from(step) * 0.3).min(10.0);
            corner.push(f64::from(step), [x, 0.0, 0.0, 0.0], 1, Some(1.0));
        }
        for step in 1..=10 {
            corner.push(40.0 + f64::from(step), [10.0, f64::from(step), 0.0, 0.0], 2, Some(1.0));
        }
        assert!(corner.points.iter().any(|p| p.at == [10.0, 0.0, 0.0]), "{:?}", corner.points);
        // A long job: thinned to the capacity, both ends of every stroke kept.
        for step in 0..100_000 {
            let t = 1000.0 + f64::from(step);
            let strength = if step % 5000 < 4000 { Some(1.0) } else { None };
            process.push(t, [f64::from(step) * 0.3, 5.0, 0.0, 0.0], 4, strength);
        }
        assert!(process.points.len() <= 101, "{}", process.points.len());
        assert!(process.points.iter().any(|p| p.start && p.t > 90_000.0));
        assert!(process.changes.len() <= 10);
    }

    #[test]
    fn the_overlay_stops_a_second_past_the_end_and_says_where_the_program_ends() {
        let sample =
            |t: f64| CartesianSample { t, pose: [t, 300.0, 0.0, 0.0], line: 1, gripper: false };
        let mut overlay = ProgramOverlay::new(ToolKind::Pen, 100, 10, Some(2.0));
        for step in 0..=30 {
            let t = f64::from(step) * 0.1;
            let taken = overlay.push(&sample(t), Some(1.0));
            assert_eq!(taken, t <= 3.0 + 1e-9, "t = {t}");
        }
        assert!((overlay.end() - 3.0).abs() < 1e-9);
        assert!(overlay.ends_apart_from(2.0, 0.1) && !overlay.ends_apart_from(3.0, 0.0));
        let work = overlay.into_work();
        assert_eq!(work.points().last().map(|p| p.at[0]), Some(3.0), "the stroke's end kept");
        let mut open = ProgramOverlay::new(ToolKind::Laser, 100, 10, None);
        assert!(open.push(&sample(1e6), None), "no cut-off without an end");
    }
}
