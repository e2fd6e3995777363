//! Integration tests of the virtual robot.

mod checker;
mod optimal;
mod workspace;
