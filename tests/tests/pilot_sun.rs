//! The tolerance pilot by day, end to end: the quickstart scene at a
//! low noon sun (70° from the zenith, due north, as `pipelines/daylight.ron`), its
//! atmosphere built over 3–5 µm by real LOWTRAN7 runs, traced by `irsig-trace --tolerance
//! 1 --sun-zenith-deg 70` on a small view of the quickstart camera. The decision is
//! written beside the outputs and names the sun's two models: in 3–5 µm the sun stays on,
//! its measured effect in kelvin in the reason. The image is held to the tolerance
//! against a converged rendering (8 × 8 rays per pixel, 8 bounces, 16 sky-view rays, the
//! full spectral grid, 16 shadow rays per hit) from two seeds whose own difference is
//! checked, and the one-sub-band warning, which the pilot's measured choice makes moot,
//! is not given.
//!
//! LOWTRAN7 is `$IRSIG_LOWTRAN`, else `lowtran7` on PATH; this test never skips.

use std::path::Path;

use irsig_model::decision::{Decision, SwitchableModel};
use irsig_radiometry::Band;
use irsig_tests::{bin, lowtran};

const TOLERANCE_K: f64 = 1.0;

fn layer(path: &Path, name: &str) -> Vec<f64> {
    let r = irsig_raster::read_exr(
        &std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display())),
    )
    .unwrap();
    r.layer(name)
        .unwrap_or_else(|| panic!("{}: no layer {name}", path.display()))
        .data
        .iter()
        .map(|&v| f64::from(v))
        .collect()
}

/// The |x| below which `p` % of `values` lie.
fn percentile(values: &[f64], p: f64) -> f64 {
    let mut v: Vec<f64> = values.iter().map(|x| x.abs()).collect();
    v.sort_by(f64::total_cmp);
    let i = ((p / 100.0) * (v.len() - 1) as f64).ceil() as usize;
    v[i.min(v.len() - 1)]
}

#[test]
fn the_pilot_decides_the_sun_in_3_5_um_and_its_image_holds_the_tolerance() {
    let start = std::time::Instant::now();
    let dir = tempfile::tempdir().unwrap();
    let plan = irsig_tests::quickstart_plan(
        dir.path(),
        "plan.ron",
        &["--atmosphere", "midlat-winter"],
        &[
            "--sun-zenith-deg",
            "70",
            "--day-of-year",
            "172",
            "--wavenumber-per-cm",
            "1980,3340,20",
        ],
    );
    let spa = dir.path().join("noon.spa");
    bin("irsig-atmos")
        .env("IRSIG_LOWTRAN", lowtran())
        .arg("build")
        .arg(&plan)
        .arg("-o")
        .arg(&spa)
        .assert()
        .success();
    eprintln!("atmosphere built in {:.1} s", start.elapsed().as_secs_f64());
    // The quickstart camera at 64 x 48 pixels.
    let view = dir.path().join("small.ron");
    std::fs::write(
        &view,
        "LookAt(position_m: (0.0, -22.6851, 5.0), target_m: (1.5, 0.0, 1.0), \
         pixels: (64, 48), fov_deg: (47.0, 36.0))",
    )
    .unwrap();
    let trace = |prefix: &str, extra: &[&str]| {
        let out = bin("irsig-trace")
            .arg("--scene")
            .arg(dir.path().join("scene.raw"))
            .args(["--materials", "pipelines/daylight/materials.ron"])
            .arg("--view")
            .arg(&view)
            .arg("--atmosphere")
            .arg(&spa)
            .args(["--band", "3-5"])
            .args(["--sun-zenith-deg", "70", "--sun-azimuth-deg", "0"])
            .args(extra)
            .arg("-o")
            .arg(dir.path().join(prefix))
            .assert()
            .success();
        String::from_utf8_lossy(&out.get_output().stderr).into_owned()
    };
    let t = std::time::Instant::now();
    let stderr = trace("tol", &["--tolerance", &TOLERANCE_K.to_string()]);
    let piloted_s = t.elapsed().as_secs_f64();
    assert!(
        !stderr.contains("one sub-band (the default)"),
        "the pilot chose the sub-bands, yet: {stderr}"
    );
    let text = std::fs::read_to_string(dir.path().join("tol.decision.ron")).unwrap();
    let d: Decision = irsig_formats::canonical::from_ron("decision", &text).unwrap();
    let sun = d.choice(SwitchableModel::Sun).expect("the sun's choice");
    let shadow = d
        .choice(SwitchableModel::ShadowRays)
        .expect("the shadow rays");
    let sub_bands = d.choice(SwitchableModel::SubBands).expect("the sub-bands");
    eprintln!(
        "decision at {TOLERANCE_K} K: sun {} ({}); shadow rays {} ({}); sub-bands {} ({}), \
         sub-band error {:.4} K; relative cost {:.3}; traced in {piloted_s:.1} s",
        sun.setting,
        sun.reason,
        shadow.setting,
        shadow.reason,
        sub_bands.setting,
        sub_bands.reason,
        sub_bands.error.percentile_k,
        d.relative_cost
    );
    // In 3-5 um the sun's reflected beam is kelvins on the low-emissivity surfaces.
    assert_eq!(sun.setting, "on", "{}", sun.reason);
    assert!(sun.reason.contains("K at worst"), "{}", sun.reason);
    assert!(
        d.relative_to.contains("the sun on, 64 shadow rays"),
        "{}",
        d.relative_to
    );

    let reference = |prefix: &str, seed: &str| {
        trace(
            prefix,
            &[
                "--supersample",
                "8",
                "--bounces",
                "8",
                "--sky-view-rays",
                "16",
                "--sub-bands",
                "full",
                "--sun-shadow-rays",
                "16",
                "--seed",
                seed,
            ],
        );
    };
    reference("ref-a", "11");
    reference("ref-b", "22");
    let band = Band::new(3.0, 5.0).unwrap();
    let kelvin = |prefix: &str| -> Vec<f64> {
        layer(
            &dir.path().join(format!("{prefix}.radiance.exr")),
            "radiance",
        )
        .iter()
        .map(|&l| band.temperature(l))
        .collect()
    };
    let (a, b, got) = (kelvin("ref-a"), kelvin("ref-b"), kelvin("tol"));
    let noise: Vec<f64> = a.iter().zip(&b).map(|(a, b)| 0.5 * (a - b)).collect();
    let truth: Vec<f64> = a.iter().zip(&b).map(|(a, b)| 0.5 * (a + b)).collect();
    let marked = layer(&dir.path().join("tol.truth.exr"), "not_guaranteed");
    let error: Vec<f64> = got
        .iter()
        .zip(&truth)
        .zip(&marked)
        .filter(|(_, m)| **m == 0.0)
        .map(|((g, t), _)| g - t)
        .collect();
    let (p99, noise_p99) = (percentile(&error, 99.0), percentile(&noise, 99.0));
    let marked_share = marked.iter().filter(|&&m| m != 0.0).count() as f64 / marked.len() as f64;
    eprintln!(
        "3-5 um by day at {TOLERANCE_K} K: p99 |dT| {p99:.3} K against the converged \
         rendering (its own noise p99 {noise_p99:.3} K), {:.2} % not guaranteed; {:.0} s \
         in all",
        100.0 * marked_share,
        start.elapsed().as_secs_f64()
    );
    assert!(noise_p99 < TOLERANCE_K / 3.0, "{noise_p99}");
    assert!(p99 <= TOLERANCE_K, "p99 {p99:.3} K");
    assert!(marked_share <= 0.005, "{marked_share}");
}
