//! Integration tests of the virtual robot.
