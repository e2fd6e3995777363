//! Integration tests of the points reader and CL generator: property tests on arbitrary input.

mod readers;
mod strategies;
