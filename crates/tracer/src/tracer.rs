//! The radiance equation along each ray: the four events of thesis Figure 6 (§3.3).

use std::fmt;

use irsig_atmosphere::range_to_ground_from_cos_m;
use irsig_model::truth::Layer;
use irsig_model::{MaterialLibrary, RawScene, Terrain};
use irsig_radiometry::{BandModel, EmissivityTable};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

use crate::camera::Camera;
use crate::env::Atmosphere;
use crate::error::{TraceError, TraceErrorKind};
use crate::geometry::{Geometry, Hit};
use crate::path_table::{PathTable, PathTermsMode};
use crate::vec::{V3, add, basis, dot, scale, sub};

/// What a ray met (thesis Figure 6, with the two kinds of miss told apart).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
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
}

/// Options of one rendering. The defaults are the thesis's model: one specular bounce,
/// no sky-view factor (F = 1), one ray per pixel.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TraceOptions {
    /// Specular reflection rays along one path (default 1; Appendix A: one is enough at
    /// earth-ambient temperatures). 0 makes specular facets reflect the sky at the mirror
    /// angle without tracing. At the last bounce a facet's specular part reflects the
    /// hemispheric sky.
    pub specular_bounces: u32,
    /// Cosine-weighted hemisphere rays per diffuse primary hit for the sky-view factor F;
    /// 0 (default) switches the model off (F = 1, no rays cast).
    pub sky_view_rays: u32,
    /// Supersampling: `n` gives n × n stratified, jittered rays per pixel; 1 (default) is
    /// one ray through the pixel centre.
    pub supersampling: u32,
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
            seed: 0,
            truth: true,
        }
    }
}

impl TraceOptions {
    fn validate(&self) -> Result<(), TraceError> {
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
    /// surface-leaving radiance of the second facet) or `L_d(θ_r)` of event 3.
    pub specular_incident_w_m2_sr: f64,
    /// Zenith angle of the reflection ray, degrees.
    pub reflected_zenith_deg: f64,
    /// Hemispheric sky radiance at the hit, `L_d`, W m⁻² sr⁻¹.
    pub sky_hemispheric_w_m2_sr: f64,
    /// Sky-view (shape) factor F (1 when the model is off).
    pub sky_view_factor: f64,
    /// Diffuse incident radiance `F·L_d + (1 − F)·L_b`, W m⁻² sr⁻¹.
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
}

impl Sample {
    /// The angle between the reversed ray and the facet normal, degrees (NaN when no facet
    /// was hit).
    #[must_use]
    pub fn incidence_deg(&self) -> f64 {
        self.cos_incidence.acos().to_degrees()
    }

    fn miss(event: Event) -> Self {
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
        }
    }
}

impl fmt::Display for Sample {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let facet = self
            .facet
            .map_or_else(|| "none".to_owned(), |i| i.to_string());
        writeln!(
            f,
            "event                      {} ({:?})",
            self.event.number(),
            self.event
        )?;
        writeln!(
            f,
            "facet                      {facet}{}",
            if self.back_face { " (back face)" } else { "" }
        )?;
        writeln!(f, "primary material           {}", self.primary_material)?;
        writeln!(f, "secondary material         {}", self.secondary_material)?;
        writeln!(f, "range_m                    {}", self.range_m)?;
        writeln!(f, "incidence_deg              {}", self.incidence_deg())?;
        writeln!(f, "kinetic temperature_k      {}", self.temperature_k)?;
        writeln!(f, "emissivity ε               {}", self.emissivity)?;
        writeln!(f, "reflectance r = 1 − ε      {}", self.reflectance)?;
        writeln!(f, "specular fraction s        {}", self.specular_fraction)?;
        writeln!(f, "L_T (W m-2 sr-1)           {}", self.blackbody_w_m2_sr)?;
        writeln!(
            f,
            "reflected zenith_deg       {}",
            self.reflected_zenith_deg
        )?;
        writeln!(
            f,
            "L_spec = L_b or L_d(θr)    {}",
            self.specular_incident_w_m2_sr
        )?;
        writeln!(
            f,
            "L_d hemispheric            {}",
            self.sky_hemispheric_w_m2_sr
        )?;
        writeln!(f, "sky-view factor F          {}", self.sky_view_factor)?;
        writeln!(
            f,
            "F·L_d + (1 − F)·L_b        {}",
            self.diffuse_incident_w_m2_sr
        )?;
        writeln!(
            f,
            "surface-leaving L(0,θ)     {}",
            self.surface_leaving_w_m2_sr
        )?;
        writeln!(f, "τ                          {}", self.transmission)?;
        writeln!(
            f,
            "L_u (W m-2 sr-1)           {}",
            self.path_radiance_w_m2_sr
        )?;
        write!(f, "L at sensor (W m-2 sr-1)   {}", self.radiance_w_m2_sr)
    }
}

/// The truth layers of one pixel: the terms of the ray through its centre that the truth
/// outputs carry, rounded to f32 as the truth EXR stores them: 40 bytes, where a whole
/// [`Sample`] is 144. (Keeping a whole sample per pixel cost 10-45 ns per primary ray at
/// 1k-1M triangles; this record, with the angle derived later, costs 2-4 ns:
/// BENCHMARKS.md.) [`Tracer::probe`] gives every term of a pixel in f64. Terms that do not
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
}

// The sizes the frame's memory traffic was measured at (the doc above).
const _: () = assert!(std::mem::size_of::<TruthPixel>() == 40);
const _: () = assert!(std::mem::size_of::<Sample>() == 144);

impl TruthPixel {
    /// The angle between the reversed ray and the facet normal, degrees, rounded to f32 (NaN
    /// when no facet was hit).
    #[must_use]
    pub fn incidence_deg(&self) -> f32 {
        self.cos_incidence.acos().to_degrees() as f32
    }

    /// The value of truth `layer` for this pixel, as the truth EXR stores it; `None` for
    /// the layers that come from the pixel's radiance instead ([`Layer::Radiance`],
    /// [`Layer::ApparentTemperature`]).
    #[must_use]
    pub fn layer(&self, layer: Layer) -> Option<f32> {
        Some(match layer {
            Layer::MaterialPrimary => f32::from(self.primary_material),
            Layer::MaterialSecondary => f32::from(self.secondary_material),
            Layer::Event => f32::from(self.event.number()),
            Layer::Range => self.range_m,
            Layer::Incidence => self.incidence_deg(),
            Layer::KineticTemperature => self.temperature_k,
            Layer::Emissivity => self.emissivity,
            Layer::Transmission => self.transmission,
            Layer::PathRadiance => self.path_radiance_w_m2_sr,
            Layer::SkyViewFactor => self.sky_view_factor,
            Layer::Radiance | Layer::ApparentTemperature => return None,
        })
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
}

impl Frame {
    /// One truth layer of every pixel, row-major, as the truth EXR stores it (f32; NaN
    /// where the term does not apply). `None` when the frame kept no truth or the layer
    /// comes from the radiance ([`TruthPixel::layer`]).
    #[must_use]
    pub fn truth_layer(&self, layer: Layer) -> Option<Vec<f32>> {
        if self.truth.is_empty() {
            return None;
        }
        self.truth.iter().map(|p| p.layer(layer)).collect()
    }

    /// The radiance of every pixel rounded to f32, as the radiance EXR stores it.
    #[must_use]
    pub fn radiance_f32(&self) -> Vec<f32> {
        self.radiance_w_m2_sr.iter().map(|&l| l as f32).collect()
    }
}

#[derive(Debug, Clone)]
struct MaterialData {
    id: u16,
    /// The project's one angular-emissivity interpolation (linear, held beyond the ends).
    emissivity: EmissivityTable,
    specular_fraction: f64,
}

/// What the tracer keeps per facet, attached to the facet's record in the geometry so a hit
/// reads it with the plane, in one cache line.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FacetRadiometry {
    /// Index into the tracer's material list (not the material id).
    material: u16,
    temperature_k: f64,
    /// L_T, W m⁻² sr⁻¹.
    blackbody: f64,
}

/// A scene ready to trace: the BVH, per-facet radiometry (L_T precomputed), the terrain,
/// the band and the atmosphere. Build it once and render as many views as needed.
#[derive(Debug)]
pub struct Tracer<R, A> {
    geometry: Geometry<FacetRadiometry>,
    materials: Vec<MaterialData>,
    terrain: Terrain,
    /// The terrain's L_T, W m⁻² sr⁻¹.
    terrain_blackbody: f64,
    terrain_leaving: f64,
    band: R,
    atmosphere: A,
    path_terms: PathTermsMode,
}

/// Per-ray state shared by the events.
struct Ctx<'a> {
    options: &'a TraceOptions,
    rng: Option<ChaCha8Rng>,
    /// The pixel's index in the image, from which its random stream is seeded.
    pixel_index: u64,
}

impl Ctx<'_> {
    /// The pixel's random stream, seeded on first use (most pixels never draw).
    fn rng(&mut self) -> &mut ChaCha8Rng {
        let seed = splitmix64(self.options.seed ^ splitmix64(self.pixel_index));
        self.rng
            .get_or_insert_with(|| ChaCha8Rng::seed_from_u64(seed))
    }
}

/// What every ray of one frame shares, computed once per frame rather than per ray.
struct FrameConsts<'a> {
    camera: &'a Camera,
    /// Image-plane u of each column's centre.
    us: Vec<f64>,
    /// Image-plane v of each row's centre.
    vs: Vec<f64>,
    /// The sensor in local coordinates.
    origin: V3,
    /// The sensor's altitude, metres (clamped at the ground).
    sensor_alt: f64,
    /// Cosine of the Earth's limb's angle from nadir seen from the sensor: rays with a
    /// larger cosine of their nadir angle meet the ground.
    cos_critical_nadir: f64,
    /// The primary hits' path terms, when [`PathTermsMode::Tabulated`].
    path_table: Option<PathTable>,
}

fn splitmix64(mut x: u64) -> u64 {
    x = x.wrapping_add(0x9E37_79B9_7F4A_7C15);
    x = (x ^ (x >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    x = (x ^ (x >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    x ^ (x >> 31)
}

impl<R: BandModel, A: Atmosphere> Tracer<R, A> {
    /// Validates the scene and materials, builds the BVH and precomputes each facet's L_T.
    ///
    /// # Errors
    /// The raw scene or material library is invalid, or a facet names an unknown material.
    pub fn new(
        scene: &RawScene,
        materials: &MaterialLibrary,
        band: R,
        atmosphere: A,
    ) -> Result<Self, TraceError> {
        scene
            .validate()
            .map_err(|e| TraceError::new(TraceErrorKind::InvalidScene(e)))?;
        materials
            .validate()
            .map_err(|e| TraceError::new(TraceErrorKind::InvalidMaterials(e)))?;
        let mut slot_of = vec![u16::MAX; usize::from(u16::MAX) + 1];
        let mut mats = Vec::with_capacity(materials.materials.len());
        for (slot, m) in materials.materials.iter().enumerate() {
            slot_of[usize::from(m.id.0)] = slot as u16;
            let (angle_deg, emissivity) = m.emissivity.iter().copied().unzip();
            let emissivity = EmissivityTable::new(angle_deg, emissivity).map_err(|e| {
                TraceError::new(TraceErrorKind::InvalidEmissivity {
                    material: m.id.0,
                    reason: e.to_string(),
                })
            })?;
            mats.push(MaterialData {
                id: m.id.0,
                emissivity,
                specular_fraction: m.specular_fraction,
            });
        }
        let mut facets = Vec::with_capacity(scene.facets.len());
        let mut triangles = Vec::with_capacity(scene.facets.len());
        for (i, f) in scene.facets.iter().enumerate() {
            let slot = slot_of[usize::from(f.material.0)];
            if slot == u16::MAX {
                return Err(TraceError::new(TraceErrorKind::UnknownMaterial {
                    facet: i,
                    material: f.material.0,
                }));
            }
            facets.push(FacetRadiometry {
                material: slot,
                temperature_k: f.temperature_k,
                blackbody: band.radiance(f.temperature_k),
            });
            // Indices were checked by validate().
            triangles.push(f.vertices.map(|v| scene.positions_m[v as usize]));
        }
        let terrain = scene.terrain;
        let terrain_blackbody = band.radiance(terrain.temperature_k);
        let terrain_leaving = terrain.emissivity * terrain_blackbody
            + (1.0 - terrain.emissivity) * atmosphere.sky_hemispheric(0.0);
        Ok(Self {
            geometry: Geometry::with_data(&triangles, &facets),
            materials: mats,
            terrain,
            terrain_blackbody,
            terrain_leaving,
            band,
            atmosphere,
            path_terms: PathTermsMode::Exact,
        })
    }

    /// The geometry (BVH and re-centring).
    #[must_use]
    pub fn geometry(&self) -> &Geometry<FacetRadiometry> {
        &self.geometry
    }

    /// The band.
    #[must_use]
    pub fn band(&self) -> &R {
        &self.band
    }

    fn frame_consts<'a>(&self, camera: &'a Camera) -> FrameConsts<'a> {
        let [w, h] = camera.pixels;
        let sensor_alt = camera.position_m[2].max(0.0);
        FrameConsts {
            camera,
            us: (0..w).map(|c| camera.u_at(f64::from(c) + 0.5)).collect(),
            vs: (0..h).map(|r| camera.v_at(f64::from(r) + 0.5)).collect(),
            origin: self.geometry.to_local(camera.position_m),
            sensor_alt,
            cos_critical_nadir: self
                .atmosphere
                .critical_nadir_angle_deg(sensor_alt)
                .to_radians()
                .cos(),
            path_table: (self.path_terms == PathTermsMode::Tabulated).then(|| {
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
                PathTable::new(
                    &self.atmosphere,
                    sensor_alt,
                    [lo[2].max(0.0), hi[2].max(0.0)],
                    [near, far],
                )
            }),
        }
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

    /// Apparent (blackbody) temperature of a radiance, K.
    #[must_use]
    pub fn apparent_temperature_k(&self, radiance_w_m2_sr: f64) -> f64 {
        self.band.temperature(radiance_w_m2_sr)
    }

    /// Renders every pixel of `camera`'s image, rows in parallel (rayon). `progress` is
    /// called with 1 after each row. The result does not depend on the thread count.
    ///
    /// # Errors
    /// The options are out of range.
    pub fn render(
        &self,
        camera: &Camera,
        options: &TraceOptions,
        progress: &(dyn Fn(u64) + Sync),
    ) -> Result<Frame, TraceError> {
        options.validate()?;
        let [w, h] = camera.pixels;
        let n = w as usize * h as usize;
        let fc = self.frame_consts(camera);
        // Rows write straight into the frame: no per-row vectors to gather and copy.
        let row_len = w.max(1) as usize;
        let mut radiance = vec![0.0; n];
        let mut truth = Vec::new();
        if options.truth {
            truth = vec![TruthPixel::from(&Sample::miss(Event::Sky)); n];
            radiance
                .par_chunks_mut(row_len)
                .zip(truth.par_chunks_mut(row_len))
                .enumerate()
                .for_each(|(row, (rad, tru))| {
                    let mut centre = Sample::miss(Event::Sky);
                    for (col, (l_out, t_out)) in rad.iter_mut().zip(tru.iter_mut()).enumerate() {
                        *l_out =
                            self.pixel::<true>(&fc, options, col as u32, row as u32, &mut centre);
                        *t_out = TruthPixel::from(&centre);
                    }
                    progress(1);
                });
        } else {
            radiance
                .par_chunks_mut(row_len)
                .enumerate()
                .for_each(|(row, rad)| {
                    let mut scratch = Sample::miss(Event::Sky);
                    for (col, l_out) in rad.iter_mut().enumerate() {
                        *l_out =
                            self.pixel::<false>(&fc, options, col as u32, row as u32, &mut scratch);
                    }
                    progress(1);
                });
        }
        Ok(Frame {
            width: w,
            height: h,
            radiance_w_m2_sr: radiance,
            truth,
        })
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
        self.pixel::<true>(&self.frame_consts(camera), options, column, row, &mut s);
        Ok(s)
    }

    /// Radiance of a pixel (mean over its sub-pixel rays). With `TRUTH`, the centre ray's
    /// terms go to `centre` (written in place: a sample is 144 bytes, and moving it
    /// through every call level showed as memory copies in the profile); without, `centre`
    /// is not touched.
    fn pixel<const TRUTH: bool>(
        &self,
        fc: &FrameConsts<'_>,
        options: &TraceOptions,
        col: u32,
        row: u32,
        centre: &mut Sample,
    ) -> f64 {
        let camera = fc.camera;
        let mut ctx = Ctx {
            options,
            rng: None,
            pixel_index: u64::from(row) * u64::from(camera.pixels[0]) + u64::from(col),
        };
        // Bit for bit `camera.pixel_direction(col, row)`, without its divisions.
        let dir = camera.direction_uv(fc.us[col as usize], fc.vs[row as usize]);
        let centre_radiance = self.shade::<TRUTH>(fc, dir, &mut ctx, centre);
        let n = options.supersampling;
        if n <= 1 {
            return centre_radiance;
        }
        let mut sum = 0.0;
        for j in 0..n {
            for i in 0..n {
                let (jx, jy): (f64, f64) = {
                    let rng = ctx.rng();
                    (rng.random(), rng.random())
                };
                let x = f64::from(col) + (f64::from(i) + jx) / f64::from(n);
                let y = f64::from(row) + (f64::from(j) + jy) / f64::from(n);
                // Only the centre ray's terms are kept: the sub-pixel rays compute radiance.
                sum += self.shade::<false>(fc, camera.direction_at(x, y), &mut ctx, centre);
            }
        }
        sum / f64::from(n * n)
    }

    /// The full radiance equation along one primary ray: the radiance at the sensor. With
    /// `TRUTH`, every term also goes to `s` (the incidence angle as its cosine: the angle
    /// is derived where it is shown, [`Sample::incidence_deg`] or a truth layer); without, `s` is not
    /// touched. Both give the same radiance, bit for bit.
    fn shade<const TRUTH: bool>(
        &self,
        fc: &FrameConsts<'_>,
        dir: V3,
        ctx: &mut Ctx<'_>,
        s: &mut Sample,
    ) -> f64 {
        let Some(hit) = self
            .geometry
            .closest_hit(fc.origin, dir, 0.0, f64::INFINITY, None)
        else {
            return self.miss::<TRUTH>(fc, dir, s);
        };
        let hit_alt = self.geometry.to_world(hit.point_local)[2].max(0.0);
        let leaving = self.surface::<TRUTH>(&hit, dir, hit_alt, 0, ctx, s);
        let path = match &fc.path_table {
            Some(table) => table.path(hit_alt, hit.distance_m),
            None => self.atmosphere.path(fc.sensor_alt, hit_alt, hit.distance_m),
        };
        let radiance = path.transmission * leaving + path.path_radiance_w_m2_sr;
        if TRUTH {
            s.range_m = hit.distance_m;
            s.transmission = path.transmission;
            s.path_radiance_w_m2_sr = path.path_radiance_w_m2_sr;
            s.radiance_w_m2_sr = radiance;
        }
        radiance
    }

    /// Event 1: the ray leaves the scene from the sensor. The ground test compares
    /// cosines, so a miss costs no arc cosine unless it sees the sky.
    fn miss<const TRUTH: bool>(&self, fc: &FrameConsts<'_>, dir: V3, s: &mut Sample) -> f64 {
        let alt = fc.sensor_alt;
        let cos_nadir = (-dir[2]).clamp(-1.0, 1.0);
        if cos_nadir > fc.cos_critical_nadir {
            let range = range_to_ground_from_cos_m(alt, cos_nadir).unwrap_or(0.0);
            let path = self.atmosphere.path(alt, 0.0, range);
            let radiance = path.transmission * self.terrain_leaving + path.path_radiance_w_m2_sr;
            if TRUTH {
                *s = Sample::miss(Event::Terrain);
                s.range_m = range;
                s.temperature_k = self.terrain.temperature_k;
                s.emissivity = self.terrain.emissivity;
                s.reflectance = 1.0 - self.terrain.emissivity;
                s.blackbody_w_m2_sr = self.terrain_blackbody;
                s.surface_leaving_w_m2_sr = self.terrain_leaving;
                s.transmission = path.transmission;
                s.path_radiance_w_m2_sr = path.path_radiance_w_m2_sr;
                s.radiance_w_m2_sr = radiance;
            }
            radiance
        } else {
            let zenith_deg = dir[2].clamp(-1.0, 1.0).acos().to_degrees();
            let radiance = self.atmosphere.sky_radiance(alt, zenith_deg);
            if TRUTH {
                *s = Sample::miss(Event::Sky);
                s.transmission = 0.0;
                s.path_radiance_w_m2_sr = radiance;
                s.radiance_w_m2_sr = radiance;
            }
            radiance
        }
    }

    /// Radiance arriving at a surface point at altitude `alt` along `dir` from outside the
    /// scene: the sky above the horizon, the terrain below it.
    fn escaped(&self, dir: V3, alt: f64) -> f64 {
        let nadir = (-dir[2]).clamp(-1.0, 1.0).acos().to_degrees();
        if nadir < self.atmosphere.critical_nadir_angle_deg(alt) {
            self.terrain_leaving
        } else {
            self.atmosphere.sky_radiance(alt, 180.0 - nadir)
        }
    }

    /// Surface-leaving radiance of a hit at altitude `alt` (events 2–4), `depth` specular
    /// bounces already spent; with `TRUTH`, every term into `s`.
    fn surface<const TRUTH: bool>(
        &self,
        hit: &Hit<FacetRadiometry>,
        dir: V3,
        alt: f64,
        depth: u32,
        ctx: &mut Ctx<'_>,
        s: &mut Sample,
    ) -> f64 {
        let fd = hit.data;
        let m = &self.materials[usize::from(fd.material)];
        let eps = m.emissivity.at_cos(hit.cos_incidence);
        let r = 1.0 - eps;
        let sfrac = m.specular_fraction;
        let sky_hemi = self.atmosphere.sky_hemispheric(alt);
        if TRUTH {
            *s = Sample::miss(Event::Diffuse);
            s.primary_material = m.id;
            s.facet = Some(hit.facet);
            s.back_face = hit.back_face;
            s.cos_incidence = hit.cos_incidence;
            s.temperature_k = fd.temperature_k;
            s.emissivity = eps;
            s.reflectance = r;
            s.specular_fraction = sfrac;
            s.blackbody_w_m2_sr = fd.blackbody;
            s.sky_hemispheric_w_m2_sr = sky_hemi;
        }
        let mut spec = 0.0;
        if sfrac > 0.0 {
            // Mirror direction about the normal facing the ray.
            let refl = sub(dir, scale(hit.normal, 2.0 * dot(dir, hit.normal)));
            if TRUTH {
                s.reflected_zenith_deg = refl[2].clamp(-1.0, 1.0).acos().to_degrees();
            }
            let event;
            (spec, event) = if depth < ctx.options.specular_bounces {
                let eps_m = self.geometry.surface_epsilon_m();
                match self.geometry.closest_hit(
                    hit.point_local,
                    refl,
                    eps_m,
                    f64::INFINITY,
                    Some(hit.facet),
                ) {
                    Some(h2) => {
                        if TRUTH {
                            s.secondary_material = self.materials[usize::from(h2.data.material)].id;
                        }
                        let alt2 = self.geometry.to_world(h2.point_local)[2].max(0.0);
                        // L_b: the second facet's surface-leaving radiance (its own terms
                        // are not kept).
                        let l_b = self.surface::<false>(&h2, refl, alt2, depth + 1, ctx, s);
                        (l_b, Event::SpecularHitsFacet)
                    }
                    None => (self.escaped(refl, alt), Event::SpecularEscapes),
                }
            } else {
                // No bounce left: the mirror reflects the hemispheric sky.
                (sky_hemi, Event::SpecularEscapes)
            };
            if TRUTH {
                s.event = event;
                s.specular_incident_w_m2_sr = spec;
            }
        }
        let mut diffuse = 0.0;
        if sfrac < 1.0 {
            let (l, f) = if depth == 0 && ctx.options.sky_view_rays > 0 {
                self.hemisphere(hit, alt, ctx)
            } else {
                (sky_hemi, 1.0)
            };
            diffuse = l;
            if TRUTH {
                s.sky_view_factor = f;
                s.diffuse_incident_w_m2_sr = l;
            }
        }
        let leaving = eps * fd.blackbody + r * (sfrac * spec + (1.0 - sfrac) * diffuse);
        if TRUTH {
            s.surface_leaving_w_m2_sr = leaving;
        }
        leaving
    }

    /// Diffuse incident radiance over the hemisphere above a hit by N cosine-weighted,
    /// stratified rays, and the sky-view factor F (the cosine-weighted fraction of rays that
    /// reach the sky). A blocked ray brings the surface-leaving radiance of the facet it
    /// hits, `ε₂·L_T2 + r₂·L_d` (no further rays); an unblocked one the sky at its zenith
    /// angle, or the terrain below the horizon.
    fn hemisphere(&self, hit: &Hit<FacetRadiometry>, alt: f64, ctx: &mut Ctx<'_>) -> (f64, f64) {
        let n = ctx.options.sky_view_rays;
        let m = (f64::from(n).sqrt()) as u32;
        let (t, b) = basis(hit.normal);
        let eps_m = self.geometry.surface_epsilon_m();
        let (mut sum, mut sky) = (0.0, 0u32);
        for k in 0..n {
            let (xi1, xi2): (f64, f64) = {
                let rng = ctx.rng();
                (rng.random(), rng.random())
            };
            // An m × m grid of strata, then any remainder unstratified.
            let (u1, u2) = if k < m * m {
                (
                    (f64::from(k % m) + xi1) / f64::from(m),
                    (f64::from(k / m) + xi2) / f64::from(m),
                )
            } else {
                (xi1, xi2)
            };
            // Malley's method: uniform on the disc, projected up.
            let rad = u1.sqrt();
            let phi = std::f64::consts::TAU * u2;
            let z = (1.0 - u1).max(0.0).sqrt();
            let d = add(
                add(scale(t, rad * phi.cos()), scale(b, rad * phi.sin())),
                scale(hit.normal, z),
            );
            match self.geometry.closest_hit(
                hit.point_local,
                d,
                eps_m,
                f64::INFINITY,
                Some(hit.facet),
            ) {
                Some(h2) => {
                    let fd = h2.data;
                    let m2 = &self.materials[usize::from(fd.material)];
                    let e2 = m2.emissivity.at_cos(h2.cos_incidence);
                    let alt2 = self.geometry.to_world(h2.point_local)[2].max(0.0);
                    sum += e2 * fd.blackbody + (1.0 - e2) * self.atmosphere.sky_hemispheric(alt2);
                }
                None => {
                    if d[2] >= 0.0 {
                        sky += 1;
                    }
                    sum += self.escaped(d, alt);
                }
            }
        }
        (sum / f64::from(n), f64::from(sky) / f64::from(n))
    }
}
