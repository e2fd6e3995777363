//! Integration tests of the joint-trajectory builder.

mod trajectory;
