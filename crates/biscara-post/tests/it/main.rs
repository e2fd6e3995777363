//! Integration tests of the CL reader and postprocessor: property tests on arbitrary input.

mod readers;
mod strategies;
