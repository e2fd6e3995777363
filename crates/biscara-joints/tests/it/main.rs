//! Integration tests of the joint-trajectory builder.

mod optimal;
mod trajectory;
