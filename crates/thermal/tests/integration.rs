//! The thermal solver's integration tests, one module per file, in one test binary: one link and one set of
//! generic instantiations instead of one per file, and one pool of test threads across
//! all of them.
//! `cargo test -p irsig-thermal --test integration analytic::` runs one module.

mod analytic;
mod common;
mod convergence;
mod extremes;
mod independent;
