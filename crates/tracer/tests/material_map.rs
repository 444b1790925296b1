//! Material maps in the rendered image, on a tilted quad seen by a known camera, checked
//! against hand geometry (the ray intersected with the quad's plane, its texture
//! coordinates from the quad's corners) and the radiance equation by hand: in a vacuum
//! under a uniform sky `L_s`, a facet of emissivity ε at T leaves `ε σT⁴/π + (1 − ε) L_s`
//! whatever its specular share (mirror and hemisphere see the same sky).
//!
//! - An 8 × 8 index checkerboard (Nearest) gives every pixel well inside a texel exactly
//!   that texel's material's radiance.
//! - A 2 × 1 index map (Bilinear) gives the area-fraction mixture `(1 − w) L_a + w L_b`,
//!   `w` linear between the two texel centres: halfway, on the 50/50 boundary, the mean of
//!   the two materials' radiances.
//! - With per-material temperatures on the facets (`RawScene::mix_temperatures`), each
//!   material emits at its own: the checkerboard's pixels are `εₖ σTₖ⁴/π + (1 − εₖ) L_s`
//!   at their material's `Tₖ`, and the bilinear map's `Σ wᵢ (εᵢ σTᵢ⁴/π + (1 − εᵢ) L_s)`.
//! - The refusals the tracer owns: a facet of a mapped material without texture
//!   coordinates, a material map whose image was not given, and specular materials of one
//!   map with different RMS slopes.

use irsig_model::image_map::{ImageMaps, MapFilter};
use irsig_model::material_map::{IndexEntry, MapForm, MaterialMap};
use irsig_model::{MaterialId, MaterialLibrary, MixTemperatures, RawScene, View};
use irsig_radiometry::{BandModel, TotalRadiance};
use irsig_texture::{MaterialMaps, MixMap};
use irsig_tracer::testing::{grey_materials, raw_scene};
use irsig_tracer::{Camera, TraceErrorKind, TraceOptions, Tracer, Vacuum};

const HALF_M: f64 = 5.0;
const TILT_DEG: f64 = 25.0;
const SENSOR_M: [f64; 3] = [1.0, -2.0, 60.0];
const PIXELS: u32 = 96;
const FOV_DEG: f64 = 12.0;
const T_K: f64 = 300.0;
const SKY_W_M2_SR: f64 = 30.0;
/// The two mapped materials' emissivities (ids 2 and 3) and the host's (id 1, never seen).
const EPS_A: f64 = 0.95;
const EPS_B: f64 = 0.6;
const EPS_HOST: f64 = 0.2;

fn slope() -> f64 {
    TILT_DEG.to_radians().tan()
}

/// The quad (-5, -5) to (5, 5) in x and y on z = y·tan 25°, material 1 at 300 K, with
/// u = (x + 5)/10, v = (y + 5)/10 at its corners.
fn tilted_quad(with_uv: bool) -> RawScene {
    let corners = [
        [-HALF_M, -HALF_M],
        [HALF_M, -HALF_M],
        [HALF_M, HALF_M],
        [-HALF_M, HALF_M],
    ];
    let positions: Vec<[f64; 3]> = corners.iter().map(|&[x, y]| [x, y, y * slope()]).collect();
    let mesh = (positions, vec![[0, 1, 2], [0, 2, 3]]);
    let mut scene = raw_scene(&[(&mesh, 1, T_K)]);
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

fn map(filter: MapFilter) -> ImageMaps {
    ImageMaps {
        temperature_offset_k: None,
        emissivity_scale: None,
        material: Some(MaterialMap {
            image: "m.png".into(),
            form: MapForm::Index {
                table: vec![
                    IndexEntry {
                        grey: 0,
                        material: "grey2".into(),
                    },
                    IndexEntry {
                        grey: 1,
                        material: "grey3".into(),
                    },
                ],
            },
            filter,
        }),
    }
}

/// Host 1 (mapped), 2 (ε 0.95, 30 % specular) and 3 (ε 0.6, diffuse).
fn library(filter: MapFilter) -> MaterialLibrary {
    let mut lib = grey_materials(&[(1, EPS_HOST, 0.0), (2, EPS_A, 0.3), (3, EPS_B, 0.0)]);
    lib.materials[0].maps = Some(map(filter));
    lib
}

/// The map with an image of `width × height` values (row 0 at the top).
fn loaded(
    filter: MapFilter,
    width: usize,
    height: usize,
    values: &[u16],
) -> Vec<(MaterialId, MaterialMaps)> {
    let mix = MixMap::from_index(width, height, values, &[(0, 0), (1, 1)], 2, filter).unwrap();
    let maps = MaterialMaps::new(&map(filter), |_, _| unreachable!("no grey map"))
        .unwrap()
        .with_material(mix);
    vec![(MaterialId(1), maps)]
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
        atmosphere: Vacuum {
            sky_radiance_w_m2_sr: SKY_W_M2_SR,
        },
        emissivity: None,
    };
    Tracer::with_sub_bands_and_maps(scene, lib, TotalRadiance, vec![one], maps)
}

fn radiances(t: &Tracer<TotalRadiance, Vacuum>) -> Vec<f64> {
    // No sky-view rays: the diffuse share sees the hemispheric sky (rays below the tilted
    // quad's horizon would see the terrain).
    t.render(&camera(), &TraceOptions::default(), &|_| {})
        .unwrap()
        .radiance_w_m2_sr
}

/// A facet of emissivity `eps` at 300 K under the sky, by hand.
fn leaving(eps: f64) -> f64 {
    eps * TotalRadiance.radiance(T_K) + (1.0 - eps) * SKY_W_M2_SR
}

/// A facet of emissivity `eps` at `t_k` under the sky, by hand: `ε σT⁴/π + (1 − ε) L_s`.
fn leaving_at(eps: f64, t_k: f64) -> f64 {
    const SIGMA: f64 = 5.670_374_419e-8;
    eps * SIGMA * t_k.powi(4) / std::f64::consts::PI + (1.0 - eps) * SKY_W_M2_SR
}

/// The two mapped materials' own temperatures, in the map's order (grey2, grey3), K.
const T_A_K: f64 = 331.5;
const T_B_K: f64 = 287.25;

/// The tilted quad with both facets' materials at [`T_A_K`] and [`T_B_K`], and its
/// facets at their radiative mean (what irsig-therm writes; the tracer reads the
/// materials' own).
fn tilted_quad_at_two_temperatures() -> RawScene {
    let mut scene = tilted_quad(true);
    for (i, f) in scene.facets.iter_mut().enumerate() {
        f.temperature_k = 310.0;
        scene.mix_temperatures.push(MixTemperatures {
            facet: i as u32,
            temperatures_k: vec![T_A_K, T_B_K],
        });
    }
    scene
}

/// The texture coordinates where pixel `(column, row)`'s centre ray meets the quad's
/// plane: `O + s·d` on z = y·tan θ, `s = (tan θ·O_y − O_z)/(d_z − tan θ·d_y)`.
fn uv_of(camera: &Camera, column: u32, row: u32) -> Option<[f64; 2]> {
    let d = camera.pixel_direction(column, row);
    let o = SENSOR_M;
    let s = (slope() * o[1] - o[2]) / (d[2] - slope() * d[1]);
    let (x, y) = (o[0] + s * d[0], o[1] + s * d[1]);
    if s <= 0.0 || x.abs() >= HALF_M || y.abs() >= HALF_M {
        return None;
    }
    Some([(x + HALF_M) / (2.0 * HALF_M), (y + HALF_M) / (2.0 * HALF_M)])
}

#[test]
fn a_nearest_index_map_gives_each_pixel_its_texels_material() {
    const N: usize = 8;
    // Texel (i, j), column i from the left and row j from the bottom: value (i + j) mod 2.
    let values: Vec<u16> = (0..N * N)
        .map(|k| ((k % N + (N - 1 - k / N)) % 2) as u16)
        .collect();
    let t = tracer(
        &tilted_quad(true),
        &library(MapFilter::Nearest),
        loaded(MapFilter::Nearest, N, N, &values),
    )
    .unwrap();
    let image = radiances(&t);
    let cam = camera();
    let (mut checked, mut b) = (0, 0);
    for row in 0..PIXELS {
        for column in 0..PIXELS {
            let Some([u, v]) = uv_of(&cam, column, row) else {
                continue;
            };
            let (x, y) = (u * N as f64, v * N as f64);
            let near_edge = |c: f64| (c - c.round()).abs() < 0.01;
            if near_edge(x) || near_edge(y) {
                continue;
            }
            let odd = (x.floor() as usize + y.floor() as usize) % 2 == 1;
            let expected = leaving(if odd { EPS_B } else { EPS_A });
            let got = image[(row * PIXELS + column) as usize];
            assert!(
                (got / expected - 1.0).abs() < 1e-12,
                "pixel ({column}, {row}) at texel ({x:.3}, {y:.3}): {got}, expected {expected}"
            );
            checked += 1;
            b += usize::from(odd);
        }
    }
    assert!(checked > 3000, "{checked} pixels checked");
    assert!(b > checked / 4 && b < 3 * checked / 4, "{b} of {checked}");
}

#[test]
fn a_bilinear_index_map_mixes_by_area_fraction_and_its_5050_boundary_is_the_mean() {
    // Two texels side by side: material 2 on the left (centre u = 1/4), 3 on the right
    // (centre u = 3/4); repeated, so u = 0 is a boundary too.
    let t = tracer(
        &tilted_quad(true),
        &library(MapFilter::Bilinear),
        loaded(MapFilter::Bilinear, 2, 1, &[0, 1]),
    )
    .unwrap();
    let image = radiances(&t);
    let cam = camera();
    let (la, lb) = (leaving(EPS_A), leaving(EPS_B));
    let (mut checked, mut boundary) = (0, 0);
    for row in 0..PIXELS {
        for column in 0..PIXELS {
            let Some([u, _]) = uv_of(&cam, column, row) else {
                continue;
            };
            // The fraction of material 3: 0 at u = 1/4, 1 at u = 3/4, linear between,
            // and back down to 0 at u = 5/4 (= 1/4 repeated).
            let w = 1.0 - ((u - 0.75).abs() * 2.0).min(1.0);
            let w = if u < 0.25 { (0.25 - u) * 2.0 } else { w };
            let expected = (1.0 - w) * la + w * lb;
            let got = image[(row * PIXELS + column) as usize];
            assert!(
                (got / expected - 1.0).abs() < 1e-6,
                "pixel ({column}, {row}) at u = {u}: {got}, expected {expected} (w = {w})"
            );
            if (u - 0.5).abs() < 1e-3 {
                // Within a thousandth of the boundary: the mean, give or take the slope
                // 2·|L_a − L_b| per unit of u over the distance, and the
                // fractions' f32 rounding.
                let mean = 0.5 * (la + lb);
                let slack = 2.0 * (la - lb).abs() * (u - 0.5).abs() + 1e-6 * mean;
                assert!(
                    (got - mean).abs() <= slack,
                    "{got} against {mean} ± {slack}"
                );
                boundary += 1;
            }
            checked += 1;
        }
    }
    assert!(
        checked > 3000 && boundary > 5,
        "{checked} pixels, {boundary} on the boundary"
    );
}

/// Texel (i, j), column i from the left and row j from the bottom: value (i + j) mod 2.
fn checkerboard(n: usize) -> Vec<u16> {
    (0..n * n)
        .map(|k| ((k % n + (n - 1 - k / n)) % 2) as u16)
        .collect()
}

#[test]
fn each_material_of_a_nearest_map_emits_at_its_own_temperature() {
    const N: usize = 8;
    let t = tracer(
        &tilted_quad_at_two_temperatures(),
        &library(MapFilter::Nearest),
        loaded(MapFilter::Nearest, N, N, &checkerboard(N)),
    )
    .unwrap();
    let image = radiances(&t);
    let cam = camera();
    let (mut checked, mut b) = (0, 0);
    for row in 0..PIXELS {
        for column in 0..PIXELS {
            let Some([u, v]) = uv_of(&cam, column, row) else {
                continue;
            };
            let (x, y) = (u * N as f64, v * N as f64);
            let near_edge = |c: f64| (c - c.round()).abs() < 0.01;
            if near_edge(x) || near_edge(y) {
                continue;
            }
            let odd = (x.floor() as usize + y.floor() as usize) % 2 == 1;
            let expected = if odd {
                leaving_at(EPS_B, T_B_K)
            } else {
                leaving_at(EPS_A, T_A_K)
            };
            let got = image[(row * PIXELS + column) as usize];
            assert!(
                (got / expected - 1.0).abs() < 1e-9,
                "pixel ({column}, {row}) at texel ({x:.3}, {y:.3}): {got}, expected {expected}"
            );
            checked += 1;
            b += usize::from(odd);
        }
    }
    assert!(checked > 3000, "{checked} pixels checked");
    assert!(b > checked / 4 && b < 3 * checked / 4, "{b} of {checked}");
}

#[test]
fn a_bilinear_mixture_emits_each_material_at_its_own_temperature() {
    let t = tracer(
        &tilted_quad_at_two_temperatures(),
        &library(MapFilter::Bilinear),
        loaded(MapFilter::Bilinear, 2, 1, &[0, 1]),
    )
    .unwrap();
    let image = radiances(&t);
    let cam = camera();
    let (la, lb) = (leaving_at(EPS_A, T_A_K), leaving_at(EPS_B, T_B_K));
    let (mut checked, mut boundary) = (0, 0);
    for row in 0..PIXELS {
        for column in 0..PIXELS {
            let Some([u, _]) = uv_of(&cam, column, row) else {
                continue;
            };
            let w = 1.0 - ((u - 0.75).abs() * 2.0).min(1.0);
            let w = if u < 0.25 { (0.25 - u) * 2.0 } else { w };
            // Σ wᵢ εᵢ L(Tᵢ) + Σ wᵢ (1 − εᵢ) L_s: each material's own leaving radiance,
            // weighted by its fraction.
            let expected = (1.0 - w) * la + w * lb;
            let got = image[(row * PIXELS + column) as usize];
            assert!(
                (got / expected - 1.0).abs() < 1e-6,
                "pixel ({column}, {row}) at u = {u}: {got}, expected {expected} (w = {w})"
            );
            if w > 0.05 && w < 0.95 {
                boundary += 1;
            }
            checked += 1;
        }
    }
    assert!(
        checked > 3000 && boundary > 500,
        "{checked} pixels, {boundary} mixed"
    );
}

#[test]
fn per_material_temperatures_that_do_not_fit_the_map_are_refused() {
    let load = || loaded(MapFilter::Nearest, 2, 1, &[0, 1]);
    let mut scene = tilted_quad_at_two_temperatures();
    scene.mix_temperatures[1].temperatures_k.push(300.0);
    let e = tracer(&scene, &library(MapFilter::Nearest), load()).unwrap_err();
    let text = e.to_string();
    assert!(
        text.contains("mix_temperatures[1]: facet 1 (material 1 (grey1)) has 3")
            && text.contains("`m.png` mixes 2 materials"),
        "{text}"
    );
    // A facet whose material has no map.
    let mut lib = library(MapFilter::Nearest);
    lib.materials[0].maps = None;
    let e = tracer(&tilted_quad_at_two_temperatures(), &lib, Vec::new()).unwrap_err();
    assert!(
        e.to_string().contains("the material has no material map"),
        "{e}"
    );
}

#[test]
fn the_tracer_refuses_what_it_cannot_lay_or_mix() {
    let values = [0, 1];
    let load = || loaded(MapFilter::Nearest, 2, 1, &values);
    // No texture coordinates on the mapped facets.
    let e = tracer(&tilted_quad(false), &library(MapFilter::Nearest), load()).unwrap_err();
    assert!(
        matches!(
            e.kind,
            TraceErrorKind::NoTextureCoordinates { material: 1, .. }
        ),
        "{e}"
    );
    // The map's image not given.
    let e = tracer(&tilted_quad(true), &library(MapFilter::Nearest), Vec::new()).unwrap_err();
    assert!(
        e.to_string().contains("was not given with its image"),
        "{e}"
    );
    // Two specular materials of different roughness in one map.
    let mut lib = library(MapFilter::Nearest);
    lib.materials[2].specular_fraction = 0.5;
    lib.materials[2].rms_slope = Some(0.2);
    let e = tracer(&tilted_quad(true), &lib, load()).unwrap_err();
    assert!(e.to_string().contains("RMS slope"), "{e}");
    // The same slope on both is fine.
    lib.materials[1].rms_slope = Some(0.2);
    assert!(tracer(&tilted_quad(true), &lib, load()).is_ok());
}

#[test]
fn an_emissivity_scale_is_checked_against_the_mapped_materials_not_the_host() {
    use irsig_model::image_map::ImageMap;
    use irsig_texture::GreyImage;
    // A scale of 1 at black rising by `per_grey` to white, on the host of the map.
    let with_scale = |lib: &mut MaterialLibrary, per_grey: f64| {
        let mut maps = map(MapFilter::Nearest);
        maps.emissivity_scale = Some(ImageMap {
            image: "scale.png".into(),
            at_black: 1.0,
            per_grey,
            filter: MapFilter::Nearest,
        });
        lib.materials[0].maps = Some(maps.clone());
        let mix =
            MixMap::from_index(2, 1, &[0, 1], &[(0, 0), (1, 1)], 2, MapFilter::Nearest).unwrap();
        let loaded = MaterialMaps::new(&maps, |_, _| GreyImage::new(2, 2, vec![1.0; 4]))
            .unwrap()
            .with_material(mix);
        vec![(MaterialId(1), loaded)]
    };
    // The host's ε (0.2) is never seen under its map; the mapped materials' greatest is 0.95,
    // so a scale of 1.2 would take it to 1.14: refused, where the host's ε alone (0.24)
    // would have let it through to a clamp.
    let mut lib = library(MapFilter::Nearest);
    let maps = with_scale(&mut lib, 0.2);
    let e = tracer(&tilted_quad(true), &lib, maps).unwrap_err();
    match e.kind {
        TraceErrorKind::EmissivityScaleOutOfRange {
            material,
            max_emissivity,
            ..
        } => assert_eq!((material, max_emissivity), (1, EPS_A)),
        ref other => panic!("{other}"),
    }
    // A host of ε 0.99 under a scale of 1.05 (1.04 were it seen) is allowed: the mapped
    // materials reach 0.95 × 1.05 = 0.9975.
    let mut lib = library(MapFilter::Nearest);
    lib.materials[0].emissivity = vec![(0.0, 0.99)];
    let maps = with_scale(&mut lib, 0.05);
    assert!(tracer(&tilted_quad(true), &lib, maps).is_ok());
}
