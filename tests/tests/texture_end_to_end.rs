//! A textured asset through the real tools: an OBJ panel with texture coordinates (`vt`),
//! its `.mtl` naming a PNG (`map_Kd`), all written here (and the same panel as a GLB that
//! carries the PNG inside it, written out by `irsig-import --images`); `irsig-import`, `irsig-flatten`,
//! and `irsig-trace` with a materials file whose temperature map names that PNG. The panel
//! is 8 m square on the ground, one repetition of a 2 × 2 grey image across it; seen from
//! 100 m straight above, each pixel whose centre ray meets the panel well inside a
//! quarter renders, by hand geometry, the quarter's offset: 300 K plus 10 K × the grey
//! (white 10 K bottom-left, 51/255 = 0.2 → 2 K top-right, black 0 K elsewhere); the truth
//! EXR's `texture_temperature_offset` holds it, its `texture_emissivity_scale` 1 (no
//! emissivity map); the terrain around holds NaN in both. The same scene with the map
//! taken out of the materials writes no texture layers at all; traced in four tiles and
//! merged by `irsig-merge`, its truth EXR is the whole frame's, byte for byte.

// A scale of exactly 1 (no emissivity map) is stored exactly.
#![allow(clippy::float_cmp)]

use std::path::Path;

use crate::textured_panel::{
    SIDE_M, ground_points, import_and_flatten, import_and_flatten_glb, layer, trace,
};
use irsig_tests::bin;

/// A centre ray this close to a quarter's or the panel's edge (m) is not checked.
const EDGE_MARGIN_M: f64 = 0.05;

const MTL: &str = "newmtl panel\nKd 1 1 1\nmap_Kd quarters.png\n";

/// The materials: ε = 1 up to 60° (the view is within 3° of the normal), the temperature
/// map naming the PNG (`maps`), or none.
fn materials(maps: bool) -> String {
    let map = if maps {
        "maps: Some((temperature_offset_k: Some((image: \"quarters.png\", at_black: 0.0, \
         per_grey: 10.0, filter: Nearest)))),"
    } else {
        ""
    };
    format!(
        "(materials: [(id: 1, name: \"panel\", emissivity: [(0.0, 1.0), (60.0, 1.0), \
         (90.0, 0.0)], specular_fraction: 0.0, source: \"test\", {map})])"
    )
}

/// Writes the asset (OBJ, MTL, PNG), imports, flattens and traces it with or without the
/// map; the truth EXR.
fn traced(dir: &Path, maps: bool) -> irsig_raster::Raster {
    std::fs::write(dir.join("quarters.png"), quarters_png()).unwrap();
    import_and_flatten(dir, MTL, &materials(maps));
    trace(dir, &[])
}

#[test]
fn a_textured_obj_renders_its_image_where_the_asset_puts_it() {
    let dir = tempfile::tempdir().unwrap();
    assert_quarters(&traced(dir.path(), true));
}

#[test]
fn a_glb_with_its_image_inside_renders_it_where_the_asset_puts_it() {
    // The same panel as a GLB whose base colour image is a buffer view of its own binary
    // chunk: `irsig-import --images` writes it out, and the map names the file written.
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let map = "maps: Some((temperature_offset_k: Some((image: \"images/image-0-quarters.png\", \
               at_black: 0.0, per_grey: 10.0, filter: Nearest)))),";
    let materials = format!(
        "(materials: [(id: 1, name: \"panel\", emissivity: [(0.0, 1.0), (60.0, 1.0), \
         (90.0, 0.0)], specular_fraction: 0.0, source: \"test\", {map})])"
    );
    import_and_flatten_glb(d, &quarters_png(), &materials);
    assert_quarters(&trace(d, &[]));
}

/// The 2 × 2 grey image, row 0 at the top: top-left black, top-right 51, bottom-left
/// white, bottom-right black; as PNG bytes.
fn quarters_png() -> Vec<u8> {
    let mut png = Vec::new();
    image::GrayImage::from_raw(2, 2, vec![0, 51, 255, 0])
        .unwrap()
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .unwrap();
    png
}

/// Each pixel whose centre ray meets the panel well inside a quarter shows the quarter's
/// offset in the truth EXR, and its temperature; the terrain around, no texture.
fn assert_quarters(truth: &irsig_raster::Raster) {
    let offset = layer(truth, "texture_temperature_offset");
    let scale = layer(truth, "texture_emissivity_scale");
    let kinetic = layer(truth, "kinetic_temperature");
    let apparent = layer(truth, "apparent_temperature");
    let mut seen = [0usize; 4];
    let mut terrain = 0;
    for (k, x, y) in ground_points() {
        let inside = |c: f64| c > EDGE_MARGIN_M && c < SIDE_M - EDGE_MARGIN_M;
        let outside = |c: f64| !(-EDGE_MARGIN_M..=SIDE_M + EDGE_MARGIN_M).contains(&c);
        if outside(x) || outside(y) {
            assert!(offset[k].is_nan() && scale[k].is_nan(), "pixel {k}");
            terrain += 1;
            continue;
        }
        let half = SIDE_M / 2.0;
        if !(inside(x) && inside(y))
            || (x - half).abs() < EDGE_MARGIN_M
            || (y - half).abs() < EDGE_MARGIN_M
        {
            continue;
        }
        // u = x/8, v = y/8: the quarter (i, j) from the bottom-left.
        let (i, j) = (usize::from(x >= half), usize::from(y >= half));
        let expected_k = match (i, j) {
            (0, 0) => 10.0,
            (1, 1) => 10.0 * 51.0 / 255.0,
            _ => 0.0,
        };
        let at = format!("pixel {k}, quarter ({i}, {j})");
        assert!(
            (f64::from(offset[k]) - expected_k).abs() < 1e-5,
            "{at}: {}",
            offset[k]
        );
        assert_eq!(scale[k], 1.0, "{at}");
        assert!(
            (f64::from(kinetic[k]) - (300.0 + expected_k)).abs() < 1e-4,
            "{at}"
        );
        // ε = 1 in a vacuum: the apparent temperature is the kinetic one, to the
        // inverse table's accuracy.
        assert!(
            (f64::from(apparent[k]) - (300.0 + expected_k)).abs() < 0.01,
            "{at}"
        );
        seen[2 * j + i] += 1;
    }
    // 8 m of the 10.5 m field: about 24 × 24 pixels on the panel, a quarter each.
    assert!(seen.iter().all(|&n| n > 80), "{seen:?}");
    assert!(terrain > 100, "{terrain}");
}

#[test]
fn the_same_scene_without_the_map_writes_no_texture_layers() {
    let dir = tempfile::tempdir().unwrap();
    let truth = traced(dir.path(), false);
    assert!(truth.layer("kinetic_temperature").is_some());
    assert!(truth.layer("texture_temperature_offset").is_none());
    assert!(truth.layer("texture_emissivity_scale").is_none());
}

#[test]
fn a_textured_frame_traced_in_tiles_merges_into_the_whole_frames_truth() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    traced(d, true);
    let tiles = d.join("tiles");
    std::fs::create_dir(&tiles).unwrap();
    let mut files = Vec::new();
    for i in 1..=4 {
        let prefix = tiles.join(format!("t{i}"));
        bin("irsig-trace")
            .arg("--scene")
            .arg(d.join("scene.raw"))
            .arg("--materials")
            .arg(d.join("materials.ron"))
            .arg("--view")
            .arg(d.join("view.ron"))
            .args(["--atmosphere", "none", "--tile", &format!("{i}/2x2"), "-o"])
            .arg(&prefix)
            .assert()
            .success();
        for kind in ["radiance", "truth"] {
            files.push(tiles.join(format!("t{i}.{kind}.exr")));
        }
    }
    // The merge knows a tile's texture layers as a truth tile's, and the merged truth is
    // the whole frame's, byte for byte.
    bin("irsig-merge")
        .args(&files)
        .arg("--truth-exr")
        .arg(d.join("merged.truth.exr"))
        .assert()
        .success();
    let read = |name: &str| std::fs::read(d.join(name)).unwrap();
    assert!(read("merged.truth.exr") == read("out.truth.exr"));
}
