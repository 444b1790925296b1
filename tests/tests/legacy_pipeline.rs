//! The 1990-style inputs of `pipelines/legacy/` (facet files, scene file, viewing files, an
//! execute file, DIRTRAN tables) through its Makefile, which chains the stage tools with
//! Unix pipes; the same images made without the pipe, byte for byte; and `irsig-trace`'s
//! reading of legacy viewing and execute files, including malformed ones (exit 1, file,
//! line and column, nothing written).

use std::path::{Path, PathBuf};
use std::process::Command;

use irsig_tests::{bin, bin_path, repo_root};

/// A scratch copy of `pipelines/legacy` (its files only, no build outputs).
fn legacy_copy() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    for entry in std::fs::read_dir(repo_root().join("pipelines/legacy")).unwrap() {
        let path = entry.unwrap().path();
        if path.is_file() {
            std::fs::copy(&path, dir.path().join(path.file_name().unwrap())).unwrap();
        }
    }
    dir
}

fn grey(path: &Path) -> image::GrayImage {
    // By content: the 1990 names (`a.img`, `a.map`) carry no PNG extension.
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    image::load_from_memory(&bytes)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .to_luma8()
}

/// The interaction map's bytes (its palette indices), each pixel's primary material in
/// the upper nibble: a viewer shows the palette's colours instead.
struct Map {
    width: usize,
    bytes: Vec<u8>,
}

impl Map {
    fn read(path: &Path) -> Self {
        let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let (width, _, bytes) = irsig_raster::read_png_indices(&bytes)
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        Self { width, bytes }
    }

    fn primary(&self, x: usize, y: usize) -> u8 {
        self.bytes[y * self.width + x] >> 4
    }
}

fn bin_dir() -> PathBuf {
    bin_path("irsig-trace").parent().unwrap().to_path_buf()
}

#[test]
#[allow(clippy::float_cmp)] // the library's numbers are the files' numbers, exactly
fn the_makefile_turns_1990_inputs_into_images() {
    let dir = legacy_copy();
    let out = Command::new("make")
        .current_dir(dir.path())
        .arg(format!("IRSIG_BIN={}", bin_dir().display()))
        .output()
        .expect("GNU make (installed by .ci/run)");
    assert!(
        out.status.success(),
        "make failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let build = dir.path().join("build");
    assert!(build.join("atmosphere.ron").is_file());
    // The library made from the material index carries the .ems rows and the flags.
    let library = std::fs::read_to_string(build.join("materials.ron")).unwrap();
    let library: irsig_model::MaterialLibrary = ron::from_str(&library).unwrap();
    let ids: Vec<u16> = library.materials.iter().map(|m| m.id.0).collect();
    assert_eq!(ids, [1, 2, 4, 5, 6]);
    let water = &library.materials[4];
    assert_eq!(water.name, "water");
    assert_eq!(water.specular_fraction, 1.0);
    assert_eq!(water.emissivity.first(), Some(&(0.0, 0.985191)));
    assert_eq!(water.emissivity.last(), Some(&(90.0, 0.0)));
    assert_eq!(library.materials[1].specular_fraction, 0.0);
    for f in ["frame-04", "frame-14", "pond"] {
        for ext in ["map.png", "dc.png", "lut"] {
            assert!(build.join(format!("{f}.{ext}")).is_file(), "{f}.{ext}");
        }
        let dc = grey(&build.join(format!("{f}.dc.png")));
        assert_eq!(
            (dc.width(), dc.height()),
            (128, 128),
            "{f}: the viewing file's M N"
        );
        // The LUT has one row per count: DC, radiance, K, °C.
        let lut = std::fs::read_to_string(build.join(format!("{f}.lut"))).unwrap();
        assert!(
            lut.lines().count() >= 256,
            "{f}: {} LUT lines",
            lut.lines().count()
        );
    }

    // Frame 14 looks straight down from 0.7 km (the viewing file's km, in metres) with a
    // 1° field: 12.2 m across 128 pixels, north up (κ = 0). The interaction map's upper
    // nibble is the material index of materials.mat: the truck's steel roof (4) at the
    // centre; 5.9 m west of it, on the road's centre line, asphalt (1); the top-left
    // corner, 6.1 m north and west, grass (2).
    let map = Map::read(&build.join("frame-14.map.png"));
    assert_eq!(map.primary(64, 64), 4, "truck roof");
    assert_eq!(map.primary(2, 64), 1, "road");
    assert_eq!(map.primary(0, 0), 2, "grass");
    // The pond (the thesis's facet sample, material 6 = water) is in the low view, and,
    // being specular, reflects the sky (lower nibble 0) or an object.
    let pond = Map::read(&build.join("pond.map.png"));
    assert!(pond.bytes.iter().any(|p| p >> 4 == 6), "water seen");

    // The same frame without the pipe: flatten reads every facet file itself (no
    // import), trace takes the viewing file directly with per-output flags. Same bytes.
    let raw = dir.path().join("direct.raw");
    bin("irsig-flatten")
        .current_dir(dir.path())
        .args(["scene.scn", "--legacy-unit", "km", "-o"])
        .arg(&raw)
        .assert()
        .success();
    bin("irsig-trace")
        .current_dir(dir.path())
        .args([
            "--scene",
            "direct.raw",
            "--materials",
            "build/materials.ron",
        ])
        .args([
            "--atmosphere",
            "build/atmosphere.ron",
            "--atmosphere-model",
            "layered",
            "--view",
            "frame-14.view",
        ])
        .args([
            "--map-png",
            "d.map.png",
            "--dc-png",
            "d.dc.png",
            "--lut",
            "d.lut",
        ])
        .assert()
        .success();
    for (made, direct) in [
        ("build/frame-14.map.png", "d.map.png"),
        ("build/frame-14.dc.png", "d.dc.png"),
        ("build/frame-14.lut", "d.lut"),
    ] {
        assert!(
            std::fs::read(dir.path().join(made)).unwrap()
                == std::fs::read(dir.path().join(direct)).unwrap(),
            "{made} differs from {direct}"
        );
    }
    // make again: everything is up to date.
    let again = Command::new("make")
        .current_dir(dir.path())
        .args(["-q", &format!("IRSIG_BIN={}", bin_dir().display())])
        .status()
        .unwrap();
    assert!(again.success(), "make -q: not up to date after a build");
}

/// Scene, materials and a raw scene in a scratch directory, for irsig-trace alone.
fn trace_scratch() -> tempfile::TempDir {
    let dir = legacy_copy();
    bin("irsig-material")
        .current_dir(dir.path())
        .args(["convert", "materials.mat", "-o", "materials.ron"])
        .assert()
        .success();
    bin("irsig-flatten")
        .current_dir(dir.path())
        .args(["scene.scn", "--legacy-unit", "km", "-o", "scene.raw"])
        .assert()
        .success();
    dir
}

fn trace(dir: &Path, args: &[&str]) -> std::process::Output {
    let mut cmd = bin("irsig-trace");
    cmd.current_dir(dir)
        .args(["--scene", "scene.raw", "--materials", "materials.ron"])
        .args(args);
    cmd.output().unwrap()
}

#[test]
fn an_execute_file_gives_one_output_set_per_frame() {
    let dir = trace_scratch();
    std::fs::create_dir(dir.path().join("seq")).unwrap();
    // Two frames, paths relative to the execute file (in seq/), small images.
    for (name, z) in [("a.view", 0.7), ("b.view", 0.35)] {
        std::fs::write(
            dir.path().join("seq").join(name),
            format!("0 0 {z}\n16 12\n0 0 0\n1 1\n"),
        )
        .unwrap();
    }
    std::fs::write(
        dir.path().join("seq/run.exec"),
        "a.view ../scene.scn a.map a.img a.lut\nb.view ../scene.scn b.map b.img b.lut\n",
    )
    .unwrap();
    let out = trace(dir.path(), &["--execute", "seq/run.exec"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for f in ["a", "b"] {
        for ext in ["map", "img", "lut"] {
            assert!(
                dir.path().join(format!("seq/{f}.{ext}")).is_file(),
                "{f}.{ext}"
            );
        }
        let img = grey(&dir.path().join(format!("seq/{f}.img")));
        assert_eq!((img.width(), img.height()), (16, 12));
    }
    // Both look straight down at the truck roof's centre: material 4 in the upper nibble.
    for f in ["a", "b"] {
        let map = Map::read(&dir.path().join(format!("seq/{f}.map")));
        assert_eq!(map.primary(8, 6), 4, "{f}");
    }
    // The execute frames equal the same views traced one by one.
    let out = trace(
        dir.path(),
        &[
            "--view",
            "seq/b.view",
            "--map-png",
            "b.map",
            "--dc-png",
            "b.img",
        ],
    );
    assert!(out.status.success());
    assert_eq!(
        std::fs::read(dir.path().join("seq/b.img")).unwrap(),
        std::fs::read(dir.path().join("b.img")).unwrap()
    );
}

#[test]
fn malformed_legacy_views_and_execute_files_fail_at_their_place() {
    let dir = trace_scratch();
    let write = |name: &str, text: &str| std::fs::write(dir.path().join(name), text).unwrap();
    write("ok.view", "0 0 0.7\n8 8\n0 0 0\n1 1\n");
    // (file, text, args, the location and words the message must hold)
    let cases: Vec<(&str, &str, Vec<&str>, &str, &str)> = vec![
        (
            "fov.view",
            "0 0 0.7\n8 8\n0 0 0\n1 180\n",
            vec!["--view", "fov.view", "-o", "out/x"],
            "fov.view:4:3",
            "strictly between 0 and 180",
        ),
        (
            "short.view",
            "0 0 0.7\n8 8\n0 0\n",
            vec!["--view", "short.view", "-o", "out/x"],
            "short.view:3",
            "value 8 of 10",
        ),
        (
            "inf.view",
            "0 inf 0.7\n8 8\n0 0 0\n1 1\n",
            vec!["--view", "inf.view", "-o", "out/x"],
            "inf.view:1:3",
            "finite",
        ),
        (
            "cut.exec",
            "ok.view scene.scn m1 i1 l1\nok.view scene.scn m2\n",
            vec!["--execute", "cut.exec"],
            "cut.exec:2",
            "the output image of frame 2",
        ),
        (
            "two.exec",
            "ok.view scene.scn m1 i1 l1\nok.view other.scn m2 i2 l2\n",
            vec!["--execute", "two.exec"],
            "two.exec:2:9",
            "one BVH",
        ),
        (
            "dup.exec",
            "ok.view scene.scn m1 i1 l1\nok.view scene.scn m2 i1 l2\n",
            vec!["--execute", "dup.exec"],
            "dup.exec:2:22",
            "frame 1 also writes",
        ),
        (
            "missing.exec",
            "nowhere.view scene.scn m1 i1 l1\n",
            vec!["--execute", "missing.exec"],
            "nowhere.view",
            "",
        ),
    ];
    for (name, text, args, location, words) in cases {
        write(name, text);
        let out = trace(dir.path(), &args);
        // miette wraps long messages behind a `│` margin: compare the words only.
        let stderr: Vec<String> = String::from_utf8_lossy(&out.stderr)
            .split_whitespace()
            .filter(|w| !matches!(*w, "│" | "·" | "×"))
            .map(str::to_owned)
            .collect();
        let stderr = stderr.join(" ");
        assert_eq!(out.status.code(), Some(1), "{name}: {stderr}");
        assert!(
            stderr.contains(location),
            "{name}: expected {location} in\n{stderr}"
        );
        assert!(
            stderr.contains(words),
            "{name}: expected `{words}` in\n{stderr}"
        );
    }
    // Nothing was written by any of them.
    for f in ["out", "m1", "i1", "l1", "m2"] {
        assert!(!dir.path().join(f).exists(), "{f} written");
    }
}
