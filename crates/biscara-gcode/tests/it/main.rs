//! Integration tests of the G-code interpreter: one test binary, one module per feature.

mod dialects;
mod fanuc;
mod features;
mod memory;
mod no_panic;
mod owords;
mod python;
mod splines;
mod strategies;
mod streaming;
