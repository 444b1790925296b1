//! The file formats' integration tests, one module per file, in one test binary: one link and one
//! set of generic instantiations instead of one per file, and one pool of test threads
//! across all of them.
//! `cargo test -p irsig-formats --test integration binary_object_files::` runs one module.

mod binary_object_files;
mod canonical_roundtrip;
mod canonical_samples;
mod legacy_roundtrip;
mod legacy_samples;
mod malformed;
mod mesh_files;
mod radtran_files;
mod weather_files;
