//! The radiometry's integration tests, one module per file, in one test binary: one link and one set of
//! generic instantiations instead of one per file, and one pool of test threads across
//! all of them.
//! `cargo test -p irsig-radiometry --test integration band::` runs one module.

mod band;
mod common;
mod fresnel;
mod rough;
mod thesis_tables;
