//! `irsig-atmos plan`: the radiative-transfer runs a scene needs. Reads
//! the raw scene (its lowest point is the ground) and its views (`irsig_formats::views`:
//! a RON view or list, or a 1990 viewing file), and writes `DIR/plan.ron` (the node lists, `irsig_model::AtmospherePlan`)
//! and one LOWTRAN7 card deck per path, `DIR/runs/NNNN.tape5`, in the order of
//! `irsig_atmosphere::plan::paths`. The directory appears whole or not at all.

use std::path::{Path, PathBuf};

use clap::Args;
use irsig_atmosphere::plan::{add_aerosol, add_slabs, add_sun, add_suns, deck, make_plan, paths};
use irsig_atmosphere::sun::SunSpec;
use irsig_cli::args::GroundAlbedo;
use irsig_cli::args::atmosphere::StandardModel;
use irsig_cli::args::inputs::Scene;
use irsig_cli::args::outputs::{Name, Output};
use irsig_cli::args::{AtmosphereArgs, DayOfYear, SunArgs, ViewArgs};
use irsig_formats::canonical;
use irsig_formats::radtran::tape5;
use irsig_model::{AerosolModel, AtmospherePlan, PlanAerosol, PlanModel, RadiosondeLevel};
use miette::{IntoDiagnostic, WrapErr, miette};

use crate::plan_sun;

/// Arguments of `irsig-atmos plan`.
#[derive(Debug, Clone, Args)]
#[command(after_help = "\
Examples:
  irsig-flatten pipelines/quickstart/scene.ron --materials pipelines/quickstart/materials.ron -o scene.raw
  irsig-atmos plan --scene scene.raw --view pipelines/quickstart/view.ron --atmosphere tropical \
      -o tropical-plan
  irsig-atmos plan --scene scene.raw --view view.ron --radiosonde site.rsd -o site-plan
  irsig-atmos plan --scene scene.raw --view view.ron --atmosphere midlat-summer \
      --sun-zenith-deg 30 --day-of-year 172 -o noon-plan
  irsig-atmos plan --scene scene.raw --view view.ron --atmosphere midlat-winter \
      --sun-zenith-deg 70 --day-of-year 172 --band 3-14 -o mwir-plan
  irsig-atmos plan --scene scene.raw --view view.ron --atmosphere midlat-summer \
      --aerosol rural --visibility-km 23 --sun-zenith-deg 30 --day-of-year 172 -o hazy-noon
  irsig-atmos plan --scene scene.raw --view view.ron --atmosphere us-std-1976 \
      --sun-utc 2026-06-21T16:00:00Z --latitude-deg 43.08 --longitude-deg -77.67 -o rit-plan
  irsig-atmos build tropical-plan -o tropical.spa
  irsig-atmos plan --loads --atmosphere midlat-summer --aerosol rural --visibility-km 23 \
      --sun-zeniths-deg 20:85:5,87.5,89,89.9 --day-of-year 172 -o june-loads
  irsig-atmos build june-loads -o june-loads.ron",
    group(clap::ArgGroup::new("model").args(["atmosphere", "radiosonde"]).required(true)),
    mut_arg("view", |a| a.required_unless_present("loads")),
    mut_arg("scene", |a| a.required_unless_present("loads")),
    mut_arg("ground_albedo", |a| a.requires("loads").help(
        "With --loads: the ground's albedo, 0-1 (LOWTRAN7's SALB, to 0.01): sunlight the \
         ground reflects that the sky scatters back down. Default 0, a black ground"
    )),
    mut_arg("atmosphere", |a| a.alias("model")),
    mut_arg("band", |a| a.conflicts_with_all(["wavenumber_per_cm", "loads"]).help(
        "The band the plan's spectra cover: MIN-MAX in micrometres (3-5, 8-14, or 3-14 for \
         a scene traced in both) or a sensor response file (formats/srf.md), as irsig-trace \
         takes it; each run then spans it in LOWTRAN7's 5 cm-1 steps (3-5 is 2000,3335,5). \
         Or --wavenumber-per-cm. Default 8-14"
    )),
    mut_arg("legacy_unit", |a| a.alias("view-unit")),
    mut_arg("scene", |a| a.help(
        "The raw scene (binary or RON, as irsig-flatten writes it); its lowest point is the \
         ground of every path"
    )),
    mut_arg("sun_zenith_deg", |a| a.requires(clap::builder::Resettable::<clap::Id>::Reset).requires("day_of_year").help(
        "The sun's zenith angle at the scene, degrees, 0 to below 90: adds LOWTRAN7's direct \
         solar irradiance runs (IEMSCT = 3) at the sky altitudes; with --day-of-year. \
         --sun-utc with the place, or a view file's `sun`, does the same (one of them). \
         Without any the plan is for night (no solar runs)"
    )),
    mut_arg("sun_azimuth_deg", |a| a.requires(clap::builder::Resettable::<clap::Id>::Reset).help(
        "The sun's azimuth, degrees clockwise from north, in [0, 360): taken, and not needed \
         (the scattered sunlight is tabulated at azimuths from the sun's vertical plane)"
    )),
    mut_arg("sun_utc", |a| a.value_parser(crate::plan_sun::utc_or_range).help(
        "The sun seen at this time, UTC (`YYYY-MM-DDTHH:MM:SSZ`), from --latitude-deg, \
         --longitude-deg and --altitude-m: the plan takes its geometric zenith angle (NREL's \
         SPA) and its day of the year. Or the suns of a day, START/END/STEP \
         (`2026-06-21T10:00:00Z/2026-06-22T10:00:00Z/PT1H`): the direct beam at every lit \
         moment's zenith angle and at rows between them (every 5 deg to 80, 2 deg to 86, 1 \
         deg to 87, 0.5 deg to 89.5), for one build that irsig-trace interpolates for any sun among them; the \
         moments with the sun below the horizon are dropped, and said"
    )),
    mut_arg("day_of_year", |a| a.help(
        "The day of the year, 1-366, for the Earth-Sun distance (LOWTRAN7's IDAY); with \
         --sun-zenith-deg, or with a view file's sun given as a direction (a sun given by \
         time has its own day)"
    )),
    mut_arg("name", |a| a.help(
        "The atmosphere's name (default: the model's or the radiosonde file's)"
    )),
    mut_arg("output", |a| a.help(
        "The plan directory to write (must not exist, or be empty); or, for a name ending in \
         `.ron`, the plan file alone, without decks: `irsig-atmos build FILE.ron` writes them \
         from it (a pipeline's stages pass files, not directories)"
    )),
    group(clap::ArgGroup::new("output_required").args(["output"]).required(true)),
)]
pub struct PlanArgs {
    /// `--scene FILE`.
    #[command(flatten)]
    pub scene: Scene,
    /// `--view FILE` (repeatable, at least one) and the unit of 1990 viewing files.
    #[command(flatten)]
    pub views: ViewArgs,
    /// `--atmosphere`: a LOWTRAN7 standard model (the old spelling `--model` is kept).
    #[command(flatten)]
    pub atmosphere: AtmosphereArgs<StandardModel>,
    /// Plan a day's broadband thermal loads at the ground instead of a scene's
    /// atmosphere: at each of --sun-zeniths-deg, the direct normal sunlight (IEMSCT = 3)
    /// and the diffuse sky's (IEMSCT = 2 with multiple scattering, 9-66 lines of sight),
    /// and the sky's downwelling longwave (IEMSCT = 1, 8 lines of sight); `build` writes
    /// the table (formats/canonical/broadband-loads.md). No scene or view.
    #[arg(long, requires_all = ["sun_zeniths_deg", "day_of_year"],
          conflicts_with_all = ["scene", "view", "sun_zenith_deg", "sun_utc", "sun_scattering",
                                "slabs", "wavenumber_per_cm"])]
    pub loads: bool,
    /// The sun's zenith angles, degrees, 0 to below 90, as values and ranges
    /// `FROM:TO:STEP`, comma-separated (`20:85:5,87.5,89,89.9`), with --day-of-year: the
    /// day's from its lowest to the horizon, 2-5 deg apart (docs/accuracy.md measures the
    /// interpolation between rows). With --loads, the suns of the loads table; else the
    /// direct beam of each for one atmosphere that irsig-trace interpolates for any sun
    /// among them; with --sun-scattering, each sun's scattered sunlight too (every sunlit
    /// path once per sun; not with --slabs, whose tables hold one sun's).
    #[arg(long, value_name = "LIST", conflicts_with_all = ["sun_zenith_deg", "sun_utc"],
          value_parser = crate::plan_loads::sun_zeniths)]
    pub sun_zeniths_deg: Option<crate::plan_loads::SunZeniths>,
    /// `--ground-albedo` (with --loads).
    #[command(flatten)]
    pub ground_albedo: GroundAlbedo,
    /// A DIRTRAN `.rsd` radiosonde (km, mb, degC, dew-point depression degC) as LOWTRAN7's
    /// user-defined model; its first level is the ground.
    #[arg(long, value_name = "FILE.rsd")]
    pub radiosonde: Option<String>,
    /// Where the sun is: `--sun-zenith-deg` (with `--day-of-year`), or `--sun-utc` with the
    /// place.
    #[command(flatten)]
    pub sun: SunArgs,
    /// `--day-of-year D`.
    #[command(flatten)]
    pub day_of_year: DayOfYear,
    /// With a sun, also run every slant and sky path for the sunlight it
    /// scatters (LOWTRAN7's IEMSCT = 2) at 10 azimuths from the sun, and the direct beam at
    /// 3 more altitudes: about ten times the runs. irsig-trace adds that sunlight to every
    /// sky ray, the hemispheric sky and every view path; a hazy 3-5 um sky is where it
    /// matters (docs/accuracy.md, "Scattered sunlight in the tracer").
    #[arg(long)]
    pub sun_scattering: bool,
    /// Also run LOWTRAN7 for slabs that end above the ground: from each observer to target
    /// altitudes up to the scene's top (2, 5, 10, 25 m, 25 m apart to 100, 50 above), at nadir
    /// and zenith angles 0-80 deg (11 each), and by day with scattered sunlight at each of
    /// the sun's azimuths; irsig-trace then takes a view path to a facet above the ground
    /// from them (the slab tables, docs/accuracy.md). The note says what they cost.
    #[arg(long)]
    pub slabs: bool,
    /// The spectral range and step of every run, cm⁻¹: `V1,V2,DV` (LOWTRAN7's card 4).
    /// The default, 710,1250,5, covers 8–14 µm; 710,3335,5 covers 3–5 µm as well (3 µm is
    /// 3333.3 cm⁻¹), for a scene traced in both bands. Runs take longer the wider it is.
    #[arg(long, value_name = "V1,V2,DV", value_parser = wavenumber_range)]
    pub wavenumber_per_cm: Option<[f64; 3]>,
    /// `--band`: the band the plan covers, as the tracer names it (instead of
    /// --wavenumber-per-cm).
    #[command(flatten)]
    pub band: crate::common::BandArgs,
    /// LOWTRAN7's boundary-layer aerosol in every path: rural, urban, maritime,
    /// tropospheric or desert, each with --visibility-km (desert also with
    /// --wind-speed-m-s); or none. Without it the paths have no aerosol (IHAZE 0).
    #[arg(long, value_name = "MODEL")]
    pub aerosol: Option<String>,
    /// The meteorological range (visibility) at the ground, km, above 0 and at most 337
    /// (LOWTRAN7's VIS: the ground's extinction at 0.55 um, aerosol and air, is 3.912/VIS
    /// per km); with --aerosol.
    #[arg(long, value_name = "KM", value_parser = visibility_km)]
    pub visibility_km: Option<f64>,
    /// The desert aerosol's wind speed at 10 m, m/s, 0-30 (LOWTRAN7's WSS); with
    /// --aerosol desert.
    #[arg(long, value_name = "M/S", value_parser = wind_speed)]
    pub wind_speed_m_s: Option<f64>,
    /// `--name`: of the atmosphere.
    #[command(flatten)]
    pub name: Name,
    /// `-o PATH`: the plan directory, or the plan file.
    #[command(flatten)]
    pub output: Output,
}

/// Whether `-o` names a plan file (`….ron`) rather than a plan directory.
pub(crate) fn plan_file_only(output: &Path) -> bool {
    output.extension().is_some_and(|e| e == "ron")
}

/// `--wavenumber-per-cm`: three numbers `V1,V2,DV`, cm⁻¹, with 0 < V1 < V2 ≤ 50000 (the
/// range of LOWTRAN7's spectra) and a step DV from 1 (its finest) to V2 − V1.
fn wavenumber_range(s: &str) -> Result<[f64; 3], String> {
    let values: Vec<f64> = s
        .split(',')
        .map(|v| v.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|_| format!("expected three numbers V1,V2,DV in cm-1, found `{s}`"))?;
    let [v1, v2, dv] = values[..] else {
        return Err(format!(
            "expected three numbers V1,V2,DV in cm-1, found {} in `{s}`",
            values.len()
        ));
    };
    if !(v1.is_finite() && v2.is_finite() && dv.is_finite()) {
        return Err(format!("expected finite numbers, found `{s}`"));
    }
    if !(v1 > 0.0 && v2 > v1 && v2 <= 50_000.0) {
        return Err(format!(
            "expected 0 < V1 < V2 <= 50000 cm-1 (LOWTRAN7's spectra), found V1 = {v1}, V2 = {v2}"
        ));
    }
    if !(1.0..=v2 - v1).contains(&dv) {
        return Err(format!(
            "expected a step DV from 1 cm-1 (LOWTRAN7's finest) to V2 - V1 = {}, found {dv}",
            v2 - v1
        ));
    }
    Ok([v1, v2, dv])
}

/// LOWTRAN7's step for a band's runs, cm⁻¹: the default plan's and its 5 cm⁻¹ model's.
const BAND_STEP_PER_CM: f64 = 5.0;

/// The runs' `V1,V2,DV` that cover a band from `min_um` to `max_um`: its ends in cm⁻¹
/// (10⁴/λ) widened outwards to the next multiple of 5 cm⁻¹, in steps of 5 (8-14 µm is
/// 710,1250,5, the default plan's; 3-5 µm is 2000,3335,5).
///
/// # Errors
/// A band whose short end is below 0.2 µm (above LOWTRAN7's 50,000 cm⁻¹), or too narrow
/// for one 5 cm⁻¹ step.
fn band_wavenumbers_per_cm(min_um: f64, max_um: f64) -> Result<[f64; 3], String> {
    let step = BAND_STEP_PER_CM;
    let v1 = (1e4 / max_um / step).floor() * step;
    let v2 = (1e4 / min_um / step).ceil() * step;
    let v1 = v1.max(step);
    if v2 > 50_000.0 {
        return Err(format!(
            "a band from {min_um} um reaches {v2} cm-1, above LOWTRAN7's 50000 cm-1 (0.2 um)"
        ));
    }
    if v2 <= v1 {
        return Err(format!(
            "the band {min_um}-{max_um} um is narrower than one 5 cm-1 step"
        ));
    }
    Ok([v1, v2, step])
}

/// `--visibility-km`: a finite range above 0 and at most 337 km.
fn visibility_km(s: &str) -> Result<f64, String> {
    let v: f64 = s
        .trim()
        .parse()
        .map_err(|_| format!("expected a meteorological range in km, found `{s}`"))?;
    let max_km = irsig_model::MAX_VISIBILITY_M / 1000.0;
    if !(v.is_finite() && v > 0.0) {
        return Err(format!(
            "expected a meteorological range above 0 km, found {v}"
        ));
    }
    if v > max_km {
        return Err(format!(
            "{v} km is clearer than the air itself allows LOWTRAN7's aerosol (its visibility counts the air's 0.01159 per km at 0.55 um): expected at most {max_km} km"
        ));
    }
    if (v * 1000.0).round() <= 0.0 {
        return Err(format!(
            "{v} km rounds to 0 at the 1 m a LOWTRAN7 deck holds: expected at least 0.001 km"
        ));
    }
    Ok(v)
}

/// `--wind-speed-m-s`: a finite speed from 0 to 30 m/s (the desert model's tables).
fn wind_speed(s: &str) -> Result<f64, String> {
    let w: f64 = s
        .trim()
        .parse()
        .map_err(|_| format!("expected a wind speed in m/s, found `{s}`"))?;
    if !(w.is_finite() && (0.0..=30.0).contains(&w)) {
        return Err(format!(
            "expected a wind speed from 0 to 30 m/s (LOWTRAN7's desert aerosol tables), found {w}"
        ));
    }
    Ok(w)
}

/// The aerosol the flags ask for: none without `--aerosol` (or with `--aerosol none`).
///
/// # Errors
/// An unknown model, a model without `--visibility-km`, a visibility or wind speed with
/// no model that uses it; each names its flag.
pub(crate) fn aerosol_of(
    model: Option<&str>,
    visibility_km: Option<f64>,
    wind_speed_m_s: Option<f64>,
) -> miette::Result<Option<PlanAerosol>> {
    let names = || {
        AerosolModel::ALL
            .map(|m| m.1)
            .iter()
            .chain(&["none"])
            .copied()
            .collect::<Vec<_>>()
            .join(", ")
    };
    let model = match model {
        None | Some("none") => None,
        Some(m) => Some(
            AerosolModel::ALL
                .iter()
                .find(|(_, n)| *n == m)
                .map(|&(k, _)| k)
                .ok_or_else(|| {
                    irsig_cli::usage_error(format!(
                        "--aerosol {m}: unknown aerosol model, expected one of {}",
                        names()
                    ))
                })?,
        ),
    };
    let Some(model) = model else {
        if let Some(v) = visibility_km {
            return Err(irsig_cli::usage_error(format!(
                "--visibility-km {v}: a visibility is the aerosol's; give --aerosol MODEL ({}) with it",
                names()
            )));
        }
        if let Some(w) = wind_speed_m_s {
            return Err(irsig_cli::usage_error(format!(
                "--wind-speed-m-s {w}: the wind speed is the desert aerosol's; give --aerosol desert with it"
            )));
        }
        return Ok(None);
    };
    let Some(v) = visibility_km else {
        return Err(irsig_cli::usage_error(format!(
            "--aerosol {}: expected --visibility-km KM with it (LOWTRAN7's meteorological range at the ground; irsig takes no default)",
            model.name()
        )));
    };
    match (model, wind_speed_m_s) {
        (AerosolModel::Desert, None) => {
            return Err(irsig_cli::usage_error(
                "--aerosol desert: expected --wind-speed-m-s M/S with it (the desert aerosol's extinction depends on the wind speed at 10 m, 0-30 m/s)",
            ));
        }
        (AerosolModel::Desert, Some(_)) | (_, None) => {}
        (m, Some(w)) => {
            return Err(irsig_cli::usage_error(format!(
                "--wind-speed-m-s {w}: the wind speed is the desert aerosol's, not `{}`'s",
                m.name()
            )));
        }
    }
    Ok(Some(PlanAerosol {
        model,
        visibility_m: v * 1000.0,
        wind_speed_m_s,
    }))
}

/// The standard models by name and number.
pub(crate) use irsig_atmosphere::STANDARD_MODELS as MODELS;

/// The model a `--model` or `--radiosonde` names, and a default name.
pub(crate) fn model_of(
    model: Option<&str>,
    radiosonde: Option<&str>,
) -> miette::Result<(PlanModel, String)> {
    if let Some(path) = radiosonde {
        let input = irsig_cli::read_input(path)?;
        let text = irsig_formats::legacy::decode(&input.name, &input.bytes)?;
        let table = irsig_formats::legacy::rsd::parse(&input.name, text)?;
        let levels = table
            .rows
            .iter()
            .map(|r| RadiosondeLevel {
                altitude_m: r.altitude_km * 1000.0,
                pressure_hpa: r.pressure_mb,
                temperature_k: r.temperature_c + 273.15,
                dew_point_depression_k: r.dew_point_depression_c,
            })
            .collect();
        let stem = Path::new(path).file_stem().map_or_else(
            || "radiosonde".to_owned(),
            |s| s.to_string_lossy().into_owned(),
        );
        return Ok((PlanModel::Radiosonde(levels), stem));
    }
    let m = model.unwrap_or("us-std-1976");
    MODELS
        .iter()
        .find(|(n, k)| *n == m || k.to_string() == m)
        .map(|&(n, k)| (PlanModel::Standard(k), n.to_owned()))
        .ok_or_else(|| {
            irsig_cli::usage_error(format!(
                "unknown model `{m}`: expected one of {} (or 1-6)",
                MODELS.map(|m| m.0).join(", ")
            ))
        })
}

/// Writes `files` (relative paths and contents) as the directory `dir`, all or nothing,
/// through the staged writer, which an interrupt cleans up after.
pub(crate) fn write_dir_atomic(dir: &Path, files: &[(PathBuf, Vec<u8>)]) -> miette::Result<()> {
    irsig_cli::write_dir_atomic(dir, files).wrap_err("cannot write the plan")
}

/// The deck file of run `i`, relative to the plan directory.
pub(crate) fn deck_name(i: usize) -> PathBuf {
    PathBuf::from("runs").join(format!("{i:04}.tape5"))
}

/// Runs `irsig-atmos plan`.
///
/// # Errors
/// Unreadable or invalid scene, views or radiosonde; an observer below 2 m above the
/// scene's lowest point; an unknown model; an output directory that exists and is not
/// empty.
pub fn run(a: &PlanArgs) -> miette::Result<()> {
    if a.loads {
        return crate::plan_loads::run(a);
    }
    let output = a.output.required()?;
    let scene = a.scene.required()?;
    let inputs = std::iter::once(scene)
        .chain(a.views.files.iter().map(String::as_str))
        .chain(a.radiosonde.as_deref());
    irsig_cli::refuse_output_is_input(inputs, [output])?;
    // The flags first: a wrong one is refused before any file is read.
    let aerosol = aerosol_of(a.aerosol.as_deref(), a.visibility_km, a.wind_speed_m_s)?;
    if let Some(z) = a.sun.sun_zenith_deg {
        plan_sun::rounds_above_horizon(z)
            .map_err(|e| irsig_cli::usage_error(format!("--sun-zenith-deg {z}: {e}")))?;
    }
    let day_suns = day_suns(a)?;
    let input = irsig_cli::read_input(scene)?;
    let scene = canonical::read_raw_scene(&input.name, &input.bytes)?;
    let lowest = scene
        .positions_m
        .iter()
        .map(|p| p[2])
        .fold(f64::INFINITY, f64::min);
    let highest = scene
        .positions_m
        .iter()
        .map(|p| p[2])
        .fold(f64::NEG_INFINITY, f64::max);
    // The terrain beyond the objects is the plane z = 0.
    let ground_z = lowest.min(0.0);
    let (files, view_sun) = a.views.read()?;
    let observers: Vec<f64> = files
        .iter()
        .flat_map(|(_, views)| views.iter().map(|view| view.position_m()[2] - ground_z))
        .collect();
    // The flags' sun, and how they gave it, for messages. A plan is the same at any
    // azimuth (its scattered sunlight is tabulated at azimuths from the sun's vertical
    // plane), so a zenith angle alone is a sun here.
    let spec = a.sun.spec().or_else(|| {
        a.sun.sun_zenith_deg.map(|zenith_deg| SunSpec::Direction {
            zenith_deg,
            azimuth_deg: 0.0,
        })
    });
    let flags = spec.map(|spec| {
        let given = match &spec {
            SunSpec::Direction { zenith_deg, .. } => format!("--sun-zenith-deg {zenith_deg}"),
            SunSpec::At { utc, .. } => format!("--sun-utc {utc}"),
        };
        (spec, given)
    });
    let sun = match &day_suns {
        Some(_) => refuse_a_views_sun_beside(view_sun.as_ref())?,
        None => plan_sun::choose(
            flags.as_ref().map(|(spec, given)| (spec, given.as_str())),
            a.day_of_year.day,
            a.sun_scattering,
            view_sun.as_ref(),
        )?,
    };
    let (model, default_name) = model_of(a.atmosphere.given(), a.radiosonde.as_deref())?;
    let name = a.name.value.clone().unwrap_or(default_name);
    let mut plan = make_plan(&name, model, &observers)
        .map_err(|e| miette!("{}: {e}", a.views.files.join(", ")))?;
    if let Some(range) = a.wavenumber_per_cm {
        plan.wavenumber_per_cm = range;
    } else if a.band.given().is_some() {
        let band = a.band.load()?;
        plan.wavenumber_per_cm =
            band_wavenumbers_per_cm(band.lambda_min_um(), band.lambda_max_um())
                .map_err(|e| miette!("--band: {e}"))?;
    }
    if let Some(sun) = sun {
        // Rounded to the 0.001 deg a deck holds (`plan_sun` refused what rounds to 90).
        let z = sun.zenith_deg;
        add_sun(&mut plan, z, sun.day_of_year, a.sun_scattering)
            .map_err(|e| irsig_cli::usage_error(format!("the sun at {z} deg: {e}")))?;
    }
    if let Some(day) = &day_suns {
        add_suns(
            &mut plan,
            &day.zenith_deg,
            day.day_of_year,
            a.sun_scattering,
        )
        .map_err(|e| irsig_cli::usage_error(format!("the suns of the day: {e}")))?;
        irsig_cli::note!("{}", day.note);
    }
    if let Some(aer) = aerosol {
        add_aerosol(&mut plan, aer)
            .map_err(|e| irsig_cli::usage_error(format!("--aerosol: {e}")))?;
    }
    if a.slabs {
        // The scene's top above its lowest point, to the metre above.
        let top = (highest - ground_z).ceil();
        add_slabs(&mut plan, top).map_err(|e| irsig_cli::usage_error(format!("--slabs: {e}")))?;
    }
    let plan_text = canonical::to_ron(&plan).into_diagnostic()?;
    let all = paths(&plan);
    if plan_file_only(output) {
        // Every deck is checked as the directory's would be, then left to `build`.
        for (i, p) in all.iter().enumerate() {
            let d = deck(&plan, p).map_err(|e| miette!("{e}"))?;
            tape5::write(&d).map_err(|e| miette!("deck of path {i}: {e}"))?;
        }
        irsig_cli::write_output(Some(output), |w: &mut dyn std::io::Write| {
            w.write_all(plan_text.as_bytes())
        })?;
    } else {
        let mut files = vec![(PathBuf::from("plan.ron"), plan_text.into_bytes())];
        for (i, p) in all.iter().enumerate() {
            let d = deck(&plan, p).map_err(|e| miette!("{e}"))?;
            let text = tape5::write(&d).map_err(|e| miette!("deck of path {i}: {e}"))?;
            files.push((deck_name(i), text.into_bytes()));
        }
        write_dir_atomic(output, &files)?;
    }
    irsig_cli::note!("{}", summary(&plan, output, all.len(), ground_z));
    // Without slabs, a view path that ends on a facet well above the ground is made from
    // paths to the ground or to space: said, with what that costs, rather than left silent.
    if plan.slabs.is_none() && highest - ground_z > SLAB_WORTH_M {
        irsig_cli::note!(
            "the scene stands {:.0} m above its lowest point: view paths to its facets up there are made from paths that end at the ground or in space (LOWTRAN7's band-model averages do not multiply along a path: traced through hazy 3.4-4.1 um air by day, an 87 m slab's path radiance was +58 % off LOWTRAN7's own, docs/accuracy.md \"Slab tables\"); --slabs runs LOWTRAN7 for those slabs themselves",
            highest - ground_z
        );
    }
    Ok(())
}

/// The suns of a day the flags ask for (`--sun-zeniths-deg`, or `--sun-utc` as a range),
/// if any; refused with `--sun-scattering` and `--slabs` together (a slab table holds one
/// sun's scattered sunlight).
fn day_suns(a: &PlanArgs) -> miette::Result<Option<plan_sun::DaySuns>> {
    let suns = match (&a.sun_zeniths_deg, &a.sun.sun_utc) {
        (Some(z), _) => plan_sun::suns_of_zeniths(&z.0, a.day_of_year.day)?,
        (None, Some(utc)) if plan_sun::is_range(utc) => {
            plan_sun::suns_of_times(utc, &a.sun.place, a.day_of_year.day)?
        }
        _ => return Ok(None),
    };
    if a.sun_scattering && a.slabs && suns.zenith_deg.len() > 1 {
        return Err(irsig_cli::usage_error(format!(
            "--sun-scattering with --slabs plans the sunlight the air scatters into a slab \
             for one sun (a slab table holds one sun's), and {} gives {} suns: plan a day's \
             suns with --sun-scattering and no --slabs, or --slabs and no --sun-scattering",
            if a.sun_zeniths_deg.is_some() {
                "--sun-zeniths-deg"
            } else {
                "--sun-utc"
            },
            suns.zenith_deg.len()
        )));
    }
    Ok(Some(suns))
}

/// A plan of a day's suns from the flags takes no `sun` from a view file: refused, naming
/// it, as a sun given twice is.
fn refuse_a_views_sun_beside(
    view: Option<&irsig_formats::views::ViewSun<SunSpec>>,
) -> miette::Result<Option<plan_sun::PlanSunChoice>> {
    match view {
        Some(v) => Err(irsig_cli::usage_error(format!(
            "the flags give the suns of a day and the view file gives a `sun` at {}: give \
             the suns once",
            v.location
        ))),
        None => Ok(None),
    }
}

/// The plan in one line for stderr: its paths, its sun (and whether the sunlight scattered
/// into the paths is in it), its slabs, its aerosol (said either way: never a silent
/// default) and its observers.
fn summary(plan: &AtmospherePlan, output: &Path, paths: usize, ground_z: f64) -> String {
    let sun = plan.sun.as_ref().map_or_else(String::new, |s| {
        // Said either way: whether the sunlight scattered into the paths is in the plan.
        let scattered = if s.relative_azimuth_deg.is_empty() {
            "; the direct beam only, no scattered sunlight (--sun-scattering adds it)".to_owned()
        } else if s.further_zenith_deg.is_empty() {
            format!(
                ", and the sunlight scattered into every slant and sky path at {} azimuths",
                s.relative_azimuth_deg.len()
            )
        } else {
            format!(
                ", and each sun's sunlight scattered into every slant and sky path at {} \
                 azimuths, and the aerosol's phase function at each altitude ({} short runs, \
                 which the interpolation between the suns divides out)",
                s.relative_azimuth_deg.len(),
                s.altitude_m.len() * irsig_atmosphere::plan::SCATTERING_DEG.len()
            )
        };
        let zeniths = s.zeniths_deg();
        let at = match zeniths.as_slice() {
            [one] => format!("the sun at {one} deg from the zenith"),
            [first, .., last] => format!(
                "{} suns from {first} to {last} deg from the zenith",
                zeniths.len()
            ),
            [] => String::new(),
        };
        format!(
            " ({at} on day {}: its direct beam at {} altitudes{scattered})",
            s.day_of_year,
            s.altitude_m.len(),
        )
    });
    // Said either way: a plan's aerosol is never a silent default.
    let aerosol_text = plan.aerosol.as_ref().map_or_else(
        || "no aerosol".to_owned(),
        |x| {
            format!(
                "{} aerosol, visibility {} km{}",
                x.model.name(),
                x.visibility_m / 1000.0,
                x.wind_speed_m_s
                    .map_or_else(String::new, |w| format!(", wind {w} m/s"))
            )
        },
    );
    // Said when asked for: what the slabs cost, per observer.
    let slab_text = plan.slabs.as_ref().map_or_else(String::new, |s| {
        let per = 1 + plan
            .sun
            .as_ref()
            .map_or(0, |x| x.relative_azimuth_deg.len());
        let runs: Vec<String> = plan
            .observers_m
            .iter()
            .map(|&o| format!("{} at {o} m", s.runs_of(o) * per))
            .collect();
        format!(
            ", slabs to {} target altitudes up to {} m ({} runs per observer: {})",
            s.target_m.len(),
            s.target_m.last().copied().unwrap_or(0.0),
            if per > 1 {
                "thermal and scattered"
            } else {
                "thermal"
            },
            runs.join(", ")
        )
    });
    format!(
        "{}: {} paths{sun}{slab_text}, {aerosol_text}, for {} observer(s) at {} m above the scene's lowest point ({} m)",
        output.display(),
        paths,
        plan.observers_m.len(),
        plan.observers_m
            .iter()
            .map(|h| format!("{h}"))
            .collect::<Vec<_>>()
            .join(", "),
        ground_z
    )
}

/// The height of a scene above its lowest point, metres, from which `plan` says that it
/// has no slab tables: a facet a few metres up is seen through nearly the whole path to
/// the ground, whose tables are LOWTRAN7's own.
const SLAB_WORTH_M: f64 = 25.0;
