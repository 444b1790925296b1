//! The atmosphere models' integration tests, one module per file, in one test binary: one link and one set of
//! generic instantiations instead of one per file, and one pool of test threads across
//! all of them.
//! `cargo test -p irsig-atmosphere --test integration builtin::` runs one module.

mod builtin;
mod common;
mod lowtran;
mod models;
mod shared_paths;
mod spectral;
