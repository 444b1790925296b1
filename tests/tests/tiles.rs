//! A frame traced in tiles (`irsig-trace --tile`) and merged (`irsig-merge`): the merged
//! radiance EXR, truth EXR, interaction map, digital counts and LUT are byte for byte those
//! of the frame traced whole, with supersampling, sky-view rays, adaptive supersampling,
//! the tolerance pilot's decision and the error budget's layers; and every bad request — a tile outside the image, a
//! missing or overlapping tile, tiles of different runs, a file that is no tile — is
//! refused with a message naming it, writing nothing.

use std::path::{Path, PathBuf};

use irsig_tests::bin;
use predicates::prelude::*;

/// The quickstart camera at 60 × 45 pixels: the panel, the pool, the car and the sky.
const VIEW: &str = "LookAt(position_m: (0.0, -22.6851, 5.0), target_m: (1.5, 0.0, 1.0), \
                    pixels: (60, 45), fov_deg: (47.0, 36.0), gain_dc_per_k: Some(3.0))";

const MATERIALS: &str = "pipelines/quickstart/materials.ron";

/// The quickstart scene flattened into `dir`, and the view; returns (raw, view).
fn inputs(dir: &Path) -> (PathBuf, PathBuf) {
    let raw = dir.join("scene.raw");
    bin("irsig-flatten")
        .args([
            "pipelines/quickstart/scene.ron",
            "--materials",
            MATERIALS,
            "-o",
        ])
        .arg(&raw)
        .assert()
        .success();
    let view = dir.join("view.ron");
    std::fs::write(&view, VIEW).unwrap();
    (raw, view)
}

/// irsig-trace of the scene with every model that draws random numbers or looks at
/// neighbours switched on.
fn trace(raw: &Path, view: &Path, extra: &[&str]) -> assert_cmd::Command {
    let mut cmd = bin("irsig-trace");
    cmd.arg("--scene")
        .arg(raw)
        .args(["--materials", MATERIALS, "--view"])
        .arg(view)
        .args(["--atmosphere", "us-std-1976", "--seed", "5"])
        .args(extra);
    cmd
}

const MODELS: [&str; 6] = [
    "--supersample",
    "3",
    "--sky-view-rays",
    "4",
    "--adaptive-supersampling",
    "0.25",
];

/// Every file in `dir`, sorted.
fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .map(|d| {
            d.map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
                .collect()
        })
        .unwrap_or_default();
    v.sort();
    v
}

fn assert_same_files(whole: &Path, merged: &Path) {
    assert_eq!(names(whole), names(merged));
    for name in names(whole) {
        let (a, b) = (
            std::fs::read(whole.join(&name)).unwrap(),
            std::fs::read(merged.join(&name)).unwrap(),
        );
        assert!(a == b, "{name} differs from the whole frame's");
    }
}

/// Traces the 6 tiles of a 3 x 2 grid into `dir`, as t1..t6.
fn trace_grid(raw: &Path, view: &Path, dir: &Path, extra: &[&str]) {
    std::fs::create_dir_all(dir).unwrap();
    for i in 1..=6 {
        trace(raw, view, extra)
            .args(["--tile", &format!("{i}/3x2"), "-o"])
            .arg(dir.join(format!("t{i}")))
            .assert()
            .success();
    }
}

/// `text` in a message however the terminal renderer wrapped it (its line breaks and `│`
/// margins taken out, runs of spaces made one).
fn says(text: &'static str) -> impl Predicate<str> {
    predicate::function(move |out: &str| {
        let flat = out.replace('│', " ");
        let flat = flat.split_whitespace().collect::<Vec<_>>().join(" ");
        flat.contains(text)
    })
}

fn tile_files(dir: &Path) -> Vec<PathBuf> {
    names(dir).iter().map(|n| dir.join(n)).collect()
}

#[test]
fn tiles_merge_into_the_whole_frames_bytes() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let (raw, view) = inputs(d);
    std::fs::create_dir(d.join("whole")).unwrap();
    trace(&raw, &view, &MODELS)
        .arg("-o")
        .arg(d.join("whole/frame"))
        .assert()
        .success();
    assert_eq!(
        names(&d.join("whole")),
        [
            "frame.dc.png",
            "frame.lut.txt",
            "frame.map.png",
            "frame.radiance.exr",
            "frame.truth.exr"
        ]
    );
    let tiles = d.join("tiles");
    trace_grid(&raw, &view, &tiles, &MODELS);
    // A tile is its radiance and truth EXRs, nothing that needs the whole frame.
    assert_eq!(names(&tiles).len(), 12);
    assert!(names(&tiles).iter().all(|n| n.ends_with(".exr")));
    std::fs::create_dir(d.join("merged")).unwrap();
    bin("irsig-merge")
        .args(tile_files(&tiles))
        .arg("-o")
        .arg(d.join("merged/frame"))
        .args(["--view"])
        .arg(&view)
        .assert()
        .success();
    assert_same_files(&d.join("whole"), &d.join("merged"));

    // Rectangles of any shape, given by X,Y,W,H, and the per-output flags of a pipeline
    // stage: the same bytes.
    let rects = d.join("rects");
    std::fs::create_dir(&rects).unwrap();
    for (i, rect) in ["0,0,60,7", "0,7,1,38", "1,7,59,30", "1,37,59,8"]
        .iter()
        .enumerate()
    {
        trace(&raw, &view, &MODELS)
            .args(["--tile", rect, "--radiance-exr"])
            .arg(rects.join(format!("r{i}.radiance.exr")))
            .arg("--truth-exr")
            .arg(rects.join(format!("r{i}.truth.exr")))
            .assert()
            .success();
    }
    let one = d.join("one");
    std::fs::create_dir(&one).unwrap();
    bin("irsig-merge")
        .args(tile_files(&rects))
        .args(["--band", "8-14", "--view"])
        .arg(&view)
        .arg("--radiance-exr")
        .arg(one.join("frame.radiance.exr"))
        .arg("--truth-exr")
        .arg(one.join("frame.truth.exr"))
        .arg("--map-png")
        .arg(one.join("frame.map.png"))
        .arg("--dc-png")
        .arg(one.join("frame.dc.png"))
        .arg("--lut")
        .arg(one.join("frame.lut.txt"))
        .assert()
        .success();
    assert_same_files(&d.join("whole"), &one);
}

#[test]
fn tiles_share_the_whole_frames_tolerance_decision() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let (raw, view) = inputs(d);
    std::fs::create_dir(d.join("whole")).unwrap();
    trace(&raw, &view, &["--tolerance", "0.3"])
        .arg("-o")
        .arg(d.join("whole/frame"))
        .arg("--no-dc")
        .assert()
        .success();
    let decision = d.join("whole/frame.decision.ron");
    assert!(decision.is_file());
    // The pilot alone, as a pipeline's first stage: the same decision, no image.
    let pilot = d.join("pilot.decision.ron");
    trace(&raw, &view, &["--tolerance", "0.3", "--decision-out"])
        .arg(&pilot)
        .assert()
        .success();
    assert_eq!(
        std::fs::read(&pilot).unwrap(),
        std::fs::read(&decision).unwrap()
    );
    let tiles = d.join("tiles");
    trace_grid(
        &raw,
        &view,
        &tiles,
        &["--decision", pilot.to_str().unwrap()],
    );
    std::fs::create_dir(d.join("merged")).unwrap();
    bin("irsig-merge")
        .args(tile_files(&tiles))
        .arg("-o")
        .arg(d.join("merged/frame"))
        .arg("--no-dc")
        .assert()
        .success();
    std::fs::remove_file(&decision).unwrap();
    assert_same_files(&d.join("whole"), &d.join("merged"));
}

#[test]
fn tiles_with_the_error_budget_merge_into_the_whole_frames_bytes() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let (raw, view) = inputs(d);
    let pilot = d.join("pilot.decision.ron");
    trace(&raw, &view, &["--tolerance", "0.3", "--decision-out"])
        .arg(&pilot)
        .assert()
        .success();
    let uncertainties = d.join("u.ron");
    std::fs::write(
        &uncertainties,
        "(temperature: [(facets: All, sigma_k: 0.2)], emissivity: [(material: 1, sigma: 0.01)], \
         transmission_relative: 0.02, path_radiance_relative: 0.05)",
    )
    .unwrap();
    let extra = [
        "--decision",
        pilot.to_str().unwrap(),
        "--uncertainties",
        uncertainties.to_str().unwrap(),
    ];
    std::fs::create_dir(d.join("whole")).unwrap();
    trace(&raw, &view, &extra)
        .arg("-o")
        .arg(d.join("whole/frame"))
        .assert()
        .success();
    // The truth EXR holds the budget's σ layers, σ_model the decision's predicted error.
    let truth =
        irsig_raster::read_exr(&std::fs::read(d.join("whole/frame.truth.exr")).unwrap()).unwrap();
    let model = truth.layer("sigma_model").expect("a sigma_model layer");
    assert!(
        model.data.iter().all(|&s| s > 0.0 && s <= 0.3),
        "{:?}",
        &model.data[..4]
    );
    assert!(truth.layer("sigma_total").is_some());
    let tiles = d.join("tiles");
    trace_grid(&raw, &view, &tiles, &extra);
    std::fs::create_dir(d.join("merged")).unwrap();
    bin("irsig-merge")
        .args(tile_files(&tiles))
        .arg("-o")
        .arg(d.join("merged/frame"))
        .arg("--view")
        .arg(&view)
        .assert()
        .success();
    assert_same_files(&d.join("whole"), &d.join("merged"));
}

#[test]
fn bad_tiles_are_refused_and_nothing_is_written() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let (raw, view) = inputs(d);
    let out = d.join("out");
    std::fs::create_dir(&out).unwrap();

    // A tile outside the 60 x 45 image, by rectangle or by grid.
    for (tile, message) in [
        ("50,0,16,16", "outside the 60x45 image"),
        ("0,40,8,8", "outside the 60x45 image"),
        ("7/3x2", "expected a tile from 1 to 6"),
        ("1/61x1", "does not fit a 60x45"),
        ("0,0,0,5", "has no pixels"),
        ("3/3", "expected I/CxR"),
    ] {
        trace(&raw, &view, &[])
            .args(["--tile", tile, "-o"])
            .arg(out.join("t"))
            .assert()
            .code(2)
            .stderr(says(message));
    }
    // What needs the whole frame cannot come from a tile.
    for flag in ["--dc-png", "--map-png", "--lut"] {
        trace(&raw, &view, &[])
            .args(["--tile", "1/2x2", "--radiance-exr"])
            .arg(out.join("r.exr"))
            .arg(flag)
            .arg(out.join("x"))
            .assert()
            .code(2)
            .stderr(says("cannot be used with"));
    }
    trace(&raw, &view, &["--tolerance", "0.3"])
        .args(["--tile", "1/2x2", "-o"])
        .arg(out.join("t"))
        .assert()
        .code(2);
    assert!(names(&out).is_empty(), "{:?}", names(&out));

    let tiles = d.join("tiles");
    trace_grid(&raw, &view, &tiles, &[]);
    let all = tile_files(&tiles);
    let merge = |files: &[PathBuf]| {
        let mut cmd = bin("irsig-merge");
        cmd.args(files).arg("-o").arg(out.join("frame"));
        cmd.assert()
    };
    // A missing tile: t4 (rows 22-44, columns 0-19).
    let missing: Vec<PathBuf> = all
        .iter()
        .filter(|p| !p.file_name().unwrap().to_string_lossy().starts_with("t4."))
        .cloned()
        .collect();
    merge(&missing)
        .code(1)
        .stderr(says("no tile holds pixel (column 0, row 22)").and(says("a tile is missing")));
    // An overlapping tile, and the same tile twice.
    let extra = d.join("extra");
    std::fs::create_dir(&extra).unwrap();
    trace(&raw, &view, &[])
        .args(["--tile", "15,10,10,20", "-o"])
        .arg(extra.join("x"))
        .assert()
        .success();
    let mut overlapping = all.clone();
    overlapping.push(extra.join("x.radiance.exr"));
    merge(&overlapping)
        .code(1)
        .stderr(says("overlap").and(says("x.radiance.exr")));
    let mut twice = all.clone();
    twice.push(all[0].clone());
    merge(&twice).code(1).stderr(says("overlap"));
    // A tile of another run: another number of bounces.
    trace(&raw, &view, &["--bounces", "2"])
        .args(["--tile", "2/3x2", "-o"])
        .arg(extra.join("t2"))
        .assert()
        .success();
    let mut other_run: Vec<PathBuf> = all
        .iter()
        .filter(|p| !p.file_name().unwrap().to_string_lossy().starts_with("t2."))
        .cloned()
        .collect();
    other_run.push(extra.join("t2.radiance.exr"));
    other_run.push(extra.join("t2.truth.exr"));
    merge(&other_run)
        .code(1)
        .stderr(says("come from different runs"));
    // A tile of a bigger frame of the same scene.
    let big = d.join("big.ron");
    std::fs::write(&big, VIEW.replace("(60, 45)", "(64, 45)")).unwrap();
    trace(&raw, &big, &[])
        .args(["--tile", "2/3x2", "-o"])
        .arg(extra.join("b2"))
        .assert()
        .success();
    let mut bigger = missing.clone();
    bigger.push(extra.join("b2.radiance.exr"));
    merge(&bigger)
        .code(1)
        .stderr(says("come from different runs"));
    // A file that is no tile: the sensor stage's output.
    let sensed = extra.join("sensed.exr");
    bin("irsig-sensor")
        .arg(&all[0])
        .args(["--mtf", "box:3x3", "-o"])
        .arg(&sensed)
        .assert()
        .success();
    let mut with_sensed = all.clone();
    with_sensed.push(sensed);
    merge(&with_sensed)
        .code(1)
        .stderr(says("says nothing of the frame"));
    // Not an EXR at all.
    let junk = extra.join("junk.exr");
    std::fs::write(&junk, "not an image").unwrap();
    merge(&[junk])
        .code(1)
        .stderr(says("junk.exr:1:1: not a readable EXR"));
    // An output made from tiles not given.
    let radiance_only: Vec<PathBuf> = all
        .iter()
        .filter(|p| p.to_string_lossy().ends_with(".radiance.exr"))
        .cloned()
        .collect();
    bin("irsig-merge")
        .args(&radiance_only)
        .arg("--truth-exr")
        .arg(out.join("t.exr"))
        .assert()
        .code(2)
        .stderr(says("--truth-exr is made from truth tiles"));
    // An output in a directory that does not exist, refused before the tiles are pasted.
    bin("irsig-merge")
        .args(&all)
        .arg("-o")
        .arg(d.join("no-such-dir").join("frame"))
        .assert()
        .code(1)
        .stderr(says("is not an existing directory").and(says("no-such-dir")));
    assert!(names(&out).is_empty(), "nothing written: {:?}", names(&out));
}
