//! `irsig-trace`: renders a raw scene through an atmosphere for one or more views and writes,
//! per view, the radiance image (f32 EXR), the truth layers (multi-layer f32 EXR), the
//! legacy interaction map (8-bit nibble PNG) when the material ids fit in four bits, and
//! the digital-count image (8- or 16-bit PNG) with its LUT (quantisation by
//! `irsig-sensor-model`: the thesis's DC/K auto-bias of Figure 14, or a fixed calibration).
//!
//! The tracing is `irsig-tracer`; this crate reads the canonical files, picks the band and
//! the atmosphere, and writes the outputs, all or none of them.
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
//! ```
//!
//! A view file is canonical RON (one view or a list) or a 1990 viewing file, told apart by
//! its first character (`views`); the viewing file's position is in `--view-unit` (km, as
//! in the thesis) and becomes metres on reading. A 1990 execute file sequences viewing
//! files into frames, each writing the map, DC image and LUT it names.
//!
//! `-o PREFIX` writes every output under one prefix; the per-output flags write only the
//! files named, for one view, so that `irsig-run` and Makefiles see each file a stage
//! writes.

mod atmos;
mod views;

use std::io::Cursor;
use std::path::{Path, PathBuf};

use clap::Parser;
use irsig_formats::ParseError;
use irsig_model::{LengthUnit, MaterialLibrary, ModelError, RawScene, View};
use irsig_radiometry::Band;
use irsig_raster::{Raster, exr_bytes, write_png_gray8, write_png_gray16};
use irsig_sensor_model::quantise::{BandConversion, Quantiser};
use irsig_tracer::{
    Atmosphere, Camera, Frame, Radiometry, TotalRadiance, TraceOptions, Tracer, Vacuum,
};
use miette::{IntoDiagnostic, WrapErr, miette};
use serde::de::DeserializeOwned;

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
      to write (paths relative to flyby.exec); the BVH is built once

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
    /// LUT), paths relative to it. Each frame writes its interaction map PNG, its DC image
    /// PNG and its LUT under the names given; the BVH of --scene is built once. Every
    /// frame must name the same scene file: the legacy scene that --scene was flattened
    /// from.
    #[arg(long, value_name = "FILE", conflicts_with_all = [
        "view", "out", "radiance_exr", "truth_exr", "map_png", "dc_png", "lut"
    ])]
    pub execute: Option<String>,
    /// The band in micrometres, `MIN-MAX` (default the thesis's 8-14, flat response), or
    /// `total` for the whole spectrum (σT⁴/π), exact and for checking by hand. Use the band
    /// the atmosphere's tables were integrated over.
    #[arg(long, default_value = "8-14", value_name = "MIN-MAX|total")]
    pub band: String,
    /// The atmosphere: a built-in name (`us-std-1976`, `midlat-winter`, ...), a canonical
    /// atmosphere file (RON), or `none` (a vacuum whose sky has radiance --sky-radiance).
    #[arg(long, default_value = "none", value_name = "NAME|FILE")]
    pub atmosphere: String,
    /// The atmosphere model: `table` (slant-path tables), `layered` (eq. 8-9), `thesis`
    /// (eq. 10-11, the 1990 model) or `none`.
    #[arg(long, default_value = "table", value_parser = ["table", "layered", "thesis", "none"])]
    pub atmosphere_model: String,
    /// Sky radiance for `--atmosphere none`, W m^-2 sr^-1 (0: cold space).
    #[arg(long, default_value_t = 0.0, value_name = "W_M2_SR")]
    pub sky_radiance: f64,
    /// Output path prefix; files are PREFIX.radiance.exr, PREFIX.truth.exr, PREFIX.map.png,
    /// PREFIX.dc.png and PREFIX.lut.txt (PREFIX.NNNN.* for several views). Give this, or
    /// one or more of the per-output flags below, or --probe.
    #[arg(short = 'o', long, value_name = "PREFIX")]
    pub out: Option<PathBuf>,
    /// Write the radiance image (f32 EXR, W m^-2 sr^-1) to FILE. The per-output flags write
    /// only the outputs named, for one view, so that a pipeline or a Makefile sees every
    /// file a stage writes. Any one of them may be `-`, standard output (e.g. piped into
    /// `irsig-sensor -`).
    #[arg(long, value_name = "FILE", conflicts_with = "out")]
    pub radiance_exr: Option<PathBuf>,
    /// Write the truth layers (multi-layer f32 EXR) to FILE.
    #[arg(long, value_name = "FILE", conflicts_with = "out")]
    pub truth_exr: Option<PathBuf>,
    /// Write the legacy interaction map (8-bit nibble PNG) to FILE; an error when a
    /// material id does not fit in four bits.
    #[arg(long, value_name = "FILE", conflicts_with = "out")]
    pub map_png: Option<PathBuf>,
    /// Write the digital-count image (PNG, --dc-bits deep) to FILE.
    #[arg(long, value_name = "FILE", conflicts_with = "out")]
    pub dc_png: Option<PathBuf>,
    /// Write the digital-count LUT (text: DC, radiance, K, degC) to FILE.
    #[arg(long, value_name = "FILE", conflicts_with = "out")]
    pub lut: Option<PathBuf>,
    /// Specular bounces per path (thesis: 1).
    #[arg(long, default_value_t = 1)]
    pub bounces: u32,
    /// Sky-view factor rays per diffuse hit (0: off, F = 1 as in the thesis).
    #[arg(long, default_value_t = 0, value_name = "N")]
    pub sky_view_rays: u32,
    /// Supersampling: N for N x N stratified rays per pixel (1: one ray through the centre).
    #[arg(long, default_value_t = 1, value_name = "N")]
    pub supersample: u32,
    /// Seed for sky-view directions and sub-pixel jitter.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Path terms (τ, L_u) of facet hits: `exact` (one atmosphere call per hit) or
    /// `tabulated` (a per-frame altitude × range table; worst error 15 mK, see
    /// docs/accuracy.md; faster from about 200 × 200 pixels up).
    #[arg(long, default_value = "exact", value_parser = ["exact", "tabulated"])]
    pub path_terms: String,
    /// Print every term of the radiance equation for pixel COLUMN,ROW of the first view and
    /// write no files.
    #[arg(long, value_name = "COLUMN,ROW", value_parser = parse_pixel)]
    pub probe: Option<(u32, u32)>,
    /// Digital-count image: `auto` (thesis Figure 14: DC/K around the scene's mid radiance,
    /// auto-bias), `fixed` (DC/K at --reference-k, whose radiance maps to
    /// --dc-at-reference, the same in every scene) or `none`.
    #[arg(long, default_value = "auto", value_parser = ["auto", "fixed", "none"])]
    pub dc: String,
    /// Gain in digital counts per kelvin (default: the view's gain, else 2).
    #[arg(long, value_name = "DC_PER_K")]
    pub dc_per_k: Option<f64>,
    /// Bits per count of the DC image (8 or 16).
    #[arg(long, default_value_t = 8, value_parser = clap::value_parser!(u8).range(1..=16))]
    pub dc_bits: u8,
    /// Reference temperature of `--dc fixed`, K.
    #[arg(long, default_value_t = 300.0, value_name = "K")]
    pub reference_k: f64,
    /// Count that the reference temperature's radiance maps to in `--dc fixed` (default
    /// mid-scale).
    #[arg(long, value_name = "DC")]
    pub dc_at_reference: Option<f64>,
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
    }

    /// Where each output of frame `index` (from 0) of `frames` goes; `None` for an output
    /// not wanted. With -o PREFIX every output is wanted (the map when the ids fit, the
    /// counts unless `--dc none`); with the per-output flags only those named.
    fn outputs(&self, index: usize, frames: usize, map_fits: bool) -> Outputs {
        match &self.out {
            Some(prefix) => {
                let stem = if frames == 1 {
                    prefix.clone()
                } else {
                    numbered(prefix, index + 1)
                };
                let dc = self.dc != "none";
                Outputs {
                    radiance_exr: Some(with_suffix(&stem, "radiance.exr")),
                    truth_exr: Some(with_suffix(&stem, "truth.exr")),
                    map_png: map_fits.then(|| with_suffix(&stem, "map.png")),
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

fn parse_unit(s: &str) -> Result<LengthUnit, String> {
    s.parse()
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

/// Reads one canonical RON file and validates it.
fn read_canonical<T: DeserializeOwned>(
    path: &str,
    validate: impl Fn(&T) -> Result<(), ModelError>,
) -> miette::Result<T> {
    let input = irsig_cli::read_input(path)?;
    let text = std::str::from_utf8(&input.bytes).map_err(|e| {
        ParseError::in_binary(&input.name, e.valid_up_to(), "expected UTF-8 RON text")
    })?;
    let value: T = ron::from_str(text).map_err(|e| {
        let offset = irsig_formats::offset_of(text, e.span.start.line, e.span.start.col);
        ParseError::at_offset(&input.name, text, offset, e.code.to_string())
    })?;
    validate(&value).map_err(|e| miette!("{}: {e}", input.name))?;
    Ok(value)
}

/// Runs the tool.
///
/// # Errors
/// Bad input (with file, line and column where there is one) or an unwritable output.
pub fn run(cli: Cli) -> miette::Result<()> {
    if cli.probe.is_none() && cli.out.is_none() && !cli.has_output_flags() && cli.execute.is_none()
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
    if cli.dc == "none" && (cli.dc_png.is_some() || cli.lut.is_some()) {
        return Err(irsig_cli::usage_error(
            "--dc-png and --lut need digital counts: drop `--dc none`",
        ));
    }
    if cli.dc == "none" && cli.execute.is_some() {
        return Err(irsig_cli::usage_error(
            "an execute file names each frame's DC image and LUT: drop `--dc none`",
        ));
    }
    if !cli.sky_radiance.is_finite() || cli.sky_radiance < 0.0 {
        return Err(irsig_cli::usage_error(format!(
            "--sky-radiance {} is out of range: expected a finite radiance of 0 or more",
            cli.sky_radiance
        )));
    }
    let scene = {
        let input = irsig_cli::read_input(&cli.scene)?;
        irsig_formats::canonical::read_raw_scene(&input.name, &input.bytes)?
    };
    let materials: MaterialLibrary = read_canonical(&cli.materials, MaterialLibrary::validate)?;
    let (views, outputs) = match &cli.execute {
        Some(path) => {
            let (views, outputs) = views::read_execute(path, cli.view_unit)?;
            (views, Some(outputs))
        }
        None => {
            let mut views = Vec::new();
            for v in &cli.view {
                views.extend(views::read_views(v, cli.view_unit)?);
            }
            (views, None)
        }
    };
    let job = Job {
        views: &views,
        outputs: outputs.as_deref(),
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(cli.threads.unwrap_or(0))
        .build()
        .into_diagnostic()?;
    if cli.band == "total" {
        pool.install(|| with_atmosphere(&cli, &scene, &materials, &job, TotalRadiance))
    } else {
        let band = parse_band(&cli.band)?;
        pool.install(|| with_atmosphere(&cli, &scene, &materials, &job, BandRadiometry(band)))
    }
}

/// `MIN-MAX` in micrometres → a flat-response band.
fn parse_band(text: &str) -> miette::Result<Band> {
    let bad = || {
        irsig_cli::usage_error(format!(
            "--band `{text}`: expected MIN-MAX in micrometres such as 8-14, or `total`"
        ))
    };
    let (a, b) = text.split_once('-').ok_or_else(bad)?;
    let a: f64 = a.trim().parse().map_err(|_| bad())?;
    let b: f64 = b.trim().parse().map_err(|_| bad())?;
    Band::new(a, b).map_err(|e| irsig_cli::usage_error(format!("--band `{text}`: {e}")))
}

/// `irsig_radiometry::Band` as the tracer's band model.
#[derive(Debug)]
struct BandRadiometry(Band);

impl Radiometry for BandRadiometry {
    fn radiance(&self, temperature_k: f64) -> f64 {
        self.0.radiance(temperature_k)
    }
    fn radiance_derivative(&self, temperature_k: f64) -> f64 {
        self.0.radiance_derivative(temperature_k)
    }
    fn temperature(&self, radiance_w_m2_sr: f64) -> f64 {
        self.0.temperature(radiance_w_m2_sr)
    }
}

/// The frames of one run: their views and, from an execute file, the files each writes
/// (`None`: the outputs follow from -o or the per-output flags).
struct Job<'a> {
    views: &'a [View],
    outputs: Option<&'a [Outputs]>,
}

fn with_atmosphere<R: Radiometry>(
    cli: &Cli,
    scene: &RawScene,
    materials: &MaterialLibrary,
    job: &Job<'_>,
    radiometry: R,
) -> miette::Result<()> {
    if cli.atmosphere == "none" {
        let vacuum = Vacuum {
            sky_radiance_w_m2_sr: cli.sky_radiance,
        };
        return trace_all(cli, scene, materials, job, radiometry, vacuum);
    }
    let atmosphere = if irsig_atmosphere::BUILTIN_NAMES.contains(&cli.atmosphere.as_str()) {
        irsig_atmosphere::builtin(&cli.atmosphere).map_err(|e| miette!("{e}"))?
    } else {
        read_canonical(&cli.atmosphere, irsig_model::Atmosphere::validate)?
    };
    let kind: irsig_atmosphere::ModelKind =
        cli.atmosphere_model.parse().map_err(|e| miette!("{e}"))?;
    let model = irsig_atmosphere::AtmosphereModel::new(&atmosphere, kind)
        .map_err(|e| miette!("{e}"))
        .wrap_err_with(|| format!("cannot build the {kind} model of `{}`", cli.atmosphere))?;
    // The sky is precomputed up to the highest sensor or scene point.
    let top = job
        .views
        .iter()
        .map(|v| v.position_m()[2])
        .chain(scene.positions_m.iter().map(|p| p[2]))
        .fold(0.0_f64, f64::max);
    if cli.band == "total" {
        eprintln!(
            "irsig-trace: warning: the `total` band (whole spectrum) is combined with `{}`, \
             whose tables cover {:?} um: facet radiances and path terms are in different \
             bands; use this only to check the geometry and the event logic",
            cli.atmosphere, atmosphere.band_um
        );
    }
    let air = atmos::Precomputed::new(model, top);
    for w in &air.warnings {
        eprintln!("irsig-trace: warning: {}: {w}", cli.atmosphere);
    }
    trace_all(cli, scene, materials, job, radiometry, air)
}

fn trace_all<R: Radiometry, A: Atmosphere>(
    cli: &Cli,
    scene: &RawScene,
    materials: &MaterialLibrary,
    job: &Job<'_>,
    radiometry: R,
    atmosphere: A,
) -> miette::Result<()> {
    let options = TraceOptions {
        specular_bounces: cli.bounces,
        sky_view_rays: cli.sky_view_rays,
        supersampling: cli.supersample,
        seed: cli.seed,
        truth: true,
    };
    let tracer = Tracer::new(scene, materials, radiometry, atmosphere)
        .map_err(|e| miette!("{e}"))
        .wrap_err_with(|| format!("cannot trace `{}` with `{}`", cli.scene, cli.materials))?
        .with_path_terms(if cli.path_terms == "tabulated" {
            irsig_tracer::PathTermsMode::Tabulated
        } else {
            irsig_tracer::PathTermsMode::Exact
        });
    let views = job.views;
    let cameras = views
        .iter()
        .map(|v| Camera::from_view(v).map_err(|e| miette!("{e}")))
        .collect::<miette::Result<Vec<_>>>()?;
    if let Some((column, row)) = cli.probe {
        let cam = &cameras[0];
        let s = tracer
            .probe(cam, &options, column, row)
            .map_err(|e| miette!("--probe: {e}"))?;
        println!("pixel ({column}, {row}), view 1");
        println!("{s}");
        println!(
            "apparent temperature_k     {}",
            tracer.apparent_temperature_k(s.radiance_w_m2_sr)
        );
        return Ok(());
    }
    if cli.out.is_none() && !cli.has_output_flags() && job.outputs.is_none() {
        return Ok(());
    }
    if cli.out.is_none() && job.outputs.is_none() && cameras.len() > 1 {
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
    let mut files = Vec::new();
    let total_rows: u64 = cameras.iter().map(|c| u64::from(c.pixels[1])).sum();
    let bar = irsig_cli::progress_bar(total_rows, "tracing");
    for (i, cam) in cameras.iter().enumerate() {
        let out = match job.outputs {
            Some(all) => all.get(i).cloned().unwrap_or_default(),
            None => cli.outputs(i, cameras.len(), map_fits),
        };
        // The per-pixel terms are kept only when an output of this frame reads them.
        let options = TraceOptions {
            truth: out.truth_exr.is_some() || out.map_png.is_some(),
            ..options
        };
        let frame = tracer
            .render(cam, &options, &|n| bar.inc(n))
            .map_err(|e| miette!("{e}"))?;
        if let Some(path) = out.radiance_exr {
            files.push((
                path,
                exr_bytes(&radiance_raster(&frame)?).into_diagnostic()?,
            ));
        }
        if let Some(path) = out.truth_exr {
            let truth = truth_raster(&tracer, &frame)?;
            files.push((path, exr_bytes(&truth).into_diagnostic()?));
        }
        if let Some(path) = out.map_png {
            files.push((path, interaction_map(&frame)?));
        }
        if out.dc_png.is_some() || out.lut.is_some() {
            let view_gain = views.get(i).and_then(View::gain_dc_per_k);
            let (png, lut) = dc_image(cli, &tracer, &frame, view_gain)?;
            files.extend(out.dc_png.map(|path| (path, png)));
            files.extend(out.lut.map(|path| (path, lut)));
        }
    }
    bar.finish_and_clear();
    if !map_fits && cli.out.is_some() {
        eprintln!(
            "irsig-trace: interaction map not written: material id {max_id} does not fit the \
             legacy 4-bit nibble (ids 1 to 15); the truth EXR's material_primary and \
             material_secondary layers hold the same information losslessly"
        );
    }
    irsig_cli::write_files_atomic(&files)
}

/// `irsig-sensor-model`'s band conversions from the tracer's band.
struct BandAdapter<'a, R>(&'a R);

impl<R: Radiometry> BandConversion for BandAdapter<'_, R> {
    fn radiance(&self, temperature_k: f64) -> f64 {
        self.0.radiance(temperature_k)
    }
    fn radiance_derivative(&self, temperature_k: f64) -> f64 {
        self.0.radiance_derivative(temperature_k)
    }
    fn temperature(&self, radiance_w_m2_sr: f64) -> f64 {
        self.0.temperature(radiance_w_m2_sr)
    }
}

/// The DC image (PNG, 8 or 16 bits) and its LUT text.
fn dc_image<R: Radiometry, A: Atmosphere>(
    cli: &Cli,
    tracer: &Tracer<R, A>,
    frame: &Frame,
    view_gain: Option<f64>,
) -> miette::Result<(Vec<u8>, Vec<u8>)> {
    let band = BandAdapter(tracer.radiometry());
    let gain = cli.dc_per_k.or(view_gain).unwrap_or(2.0);
    let radiance: Vec<f32> = frame.radiance_w_m2_sr.iter().map(|&l| l as f32).collect();
    let q = if cli.dc == "fixed" {
        let mid = f64::from(1u32 << (cli.dc_bits - 1));
        Quantiser::fixed(
            cli.dc_bits,
            gain,
            cli.reference_k,
            cli.dc_at_reference.unwrap_or(mid),
            &band,
        )
    } else {
        Quantiser::auto_bias_from_image(cli.dc_bits, gain, &radiance, &band)
    }
    .map_err(|e| miette!("digital counts: {e}"))?;
    let (w, h) = raster_size(frame);
    let counts = q
        .quantise(&radiance, w)
        .map_err(|e| miette!("digital counts: {e}"))?;
    let mut png = Vec::new();
    if cli.dc_bits <= 8 {
        let bytes: Vec<u8> = counts.iter().map(|&c| c.min(255) as u8).collect();
        write_png_gray8(&mut Cursor::new(&mut png), w, h, &bytes).into_diagnostic()?;
    } else {
        write_png_gray16(&mut Cursor::new(&mut png), w, h, &counts).into_diagnostic()?;
    }
    Ok((png, q.lut(&band).to_string().into_bytes()))
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

fn raster_size(frame: &Frame) -> (usize, usize) {
    (frame.width as usize, frame.height as usize)
}

fn radiance_raster(frame: &Frame) -> miette::Result<Raster> {
    let (w, h) = raster_size(frame);
    let mut r = Raster::new(w, h);
    r.push_layer(
        "radiance",
        "W m^-2 sr^-1",
        frame.radiance_w_m2_sr.iter().map(|&x| x as f32).collect(),
    )
    .into_diagnostic()?;
    Ok(r)
}

/// The truth layers: the terms of each pixel's centre ray. NaN where a term does not apply
/// (no facet hit).
fn truth_raster<R: Radiometry, A: Atmosphere>(
    tracer: &Tracer<R, A>,
    frame: &Frame,
) -> miette::Result<Raster> {
    let (w, h) = raster_size(frame);
    let mut r = Raster::new(w, h);
    let t = &frame.truth;
    let layer =
        |f: &dyn Fn(&irsig_tracer::TruthPixel) -> f32| -> Vec<f32> { t.iter().map(f).collect() };
    let layers: Vec<(&str, &str, Vec<f32>)> = vec![
        (
            "material_primary",
            "",
            layer(&|s| f32::from(s.primary_material)),
        ),
        (
            "material_secondary",
            "",
            layer(&|s| f32::from(s.secondary_material)),
        ),
        ("event", "", layer(&|s| f32::from(s.event.number()))),
        ("range", "m", layer(&|s| s.range_m)),
        (
            "incidence",
            "deg",
            layer(&irsig_tracer::TruthPixel::incidence_deg),
        ),
        ("kinetic_temperature", "K", layer(&|s| s.temperature_k)),
        ("emissivity", "", layer(&|s| s.emissivity)),
        ("transmission", "", layer(&|s| s.transmission)),
        (
            "path_radiance",
            "W m^-2 sr^-1",
            layer(&|s| s.path_radiance_w_m2_sr),
        ),
        ("sky_view_factor", "", layer(&|s| s.sky_view_factor)),
        (
            "apparent_temperature",
            "K",
            frame
                .radiance_w_m2_sr
                .iter()
                .map(|&l| tracer.apparent_temperature_k(l) as f32)
                .collect(),
        ),
    ];
    for (name, unit, data) in layers {
        r.push_layer(name, unit, data).into_diagnostic()?;
    }
    Ok(r)
}

/// The 1990 interaction map (thesis §4.2): primary material id in the upper nibble,
/// reflected material id in the lower; 0 where nothing was hit. The caller has checked that
/// every id is at most 15.
fn interaction_map(frame: &Frame) -> miette::Result<Vec<u8>> {
    let (w, h) = raster_size(frame);
    let data: Vec<u8> = frame
        .truth
        .iter()
        .map(|s| ((s.primary_material as u8 & 0x0f) << 4) | (s.secondary_material as u8 & 0x0f))
        .collect();
    let mut bytes = Vec::new();
    write_png_gray8(&mut Cursor::new(&mut bytes), w, h, &data).into_diagnostic()?;
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
}
