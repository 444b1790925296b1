//! A material map through the real tools: an OBJ panel with texture coordinates, its
//! `.mtl` naming it `panel`, and a materials file whose `panel` lays a 2 × 1 grey index
//! image on it: the left texel (stored 0) names `black` (ε 1), the right (255) `grey`
//! (ε 0.5), both diffuse. `irsig-import`, `irsig-flatten` and `irsig-trace` in a vacuum with
//! no sky, seen from 100 m straight above in 8–14 µm: nothing above the panel reflects, so
//! each pixel's radiance is its emission alone, and the expected apparent temperatures come
//! from a Planck integral by Simpson's rule and a bisection (`irsig_tests::slant_plate`),
//! nothing of the code under test.
//!
//! - `Nearest`: each half is its material, whole: ε 1 at 300 K reads 300 K, ε 0.5 reads the
//!   temperature whose band radiance is half of 300 K's, and the truth's
//!   `material_primary` names the half's material, not the panel.
//! - `Bilinear`: between the texel centres (u 0.25 and 0.75) the fractions are linear in u,
//!   and the emission is the fraction-weighted mean `Σ wᵢ εᵢ B(T)`.
//! - Per-material temperatures in the raw scene (`mix_temperatures`, what `irsig-therm`
//!   writes): `black` at 290 K and `grey` at 320 K on the same facets, each half emitted at
//!   its own material's temperature.

use std::path::Path;

use crate::textured_panel::{SIDE_M, ground_points, import_and_flatten, layer, trace};
use irsig_model::MixTemperatures;
use irsig_tests::slant_plate::{apparent_k, band_radiance};

/// A centre ray this close to the panel's edge or the texels' border (m) is not checked:
/// more than half a pixel's footprint (10.5 m over 32 pixels).
const EDGE_MARGIN_M: f64 = 0.2;

const MTL: &str = "newmtl panel\nKd 1 1 1\n";

/// The ids of the two mapped materials and of the panel that hosts the map.
const BLACK_ID: f32 = 1.0;
const GREY_ID: f32 = 2.0;

/// The library: `black` and `grey` (ε constant to 60°, the view is within 3° of the
/// normal) and `panel`, whose map names them, read with `filter`.
fn materials(filter: &str) -> String {
    let plain = |id: u32, name: &str, e: f64| {
        format!(
            "(id: {id}, name: \"{name}\", emissivity: [(0.0, {e}), (60.0, {e}), (90.0, 0.0)], \
             specular_fraction: 0.0, source: \"test\")"
        )
    };
    format!(
        "(materials: [{}, {}, (id: 3, name: \"panel\", emissivity: [(0.0, 0.8)], \
         specular_fraction: 0.0, source: \"test\", maps: Some((material: Some((image: \
         \"halves.png\", form: Index(table: [(grey: 0, material: \"black\"), (grey: 255, \
         material: \"grey\")]), filter: {filter})))))])",
        plain(1, "black", 1.0),
        plain(2, "grey", 0.5)
    )
}

/// Writes the asset and the map, imports and flattens it; `temperatures` (black's, grey's),
/// when given, go into the raw scene as every panel facet's per-material temperatures. Then
/// traces it in 8–14 µm: the truth EXR.
fn traced(dir: &Path, filter: &str, temperatures: Option<[f64; 2]>) -> irsig_raster::Raster {
    image::GrayImage::from_raw(2, 1, vec![0, 255])
        .unwrap()
        .save(dir.join("halves.png"))
        .unwrap();
    import_and_flatten(dir, MTL, &materials(filter));
    if let Some(t) = temperatures {
        let raw = dir.join("scene.raw");
        let bytes = std::fs::read(&raw).unwrap();
        let mut scene = irsig_formats::canonical::read_raw_scene("scene.raw", &bytes).unwrap();
        assert_eq!(scene.facets.len(), 2, "the panel's two triangles");
        scene.mix_temperatures = (0..2)
            .map(|facet| MixTemperatures {
                facet,
                temperatures_k: t.to_vec(),
            })
            .collect();
        std::fs::write(&raw, ron::to_string(&scene).unwrap()).unwrap();
    }
    trace(dir, &["--band", "8-14"])
}

/// Each pixel whose centre ray meets the panel more than the margin inside it: its index
/// in the frame and the texture coordinate u there (x / side).
fn panel_pixels() -> Vec<(usize, f64)> {
    let inside = |c: f64| c > EDGE_MARGIN_M && c < SIDE_M - EDGE_MARGIN_M;
    ground_points()
        .into_iter()
        .filter(|&(_, x, y)| inside(x) && inside(y))
        .map(|(k, x, _)| (k, x / SIDE_M))
        .collect()
}

/// The apparent temperature, K, of a grey surface of emissivity `e` at `t_k`, alone.
fn grey_k(e: f64, t_k: f64) -> f64 {
    apparent_k(e * band_radiance(t_k))
}

/// Checks the two halves under `Nearest`: each half's material id and apparent temperature
/// (`black`'s and `grey`'s expected, K); how many pixels each half had.
fn check_halves(truth: &irsig_raster::Raster, black_k: f64, grey_k: f64) -> [usize; 2] {
    let apparent = layer(truth, "apparent_temperature");
    let material = layer(truth, "material_primary");
    let mut seen = [0; 2];
    let border = EDGE_MARGIN_M / SIDE_M;
    for (k, u) in panel_pixels() {
        if (u - 0.5).abs() < border {
            continue;
        }
        let (half, id, expected) = if u < 0.5 {
            (0, BLACK_ID, black_k)
        } else {
            (1, GREY_ID, grey_k)
        };
        let at = format!("pixel {k} at u {u:.3}");
        assert!((material[k] - id).abs() < 0.5, "{at}: id {}", material[k]);
        // The inverse table's accuracy, 0.01 K, and the bisection's.
        assert!(
            (f64::from(apparent[k]) - expected).abs() < 0.02,
            "{at}: {} K against {expected:.3} K",
            apparent[k]
        );
        seen[half] += 1;
    }
    seen
}

#[test]
fn each_half_of_an_index_map_is_its_own_material() {
    let dir = tempfile::tempdir().unwrap();
    let truth = traced(dir.path(), "Nearest", None);
    let expected_grey = grey_k(0.5, 300.0);
    // Half the radiance of 300 K in 8–14 µm is about 40 K colder: the check can tell the
    // halves.
    assert!(300.0 - expected_grey > 30.0, "{expected_grey}");
    let seen = check_halves(&truth, 300.0, expected_grey);
    // About 22 × 11 pixels a half.
    assert!(seen.iter().all(|&n| n > 150), "{seen:?}");
}

#[test]
fn a_bilinear_index_map_mixes_the_emission_by_area_fraction() {
    let dir = tempfile::tempdir().unwrap();
    let truth = traced(dir.path(), "Bilinear", None);
    let apparent = layer(&truth, "apparent_temperature");
    let mut checked = 0;
    for (k, u) in panel_pixels() {
        // Between the texel centres, away from the wrap at the image's edges.
        if !(0.3..=0.7).contains(&u) {
            continue;
        }
        let grey_share = (u - 0.25) / 0.5;
        let e = (1.0 - grey_share) + grey_share * 0.5;
        let expected = grey_k(e, 300.0);
        assert!(
            (f64::from(apparent[k]) - expected).abs() < 0.02,
            "pixel {k} at u {u:.3}: {} K against {expected:.3} K (ε {e:.4})",
            apparent[k]
        );
        checked += 1;
    }
    assert!(checked > 100, "{checked}");
}

#[test]
fn per_material_temperatures_emit_each_material_at_its_own() {
    let dir = tempfile::tempdir().unwrap();
    let truth = traced(dir.path(), "Nearest", Some([290.0, 320.0]));
    // Were the facet's 300 K emitted, the black half would read 300 K and the grey
    // 0.5·B(300): both far from these.
    let expected_grey = grey_k(0.5, 320.0);
    assert!((expected_grey - grey_k(0.5, 300.0)).abs() > 10.0);
    let seen = check_halves(&truth, 290.0, expected_grey);
    assert!(seen.iter().all(|&n| n > 150), "{seen:?}");
}
