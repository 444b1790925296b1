//! The radiance equation along each ray: the four events of thesis Figure 6 (§3.3).

use irsig_atmosphere::PathTerms;
use irsig_model::truth::Layer;
use irsig_model::{MaterialLibrary, RawScene, Terrain};
use irsig_radiometry::{BandModel, EmissivityTable, InverseTable};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

use crate::camera::Camera;
use crate::env::Atmosphere;
use crate::error::{TraceError, TraceErrorKind};
use crate::geometry::Geometry;
use crate::path::Path;
use crate::path_table::{PathTable, PathTermsMode};
use crate::refine::{PixelSampling, Refinement};
use crate::sun::{Sun, SunBeam, SunGeometry};
use crate::tile::Tile;
use crate::vec::V3;

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
    /// ε at the incidence angle (the terrain's band emissivity for a terrain miss).
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
        }
    }
}

/// The truth layers of one pixel: the terms of the ray through its centre that the truth
/// outputs carry, rounded to f32 as the truth EXR stores them: 56 bytes, where a whole
/// [`Sample`] is 192 (160 when measured; the sun's four terms are kept in [`SunPixel`]).
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
    /// ε at the incidence angle (the terrain's band emissivity for a terrain miss).
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
const _: () = assert!(std::mem::size_of::<Sample>() == 192);
const _: () = assert!(std::mem::size_of::<SunPixel>() == 16);

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
            | Layer::SolarIrradiance
            | Layer::SunVisibleFraction
            | Layer::ReflectedSolarRadiance
            | Layer::SunShare => return None,
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

/// One sub-band of a spectral rendering: its part of the band, the atmosphere over it and
/// the materials' emissivity over it. A rendering sums the radiance equation over its
/// sub-bands (issue of band averaging: one band-mean τ times one band radiance is only an
/// approximation, measured in docs/accuracy.md).
#[derive(Debug, Clone)]
pub struct SubBand<B, A> {
    /// The blackbody radiance over this sub-band (its wavelengths, weighted by the
    /// response).
    pub band: B,
    /// The atmosphere over this sub-band.
    pub atmosphere: A,
    /// Each material's angular emissivity over this sub-band, in the library's order;
    /// `None`: the materials' own band tables.
    pub emissivity: Option<Vec<EmissivityTable>>,
}

#[derive(Debug, Clone)]
pub(crate) struct MaterialData {
    pub(crate) id: u16,
    pub(crate) name: String,
    pub(crate) specular_fraction: f64,
    /// The specular share's lobe for the sun's glint, where the material has an RMS slope
    /// above 0 and a specular share ([`crate::lobe`]); `None`: a mirror.
    pub(crate) lobe: Option<crate::lobe::Lobe>,
}

/// What the tracer keeps per facet, attached to the facet's record in the geometry so a hit
/// reads it with the plane, in one cache line.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FacetRadiometry {
    /// Index into the tracer's material list (not the material id).
    pub(crate) material: u16,
    /// Index into the tracer's distinct temperatures, and so into every band set's
    /// blackbody tables.
    pub(crate) temperature_index: u32,
    pub(crate) temperature_k: f64,
    /// L_T in the tracer's first sub-band (the whole band when there is one), W m⁻² sr⁻¹:
    /// kept here, beside the plane, because a table costs a cache miss per hit at 1M
    /// triangles.
    pub(crate) blackbody: f64,
}

/// A sub-band as the tracer keeps it: the atmosphere, each material's emissivity and the
/// blackbody radiance of every facet temperature, precomputed.
#[derive(Debug)]
pub(crate) struct BandData<A> {
    pub(crate) atmosphere: A,
    /// Per material slot.
    pub(crate) emissivity: Vec<EmissivityTable>,
    /// Per material slot: the table is the tracer's own, so a recorded hit's ε holds here.
    pub(crate) own_emissivity: Vec<bool>,
    /// L_T per temperature index, W m⁻² sr⁻¹; empty when `inline`.
    pub(crate) blackbody: Vec<f64>,
    /// dL_T/dT per temperature index, W m⁻² sr⁻¹ K⁻¹ (for the error budget).
    pub(crate) derivative: Vec<f64>,
    /// The facet records hold this sub-band's L_T (the tracer's own first sub-band).
    pub(crate) inline: bool,
    /// The terrain's L_T and surface-leaving radiance, W m⁻² sr⁻¹.
    pub(crate) terrain_blackbody: f64,
    pub(crate) terrain_leaving: f64,
    /// The sunlight in `terrain_leaving`, W m⁻² sr⁻¹: the beam's and the scattered sky's
    /// (0 at night).
    pub(crate) terrain_solar: f64,
    /// The sun's direct beam in this sub-band ([`Tracer::with_sun`]); `None`: no sun.
    pub(crate) sun: Option<SunBeam>,
}

impl<A> BandData<A> {
    /// ε of a recorded hit in this sub-band: the one found when the hit was recorded where
    /// the material's table is the tracer's own, else looked up (bit for bit the same).
    #[inline]
    pub(crate) fn emissivity_of(&self, surface: &crate::path::Surface) -> f64 {
        let slot = usize::from(surface.data.material);
        if self.own_emissivity[slot] {
            surface.emissivity
        } else {
            self.emissivity[slot].at_cos(surface.cos_incidence)
        }
    }

    /// L_T of a facet in this sub-band, W m⁻² sr⁻¹.
    #[inline]
    pub(crate) fn blackbody_of(&self, facet: &FacetRadiometry) -> f64 {
        if self.inline {
            facet.blackbody
        } else {
            self.blackbody[facet.temperature_index as usize]
        }
    }
}

/// The sub-bands a radiance is summed over, ready for a tracer's scene: its own
/// ([`Tracer::with_sub_bands`]) or another set on the same scene ([`Tracer::band_set`]),
/// which the pilot evaluates recorded paths with.
#[derive(Debug)]
pub struct BandSet<A> {
    pub(crate) bands: Vec<BandData<A>>,
    /// Every sub-band's atmosphere model shares the first's grids, so a path is located
    /// once and evaluated in each ([`BandSet::path_terms`]).
    pub(crate) shared_grids: bool,
}

impl<A: Atmosphere> BandSet<A> {
    fn new(bands: Vec<BandData<A>>) -> Self {
        let shared_grids = match bands.first().and_then(|b| b.atmosphere.model()) {
            Some(first) => bands.iter().all(|b| {
                b.atmosphere
                    .model()
                    .is_some_and(|m| first.shares_path_grids(m))
            }),
            None => false,
        };
        Self {
            bands,
            shared_grids,
        }
    }

    /// The path terms of every sub-band for the path between a sensor at `sensor_m`
    /// and a point at `target_m`, `range_m` apart, passed to `each` in sub-band order: the
    /// same terms, bit for bit, as each sub-band's own `path`, with the grid searches done
    /// once when the sub-bands share their grids.
    #[inline]
    pub(crate) fn path_terms(
        &self,
        sensor_m: f64,
        target_m: f64,
        range_m: f64,
        mut each: impl FnMut(usize, &BandData<A>, PathTerms),
    ) {
        let located = if self.shared_grids {
            self.bands
                .first()
                .and_then(|b| b.atmosphere.model())
                .map(|m| m.locate_path(sensor_m, target_m, range_m))
        } else {
            None
        };
        for (k, b) in self.bands.iter().enumerate() {
            let p = match (&located, b.atmosphere.model()) {
                (Some(g), Some(m)) => m.path_along(g),
                _ => b.atmosphere.path(sensor_m, target_m, range_m),
            };
            each(k, b, p);
        }
    }
}

impl<A> BandSet<A> {
    /// The number of sub-bands.
    #[must_use]
    pub fn len(&self) -> usize {
        self.bands.len()
    }

    /// Whether the set has no sub-band (never, once built).
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.bands.is_empty()
    }
}

/// A scene ready to trace: the BVH, per-facet radiometry (L_T precomputed), the terrain,
/// the band (and its sub-bands, each with its atmosphere). Build it once and render as many
/// views as needed.
#[derive(Debug)]
pub struct Tracer<B, A> {
    pub(crate) geometry: Geometry<FacetRadiometry>,
    pub(crate) materials: Vec<MaterialData>,
    pub(crate) terrain: Terrain,
    /// The whole band: what the apparent temperature inverts.
    pub(crate) band: B,
    /// The sub-bands the radiance equation is summed over (one: the band itself).
    pub(crate) bands: BandSet<A>,
    /// Every distinct facet temperature, K, in temperature-index order.
    pub(crate) temperatures: Vec<f64>,
    /// Each material's band emissivity, by slot.
    pub(crate) emissivity: Vec<EmissivityTable>,
    pub(crate) path_terms: PathTermsMode,
    /// Pixels refined to a standard-error target ([`crate::refine`]); `None`: the options'
    /// supersampling.
    pub(crate) refinement: Option<Refinement>,
    /// The sun's geometry when it shines ([`Tracer::with_sun`]): each facet hit then casts
    /// shadow rays toward it. Its beam, per sub-band, is in [`BandData::sun`].
    pub(crate) sun: Option<SunGeometry>,
}

/// The side an edge candidate's refinement starts at: four rounds of 4 × 4 rays.
pub const EDGE_SIDE: u32 = 4;

/// The span of [`Tracer::inverse_table`], K: the apparent temperatures of earth-ambient
/// scenes and of the clear sky in the thermal infrared.
pub const INVERSE_TABLE_K: [f64; 2] = [150.0, 500.0];

/// The inverse table of `band` over the radiances of [`INVERSE_TABLE_K`]: what
/// [`Tracer::inverse_table`] gives, for a tool that has let its tracer go.
#[must_use]
pub fn inverse_table<B: BandModel>(band: &B) -> InverseTable<'_, B> {
    let [lo, hi] = INVERSE_TABLE_K.map(|t| band.radiance(t));
    InverseTable::new(band, &[lo, hi])
}

/// The stream of a pixel's refinement rays (its centre ray's is 0).
pub(crate) const REFINEMENT_STREAM: u64 = 0x7265_6669_6e65_6d74;
/// The stream of the pilot's sub-pixel probe of a pixel.
pub(crate) const PROBE_STREAM: u64 = 0x7072_6f62_6500_0000;
/// The stream of the pilot's re-traced sky-view rays of a pixel (plus the ray count).
pub(crate) const SKY_VIEW_STREAM: u64 = 0x736b_7976_6965_7700;
/// Mixed into a stream's seed for its shadow rays' points on the sun's disk: their own
/// stream, so that a sun leaves every other draw of the pixel as it was.
pub(crate) const SUN_STREAM: u64 = 0x7375_6e64_6973_6b00;
/// Mixed in like [`SUN_STREAM`] for the shadow rays only the sun's truth layers read.
pub(crate) const SUN_TRUTH_STREAM: u64 = 0x7375_6e74_7275_7468;

/// Per-ray state shared by the events.
pub(crate) struct Ctx<'a> {
    pub(crate) options: &'a TraceOptions,
    rng: Option<ChaCha8Rng>,
    /// The stream's points on the sun's disk ([`SUN_STREAM`]).
    sun_rng: Option<ChaCha8Rng>,
    /// The points on the disk of a ray whose sun truth alone needs shadow rays
    /// ([`SUN_TRUTH_STREAM`]).
    sun_truth_rng: Option<ChaCha8Rng>,
    /// This ray's truth is kept: a primary facet with no diffuse part then casts shadow
    /// rays too, for the sun's truth layers only.
    pub(crate) sun_truth: bool,
    /// Shadow rays per facet hit in place of the sun's own count (the pilot's measurement
    /// of each count on offer); `None`: the sun's.
    pub(crate) shadow_rays: Option<u32>,
    /// The pixel's index in the image, from which its random stream is seeded.
    pixel_index: u64,
    /// Which of the pixel's streams (0: its centre ray's and supersampling's).
    stream: u64,
}

impl<'a> Ctx<'a> {
    /// The state of a ray of pixel `pixel_index` (row-major) rendered with `options`.
    pub(crate) fn for_pixel(options: &'a TraceOptions, pixel_index: u64) -> Self {
        Self {
            options,
            rng: None,
            sun_rng: None,
            sun_truth_rng: None,
            sun_truth: false,
            shadow_rays: None,
            pixel_index,
            stream: 0,
        }
    }

    /// The same pixel with stream `stream` of its own (see [`REFINEMENT_STREAM`]).
    pub(crate) fn stream(mut self, stream: u64) -> Self {
        self.stream = stream;
        self.rng = None;
        self.sun_rng = None;
        self.sun_truth_rng = None;
        self
    }

    /// A uniform draw in [0, 1) from the pixel's stream.
    pub(crate) fn jitter(&mut self) -> f64 {
        self.rng().random()
    }

    /// The pixel's random stream, seeded on first use (most pixels never draw).
    pub(crate) fn rng(&mut self) -> &mut ChaCha8Rng {
        let seed = splitmix64(self.options.seed ^ splitmix64(self.pixel_index) ^ self.stream);
        self.rng
            .get_or_insert_with(|| ChaCha8Rng::seed_from_u64(seed))
    }

    /// The stream's own random numbers for points on the sun's disk, seeded on first use.
    pub(crate) fn sun_rng(&mut self) -> &mut ChaCha8Rng {
        let seed = splitmix64(
            self.options.seed ^ splitmix64(self.pixel_index) ^ splitmix64(self.stream ^ SUN_STREAM),
        );
        self.sun_rng
            .get_or_insert_with(|| ChaCha8Rng::seed_from_u64(seed))
    }

    /// The stream's random numbers for the shadow rays that only the sun's truth layers
    /// read (a primary mirror's), seeded on first use: apart from [`Self::sun_rng`], so that
    /// keeping the truth leaves the rendered radiance as it is.
    pub(crate) fn sun_truth_rng(&mut self) -> &mut ChaCha8Rng {
        let seed = splitmix64(
            self.options.seed
                ^ splitmix64(self.pixel_index)
                ^ splitmix64(self.stream ^ SUN_TRUTH_STREAM),
        );
        self.sun_truth_rng
            .get_or_insert_with(|| ChaCha8Rng::seed_from_u64(seed))
    }

    /// Visits the `n × n` stratified sub-pixel positions of pixel (`col`, `row`), row by
    /// row, each jittered in its cell by two draws of the pixel's stream made just before
    /// it is visited (so that what a visit draws, sky-view rays say, comes between). The
    /// one routine of the renderer's supersampling and of the pilot's, which must replay
    /// the renderer's rays exactly.
    pub(crate) fn for_each_subpixel(
        &mut self,
        (col, row): (u32, u32),
        n: u32,
        mut visit: impl FnMut(&mut Self, f64, f64),
    ) {
        for j in 0..n {
            for i in 0..n {
                let (jx, jy): (f64, f64) = {
                    let rng = self.rng();
                    (rng.random(), rng.random())
                };
                let x = f64::from(col) + (f64::from(i) + jx) / f64::from(n);
                let y = f64::from(row) + (f64::from(j) + jy) / f64::from(n);
                visit(self, x, y);
            }
        }
    }
}

/// What every ray of one frame shares, computed once per frame rather than per ray.
pub(crate) struct FrameConsts<'a> {
    camera: &'a Camera,
    /// The pixels whose centre rays [`Tracer::pixel`] may be asked for: a tile and its
    /// margin, so that a tile of a very wide or tall image holds tables of its own size.
    window: Tile,
    /// Image-plane u of the centre of each of the window's columns, from its first.
    us: Vec<f64>,
    /// Image-plane v of the centre of each of the window's rows, from its first.
    vs: Vec<f64>,
    /// The sensor in local coordinates.
    pub(crate) origin: V3,
    /// The sensor's altitude, metres (clamped at the ground).
    pub(crate) sensor_alt: f64,
    /// Cosine of the Earth's limb's angle from nadir seen from the sensor: rays with a
    /// larger cosine of their nadir angle meet the ground.
    pub(crate) cos_critical_nadir: f64,
    /// The primary hits' path terms in every sub-band, when [`PathTermsMode::Tabulated`].
    pub(crate) path_table: Option<PathTable>,
}

impl FrameConsts<'_> {
    /// The camera of the frame.
    pub(crate) fn camera(&self) -> &Camera {
        self.camera
    }
}

/// For every pixel of a `w × h` image of apparent temperatures `t` (row-major), the largest
/// difference between it and one of its 8 neighbours, K.
pub(crate) fn contrast_of(t: &[f64], w: usize, h: usize) -> Vec<f64> {
    (0..w * h)
        .into_par_iter()
        .map(|i| {
            let (col, row) = (i % w, i / w);
            let rows = row.saturating_sub(1)..(row + 2).min(h);
            rows.flat_map(|r| (col.saturating_sub(1)..(col + 2).min(w)).map(move |c| r * w + c))
                .map(|j| (t[i] - t[j]).abs())
                .fold(0.0, f64::max)
        })
        .collect()
}

/// The terrain background's surface-leaving radiance in sub-band `b`, W m⁻² sr⁻¹:
/// `ε·L_T + (1 − ε)·L_d(0)`, and with a sun or by day its sunlight ([`terrain_solar`])
/// more (the terrain is flat and unshadowed).
fn terrain_leaving<A: Atmosphere>(
    terrain: &Terrain,
    b: &BandData<A>,
    sun: Option<(&SunBeam, &SunGeometry)>,
) -> f64 {
    let eps = terrain.emissivity;
    let night = eps * b.terrain_blackbody + (1.0 - eps) * b.atmosphere.sky_hemispheric(0.0);
    if sun.is_none() && b.atmosphere.scattered().is_none() {
        return night;
    }
    night + terrain_solar(terrain, b, sun)
}

/// The sunlight in the terrain background's surface-leaving radiance in one sub-band,
/// W m⁻² sr⁻¹: the beam's `(1 − ε)·E_n(0)·cos θ_sun/π`, and by day the scattered sky's
/// `(1 − ε)·L_d,scattered(0)` (0 without either).
fn terrain_solar<A: Atmosphere>(
    terrain: &Terrain,
    b: &BandData<A>,
    sun: Option<(&SunBeam, &SunGeometry)>,
) -> f64 {
    let direct = sun.map_or(0.0, |(beam, geometry)| {
        let cos_zenith = geometry.to_sun[2].max(0.0);
        (1.0 - terrain.emissivity)
            * beam.normal_w_m2(0.0)
            * cos_zenith
            * std::f64::consts::FRAC_1_PI
    });
    match b.atmosphere.scattered() {
        None => direct,
        Some(s) => direct + (1.0 - terrain.emissivity) * s.sky_hemispheric(0.0),
    }
}

fn splitmix64(mut x: u64) -> u64 {
    x = x.wrapping_add(0x9E37_79B9_7F4A_7C15);
    x = (x ^ (x >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    x = (x ^ (x >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    x ^ (x >> 31)
}

impl<B: BandModel + Clone, A: Atmosphere> Tracer<B, A> {
    /// Validates the scene and materials, builds the BVH and precomputes each facet's L_T,
    /// for one band and its atmosphere.
    ///
    /// # Errors
    /// The raw scene or material library is invalid, or a facet names an unknown material.
    pub fn new(
        scene: &RawScene,
        materials: &MaterialLibrary,
        band: B,
        atmosphere: A,
    ) -> Result<Self, TraceError> {
        let one = SubBand {
            band: band.clone(),
            atmosphere,
            emissivity: None,
        };
        Self::with_sub_bands(scene, materials, band, vec![one])
    }
}

impl<B: BandModel, A: Atmosphere> Tracer<B, A> {
    /// [`Tracer::new`] for a radiance summed over `sub_bands` (the spectral model): each
    /// sub-band brings its own blackbody radiance, atmosphere and, optionally, material
    /// emissivities. `band` is the whole band, whose inverse gives the apparent
    /// temperature; the sub-bands should partition it.
    ///
    /// # Errors
    /// As [`Tracer::new`]; also no sub-band, or a sub-band whose emissivity list does not
    /// have one table per material.
    pub fn with_sub_bands(
        scene: &RawScene,
        materials: &MaterialLibrary,
        band: B,
        sub_bands: Vec<SubBand<B, A>>,
    ) -> Result<Self, TraceError> {
        scene
            .validate()
            .map_err(|e| TraceError::new(TraceErrorKind::InvalidScene(e)))?;
        materials
            .validate()
            .map_err(|e| TraceError::new(TraceErrorKind::InvalidMaterials(e)))?;
        if sub_bands.is_empty() {
            return Err(TraceError::new(TraceErrorKind::InvalidOptions(
                "no sub-band: expected at least one".into(),
            )));
        }
        let mut slot_of = vec![u16::MAX; usize::from(u16::MAX) + 1];
        let mut mats = Vec::with_capacity(materials.materials.len());
        let mut tables = Vec::with_capacity(materials.materials.len());
        for (slot, m) in materials.materials.iter().enumerate() {
            slot_of[usize::from(m.id.0)] = slot as u16;
            let (angle_deg, emissivity) = m.emissivity.iter().copied().unzip();
            let table = EmissivityTable::new(angle_deg, emissivity).map_err(|e| {
                TraceError::new(TraceErrorKind::InvalidEmissivity {
                    material: m.id.0,
                    reason: e.to_string(),
                })
            })?;
            tables.push(table);
            mats.push(MaterialData {
                id: m.id.0,
                name: m.name.clone(),
                specular_fraction: m.specular_fraction,
                lobe: m
                    .rms_slope
                    .filter(|&sigma| sigma > 0.0 && m.specular_fraction > 0.0)
                    .map(crate::lobe::Lobe::new),
            });
        }
        // One table entry per distinct temperature (scenes hold few, and neighbouring facets
        // usually share one), so K sub-bands cost K small tables, not K × facets; the
        // records' L_T is read from the first sub-band's.
        let mut temperatures: Vec<f64> = Vec::new();
        let mut index_of: std::collections::HashMap<u64, u32> = std::collections::HashMap::new();
        let mut last: Option<(u64, u32)> = None;
        let mut temperature_index = Vec::with_capacity(scene.facets.len());
        for (i, f) in scene.facets.iter().enumerate() {
            if slot_of[usize::from(f.material.0)] == u16::MAX {
                return Err(TraceError::new(TraceErrorKind::UnknownMaterial {
                    facet: i,
                    material: f.material.0,
                }));
            }
            let bits = f.temperature_k.to_bits();
            temperature_index.push(match last {
                Some((b, index)) if b == bits => index,
                _ => {
                    let index = *index_of.entry(bits).or_insert_with(|| {
                        temperatures.push(f.temperature_k);
                        (temperatures.len() - 1) as u32
                    });
                    last = Some((bits, index));
                    index
                }
            });
        }
        drop(index_of);
        let first = &sub_bands[0].band;
        let blackbody: Vec<f64> = temperatures.iter().map(|&t| first.radiance(t)).collect();
        let radiometry = |i: usize| {
            let t = temperature_index[i] as usize;
            FacetRadiometry {
                material: slot_of[usize::from(scene.facets[i].material.0)],
                temperature_index: t as u32,
                temperature_k: temperatures[t],
                blackbody: blackbody[t],
            }
        };
        // Indices were checked by validate().
        let triangle = |i: usize| {
            scene.facets[i]
                .vertices
                .map(|v| scene.positions_m[v as usize])
        };
        let geometry = Geometry::with_data(scene.facets.len(), triangle, radiometry);
        drop(temperature_index);
        let mut tracer = Self {
            geometry,
            materials: mats,
            terrain: scene.terrain,
            band,
            bands: BandSet {
                bands: Vec::new(),
                shared_grids: false,
            },
            temperatures,
            emissivity: tables,
            path_terms: PathTermsMode::Exact,
            refinement: None,
            sun: None,
        };
        let mut own = tracer.band_set(sub_bands)?;
        // The first sub-band's L_T is in the facet records.
        own.bands[0].inline = true;
        own.bands[0].blackbody = Vec::new();
        tracer.bands = own;
        Ok(tracer)
    }

    /// This tracer with its sub-bands replaced by `sub_bands` (another atmosphere or
    /// another partition of the band), the BVH kept. The sun, whose beam is given per
    /// sub-band, goes with the old sub-bands: give it again ([`Self::with_sun`]).
    ///
    /// # Errors
    /// As [`Tracer::band_set`].
    pub fn with_bands(mut self, sub_bands: Vec<SubBand<B, A>>) -> Result<Self, TraceError> {
        self.bands = self.band_set(sub_bands)?;
        self.sun = None;
        Ok(self)
    }

    /// This tracer lit by `sun` (`None`: no sun, the default), whose beam list holds one
    /// beam per sub-band of the tracer's own ([`crate::sun`] says what the sun adds). Band
    /// sets made for other sub-bands ([`Self::band_set`]) have no sun. Setting a sun again
    /// replaces the previous one.
    ///
    /// # Errors
    /// A sun direction that is not a finite non-zero vector, an angular radius outside
    /// (0°, 10°], a shadow-ray count outside 1 to [`crate::sun::MAX_SHADOW_RAYS`], or not
    /// one beam per sub-band.
    pub fn with_sun(mut self, sun: Option<Sun>) -> Result<Self, TraceError> {
        let Some(sun) = sun else {
            self.remove_sun();
            return Ok(self);
        };
        let geometry = sun.geometry()?;
        if sun.beams.len() != self.bands.len() {
            return Err(TraceError::new(TraceErrorKind::InvalidOptions(format!(
                "sun: {} beams for {} sub-bands: expected one per sub-band",
                sun.beams.len(),
                self.bands.len()
            ))));
        }
        self.remove_sun();
        let terrain = self.terrain;
        for (b, beam) in self.bands.bands.iter_mut().zip(sun.beams) {
            b.terrain_leaving = terrain_leaving(&terrain, b, Some((&beam, &geometry)));
            b.terrain_solar = terrain_solar(&terrain, b, Some((&beam, &geometry)));
            b.sun = Some(beam);
        }
        self.sun = Some(geometry);
        Ok(self)
    }

    /// Takes the sun away, its terrain term with it.
    fn remove_sun(&mut self) {
        if self.sun.take().is_none() {
            return;
        }
        let terrain = self.terrain;
        for b in &mut self.bands.bands {
            b.sun = None;
            b.terrain_leaving = terrain_leaving(&terrain, b, None);
            b.terrain_solar = terrain_solar(&terrain, b, None);
        }
    }

    /// `set` (made by [`Self::band_set`]) lit by this tracer's sun with one beam per
    /// sub-band: what the pilot evaluates a sunlit frame's recorded paths with, so that
    /// its sub-band sets carry the sunlight of their own sub-bands. `None`: no sun, the
    /// set as it was.
    ///
    /// # Errors
    /// Beams given to a tracer without a sun, or not one beam per sub-band.
    pub fn lit_band_set<S: Atmosphere>(
        &self,
        mut set: BandSet<S>,
        beams: Option<Vec<SunBeam>>,
    ) -> Result<BandSet<S>, TraceError> {
        let Some(beams) = beams else {
            return Ok(set);
        };
        let bad = |m: String| TraceError::new(TraceErrorKind::InvalidOptions(m));
        let geometry = self
            .sun
            .as_ref()
            .ok_or_else(|| bad("sun beams for a band set of a tracer without a sun".into()))?;
        if beams.len() != set.len() {
            return Err(bad(format!(
                "sun: {} beams for {} sub-bands: expected one per sub-band",
                beams.len(),
                set.len()
            )));
        }
        let terrain = self.terrain;
        for (b, beam) in set.bands.iter_mut().zip(beams) {
            b.terrain_leaving = terrain_leaving(&terrain, b, Some((&beam, geometry)));
            b.terrain_solar = terrain_solar(&terrain, b, Some((&beam, geometry)));
            b.sun = Some(beam);
        }
        Ok(set)
    }

    /// Whether the sun shines on this tracer's scene ([`Self::with_sun`]).
    #[must_use]
    pub fn has_sun(&self) -> bool {
        self.sun.is_some()
    }

    /// The sub-bands `sub_bands` prepared for this tracer's scene: every facet temperature's
    /// and the terrain's blackbody radiance in each, and each material's emissivity. For
    /// evaluating recorded paths under another band model or atmosphere (the pilot).
    ///
    /// # Errors
    /// No sub-band, or a sub-band whose emissivity list does not have one table per
    /// material.
    pub fn band_set<S: Atmosphere>(
        &self,
        sub_bands: Vec<SubBand<B, S>>,
    ) -> Result<BandSet<S>, TraceError> {
        if sub_bands.is_empty() {
            return Err(TraceError::new(TraceErrorKind::InvalidOptions(
                "no sub-band: expected at least one".into(),
            )));
        }
        let terrain = self.terrain;
        let mut bands = Vec::with_capacity(sub_bands.len());
        for (k, sb) in sub_bands.into_iter().enumerate() {
            let emissivity = match sb.emissivity {
                None => self.emissivity.clone(),
                Some(e) if e.len() == self.emissivity.len() => e,
                Some(e) => {
                    return Err(TraceError::new(TraceErrorKind::InvalidOptions(format!(
                        "sub-band {}: {} emissivity tables for {} materials",
                        k + 1,
                        e.len(),
                        self.emissivity.len()
                    ))));
                }
            };
            let (blackbody, derivative) = self
                .temperatures
                .iter()
                .map(|&t| sb.band.radiance_and_derivative(t))
                .unzip();
            let terrain_blackbody = sb.band.radiance(terrain.temperature_k);
            let own_emissivity = emissivity
                .iter()
                .zip(&self.emissivity)
                .map(|(a, b)| a == b)
                .collect();
            bands.push(BandData {
                atmosphere: sb.atmosphere,
                emissivity,
                own_emissivity,
                blackbody,
                derivative,
                inline: false,
                terrain_blackbody,
                terrain_leaving: 0.0,
                terrain_solar: 0.0,
                sun: None,
            });
            let b = bands.last_mut().expect("just pushed");
            b.terrain_leaving = terrain_leaving(&terrain, b, None);
            b.terrain_solar = terrain_solar(&terrain, b, None);
        }
        Ok(BandSet::new(bands))
    }

    /// The geometry (BVH and re-centring).
    #[must_use]
    pub fn geometry(&self) -> &Geometry<FacetRadiometry> {
        &self.geometry
    }

    /// The whole band.
    #[must_use]
    pub fn band(&self) -> &B {
        &self.band
    }

    /// How many sub-bands the radiance equation is summed over (1: the band model).
    #[must_use]
    pub fn sub_bands(&self) -> usize {
        self.bands.len()
    }

    fn frame_consts<'a>(&self, camera: &'a Camera, window: Tile) -> FrameConsts<'a> {
        self.frame_consts_with(camera, self.path_terms == PathTermsMode::Tabulated, window)
    }

    /// What a frame's rays share, with this tracer's path-term table when `table`, for
    /// the centre rays of the pixels of `window` (a rectangle of the image).
    pub(crate) fn frame_consts_with<'a>(
        &self,
        camera: &'a Camera,
        table: bool,
        window: Tile,
    ) -> FrameConsts<'a> {
        let sensor_alt = camera.position_m[2].max(0.0);
        let (columns, rows) = (
            window.x..window.x + window.width,
            window.y..window.y + window.height,
        );
        FrameConsts {
            camera,
            window,
            us: columns.map(|c| camera.u_at(f64::from(c) + 0.5)).collect(),
            vs: rows.map(|r| camera.v_at(f64::from(r) + 0.5)).collect(),
            origin: self.geometry.to_local(camera.position_m),
            sensor_alt,
            cos_critical_nadir: self.cos_critical_nadir(camera),
            path_table: table.then(|| self.path_table(camera, &self.bands)),
        }
    }

    /// Cosine of the Earth's limb's angle from nadir seen from `camera` (clamped at the
    /// ground): rays with a larger cosine of their nadir angle meet the terrain, the rest
    /// see the sky.
    pub(crate) fn cos_critical_nadir(&self, camera: &Camera) -> f64 {
        self.bands.bands[0]
            .atmosphere
            .critical_nadir_angle_deg(camera.position_m[2].max(0.0))
            .to_radians()
            .cos()
    }

    /// The path-term table of `camera`'s frame for every sub-band of `set`: over the
    /// scene's altitudes, from the nearest to the farthest point of its box.
    pub(crate) fn path_table<S: Atmosphere>(&self, camera: &Camera, set: &BandSet<S>) -> PathTable {
        let sensor_alt = camera.position_m[2].max(0.0);
        let [lo, hi] = self.geometry.bounds_m();
        let p = camera.position_m;
        // Nearest and farthest points of the box from the sensor.
        let near: f64 = (0..3)
            .map(|k| (p[k] - p[k].clamp(lo[k], hi[k])).powi(2))
            .sum::<f64>()
            .sqrt();
        let far: f64 = (0..3)
            .map(|k| (p[k] - lo[k]).abs().max((p[k] - hi[k]).abs()).powi(2))
            .sum::<f64>()
            .sqrt();
        let atmospheres: Vec<&S> = set.bands.iter().map(|b| &b.atmosphere).collect();
        PathTable::new(
            &atmospheres,
            sensor_alt,
            [lo[2].max(0.0), hi[2].max(0.0)],
            [near, far],
        )
    }

    /// Chooses how primary hits get their path terms (default [`PathTermsMode::Exact`]).
    #[must_use]
    pub fn with_path_terms(mut self, mode: PathTermsMode) -> Self {
        self.path_terms = mode;
        self
    }

    /// How primary hits get their path terms.
    #[must_use]
    pub fn path_terms(&self) -> PathTermsMode {
        self.path_terms
    }

    /// Refines every frame's pixels to a standard-error target ([`crate::refine`]), or not
    /// (`None`, the default: the options' supersampling).
    ///
    /// # Errors
    /// A refinement out of range.
    pub fn with_refinement(mut self, refinement: Option<Refinement>) -> Result<Self, TraceError> {
        if let Some(r) = &refinement {
            r.validate()
                .map_err(|m| TraceError::new(TraceErrorKind::InvalidOptions(m)))?;
        }
        self.refinement = refinement;
        Ok(self)
    }

    /// The refinement frames are rendered with.
    #[must_use]
    pub fn refinement(&self) -> Option<Refinement> {
        self.refinement
    }

    /// Apparent (blackbody) temperature of a radiance in the whole band, K.
    #[must_use]
    pub fn apparent_temperature_k(&self, radiance_w_m2_sr: f64) -> f64 {
        self.band.temperature(radiance_w_m2_sr)
    }

    /// The inverse table every image of this tracer takes apparent temperatures through
    /// (adaptive supersampling's edge test, the truth EXR's `apparent_temperature`): over
    /// the band radiances of [`INVERSE_TABLE_K`], whatever the image. The same radiance so
    /// gets the same temperature, bit for bit, in a whole frame and in each of its tiles: a
    /// table over an image's own radiance range starts Newton's polish elsewhere for a tile
    /// than for its frame, and the last bits, and so an edge test at its threshold, could
    /// differ. Radiances outside the span are solved cold, to the same precision.
    #[must_use]
    pub fn inverse_table(&self) -> InverseTable<'_, B> {
        inverse_table(&self.band)
    }

    /// Renders every pixel of `camera`'s image, rows in parallel (rayon): the whole image as
    /// one tile ([`Self::render_tile`]). `progress` is called with 1 after each row. The
    /// result does not depend on the thread count.
    ///
    /// # Errors
    /// The options are out of range.
    pub fn render(
        &self,
        camera: &Camera,
        options: &TraceOptions,
        progress: &(dyn Fn(u64) + Sync),
    ) -> Result<Frame, TraceError> {
        let [w, h] = camera.pixels;
        self.render_tile(camera, options, Tile::whole(w, h), progress)
    }

    /// The pixels of `frame` whose apparent temperature differs from one of its 8
    /// neighbours' by more than `threshold_k` (the diagonal ones count: a corner of a facet
    /// can cut into a pixel whose 4-neighbours' centres all miss it).
    pub(crate) fn edges(&self, frame: &Frame, threshold_k: f64) -> Vec<bool> {
        let inverse = self.inverse_table();
        let t: Vec<f64> = frame
            .radiance_w_m2_sr
            .par_chunks(4096)
            .flat_map_iter(|run| inverse.temperatures(run.iter().copied()))
            .collect();
        let (w, h) = (frame.width as usize, frame.height as usize);
        contrast_of(&t, w, h)
            .into_iter()
            .map(|c| c > threshold_k)
            .collect()
    }

    /// Renders the pixels of `tile` of `camera`'s image, rows in parallel, exactly as
    /// [`Self::render`] renders them in the whole image: each pixel's rays and random
    /// stream are its own (seeded by its index in the whole image), and adaptive
    /// supersampling compares the tile's pixels with their neighbours' centre rays over a
    /// one-pixel margin, so every pixel is bit for bit the whole frame's. The frame returned
    /// is the tile's: `tile.width × tile.height`, row 0 the tile's top row. What it holds
    /// beyond its pixels is of the tile's size too, never the image's: the camera's
    /// per-column and per-row directions over the tile's columns and rows and its margin,
    /// and, with adaptive supersampling or refinement, the centre rays of the margin.
    ///
    /// # Errors
    /// The options are out of range, or the tile is empty or reaches beyond the image.
    pub fn render_tile(
        &self,
        camera: &Camera,
        options: &TraceOptions,
        tile: Tile,
        progress: &(dyn Fn(u64) + Sync),
    ) -> Result<Frame, TraceError> {
        options.validate()?;
        let [w, h] = camera.pixels;
        tile.check(w, h)
            .map_err(|e| TraceError::new(TraceErrorKind::InvalidTile(e)))?;
        // Every pixel a tile traces lies in it or in its one-pixel margin.
        let fc = self.frame_consts(camera, tile.grown(1, w, h));
        if let Some(refinement) = self.refinement {
            if options.supersampling != 1 || options.adaptive_threshold_k.is_some() {
                return Err(TraceError::new(TraceErrorKind::InvalidOptions(
                    "refinement replaces supersampling: give one ray per pixel (supersampling \
                     1, no adaptive threshold) with it"
                        .into(),
                )));
            }
            return Ok(self.render_refined(&fc, options, &refinement, tile, progress));
        }
        let adaptive = options
            .adaptive_threshold_k
            .filter(|_| options.supersampling > 1);
        let Some(threshold_k) = adaptive else {
            return Ok(self.render_rect(&fc, options, tile, progress));
        };
        // The centre rays of the tile and a one-pixel margin: an edge test needs all 8
        // neighbours, as in the whole frame (the margin stops at the image's border, where
        // the whole frame's neighbourhood stops too).
        let centre_options = TraceOptions {
            supersampling: 1,
            adaptive_threshold_k: None,
            ..*options
        };
        let halo = tile.grown(1, w, h);
        let centres = self.render_rect(&fc, &centre_options, halo, &|_| {});
        let refine = self.edges(&centres, threshold_k);
        let tw = tile.width as usize;
        let (mut radiance, flags, truth, sun) = if halo == tile {
            // The whole image: the margin is empty, nothing to crop.
            (centres.radiance_w_m2_sr, refine, centres.truth, centres.sun)
        } else {
            let (dx, dy) = ((tile.x - halo.x) as usize, (tile.y - halo.y) as usize);
            let hw = halo.width as usize;
            let crop = |r: usize| (r + dy) * hw + dx..(r + dy) * hw + dx + tw;
            let mut radiance = Vec::with_capacity(tile.pixels());
            let mut flags = Vec::with_capacity(tile.pixels());
            let mut truth = Vec::new();
            let mut sun = Vec::new();
            for r in 0..tile.height as usize {
                radiance.extend_from_slice(&centres.radiance_w_m2_sr[crop(r)]);
                flags.extend_from_slice(&refine[crop(r)]);
                if !centres.truth.is_empty() {
                    truth.extend_from_slice(&centres.truth[crop(r)]);
                }
                if !centres.sun.is_empty() {
                    sun.extend_from_slice(&centres.sun[crop(r)]);
                }
            }
            (radiance, flags, truth, sun)
        };
        let full = TraceOptions {
            adaptive_threshold_k: None,
            ..*options
        };
        radiance
            .par_chunks_mut(tw)
            .zip(flags.par_chunks(tw))
            .enumerate()
            .for_each(|(r, (rad, flags))| {
                let mut path = Path::default();
                let mut scratch = Sample::miss(Event::Sky);
                let row = tile.y + r as u32;
                for (c, (l_out, &flag)) in rad.iter_mut().zip(flags).enumerate() {
                    if flag {
                        *l_out = self.pixel::<false>(
                            &fc,
                            &full,
                            tile.x + c as u32,
                            row,
                            &mut path,
                            &mut scratch,
                        );
                    }
                }
                progress(1);
            });
        Ok(Frame {
            width: tile.width,
            height: tile.height,
            radiance_w_m2_sr: radiance,
            truth,
            sampling: Vec::new(),
            sun,
        })
    }

    /// [`Self::render_tile`] with refinement: the centre rays of the tile and a one-pixel
    /// margin, the candidates among the tile's pixels (an edge against a neighbour, or a
    /// thin facet near), and each candidate refined to the target.
    fn render_refined(
        &self,
        fc: &FrameConsts<'_>,
        options: &TraceOptions,
        refinement: &Refinement,
        tile: Tile,
        progress: &(dyn Fn(u64) + Sync),
    ) -> Frame {
        let camera = fc.camera();
        let [w, h] = camera.pixels;
        let halo = tile.grown(1, w, h);
        // The centre pass keeps every centre's terms: a pixel that stays with its centre
        // ray gives the budget its sensitivities.
        let centres = self.refinement_centres(fc, options, halo);
        let inverse = self.inverse_table();
        let calm: Vec<f64> = centres
            .calm_w_m2_sr
            .par_chunks(4096)
            .flat_map_iter(|run| inverse.temperatures(run.iter().copied()))
            .collect();
        let contrast = contrast_of(&calm, halo.width as usize, halo.height as usize);
        let thin = self.thin_pixels_in(camera, tile);
        // What a thin facet, which no centre may have seen, could hide: the same for a tile
        // as for its frame.
        let thin_contrast_k = self.contrast_bound_k();
        let (hw, tw) = (halo.width as usize, tile.width as usize);
        let (dx, dy) = ((tile.x - halo.x) as usize, (tile.y - halo.y) as usize);
        let mut radiance = vec![0.0; tile.pixels()];
        let mut sampling = vec![PixelSampling::default(); tile.pixels()];
        radiance
            .par_chunks_mut(tw)
            .zip(sampling.par_chunks_mut(tw))
            .enumerate()
            .for_each(|(r, (rad, smp))| {
                let mut path = Path::default();
                let row = tile.y + r as u32;
                for (c, (l_out, s_out)) in rad.iter_mut().zip(smp.iter_mut()).enumerate() {
                    let col = tile.x + c as u32;
                    let at = (r + dy) * hw + c + dx;
                    let is_thin = thin[r * tw + c];
                    if contrast[at] > refinement.edge_k || is_thin {
                        let start = if is_thin {
                            refinement.thin_side
                        } else {
                            EDGE_SIDE.min(refinement.max_side)
                        };
                        let one = (col, row);
                        // What a sliver could hide: the neighbours' contrast, or for a thin
                        // facet, which no centre may have seen, the frame's.
                        let hide = if is_thin {
                            thin_contrast_k
                        } else {
                            contrast[at]
                        };
                        (*l_out, *s_out) = if options.truth {
                            self.refine_pixel::<true>(
                                fc, options, refinement, &inverse, one, start, hide, &mut path,
                            )
                        } else {
                            self.refine_pixel::<false>(
                                fc, options, refinement, &inverse, one, start, hide, &mut path,
                            )
                        };
                    } else {
                        *l_out = centres.radiance_w_m2_sr[at];
                        *s_out = PixelSampling::from_truth(&centres.truth[at]);
                    }
                }
                progress(1);
            });
        let crop = |all: &[SunPixel]| -> Vec<SunPixel> {
            (0..tile.height as usize)
                .flat_map(|r| {
                    let start = (r + dy) * hw + dx;
                    all[start..start + tw].iter().copied()
                })
                .collect()
        };
        let (truth, sun) = if options.truth {
            let truth = (0..tile.height as usize)
                .flat_map(|r| {
                    let start = (r + dy) * hw + dx;
                    centres.truth[start..start + tw].iter().copied()
                })
                .collect();
            let sun = if self.sun.is_some() {
                crop(&centres.sun)
            } else {
                Vec::new()
            };
            (truth, sun)
        } else {
            (Vec::new(), Vec::new())
        };
        Frame {
            width: tile.width,
            height: tile.height,
            radiance_w_m2_sr: radiance,
            truth,
            sampling,
            sun,
        }
    }

    /// The pixels of `tile` (checked to lie in the image), rows in parallel: a frame of the
    /// tile's size.
    fn render_rect(
        &self,
        fc: &FrameConsts<'_>,
        options: &TraceOptions,
        tile: Tile,
        progress: &(dyn Fn(u64) + Sync),
    ) -> Frame {
        let n = tile.pixels();
        let row_len = tile.width.max(1) as usize;
        let mut radiance = vec![0.0; n];
        let mut truth = Vec::new();
        let mut sun = Vec::new();
        if options.truth && self.sun.is_some() {
            // The sun's layers in a vector of their own, so that a night frame's loop
            // below stays as it was.
            truth = vec![TruthPixel::from(&Sample::miss(Event::Sky)); n];
            sun = vec![SunPixel::from(&Sample::miss(Event::Sky)); n];
            radiance
                .par_chunks_mut(row_len)
                .zip(truth.par_chunks_mut(row_len))
                .zip(sun.par_chunks_mut(row_len))
                .enumerate()
                .for_each(|(r, ((rad, tru), sun))| {
                    let mut path = Path::default();
                    let mut centre = Sample::miss(Event::Sky);
                    let row = tile.y + r as u32;
                    for (c, ((l_out, t_out), s_out)) in rad
                        .iter_mut()
                        .zip(tru.iter_mut())
                        .zip(sun.iter_mut())
                        .enumerate()
                    {
                        *l_out = self.pixel::<true>(
                            fc,
                            options,
                            tile.x + c as u32,
                            row,
                            &mut path,
                            &mut centre,
                        );
                        *t_out = TruthPixel::from(&centre);
                        *s_out = SunPixel::from(&centre);
                    }
                    progress(1);
                });
        } else if options.truth {
            truth = vec![TruthPixel::from(&Sample::miss(Event::Sky)); n];
            radiance
                .par_chunks_mut(row_len)
                .zip(truth.par_chunks_mut(row_len))
                .enumerate()
                .for_each(|(r, (rad, tru))| {
                    let mut path = Path::default();
                    let mut centre = Sample::miss(Event::Sky);
                    let row = tile.y + r as u32;
                    for (c, (l_out, t_out)) in rad.iter_mut().zip(tru.iter_mut()).enumerate() {
                        *l_out = self.pixel::<true>(
                            fc,
                            options,
                            tile.x + c as u32,
                            row,
                            &mut path,
                            &mut centre,
                        );
                        *t_out = TruthPixel::from(&centre);
                    }
                    progress(1);
                });
        } else {
            radiance
                .par_chunks_mut(row_len)
                .enumerate()
                .for_each(|(r, rad)| {
                    let mut path = Path::default();
                    let mut scratch = Sample::miss(Event::Sky);
                    let row = tile.y + r as u32;
                    for (c, l_out) in rad.iter_mut().enumerate() {
                        *l_out = self.pixel::<false>(
                            fc,
                            options,
                            tile.x + c as u32,
                            row,
                            &mut path,
                            &mut scratch,
                        );
                    }
                    progress(1);
                });
        }
        Frame {
            width: tile.width,
            height: tile.height,
            radiance_w_m2_sr: radiance,
            truth,
            sampling: Vec::new(),
            sun,
        }
    }

    /// Every term of the ray through the centre of pixel `(column, row)`, exactly as
    /// [`Self::render`] computes them for the truth outputs, in f64.
    ///
    /// # Errors
    /// The pixel lies outside the image, or the options are out of range.
    pub fn probe(
        &self,
        camera: &Camera,
        options: &TraceOptions,
        column: u32,
        row: u32,
    ) -> Result<Sample, TraceError> {
        options.validate()?;
        let [w, h] = camera.pixels;
        if column >= w || row >= h {
            return Err(TraceError::new(TraceErrorKind::PixelOutsideImage {
                column,
                row,
                width: w,
                height: h,
            }));
        }
        let mut s = Sample::miss(Event::Sky);
        let mut path = Path::default();
        self.pixel::<true>(
            &self.frame_consts(
                camera,
                Tile {
                    x: column,
                    y: row,
                    width: 1,
                    height: 1,
                },
            ),
            options,
            column,
            row,
            &mut path,
            &mut s,
        );
        Ok(s)
    }

    /// Radiance of a pixel (mean over its sub-pixel rays). With `TRUTH`, the centre ray's
    /// terms go to `centre` (written in place: a sample is 192 bytes, and moving it
    /// through every call level showed as memory copies in the profile); without, `centre`
    /// is not touched. `path` is scratch space reused from pixel to pixel.
    fn pixel<const TRUTH: bool>(
        &self,
        fc: &FrameConsts<'_>,
        options: &TraceOptions,
        col: u32,
        row: u32,
        path: &mut Path,
        centre: &mut Sample,
    ) -> f64 {
        let camera = fc.camera;
        let mut ctx = Ctx::for_pixel(
            options,
            u64::from(row) * u64::from(camera.pixels[0]) + u64::from(col),
        );
        // Bit for bit `camera.pixel_direction(col, row)`, without its divisions; the pixel
        // lies in the window (`frame_consts`'s callers make it so).
        let dir = camera.direction_uv(
            fc.us[(col - fc.window.x) as usize],
            fc.vs[(row - fc.window.y) as usize],
        );
        ctx.sun_truth = TRUTH;
        self.follow(fc, dir, &mut ctx, path);
        ctx.sun_truth = false;
        let centre_radiance = self.radiance::<TRUTH>(fc, path, centre);
        let n = options.supersampling;
        if n <= 1 {
            return centre_radiance;
        }
        let mut sum = 0.0;
        ctx.for_each_subpixel((col, row), n, |ctx, x, y| {
            // Only the centre ray's terms are kept: the sub-pixel rays compute radiance.
            self.follow(fc, camera.direction_at(x, y), ctx, path);
            sum += self.radiance::<false>(fc, path, centre);
        });
        sum / f64::from(n * n)
    }
}

#[cfg(test)]
mod event_names {
    use super::Event;

    #[test]
    fn every_event_is_a_class_event_a_decision_may_name() {
        let names: Vec<&str> = Event::ALL.iter().map(|e| e.name()).collect();
        assert_eq!(names, irsig_model::decision::CLASS_EVENTS);
    }
}
