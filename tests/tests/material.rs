//! End-to-end tests of `irsig-material`: the Fresnel generator against the shared
//! reference `.ems` and a hand computation, bad input refused with exit 1 or 2 and no
//! output; the stage's place (`irsig material`, the pipeline runner checking its
//! parameters, and no material subcommands left in `irsig-atmos`). Material-library
//! conversion is tested beside the tool (`tools/material/tests/convert.rs`). A table that
//! is one band's (`band_um`) is refused by `irsig-trace` in another band.

use irsig_tests::bin;
use predicates::prelude::*;

fn stdout_of(args: &[&str]) -> String {
    let out = bin("irsig-material").args(args).assert().success();
    String::from_utf8(out.get_output().stdout.clone()).unwrap()
}

/// `(angle_deg, emissivity)` rows of a legacy `.ems` text.
fn ems_rows(text: &str) -> Vec<(f64, f64)> {
    irsig_formats::legacy::ems::parse("out.ems", text)
        .unwrap()
        .to_pairs()
}

#[test]
#[allow(clippy::float_cmp)] // the angles are small integers, printed and read exactly
fn fresnel_water_from_the_hale_querry_table_matches_the_reference_ems() {
    // formats/legacy/samples/water-hale-querry.ems is the shared reference (same sha256):
    // the same physics by a 0.0005 µm trapezoid rule, printed to 6 decimals.
    let out = stdout_of(&[
        "fresnel",
        "--nk-table",
        "formats/samples/water-hale-querry-nk.txt",
        "--band",
        "8-14",
        "--planck-temperature",
        "300",
        "--angles",
        "0:90:5",
        "--legacy",
    ]);
    let reference = std::fs::read_to_string(
        irsig_tests::repo_root().join("formats/legacy/samples/water-hale-querry.ems"),
    )
    .unwrap();
    let (ours, theirs) = (ems_rows(&out), ems_rows(&reference));
    assert_eq!(ours.len(), theirs.len());
    for (a, b) in ours.iter().zip(&theirs) {
        assert_eq!(a.0, b.0);
        assert!((a.1 - b.1).abs() < 6e-7, "{a:?} vs {b:?}");
    }
}

#[test]
fn fresnel_constant_index_writes_a_material_library_entry() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("glassy.ron");
    bin("irsig-material")
        .args([
            "fresnel",
            "--n",
            "1.2",
            "--k",
            "0.05",
            "--angles",
            "0,30,60,90",
        ])
        .args([
            "--name",
            "glassy",
            "--id",
            "3",
            "-o",
            path.to_str().unwrap(),
        ])
        .assert()
        .success();
    let text = std::fs::read_to_string(&path).unwrap();
    let lib: irsig_model::MaterialLibrary =
        irsig_formats::canonical::from_ron("glassy.ron", &text).unwrap();
    let m = &lib.materials[0];
    assert_eq!(
        (m.id.0, m.name.as_str(), m.specular_fraction),
        (3, "glassy", 1.0)
    );
    assert!(m.source.contains("n = 1.2, k = 0.05"), "{}", m.source);
    // Normal incidence by hand: 1 − (0.2² + 0.05²)/(2.2² + 0.05²) = 0.991761...
    let normal = 1.0 - (0.04 + 0.0025) / (4.84 + 0.0025);
    assert_eq!(m.emissivity.len(), 4);
    assert!(
        (m.emissivity[0].1 - normal).abs() < 1e-12,
        "{:?}",
        m.emissivity
    );
    assert_eq!(m.emissivity[3], (90.0, 0.0));
    // Same on stdout with `-o -`, and a `.ems` name selects the legacy layout.
    let piped = stdout_of(&[
        "fresnel",
        "--n",
        "1.2",
        "--k",
        "0.05",
        "--angles",
        "0,30,60,90",
        "--name",
        "glassy",
        "--id",
        "3",
        "-o",
        "-",
    ]);
    assert_eq!(piped, text);
    let ems = dir.path().join("glassy.ems");
    bin("irsig-material")
        .args([
            "fresnel",
            "--n",
            "1.2",
            "--k",
            "0.05",
            "--angles",
            "0,30,60,90",
        ])
        .args(["-o", ems.to_str().unwrap()])
        .assert()
        .success();
    let rows = ems_rows(&std::fs::read_to_string(&ems).unwrap());
    assert_eq!(rows, m.emissivity);
}

#[test]
fn fresnel_roughness_keeps_the_emissivity_up_at_grazing_and_is_diffuse_by_default() {
    // A smooth dielectric of normal emissivity 0.95 falls to 0 at 90°; the same facets
    // rough (RMS slope 0.8) over a diffuse body stay above 0.87, the reflection diffuse.
    let smooth = stdout_of(&["fresnel", "--n", "1.576", "--angles", "0,60,88,90"]);
    let rough = stdout_of(&[
        "fresnel",
        "--n",
        "1.36",
        "--roughness",
        "0.8",
        "--diffuse-reflectance",
        "0.0347",
        "--angles",
        "0,60,88,90",
    ]);
    let read = |t: &str| -> irsig_model::Material {
        irsig_formats::canonical::from_ron::<irsig_model::MaterialLibrary>("m.ron", t)
            .unwrap()
            .materials
            .remove(0)
    };
    let (s, r) = (read(&smooth), read(&rough));
    assert_eq!((s.specular_fraction, r.specular_fraction), (1.0, 0.0));
    assert!(
        s.emissivity[2].1 < 0.19 && s.emissivity[3].1 == 0.0,
        "{s:?}"
    );
    assert!((r.emissivity[0].1 - 0.95).abs() < 5e-4, "{r:?}");
    assert!(
        r.emissivity[2].1 > 0.87 && r.emissivity[3].1 > 0.87,
        "{r:?}"
    );
    assert!(r.source.contains("RMS slope 0.8"), "{}", r.source);
    // The facets' slope is recorded for the specular lobe; a smooth surface records none.
    assert_eq!((s.rms_slope, r.rms_slope), (None, Some(0.8)));
}

#[test]
fn the_rough_surface_library_is_what_its_generator_makes() {
    // pipelines/materials/rough-surfaces.ron, remade by its script with this build's tool:
    // the same bytes, and a valid library.
    let root = irsig_tests::repo_root();
    let out = std::process::Command::new("sh")
        .arg("pipelines/materials/generate.sh")
        .env("IRSIG_MATERIAL", irsig_tests::bin_path("irsig-material"))
        .current_dir(&root)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let made = String::from_utf8(out.stdout).unwrap();
    let committed =
        std::fs::read_to_string(root.join("pipelines/materials/rough-surfaces.ron")).unwrap();
    assert!(
        made == committed,
        "rough-surfaces.ron is not what generate.sh makes"
    );
    let lib: irsig_model::MaterialLibrary =
        irsig_formats::canonical::from_ron("rough-surfaces.ron", &committed).unwrap();
    let names: Vec<&str> = lib.materials.iter().map(|m| m.name.as_str()).collect();
    for want in [
        "grass",
        "water",
        "asphalt",
        "concrete",
        "soil (clay)",
        "sand",
    ] {
        assert!(names.contains(&want), "{names:?}");
    }
    assert!(
        lib.materials
            .iter()
            .all(|m| m.source.contains("rough-surfaces.csv"))
    );
}

#[test]
fn fresnel_bad_input_exits_1_or_2_with_a_message_and_no_output() {
    let dir = tempfile::tempdir().unwrap();
    let bad_nk = dir.path().join("bad.nk");
    std::fs::write(&bad_nk, "8 1.2 0.1\n9 1.3 -0.2\n").unwrap();
    let bad_nk = bad_nk.to_str().unwrap();
    let water = "formats/samples/water-hale-querry-nk.txt";
    let cases: &[(&[&str], i32, &str)] = &[
        (&["--n", "0"], 1, "n must be finite and > 0, found 0"),
        (&["--n", "-1.5"], 1, "found -1.5"),
        (&["--n", "NaN"], 1, "found NaN"),
        (
            &["--n", "1.2", "--k", "-0.1"],
            1,
            "k must be finite and ≥ 0, found -0.1",
        ),
        (&["--n", "1.2", "--angles", "0:95:5"], 1, "0–90"),
        (&["--n", "1.2", "--angles", "30,10"], 1, "increase"),
        (&["--nk-table", bad_nk], 1, "bad.nk:2:7"),
        (&["--nk-table", "no-such-file.nk"], 1, "no-such-file.nk"),
        (
            &["--nk-table", water, "--band", "7-14"],
            1,
            "covers 8–14 µm",
        ),
        (
            &["--nk-table", water, "--planck-temperature", "-5"],
            1,
            "temperature",
        ),
        // Said as written, not as the 309 digits of 1e308.
        (
            &["--nk-table", water, "--planck-temperature", "1e308"],
            1,
            "--planck-temperature 1e308: the Planck",
        ),
        (
            &["--nk-table", water, "--planck-temperature", "1e-300"],
            1,
            "--planck-temperature 1e-300: the Planck",
        ),
        (
            &["--n", "1.2", "--nk-table", water],
            2,
            "cannot be used with",
        ),
        (&["--k", "0.1"], 2, "required"),
        (
            &["--n", "1.2", "--planck-temperature", "300"],
            2,
            "--nk-table",
        ),
        (
            &["--n", "1.2", "--roughness", "-0.1"],
            1,
            "RMS slope must be a number from 0 (smooth) to 10, found -0.1",
        ),
        (&["--n", "1.2", "--roughness", "NaN"], 1, "found NaN"),
        (&["--n", "1.2", "--roughness", "11"], 1, "found 11"),
        (
            &["--n", "1.2", "--diffuse-reflectance", "1"],
            1,
            "diffuse reflectance must be a number from 0 to below 1, found 1",
        ),
        (&["--n", "1.2", "--roughness", "x"], 2, "--roughness"),
    ];
    for (args, code, message) in cases {
        let out_file = dir.path().join("out.ron");
        let out = bin("irsig-material")
            .arg("fresnel")
            .args(*args)
            .args(["-o", out_file.to_str().unwrap()])
            .assert()
            .code(*code);
        // miette wraps long messages at 80 columns behind a `│` gutter: unwrap them.
        let stderr = String::from_utf8_lossy(&out.get_output().stderr)
            .split_whitespace()
            .filter(|w| *w != "│")
            .collect::<Vec<_>>()
            .join(" ");
        assert!(stderr.contains(message), "{args:?}: {stderr}");
        assert!(!out_file.exists(), "{args:?}: output left behind");
    }
}

#[test]
fn materials_are_irsig_materials_not_irsig_atmos() {
    for (args, refused) in [
        (&["fresnel", "--n", "1.2"][..], "'fresnel'"),
        (
            &[
                "convert",
                "--material-index",
                "formats/legacy/samples/materials.mat",
            ],
            "'--material-index'",
        ),
    ] {
        bin("irsig-atmos")
            .args(args)
            .assert()
            .code(2)
            .stderr(predicate::str::contains(refused));
    }
    // The umbrella runs it as a stage, and lists it.
    bin("irsig")
        .args([
            "material", "fresnel", "--n", "1.5", "--angles", "0", "--legacy",
        ])
        .assert()
        .success()
        .stdout(predicate::str::starts_with("0"));
    bin("irsig")
        .arg("--version")
        .assert()
        .success()
        .stdout(predicate::str::contains("  material "));
}

#[test]
fn the_pipeline_runner_checks_material_stages_before_running_any() {
    let dir = tempfile::tempdir().unwrap();
    let mat = irsig_tests::repo_root().join("formats/legacy/samples/materials.mat");
    let pipeline = format!(
        r#"Pipeline(stages: [
    Stage(tool: "material convert", args: ["{}"], params: {{"default-emissivity": 0.9}},
          outputs: {{"o": "lib.ron"}}),
    Stage(tool: "material fresnel", params: {{"--n": 1.5, "no-such-flag": 1}},
          outputs: {{"o": "glass.ron"}}),
])"#,
        mat.display()
    );
    std::fs::write(dir.path().join("p.ron"), &pipeline).unwrap();
    let out = bin("irsig-run")
        .current_dir(dir.path())
        .arg("p.ron")
        .assert()
        .code(1);
    let stderr = String::from_utf8_lossy(&out.get_output().stderr).into_owned();
    // Rejected by irsig-material's own command line, at the stage, before anything ran.
    assert!(
        stderr.contains("p.ron:4:") && stderr.contains("rejects this stage's parameters"),
        "{stderr}"
    );
    assert!(!dir.path().join("lib.ron").exists(), "a stage ran");
    // Without the bad flag both stages run.
    std::fs::write(
        dir.path().join("p.ron"),
        pipeline.replace(", \"no-such-flag\": 1", ""),
    )
    .unwrap();
    bin("irsig-run")
        .current_dir(dir.path())
        .arg("p.ron")
        .assert()
        .success();
    let lib: irsig_model::MaterialLibrary = irsig_formats::canonical::from_ron_bytes(
        "lib.ron",
        &std::fs::read(dir.path().join("lib.ron")).unwrap(),
    )
    .unwrap();
    assert_eq!(lib.materials.len(), 9);
    assert!(dir.path().join("glass.ron").exists());
}

#[test]
#[allow(clippy::float_cmp)] // values copied from the files, compared as printed there
fn dirsig_materials_become_spectral_materials_and_a_missing_ems_is_refused_at_its_filename() {
    let src = irsig_tests::repo_root().join("tests/data/third-party/dirsig-channel");
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("lib.ron");
    // The real database: its ID 100 entry names no emissivity file (line 2, the ID's
    // value at column 20) ...
    bin("irsig-material")
        .arg("dirsig")
        .arg(src.join("anadirsig.mat"))
        .arg("-o")
        .arg(&out)
        .assert()
        .code(1)
        .stderr(predicate::str::contains("anadirsig.mat:2:20"))
        .stderr(predicate::str::contains("--default-emissivity"));
    // ... and, given a default for it (and converting no THERM block), grass names
    // `emissivity/grass_texture.ems`, which is not there (line 77, the value at column 33).
    bin("irsig-material")
        .arg("dirsig")
        .arg(src.join("anadirsig.mat"))
        .args(["--default-emissivity", "0.95", "--no-thermal", "-o"])
        .arg(&out)
        .assert()
        .code(1)
        .stderr(predicate::str::contains("anadirsig.mat:77:33"))
        .stderr(predicate::str::contains("grass_texture.ems"));
    assert!(!out.exists());

    // Water (the index form, wavenumbers) and a background (the CURVE_BEGIN form, µm).
    std::fs::create_dir(dir.path().join("emissivity")).unwrap();
    for f in ["muddy_water.ems", "background_1.ems"] {
        std::fs::copy(
            src.join("emissivity").join(f),
            dir.path().join("emissivity").join(f),
        )
        .unwrap();
    }
    let mat = dir.path().join("two.mat");
    std::fs::write(
        &mat,
        "MATERIAL_ENTRY {\n  ID = 2\n  NAME = water\n  SURFACE_PROPERTIES {\n    EMISSIVITY_PROP {\n      FILENAME = emissivity/muddy_water.ems\n      SPECULAR_FRACTION = 1\n    }\n  }\n}\n\
         MATERIAL_ENTRY {\n  ID = 5\n  NAME = background\n  SURFACE_PROPERTIES {\n    EMISSIVITY_PROP {\n      FILENAME = emissivity/background_1.ems\n    }\n  }\n}\n",
    )
    .unwrap();
    bin("irsig-material")
        .arg("dirsig")
        .arg(&mat)
        .arg("-o")
        .arg(&out)
        .assert()
        .success();
    let bytes = std::fs::read(&out).unwrap();
    let lib: irsig_model::MaterialLibrary =
        irsig_formats::canonical::from_ron_bytes("lib.ron", &bytes).unwrap();
    let water = lib.by_name("water").unwrap();
    assert_eq!((water.id.0, water.specular_fraction), (2, 1.0));
    let s = water.spectral.as_ref().unwrap();
    // muddy_water.ems: 0.974 at 1050 and 950 cm⁻¹ (9.52 and 10.53 µm), so at 10 µm.
    let k = s.wavelength_um.partition_point(|&w| w < 10.0);
    assert!((s.wavelength_um[k] - 1e4 / 950.0).abs() < 1e-9);
    assert_eq!(s.emissivity[k], 0.974);
    // Its 8-14 µm average: 0.974 from 1250 cm⁻¹ (8 µm) to 750 cm⁻¹ (13.33 µm), rising to
    // 1.0 at 650 cm⁻¹ (15.38 µm), so 0.9825 at 14 µm; the last 0.67 µm hold about 7 %
    // of the 300 K band radiance, so the average lies within 0.974 + 0.07 · 0.0085.
    let (a0, e0) = water.emissivity[0];
    assert_eq!(a0, 0.0);
    assert!(e0 > 0.974 && e0 < 0.9747, "{e0}");
    // The angular factors of the file: 1 at 0°, 0 from 86° on (its lines 88-92).
    assert_eq!(water.emissivity.len(), 91);
    assert_eq!(water.emissivity[86].1, 0.0);
    let bg = lib.by_name("background").unwrap();
    let s = bg.spectral.as_ref().unwrap();
    assert_eq!(
        (s.wavelength_um[0], *s.wavelength_um.last().unwrap()),
        (0.35, 14.983)
    );
    assert!(s.emissivity.iter().all(|&e| e == 0.98));
    assert!(bg.emissivity.iter().all(|&(_, e)| (e - 0.98).abs() < 1e-12));
    assert_eq!(bg.specular_fraction, 0.0);
}

/// DIRSIG's THERM blocks: the real database's are refused where they hold what irsig
/// cannot represent, and a block irsig can represent becomes the material's thermal
/// record in SI, with the back boundary the user gives (formats/dirsig.md).
#[test]
fn a_therm_block_becomes_the_thermal_record_and_what_irsig_cannot_say_is_refused() {
    let src = irsig_tests::repo_root().join("tests/data/third-party/dirsig-channel");
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("lib.ron");
    let dirsig = |extra: &[&str]| {
        let mut cmd = bin("irsig-material");
        cmd.arg("dirsig")
            .arg(src.join("anadirsig.mat"))
            .args(["--default-emissivity", "0.95"])
            .args(extra)
            .arg("-o")
            .arg(&out);
        cmd
    };
    // Water has a THERM block (line 30, TEMP_SOLVER_NAME's value at column 24), and DIRSIG
    // does not say what lies behind its slab.
    dirsig(&[])
        .assert()
        .code(1)
        .stderr(predicate::str::contains("anadirsig.mat:30:24"))
        .stderr(predicate::str::contains("--thermal-back"));
    // Given a back, its EXPOSED_AREA of -0.4 (line 37, column 32) is refused: DIRSIG gives
    // a negative exposed area a meaning its documentation does not state.
    dirsig(&["--thermal-back", "adiabatic"])
        .assert()
        .code(1)
        .stderr(predicate::str::contains("anadirsig.mat:37:32"))
        .stderr(predicate::str::contains("negative"));
    assert!(!out.exists());

    // A block irsig can represent: 5 cm of asphalt in DIRSIG's units.
    std::fs::create_dir(dir.path().join("emissivity")).unwrap();
    std::fs::copy(
        src.join("emissivity/background_1.ems"),
        dir.path().join("emissivity/background_1.ems"),
    )
    .unwrap();
    let mat = dir.path().join("asphalt.mat");
    std::fs::write(
        &mat,
        "MATERIAL_ENTRY {\n  ID = 9\n  NAME = asphalt\n  TEMP_SOLVER_NAME = Therm\n  \
         TEMP_SOLVER {\n    SPECIFIC_HEAT = 0.22\n    MASS_DENSITY = 2.1\n    \
         THERMAL_CONDUCTIVITY = 0.75\n    SOLAR_ABSORPTION = 0.9\n    \
         THERMAL_EMISSIVITY = 0.95\n    EXPOSED_AREA = 0.4\n    THICKNESS = 5\n  }\n  \
         SURFACE_PROPERTIES {\n    EMISSIVITY_PROP {\n      FILENAME = emissivity/background_1.ems\n    }\n  }\n}\n",
    )
    .unwrap();
    bin("irsig-material")
        .arg("dirsig")
        .arg(&mat)
        .args(["--thermal-back", "temperature:288.15", "-o"])
        .arg(&out)
        .assert()
        .success();
    let lib: irsig_model::MaterialLibrary =
        irsig_formats::canonical::from_ron_bytes("lib.ron", &std::fs::read(&out).unwrap()).unwrap();
    let t = lib.by_name("asphalt").unwrap().thermal.as_ref().unwrap();
    let layer = &t.layers[0];
    // 5 cm; 2.1 g/cm³ is 2100 kg/m³; 0.22 cal/(g °C) is 0.22 × 4186.8 = 921.096 J/(kg K).
    assert!((layer.thickness_m - 0.05).abs() < 1e-12);
    assert!((layer.density_kg_m3 - 2100.0).abs() < 1e-9);
    assert!((layer.specific_heat_j_kg_k - 921.096).abs() < 1e-9);
    assert!((layer.conductivity_w_m_k - 0.75).abs() < 1e-12);
    assert_eq!(
        (t.solar_absorptance, t.thermal_emissivity),
        (Some(0.9), Some(0.95))
    );
    assert_eq!(
        t.back,
        irsig_model::thermal::BackBoundary::Temperature {
            temperature_k: 288.15
        }
    );
    assert!(t.source.contains("EXPOSED_AREA 0.4"), "{}", t.source);
    // With --no-thermal the same entry has none.
    bin("irsig-material")
        .arg("dirsig")
        .arg(&mat)
        .args(["--no-thermal", "-o"])
        .arg(&out)
        .assert()
        .success();
    let lib: irsig_model::MaterialLibrary =
        irsig_formats::canonical::from_ron_bytes("lib.ron", &std::fs::read(&out).unwrap()).unwrap();
    assert!(lib.by_name("asphalt").unwrap().thermal.is_none());
}

/// A band table for 8–14 µm (`band_um`) is refused in 3–5 µm and for the whole spectrum,
/// at its place in the library, naming both bands, and nothing is written: the tracer
/// never uses one band's values in another.
#[test]
fn an_8_14_um_band_table_is_refused_in_3_5_um() {
    let dir = tempfile::tempdir().unwrap();
    let lib = dir.path().join("lwir.ron");
    std::fs::write(
        &lib,
        "(materials: [\n  (id: 1, name: \"lwir paint\", emissivity: [(0.0, 0.9), (90.0, 0.9)],\n   \
         specular_fraction: 0.0, source: \"a test\", band_um: Some((8.0, 14.0))),\n])\n",
    )
    .unwrap();
    let scene = dir.path().join("plate.raw.ron");
    std::fs::write(
        &scene,
        "(objects: [\"plate\"], positions_m: [(-1.0, -1.0, 0.0), (1.0, -1.0, 0.0), \
         (1.0, 1.0, 0.0), (-1.0, 1.0, 0.0)], facets: [(vertices: (0, 1, 2), material: 1, \
         temperature_k: 300.0, object: 0), (vertices: (0, 2, 3), material: 1, \
         temperature_k: 300.0, object: 0)])",
    )
    .unwrap();
    let view = dir.path().join("down.ron");
    std::fs::write(
        &view,
        "LookAt(position_m: (0.0, 0.0, 10.0), target_m: (0.0, 0.0, 0.0), \
         up: (0.0, 1.0, 0.0), pixels: (2, 2), fov_deg: (1.0, 1.0))",
    )
    .unwrap();
    for (band, asked) in [("3-5", "--band 3-5 um"), ("total", "--band total")] {
        let out = bin("irsig-trace")
            .arg("--scene")
            .arg(&scene)
            .arg("--materials")
            .arg(&lib)
            .arg("--view")
            .arg(&view)
            .args([
                "--atmosphere",
                "none",
                "--sky-radiance",
                "1",
                "--band",
                band,
                "-o",
            ])
            .arg(dir.path().join("refused"))
            .assert()
            .code(1);
        let stderr = String::from_utf8_lossy(&out.get_output().stderr).into_owned();
        for want in ["lwir.ron:3:", "lwir paint", "8-14 um", asked, "spectral"] {
            assert!(stderr.contains(want), "expected `{want}` in: {stderr}");
        }
        let left: Vec<_> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n.starts_with("refused"))
            .collect();
        assert!(left.is_empty(), "{left:?}");
    }
    // Within its band it is used.
    bin("irsig-trace")
        .arg("--scene")
        .arg(&scene)
        .arg("--materials")
        .arg(&lib)
        .arg("--view")
        .arg(&view)
        .args([
            "--atmosphere",
            "none",
            "--sky-radiance",
            "1",
            "--band",
            "8-12",
            "-o",
        ])
        .arg(dir.path().join("used"))
        .assert()
        .success();
}
