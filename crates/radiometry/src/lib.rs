//! Radiometry for thermal-infrared scene simulation: blackbody band radiance `L(T)`, its
//! derivative and its inverse `T(L)` over a spectral band with an optional sensor response
//! (thesis §3.1, eq. 2 and 6), angular emissivity tables and their hemispherical mean
//! (§3.2.2, eq. 5), Fresnel emissivity from a complex refractive index, and the closed-form
//! calculators of Appendices A (specular bounces) and B (shape factor).
//!
//! Everything is SI: kelvin, metres inside, µm at the band API, radiance in W m^-2 sr^-1.
//! Constants are CODATA 2018. The crate knows no geometry and no file syntax.
//!
//! ```
//! use irsig_radiometry::Band;
//! let band = Band::default(); // 8–14 µm, flat response
//! let l = band.radiance(300.0);
//! assert!((l - 54.9335).abs() < 1e-4); // W m^-2 sr^-1
//! assert!((band.temperature(l) - 300.0).abs() < 1e-9);
//! // Apparent temperature of a grey body: ε L(T) inverted.
//! let apparent = band.temperature(0.98 * l);
//! assert!(apparent < 300.0 && apparent > 298.0);
//! ```

#![deny(clippy::print_stdout, clippy::print_stderr)]

mod band;
mod band_model;
pub mod calculators;
pub mod constants;
mod emissivity;
mod error;
pub mod fresnel;
mod inverse;
mod planck;
mod planck_weights;
mod spectral_emissivity;
mod table;

pub use band::{Band, SensorResponse, gauss_legendre};
pub use band_model::{
    AnyBand, BandModel, STEFAN_BOLTZMANN_W_M2_K4, TotalRadiance, apparent_temperatures,
};
pub use calculators::{
    Surface, bounce_radiances, bounce_temperatures, shape_factor_radiance, shape_factor_temperature,
};
pub use emissivity::EmissivityTable;
pub use error::{RadiometryError, RadiometryErrorKind};
pub use inverse::InverseTable;
pub use planck::spectral_radiance_per_um;
pub use spectral_emissivity::{band_average_emissivities, band_average_emissivity};
pub use table::RadianceTable;
