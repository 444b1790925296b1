//! The scene material library, `pipelines/materials/scene-library.ron`: what its script
//! makes from the committed sources, byte for byte; read by the canonical reader with every
//! check; every material over 3-14 um with a source, a licence and thermal properties;
//! physical bounds; a Fresnel material against a hand computation; spectra
//! against independent published values; the library traced on the quickstart scene in
//! both bands at night; and every material's thermal record solved by `irsig-therm`
//! through summer days in Golden, Colorado.

use std::path::Path;

use irsig_model::MaterialLibrary;
use irsig_radiometry::{Band, band_average_emissivity};

const LIBRARY: &str = "pipelines/materials/scene-library.ron";

fn library() -> MaterialLibrary {
    let text = std::fs::read_to_string(irsig_tests::repo_root().join(LIBRARY)).unwrap();
    irsig_formats::canonical::from_ron(LIBRARY, &text).unwrap()
}

fn material<'a>(lib: &'a MaterialLibrary, name: &str) -> &'a irsig_model::Material {
    lib.by_name(name)
        .unwrap_or_else(|| panic!("no material `{name}`"))
}

/// The value of a spectral curve at one of its own wavelengths.
fn at(wavelength_um: &[f64], values: &[f64], lam: f64) -> f64 {
    let i = wavelength_um
        .iter()
        .position(|&w| (w - lam).abs() < 1e-9)
        .unwrap_or_else(|| panic!("{lam} um is not on the curve's grid"));
    values[i]
}

/// Linear interpolation in increasing `xs`.
fn interp(xs: &[f64], ys: &[f64], x: f64) -> f64 {
    let k = xs.partition_point(|&v| v <= x).clamp(1, xs.len() - 1);
    let t = (x - xs[k - 1]) / (xs[k] - xs[k - 1]);
    ys[k - 1] + t * (ys[k] - ys[k - 1])
}

/// The `wavelength n k` rows of a refractiveindex.info page's `tabulated nk` block, by a
/// plain split.
fn nk_rows(page: &str) -> Vec<[f64; 3]> {
    let path = irsig_tests::repo_root()
        .join("pipelines/materials/sources/refractiveindex")
        .join(page);
    let mut rows: Vec<[f64; 3]> = std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .filter_map(|l| {
            let v: Vec<f64> = l
                .split_whitespace()
                .map(str::parse)
                .collect::<Result<_, _>>()
                .ok()?;
            (v.len() == 3).then(|| [v[0], v[1], v[2]])
        })
        .collect();
    rows.sort_by(|a, b| a[0].total_cmp(&b[0]));
    rows
}

/// `x` rounded to 6 significant digits, as the script hands n and k to the Fresnel tool.
fn six_digits(x: f64) -> f64 {
    format!("{x:.5e}").parse().unwrap()
}

/// A complex number as (re, im), and the few operations the Fresnel equations need.
type C = (f64, f64);
fn mul(a: C, b: C) -> C {
    (a.0 * b.0 - a.1 * b.1, a.0 * b.1 + a.1 * b.0)
}
fn div(a: C, b: C) -> C {
    let d = b.0 * b.0 + b.1 * b.1;
    ((a.0 * b.0 + a.1 * b.1) / d, (a.1 * b.0 - a.0 * b.1) / d)
}
fn sub(a: C, b: C) -> C {
    (a.0 - b.0, a.1 - b.1)
}
fn add(a: C, b: C) -> C {
    (a.0 + b.0, a.1 + b.1)
}
fn norm2(a: C) -> f64 {
    a.0 * a.0 + a.1 * a.1
}
/// The principal square root.
fn sqrt(a: C) -> C {
    let r = norm2(a).sqrt();
    let re = ((r + a.0) / 2.0).sqrt();
    let im = ((r - a.0) / 2.0).sqrt().copysign(a.1);
    (re, im)
}

/// 1 - R of unpolarised light from air onto a smooth surface of index n + ik at `theta_deg`
/// (Born & Wolf, §13.2: r_s = (cos θ − N cos θt)/(cos θ + N cos θt), r_p = (N cos θ − cos
/// θt)/(N cos θ + cos θt), N cos θt = sqrt(N² − sin² θ)).
fn fresnel_emissivity(n: f64, k: f64, theta_deg: f64) -> f64 {
    let (s, c) = theta_deg.to_radians().sin_cos();
    let big_n = (n, k);
    let n2 = mul(big_n, big_n);
    let n_cos_t = sqrt(sub(n2, (s * s, 0.0)));
    let rs = div(sub((c, 0.0), n_cos_t), add((c, 0.0), n_cos_t));
    // r_p = (N² cos θ − N cos θt) / (N² cos θ + N cos θt), the form without cos θt alone.
    let n2c = mul(n2, (c, 0.0));
    let rp = div(sub(n2c, n_cos_t), add(n2c, n_cos_t));
    1.0 - 0.5 * (norm2(rs) + norm2(rp))
}

#[test]
fn the_scene_library_is_what_its_script_makes() {
    // Remade by its script with this build's irsig-material: the same bytes.
    let root = irsig_tests::repo_root();
    let out = std::process::Command::new("python3")
        .arg("pipelines/materials/scene-library.py")
        .env("IRSIG_MATERIAL", irsig_tests::bin_path("irsig-material"))
        .current_dir(&root)
        .output()
        .expect("python3 runs (it regenerates committed data: README, Set-up)");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let committed = std::fs::read(root.join(LIBRARY)).unwrap();
    assert!(
        out.stdout == committed,
        "scene-library.ron is not what scene-library.py makes"
    );
}

#[test]
fn every_material_covers_3_to_14_um_with_its_source_licence_and_thermal_record() {
    let lib = library();
    assert!(lib.materials.len() >= 14, "{}", lib.materials.len());
    let bands = [Band::new(3.0, 5.0).unwrap(), Band::new(8.0, 14.0).unwrap()];
    for m in &lib.materials {
        let s = m.spectral.as_ref().unwrap_or_else(|| panic!("{}", m.name));
        // Covered, so the tracer averages rather than refuses it in either band.
        assert!(s.wavelength_um[0] <= 3.0 && *s.wavelength_um.last().unwrap() >= 14.0);
        for band in &bands {
            let e = band_average_emissivity(&s.wavelength_um, &s.emissivity, band, 300.0)
                .unwrap_or_else(|e| panic!("{}: {e}", m.name));
            assert!((0.0..=1.0).contains(&e), "{}: {e}", m.name);
        }
        // Physical bounds everywhere: the curve, the grid and the table.
        let grid = s.angular.iter().flat_map(|a| a.emissivity.iter().flatten());
        for &e in s.emissivity.iter().chain(grid) {
            assert!((0.0..=1.0).contains(&e), "{}: {e}", m.name);
        }
        for &(a, e) in &m.emissivity {
            assert!(
                (0.0..=90.0).contains(&a) && (0.0..=1.0).contains(&e),
                "{}",
                m.name
            );
        }
        assert!((0.0..=1.0).contains(&m.specular_fraction));
        // A source naming its licence, and a thermal record whose every layer cites a
        // table.
        assert!(
            ["CC0 1.0", "Apache-2.0"]
                .iter()
                .any(|l| m.source.contains(l)),
            "{}: {}",
            m.name,
            m.source
        );
        let t = m
            .thermal
            .as_ref()
            .unwrap_or_else(|| panic!("{}: no thermal record", m.name));
        t.validate(&m.name).unwrap();
        assert!(!t.source.is_empty());
        for layer in &t.layers {
            assert!(
                layer.source.contains("Table"),
                "{}: {}",
                m.name,
                layer.source
            );
        }
        // Solar absorptance: given, or from a curve that covers 0.3-4 um.
        assert!(
            t.solar_absorptance.is_some() || s.wavelength_um[0] <= 0.3,
            "{}",
            m.name
        );
    }
}

#[test]
fn fresnel_materials_agree_with_a_hand_computation() {
    let lib = library();
    // Glass at 10 um, normal incidence: Rubin's tabulated row there, n 1.707, k 1.123,
    // R = ((n-1)^2 + k^2) / ((n+1)^2 + k^2) = 1.760978 / 8.588978 = 0.205028.
    let glass = material(&lib, "glass (window)").spectral.as_ref().unwrap();
    let by_hand =
        1.0 - (0.707_f64.powi(2) + 1.123_f64.powi(2)) / (2.707_f64.powi(2) + 1.123_f64.powi(2));
    assert!((by_hand - 0.794_972).abs() < 1e-6, "{by_hand}");
    assert!((at(&glass.wavelength_um, &glass.emissivity, 10.0) - by_hand).abs() <= 5.1e-7);
    // Aluminium at 10 um and 60 deg: Rakic's n, k interpolated there as the script does
    // (linearly, to 6 digits), the full complex Fresnel equations by hand.
    let rows = nk_rows("aluminium-rakic.yml");
    let xs: Vec<f64> = rows.iter().map(|r| r[0]).collect();
    let n = six_digits(interp(
        &xs,
        &rows.iter().map(|r| r[1]).collect::<Vec<_>>(),
        10.0,
    ));
    let k = six_digits(interp(
        &xs,
        &rows.iter().map(|r| r[2]).collect::<Vec<_>>(),
        10.0,
    ));
    let al = material(&lib, "aluminium (polished)")
        .spectral
        .as_ref()
        .unwrap();
    let grid = al.angular.as_ref().unwrap();
    let i = al
        .wavelength_um
        .iter()
        .position(|&w| (w - 10.0).abs() < 1e-9)
        .unwrap();
    let j = grid
        .angle_deg
        .iter()
        .position(|&a| (a - 60.0).abs() < 1e-9)
        .unwrap();
    let hand = fresnel_emissivity(n, k, 60.0);
    assert!(
        (grid.emissivity[i][j] - hand).abs() <= 5.1e-7,
        "{} vs {hand}",
        grid.emissivity[i][j]
    );
    // And at normal incidence the curve is the grid's first column.
    assert!((al.emissivity[i] - fresnel_emissivity(n, k, 0.0)).abs() <= 5.1e-7);
}

#[test]
fn spectra_agree_with_independent_published_values() {
    let lib = library();
    // Water near 10 um at normal incidence: 0.99 (Masuda, Takashima & Takayama 1988,
    // Remote Sens. Environ. 24, 313, sea-surface emissivity at nadir, 10-12 um).
    let water = material(&lib, "water").spectral.as_ref().unwrap();
    let e = at(&water.wavelength_um, &water.emissivity, 10.0);
    assert!((e - 0.99).abs() < 0.003, "{e}");
    // Aluminium at 10 um, normal: the free-electron (Drude) metal of Ordal et al. (1985,
    // Appl. Opt. 24, 4493), plasma frequency 1.19e5 cm-1 and damping 660 cm-1, gives
    // eps = 1 - wp^2/(w^2 + i w g) at w = 1000 cm-1, N = sqrt(eps), and 1 - R = 0.0105:
    // an independent set of optical constants. Handbook values for polished sheet,
    // 0.02-0.05 (Incropera & DeWitt Table A.13: 0.03), are higher by the oxide and
    // roughness a clean film lacks; README.md says so.
    let (wp, g, w) = (1.19e5_f64, 660.0_f64, 1000.0_f64);
    let d = w * w + g * g;
    let eps = (1.0 - wp * wp / d, wp * wp * g / (w * d));
    let big_n = sqrt(eps);
    let drude = fresnel_emissivity(big_n.0, big_n.1, 0.0);
    assert!((drude - 0.0105).abs() < 5e-4, "{drude}");
    let al = material(&lib, "aluminium (polished)")
        .spectral
        .as_ref()
        .unwrap();
    let e = at(&al.wavelength_um, &al.emissivity, 10.0);
    assert!((e - drude).abs() < 0.003, "{e} vs {drude}");
    assert!(e < 0.02);
}

/// Traces the quickstart scene, flattened with the scene library's materials in the
/// quickstart's material slots, at night through a built-in atmosphere in `band`; returns
/// the apparent temperatures of every pixel.
fn trace_quickstart_with_the_library(dir: &Path, band: &str) -> Vec<f32> {
    // The quickstart's objects name five materials; the library's first five stand in
    // for them by id (water, two ices, two snows), enough to exercise every material
    // class the scene has.
    let raw = dir.join("scene.raw");
    irsig_tests::bin("irsig-flatten")
        .arg("pipelines/quickstart/scene.ron")
        .args(["--materials", "pipelines/quickstart/materials.ron", "-o"])
        .arg(&raw)
        .assert()
        .success();
    let truth = dir.join(format!("{band}.truth.exr"));
    irsig_tests::bin("irsig-trace")
        .arg("--scene")
        .arg(&raw)
        .args(["--materials", LIBRARY])
        .args(["--view", "pipelines/quickstart/view.ron"])
        .args(["--atmosphere", "us-std-1976", "--band", band, "--truth-exr"])
        .arg(&truth)
        .arg("--radiance-exr")
        .arg(dir.join(format!("{band}.radiance.exr")))
        .assert()
        .success();
    let raster = irsig_raster::read_exr(&std::fs::read(&truth).unwrap()).unwrap();
    raster.layer("apparent_temperature").unwrap().data.clone()
}

#[test]
fn the_library_traces_the_quickstart_scene_in_both_bands_at_night() {
    let dir = tempfile::tempdir().unwrap();
    for band in ["8-14", "3-5"] {
        let t = trace_quickstart_with_the_library(dir.path(), band);
        assert!(!t.is_empty());
        // Apparent temperatures are physical: the sky is colder than the ground, and
        // nothing is colder than deep space's view through the atmosphere or hotter than
        // the hottest facet (the panel, 325 K).
        for &v in &t {
            assert!(
                v.is_finite() && (150.0..=330.0).contains(&v),
                "{band}: {v} K"
            );
        }
    }
}

#[test]
fn every_thermal_record_is_solved_through_a_summer_day() {
    // One horizontal 1 m square per material, 3 m apart, under the sample TMY3 weather of
    // Golden, Colorado (formats/samples), solved for 48 hours up to 19:00 UTC on 7 August
    // (noon at the site, air 31 C, direct normal irradiance 769 W/m2 the hour before).
    let lib = library();
    let n = lib.materials.len();
    let mut positions = String::new();
    let mut facets = String::new();
    for (i, m) in lib.materials.iter().enumerate() {
        let x = 3.0 * i as f64;
        for (dx, dy) in [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)] {
            positions += &format!("({:.1}, {dy:.1}, 0.0), ", x + dx);
        }
        let v = 4 * i;
        for tri in [[v, v + 1, v + 2], [v, v + 2, v + 3]] {
            facets += &format!(
                "(vertices: ({}, {}, {}), material: {}, temperature_k: 300.0, object: {i}), ",
                tri[0], tri[1], tri[2], m.id.0
            );
        }
    }
    let objects: Vec<String> = (0..n).map(|i| format!("\"m{i}\"")).collect();
    let scene = format!(
        "(terrain: (temperature_k: 300.0, emissivity: 0.95), objects: [{}], positions_m: [{positions}], facets: [{facets}])",
        objects.join(", ")
    );
    let dir = tempfile::tempdir().unwrap();
    let scene_path = dir.path().join("squares.ron");
    std::fs::write(&scene_path, scene).unwrap();
    let prefix = dir.path().join("noon");
    irsig_tests::bin("irsig-therm")
        .arg(&scene_path)
        .args(["--materials", LIBRARY])
        .args(["--weather", "formats/samples/golden-tmy3-aug.epw"])
        .args(["--at", "2026-08-07T19:00Z", "--spin-up-h", "48", "-o"])
        .arg(&prefix)
        .assert()
        .success();
    let bytes = std::fs::read(dir.path().join("noon.raw")).unwrap();
    let solved = irsig_formats::canonical::read_raw_scene("noon.raw", &bytes).unwrap();
    let t = |name: &str| {
        let slot = lib.materials.iter().position(|m| m.name == name).unwrap();
        solved.facets[2 * slot].temperature_k
    };
    for (i, m) in lib.materials.iter().enumerate() {
        let (a, b) = (
            solved.facets[2 * i].temperature_k,
            solved.facets[2 * i + 1].temperature_k,
        );
        // Physical at a summer noon with air at 304 K: no surface below freezing or above
        // 80 C, and a square's two halves alike.
        assert!(
            (273.0..=353.0).contains(&a) && (a - b).abs() < 0.5,
            "{}: {a} K, {b} K",
            m.name
        );
    }
    // Sunlight decides the order: rust (solar absorptance 0.80) is far above polished
    // aluminium (0.08), whose low emissivity keeps it near the air; the mixed pond stays
    // near the air.
    assert!(t("steel (rusted)") > t("aluminium (polished)") + 10.0);
    assert!((t("water") - 304.0).abs() < 10.0, "{}", t("water"));
}
