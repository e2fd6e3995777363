//! Integration tests of the G-code interpreter: one test binary, one module per feature.

mod common;
mod conformance;
mod dialects;
mod endless;
mod fanuc;
mod features;
mod fourth_round;
mod memory;
mod no_panic;
mod owords;
#[cfg(feature = "python")]
mod python;
mod rs274_record;
mod splines;
mod strategies;
mod streaming;
