//! A day's scattered sunlight from one build, against LOWTRAN7 run for each sun itself.
//!
//! A plan of suns at the rows a day's table puts between its lit moments
//! (`irsig_atmosphere::plan::day_sun_grid_deg`, here 15–89°), with the sunlight a rural
//! aerosol scatters into a few slant and sky paths (LOWTRAN7's IEMSCT = 2 at each sun) in
//! 3.4–4.1 µm (2440–2940 cm⁻¹, where the scattered sunlight is a large part of a path's
//! radiance by day), is built by `irsig-atmos build`; a second plan holds suns between
//! those rows as rows of its own. The first table read for each of those suns
//! (`SunlitPaths::at_zenith`, which interpolates between its suns) is held to 0.5 % of the
//! second's scattered sunlight above 10° of elevation; below 10° the error is printed and
//! held to the bound `docs/accuracy.md` states. The same with every other row left out
//! (rows 10° apart) is printed: what a coarser scattered grid would cost in accuracy.
//!
//! LOWTRAN7 is `$IRSIG_LOWTRAN`, else `lowtran7` on PATH
//! (`sh scripts/atmosphere/install-lowtran.sh` builds it). When it is missing these tests
//! fail, saying so: they never skip.

use std::path::Path;

use irsig_atmosphere::sunlit::SunlitPaths;
use irsig_formats::canonical;
use irsig_model::SpectralAtmosphere;
use irsig_tests::{bin, lowtran};

/// The band, µm: a hair inside the plan's 2440–2940 cm⁻¹.
const LO_UM: f64 = 3.402;
const HI_UM: f64 = 4.097;

/// A plan of the slant paths from 1 km at nadir 0° and 60°, the sky from 0 and 1 km at
/// zenith 0°, 60° and 85°, and the suns `zeniths` (the first, then the further ones) with
/// the sunlight scattered into every path at azimuths 0°, 90° and 180° from the sun, on
/// day 172, mid-latitude summer with a rural aerosol of 10 km visibility, over 2440–2940
/// cm⁻¹ every 10, as RON.
fn plan_ron(zeniths: &[f64]) -> String {
    let further: Vec<String> = zeniths[1..].iter().map(|z| format!("{z:.3}")).collect();
    format!(
        "(
  name: \"day\",
  model: Standard(2),
  wavenumber_per_cm: (2440.0, 2940.0, 10.0),
  path_end_m: 1.0,
  observers_m: [1000.0],
  levels_m: [1000.0],
  correction_altitude_m: 1000.0,
  correction_nadir_deg: [0.0, 5.0, 10.0],
  ground_sky_zenith_deg: [0.0],
  hemispheric: [],
  slant_altitude_m: [1000.0],
  slant_nadir_deg: [0.0, 60.0],
  sky_altitude_m: [0.0, 1000.0],
  sky_zenith_deg: [0.0, 60.0, 85.0],
  sun: Some((
    zenith_deg: {:.3},
    day_of_year: 172,
    altitude_m: [0.0, 1000.0],
    relative_azimuth_deg: [0.0, 90.0, 180.0],
    further_zenith_deg: [{}],
  )),
  aerosol: Some((model: Rural, visibility_m: 10000.0)),
)
",
        zeniths[0],
        further.join(", ")
    )
}

/// `irsig-atmos build` of [`plan_ron`] for `zeniths` into `dir/NAME.spa` (the plan's own
/// model, LOWTRAN7's 2), read back.
fn build(dir: &Path, name: &str, zeniths: &[f64]) -> SpectralAtmosphere {
    let plan = dir.join(name);
    std::fs::create_dir(&plan).unwrap();
    std::fs::write(plan.join("plan.ron"), plan_ron(zeniths)).unwrap();
    let out = dir.join(format!("{name}.spa"));
    bin("irsig-atmos")
        .env("IRSIG_LOWTRAN", lowtran())
        .arg("build")
        .arg(&plan)
        .arg("-o")
        .arg(&out)
        .assert()
        .success();
    canonical::read_spectral_atmosphere(name, &std::fs::read(&out).unwrap()).unwrap()
}

/// `table` with every other further sun left out (the first and the last kept): rows
/// twice as far apart, from the same runs.
fn every_other_row(table: &SpectralAtmosphere) -> SpectralAtmosphere {
    let mut coarse = table.clone();
    if let Some(s) = &mut coarse.solar {
        let last = s.further_suns.len() - 1;
        s.further_suns = s
            .further_suns
            .iter()
            .enumerate()
            .filter(|(i, _)| i % 2 == 1 || *i == last)
            .map(|(_, b)| b.clone())
            .collect();
        s.apparent_zenith_deg.clear();
    }
    coarse.validate().unwrap();
    coarse
}

/// Suns between the day table's rows, none on one: above 10° of elevation, then below.
const HIGH: [f64; 4] = [22.7, 47.3, 63.1, 77.5];
const LOW: [f64; 3] = [81.0, 85.1, 87.8];

/// The worst relative errors `(of the scattered sunlight, of the whole path radiance)` of
/// `table` read for the sun `zenith_deg` against `exact` (which has it as a row), over
/// the slant and sky paths and azimuths of [`plan_ron`].
fn worst(table: &SpectralAtmosphere, exact: &SpectralAtmosphere, zenith_deg: f64) -> [f64; 2] {
    let got = SunlitPaths::at_zenith(table, LO_UM, HI_UM, |_| 1.0, zenith_deg).unwrap();
    let want = SunlitPaths::at_zenith(exact, LO_UM, HI_UM, |_| 1.0, zenith_deg).unwrap();
    let mut out = [0.0_f64; 2];
    for az in [0.0, 90.0, 180.0] {
        let mut pairs = Vec::new();
        for nadir in [0.0, 60.0] {
            pairs.push((
                got.path_radiance(1000.0, nadir, az),
                want.path_radiance(1000.0, nadir, az),
            ));
        }
        for h in [0.0, 1000.0] {
            for zenith in [0.0, 60.0, 85.0] {
                pairs.push((
                    got.sky_radiance(h, zenith, az),
                    want.sky_radiance(h, zenith, az),
                ));
            }
        }
        for (g, w) in pairs {
            assert!(w.scattered_w_m2_sr > 0.0, "{zenith_deg}: {w:?}");
            let d = (g.scattered_w_m2_sr - w.scattered_w_m2_sr).abs();
            out[0] = out[0].max(d / w.scattered_w_m2_sr);
            out[1] = out[1].max(d / w.total_w_m2_sr());
        }
    }
    out
}

#[test]
fn the_scattered_sunlight_between_the_rows_of_one_build_is_lowtran7s_for_that_sun() {
    let dir = tempfile::tempdir().unwrap();
    let rows: Vec<f64> = irsig_atmosphere::plan::day_sun_grid_deg()
        .into_iter()
        .filter(|&z| (15.0..=89.0).contains(&z))
        .collect();
    let day = build(dir.path(), "day", &rows);
    let suns: Vec<f64> = HIGH.iter().chain(&LOW).copied().collect();
    let exact = build(dir.path(), "exact", &suns);
    let coarse = every_other_row(&day);
    // A row of the table is its own run, to the rounding of a logarithm and back.
    let own = SunlitPaths::at_zenith(&day, LO_UM, HI_UM, |_| 1.0, 60.0).unwrap();
    let s = day.solar.as_ref().unwrap();
    let row = s.zeniths_deg().iter().position(|&z| z == 60.0).unwrap();
    let mut one = day.clone();
    if let Some(o) = &mut one.solar {
        let b = &s.further_suns[row - 1];
        o.zenith_deg = b.zenith_deg;
        o.transmission.clone_from(&b.transmission);
        o.path_scattered_w_m2_sr_per_unit
            .clone_from(&b.path_scattered_w_m2_sr_per_unit);
        o.sky_scattered_w_m2_sr_per_unit
            .clone_from(&b.sky_scattered_w_m2_sr_per_unit);
        o.further_suns.clear();
        o.apparent_zenith_deg.clear();
    }
    let alone = SunlitPaths::new(&one, LO_UM, HI_UM, |_| 1.0).unwrap();
    let (a, b) = (
        own.sky_radiance(0.0, 60.0, 90.0).scattered_w_m2_sr,
        alone.sky_radiance(0.0, 60.0, 90.0).scattered_w_m2_sr,
    );
    assert!((a - b).abs() <= 1e-12 * b, "{a} {b}");
    println!("sun zenith | rows 5 deg apart: of the scattered, of the path | rows 10 deg apart");
    for &z in &suns {
        let [fine_s, fine_p] = worst(&day, &exact, z);
        let [coarse_s, coarse_p] = worst(&coarse, &exact, z);
        println!(
            "{z:5.1} | {:.3} % {:.3} % | {:.3} % {:.3} %",
            100.0 * fine_s,
            100.0 * fine_p,
            100.0 * coarse_s,
            100.0 * coarse_p
        );
        // Above 10 deg of elevation, the floor; below, the bound docs/accuracy.md states.
        let bound = if z <= 80.0 { 0.005 } else { 0.05 };
        assert!(fine_s < bound, "the sun at {z} deg: {fine_s}");
    }
    // A sun outside the table's suns is refused, naming them.
    let e = SunlitPaths::at_zenith(&day, LO_UM, HI_UM, |_| 1.0, 12.0)
        .unwrap_err()
        .to_string();
    assert!(e.contains("from 15 to 89"), "{e}");
}
