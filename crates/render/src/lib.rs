//! irsig-render: one frame's library work, between the command lines of `irsig-trace` and
//! `irsig-merge` and the libraries that do the physics.
//!
//! A [`PlanBuilder`] takes a typed [`Request`] (the band, the atmosphere, the models or a
//! tolerance, the counts' calibration) and the inputs' bytes (scene, materials, views,
//! declared uncertainties, a decision), reads and checks them, and builds the [`Plan`],
//! which renders: it resolves the
//! atmosphere for the band (a vacuum, a built-in or a file; band tables, or spectra
//! collapsed over the band or each sub-band, [`band`]), averages spectral materials over
//! them ([`materials`]), builds the tracer once, runs the tolerance pilot per frame when
//! asked ([`tolerance`]), traces, and makes each frame's files ([`products`]: radiance,
//! truth and budget layers, counts, LUT, interaction map), which it gives to the caller's
//! [`Sink`]. `irsig-merge` makes the same files from merged tiles with
//! [`products::merged`]. Nothing here reads or writes a file, parses a flag or prints:
//! every error is a [`RenderError`] that keeps the error it wraps as its source (an
//! input's parse error with its place in the file); errors about the request are its
//! [`RequestError`]s naming a [`Setting`]; warnings go to the sink.
//!
//! ```
//! use irsig_render::{AtmosphereRequest, BandRequest, PlanBuilder, Request, Spelling};
//! let request = Request {
//!     band: BandRequest::total(),
//!     atmosphere: AtmosphereRequest::Vacuum { sky_radiance_w_m2_sr: -1.0 },
//!     settings: Default::default(),
//!     tolerance: None,
//!     sun: None,
//!     counts: Default::default(),
//!     defaulted: vec![],
//!     spelling: Spelling(|setting| format!("{setting:?}")),
//! };
//! // A sky radiance below 0 is refused before anything is read.
//! let e = PlanBuilder::new(request).unwrap_err();
//! assert!(e.to_string().contains("out of range"));
//! ```

#![deny(clippy::print_stdout, clippy::print_stderr)]

mod air;
pub mod band;
pub mod budget;
mod error;
pub mod guarantee;
mod maps;
pub mod materials;
mod observer;
mod plan;
pub mod products;
mod run_hash;
pub mod settings;
pub mod sun;
pub mod tolerance;

pub use air::AtmosphereRequest;
pub use band::BandRequest;
pub use error::{CallerError, RenderError, RenderErrorKind, RequestError, Setting, Spelling};
pub use maps::read_material_map_of;
pub use plan::{
    DATA_ERROR_BYTES_PER_PIXEL, FRAME_BYTES_PER_PIXEL, Plan, PlanBuilder, Request, Sink,
    TEXTURE_BYTES_PER_PIXEL, TileRequest, ToleranceRequest,
};
pub use run_hash::RunHash;
pub use sun::SunRequest;
