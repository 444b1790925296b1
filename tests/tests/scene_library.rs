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
    assert!(lib.materials.len() >= 25, "{}", lib.materials.len());
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

/// n + ik of a `wavelength n k` table at `lam`, each interpolated linearly.
fn index_at(rows: &[[f64; 3]], lam: f64) -> C {
    let xs: Vec<f64> = rows.iter().map(|r| r[0]).collect();
    let n: Vec<f64> = rows.iter().map(|r| r[1]).collect();
    let k: Vec<f64> = rows.iter().map(|r| r[2]).collect();
    (interp(&xs, &n, lam), interp(&xs, &k, lam))
}

/// |(a - b) / (a + b)|²: the normal-incidence reflectance of the interface between media of
/// indices a and b (Born & Wolf, §13.2, at θ = 0).
fn interface_reflectance(a: C, b: C) -> f64 {
    norm2(div(sub(a, b), add(a, b)))
}

#[test]
fn coatings_agree_with_a_hand_computation() {
    let lib = library();
    // Paint at 10 µm: Zhang's PMMA rows at 9.9710 µm (1.49760, 0.0334) and 10.048 µm
    // (1.50342, 0.0575) give, a fraction 0.029/0.077 of the way, n 1.499792 and k 0.042477;
    // R = (0.499792² + 0.042477²) / (2.499792² + 0.042477²) = 0.251596 / 6.250764 = 0.040250.
    let by_hand = 1.0
        - (0.499_792_f64.powi(2) + 0.042_477_f64.powi(2))
            / (2.499_792_f64.powi(2) + 0.042_477_f64.powi(2));
    assert!((by_hand - 0.959_750).abs() < 2e-6, "{by_hand}");
    // The script hands n and k to irsig-material rounded to 6 digits.
    let pmma = index_at(&nk_rows("pmma-zhang-mitsubishi.yml"), 10.0);
    let fresnel = fresnel_emissivity(six_digits(pmma.0), six_digits(pmma.1), 0.0);
    assert!((fresnel - by_hand).abs() < 2e-6, "{fresnel} vs {by_hand}");
    for name in [
        "steel (painted, white)",
        "steel (painted, black)",
        "roofing (white-painted steel)",
        "roofing (black-painted steel)",
        "aluminium (painted, white)",
        "aluminium (painted, black)",
    ] {
        let s = material(&lib, name).spectral.as_ref().unwrap();
        let e = at(&s.wavelength_um, &s.emissivity, 10.0);
        assert!((e - fresnel).abs() <= 5.1e-7, "{name}: {e} vs {fresnel}");
    }
    // Anodised aluminium: 15 µm of Franta's alumina on Rakić's aluminium (n, k as
    // interpolated, not rounded: the script sums the film itself), the film's
    // reflections summed incoherently (Siegel & Howell): R = R01 + (1 - R01)² R12 t² /
    // (1 - R01 R12 t²), t = exp(-4π k d / λ), at a wavelength where the film absorbs
    // (12 µm) and one where it barely does (4 µm, so the aluminium shows through).
    let film = nk_rows("alumina-franta.yml");
    let metal = nk_rows("aluminium-rakic.yml");
    let anodised = material(&lib, "aluminium (anodised)")
        .spectral
        .as_ref()
        .unwrap();
    for lam in [4.0, 12.0] {
        let n1 = index_at(&film, lam);
        let n2 = index_at(&metal, lam);
        let r01 = interface_reflectance((1.0, 0.0), n1);
        let r12 = interface_reflectance(n1, n2);
        let t2 = (-2.0 * 4.0 * std::f64::consts::PI * n1.1 * 15.0 / lam).exp();
        let e = 1.0 - (r01 + (1.0 - r01).powi(2) * r12 * t2 / (1.0 - r01 * r12 * t2));
        let lib_e = at(&anodised.wavelength_um, &anodised.emissivity, lam);
        assert!((lib_e - e).abs() <= 5.1e-7, "{lam} µm: {lib_e} vs {e}");
    }
    let bare = material(&lib, "aluminium (polished)")
        .spectral
        .as_ref()
        .unwrap();
    let e4 = at(&anodised.wavelength_um, &anodised.emissivity, 4.0);
    assert!(e4 < 0.1 && e4 >= at(&bare.wavelength_um, &bare.emissivity, 4.0));
    // At 12 µm the film is opaque (k 1.21: t² = e^-38): the air-film interface alone,
    // n 0.937766 + 1.209823i interpolated by hand between Franta's rows at 11.9492 and
    // 12.0876 µm, R01 = (0.062234² + 1.209823²) / (1.937766² + 1.209823²) = 1.467545 /
    // 5.218609 = 0.281214.
    let e12 = at(&anodised.wavelength_um, &anodised.emissivity, 12.0);
    assert!((e12 - (1.0 - 0.281_214)).abs() < 2e-6, "{e12}");
}

#[test]
fn the_canopies_are_the_grass_curve_and_calm_water_a_smooth_surface() {
    // Named models on measured curves: the leaves' spectrum is the grass's; only
    // structure and thermal records differ.
    let lib = library();
    let grass = material(&lib, "grass").spectral.as_ref().unwrap();
    for name in ["canopy (deciduous)", "canopy (conifer)"] {
        let s = material(&lib, name).spectral.as_ref().unwrap();
        assert_eq!(s.wavelength_um, grass.wavelength_um, "{name}");
        assert_eq!(s.emissivity, grass.emissivity, "{name}");
    }
    // Oke's albedos, deciduous 0.15-0.20 and coniferous 0.05-0.15, at their middles.
    let solar = |name: &str| {
        material(&lib, name)
            .thermal
            .as_ref()
            .unwrap()
            .solar_absorptance
            .unwrap()
    };
    assert!((solar("canopy (deciduous)") - (1.0 - 0.175)).abs() < 1e-12);
    assert!((solar("canopy (conifer)") - (1.0 - 0.10)).abs() < 1e-12);
    // Calm water is the smooth Fresnel surface of Hale & Querry's row at 10 µm, n 1.218,
    // k 0.0508: R = (0.218² + 0.0508²) / (2.218² + 0.0508²) = 0.0501046 / 4.9221046 =
    // 0.0101795, ε = 0.989820; the rippled pond's facets tilt away from the normal and
    // emit a little less there (0.99 at nadir, Masuda et al. 1988, is both).
    let by_hand =
        1.0 - (0.218_f64.powi(2) + 0.0508_f64.powi(2)) / (2.218_f64.powi(2) + 0.0508_f64.powi(2));
    assert!((by_hand - 0.989_820).abs() < 1e-6, "{by_hand}");
    let calm = material(&lib, "water (calm)").spectral.as_ref().unwrap();
    let e = at(&calm.wavelength_um, &calm.emissivity, 10.0);
    assert!((e - by_hand).abs() <= 5.1e-7, "{e} vs {by_hand}");
    let rippled = material(&lib, "water").spectral.as_ref().unwrap();
    let r = at(&rippled.wavelength_um, &rippled.emissivity, 10.0);
    assert!(r < e && e - r < 0.002, "{r} vs {e}");
}

#[test]
fn every_source_file_is_listed_and_every_material_names_files_that_exist() {
    // The provenance record and the data agree: every file under sources/ is in
    // SOURCES.md and read by some material, and every file a material names is there.
    let lib = library();
    let root = irsig_tests::repo_root().join("pipelines/materials/sources");
    let listing = std::fs::read_to_string(root.join("SOURCES.md")).unwrap();
    let sources: String = lib.materials.iter().map(|m| m.source.as_str()).collect();
    let mut files = Vec::new();
    for dir in std::fs::read_dir(&root).unwrap() {
        let dir = dir.unwrap().path();
        if dir.is_dir() {
            for f in std::fs::read_dir(&dir).unwrap() {
                let f = f.unwrap().path();
                let name = f.file_name().unwrap().to_str().unwrap().to_owned();
                let sub = dir.file_name().unwrap().to_str().unwrap().to_owned();
                files.push((sub, name));
            }
        }
    }
    assert!(files.len() >= 10, "{files:?}");
    for (sub, name) in &files {
        assert!(
            listing.contains(&format!("`{name}`")),
            "{sub}/{name} is not in SOURCES.md"
        );
        if !name.starts_with("LICENSE") {
            let path = format!("sources/{sub}/{name}");
            assert!(sources.contains(&path), "no material reads {path}");
        }
    }
    for (i, _) in sources.match_indices("sources/") {
        let tail = &sources[i + "sources/".len()..];
        let end = tail.find([')', ';', ',', ' ']).unwrap_or(tail.len());
        let path = root.join(&tail[..end]);
        assert!(path.is_file(), "{} is named but missing", path.display());
    }
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
    // Paint over 8-14 µm against handbook paints' total emissivities near 300 K, white
    // acrylic 0.90 and black (Parsons) 0.98 (Incropera & DeWitt, Table A.13): the binder
    // surface lies between them.
    let paint = material(&lib, "steel (painted, white)")
        .spectral
        .as_ref()
        .unwrap();
    let lwir = Band::new(8.0, 14.0).unwrap();
    let e = band_average_emissivity(&paint.wavelength_um, &paint.emissivity, &lwir, 300.0).unwrap();
    assert!((0.90..=0.98).contains(&e), "{e}");
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
    // Paint's colour is its solar absorptance (0.98 black, 0.26 white): on the same sheet,
    // the black runs more than 15 K hotter; the insulated roof's sheet as much.
    for (black, white) in [
        ("steel (painted, black)", "steel (painted, white)"),
        (
            "roofing (black-painted steel)",
            "roofing (white-painted steel)",
        ),
        ("aluminium (painted, black)", "aluminium (painted, white)"),
    ] {
        assert!(
            t(black) > t(white) + 15.0,
            "{black}: {} K, {white}: {} K",
            t(black),
            t(white)
        );
    }
    // The canopies' leaves transpire and meet the air on both sides: near the air (304 K),
    // not as hot as the soil-backed, sunlit black paint.
    for canopy in ["canopy (deciduous)", "canopy (conifer)"] {
        assert!((t(canopy) - 304.0).abs() < 5.0, "{canopy}: {} K", t(canopy));
    }
    assert!((t("water") - 304.0).abs() < 10.0, "{}", t("water"));
}
