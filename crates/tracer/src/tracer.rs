//! The radiance equation along each ray: the four events of thesis Figure 6 (§3.3).

use irsig_atmosphere::PathTerms;
use irsig_model::truth::Layer;
use irsig_model::{MaterialLibrary, RawScene, Terrain};
use irsig_radiometry::{BandModel, EmissivityTable, InverseTable};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

use crate::camera::Camera;
use crate::charge::{ChargeSink, Charges, Tally};
use crate::env::Atmosphere;
use crate::error::{TraceError, TraceErrorKind};
use crate::geometry::Geometry;
use crate::path::Path;
use crate::path_table::{PathTable, PathTermsMode};
use crate::refine::{PixelSampling, Refinement};
use crate::sun::{Sun, SunBeam, SunGeometry};
use crate::terrain;
use crate::tile::Tile;
use crate::vec::V3;

mod render;
mod sample;

pub use sample::*;

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
    /// The material's statistical texture, drawn; `None` where it has none (or one that
    /// varies nothing), and its hits are shaded exactly as without the field.
    pub(crate) texture: Option<irsig_texture::TextureFields>,
    /// The material's image maps with their images ([`Tracer::with_sub_bands_and_maps`]).
    pub(crate) maps: Option<irsig_texture::MaterialMaps>,
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
    /// L_T and dL_T/dT over the temperatures textured hits reach
    /// ([`crate::texture`]); `None` when no material's texture varies the temperature.
    pub(crate) textured: Option<crate::texture::BlackbodyTable>,
}

impl<A> BandData<A> {
    /// ε of a recorded hit in this sub-band: the one found when the hit was recorded where
    /// the material's table is the tracer's own, else looked up (bit for bit the same).
    /// A textured hit's ε is the table's scaled by the texel, held to 0 to 1.
    #[inline]
    pub(crate) fn emissivity_of(&self, surface: &crate::path::Surface) -> f64 {
        let slot = usize::from(surface.data.material);
        let eps = if self.own_emissivity[slot] {
            surface.emissivity
        } else {
            self.emissivity[slot].at_cos(surface.cos_incidence)
        };
        match surface.texel {
            None => eps,
            Some(texel) => texel.emissivity(eps),
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

    /// L_T at a hit in this sub-band, W m⁻² sr⁻¹: the facet's, or at a texture's
    /// temperature offset the textured table's.
    #[inline]
    pub(crate) fn blackbody_at(&self, surface: &crate::path::Surface) -> f64 {
        match (surface.texel, &self.textured) {
            (Some(texel), Some(table)) if texel.temperature_offset_k != 0.0 => {
                table
                    .at(surface.data.temperature_k + texel.temperature_offset_k)
                    .0
            }
            _ => self.blackbody_of(&surface.data),
        }
    }

    /// dL_T/dT at a hit in this sub-band, W m⁻² sr⁻¹ K⁻¹ (the error budget's
    /// sensitivity), at its textured temperature where it has one.
    #[inline]
    pub(crate) fn derivative_at(&self, surface: &crate::path::Surface) -> f64 {
        match (surface.texel, &self.textured) {
            (Some(texel), Some(table)) if texel.temperature_offset_k != 0.0 => {
                table
                    .at(surface.data.temperature_k + texel.temperature_offset_k)
                    .1
            }
            _ => self.derivative[surface.data.temperature_index as usize],
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
    /// The terrain's material slot, when it names one ([`crate::terrain`]).
    pub(crate) terrain_slot: Option<u16>,
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
    /// The error budget's input group of each raw-scene facet ([`Tracer::with_budget_groups`]);
    /// `None`: no charges are kept.
    pub(crate) budget_groups: Option<Vec<u32>>,
    /// The temperatures, K, that hits of a material whose texture varies the temperature
    /// can reach (its facets' temperatures, plus and minus the largest offset); `None`
    /// when there is none, and no sub-band tabulates them.
    pub(crate) textured_span_k: Option<[f64; 2]>,
    /// Per raw-scene facet, its texture coordinates at a world point where its material has
    /// image maps ([`crate::texture::UvMap`]); empty when no material has any.
    pub(crate) uv_maps: Vec<Option<crate::texture::UvMap>>,
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
        Self::with_sub_bands_and_maps(scene, materials, band, sub_bands, Vec::new())
    }

    /// [`Tracer::with_sub_bands`] with image maps: `maps` gives, for each material of the
    /// library that has `maps`, its maps with their images read (`irsig-raster` reads
    /// them; the tracer knows no file).
    ///
    /// # Errors
    /// As [`Tracer::with_sub_bands`]; also a facet of a material with maps that has no
    /// texture coordinates, or an emissivity-scale map that takes ε outside 0 to 1.
    pub fn with_sub_bands_and_maps(
        scene: &RawScene,
        materials: &MaterialLibrary,
        band: B,
        sub_bands: Vec<SubBand<B, A>>,
        maps: Vec<(irsig_model::MaterialId, irsig_texture::MaterialMaps)>,
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
            let texture = match &m.texture {
                Some(t) if t.varies() => {
                    Some(irsig_texture::TextureFields::new(t).map_err(|e| {
                        TraceError::new(TraceErrorKind::InvalidOptions(format!(
                            "material {}: {e}",
                            m.id.0
                        )))
                    })?)
                }
                _ => None,
            };
            mats.push(MaterialData {
                id: m.id.0,
                name: m.name.clone(),
                specular_fraction: m.specular_fraction,
                lobe: m
                    .rms_slope
                    .filter(|&sigma| sigma > 0.0 && m.specular_fraction > 0.0)
                    .map(crate::lobe::Lobe::new),
                texture,
                maps: None,
            });
        }
        for (id, m) in maps {
            if let Some(slot) = mats.iter().position(|d| d.id == id.0) {
                mats[slot].maps = Some(m);
            }
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
        let terrain_slot = match scene.terrain.material {
            None => None,
            Some(m) if slot_of[usize::from(m.0)] == u16::MAX => {
                return Err(TraceError::new(TraceErrorKind::UnknownTerrainMaterial {
                    material: m.0,
                }));
            }
            Some(m) => Some(slot_of[usize::from(m.0)]),
        };
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
            terrain_slot,
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
            budget_groups: None,
            textured_span_k: None,
            uv_maps: Vec::new(),
        };
        let has_maps: Vec<bool> = tracer.materials.iter().map(|m| m.maps.is_some()).collect();
        let slot = |id: u16| usize::from(slot_of[usize::from(id)]);
        tracer.uv_maps = crate::texture::facet_uv_maps(scene, slot, &has_maps)?;
        tracer.textured_span_k = tracer.textured_span(scene);
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
        let mut bands = std::mem::take(&mut self.bands.bands);
        for (b, beam) in bands.iter_mut().zip(sun.beams) {
            let eps = self.terrain_emissivity(b);
            b.terrain_leaving = terrain::leaving(eps, b, Some((&beam, &geometry)));
            b.terrain_solar = terrain::solar(eps, b, Some((&beam, &geometry)));
            b.sun = Some(beam);
        }
        self.bands.bands = bands;
        self.sun = Some(geometry);
        Ok(self)
    }

    /// Takes the sun away, its terrain term with it.
    fn remove_sun(&mut self) {
        if self.sun.take().is_none() {
            return;
        }
        let mut bands = std::mem::take(&mut self.bands.bands);
        for b in &mut bands {
            let eps = self.terrain_emissivity(b);
            b.sun = None;
            b.terrain_leaving = terrain::leaving(eps, b, None);
            b.terrain_solar = terrain::solar(eps, b, None);
        }
        self.bands.bands = bands;
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
        for (b, beam) in set.bands.iter_mut().zip(beams) {
            let eps = self.terrain_emissivity(b);
            b.terrain_leaving = terrain::leaving(eps, b, Some((&beam, geometry)));
            b.terrain_solar = terrain::solar(eps, b, Some((&beam, geometry)));
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
            crate::texture::check_emissivity_scales(&self.materials, &emissivity, k)?;
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
            let textured = self
                .textured_span_k
                .map(|span| crate::texture::BlackbodyTable::new(&sb.band, span));
            bands.push(BandData {
                textured,
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
            let eps = self.terrain_emissivity(b);
            b.terrain_leaving = terrain::leaving(eps, b, None);
            b.terrain_solar = terrain::solar(eps, b, None);
        }
        Ok(BandSet::new(bands))
    }

    /// The span of temperatures, K, that the hits of materials whose texture varies the
    /// temperature reach: their facets' coldest minus and hottest plus the largest offset
    /// any of them gives. `None`: no such material has a facet.
    fn textured_span(&self, scene: &RawScene) -> Option<[f64; 2]> {
        let offset: Vec<f64> = self
            .materials
            .iter()
            .map(|m| {
                m.texture
                    .as_ref()
                    .map_or(0.0, irsig_texture::TextureFields::max_temperature_offset_k)
                    + m.maps
                        .as_ref()
                        .map_or(0.0, irsig_texture::MaterialMaps::max_temperature_offset_k)
            })
            .collect();
        if offset.iter().all(|&o| o <= 0.0) {
            return None;
        }
        let slot_of: std::collections::HashMap<u16, usize> = self
            .materials
            .iter()
            .enumerate()
            .map(|(slot, m)| (m.id, slot))
            .collect();
        let mut span: Option<[f64; 2]> = None;
        for f in &scene.facets {
            let o = slot_of.get(&f.material.0).map_or(0.0, |&s| offset[s]);
            if o > 0.0 {
                let [lo, hi] = span.get_or_insert([f64::INFINITY, f64::NEG_INFINITY]);
                *lo = lo.min(f.temperature_k - o);
                *hi = hi.max(f.temperature_k + o);
            }
        }
        span
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
