//! Cartesian interpolation (work in progress: see the motion issue).
