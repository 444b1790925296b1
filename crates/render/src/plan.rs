//! A run of frames: its inputs read and checked ([`Plan`]), the atmosphere resolved for the
//! band (a vacuum, band tables, or spectra collapsed over the band or each sub-band), the
//! tracer built once, each frame's settings (as asked, from a decision, or chosen by the
//! tolerance pilot), and each frame traced and turned into its files, which go to the
//! caller's [`Sink`].

use std::collections::HashMap;
use std::str::FromStr;
use std::sync::{Arc, Mutex};

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
use irsig_tracer::pilot::{BandChoice, PilotSpace, SunOffer, Supersample};
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
mod frames;

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

/// A run: its request and inputs, read and checked as they come.
#[derive(Debug)]
pub struct Plan {
    request: Request,
    run: RunHash,
    /// Taken by the rendering, which drops it once the tracer is built unless the error
    /// budget reads it (its facets' temperatures and emissivities).
    scene: Mutex<Option<RawScene>>,
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
    warnings: Mutex<Vec<String>>,
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
    /// A plan of `request`, checked: a vacuum's sky radiance finite and not negative, a
    /// tolerance above 0 K at a percentile in (0, 100], a sun above the horizon (with a
    /// tolerance, the pilot decides the sun's models too).
    ///
    /// # Errors
    /// A request error naming the setting.
    pub fn new(request: Request) -> Result<Self, RenderError> {
        if let AtmosphereRequest::Vacuum {
            sky_radiance_w_m2_sr: sky,
        } = request.atmosphere
            && (!sky.is_finite() || sky < 0.0)
        {
            return Err(RequestError::with_value(
                Setting::SkyRadiance,
                sky,
                "out of range: expected a finite radiance of 0 or more",
            )
            .into());
        }
        if let Some(t) = &request.tolerance {
            irsig_model::decision::check_tolerance(t.tolerance_k, "tolerance")
                .map_err(|e| RequestError::new(Setting::Tolerance, e.kind.to_string()))?;
            irsig_model::decision::check_percentile(t.percentile, "percentile")
                .map_err(|e| RequestError::new(Setting::TolerancePercentile, e.kind.to_string()))?;
        }
        let sun = match &request.sun {
            None => None,
            Some(s) => Some(s.position()?),
        };
        let warnings = Vec::new();
        let mut inputs = Vec::new();
        match &request.atmosphere {
            AtmosphereRequest::File { bytes, .. } => inputs.push(InputRecord {
                stage: "trace".into(),
                role: "atmosphere".into(),
                sha256: sha256_hex(bytes),
            }),
            AtmosphereRequest::Builtin(name) => {
                let data = air::builtin_bytes(name, air::band_range_um(&request.band));
                inputs.push(InputRecord {
                    stage: "trace".into(),
                    role: "atmosphere (a built-in's spectra)".into(),
                    sha256: sha256_hex(data),
                });
            }
            AtmosphereRequest::Vacuum { .. } => {}
        }
        Ok(Self {
            request,
            run: RunHash::default(),
            scene: Mutex::new(None),
            scene_name: String::new(),
            materials: MaterialLibrary::default(),
            materials_name: String::new(),
            maps: Vec::new(),
            views: Vec::new(),
            uncertainties: None,
            decision: None,
            decision_file: None,
            sun,
            inputs,
            warnings: Mutex::new(warnings),
        })
    }

    /// Reads the raw scene (canonical RON or binary) from `bytes` of the file `name`. The
    /// first input read: the run hash starts with it.
    ///
    /// # Errors
    /// A malformed scene, at its place in the file.
    pub fn read_scene(&mut self, name: &str, bytes: &[u8]) -> Result<(), RenderError> {
        self.run.field("scene", bytes);
        self.record_input("scene", bytes);
        let scene = irsig_formats::canonical::read_raw_scene(name, bytes)
            .map_err(|e| RenderError::input(format!("reading the scene `{name}`"), e))?;
        *self.scene.get_mut().map_err(|_| poisoned())? = Some(scene);
        name.clone_into(&mut self.scene_name);
        Ok(())
    }

    /// Reads the material library after the scene: spectral materials' band tables become
    /// their curves averaged over the band (the curves stay, for the sub-bands), and every
    /// facet's material must be in it.
    ///
    /// # Errors
    /// A malformed library, a spectral curve short of the band (at its wavelengths), a
    /// facet whose material the library lacks (at the facet in the scene file, `scene` its
    /// bytes), spectral materials with the whole spectrum as band.
    pub fn read_materials(
        &mut self,
        name: &str,
        bytes: &[u8],
        scene_bytes: &[u8],
    ) -> Result<(), RenderError> {
        let lib: MaterialLibrary = from_ron_bytes(name, bytes)
            .map_err(|e| RenderError::input(format!("reading the materials `{name}`"), e))?;
        self.record_input("materials", bytes);
        check_material_bands(
            &lib,
            &self.request.band.band,
            name,
            bytes,
            self.request.spelling,
        )?;
        let lib = match &self.request.band.band {
            _ if lib.materials.iter().all(|m| m.spectral.is_none()) => lib,
            AnyBand::Band(band) => {
                crate::materials::band_library(&lib, band, name, &String::from_utf8_lossy(bytes))?
            }
            AnyBand::Total(_) => {
                return Err(RequestError::with_value(
                    Setting::Band,
                    "total",
                    format!(
                        "`{name}` has spectral materials, which the whole spectrum cannot \
                         average: give a band of wavelengths"
                    ),
                )
                .into());
            }
        };
        let guard = self.scene.get_mut().map_err(|_| poisoned())?;
        let scene = guard
            .as_ref()
            .ok_or_else(|| RenderError::internal("the scene is read before the materials"))?;
        // A terrain or a facet whose material the library lacks, at its place in the scene
        // file.
        let unknown = |path: &str, message: String| {
            RenderError::input(
                format!("the scene's materials in `{name}`"),
                raw_scene_error_at_path(&self.scene_name, scene_bytes, scene, path, message),
            )
        };
        if let Some(m) = scene.terrain.material
            && lib.by_id(m).is_none()
        {
            return Err(unknown(
                "terrain.material",
                format!(
                    "the terrain's material is {}, which the material library {name} does not \
                     define",
                    m.0
                ),
            ));
        }
        if let Some((i, f)) = scene
            .facets
            .iter()
            .enumerate()
            .find(|(_, f)| lib.by_id(f.material).is_none())
        {
            return Err(unknown(
                &format!("facets[{i}].material"),
                format!(
                    "facets[{i}] uses material {}, which the material library {name} does not \
                     define",
                    f.material.0
                ),
            ));
        }
        self.run.field("materials", format!("{lib:?}").as_bytes());
        let (maps, images) = crate::maps::read_maps(&lib, name)?;
        for bytes in &images {
            self.record_input("map image", bytes);
            self.run.field("map image", bytes);
        }
        self.maps = maps;
        self.materials = lib;
        name.clone_into(&mut self.materials_name);
        Ok(())
    }

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

    /// Records an input the run read that the plan does not read itself (a view file, an
    /// execute file): its role and its bytes' SHA-256, for the images' provenance.
    pub fn record_input(&mut self, role: &str, bytes: &[u8]) {
        self.inputs.push(InputRecord {
            stage: "trace".into(),
            role: role.into(),
            sha256: sha256_hex(bytes),
        });
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

    /// Adds frames, one per view, in order; a camera below the ground is warned about.
    pub fn add_views(&mut self, views: impl IntoIterator<Item = View>) {
        let first = self.views.len();
        self.views.extend(views);
        if let Some(w) = crate::observer::below_ground(&self.views[first..], first) {
            self.warn(w);
        }
    }

    /// The views, one per frame.
    #[must_use]
    pub fn views(&self) -> &[View] {
        &self.views
    }

    /// Reads the declared uncertainties (canonical RON) after the scene and the materials:
    /// an object the scene does not have, or an emissivity ± that would leave [0, 1], is an
    /// error at its line and column.
    ///
    /// # Errors
    /// As said, or a malformed file.
    pub fn read_uncertainties(&mut self, name: &str, bytes: &[u8]) -> Result<(), RenderError> {
        let context = || format!("reading the uncertainties `{name}`");
        let text = irsig_formats::canonical::utf8(name, bytes)
            .map_err(|e| RenderError::input(context(), e))?;
        let u: Uncertainties =
            from_ron_bytes(name, bytes).map_err(|e| RenderError::input(context(), e))?;
        self.record_input("uncertainties", bytes);
        let guard = self.scene.get_mut().map_err(|_| poisoned())?;
        let objects = &guard
            .as_ref()
            .ok_or_else(|| RenderError::internal("the scene is read before the uncertainties"))?
            .objects;
        // An object the raw scene does not have (a misspelt name) would select no facet and
        // silently declare nothing.
        for (i, t) in u.temperature.iter().enumerate() {
            if let Facets::Object(object) = &t.facets
                && !objects.iter().any(|o| o == object)
            {
                return Err(RenderError::input(
                    context(),
                    error_at_path(
                        name,
                        text,
                        &format!("temperature[{i}].facets"),
                        format!(
                            "invalid uncertainties file: `temperature[{i}].facets`: the raw scene \
                         has no object `{object}`; its objects include {}",
                            // A few, not a million names.
                            objects
                                .iter()
                                .take(8)
                                .map(|o| format!("`{o}`"))
                                .collect::<Vec<_>>()
                                .join(", ")
                        ),
                    ),
                ));
            }
        }
        let materials = &self.materials;
        u.check_emissivity(|id| {
            let m = materials.materials.iter().find(|m| m.id == id)?;
            let normal = m.emissivity.first().map(|r| r.1)?;
            let most = m.emissivity.iter().map(|r| r.1).fold(0.0, f64::max);
            Some((normal, most))
        })
        .map_err(|e| {
            RenderError::input(
                context(),
                error_at_path(
                    name,
                    text,
                    &e.path,
                    format!("invalid uncertainties file: `{}`: {}", e.path, e.kind),
                ),
            )
        })?;
        // The budget's layers are pixels of the truth EXR: tiles of other uncertainties
        // differ.
        self.run.field("uncertainties", format!("{u:?}").as_bytes());
        self.uncertainties = Some(u);
        Ok(())
    }

    /// Reads a decision an earlier run wrote, to apply to every frame: each choice is
    /// checked here, where the file's text can point at it.
    ///
    /// # Errors
    /// A malformed decision, or a choice that is not a setting of its model (at the
    /// choice).
    pub fn read_decision(&mut self, name: &str, bytes: &[u8]) -> Result<(), RenderError> {
        // Not an input of the record: its choices are the frame's settings, which a frame
        // piloted anew and a tile given its decision share, and so do their images.
        let context = || format!("reading the decision `{name}`");
        let d: Decision =
            from_ron_bytes(name, bytes).map_err(|e| RenderError::input(context(), e))?;
        if let Err((i, message)) = Settings::of(&self.request.settings).with_decision(&d) {
            return Err(RenderError::input(
                context(),
                error_at_path(
                    name,
                    &String::from_utf8_lossy(bytes),
                    &format!("choices[{i}].setting"),
                    message,
                ),
            ));
        }
        self.decision = Some(d);
        self.decision_file = Some((name.to_owned(), String::from_utf8_lossy(bytes).into_owned()));
        Ok(())
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

    /// Takes the warnings gathered so far to `sink`.
    fn flush_warnings(&self, sink: &mut dyn Sink) {
        let taken = std::mem::take(
            &mut *self
                .warnings
                .lock()
                .unwrap_or_else(std::sync::PoisonError::into_inner),
        );
        for w in taken {
            sink.warning(&w);
        }
    }

    fn warn(&self, text: String) {
        self.warnings
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
            .push(text);
    }

    /// The band's model, then the atmosphere over it.
    fn dispatch(self, job: &mut Job<'_>) -> Result<(), RenderError> {
        match self.request.band.band.clone() {
            AnyBand::Total(_) => {
                let mut run = self.run.clone();
                run.field("band", format!("{TotalRadiance:?}").as_bytes());
                self.with_atmosphere(run, TotalRadiance, None, job)
            }
            AnyBand::Band(band) => {
                let mut run = self.run.clone();
                run.field("band", format!("{band:?}").as_bytes());
                let split = Split::of(&band);
                self.with_atmosphere(run, band.clone(), Some(&split), job)
            }
        }
    }
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

/// `sha256:` and the 64 hex digits of `bytes`.
fn sha256_hex(bytes: &[u8]) -> String {
    use sha2::Digest as _;
    let mut hex = String::from("sha256:");
    for b in sha2::Sha256::digest(bytes) {
        hex.push_str(&format!("{b:02x}"));
    }
    hex
}

fn poisoned() -> RenderError {
    RenderError::internal("a lock of the run was poisoned by a panic")
}

/// The camera of view `index`.
fn camera(index: usize, view: &View) -> Result<Camera, RenderError> {
    Camera::from_view(view)
        .map_err(|e| RenderError::trace(format!("the camera of view {}", index + 1), e))
}

/// Refuses a material whose angular table is one band's (`band_um`) and that has no
/// spectral curve, when the trace's band is not within that band: its 8–14 µm values are
/// not its 3–5 µm ones, and using them there would be silently wrong. The error points at
/// the material's `band_um` in `file` and names the band asked for.
///
/// # Errors
/// The first such material.
fn check_material_bands(
    lib: &MaterialLibrary,
    band: &AnyBand,
    file: &str,
    bytes: &[u8],
    spelling: Spelling,
) -> Result<(), RenderError> {
    let band_setting = spelling.of(Setting::Band);
    // A band is within the table's when its edges are, to a part in 1e9 (the band's edges
    // are parsed from the same decimals the library writes).
    let within = |(shortest, longest): (f64, f64), lo: f64, hi: f64| {
        lo >= shortest * (1.0 - 1e-9) && hi <= longest * (1.0 + 1e-9)
    };
    for (i, m) in lib.materials.iter().enumerate() {
        let (Some(table_band), None) = (m.band_um, &m.spectral) else {
            continue;
        };
        let asked = match band {
            AnyBand::Band(b) if within(table_band, b.lambda_min_um(), b.lambda_max_um()) => {
                continue;
            }
            AnyBand::Band(b) => format!(
                "{band_setting} {}-{} um",
                b.lambda_min_um(),
                b.lambda_max_um()
            ),
            AnyBand::Total(_) => format!("{band_setting} total (the whole spectrum)"),
        };
        return Err(RenderError::input(
            format!("the materials `{file}` for the band"),
            error_at_path(
                file,
                &String::from_utf8_lossy(bytes),
                &format!("materials[{i}].band_um"),
                format!(
                    "material `{}`: its emissivity table is for {}-{} um, and the trace asks for \
                 {asked}: give it a `spectral` curve over that band (irsig-material fresnel \
                 with an n, k table, or DIRSIG .ems curves through irsig-material dirsig) rather than \
                 use its {}-{} um values there",
                    m.name, table_band.0, table_band.1, table_band.0, table_band.1
                ),
            ),
        ));
    }
    Ok(())
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
