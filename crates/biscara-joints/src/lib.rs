//! Joint trajectories (work in progress: see the motion issue).
