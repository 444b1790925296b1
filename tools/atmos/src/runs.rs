//! Running a plan's decks: LOWTRAN7 on each (one process per run in a scratch directory,
//! in parallel, progress on stderr), or a given `runs/NNNN.tape7` read instead, and what
//! every build takes from the runs besides their spectra (which
//! `irsig_atmosphere::plan::run_spectra` reads): the model's temperature profile. Shared
//! by the spectral atmosphere's build (`build.rs`) and the broadband loads'
//! (`build_loads.rs`).

use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

use irsig_atmosphere::AtmosphereError;
use irsig_atmosphere::plan::{PathSpectra, RunKind, RunSpectra, lowtran_spectra, run_spectra};
use irsig_atmosphere::refraction::{ApparentZenith, apparent_zenith};
use irsig_formats::ParseError;
use irsig_formats::radtran::{lowtran_tape6, lowtran_tape7, tape5};
use irsig_model::interp::linear;
use irsig_model::{PlanAerosol, PlanModel};
use miette::{Report, WrapErr, miette};

use crate::lowtran;
use crate::plan::deck_name;

/// One run's result.
pub(crate) struct RunResult {
    pub spectra: PathSpectra,
    /// LOWTRAN7's profile of the run (TAPE6): altitude (km), pressure (mb), temperature
    /// (K) per level.
    pub profile: Vec<[f64; 3]>,
    /// How the run was moved off its node, when LOWTRAN7 could not run the node itself.
    pub nudged: Option<String>,
    /// A direct solar run's zenith angles: the geometric one of the deck and the apparent
    /// one LOWTRAN7 ran (`irsig_atmosphere::refraction`). `None`: not a solar run, or its
    /// output was given (run at the deck's angle).
    pub sun: Option<ApparentZenith>,
}

/// The deck `text` with its card 3 angle moved by `delta_deg`.
pub(crate) fn nudged(name: &str, text: &str, delta_deg: f64) -> Result<String, Report> {
    let mut d = tape5::parse(name, text)?;
    if let Some(tape5::Step::Full(c)) = d.steps.first_mut()
        && let tape5::Card3::Path { angle_deg, .. } = &mut c.geometry.card3
    {
        *angle_deg = ((*angle_deg + delta_deg) * 1000.0).round() / 1000.0;
    }
    tape5::write(&d).map_err(|e| miette!("{name}: {e}"))
}

pub(crate) fn located(
    file: &str,
    text: &str,
    pos: irsig_formats::legacy::Position,
    message: String,
) -> Report {
    Report::new(irsig_formats::ParseError::at_line_column(
        file, text, pos.line, pos.column, message,
    ))
}

/// Reads a run's given outputs.
pub(crate) fn read_given(tape7: &Path, want: RunKind) -> Result<RunResult, Report> {
    let input = irsig_cli::read_input(tape7)?;
    let text = irsig_formats::legacy::decode(&input.name, &input.bytes)?;
    let RunSpectra { spectra, notes } = run_spectra(&input.name, text, want)?;
    for n in notes {
        irsig_cli::note!("irsig-atmos: warning: {n}");
    }
    let t6 = tape7.with_extension("tape6");
    let mut profile = Vec::new();
    if t6.is_file() {
        let input = irsig_cli::read_input(&t6)?;
        let text = irsig_formats::legacy::decode(&input.name, &input.bytes)?;
        let tape6 = lowtran_tape6::parse(&input.name, text)?;
        profile = tape6
            .runs
            .first()
            .map(|r| r.profile.clone())
            .unwrap_or_default();
        // A TAPE6 is given for its profile: one without two levels of it is cut short or
        // is not LOWTRAN7's.
        if profile.len() < 2 {
            return Err(Report::new(ParseError::at_offset(
                &input.name,
                text,
                text.trim_end().len().saturating_sub(1),
                format!(
                    "expected the first run's ATMOSPHERIC PROFILES table with at least two \
                     levels (the profile's temperatures come from it), found {} by the end of \
                     the file",
                    profile.len()
                ),
            )));
        }
    }
    Ok(RunResult {
        spectra,
        profile,
        nudged: None,
        sun: None,
    })
}

/// The sun's zenith angles, degrees, by which a rejected scattering run of a loads plan is
/// moved up, in turn. LOWTRAN7 gives up on a path (`GEOINP- THE ENTIRE PATH LIES ABOVE
/// THE TOP ZMAX`) when, seen from the far end of the line of sight at the top of its
/// atmosphere (100 km), the sun stands within about 0.02° below that point's horizon: a
/// low sun and a line of sight away from it (the sun at 80°, a line of sight 89.86° from
/// the zenith; the sun at 89.5°, one at 30°). Moving the sun 0.05° leaves that band; the
/// scattered radiance of the one line of sight changes by about the DHI's change over
/// 0.05° of the sun, well under 1 % of a small weight.
const SUN_NUDGES_DEG: [f64; 3] = [0.05, 0.1, 0.2];

/// The deck `text` with its sun (card 3A2's PARM2, the solar zenith angle) `delta_deg`
/// higher, not above the zenith.
fn sun_higher(name: &str, text: &str, delta_deg: f64) -> Result<String, Report> {
    let mut d = tape5::parse(name, text)?;
    if let Some(tape5::Step::Full(c)) = d.steps.first_mut()
        && let Some(sc) = c.geometry.scattering.as_mut()
    {
        sc.card3a2[1] = (((sc.card3a2[1] - delta_deg) * 1000.0).round() / 1000.0).max(0.0);
    }
    tape5::write(&d).map_err(|e| miette!("{name}: {e}"))
}

/// One LOWTRAN7 run of a deck, and how it was moved off its node: LOWTRAN7's geometry
/// breaks down on a few metre-long grazing paths (the tropical model, 2 m down to 1 m at
/// 85° from nadir: its range comes out 0 and every value NaN). Such a path is run again
/// 0.001° closer to nadir.
fn attempt(
    exe: &Path,
    name: &str,
    text: &str,
    card3: irsig_formats::legacy::Position,
) -> Result<(lowtran::Output, Option<String>), Report> {
    let out = lowtran::run(exe, text).map_err(|m| located(name, text, card3, m))?;
    if !out.tape7.contains("NaN") {
        return Ok((out, None));
    }
    // Card 3's ANGLE is the zenith angle at H1: +0.001 moves a downward path toward
    // nadir and an upward one away from the zenith.
    let again = nudged(name, text, 0.001)?;
    let out = lowtran::run(exe, &again).map_err(|m| located(name, text, card3, m))?;
    if out.tape7.contains("NaN") {
        return Err(located(
            name,
            text,
            card3,
            "LOWTRAN7 printed NaN for this path, and for the path 0.001 deg away".into(),
        ));
    }
    Ok((
        out,
        Some("LOWTRAN7 gave NaN on this path; used the path 0.001 deg closer to nadir".into()),
    ))
}

/// LOWTRAN7's messages when it rejected the run (no table in TAPE7), else `None`.
fn rejection(name: &str, out: &lowtran::Output) -> Result<Option<String>, Report> {
    let t7 = lowtran_tape7::parse(&format!("{name} -> TAPE7"), &out.tape7)?;
    if !t7.runs.first().is_none_or(lowtran_tape7::Run::failed) {
        return Ok(None);
    }
    let t6 = lowtran_tape6::parse(&format!("{name} -> TAPE6"), &out.tape6).ok();
    Ok(Some(
        t6.as_ref()
            .and_then(|t| t.runs.first())
            .map(|r| {
                r.messages
                    .iter()
                    .map(|m| m.text.as_str())
                    .collect::<Vec<_>>()
                    .join("; ")
            })
            .filter(|s| !s.is_empty())
            .unwrap_or_else(|| "no table, and no message in TAPE6".into()),
    ))
}

/// Runs LOWTRAN7 on one deck (`name` its file, `text` its content): a path LOWTRAN7
/// prints NaN for is moved 0.001° ([`attempt`]); a loads plan's scattering run it rejects
/// is run with the sun a little higher ([`SUN_NUDGES_DEG`]); the result says so.
fn run_deck(
    exe: &Path,
    name: &str,
    text: &str,
    card3: irsig_formats::legacy::Position,
    want: RunKind,
) -> Result<RunResult, Report> {
    let (mut out, mut nudge) = attempt(exe, name, text, card3)?;
    if let Some(said) = rejection(name, &out)? {
        let mut accepted = false;
        if want == RunKind::Diffuse {
            for delta in SUN_NUDGES_DEG {
                let again = sun_higher(name, text, delta)?;
                let (o, n) = attempt(exe, name, &again, card3)?;
                if rejection(name, &o)?.is_none() {
                    out = o;
                    nudge = Some(format!(
                        "LOWTRAN7 rejected this path ({said}); used the sun {delta} deg higher{}",
                        n.map_or_else(String::new, |n| format!(", and {n}"))
                    ));
                    accepted = true;
                    break;
                }
            }
        }
        if !accepted {
            return Err(located(
                name,
                text,
                card3,
                format!("LOWTRAN7 rejected this path: {said}"),
            ));
        }
    }
    let mut sun = None;
    if want == RunKind::Solar {
        let (o, s) = refracted(exe, name, text, card3, out)?;
        out = o;
        sun = Some(s);
    }
    let t7_name = format!("{name} -> TAPE7");
    let spectra = lowtran_spectra(&t7_name, &out.tape7, want)?;
    let profile = lowtran_tape6::parse(&format!("{name} -> TAPE6"), &out.tape6)
        .ok()
        .and_then(|t| t.runs.into_iter().next())
        .map(|r| r.profile)
        .unwrap_or_default();
    Ok(RunResult {
        spectra,
        profile,
        nudged: nudge,
        sun,
    })
}

/// Why finding a sun's apparent zenith stopped: a run that failed (its report), or the
/// search itself.
#[derive(Debug)]
enum Refraction {
    Run(Report),
    Search(AtmosphereError),
}

impl From<AtmosphereError> for Refraction {
    fn from(e: AtmosphereError) -> Self {
        Self::Search(e)
    }
}

/// The direct solar deck `text` with card 3's ANGLE set to `angle_deg`.
fn sun_at(name: &str, text: &str, angle_deg: f64) -> Result<String, Report> {
    let mut d = tape5::parse(name, text)?;
    if let Some(tape5::Step::Full(c)) = d.steps.first_mut()
        && let tape5::Card3::DirectSolar { angle_deg: a, .. } = &mut c.geometry.card3
    {
        *a = angle_deg;
    }
    tape5::write(&d).map_err(|e| miette!("{name}: {e}"))
}

/// The direct solar deck `text`'s card 3 ANGLE: the sun's geometric zenith angle, as the
/// plan writes it.
fn sun_angle(name: &str, text: &str) -> Result<f64, Report> {
    let d = tape5::parse(name, text)?;
    d.calculations()
        .first()
        .and_then(|c| match c.card3 {
            tape5::Card3::DirectSolar { angle_deg, .. } => Some(angle_deg),
            _ => None,
        })
        .ok_or_else(|| miette!("{name}: expected a direct solar run (card 3's alternate form)"))
}

/// LOWTRAN7's `BENDING` of a run, degrees (TAPE6's geometry summary).
fn bending_of(name: &str, out: &lowtran::Output) -> Result<f64, Report> {
    let t6 = lowtran_tape6::parse(&format!("{name} -> TAPE6"), &out.tape6)?;
    t6.runs.first().and_then(|r| r.bending_deg).ok_or_else(|| {
        miette!("{name}: LOWTRAN7's TAPE6 has no `BENDING = x DEG` for this direct solar run")
    })
}

/// The sun's beam at the apparent zenith: the deck's ANGLE is the sun's geometric zenith
/// θ_g, and LOWTRAN7 takes ANGLE as the apparent one at H1, so the deck is run again at
/// θ_g − BENDING until the bent ray leaves toward θ_g
/// ([`irsig_atmosphere::refraction::apparent_zenith`]; `first` is the run at θ_g). The
/// output of the last run, and the angles.
fn refracted(
    exe: &Path,
    name: &str,
    text: &str,
    card3: irsig_formats::legacy::Position,
    first: lowtran::Output,
) -> Result<(lowtran::Output, ApparentZenith), Report> {
    let geometric = sun_angle(name, text)?;
    let mut last = Some(first);
    let found = apparent_zenith(geometric, |angle| {
        let out = match last.take() {
            Some(out) if (angle - geometric).abs() < 5e-4 => out,
            _ => {
                let deck = sun_at(name, text, angle).map_err(Refraction::Run)?;
                let out = lowtran::run(exe, &deck)
                    .map_err(|m| Refraction::Run(located(name, text, card3, m)))?;
                if let Some(said) = rejection(name, &out).map_err(Refraction::Run)? {
                    return Err(Refraction::Run(located(
                        name,
                        text,
                        card3,
                        format!(
                            "LOWTRAN7 rejected this sun's path at its apparent zenith {angle} \
                             deg: {said}"
                        ),
                    )));
                }
                out
            }
        };
        let bending = bending_of(name, &out).map_err(Refraction::Run)?;
        last = Some(out);
        Ok(bending)
    });
    match (found, last) {
        (Ok(found), Some(out)) => Ok((out, found)),
        (Err(Refraction::Run(r)), _) => Err(r),
        (Err(Refraction::Search(e)), _) => Err(located(name, text, card3, e.to_string())),
        (Ok(_), None) => Err(miette!("{name}: no LOWTRAN7 run of the sun's path")),
    }
}

/// One run of a build: its deck, what it must give, and the output given for it, if any.
pub(crate) struct Job {
    /// The deck's file name, for messages.
    pub name: String,
    /// The deck.
    pub text: String,
    /// Where the deck's card 3 is.
    pub card3: irsig_formats::legacy::Position,
    /// What the run must give.
    pub want: RunKind,
    /// `runs/NNNN.tape7` beside the deck, read instead of running LOWTRAN7.
    pub given: Option<PathBuf>,
}

/// The job of run `i` of a plan in `plan_dir`: its deck file, checked against `ours` (the
/// deck the plan makes: its only calculation must have `ours`'s card 3), and its given
/// output; or, with `own_decks`, `ours` written here and no given output.
///
/// # Errors
/// A deck that is missing, unreadable or not the plan's path, at its line and column.
pub(crate) fn job(
    plan_dir: &Path,
    i: usize,
    own_decks: bool,
    ours: &tape5::CardDeck,
    want: RunKind,
) -> miette::Result<Job> {
    let file = plan_dir.join(deck_name(i));
    let name = file.to_string_lossy().into_owned();
    let text = if own_decks {
        tape5::write(ours).map_err(|e| miette!("{name}: {e}"))?
    } else {
        let input = irsig_cli::read_input(&name)
            .wrap_err("a plan's deck is missing: rerun irsig-atmos plan")?;
        irsig_formats::legacy::decode(&input.name, &input.bytes)?.to_owned()
    };
    let parsed = tape5::parse(&name, &text)?;
    let calcs = parsed.calculations();
    let want_card3 = &ours.calculations()[0].card3;
    if calcs.len() != 1 || calcs[0].card3 != *want_card3 {
        return Err(located(
            &name,
            &text,
            calcs[0].card3_position,
            format!(
                "expected the plan's path {i} (card 3 {want_card3:?}) as the deck's only calculation"
            ),
        ));
    }
    // The spectral range too: a given tape7 is checked against the deck, so a deck whose
    // V1, V2 or DV is not the plan's (V1 > V2 among them) would build from another range.
    let (got, planned) = (&calcs[0].card4, &ours.calculations()[0].card4);
    let range = |c: &tape5::Card4| [c.v1_per_cm, c.v2_per_cm, c.dv_per_cm];
    // Card 4 is written F10.3: within half its last digit is the same card.
    if range(got)
        .iter()
        .zip(range(planned))
        .any(|(g, p)| (g - p).abs() > 5e-4)
    {
        return Err(located(
            &name,
            &text,
            got.position,
            format!(
                "expected the plan's spectral range on card 4 (V1 {} V2 {} DV {} cm-1), found \
                 V1 {} V2 {} DV {}",
                planned.v1_per_cm,
                planned.v2_per_cm,
                planned.dv_per_cm,
                got.v1_per_cm,
                got.v2_per_cm,
                got.dv_per_cm
            ),
        ));
    }
    let card3 = calcs[0].card3_position;
    let t7 = file.with_extension("tape7");
    Ok(Job {
        name,
        text,
        card3,
        want,
        given: (!own_decks && t7.is_file()).then_some(t7),
    })
}

/// Runs every job (LOWTRAN7 on its deck, or reads its given output), `threads` at once
/// (default: the number of CPUs), with progress on stderr; stops handing out runs at the
/// first failure.
///
/// # Errors
/// LOWTRAN7 missing while a run has no given output; the first run that failed.
pub(crate) fn run_jobs(jobs: &[Job], threads: usize) -> miette::Result<Vec<RunResult>> {
    let exe = if jobs.iter().all(|j| j.given.is_some()) {
        None
    } else {
        Some(lowtran::find().map_err(|m| miette!("{m}"))?)
    };
    let bar = irsig_cli::progress_bar(jobs.len() as u64, "LOWTRAN7");
    let next = AtomicUsize::new(0);
    let results: Mutex<Vec<Option<Result<RunResult, Report>>>> =
        Mutex::new((0..jobs.len()).map(|_| None).collect());
    std::thread::scope(|s| {
        for _ in 0..threads.min(jobs.len()) {
            s.spawn(|| {
                loop {
                    let i = next.fetch_add(1, Ordering::Relaxed);
                    if i >= jobs.len() {
                        break;
                    }
                    let j = &jobs[i];
                    let r = match (&j.given, &exe) {
                        (Some(t7), _) => read_given(t7, j.want),
                        (None, Some(exe)) => run_deck(exe, &j.name, &j.text, j.card3, j.want),
                        (None, None) => Err(miette!("no LOWTRAN7 and no output for run {i}")),
                    };
                    let failed = r.is_err();
                    if let Ok(mut v) = results.lock() {
                        v[i] = Some(r);
                    }
                    bar.inc(1);
                    if failed {
                        // Stop handing out runs: the build fails anyway.
                        next.store(jobs.len(), Ordering::Relaxed);
                    }
                }
            });
        }
    });
    bar.finish_and_clear();
    let results = results
        .into_inner()
        .map_err(|_| miette!("a LOWTRAN7 worker panicked"))?;
    let mut ok = Vec::with_capacity(jobs.len());
    for r in results {
        match r {
            Some(Ok(r)) => ok.push(r),
            Some(Err(e)) => return Err(e),
            None => {}
        }
    }
    if ok.len() != jobs.len() {
        return Err(miette!("only {} of {} runs finished", ok.len(), jobs.len()));
    }
    Ok(ok)
}

/// The air temperature against altitude above the ground (m) of the runs' model, the
/// ground's altitude above sea level (m) and the model in words: a radiosonde's levels, or
/// LOWTRAN7's profile of a standard model from the first run's TAPE6 that has one.
///
/// # Errors
/// A standard model and no run with a TAPE6 profile (given outputs without their TAPE6).
#[allow(clippy::type_complexity)]
pub(crate) fn profile_temperature(
    model: &PlanModel,
    runs: &[RunResult],
) -> miette::Result<(Box<dyn Fn(f64) -> f64>, f64, String)> {
    Ok(match model {
        PlanModel::Radiosonde(levels) => {
            let ground = levels[0].altitude_m;
            let xs: Vec<f64> = levels.iter().map(|l| l.altitude_m - ground).collect();
            let ys: Vec<f64> = levels.iter().map(|l| l.temperature_k).collect();
            (
                Box::new(move |h| linear(&xs, &ys, h)),
                ground,
                format!(
                    "MODEL=7 (a radiosonde of {} levels, US Standard 1976 above)",
                    levels.len()
                ),
            )
        }
        PlanModel::Standard(m) => {
            let profile = runs
                .iter()
                .find(|r| r.profile.len() >= 2)
                .map(|r| r.profile.clone())
                .ok_or_else(|| {
                    miette!(
                        "the profile's temperatures come from LOWTRAN7's TAPE6 (runs/NNNN.tape6), and no run has one: give the TAPE6 beside a tape7, or build with --radiosonde"
                    )
                })?;
            let xs: Vec<f64> = profile.iter().map(|p| p[0] * 1000.0).collect();
            let ys: Vec<f64> = profile.iter().map(|p| p[2]).collect();
            let name = crate::plan::MODELS
                .iter()
                .find(|x| x.1 == *m)
                .map_or("?", |x| x.0);
            (
                Box::new(move |h| linear(&xs, &ys, h)),
                0.0,
                format!("MODEL={m} ({name})"),
            )
        }
    })
}

/// A plan's aerosol as the source of what a build made says it: `IHAZE=1 (rural aerosol,
/// meteorological range 23 km)`, or `IHAZE=0 (no aerosol)`.
pub(crate) fn aerosol_text(aerosol: Option<&PlanAerosol>) -> String {
    aerosol.map_or_else(
        || "IHAZE=0 (no aerosol)".to_owned(),
        |a| {
            format!(
                "IHAZE={} ({} aerosol, meteorological range {} km{})",
                a.model.ihaze(),
                a.model.name(),
                a.visibility_m / 1000.0,
                a.wind_speed_m_s
                    .map_or_else(String::new, |w| format!(", wind {w} m/s"))
            )
        },
    )
}
