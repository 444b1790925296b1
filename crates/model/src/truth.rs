//! The layers of the images the tracer writes: their names, units and order. The names are
//! the contract between the stages: `irsig-trace` writes them, `irsig-sensor` passes them
//! through (reducing labels by majority and quantities by mean when it samples),
//! `irsig-stats` selects pixels by [`Layer::MaterialPrimary`] and measures
//! [`Layer::ApparentTemperature`]. Every stage names a layer through this enum, never a
//! string of its own. `formats/sensor.md` documents the files.
//!
//! ```
//! use irsig_model::truth::Layer;
//! assert_eq!(Layer::ApparentTemperature.name(), "apparent_temperature");
//! assert_eq!(Layer::from_name("material_primary"), Some(Layer::MaterialPrimary));
//! assert!(Layer::MaterialPrimary.is_label() && !Layer::Range.is_label());
//! ```

/// One layer of the radiance EXR or the truth EXR.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Layer {
    /// Radiance at the sensor, W m⁻² sr⁻¹: the radiance EXR's one layer, and the layer the
    /// sensor stage acts on.
    Radiance,
    /// Material id of the facet the primary ray hit (0: none).
    MaterialPrimary,
    /// Material id of the facet the specular reflection ray hit (0: none).
    MaterialSecondary,
    /// The thesis's ray event, 1 to 4 (Figure 6).
    Event,
    /// Distance from the sensor to the hit, metres.
    Range,
    /// Angle between the reversed ray and the facet normal, degrees.
    Incidence,
    /// Kinetic temperature of what was hit, K.
    KineticTemperature,
    /// Emissivity at the incidence angle.
    Emissivity,
    /// Transmission of the path from the hit to the sensor.
    Transmission,
    /// Path radiance of the path to the sensor, W m⁻² sr⁻¹.
    PathRadiance,
    /// Sky-view (shape) factor F.
    SkyViewFactor,
    /// Apparent (blackbody) temperature of the radiance at the sensor in the band, K.
    ApparentTemperature,
    /// How many sub-bands the radiance equation was summed over (1: the band model); the
    /// other layers hold band-integrated values either way.
    SubBands,
    /// The error budget (with declared uncertainties): σ of the apparent temperature from
    /// the kinetic temperature's uncertainty, K.
    SigmaKineticTemperature,
    /// σ of the apparent temperature from the emissivity's uncertainty, K.
    SigmaEmissivity,
    /// σ of the apparent temperature from the atmosphere's transmission, K.
    SigmaTransmission,
    /// σ of the apparent temperature from the atmosphere's path (and sky) radiance, K.
    SigmaPathRadiance,
    /// The residual of the models the tolerance pilot chose, K: its class's root-mean-square
    /// error (against the most accurate settings, their own residual included) and the
    /// pixel's own sampling error when it was refined, added in quadrature.
    SigmaModel,
    /// The root-sum-square of the σ layers, K, and of the atmosphere data's error where the
    /// frame records it ([`Layer::AtmosphereDataError`], a bound, taken as a uniform
    /// distribution's half-width: σ = bound/√3).
    SigmaTotal,
    /// With a tolerance: 1 where the decision does not guarantee the pixel (its class
    /// cannot be afforded, or its refinement reached the cap), 0 elsewhere.
    NotGuaranteed,
    /// With a tolerance: the rays the pixel's value is the mean of where the frame was
    /// refined (1: the pixel kept its centre ray; more: a refined pixel, whose rays may
    /// have met several materials); NaN in a frame rendered without refinement.
    Samples,
    /// With a sun: the sun's direct irradiance on the surface hit, W m⁻², integrated over
    /// the band with its response as the beam is (`E_n·cos θ_i·V`, summed over the
    /// sub-bands; the terrain's flat, unshadowed `E_n·cos θ_sun` for a terrain miss).
    SolarIrradiance,
    /// With a sun: the shadow, as the fraction of the sun's disk the surface hit sees, 0
    /// (in full shadow, or the sun behind the facet) to 1 (in full sun). Unweighted by the
    /// cosine: the share of the shadow rays that reach the sun.
    SunVisibleFraction,
    /// With a sun: the sunlight in the surface-leaving radiance toward the sensor,
    /// W m⁻² sr⁻¹, before the path to the sensor (its diffuse share's `r·E·cos θ_i·V/π`,
    /// its glint, and the sunlight its mirror and sky-view rays bring from what they meet).
    ReflectedSolarRadiance,
    /// With a sun: the sun's share of the radiance at the sensor, 0 to 1: the reflected
    /// solar radiance times the path's τ over the pixel's centre-ray radiance (0 for a sky
    /// pixel, whose sky holds no sunlight in this model).
    SunShare,
    /// With a textured material in the scene: the temperature offset the texture gives at
    /// the primary hit of the pixel's centre ray, K (its statistical texture's and its
    /// temperature map's, added; 0 on an untextured facet, NaN where no facet was hit).
    TextureTemperatureOffset,
    /// With a textured material in the scene: the scale the texture puts on the emissivity
    /// at the primary hit of the pixel's centre ray (its statistical texture's and its
    /// emissivity map's, multiplied; 1 on an untextured facet, NaN where no facet was
    /// hit). The `emissivity` layer holds the scaled ε, held to 0 to 1.
    TextureEmissivityScale,
    /// With an atmosphere whose slant tables record their interpolation residual (the
    /// built-ins'): how far the atmosphere data may put the pixel's apparent temperature,
    /// K, a bound of measured errors, not a σ. The view path's by the region of the table
    /// it reads (its nadir angle; past the widest row, by the observer's altitude too),
    /// the sky's for a sky pixel, plus the sky the surface reflects (`irsig_atmosphere::
    /// data_error`). NaN past the widest row in a band never measured there.
    AtmosphereDataError,
}

impl Layer {
    /// The truth EXR's layers, in the order the tracer writes them.
    pub const TRUTH: [Self; 12] = [
        Self::MaterialPrimary,
        Self::MaterialSecondary,
        Self::Event,
        Self::Range,
        Self::Incidence,
        Self::KineticTemperature,
        Self::Emissivity,
        Self::Transmission,
        Self::PathRadiance,
        Self::SkyViewFactor,
        Self::ApparentTemperature,
        Self::SubBands,
    ];

    /// The error budget's layers, written after [`Layer::TRUTH`] when uncertainties are
    /// declared.
    pub const BUDGET: [Self; 6] = [
        Self::SigmaKineticTemperature,
        Self::SigmaEmissivity,
        Self::SigmaTransmission,
        Self::SigmaPathRadiance,
        Self::SigmaModel,
        Self::SigmaTotal,
    ];

    /// The tolerance's layers, written after the others when a frame is rendered to a
    /// tolerance (piloted or with a decision applied).
    pub const TOLERANCE: [Self; 2] = [Self::NotGuaranteed, Self::Samples];

    /// The sun's layers, written after [`Layer::TRUTH`] (before the error budget's) when
    /// the frame was traced with a sun; a night truth EXR holds none of them.
    pub const SUN: [Self; 4] = [
        Self::SolarIrradiance,
        Self::SunVisibleFraction,
        Self::ReflectedSolarRadiance,
        Self::SunShare,
    ];

    /// The texture's layers, written after [`Layer::TRUTH`] and the sun's (before the error
    /// budget's) when the scene has a textured material; an untextured scene's truth EXR
    /// holds none of them.
    pub const TEXTURE: [Self; 2] = [Self::TextureTemperatureOffset, Self::TextureEmissivityScale];

    /// The atmosphere data's layer, written after the texture's (before the error
    /// budget's) when the atmosphere records its data error; a truth EXR of built or slab
    /// tables, or of a vacuum, holds none.
    pub const DATA: [Self; 1] = [Self::AtmosphereDataError];

    /// Every layer: the radiance, the truth layers, the error budget, the tolerance, the
    /// sun's, the texture's, the atmosphere data's.
    pub const ALL: [Self; 28] = [
        Self::Radiance,
        Self::MaterialPrimary,
        Self::MaterialSecondary,
        Self::Event,
        Self::Range,
        Self::Incidence,
        Self::KineticTemperature,
        Self::Emissivity,
        Self::Transmission,
        Self::PathRadiance,
        Self::SkyViewFactor,
        Self::ApparentTemperature,
        Self::SubBands,
        Self::SigmaKineticTemperature,
        Self::SigmaEmissivity,
        Self::SigmaTransmission,
        Self::SigmaPathRadiance,
        Self::SigmaModel,
        Self::SigmaTotal,
        Self::NotGuaranteed,
        Self::Samples,
        Self::SolarIrradiance,
        Self::SunVisibleFraction,
        Self::ReflectedSolarRadiance,
        Self::SunShare,
        Self::TextureTemperatureOffset,
        Self::TextureEmissivityScale,
        Self::AtmosphereDataError,
    ];

    /// The layer's name in the EXR.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::Radiance => "radiance",
            Self::MaterialPrimary => "material_primary",
            Self::MaterialSecondary => "material_secondary",
            Self::Event => "event",
            Self::Range => "range",
            Self::Incidence => "incidence",
            Self::KineticTemperature => "kinetic_temperature",
            Self::Emissivity => "emissivity",
            Self::Transmission => "transmission",
            Self::PathRadiance => "path_radiance",
            Self::SkyViewFactor => "sky_view_factor",
            Self::ApparentTemperature => "apparent_temperature",
            Self::SubBands => "sub_bands",
            Self::SigmaKineticTemperature => "sigma_kinetic_temperature",
            Self::SigmaEmissivity => "sigma_emissivity",
            Self::SigmaTransmission => "sigma_transmission",
            Self::SigmaPathRadiance => "sigma_path_radiance",
            Self::SigmaModel => "sigma_model",
            Self::SigmaTotal => "sigma_total",
            Self::NotGuaranteed => "not_guaranteed",
            Self::Samples => "samples",
            Self::SolarIrradiance => "solar_irradiance",
            Self::SunVisibleFraction => "sun_visible_fraction",
            Self::ReflectedSolarRadiance => "reflected_solar_radiance",
            Self::SunShare => "sun_share",
            Self::TextureTemperatureOffset => "texture_temperature_offset",
            Self::TextureEmissivityScale => "texture_emissivity_scale",
            Self::AtmosphereDataError => "atmosphere_data_error",
        }
    }

    /// The unit the EXR states for it (empty for labels and ratios).
    #[must_use]
    pub const fn unit(self) -> &'static str {
        match self {
            Self::Radiance | Self::PathRadiance | Self::ReflectedSolarRadiance => "W m^-2 sr^-1",
            Self::SolarIrradiance => "W m^-2",
            Self::Range => "m",
            Self::Incidence => "deg",
            Self::KineticTemperature
            | Self::ApparentTemperature
            | Self::SigmaKineticTemperature
            | Self::SigmaEmissivity
            | Self::SigmaTransmission
            | Self::SigmaPathRadiance
            | Self::SigmaModel
            | Self::SigmaTotal
            | Self::TextureTemperatureOffset
            | Self::AtmosphereDataError => "K",
            Self::MaterialPrimary
            | Self::MaterialSecondary
            | Self::Event
            | Self::SubBands
            | Self::Emissivity
            | Self::Transmission
            | Self::SkyViewFactor
            | Self::NotGuaranteed
            | Self::Samples
            | Self::SunVisibleFraction
            | Self::SunShare
            | Self::TextureEmissivityScale => "",
        }
    }

    /// Whether the layer holds labels (material ids, events, the sub-band count, ray counts), which are reduced by majority
    /// and never averaged.
    #[must_use]
    pub const fn is_label(self) -> bool {
        matches!(
            self,
            Self::MaterialPrimary
                | Self::MaterialSecondary
                | Self::Event
                | Self::SubBands
                | Self::NotGuaranteed
                | Self::Samples
        )
    }

    /// The layer of this name, if it is one of irsig's.
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|l| l.name() == name)
    }
}

impl std::fmt::Display for Layer {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique_and_round_trip() {
        for (i, a) in Layer::ALL.iter().enumerate() {
            assert_eq!(Layer::from_name(a.name()), Some(*a));
            for b in &Layer::ALL[i + 1..] {
                assert_ne!(a.name(), b.name());
            }
        }
        assert_eq!(Layer::ALL[1..13], Layer::TRUTH);
        assert_eq!(Layer::ALL[13..19], Layer::BUDGET);
        assert_eq!(Layer::ALL[19..21], Layer::TOLERANCE);
        assert_eq!(Layer::ALL[21..25], Layer::SUN);
        assert_eq!(Layer::ALL[25..27], Layer::TEXTURE);
        assert_eq!(Layer::ALL[27..], Layer::DATA);
        assert!(!Layer::AtmosphereDataError.is_label());
        assert!(Layer::SUN.iter().all(|l| !l.is_label()));
        assert!(Layer::TEXTURE.iter().all(|l| !l.is_label()));
        assert_eq!(Layer::from_name("Radiance"), None);
    }
}
