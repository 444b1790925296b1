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
use miette::{WrapErr, miette};
use rayon::prelude::*;

use crate::air::{self, AirData, AtmosphereRequest};
use crate::band::{BandRequest, Collapsed, Split, SubBandModel};
use crate::budget::Budget;
use crate::error::{RequestError, Setting, Spelling};
use crate::guarantee::Guarantee;
use crate::products::{self, FrameRadiometry};
use crate::run_hash::RunHash;
use crate::settings::{Settings, SettingsRequest};
use crate::sun::{self as sunlight, SunRequest};
use crate::tolerance::{self, Pin};

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
    views: Vec<View>,
    uncertainties: Option<Uncertainties>,
    decision: Option<Decision>,
    /// The sun's position, checked, when the request has a sun.
    sun: Option<irsig_atmosphere::sun::SunPosition>,
    /// Every input read, in order: what each image's provenance lists.
    inputs: Vec<InputRecord>,
    warnings: Mutex<Vec<String>>,
}

/// The atmosphere of the run, for any model kind its tables allow, over the band or over
/// sub-bands of it: for rendering (`A`), and for the pilot's band sets (`S`), which
/// evaluate each kind as a rendering with it would (its sky precomputed: computing the
/// hemispheric sky afresh at every pilot facet cost more than the whole pilot otherwise
/// does, and with K sub-bands K times more).
struct Air<'a, R, A, S> {
    /// The kinds on offer, most accurate first (`None`: a vacuum).
    kinds: Option<Vec<ModelKind>>,
    /// The atmosphere is spectral: sub-band counts other than 1 are on offer.
    spectral: bool,
    precomputed: SubBandsOf<'a, R, A>,
    pilot: SubBandsOf<'a, R, S>,
    /// The atmosphere data's own interpolation error between its rows, K, where its
    /// slant tables record it: the largest of the slant paths' and the sky's (grazing
    /// paths beyond 80° are the horizon classes' own).
    data_error_k: Option<f64>,
    /// The sun over the sub-bands of a count (`None`: no sun asked for).
    sun: SunOf<'a>,
}

/// The sun over the sub-bands of a count.
type SunOf<'a> = Box<dyn Fn(SubBandCount) -> miette::Result<Option<irsig_tracer::Sun>> + 'a>;

/// No sun, for any count.
fn no_sun<'a>() -> SunOf<'a> {
    Box::new(|_| Ok(None))
}

/// The interpolation error a slant table records, K (see [`Air::data_error_k`]).
fn data_error_k(residual: Option<&irsig_model::InterpolationResidual>) -> Option<f64> {
    residual.map(|r| r.slant_k.max(r.sky_k))
}

/// The sub-bands of a model kind and a count.
type SubBandsOf<'a, R, T> =
    Box<dyn Fn(ModelKind, SubBandCount) -> miette::Result<Vec<SubBand<R, T>>> + Sync + 'a>;

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
    pub fn new(request: Request) -> miette::Result<Self> {
        if let AtmosphereRequest::Vacuum {
            sky_radiance_w_m2_sr: sky,
        } = request.atmosphere
            && (!sky.is_finite() || sky < 0.0)
        {
            return Err(RequestError::of_value(
                Setting::SkyRadiance,
                sky,
                "out of range: expected a finite radiance of 0 or more",
            ));
        }
        if let Some(t) = &request.tolerance {
            irsig_model::decision::check_tolerance(t.tolerance_k, "tolerance")
                .map_err(|e| RequestError::report(Setting::Tolerance, e.kind.to_string()))?;
            irsig_model::decision::check_percentile(t.percentile, "percentile").map_err(|e| {
                RequestError::report(Setting::TolerancePercentile, e.kind.to_string())
            })?;
        }
        let sun = match &request.sun {
            None => None,
            Some(s) => Some(s.position()?),
        };
        let mut warnings = Vec::new();
        // With a tolerance the pilot chooses the sub-bands, measuring the sunlight's error
        // against the full grid.
        if let Some(s) = &request.sun
            && request.settings.sub_bands.is_none()
            && request.tolerance.is_none()
        {
            warnings.push(sunlight::one_sub_band_in_sunlight(request.spelling, s));
        }
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
            views: Vec::new(),
            uncertainties: None,
            decision: None,
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
    pub fn read_scene(&mut self, name: &str, bytes: &[u8]) -> miette::Result<()> {
        self.run.field("scene", bytes);
        self.record_input("scene", bytes);
        let scene = irsig_formats::canonical::read_raw_scene(name, bytes)?;
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
    ) -> miette::Result<()> {
        let lib: MaterialLibrary = from_ron_bytes(name, bytes)?;
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
                return Err(RequestError::of_value(
                    Setting::Band,
                    "total",
                    format!(
                        "`{name}` has spectral materials, which the whole spectrum cannot \
                         average: give a band of wavelengths"
                    ),
                ));
            }
        };
        let guard = self.scene.get_mut().map_err(|_| poisoned())?;
        let scene = guard
            .as_ref()
            .ok_or_else(|| miette!("the scene is read before the materials"))?;
        // A facet whose material the library lacks, at its place in the scene file.
        if let Some((i, f)) = scene
            .facets
            .iter()
            .enumerate()
            .find(|(_, f)| lib.by_id(f.material).is_none())
        {
            return Err(miette::Report::new(raw_scene_error_at_path(
                &self.scene_name,
                scene_bytes,
                scene,
                &format!("facets[{i}].material"),
                format!(
                    "facets[{i}] uses material {}, which the material library {name} does not \
                     define",
                    f.material.0
                ),
            )));
        }
        self.run.field("materials", format!("{lib:?}").as_bytes());
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
    pub fn read_uncertainties(&mut self, name: &str, bytes: &[u8]) -> miette::Result<()> {
        let text = irsig_formats::canonical::utf8(name, bytes)?;
        let u: Uncertainties = from_ron_bytes(name, bytes)?;
        self.record_input("uncertainties", bytes);
        let guard = self.scene.get_mut().map_err(|_| poisoned())?;
        let objects = &guard
            .as_ref()
            .ok_or_else(|| miette!("the scene is read before the uncertainties"))?
            .objects;
        // An object the raw scene does not have (a misspelt name) would select no facet and
        // silently declare nothing.
        for (i, t) in u.temperature.iter().enumerate() {
            if let Facets::Object(object) = &t.facets
                && !objects.iter().any(|o| o == object)
            {
                return Err(miette::Report::new(error_at_path(
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
                )));
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
            error_at_path(
                name,
                text,
                &e.path,
                format!("invalid uncertainties file: `{}`: {}", e.path, e.kind),
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
    pub fn read_decision(&mut self, name: &str, bytes: &[u8]) -> miette::Result<()> {
        // Not an input of the record: its choices are the frame's settings, which a frame
        // piloted anew and a tile given its decision share, and so do their images.
        let d: Decision = from_ron_bytes(name, bytes)?;
        if let Err((i, message)) = Settings::of(&self.request.settings).with_decision(&d) {
            return Err(miette::Report::new(error_at_path(
                name,
                &String::from_utf8_lossy(bytes),
                &format!("choices[{i}].setting"),
                message,
            )));
        }
        // The pilot chose these sub-bands, with the sunlight's error measured.
        if let Some(s) = &self.request.sun
            && d.choice(SwitchableModel::SubBands).is_some()
        {
            let warning = sunlight::one_sub_band_in_sunlight(self.request.spelling, s);
            self.warnings
                .lock()
                .map_err(|_| poisoned())?
                .retain(|w| *w != warning);
        }
        self.decision = Some(d);
        Ok(())
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
    pub fn tiles(&self, tile: Option<TileRequest>) -> miette::Result<Vec<Tile>> {
        self.views
            .iter()
            .map(|v| {
                let [w, h] = Camera::from_view(v).map_err(|e| miette!("{e}"))?.pixels;
                match tile {
                    None => Ok(Tile::whole(w, h)),
                    Some(t) => t
                        .of(w, h)
                        .map_err(|e| RequestError::report(Setting::Tile, e)),
                }
            })
            .collect()
    }

    /// Every term of the radiance equation for pixel `(column, row)` of the first view,
    /// as text.
    ///
    /// # Errors
    /// As [`Plan::render`], or a pixel outside the image.
    pub fn probe(self, column: u32, row: u32) -> miette::Result<String> {
        let mut out = None;
        self.dispatch(&mut Job::Probe {
            column,
            row,
            text: &mut out,
        })?;
        out.ok_or_else(|| miette!("the probe printed nothing"))
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
    pub fn converge(self, stop_k: f64, rounds: usize) -> miette::Result<Vec<ConvergedReference>> {
        if !(stop_k.is_finite() && stop_k > 0.0) {
            return Err(miette!(
                "the reference's stopping difference: expected a finite number of kelvin \
                 above 0, found {stop_k}"
            ));
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
    ) -> miette::Result<()> {
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
    pub fn rows(&self, tile: Option<TileRequest>) -> miette::Result<u64> {
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
    fn dispatch(self, job: &mut Job<'_>) -> miette::Result<()> {
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

    #[allow(clippy::too_many_lines)]
    fn with_atmosphere<R: SubBandModel>(
        &self,
        mut run: RunHash,
        band: R,
        split: Option<&Split<'_>>,
        job: &mut Job<'_>,
    ) -> miette::Result<()> {
        let top_scene = self
            .scene
            .lock()
            .map_err(|_| poisoned())?
            .as_ref()
            .ok_or_else(|| miette!("the raw scene was already traced"))?
            .positions_m
            .iter()
            .map(|p| p[2])
            .fold(0.0_f64, f64::max);
        let request = &self.request.atmosphere;
        let name = request.name().to_owned();
        if let AtmosphereRequest::Vacuum {
            sky_radiance_w_m2_sr,
        } = *request
        {
            if let Some(s) = &self.request.sun {
                return Err(sunlight::no_solar_table(
                    s,
                    "none",
                    "a vacuum",
                    self.request.spelling,
                ));
            }
            let vacuum = Vacuum {
                sky_radiance_w_m2_sr,
            };
            run.field("atmosphere", format!("{vacuum:?}").as_bytes());
            let (b1, b2) = (band.clone(), band.clone());
            let air = Air {
                kinds: None,
                spectral: false,
                precomputed: Box::new(move |_, count| whole(&b1, "none", count, || Ok(vacuum))),
                pilot: Box::new(move |_, count| whole(&b2, "none", count, || Ok(vacuum))),
                data_error_k: None,
                sun: no_sun(),
            };
            return self.trace_all(&run, band, &air, job);
        }
        // A built-in is read in spectral form when sub-bands may be asked for.
        let settings = &self.request.settings;
        let wants_spectra = split.is_some()
            && (settings.sub_bands.is_some_and(|c| !c.is_band())
                || self.request.tolerance.is_some()
                || self.decision.is_some());
        let range_um = split.map(|sp| sp.range_um);
        let mut data = air::read(request, wants_spectra, range_um)?;
        // A built-in's band tables are for the flat band they were made for (8-14 um): any
        // other band, or a sensor response, collapses its spectra instead (else the band
        // model would add the flat band's path and sky radiance to a response-weighted
        // emission).
        if let (AirData::Band(a), Some(sp)) = (&data, &split) {
            let other_band = sp.response.is_some()
                || sp
                    .range_um
                    .iter()
                    .zip(a.band_um)
                    .any(|(x, y)| (x - y).abs() > 1e-9 * y);
            if other_band && matches!(request, AtmosphereRequest::Builtin(_)) {
                data = air::read(request, true, range_um)?;
            } else if other_band {
                self.warn(format!(
                    "`{name}` holds band tables for {}-{} um, flat; the band traced is {}-{} \
                     um{}: its path and sky radiances are the tables' band's",
                    a.band_um[0],
                    a.band_um[1],
                    sp.range_um[0],
                    sp.range_um[1],
                    if sp.response.is_some() {
                        " with a sensor response"
                    } else {
                        ""
                    }
                ));
            }
        }
        // The built-ins are night atmospheres: by day the sun's geometry is part of the
        // atmosphere, which a build makes.
        if let (Some(s), AtmosphereRequest::Builtin(_)) = (&self.request.sun, request) {
            let what = match &data {
                AirData::Band(_) => {
                    "a built-in: a band atmosphere (tables integrated over a band, without spectra)"
                }
                AirData::Spectral(..) => "a built-in: a night atmosphere",
            };
            return Err(sunlight::no_solar_table(
                s,
                &name,
                &format!(
                    "{what}; the built-ins, 8-14 um and 3-5 um, are for night only, since by \
                     day the sun's geometry is part of the atmosphere"
                ),
                self.request.spelling,
            ));
        }
        match (&data, &split, request) {
            (AirData::Spectral(a, bytes), Some(sp), AtmosphereRequest::File { name, .. }) => {
                air::check_spectral_range(name, a, bytes, sp.range_um)?;
            }
            (AirData::Spectral(a, _), Some(sp), AtmosphereRequest::Builtin(name)) => {
                air::check_builtin_range(
                    name,
                    a,
                    &self.request.band,
                    sp.range_um,
                    self.request.spelling,
                )?;
            }
            _ => {}
        }
        if let AtmosphereRequest::Builtin(name) = request {
            air::check_builtin_top(name, &self.views)?;
        }
        // The sky is precomputed up to the highest sensor or scene point.
        let top = self
            .views
            .iter()
            .map(|v| v.position_m()[2])
            .fold(top_scene, f64::max);
        // The sky's precomputed levels depend on the top: so do the pixels.
        match &data {
            AirData::Band(atmosphere) => run.field(
                "atmosphere",
                format!("{atmosphere:?} top {:x}", top.to_bits()).as_bytes(),
            ),
            AirData::Spectral(_, bytes) => {
                run.field("spectral atmosphere", bytes);
                run.field("top", &top.to_bits().to_le_bytes());
            }
        }
        // Tiles of frames lit by different suns must not merge; without a sun the hash is
        // what it always was.
        if let (Some(p), Some(s)) = (&self.sun, &self.request.sun) {
            run.field(
                "sun",
                format!(
                    "{:x} {:x} {}",
                    p.zenith_deg.to_bits(),
                    p.azimuth_deg.to_bits(),
                    s.shadow_rays
                )
                .as_bytes(),
            );
        }
        if matches!(self.request.band.band, AnyBand::Total(_)) {
            let band_um = match &data {
                AirData::Band(a) => format!("{:?}", a.band_um),
                AirData::Spectral(..) => "its spectral range".to_owned(),
            };
            self.warn(format!(
                "the `total` band (whole spectrum) is combined with `{name}`, whose tables \
                 cover {band_um} um: facet radiances and path terms are in different bands; \
                 use this only to check the geometry and the event logic"
            ));
        }
        let model_name = name.clone();
        let model = move |atmosphere: &irsig_model::Atmosphere, kind: ModelKind| {
            AtmosphereModel::new(atmosphere, kind)
                .map_err(|e| miette!("{e}"))
                .wrap_err_with(|| format!("cannot build the {kind} model of `{model_name}`"))
        };
        let warned = std::sync::Once::new();
        let precompute = |model: AtmosphereModel| {
            let air = PrecomputedAtmosphere::new(model, top);
            warned.call_once(|| {
                for w in air.warnings() {
                    self.warn(format!("{name}: {w}"));
                }
            });
            air
        };
        match data {
            AirData::Band(atmosphere) => {
                if let Some(s) = &self.request.sun {
                    return Err(sunlight::no_solar_table(
                        s,
                        &name,
                        "a band atmosphere (tables integrated over a band, without spectra)",
                        self.request.spelling,
                    ));
                }
                let data_error_k = data_error_k(
                    atmosphere
                        .slant
                        .as_ref()
                        .and_then(|s| s.interpolation_residual.as_ref()),
                );
                let kinds: Vec<ModelKind> =
                    [ModelKind::Table, ModelKind::Layered, ModelKind::Thesis]
                        .into_iter()
                        .filter(|&k| AtmosphereModel::new(&atmosphere, k).is_ok())
                        .collect();
                let (a1, a2) = (atmosphere.clone(), atmosphere);
                let (m1, m2) = (model.clone(), model);
                let (b1, b2) = (band.clone(), band.clone());
                let (n1, n2) = (name.clone(), name.clone());
                let precompute = &precompute;
                let air = Air {
                    kinds: Some(kinds),
                    spectral: false,
                    precomputed: Box::new(move |kind, count| {
                        whole(&b1, &n1, count, || Ok(precompute(m1(&a1, kind)?)))
                    }),
                    pilot: Box::new(move |kind, count| {
                        whole(&b2, &n2, count, || {
                            Ok(PrecomputedAtmosphere::new(m2(&a2, kind)?, top))
                        })
                    }),
                    data_error_k,
                    sun: no_sun(),
                };
                self.trace_all(&run, band, &air, job)
            }
            AirData::Spectral(spectral, _) => {
                let Some(split) = split else {
                    return Err(air::no_spectra(&name, SubBandCount::Full));
                };
                // Each count's collapsed sub-bands, made once, from the atmosphere checked
                // once.
                let collapser =
                    irsig_atmosphere::Collapser::new(&spectral).map_err(|e| miette!("{e}"))?;
                let cache: Mutex<HashMap<SubBandCount, Arc<Collapsed>>> = Mutex::default();
                let collapsed = |count: SubBandCount| -> miette::Result<Arc<Collapsed>> {
                    if let Some(c) = cache.lock().map_err(|_| poisoned())?.get(&count) {
                        return Ok(c.clone());
                    }
                    let c = Arc::new(split.collapse(collapser, count)?);
                    cache
                        .lock()
                        .map_err(|_| poisoned())?
                        .insert(count, c.clone());
                    Ok(c)
                };
                let data_error_k = data_error_k(
                    spectral
                        .slant
                        .as_ref()
                        .and_then(|s| s.interpolation_residual.as_ref()),
                );
                let one = collapsed(SubBandCount::BAND)?;
                let kinds: Vec<ModelKind> =
                    [ModelKind::Table, ModelKind::Layered, ModelKind::Thesis]
                        .into_iter()
                        .filter(|&k| one.iter().all(|(_, a)| AtmosphereModel::new(a, k).is_ok()))
                        .collect();
                let collapsed = &collapsed;
                let precompute = &precompute;
                let materials = &self.materials;
                let scatter = crate::sun::by_day(
                    self.request.sun.as_ref(),
                    self.sun.as_ref(),
                    &spectral,
                    &name,
                    |w| self.warn(w),
                );
                let spectral_ref = &spectral;
                // The pilot evaluates its paths in every sub-band: the precomputed sky costs
                // a few ms per sub-band (table model) and saves a slant integration per ray,
                // so the pilot's sets are precomputed too (`S` = `A`), its sub-band sets on
                // PILOT_SKY_LEVELS altitudes (the full grid's 108 skies were most of its
                // cost). Sub-bands are precomputed in parallel; `collect` keeps their order.
                let sub_bands = move |kind: ModelKind, count: SubBandCount, pilot: bool| {
                    collapsed(count)?
                        .par_iter()
                        .map(|(b, a)| {
                            let m = model(a, kind)?;
                            let atmosphere = if pilot && !count.is_band() {
                                PrecomputedAtmosphere::with_levels(m, top, PILOT_SKY_LEVELS)
                            } else {
                                precompute(m)
                            };
                            let atmosphere =
                                crate::sun::with_slabs(atmosphere, spectral_ref, *split, b)?;
                            Ok(SubBand {
                                band: R::of_band(b)?,
                                atmosphere: crate::sun::scattered(
                                    atmosphere,
                                    scatter,
                                    spectral_ref,
                                    *split,
                                    b,
                                )?,
                                emissivity: crate::materials::sub_band_tables(materials, b)?,
                            })
                        })
                        .collect()
                };
                let sub_bands = &sub_bands;
                // The sun's beams over the same sub-bands; the table is checked now, before
                // anything is traced.
                let spectral = &spectral;
                let lit = |count: SubBandCount| -> miette::Result<Option<irsig_tracer::Sun>> {
                    let (Some(request), Some(position)) = (&self.request.sun, &self.sun) else {
                        return Ok(None);
                    };
                    let c = collapsed(count)?;
                    sunlight::sun(
                        request,
                        position,
                        &name,
                        spectral,
                        split,
                        &c,
                        self.request.spelling,
                    )
                    .map(Some)
                };
                lit(SubBandCount::BAND)?;
                let air = Air {
                    kinds: Some(kinds),
                    spectral: true,
                    precomputed: Box::new(move |kind, count| sub_bands(kind, count, false)),
                    pilot: Box::new(move |kind, count| sub_bands(kind, count, true)),
                    data_error_k,
                    sun: Box::new(lit),
                };
                self.trace_all(&run, band, &air, job)
            }
        }
    }

    /// The pilot's decision for `camera`'s frame, with the seconds it took.
    fn decide<R: BandModel + Clone + Send, A: Atmosphere, S: Atmosphere + Send>(
        &self,
        tolerance: &ToleranceRequest,
        tracer: &Tracer<R, A>,
        air: &Air<'_, R, A, S>,
        camera: &Camera,
    ) -> miette::Result<(irsig_tracer::pilot::Piloted, f64)> {
        let mut offer = tolerance::offer(
            &self.materials,
            air.kinds.as_deref(),
            air.spectral,
            tracer.has_sun(),
            &tolerance.pins,
            self.request.spelling,
        )?;
        let (Some(&ref_kind), Some(&ref_count)) =
            (offer.atmospheres.first(), offer.sub_bands.first())
        else {
            return Err(miette!(
                "the pilot has no atmosphere or sub-band count to offer"
            ));
        };
        // A count the band's grid cannot make (more sub-bands than grid intervals in a
        // narrow band) is not on offer, unless it is the one pinned.
        let pinned_count = offer.sub_bands.len() == 1;
        // The sub-band counts at the reference atmosphere; every other model is measured in
        // the band model (`Tracer::pilot` says why), so each atmosphere in it.
        let mut pairs: Vec<(ModelKind, SubBandCount)> = Vec::new();
        for &count in &offer.sub_bands {
            pairs.push((ref_kind, count));
        }
        pairs.push((ref_kind, SubBandCount::BAND));
        for &kind in &offer.atmospheres {
            pairs.push((kind, SubBandCount::BAND));
        }
        // The pilot's time includes making its band sets (each sub-band's sky).
        let started = std::time::Instant::now();
        let mut bands: Vec<BandChoice<S>> = Vec::new();
        let mut unavailable = Vec::new();
        let mut unique: Vec<(ModelKind, SubBandCount)> = Vec::new();
        for pair in pairs {
            if !unique.contains(&pair) {
                unique.push(pair);
            }
        }
        // Made side by side (the full grid's set is most of the time), then taken in order.
        let pilot = &air.pilot;
        let made: Vec<_> = unique
            .par_iter()
            .map(|&(kind, count)| pilot(kind, count))
            .collect();
        for ((kind, count), made) in unique.into_iter().zip(made) {
            let sub = match made {
                Ok(sub) => sub,
                Err(e) if count == ref_count || count.is_band() || pinned_count => return Err(e),
                Err(_) => {
                    unavailable.push(count);
                    continue;
                }
            };
            // By day each set carries the sun's beams over its own sub-bands.
            let beams = if tracer.has_sun() {
                (air.sun)(count)?.map(|s| s.beams)
            } else {
                None
            };
            let set = tracer
                .band_set(sub)
                .and_then(|set| tracer.lit_band_set(set, beams))
                .map_err(|e| miette!("{e}"))?;
            let (path_call_ns, sky_ns) = atmosphere_costs(kind, camera.position_m[2].max(0.0));
            bands.push(BandChoice {
                atmosphere: kind,
                sub_bands: count,
                set,
                path_call_ns,
                sky_ns,
            });
        }
        offer.sub_bands.retain(|c| !unavailable.contains(c));
        // The sun switched off is the band model's set without its beams.
        let sun = if offer.sun.is_empty() {
            None
        } else {
            let dark = tracer
                .band_set(pilot(ref_kind, SubBandCount::BAND)?)
                .map_err(|e| miette!("{e}"))?;
            Some(SunOffer {
                lit: offer.sun,
                shadow_rays: offer.shadow_rays,
                dark,
            })
        };
        let space = PilotSpace {
            bands,
            atmospheres: offer.atmospheres,
            sub_bands: offer.sub_bands,
            bounces: offer.bounces,
            sky_view_rays: offer.sky_view_rays,
            supersampling: offer.supersampling,
            path_terms: offer.path_terms,
            reasons: offer.reasons,
            pinned: offer.pinned,
            sun,
        };
        // About one pixel in 192 (1024 at 512 x 384), at least 1024 (every pixel of a
        // smaller image) and at most 4096: a thin population of pixels (edges, a small hot
        // object) of 1 % needs several hundred samples to be seen at all.
        let pixels =
            (u64::from(camera.pixels[0]) * u64::from(camera.pixels[1]) / 192).clamp(1024, 4096);
        let mut piloted = tracer
            .pilot(
                camera,
                &space,
                tolerance.tolerance_k,
                tolerance.percentile,
                pixels as u32,
                self.request.settings.seed,
            )
            .map_err(|e| RequestError::report(Setting::Tolerance, e.to_string()))?;
        // What no setting removes: said beside the decision, and left to the error budget.
        piloted.decision.data_error_k = air.data_error_k;
        Ok((piloted, started.elapsed().as_secs_f64()))
    }

    #[allow(clippy::too_many_lines)]
    fn trace_all<R: BandModel + Clone + Send + Sync, A: Atmosphere, S: Atmosphere + Send>(
        &self,
        run: &RunHash,
        band: R,
        air: &Air<'_, R, A, S>,
        job: &mut Job<'_>,
    ) -> miette::Result<()> {
        let scene = self
            .scene
            .lock()
            .map_err(|_| poisoned())?
            .take()
            .ok_or_else(|| miette!("the raw scene was already traced"))?;
        let asked = Settings::of(&self.request.settings);
        let base = match &self.decision {
            Some(d) => asked.with_decision(d).map_err(|(_, m)| miette!("{m}"))?,
            None => asked,
        };
        let (mut kind, mut count) = (base.kind, base.sub_bands);
        // The sun as the settings have it: left out, or with their shadow rays.
        let sun_of = |settings: &Settings| -> miette::Result<Option<irsig_tracer::Sun>> {
            Ok((air.sun)(settings.sub_bands)?
                .filter(|_| settings.sun_lit)
                .map(|mut sun| {
                    if let Some(n) = settings.shadow_rays {
                        sun.shadow_rays = n;
                    }
                    sun
                }))
        };
        let sun = sun_of(&base)?;
        let mut tracer = Tracer::with_sub_bands(
            &scene,
            &self.materials,
            band,
            (air.precomputed)(kind, count)?,
        )
        .and_then(|t| t.with_sun(sun))
        .map_err(|e| miette!("{e}"))
        .wrap_err_with(|| {
            format!(
                "cannot trace `{}` with `{}`",
                self.scene_name, self.materials_name
            )
        })?
        .with_path_terms(base.path_terms);
        let scene = self.uncertainties.is_some().then_some(scene);
        // The materials with a specular share: a reflection that meets one is a mirror
        // seen in a mirror, a class of the decision's own.
        let mirrors: Vec<u16> = self
            .materials
            .materials
            .iter()
            .filter(|m| m.specular_fraction > 0.0)
            .map(|m| m.id.0)
            .collect();
        let cameras = self
            .views
            .iter()
            .map(|v| Camera::from_view(v).map_err(|e| miette!("{e}")))
            .collect::<miette::Result<Vec<_>>>()?;
        let (tile, sink) = match job {
            Job::Probe { column, row, text } => {
                let cam = cameras
                    .first()
                    .ok_or_else(|| RequestError::report(Setting::Probe, "no view to probe"))?;
                let s = tracer
                    .probe(cam, &base.options, *column, *row)
                    .map_err(|e| miette!("the probed pixel ({column}, {row}): {e}"))?;
                let t = tracer.apparent_temperature_k(s.radiance_w_m2_sr);
                let sub_bands = tracer.sub_bands();
                **text = Some(format!(
                    "pixel ({column}, {row}), view 1, {sub_bands} sub-band(s)\n{s}\n\
                     apparent temperature_k     {t}\n"
                ));
                return Ok(());
            }
            Job::Converge {
                stop_k,
                rounds,
                out,
            } => {
                **out = cameras
                    .iter()
                    .map(|cam| converged_reference(&tracer, cam, *stop_k, *rounds))
                    .collect::<Result<_, _>>()
                    .map_err(|e| miette!("{e}"))?;
                return Ok(());
            }
            Job::Render {
                tile,
                progress,
                sink,
            } => (*tile, (*progress, &mut **sink)),
        };
        let (progress, sink) = sink;
        let tiles = self.tiles(tile)?;
        self.flush_warnings(sink);
        for (i, cam) in cameras.iter().enumerate() {
            let piloted;
            let (settings, decision) = match &self.request.tolerance {
                Some(tolerance) => {
                    // The pilot sees the sun asked for, whatever an earlier frame chose.
                    if self.request.sun.is_some() {
                        tracer = tracer
                            .with_sun((air.sun)(count)?)
                            .map_err(|e| miette!("{e}"))?;
                    }
                    let (p, seconds) = self.decide(tolerance, &tracer, air, cam)?;
                    piloted = p;
                    self.flush_warnings(sink);
                    sink.decision(i, &piloted.decision, seconds)?;
                    let c = piloted.chosen;
                    let mut settings = base;
                    settings.kind = c.atmosphere;
                    settings.sub_bands = c.sub_bands;
                    settings.path_terms = c.path_terms;
                    settings.options.specular_bounces = c.bounces;
                    settings.options.sky_view_rays = c.sky_view_rays;
                    settings.refinement = c.refinement;
                    settings.sun_lit = c.sun.is_none_or(|s| s.lit);
                    settings.shadow_rays = c.sun.map(|s| s.shadow_rays);
                    (
                        settings.options.supersampling,
                        settings.options.adaptive_threshold_k,
                    ) = match c.supersampling {
                        Supersample::Every(n) => (n, None),
                        Supersample::Adaptive(n) => (n, Some(tolerance.tolerance_k)),
                        Supersample::Refine(_) => (1, None),
                    };
                    settings.options.validate().map_err(|e| miette!("{e}"))?;
                    (settings, Some(&piloted.decision))
                }
                None => (base, self.decision.as_ref()),
            };
            let budget = self
                .uncertainties
                .as_ref()
                .zip(scene.as_ref())
                .map(|(u, scene)| Budget {
                    uncertainties: u,
                    scene,
                });
            let guarantee = decision.map(|decision| Guarantee {
                decision,
                camera: cam,
                origin: [tiles[i].x, tiles[i].y],
                mirrors: &mirrors,
            });
            if settings.kind != kind || settings.sub_bands != count {
                // New sub-bands drop the sun, whose beams are per sub-band: lit again.
                let sun = sun_of(&settings)?;
                tracer = tracer
                    .with_bands((air.precomputed)(settings.kind, settings.sub_bands)?)
                    .and_then(|t| t.with_sun(sun))
                    .map_err(|e| miette!("{e}"))?;
                (kind, count) = (settings.kind, settings.sub_bands);
            } else if self.request.sun.is_some() {
                tracer = tracer
                    .with_sun(sun_of(&settings)?)
                    .map_err(|e| miette!("{e}"))?;
            }
            self.flush_warnings(sink);
            let wanted = sink.files(i);
            if !wanted.any() {
                // Only the pilot's decision was asked for.
                continue;
            }
            tracer = tracer
                .with_path_terms(settings.path_terms)
                .with_refinement(settings.refinement)
                .map_err(|e| miette!("{e}"))?;
            // The per-pixel terms are kept only when a file of this frame reads them.
            let options = TraceOptions {
                truth: wanted.wants(FrameFile::TruthExr) || wanted.wants(FrameFile::MapPng),
                ..settings.options
            };
            let frame = if tile.is_some() {
                tracer.render_tile(cam, &options, tiles[i], progress)
            } else {
                tracer.render(cam, &options, progress)
            }
            .map_err(|e| miette!("{e}"))?;
            let part = FramePart {
                frame_width: cam.pixels[0] as usize,
                frame_height: cam.pixels[1] as usize,
                x: tiles[i].x as usize,
                y: tiles[i].y as usize,
                run: run.frame(&self.views[i], &settings),
            };
            let radiometry = FrameRadiometry {
                band: tracer.band().clone(),
                sub_bands: tracer.sub_bands(),
                view_gain: self.views.get(i).and_then(View::gain_dc_per_k),
                counts: self.request.counts,
                provenance: Some(self.provenance(&settings)),
            };
            let mut emit = |kind, bytes| sink.file(i, kind, bytes);
            if i + 1 == cameras.len() {
                // The last frame's files need the band, not the scene: the BVH and the facet
                // records (about 100 bytes a facet) go before the files are made, which hold
                // the frame's layers and encoded files (the frame's peak memory was there).
                drop(tracer);
                return products::traced(
                    &radiometry,
                    frame,
                    &wanted,
                    &part,
                    budget.as_ref(),
                    guarantee.as_ref(),
                    &mut emit,
                );
            }
            products::traced(
                &radiometry,
                frame,
                &wanted,
                &part,
                budget.as_ref(),
                guarantee.as_ref(),
                &mut emit,
            )?;
        }
        Ok(())
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
    atmosphere: impl FnOnce() -> miette::Result<T>,
) -> miette::Result<Vec<SubBand<R, T>>> {
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

fn poisoned() -> miette::Report {
    miette!("a lock of the run was poisoned by a panic")
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
) -> miette::Result<()> {
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
        return Err(error_at_path(
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
        )
        .into());
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
