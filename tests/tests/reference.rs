//! The converged reference through `irsig-trace`'s own flags (`irsig_trace::plan_of`,
//! `Plan::converge`): what the shipped pipelines' `--tolerance` rows are measured against
//! (`examples/tolerance_rows.rs`, docs/accuracy.md).

use clap::Parser;

const SIGMA: f64 = 5.670_374_419e-8;

/// A grey diffuse plate 4 km across at 300 K, ε 0.5, under a uniform sky of a 250 K
/// blackbody's total radiance, seen from 10 m straight down: every ray hits the plate and
/// every sky-view ray from it sees the sky, so each pixel's total radiance is
/// ε σ 300⁴/π + (1 − ε) σ 250⁴/π, and its apparent temperature (0.5 · 300⁴ + 0.5 · 250⁴)^¼
/// = 277.43… K, with no error to converge.
#[test]
fn the_reference_of_a_plate_under_a_uniform_sky_is_its_hand_temperature_with_no_error() {
    let dir = tempfile::tempdir().unwrap();
    let scene = irsig_tests::hazy_day::plate(dir.path(), 0.0);
    let materials = dir.path().join("grey.materials.ron");
    std::fs::write(
        &materials,
        "(materials: [(id: 1, name: \"grey\", emissivity: [(0.0, 0.5), (90.0, 0.5)], \
         specular_fraction: 0.0, source: \"a test\")])",
    )
    .unwrap();
    let view = dir.path().join("down.view.ron");
    std::fs::write(
        &view,
        "LookAt(position_m: (0.0, 0.0, 10.0), target_m: (0.0, 0.0, 0.0), up: (0.0, 1.0, 0.0), \
         pixels: (6, 4), fov_deg: (30.0, 20.0))",
    )
    .unwrap();
    let sky = SIGMA * 250.0_f64.powi(4) / std::f64::consts::PI;
    let sky = sky.to_string();
    let args = |more: &[&str]| {
        let mut a: Vec<String> = [
            "irsig-trace",
            "--scene",
            scene.to_str().unwrap(),
            "--materials",
            materials.to_str().unwrap(),
            "--view",
            view.to_str().unwrap(),
            "--band",
            "total",
            "--atmosphere",
            "none",
            "--sky-radiance",
            &sky,
        ]
        .map(str::to_owned)
        .to_vec();
        a.extend(more.iter().map(|s| (*s).to_owned()));
        irsig_trace::Cli::parse_from(a)
    };
    let plan = irsig_trace::plan_of(&args(&[])).unwrap();
    let references = plan.converge(0.01, 3).unwrap();
    assert_eq!(references.len(), 1, "one view, one reference");
    let r = &references[0];
    let hand = (0.5 * 300.0_f64.powi(4) + 0.5 * 250.0_f64.powi(4)).powf(0.25);
    for (i, (t, e)) in r.truth.iter().zip(&r.error).enumerate() {
        assert!(
            (t - hand).abs() < 1e-6,
            "pixel {i}: {t} K, by hand {hand} K"
        );
        assert!(e.abs() < 1e-6, "pixel {i}: its halves differ by {e} K");
    }
    assert_eq!(r.pixels_per_round, [24, 0, 0], "nothing to converge");
    assert!(r.capped.is_empty());

    // A stopping difference that is not above 0 K is refused before tracing.
    for bad in [0.0, -0.1, f64::NAN] {
        let e = irsig_trace::plan_of(&args(&[]))
            .unwrap()
            .converge(bad, 3)
            .unwrap_err();
        assert!(format!("{e}").contains("stopping difference"), "{bad}: {e}");
    }
}
