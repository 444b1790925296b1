//! The tracer's integration tests, one module per file, in one test binary: one link and one
//! set of generic instantiations instead of one per file, and one pool of test threads
//! across all of them.
//! `cargo test -p irsig-tracer --test integration adaptive::` runs one module.

mod adaptive;
mod air;
mod budget;
mod budget_mixed;
mod data_error;
mod exposure;
mod footprint;
mod guarantee;
mod guarantee_sun;
mod image_map;
mod material_map;
mod path_table;
mod pilot;
mod radiance;
mod refine;
mod spectral;
mod sun;
mod sun_path;
mod sun_truth;
mod terrain;
mod texture;
mod texture_tolerance;
mod texture_truth;
mod tiles;
mod trades;
