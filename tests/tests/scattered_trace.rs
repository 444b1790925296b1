//! Scattered sunlight in the tracer: `irsig-trace` by day through an atmosphere
//! built with `--sun-scattering` against LOWTRAN7 run here for the same paths and sun
//! (IEMSCT = 2, decks written column by column). A small plan over the 3.4–4.1 µm window
//! (2440–2940 cm⁻¹ every 10), US Standard 1976 with a rural 10 km aerosol, sun at 30° on
//! day 172, is built by `irsig-atmos build` with real LOWTRAN7. Every path checked is
//! between the plan's rows in altitude, angle and azimuth:
//!
//! - **a sky pixel**: its radiance (thermal plus scattered) against LOWTRAN7's `TOTAL RAD`,
//!   and its scattered part (the pixel by day less the same pixel without the sun) against
//!   LOWTRAN7's scattered column;
//! - **a plate lit by the hemispheric sky**: the scattered part of its hemispheric sky
//!   (thesis eq. 5) against LOWTRAN7's scattered sky integrated over the hemisphere by a
//!   Gauss–Legendre rule in cos z and in azimuth;
//! - **facets above the ground seen along slant paths** (down onto a plate, and up at one):
//!   the scattered part of the path radiance (the probe's `L_u` by day less at night)
//!   against LOWTRAN7's for the path from the observer to the facet, within 1 % of the
//!   path radiance (the floor); the thermal part, the night's model, is printed
//!   beside.
//!
//! Values come from `irsig-trace --probe`. Errors are printed (`--nocapture`) for
//! docs/accuracy.md. LOWTRAN7 is `$IRSIG_LOWTRAN`, else `lowtran7` on PATH; never skipped.

use irsig_atmosphere::plan::RELATIVE_AZIMUTH_DEG;
use irsig_tests::hazy_day::{
    DAY, DV, SUN_ZENITH_DEG, V1, V2, band_integral, build, direction, lowtran_sunlit, plate, probe,
};

fn plan_ron() -> String {
    let az: Vec<String> = RELATIVE_AZIMUTH_DEG
        .iter()
        .map(|a| format!("{a:.1}"))
        .collect();
    format!(
        "(
  name: \"scattered\",
  model: Standard(6),
  wavenumber_per_cm: ({V1:.1}, {V2:.1}, {DV:.1}),
  path_end_m: 1.0,
  observers_m: [1000.0],
  levels_m: [50.0, 100.0, 200.0, 300.0, 500.0, 700.0, 1000.0],
  correction_altitude_m: 1000.0,
  correction_nadir_deg: [0.0, 20.0, 40.0],
  ground_sky_zenith_deg: [0.0, 10.0, 20.0, 30.0, 40.0, 50.0, 60.0, 70.0, 80.0, 90.0],
  hemispheric: [],
  slant_altitude_m: [100.0, 300.0, 500.0, 700.0, 1000.0],
  slant_nadir_deg: [30.0, 40.0, 50.0, 60.0],
  sky_altitude_m: [0.0, 300.0, 1000.0],
  sky_zenith_deg: [0.0, 10.0, 20.0, 30.0, 40.0, 50.0, 60.0, 70.0, 80.0, 90.0],
  sun: Some((
    zenith_deg: {SUN_ZENITH_DEG:.1},
    day_of_year: {DAY},
    altitude_m: [0.0, 300.0, 500.0, 700.0, 1000.0],
    relative_azimuth_deg: [{}],
  )),
  aerosol: Some((model: Rural, visibility_m: 10000.0)),
)
",
        az.join(", ")
    )
}

#[test]
fn the_tracers_scattered_sunlight_is_lowtran7s_between_rows() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let spa = build(d, "day", &plan_ron());

    // A sky pixel from 600 m (between the sun's 500 and 700 m rows), 35° from the zenith
    // (rows every 10°), 52.5° in azimuth from the sun (rows at 45 and 60°).
    let (h, zenith, az) = (600.0, 35.0, 52.5);
    let sky_scene = plate(d, 0.0);
    let look = direction(zenith, az);
    let day = probe(d, &spa, &sky_scene, (h, look), true, &[])["radiance"];
    let night = probe(d, &spa, &sky_scene, (h, look), false, &[])["radiance"];
    let rows = lowtran_sunlit(3, h / 1000.0, 0.0, zenith, az);
    let (total, scattered) = (
        band_integral(&rows, true, |r| r.total),
        band_integral(&rows, true, |r| r.scattered),
    );
    let sky_error = (day - total) / total;
    let sky_scattered_error = (day - night - scattered) / scattered;
    eprintln!(
        "sky pixel {h} m, zenith {zenith}, azimuth {az}: LOWTRAN7 {total:.5e} W/m2/sr ({:.1} % scattered); traced {day:.5e}: {:+.3} % of the radiance, {:+.2} % of the scattered part",
        100.0 * scattered / total,
        100.0 * sky_error,
        100.0 * sky_scattered_error
    );
    assert!(scattered > 0.2 * total, "{scattered} of {total}");
    assert!(sky_error.abs() < 0.01, "{sky_error}");
    assert!(sky_scattered_error.abs() < 0.02, "{sky_scattered_error}");

    // A plate at 600 m seen from 850 m: its hemispheric sky's scattered part against
    // LOWTRAN7's scattered sky over the hemisphere, (1/π)∫∫ L cos z dΩ = (2/π)∫₀^π ∫₀¹ L μ
    // dμ dφ, by Gauss–Legendre rules of 8 points in μ and 16 in φ.
    let plate_scene = plate(d, 600.0);
    let down = direction(180.0 - 40.0, 100.0);
    let day = probe(d, &spa, &plate_scene, (850.0, down), true, &[])["hemispheric"];
    let night = probe(d, &spa, &plate_scene, (850.0, down), false, &[])["hemispheric"];
    let (mu, wmu) = gauss_legendre(8, 0.0, 1.0);
    let (phi, wphi) = gauss_legendre(16, 0.0, 180.0);
    let mut jobs = Vec::new();
    for (i, &m) in mu.iter().enumerate() {
        for (j, &f) in phi.iter().enumerate() {
            jobs.push((m, f, wmu[i] * wphi[j].to_radians()));
        }
    }
    let hemi: f64 = std::thread::scope(|s| {
        let handles: Vec<_> = jobs
            .chunks(jobs.len().div_ceil(2))
            .map(|chunk| {
                s.spawn(move || {
                    chunk
                        .iter()
                        .map(|&(m, f, w)| {
                            let rows = lowtran_sunlit(3, 0.6, 0.0, m.acos().to_degrees(), f);
                            w * m * band_integral(&rows, true, |r| r.scattered)
                        })
                        .sum::<f64>()
                })
            })
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).sum::<f64>()
    }) * 2.0
        / std::f64::consts::PI;
    let hemi_error = (day - night - hemi) / hemi;
    eprintln!(
        "hemispheric sky at 600 m: LOWTRAN7's scattered part {hemi:.5e} W/m2/sr (thermal {night:.5e}); traced {:.5e}: {:+.2} %",
        day - night,
        100.0 * hemi_error
    );
    assert!(hemi_error.abs() < 0.02, "{hemi_error}");

    // Facets above the ground: the path radiance of the view path itself.
    // (observer m, facet m, zenith angle at the observer, azimuth from the sun, whether
    // the floor is asserted). Two paths are measured, not held to the floor, because the
    // model misses it there (docs/accuracy.md): the 87 m path and the path looking up.
    // Each is a difference of two longer paths, which LOWTRAN7's band model does not
    // obey: with LOWTRAN7's own terms at both ends the difference is +21.5 % and +6.4 %
    // of the scattered part (scripts/accuracy/slab-additivity.py). With slab tables (a plan
    // with `slabs`) both are held: tests/tests/slab_trace.rs.
    for (observer, facet, zenith, az, floor) in [
        (850.0, 150.0, 180.0 - 47.0, 100.0, true),
        (850.0, 50.0, 180.0 - 47.0, 100.0, true),
        (850.0, 400.0, 180.0 - 35.0, 15.0, true),
        (650.0, 600.0, 180.0 - 55.0, 165.0, false),
        (150.0, 800.0, 40.0, 70.0, false),
    ] {
        let scene = plate(d, facet);
        let terms = probe(
            d,
            &spa,
            &scene,
            (observer, direction(zenith, az)),
            true,
            &[],
        );
        let night = probe(
            d,
            &spa,
            &scene,
            (observer, direction(zenith, az)),
            false,
            &[],
        )["path"];
        let rows = lowtran_sunlit(2, observer / 1000.0, facet / 1000.0, zenith, az);
        let (total, scattered) = (
            band_integral(&rows, true, |r| r.total),
            band_integral(&rows, true, |r| r.scattered),
        );
        let error = (terms["path"] - total) / total;
        let scattered_error = (terms["path"] - night - scattered) / scattered;
        let thermal_error = (night - (total - scattered)) / total;
        // LOWTRAN7's τ of the path, the plain mean over the grid (the band is flat).
        let tau = rows.iter().map(|r| r.trans).sum::<f64>() / rows.len() as f64;
        eprintln!(
            "path {observer} m -> facet at {facet} m, zenith {zenith}, azimuth {az} (range {:.1} m, tau {:.4}, LOWTRAN7's {tau:.4}): LOWTRAN7 {total:.5e} W/m2/sr ({:.1} % scattered); traced {:.5e}: {:+.3} % of the path radiance, of which the thermal part {:+.3} % and the scattered part {:+.3} % ({:+.2} % of itself)",
            terms["range"],
            terms["transmission"],
            100.0 * scattered / total,
            terms["path"],
            100.0 * error,
            100.0 * thermal_error,
            100.0 * scattered_error * scattered / total,
            100.0 * scattered_error
        );
        assert!(scattered > 0.02 * total, "{scattered} of {total}");
        // The floor, for the scattered sunlight: its error within 1 % of the path
        // radiance. The thermal part is the night's model of a slab above the ground (the
        // `table` model's correction over the layered one, docs/accuracy.md), unchanged
        // by day and not this test's subject; its error is printed beside.
        let share = scattered_error * scattered / total;
        if floor {
            assert!(
                share.abs() < 0.01,
                "{observer} {facet} {zenith} {az}: {share}"
            );
        }
    }
}

/// The `n`-point Gauss–Legendre rule on `[a, b]`: nodes and weights (Newton on the
/// Legendre recurrence, Golub–Welsch's values to 1e-15).
fn gauss_legendre(n: usize, a: f64, b: f64) -> (Vec<f64>, Vec<f64>) {
    let (mut x, mut w) = (Vec::new(), Vec::new());
    for i in 0..n {
        let mut z = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 0.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, z);
            for k in 2..=n {
                let p2 = ((2 * k - 1) as f64 * z * p1 - (k - 1) as f64 * p0) / k as f64;
                p0 = p1;
                p1 = p2;
            }
            dp = n as f64 * (z * p1 - p0) / (z * z - 1.0);
            let dz = p1 / dp;
            z -= dz;
            if dz.abs() < 1e-15 {
                break;
            }
        }
        x.push(0.5 * (b - a) * z + 0.5 * (b + a));
        w.push((b - a) / ((1.0 - z * z) * dp * dp));
    }
    (x, w)
}
