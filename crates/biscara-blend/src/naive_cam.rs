//! G64 Q: LinuxCNC's naive-CAM detector, a stage before blending.
//!
//! CAM output often approximates a straight edge by many nearly collinear short moves. Under
//! G64 with a Q tolerance (a straight feed move's [`Motion::naive_cam`]), consecutive straight
//! feed moves (G1) are merged into one while every end point the merged move leaves out lies
//! within Q of the straight line from the chain's start to its new end. A move joins the chain
//! only when it is a G1 like the chain's moves: the same feed, the same P, the same Q, C not
//! turning, no extrusion; anything else (a rapid, an arc, an event, a move without Q, another
//! feed, a move that feeds filament) ends the chain first, and so do [`MAX_MERGED`] moves. The
//! merged move keeps the line of the last move it replaces (as LinuxCNC's does).
//!
//! Every point of the programmed polyline then lies within Q of the merged move and every
//! point of the merged move within Q of the polyline (each left-out point is within Q of the
//! chord, and the polyline runs from the chord's start to its end); the blends that follow keep
//! the path within P of the merged moves: the blended path lies within P + Q of the program.

use std::collections::VecDeque;

use biscara_motion::{Motion, MotionKind};

/// The most moves merged into one (LinuxCNC's bound too): the check of a new end point costs
/// one distance per point held.
pub const MAX_MERGED: usize = 100;

/// Merges nearly collinear straight feed moves; see the module documentation.
///
/// Holds at most [`MAX_MERGED`] end points and two motions to yield: memory does not grow with
/// the program.
#[derive(Debug)]
pub struct NaiveCam<I: Iterator> {
    motions: I,
    /// Where the next motion from the source starts.
    position: [f64; 4],
    /// The chain: where it starts, its first move (for its feed and tolerances), and the end
    /// points of its moves (the last is its end).
    start: [f64; 4],
    first: Option<Motion>,
    points: Vec<[f64; 4]>,
    last_line: usize,
    out: VecDeque<Motion>,
    /// The source's error, given after what was read before it.
    error: Option<I::Item>,
    done: bool,
}

impl<I, E> NaiveCam<I>
where
    I: Iterator<Item = Result<Motion, E>>,
{
    /// Merges the motions of `motions`, the first of which starts at `start`, each with its
    /// own tolerance ([`Motion::naive_cam`]).
    pub fn new(motions: I, start: [f64; 4]) -> NaiveCam<I> {
        NaiveCam {
            motions,
            position: start,
            start,
            first: None,
            points: Vec::new(),
            last_line: 0,
            out: VecDeque::new(),
            error: None,
            done: false,
        }
    }

    /// The chain as one move, queued.
    fn flush(&mut self) {
        if let (Some(first), Some(&end)) = (self.first.take(), self.points.last()) {
            let MotionKind::Linear { feed, .. } = first.kind else { unreachable!("a G1") };
            let kind = MotionKind::Linear { end, feed };
            self.out.push_back(Motion { line: self.last_line, kind, ..first });
        }
        self.points.clear();
    }

    /// Whether `motion` (a G1 to `end`) can join the chain.
    fn joins(&self, motion: &Motion, end: [f64; 4]) -> bool {
        let Some(first) = self.first else { return false };
        let (MotionKind::Linear { feed, .. }, MotionKind::Linear { feed: chain_feed, .. }) =
            (motion.kind, first.kind)
        else {
            return false;
        };
        let same = feed == chain_feed
            && motion.blend == first.blend
            && motion.naive_cam == first.naive_cam;
        let Some(tolerance) = first.naive_cam.filter(|_| same) else { return false };
        if self.points.len() >= MAX_MERGED {
            return false;
        }
        self.points.iter().all(|&point| distance_to_chord(point, self.start, end) <= tolerance)
    }

    fn take(&mut self, motion: Motion) {
        let from = self.position;
        let end = motion.kind.end();
        if let Some(end) = end {
            self.position = end;
        }
        // A move that feeds filament keeps it: merged, its extrusion would be lost.
        let mergeable = matches!(motion.kind, MotionKind::Linear { .. })
            && motion.blend.is_some()
            && motion.extrude.is_none()
            && motion.naive_cam.is_some_and(|q| q > 0.0);
        let Some(end) = end.filter(|end| mergeable && end[3] == from[3]) else {
            self.flush();
            self.out.push_back(motion);
            return;
        };
        if !self.joins(&motion, end) {
            self.flush();
            self.start = from;
            self.first = Some(motion);
        }
        self.points.push(end);
        self.last_line = motion.line;
    }
}

/// The distance from `point` to the segment from `a` to `b` (XYZ).
fn distance_to_chord(point: [f64; 4], a: [f64; 4], b: [f64; 4]) -> f64 {
    let ab = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let ap = [point[0] - a[0], point[1] - a[1], point[2] - a[2]];
    let length2 = ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2];
    let along = if length2 > 0.0 {
        ((ap[0] * ab[0] + ap[1] * ab[1] + ap[2] * ab[2]) / length2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let off: [f64; 3] = std::array::from_fn(|k| ap[k] - along * ab[k]);
    (off[0] * off[0] + off[1] * off[1] + off[2] * off[2]).sqrt()
}

impl<I, E> Iterator for NaiveCam<I>
where
    I: Iterator<Item = Result<Motion, E>>,
{
    type Item = Result<Motion, E>;

    fn next(&mut self) -> Option<Self::Item> {
        loop {
            if let Some(motion) = self.out.pop_front() {
                return Some(Ok(motion));
            }
            if self.done {
                return self.error.take();
            }
            match self.motions.next() {
                // No chain held and a motion that cannot start one (any program without
                // G64 Q): it passes at once.
                Some(Ok(motion)) if self.first.is_none() && motion.naive_cam.is_none() => {
                    if let Some(end) = motion.kind.end() {
                        self.position = end;
                    }
                    return Some(Ok(motion));
                }
                Some(Ok(motion)) => self.take(motion),
                Some(Err(err)) => {
                    // What was read before the error goes first, as one move.
                    self.flush();
                    self.done = true;
                    self.error = Some(Err(err));
                }
                None => {
                    self.done = true;
                    self.flush();
                }
            }
        }
    }
}
