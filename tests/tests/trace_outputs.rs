//! `irsig-trace` end to end: the per-output flags write exactly the files named, with the
//! same bytes as the `-o PREFIX` form; conflicting or impossible requests are refused
//! before anything is written.

use std::path::Path;

use irsig_tests::bin;
use predicates::prelude::*;

/// A small view of the sample boxes (the demo camera at 48 × 36 pixels).
const VIEW: &str = "LookAt(position_m: (1.5, -14.0, 3.0), target_m: (1.5, 1.0, 0.5), \
                    pixels: (48, 36), fov_deg: (64.0, 48.0))";

/// Flattens the sample scene into `dir` and writes the small view; returns (raw, view).
fn inputs(dir: &Path) -> (std::path::PathBuf, std::path::PathBuf) {
    let raw = dir.join("scene.raw");
    bin("irsig-flatten")
        .args([
            "formats/canonical/samples/scene.ron",
            "--materials",
            "formats/canonical/samples/materials.ron",
            "-o",
        ])
        .arg(&raw)
        .assert()
        .success();
    let view = dir.join("view.ron");
    std::fs::write(&view, VIEW).unwrap();
    (raw, view)
}

fn trace(raw: &Path, view: &Path) -> assert_cmd::Command {
    let mut cmd = bin("irsig-trace");
    cmd.arg("--scene")
        .arg(raw)
        .args(["--materials", "formats/canonical/samples/materials.ron"])
        .arg("--view")
        .arg(view)
        .args(["--atmosphere", "us-std-1976"]);
    cmd
}

#[test]
fn per_output_flags_write_only_the_files_named_with_the_prefix_forms_bytes() {
    let dir = tempfile::tempdir().unwrap();
    let (raw, view) = inputs(dir.path());
    let prefix = dir.path().join("all");
    trace(&raw, &view).arg("-o").arg(&prefix).assert().success();

    let only = dir.path().join("only");
    std::fs::create_dir(&only).unwrap();
    trace(&raw, &view)
        .arg("--radiance-exr")
        .arg(only.join("r.exr"))
        .arg("--lut")
        .arg(only.join("l.txt"))
        .assert()
        .success();
    let mut written: Vec<_> = std::fs::read_dir(&only)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    written.sort();
    assert_eq!(written, ["l.txt", "r.exr"]);
    let read = |p: &Path| std::fs::read(p).unwrap();
    assert_eq!(
        read(&only.join("r.exr")),
        read(&dir.path().join("all.radiance.exr"))
    );
    assert_eq!(
        read(&only.join("l.txt")),
        read(&dir.path().join("all.lut.txt"))
    );

    // The other three, in a second run: the same bytes again.
    trace(&raw, &view)
        .arg("--truth-exr")
        .arg(only.join("t.exr"))
        .arg("--map-png")
        .arg(only.join("m.png"))
        .arg("--dc-png")
        .arg(only.join("d.png"))
        .assert()
        .success();
    for (mine, theirs) in [
        ("t.exr", "all.truth.exr"),
        ("m.png", "all.map.png"),
        ("d.png", "all.dc.png"),
    ] {
        assert_eq!(
            read(&only.join(mine)),
            read(&dir.path().join(theirs)),
            "{mine}"
        );
    }
}

/// The interaction map is the 1990 nibble bytes as palette indices: each pixel's index is
/// `primary · 16 + reflected`, the ids the truth EXR's material layers hold; a viewer shows
/// the palette, in which every material has its own colour and nothing hit is black.
#[test]
fn the_maps_indices_are_the_truths_ids_and_its_palette_is_visible() {
    let dir = tempfile::tempdir().unwrap();
    let (raw, view) = inputs(dir.path());
    let prefix = dir.path().join("f");
    trace(&raw, &view).arg("-o").arg(&prefix).assert().success();
    let png = std::fs::read(dir.path().join("f.map.png")).unwrap();
    let (w, h, indices) = irsig_raster::read_png_indices(&png).unwrap();
    assert_eq!((w, h), (48, 36));
    let truth =
        irsig_raster::read_exr(&std::fs::read(dir.path().join("f.truth.exr")).unwrap()).unwrap();
    let layer = |name: &str| &truth.layer(name).unwrap().data;
    let (primary, reflected) = (layer("material_primary"), layer("material_secondary"));
    let want: Vec<u8> = primary
        .iter()
        .zip(reflected)
        .map(|(&p, &s)| (p as u8) * 16 + s as u8)
        .collect();
    assert_eq!(indices, want);
    // The view sees the sky or the terrain (0) and two materials at least.
    let distinct: std::collections::BTreeSet<u8> = indices.iter().map(|i| i >> 4).collect();
    assert!(distinct.contains(&0) && distinct.len() >= 3, "{distinct:?}");
    let rgb = image::load_from_memory(&png).unwrap().into_rgb8();
    for (i, pixel) in rgb.pixels().enumerate() {
        let visible = pixel.0.iter().map(|&c| u32::from(c)).sum::<u32>() >= 200;
        assert_eq!(visible, indices[i] >= 16, "pixel {i}: index {}", indices[i]);
    }
}

#[test]
fn one_output_goes_to_standard_output_with_the_file_forms_bytes() {
    let dir = tempfile::tempdir().unwrap();
    let (raw, view) = inputs(dir.path());
    let file = dir.path().join("r.exr");
    trace(&raw, &view)
        .arg("--radiance-exr")
        .arg(&file)
        .assert()
        .success();
    let piped = trace(&raw, &view)
        .args(["--radiance-exr", "-"])
        .arg("--lut")
        .arg(dir.path().join("l.txt"))
        .output()
        .unwrap();
    assert!(piped.status.success());
    assert_eq!(piped.stdout, std::fs::read(&file).unwrap());
    assert!(dir.path().join("l.txt").exists());
    // And the sensor stage reads it from its standard input.
    bin("irsig-sensor")
        .args(["-", "-o"])
        .arg(dir.path().join("s.exr"))
        .write_stdin(piped.stdout)
        .assert()
        .success();
    assert!(dir.path().join("s.exr").exists());
}

#[test]
fn two_outputs_to_standard_output_are_a_usage_error() {
    let dir = tempfile::tempdir().unwrap();
    let (raw, view) = inputs(dir.path());
    trace(&raw, &view)
        .args(["--radiance-exr", "-", "--dc-png", "-"])
        .assert()
        .code(2)
        .stdout(predicate::str::is_empty())
        .stderr(predicate::str::contains("only one output"));
}

#[test]
fn prefix_and_per_output_flags_together_are_a_usage_error() {
    let dir = tempfile::tempdir().unwrap();
    let (raw, view) = inputs(dir.path());
    trace(&raw, &view)
        .arg("-o")
        .arg(dir.path().join("p"))
        .arg("--radiance-exr")
        .arg(dir.path().join("r.exr"))
        .assert()
        .code(2);
    assert!(!dir.path().join("r.exr").exists());
}

#[test]
fn per_output_flags_with_several_views_are_refused_before_anything_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let (raw, _) = inputs(dir.path());
    let two = dir.path().join("two.ron");
    std::fs::write(&two, format!("[{VIEW}, {VIEW}]")).unwrap();
    trace(&raw, &two)
        .arg("--radiance-exr")
        .arg(dir.path().join("r.exr"))
        .assert()
        .code(2)
        .stderr(predicate::str::contains("2 views"));
    assert!(!dir.path().join("r.exr").exists());
}

#[test]
fn no_dc_with_a_dc_output_is_a_usage_error() {
    let dir = tempfile::tempdir().unwrap();
    let (raw, view) = inputs(dir.path());
    trace(&raw, &view)
        .args(["--no-dc", "--dc-png"])
        .arg(dir.path().join("d.png"))
        .assert()
        .code(2)
        .stderr(predicate::str::contains("--no-dc"));
}

#[test]
fn an_interaction_map_that_cannot_hold_the_ids_is_an_error_and_nothing_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let (raw, view) = inputs(dir.path());
    // The sample library with one more material, id 16: beyond the 4-bit nibble.
    let library = std::fs::read_to_string(
        irsig_tests::repo_root().join("formats/canonical/samples/materials.ron"),
    )
    .unwrap();
    let mut lib: irsig_model::MaterialLibrary = ron::from_str(&library).unwrap();
    let mut extra = lib.materials[0].clone();
    extra.id = irsig_model::MaterialId(16);
    extra.name = "sixteenth".into();
    lib.materials.push(extra);
    let big = dir.path().join("big.ron");
    std::fs::write(&big, ron::to_string(&lib).unwrap()).unwrap();
    bin("irsig-trace")
        .arg("--scene")
        .arg(&raw)
        .arg("--materials")
        .arg(&big)
        .arg("--view")
        .arg(&view)
        .arg("--radiance-exr")
        .arg(dir.path().join("r.exr"))
        .arg("--map-png")
        .arg(dir.path().join("m.png"))
        .assert()
        .code(1)
        .stderr(predicate::str::contains("id 16"));
    assert!(!dir.path().join("r.exr").exists());
    assert!(!dir.path().join("m.png").exists());
}

#[test]
fn with_a_tolerance_the_decision_is_written_beside_the_outputs_and_says_where() {
    // `--tolerance` with per-output flags and no --decision-out used to print the decision
    // and keep no file, saying nothing.
    let dir = tempfile::tempdir().unwrap();
    let (raw, view) = inputs(dir.path());
    let radiance = dir.path().join("r.exr");
    let decision = dir.path().join("r.decision.ron");
    trace(&raw, &view)
        .args(["--tolerance", "1", "--radiance-exr"])
        .arg(&radiance)
        .assert()
        .success()
        .stderr(predicate::str::contains(format!(
            "the decision goes to {}",
            decision.display()
        )));
    let text = std::fs::read_to_string(&decision).unwrap();
    let d: irsig_model::decision::Decision =
        irsig_formats::canonical::from_ron("decision", &text).unwrap();
    assert!((d.tolerance_k - 1.0).abs() < 1e-12, "{text}");
    // The built-in's rows record their interpolation error (crates/atmosphere/data): the
    // decision summarises it over the view paths, apart from the tolerance; it writes no
    // one-number `data_error_k` any more.
    assert!(
        d.data_error
            .is_some_and(|e| e.p99_k > 0.0 && e.p99_k <= e.max_k && e.max_k < 10.0),
        "{text}"
    );
    assert!(
        d.data_error_k.is_none() && !text.contains("data_error_k"),
        "{text}"
    );
    // Every output to standard output: no file to put it beside, and the note says so.
    trace(&raw, &view)
        .args(["--tolerance", "1", "--radiance-exr", "-"])
        .assert()
        .success()
        .stderr(predicate::str::contains(
            "the decision is not written (every output goes to standard output)",
        ));
}
