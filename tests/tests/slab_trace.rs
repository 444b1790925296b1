//! Slab tables: view paths that end above the ground, from a
//! plan whose `slabs` ask LOWTRAN7 for slabs from each observer, against LOWTRAN7 run here
//! for the path itself (decks written column by column, nothing mocked). The atmosphere
//! is `scattered_trace.rs`'s (3.4–4.1 µm every 10 cm⁻¹, US Standard 1976, rural 10 km,
//! sun at 30° on day 172) with small slant and sky tables; the slab rows are targets at
//! 500, 575, 625, 700 and 900 m, nadir angles 40–70° and zenith angles 20–60°, and every
//! path checked lies between rows in target, angle and azimuth:
//!
//! - **by day**, the two paths the difference of two paths missed the floor on (650 m down
//!   to 600 m at nadir 55°, 165° from the sun; 150 m up to 800 m at zenith 40°, 70°): the
//!   scattered part of the probe's path radiance (by day less without the sun) within 1 %
//!   of LOWTRAN7's path radiance (the floor); the whole path radiance's error,
//!   thermal part included, and τ are printed for docs/accuracy.md;
//! - **at night** (a plan without a sun), the 87 m slab's thermal path radiance and τ;
//! - a frame whose paths the tables do not cover (its camera 10 m above their observer)
//!   says so once, with why; one they cover says nothing;
//! - a slab table out of order or of a wrong length is refused at its line, naming the
//!   field; a plan asking for slabs without observers is refused, naming the field.
//!
//! LOWTRAN7 is `$IRSIG_LOWTRAN`, else `lowtran7` on PATH; never skipped.

use irsig_atmosphere::plan::RELATIVE_AZIMUTH_DEG;
use irsig_tests::hazy_day::{
    BAND, DAY, DV, Row, SUN_ZENITH_DEG, V1, V2, band_integral, build, direction, lowtran_sunlit,
    plate, probe,
};
use irsig_tests::{bin, lowtran};

fn plan_ron(sun: bool, observers: &str) -> String {
    let az: Vec<String> = RELATIVE_AZIMUTH_DEG
        .iter()
        .map(|a| format!("{a:.1}"))
        .collect();
    let sun = if sun {
        format!(
            "sun: Some((zenith_deg: {SUN_ZENITH_DEG:.1}, day_of_year: {DAY}, \
             altitude_m: [0.0, 1000.0], relative_azimuth_deg: [{}])),",
            az.join(", ")
        )
    } else {
        String::new()
    };
    format!(
        "(
  name: \"slab\",
  model: Standard(6),
  wavenumber_per_cm: ({V1:.1}, {V2:.1}, {DV:.1}),
  path_end_m: 1.0,
  observers_m: [{observers}],
  levels_m: [50.0, 1000.0],
  correction_altitude_m: 1000.0,
  correction_nadir_deg: [0.0, 20.0, 40.0],
  ground_sky_zenith_deg: [0.0, 45.0, 90.0],
  hemispheric: [],
  slant_altitude_m: [100.0, 1000.0],
  slant_nadir_deg: [0.0, 30.0, 60.0],
  sky_altitude_m: [0.0, 1000.0],
  sky_zenith_deg: [0.0, 45.0, 90.0],
  {sun}
  aerosol: Some((model: Rural, visibility_m: 10000.0)),
  slabs: Some((
    target_m: [500.0, 575.0, 625.0, 700.0, 900.0],
    nadir_deg: [40.0, 50.0, 60.0, 70.0],
    zenith_deg: [20.0, 30.0, 50.0, 60.0],
  )),
)
"
    )
}

/// What `irsig-trace` says on stderr rendering 4 × 4 pixels of `scene` through `spa` from
/// `observer_m` up, looking along `look` (`probe`'s materials, already written in `dir`).
fn render_warnings(
    dir: &std::path::Path,
    spa: &std::path::Path,
    scene: &std::path::Path,
    observer_m: f64,
    look: [f64; 3],
) -> String {
    let view = dir.join("frame-view.ron");
    let t = look.map(|c| c * 100.0);
    std::fs::write(
        &view,
        format!(
            "LookAt(position_m: (0.0, 0.0, {observer_m:?}), target_m: ({:?}, {:?}, {:?}), \
             up: (0.0, 0.0, 1.0), pixels: (4, 4), fov_deg: (1.0, 1.0))",
            t[0],
            t[1],
            observer_m + t[2]
        ),
    )
    .unwrap();
    let out = bin("irsig-trace")
        .arg("--scene")
        .arg(scene)
        .arg("--materials")
        .arg(dir.join("materials.ron"))
        .arg("--view")
        .arg(&view)
        .arg("--atmosphere")
        .arg(spa)
        .args(["--band", BAND, "--sub-bands", "1", "-o"])
        .arg(dir.join("frame.exr"))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(out.status.success(), "{err}");
    err
}

/// LOWTRAN7's band-mean τ, `∫ τ dλ / ∫ dλ` (the band is flat).
fn band_tau(rows: &[Row]) -> f64 {
    band_integral(rows, false, |r| r.trans) / band_integral(rows, false, |_| 1.0)
}

#[test]
fn slab_tables_hold_lowtran7s_slabs_between_rows_by_day_and_at_night() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let day = build(d, "day", &plan_ron(true, "150.0, 650.0"));

    // (observer m, facet m, zenith angle at the observer, azimuth from the sun)
    for (observer, facet, zenith, az) in [
        (650.0, 600.0, 180.0 - 55.0, 165.0),
        (150.0, 800.0, 40.0, 70.0),
    ] {
        let scene = plate(d, facet);
        let look = direction(zenith, az);
        let lit = probe(d, &day, &scene, (observer, look), true, &[]);
        let dark = probe(d, &day, &scene, (observer, look), false, &[]);
        let rows = lowtran_sunlit(2, observer / 1000.0, facet / 1000.0, zenith, az);
        let total = band_integral(&rows, true, |r| r.total);
        let scattered = band_integral(&rows, true, |r| r.scattered);
        let thermal = band_integral(&rows, true, |r| r.thermal);
        let tau = band_tau(&rows);
        let error = (lit["path"] - total) / total;
        let scattered_share = (lit["path"] - dark["path"] - scattered) / total;
        let thermal_error = (dark["path"] - thermal) / thermal;
        eprintln!(
            "day: {observer} m -> facet at {facet} m, zenith {zenith}, azimuth {az} (range {:.1} m): \
             LOWTRAN7 {total:.5e} W/m2/sr ({:.1} % scattered), tau {tau:.4}; traced {:.5e}: \
             {:+.3} % of the path radiance, scattered part {:+.3} % of it ({:+.2} % of itself), \
             thermal part {:+.3} % of itself; tau {:.4} ({:+.4})",
            lit["range"],
            100.0 * scattered / total,
            lit["path"],
            100.0 * error,
            100.0 * scattered_share,
            100.0 * scattered_share * total / scattered,
            100.0 * thermal_error,
            lit["transmission"],
            lit["transmission"] - tau
        );
        assert!(scattered > 0.02 * total, "{scattered} of {total}");
        // The floor: the scattered sunlight within 1 % of the path radiance.
        assert!(
            scattered_share.abs() < 0.01,
            "{observer} {facet} {zenith} {az}: {scattered_share}"
        );
        // The thermal part and τ are the slab tables' too (they were −54 % and 0.009 off
        // with the night's model on the 87 m slab).
        assert!(thermal_error.abs() < 0.02, "{thermal_error}");
        assert!((lit["transmission"] - tau).abs() < 0.002);
    }

    // Night: a plan without a sun; the 87 m slab's thermal path radiance and τ.
    let night = build(d, "night", &plan_ron(false, "650.0"));
    let (observer, facet, zenith, az) = (650.0, 600.0, 180.0 - 55.0, 165.0);
    let scene = plate(d, facet);
    let terms = probe(
        d,
        &night,
        &scene,
        (observer, direction(zenith, az)),
        false,
        &[],
    );
    let rows = lowtran_sunlit(2, observer / 1000.0, facet / 1000.0, zenith, az);
    let thermal = band_integral(&rows, true, |r| r.thermal);
    let tau = band_tau(&rows);
    let error = (terms["path"] - thermal) / thermal;
    eprintln!(
        "night: {observer} m -> facet at {facet} m, zenith {zenith}: LOWTRAN7 {thermal:.5e} \
         W/m2/sr, tau {tau:.4}; traced {:.5e} ({:+.3} %), tau {:.4} ({:+.4})",
        terms["path"],
        100.0 * error,
        terms["transmission"],
        terms["transmission"] - tau
    );
    assert!(error.abs() < 0.02, "{error}");
    assert!((terms["transmission"] - tau).abs() < 0.002);

    // A frame whose paths the tables cover says nothing of them; from 10 m above the
    // tables' observer every path falls back, and the frame says so once, with why.
    let look = direction(zenith, az);
    let quiet = render_warnings(d, &night, &scene, observer, look);
    assert!(!quiet.contains("are not the slab tables'"), "{quiet}");
    let told = render_warnings(d, &night, &scene, observer + 10.0, look);
    assert_eq!(
        told.matches("are not the slab tables'").count(),
        1,
        "{told}"
    );
    assert!(
        told.contains("16 of the 16 view paths to facets (100.0 %)")
            && told.contains("16 because the observer is none of the tables'")
            && told.contains("the camera is at 660.0 m, the tables' observers at 650.0 m"),
        "{told}"
    );

    // A slab table out of order, or of a wrong length, is refused at its line and column,
    // naming the field.
    let ron = d.join("night.ron");
    bin("irsig-atmos")
        .env("IRSIG_LOWTRAN", lowtran())
        .arg("build")
        .arg(d.join("plan-night"))
        .args(["--atmosphere", "us-std-1976", "-o"])
        .arg(&ron)
        .assert()
        .success();
    let text = std::fs::read_to_string(&ron).unwrap();
    let up = "up: Some((target_m: [650.0, 700.0, 900.0], angle_deg: [20.0, 30.0, 50.0, 60.0], \
              transmission: [1.0, ";
    assert!(text.contains(up), "the night's up table from 650 m");
    for (bad, field) in [
        (
            text.replace(
                "target_m: [650.0, 700.0, 900.0]",
                "target_m: [650.0, 900.0, 700.0]",
            ),
            "`slabs[0].up.target_m[2]`",
        ),
        (
            text.replace(up, &up.replace("[1.0, ", "[")),
            "`slabs[0].up.transmission`",
        ),
    ] {
        let file = d.join("bad.ron");
        std::fs::write(&file, bad).unwrap();
        let out = bin("irsig-trace")
            .arg("--scene")
            .arg(&scene)
            .arg("--materials")
            .arg(d.join("materials.ron"))
            .arg("--view")
            .arg(d.join("view.ron"))
            .arg("--atmosphere")
            .arg(&file)
            .args(["--band", BAND, "--probe", "0,0"])
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success());
        assert!(err.contains("bad.ron:") && err.contains(field), "{err}");
    }

    // A plan asking for slabs without an observer to run them from.
    let p = d.join("plan-none");
    std::fs::create_dir(&p).unwrap();
    std::fs::write(p.join("plan.ron"), plan_ron(false, "")).unwrap();
    let out = bin("irsig-atmos")
        .env("IRSIG_LOWTRAN", lowtran())
        .arg("build")
        .arg(&p)
        .args(["--atmosphere", "us-std-1976", "-o"])
        .arg(d.join("none.spa"))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(
        err.contains("slabs") && err.contains("observers_m"),
        "{err}"
    );
}
