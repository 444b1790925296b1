//! Scattered sunlight in the tracer (issue 30): `irsig-trace` by day through an atmosphere
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
//!   path radiance (issue 30's floor); the thermal part, the night's model, is printed
//!   beside.
//!
//! Values come from `irsig-trace --probe`. Errors are printed (`--nocapture`) for
//! docs/accuracy.md. LOWTRAN7 is `$IRSIG_LOWTRAN`, else `lowtran7` on PATH; never skipped.

use std::path::Path;

use irsig_atmosphere::plan::RELATIVE_AZIMUTH_DEG;
use irsig_tests::{bin, lowtran};

const SUN_ZENITH_DEG: f64 = 30.0;
/// The sun's azimuth from north toward east, degrees: the view's azimuths are measured
/// from it.
const SUN_AZIMUTH_DEG: f64 = 120.0;
const DAY: u32 = 172;
const V1: f64 = 2440.0;
const V2: f64 = 2940.0;
const DV: f64 = 10.0;
/// The band traced: the grid's span, a hair inside its ends.
const BAND: &str = "3.40137-4.09836";
/// LOWTRAN7's card 2 for the plan's aerosol: rural (IHAZE 1), visibility 10 km.
const CARD2: &str =
    "    1    0    0    0    0    0    10.000     0.000     0.000     0.000     0.000";

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

/// One row of an IEMSCT = 2 TAPE7: wavenumber (cm⁻¹), the scattered and the total radiance
/// (W cm⁻² sr⁻¹ per cm⁻¹).
struct Row {
    nu: f64,
    trans: f64,
    scattered: f64,
    total: f64,
}

/// LOWTRAN7's radiance with single-scattered sunlight along one path (cards 1, 2, 3, 3A1
/// IPARM 2 IPH 2 IDAY ISOURC 0, 3A2 PARM1 = azimuth of the line of sight from the sun,
/// PARM2 = the sun's zenith, 4, 5): `itype` 2 from `h1_km` to `h2_km`, 3 from `h1_km` to
/// space, `angle_deg` the zenith angle at `h1_km`.
fn lowtran_sunlit(itype: u32, h1_km: f64, h2_km: f64, angle_deg: f64, az_deg: f64) -> Vec<Row> {
    let deck = format!(
        "    6{itype:5}    2    0    0    0    0    0    0    0    0    0    0   0.000   0.00\n\
         {CARD2}\n\
         {h1_km:10.3}{h2_km:10.3}{angle_deg:10.3}{:10.3}{:10.3}{:10.3}{:5}\n\
         \x20   2    2{DAY:5}    0\n\
         {az_deg:10.3}{SUN_ZENITH_DEG:10.3}{:10.3}{:10.3}{:10.3}{:10.3}{:10.3}{:10.3}\n\
         {V1:10.3}{V2:10.3}{DV:10.3}\n\
         \x20   0\n",
        0.0, 0.0, 0.0, 0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    );
    let t7 = irsig_tests::run_lowtran(&deck).tape7;
    let mut lines = t7
        .lines()
        .skip_while(|l| !l.trim_start().starts_with("FREQ"));
    let header = lines.next().expect("a column header in TAPE7");
    assert!(header.contains("TOTAL RAD"), "{header}\n{deck}");
    lines
        .take_while(|l| l.trim() != "-9999.")
        .map(|l| {
            let w: Vec<f64> = l.split_whitespace().map(|x| x.parse().unwrap()).collect();
            // FREQ TRANS THERMAL PATH-SCATTERED SINGLE GROUND GROUND-SINGLE TOTAL …
            Row {
                nu: w[0],
                trans: w[1],
                scattered: w[3],
                total: w[7],
            }
        })
        .collect()
}

/// `∫ L_λ dλ` over the grid, W m⁻² sr⁻¹, of a radiance per cm⁻¹ in W cm⁻² sr⁻¹ (per µm at
/// the points, `L_λ = L_ν ν² / 10⁴`, ×10⁴ for m⁻²; the trapezoid in wavelength).
fn band_integral(rows: &[Row], y: impl Fn(&Row) -> f64) -> f64 {
    let nodes: Vec<(f64, f64)> = rows
        .iter()
        .map(|r| (1e4 / r.nu, y(r) * r.nu * r.nu))
        .collect();
    nodes
        .windows(2)
        .map(|w| 0.5 * (w[0].1 + w[1].1) * (w[0].0 - w[1].0))
        .sum()
}

/// The direction of a line of sight `zenith_deg` from straight up and `azimuth_deg` from
/// the sun's azimuth, scene frame (x east, y north, z up).
fn direction(zenith_deg: f64, azimuth_deg: f64) -> [f64; 3] {
    let (sz, cz) = zenith_deg.to_radians().sin_cos();
    let (sa, ca) = (SUN_AZIMUTH_DEG + azimuth_deg).to_radians().sin_cos();
    [sz * sa, sz * ca, cz]
}

/// A horizontal blackbody square 4 km across at `z_m`, in `dir`.
fn plate(dir: &Path, z_m: f64) -> std::path::PathBuf {
    let scene = dir.join(format!("plate-{z_m}.raw.ron"));
    std::fs::write(
        &scene,
        format!(
            "(objects: [\"plate\"], \
             positions_m: [(-2e3, -2e3, {z_m:?}), (2e3, -2e3, {z_m:?}), \
                           (2e3, 2e3, {z_m:?}), (-2e3, 2e3, {z_m:?})], \
             facets: [(vertices: (0, 1, 2), material: 1, temperature_k: 300.0, object: 0), \
                      (vertices: (0, 2, 3), material: 1, temperature_k: 300.0, object: 0)])"
        ),
    )
    .unwrap();
    scene
}

/// The probe's terms of the one pixel of a view from `(0, 0, observer_m)` along `look`
/// (0.01° across) onto `scene` in the built atmosphere `spa`, with the sun or without.
fn probe(
    dir: &Path,
    spa: &Path,
    scene: &Path,
    observer_m: f64,
    look: [f64; 3],
    sun: bool,
) -> std::collections::HashMap<String, f64> {
    probe_with(dir, spa, scene, observer_m, look, sun, &[])
}

#[allow(clippy::too_many_arguments)]
fn probe_with(
    dir: &Path,
    spa: &Path,
    scene: &Path,
    observer_m: f64,
    look: [f64; 3],
    sun: bool,
    extra: &[&str],
) -> std::collections::HashMap<String, f64> {
    let view = dir.join("view.ron");
    let t = [
        look[0] * 100.0,
        look[1] * 100.0,
        observer_m + look[2] * 100.0,
    ];
    std::fs::write(
        &view,
        format!(
            "LookAt(position_m: (0.0, 0.0, {observer_m:?}), target_m: ({:?}, {:?}, {:?}), \
             up: (0.0, 0.0, 1.0), pixels: (1, 1), fov_deg: (0.01, 0.01))",
            t[0], t[1], t[2]
        ),
    )
    .unwrap();
    let materials = dir.join("materials.ron");
    std::fs::write(
        &materials,
        "(materials: [(id: 1, name: \"grey\", emissivity: [(0.0, 0.2), (90.0, 0.2)], \
         specular_fraction: 0.0, source: \"a test\")])",
    )
    .unwrap();
    let mut cmd = bin("irsig-trace");
    cmd.arg("--scene")
        .arg(scene)
        .arg("--materials")
        .arg(&materials)
        .arg("--view")
        .arg(&view)
        .arg("--atmosphere")
        .arg(spa)
        .args(["--band", BAND, "--probe", "0,0"])
        .args(extra);
    if sun {
        cmd.args(["--sun-zenith-deg", &SUN_ZENITH_DEG.to_string()])
            .args(["--sun-azimuth-deg", &SUN_AZIMUTH_DEG.to_string()]);
    }
    let out = cmd.output().unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    let mut terms = std::collections::HashMap::new();
    for line in text.lines() {
        for (label, key) in [
            ("L_d hemispheric", "hemispheric"),
            ("L_u (W m-2 sr-1)", "path"),
            ("L at sensor (W m-2 sr-1)", "radiance"),
            ("τ ", "transmission"),
            ("range_m", "range"),
        ] {
            if let Some(rest) = line.strip_prefix(label) {
                terms.insert(key.to_owned(), rest.trim().parse::<f64>().unwrap());
            }
        }
    }
    terms
}

#[test]
fn the_tracers_scattered_sunlight_is_lowtran7s_between_rows() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let p = d.join("plan");
    std::fs::create_dir(&p).unwrap();
    std::fs::write(p.join("plan.ron"), plan_ron()).unwrap();
    let spa = d.join("day.spa");
    let t = std::time::Instant::now();
    bin("irsig-atmos")
        .env("IRSIG_LOWTRAN", lowtran())
        .arg("build")
        .arg(&p)
        .args(["--model", "us-std-1976", "-o"])
        .arg(&spa)
        .assert()
        .success();
    eprintln!("built in {:.1} s", t.elapsed().as_secs_f64());

    // A sky pixel from 600 m (between the sun's 500 and 700 m rows), 35° from the zenith
    // (rows every 10°), 52.5° in azimuth from the sun (rows at 45 and 60°).
    let (h, zenith, az) = (600.0, 35.0, 52.5);
    let sky_scene = plate(d, 0.0);
    let look = direction(zenith, az);
    let day = probe(d, &spa, &sky_scene, h, look, true)["radiance"];
    let night = probe(d, &spa, &sky_scene, h, look, false)["radiance"];
    let rows = lowtran_sunlit(3, h / 1000.0, 0.0, zenith, az);
    let (total, scattered) = (
        band_integral(&rows, |r| r.total),
        band_integral(&rows, |r| r.scattered),
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
    let day = probe(d, &spa, &plate_scene, 850.0, down, true)["hemispheric"];
    let night = probe(d, &spa, &plate_scene, 850.0, down, false)["hemispheric"];
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
                            w * m * band_integral(&rows, |r| r.scattered)
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
        let terms = probe(d, &spa, &scene, observer, direction(zenith, az), true);
        let night = probe(d, &spa, &scene, observer, direction(zenith, az), false)["path"];
        let rows = lowtran_sunlit(2, observer / 1000.0, facet / 1000.0, zenith, az);
        let (total, scattered) = (
            band_integral(&rows, |r| r.total),
            band_integral(&rows, |r| r.scattered),
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
        // Issue 30's floor, for the scattered sunlight: its error within 1 % of the path
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
