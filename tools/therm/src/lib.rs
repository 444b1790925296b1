//! `irsig-therm`: every facet's temperature from a heat balance over time — the sun and the
//! shadows the scene casts, the sky, the wind, the air, the other facets, and each wall's
//! thermal mass — written as raw scenes that `irsig-trace` reads unchanged.
//!
//! The tool wires the libraries together and decides nothing physical itself: the scene and
//! materials come through `irsig-formats`, the weather too (`irsig_formats::weather`), the
//! sun's position from `irsig_atmosphere::sun`, what each facet sees from
//! `irsig_tracer::exposure` (shadow rays and view factors through the scene's BVH), and
//! the walls' conduction and surface balance from `irsig-thermal`. [`solve`] is the time
//! loop that assembles each facet's loads.
//!
//! ```text
//! irsig-therm scene.raw --materials materials.ron --weather site.epw \
//!     --at 2026-07-15T14:00[America/Denver] -o hot
//! # -> hot.raw: the scene with every facet's temperature at 14:00 local time
//! ```

use std::path::{Path, PathBuf};

use clap::Parser;
use irsig_model::history::{TemperatureHistory, ThermalProvenance};
use irsig_model::provenance::InputRecord;
use irsig_model::thermal_decision::ThermalDecision;
use irsig_model::weather::Weather;
use irsig_model::{MaterialLibrary, RawScene};
use miette::miette;

pub mod environment;
pub mod models;
pub mod pilot;
pub mod prepare;
mod report;
pub mod setup;
pub mod solve;

use environment::Site;
use models::Models;
use prepare::{Outcome, Prepared};

const EXAMPLE: &str = "\
Examples:
  irsig-therm scene.raw --materials materials.ron --weather site.epw \\
      --at 2026-07-15T14:00[America/Denver] -o hot
      the scene's temperatures at 14:00 local time -> hot.raw, after three days of
      spin-up under the weather file's sun, sky, air and wind
  irsig-therm scene.raw --materials materials.ron --weather site.epw \\
      --at 2026-07-15T06:00Z/2026-07-16T06:00Z/PT1H -o day/t --history day/history.thm \\
      --hold panel=325 --heat car=150
      a scene for every hour of a day (day/t.20260715T060000Z.raw, ...) and every
      facet's temperature at every step; the object `panel` held at 325 K, 150 W/m2
      deposited behind the facets of `car`

Every material the solved facets use needs a `thermal` record (layers, back boundary,
solar absorptance; formats/canonical/material-library.md). Times take an offset or an
IANA zone: 2026-07-15T14:00Z, 2026-07-15T14:00-06:00, 2026-07-15T14:00[America/Denver].";

/// Facet temperatures from a heat balance over time, written as raw scenes.
#[derive(Debug, Parser)]
#[command(name = "irsig-therm", version, about, after_help = EXAMPLE)]
pub struct Cli {
    /// The raw scene (`irsig-flatten`'s output, binary or RON), or `-` for stdin. Its
    /// facets' temperatures are replaced; a facet's exposed side is its winding's front.
    pub scene: String,
    /// The material library: every solved facet's material with a `thermal` record.
    #[arg(long, value_name = "FILE")]
    pub materials: String,
    /// The weather: an EPW file or a CSV with a unit header (formats/weather.md). Its air
    /// temperature, dew point, pressure and wind drive convection and evaporation; its
    /// direct normal and diffuse horizontal irradiance the sunlight; its downwelling
    /// longwave the sky, or Prata's clear-sky formula where it has none.
    #[arg(long, value_name = "FILE")]
    pub weather: String,
    /// The moments whose scenes are written: a time, or START/END/STEP (such as
    /// 2026-07-15T06:00Z/2026-07-16T06:00Z/PT1H); repeatable. They must lie on the time
    /// step's grid from the first.
    #[arg(long, required = true, value_name = "TIME")]
    pub at: Vec<String>,
    /// Output: PREFIX.raw for one moment, PREFIX.YYYYMMDDTHHMMSSZ.raw (UTC) for several.
    #[arg(short = 'o', long = "output", value_name = "PREFIX")]
    pub output: PathBuf,
    /// Also write every facet's surface temperature at every step from the first moment
    /// to the last (formats/canonical/temperature-history.md).
    #[arg(long, value_name = "FILE")]
    pub history: Option<PathBuf>,
    /// Read an EPW file's rows as this year, whatever their year fields say (default: the
    /// first moment's year, UTC): a typical-year file (TMY, IWEC) takes each month from
    /// another year. The CSV form's times are absolute and ignore it.
    #[arg(long, value_name = "YEAR")]
    pub weather_year: Option<i64>,
    /// The site's latitude, degrees north (default: the weather file's).
    #[arg(
        long,
        value_name = "DEG",
        allow_hyphen_values = true,
        requires = "longitude_deg"
    )]
    pub latitude_deg: Option<f64>,
    /// The site's longitude, degrees east (default: the weather file's).
    #[arg(
        long,
        value_name = "DEG",
        allow_hyphen_values = true,
        requires = "latitude_deg"
    )]
    pub longitude_deg: Option<f64>,
    /// The site's altitude above sea level, m, with --latitude-deg (the weather file's
    /// with its site).
    #[arg(
        long,
        default_value_t = 0.0,
        value_name = "M",
        allow_hyphen_values = true
    )]
    pub altitude_m: f64,
    /// Hold every facet of an object at a temperature, OBJECT=K (a heated blackbody
    /// panel); repeatable. OBJECT is a placed object's name, or #N for the N-th (from 0)
    /// where placements share a name.
    #[arg(long, value_name = "OBJECT=K")]
    pub hold: Vec<String>,
    /// Heat deposited behind every facet of an object, OBJECT=W/m2 (an engine under a
    /// hood); repeatable.
    #[arg(long, value_name = "OBJECT=W_M2")]
    pub heat: Vec<String>,
    /// The ground beyond the scene: solved as an open horizontal facet of this library
    /// material (its temperature becomes the scene's terrain background). Without it the
    /// ground is at the air's temperature and the terrain background is left as it is.
    #[arg(long, value_name = "NAME")]
    pub ground_material: Option<String>,
    /// The share of sunlight the ground beyond the scene reflects (default: 1 − the ground
    /// material's solar absorptance, else 0.2).
    #[arg(long, value_name = "ALBEDO")]
    pub ground_albedo: Option<f64>,
    /// The models, each a named approximation (docs/accuracy.md, "The thermal model").
    #[command(flatten)]
    pub models: Models,
    /// Choose the cheapest settings of the models that keep every facet's temperature
    /// within K kelvin of a converged solve (the 99th percentile over the pilot's facets and
    /// the moments), instead of the model flags' settings; print the decision on stderr.
    #[arg(long, value_name = "K")]
    pub tolerance: Option<f64>,
    /// With --tolerance, also write the decision (canonical RON) here.
    #[arg(long, value_name = "FILE", requires = "tolerance")]
    pub decision_out: Option<PathBuf>,
    /// Threads (default: all cores); results are the same at any count.
    #[arg(long)]
    pub threads: Option<usize>,
    /// Seed of the hemisphere rays' streams.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
}

/// Runs the tool.
///
/// # Errors
/// Bad input, named at its file, line and column; a run that cannot be carried out.
pub fn run(cli: Cli) -> miette::Result<()> {
    if let Some(n) = cli.threads {
        rayon::ThreadPoolBuilder::new()
            .num_threads(n.max(1))
            .build_global()
            .map_err(|e| miette!("cannot start {n} threads: {e}"))?;
    }
    let times = moments(&cli.at)?;
    let outputs = output_paths(&cli.output, &times)?;
    let mut all_outputs: Vec<&Path> = outputs.iter().map(PathBuf::as_path).collect();
    if let Some(h) = &cli.history {
        all_outputs.push(h);
    }
    if let Some(d) = &cli.decision_out {
        all_outputs.push(d);
    }
    irsig_cli::refuse_output_is_input([&cli.scene, &cli.materials, &cli.weather], &all_outputs)?;
    for o in &all_outputs {
        irsig_cli::check_output(o)?;
    }
    let scene_in = irsig_cli::read_input(&cli.scene)?;
    let scene = irsig_formats::canonical::read_raw_scene(&scene_in.name, &scene_in.bytes)?;
    let materials_in = irsig_cli::read_input(&cli.materials)?;
    let materials: MaterialLibrary =
        irsig_formats::canonical::from_ron_bytes(&materials_in.name, &materials_in.bytes)?;
    let weather_in = irsig_cli::read_input(&cli.weather)?;
    // A typical-year file takes each month from another year: it is read as the year of
    // the first moment unless told otherwise.
    let year = cli
        .weather_year
        .or_else(|| irsig_model::time::year_utc(times[0]));
    let weather = irsig_formats::weather::read(
        &weather_in.name,
        &weather_in.bytes,
        &irsig_formats::weather::Options { year },
    )?;
    let site = site(&cli, &weather)?;
    let inputs = vec![
        record("scene", &scene_in),
        record("materials", &materials_in),
        record("weather", &weather_in),
    ];
    let prepared = Prepared::new(&cli, &scene, &materials, &weather, &weather_in.name, site)?;
    let (models, decision) = match cli.tolerance {
        Some(k) => {
            let (models, decision) = pilot::decide(&prepared, &cli.models, &times, k)?;
            report::print(&decision);
            (models, Some(decision))
        }
        None => (cli.models.clone(), None),
    };
    let outcome = prepared.solve(&models, &times, cli.history.is_some())?;
    let provenance = ThermalProvenance {
        irsig_version: env!("CARGO_PKG_VERSION").into(),
        inputs,
        site: (site.latitude_deg, site.longitude_deg, site.altitude_m),
        start_s: outcome.start_s,
        step_s: models.step_s,
        radiation: prepared.radiation(),
        models: models.describe(),
    };
    write(
        &cli,
        &scene,
        &outputs,
        outcome,
        provenance,
        decision.as_ref(),
    )
}

/// Stages every moment's scene and the history, and renames them into place together.
fn write(
    cli: &Cli,
    scene: &RawScene,
    outputs: &[PathBuf],
    outcome: Outcome,
    provenance: ThermalProvenance,
    decision: Option<&ThermalDecision>,
) -> miette::Result<()> {
    let mut staged = irsig_cli::Staged::new();
    if let (Some(path), Some(d)) = (&cli.decision_out, decision) {
        d.validate()
            .map_err(|e| miette!("the decision would break its own rules: {e}"))?;
        let text = irsig_formats::canonical::to_ron_pretty(d)
            .map_err(|e| miette!("cannot write the decision: {e}"))?;
        staged.stage(path, text.as_bytes())?;
    }
    for ((path, surface), ground) in outputs
        .iter()
        .zip(&outcome.surface_k)
        .zip(&outcome.ground_k)
    {
        let mut at = scene.clone();
        for (f, &t) in at.facets.iter_mut().zip(surface) {
            f.temperature_k = t;
        }
        if let Some(g) = ground {
            at.terrain.temperature_k = *g;
        }
        let bytes = irsig_formats::canonical::binary::encode(&at)
            .map_err(|e| miette!("cannot encode the scene for `{}`: {e}", path.display()))?;
        staged.stage(path, &bytes)?;
    }
    if let (Some(path), Some((time_s, temperature_k))) = (&cli.history, outcome.history) {
        let history = TemperatureHistory {
            time_s,
            facets: u32::try_from(scene.facets.len())
                .map_err(|_| miette!("more facets than a history holds"))?,
            temperature_k,
            provenance,
        };
        history
            .validate()
            .map_err(|e| miette!("the history would break its own rules: {e}"))?;
        let bytes = irsig_formats::canonical::binary_history::encode(&history)
            .map_err(|e| miette!("cannot encode the history: {e}"))?;
        staged.stage(path, &bytes)?;
    }
    staged.commit()
}

fn record(role: &str, input: &irsig_cli::Input) -> InputRecord {
    InputRecord {
        stage: "therm".into(),
        role: role.into(),
        sha256: input.sha256(),
    }
}

/// The moments asked for, increasing, each once.
fn moments(at: &[String]) -> miette::Result<Vec<f64>> {
    let mut times = Vec::new();
    for text in at {
        times.extend(
            irsig_formats::time::parse_times(text)
                .map_err(|e| irsig_cli::usage_error(format!("--at {e}")))?,
        );
    }
    times.sort_by(f64::total_cmp);
    times.dedup();
    Ok(times)
}

/// The files the moments are written to.
fn output_paths(prefix: &Path, times: &[f64]) -> miette::Result<Vec<PathBuf>> {
    if times.len() == 1 {
        let mut name = prefix.as_os_str().to_owned();
        name.push(".raw");
        return Ok(vec![PathBuf::from(name)]);
    }
    times
        .iter()
        .map(|&t| {
            let stamp = irsig_model::time::compact_utc(t).ok_or_else(|| {
                irsig_cli::usage_error(format!("--at: time {t} s has no calendar date"))
            })?;
            let mut name = prefix.as_os_str().to_owned();
            name.push(format!(".{stamp}.raw"));
            Ok(PathBuf::from(name))
        })
        .collect()
}

fn site(cli: &Cli, weather: &Weather) -> miette::Result<Site> {
    match (cli.latitude_deg, cli.longitude_deg, &weather.site) {
        (Some(latitude_deg), Some(longitude_deg), _) => Ok(Site {
            latitude_deg,
            longitude_deg,
            altitude_m: cli.altitude_m,
        }),
        (_, _, Some(s)) => Ok(Site {
            latitude_deg: s.latitude_deg,
            longitude_deg: s.longitude_deg,
            altitude_m: s.elevation_m,
        }),
        _ => Err(irsig_cli::usage_error(
            "the weather file names no site: give --latitude-deg and --longitude-deg",
        )),
    }
}
