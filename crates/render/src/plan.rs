//! A run of frames: its inputs read and checked ([`Plan`]), the atmosphere resolved for the
//! band (a vacuum, band tables, or spectra collapsed over the band or each sub-band), the
//! tracer built once, each frame's settings (as asked, from a decision, or chosen by the
//! tolerance pilot), and each frame traced and turned into its files, which go to the
//! caller's [`Sink`].

use std::collections::HashMap;
use std::str::FromStr;
use std::sync::Arc;

use irsig_atmosphere::{AtmosphereModel, ModelKind, PrecomputedAtmosphere, SubBandCount};
use irsig_formats::canonical::{error_at_path, from_ron_bytes, raw_scene_error_at_path};
use irsig_model::decision::{Decision, SwitchableModel};
use irsig_model::frame::{FrameFile, FrameFiles};
use irsig_model::provenance::{InputRecord, Provenance};
use irsig_model::uncertainty::{Facets, Uncertainties};
use irsig_model::{MaterialLibrary, RawScene, View};
use irsig_radiometry::{AnyBand, BandModel, TotalRadiance};
use irsig_raster::FramePart;
use irsig_sensor_model::quantise::CountRequest;
use irsig_tracer::pilot::{BandChoice, PilotSpace, SunOffer};
use irsig_tracer::reference::{ConvergedReference, converged_reference};
use irsig_tracer::{Atmosphere, Camera, SubBand, Tile, TraceOptions, Tracer, Vacuum};
use rayon::prelude::*;

use crate::air::{self, AirData, AtmosphereRequest};
use crate::band::{BandRequest, Collapsed, Split, SubBandModel};
use crate::budget::Budget;
use crate::error::{RenderError, RequestError, Setting, Spelling};
use crate::guarantee::Guarantee;
use crate::products::{self, FrameRadiometry};
use crate::run_hash::RunHash;
use crate::settings::{Settings, SettingsRequest};
use crate::sun::{self as sunlight, SunRequest};
use crate::tolerance::{self, Pin};

mod atmosphere;
mod builder;
mod frames;

pub use builder::PlanBuilder;

/// A tolerance to pilot each frame to.
#[derive(Debug, Clone, PartialEq)]
pub struct ToleranceRequest {
    /// The tolerance, K.
    pub tolerance_k: f64,
    /// The percentile of pixels it applies to, (0, 100].
    pub percentile: f64,
    /// Models fixed by hand.
    pub pins: Vec<Pin>,
}

/// What to render, as typed data (a tool turns its flags into this once).
#[derive(Debug, Clone, PartialEq)]
pub struct Request {
    /// The band.
    pub band: BandRequest,
    /// The atmosphere.
    pub atmosphere: AtmosphereRequest,
    /// The models, where not the defaults.
    pub settings: SettingsRequest,
    /// A tolerance the pilot chooses the models for (instead of `settings`).
    pub tolerance: Option<ToleranceRequest>,
    /// A sun lighting the scene (`None`: no sun, a night).
    pub sun: Option<SunRequest>,
    /// How radiance becomes digital counts.
    pub counts: CountRequest,
    /// The settings the user left at their defaults, where a default changes the physics
    /// (the band, the atmosphere): the plan says what it took, through the sink's notes.
    pub defaulted: Vec<Setting>,
    /// How the request's maker spells its settings, for what the plan says about them.
    pub spelling: Spelling,
}

/// A tile of every frame: a rectangle `X,Y,W,H` or tile `I/CxR` of a grid, resolved
/// against each view's image.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TileRequest {
    /// `X,Y,W,H`.
    Rect(Tile),
    /// `I/CxR`: tile `index` (from 1, row by row from the top-left) of `columns × rows`.
    Grid {
        /// The tile, from 1.
        index: u32,
        /// Grid columns.
        columns: u32,
        /// Grid rows.
        rows: u32,
    },
}

impl TileRequest {
    /// The tile of a `width × height` image.
    ///
    /// # Errors
    /// A grid that does not fit the image, or a tile outside it.
    pub fn of(self, width: u32, height: u32) -> Result<Tile, String> {
        let tile = match self {
            Self::Rect(t) => t,
            Self::Grid {
                index,
                columns,
                rows,
            } => Tile::of_grid(index, columns, rows, width, height).map_err(|e| e.to_string())?,
        };
        tile.check(width, height).map_err(|e| e.to_string())?;
        Ok(tile)
    }
}

impl FromStr for TileRequest {
    type Err = String;

    /// `X,Y,W,H` (pixels) or `I/CxR`.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let number = |t: &str, what: &str| {
            t.trim()
                .parse::<u32>()
                .map_err(|_| format!("expected {what} (a whole number), found `{t}` in `{s}`"))
        };
        if let Some((index, grid)) = s.split_once('/') {
            let (columns, rows) = grid
                .split_once(['x', 'X'])
                .ok_or_else(|| format!("expected I/CxR such as 6/4x4, found `{s}`"))?;
            return Ok(Self::Grid {
                index: number(index, "a tile number I")?,
                columns: number(columns, "a number of columns C")?,
                rows: number(rows, "a number of rows R")?,
            });
        }
        let parts: Vec<&str> = s.split(',').collect();
        let [x, y, w, h] = parts[..] else {
            return Err(format!(
                "expected X,Y,W,H (pixels) such as 0,0,256,256, or I/CxR such as 6/4x4; \
                 found `{s}`"
            ));
        };
        Ok(Self::Rect(Tile {
            x: number(x, "a column X")?,
            y: number(y, "a row Y")?,
            width: number(w, "a width W")?,
            height: number(h, "a height H")?,
        }))
    }
}

/// Where a run's frames go.
pub trait Sink {
    /// The files frame `index` makes; none at all: only its decision (with a tolerance).
    fn files(&self, index: usize) -> FrameFiles<()>;
    /// The pilot's decision for frame `index`, and the seconds the pilot took.
    ///
    /// # Errors
    /// The caller's, when it cannot keep the decision.
    fn decision(&mut self, index: usize, decision: &Decision, seconds: f64) -> miette::Result<()>;
    /// One encoded file of frame `index`.
    ///
    /// # Errors
    /// The caller's, when it cannot keep the file.
    fn file(&mut self, index: usize, kind: FrameFile, bytes: Vec<u8>) -> miette::Result<()>;
    /// Something the user should know that is not an error.
    fn warning(&mut self, text: &str);
}

/// What tracing a frame holds per pixel with every truth layer, bytes: the radiance, the
/// truth and sampling records and the encoded layers (README, "Memory per pixel";
/// `tests/tests/memory.rs` holds a tile to it).
pub const FRAME_BYTES_PER_PIXEL: u64 = 150;

/// What a textured frame holds per pixel beyond [`FRAME_BYTES_PER_PIXEL`], bytes: each
/// pixel's texture truth (an 8-byte record of the offset and the scale at the primary hit)
/// and its two f32 layers in the truth EXR.
pub const TEXTURE_BYTES_PER_PIXEL: u64 = 16;

/// What a frame through an atmosphere holds per pixel beyond [`FRAME_BYTES_PER_PIXEL`],
/// bytes: each pixel's atmosphere-data error (an f32 record) and its f32 layer in the truth
/// EXR. Counted for every atmosphere but a vacuum: whether a file's tables record their
/// residual is known only once it is read, and the check must not under-count.
pub const DATA_ERROR_BYTES_PER_PIXEL: u64 = 8;

/// A run: its request and its inputs, read and checked ([`PlanBuilder`]), which probing,
/// converging or rendering it consumes.
#[derive(Debug)]
pub struct Plan {
    request: Request,
    run: RunHash,
    /// Moved into the rendering, which drops it once the tracer is built unless the error
    /// budget reads it (its facets' temperatures and emissivities).
    scene: Option<RawScene>,
    scene_name: String,
    materials: MaterialLibrary,
    materials_name: String,
    /// The materials' image maps, their images read ([`crate::maps`]).
    maps: crate::maps::Maps,
    views: Vec<View>,
    uncertainties: Option<Uncertainties>,
    decision: Option<Decision>,
    /// The decision's file name and text, to point at a choice this run cannot keep.
    decision_file: Option<(String, String)>,
    /// The sun's position, checked, when the request has a sun.
    sun: Option<irsig_atmosphere::sun::SunPosition>,
    /// Every input read, in order: what each image's provenance lists.
    inputs: Vec<InputRecord>,
    /// What reading the inputs warned of, in order: the sink's first warnings.
    warnings: Vec<String>,
}

/// The data error of `atmosphere`'s `table` model (what an atmosphere's `Air::data` is).
fn data_error_of(
    atmosphere: &irsig_model::Atmosphere,
) -> Option<irsig_atmosphere::data_error::DataError> {
    irsig_atmosphere::AtmosphereModel::new(atmosphere, irsig_atmosphere::ModelKind::Table)
        .ok()?
        .data_error()
}

/// Altitude levels of the sky in the pilot's sub-band sets (a rendering's have
/// [`irsig_atmosphere::SKY_LEVELS`]). Interpolating linearly in altitude commutes with
/// summing sub-bands, so coarser levels change every count's sky alike and leave the
/// sub-band error the pilot measures: on the quickstart and the thesis experiment its
/// choices and errors are those of 33 levels (docs/accuracy.md).
const PILOT_SKY_LEVELS: usize = 5;

/// Unit costs of the atmosphere models for the pilot's cost model, ns (BENCHMARKS.md "The
/// tolerance pilot's cost model"): one `path` call by a sensor `sensor_alt_m` above the
/// ground, and precomputing the sky of one sub-band up to a few km. A path's cost grows
/// with the profile levels it crosses (each a piece of the layered walk): it is priced by
/// the built-in levels below the sensor, fitted to the quickstart (5 m, no level) and to
/// `cargo bench -p irsig-atmosphere --bench path` (1 km, seven).
fn atmosphere_costs(kind: ModelKind, sensor_alt_m: f64) -> (f64, f64) {
    let levels = irsig_atmosphere::plan::LEVELS_M
        .iter()
        .filter(|&&z| z <= sensor_alt_m)
        .count() as f64;
    match kind {
        ModelKind::Table => (165.0 + 23.0 * levels, 3e6),
        ModelKind::Layered => (70.0 + 30.0 * levels, 88e6),
        ModelKind::Thesis => (57.0 + 7.5 * levels, 121e6),
        ModelKind::None => (5.0, 0.0),
    }
}

impl Plan {
    /// What the run takes where the request said nothing and the default changes the
    /// physics (`Request::defaulted`), one line each, for the user.
    #[must_use]
    pub fn notes(&self) -> Vec<String> {
        let mut notes = Vec::new();
        for setting in &self.request.defaulted {
            match (setting, &self.request.atmosphere) {
                (Setting::Band, _) => notes.push(format!(
                    "no band given: tracing {} (the thesis's band)",
                    self.request.band.record
                )),
                (
                    Setting::Atmosphere,
                    AtmosphereRequest::Vacuum {
                        sky_radiance_w_m2_sr,
                    },
                ) => notes.push(format!(
                    "no atmosphere given: a vacuum (τ = 1, no path radiance) under a sky of \
                     {sky_radiance_w_m2_sr} W m^-2 sr^-1; name a built-in ({}), a file, or \
                     `none` to say so",
                    irsig_atmosphere::BUILTIN_NAMES.join(", ")
                )),
                _ => {}
            }
        }
        notes
    }

    /// What frame images rendered with `settings` record of their making.
    fn provenance(&self, settings: &Settings) -> Provenance {
        let vacuum = matches!(self.request.atmosphere, AtmosphereRequest::Vacuum { .. });
        Provenance {
            band: self.request.band.record.clone(),
            sub_bands: settings.sub_bands.to_string(),
            atmosphere: match &self.request.atmosphere {
                AtmosphereRequest::File { .. } => "file".to_owned(),
                other => other.name().to_owned(),
            },
            atmosphere_model: if vacuum { "none" } else { settings.kind.name() }.to_owned(),
            inputs: self.inputs.clone(),
            // The sun that lit the image: none where a decision left it out, with the
            // shadow rays a decision chose.
            sun: self
                .sun
                .as_ref()
                .zip(self.request.sun.as_ref())
                .filter(|_| settings.sun_lit)
                .map(|(p, s)| irsig_model::provenance::SunRecord {
                    zenith_deg: p.zenith_deg,
                    azimuth_deg: p.azimuth_deg,
                    shadow_rays: settings.shadow_rays.unwrap_or(s.shadow_rays),
                }),
        }
    }

    /// The views, one per frame.
    #[must_use]
    pub fn views(&self) -> &[View] {
        &self.views
    }

    /// An error about the sub-band count the decision chose (which only the atmosphere's
    /// grid can refuse), said at the decision's choice rather than as a flag the user never
    /// typed; any other error as it is.
    fn at_decision_sub_bands(&self, report: RenderError) -> RenderError {
        let (Some(d), Some((name, text))) = (&self.decision, &self.decision_file) else {
            return report;
        };
        let Some(i) = d
            .choices
            .iter()
            .position(|c| c.model == SwitchableModel::SubBands)
        else {
            return report;
        };
        let Some(e) = report.as_request() else {
            return report;
        };
        if e.setting != Setting::SubBands {
            return report;
        }
        let value = e.value.as_deref().unwrap_or("");
        let message = format!(
            "this decision's `{value}` cannot be kept for this run: {}",
            e.message
        );
        RenderError::input(
            format!("keeping the decision `{name}`"),
            error_at_path(name, text, &format!("choices[{i}].setting"), message),
        )
    }

    /// The largest material id of the library (0 for none): the interaction map holds ids
    /// up to 15.
    #[must_use]
    pub fn max_material_id(&self) -> u32 {
        self.materials
            .materials
            .iter()
            .map(|m| u32::from(m.id.0))
            .max()
            .unwrap_or(0)
    }

    /// Whether every material id fits the interaction map's nibble (1 to 15).
    #[must_use]
    pub fn map_fits(&self) -> bool {
        self.max_material_id() <= u32::from(irsig_formats::legacy::map::MAX_ID)
    }

    /// The files a frame can make: the interaction map only when the ids fit it, and the
    /// map, counts and LUT only of a whole frame (a tile's are the merge's: they need the
    /// whole frame).
    #[must_use]
    pub fn file_kinds(&self, whole: bool) -> Vec<FrameFile> {
        FrameFile::ALL
            .into_iter()
            .filter(|k| match k {
                FrameFile::MapPng => self.map_fits() && whole,
                FrameFile::DcPng | FrameFile::Lut => whole,
                FrameFile::RadianceExr | FrameFile::TruthExr => true,
            })
            .collect()
    }

    /// Every frame's tile: the whole image, or `tile` of it.
    ///
    /// # Errors
    /// A view that is not a camera, or a tile that does not fit a view's image (a request
    /// error).
    pub fn tiles(&self, tile: Option<TileRequest>) -> Result<Vec<Tile>, RenderError> {
        self.views
            .iter()
            .enumerate()
            .map(|(i, v)| {
                let [w, h] = camera(i, v)?.pixels;
                match tile {
                    None => Ok(Tile::whole(w, h)),
                    Some(t) => t
                        .of(w, h)
                        .map_err(|e| RequestError::new(Setting::Tile, e).into()),
                }
            })
            .collect()
    }

    /// The largest frame (or, with `tile`, the largest tile and its one-pixel margin), in
    /// pixels, and what tracing it holds at [`Plan::bytes_per_pixel`], bytes: what a tool
    /// checks against the machine before any pilot runs.
    ///
    /// # Errors
    /// As [`Plan::tiles`].
    pub fn largest_frame(&self, tile: Option<TileRequest>) -> Result<([u64; 2], u64), RenderError> {
        let tiles = self.tiles(tile)?;
        let margin = u64::from(tile.is_some()) * 2;
        let largest = tiles
            .iter()
            .map(|t| [u64::from(t.width) + margin, u64::from(t.height) + margin])
            .max_by_key(|[w, h]| w * h)
            .unwrap_or([0, 0]);
        let bytes = largest[0]
            .saturating_mul(largest[1])
            .saturating_mul(self.bytes_per_pixel());
        Ok((largest, bytes))
    }

    /// What tracing holds per pixel of a frame with every truth layer, bytes:
    /// [`FRAME_BYTES_PER_PIXEL`], [`TEXTURE_BYTES_PER_PIXEL`] more when a material is
    /// textured, and [`DATA_ERROR_BYTES_PER_PIXEL`] more through an atmosphere.
    #[must_use]
    pub fn bytes_per_pixel(&self) -> u64 {
        let textured = self
            .materials
            .materials
            .iter()
            .any(|m| m.texture.is_some() || m.maps.is_some());
        let air = !matches!(self.request.atmosphere, AtmosphereRequest::Vacuum { .. });
        FRAME_BYTES_PER_PIXEL
            + u64::from(textured) * TEXTURE_BYTES_PER_PIXEL
            + u64::from(air) * DATA_ERROR_BYTES_PER_PIXEL
    }

    /// Every term of the radiance equation for pixel `(column, row)` of the first view,
    /// as text.
    ///
    /// # Errors
    /// As [`Plan::render`], or a pixel outside the image.
    pub fn probe(self, column: u32, row: u32) -> Result<String, RenderError> {
        let mut out = None;
        self.dispatch(&mut Job::Probe {
            column,
            row,
            text: &mut out,
        })?;
        out.ok_or_else(|| RenderError::internal("the probe printed nothing"))
    }

    /// Every frame converged by construction, its own error per pixel measured
    /// ([`converged_reference`]): the truth a tolerance is promised against, to check it
    /// on a scene (`irsig-tests`'s `tolerance_rows`). Its atmosphere model, path terms,
    /// sub-bands and sun are the request's settings; its rays a pixel, sky-view rays and 8
    /// bounces are the rounds' own, the first `rounds` of them, each pixel's stopping when
    /// its two halves differ by `stop_k` or less. A tolerance or a decision in the request
    /// is not used.
    ///
    /// # Errors
    /// A stopping difference that is not a finite number above 0 K, or as
    /// [`Plan::render`].
    pub fn converge(
        self,
        stop_k: f64,
        rounds: usize,
    ) -> Result<Vec<ConvergedReference>, RenderError> {
        if !(stop_k.is_finite() && stop_k > 0.0) {
            return Err(RenderError::refused(format!(
                "the reference's stopping difference: expected a finite number of kelvin \
                 above 0, found {stop_k}"
            )));
        }
        let mut out = Vec::new();
        self.dispatch(&mut Job::Converge {
            stop_k,
            rounds,
            out: &mut out,
        })?;
        Ok(out)
    }

    /// Traces every frame (or its `tile`) and gives its files to `sink`; `progress` is
    /// called with the number of rows traced as they are.
    ///
    /// # Errors
    /// An atmosphere or settings the scene cannot be traced with, a failed pilot, or the
    /// sink's own errors.
    pub fn render(
        self,
        tile: Option<TileRequest>,
        progress: &(dyn Fn(u64) + Sync),
        sink: &mut dyn Sink,
    ) -> Result<(), RenderError> {
        self.dispatch(&mut Job::Render {
            tile,
            progress,
            sink,
        })
    }

    /// The rows a rendering traces: the tiles' heights summed over the frames.
    ///
    /// # Errors
    /// As [`Plan::tiles`].
    pub fn rows(&self, tile: Option<TileRequest>) -> Result<u64, RenderError> {
        Ok(self.tiles(tile)?.iter().map(|t| u64::from(t.height)).sum())
    }

    /// The band's model, then the atmosphere over it; the scene and the reading's
    /// warnings move from the plan to the job.
    fn dispatch(mut self, job: &mut Job<'_>) -> Result<(), RenderError> {
        let mut taken = Taken {
            run: self.run.clone(),
            scene: self.scene.take(),
            notes: std::mem::take(&mut self.warnings),
        };
        match self.request.band.band.clone() {
            AnyBand::Total(_) => {
                taken
                    .run
                    .field("band", format!("{TotalRadiance:?}").as_bytes());
                self.with_atmosphere(taken, AnyBand::Total(TotalRadiance), None, job)
            }
            AnyBand::Band(band) => {
                taken.run.field("band", format!("{band:?}").as_bytes());
                let split = Split::of(&band);
                self.with_atmosphere(taken, AnyBand::Band(band.clone()), Some(&split), job)
            }
        }
    }
}

/// What a job takes from the plan on its way to the tracer: the run's hash as fed so far,
/// the raw scene (moved into the tracer's making), and the warnings said so far, in order,
/// which the sink gets before the first frame.
struct Taken {
    run: RunHash,
    scene: Option<RawScene>,
    notes: Vec<String>,
}

/// What a run does once its atmosphere is ready.
enum Job<'a> {
    /// Prints one pixel's terms.
    Probe {
        column: u32,
        row: u32,
        text: &'a mut Option<String>,
    },
    /// Converges every frame's reference ([`Plan::converge`]).
    Converge {
        stop_k: f64,
        rounds: usize,
        out: &'a mut Vec<ConvergedReference>,
    },
    /// Traces every frame.
    Render {
        tile: Option<TileRequest>,
        progress: &'a (dyn Fn(u64) + Sync),
        sink: &'a mut dyn Sink,
    },
}

/// One sub-band, the whole band, for the band model.
fn whole<R: Clone, T>(
    band: &R,
    name: &str,
    count: SubBandCount,
    atmosphere: impl FnOnce() -> Result<T, RenderError>,
) -> Result<Vec<SubBand<R, T>>, RenderError> {
    if !count.is_band() {
        return Err(air::no_spectra(name, count));
    }
    Ok(vec![SubBand {
        band: band.clone(),
        atmosphere: atmosphere()?,
        emissivity: None,
    }])
}

/// The camera of view `index`.
fn camera(index: usize, view: &View) -> Result<Camera, RenderError> {
    Camera::from_view(view)
        .map_err(|e| RenderError::trace(format!("the camera of view {}", index + 1), e))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tiles_are_a_rectangle_or_a_grid_cell() {
        assert_eq!(
            "6/4x4".parse::<TileRequest>(),
            Ok(TileRequest::Grid {
                index: 6,
                columns: 4,
                rows: 4
            })
        );
        let t: TileRequest = "0,0,256,128".parse().unwrap();
        assert_eq!(t.of(512, 384).unwrap().width, 256);
        assert!(t.of(128, 128).is_err());
        assert!("6/4".parse::<TileRequest>().is_err());
        assert!("1,2,3".parse::<TileRequest>().is_err());
        assert!("-1,0,4,4".parse::<TileRequest>().is_err());
    }
}
