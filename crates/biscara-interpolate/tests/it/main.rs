//! Integration tests of the interpolator.

mod interpolation;
mod strategies;
