//! `irsig-trace` with spectral materials, a sensor response and the 3-5 µm window, against
//! LOWTRAN7's own spectral integral (`irsig_tests::slant_plate`), the companion of
//! `spectral_trace.rs` (the sub-bands of a blackbody):
//!
//! - a material whose emissivity steps inside the band, or is given on a wavelength-angle
//!   grid, is averaged per sub-band and over the band as the integral of ε B says;
//! - a spectral curve short of the band is refused at its place;
//! - sub-bands with a sensor response file sum to the response-weighted integral;
//! - a built-in traces 3-5 µm at night and refuses a band it does not hold.

use irsig_tests::bin;
use irsig_tests::slant_plate::*;

/// A Lambertian material whose emissivity steps from 0.5 below 10 µm to 0.9 above
/// (between 10 and 10.000001 µm), with a flat angular shape.
const STEP: &str = "(materials: [(id: 1, name: \"step\", emissivity: [(0.0, 1.0), (90.0, 1.0)], \
    specular_fraction: 0.0, source: \"a step\",\n\
    spectral: Some((wavelength_um: [7.0, 10.0, 10.000001, 15.0], emissivity: [0.5, 0.5, 0.9, 0.9])))])";

#[test]
fn a_spectral_material_is_averaged_per_sub_band_and_over_the_band() {
    let dir = tempfile::tempdir().unwrap();
    let step = dir.path().join("step.ron");
    std::fs::write(&step, STEP).unwrap();
    let eps = |w: f64| if w <= 10.0 { 0.5 } else { 0.9 };
    let a = irsig_atmosphere::builtin_spectral("us-std-1976").unwrap();
    let s = a.slant.as_ref().unwrap();
    // Full grid: ∫ τ (ε B + (1 − ε) L_hemi) dλ + L_path by hand, from the built-in's
    // LOWTRAN7 spectra (10 µm is a grid point, so every grid interval lies on one side of
    // the step): within the 0.02 K of the full grid's floor.
    for (t_k, altitude_m, nadir_deg) in [(300.0, 1000.0, 0.0), (260.0, 300.0, 60.0)] {
        let (ai, ni) = (
            node(&s.altitude_m, altitude_m),
            node(&s.nadir_deg, nadir_deg),
        );
        let expected = apparent_k(lowtran_integral_of(&a, ai, ni, t_k, eps, &[1000.0], |_| {
            1.0
        }));
        let (full, n) = probe_with(
            dir.path(),
            Some(&step),
            "us-std-1976",
            Some("full"),
            t_k,
            altitude_m,
            nadir_deg,
        );
        assert_eq!(n, 108);
        let dt = apparent_k(full) - expected;
        eprintln!(
            "step material, {t_k} K from {altitude_m} m at {nadir_deg} deg: full grid {dt:+.4} K"
        );
        assert!(
            dt.abs() < 0.02,
            "{t_k} K, {altitude_m} m, {nadir_deg} deg: {dt} K"
        );
        // A grey material of the band-average emissivity is not the same thing: the step
        // weights the two halves of the band by the atmosphere as well.
        let grey = |e: f64| apparent_k(lowtran_integral_of(&a, ai, ni, t_k, |_| e, &[], |_| 1.0));
        assert!((grey(0.5) - expected).abs() > 1.0);
    }

    // The band model: the band average over 8-14 µm, Planck-weighted at 300 K,
    // (0.5 ∫₈¹⁰ B + 0.9 ∫₁₀¹⁴ B) / ∫₈¹⁴ B by the test's own Simpson sums, traced as a grey
    // material of that emissivity gives the same radiance.
    let planck_300 = |l: f64| planck_per_um(l, 300.0);
    let (low, high) = (
        simpson(8.0, 10.0, 4000, planck_300),
        simpson(10.0, 14.0, 4000, planck_300),
    );
    let mean = (0.5 * low + 0.9 * high) / (low + high);
    // 300 K: 19.44 of the 54.93 W m-2 sr-1 lie below 10 um (a midpoint sum of 20 000
    // intervals, separately), so ε̄ = 0.5 + 0.4 · 35.49 / 54.93 = 0.7584.
    assert!((mean - 0.7584).abs() < 1e-4, "{mean}");
    let grey = dir.path().join("grey.ron");
    std::fs::write(
        &grey,
        format!(
            "(materials: [(id: 1, name: \"grey\", emissivity: [(0.0, {mean:?}), (90.0, {mean:?})], \
             specular_fraction: 0.0, source: \"the step's band mean\")])"
        ),
    )
    .unwrap();
    for (t_k, altitude_m, nadir_deg) in [(300.0, 1000.0, 0.0), (260.0, 300.0, 60.0)] {
        let (band, one) = probe_with(
            dir.path(),
            Some(&step),
            "us-std-1976",
            None,
            t_k,
            altitude_m,
            nadir_deg,
        );
        let (reference, _) = probe_with(
            dir.path(),
            Some(&grey),
            "us-std-1976",
            None,
            t_k,
            altitude_m,
            nadir_deg,
        );
        assert_eq!(one, 1);
        assert!(
            (band / reference - 1.0).abs() < 1e-6,
            "{band} vs {reference}"
        );
    }
}

/// A material whose angular shape changes with wavelength: the step of [`STEP`] at normal
/// incidence, but at 60° the long-wavelength half falls to 0.3 while the short one stays
/// 0.5 (ε(λ, θ) on a grid, `spectral.angular`). No separable form ε(λ) · f(θ) gives that.
const CROSSED: &str = "(materials: [(id: 1, name: \"crossed\", emissivity: [(0.0, 1.0), (90.0, 1.0)], \
    specular_fraction: 0.0, source: \"a step whose halves part with angle\",\n\
    spectral: Some((wavelength_um: [7.0, 10.0, 10.000001, 15.0], emissivity: [0.5, 0.5, 0.9, 0.9], \
    angular: Some((angle_deg: [0.0, 60.0, 90.0], \
    emissivity: [[0.5, 0.5, 0.0], [0.5, 0.5, 0.0], [0.9, 0.3, 0.0], [0.9, 0.3, 0.0]])))))])";

#[test]
fn a_material_with_emissivity_on_a_wavelength_angle_grid_is_averaged_angle_by_angle() {
    let dir = tempfile::tempdir().unwrap();
    let crossed = dir.path().join("crossed.ron");
    std::fs::write(&crossed, CROSSED).unwrap();
    let a = irsig_atmosphere::builtin_spectral("us-std-1976").unwrap();
    let s = a.slant.as_ref().unwrap();
    // Seen at 60° (the plate is horizontal, so the incidence is the nadir angle): by hand
    // from the built-in's LOWTRAN7 spectra with ε = 0.5 below 10 µm and 0.3 above. The
    // separable form (the 0° curve times a flat shape) would give 0.5 and 0.9.
    let (t_k, altitude_m, nadir_deg) = (300.0, 300.0, 60.0);
    let (ai, ni) = (
        node(&s.altitude_m, altitude_m),
        node(&s.nadir_deg, nadir_deg),
    );
    let at_60 = |w: f64| if w <= 10.0 { 0.5 } else { 0.3 };
    let expected = apparent_k(lowtran_integral_of(
        &a,
        ai,
        ni,
        t_k,
        at_60,
        &[1000.0],
        |_| 1.0,
    ));
    let separable = apparent_k(lowtran_integral_of(
        &a,
        ai,
        ni,
        t_k,
        |w| if w <= 10.0 { 0.5 } else { 0.9 },
        &[1000.0],
        |_| 1.0,
    ));
    assert!((separable - expected).abs() > 5.0, "{separable} {expected}");
    let (full, n) = probe_with(
        dir.path(),
        Some(&crossed),
        "us-std-1976",
        Some("full"),
        t_k,
        altitude_m,
        nadir_deg,
    );
    assert_eq!(n, 108);
    let dt = apparent_k(full) - expected;
    assert!(dt.abs() < 0.02, "full grid {dt:+.4} K");
}

#[test]
fn a_spectral_curve_short_of_the_band_is_refused_at_its_place() {
    let dir = tempfile::tempdir().unwrap();
    let short = dir.path().join("short.ron");
    std::fs::write(
        &short,
        "(materials: [(id: 1, name: \"short\", emissivity: [(0.0, 1.0)],\n\
         specular_fraction: 0.0, source: \"x\",\n\
         spectral: Some((wavelength_um: [8.5, 14.0], emissivity: [0.9, 0.9])))])",
    )
    .unwrap();
    let view = dir.path().join("view.ron");
    std::fs::write(
        &view,
        "LookAt(position_m: (0.0, 0.0, 100.0), target_m: (0.0, 0.0, 1.0), up: (0.0, 1.0, 0.0), \
         pixels: (2, 2), fov_deg: (1.0, 1.0))",
    )
    .unwrap();
    let out = dir.path().join("out");
    for sub_bands in [None, Some("4")] {
        bin("irsig-trace")
            .arg("--scene")
            .arg(scene(dir.path(), 300.0))
            .arg("--materials")
            .arg(&short)
            .arg("--view")
            .arg(&view)
            .args(sub_bands.map(|k| ["--sub-bands", k]).into_iter().flatten())
            .arg("-o")
            .arg(&out)
            .assert()
            .code(1)
            .stderr(predicates::str::contains("short.ron:3:"))
            .stderr(predicates::str::contains("8.5"));
        assert_eq!(
            std::fs::read_dir(dir.path())
                .unwrap()
                .filter(|e| e
                    .as_ref()
                    .unwrap()
                    .file_name()
                    .to_string_lossy()
                    .starts_with("out"))
                .count(),
            0
        );
    }
}

/// A sensor response zero over 8–10 µm, rising to 1 at 11.11 µm, flat to 12.5 µm and
/// falling to 0.5 at 14 µm: its corners on LOWTRAN7's grid (1000, 900 and 800 cm⁻¹).
const RESPONSE: &str =
    "# wavelength_um response\n8.0 0\n10.0 0\n11.111111111111111 1\n12.5 1\n14.0 0.5\n";

/// The response of [`RESPONSE`] at `wavelength_um`, linear between its corners.
fn response(wavelength_um: f64) -> f64 {
    let corners = [
        (8.0, 0.0),
        (10.0, 0.0),
        (1e4 / 900.0, 1.0),
        (12.5, 1.0),
        (14.0, 0.5),
    ];
    corners
        .windows(2)
        .find(|w| wavelength_um <= w[1].0)
        .map_or(0.0, |w| {
            let t = (wavelength_um - w[0].0) / (w[1].0 - w[0].0);
            w[0].1 + t * (w[1].1 - w[0].1)
        })
}

/// `∫ S(λ) B(λ, T) dλ` over 8–14 µm, W m⁻² sr⁻¹: composite Simpson on each of the
/// response's linear pieces (600 intervals each).
fn response_band_radiance(t_k: f64) -> f64 {
    let corners = [8.0, 10.0, 1e4 / 900.0, 12.5, 14.0];
    corners
        .windows(2)
        .map(|w| simpson(w[0], w[1], 600, |l| response(l) * planck_per_um(l, t_k)))
        .sum()
}

/// The apparent temperature of a radiance in the response's band, K.
fn response_apparent_k(radiance: f64) -> f64 {
    invert(radiance, response_band_radiance)
}

#[test]
fn sub_bands_with_a_sensor_response_file_sum_to_the_response_weighted_integral() {
    let dir = tempfile::tempdir().unwrap();
    let srf = dir.path().join("sensor.srf");
    std::fs::write(&srf, RESPONSE).unwrap();
    let srf = srf.to_string_lossy().into_owned();
    let a = irsig_atmosphere::builtin_spectral("us-std-1976").unwrap();
    let s = a.slant.as_ref().unwrap();
    let black = dir.path().join("black.ron").to_string_lossy().into_owned();
    for (t_k, altitude_m, nadir_deg) in [(300.0, 1000.0, 0.0), (260.0, 3000.0, 70.0)] {
        let (ai, ni) = (
            node(&s.altitude_m, altitude_m),
            node(&s.nadir_deg, nadir_deg),
        );
        // ∫ S (τ B + L_path) dλ on LOWTRAN7's grid, the response's corners among its nodes.
        let integral = lowtran_integral_of(&a, ai, ni, t_k, |_| 1.0, &[], response);
        let expected = response_apparent_k(integral);
        let run = |band: &str, k: &str| {
            let args: Vec<String> = [
                "--materials",
                &black,
                "--atmosphere",
                "us-std-1976",
                "--band",
                band,
                "--sub-bands",
                k,
            ]
            .iter()
            .map(|a| (*a).to_owned())
            .collect();
            probe_args(dir.path(), &args, t_k, altitude_m, nadir_deg)
        };
        // The full grid: one sub-band per grid interval the response reaches, 10-14 um
        // (the 8-10 um intervals, where it is 0, are left out): 715-1000 cm-1 every 5,
        // 57 intervals, and 14 um (714.29 cm-1) to 715.
        let (full, n) = run(&srf, "full");
        assert_eq!(n, 58);
        let (sixteen, n16) = run(&srf, "16");
        assert!(n16 <= 16, "{n16}");
        let (band, one) = run(&srf, "1");
        assert_eq!(one, 1);
        let [full_k, sixteen_k, band_k] =
            [full, sixteen, band].map(|l| response_apparent_k(l) - expected);
        eprintln!(
            "response, {t_k} K from {altitude_m} m at {nadir_deg} deg: full {full_k:+.4} K, \
             16 {sixteen_k:+.4} K, band {band_k:+.4} K"
        );
        assert!(full_k.abs() < 0.02, "{full_k} K");
        assert!(sixteen_k.abs() < 0.02, "{sixteen_k} K");
        // The band model has the band-averaging error of docs/accuracy.md, no more: it
        // once added the flat 8-14 um tables' path and sky radiance to the response's
        // emission (+9 K here at 300 K through 1 km, +24 K at 260 K through 3 km at 70°).
        assert!(band_k.abs() < 2.0, "{band_k} K");
        assert!(
            band_k.abs() > 10.0 * full_k.abs(),
            "{band_k} K, full {full_k} K"
        );
        // The flat band over the same range is another sensor: a radiance that differs
        // by far more than these errors (the 8-10 um part, missing from the response,
        // holds a third of the 300 K band radiance).
        let (flat, _) = run("8-14", "full");
        let flat_expected = lowtran_integral(&a, ai, ni, t_k);
        assert!(
            (flat / flat_expected - 1.0).abs() < 1e-3,
            "{flat} vs {flat_expected}"
        );
        assert!((flat / full - 1.0).abs() > 0.3, "{flat} vs {full}");
        // A flat band other than the built-in tables' 8-14 um: the band model within the
        // band-averaging error of the full grid (0.05 K here), not off by the 12-14 um
        // path radiance.
        let (narrow_band, _) = run("8-12", "1");
        let (narrow_full, _) = run("8-12", "full");
        assert!(
            (narrow_band / narrow_full - 1.0).abs() < 0.01,
            "{narrow_band} vs {narrow_full}"
        );
    }
}

/// LOWTRAN7's 3–5 µm band values of the US Standard 1976 vertical path from `observer_m`
/// to 1 m (`crates/atmosphere/data/lowtran/us-std-1976/us-std-1976.mwir-band.csv`, written
/// by `scripts/atmosphere/regen.py --mwir` from LOWTRAN7's spectra before they were
/// quantised): band-mean τ and path radiance, W m⁻² sr⁻¹.
fn mwir_level(band_um: &str, observer_m: f64) -> (f64, f64) {
    let text = std::fs::read_to_string(
        irsig_tests::repo_root()
            .join("crates/atmosphere/data/lowtran/us-std-1976/us-std-1976.mwir-band.csv"),
    )
    .unwrap();
    text.lines()
        .map(|l| l.split(',').collect::<Vec<_>>())
        .find(|f| f[0] == band_um && f[1] == "level" && f[2].parse::<f64>() == Ok(observer_m))
        .map(|f| (f[4].parse().unwrap(), f[5].parse().unwrap()))
        .unwrap()
}

#[test]
fn a_builtin_traces_3_to_5_um_at_night_and_refuses_a_band_it_does_not_hold() {
    use irsig_radiometry::Band;
    let dir = tempfile::tempdir().unwrap();
    scene(dir.path(), 300.0);
    let black = dir.path().join("black.ron").to_string_lossy().into_owned();
    // A 300 K blackbody 1 km straight below, in 3-5 um and in 3.4-4.2 um (one band, the
    // band model: τ̄·L(300 K) + L_path, exact at a node): LOWTRAN7's band values.
    for (flag, band_um, lo, hi) in [
        ("3-5", "3.0-5.0", 3.0, 5.0),
        ("3.4-4.2", "3.4-4.2", 3.4, 4.2),
    ] {
        let args: Vec<String> = [
            "--materials",
            &black,
            "--atmosphere",
            "us-std-1976",
            "--band",
            flag,
        ]
        .iter()
        .map(|s| (*s).to_owned())
        .collect();
        let (l, n) = probe_args(dir.path(), &args, 300.0, 1000.0, 0.0);
        assert_eq!(n, 1);
        let band = Band::new(lo, hi).unwrap();
        let (tau, path) = mwir_level(band_um, 1000.0);
        let want = tau * band.radiance(300.0) + path;
        let error = band.temperature(l) - band.temperature(want);
        eprintln!("{flag} um, 300 K through 1 km: traced {l}, LOWTRAN7 {want}: {error:+.5} K");
        assert!(error.abs() < 0.002, "{flag}: {error} K");
    }
    let refused = |extra: &[&str]| {
        let out = bin("irsig-trace")
            .arg("--scene")
            .arg(scene(dir.path(), 300.0))
            .args(["--materials", &black, "--view"])
            .arg(dir.path().join("view.ron"))
            .args(["--atmosphere", "us-std-1976", "--probe", "0,0"])
            .args(extra)
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2));
        String::from_utf8_lossy(&out.stderr).into_owned()
    };
    // A band inside neither range: refused at its flag, naming both, each end rounded
    // inward (1e4/1350 = 7.407407, 1e4/710 = 14.084507, 1e4/3340 = 2.994012 um) so that
    // the ranges typed back are taken.
    for band in ["4-9", "2.5-4", "5-7.5"] {
        let e = refused(&["--band", band]);
        assert!(
            e.contains(&format!("--band {band}"))
                && e.contains("7.408-14.084 um")
                && e.contains("2.995-5.000 um"),
            "{band}: {e}"
        );
    }
    // By day: the built-ins are night atmospheres; the message says how to build a day one.
    let e = refused(&[
        "--band",
        "3-5",
        "--sun-zenith-deg",
        "30",
        "--sun-azimuth-deg",
        "0",
    ]);
    assert!(
        e.contains("night only") && e.contains("irsig-atmos plan"),
        "{e}"
    );
}
