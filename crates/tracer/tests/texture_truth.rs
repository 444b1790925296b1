//! The texture's truth layers: a checkerboard temperature map (8 × 8 texels of +0 and
//! +10 K, nearest filter) and a constant emissivity map (grey 0.5 mapped to 0.6 + 0.4·g =
//! 0.8) on a tilted quad seen by a known camera. At every pixel whose centre ray meets the
//! quad well inside a texel, `texture_temperature_offset` holds the texel hand geometry
//! predicts (the ray intersected with the quad's plane), `texture_emissivity_scale` holds
//! 0.8, and the kinetic temperature and ε layers hold the textured values; off the quad
//! (the terrain beyond) both are NaN. The layers are the centre ray's under supersampling, adaptive
//! supersampling, refinement and tiles alike, and an untextured scene keeps none.

// The layers hold f64 values rounded to f32 once: compared exactly with the same rounding.
#![allow(clippy::float_cmp)]

use irsig_model::image_map::{ImageMap, ImageMaps, MapFilter};
use irsig_model::truth::Layer;
use irsig_model::{MaterialId, MaterialLibrary, RawScene, View};
use irsig_radiometry::TotalRadiance;
use irsig_texture::{GreyImage, MaterialMaps};
use irsig_tracer::testing::{grey_materials, raw_scene};
use irsig_tracer::{Camera, Frame, Refinement, Tile, TraceOptions, Tracer, Vacuum};

/// The quad's half-width, m, and its slope: the plane z = y·tan 25°, turned about x.
const HALF_M: f64 = 5.0;
const TILT_DEG: f64 = 25.0;
/// Texels along each side of the checkerboard.
const TEXELS: usize = 8;
const SENSOR_M: [f64; 3] = [1.0, -2.0, 60.0];
/// Wider than the quad (it spans about ±5.3° from the sensor): the border sees the
/// terrain beyond it.
const PIXELS: u32 = 64;
const FOV_DEG: f64 = 14.0;
/// A hit's texture coordinates must lie this far (texels) from a texel's edge to be
/// checked: the hit is found to well under 10⁻⁶ m, a texel is 1.25 m.
const EDGE_MARGIN_TEXELS: f64 = 0.01;
/// The material's ε, and the emissivity map's scale: 0.6 + 0.4 × grey 0.5.
const EMISSIVITY: f64 = 0.9;
const SCALE: f64 = 0.8;

fn slope() -> f64 {
    TILT_DEG.to_radians().tan()
}

/// The quad (-5, -5) to (5, 5) in x and y on z = y·tan 25°, texture coordinates
/// u = (x + 5)/10, v = (y + 5)/10 at its corners, material 1 at 300 K.
fn tilted_quad() -> RawScene {
    let corners = [
        [-HALF_M, -HALF_M],
        [HALF_M, -HALF_M],
        [HALF_M, HALF_M],
        [-HALF_M, HALF_M],
    ];
    let positions: Vec<[f64; 3]> = corners.iter().map(|&[x, y]| [x, y, y * slope()]).collect();
    let mesh = (positions, vec![[0, 1, 2], [0, 2, 3]]);
    let mut scene = raw_scene(&[(&mesh, 1, 300.0)]);
    let uv = |k: usize| {
        let [x, y] = corners[k];
        [(x + HALF_M) / (2.0 * HALF_M), (y + HALF_M) / (2.0 * HALF_M)]
    };
    for f in &mut scene.facets {
        f.uv = Some(f.vertices.map(|v| uv(v as usize)));
    }
    scene
}

/// Texel (i, j) (column i from the left, row j from the bottom) is white where i + j is
/// odd; row 0 at the top as images are stored.
fn checkerboard() -> GreyImage {
    let grey = (0..TEXELS * TEXELS)
        .map(|k| {
            let (row, i) = (k / TEXELS, k % TEXELS);
            let j = TEXELS - 1 - row;
            if (i + j) % 2 == 1 { 1.0 } else { 0.0 }
        })
        .collect();
    GreyImage::new(TEXELS, TEXELS, grey).unwrap()
}

fn maps() -> ImageMaps {
    let map = |image: &str, at_black, per_grey| ImageMap {
        image: image.into(),
        at_black,
        per_grey,
        filter: MapFilter::Nearest,
    };
    ImageMaps {
        temperature_offset_k: Some(map("checker.png", 0.0, 10.0)),
        emissivity_scale: Some(map("half.png", 0.6, 0.4)),
        material: None,
    }
}

fn textured() -> Tracer<TotalRadiance, Vacuum> {
    let maps = maps();
    let mut lib = grey_materials(&[(1, EMISSIVITY, 0.0)]);
    lib.materials[0].maps = Some(maps.clone());
    let loaded = MaterialMaps::new(&maps, |name, _| match name {
        "temperature_offset_k" => Ok(checkerboard()),
        _ => GreyImage::new(1, 1, vec![0.5]),
    })
    .unwrap();
    tracer(&lib, vec![(MaterialId(1), loaded)])
}

fn tracer(
    lib: &MaterialLibrary,
    maps: Vec<(MaterialId, MaterialMaps)>,
) -> Tracer<TotalRadiance, Vacuum> {
    let one = irsig_tracer::SubBand {
        band: TotalRadiance,
        atmosphere: Vacuum::default(),
        emissivity: None,
    };
    Tracer::with_sub_bands_and_maps(&tilted_quad(), lib, TotalRadiance, vec![one], maps).unwrap()
}

fn camera() -> Camera {
    Camera::from_view(&View::Legacy {
        position_m: SENSOR_M,
        pixels: [PIXELS, PIXELS],
        omega_phi_kappa_deg: [0.0, 0.0, 0.0],
        fov_deg: [FOV_DEG, FOV_DEG],
        gain_dc_per_k: None,
    })
    .unwrap()
}

/// Where the centre ray of pixel `(column, row)` meets the quad's plane, by hand: from
/// `O + s·d` on z = y·tan θ, `s = (tan θ·O_y − O_z)/(d_z − tan θ·d_y)`; its `(x, y)`, m.
fn plane_point(camera: &Camera, column: u32, row: u32) -> [f64; 2] {
    let d = camera.pixel_direction(column, row);
    let o = SENSOR_M;
    let s = (slope() * o[1] - o[2]) / (d[2] - slope() * d[1]);
    [o[0] + s * d[0], o[1] + s * d[1]]
}

/// The texture coordinates, in texels, of where the centre ray of pixel `(column, row)`
/// meets the quad; `None` off the quad.
fn texel_coordinates(camera: &Camera, column: u32, row: u32) -> Option<[f64; 2]> {
    let [x, y] = plane_point(camera, column, row);
    if x.abs() >= HALF_M || y.abs() >= HALF_M {
        return None;
    }
    let per_m = TEXELS as f64 / (2.0 * HALF_M);
    Some([(x + HALF_M) * per_m, (y + HALF_M) * per_m])
}

fn layer(frame: &Frame, layer: Layer) -> Vec<f32> {
    frame
        .truth_layer(layer)
        .unwrap_or_else(|| panic!("no `{layer}` layer"))
}

#[test]
fn each_pixel_holds_the_offset_and_scale_of_the_texel_hand_geometry_predicts() {
    let frame = textured()
        .render(&camera(), &TraceOptions::default(), &|_| {})
        .unwrap();
    let offset = layer(&frame, Layer::TextureTemperatureOffset);
    let scale = layer(&frame, Layer::TextureEmissivityScale);
    let kinetic = layer(&frame, Layer::KineticTemperature);
    let emissivity = layer(&frame, Layer::Emissivity);
    let cam = camera();
    let (mut checked, mut hot, mut off) = (0, 0, 0);
    for row in 0..PIXELS {
        for column in 0..PIXELS {
            let p = (row * PIXELS + column) as usize;
            let Some([x, y]) = texel_coordinates(&cam, column, row) else {
                // Clearly off the quad (the ray meets the terrain beyond): no facet hit,
                // nothing to record.
                let [x, y] = plane_point(&cam, column, row);
                if x.abs().max(y.abs()) > HALF_M + 1e-3 {
                    assert!(offset[p].is_nan() && scale[p].is_nan(), "({column}, {row})");
                    off += 1;
                }
                continue;
            };
            let near_edge = |c: f64| (c - c.round()).abs() < EDGE_MARGIN_TEXELS;
            if near_edge(x) || near_edge(y) {
                continue;
            }
            let (i, j) = (x.floor() as usize, y.floor() as usize);
            let expected_k = if (i + j) % 2 == 1 { 10.0 } else { 0.0 };
            assert_eq!(
                offset[p], expected_k as f32,
                "({column}, {row}) at texel ({i}, {j})"
            );
            // 0.6 + 0.4·0.5 = 0.8 in f64, rounded to f32 once.
            assert_eq!(scale[p], SCALE as f32, "({column}, {row})");
            assert_eq!(kinetic[p], (300.0 + expected_k) as f32);
            assert!((f64::from(emissivity[p]) - EMISSIVITY * SCALE).abs() < 1e-6);
            checked += 1;
            hot += usize::from(expected_k > 0.0);
        }
    }
    assert!(checked > 1500, "{checked} pixels checked");
    assert!(
        hot > checked / 4 && hot < 3 * checked / 4,
        "{hot} of {checked}"
    );
    assert!(off > 100, "{off} pixels off the quad");
}

#[test]
fn an_untextured_scene_keeps_no_texture_layers_and_untextured_facets_hold_none() {
    let plain = tracer(&grey_materials(&[(1, EMISSIVITY, 0.0)]), Vec::new());
    assert!(!plain.is_textured());
    let frame = plain
        .render(&camera(), &TraceOptions::default(), &|_| {})
        .unwrap();
    assert!(frame.texture.is_empty());
    assert_eq!(frame.truth_layer(Layer::TextureTemperatureOffset), None);
    assert_eq!(frame.truth_layer(Layer::TextureEmissivityScale), None);
    // Textured, without the truth: no layers either.
    let t = textured();
    assert!(t.is_textured());
    let bare = TraceOptions {
        truth: false,
        ..TraceOptions::default()
    };
    let frame = t.render(&camera(), &bare, &|_| {}).unwrap();
    assert!(frame.texture.is_empty() && frame.truth.is_empty());
}

#[test]
fn a_facet_whose_material_has_no_texture_holds_offset_0_and_scale_1() {
    // Two materials in the library, the mapped one on no facet: the scene is textured,
    // every facet hit is not.
    let maps = maps();
    let mut lib = grey_materials(&[(1, EMISSIVITY, 0.0), (2, 0.5, 0.0)]);
    lib.materials[1].maps = Some(maps.clone());
    let loaded = MaterialMaps::new(&maps, |_, _| GreyImage::new(1, 1, vec![0.5])).unwrap();
    let t = tracer(&lib, vec![(MaterialId(2), loaded)]);
    assert!(t.is_textured());
    let frame = t
        .render(&camera(), &TraceOptions::default(), &|_| {})
        .unwrap();
    let centre = (PIXELS / 2 * PIXELS + PIXELS / 2) as usize;
    assert_eq!(layer(&frame, Layer::TextureTemperatureOffset)[centre], 0.0);
    assert_eq!(layer(&frame, Layer::TextureEmissivityScale)[centre], 1.0);
    assert!(layer(&frame, Layer::TextureTemperatureOffset)[0].is_nan());
}

/// The texture layers of `frame` as bit patterns (NaN compares equal to itself).
fn bits(frame: &Frame) -> Vec<[u32; 2]> {
    frame
        .texture
        .iter()
        .map(|t| {
            [
                t.temperature_offset_k.to_bits(),
                t.emissivity_scale.to_bits(),
            ]
        })
        .collect()
}

#[test]
fn the_layers_are_the_centre_rays_however_the_pixel_is_sampled_or_tiled() {
    let t = textured();
    let cam = camera();
    let centre = t.render(&cam, &TraceOptions::default(), &|_| {}).unwrap();
    let expected = bits(&centre);
    assert_eq!(expected.len(), (PIXELS * PIXELS) as usize);
    // 3 × 3 rays a pixel, everywhere or at edges only: the radiance changes at the
    // checkerboard's edges, the truth does not.
    for adaptive_threshold_k in [None, Some(1.0)] {
        let options = TraceOptions {
            supersampling: 3,
            adaptive_threshold_k,
            ..TraceOptions::default()
        };
        let frame = t.render(&cam, &options, &|_| {}).unwrap();
        assert_eq!(bits(&frame), expected, "{adaptive_threshold_k:?}");
        assert_ne!(frame.radiance_w_m2_sr, centre.radiance_w_m2_sr);
    }
    // Refined to a tolerance.
    let refined = textured()
        .with_refinement(Some(Refinement {
            target_k: 0.5,
            edge_k: 1.0,
            max_side: 4,
            thin_side: 2,
        }))
        .unwrap()
        .render(&cam, &TraceOptions::default(), &|_| {})
        .unwrap();
    assert_eq!(bits(&refined), expected);
    // A tile is the whole frame's rectangle, with and without adaptive supersampling's
    // margin.
    let tile = Tile {
        x: 10,
        y: 20,
        width: 17,
        height: 9,
    };
    let cropped: Vec<[u32; 2]> = (tile.y..tile.y + tile.height)
        .flat_map(|r| {
            let start = (r * PIXELS + tile.x) as usize;
            expected[start..start + tile.width as usize].to_vec()
        })
        .collect();
    for adaptive_threshold_k in [None, Some(1.0)] {
        let options = TraceOptions {
            supersampling: 2,
            adaptive_threshold_k,
            ..TraceOptions::default()
        };
        let frame = t.render_tile(&cam, &options, tile, &|_| {}).unwrap();
        assert_eq!(bits(&frame), cropped, "{adaptive_threshold_k:?}");
    }
}
