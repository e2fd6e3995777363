//! Integration tests of the kinematics crate: property round trips and the paper's equations.

mod paper;
mod round_trip;
mod strategies;
