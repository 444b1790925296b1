//! `irsig-trace`: renders a raw scene through an atmosphere for one or more views and writes,
//! per view, the radiance image (f32 EXR), the truth layers (multi-layer f32 EXR), the
//! legacy interaction map (8-bit nibble PNG) when the material ids fit in four bits, and
//! the digital-count image (8- or 16-bit PNG) with its LUT.
//!
//! This crate is the command line only: it reads files through `irsig-formats`, asks
//! `irsig-atmosphere` for the atmosphere, `irsig-tracer` for the frames and
//! `irsig-sensor-model` for the counts, and writes the outputs, all or none of them.
//!
//! ```text
//! irsig-trace --scene world.raw.ron --materials materials.ron --view view.ron -o out/frame
//! # -> out/frame.radiance.exr, out/frame.truth.exr, out/frame.map.png, out/frame.dc.png,
//! #    out/frame.lut.txt
//! irsig-trace --scene world.raw --materials materials.ron --view view.ron \
//!     --radiance-exr out/frame.exr --dc-png out/frame.png   # only these two
//! irsig-trace --scene world.raw.ron --materials materials.ron --view view.ron --probe 128,128
//! irsig-trace --scene world.raw --materials materials.ron --view frame1.view -o out/f1
//! irsig-trace --scene world.raw --materials materials.ron --execute flyby.exec
//! irsig-trace --scene world.raw --materials materials.ron --view view.ron --tile 6/4x4 \
//!     -o tiles/t06      # tile 6 of a 4 x 4 grid; irsig-merge puts the frame together
//! ```
//!
//! `-o PREFIX` writes every output under one prefix; the per-output flags write only the
//! files named, for one view, so that `irsig-run` and Makefiles see each file a stage
//! writes.
//!
//! Every EXR says which frame it is part of and which run made it (`irsig.run`, a SHA-256
//! of the inputs and of the settings the pixels depend on; formats/images.md): a tile
//! (`--tile`) is a rectangle of its frame, and the tiles of a frame merge (irsig-merge)
//! into the bytes the frame traced whole writes.

mod spectral_materials;
mod tolerance;

use std::path::{Path, PathBuf};
use std::sync::Mutex;

use clap::Parser;
use irsig_atmosphere::{AtmosphereModel, ModelKind, PrecomputedAtmosphere, SubBandCount};
pub use irsig_cli::args::TraceBand;
use irsig_cli::args::{DcArgs, named};
use irsig_formats::canonical::{from_ron_bytes, read_raw_scene};
use irsig_formats::legacy::decode;
use irsig_formats::views::{parse_views, read_execute};
use irsig_model::decision::{Decision, SwitchableModel};
use irsig_model::truth::Layer;
use irsig_model::uncertainty::Uncertainties;
use irsig_model::{LengthUnit, MaterialLibrary, RawScene, SpectralAtmosphere, View};
use irsig_radiometry::{Band, BandModel, TotalRadiance, spectral_radiance_per_um};
use irsig_raster::{FramePart, Raster, counts_png, into_exr_bytes, write_png_gray8};
use irsig_tracer::pilot::{BandChoice, PilotSpace, Supersample};
use irsig_tracer::{
    Atmosphere, Camera, Frame, PathTermsMode, SubBand, Tile, TraceOptions, Tracer, Vacuum,
};
use miette::{IntoDiagnostic, WrapErr, miette};
use rayon::prelude::*;
use sha2::{Digest, Sha256};

const EXAMPLE: &str = "\
Examples:
  irsig-trace --scene world.raw.ron --materials materials.ron --view view.ron -o out/frame
      writes out/frame.radiance.exr, out/frame.truth.exr, out/frame.map.png, and the
      digital counts out/frame.dc.png with out/frame.lut.txt
  irsig-trace --scene world.raw.ron --materials materials.ron --view flyby.ron -o out/f
      flyby.ron holds a list of views: writes out/f.0001.radiance.exr, out/f.0002..., with
      the BVH built once
  irsig-trace --scene world.raw --materials materials.ron --view view.ron \\
      --radiance-exr frame.exr --dc-png frame.png --lut frame.lut
      writes only the outputs named (one view), as a pipeline stage or a Makefile rule does
  irsig-trace --scene world.raw.ron --materials materials.ron --view view.ron --probe 128,64
      prints every term of the radiance equation for pixel column 128, row 64
  irsig-trace --scene world.raw --materials materials.ron --view frame1.view -o out/f1
      frame1.view is a 1990 viewing file (numbers; position in km, see --view-unit)
  irsig-trace --scene world.raw --materials materials.ron --execute flyby.exec
      a 1990 execute file: per frame a viewing file and the map image, DC image and LUT
      to write (names relative to flyby.exec); the BVH is built once
  irsig-trace --scene world.raw --materials materials.ron --view view.ron --tile 6/4x4 \\
      -o tiles/t06
      tile 6 of a 4 x 4 grid (row by row from the top-left): tiles/t06.radiance.exr and
      tiles/t06.truth.exr, its pixels bit for bit the whole frame's; irsig-merge
      tiles/*.exr -o out/frame writes the frame's files

Pixel (0, 0) is the top-left; rows run downwards.";

/// Render a raw scene: radiance EXR, truth EXR and the legacy interaction map per view.
#[derive(Debug, Parser)]
#[command(name = "irsig-trace", version, about, after_help = EXAMPLE)]
pub struct Cli {
    /// The raw scene (canonical RON or the binary form `irsig-flatten` writes), or `-` for
    /// stdin.
    #[arg(long, value_name = "FILE")]
    pub scene: String,
    /// The material library (canonical RON).
    #[arg(long, value_name = "FILE")]
    pub materials: String,
    /// One or more view files, each a canonical RON view, a RON list of views, or a 1990
    /// viewing file (told apart by their first character: a number starts a viewing file);
    /// frames are numbered in the order given.
    #[arg(long, value_name = "FILE", num_args = 1.., required_unless_present = "execute")]
    pub view: Vec<String>,
    /// Length unit of the positions in 1990 viewing files (km in the thesis's files),
    /// converted to metres on reading. Canonical views are always in metres.
    #[arg(long, default_value = "km", value_name = "UNIT", value_parser = parse_unit)]
    pub view_unit: LengthUnit,
    /// A 1990 execute file: frames of (viewing file, scene file, map image, output image,
    /// LUT), names relative to its folder. Each frame writes its interaction map PNG, its
    /// DC image PNG and its LUT under the names given; the BVH of --scene is built once.
    /// Every frame must name the same scene file: the legacy scene that --scene was
    /// flattened from.
    #[arg(long, value_name = "FILE", conflicts_with_all = [
        "view", "output", "radiance_exr", "truth_exr", "map_png", "dc_png", "lut"
    ])]
    pub execute: Option<String>,
    /// The band: `MIN-MAX` in micrometres (flat response) or a sensor response file
    /// (formats/srf.md); or `total`, the whole spectrum (σT⁴/π), exact and for checking by
    /// hand. A built-in atmosphere is collapsed from its spectra over any band other than
    /// its tables' flat 8-14; with a band-form atmosphere file use the band its tables were
    /// integrated over.
    #[arg(long, default_value = "8-14", value_name = "MIN-MAX|FILE|total")]
    pub band: TraceBand,
    /// The atmosphere: a built-in name (`us-std-1976`, `midlat-winter`; both also in
    /// spectral form), a canonical atmosphere file (RON), a spectral atmosphere file (what
    /// `irsig-atmos build` writes), or `none` (a vacuum whose sky has radiance
    /// --sky-radiance).
    #[arg(long, default_value = "none", value_name = "NAME|FILE")]
    pub atmosphere: String,
    /// Sum the radiance equation over sub-bands of the band (the spectral model), each
    /// with its own τ, path and sky radiance collapsed from a spectral atmosphere: K
    /// sub-bands, each holding an equal share of the band's response-weighted blackbody
    /// radiance at 300 K, or `full`, one per interval of the atmosphere's spectral grid.
    /// 1, the default, is the band model: one band-mean τ times the band radiance, the
    /// faster model (docs/accuracy.md measures what it costs in kelvin).
    #[arg(long, value_name = "K|full", value_parser = parse_sub_bands)]
    pub sub_bands: Option<SubBandCount>,
    /// The atmosphere model: `table` (slant-path tables), `layered` (eq. 8-9), `thesis`
    /// (eq. 10-11, the 1990 model) or `none`.
    /// [default: table]
    #[arg(long, value_name = "MODEL", value_parser = named::<ModelKind>(&ModelKind::NAMES))]
    pub atmosphere_model: Option<ModelKind>,
    /// Sky radiance for `--atmosphere none`, W m^-2 sr^-1 (0: cold space).
    #[arg(long, default_value_t = 0.0, value_name = "W_M2_SR")]
    pub sky_radiance: f64,
    /// Output path prefix; files are PREFIX.radiance.exr, PREFIX.truth.exr, PREFIX.map.png,
    /// PREFIX.dc.png and PREFIX.lut.txt (PREFIX.NNNN.* for several views). Give this, or
    /// one or more of the per-output flags below, or --probe.
    #[arg(short = 'o', long, value_name = "PREFIX")]
    pub output: Option<PathBuf>,
    /// Write the radiance image (f32 EXR, W m^-2 sr^-1) to FILE. The per-output flags write
    /// only the outputs named, for one view, so that a pipeline or a Makefile sees every
    /// file a stage writes. Any one of them may be `-`, standard output (e.g. piped into
    /// `irsig-sensor -`).
    #[arg(long, value_name = "FILE", conflicts_with = "output")]
    pub radiance_exr: Option<PathBuf>,
    /// Write the truth layers (multi-layer f32 EXR) to FILE.
    #[arg(long, value_name = "FILE", conflicts_with = "output")]
    pub truth_exr: Option<PathBuf>,
    /// Write the legacy interaction map (8-bit nibble PNG) to FILE; an error when a
    /// material id does not fit in four bits.
    #[arg(long, value_name = "FILE", conflicts_with = "output")]
    pub map_png: Option<PathBuf>,
    /// Write the digital-count image (PNG, --dc-bits deep) to FILE.
    #[arg(long, value_name = "FILE", conflicts_with_all = ["output", "no_dc"])]
    pub dc_png: Option<PathBuf>,
    /// Write the digital-count LUT (text: DC, radiance, K, degC) to FILE.
    #[arg(long, value_name = "FILE", conflicts_with_all = ["output", "no_dc"])]
    pub lut: Option<PathBuf>,
    /// With -o, write no DC image or LUT.
    #[arg(long, conflicts_with = "execute")]
    pub no_dc: bool,
    /// Specular bounces per path (thesis: 1) [default: 1].
    #[arg(long)]
    pub bounces: Option<u32>,
    /// Sky-view factor rays per diffuse hit (0: off, F = 1 as in the thesis) [default: 0].
    #[arg(long, value_name = "N")]
    pub sky_view_rays: Option<u32>,
    /// Supersampling: N for N x N stratified rays per pixel (1: one ray through the centre)
    /// [default: 1].
    #[arg(long, value_name = "N")]
    pub supersample: Option<u32>,
    /// Adaptive supersampling: give the N x N rays of --supersample only to pixels whose
    /// centre ray's apparent temperature differs from a neighbour's by more than K kelvin
    /// (edges); the others keep their centre ray.
    #[arg(long, value_name = "K", requires = "supersample")]
    pub adaptive_supersampling: Option<f64>,
    /// Seed for sky-view directions and sub-pixel jitter.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Path terms (τ, L_u) of facet hits: `exact` (one atmosphere call per hit) or
    /// `tabulated` (a per-frame altitude × range table; worst error 15 mK, see
    /// docs/accuracy.md; faster from about 200 × 200 pixels up) [default: exact].
    #[arg(long, value_name = "MODE", value_parser = named::<PathTermsMode>(&PathTermsMode::NAMES))]
    pub path_terms: Option<PathTermsMode>,
    /// Let the tool choose the models (atmosphere, bounces, sky-view rays, supersampling,
    /// path terms, sub-bands) for this scene and view: the cheapest whose predicted error
    /// against the most accurate settings stays within K kelvin at --tolerance-percentile
    /// of the pixels. A pilot over a sample of pixels decides per frame; the decision is
    /// printed on stderr and written beside the outputs (PREFIX.decision.ron with -o, else
    /// --decision-out). Pin a model by hand with --pin.
    #[arg(long, value_name = "K", allow_negative_numbers = true, conflicts_with_all = [
        "atmosphere_model", "bounces", "sky_view_rays", "supersample", "path_terms",
        "adaptive_supersampling", "decision", "sub_bands",
    ])]
    pub tolerance: Option<f64>,
    /// The percentile of pixels --tolerance applies to, more than 0 and at most 100.
    #[arg(
        long,
        default_value_t = 99.0,
        value_name = "P",
        requires = "tolerance",
        allow_negative_numbers = true
    )]
    pub tolerance_percentile: f64,
    /// With --tolerance, fix one model's setting: MODEL=SETTING, with MODEL one of
    /// atmosphere (table, layered, thesis), bounces (N), sky-view (N rays, 0: off),
    /// supersampling (N or adaptive-N), path-terms (exact, tabulated), sub-bands (1, K,
    /// full). Repeat for several.
    #[arg(long, value_name = "MODEL=SETTING", requires = "tolerance")]
    pub pin: Vec<tolerance::Pin>,
    /// Apply a decision an earlier --tolerance run wrote (for every frame), instead of
    /// piloting: tiles of one frame share their frame's decision.
    #[arg(long, value_name = "FILE")]
    pub decision: Option<String>,
    /// Declared uncertainties of the inputs (canonical RON, formats/canonical/
    /// uncertainties.md): the truth EXR gains the error budget, one σ layer (K) per source
    /// and their root-sum-square.
    #[arg(long, value_name = "FILE")]
    pub uncertainties: Option<String>,
    /// With --tolerance and the per-output flags, write the decision (canonical RON) to
    /// FILE.
    #[arg(
        long,
        value_name = "FILE",
        requires = "tolerance",
        conflicts_with = "output"
    )]
    pub decision_out: Option<PathBuf>,
    /// Print every term of the radiance equation for pixel COLUMN,ROW of the first view and
    /// write no files.
    #[arg(long, value_name = "COLUMN,ROW", value_parser = parse_pixel)]
    pub probe: Option<(u32, u32)>,
    /// Trace one tile of the image: X,Y,W,H (W x H pixels from column X, row Y) or I/CxR
    /// (tile I, from 1 row by row, of a grid of C columns and R rows). Writes the radiance
    /// and truth EXRs of the tile, each pixel bit for bit the whole frame's; irsig-merge
    /// assembles a frame's tiles and writes its map, counts and LUT, which depend on the
    /// whole frame.
    #[arg(long, value_name = "X,Y,W,H|I/CxR", value_parser = parse_tile, conflicts_with_all = [
        "probe", "tolerance", "execute", "map_png", "dc_png", "lut",
    ])]
    pub tile: Option<TileArg>,
    /// How radiance becomes digital counts. Without a gain the view's DC/K is used, else
    /// 2 counts per kelvin (the thesis's auto-bias).
    #[command(flatten)]
    pub dc: DcArgs,
    /// Worker threads (default: all cores). The images do not depend on it.
    #[arg(long)]
    pub threads: Option<usize>,
}

impl Cli {
    fn has_output_flags(&self) -> bool {
        self.radiance_exr.is_some()
            || self.truth_exr.is_some()
            || self.map_png.is_some()
            || self.dc_png.is_some()
            || self.lut.is_some()
            || self.decision_out.is_some()
    }

    /// Where each output of frame `index` (from 0) of `frames` goes; `None` for an output
    /// not wanted. With -o PREFIX every output is wanted (the map when the ids fit, the
    /// counts unless `--no-dc`); with the per-output flags only those named.
    fn outputs(&self, index: usize, frames: usize, map_fits: bool) -> Outputs {
        match &self.output {
            Some(prefix) => {
                let stem = if frames == 1 {
                    prefix.clone()
                } else {
                    numbered(prefix, index + 1)
                };
                // A tile's map and counts are the merge's: they need the whole frame.
                let whole = self.tile.is_none();
                let dc = !self.no_dc && whole;
                Outputs {
                    radiance_exr: Some(with_suffix(&stem, "radiance.exr")),
                    truth_exr: Some(with_suffix(&stem, "truth.exr")),
                    map_png: (map_fits && whole).then(|| with_suffix(&stem, "map.png")),
                    dc_png: dc.then(|| with_suffix(&stem, "dc.png")),
                    lut: dc.then(|| with_suffix(&stem, "lut.txt")),
                }
            }
            None => Outputs {
                radiance_exr: self.radiance_exr.clone(),
                truth_exr: self.truth_exr.clone(),
                map_png: self.map_png.clone(),
                dc_png: self.dc_png.clone(),
                lut: self.lut.clone(),
            },
        }
    }
}

/// The files one frame writes.
#[derive(Debug, Clone, Default)]
struct Outputs {
    radiance_exr: Option<PathBuf>,
    truth_exr: Option<PathBuf>,
    map_png: Option<PathBuf>,
    dc_png: Option<PathBuf>,
    lut: Option<PathBuf>,
}

impl Outputs {
    /// The files named.
    fn paths(&self) -> impl Iterator<Item = &PathBuf> {
        [
            &self.radiance_exr,
            &self.truth_exr,
            &self.map_png,
            &self.dc_png,
            &self.lut,
        ]
        .into_iter()
        .flatten()
    }
}

fn parse_unit(s: &str) -> Result<LengthUnit, String> {
    s.parse()
}

fn parse_sub_bands(s: &str) -> Result<SubBandCount, String> {
    s.parse()
}

/// `--tile`: a rectangle, or a tile of a grid (resolved against each view's image).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TileArg {
    /// `X,Y,W,H`.
    Rect(Tile),
    /// `I/CxR`: tile `index` (from 1) of `columns × rows`.
    Grid {
        /// The tile, from 1, row by row from the top-left.
        index: u32,
        /// Grid columns.
        columns: u32,
        /// Grid rows.
        rows: u32,
    },
}

impl TileArg {
    /// The tile of a `width × height` image.
    fn of(self, width: u32, height: u32) -> Result<Tile, String> {
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

fn parse_tile(s: &str) -> Result<TileArg, String> {
    let number = |t: &str, what: &str| {
        t.trim()
            .parse::<u32>()
            .map_err(|_| format!("expected {what} (a whole number), found `{t}` in `{s}`"))
    };
    if let Some((index, grid)) = s.split_once('/') {
        let (columns, rows) = grid
            .split_once(['x', 'X'])
            .ok_or_else(|| format!("expected I/CxR such as 6/4x4, found `{s}`"))?;
        return Ok(TileArg::Grid {
            index: number(index, "a tile number I")?,
            columns: number(columns, "a number of columns C")?,
            rows: number(rows, "a number of rows R")?,
        });
    }
    let parts: Vec<&str> = s.split(',').collect();
    let [x, y, w, h] = parts[..] else {
        return Err(format!(
            "expected X,Y,W,H (pixels) such as 0,0,256,256, or I/CxR such as 6/4x4; found `{s}`"
        ));
    };
    Ok(TileArg::Rect(Tile {
        x: number(x, "a column X")?,
        y: number(y, "a row Y")?,
        width: number(w, "a width W")?,
        height: number(h, "a height H")?,
    }))
}

fn parse_pixel(s: &str) -> Result<(u32, u32), String> {
    let (a, b) = s
        .split_once(',')
        .ok_or_else(|| format!("expected COLUMN,ROW such as 128,64, found `{s}`"))?;
    let p = |t: &str| {
        t.trim()
            .parse::<u32>()
            .map_err(|_| format!("expected a pixel index (0 or more), found `{t}`"))
    };
    Ok((p(a)?, p(b)?))
}

/// The frames of one run: their views and, from an execute file, the files each writes
/// (`None`: the outputs follow from -o or the per-output flags); and the hash of what
/// every frame's pixels depend on, fed as the run's inputs are read.
struct Job {
    views: Vec<View>,
    outputs: Option<Vec<Outputs>>,
    run: Sha256,
}

/// Reads the views: every --view file, or the frames of --execute.
fn read_job(cli: &Cli) -> miette::Result<Job> {
    if let Some(path) = &cli.execute {
        let input = irsig_cli::read_input(path)?;
        let text = decode(&input.name, &input.bytes)?;
        let frames = read_execute(&input.name, text, &input.base_dir(), cli.view_unit)?;
        let outputs = frames
            .iter()
            .map(|f| Outputs {
                map_png: Some(f.map_png.clone()),
                dc_png: Some(f.dc_png.clone()),
                lut: Some(f.lut.clone()),
                ..Outputs::default()
            })
            .collect();
        let views = frames.into_iter().map(|f| f.view).collect();
        return Ok(Job {
            views,
            outputs: Some(outputs),
            run: Sha256::new(),
        });
    }
    let mut views = Vec::new();
    for path in &cli.view {
        let input = irsig_cli::read_input(path)?;
        let text = decode(&input.name, &input.bytes)?;
        views.extend(parse_views(&input.name, text, cli.view_unit)?);
    }
    Ok(Job {
        views,
        outputs: None,
        run: Sha256::new(),
    })
}

/// Runs the tool.
///
/// # Errors
/// Bad input (with file, line and column where there is one) or an unwritable output.
pub fn run(cli: Cli) -> miette::Result<()> {
    if cli.probe.is_none()
        && cli.output.is_none()
        && !cli.has_output_flags()
        && cli.execute.is_none()
    {
        return Err(irsig_cli::usage_error(
            "give -o PREFIX for all the output files, per-output flags such as \
             --radiance-exr FILE, or --probe COLUMN,ROW",
        ));
    }
    let to_stdout = [
        &cli.radiance_exr,
        &cli.truth_exr,
        &cli.map_png,
        &cli.dc_png,
        &cli.lut,
    ]
    .iter()
    .filter(|p| p.as_deref().is_some_and(|p| p.as_os_str() == "-"))
    .count();
    if to_stdout > 1 {
        return Err(irsig_cli::usage_error(
            "only one output can go to standard output (`-`)",
        ));
    }
    if let Some(t) = cli.tolerance {
        irsig_model::decision::check_tolerance(t, "--tolerance")
            .and_then(|()| {
                irsig_model::decision::check_percentile(
                    cli.tolerance_percentile,
                    "--tolerance-percentile",
                )
            })
            .map_err(|e| irsig_cli::usage_error(format!("{}: {}", e.path, e.kind)))?;
    }
    if !cli.sky_radiance.is_finite() || cli.sky_radiance < 0.0 {
        return Err(irsig_cli::usage_error(format!(
            "--sky-radiance {} is out of range: expected a finite radiance of 0 or more",
            cli.sky_radiance
        )));
    }
    let mut run = Sha256::new();
    run.update(RUN_HASH_VERSION);
    let scene_input = irsig_cli::read_input(&cli.scene)?;
    hash_field(&mut run, "scene", &scene_input.bytes);
    let scene = read_raw_scene(&scene_input.name, &scene_input.bytes)?;
    // Spectral materials: their band tables are their curves averaged over the band (the
    // curves stay, for the sub-bands).
    let materials: MaterialLibrary = {
        let input = irsig_cli::read_input(&cli.materials)?;
        let lib: MaterialLibrary = from_ron_bytes(&input.name, &input.bytes)?;
        match &cli.band {
            _ if lib.materials.iter().all(|m| m.spectral.is_none()) => lib,
            TraceBand::Band(arg) => spectral_materials::band_library(
                &lib,
                &arg.load()?,
                &input.name,
                &String::from_utf8_lossy(&input.bytes),
            )?,
            TraceBand::Total => {
                return Err(irsig_cli::usage_error(format!(
                    "`{}` has spectral materials, which the `total` band (the whole \
                     spectrum) cannot average: give --band",
                    cli.materials
                )));
            }
        }
    };
    // A facet whose material the library lacks, at its place in the scene file.
    if let Some((i, f)) = scene
        .facets
        .iter()
        .enumerate()
        .find(|(_, f)| materials.by_id(f.material).is_none())
    {
        return Err(miette::Report::new(
            irsig_formats::canonical::raw_scene_error_at_path(
                &scene_input.name,
                &scene_input.bytes,
                &scene,
                &format!("facets[{i}].material"),
                format!(
                    "facets[{i}] uses material {}, which the material library {} does not define",
                    f.material.0, cli.materials
                ),
            ),
        ));
    }
    drop(scene_input);
    hash_field(&mut run, "materials", format!("{materials:?}").as_bytes());
    let job = read_job(&cli)?;
    let uncertainties = match &cli.uncertainties {
        Some(path) => Some(read_uncertainties(path, &materials, &scene.objects)?),
        None => None,
    };
    // The budget's layers are pixels of the truth EXR: tiles of other uncertainties differ.
    if let Some(u) = &uncertainties {
        hash_field(&mut run, "uncertainties", format!("{u:?}").as_bytes());
    }
    let mut inputs = Inputs {
        scene: Mutex::new(Some(scene)),
        materials,
        job,
        uncertainties,
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(cli.threads.unwrap_or(0))
        .build()
        .into_diagnostic()?;
    match &cli.band {
        TraceBand::Total => {
            hash_field(&mut run, "band", format!("{TotalRadiance:?}").as_bytes());
            inputs.job.run = run;
            pool.install(|| with_atmosphere(&cli, &inputs, TotalRadiance, None))
        }
        TraceBand::Band(arg) => {
            let band = arg.load()?;
            hash_field(&mut run, "band", format!("{band:?}").as_bytes());
            inputs.job.run = run;
            let split = Split::of(&band);
            pool.install(|| with_atmosphere(&cli, &inputs, band.clone(), Some(&split)))
        }
    }
}

/// The first words of every run hash: a new rule for what the hash covers gets a new
/// version, so that tiles of the two rules never merge.
const RUN_HASH_VERSION: &[u8] = b"irsig-trace run 1\n";

/// Feeds one named input into a run hash, its length first, so that no two different
/// sequences of inputs hash alike.
fn hash_field(run: &mut Sha256, name: &str, bytes: &[u8]) {
    run.update(name.as_bytes());
    run.update((bytes.len() as u64).to_le_bytes());
    run.update(bytes);
}

/// The run of one frame, as its EXRs name it (`irsig.run`): the hash of the inputs (scene
/// bytes, materials, band, atmosphere), the view and the settings the pixels are rendered
/// with; not the outputs, the tile, the thread count or the digital-count flags, which
/// change no pixel. A frame traced whole and every tile of it name the same run.
fn frame_run(run: &Sha256, view: &View, settings: &Settings) -> String {
    let sub_bands = settings.sub_bands;
    let mut h = run.clone();
    hash_field(&mut h, "view", format!("{view:?}").as_bytes());
    let options = TraceOptions {
        truth: true,
        ..settings.options
    };
    let mut settings = format!("{options:?} {:?} {:?}", settings.kind, settings.path_terms);
    if !sub_bands.is_band() {
        settings.push_str(&format!(" sub-bands {sub_bands}"));
    }
    hash_field(&mut h, "settings", settings.as_bytes());
    let digest = h.finalize();
    let mut hex = String::with_capacity(7 + 64);
    hex.push_str("sha256:");
    for b in digest {
        hex.push_str(&format!("{b:02x}"));
    }
    hex
}

/// The declared uncertainties (canonical RON), checked against the material library: an
/// emissivity ± that would leave [0, 1] is an error at its line and column.
fn read_uncertainties(
    path: &str,
    materials: &MaterialLibrary,
    objects: &[String],
) -> miette::Result<Uncertainties> {
    let input = irsig_cli::read_input(path)?;
    let text = irsig_formats::canonical::utf8(&input.name, &input.bytes)?;
    let u: Uncertainties = from_ron_bytes(&input.name, &input.bytes)?;
    // An object the raw scene does not have (a misspelt name) would select no facet and
    // silently declare nothing.
    for (i, t) in u.temperature.iter().enumerate() {
        if let irsig_model::uncertainty::Facets::Object(name) = &t.facets {
            if !objects.iter().any(|o| o == name) {
                return Err(miette::Report::new(
                    irsig_formats::canonical::error_at_path(
                        &input.name,
                        text,
                        &format!("temperature[{i}].facets"),
                        format!(
                            "invalid uncertainties file: `temperature[{i}].facets`: the raw scene \
                         has no object `{name}`; its objects include {}",
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
    }
    u.check_emissivity(|id| {
        let m = materials.materials.iter().find(|m| m.id == id)?;
        let normal = m.emissivity.first().map(|r| r.1)?;
        let most = m.emissivity.iter().map(|r| r.1).fold(0.0, f64::max);
        Some((normal, most))
    })
    .map_err(|e| {
        irsig_formats::canonical::error_at_path(
            &input.name,
            text,
            &e.path,
            format!("invalid uncertainties file: `{}`: {}", e.path, e.kind),
        )
    })?;
    Ok(u)
}

/// The atmosphere `--atmosphere` names, in band or spectral form.
#[allow(clippy::large_enum_variant)] // one per run
enum AirData {
    Band(irsig_model::Atmosphere),
    /// A spectral atmosphere and the bytes it was read from (what the run hash covers).
    Spectral(SpectralAtmosphere, Vec<u8>),
}

/// A sub-band count's sub-bands: their band models and collapsed atmospheres.
type Collapsed = std::sync::Arc<Vec<(Band, irsig_model::Atmosphere)>>;

/// The atmosphere `--atmosphere` names: a built-in (in spectral form when `spectral`), else
/// a file, spectral or not by its content.
fn read_atmosphere(name: &str, spectral: bool) -> miette::Result<AirData> {
    if irsig_atmosphere::BUILTIN_NAMES.contains(&name) {
        if spectral {
            let a = irsig_atmosphere::builtin_spectral(name).map_err(|e| miette!("{e}"))?;
            let bytes = irsig_atmosphere::builtin_spectral_bytes(name).unwrap_or_default();
            return Ok(AirData::Spectral(a, bytes.to_vec()));
        }
        return irsig_atmosphere::builtin(name)
            .map(AirData::Band)
            .map_err(|e| miette!("{e}"));
    }
    if !Path::new(name).exists() {
        return Err(irsig_cli::usage_error(format!(
            "--atmosphere `{name}`: no built-in atmosphere or file of that name; built-ins \
             are: {}, or `none` for a vacuum",
            irsig_atmosphere::BUILTIN_NAMES.join(", ")
        )));
    }
    let input = irsig_cli::read_input(name)?;
    if irsig_formats::canonical::binary_spectral::is_binary(&input.bytes) {
        let a = irsig_formats::canonical::read_spectral_atmosphere(&input.name, &input.bytes)?;
        return Ok(AirData::Spectral(a, input.bytes));
    }
    match from_ron_bytes::<irsig_model::Atmosphere>(&input.name, &input.bytes) {
        Ok(a) => Ok(AirData::Band(a)),
        Err(band_error) => {
            // A spectral atmosphere in RON has a spectral grid; a band one has none.
            let text = irsig_formats::canonical::utf8(&input.name, &input.bytes)?;
            if text.contains("grid") {
                let a = from_ron_bytes::<SpectralAtmosphere>(&input.name, &input.bytes)?;
                Ok(AirData::Spectral(a, input.bytes))
            } else {
                Err(band_error.into())
            }
        }
    }
}

/// The reference temperature of the sub-bands' equal shares, K: about the scenes'
/// (earth-ambient) temperatures, where the band's radiance is what the sensor sees.
const SHARE_REFERENCE_K: f64 = 300.0;

/// How the band divides into sub-bands: its range, a sub-band's band model, and its
/// response (the weight of [`irsig_atmosphere::collapse`]).
struct Split<'a> {
    range_um: [f64; 2],
    response: Option<&'a irsig_radiometry::SensorResponse>,
}

impl<'a> Split<'a> {
    fn of(band: &'a Band) -> Self {
        Self {
            range_um: [band.lambda_min_um(), band.lambda_max_um()],
            response: band.response(),
        }
    }

    /// The band model of `[a, b]` µm with the band's response; `None` where the response
    /// is 0 throughout.
    fn sub_band(&self, a: f64, b: f64) -> miette::Result<Option<Band>> {
        let flat = Band::new(a, b).map_err(|e| miette!("sub-band {a}-{b} um: {e}"))?;
        match self.response {
            None => Ok(Some(flat)),
            Some(r) => Ok(flat.with_response(r).ok()),
        }
    }

    fn weight(&self, wavelength_um: f64) -> f64 {
        self.response.map_or(1.0, |r| r.at(wavelength_um))
    }

    /// The sub-bands of `count`: their edges and band models (those the response
    /// reaches), each with the atmosphere collapsed over it.
    fn collapse(
        &self,
        spectral: &SpectralAtmosphere,
        count: SubBandCount,
    ) -> miette::Result<Vec<(Band, irsig_model::Atmosphere)>> {
        let [lo, hi] = self.range_um;
        let share = |a: f64, b: f64| match self.sub_band(a, b) {
            Ok(Some(band)) => band.radiance(SHARE_REFERENCE_K),
            Ok(None) => 0.0,
            Err(_) => f64::NAN,
        };
        let edges = irsig_atmosphere::sub_band_edges(&spectral.grid, lo, hi, count, share)
            .map_err(|e| irsig_cli::usage_error(format!("--sub-bands {count}: {e}")))?;
        let collapser = irsig_atmosphere::Collapser::new(spectral).map_err(|e| miette!("{e}"))?;
        edges
            .par_windows(2)
            .map(|w| {
                let Some(band) = self.sub_band(w[0], w[1])? else {
                    return Ok(None);
                };
                let at = |e: irsig_atmosphere::AtmosphereError| {
                    miette!("sub-band {}-{} um: {e}", w[0], w[1])
                };
                let mut atmosphere = collapser
                    .collapse(w[0], w[1], |l| self.weight(l))
                    .map_err(at)?;
                if !count.is_band() {
                    // τ as the target sees it: weighted by the blackbody at the reference
                    // temperature, so that τ times the sub-band's L_T is ∫ τ B dλ across
                    // the sub-band (without it the full grid reads up to 0.024 K warm in
                    // a tropical atmosphere; docs/accuracy.md). Radiances keep the
                    // response alone.
                    let seen = collapser
                        .collapse(w[0], w[1], |l| {
                            self.weight(l) * spectral_radiance_per_um(l, SHARE_REFERENCE_K)
                        })
                        .map_err(at)?;
                    with_transmission(&mut atmosphere, &seen);
                }
                Ok(Some((band, atmosphere)))
            })
            .filter_map(Result::transpose)
            .collect()
    }
}

/// `atmosphere` with the transmittances of `seen`, the same atmosphere collapsed with
/// another weight: the profile's, the `.cor` fit's and the slant tables'.
fn with_transmission(atmosphere: &mut irsig_model::Atmosphere, seen: &irsig_model::Atmosphere) {
    for (level, s) in atmosphere.levels.iter_mut().zip(&seen.levels) {
        level.transmission = s.transmission;
    }
    atmosphere.transmission_correction = seen.transmission_correction;
    if let (Some(slant), Some(s)) = (atmosphere.slant.as_mut(), seen.slant.as_ref()) {
        slant.transmission.clone_from(&s.transmission);
    }
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
}

/// The sub-bands of a model kind and a count.
type SubBandsOf<'a, R, T> =
    Box<dyn Fn(ModelKind, SubBandCount) -> miette::Result<Vec<SubBand<R, T>>> + 'a>;

/// What a run reads besides the band and the atmosphere.
struct Inputs {
    /// Taken by `trace_all`, which drops it once the tracer is built unless the error
    /// budget reads it (its facets' temperatures and emissivities): at 1M facets it is
    /// 44 MB that a frame's outputs need not share memory with.
    scene: Mutex<Option<RawScene>>,
    materials: MaterialLibrary,
    job: Job,
    uncertainties: Option<Uncertainties>,
}

/// A band model that sub-bands of a band can be: [`Band`], not the whole spectrum.
trait SubBandModel: BandModel + Clone {
    fn of_band(band: &Band) -> miette::Result<Self>;
}

impl SubBandModel for Band {
    fn of_band(band: &Band) -> miette::Result<Self> {
        Ok(band.clone())
    }
}

impl SubBandModel for TotalRadiance {
    fn of_band(_: &Band) -> miette::Result<Self> {
        Err(irsig_cli::usage_error(
            "the `total` band (the whole spectrum) has no sub-bands",
        ))
    }
}

/// A spectral atmosphere file must cover the band: else an error at its grid (`grid.points`,
/// in the RON or in the binary form's RON header), before anything is traced.
fn check_spectral_range(
    name: &str,
    a: &SpectralAtmosphere,
    bytes: &[u8],
    [lo, hi]: [f64; 2],
) -> miette::Result<()> {
    let wavelengths = a.grid.points.iter().map(|&p| match a.grid.axis {
        irsig_model::SpectralAxis::WavenumberPerCm => 1e4 / p,
        irsig_model::SpectralAxis::WavelengthUm => p,
    });
    let (min, max) = wavelengths.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), w| {
        (lo.min(w), hi.max(w))
    });
    let slack = 1e-9 * max;
    if lo >= min - slack && hi <= max + slack {
        return Ok(());
    }
    let message = format!(
        "the band {lo}-{hi} um reaches outside this atmosphere's spectral grid, {min:.6}-{max:.6} \
         um: trace a band inside the grid, or build the atmosphere over the band"
    );
    let file = if name == "-" { "<stdin>" } else { name };
    let e = if irsig_formats::canonical::binary_spectral::is_binary(bytes) {
        // The header's RON starts at byte 16.
        let header_len = bytes
            .get(12..16)
            .map_or(0, |b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize);
        let header = bytes
            .get(16..16 + header_len)
            .map(String::from_utf8_lossy)
            .unwrap_or_default();
        let (start, _) = irsig_formats::ron_tree::locate(&header, "grid.points");
        irsig_formats::ParseError::in_binary(file, 16 + start, message)
    } else {
        irsig_formats::canonical::error_at_path(
            file,
            &String::from_utf8_lossy(bytes),
            "grid.points",
            message,
        )
    };
    Err(miette::Report::new(e))
}

/// The error of sub-bands asked of an atmosphere without spectra.
fn no_spectra(name: &str, count: SubBandCount) -> miette::Report {
    irsig_cli::usage_error(format!(
        "--sub-bands {count}: the atmosphere `{name}` has no spectra; sub-bands need a \
         spectral atmosphere (a built-in, or a file irsig-atmos build wrote), and the \
         `total` band has none"
    ))
}

/// One sub-band, the whole band, for the band model.
fn whole<R: Clone, T>(
    band: &R,
    name: &str,
    count: SubBandCount,
    atmosphere: impl FnOnce() -> miette::Result<T>,
) -> miette::Result<Vec<SubBand<R, T>>> {
    if !count.is_band() {
        return Err(no_spectra(name, count));
    }
    Ok(vec![SubBand {
        band: band.clone(),
        atmosphere: atmosphere()?,
        emissivity: None,
    }])
}

#[allow(clippy::too_many_lines)]
fn with_atmosphere<R: SubBandModel>(
    cli: &Cli,
    inputs: &Inputs,
    band: R,
    split: Option<&Split<'_>>,
) -> miette::Result<()> {
    let job = &inputs.job;
    let top_scene = inputs
        .scene
        .lock()
        .map_err(|_| miette!("the raw scene's lock is poisoned"))?
        .as_ref()
        .ok_or_else(|| miette!("the raw scene was already traced"))?
        .positions_m
        .iter()
        .map(|p| p[2])
        .fold(0.0_f64, f64::max);
    let mut run = job.run.clone();
    if cli.atmosphere == "none" {
        let vacuum = Vacuum {
            sky_radiance_w_m2_sr: cli.sky_radiance,
        };
        hash_field(&mut run, "atmosphere", format!("{vacuum:?}").as_bytes());
        let (b1, b2) = (band.clone(), band.clone());
        let air = Air {
            kinds: None,
            spectral: false,
            precomputed: Box::new(move |_, count| whole(&b1, "none", count, || Ok(vacuum))),
            pilot: Box::new(move |_, count| whole(&b2, "none", count, || Ok(vacuum))),
        };
        return trace_all(cli, inputs, &run, band, &air);
    }
    // A built-in is read in spectral form when sub-bands may be asked for.
    let wants_spectra = split.is_some()
        && (cli.sub_bands.is_some_and(|c| !c.is_band())
            || cli.tolerance.is_some()
            || cli.decision.is_some());
    let mut data = read_atmosphere(&cli.atmosphere, wants_spectra)?;
    // A built-in's band tables are for the flat band they were made for (8-14 um): any
    // other band, or a sensor response, collapses its spectra instead (else the band model
    // would add the flat band's path and sky radiance to a response-weighted emission).
    if let (AirData::Band(a), Some(sp)) = (&data, &split) {
        let other_band = sp.response.is_some()
            || sp
                .range_um
                .iter()
                .zip(a.band_um)
                .any(|(x, y)| (x - y).abs() > 1e-9 * y);
        if other_band && irsig_atmosphere::BUILTIN_NAMES.contains(&cli.atmosphere.as_str()) {
            data = read_atmosphere(&cli.atmosphere, true)?;
        } else if other_band {
            eprintln!(
                "irsig-trace: warning: `{}` holds band tables for {}-{} um, flat; the band \
                 traced is {}-{} um{}: its path and sky radiances are the tables' band's",
                cli.atmosphere,
                a.band_um[0],
                a.band_um[1],
                sp.range_um[0],
                sp.range_um[1],
                if sp.response.is_some() {
                    " with a sensor response"
                } else {
                    ""
                }
            );
        }
    }
    if let (AirData::Spectral(a, bytes), Some(sp)) = (&data, &split)
        && (cli.atmosphere == "-" || Path::new(&cli.atmosphere).exists())
    {
        check_spectral_range(&cli.atmosphere, a, bytes, sp.range_um)?;
    }
    // The sky is precomputed up to the highest sensor or scene point.
    let top = job
        .views
        .iter()
        .map(|v| v.position_m()[2])
        .fold(top_scene, f64::max);
    // The sky's precomputed levels depend on the top: so do the pixels.
    match &data {
        AirData::Band(atmosphere) => hash_field(
            &mut run,
            "atmosphere",
            format!("{atmosphere:?} top {:x}", top.to_bits()).as_bytes(),
        ),
        AirData::Spectral(_, bytes) => {
            hash_field(&mut run, "spectral atmosphere", bytes);
            hash_field(&mut run, "top", &top.to_bits().to_le_bytes());
        }
    }
    if cli.band == TraceBand::Total {
        let band_um = match &data {
            AirData::Band(a) => format!("{:?}", a.band_um),
            AirData::Spectral(..) => "its spectral range".to_owned(),
        };
        eprintln!(
            "irsig-trace: warning: the `total` band (whole spectrum) is combined with `{}`, \
             whose tables cover {band_um} um: facet radiances and path terms are in different \
             bands; use this only to check the geometry and the event logic",
            cli.atmosphere
        );
    }
    let name = cli.atmosphere.clone();
    let model = move |atmosphere: &irsig_model::Atmosphere, kind: ModelKind| {
        AtmosphereModel::new(atmosphere, kind)
            .map_err(|e| miette!("{e}"))
            .wrap_err_with(|| format!("cannot build the {kind} model of `{name}`"))
    };
    let warned = std::sync::Once::new();
    let precompute = move |model: AtmosphereModel| {
        let air = PrecomputedAtmosphere::new(model, top);
        warned.call_once(|| {
            for w in air.warnings() {
                eprintln!("irsig-trace: warning: {}: {w}", cli.atmosphere);
            }
        });
        air
    };
    match data {
        AirData::Band(atmosphere) => {
            let kinds: Vec<ModelKind> = [ModelKind::Table, ModelKind::Layered, ModelKind::Thesis]
                .into_iter()
                .filter(|&k| AtmosphereModel::new(&atmosphere, k).is_ok())
                .collect();
            let (a1, a2) = (atmosphere.clone(), atmosphere);
            let (m1, m2) = (model.clone(), model);
            let (b1, b2) = (band.clone(), band.clone());
            let air = Air {
                kinds: Some(kinds),
                spectral: false,
                precomputed: Box::new(move |kind, count| {
                    whole(&b1, &cli.atmosphere, count, || {
                        Ok(precompute(m1(&a1, kind)?))
                    })
                }),
                pilot: Box::new(move |kind, count| {
                    whole(&b2, &cli.atmosphere, count, || {
                        Ok(PrecomputedAtmosphere::new(m2(&a2, kind)?, top))
                    })
                }),
            };
            trace_all(cli, inputs, &run, band, &air)
        }
        AirData::Spectral(spectral, _) => {
            let Some(split) = split else {
                return Err(no_spectra(&cli.atmosphere, SubBandCount::Full));
            };
            // Each count's collapsed sub-bands, made once.
            let cache: std::sync::Mutex<std::collections::HashMap<SubBandCount, Collapsed>> =
                std::sync::Mutex::default();
            let collapsed = |count: SubBandCount| -> miette::Result<Collapsed> {
                if let Some(c) = cache.lock().map_err(|_| miette!("poisoned"))?.get(&count) {
                    return Ok(c.clone());
                }
                let c = std::sync::Arc::new(split.collapse(&spectral, count)?);
                cache
                    .lock()
                    .map_err(|_| miette!("poisoned"))?
                    .insert(count, c.clone());
                Ok(c)
            };
            let one = collapsed(SubBandCount::BAND)?;
            let kinds: Vec<ModelKind> = [ModelKind::Table, ModelKind::Layered, ModelKind::Thesis]
                .into_iter()
                .filter(|&k| one.iter().all(|(_, a)| AtmosphereModel::new(a, k).is_ok()))
                .collect();
            let collapsed = &collapsed;
            // The pilot evaluates its paths in every sub-band: the precomputed sky costs a
            // few ms per sub-band (table model) and saves a slant integration per ray, so
            // the pilot's sets are precomputed too (`S` = `A`), its sub-band sets on
            // PILOT_SKY_LEVELS altitudes (the full grid's 108 skies were most of its cost).
            let sub_bands = move |kind: ModelKind, count: SubBandCount, pilot: bool| {
                collapsed(count)?
                    .iter()
                    .map(|(b, a)| {
                        let m = model(a, kind)?;
                        Ok(SubBand {
                            band: R::of_band(b)?,
                            atmosphere: if pilot && !count.is_band() {
                                PrecomputedAtmosphere::with_levels(m, top, PILOT_SKY_LEVELS)
                            } else {
                                precompute(m)
                            },
                            emissivity: spectral_materials::sub_band_tables(&inputs.materials, b)?,
                        })
                    })
                    .collect()
            };
            let sub_bands = &sub_bands;
            let air = Air {
                kinds: Some(kinds),
                spectral: true,
                precomputed: Box::new(move |kind, count| sub_bands(kind, count, false)),
                pilot: Box::new(move |kind, count| sub_bands(kind, count, true)),
            };
            trace_all(cli, inputs, &run, band, &air)
        }
    }
}

/// What a frame is rendered with: the options, the atmosphere model, the path terms and
/// the sub-bands.
#[derive(Debug, Clone, Copy)]
struct Settings {
    options: TraceOptions,
    kind: ModelKind,
    path_terms: PathTermsMode,
    sub_bands: SubBandCount,
}

impl Settings {
    /// The settings of the command line (or their defaults).
    fn from_cli(cli: &Cli) -> Self {
        Self {
            options: TraceOptions {
                specular_bounces: cli.bounces.unwrap_or(1),
                sky_view_rays: cli.sky_view_rays.unwrap_or(0),
                supersampling: cli.supersample.unwrap_or(1),
                adaptive_threshold_k: cli.adaptive_supersampling,
                seed: cli.seed,
                truth: true,
            },
            kind: cli.atmosphere_model.unwrap_or(ModelKind::Table),
            path_terms: cli.path_terms.unwrap_or_default(),
            sub_bands: cli.sub_bands.unwrap_or(SubBandCount::BAND),
        }
    }

    /// These settings with a decision's choices applied; a choice that is not a setting of
    /// its model, or puts an option out of range, is returned with its index.
    fn with_decision(mut self, d: &Decision) -> Result<Self, (usize, String)> {
        for (i, c) in d.choices.iter().enumerate() {
            let bad = || {
                (
                    i,
                    format!(
                        "the decision's {}={} is not a setting of that model",
                        c.model, c.setting
                    ),
                )
            };
            match c.model {
                SwitchableModel::Atmosphere => {
                    self.kind = c.setting.parse().map_err(|_| bad())?;
                }
                SwitchableModel::Bounces => {
                    self.options.specular_bounces = c.setting.parse().map_err(|_| bad())?;
                }
                SwitchableModel::SkyView => {
                    self.options.sky_view_rays = c.setting.parse().map_err(|_| bad())?;
                }
                SwitchableModel::Supersampling => {
                    let (n, adaptive) = match tolerance::parse_supersample(&c.setting) {
                        Some(Supersample::Every(n)) => (n, None),
                        Some(Supersample::Adaptive(n)) => (n, Some(d.tolerance_k)),
                        None => return Err(bad()),
                    };
                    self.options.supersampling = n;
                    self.options.adaptive_threshold_k = adaptive;
                }
                SwitchableModel::PathTerms => {
                    self.path_terms = c.setting.parse().map_err(|_| bad())?;
                }
                SwitchableModel::SubBands => {
                    self.sub_bands = c.setting.parse().map_err(|_| bad())?;
                }
            }
            self.options
                .validate()
                .map_err(|e| (i, format!("the decision's {}={}: {e}", c.model, c.setting)))?;
        }
        Ok(self)
    }
}

/// Altitude levels of the sky in the pilot's sub-band sets (a rendering's have
/// [`irsig_atmosphere::SKY_LEVELS`]). Interpolating linearly in altitude commutes with
/// summing sub-bands, so coarser levels change every count's sky alike and leave the
/// sub-band error the pilot measures: on the quickstart and the thesis experiment its
/// choices and errors are those of 33 levels (docs/accuracy.md).
const PILOT_SKY_LEVELS: usize = 5;

/// Unit costs of the atmosphere models for the pilot's cost model, ns (BENCHMARKS.md):
/// one `path` call, and precomputing the sky of one sub-band up to a few km.
fn atmosphere_costs(kind: ModelKind) -> (f64, f64) {
    match kind {
        ModelKind::Table => (880.0, 5e6),
        ModelKind::Layered => (830.0, 88e6),
        ModelKind::Thesis => (92.0, 121e6),
        ModelKind::None => (5.0, 0.0),
    }
}

/// The pilot's decision for `camera`'s frame.
fn decide<R: BandModel + Clone, A: Atmosphere, S: Atmosphere>(
    cli: &Cli,
    tracer: &Tracer<R, A>,
    materials: &MaterialLibrary,
    air: &Air<'_, R, A, S>,
    camera: &Camera,
    tolerance_k: f64,
) -> miette::Result<Decision> {
    let mut offer = tolerance::offer(materials, air.kinds.as_deref(), air.spectral, &cli.pin)
        .map_err(irsig_cli::usage_error)?;
    let (Some(&ref_kind), Some(&ref_count)) = (offer.atmospheres.first(), offer.sub_bands.first())
    else {
        return Err(miette!(
            "the pilot has no atmosphere or sub-band count to offer"
        ));
    };
    // A count the band's grid cannot make (more sub-bands than grid intervals in a narrow
    // band) is not on offer, unless it is the one pinned.
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
    for (kind, count) in pairs {
        let (atmosphere, sub_bands) = (kind.name().to_owned(), count.to_string());
        if bands
            .iter()
            .any(|b| b.atmosphere == atmosphere && b.sub_bands == sub_bands)
        {
            continue;
        }
        let sub = match (air.pilot)(kind, count) {
            Ok(sub) => sub,
            Err(e) if count == ref_count || count.is_band() || pinned_count => return Err(e),
            Err(_) => {
                unavailable.push(count);
                continue;
            }
        };
        let set = tracer.band_set(sub).map_err(|e| miette!("{e}"))?;
        let (path_call_ns, sky_ns) = atmosphere_costs(kind);
        bands.push(BandChoice {
            atmosphere,
            sub_bands,
            set,
            path_call_ns,
            sky_ns,
        });
    }
    offer.sub_bands.retain(|c| !unavailable.contains(c));
    let space = PilotSpace {
        bands,
        atmospheres: offer
            .atmospheres
            .iter()
            .map(|k| k.name().to_owned())
            .collect(),
        sub_bands: offer.sub_bands.iter().map(ToString::to_string).collect(),
        bounces: offer.bounces,
        sky_view_rays: offer.sky_view_rays,
        supersampling: offer.supersampling,
        path_terms: offer.path_terms,
        reasons: offer.reasons,
        pinned: offer.pinned,
    };
    // About one pixel in 192 (1024 at 512 x 384), at least 1024 (every pixel of a smaller
    // image) and at most 4096: a thin population of pixels (edges, a small hot object) of
    // 1 % needs several hundred samples to be seen at all.
    let pixels =
        (u64::from(camera.pixels[0]) * u64::from(camera.pixels[1]) / 192).clamp(1024, 4096);
    let decision = tracer
        .pilot(
            camera,
            &space,
            tolerance_k,
            cli.tolerance_percentile,
            pixels as u32,
            cli.seed,
        )
        .map_err(|e| irsig_cli::usage_error(e.to_string()))?;
    eprint!("{}", tolerance::table(&decision));
    // What the pilot cost, for comparing with the rendering it chose (the decision file
    // holds no time: it must be the same on every run).
    eprintln!(
        "  pilot: {} pixels in {:.3} s",
        decision.pilot_pixels,
        started.elapsed().as_secs_f64()
    );
    Ok(decision)
}

#[allow(clippy::too_many_lines)]
fn trace_all<R: BandModel + Clone, A: Atmosphere, S: Atmosphere>(
    cli: &Cli,
    inputs: &Inputs,
    run: &Sha256,
    band: R,
    air: &Air<'_, R, A, S>,
) -> miette::Result<()> {
    let Inputs {
        scene: _,
        materials,
        job,
        uncertainties,
    } = inputs;
    let uncertainties = uncertainties.as_ref();
    let scene = inputs
        .scene
        .lock()
        .map_err(|_| miette!("the raw scene's lock is poisoned"))?
        .take()
        .ok_or_else(|| miette!("the raw scene was already traced"))?;
    let applied = match &cli.decision {
        Some(path) => {
            let input = irsig_cli::read_input(path)?;
            let d: Decision = from_ron_bytes(&input.name, &input.bytes)?;
            // Each choice is checked here, where the file's text can point at it.
            if let Err((i, message)) = Settings::from_cli(cli).with_decision(&d) {
                return Err(miette::Report::new(
                    irsig_formats::canonical::error_at_path(
                        &input.name,
                        &String::from_utf8_lossy(&input.bytes),
                        &format!("choices[{i}].setting"),
                        message,
                    ),
                ));
            }
            Some(d)
        }
        None => None,
    };
    let base = match &applied {
        Some(d) => Settings::from_cli(cli)
            .with_decision(d)
            .map_err(|(_, m)| miette!("{m}"))?,
        None => Settings::from_cli(cli),
    };
    let (mut kind, mut count) = (base.kind, base.sub_bands);
    let mut tracer =
        Tracer::with_sub_bands(&scene, materials, band, (air.precomputed)(kind, count)?)
            .map_err(|e| miette!("{e}"))
            .wrap_err_with(|| format!("cannot trace `{}` with `{}`", cli.scene, cli.materials))?
            .with_path_terms(base.path_terms);
    let scene = uncertainties.is_some().then_some(scene);
    let views = &job.views;
    let cameras = views
        .iter()
        .map(|v| Camera::from_view(v).map_err(|e| miette!("{e}")))
        .collect::<miette::Result<Vec<_>>>()?;
    if let Some((column, row)) = cli.probe {
        let cam = &cameras[0];
        let s = tracer
            .probe(cam, &base.options, column, row)
            .map_err(|e| miette!("--probe: {e}"))?;
        let t = tracer.apparent_temperature_k(s.radiance_w_m2_sr);
        let sub_bands = tracer.sub_bands();
        return irsig_cli::write_output(None, |w| {
            writeln!(
                w,
                "pixel ({column}, {row}), view 1, {sub_bands} sub-band(s)"
            )?;
            writeln!(w, "{s}")?;
            writeln!(w, "apparent temperature_k     {t}")
        });
    }
    if cli.output.is_none() && !cli.has_output_flags() && job.outputs.is_none() {
        return Ok(());
    }
    if cli.output.is_none() && job.outputs.is_none() && cameras.len() > 1 {
        return Err(irsig_cli::usage_error(format!(
            "the per-output flags name one file each, but {} views were given: trace one \
             view per run, or use -o PREFIX for numbered outputs",
            cameras.len()
        )));
    }
    let max_id = materials
        .materials
        .iter()
        .map(|m| m.id.0)
        .max()
        .unwrap_or(0);
    let map_fits = max_id <= 15;
    let first_map = job
        .outputs
        .as_ref()
        .and_then(|o| o.first())
        .and_then(|o| o.map_png.as_ref());
    if !map_fits && let Some(path) = cli.map_png.as_ref().or(first_map) {
        return Err(miette!(
            "{}: interaction map not written: material id {max_id} of `{}` does not fit the \
             legacy 4-bit nibble (ids 1 to 15); the truth EXR's material_primary and \
             material_secondary layers hold the same information losslessly",
            path.display(),
            cli.materials
        ));
    }
    // Every view's tile, checked before anything is traced.
    let tiles = cameras
        .iter()
        .map(|c| {
            let [w, h] = c.pixels;
            match cli.tile {
                None => Ok(Tile::whole(w, h)),
                Some(t) => t
                    .of(w, h)
                    .map_err(|e| irsig_cli::usage_error(format!("--tile: {e}"))),
            }
        })
        .collect::<miette::Result<Vec<_>>>()?;
    let outputs: Vec<Outputs> = (0..cameras.len())
        .map(|i| match &job.outputs {
            Some(all) => all.get(i).cloned().unwrap_or_default(),
            None => cli.outputs(i, cameras.len(), map_fits),
        })
        .collect();
    // Every output's place, checked before anything is traced: a fly-by would otherwise
    // fail only when its first frame is written.
    for path in outputs
        .iter()
        .flat_map(Outputs::paths)
        .chain(&cli.decision_out)
    {
        irsig_cli::check_output(path)?;
    }
    // Each frame is staged as soon as it is traced (memory and descriptors bounded by one
    // frame); all of them are renamed into place together when every frame succeeded.
    let mut staged = irsig_cli::Staged::new();
    let total_rows: u64 = tiles.iter().map(|t| u64::from(t.height)).sum();
    let bar = irsig_cli::progress_bar(total_rows, "tracing");
    for ((i, cam), out) in cameras.iter().enumerate().zip(outputs) {
        let (settings, model_k) = match cli.tolerance {
            Some(tolerance_k) => {
                let d = decide(cli, &tracer, materials, air, cam, tolerance_k)?;
                let settings = base.with_decision(&d).map_err(|(_, m)| miette!("{m}"))?;
                let decision_file = match &cli.output {
                    Some(_) => out
                        .radiance_exr
                        .as_ref()
                        .map(|p| sibling(p, "radiance.exr", "decision.ron")),
                    None => cli.decision_out.clone(),
                };
                if let Some(path) = decision_file {
                    let text = irsig_formats::canonical::to_ron(&d).into_diagnostic()?;
                    staged.stage(&path, &text.into_bytes())?;
                }
                (settings, d.predicted.percentile_k)
            }
            None => (
                base,
                applied.as_ref().map_or(0.0, |d| d.predicted.percentile_k),
            ),
        };
        let budget = uncertainties.zip(scene.as_ref()).map(|(u, scene)| Budget {
            uncertainties: u,
            scene,
            model_k,
        });
        if settings.kind != kind || settings.sub_bands != count {
            tracer = tracer
                .with_bands((air.precomputed)(settings.kind, settings.sub_bands)?)
                .map_err(|e| miette!("{e}"))?;
            (kind, count) = (settings.kind, settings.sub_bands);
        }
        let images = out.radiance_exr.is_some()
            || out.truth_exr.is_some()
            || out.map_png.is_some()
            || out.dc_png.is_some()
            || out.lut.is_some();
        if !images {
            // Only the pilot's decision was asked for.
            continue;
        }
        tracer = tracer.with_path_terms(settings.path_terms);
        // The per-pixel terms are kept only when an output of this frame reads them.
        let options = TraceOptions {
            truth: out.truth_exr.is_some() || out.map_png.is_some(),
            ..settings.options
        };
        let tile = tiles[i];
        let frame = if cli.tile.is_some() {
            tracer.render_tile(cam, &options, tile, &|n| bar.inc(n))
        } else {
            tracer.render(cam, &options, &|n| bar.inc(n))
        }
        .map_err(|e| miette!("{e}"))?;
        let part = FramePart {
            frame_width: cam.pixels[0] as usize,
            frame_height: cam.pixels[1] as usize,
            x: tile.x as usize,
            y: tile.y as usize,
            run: frame_run(run, &views[i], &settings),
        };
        let radiometry = FrameRadiometry {
            band: tracer.band().clone(),
            sub_bands: tracer.sub_bands(),
            view_gain: views.get(i).and_then(View::gain_dc_per_k),
        };
        let write = |staged: &mut irsig_cli::Staged| {
            write_frame(cli, &radiometry, frame, out, &part, budget.as_ref(), staged)
        };
        if i + 1 == cameras.len() {
            // The last frame's outputs need the band, not the scene: the BVH and the facet
            // records (about 100 bytes a facet) go before the outputs are made, which hold
            // the frame's layers and encoded files (the frame's peak memory was there).
            drop(tracer);
            write(&mut staged)?;
            break;
        }
        write(&mut staged)?;
    }
    bar.finish_and_clear();
    if !map_fits && cli.output.is_some() && cli.tile.is_none() {
        eprintln!(
            "irsig-trace: interaction map not written: material id {max_id} does not fit the \
             legacy 4-bit nibble (ids 1 to 15); the truth EXR's material_primary and \
             material_secondary layers hold the same information losslessly"
        );
    }
    staged.commit()
}

/// What a frame's outputs need besides its pixels: the band its radiances are in, how many
/// sub-bands they were summed over, and the view's gain (DC/K) if it has one.
struct FrameRadiometry<R> {
    band: R,
    sub_bands: usize,
    view_gain: Option<f64>,
}

/// Encodes and stages the files `out` names of one traced frame (or tile). The truth EXR
/// comes last: its layers are made from the frame's per-pixel records, which are dropped
/// before the layers are encoded.
fn write_frame<R: BandModel>(
    cli: &Cli,
    radiometry: &FrameRadiometry<R>,
    mut frame: Frame,
    out: Outputs,
    part: &FramePart,
    budget: Option<&Budget<'_>>,
    staged: &mut irsig_cli::Staged,
) -> miette::Result<()> {
    let radiance = frame.radiance_f32();
    let (w, h) = (frame.width as usize, frame.height as usize);
    if let Some(path) = out.map_png {
        staged.stage(&path, &interaction_map(&frame)?)?;
    }
    if out.dc_png.is_some() || out.lut.is_some() {
        let band = &radiometry.band;
        let q = cli
            .dc
            .tracer_quantiser(radiometry.view_gain, &radiance, band)?;
        if let Some(path) = out.dc_png {
            let counts = q
                .quantise(&radiance, w)
                .map_err(|e| miette!("digital counts: {e}"))?;
            staged.stage(
                &path,
                &counts_png(&counts, w, h, cli.dc.dc_bits).into_diagnostic()?,
            )?;
        }
        if let Some(path) = out.lut {
            staged.stage(&path, &q.lut(band).to_string().into_bytes())?;
        }
    }
    if let Some(path) = out.radiance_exr {
        let mut r = Raster::new(w, h).with_part(part.clone());
        push(&mut r, Layer::Radiance, radiance)?;
        staged.stage(&path, &into_exr_bytes(r).into_diagnostic()?)?;
    }
    if let Some(path) = out.truth_exr {
        let r = truth_raster(radiometry, &frame, budget)?.with_part(part.clone());
        frame.truth = Vec::new();
        staged.stage(&path, &into_exr_bytes(r).into_diagnostic()?)?;
    }
    Ok(())
}

/// `path` with its `suffix` replaced by `with` (`f.0001.radiance.exr` → `f.0001.decision.ron`).
fn sibling(path: &Path, suffix: &str, with: &str) -> PathBuf {
    let s = path.to_string_lossy();
    PathBuf::from(match s.strip_suffix(suffix) {
        Some(stem) => format!("{stem}{with}"),
        None => format!("{s}.{with}"),
    })
}

fn numbered(prefix: &Path, n: usize) -> PathBuf {
    let mut s = prefix.as_os_str().to_owned();
    s.push(format!(".{n:04}"));
    PathBuf::from(s)
}

fn with_suffix(stem: &Path, suffix: &str) -> PathBuf {
    let mut s = stem.as_os_str().to_owned();
    s.push(".");
    s.push(suffix);
    PathBuf::from(s)
}

fn push(raster: &mut Raster, layer: Layer, data: Vec<f32>) -> miette::Result<()> {
    raster
        .push_layer(layer.name(), layer.unit(), data)
        .into_diagnostic()
}

/// The truth layers (`irsig_model::truth::Layer::TRUTH`, in order): the terms of each
/// pixel's centre ray, and the apparent temperature of its radiance. NaN where a term does
/// not apply (no facet hit).
fn truth_raster<R: BandModel>(
    radiometry: &FrameRadiometry<R>,
    frame: &Frame,
    budget: Option<&Budget<'_>>,
) -> miette::Result<Raster> {
    let mut r = Raster::new(frame.width as usize, frame.height as usize);
    // The tracer's table, the same for a frame and its tiles.
    let inverse = irsig_tracer::inverse_table(&radiometry.band);
    let apparent: Vec<f64> = frame
        .radiance_w_m2_sr
        .par_chunks(4096)
        .flat_map_iter(|run| inverse.temperatures(run.iter().copied()))
        .collect();
    // The layers in parallel, each one pass over the pixels.
    let layers: Vec<miette::Result<Vec<f32>>> = Layer::TRUTH
        .par_iter()
        .map(|&layer| match frame.truth_layer(layer) {
            Some(data) => Ok(data),
            None if layer == Layer::ApparentTemperature => {
                Ok(apparent.iter().map(|&t| t as f32).collect())
            }
            None if layer == Layer::SubBands => {
                Ok(vec![radiometry.sub_bands as f32; apparent.len()])
            }
            None => Err(miette!("the frame holds no `{layer}` layer")),
        })
        .collect();
    for (layer, data) in Layer::TRUTH.into_iter().zip(layers) {
        push(&mut r, layer, data?)?;
    }
    if let Some(budget) = budget {
        for (layer, data) in budget.layers(&radiometry.band, frame, &apparent) {
            push(&mut r, layer, data)?;
        }
    }
    Ok(r)
}

/// The error budget of a run: the declared uncertainties, the scene they name facets of,
/// and the residual of the models chosen by the tolerance pilot.
struct Budget<'a> {
    uncertainties: &'a Uncertainties,
    scene: &'a RawScene,
    /// The pilot's predicted error at its percentile, K (0 without `--tolerance`).
    model_k: f64,
}

impl Budget<'_> {
    /// The σ layers ([`Layer::BUDGET`]), K: each declared uncertainty propagated to the
    /// apparent temperature through the radiance equation's partial derivatives at the
    /// pixel (`∂L/∂T = Σ τ·ε·dL_T/dT`, `∂L/∂ε = Σ τ·(L_T − L_reflected)`, `∂L/∂τ = L − L_u`
    /// for a relative σ of τ, `L_u` for a relative σ of the path radiance), over the band's
    /// dL/dT at the pixel's apparent temperature; and their root-sum-square.
    fn layers<R: BandModel>(
        &self,
        band: &R,
        frame: &Frame,
        apparent: &[f64],
    ) -> Vec<(Layer, Vec<f32>)> {
        let u = self.uncertainties;
        let per_pixel: Vec<[f64; 5]> = frame
            .truth
            .par_iter()
            .zip(&frame.radiance_w_m2_sr)
            .zip(apparent)
            .map(|((p, &l), &t)| {
                let slope = band.radiance_derivative(t);
                let in_k = |sigma_l: f64| {
                    if slope > 0.0 && sigma_l.is_finite() {
                        sigma_l.abs() / slope
                    } else {
                        0.0
                    }
                };
                let (temperature, emissivity) = match self.scene.facets.get(p.facet as usize) {
                    Some(facet) => {
                        let object = self
                            .scene
                            .objects
                            .get(facet.object as usize)
                            .map_or("", String::as_str);
                        (
                            in_k(
                                f64::from(p.temperature_sensitivity)
                                    * u.temperature_sigma_k(facet.material, object),
                            ),
                            in_k(
                                f64::from(p.emissivity_sensitivity)
                                    * u.emissivity_sigma(facet.material),
                            ),
                        )
                    }
                    None => (0.0, 0.0),
                };
                let path = f64::from(p.path_radiance_w_m2_sr);
                let path = if path.is_finite() { path } else { 0.0 };
                [
                    temperature,
                    emissivity,
                    in_k(u.transmission_relative * (l - path)),
                    in_k(u.path_radiance_relative * path),
                    self.model_k,
                ]
            })
            .collect();
        let mut out: Vec<(Layer, Vec<f32>)> = Layer::BUDGET[..5]
            .iter()
            .enumerate()
            .map(|(k, &layer)| (layer, per_pixel.iter().map(|s| s[k] as f32).collect()))
            .collect();
        out.push((
            Layer::SigmaTotal,
            per_pixel
                .iter()
                .map(|s| s.iter().map(|v| v * v).sum::<f64>().sqrt() as f32)
                .collect(),
        ));
        out
    }
}

/// The 1990 interaction map (thesis §4.2): primary material id in the upper nibble,
/// reflected material id in the lower; 0 where nothing was hit. The caller has checked that
/// every id is at most 15.
fn interaction_map(frame: &Frame) -> miette::Result<Vec<u8>> {
    let data: Vec<u8> = frame
        .truth
        .iter()
        .map(|s| {
            irsig_formats::legacy::map::pixel(s.primary_material, s.secondary_material)
                .ok_or_else(|| miette!("material id above 15 in the interaction map"))
        })
        .collect::<miette::Result<_>>()?;
    let mut bytes = Vec::new();
    write_png_gray8(
        &mut bytes,
        frame.width as usize,
        frame.height as usize,
        &data,
    )
    .into_diagnostic()?;
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pixel_argument_parses_and_rejects_junk() {
        assert_eq!(parse_pixel("128,64"), Ok((128, 64)));
        assert!(parse_pixel("128").is_err());
        assert!(parse_pixel("-1,3").is_err());
    }

    #[test]
    fn numbered_and_suffixed_names() {
        let p = numbered(Path::new("out/f"), 7);
        assert_eq!(
            with_suffix(&p, "truth.exr"),
            PathBuf::from("out/f.0007.truth.exr")
        );
    }

    #[test]
    fn the_band_is_total_or_the_shared_band() {
        assert_eq!("total".parse::<TraceBand>(), Ok(TraceBand::Total));
        assert_eq!(
            "8-14".parse::<TraceBand>(),
            Ok(TraceBand::Band(irsig_cli::args::BandArg::default()))
        );
        assert!("8:14".parse::<TraceBand>().is_err());
    }
}
