//! irsig-therm's integration tests, one module per file, in one test binary: one link and one set of
//! generic instantiations instead of one per file, and one pool of test threads across
//! all of them.
//! `cargo test -p irsig-therm --test integration cli::` runs one module.

mod cli;
mod mixture;
mod shadow;
