//! `irsig-atmos build` with MODTRAN-layout tape7s for a plan's sunlit paths (IEMSCT 2) and
//! the sun's paths (IEMSCT 3), end to end with real LOWTRAN7.
//!
//! No MODTRAN output of these paths exists here, so the given files are **layout samples,
//! not MODTRAN output**: MODTRAN's column headers as documented (formats/radtran/
//! modtran-tape7.md) holding LOWTRAN7's printed numbers for the same deck, written by
//! [`modtran_layout`] from LOWTRAN7's TAPE7. A build that takes them must give the
//! atmosphere of the build that runs LOWTRAN7 on every path, exactly: the same numbers,
//! read from other columns, in other units (W cm⁻² → W m⁻² at the boundary). A file of the
//! wrong mode for its path is refused at card 1's IEMSCT; a scattered column above its
//! single-scattered part is warned of.
//!
//! LOWTRAN7 is `$IRSIG_LOWTRAN`, else `lowtran7` on PATH
//! (`sh scripts/atmosphere/install-lowtran.sh` builds it); without it these tests fail,
//! saying so.

use std::path::{Path, PathBuf};

use assert_cmd::Command;
use irsig_atmosphere::plan::{Path as PlanPath, deck, paths};
use irsig_formats::canonical;
use irsig_formats::radtran::{lowtran_tape7, tape5};
use irsig_model::{AtmospherePlan, SpectralAtmosphere};

fn atmos() -> Command {
    Command::cargo_bin("irsig-atmos").unwrap()
}

fn lowtran() -> PathBuf {
    irsig_atmos::lowtran::find().unwrap_or_else(|m| panic!("these tests need LOWTRAN7: {m}"))
}

/// A small day plan: US Standard 1976, rural aerosol (23 km), 2500–2600 cm⁻¹ every 20, the
/// sun 30° from the zenith on day 95, its beam at 0 and 1000 m, and each slant and sky path
/// also run for the sunlight it scatters 60° of azimuth from the sun.
const PLAN: &str = "(
  name: \"day\",
  model: Standard(6),
  wavenumber_per_cm: (2500.0, 2600.0, 20.0),
  path_end_m: 1.0,
  observers_m: [1000.0],
  levels_m: [1000.0],
  correction_altitude_m: 1000.0,
  correction_nadir_deg: [0.0, 5.0, 10.0],
  ground_sky_zenith_deg: [0.0],
  hemispheric: [],
  slant_altitude_m: [1000.0],
  slant_nadir_deg: [45.0],
  sky_altitude_m: [0.0],
  sky_zenith_deg: [30.0],
  sun: Some((
    zenith_deg: 30.0,
    day_of_year: 95,
    altitude_m: [0.0, 1000.0],
    relative_azimuth_deg: [60.0],
  )),
  aerosol: Some((model: Rural, visibility_m: 23000.0)),
)
";

/// The plan directory: plan.ron and each path's deck (`runs/NNNN.tape5`), as
/// `irsig-atmos plan` writes them; and the plan's paths.
fn plan_dir(dir: &Path) -> (PathBuf, AtmospherePlan, Vec<PlanPath>) {
    let p = dir.join("plan");
    std::fs::create_dir_all(p.join("runs")).unwrap();
    std::fs::write(p.join("plan.ron"), PLAN).unwrap();
    let plan: AtmospherePlan = canonical::from_ron_bytes("plan.ron", PLAN.as_bytes()).unwrap();
    let all = paths(&plan);
    for (i, path) in all.iter().enumerate() {
        let d = tape5::write(&deck(&plan, path).unwrap()).unwrap();
        std::fs::write(p.join(format!("runs/{i:04}.tape5")), d).unwrap();
    }
    (p, plan, all)
}

fn build(plan: &Path, out: &Path) -> (SpectralAtmosphere, String) {
    let o = atmos()
        .env("IRSIG_LOWTRAN", lowtran())
        .arg("build")
        .arg(plan)
        .arg("-o")
        .arg(out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(o.status.success(), "{stderr}");
    let a = canonical::read_spectral_atmosphere("built", &std::fs::read(out).unwrap()).unwrap();
    (a, stderr)
}

/// `irsig-atmos build` of `plan` refused (exit 1), with each of `said` on stderr and
/// nothing written to `out`.
fn refused(plan: &Path, out: &Path, said: &[&str]) {
    let mut assert = atmos()
        .env("IRSIG_LOWTRAN", lowtran())
        .arg("build")
        .arg(plan)
        .arg("-o")
        .arg(out)
        .assert()
        .code(1);
    for s in said {
        assert = assert.stderr(predicates::str::contains(*s));
    }
    assert!(!out.exists());
}

/// LOWTRAN7's TAPE7 for the deck `runs/NNNN.tape5`, run here.
fn lowtran_tape7_of(plan: &Path, i: usize) -> String {
    let run = irsig_atmos::lowtran::run(
        &lowtran(),
        &std::fs::read_to_string(plan.join(format!("runs/{i:04}.tape5"))).unwrap(),
    )
    .unwrap();
    run.tape7
}

/// A MODTRAN-layout tape7 (a layout sample, not MODTRAN output) holding the numbers of
/// LOWTRAN7's TAPE7 `t7` for the same path: IEMSCT 3 as `FREQ TRANS SOL TR SOLAR DEPTH`,
/// IEMSCT 2 as the radiance-mode columns LOWTRAN7 has counterparts for (THRML_SCT and
/// SURF_EMIS 0, no multiple scattering: SOL_SCAT = SING_SCAT unless `single_scale` says
/// otherwise, to stand for a multiple-scattering run).
fn modtran_layout(t7: &str, single_scale: f64) -> String {
    let parsed = lowtran_tape7::parse("TAPE7", t7).unwrap();
    let run = &parsed.runs[0];
    let iemsct = run.header.as_ref().unwrap().iemsct;
    let tab = run.table.as_ref().unwrap();
    let c = &tab.columns;
    let mut s = format!(
        "T F 6    2{iemsct:5}    0    6    6    6    6    6    6    1    0    0   0.000   0.00\n\
         LAYOUT SAMPLE, NOT MODTRAN OUTPUT: LOWTRAN7's numbers under MODTRAN's column names.\n\
         \x20   2500.0    2600.0      20.0\n"
    );
    let n = tab.wavenumber_per_cm().len();
    let rows: Vec<Vec<f64>> = (0..n)
        .map(|k| c.iter().map(|col| col[k]).collect())
        .collect();
    if iemsct == 3 {
        s.push_str("    FREQ   TRANS  SOL TR   SOLAR     DEPTH\n");
        for r in &rows {
            s.push_str(&format!(
                " {:7.2} {:7.4} {:.2E} {:.2E} {:.3E}\n",
                r[0], r[1], r[2], r[3], r[4]
            ));
        }
    } else {
        assert_eq!(iemsct, 2);
        s.push_str("    FREQ  TOT_TRANS  PTH_THRML  THRML_SCT  SURF_EMIS   SOL_SCAT  SING_SCAT  GRND_RFLT  DRCT_RFLT  TOTAL_RAD\n");
        for r in &rows {
            s.push_str(&format!(
                " {:7.2} {:10.4} {:10.4E} {:10.4E} {:10.4E} {:10.4E} {:10.4E} {:10.4E} {:10.4E} {:10.4E}\n",
                r[0],
                r[1],
                r[2],
                0.0,
                0.0,
                r[3],
                r[4] * single_scale,
                r[5],
                r[6],
                r[7]
            ));
        }
    }
    s.push_str(" -9999.\n");
    s
}

#[test]
fn modtran_layout_solar_runs_build_the_atmosphere_lowtran7_builds() {
    let dir = tempfile::tempdir().unwrap();
    let (plan, _, all) = plan_dir(dir.path());
    let sunlit: Vec<usize> = (0..all.len())
        .filter(|&i| {
            matches!(
                all[i],
                PlanPath::DownSunlit { .. } | PlanPath::UpSunlit { .. }
            )
        })
        .collect();
    let sun: Vec<usize> = (0..all.len())
        .filter(|&i| matches!(all[i], PlanPath::Sun { .. }))
        .collect();
    assert!(!sunlit.is_empty() && sun.len() == 2, "{all:?}");
    let (by_lowtran, _) = build(&plan, &dir.path().join("lowtran.spa"));
    assert!(
        by_lowtran.source.contains("0 given"),
        "{}",
        by_lowtran.source
    );
    for &i in sunlit.iter().chain(&sun) {
        let m = modtran_layout(&lowtran_tape7_of(&plan, i), 1.0);
        std::fs::write(plan.join(format!("runs/{i:04}.tape7")), m).unwrap();
    }
    let (mut by_modtran, stderr) = build(&plan, &dir.path().join("modtran.spa"));
    let given = sunlit.len() + sun.len();
    assert!(
        by_modtran.source.contains(&format!("{given} given")),
        "{}",
        by_modtran.source
    );
    assert!(!stderr.contains("warning"), "{stderr}");
    // The same numbers, from MODTRAN's columns: the same atmosphere, solar tables included.
    by_modtran.source.clone_from(&by_lowtran.source);
    assert_eq!(by_modtran, by_lowtran);

    // A scattered column above its single-scattered part: multiple scattering, warned of.
    let i = sunlit[0];
    let m = modtran_layout(&lowtran_tape7_of(&plan, i), 0.8);
    std::fs::write(plan.join(format!("runs/{i:04}.tape7")), m).unwrap();
    let (_, stderr) = build(&plan, &dir.path().join("multiple.spa"));
    assert!(
        stderr.contains(&format!("{i:04}.tape7: MODTRAN's SOL_SCAT includes multiple scattering (up to 20.0 % above SING_SCAT)")),
        "{stderr}"
    );
}

#[test]
fn a_modtran_tape7_of_the_wrong_mode_is_refused_at_card_1() {
    let dir = tempfile::tempdir().unwrap();
    let (plan, _, all) = plan_dir(dir.path());
    let first = |f: fn(&PlanPath) -> bool| (0..all.len()).find(|&i| f(&all[i])).unwrap();
    let sun = first(|p| matches!(p, PlanPath::Sun { .. }));
    let sunlit = first(|p| matches!(p, PlanPath::DownSunlit { .. }));
    // pyradi's tape7-05, a real MODTRAN radiance run with solar scattering (IEMSCT 2),
    // given for the sun's path.
    let tape7_05 =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/data/third-party/pyradi/tape7-05");
    let t7 = plan.join(format!("runs/{sun:04}.tape7"));
    std::fs::copy(&tape7_05, &t7).unwrap();
    let out = dir.path().join("never.spa");
    refused(
        &plan,
        &out,
        &[
            &format!("{sun:04}.tape7:1:11"),
            "expected a direct solar irradiance run (IEMSCT = 3",
            "found card 1's IEMSCT = 2",
        ],
    );
    std::fs::remove_file(&t7).unwrap();
    // tape7-05 without its SOL_SCAT column, for a sunlit path: the right IEMSCT without
    // the column, an error at the column header (line 11).
    let text = std::fs::read_to_string(&tape7_05).unwrap();
    let mut cut = String::new();
    let mut in_rows = false;
    for line in text.split_inclusive('\n') {
        if line.trim_start().starts_with("FREQ") {
            cut.push_str(&line.replace("   SOL_SCAT", ""));
            in_rows = true;
        } else if in_rows && line.trim() != "-9999." {
            let mut w: Vec<&str> = line.split_whitespace().collect();
            w.remove(5);
            cut.push_str(&format!(" {}\r\n", w.join(" ")));
        } else {
            cut.push_str(line);
        }
    }
    let sunlit_t7 = plan.join(format!("runs/{sunlit:04}.tape7"));
    std::fs::write(&sunlit_t7, cut).unwrap();
    refused(
        &plan,
        &out,
        &[
            &format!("{sunlit:04}.tape7:11:1"),
            "found card 1's IEMSCT = 2 without a SOL_SCAT column",
        ],
    );
    // The direct solar layout sample given for a sunlit path.
    let layout = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../formats/radtran/samples/modtran-iemsct3-layout.tape7");
    std::fs::copy(&layout, plan.join(format!("runs/{sunlit:04}.tape7"))).unwrap();
    refused(
        &plan,
        &out,
        &[
            &format!("{sunlit:04}.tape7:1:11"),
            "expected a solar scattering run (IEMSCT = 2, column SOL_SCAT)",
            "found card 1's IEMSCT = 3",
        ],
    );
}
