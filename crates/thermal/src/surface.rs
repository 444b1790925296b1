//! The exposed surface: its optical and wetting properties, the loads on it, and its
//! energy balance.

use irsig_model::thermal::Roughness;

use crate::convection::{Convection, ConvectionAt, ForcedCache, Orientation};
use crate::error::ThermalError;
use crate::latent::LatentAt;
use crate::{MAX_TEMPERATURE_K, MIN_TEMPERATURE_K};

/// The Stefan–Boltzmann constant, W m⁻² K⁻⁴ (CODATA 2018, exact from the SI's defining
/// constants).
pub const STEFAN_BOLTZMANN_W_M2_K4: f64 = 5.670_374_419e-8;

/// How a facet's exposed surface takes up and gives off heat. The tool resolves the
/// material record's optional absorptance and emissivity before building it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Surface {
    /// The share of incident sunlight (0.3–4 µm) absorbed, 0 to 1.
    pub solar_absorptance: f64,
    /// Broadband thermal-infrared hemispherical emissivity, 0 to 1: the share of incident
    /// longwave absorbed (Kirchhoff, grey) and the factor of `σ T⁴` emitted.
    pub thermal_emissivity: f64,
    /// The wet share of the surface, 0 (dry) to 1: see [`crate::latent`].
    pub wet_fraction: f64,
    /// The surface's roughness to the wind ([`Convection::Doe2`]'s multiplier).
    pub roughness: Roughness,
    /// The convection correlation.
    pub convection: Convection,
}

impl Surface {
    /// Checks the numbers.
    ///
    /// # Errors
    /// [`crate::ThermalErrorKind::InvalidInput`] naming the first number out of its range.
    pub fn validate(&self) -> Result<(), ThermalError> {
        for (name, v) in [
            ("solar_absorptance", self.solar_absorptance),
            ("thermal_emissivity", self.thermal_emissivity),
            ("wet_fraction", self.wet_fraction),
        ] {
            if !(0.0..=1.0).contains(&v) {
                return Err(ThermalError::input(format!(
                    "surface {name} {v} must lie between 0 and 1"
                )));
            }
        }
        if !self.convection.is_valid() {
            return Err(ThermalError::input(format!(
                "{:?}: a given convective coefficient must lie between 0 and 1e12 W/m²/K",
                self.convection
            )));
        }
        Ok(())
    }
}

/// What acts on a facet at one instant. Irradiances are incident, before the surface's
/// absorptance and emissivity are applied.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Loads {
    /// Solar irradiance on the surface, W m⁻², ≥ 0: beam · cos θ · visible fraction of the
    /// sun's disk + diffuse sky + reflected from the ground and other facets.
    pub shortwave_w_m2: f64,
    /// Longwave irradiance on the surface, W m⁻², ≥ 0: from the sky, the ground and other
    /// facets.
    pub longwave_w_m2: f64,
    /// The outdoor air's temperature, K.
    pub air_temperature_k: f64,
    /// The outdoor air's dew point, K (its water vapour, for a wet surface's latent heat; a
    /// dew point above the air temperature is taken as given).
    pub dew_point_k: f64,
    /// Air pressure at the facet, Pa.
    pub pressure_pa: f64,
    /// Wind speed at the facet, m/s, ≥ 0.
    pub wind_speed_m_s: f64,
    /// A heat source deposited at the wall's back node, W m⁻² (an engine under a hood, a
    /// heater behind a panel; 0 for none; negative for a sink).
    pub source_w_m2: f64,
}

impl Loads {
    /// The loads a share `f` of the way from `self` to `to`, each linearly.
    #[must_use]
    pub fn lerp(&self, to: &Self, f: f64) -> Self {
        let mix = |a: f64, b: f64| irsig_model::interp::lerp(a, b, f);
        Self {
            shortwave_w_m2: mix(self.shortwave_w_m2, to.shortwave_w_m2),
            longwave_w_m2: mix(self.longwave_w_m2, to.longwave_w_m2),
            air_temperature_k: mix(self.air_temperature_k, to.air_temperature_k),
            dew_point_k: mix(self.dew_point_k, to.dew_point_k),
            pressure_pa: mix(self.pressure_pa, to.pressure_pa),
            wind_speed_m_s: mix(self.wind_speed_m_s, to.wind_speed_m_s),
            source_w_m2: mix(self.source_w_m2, to.source_w_m2),
        }
    }

    /// Checks every number against its physical range.
    ///
    /// # Errors
    /// [`crate::ThermalErrorKind::InvalidInput`] naming the first number out of its range.
    pub fn validate(&self) -> Result<(), ThermalError> {
        let temperature = MIN_TEMPERATURE_K..=MAX_TEMPERATURE_K;
        // One chain of comparisons on the way through every step; the message only on a
        // failure.
        let fine = (0.0..=1e7).contains(&self.shortwave_w_m2)
            && (0.0..=1e7).contains(&self.longwave_w_m2)
            && temperature.contains(&self.air_temperature_k)
            && temperature.contains(&self.dew_point_k)
            && (1.0..=1e7).contains(&self.pressure_pa)
            && (0.0..=1e3).contains(&self.wind_speed_m_s)
            && (-1e9..=1e9).contains(&self.source_w_m2);
        if fine {
            return Ok(());
        }
        for (name, v, range) in [
            ("shortwave_w_m2", self.shortwave_w_m2, 0.0..=1e7),
            ("longwave_w_m2", self.longwave_w_m2, 0.0..=1e7),
            (
                "air_temperature_k",
                self.air_temperature_k,
                temperature.clone(),
            ),
            ("dew_point_k", self.dew_point_k, temperature),
            ("pressure_pa", self.pressure_pa, 1.0..=1e7),
            ("wind_speed_m_s", self.wind_speed_m_s, 0.0..=1e3),
            ("source_w_m2", self.source_w_m2, -1e9..=1e9),
        ] {
            if !range.contains(&v) {
                return Err(ThermalError::input(format!(
                    "load {name} {v} must lie between {} and {}",
                    range.start(),
                    range.end()
                )));
            }
        }
        Ok(())
    }
}

/// The surface balance with one set of loads fixed.
#[derive(Debug, Clone, Copy)]
pub(crate) struct SurfaceAt {
    absorbed_shortwave_w_m2: f64,
    absorbed_longwave_w_m2: f64,
    emissivity_sigma: f64,
    air_k: f64,
    convection: ConvectionAt,
    latent: LatentAt,
}

/// The energy leaving the surface by each route at one surface temperature, W m⁻², and
/// each one's derivative in that temperature, W m⁻² K⁻¹.
#[derive(Debug, Clone, Copy)]
pub(crate) struct SurfaceParts {
    pub emitted: f64,
    pub convected: f64,
    pub latent: f64,
    pub d_emitted: f64,
    pub d_convected: f64,
    pub d_latent: f64,
}

impl SurfaceParts {
    /// What leaves in all, W m⁻².
    #[inline]
    pub(crate) fn leaving(&self) -> f64 {
        self.emitted + self.convected + self.latent
    }

    /// Its derivative in the surface temperature, W m⁻² K⁻¹.
    #[inline]
    pub(crate) fn d_leaving(&self) -> f64 {
        self.d_emitted + self.d_convected + self.d_latent
    }

    /// The parts `delta_k` further on, to first order: what Newton's last step solved.
    pub(crate) fn extrapolated(&self, delta_k: f64) -> Self {
        Self {
            emitted: self.emitted + self.d_emitted * delta_k,
            convected: self.convected + self.d_convected * delta_k,
            latent: self.latent + self.d_latent * delta_k,
            ..*self
        }
    }
}

impl SurfaceAt {
    pub(crate) fn new(
        surface: &Surface,
        orientation: Orientation,
        loads: &Loads,
        cache: &mut ForcedCache,
    ) -> Self {
        Self {
            absorbed_shortwave_w_m2: surface.solar_absorptance * loads.shortwave_w_m2,
            absorbed_longwave_w_m2: surface.thermal_emissivity * loads.longwave_w_m2,
            emissivity_sigma: surface.thermal_emissivity * STEFAN_BOLTZMANN_W_M2_K4,
            air_k: loads.air_temperature_k,
            convection: ConvectionAt::new(
                surface.convection,
                surface.roughness,
                orientation,
                loads.wind_speed_m_s,
                cache,
            ),
            latent: LatentAt::new(surface.wet_fraction, loads.dew_point_k, loads.pressure_pa),
        }
    }

    pub(crate) fn absorbed_shortwave_w_m2(&self) -> f64 {
        self.absorbed_shortwave_w_m2
    }

    pub(crate) fn absorbed_longwave_w_m2(&self) -> f64 {
        self.absorbed_longwave_w_m2
    }

    /// What is absorbed, W m⁻².
    #[inline]
    pub(crate) fn absorbed_w_m2(&self) -> f64 {
        self.absorbed_shortwave_w_m2 + self.absorbed_longwave_w_m2
    }

    /// What leaves the surface by emission, convection and latent heat at `surface_k`, and
    /// the derivatives; the net flux into the surface is `absorbed − leaving`.
    #[inline]
    pub(crate) fn parts(&self, surface_k: f64) -> SurfaceParts {
        let delta = surface_k - self.air_k;
        let c = self.convection.eval(delta);
        let t2 = surface_k * surface_k;
        let (latent, d_latent) = if self.latent.is_dry() {
            (0.0, 0.0)
        } else {
            let l = self.latent.eval(surface_k, c.h, c.dh_dt(delta));
            (l.flux_w_m2, l.derivative_w_m2_k)
        };
        SurfaceParts {
            emitted: self.emissivity_sigma * t2 * t2,
            convected: c.h * delta,
            latent,
            d_emitted: 4.0 * self.emissivity_sigma * t2 * surface_k,
            d_convected: c.flux_derivative,
            d_latent,
        }
    }
}
