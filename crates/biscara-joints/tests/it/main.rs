//! Integration tests of the joint-trajectory builder.

mod blend;
mod optimal;
mod torque;
mod trajectory;
