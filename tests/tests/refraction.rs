//! A low sun's beam at its apparent zenith. LOWTRAN7 takes a direct solar run's card 3
//! ANGLE as the apparent (refracted) zenith angle at H1; the sun stands at its geometric
//! zenith θ_g, so the beam that reaches H1 is the ray run at the θ_a for which θ_a +
//! BENDING(θ_a) = θ_g. `irsig-atmos build` of a plan with suns at 30°, 80° (10° up) and
//! 87° (3° up) is checked against LOWTRAN7 run here: this test finds θ_a on its own, by
//! bisection on the `BENDING = x DEG` LOWTRAN7 prints in TAPE6, then compares the build's
//! 3–5 and 8–14 µm beams with LOWTRAN7's at that angle (the floor: 1 %), and the
//! high sun's with LOWTRAN7's at its own angle, unchanged.
//!
//! LOWTRAN7 is `$IRSIG_LOWTRAN`, else `lowtran7` on PATH
//! (`sh scripts/atmosphere/install-lowtran.sh` builds it). When it is missing this test
//! fails, saying so: it never skips.

#![allow(clippy::float_cmp)] // angles copied through a deck

use irsig_atmosphere::solar::DirectSun;
use irsig_formats::canonical;
use irsig_tests::{bin, lowtran, run_lowtran};

/// The tropical model (LOWTRAN7's MODEL 1): the wettest air, the largest change of the
/// 8–14 µm beam with the sun's angle.
const MODEL: u32 = 1;
const DAY: u32 = 172;
/// 710–3335 cm⁻¹ every 5: 3–5 µm and 8–14 µm in one run (the bending depends on the range's
/// mean wavenumber, so the test's runs use the build's).
const V: [f64; 3] = [710.0, 3335.0, 5.0];
const SUNS_DEG: [f64; 3] = [30.0, 80.0, 87.0];
const ALTITUDES_M: [f64; 2] = [0.0, 1000.0];

fn plan_ron() -> String {
    format!(
        "(
  name: \"low-sun\",
  model: Standard({MODEL}),
  wavenumber_per_cm: ({:.1}, {:.1}, {:.1}),
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
    zenith_deg: {:.1},
    further_zenith_deg: [{:.1}, {:.1}],
    day_of_year: {DAY},
    altitude_m: [{:.1}, {:.1}],
  )),
)
",
        V[0], V[1], V[2], SUNS_DEG[0], SUNS_DEG[1], SUNS_DEG[2], ALTITUDES_M[0], ALTITUDES_M[1]
    )
}

/// A direct solar irradiance deck written here by columns (LOWTRAN7 user's guide: card 1
/// `13I5,F8.3,F7.2`, card 2 `6I5,5F10.3`, card 3's alternate form
/// `3F10.3,I5,5X,F10.3,I5,F10.3` H1 H2 ANGLE IDAY RO ISOURC ANGLEM, card 4, card 5).
fn deck(h1_km: f64, angle_deg: f64) -> String {
    format!(
        "{MODEL:5}    3    3    0    0    0    0    0    0    0    0    0    0   0.000   0.00\n\
         \x20   0    0    0    0    0    0     0.000     0.000     0.000     0.000     0.000\n\
         {h1_km:10.3}{:10.3}{angle_deg:10.3}{DAY:5}     {:10.3}{:5}{:10.3}\n\
         {:10.3}{:10.3}{:10.3}\n\
         \x20   0\n",
        0.0, 0.0, 0, 0.0, V[0], V[1], V[2]
    )
}

/// One run: the bending TAPE6 prints (`BENDING = x DEG`, read by words here) and the
/// TAPE7 rows `(ν cm⁻¹, τ, E_toa W cm⁻² per cm⁻¹)`.
fn run(h1_km: f64, angle_deg: f64) -> (f64, Vec<[f64; 3]>) {
    let out = run_lowtran(&deck(h1_km, angle_deg));
    let bending = out
        .tape6
        .lines()
        .find_map(|l| {
            let t = l.trim();
            t.strip_prefix("BENDING =")
                .and_then(|r| r.trim().strip_suffix("DEG"))
                .map(|v| v.trim().parse::<f64>().unwrap())
        })
        .expect("a BENDING line in TAPE6");
    let rows = out
        .tape7
        .lines()
        .skip_while(|l| !l.trim_start().starts_with("FREQ"))
        .skip(1)
        .take_while(|l| l.trim() != "-9999.")
        .map(|l| {
            let w: Vec<f64> = l.split_whitespace().map(|x| x.parse().unwrap()).collect();
            [w[0], w[1], w[3]]
        })
        .collect();
    (bending, rows)
}

/// The apparent zenith at `h1_km` of a sun at `geometric_deg`, by bisection on a 0.001°
/// grid of θ + BENDING(θ) − θ_g (increasing in θ): the angle of the two last bracketing
/// it whose residual is smaller.
fn apparent_by_bisection(h1_km: f64, geometric_deg: f64) -> f64 {
    let residual = |milli: i64| {
        #[allow(clippy::cast_precision_loss)]
        let a = milli as f64 / 1000.0;
        a + run(h1_km, a).0 - geometric_deg
    };
    #[allow(clippy::cast_possible_truncation)]
    let mut hi = (geometric_deg * 1000.0).round() as i64;
    let mut lo = hi - 1000;
    assert!(residual(lo) < 0.0 && residual(hi) >= 0.0);
    while hi - lo > 1 {
        let mid = (lo + hi) / 2;
        if residual(mid) > 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    let best = if residual(lo).abs() < residual(hi).abs() {
        lo
    } else {
        hi
    };
    #[allow(clippy::cast_precision_loss)]
    let a = best as f64 / 1000.0;
    a
}

/// `∫ τ E_toa dλ` over `[lo_um, hi_um]`, W m⁻²: the trapezoid in wavelength over the rows
/// inside the band, closed at each edge by a value linear in wavenumber (the rule
/// formats/canonical/spectral-atmosphere.md states for a band), from W cm⁻² per cm⁻¹.
fn band_beam(rows: &[[f64; 3]], lo_um: f64, hi_um: f64) -> f64 {
    let per_um = |r: &[f64; 3]| r[1] * r[2] * 1e4 * r[0] * r[0] / 1e4;
    let at_edge = |um: f64| -> (f64, f64) {
        let nu = 1e4 / um;
        let k = rows.iter().position(|r| r[0] >= nu).unwrap();
        if (rows[k][0] - nu).abs() < 1e-9 {
            return (um, per_um(&rows[k]));
        }
        let (a, b) = (&rows[k - 1], &rows[k]);
        let t = (nu - a[0]) / (b[0] - a[0]);
        (um, per_um(a) + t * (per_um(b) - per_um(a)))
    };
    let mut nodes = vec![at_edge(lo_um)];
    let mut inside: Vec<(f64, f64)> = rows
        .iter()
        .map(|r| (1e4 / r[0], per_um(r)))
        .filter(|&(l, _)| l > lo_um * (1.0 + 1e-12) && l < hi_um * (1.0 - 1e-12))
        .collect();
    inside.sort_by(|a, b| a.0.total_cmp(&b.0));
    nodes.extend(inside);
    nodes.push(at_edge(hi_um));
    nodes
        .windows(2)
        .map(|w| 0.5 * (w[0].1 + w[1].1) * (w[1].0 - w[0].0))
        .sum()
}

#[test]
fn a_low_suns_beam_is_lowtran7s_at_the_apparent_zenith_and_a_high_suns_is_unchanged() {
    let dir = tempfile::tempdir().unwrap();
    let plan = dir.path().join("plan.ron");
    std::fs::write(&plan, plan_ron()).unwrap();
    let out = dir.path().join("low-sun.spa");
    bin("irsig-atmos")
        .env("IRSIG_LOWTRAN", lowtran())
        .arg("build")
        .arg(&plan)
        .arg("-o")
        .arg(&out)
        .assert()
        .success();
    let a = canonical::read_spectral_atmosphere("built", &std::fs::read(&out).unwrap()).unwrap();
    let solar = a.solar.as_ref().expect("a solar table");
    assert_eq!(solar.zeniths_deg(), SUNS_DEG);
    // The table keeps the suns' geometric angles and records the angles run.
    let apparent = &solar.apparent_zenith_deg;
    assert_eq!(apparent.len(), SUNS_DEG.len() * ALTITUDES_M.len());
    assert!(a.source.contains("apparent zenith"), "{}", a.source);

    for (k, &z) in SUNS_DEG.iter().enumerate() {
        for (j, &h) in ALTITUDES_M.iter().enumerate() {
            let h_km = h / 1000.0;
            let run_at = apparent[k * ALTITUDES_M.len() + j];
            let truth_deg = if z < 60.0 {
                // A high sun: run at its own angle, unchanged to the 0.001 deg a deck holds
                // (LOWTRAN7 bends it 0.009 deg from the ground).
                assert_eq!(run_at, z, "sun at {z} deg, {h} m");
                z
            } else {
                let by_bisection = apparent_by_bisection(h_km, z);
                eprintln!(
                    "sun at {z} deg, {h} m: the build ran {run_at} deg, bisection on \
                     LOWTRAN7's BENDING finds {by_bisection} deg"
                );
                assert!(
                    (run_at - by_bisection).abs() <= 0.002,
                    "sun at {z} deg, {h} m: {run_at} against {by_bisection}"
                );
                by_bisection
            };
            let truth = run(h_km, truth_deg).1;
            let geometric = run(h_km, z).1;
            for (lo, hi) in [(3.0, 5.0), (8.0, 14.0)] {
                let built = DirectSun::new(&a, lo, hi, |_| 1.0)
                    .unwrap()
                    .at_zenith(z)
                    .unwrap()
                    .normal_w_m2(h);
                let (want, old) = (band_beam(&truth, lo, hi), band_beam(&geometric, lo, hi));
                let error = built / want - 1.0;
                eprintln!(
                    "{lo}-{hi} um, sun at {z} deg, {h} m: built {built:.5e} W m-2, LOWTRAN7 at \
                     {truth_deg} deg {want:.5e} ({:+.4} %); run at the geometric angle it \
                     would be {:+.3} %",
                    100.0 * error,
                    100.0 * (old / want - 1.0)
                );
                let floor = if z < 60.0 { 1e-6 } else { 0.01 };
                assert!(
                    error.abs() < floor,
                    "{lo}-{hi} um, {z} deg, {h} m: {error:+.3e}"
                );
                if z > 85.0 {
                    // The old beam, at the geometric angle, fails the floor: the test tells
                    // the two apart.
                    assert!(old / want - 1.0 < -0.01, "{lo}-{hi} um, {z} deg, {h} m");
                }
            }
        }
    }
}
