//! Image maps in the rendered image: a checkerboard temperature map (8 × 8 texels of +0 and
//! +10 K, nearest filter) on a tilted quad seen by a known camera renders, at every pixel
//! whose centre ray meets the quad well inside a texel, the texel hand geometry predicts
//! (the ray intersected with the quad's plane, its texture coordinates computed from the
//! quad's corners); a map combines with a statistical texture (offsets add); the refusals:
//! a facet of a mapped material without texture coordinates, named with its object, and an
//! emissivity scale that would take ε above 1.

use irsig_model::image_map::{ImageMap, ImageMaps, MapFilter};
use irsig_model::{MaterialId, MaterialLibrary, RawScene, View};
use irsig_radiometry::{BandModel, TotalRadiance};
use irsig_texture::{GreyImage, MaterialMaps};
use irsig_tracer::testing::{grey_materials, raw_scene};
use irsig_tracer::{Camera, TraceErrorKind, TraceOptions, Tracer, Vacuum};

/// The quad's half-width, m, and its slope: the plane z = y·tan 25°, turned about x.
const HALF_M: f64 = 5.0;
const TILT_DEG: f64 = 25.0;
/// Texels along each side of the checkerboard.
const TEXELS: usize = 8;
/// The sensor's position and view.
const SENSOR_M: [f64; 3] = [1.0, -2.0, 60.0];
const PIXELS: u32 = 96;
const FOV_DEG: f64 = 12.0;
/// How far, in texels, a hit's texture coordinates must be from a texel edge to be
/// checked: the hit point is found in f32 and refined in f64, to well under 10⁻⁶ m, and a
/// texel is 1.25 m across, so a hundredth of a texel is a wide margin.
const EDGE_MARGIN_TEXELS: f64 = 0.01;

fn slope() -> f64 {
    TILT_DEG.to_radians().tan()
}

/// The quad (-5, -5) to (5, 5) in x and y on the plane z = y·tan 25°, two triangles, with
/// texture coordinates u = (x + 5)/10, v = (y + 5)/10 at its corners, material 1 at 300 K.
fn tilted_quad(with_uv: bool) -> RawScene {
    let corners = [
        [-HALF_M, -HALF_M],
        [HALF_M, -HALF_M],
        [HALF_M, HALF_M],
        [-HALF_M, HALF_M],
    ];
    let positions: Vec<[f64; 3]> = corners.iter().map(|&[x, y]| [x, y, y * slope()]).collect();
    let mesh = (positions, vec![[0, 1, 2], [0, 2, 3]]);
    let mut scene = raw_scene(&[(&mesh, 1, 300.0)]);
    if with_uv {
        let uv = |k: usize| {
            let [x, y] = corners[k];
            [(x + HALF_M) / (2.0 * HALF_M), (y + HALF_M) / (2.0 * HALF_M)]
        };
        for f in &mut scene.facets {
            f.uv = Some(f.vertices.map(|v| uv(v as usize)));
        }
    }
    scene
}

/// The checkerboard, row 0 at the top as images are stored: texel (i, j) (column i from
/// the left, row j from the bottom) is white where i + j is odd.
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

fn temperature_map(per_grey_k: f64, filter: MapFilter) -> ImageMaps {
    ImageMaps {
        temperature_offset_k: Some(ImageMap {
            image: "checker.png".into(),
            at_black: 0.0,
            per_grey: per_grey_k,
            filter,
        }),
        emissivity_scale: None,
        material: None,
    }
}

fn library(maps: &ImageMaps, emissivity: f64) -> MaterialLibrary {
    let mut lib = grey_materials(&[(1, emissivity, 0.0)]);
    lib.materials[0].maps = Some(maps.clone());
    lib
}

fn loaded(maps: &ImageMaps) -> Vec<(MaterialId, MaterialMaps)> {
    vec![(
        MaterialId(1),
        MaterialMaps::new(maps, |_, _| Ok(checkerboard())).unwrap(),
    )]
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

fn tracer(
    scene: &RawScene,
    lib: &MaterialLibrary,
    maps: Vec<(MaterialId, MaterialMaps)>,
) -> Result<Tracer<TotalRadiance, Vacuum>, irsig_tracer::TraceError> {
    let one = irsig_tracer::SubBand {
        band: TotalRadiance,
        atmosphere: Vacuum::default(),
        emissivity: None,
    };
    Tracer::with_sub_bands_and_maps(scene, lib, TotalRadiance, vec![one], maps)
}

/// Each pixel's apparent temperature, K.
fn temperatures(t: &Tracer<TotalRadiance, Vacuum>) -> Vec<f64> {
    t.render(&camera(), &TraceOptions::default(), &|_| {})
        .unwrap()
        .radiance_w_m2_sr
        .iter()
        .map(|&l| TotalRadiance.temperature(l))
        .collect()
}

/// Where the centre ray of pixel `(column, row)` meets the quad's plane, by hand: from
/// `O + s·d` on z = y·tan θ, `s = (tan θ·O_y − O_z)/(d_z − tan θ·d_y)`; the point's
/// texture coordinates, `((x + 5)/10, (y + 5)/10)`, in texels; `None` off the quad.
fn texel_coordinates(camera: &Camera, column: u32, row: u32) -> Option<[f64; 2]> {
    let d = camera.pixel_direction(column, row);
    let o = SENSOR_M;
    let s = (slope() * o[1] - o[2]) / (d[2] - slope() * d[1]);
    let (x, y) = (o[0] + s * d[0], o[1] + s * d[1]);
    if s <= 0.0 || x.abs() >= HALF_M || y.abs() >= HALF_M {
        return None;
    }
    let per_m = TEXELS as f64 / (2.0 * HALF_M);
    Some([(x + HALF_M) * per_m, (y + HALF_M) * per_m])
}

#[test]
fn every_pixel_well_inside_a_texel_renders_the_texel_hand_geometry_predicts() {
    let maps = temperature_map(10.0, MapFilter::Nearest);
    let t = tracer(&tilted_quad(true), &library(&maps, 1.0), loaded(&maps)).unwrap();
    let image = temperatures(&t);
    let cam = camera();
    let (mut checked, mut hot, mut excluded) = (0, 0, 0);
    for row in 0..PIXELS {
        for column in 0..PIXELS {
            let Some([x, y]) = texel_coordinates(&cam, column, row) else {
                continue;
            };
            let near_edge = |c: f64| (c - c.round()).abs() < EDGE_MARGIN_TEXELS;
            if near_edge(x) || near_edge(y) {
                excluded += 1;
                continue;
            }
            let (i, j) = (x.floor() as usize, y.floor() as usize);
            // ε = 1 in a vacuum: the apparent temperature is the kinetic one, 300 K plus
            // the texel's 0 or 10 K.
            let expected = if (i + j) % 2 == 1 { 310.0 } else { 300.0 };
            let got = image[(row * PIXELS + column) as usize];
            assert!(
                (got - expected).abs() < 1e-6,
                "pixel ({column}, {row}) at texel ({i}, {j}): {got} K, expected {expected} K"
            );
            checked += 1;
            hot += usize::from(expected > 305.0);
        }
    }
    // The quad fills most of the view: thousands of pixels checked, both colours seen.
    assert!(
        checked > 3000,
        "{checked} pixels checked, {excluded} on edges"
    );
    assert!(
        hot > checked / 4 && hot < 3 * checked / 4,
        "{hot} of {checked}"
    );
}

#[test]
fn a_map_and_a_statistical_texture_add_their_offsets() {
    use irsig_model::texture::{
        CorrelationLength, FieldFilter, FieldSpectrum, RandomField, StatisticalTexture,
    };
    let maps = temperature_map(10.0, MapFilter::Nearest);
    let texture = StatisticalTexture {
        seed: 3,
        temperature_offset_k: Some(RandomField {
            sigma: 0.5,
            spectrum: FieldSpectrum::Gaussian {
                correlation_length_m: CorrelationLength::Isotropic(2.0),
            },
        }),
        emissivity_scale: None,
        filter: FieldFilter::Point,
    };
    let fields = irsig_texture::TextureFields::new(&texture).unwrap();
    let mut lib = library(&maps, 1.0);
    lib.materials[0].texture = Some(texture);
    let t = tracer(&tilted_quad(true), &lib, loaded(&maps)).unwrap();
    let image = temperatures(&t);
    let cam = camera();
    let mut checked = 0;
    let pixels = (0..PIXELS)
        .step_by(7)
        .flat_map(|r| (0..PIXELS).step_by(5).map(move |c| (r, c)));
    for (row, column) in pixels {
        let Some([x, y]) = texel_coordinates(&cam, column, row) else {
            continue;
        };
        let near_edge = |c: f64| (c - c.round()).abs() < EDGE_MARGIN_TEXELS;
        if near_edge(x) || near_edge(y) {
            continue;
        }
        let (i, j) = (x.floor() as usize, y.floor() as usize);
        let map_k = if (i + j) % 2 == 1 { 10.0 } else { 0.0 };
        // The world point, from the texel coordinates back through u = (x + 5)/10.
        let per_m = TEXELS as f64 / (2.0 * HALF_M);
        let (px, py) = (x / per_m - HALF_M, y / per_m - HALF_M);
        let field_k = fields.sample([px, py, py * slope()]).temperature_offset_k;
        let got = image[(row * PIXELS + column) as usize];
        assert!(
            (got - (300.0 + map_k + field_k)).abs() < 1e-6,
            "{got} {map_k} {field_k}"
        );
        checked += 1;
    }
    assert!(checked > 100, "{checked}");
}

#[test]
fn a_mapped_material_on_a_facet_without_texture_coordinates_is_refused_naming_its_object() {
    let maps = temperature_map(10.0, MapFilter::Bilinear);
    let e = tracer(&tilted_quad(false), &library(&maps, 1.0), loaded(&maps)).unwrap_err();
    match &e.kind {
        TraceErrorKind::NoTextureCoordinates {
            facet,
            object,
            material,
        } => assert_eq!((*facet, object.as_str(), *material), (0, "part0", 1)),
        other => panic!("{other}"),
    }
    assert!(e.to_string().contains("object `part0`"), "{e}");
    // Without maps the same scene traces.
    assert!(
        tracer(
            &tilted_quad(false),
            &grey_materials(&[(1, 1.0, 0.0)]),
            Vec::new()
        )
        .is_ok()
    );
}

#[test]
fn an_emissivity_scale_that_takes_epsilon_above_1_is_refused_not_clamped() {
    let scale = |at_black, per_grey| ImageMaps {
        temperature_offset_k: None,
        emissivity_scale: Some(ImageMap {
            image: "checker.png".into(),
            at_black,
            per_grey,
            filter: MapFilter::Nearest,
        }),
        material: None,
    };
    // ε = 0.8: a scale up to 1.2 keeps ε at 0.96 and is allowed; up to 1.3 (ε 1.04) is not.
    let ok = scale(1.0, 0.2);
    assert!(tracer(&tilted_quad(true), &library(&ok, 0.8), loaded(&ok)).is_ok());
    let too_much = scale(1.0, 0.3);
    let e = tracer(
        &tilted_quad(true),
        &library(&too_much, 0.8),
        loaded(&too_much),
    )
    .unwrap_err();
    assert!(
        matches!(
            e.kind,
            TraceErrorKind::EmissivityScaleOutOfRange {
                material: 1,
                sub_band: 1,
                ..
            }
        ),
        "{e}"
    );
    // The image's own greys count, not the mapping's at white: an all-black image under
    // the same mapping scales by 1 everywhere and is allowed.
    let black = MaterialMaps::new(&too_much, |_, _| GreyImage::new(2, 2, vec![0.0; 4])).unwrap();
    assert!(
        tracer(
            &tilted_quad(true),
            &library(&too_much, 0.8),
            vec![(MaterialId(1), black)]
        )
        .is_ok()
    );
}
