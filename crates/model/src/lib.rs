//! The canonical irsig data model: what the stages hand each other.
//!
//! Every type here is plain data with serde derives and a `validate` method. Units are SI
//! and are named in field names wherever they could be confused: lengths in metres
//! (`_m`), temperatures in kelvin (`_k`), angles in degrees at the file boundary (`_deg`),
//! radiance in W m⁻² sr⁻¹ (`_w_m2_sr`).
//!
//! | type | written by | read by |
//! | --- | --- | --- |
//! | [`Object`] | `irsig-import` | `irsig-flatten` |
//! | [`Scene`] | the user | `irsig-flatten` |
//! | [`RawScene`] | `irsig-flatten` | `irsig-trace` |
//! | [`MaterialLibrary`] | the user, `irsig-material` | import, flatten, trace |
//! | [`Atmosphere`] | `irsig-atmos convert`, built-ins | `irsig-trace` |
//! | [`SpectralAtmosphere`] | `irsig-atmos build`, built-ins | `irsig-atmosphere::collapse` |
//! | [`loads::LoadsPlan`] | `irsig-atmos plan --loads` | `irsig-atmos build` |
//! | [`loads::BroadbandLoads`] | `irsig-atmos build` | the thermal model |
//! | [`View`] | the user, `irsig-atmos`/legacy conversion | `irsig-trace` |
//! | [`RegionSet`] | the user | `irsig-stats` |
//! | [`weather::Weather`] | `irsig-formats` (EPW, CSV) | `irsig-therm` |
//! | [`truth::Layer`] names | `irsig-trace` (EXR layers) | sensor, stats |
//! | [`frame::FrameFile`] kinds | `irsig-trace`, `irsig-merge` | `irsig-cli` (naming) |
//!
//! This crate knows no file syntax (the `irsig-formats` crate reads and writes these types
//! as RON, binary and the legacy formats), no physics and no geometry beyond the shapes of
//! the data.
//!
//! ```
//! use irsig_model::{Material, MaterialId, MaterialLibrary};
//! let lib = MaterialLibrary {
//!     materials: vec![Material {
//!         id: MaterialId(1),
//!         name: "asphalt".into(),
//!         emissivity: vec![(0.0, 0.96), (90.0, 0.0)],
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
//! assert!(lib.validate().is_ok());
//! assert_eq!(lib.by_name("asphalt").map(|m| m.id), Some(MaterialId(1)));
//! ```

#![deny(clippy::print_stdout, clippy::print_stderr)]

mod atmosphere;
pub mod decision;
mod error;
pub mod frame;
pub mod history;
pub mod image_map;
pub mod interp;
pub mod limits;
pub mod loads;
mod material;
pub mod material_map;
mod object;
mod plan;
pub mod provenance;
mod raw;
mod regions;
mod scene;
mod spectral;
pub mod texture;
pub mod thermal;
pub mod thermal_decision;
pub mod time;
pub mod truth;
pub mod uncertainty;
mod view;
pub mod weather;

pub use atmosphere::{
    Atmosphere, AtmosphereLevel, InterpolationResidual, RadiosondeLevel, SlantTables,
};
pub use error::{ModelError, ModelErrorKind};
pub use material::{Material, MaterialId, MaterialLibrary, SpectralAngular, SpectralEmissivity};
pub use object::{Facet, FacetUv, MAX_UV, Object, triangle_is_degenerate};
pub use plan::{
    AerosolModel, AtmospherePlan, MAX_VISIBILITY_M, PlanAerosol, PlanModel, PlanSlabs, PlanSun,
};
pub use raw::{MixTemperatures, RawFacet, RawScene};
pub use regions::{PixelBox, ReferenceColumn, ReferenceValue, Region, RegionSet};
pub use scene::{FacetOverride, FacetSelection, Placement, Scene, Terrain};
pub use spectral::{
    CorrectionPaths, ProfileLevel, SolarBeam, SolarPhase, SpectralAtmosphere, SpectralAxis,
    SpectralGrid, SpectralSlab, SpectralSlabTable, SpectralSlantTables, SpectralSolar,
};
pub use view::{LengthUnit, View};
