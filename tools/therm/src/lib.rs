//! `irsig-therm`: every facet's temperature from a heat balance over time — the sun and the
//! shadows the scene casts, the sky, the wind, the air, the other facets, and each wall's
//! thermal mass — written as raw scenes that `irsig-trace` reads unchanged.
//!
//! The tool wires the libraries together and decides nothing physical itself: the scene and
//! materials come through `irsig-formats`, the weather too (`irsig_formats::weather`), the
//! sun's position from `irsig_atmosphere::sun`, what each facet sees from
//! `irsig_tracer::exposure` (shadow rays and view factors through the scene's BVH), and
//! the walls' conduction and surface balance from `irsig-thermal`, a material map's image
//! from `irsig-render`. [`solve`] is the time loop that assembles each facet's loads;
//! [`mixture`] solves a facet under a material map material by material.
//!
//! ```text
//! irsig-therm scene.raw --materials materials.ron --weather site.epw \
//!     --at 2026-07-15T14:00[America/Denver] -o hot
//! # -> hot.raw: the scene with every facet's temperature at 14:00 local time
//! ```

use std::path::{Path, PathBuf};

use clap::Parser;
use irsig_cli::args::inputs::Materials;
use irsig_cli::args::outputs::Output;
use irsig_cli::args::{DecisionOut, GroundAlbedo, PlaceArgs, Seed, ThreadsArgs, Tolerance};
use irsig_model::history::{TemperatureHistory, ThermalProvenance};
use irsig_model::loads::BroadbandLoads;
use irsig_model::provenance::InputRecord;
use irsig_model::thermal_decision::ThermalDecision;
use irsig_model::weather::Weather;
use irsig_model::{MaterialLibrary, RawScene};
use miette::miette;

pub mod environment;
pub mod mixture;
pub mod models;
pub mod pilot;
pub mod prepare;
mod report;
pub mod setup;
pub mod solve;

use environment::{Site, SkyLongwave, Sunlight};
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
  irsig-therm scene.raw --materials materials.ron --weather site.epw \\
      --at 2026-07-15T06:00Z --raw dawn.raw --at 2026-07-15T12:00Z --raw noon.raw
      each moment's scene named, in time order (as a pipeline's stage names them)

Every material the solved facets use needs a `thermal` record (layers, back boundary,
solar absorptance; formats/canonical/material-library.md); a facet under a material map
needs each of the map's materials' instead (--mixture per-material, the default). Times take an offset or an
IANA zone: 2026-07-15T14:00Z, 2026-07-15T14:00-06:00, 2026-07-15T14:00[America/Denver].";

/// Facet temperatures from a heat balance over time, written as raw scenes.
#[derive(Debug, Parser)]
#[command(
    name = "irsig-therm",
    version,
    about,
    after_help = EXAMPLE,
    group(clap::ArgGroup::new("materials_required").args(["materials"]).required(true)),
    mut_arg("materials", |a| a.help(
        "The material library: every solved facet's material with a `thermal` record"
    )),
    group(clap::ArgGroup::new("output_required").args(["output", "raw"]).required(true)),
    mut_arg("output", |a| a.help(
        "Where the scenes go: PATH.raw for one moment, PATH.YYYYMMDDTHHMMSSZ.raw (UTC) for \
         several"
    )),
    mut_arg("latitude_deg", |a| a.requires("longitude_deg").help(
        "The site's latitude, degrees north, in [-90, 90] (default: the weather file's)"
    )),
    mut_arg("longitude_deg", |a| a.requires("latitude_deg").help(
        "The site's longitude, degrees east, in [-180, 180] (default: the weather file's)"
    )),
    mut_arg("altitude_m", |a| a.help(
        "The site's altitude above sea level, m, with --latitude-deg (the weather file's \
         with its site)"
    )),
    mut_arg("seed", |a| a.help("Seed of the hemisphere rays' streams")),
    mut_arg("ground_albedo", |a| a.help(
        "The share of sunlight the ground beyond the scene reflects, 0 to 1 (default: 1 − the \
         ground material's solar absorptance, else 0.2)"
    )),
    mut_arg("tolerance", |a| a.help(
        "Choose the cheapest settings of the models that keep every facet's temperature \
         within K kelvin of a converged solve (the 99th percentile over the pilot's facets \
         and the moments), instead of the model flags' settings; print the decision on \
         stderr"
    )),
    mut_arg("decision_out", |a| a.help(
        "With --tolerance, also write the decision (canonical RON) here"
    )),
)]
pub struct Cli {
    /// The raw scene (`irsig-flatten`'s output, binary or RON), or `-` for stdin. Its
    /// facets' temperatures are replaced; a facet's exposed side is its winding's front.
    pub scene: String,
    /// `--materials FILE`.
    #[command(flatten)]
    pub materials: Materials,
    /// The weather: an EPW file or a CSV with a unit header (formats/weather.md). Its air
    /// temperature, dew point, pressure and wind drive convection and evaporation; its
    /// direct normal and diffuse horizontal irradiance the sunlight; its downwelling
    /// longwave the sky, or Prata's clear-sky formula where it has none.
    #[arg(long, value_name = "FILE")]
    pub weather: String,
    /// Sunlight and sky longwave from this loads table (`irsig-atmos plan --loads` and
    /// `build`: LOWTRAN7's clear sky at each sun zenith angle), where the weather file has
    /// no radiation columns or --sunlight/--sky-longwave ask for it.
    #[arg(long, value_name = "FILE")]
    pub loads_table: Option<String>,
    /// Where the sunlight comes from (default: the weather file's dni and dhi columns when
    /// it has them, else --loads-table).
    #[arg(long, value_enum, value_name = "SOURCE")]
    pub sunlight: Option<Sunlight>,
    /// Where the sky's longwave comes from (default: the weather file's column when it has
    /// one, else --loads-table, else Prata's clear-sky formula from the air's temperature
    /// and dew point).
    #[arg(long, value_enum, value_name = "SOURCE")]
    pub sky_longwave: Option<SkyLongwave>,
    /// Read an EPW file's rows as this year, whatever their year fields say (default: the
    /// first moment's year, UTC): a typical-year file (TMY, IWEC) takes each month from
    /// another year. The CSV form's times are absolute and ignore it.
    #[arg(long, value_name = "YEAR")]
    pub weather_year: Option<i64>,
    /// The moments whose scenes are written: a time, or START/END/STEP (such as
    /// 2026-07-15T06:00Z/2026-07-16T06:00Z/PT1H); repeatable. They must lie on the time
    /// step's grid from the first.
    #[arg(long, required = true, value_name = "TIME")]
    pub at: Vec<String>,
    /// `-o PREFIX`.
    #[command(flatten)]
    pub output: Output,
    /// Write the moments' scenes to these files (binary raw scenes), one --raw per moment
    /// in time order, instead of PREFIX...: a pipeline's stage names every file it makes
    /// (a day's frames: one --at and one --raw per frame).
    #[arg(long, value_name = "FILE", conflicts_with = "output")]
    pub raw: Vec<PathBuf>,
    /// Also write every facet's surface temperature at every step from the first moment
    /// to the last (formats/canonical/temperature-history.md).
    #[arg(long, value_name = "FILE")]
    pub history: Option<PathBuf>,
    /// The site (default: the weather file's).
    #[command(flatten)]
    pub place: PlaceArgs,
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
    /// `--ground-albedo`.
    #[command(flatten)]
    pub ground_albedo: GroundAlbedo,
    /// The models, each a named approximation (docs/accuracy.md, "The thermal model").
    #[command(flatten)]
    pub models: Models,
    /// `--tolerance K`.
    #[command(flatten)]
    pub tolerance: Tolerance,
    /// `--decision-out FILE`.
    #[command(flatten)]
    pub decision_out: DecisionOut,
    /// `--threads N`.
    #[command(flatten)]
    pub threads: ThreadsArgs,
    /// `--seed`.
    #[command(flatten)]
    pub seed: Seed,
}

/// Runs the tool.
///
/// # Errors
/// Bad input, named at its file, line and column; a run that cannot be carried out.
pub fn run(cli: Cli) -> miette::Result<()> {
    cli.threads.pool()?.install(|| run_in_pool(&cli))
}

fn run_in_pool(cli: &Cli) -> miette::Result<()> {
    let materials_file = cli.materials.required()?;
    let times = moments(&cli.at)?;
    let outputs = if cli.raw.is_empty() {
        output_paths(cli.output.required()?, &times)?
    } else if cli.raw.len() == times.len() {
        cli.raw.clone()
    } else {
        return Err(irsig_cli::usage_error(format!(
            "--raw names {} file(s), and --at gives {} moment(s): give one --raw per moment, \
             in time order, or -o PREFIX",
            cli.raw.len(),
            times.len()
        )));
    };
    let mut all_outputs: Vec<&Path> = outputs.iter().map(PathBuf::as_path).collect();
    if let Some(h) = &cli.history {
        all_outputs.push(h);
    }
    if let Some(d) = &cli.decision_out.path {
        all_outputs.push(d);
    }
    irsig_cli::refuse_output_is_input(
        [cli.scene.as_str(), materials_file, cli.weather.as_str()]
            .into_iter()
            .chain(cli.loads_table.as_deref()),
        &all_outputs,
    )?;
    for o in &all_outputs {
        irsig_cli::check_output(o)?;
    }
    let scene_in = irsig_cli::read_input(&cli.scene)?;
    let scene = irsig_formats::canonical::read_raw_scene(&scene_in.name, &scene_in.bytes)?;
    let materials_in = irsig_cli::read_input(materials_file)?;
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
    let site = site(cli, &weather)?;
    let mut inputs = vec![
        record("scene", &scene_in),
        record("materials", &materials_in),
        record("weather", &weather_in),
    ];
    let loads = match &cli.loads_table {
        Some(file) => {
            let input = irsig_cli::read_input(file)?;
            inputs.push(record("loads", &input));
            Some(irsig_formats::canonical::from_ron_bytes::<BroadbandLoads>(
                &input.name,
                &input.bytes,
            )?)
        }
        None => None,
    };
    let prepared = Prepared::new(
        cli,
        &scene,
        &materials,
        (&weather, &weather_in.name),
        loads.as_ref(),
        site,
    )?;
    // A map's image decides its facets' parts as much as the materials file does.
    inputs.extend(prepared.map_images().iter().map(|sha256| InputRecord {
        stage: "therm".into(),
        role: "map image".into(),
        sha256: sha256.clone(),
    }));
    let (models, decision) = match cli.tolerance.kelvin {
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
        cli,
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
    if let (Some(path), Some(d)) = (&cli.decision_out.path, decision) {
        d.validate()
            .map_err(|e| miette!("the decision would break its own rules: {e}"))?;
        let text = irsig_formats::canonical::to_ron_pretty(d)
            .map_err(|e| miette!("cannot write the decision: {e}"))?;
        staged.stage(path, text.as_bytes())?;
    }
    for (((path, surface), ground), mix) in outputs
        .iter()
        .zip(&outcome.surface_k)
        .zip(&outcome.ground_k)
        .zip(&outcome.mix_k)
    {
        let mut at = scene.clone();
        for (f, &t) in at.facets.iter_mut().zip(surface) {
            f.temperature_k = t;
        }
        // A facet solved part by part carries its materials' own temperatures; any the
        // scene came with are the solve's to replace.
        at.mix_temperatures.clone_from(mix);
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

/// The flags' own rules, before a file is read (and when `irsig-run` asks of a stage):
/// the moments parse and, with `-o`, name distinct outputs.
impl irsig_cli::CheckArgs for Cli {
    fn check_args(&self) -> miette::Result<()> {
        let times = moments(&self.at)?;
        match &self.output.path {
            Some(prefix) => output_paths(prefix, &times).map(drop),
            None => Ok(()),
        }
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
    match (
        cli.place.latitude_deg,
        cli.place.longitude_deg,
        &weather.site,
    ) {
        (Some(latitude_deg), Some(longitude_deg), _) => Ok(Site {
            latitude_deg,
            longitude_deg,
            altitude_m: cli.place.altitude_m,
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
