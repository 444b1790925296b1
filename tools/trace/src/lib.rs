//! `irsig-trace`: a raw scene through an atmosphere, per view: the radiance and truth EXRs,
//! the 1990 interaction map, the digital counts and their LUT (`--help` shows examples).
//! The command line only: the flags become an `irsig_render::Request`, the inputs' bytes go
//! to an `irsig_render::Plan`, which does the frame's work, and the files it gives back are
//! staged (`irsig_cli::StagedFrames`) and renamed into place together, or none of them.

use std::path::{Path, PathBuf};

use clap::Parser;
use irsig_atmosphere::sun::SunSpec;
use irsig_atmosphere::{ModelKind, SubBandCount};
use irsig_cli::args::{BandArg, DcArgs, FrameOutputArgs, VIEW_UNIT_DEFAULT, length_unit, named};
use irsig_formats::legacy::decode;
use irsig_formats::views::{ViewSun, read_execute};
use irsig_model::LengthUnit;
use irsig_model::decision::Decision;
use irsig_model::frame::{FrameFile, FrameFiles};
use irsig_render::tolerance::Pin;
use irsig_render::{
    AtmosphereRequest, BandRequest, Plan, Request, RequestError, Setting, Sink, TileRequest,
    ToleranceRequest,
};
use irsig_tracer::PathTermsMode;
use miette::IntoDiagnostic;
pub mod sun;

/// `--help`'s examples.
const EXAMPLE: &str = include_str!("examples.txt");

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
    #[arg(long, default_value = VIEW_UNIT_DEFAULT, value_name = "UNIT", value_parser = length_unit)]
    pub view_unit: LengthUnit,
    /// A 1990 execute file: frames of (viewing file, scene file, map image, output image,
    /// LUT), names relative to its folder. Each frame writes its interaction map PNG, its
    /// DC image PNG and its LUT under the names given; the BVH of --scene is built once.
    /// Every frame must name the same scene file: the legacy scene that --scene was
    /// flattened from.
    #[arg(long, value_name = "FILE", conflicts_with_all = [
        "view", "output", "radiance_exr", "truth_exr", "map_png", "dc_png", "lut", "no_dc"
    ])]
    pub execute: Option<String>,
    /// The band: `MIN-MAX` in micrometres (flat response), a sensor response file
    /// (formats/srf.md), or `total`, the whole spectrum (σT⁴/π), exact and for checking by
    /// hand [default: 8-14]. A built-in atmosphere is collapsed from its spectra over any
    /// band other than its tables' flat 8-14; with a band-form atmosphere file use the band
    /// its tables were integrated over.
    #[arg(long, value_name = "MIN-MAX|FILE|total")]
    pub band: Option<BandArg>,
    /// The atmosphere: a built-in LOWTRAN7 model (us-std-1976, tropical, midlat-summer,
    /// midlat-winter, subarctic-summer, subarctic-winter; spectra 7.41-14.08 um, and
    /// 2.99-5.00 um at night: with a sun, build the atmosphere for it with `irsig-atmos plan
    /// --sun-zenith-deg` and `build`), a canonical or spectral atmosphere file (`irsig-atmos
    /// build` writes one), or `none` (a vacuum under --sky-radiance) [default: none, with a
    /// note on stderr].
    #[arg(long, value_name = "NAME|FILE")]
    pub atmosphere: Option<String>,
    /// Sum the radiance equation over sub-bands of the band (the spectral model), each
    /// with its own τ, path and sky radiance collapsed from a spectral atmosphere: K
    /// sub-bands, each holding an equal share of the band's response-weighted blackbody
    /// radiance at 300 K, or `full`, one per interval of the atmosphere's spectral grid.
    /// 1, the default, is the band model: one band-mean τ times the band radiance, the
    /// faster model (docs/accuracy.md measures what it costs in kelvin).
    #[arg(long, value_name = "K|full")]
    pub sub_bands: Option<SubBandCount>,
    /// The atmosphere model: `table` (slant-path tables), `layered` (eq. 8-9), `thesis`
    /// (eq. 10-11, the 1990 model) or `none`.
    /// [default: table]
    #[arg(long, value_name = "MODEL", value_parser = named::<ModelKind>(&ModelKind::NAMES))]
    pub atmosphere_model: Option<ModelKind>,
    /// Sky radiance for `--atmosphere none`, W m^-2 sr^-1 (0: cold space).
    #[arg(long, default_value_t = 0.0, value_name = "W_M2_SR")]
    pub sky_radiance: f64,
    /// Where the frame's files go: -o PREFIX for all of them (PREFIX.NNNN.* for several
    /// views), or one flag per file for one view. Give these, or --probe.
    #[command(flatten)]
    pub output: FrameOutputArgs,
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
    /// `tabulated` (a per-frame altitude × range table; worst error 7 mK, see
    /// docs/accuracy.md; faster from about 200 × 200 pixels up) [default: exact].
    #[arg(long, value_name = "MODE", value_parser = named::<PathTermsMode>(&PathTermsMode::NAMES))]
    pub path_terms: Option<PathTermsMode>,
    /// Let the tool choose the models (atmosphere, bounces, sky-view rays, supersampling,
    /// path terms, sub-bands; by day also whether the sun may be left out and its shadow
    /// rays) for this scene and view: the cheapest whose error against a
    /// converged rendering stays within K kelvin at --tolerance-percentile of the pixels and
    /// in every population of them (materials, mirrors, grazing, thin features); refused
    /// when no setting on offer can keep it. A pilot decides per frame; the decision is
    /// printed on stderr and written beside the outputs (PREFIX.decision.ron with -o,
    /// --decision-out, else beside the first output file). Pin a model with --pin.
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
    /// full), and by day sun (on, off) and shadow-rays (N). Repeat for several.
    #[arg(long, value_name = "MODEL=SETTING", requires = "tolerance")]
    pub pin: Vec<Pin>,
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
    /// FILE instead of beside the first output.
    #[arg(
        long,
        value_name = "FILE",
        requires = "tolerance",
        conflicts_with = "output"
    )]
    pub decision_out: Option<PathBuf>,
    /// Print every term of the radiance equation for pixel COLUMN,ROW of the first view and
    /// write no files.
    #[arg(long, value_name = "COLUMN,ROW", value_parser = irsig_cli::args::pixel)]
    pub probe: Option<(u32, u32)>,
    /// Trace one tile of the image: X,Y,W,H (W x H pixels from column X, row Y) or I/CxR
    /// (tile I, from 1 row by row, of a grid of C columns and R rows). Writes the radiance
    /// and truth EXRs of the tile, each pixel bit for bit the whole frame's; irsig-merge
    /// assembles a frame's tiles and writes its map, counts and LUT, which depend on the
    /// whole frame.
    #[arg(long, value_name = "X,Y,W,H|I/CxR", conflicts_with_all = [
        "probe", "tolerance", "execute", "map_png", "dc_png", "lut",
    ])]
    pub tile: Option<TileRequest>,
    /// How radiance becomes digital counts. Without a gain the view's DC/K is used, else
    /// 2 counts per kelvin (the thesis's auto-bias).
    #[command(flatten)]
    pub dc: DcArgs,
    #[command(flatten)]
    pub sun: sun::SunArgs,
    /// Worker threads (default: all cores). The images do not depend on it.
    #[arg(long)]
    pub threads: Option<usize>,
}

/// The request the flags make, lit by their sun or `view_sun`, a view file's.
fn request(cli: &Cli, view_sun: Option<ViewSun<SunSpec>>) -> miette::Result<Request> {
    let arg = BandArg::or_default(cli.band.as_ref());
    let (band, record) = arg.load_recorded()?;
    let band = BandRequest::new(band, record, arg.to_string());
    let name = cli.atmosphere.as_deref().unwrap_or("none");
    let atmosphere = AtmosphereRequest::named(name, cli.sky_radiance, |name| {
        Ok(irsig_cli::read_input_if_any(name)?.map(|i| (i.name, i.bytes)))
    })?;
    let mut defaulted = Vec::new();
    defaulted.extend(cli.band.is_none().then_some(Setting::Band));
    defaulted.extend(cli.atmosphere.is_none().then_some(Setting::Atmosphere));
    Ok(Request {
        band,
        atmosphere,
        settings: irsig_render::settings::SettingsRequest {
            atmosphere_model: cli.atmosphere_model,
            bounces: cli.bounces,
            sky_view_rays: cli.sky_view_rays,
            supersample: cli.supersample,
            adaptive_threshold_k: cli.adaptive_supersampling,
            seed: cli.seed,
            path_terms: cli.path_terms,
            sub_bands: cli.sub_bands,
        },
        tolerance: cli.tolerance.map(|tolerance_k| ToleranceRequest {
            tolerance_k,
            percentile: cli.tolerance_percentile,
            pins: cli.pin.clone(),
        }),
        sun: cli.sun.request_with(view_sun)?,
        counts: cli.dc.request(),
        defaulted,
    })
}

/// A request error as bad usage, naming the flag of its setting.
fn as_usage(report: miette::Report) -> miette::Report {
    let Some(e) = report.downcast_ref::<RequestError>() else {
        return report;
    };
    let joint = if e.value.is_some() { " " } else { ": " };
    irsig_cli::usage_error(format!("--{}{joint}{e}", e.setting.name()))
}

/// Reads the inputs into a plan: the scene, the materials, the views (of --view or
/// --execute), the uncertainties and a decision. With --execute, also each frame's files.
fn plan(cli: &Cli) -> miette::Result<(Plan, Option<Vec<FrameFiles<PathBuf>>>)> {
    let (view_files, view_sun) = sun::read_views(&cli.view, cli.view_unit)?;
    let mut plan = Plan::new(request(cli, view_sun)?)?;
    let scene = irsig_cli::read_input(&cli.scene)?;
    plan.read_scene(&scene.name, &scene.bytes)?;
    let materials = irsig_cli::read_input(&cli.materials)?;
    plan.read_materials(&materials.name, &materials.bytes, &scene.bytes)?;
    drop(scene);
    let mut execute_files = None;
    if let Some(path) = &cli.execute {
        let input = irsig_cli::read_input(path)?;
        plan.record_input("execute file", &input.bytes);
        let text = decode(&input.name, &input.bytes)?;
        let frames = read_execute(&input.name, text, &input.base_dir(), cli.view_unit)?;
        let files = frames.iter().map(|f| FrameFiles {
            map_png: Some(f.map_png.clone()),
            dc_png: Some(f.dc_png.clone()),
            lut: Some(f.lut.clone()),
            ..FrameFiles::default()
        });
        execute_files = Some(files.collect());
        plan.add_views(frames.into_iter().map(|f| f.view));
    }
    for (input, views) in view_files {
        plan.record_input("view", &input.bytes);
        plan.add_views(views);
    }
    if let Some(path) = &cli.uncertainties {
        let input = irsig_cli::read_input(path)?;
        plan.read_uncertainties(&input.name, &input.bytes)?;
    }
    if let Some(path) = &cli.decision {
        let input = irsig_cli::read_input(path)?;
        plan.read_decision(&input.name, &input.bytes)?;
    }
    Ok((plan, execute_files))
}

/// The plan the flags make, its inputs read: what `irsig-trace` would render (the
/// tolerance's verification, `irsig-tests`'s `tolerance_rows`, converges it instead).
///
/// # Errors
/// As the tool's, for its inputs.
pub fn plan_of(cli: &Cli) -> miette::Result<Plan> {
    plan(cli).map(|(plan, _)| plan).map_err(as_usage)
}

/// Runs the tool.
///
/// # Errors
/// Bad input (with file, line and column where there is one) or an unwritable output.
pub fn run(cli: Cli) -> miette::Result<()> {
    trace(&cli).map_err(as_usage)
}

fn trace(cli: &Cli) -> miette::Result<()> {
    let out = &cli.output;
    let outputs = out.output.is_some() || out.has_files() || cli.decision_out.is_some();
    if cli.probe.is_none() && !outputs && cli.execute.is_none() {
        return Err(irsig_cli::usage_error(
            "give -o PREFIX for all the output files, per-output flags such as \
             --radiance-exr FILE, or --probe COLUMN,ROW",
        ));
    }
    out.check_stdout()?;
    let (plan, execute_files) = plan(cli)?;
    plan.notes()
        .iter()
        .for_each(|n| irsig_cli::note!("irsig-trace: note: {n}"));
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(cli.threads.unwrap_or(0))
        .build()
        .into_diagnostic()?;
    if let Some((column, row)) = cli.probe {
        let text = pool.install(|| plan.probe(column, row))?;
        return irsig_cli::write_output(None, |w| w.write_all(text.as_bytes()));
    }
    if !outputs && execute_files.is_none() {
        return Ok(());
    }
    let frames = plan.views().len();
    let (max_id, map_fits) = (plan.max_material_id(), plan.map_fits());
    let asked_map = execute_files
        .as_ref()
        .and_then(|f| f.first()?.map_png.clone());
    if !map_fits && let Some(path) = out.map_png.as_ref().or(asked_map.as_ref()) {
        return Err(miette::miette!(
            "{}: {} of `{}`",
            path.display(),
            irsig_render::products::map_refusal(max_id),
            cli.materials
        ));
    }
    // Every frame's tile and files are checked before anything is traced: a fly-by would
    // otherwise fail only when its first frame is written.
    let rows = plan.rows(cli.tile)?;
    let (whole, kinds) = (cli.tile.is_none(), plan.file_kinds(cli.tile.is_none()));
    let files = match execute_files {
        Some(files) => files,
        None => out.frames(frames, &kinds)?,
    };
    // Each frame's decision (with --tolerance) goes beside its files, or to --decision-out.
    let decisions: Vec<Option<PathBuf>> = (0..frames)
        .map(|i| match (&cli.tolerance, &cli.decision_out) {
            (None, _) => None,
            (Some(_), Some(path)) => Some(path.clone()),
            (Some(_), None) => out.decision_file(i, frames, &files[i]),
        })
        .collect();
    let more: Vec<&Path> = decisions.iter().flatten().map(PathBuf::as_path).collect();
    let named = [&cli.scene, &cli.materials].into_iter().chain(&cli.view);
    let named = named.chain(
        cli.atmosphere
            .iter()
            .chain(&cli.execute)
            .chain(&cli.decision),
    );
    let named = named.chain(&cli.uncertainties).map(String::as_str);
    let written = files
        .iter()
        .flat_map(|f| f.iter().map(|(_, p)| p.as_path()));
    irsig_cli::refuse_output_is_input(
        named.chain(BandArg::response_file(cli.band.as_ref())),
        written.chain(more.iter().copied()),
    )?;
    let frames = irsig_cli::StagedFrames::new(files, &more)?;
    let mut sink = Staging { frames, decisions };
    let bar = irsig_cli::progress_bar(rows, "tracing");
    pool.install(|| plan.render(cli.tile, &|n| bar.inc(n), &mut sink))?;
    bar.finish_and_clear();
    if !map_fits && out.output.is_some() && whole {
        let refusal = irsig_render::products::map_refusal(max_id);
        irsig_cli::note!("irsig-trace: {refusal}");
    }
    sink.frames.commit()
}

/// The frames' files, staged as they come, and each frame's decision beside them.
struct Staging {
    frames: irsig_cli::StagedFrames,
    decisions: Vec<Option<PathBuf>>,
}

impl Sink for Staging {
    fn files(&self, index: usize) -> FrameFiles<()> {
        self.frames.wanted(index)
    }

    fn decision(&mut self, index: usize, d: &Decision, seconds: f64) -> miette::Result<()> {
        let table = irsig_render::tolerance::table(d);
        irsig_cli::note!("irsig-trace: --{}", table.trim_end());
        // What the pilot cost, for comparing with the rendering it chose (the decision file
        // holds no time: it must be the same on every run).
        irsig_cli::note!("  pilot: {} pixels in {seconds:.3} s", d.pilot_pixels);
        match self.decisions.get(index).cloned().flatten() {
            Some(path) => {
                let text = irsig_formats::canonical::to_ron(d).into_diagnostic()?;
                irsig_cli::note!("irsig-trace: the decision goes to {}", path.display());
                self.frames.stage_other(&path, text.as_bytes())
            }
            None => {
                irsig_cli::note!(
                    "irsig-trace: note: the decision is not written (every output goes to \
                     standard output): give --decision-out FILE to keep it"
                );
                Ok(())
            }
        }
    }

    fn file(&mut self, index: usize, kind: FrameFile, bytes: Vec<u8>) -> miette::Result<()> {
        self.frames.stage(index, kind, &bytes)
    }

    fn warning(&mut self, text: &str) {
        irsig_cli::note!("irsig-trace: warning: {text}");
    }
}
