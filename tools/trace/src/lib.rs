//! `irsig-trace`: a raw scene through an atmosphere, per view: the radiance and truth EXRs,
//! the 1990 interaction map, the digital counts and their LUT (`--help` shows examples).
//! The command line only: the flags become an `irsig_render::Request`, the inputs' bytes go
//! to an `irsig_render::Plan`, which does the frame's work, and the files it gives back are
//! staged (`irsig_cli::StagedFrames`) and renamed into place together, or none of them.

use std::path::{Path, PathBuf};

use clap::Parser;
use irsig_atmosphere::sun::SunSpec;
use irsig_atmosphere::{ModelKind, SubBandCount};
use irsig_cli::args::inputs::{Decision, Materials, Scene, Uncertainties};
use irsig_cli::args::{
    AtmosphereArgs, BandArgs, DcArgs, DecisionOut, FrameOutputArgs, Seed, SunArgs, ThreadsArgs,
    Tolerance, TrailingViews, ViewArgs, atmosphere, band, named,
};
use irsig_formats::legacy::decode;
use irsig_formats::views::{ViewSun, read_execute};
use irsig_model::decision::Decision as PilotDecision;
use irsig_model::frame::{FrameFile, FrameFiles};
use irsig_render::tolerance::Pin;
use irsig_render::{
    AtmosphereRequest, BandRequest, Plan, PlanBuilder, Request, RequestError, Setting, Sink,
    TileRequest, ToleranceRequest,
};
use irsig_tracer::PathTermsMode;
use miette::IntoDiagnostic;
mod check;
pub mod sun;

/// `--help`'s examples.
const EXAMPLE: &str = include_str!("examples.txt");

/// Render a raw scene: radiance EXR, truth EXR and the legacy interaction map per view.
#[derive(Debug, Parser)]
#[command(
    name = "irsig-trace",
    version,
    about,
    after_help = EXAMPLE,
    group(clap::ArgGroup::new("materials_required").args(["materials"]).required(true)),
    group(clap::ArgGroup::new("scene_required").args(["scene"]).required(true)),
    mut_arg("view", |a| a.required_unless_present("execute")),
    mut_arg("legacy_unit", |a| a.alias("view-unit")),
    mut_arg("seed", |a| a.help("Seed for sky-view directions and sub-pixel jitter")),
    mut_arg("tolerance", |a| a.help(
        "Let the tool choose the models (atmosphere, bounces, sky-view rays, supersampling, \
         path terms, sub-bands; by day also whether the sun may be left out and its shadow \
         rays) for this scene and view: the cheapest whose error against a converged \
         rendering stays within K kelvin at --tolerance-percentile of the pixels and in every \
         population of them (materials, mirrors, grazing, thin features); refused when no \
         setting on offer can keep it. A pilot decides per frame; the decision is printed on \
         stderr and written beside the outputs (PREFIX.decision.ron with -o, --decision-out, \
         else beside the first output file). Pin a model with --pin"
    ).conflicts_with_all([
        "atmosphere_model", "bounces", "sky_view_rays", "supersample", "path_terms",
        "adaptive_supersampling", "decision", "sub_bands",
    ])),
    mut_arg("decision_out", |a| a.help(
        "With --tolerance and the per-output flags, write the decision (canonical RON) to \
         FILE instead of beside the first output"
    ).conflicts_with("output")),
    mut_arg("decision", |a| a.help(
        "Apply a decision an earlier --tolerance run wrote (for every frame), instead of \
         piloting: tiles of one frame share their frame's decision"
    )),
    mut_arg("uncertainties", |a| a.help(
        "Declared uncertainties of the inputs (canonical RON, \
         formats/canonical/uncertainties.md): the truth EXR gains the error budget, one σ \
         layer (K) per source and their root-sum-square"
    )),
    mut_arg("sun_zenith_deg", |a| a.help(
        "Light the scene by the sun at this zenith angle, degrees (0 overhead, below 90), with \
         --sun-azimuth-deg. The atmosphere must be a spectral one built for this sun, whose \
         solar table is for this zenith angle within 0.0011 deg: `irsig-atmos plan \
         --sun-zenith-deg Z --day-of-year D`, then `irsig-atmos build`"
    )),
    mut_arg("sun_utc", |a| a.help(
        "Light the scene by the sun seen at this time, UTC (`YYYY-MM-DDTHH:MM:SSZ`), from \
         --latitude-deg, --longitude-deg and --altitude-m (NREL's SPA, geometric: the zenith \
         angle `irsig-atmos sun` prints without --pressure-hpa, which is the one to build the \
         atmosphere for)"
    )),
)]
pub struct Cli {
    /// `--scene FILE`.
    #[command(flatten)]
    pub scene: Scene,
    /// `--materials FILE`.
    #[command(flatten)]
    pub materials: Materials,
    /// The old spelling `--view A B C` (before the views: it reads their places).
    #[command(flatten)]
    pub trailing_views: TrailingViews,
    /// `--view FILE`, repeatable, and `--legacy-unit` of 1990 viewing and execute files.
    #[command(flatten)]
    pub views: ViewArgs,
    /// A 1990 execute file: frames of (viewing file, scene file, map image, output image,
    /// LUT), names relative to its folder. Each frame writes its interaction map PNG, its
    /// DC image PNG and its LUT under the names given; the BVH of --scene is built once.
    /// Every frame must name the same scene file: the legacy scene that --scene was
    /// flattened from.
    #[arg(long, value_name = "FILE", conflicts_with_all = [
        "view", "output", "radiance_exr", "truth_exr", "map_png", "dc_png", "lut", "no_dc"
    ])]
    pub execute: Option<String>,
    /// `--band`: every form.
    #[command(flatten)]
    pub band: BandArgs<band::Traced>,
    /// `--atmosphere`: a built-in, a file or `none`.
    #[command(flatten)]
    pub atmosphere: AtmosphereArgs<atmosphere::Traced>,
    /// Sum the radiance equation over sub-bands of the band (the spectral model), each
    /// with its own τ, path and sky radiance collapsed from a spectral atmosphere: K
    /// sub-bands, each holding an equal share of the band's response-weighted blackbody
    /// radiance at 300 K, or `full`, one per interval of the atmosphere's spectral grid.
    /// 1, the default at night, is the band model: one band-mean τ times the band
    /// radiance, the faster model (docs/accuracy.md measures what it costs in kelvin). By
    /// day the default is 16, said on stderr (docs/accuracy.md, "Sub-bands by day").
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
    /// `--seed`.
    #[command(flatten)]
    pub seed: Seed,
    /// Path terms (τ, L_u) of facet hits: `exact` (one atmosphere call per hit) or
    /// `tabulated` (a per-frame altitude × range table; worst error 7 mK, see
    /// docs/accuracy.md; faster from about 200 × 200 pixels up) [default: exact].
    #[arg(long, value_name = "MODE", value_parser = named::<PathTermsMode>(&PathTermsMode::NAMES))]
    pub path_terms: Option<PathTermsMode>,
    /// `--tolerance K`.
    #[command(flatten)]
    pub tolerance: Tolerance,
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
    /// `--decision FILE`.
    #[command(flatten)]
    pub decision: Decision,
    /// `--uncertainties FILE`.
    #[command(flatten)]
    pub uncertainties: Uncertainties,
    /// `--decision-out FILE`.
    #[command(flatten)]
    pub decision_out: DecisionOut,
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
    /// Where the sun is: a direction or a time and a place. Without these flags, no sun: a
    /// night (or a view file's `sun`).
    #[command(flatten)]
    pub sun: SunArgs,
    /// Shadow rays per facet hit toward the sun: 1 aims at the disk's centre (hard
    /// shadows); more sample the disk (soft edges). With a sun of these flags or of the
    /// view file; default 1. With --tolerance the pilot chooses them (pin them with
    /// --pin shadow-rays=N).
    #[arg(long, value_name = "N", conflicts_with = "tolerance")]
    pub sun_shadow_rays: Option<u32>,
    /// `--threads N`: worker threads.
    #[command(flatten)]
    pub threads: ThreadsArgs,
}

/// The request the flags make, lit by their sun or `view_sun`, a view file's.
fn request(cli: &Cli, view_sun: Option<ViewSun<SunSpec>>) -> miette::Result<Request> {
    check::check_pins(&cli.pin)?;
    let (band, record) = cli.band.load_recorded()?;
    let band = BandRequest::new(band, record, cli.band.or_default().to_string());
    let name = cli.atmosphere.given().unwrap_or("none");
    let atmosphere = AtmosphereRequest::named(name, cli.sky_radiance, |name| {
        Ok(irsig_cli::read_input_if_any(name)?.map(|i| (i.name, i.bytes)))
    })?;
    let mut defaulted = Vec::new();
    defaulted.extend(cli.band.given().is_none().then_some(Setting::Band));
    defaulted.extend(
        cli.atmosphere
            .given()
            .is_none()
            .then_some(Setting::Atmosphere),
    );
    Ok(Request {
        band,
        atmosphere,
        settings: irsig_render::settings::SettingsRequest {
            atmosphere_model: cli.atmosphere_model,
            bounces: cli.bounces,
            sky_view_rays: cli.sky_view_rays,
            supersample: cli.supersample,
            adaptive_threshold_k: cli.adaptive_supersampling,
            seed: cli.seed.value,
            path_terms: cli.path_terms,
            sub_bands: cli.sub_bands,
        },
        tolerance: cli.tolerance.kelvin.map(|tolerance_k| ToleranceRequest {
            tolerance_k,
            percentile: cli.tolerance_percentile,
            pins: cli.pin.clone(),
        }),
        sun: sun::request(&cli.sun, cli.sun_shadow_rays, view_sun)?,
        counts: cli.dc.request(),
        defaulted,
        spelling: irsig_render::Spelling(flag),
    })
}

/// The flag that gives `setting`: the library names settings, each tool its flags.
#[must_use]
pub fn flag(setting: Setting) -> String {
    let name = match setting {
        Setting::Band => "band",
        Setting::Atmosphere => "atmosphere",
        Setting::SkyRadiance => "sky-radiance",
        Setting::SubBands => "sub-bands",
        Setting::Tolerance => "tolerance",
        Setting::TolerancePercentile => "tolerance-percentile",
        Setting::Pin => "pin",
        Setting::Tile => "tile",
        Setting::Probe => "probe",
        Setting::Sun(field) => irsig_cli::args::sun::flag(field),
        Setting::SunShadowRays => "sun-shadow-rays",
    };
    format!("--{name}")
}

/// A request error as bad usage, naming the flag of its setting: one the tool made itself,
/// or one the plan refused the request with. The tool's own errors that the plan passed
/// back (its sink's: an output named twice, a broken pipe) come out as the tool made them,
/// so that the exit code is theirs.
pub(crate) fn as_usage(report: miette::Report) -> miette::Report {
    let report = match report.downcast::<irsig_render::RenderError>() {
        Ok(e) => e.into_caller().unwrap_or_else(miette::Report::new),
        Err(report) => report,
    };
    let Some(e) = report.downcast_ref::<RequestError>().or_else(|| {
        report
            .downcast_ref::<irsig_render::RenderError>()
            .and_then(irsig_render::RenderError::as_request)
    }) else {
        return report;
    };
    let joint = if e.value.is_some() { " " } else { ": " };
    irsig_cli::usage_error(format!("{}{joint}{e}", flag(e.setting)))
}

/// Reads the inputs into a plan: the scene, the materials, the views (of --view or
/// --execute), the uncertainties and a decision. With --execute, also each frame's files.
fn plan(cli: &Cli) -> miette::Result<(Plan, Option<Vec<FrameFiles<PathBuf>>>)> {
    let view_paths = cli.trailing_views.files(&cli.views);
    let (view_files, view_sun) =
        irsig_cli::args::view::read_views(view_paths, cli.views.unit.unit())?;
    let mut plan = PlanBuilder::new(request(cli, view_sun)?)?;
    let scene = irsig_cli::read_input(cli.scene.required()?)?;
    plan.read_scene(&scene.name, &scene.bytes)?;
    let materials = irsig_cli::read_input(cli.materials.required()?)?;
    plan.read_materials(&materials.name, &materials.bytes, &scene.bytes)?;
    drop(scene);
    let mut execute_files = None;
    if let Some(path) = &cli.execute {
        let input = irsig_cli::read_input(path)?;
        plan.record_input("execute file", &input.bytes);
        let text = decode(&input.name, &input.bytes)?;
        let frames = read_execute(&input.name, text, &input.base_dir(), cli.views.unit.unit())?;
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
    if let Some(path) = &cli.uncertainties.file {
        let input = irsig_cli::read_input(path)?;
        plan.read_uncertainties(&input.name, &input.bytes)?;
    }
    if let Some(path) = &cli.decision.file {
        let input = irsig_cli::read_input(path)?;
        plan.read_decision(&input.name, &input.bytes)?;
    }
    Ok((plan.build(), execute_files))
}

/// The plan the flags make, its inputs read: what `irsig-trace` would render (the
/// tolerance's verification, `irsig-tests`'s `tolerance_rows`, converges it instead).
///
/// # Errors
/// As the tool's, for its inputs.
pub fn plan_of(cli: &Cli) -> miette::Result<Plan> {
    plan(cli).map(|(plan, _)| plan).map_err(as_usage)
}

/// Refuses a frame (or, with `tile`, a tile and its margin) too large for the machine,
/// before a pilot spends minutes on it and the allocation aborts the process with its
/// staged files left behind: the largest one's [`Plan::bytes_per_pixel`] against what the
/// process may still take ([`irsig_cli::memory`]).
///
/// # Errors
/// A frame that does not fit, or a tile the frame does not hold.
pub fn fits_in_memory(plan: &Plan, tile: Option<TileRequest>) -> miette::Result<()> {
    let ([w, h], bytes) = plan.largest_frame(tile)?;
    let what = if tile.is_some() {
        "a tile and its one-pixel margin"
    } else {
        "a frame"
    };
    irsig_cli::memory::check_fits(
        bytes,
        &format!(
            "tracing {what}, {w} x {h} pixels at {} bytes a pixel,",
            plan.bytes_per_pixel()
        ),
        "trace it in tiles (--tile), which need as much per pixel of the tile, or on a \
         machine with more memory",
    )
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
    let outputs = out.prefix.path.is_some() || out.has_files() || cli.decision_out.path.is_some();
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
    let pool = cli.threads.pool()?;
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
            cli.materials.file.as_deref().unwrap_or_default()
        ));
    }
    // Every frame's tile and files are checked before anything is traced: a fly-by would
    // otherwise fail only when its first frame is written.
    let rows = plan.rows(cli.tile)?;
    fits_in_memory(&plan, cli.tile)?;
    let (whole, kinds) = (cli.tile.is_none(), plan.file_kinds(cli.tile.is_none()));
    let files = match execute_files {
        Some(files) => files,
        None => out.frames(frames, &kinds)?,
    };
    // Each frame's decision (with --tolerance) goes beside its files, or to --decision-out.
    let decisions: Vec<Option<PathBuf>> = (0..frames)
        .map(|i| match (&cli.tolerance.kelvin, &cli.decision_out.path) {
            (None, _) => None,
            (Some(_), Some(path)) => Some(path.clone()),
            (Some(_), None) => out.decision_file(i, frames, &files[i]),
        })
        .collect();
    let more: Vec<&Path> = decisions.iter().flatten().map(PathBuf::as_path).collect();
    let named = [cli.scene.required()?]
        .into_iter()
        .chain(cli.materials.file.as_deref())
        .chain(
            cli.trailing_views
                .files(&cli.views)
                .iter()
                .map(String::as_str),
        );
    let named = named.chain(
        cli.atmosphere
            .given()
            .into_iter()
            .chain(cli.execute.as_deref())
            .chain(cli.decision.file.as_deref()),
    );
    let named = named.chain(cli.uncertainties.file.as_deref());
    let written = files
        .iter()
        .flat_map(|f| f.iter().map(|(_, p)| p.as_path()));
    irsig_cli::refuse_output_is_input(
        named.chain(cli.band.response_file()),
        written.chain(more.iter().copied()),
    )?;
    let frames = irsig_cli::StagedFrames::new(files, &more)?;
    let mut sink = Staging { frames, decisions };
    let bar = irsig_cli::progress_bar(rows, "tracing");
    pool.install(|| plan.render(cli.tile, &|n| bar.inc(n), &mut sink))?;
    bar.finish_and_clear();
    if !map_fits && out.prefix.path.is_some() && whole {
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

    fn decision(&mut self, index: usize, d: &PilotDecision, seconds: f64) -> miette::Result<()> {
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
