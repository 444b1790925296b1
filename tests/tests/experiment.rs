//! The thesis-experiment pipeline (`pipelines/thesis-experiment.ron`, Shor 1990 §4.5–5.1)
//! end to end, and `irsig-stats` on its outputs: the table has every Table 7 region; a
//! blackbody panel's apparent temperature lies within a hand-computed bound of its kinetic
//! temperature over the 10 m path; the regions rank as emissivity × temperature and the
//! reflected background predict; a regions file that does not fit the image fails at its
//! line and column and writes nothing.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use irsig_tests::{bin, repo_root};

/// The regions of Shor (1990) Table 7, in its (rank) order.
const TABLE_7: [&str; 8] = [
    "Top Pyramid",
    "Left Concrete",
    "Right Concrete",
    "Bottom Pyramid",
    "Left Pool",
    "Right Pool",
    "Left Blackbody",
    "Right Blackbody",
];

/// Kinetic temperatures of scene.ron (Table 4, °C + 273.15), K.
const BLACKBODY_K: f64 = 308.14;

/// Copies the pipeline file and its directory (without earlier outputs) into a fresh
/// directory, so that the test writes nothing into the repository.
fn copy_pipeline() -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let src = repo_root().join("pipelines");
    std::fs::copy(
        src.join("thesis-experiment.ron"),
        dir.path().join("thesis-experiment.ron"),
    )
    .unwrap();
    let data = dir.path().join("thesis-experiment");
    std::fs::create_dir_all(data.join("objects")).unwrap();
    for sub in ["", "objects"] {
        for entry in std::fs::read_dir(src.join("thesis-experiment").join(sub)).unwrap() {
            let path = entry.unwrap().path();
            if path.extension().is_some_and(|e| e == "ron") {
                std::fs::copy(&path, data.join(sub).join(path.file_name().unwrap())).unwrap();
            }
        }
    }
    let pipeline = dir.path().join("thesis-experiment.ron");
    (dir, pipeline)
}

fn run_pipeline(pipeline: &Path) {
    let out = bin("irsig-run")
        .arg(pipeline)
        .args(["--quiet"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "irsig-run failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Per region, the named CSV columns of `irsig-stats --format csv` on the pipeline's
/// outputs (kelvin).
fn stats_csv(data: &Path, extra: &[&str]) -> HashMap<String, HashMap<String, f64>> {
    irsig_tests::stats_csv(
        &data.join("out/experiment.truth.exr"),
        &data.join("regions.ron"),
        extra,
    )
}

/// Band radiance of a blackbody, 8–14 µm, W m⁻² sr⁻¹, by Simpson's rule on Planck's law
/// (CODATA 2018): independent of irsig-radiometry's series.
fn planck_8_14(t_k: f64) -> f64 {
    const H: f64 = 6.626_070_15e-34;
    const C: f64 = 299_792_458.0;
    const K: f64 = 1.380_649e-23;
    let (a, b, n) = (8e-6, 14e-6, 2000);
    let step = (b - a) / f64::from(n);
    let mut sum = 0.0;
    for i in 0..=n {
        let l = a + step * f64::from(i);
        let weight = if i == 0 || i == n {
            1.0
        } else if i % 2 == 1 {
            4.0
        } else {
            2.0
        };
        sum += weight * 2.0 * H * C * C / l.powi(5) / ((H * C / (l * K * t_k)).exp() - 1.0);
    }
    sum * step / 3.0
}

/// The temperature whose 8–14 µm band radiance is `l`, by bisection on [`planck_8_14`].
fn temperature_8_14(l: f64) -> f64 {
    let (mut lo, mut hi) = (150.0, 450.0);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if planck_8_14(mid) < l {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// `irsig-stats --layer` of a layer that is not a temperature: its columns carry the
/// layer's unit (metres for `range`, none for `emissivity`), and what only a temperature
/// can take (`--celsius`, the regions file's reference temperatures) is refused, as is a
/// layer of labels.
fn layers_other_than_temperatures_keep_their_units(data: &Path) {
    let truth = data.join("out/experiment.truth.exr");
    let text = std::fs::read_to_string(data.join("regions.ron")).unwrap();
    let mut set: irsig_model::RegionSet =
        irsig_formats::canonical::from_ron("regions.ron", &text).unwrap();
    assert!(!set.references.is_empty());
    set.references.clear();
    for r in &mut set.regions {
        r.references.clear();
    }
    let bare = data.join("out/regions-without-references.ron");
    std::fs::write(&bare, ron::to_string(&set).unwrap()).unwrap();
    let range = irsig_tests::stats_csv(&truth, &bare, &["--layer", "range"]);
    let emissivity = irsig_tests::stats_csv(&truth, &bare, &["--layer", "emissivity"]);
    for region in TABLE_7 {
        let (r, e) = (&range[region], &emissivity[region]);
        // The camera is metres from every object, and every emissivity a fraction.
        assert!(
            r["min_m"] > 0.0 && r["max_m"] < 100.0 && !r.contains_key("mean_k"),
            "{r:?}"
        );
        assert!(
            e["min"] > 0.0 && e["max"] <= 1.0 && !e.contains_key("mean_k"),
            "{e:?}"
        );
    }
    let refused = |regions: &Path, extra: &[&str], want: &str| {
        let out = irsig_tests::bin("irsig-stats")
            .arg(&truth)
            .arg("--regions")
            .arg(regions)
            .args(extra)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(
            !out.status.success() && stderr.contains(want),
            "{extra:?}: expected a refusal naming `{want}`: {stderr}"
        );
    };
    refused(&bare, &["--layer", "range", "--celsius"], "--celsius");
    refused(
        &data.join("regions.ron"),
        &["--layer", "range"],
        "references",
    );
    refused(&bare, &["--layer", "event"], "labels");
    refused(&bare, &["--layer", "no_such_layer"], "no_such_layer");
}

#[test]
fn the_pipeline_writes_every_table_7_region_and_the_regions_rank_as_physics_predicts() {
    let (_dir, pipeline) = copy_pipeline();
    run_pipeline(&pipeline);
    let data = pipeline.parent().unwrap().join("thesis-experiment");
    for f in [
        "scene.raw",
        "experiment.radiance.exr",
        "experiment.truth.exr",
        "experiment.map.png",
        "experiment.sensor.exr",
        "experiment.preview.png",
    ] {
        assert!(data.join("out").join(f).is_file(), "{f} not written");
    }

    // The printed table: every region of Table 7, with the thesis's values beside ours.
    let table = std::fs::read_to_string(data.join("out/table.txt")).unwrap();
    for region in TABLE_7 {
        let line = table
            .lines()
            .find(|l| l.starts_with(region))
            .unwrap_or_else(|| panic!("no row for {region} in\n{table}"));
        assert_eq!(
            line.split_whitespace().count(),
            region.split_whitespace().count() + 5 + 6,
            "{line}"
        );
    }
    assert!(table.contains("mean_c") && table.contains("synthetic_1990_c"));

    // The kinetic temperatures the regions select are Table 4's: each region sees only its
    // object (the material filter and the boxes are right).
    let kinetic = stats_csv(&data, &["--layer", "kinetic_temperature"]);
    let table_4_k = [
        ("Top Pyramid", 272.47),
        ("Bottom Pyramid", 274.12),
        ("Left Concrete", 276.385),
        ("Right Concrete", 276.385),
        ("Left Pool", 286.5),
        ("Right Pool", 286.5),
        ("Left Blackbody", BLACKBODY_K),
        ("Right Blackbody", BLACKBODY_K),
    ];
    for (region, t) in table_4_k {
        let r = &kinetic[region];
        // f32 layers: 308.14 is stored to within 3e-5 K.
        assert!(
            (r["min_k"] - t).abs() < 1e-4 && (r["max_k"] - t).abs() < 1e-4,
            "{region}: {r:?}"
        );
        assert!(
            r["pixels"] >= 100.0,
            "{region}: only {} pixels",
            r["pixels"]
        );
    }

    layers_other_than_temperatures_keep_their_units(&data);

    // The ranking. Each region's sensor-reaching radiance is ε·L(T) + (1 − ε)·L_bg (path
    // effects over 10 m are ~0.5 % and shift every region alike). Over the angles the
    // camera sees (0-65°) the emissivity tables of materials.ron span: concrete 0.917-0.984,
    // water 0.898-0.979, wood 0.819-0.956, black paint 0.726-0.929; any background other
    // than the panel lies between the zenith sky (7.84 W m^-2 sr^-1, midlat-winter .dwr)
    // and the warmest other surface, the pool, L(286.5 K). That brackets: panel
    // [47.2, 60.7], pool [40.6, 44.3], concrete [34.8, 37.4], pyramid [29.9, 36.2] W m^-2
    // sr^-1: panel > pool > concrete, pool > pyramid, whatever the exact angles.
    let apparent = stats_csv(
        &data,
        &[
            "--radiance",
            &data.join("out/experiment.sensor.exr").to_string_lossy(),
        ],
    );
    let mean = |r: &str| apparent[r]["mean_k"];
    for hot in ["Left Blackbody", "Right Blackbody"] {
        for pool in ["Left Pool", "Right Pool"] {
            assert!(
                mean(hot) > mean(pool),
                "{hot} {} <= {pool} {}",
                mean(hot),
                mean(pool)
            );
        }
    }
    for pool in ["Left Pool", "Right Pool"] {
        for cold in [
            "Left Concrete",
            "Right Concrete",
            "Top Pyramid",
            "Bottom Pyramid",
        ] {
            assert!(
                mean(pool) > mean(cold),
                "{pool} {} <= {cold} {}",
                mean(pool),
                mean(cold)
            );
        }
    }
    // The right half of the pool mirrors the warm panel, the left half the sky (the
    // thesis's "reflection from the background upon the pool", §5.0): at the same angles
    // and temperature the right half is warmer, because its background is at least
    // ε_paint,min·L(308.14 K) = 45.0 > L(286.5 K) = 44.3 W m^-2 sr^-1 ≥ the left half's.
    assert!(
        mean("Right Pool") > mean("Left Pool") + 1.0,
        "right pool {} vs left pool {}",
        mean("Right Pool"),
        mean("Left Pool")
    );
    // Each within its bracket above, as a temperature (path effects: ±0.3 K).
    let within = |r: &str, lo: f64, hi: f64| {
        let (a, b) = (temperature_8_14(lo) - 0.3, temperature_8_14(hi) + 0.3);
        assert!(
            (a..=b).contains(&mean(r)),
            "{r}: {} not in [{a}, {b}]",
            mean(r)
        );
    };
    within("Left Blackbody", 47.2, 60.7);
    within("Right Blackbody", 47.2, 60.7);
    within("Left Pool", 40.6, 44.3);
    within("Left Concrete", 34.8, 37.4);
    within("Right Concrete", 34.8, 37.4);
    within("Top Pyramid", 29.9, 36.2);
    within("Bottom Pyramid", 29.9, 36.2);

    // The README's table (°C, 2 decimals) is what the pipeline gives: "ours" is the mean
    // after the blur, the other columns Table 7's values, the differences theirs.
    let readme =
        std::fs::read_to_string(repo_root().join("pipelines/thesis-experiment/README.md")).unwrap();
    let rows: Vec<Vec<f64>> = TABLE_7
        .iter()
        .map(|region| {
            let line = readme
                .lines()
                .find(|l| l.starts_with(&format!("| {region} | ")))
                .unwrap_or_else(|| panic!("no README row for {region}"));
            let cells: Vec<f64> = line
                .trim_matches('|')
                .split('|')
                .skip(1)
                .map(|c| {
                    c.trim()
                        .replace('−', "-")
                        .trim_start_matches('+')
                        .parse()
                        .unwrap()
                })
                .collect();
            assert_eq!(cells.len(), 6, "{line}");
            let ours = mean(region) - 273.15;
            assert!(
                (cells[0] - ours).abs() <= 0.005 + 1e-9,
                "{region}: the README says {} °C, the pipeline gives {ours}",
                cells[0]
            );
            let (real, synthetic) = (cells[2], cells[3]);
            assert!((cells[4] - (cells[0] - real)).abs() <= 0.011, "{line}");
            assert!((cells[5] - (cells[0] - synthetic)).abs() <= 0.011, "{line}");
            vec![ours, real, synthetic]
        })
        .collect();
    let mean_abs = |column: usize| {
        rows.iter().map(|r| (r[0] - r[column]).abs()).sum::<f64>() / rows.len() as f64
    };
    for (column, what) in [(1, "ours − real"), (2, "ours − 1990 synthetic")] {
        let printed = if column == 1 { "2.10" } else { "0.66" };
        let stated = format!("mean |{what}| = {printed} K");
        assert!(
            readme.to_lowercase().contains(&stated.to_lowercase()),
            "the README no longer states `{stated}`"
        );
        let measured = mean_abs(column);
        assert!(
            (measured - printed.parse::<f64>().unwrap()).abs() <= 0.005 + 1e-9,
            "{what}: the README says {printed} K, the pipeline gives {measured}"
        );
    }

    regions_that_do_not_fit_fail_at_their_line_and_column(&data);
}

#[test]
fn a_true_blackbody_panel_appears_within_the_path_bound_of_its_kinetic_temperature() {
    // The same experiment with the panel's paint made a blackbody (ε = 1 at every angle).
    let (_dir, pipeline) = copy_pipeline();
    let data = pipeline.parent().unwrap().join("thesis-experiment");
    let materials = std::fs::read_to_string(data.join("materials.ron")).unwrap();
    let (head, rest) = materials.split_once("name: \"black paint\",").unwrap();
    let (_, tail) = rest.split_once("specular_fraction").unwrap();
    let patched = format!(
        "{head}name: \"black paint\",\n      emissivity: [(0.0, 1.0), (90.0, 1.0)],\n      \
         specular_fraction{tail}"
    );
    std::fs::write(data.join("materials.ron"), patched).unwrap();
    run_pipeline(&pipeline);
    let apparent = stats_csv(
        &data,
        &[
            "--radiance",
            &data.join("out/experiment.sensor.exr").to_string_lossy(),
        ],
    );

    // Hand bound. The camera-panel path is ~10.3 m of the lowest 5 m of air. The
    // midlat-winter .atm gives, for the lowest 50 m, τ = 0.970472: a shorter path through
    // the same air absorbs less, so 1 − τ_path ≤ a = 0.0296. The air emits what it absorbs
    // at its own temperature, at most the surface air's 272.2 K (the profile cools
    // upwards). So L_app = τ·L(T) + L_u ≥ L(T) − a·(L(T) − L(272.2 K)), and L_app < L(T)
    // since the air is colder than the panel.
    let l_panel = planck_8_14(BLACKBODY_K);
    let a = 1.0 - 0.970_472;
    let lowest_k = temperature_8_14(l_panel - a * (l_panel - planck_8_14(272.2)));
    assert!(BLACKBODY_K - lowest_k < 1.2, "bound {lowest_k}");
    for region in ["Left Blackbody", "Right Blackbody"] {
        let r = &apparent[region];
        let t = r["mean_k"];
        assert!(
            (lowest_k..BLACKBODY_K - 0.01).contains(&t),
            "{region}: {t} K not in [{lowest_k}, {BLACKBODY_K} − 0.01) K"
        );
        // A uniform blackbody region stays uniform after the blur (boxes ≥ 3 px inside).
        assert!(r["std_dev_k"] < 0.05, "{region}: {r:?}");
    }
}

/// A region beyond the image, or one that selects nothing, fails at its line and column
/// and writes nothing (on the outputs of a run, to save tracing again).
fn regions_that_do_not_fit_fail_at_their_line_and_column(data: &Path) {
    let bad = data.join("bad-regions.ron");
    std::fs::write(
        &bad,
        "(\n  regions: [\n    (name: \"ok\", material: Some(1)),\n    \
         (name: \"off\", pixels: Some((columns: (250, 300), rows: (0, 5)))),\n  ],\n)\n",
    )
    .unwrap();
    let out_file = data.join("out/bad-table.txt");
    let out = bin("irsig-stats")
        .arg(data.join("out/experiment.truth.exr"))
        .arg("--regions")
        .arg(&bad)
        .arg("-o")
        .arg(&out_file)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("bad-regions.ron:4:"), "{stderr}");
    assert!(stderr.contains("beyond the image"), "{stderr}");
    assert!(!out_file.exists());

    // A region that selects nothing (no pixel of material 9) is an error too.
    std::fs::write(&bad, "(regions: [(name: \"none\", material: Some(9))])").unwrap();
    let out = bin("irsig-stats")
        .arg(data.join("out/experiment.truth.exr"))
        .arg("--regions")
        .arg(&bad)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("bad-regions.ron:1:"), "{stderr}");
    assert!(stderr.contains("selects no pixel"), "{stderr}");
    assert!(out.stdout.is_empty());
}
