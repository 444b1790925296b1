//! A day's scattered sunlight from one build, against LOWTRAN7 run for each sun itself.
//!
//! A plan of suns at the rows a day's table puts between its lit moments
//! (`irsig_atmosphere::plan::day_sun_grid_deg`, here 15–89°), with the sunlight a rural
//! aerosol scatters into a few slant and sky paths (LOWTRAN7's IEMSCT = 2 at each sun) in
//! 3.4–4.1 µm (2440–2940 cm⁻¹, where the scattered sunlight is a large part of a path's
//! radiance by day), is built by `irsig-atmos build`; a second plan holds suns between
//! those rows as rows of its own. The first table read for each of those suns
//! (`SunlitPaths::at_zenith`, which interpolates between its suns) is compared with the
//! second's scattered sunlight, on lines of sight away from the sun and, apart, within
//! 15° of it (the aureole), the build's measured phase function divided out of each node
//! (`SpectralSolar::phase`); the errors are printed and held to the bounds
//! `docs/accuracy.md` states: 0.5 % away from the sun, 2 % within 15° of it. The same
//! with every other row left out (rows 10° apart) is printed: what a coarser scattered
//! grid would cost in accuracy.
//!
//! The same build is then traced: `irsig-trace` by a sun between the day table's rows reads
//! the table's interpolation at that sun, and lands within its bound of the trace through
//! the table that holds the sun as a row.
//!
//! LOWTRAN7 is `$IRSIG_LOWTRAN`, else `lowtran7` on PATH
//! (`sh scripts/atmosphere/install-lowtran.sh` builds it). When it is missing these tests
//! fail, saying so: they never skip.

use std::path::Path;

use irsig_atmosphere::sunlit::SunlitPaths;
use irsig_formats::canonical;
use irsig_model::SpectralAtmosphere;
use irsig_tests::hazy_day::{BAND, SUN_AZIMUTH_DEG, direction, plate, probe};
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
    let plan = dir.join(format!("{name}.ron"));
    std::fs::write(&plan, plan_ron(zeniths)).unwrap();
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

/// The angle between a line of sight `los_zenith_deg` from straight up and
/// `azimuth_deg` from the sun's vertical plane and the sun `sun_zenith_deg` from the
/// zenith, degrees (spherical law of cosines).
fn from_sun_deg(los_zenith_deg: f64, azimuth_deg: f64, sun_zenith_deg: f64) -> f64 {
    let (l, a, s) = (
        los_zenith_deg.to_radians(),
        azimuth_deg.to_radians(),
        sun_zenith_deg.to_radians(),
    );
    (l.cos() * s.cos() + l.sin() * s.sin() * a.cos())
        .clamp(-1.0, 1.0)
        .acos()
        .to_degrees()
}

/// Lines of sight closer than this to the sun, degrees, are tabled apart: the aerosol's
/// forward peak (the aureole) moves across a fixed line of sight as the sun moves.
const AUREOLE_DEG: f64 = 15.0;

/// The worst relative errors of `table` read for the sun `zenith_deg` against `exact`
/// (which has it as a row), over the slant and sky paths and azimuths of [`plan_ron`]:
/// `[of the scattered sunlight, of the whole path radiance]` for lines of sight
/// [`AUREOLE_DEG`] or more from the sun, then the same for those closer.
fn worst(table: &SpectralAtmosphere, exact: &SpectralAtmosphere, zenith_deg: f64) -> [f64; 4] {
    let got = SunlitPaths::at_zenith(table, LO_UM, HI_UM, |_| 1.0, zenith_deg).unwrap();
    let want = SunlitPaths::at_zenith(exact, LO_UM, HI_UM, |_| 1.0, zenith_deg).unwrap();
    let mut out = [0.0_f64; 4];
    for az in [0.0, 90.0, 180.0] {
        let mut pairs = Vec::new();
        for nadir in [0.0, 60.0] {
            pairs.push((
                180.0 - nadir,
                got.path_radiance(1000.0, nadir, az),
                want.path_radiance(1000.0, nadir, az),
            ));
        }
        for h in [0.0, 1000.0] {
            for zenith in [0.0, 60.0, 85.0] {
                pairs.push((
                    zenith,
                    got.sky_radiance(h, zenith, az),
                    want.sky_radiance(h, zenith, az),
                ));
            }
        }
        for (los, g, w) in pairs {
            assert!(w.scattered_w_m2_sr > 0.0, "{zenith_deg}: {w:?}");
            let d = (g.scattered_w_m2_sr - w.scattered_w_m2_sr).abs();
            let k = if from_sun_deg(los, az, zenith_deg) >= AUREOLE_DEG {
                0
            } else {
                2
            };
            out[k] = out[k].max(d / w.scattered_w_m2_sr);
            out[k + 1] = out[k + 1].max(d / w.total_w_m2_sr());
        }
    }
    out
}

#[test]
fn the_scattered_sunlight_between_the_rows_of_one_build_is_lowtran7s_for_that_sun() {
    let dir = tempfile::tempdir().unwrap();
    let rows: Vec<f64> = irsig_atmosphere::plan::day_sun_grid_deg()
        .into_iter()
        .filter(|&z| (15.0..=88.0).contains(&z))
        .collect();
    let day = build(dir.path(), "day", &rows);
    let suns: Vec<f64> = HIGH.iter().chain(&LOW).copied().collect();
    let exact = build(dir.path(), "exact", &suns);
    let coarse = every_other_row(&day);
    // A row of the table is its own run, to the rounding of a logarithm and back.
    let own = SunlitPaths::at_zenith(&day, LO_UM, HI_UM, |_| 1.0, 60.0).unwrap();
    let s = day.solar.as_ref().unwrap();
    let row = s
        .zeniths_deg()
        .iter()
        .position(|&z| (z - 60.0).abs() < 1e-9)
        .unwrap();
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
    let mut worst_seen = Vec::new();
    println!(
        "sun zenith | rows 5 deg apart: of the scattered, of the path; within {AUREOLE_DEG} \
         deg of the sun, the same | rows 10 deg apart: the same"
    );
    for &z in &suns {
        let fine = worst(&day, &exact, z);
        let coarse = worst(&coarse, &exact, z);
        let pc = |v: [f64; 4]| {
            format!(
                "{:.3} % {:.3} %; {:.3} % {:.3} %",
                100.0 * v[0],
                100.0 * v[1],
                100.0 * v[2],
                100.0 * v[3]
            )
        };
        println!("{z:5.1} | {} | {}", pc(fine), pc(coarse));
        worst_seen.push((z, fine[0], fine[2]));
    }
    // The bounds docs/accuracy.md states with rows 5 deg apart: 0.5 % of the scattered
    // sunlight away from the sun (the floor, at every sun here, below 10 deg of elevation
    // too), 2 % within AUREOLE_DEG of it (where the sun's own aureole crosses the line of
    // sight between two rows: the phase function divided out, what is left is a dip of a
    // few per cent exactly on the sun whose cause docs/accuracy.md says was not found).
    for (z, away, near) in worst_seen {
        assert!(away < 0.005, "the sun at {z} deg: {away} away from the sun");
        assert!(near < 0.02, "the sun at {z} deg: {near} near the sun");
    }
    // The build measured the phase function at each of the sun's altitudes, on the sun
    // more than 3 times what it is 10 deg away (LOWTRAN7's rural aerosol's forward peak).
    let phase = day.solar.as_ref().unwrap().phase.as_ref().unwrap();
    let at = |deg: f64| {
        let k = phase
            .scattering_deg
            .iter()
            .position(|&t| (t - deg).abs() < 1e-9)
            .unwrap();
        let n = day.grid.points.len();
        phase.scattered_w_m2_sr_per_unit_per_m[k * n..(k + 1) * n]
            .iter()
            .map(|&v| f64::from(v))
            .sum::<f64>()
    };
    assert!(at(0.0) > 3.0 * at(10.0), "{} {}", at(0.0), at(10.0));
    // A sun outside the table's suns is refused, naming them.
    let e = SunlitPaths::at_zenith(&day, LO_UM, HI_UM, |_| 1.0, 12.0)
        .unwrap_err()
        .to_string();
    assert!(e.contains("from 15 to 88"), "{e}");
    the_tracer_reads_the_days_table_at_the_frames_sun(dir.path(), &day);
}

/// Through `irsig-trace --probe`: a plate on the ground seen from 1 km at nadir 60° and
/// 90° in azimuth from the sun (a node of both tables, far from the sun's aureole), by a
/// sun between the day table's rows. The scattered part of the pixel's path radiance (the
/// probe's `L_u` by day less the same at night) is the day table's interpolation at the
/// frame's sun (`SunlitPaths::at_zenith`), not a row's; and it lies within the
/// interpolation's stated 0.5 % of what the tracer gives through the table that holds
/// that sun as a row of its own.
fn the_tracer_reads_the_days_table_at_the_frames_sun(dir: &Path, day: &SpectralAtmosphere) {
    let (day_spa, exact_spa) = (dir.join("day.spa"), dir.join("exact.spa"));
    let scene = plate(dir, 0.0);
    let observer = (1000.0, direction(180.0 - 60.0, 90.0));
    let (lo, hi) = BAND.split_once('-').unwrap();
    let (lo, hi): (f64, f64) = (lo.parse().unwrap(), hi.parse().unwrap());
    let scattered_part = |spa: &Path, zenith_deg: f64| {
        let (z, a) = (zenith_deg.to_string(), SUN_AZIMUTH_DEG.to_string());
        let sun = ["--sun-zenith-deg", &z, "--sun-azimuth-deg", &a];
        probe(dir, spa, &scene, observer, false, &sun)["path"]
            - probe(dir, spa, &scene, observer, false, &[])["path"]
    };
    for zenith_deg in [47.3, 77.5] {
        let traced = scattered_part(&day_spa, zenith_deg);
        let read = SunlitPaths::at_zenith(day, lo, hi, |_| 1.0, zenith_deg)
            .unwrap()
            .path_radiance(1000.0, 60.0, 90.0)
            .scattered_w_m2_sr;
        let exact = scattered_part(&exact_spa, zenith_deg);
        println!(
            "traced by a sun at {zenith_deg} deg: scattered path radiance {traced:.5e} W/m2/sr \
             through the day table (its interpolation read directly {read:.5e}), {exact:.5e} \
             through the table with that sun as a row ({:+.2} %)",
            100.0 * (traced - exact) / exact
        );
        assert!((traced - read).abs() <= 1e-4 * read, "{traced} {read}");
        assert!((traced - exact).abs() <= 0.005 * exact, "{traced} {exact}");
    }
}
