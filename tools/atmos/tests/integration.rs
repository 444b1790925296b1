//! irsig-atmos's integration tests, one module per file, in one test binary: one link and one set of
//! generic instantiations instead of one per file, and one pool of test threads across
//! all of them.
//! `cargo test -p irsig-atmos --test integration convert::` runs one module.

mod convert;
mod modtran_solar;
mod sun;
