//! irsig-tracer: the radiometric ray tracer of irsig (thesis §3.3, Figure 6, Appendix H).
//!
//! A [`Tracer`] holds a flattened scene in an obvhs CWBVH with a watertight triangle test
//! ([`geometry`]), every facet's blackbody radiance `L_T` precomputed, the terrain
//! background, a band model (`irsig_radiometry::BandModel`) and an atmosphere ([`Atmosphere`]). A
//! [`Camera`] (the ω φ κ matrix of Appendix H or a look-at view; pixel (0, 0) is the
//! top-left, see [`camera`]) gives the primary rays. Each ray meets one of the events of
//! thesis Figure 6 ([`Event`]) and gets
//!
//! ```text
//! L = τ·[ε(φ)·L_T + r(φ)·(s·L_spec + (1 − s)·(F·L_d + (1 − F)·L_b))] + L_u
//! ```
//!
//! with `s` the material's specular fraction, `L_spec` the surface-leaving radiance of the
//! facet the reflection ray hits (or the sky at the mirror angle), and `F` the sky-view
//! factor when that model is switched on ([`TraceOptions`]). τ and L_u come from the
//! atmosphere for the path between the hit point and the sensor (both altitudes). Facets
//! are two-sided ([`geometry`] explains why).
//!
//! With a sun ([`Tracer::with_sun`], [`sun`]), each facet of a path casts shadow rays
//! toward it and reflects its beam: Lambertian for the diffuse share, a glint from the
//! disk for the specular share.
//!
//! The tracer knows no file syntax; `irsig-trace` reads files and writes images.
//!
//! ```
//! use irsig_model::{Material, MaterialId, MaterialLibrary, RawFacet, RawScene, Terrain, View};
//! use irsig_radiometry::TotalRadiance;
//! use irsig_tracer::{Camera, TraceOptions, Tracer, Vacuum};
//!
//! // A 10 m blackbody square at 300 K on the ground, seen straight down from 100 m.
//! let scene = RawScene {
//!     terrain: Terrain::default(),
//!     objects: vec!["plate".into()],
//!     positions_m: vec![[-5.0, -5.0, 0.0], [5.0, -5.0, 0.0], [5.0, 5.0, 0.0], [-5.0, 5.0, 0.0]],
//!     facets: [[0, 1, 2], [0, 2, 3]]
//!         .map(|vertices| RawFacet { vertices, material: MaterialId(1), temperature_k: 300.0, object: 0, uv: None })
//!         .to_vec(),
//!     mix_temperatures: Vec::new(),
//! };
//! let materials = MaterialLibrary {
//!     materials: vec![Material {
//!         id: MaterialId(1),
//!         name: "black".into(),
//!         emissivity: vec![(0.0, 1.0), (90.0, 1.0)],
//!         specular_fraction: 0.0,
//!         source: "example".into(),
//!         band_um: None,
//!         spectral: None,
//!         rms_slope: None,
//!         thermal: None,
//!         texture: None,
//!         maps: None,
//!     }],
//! };
//! let tracer = Tracer::new(&scene, &materials, TotalRadiance, Vacuum::default())?;
//! let camera = Camera::from_view(&View::Legacy {
//!     position_m: [0.0, 0.0, 100.0],
//!     pixels: [4, 4],
//!     omega_phi_kappa_deg: [0.0, 0.0, 0.0],
//!     fov_deg: [2.0, 2.0],
//!     gain_dc_per_k: None,
//! })?;
//! let frame = tracer.render(&camera, &TraceOptions::default(), &|_| {})?;
//! let t = tracer.apparent_temperature_k(frame.radiance_w_m2_sr[5]);
//! assert!((t - 300.0).abs() < 1e-9);
//! # Ok::<(), irsig_tracer::TraceError>(())
//! ```

#![deny(clippy::print_stdout, clippy::print_stderr)]

pub mod camera;
pub mod charge;
pub mod data_error;
mod day;
mod differential;
pub mod env;
mod error;
pub mod exposure;
pub mod geometry;
pub mod horizon_census;
mod lobe;
mod mixture;
mod path;
mod path_table;
pub mod pilot;
mod probe_text;
pub mod reference;
pub mod refine;
mod shade;
pub mod slab_census;
pub mod sun;
mod terrain;
#[cfg(any(test, feature = "testing"))]
pub mod testing;
mod texture;
pub mod tile;
mod tracer;

pub use camera::{
    Camera, look_at_omega_phi_kappa_deg, omega_phi_kappa_matrix, thesis_look_at_angles_deg,
};
pub use charge::{Charge, Charges, NO_GROUP};
pub use env::{Atmosphere, Vacuum};
pub use error::{TraceError, TraceErrorKind};
pub use glam::DVec3;
pub use lobe::{DISK_PSI_NODES, DISK_U_NODES};
pub use path_table::{
    PATH_TABLE_ALTITUDES, PATH_TABLE_RANGES, PathTermsMode, UnknownPathTermsMode,
};
pub use refine::{PixelSampling, Refinement};
pub use sun::{SUN_ANGULAR_RADIUS_DEG, Sun, SunBeam};
pub use tile::{Tile, TileError};
pub use tracer::{
    BandSet, Event, FacetRadiometry, Frame, INVERSE_TABLE_K, Sample, SubBand, SunPixel,
    TexturePixel, TraceOptions, Tracer, TruthPixel, inverse_table,
};
