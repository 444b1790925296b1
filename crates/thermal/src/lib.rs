//! Facet temperatures from physics: transient one-dimensional conduction through a facet's
//! wall of layers, implicit time stepping, and the energy balance of its exposed surface.
//!
//! Each facet is a wall (its material's layers, front first, and what lies behind them:
//! [`irsig_model::thermal::ThermalProperties`]) cut into finite volumes ([`Wall`],
//! [`Discretisation`]), with an exposed [`Surface`] that absorbs sunlight and longwave
//! radiation, emits `ε σ T⁴`, convects to the air by a named correlation ([`Convection`])
//! and, where wet, evaporates ([`latent`]). [`step`] advances its node temperatures over
//! one time step from the [`Loads`] at the step's start and end by Backward Euler,
//! Crank–Nicolson or TR-BDF2 ([`Scheme`]), solving the nonlinear surface balance exactly,
//! and returns the step's energy terms ([`StepFluxes`]), which close to round-off.
//!
//! The crate is pure physics: the loads arrive as numbers. It knows no ray tracer, no
//! atmosphere model, no weather file or other file syntax and no command line, and never
//! prints; `irsig-therm` computes the loads and drives it facet by facet. Everything is SI:
//! kelvin, metres, seconds, W m⁻², J m⁻².
//!
//! ```
//! use irsig_model::thermal::{BackBoundary, Roughness, ThermalLayer, ThermalProperties};
//! use irsig_thermal::{
//!     Convection, Discretisation, Facet, Loads, Orientation, Scheme, Scratch, Surface,
//!     TimeStep, Wall, step,
//! };
//!
//! // 0.1 m of concrete on an insulated back (Incropera, Table A.3).
//! let props = ThermalProperties {
//!     layers: vec![ThermalLayer {
//!         thickness_m: 0.1,
//!         conductivity_w_m_k: 1.4,
//!         density_kg_m3: 2300.0,
//!         specific_heat_j_kg_k: 880.0,
//!         source: "Incropera, Table A.3".into(),
//!     }],
//!     back: BackBoundary::Adiabatic,
//!     solar_absorptance: Some(0.65),
//!     thermal_emissivity: Some(0.9),
//!     wet_fraction: 0.0,
//!     roughness: Roughness::MediumRough,
//!     source: "example".into(),
//! };
//! let wall = Wall::new(&props, &Discretisation::max_spacing(0.01, 2)).unwrap();
//! let surface = Surface {
//!     solar_absorptance: 0.65,
//!     thermal_emissivity: 0.9,
//!     wet_fraction: 0.0,
//!     roughness: Roughness::MediumRough,
//!     convection: Convection::Doe2,
//! };
//! let facet = Facet {
//!     wall: &wall,
//!     surface: &surface,
//!     orientation: Orientation { cos_tilt: 1.0, windward: true },
//! };
//! let noon = Loads {
//!     shortwave_w_m2: 800.0,
//!     longwave_w_m2: 350.0,
//!     air_temperature_k: 300.0,
//!     dew_point_k: 285.0,
//!     pressure_pa: 101_325.0,
//!     wind_speed_m_s: 2.0,
//!     source_w_m2: 0.0,
//! };
//! let mut temps = wall.uniform_state(300.0);
//! let mut scratch = Scratch::new();
//! let time_step = TimeStep { dt_s: 300.0, scheme: Scheme::BackwardEuler };
//! let mut total = irsig_thermal::StepFluxes::default();
//! for _ in 0..12 {
//!     total += step(&facet, &mut temps, &noon, &noon, time_step, &mut scratch).unwrap();
//! }
//! // An hour in the noon sun warms the surface well above the air.
//! assert!(temps[0] > 310.0 && temps[0] < 350.0);
//! // Every joule is accounted for.
//! assert!(total.imbalance_j_m2().abs() < 1e-6 * total.absorbed_shortwave_j_m2);
//! ```

#![deny(clippy::print_stdout, clippy::print_stderr)]

mod convection;
mod error;
pub mod latent;
pub mod sky;
mod step;
mod surface;
mod wall;

pub use convection::{Convection, Orientation};
pub use error::{ThermalError, ThermalErrorKind};
pub use step::{
    Facet, SURFACE_TOLERANCE_K, Scheme, Scratch, StepFluxes, TimeStep, step, step_held,
};
pub use surface::{Loads, STEFAN_BOLTZMANN_W_M2_K4, Surface};
pub use wall::{Discretisation, MAX_NODES, NodeSpacing, Wall};

/// The lowest temperature the solver accepts or produces, K.
pub const MIN_TEMPERATURE_K: f64 = 1.0;
/// The highest temperature the solver accepts or produces, K.
pub const MAX_TEMPERATURE_K: f64 = 5000.0;
