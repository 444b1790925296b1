//! The thesis fly-by pipeline (`pipelines/thesis-flyby.ron`, a stand-in for thesis §4.4):
//! its committed data against thesis Tables 1 and 2, and a run at reduced size (three
//! frames at 64 × 64, a test copy of the pipeline) checked against hand-computed radiometry
//! through the LOWTRAN7 reference tables, the camera geometry of the legacy viewing files,
//! and the contact sheet's layout.

use std::path::{Path, PathBuf};

use irsig_formats::legacy::view;
use irsig_model::{LengthUnit, Object};
use irsig_raster::{Raster, read_exr};
use irsig_tests::{bin, repo_root};

/// Thesis Table 2: frame, sensor position (km), ω φ κ (deg), gain (DC/K), FOV x, y (deg).
#[allow(clippy::type_complexity)]
const TABLE_2: [(u32, [f64; 3], [f64; 3], f64, [f64; 2]); 24] = [
    (
        1,
        [1.60, -3.00, 0.70],
        [78.3664, 0.0, 28.0725],
        2.0,
        [1.0, 1.0],
    ),
    (
        2,
        [0.80, -3.00, 0.70],
        [77.2948, 0.0, 14.9314],
        2.0,
        [1.0, 1.0],
    ),
    (
        3,
        [0.40, -3.00, 0.70],
        [76.9772, 0.0, 7.5946],
        2.0,
        [1.0, 1.0],
    ),
    (4, [0.00, -3.00, 0.70], [76.8660, 0.0, 0.0], 2.0, [1.0, 1.0]),
    (
        5,
        [-0.40, -3.00, 0.70],
        [76.9772, 0.0, -7.5946],
        2.0,
        [1.0, 1.0],
    ),
    (
        6,
        [-0.80, -3.00, 0.70],
        [77.2948, 0.0, -14.9314],
        2.0,
        [1.0, 1.0],
    ),
    (
        7,
        [-1.60, -3.00, 0.70],
        [78.3664, 0.0, -28.0725],
        2.0,
        [1.0, 1.0],
    ),
    (
        8,
        [-3.20, -3.00, 0.70],
        [80.9328, 0.0, -46.8476],
        2.0,
        [1.0, 1.0],
    ),
    (
        9,
        [0.00, -12.00, 0.70],
        [86.6615, 0.0, 0.0],
        2.0,
        [1.0, 1.0],
    ),
    (
        10,
        [0.00, -9.00, 0.70],
        [85.5526, 0.0, 0.0],
        2.0,
        [1.0, 1.0],
    ),
    (
        11,
        [0.00, -6.00, 0.70],
        [83.3456, 0.0, 0.0],
        2.0,
        [1.0, 1.0],
    ),
    (
        12,
        [0.00, -3.00, 0.70],
        [76.8660, 0.0, 0.0],
        2.0,
        [1.0, 1.0],
    ),
    (
        13,
        [0.00, -1.50, 0.70],
        [64.9831, 0.0, 0.0],
        2.0,
        [1.0, 1.0],
    ),
    (14, [0.00, 0.00, 0.70], [0.0, 0.0, 0.0], 2.0, [1.0, 1.0]),
    (15, [0.00, 1.50, 0.70], [64.9831, 0.0, 0.0], 2.0, [1.0, 1.0]),
    (16, [0.00, 3.00, 0.70], [76.8660, 0.0, 0.0], 2.0, [1.0, 1.0]),
    (
        17,
        [-0.80, -3.00, 0.70],
        [77.2948, 0.0, -14.9314],
        1.0,
        [1.0, 1.0],
    ),
    (
        18,
        [-0.80, -3.00, 0.70],
        [77.2948, 0.0, -14.9314],
        2.0,
        [1.0, 1.0],
    ),
    (
        19,
        [-0.80, -3.00, 0.70],
        [77.2948, 0.0, -14.9314],
        3.0,
        [1.0, 1.0],
    ),
    (
        20,
        [-0.80, -3.00, 0.70],
        [77.2948, 0.0, -14.9314],
        4.0,
        [1.0, 1.0],
    ),
    (
        21,
        [0.00, -3.00, 0.70],
        [76.8660, 0.0, 0.0],
        2.0,
        [1.0, 2.0],
    ),
    (
        22,
        [0.00, -3.00, 0.70],
        [76.8660, 0.0, 0.0],
        2.0,
        [2.0, 1.0],
    ),
    (
        23,
        [0.00, -3.00, 0.70],
        [76.8660, 0.0, 0.0],
        2.0,
        [3.0, 3.0],
    ),
    (
        24,
        [0.00, -3.00, 0.70],
        [76.8660, 0.0, 0.0],
        2.0,
        [4.0, 2.0],
    ),
];

fn flyby_dir() -> PathBuf {
    repo_root().join("pipelines/thesis-flyby")
}

#[test]
#[allow(clippy::float_cmp)] // decimal literals parse to the same f64 as the same Rust literal
fn the_24_viewing_files_are_table_2_and_follow_eq_13_14() {
    let pipeline = std::fs::read_to_string(repo_root().join("pipelines/thesis-flyby.ron")).unwrap();
    for (frame, pos, opk, gain, fov) in TABLE_2 {
        let name = format!("frame-{frame:02}.view");
        // Every frame is in the pipeline's sweep, once.
        assert_eq!(
            pipeline
                .matches(&format!("{{\"n\": \"{frame:02}\"}}"))
                .count(),
            1,
            "{name} in the sweep"
        );
        let text = std::fs::read_to_string(flyby_dir().join("views").join(&name)).unwrap();
        let v = view::parse(&name, &text).unwrap();
        assert_eq!(v.position, pos, "{name}");
        assert_eq!(v.pixels, [256, 256], "{name}: §4.4 says 256 x 256");
        assert_eq!(v.gain_dc_per_k, Some(gain), "{name}");
        assert_eq!(v.fov_deg, fov, "{name}");
        // Eq. 13-14 (irsig-tracer's implementation, tested there against the same table)
        // from the position in metres: the angles the file gives.
        let (omega, kappa) = irsig_tracer::camera::thesis_look_at_angles_deg(
            irsig_tracer::DVec3::from(v.to_view(LengthUnit::Km).position_m()),
        );
        // Frames 15 and 16 (y > 0) carry ω negated, on purpose (see the file's comment and
        // pipelines/thesis-flyby/README.md): that is what shows the scene upside down, as
        // the thesis's Figure 17 does.
        let sign = if pos[1] > 0.0 { -1.0 } else { 1.0 };
        assert_eq!(
            v.omega_phi_kappa_deg,
            [sign * opk[0], opk[1], opk[2]],
            "{name}"
        );
        assert!(
            (sign * omega - v.omega_phi_kappa_deg[0]).abs() < 6e-5,
            "{name}: ω {omega}"
        );
        assert!(
            (kappa - v.omega_phi_kappa_deg[2]).abs() < 6e-5,
            "{name}: κ {kappa}"
        );
    }
}

#[test]
fn the_objects_have_table_1_facet_counts_materials_and_temperatures() {
    let read = |name: &str| -> Object {
        let path = flyby_dir().join("objects").join(name);
        let bytes = std::fs::read(&path).unwrap();
        irsig_formats::canonical::from_ron_bytes(name, &bytes).unwrap()
    };
    // Material ids of materials.ron (checked by name below).
    let (steel, glass, rubber, asphalt, conifer, grass) = (1, 2, 3, 4, 5, 6);
    let lib_bytes = std::fs::read(flyby_dir().join("materials.ron")).unwrap();
    let lib: irsig_model::MaterialLibrary =
        irsig_formats::canonical::from_ron_bytes("materials.ron", &lib_bytes).unwrap();
    for (id, name) in [
        (steel, "steel"),
        (glass, "glass"),
        (rubber, "tyre-rubber"),
        (asphalt, "asphalt"),
        (conifer, "conifer"),
        (grass, "grass"),
    ] {
        assert!(
            lib.materials.iter().any(|m| m.id.0 == id && m.name == name),
            "{name} is id {id}"
        );
    }
    let temps = |o: &Object, m: u16| -> Vec<f64> {
        o.facets
            .iter()
            .filter(|f| f.material.0 == m)
            .map(|f| f.temperature_k.expect("every facet has a temperature"))
            .collect()
    };
    let range = |t: &[f64]| {
        (
            t.iter().copied().fold(f64::INFINITY, f64::min),
            t.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        )
    };
    let vehicle = read("vehicle.ron");
    assert_eq!(vehicle.facets.len(), 500, "Table 1: 500 facets");
    assert_eq!(range(&temps(&vehicle, steel)), (290.30, 338.70));
    assert_eq!(range(&temps(&vehicle, glass)), (292.77, 292.77));
    assert_eq!(range(&temps(&vehicle, rubber)), (300.00, 300.00));
    let road = read("road.ron");
    assert_eq!(road.facets.len(), 4);
    assert_eq!(range(&temps(&road, asphalt)), (293.15, 293.15));
    let tree = read("conifer.ron");
    assert_eq!(tree.facets.len(), 72);
    assert_eq!(range(&temps(&tree, conifer)), (289.15, 292.30));
    let field = read("field.ron");
    assert_eq!(field.facets.len(), 4);
    assert_eq!(range(&temps(&field, grass)), (286.18, 286.18));
}

/// Copies the fly-by pipeline to a scratch directory with only `frames` kept and every
/// viewing file at `pixels` x `pixels`.
fn reduced_copy(frames: &[u32], pixels: u32) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let src = flyby_dir();
    let dst = dir.path().join("thesis-flyby");
    for sub in ["", "objects", "views"] {
        std::fs::create_dir_all(dst.join(sub)).unwrap();
        for entry in std::fs::read_dir(src.join(sub)).unwrap() {
            let path = entry.unwrap().path();
            if !path.is_file() {
                continue;
            }
            let mut text = std::fs::read_to_string(&path).unwrap();
            if sub == "views" {
                assert_eq!(text.matches("\n256 256\n").count(), 1, "{}", path.display());
                text = text.replace("\n256 256\n", &format!("\n{pixels} {pixels}\n"));
            }
            std::fs::write(dst.join(sub).join(path.file_name().unwrap()), text).unwrap();
        }
    }
    let pipeline = std::fs::read_to_string(repo_root().join("pipelines/thesis-flyby.ron")).unwrap();
    let kept: Vec<String> = frames
        .iter()
        .map(|f| format!("{{\"n\": \"{f:02}\"}}"))
        .collect();
    let reduced: String = pipeline
        .lines()
        .filter(|l| !l.trim_start().starts_with("{\"n\":") || kept.iter().any(|k| l.contains(k)))
        .map(|l| format!("{l}\n"))
        .collect();
    std::fs::write(dir.path().join("thesis-flyby.ron"), reduced).unwrap();
    dir
}

fn exr(path: &Path) -> Raster {
    read_exr(&std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))).unwrap()
}

fn layer<'a>(r: &'a Raster, name: &str) -> &'a [f32] {
    &r.layer(name)
        .unwrap_or_else(|| panic!("no layer {name}"))
        .data
}

/// A whitespace table of numbers, one record per line.
fn table(path: &Path) -> Vec<Vec<f64>> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .filter(|l| !l.trim().is_empty())
        .map(|l| l.split_whitespace().map(|t| t.parse().unwrap()).collect())
        .collect()
}

/// Band radiance (8-14 um) of a blackbody, W m^-2 sr^-1, by linear interpolation in the
/// LOWTRAN7 reference `.rtt` (exact Planck integrals at every kelvin, W cm^-2 sr^-1).
fn rtt_radiance(rtt: &[Vec<f64>], t_k: f64) -> f64 {
    let i = rtt.iter().position(|r| r[0] > t_k).unwrap() - 1;
    let (a, b) = (&rtt[i], &rtt[i + 1]);
    1e4 * (a[1] + (b[1] - a[1]) * (t_k - a[0]) / (b[0] - a[0]))
}

/// Its inverse, by bisection on the same interpolation.
fn rtt_temperature(rtt: &[Vec<f64>], l: f64) -> f64 {
    let (mut lo, mut hi) = (200.0, 349.0);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if rtt_radiance(rtt, mid) < l {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

#[test]
fn reduced_flyby_runs_and_its_radiometry_checks_by_hand() {
    const PIXELS: usize = 64;
    let frames = [4, 14, 16];
    let dir = reduced_copy(&frames, PIXELS as u32);
    bin("irsig-run")
        .current_dir(dir.path())
        .arg("thesis-flyby.ron")
        .assert()
        .success();
    let build = dir.path().join("thesis-flyby/build");
    for f in frames {
        for suffix in ["radiance.exr", "truth.exr", "map.png", "dc.png", "lut.txt"] {
            assert!(
                build.join(format!("frame-{f:02}.{suffix}")).is_file(),
                "{f} {suffix}"
            );
        }
    }
    let written = std::fs::read_dir(&build).unwrap().count();
    assert_eq!(
        written,
        1 + frames.len() * 5 + 1,
        "raw scene, 5 per frame, sheet"
    );

    // The contact sheet: 3 tiles of 64 x 64 in one row (8 columns asked, 3 tiles), 4-pixel
    // gaps: 3*64 + 4*4 by 64 + 2*4, and tile 2 is frame 14's DC image, bit for bit
    // (outside the label box in its top-left corner).
    let sheet = image::open(build.join("contact-sheet.png"))
        .unwrap()
        .to_luma8();
    assert_eq!((sheet.width(), sheet.height()), (208, 72));
    let dc14 = image::open(build.join("frame-14.dc.png"))
        .unwrap()
        .to_luma8();
    for y in 20..64 {
        for x in 0..64 {
            assert_eq!(
                sheet.get_pixel(4 + 68 + x, 4 + y),
                dc14.get_pixel(x, y),
                "sheet pixel ({x}, {y}) of tile 2"
            );
        }
    }

    // Frame 14 looks straight down from 700 m: the vehicle's flat steel roofs fill pixels.
    // Expected, per pixel, from thesis eq. 1 with the LOWTRAN7 reference tables
    // (shared/reference/atmospheres/us-std-1976, copied in formats/legacy/samples):
    //   L = τ·(ε·B(T) + (1 − ε)·L_refl) + L_u
    // τ and L_u of the 700 m nadir path (the .atm row at 0.7 km: the target roofs at 2.4
    // and 3 m shorten it by about 3 m, worth < 0.06 W m^-2 sr^-1 in L_u and 1e-3 in τ); ε =
    // 0.92, steel's table value from 0° to 50°; L_refl the sky: the specular 30 % of the
    // reflectance sees the zenith sky (.dwr 0°), the diffuse 70 % the hemispheric mean
    // (.dwr last row), the thesis's F = 1.
    let samples = repo_root().join("formats/legacy/samples");
    let atm = table(&samples.join("us-std-1976.atm"));
    let dwr = table(&samples.join("us-std-1976.dwr"));
    let rtt = table(&samples.join("us-std-1976.rtt"));
    let row = atm.iter().find(|r| (r[2] - 0.7).abs() < 1e-9).unwrap();
    let (tau, l_u) = (row[3], 1e4 * row[4]);
    let l_refl = 1e4 * (0.3 * dwr[0][1] + 0.7 * dwr.last().unwrap()[1]);
    let truth = exr(&build.join("frame-14.truth.exr"));
    let radiance = exr(&build.join("frame-14.radiance.exr"));
    let (material, incidence, kinetic, apparent) = (
        layer(&truth, "material_primary"),
        layer(&truth, "incidence"),
        layer(&truth, "kinetic_temperature"),
        layer(&truth, "apparent_temperature"),
    );
    let l = layer(&radiance, "radiance");
    let mut roof = 0;
    for i in 0..PIXELS * PIXELS {
        if (material[i] - 1.0).abs() > 0.5 || incidence[i] > 1.0 {
            continue;
        }
        roof += 1;
        let t_k = f64::from(kinetic[i]);
        let expected = tau * (0.92 * rtt_radiance(&rtt, t_k) + 0.08 * l_refl) + l_u;
        let t_expected = rtt_temperature(&rtt, expected);
        // 0.15 K: the 3 m shorter path (< 0.08 K), the .rtt's linear interpolation over
        // 1 K (< 0.01 K), f32 storage; the band model is the same (flat 8-14 um).
        let t_app = f64::from(apparent[i]);
        assert!(
            (t_app - t_expected).abs() < 0.15,
            "pixel {i}: apparent {t_app} K, expected {t_expected} K (kinetic {t_k} K)"
        );
        assert!(
            (f64::from(l[i]) - expected).abs() < 0.15 * 0.8,
            "pixel {i} radiance"
        );
        // Through 700 m of air (τ = 0.84, air 283.6-288 K) and ε = 0.92 before a cold sky,
        // a roof warmer than the air looks cooler than it is.
        assert!(t_app < t_k, "pixel {i}");
    }
    // The cab (2.8 x 2.5 m) and the launcher body's roof either side of the tube: at 700 m
    // and 1° over 64 pixels (0.19 m per pixel) well over a hundred roof pixels.
    assert!(roof > 100, "only {roof} flat steel roof pixels in frame 14");

    // Frames 4 and 16 look at the origin from 3 km south and 3 km north. Frame 4 is
    // upright: the near ground is at the bottom of the image, so the top row is farther
    // away than the bottom row. Frame 16 (ω negated, as in the thesis's Figure 17) is
    // upside down: the other way round.
    let mean_range = |f: u32, row: usize| {
        let truth = exr(&build.join(format!("frame-{f:02}.truth.exr")));
        let r = &layer(&truth, "range")[row * PIXELS..(row + 1) * PIXELS];
        r.iter().map(|&v| f64::from(v)).sum::<f64>() / PIXELS as f64
    };
    assert!(mean_range(4, 0) > mean_range(4, PIXELS - 1) + 10.0);
    assert!(mean_range(16, 0) + 10.0 < mean_range(16, PIXELS - 1));
    // Both look at the origin from about 3.08 km: the centre rows' range.
    for f in [4, 16] {
        let r = mean_range(f, PIXELS / 2);
        assert!((r - 3080.6).abs() < 60.0, "frame {f}: centre range {r} m");
    }
}
