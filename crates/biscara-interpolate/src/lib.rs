//! Cartesian interpolation (docs/motion.md): turns a stream of [`Motion`]s into a stream of
//! [`CartesianSample`]s at a fixed time step, as the paper's `interpolation` did, and writes and
//! reads the path CSV.
//!
//! Lines, true arcs and helices ([`Segment`]); C in proportion to the path parameter; three
//! velocity profiles ([`Profile`]): the paper's constant speed, a trapezoid with an exact stop
//! at every corner, and the time-optimal one under the joints' velocity and acceleration limits
//! (TOPP-RA, from `biscara-timing`), also from rest to rest. Every programmed end point is hit
//! exactly by a sample, because each motion's duration is rounded up to whole steps (its speed
//! lowered, never raised). A [`SpeedLimit`] lets a later stage (the joint velocities) slow a move
//! down.
//!
//! It knows nothing of G-code text or of kinematics: motions come from any iterator, and joint
//! limits arrive through [`SpeedLimit`]. It streams: memory does not grow with the program.
//!
//! ```
//! use biscara_interpolate::{CartesianLimits, InterpolationConfig, Interpolator, NoSpeedLimit, Profile};
//! use biscara_motion::{Feed, Motion, MotionKind};
//!
//! let config = InterpolationConfig {
//!     dt: 0.1,
//!     profile: Profile::Constant,
//!     start: [0.0, 400.0, 50.0, 0.0],
//!     limits: CartesianLimits {
//!         rapid_velocity: 500.0, rapid_rotation: 360.0,
//!         acceleration: 5000.0, rotation_acceleration: 7200.0,
//!     },
//!     grip_time: 0.0,
//! };
//! let feed = Feed { mm_per_min: 600.0, inverse_time: false };
//! let motions = [Ok::<_, std::convert::Infallible>(Motion {
//!     line: 1,
//!     kind: MotionKind::Linear { end: [10.0, 400.0, 50.0, 0.0], feed },
//!     extrude: None,
//!     blend: None,
//!     naive_cam: None,
//! })];
//! let samples: Vec<_> = Interpolator::new(motions.into_iter(), config, NoSpeedLimit, |_| {})
//!     .collect::<Result<_, _>>()?;
//! assert_eq!(samples.len(), 11); // t = 0 and ten steps of 1 mm at 10 mm/s
//! assert_eq!(samples[10].pose, [10.0, 400.0, 50.0, 0.0]);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod chain;
mod csv;
mod interpolator;
mod profile;

pub use biscara_motion::Motion;

pub use biscara_motion::Segment;
pub use biscara_timing::Constraint;
pub use csv::{PATH_HEADER, PathCsvError, PathCsvReader, PathCsvWriter, read_path_csv};
pub use interpolator::{
    CartesianLimits, CartesianSample, InterpolateError, InterpolationConfig, Interpolator,
    JointBound, MAX_JOINTS, NoSpeedLimit, PLANNER_FALLBACK, RateLimit, SlowDown, SpeedLimit,
};
pub use profile::{Profile, Timing};
