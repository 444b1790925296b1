//! Helpers shared by the radiometry integration tests.

pub mod water;
