//! What the tracer hands back: the event a ray met, the options of a rendering, one ray's
//! sample with every term of its radiance equation, the truth and sun layers of a pixel,
//! and a frame of them.

use super::*;

/// What a ray met (thesis Figure 6, with the two kinds of miss told apart).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Event {
    /// Event 1, above the horizon: the ray sees the sky path from the sensor to space.
    Sky,
    /// Event 1, below the horizon: the ray sees the terrain background.
    Terrain,
    /// Event 2: a purely diffuse facet.
    Diffuse,
    /// Event 3: a facet with a specular part whose reflection ray leaves the scene.
    SpecularEscapes,
    /// Event 4: a facet with a specular part whose reflection ray hits another facet.
    SpecularHitsFacet,
}

impl Event {
    /// The thesis's event number (1 to 4).
    #[must_use]
    pub fn number(self) -> u8 {
        match self {
            Self::Sky | Self::Terrain => 1,
            Self::Diffuse => 2,
            Self::SpecularEscapes => 3,
            Self::SpecularHitsFacet => 4,
        }
    }

    /// Every event, in the order of [`Self::name`]'s.
    pub const ALL: [Self; 5] = [
        Self::Sky,
        Self::Terrain,
        Self::Diffuse,
        Self::SpecularEscapes,
        Self::SpecularHitsFacet,
    ];

    /// The event's name in files: `sky`, `terrain`, `diffuse`, `specular-escapes`,
    /// `specular-hits-facet`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Sky => "sky",
            Self::Terrain => "terrain",
            Self::Diffuse => "diffuse",
            Self::SpecularEscapes => "specular-escapes",
            Self::SpecularHitsFacet => "specular-hits-facet",
        }
    }

    /// The event named `name` ([`Self::name`]).
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|e| e.name() == name)
    }
}

/// Options of one rendering. The defaults are the thesis's model: one specular bounce,
/// no sky-view factor (F = 1), one ray per pixel.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TraceOptions {
    /// Specular reflection rays along one path (default 1; Appendix A: one is enough at
    /// earth-ambient temperatures). Where the bounces run out (at once with 0), a specular
    /// part reflects the environment along its mirror direction without tracing: the sky at
    /// the mirror angle, or the terrain where the direction points below the horizon.
    pub specular_bounces: u32,
    /// Cosine-weighted hemisphere rays per diffuse primary hit for the sky-view factor F;
    /// 0 (default) switches the model off (F = 1, no rays cast).
    pub sky_view_rays: u32,
    /// Supersampling: `n` gives n × n stratified, jittered rays per pixel; 1 (default) is
    /// one ray through the pixel centre.
    pub supersampling: u32,
    /// Adaptive supersampling (the thesis's §3.3.4 countermeasure): with a threshold, only
    /// pixels whose centre ray's apparent temperature differs from one of its 8 neighbours'
    /// by more than this many kelvin get the n × n rays; the others keep their centre ray. A pixel
    /// that is refined gets exactly what a full n × n rendering gives it. `None` (default):
    /// every pixel gets n × n.
    pub adaptive_threshold_k: Option<f64>,
    /// Seed of every random choice (sky-view directions, sub-pixel jitter). Each pixel
    /// draws from its own stream derived from the seed and its index, so the image does not
    /// depend on the thread count.
    pub seed: u64,
    /// Keep the truth layers of each pixel's centre ray in [`Frame::truth`] (default). Off,
    /// the frame holds the radiance only: a renderer that needs neither the truth layers
    /// nor the interaction map saves writing them and the terms only they read.
    pub truth: bool,
}

impl Default for TraceOptions {
    fn default() -> Self {
        Self {
            specular_bounces: 1,
            sky_view_rays: 0,
            supersampling: 1,
            adaptive_threshold_k: None,
            seed: 0,
            truth: true,
        }
    }
}

impl TraceOptions {
    /// Checks every option against its range (what [`Tracer`] checks before tracing).
    ///
    /// # Errors
    /// The first option out of range.
    pub fn validate(&self) -> Result<(), TraceError> {
        let bad = |m: String| Err(TraceError::new(TraceErrorKind::InvalidOptions(m)));
        if self.specular_bounces > 64 {
            return bad(format!(
                "specular_bounces {} is out of range: expected 0 to 64",
                self.specular_bounces
            ));
        }
        if self.supersampling == 0 || self.supersampling > 64 {
            return bad(format!(
                "supersampling {} is out of range: expected 1 to 64",
                self.supersampling
            ));
        }
        if let Some(t) = self.adaptive_threshold_k
            && !(t.is_finite() && t > 0.0)
        {
            return bad(format!(
                "adaptive_threshold_k {t} is out of range: expected a finite number of kelvin \
                 above 0"
            ));
        }
        if self.sky_view_rays > 1 << 20 {
            return bad(format!(
                "sky_view_rays {} is out of range: expected 0 to {}",
                self.sky_view_rays,
                1 << 20
            ));
        }
        Ok(())
    }
}

/// Every term of the radiance equation for one ray,
/// `L = τ·[ε·L_T + r·(s·L_spec + (1 − s)·(F·L_d + (1 − F)·L_b))] + L_u`.
/// Terms that do not apply (no facet hit, no specular part) are NaN.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// What the ray met.
    pub event: Event,
    /// Material id of the facet hit (0: none).
    pub primary_material: u16,
    /// Material id of the facet the specular reflection ray hit (0: none).
    pub secondary_material: u16,
    /// Raw-scene index of the facet hit, if any.
    pub facet: Option<u32>,
    /// True when the facet was hit on its back face.
    pub back_face: bool,
    /// Distance from the sensor to the hit (or to the terrain), metres.
    pub range_m: f64,
    /// Cosine of the angle between the reversed ray and the facet normal (the angle:
    /// [`Self::incidence_deg`]).
    pub cos_incidence: f64,
    /// Kinetic temperature of what was hit (facet or terrain), K.
    pub temperature_k: f64,
    /// ε at the incidence angle (for a terrain miss the terrain's constant emissivity, or
    /// its material's at the ray's incidence).
    pub emissivity: f64,
    /// Reflectance `r = 1 − ε`.
    pub reflectance: f64,
    /// The material's specular fraction `s`.
    pub specular_fraction: f64,
    /// `L_T`, blackbody band radiance at the kinetic temperature, W m⁻² sr⁻¹.
    pub blackbody_w_m2_sr: f64,
    /// Radiance arriving along the mirror direction, W m⁻² sr⁻¹: `L_b` of event 4 (the
    /// surface-leaving radiance of the second facet) or `L_d(θ_r)` of event 3, plus the sun's
    /// glint: the disk where a smooth reflection leaves inside it, a rough material's lobe
    /// over the disk ([`crate::sun`]).
    pub specular_incident_w_m2_sr: f64,
    /// Zenith angle of the reflection ray, degrees.
    pub reflected_zenith_deg: f64,
    /// Hemispheric sky radiance at the hit, `L_d`, W m⁻² sr⁻¹.
    pub sky_hemispheric_w_m2_sr: f64,
    /// Sky-view (shape) factor F (1 when the model is off).
    pub sky_view_factor: f64,
    /// Diffuse incident radiance `F·L_d + (1 − F)·L_b`, W m⁻² sr⁻¹, plus with a sun its
    /// `E_n·cos θ_i·V/π` ([`crate::sun`]).
    pub diffuse_incident_w_m2_sr: f64,
    /// Surface-leaving radiance towards the sensor, W m⁻² sr⁻¹.
    pub surface_leaving_w_m2_sr: f64,
    /// τ of the path from the hit to the sensor.
    pub transmission: f64,
    /// `L_u`, path radiance of the path to the sensor (the whole sky path for a sky
    /// miss), W m⁻² sr⁻¹.
    pub path_radiance_w_m2_sr: f64,
    /// Radiance at the sensor, W m⁻² sr⁻¹.
    pub radiance_w_m2_sr: f64,
    /// ∂L/∂T of the facet hit's kinetic temperature, `Σ τ·ε·dL_T/dT` over the sub-bands,
    /// W m⁻² sr⁻¹ K⁻¹ (0 for a miss): what the error budget propagates a temperature's
    /// uncertainty by.
    pub temperature_sensitivity: f64,
    /// ∂L/∂ε of the facet hit, `Σ τ·(L_T − L_reflected)`, W m⁻² sr⁻¹ (0 for a miss).
    pub emissivity_sensitivity: f64,
    /// With a sun ([`crate::sun`]): the beam's irradiance on the surface hit, W m⁻², summed
    /// over the sub-bands, `Σ E_n·cos θ_i·V` (the terrain's `Σ E_n(0)·cos θ_sun`). NaN
    /// without a sun or for a sky miss.
    pub solar_irradiance_w_m2: f64,
    /// With a sun: the fraction of the shadow rays from the surface hit that reach the sun,
    /// 0 to 1 (1 on the unshadowed terrain with the sun above the horizon). NaN without a
    /// sun or for a sky miss.
    pub sun_visible_fraction: f64,
    /// With a sun: the sunlight in the surface-leaving radiance, W m⁻² sr⁻¹, summed over
    /// the sub-bands: `r·[(1 − s)·(E_n·cos θ_i·V/π + what sky-view rays bring from the
    /// sunlit terrain) + s·(glint + what the mirror brings of sunlight)]`. NaN without a sun
    /// or for a sky miss.
    pub reflected_solar_w_m2_sr: f64,
    /// With a sun: the sun's share of the radiance at the sensor, `Σ τ·L_solar / L`, 0 to 1
    /// (0 for a sky miss). NaN without a sun.
    pub sun_share: f64,
    /// The temperature offset the primary facet's texture gives at the hit, K (already in
    /// [`Self::temperature_k`]): 0 for an untextured material, NaN for a miss.
    pub texture_offset_k: f64,
    /// The scale the primary facet's texture puts on ε at the hit, before ε is held to 0
    /// to 1 (already in [`Self::emissivity`]): 1 for an untextured material, NaN for a
    /// miss.
    pub texture_emissivity_scale: f64,
}

impl Sample {
    /// The angle between the reversed ray and the facet normal, degrees (NaN when no facet
    /// was hit).
    #[must_use]
    pub fn incidence_deg(&self) -> f64 {
        self.cos_incidence.acos().to_degrees()
    }

    pub(crate) fn miss(event: Event) -> Self {
        Self {
            event,
            primary_material: 0,
            secondary_material: 0,
            facet: None,
            back_face: false,
            range_m: f64::NAN,
            cos_incidence: f64::NAN,
            temperature_k: f64::NAN,
            emissivity: f64::NAN,
            reflectance: f64::NAN,
            specular_fraction: f64::NAN,
            blackbody_w_m2_sr: f64::NAN,
            specular_incident_w_m2_sr: f64::NAN,
            reflected_zenith_deg: f64::NAN,
            sky_hemispheric_w_m2_sr: f64::NAN,
            sky_view_factor: f64::NAN,
            diffuse_incident_w_m2_sr: f64::NAN,
            surface_leaving_w_m2_sr: f64::NAN,
            transmission: f64::NAN,
            path_radiance_w_m2_sr: f64::NAN,
            radiance_w_m2_sr: f64::NAN,
            temperature_sensitivity: 0.0,
            emissivity_sensitivity: 0.0,
            solar_irradiance_w_m2: f64::NAN,
            sun_visible_fraction: f64::NAN,
            reflected_solar_w_m2_sr: f64::NAN,
            sun_share: f64::NAN,
            texture_offset_k: f64::NAN,
            texture_emissivity_scale: f64::NAN,
        }
    }
}

/// The truth layers of one pixel: the terms of the ray through its centre that the truth
/// outputs carry, rounded to f32 as the truth EXR stores them: 56 bytes, where a whole
/// [`Sample`] is 208 (160 when measured; the sun's four terms are kept in [`SunPixel`],
/// the texture's two in [`TexturePixel`]).
/// (Keeping a whole sample per pixel cost 10-45 ns per primary ray at 1k-1M triangles;
/// this record, with the angle derived later, costs 2-4 ns: BENCHMARKS.md.) [`Tracer::probe`] gives every term of a pixel in f64. Terms that do not
/// apply are NaN, as in [`Sample`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TruthPixel {
    /// What the ray met.
    pub event: Event,
    /// Material id of the facet hit (0: none).
    pub primary_material: u16,
    /// Material id of the facet the specular reflection ray hit (0: none).
    pub secondary_material: u16,
    /// Distance from the sensor to the hit (or to the terrain), metres.
    pub range_m: f32,
    /// Cosine of the angle between the reversed ray and the facet normal, kept in f64 (an
    /// f32 cosine would blur angles near the normal by 0.02°): the angle is derived when a
    /// layer is written ([`Self::incidence_deg`]), as the apparent temperature is from
    /// the radiance, so a frame whose outputs do not show it does not pay the arc cosine.
    pub cos_incidence: f64,
    /// Kinetic temperature of what was hit (facet or terrain), K.
    pub temperature_k: f32,
    /// ε at the incidence angle (for a terrain miss the terrain's constant emissivity, or
    /// its material's at the ray's incidence).
    pub emissivity: f32,
    /// τ of the path from the hit to the sensor.
    pub transmission: f32,
    /// `L_u`, path radiance of the path to the sensor, W m⁻² sr⁻¹.
    pub path_radiance_w_m2_sr: f32,
    /// Sky-view (shape) factor F (1 when the model is off).
    pub sky_view_factor: f32,
    /// Raw-scene index of the facet hit (`u32::MAX`: none): the error budget's uncertainties
    /// are per material or per object.
    pub facet: u32,
    /// [`Sample::temperature_sensitivity`], W m⁻² sr⁻¹ K⁻¹.
    pub temperature_sensitivity: f32,
    /// [`Sample::emissivity_sensitivity`], W m⁻² sr⁻¹.
    pub emissivity_sensitivity: f32,
}

// The sizes the frame's memory traffic was measured at (the doc above).
const _: () = assert!(std::mem::size_of::<TruthPixel>() == 56);
const _: () = assert!(std::mem::size_of::<Sample>() == 208);
const _: () = assert!(std::mem::size_of::<SunPixel>() == 16);
const _: () = assert!(std::mem::size_of::<TexturePixel>() == 8);

impl TruthPixel {
    /// The angle between the reversed ray and the facet normal, degrees, rounded to f32 (NaN
    /// when no facet was hit).
    #[must_use]
    pub fn incidence_deg(&self) -> f32 {
        self.cos_incidence.acos().to_degrees() as f32
    }

    /// The value of truth `layer` for this pixel, as the truth EXR stores it; `None` for
    /// the layers that come from the pixel's radiance and the declared uncertainties
    /// instead ([`Layer::Radiance`], [`Layer::ApparentTemperature`], [`Layer::BUDGET`]), and
    /// the frame's sub-band count ([`Layer::SubBands`], the tracer's).
    #[must_use]
    pub fn layer(&self, layer: Layer) -> Option<f32> {
        Self::layer_of(layer).map(|value| value(self))
    }

    /// What [`Self::layer`] reads for `layer`, as a function: a whole layer is then one
    /// pass over the pixels with no test of the layer at each.
    #[must_use]
    pub fn layer_of(layer: Layer) -> Option<fn(&Self) -> f32> {
        Some(match layer {
            Layer::MaterialPrimary => |p| f32::from(p.primary_material),
            Layer::MaterialSecondary => |p| f32::from(p.secondary_material),
            Layer::Event => |p| f32::from(p.event.number()),
            Layer::Range => |p| p.range_m,
            Layer::Incidence => Self::incidence_deg,
            Layer::KineticTemperature => |p| p.temperature_k,
            Layer::Emissivity => |p| p.emissivity,
            Layer::Transmission => |p| p.transmission,
            Layer::PathRadiance => |p| p.path_radiance_w_m2_sr,
            Layer::SkyViewFactor => |p| p.sky_view_factor,
            Layer::Radiance
            | Layer::ApparentTemperature
            | Layer::SubBands
            | Layer::SigmaKineticTemperature
            | Layer::SigmaEmissivity
            | Layer::SigmaTransmission
            | Layer::SigmaPathRadiance
            | Layer::SigmaModel
            | Layer::SigmaTotal
            | Layer::NotGuaranteed
            | Layer::Samples
            | Layer::SolarIrradiance
            | Layer::SunVisibleFraction
            | Layer::ReflectedSolarRadiance
            | Layer::SunShare
            | Layer::TextureTemperatureOffset
            | Layer::TextureEmissivityScale
            | Layer::AtmosphereDataError => return None,
        })
    }
}

/// The sun's truth layers of one pixel ([`Layer::SUN`]), rounded to f32 as the truth EXR
/// stores them: kept apart from [`TruthPixel`], in [`Frame::sun`], and only when the frame
/// is traced with a sun, so that a night frame pays nothing for them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SunPixel {
    /// [`Sample::solar_irradiance_w_m2`], W m⁻².
    pub solar_irradiance_w_m2: f32,
    /// [`Sample::sun_visible_fraction`].
    pub sun_visible_fraction: f32,
    /// [`Sample::reflected_solar_w_m2_sr`], W m⁻² sr⁻¹.
    pub reflected_solar_w_m2_sr: f32,
    /// [`Sample::sun_share`].
    pub sun_share: f32,
}

impl SunPixel {
    /// What the sun's truth layer `layer` reads, as a function; `None` for the other layers.
    #[must_use]
    pub fn layer_of(layer: Layer) -> Option<fn(&Self) -> f32> {
        Some(match layer {
            Layer::SolarIrradiance => |p| p.solar_irradiance_w_m2,
            Layer::SunVisibleFraction => |p| p.sun_visible_fraction,
            Layer::ReflectedSolarRadiance => |p| p.reflected_solar_w_m2_sr,
            Layer::SunShare => |p| p.sun_share,
            _ => return None,
        })
    }
}

/// The texture's truth layers of one pixel ([`Layer::TEXTURE`]): what the texture gave at
/// the primary hit of the pixel's centre ray, as every truth layer is the centre ray's
/// (a refined or supersampled pixel's radiance is the mean of its rays; its truth is not).
/// Rounded to f32 as the truth EXR stores them, and kept apart from [`TruthPixel`], in
/// [`Frame::texture`], only when the scene has a textured material, so that an
/// untextured frame pays nothing for them and its files keep their bytes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TexturePixel {
    /// [`Sample::texture_offset_k`], K.
    pub temperature_offset_k: f32,
    /// [`Sample::texture_emissivity_scale`].
    pub emissivity_scale: f32,
}

impl TexturePixel {
    /// What the texture's truth layer `layer` reads, as a function; `None` for the other
    /// layers.
    #[must_use]
    pub fn layer_of(layer: Layer) -> Option<fn(&Self) -> f32> {
        Some(match layer {
            Layer::TextureTemperatureOffset => |p| p.temperature_offset_k,
            Layer::TextureEmissivityScale => |p| p.emissivity_scale,
            _ => return None,
        })
    }
}

impl From<&Sample> for TexturePixel {
    fn from(s: &Sample) -> Self {
        Self {
            temperature_offset_k: s.texture_offset_k as f32,
            emissivity_scale: s.texture_emissivity_scale as f32,
        }
    }
}

impl From<&Sample> for SunPixel {
    fn from(s: &Sample) -> Self {
        Self {
            solar_irradiance_w_m2: s.solar_irradiance_w_m2 as f32,
            sun_visible_fraction: s.sun_visible_fraction as f32,
            reflected_solar_w_m2_sr: s.reflected_solar_w_m2_sr as f32,
            sun_share: s.sun_share as f32,
        }
    }
}

impl From<&Sample> for TruthPixel {
    fn from(s: &Sample) -> Self {
        Self {
            event: s.event,
            primary_material: s.primary_material,
            secondary_material: s.secondary_material,
            range_m: s.range_m as f32,
            cos_incidence: s.cos_incidence,
            temperature_k: s.temperature_k as f32,
            emissivity: s.emissivity as f32,
            transmission: s.transmission as f32,
            path_radiance_w_m2_sr: s.path_radiance_w_m2_sr as f32,
            sky_view_factor: s.sky_view_factor as f32,
            facet: s.facet.unwrap_or(u32::MAX),
            temperature_sensitivity: s.temperature_sensitivity as f32,
            emissivity_sensitivity: s.emissivity_sensitivity as f32,
        }
    }
}

/// One rendered frame: the (supersampled) radiance of every pixel and the truth layers of
/// the ray through each pixel's centre. Row-major, row 0 at the top.
#[derive(Debug, Clone, PartialEq)]
pub struct Frame {
    /// Columns.
    pub width: u32,
    /// Rows.
    pub height: u32,
    /// Radiance at the sensor per pixel, W m⁻² sr⁻¹ (mean of the sub-pixel rays).
    pub radiance_w_m2_sr: Vec<f64>,
    /// The truth layers of each pixel's centre ray; empty when [`TraceOptions::truth`] is
    /// off.
    pub truth: Vec<TruthPixel>,
    /// What refinement did to each pixel ([`Tracer::with_refinement`]); empty without it.
    pub sampling: Vec<PixelSampling>,
    /// The sun's truth layers of each pixel's centre ray; empty without a sun
    /// ([`Tracer::with_sun`]) or when [`TraceOptions::truth`] is off.
    pub sun: Vec<SunPixel>,
    /// The texture's truth layers of each pixel's centre ray; empty when no material of
    /// the scene has a texture ([`Tracer::is_textured`]) or when [`TraceOptions::truth`] is
    /// off.
    pub texture: Vec<TexturePixel>,
    /// The atmosphere data's error of each pixel, K ([`Layer::AtmosphereDataError`]);
    /// empty until the caller fills it ([`Tracer::data_error_layer`]), which it does when
    /// the atmosphere records its data error and the truth is kept.
    pub data_error_k: Vec<f32>,
    /// The error budget's partials of each pixel's value, per input group of the facets
    /// its rays met ([`crate::charge`]); empty unless the tracer was given the groups
    /// ([`Tracer::with_budget_groups`]) and the truth is kept.
    pub charges: Charges,
}

impl Frame {
    /// One truth layer of every pixel, row-major, as the truth EXR stores it (f32; NaN
    /// where the term does not apply). `None` when the frame kept no truth or the layer
    /// comes from the radiance ([`TruthPixel::layer`]).
    #[must_use]
    pub fn truth_layer(&self, layer: Layer) -> Option<Vec<f32>> {
        if let Some(value) = SunPixel::layer_of(layer) {
            if self.sun.is_empty() {
                return None;
            }
            return Some(self.sun.iter().map(value).collect());
        }
        if let Some(value) = TexturePixel::layer_of(layer) {
            if self.texture.is_empty() {
                return None;
            }
            return Some(self.texture.iter().map(value).collect());
        }
        if layer == Layer::AtmosphereDataError {
            return (!self.data_error_k.is_empty()).then(|| self.data_error_k.clone());
        }
        if self.truth.is_empty() {
            return None;
        }
        let value = TruthPixel::layer_of(layer)?;
        Some(self.truth.iter().map(value).collect())
    }

    /// The radiance of every pixel rounded to f32, as the radiance EXR stores it.
    #[must_use]
    pub fn radiance_f32(&self) -> Vec<f32> {
        self.radiance_w_m2_sr.iter().map(|&l| l as f32).collect()
    }
}
