//! Corner blending under G64 P (docs/motion.md): consecutive moves programmed under G64
//! (straight or arcs) are joined by circular fillets that stay within the tolerance P of the programmed
//! corner, and arcs tangent to the moves before and after them join the same chain, so that a
//! timing law can run through the corner without stopping.
//!
//! The [`Blender`] reads motions (with one motion of look-ahead) and yields [`Blended`] items:
//! the [`Piece`]s of a blended chain (trimmed straight moves and arcs, the fillets between
//! them), or the motions it leaves alone (events, moves under exact stop, arcs that
//! join no chain), which it passes on unchanged. It knows nothing of kinematics, limits or time.
//!
//! # The blend
//!
//! A corner between two straight moves of XYZ length `la`, `lb` that turns by θ is cut by the
//! circular arc tangent to both, of radius `r`, which starts and ends a distance
//! `d = r · tan(θ/2)` from the corner; its midpoint lies `r · (1/cos(θ/2) − 1)` from the corner,
//! the farthest the blended path gets from the programmed one. The radius is the largest with:
//!
//! - that deviation at most the tolerance P (G64 without P, or `P0`: at most
//!   [`NO_TOLERANCE_CAP_MM`]);
//! - `d` at most half of either move, so that the blends at the two ends of a move never
//!   overlap. A move too short for the blend the tolerance allows gets the smaller blend that
//!   fits (the deviation is then smaller than P), as LinuxCNC shrinks its blends; one that turns
//!   by more than [`MAX_TURN_DEG`] or whose blend would be shorter than [`MIN_TRIM_MM`] is an
//!   exact stop.
//!
//! A corner is blended when both moves carry a tolerance ([`Motion::blend`](biscara_motion::Motion::blend)); the smaller one
//! holds. Rapid and feed moves blend alike; a fillet between moves of different speeds is cut
//! at its middle, each half at the speed of the move whose corner part it replaces (so that a
//! rapid followed by a slow plunge is never slower blended than stopped).
//! The C axis moves in proportion to the length along each piece. A corner where C turns (on
//! either move) is an exact stop, and so is a straight-on junction where C's rate per mm
//! changes: C's rate along the path would jump there, and a jump in a joint's rate along the
//! path at speed is an acceleration no limit allows. Any event, move with no XYZ length or move
//! under exact stop ends the chain: the robot stops there.
//!
//! # Arcs
//!
//! A programmed arc (G2/G3) under G64 joins the chain without a fillet where its direction of
//! travel at the junction is the neighbour's (within 1e-9 rad, as for moves that go straight
//! on) and C's rate per mm does not jump. Where an arc meets a line or another arc at a corner,
//! the corner is blended as LinuxCNC does: the line and the arc are trimmed (the trimmed arc
//! keeps its centre and radius, with a shorter sweep) and joined by a circular fillet tangent to
//! both, in the arc's plane, the largest (found by bisection) for which the programmed corner
//! lies within P of the fillet, a line is trimmed by at most half of it, an arc by at most half
//! of its sweep:
//!
//! - a line and an arc: the fillet touches the arc at the point where it is cut, with the arc's
//!   own tangent there (its centre on the arc's normal, `r` from the line), so that an arc whose
//!   end radius differs a little from its start radius (a spiral: CAM coordinates rounded to a
//!   few decimals) blends too;
//! - two arcs (both circles, in one plane): the fillet's centre lies `R ± r` from each arc's
//!   centre (inside an arc's circle where it bends towards the inside of the corner, outside it
//!   where it bends away).
//!
//! The rules of straight corners hold: [`MAX_TURN_DEG`] (for the fillet's own turn too, which
//! exceeds the corner's where the arcs bend towards each other: two arcs meeting almost head-on
//! stay an exact stop), [`MIN_TRIM_MM`], C turning on either move, P0 or no P; a fillet's radius
//! is at most 10 m. A corner stays an exact stop where an
//! arc is a helix, a line leaves the arc's plane, two arcs lie in different planes or one of
//! them is a spiral, or no fillet fits (an arc that joins nothing passes unchanged, timed alone
//! as under exact stop). So a profile of lines and arcs — tangent (a rounded rectangle, cutter
//! compensation's arcs round convex corners) or meeting at corners (a slot, a keyhole) — runs
//! through without stopping.
//!
//! # G64 Q
//!
//! [`NaiveCam`] is LinuxCNC's naive-CAM detector, a stage to run before the [`Blender`]:
//! consecutive straight feed moves under G64 Q
//! ([`Motion::naive_cam`](biscara_motion::Motion::naive_cam); same feed, P and Q, C not
//! turning, nothing between them) are merged into one while every end
//! point left out lies within Q of it. The merged path lies within Q of the programmed one, the
//! blends within P of the merged one: the deviation bound becomes P + Q.
//!
//! ```
//! use biscara_blend::{Blended, Blender};
//! use biscara_motion::{Feed, Motion, MotionKind};
//!
//! let feed = Feed { mm_per_min: 6000.0, inverse_time: false };
//! let corner = |line, end| Motion {
//!     blend: Some(0.05),
//!     ..Motion::new(line, MotionKind::Linear { end, feed })
//! };
//! let motions = [corner(1, [10.0, 0.0, 0.0, 0.0]), corner(2, [10.0, 10.0, 0.0, 0.0])];
//! let items: Vec<Blended> =
//!     Blender::new(motions.into_iter().map(Ok::<_, ()>), [0.0; 4]).collect::<Result<_, _>>()?;
//! // A trimmed line, the fillet, the rest of the second line.
//! assert_eq!(items.len(), 3);
//! let Blended::Piece(fillet) = &items[1] else { panic!() };
//! assert!(fillet.radius().is_some());
//! # Ok::<(), ()>(())
//! ```

#![warn(missing_docs)]

mod arcs;
mod blender;
mod naive_cam;
mod piece;

pub use blender::{Blended, Blender, MAX_TURN_DEG, MIN_TRIM_MM, NO_TOLERANCE_CAP_MM};
pub use naive_cam::{MAX_MERGED, NaiveCam};
pub use piece::{Geometry, Piece, Speed};
