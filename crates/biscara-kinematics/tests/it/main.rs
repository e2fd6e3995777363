//! Integration tests of the kinematics crate: property round trips, θ3 in its limits and the
//! paper's equations.

mod paper;
mod round_trip;
mod strategies;
mod theta3;
