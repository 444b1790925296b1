//! The radiance equation along each ray: the four events of thesis Figure 6 (§3.3).

use irsig_model::Terrain;
use irsig_model::truth::Layer;
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
use crate::sun::SunGeometry;
use crate::tile::Tile;
use glam::DVec3;

mod bands;
mod build;
mod render;
mod sample;

pub(crate) use bands::BandData;
pub use bands::{BandSet, SubBand};
pub use sample::*;

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
    /// The slots of the materials its material map mixes, in the map's order; empty
    /// without one ([`crate::mixture`]).
    pub(crate) mix_slots: Vec<u16>,
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
    /// Whether a texture reads a ray's footprint (an image map's or a statistical
    /// texture's `Footprint` filter): only then do rays carry their cells
    /// ([`crate::differential`]); without, every texture reads the point.
    pub(crate) filters_footprint: bool,
    /// Per raw-scene facet, its per-material temperatures as temperature indices in its
    /// material map's order, where the scene gives them ([`crate::mixture`]); empty when
    /// it gives none.
    pub(crate) mix_temperatures: Vec<Option<[u32; irsig_model::material_map::MAX_MAP_MATERIALS]>>,
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
    /// The rays along a side of the pixel the ray being followed shares it with (1: the
    /// ray stands for the whole pixel): each of an `n × n` grid of sub-pixel rays stands
    /// for a cell `1/n` of the pixel across, and its cone is that much narrower, so the
    /// footprint filter averages its own cell and the pixel's mean of them is the pixel's
    /// box, not a box blurred by another pixel-wide filter at every ray.
    pub(crate) subpixel_side: u32,
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
            subpixel_side: 1,
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
        let whole = std::mem::replace(&mut self.subpixel_side, n.max(1));
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
        self.subpixel_side = whole;
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
    pub(crate) origin: DVec3,
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

impl<B: BandModel, A: Atmosphere> Tracer<B, A> {
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
