//! The radiance equation against hand computation: one facet at a known angle, the
//! specular pool with and without the hot panel (events 4 and 3), misses below and above
//! the horizon, the sky-view factor against an exact configuration factor, supersampling,
//! re-centring 500 km away, thread-count independence and two views that must agree.

use crate::air::FnAir;
use irsig_atmosphere::PathTerms;
use irsig_model::{Material, MaterialId, MaterialLibrary, RawFacet, RawScene, Terrain, View};
use irsig_radiometry::{BandModel, TotalRadiance};
use irsig_tracer::testing::{Mesh, box_mesh, ground_quad};
use irsig_tracer::{Camera, Event, TraceOptions, Tracer, Vacuum};

const L_AIR: f64 = 120.0;

fn tau(sensor_alt: f64, target_alt: f64, range: f64) -> f64 {
    (-2e-4 * range * (-(sensor_alt + target_alt) / 2.0 / 8000.0).exp()).exp()
}

fn sky(zenith_deg: f64) -> f64 {
    20.0 + 60.0 * (zenith_deg / 90.0).powi(2)
}

const SKY_HEMI: f64 = 30.0;

/// A made-up atmosphere whose every term is a closed form: τ depends on the range and on
/// both ends' altitudes, the sky on the zenith angle.
const TEST_AIR: FnAir = FnAir {
    path: |s, t, range| {
        let tr = tau(s, t, range);
        PathTerms {
            transmission: tr,
            path_radiance_w_m2_sr: (1.0 - tr) * L_AIR,
        }
    },
    sky: |_, zenith_deg| sky(zenith_deg),
    hemispheric: |_| SKY_HEMI,
};

fn material(id: u16, emissivity: Vec<(f64, f64)>, specular_fraction: f64) -> Material {
    Material {
        id: MaterialId(id),
        name: format!("m{id}"),
        emissivity,
        specular_fraction,
        source: "test".into(),
        band_um: None,
        spectral: None,
        rms_slope: None,
        thermal: None,
        texture: None,
        maps: None,
    }
}

/// A raw scene from meshes, each with a material and a temperature.
fn scene(parts: &[(Mesh, u16, f64)]) -> RawScene {
    let mut s = RawScene {
        terrain: Terrain {
            temperature_k: 290.0,
            emissivity: 0.9,
            material: None,
        },
        ..RawScene::default()
    };
    for (k, (mesh, mat, t)) in parts.iter().enumerate() {
        let base = s.positions_m.len() as u32;
        s.objects.push(format!("part{k}"));
        s.positions_m.extend(&mesh.0);
        s.facets.extend(mesh.1.iter().map(|f| RawFacet {
            vertices: f.map(|v| v + base),
            material: MaterialId(*mat),
            temperature_k: *t,
            object: k as u32,
            uv: None,
        }));
    }
    s
}

fn one_pixel(position: [f64; 3], target: [f64; 3]) -> Camera {
    Camera::from_view(&View::LookAt {
        position_m: position,
        target_m: target,
        up: [0.0, 0.0, 1.0],
        pixels: [1, 1],
        fov_deg: [0.01, 0.01],
        gain_dc_per_k: None,
    })
    .unwrap()
}

fn lt(t: f64) -> f64 {
    TotalRadiance.radiance(t)
}

fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * b.abs().max(1e-300)
}

#[test]
fn a_specular_facet_at_40_degrees_matches_the_hand_computation() {
    // A 200 m specular plate at z = 0; ε(φ) = 0.95 at 0°, 0.85 at 60°, 0 at 90°.
    let mats = MaterialLibrary {
        materials: vec![material(
            1,
            vec![(0.0, 0.95), (60.0, 0.85), (90.0, 0.0)],
            1.0,
        )],
    };
    let sc = scene(&[(ground_quad([-100.0, -100.0], [100.0, 100.0], 0.0), 1, 310.0)]);
    let tracer = Tracer::new(&sc, &mats, TotalRadiance, TEST_AIR).unwrap();
    let h = 10.0;
    let theta = 40.0_f64.to_radians();
    // Aim 0.3 m off the diagonal so the ray does not strike the shared edge exactly.
    let target = [0.3, 0.0, 0.0];
    let cam = one_pixel([0.3, -h * theta.tan(), h], target);
    let s = tracer.probe(&cam, &TraceOptions::default(), 0, 0).unwrap();
    // By hand: ε(40°) = 0.95 − 0.10·40/60; r = 1 − ε; mirror zenith = 40°.
    let eps = 0.95 - 0.10 * 40.0 / 60.0;
    let range = h / theta.cos();
    let t = tau(h, 0.0, range);
    let expected = t * (eps * lt(310.0) + (1.0 - eps) * sky(40.0)) + (1.0 - t) * L_AIR;
    assert_eq!(s.event, Event::SpecularEscapes);
    assert!(
        (s.incidence_deg() - 40.0).abs() < 1e-6,
        "{}",
        s.incidence_deg()
    );
    assert!((s.reflected_zenith_deg - 40.0).abs() < 1e-6);
    assert!(close(s.emissivity, eps, 1e-9));
    assert!(close(s.range_m, range, 1e-9));
    assert!(close(s.transmission, t, 1e-9));
    assert!(close(s.radiance_w_m2_sr, expected, 1e-9), "{s}");
    assert_eq!((s.primary_material, s.secondary_material), (1, 0));

    // The same plate diffuse: ε still at the actual 40° (not the table's first entry, the
    // 1990 slip), and the hemispheric sky.
    let mats = MaterialLibrary {
        materials: vec![material(
            1,
            vec![(0.0, 0.95), (60.0, 0.85), (90.0, 0.0)],
            0.0,
        )],
    };
    let tracer = Tracer::new(&sc, &mats, TotalRadiance, TEST_AIR).unwrap();
    let s = tracer.probe(&cam, &TraceOptions::default(), 0, 0).unwrap();
    let expected = t * (eps * lt(310.0) + (1.0 - eps) * SKY_HEMI) + (1.0 - t) * L_AIR;
    assert_eq!(s.event, Event::Diffuse);
    assert!(close(s.radiance_w_m2_sr, expected, 1e-9), "{s}");

    // Half specular: the mixture of the two.
    let mats = MaterialLibrary {
        materials: vec![material(
            1,
            vec![(0.0, 0.95), (60.0, 0.85), (90.0, 0.0)],
            0.25,
        )],
    };
    let tracer = Tracer::new(&sc, &mats, TotalRadiance, TEST_AIR).unwrap();
    let s = tracer.probe(&cam, &TraceOptions::default(), 0, 0).unwrap();
    let refl = 0.25 * sky(40.0) + 0.75 * SKY_HEMI;
    let expected = t * (eps * lt(310.0) + (1.0 - eps) * refl) + (1.0 - t) * L_AIR;
    assert!(close(s.radiance_w_m2_sr, expected, 1e-9), "{s}");
}

fn pool_scene(with_panel: bool) -> (RawScene, MaterialLibrary) {
    // Pool: specular water, ε = 0.98 flat; panel: diffuse, ε = 0.8, 350 K, a wall at
    // y = 5 from z = 0 to 5 facing −y.
    let mats = MaterialLibrary {
        materials: vec![
            material(1, vec![(0.0, 0.98), (90.0, 0.98)], 1.0),
            material(2, vec![(0.0, 0.8), (90.0, 0.8)], 0.0),
        ],
    };
    let pool = ground_quad([-5.0, -5.0], [5.0, 4.9], 0.0);
    let mut parts = vec![(pool, 1, 288.0)];
    if with_panel {
        parts.push((box_mesh([-5.0, 5.0, 0.0], [5.0, 5.2, 5.0]), 2, 350.0));
    }
    (scene(&parts), mats)
}

#[test]
fn a_specular_pool_reflects_the_hot_panel_and_then_the_sky_without_it() {
    // Camera at (0.3, −10, 5) aimed at (0.3, 0, 0): the mirror ray climbs at
    // atan(5/10) and meets the panel at y = 5, z = 2.5.
    let cam = one_pixel([0.3, -10.0, 5.0], [0.3, 0.0, 0.0]);
    let range = 125.0_f64.sqrt();
    let t = tau(5.0, 0.0, range);
    let zenith = (5.0 / 125.0_f64.sqrt()).acos().to_degrees(); // 63.43°

    let (sc, mats) = pool_scene(true);
    let tracer = Tracer::new(&sc, &mats, TotalRadiance, TEST_AIR).unwrap();
    let s = tracer.probe(&cam, &TraceOptions::default(), 0, 0).unwrap();
    // L_b is the panel's surface-leaving radiance, ε₂·L_T2 + r₂·L_d, not its blackbody
    // radiance (the 1990 code's slip).
    let lb = 0.8 * lt(350.0) + 0.2 * SKY_HEMI;
    let expected = t * (0.98 * lt(288.0) + 0.02 * lb) + (1.0 - t) * L_AIR;
    assert_eq!(s.event, Event::SpecularHitsFacet);
    assert_eq!((s.primary_material, s.secondary_material), (1, 2));
    assert!(close(s.specular_incident_w_m2_sr, lb, 1e-12));
    assert!(close(s.radiance_w_m2_sr, expected, 1e-9), "{s}");

    let (sc, mats) = pool_scene(false);
    let tracer = Tracer::new(&sc, &mats, TotalRadiance, TEST_AIR).unwrap();
    let s = tracer.probe(&cam, &TraceOptions::default(), 0, 0).unwrap();
    let expected = t * (0.98 * lt(288.0) + 0.02 * sky(zenith)) + (1.0 - t) * L_AIR;
    assert_eq!(s.event, Event::SpecularEscapes);
    assert_eq!((s.primary_material, s.secondary_material), (1, 0));
    assert!((s.reflected_zenith_deg - zenith).abs() < 1e-6);
    assert!(close(s.radiance_w_m2_sr, expected, 1e-9), "{s}");

    // Zero bounces: the pool reflects its environment at the mirror angle without tracing,
    // the sky at 63.43° as if the panel were not there.
    let (sc, mats) = pool_scene(true);
    let tracer = Tracer::new(&sc, &mats, TotalRadiance, TEST_AIR).unwrap();
    let opts = TraceOptions {
        specular_bounces: 0,
        ..TraceOptions::default()
    };
    let s = tracer.probe(&cam, &opts, 0, 0).unwrap();
    let expected = t * (0.98 * lt(288.0) + 0.02 * sky(zenith)) + (1.0 - t) * L_AIR;
    assert!(close(s.radiance_w_m2_sr, expected, 1e-9), "{s}");
}

#[test]
fn two_mirrors_need_two_bounces() {
    // Pool below, a specular (mirror, ε = 0.1) panel; the panel's reflection climbs
    // towards the sky, and a hot wall (ε = 0.9, 400 K) high behind the camera stands in
    // its way.
    let mats = MaterialLibrary {
        materials: vec![
            material(1, vec![(0.0, 0.98), (90.0, 0.98)], 1.0),
            material(2, vec![(0.0, 0.1), (90.0, 0.1)], 1.0),
            material(3, vec![(0.0, 0.9), (90.0, 0.9)], 0.0),
        ],
    };
    let sc = scene(&[
        (ground_quad([-5.0, -5.0], [5.0, 4.9], 0.0), 1, 288.0),
        (box_mesh([-5.0, 5.0, 0.0], [5.0, 5.2, 5.0]), 2, 350.0),
        (box_mesh([-5.0, -6.0, 6.0], [5.0, -5.8, 12.0]), 3, 400.0),
    ]);
    let tracer = Tracer::new(&sc, &mats, TotalRadiance, TEST_AIR).unwrap();
    let cam = one_pixel([0.3, -10.0, 5.0], [0.3, 0.0, 0.0]);
    let t = tau(5.0, 0.0, 125.0_f64.sqrt());
    let zenith = (5.0 / 125.0_f64.sqrt()).acos().to_degrees();
    // The mirror ray (0, 2, 1)/√5 meets the panel's −y face at z = 2.5; its reflection
    // (0, −2, 1)/√5 climbs back over the camera (passing y = −5.8 at z = 7.9). With one
    // bounce the panel reflects its untraced environment there, the sky at zenith
    // acos(1/√5) = 63.43°, as if the wall were not there.
    let one = tracer.probe(&cam, &TraceOptions::default(), 0, 0).unwrap();
    let lb1 = 0.1 * lt(350.0) + 0.9 * sky(zenith);
    assert!(close(one.specular_incident_w_m2_sr, lb1, 1e-12), "{one}");
    let two = tracer
        .probe(
            &cam,
            &TraceOptions {
                specular_bounces: 2,
                ..TraceOptions::default()
            },
            0,
            0,
        )
        .unwrap();
    // The second bounce finds the wall: its leaving radiance, 0.9·L_T(400 K) + 0.1·L_d.
    let wall = 0.9 * lt(400.0) + 0.1 * SKY_HEMI;
    let lb2 = 0.1 * lt(350.0) + 0.9 * wall;
    assert!(close(two.specular_incident_w_m2_sr, lb2, 1e-12), "{two}");
    let expected = t * (0.98 * lt(288.0) + 0.02 * lb2) + (1.0 - t) * L_AIR;
    assert!(close(two.radiance_w_m2_sr, expected, 1e-9));
}

#[test]
fn misses_below_the_horizon_see_the_terrain_and_above_it_the_sky() {
    let mats = MaterialLibrary {
        materials: vec![material(1, vec![(0.0, 0.9)], 0.0)],
    };
    // One small facet far off to the side so the scene is not empty.
    let sc = scene(&[(
        ground_quad([5000.0, 5000.0], [5001.0, 5001.0], 0.0),
        1,
        300.0,
    )]);
    let tracer = Tracer::new(&sc, &mats, TotalRadiance, TEST_AIR).unwrap();
    let h = 1000.0;
    // 30° from nadir: below the horizon.
    let a = 30.0_f64.to_radians();
    let cam = one_pixel([0.0, 0.0, h], [0.0, h * a.tan(), 0.0]);
    let s = tracer.probe(&cam, &TraceOptions::default(), 0, 0).unwrap();
    assert_eq!(s.event, Event::Terrain);
    // Flat-Earth range h / cos 30° = 1154.70 m; the curved ground adds about 0.03 m.
    assert!((s.range_m - h / a.cos()).abs() < 0.1, "{}", s.range_m);
    assert!(s.range_m > h / a.cos(), "{}", s.range_m);
    // The path terms are those of the flat ground at the same nadir angle: the models are
    // plane-parallel and read the slant angle from the range.
    let t = tau(h, 0.0, h / a.cos());
    let terrain = 0.9 * lt(290.0) + 0.1 * SKY_HEMI;
    let expected = t * terrain + (1.0 - t) * L_AIR;
    assert!(close(s.radiance_w_m2_sr, expected, 1e-12), "{s}");
    assert!((s.temperature_k - 290.0).abs() < 1e-12);

    // 30° above the horizontal: the sky path at zenith 60°.
    let cam = one_pixel(
        [0.0, 0.0, h],
        [0.0, 1000.0, h + 1000.0 * 30.0_f64.to_radians().tan()],
    );
    let s = tracer.probe(&cam, &TraceOptions::default(), 0, 0).unwrap();
    assert_eq!(s.event, Event::Sky);
    assert!(close(s.radiance_w_m2_sr, sky(60.0), 1e-9), "{s}");
    assert_eq!(s.primary_material, 0);

    // Just below the horizontal but above the Earth's limb (dip 1.015° at 1 km): sky.
    let cam = one_pixel(
        [0.0, 0.0, h],
        [0.0, 1000.0, h - 1000.0 * 0.5_f64.to_radians().tan()],
    );
    let s = tracer.probe(&cam, &TraceOptions::default(), 0, 0).unwrap();
    assert_eq!(s.event, Event::Sky);
    assert!(close(s.radiance_w_m2_sr, sky(90.5), 1e-9));
}

/// Howell's catalogue of configuration factors, case B-3: a differential planar element to
/// a parallel rectangle `a × b` at distance `c`, the element's normal through a corner:
/// `F = 1/(2π) [X/√(1+X²) atan(Y/√(1+X²)) + Y/√(1+Y²) atan(X/√(1+Y²))]`, X = a/c, Y = b/c.
/// (J. R. Howell, *A Catalog of Radiation Heat Transfer Configuration Factors*, 3rd ed.)
fn howell_b3(a: f64, b: f64, c: f64) -> f64 {
    let (x, y) = (a / c, b / c);
    let sx = (1.0 + x * x).sqrt();
    let sy = (1.0 + y * y).sqrt();
    (x / sx * (y / sx).atan() + y / sy * (x / sy).atan()) / (2.0 * std::f64::consts::PI)
}

#[test]
fn sky_view_factor_at_the_centre_of_a_square_pit_matches_the_configuration_factor() {
    // Floor 2 m × 2 m at z = 0 (ε = 0.5, diffuse, 300 K); four 1 m walls (ε = 1, 320 K).
    let mats = MaterialLibrary {
        materials: vec![
            material(1, vec![(0.0, 0.5)], 0.0),
            material(2, vec![(0.0, 1.0)], 0.0),
        ],
    };
    let (w, c) = (1.0, 1.0);
    let walls = [
        box_mesh([-w - 0.1, -w - 0.1, 0.0], [-w, w + 0.1, c]),
        box_mesh([w, -w - 0.1, 0.0], [w + 0.1, w + 0.1, c]),
        box_mesh([-w, -w - 0.1, 0.0], [w, -w, c]),
        box_mesh([-w, w, 0.0], [w, w + 0.1, c]),
    ];
    let mut parts = vec![(ground_quad([-w, -w], [w, w], 0.0), 1, 300.0)];
    parts.extend(walls.into_iter().map(|m| (m, 2, 320.0)));
    let sc = scene(&parts);
    let l_sky = 25.0;
    let tracer = Tracer::new(
        &sc,
        &mats,
        TotalRadiance,
        Vacuum {
            sky_radiance_w_m2_sr: l_sky,
        },
    )
    .unwrap();
    // Straight down at (0.01, 0.02): off the floor's diagonal.
    let cam = Camera::from_view(&View::Legacy {
        position_m: [0.01, 0.02, 50.0],
        pixels: [1, 1],
        omega_phi_kappa_deg: [0.0; 3],
        fov_deg: [0.001, 0.001],
        gain_dc_per_k: None,
    })
    .unwrap();
    let f_exact = 4.0 * howell_b3(w, w, c);
    assert!((f_exact - 0.5541).abs() < 1e-3, "{f_exact}");
    let opts = TraceOptions {
        sky_view_rays: 4096,
        seed: 7,
        ..TraceOptions::default()
    };
    let s = tracer.probe(&cam, &opts, 0, 0).unwrap();
    // 4096 stratified rays: the error is well below the unstratified 1σ of
    // √(F(1−F)/N) = 0.0078.
    assert!(
        (s.sky_view_factor - f_exact).abs() < 0.008,
        "F = {}",
        s.sky_view_factor
    );
    let diffuse = f_exact * l_sky + (1.0 - f_exact) * lt(320.0);
    assert!(close(s.diffuse_incident_w_m2_sr, diffuse, 0.01), "{s}");
    assert!(close(
        s.radiance_w_m2_sr,
        0.5 * lt(300.0) + 0.5 * s.diffuse_incident_w_m2_sr,
        1e-12
    ));
    // Off by default: F = 1 and the hemispheric sky.
    let s = tracer.probe(&cam, &TraceOptions::default(), 0, 0).unwrap();
    assert!((s.sky_view_factor - 1.0).abs() < f64::EPSILON);
    assert!(close(
        s.radiance_w_m2_sr,
        0.5 * lt(300.0) + 0.5 * l_sky,
        1e-12
    ));
}

fn hot_plate_tracer() -> Tracer<TotalRadiance, Vacuum> {
    let mats = MaterialLibrary {
        materials: vec![material(1, vec![(0.0, 1.0)], 0.0)],
    };
    // A hot blackbody plate at z = 1 m covering −10 < x < 0; a nadir view sees the
    // terrain (ε = 0.9, 290 K, cold sky) where the plate is not.
    let sc = scene(&[(ground_quad([-10.0, -10.0], [0.0, 10.0], 1.0), 1, 330.0)]);
    Tracer::new(
        &sc,
        &mats,
        TotalRadiance,
        Vacuum {
            sky_radiance_w_m2_sr: 0.0,
        },
    )
    .unwrap()
}

fn nadir(pos: [f64; 3], pixels: [u32; 2], fov: f64) -> Camera {
    Camera::from_view(&View::Legacy {
        position_m: pos,
        pixels,
        omega_phi_kappa_deg: [0.0; 3],
        fov_deg: [fov, fov],
        gain_dc_per_k: None,
    })
    .unwrap()
}

#[test]
fn supersampling_averages_a_pixel_split_by_an_edge() {
    let tracer = hot_plate_tracer();
    // Three columns centred on x = 0: the plate edge splits the middle column in half.
    let cam = nadir([0.0, 0.37, 101.0], [3, 1], 2.0);
    let hot = lt(330.0);
    let ground = 0.9 * lt(290.0);
    let opts = TraceOptions {
        supersampling: 8,
        ..TraceOptions::default()
    };
    let f = tracer.render(&cam, &opts, &|_| {}).unwrap();
    // Even N: the strata of the left half lie on the plate, the right half off it.
    let mid = f.radiance_w_m2_sr[1];
    assert!(close(mid, 0.5 * (hot + ground), 1e-12), "{mid}");
    assert!(close(f.radiance_w_m2_sr[0], hot, 1e-12));
    assert!(close(f.radiance_w_m2_sr[2], ground, 1e-12));
}

#[test]
fn the_radiance_does_not_depend_on_keeping_the_truth_terms() {
    // Dropping the per-pixel terms must not change a single bit of the image, with every
    // random choice (jitter, hemisphere rays) in play.
    let tracer = hot_plate_tracer();
    let cam = nadir([-3.0, 0.37, 30.0], [24, 16], 40.0);
    let with = TraceOptions {
        supersampling: 2,
        sky_view_rays: 16,
        seed: 5,
        ..TraceOptions::default()
    };
    let without = TraceOptions {
        truth: false,
        ..with
    };
    let a = tracer.render(&cam, &with, &|_| {}).unwrap();
    let b = tracer.render(&cam, &without, &|_| {}).unwrap();
    assert_eq!(a.truth.len(), 24 * 16);
    assert!(b.truth.is_empty());
    let bits = |f: &irsig_tracer::Frame| -> Vec<u64> {
        f.radiance_w_m2_sr.iter().map(|x| x.to_bits()).collect()
    };
    assert_eq!(bits(&a), bits(&b));
}

fn render_all(
    tracer: &Tracer<TotalRadiance, Vacuum>,
    cam: &Camera,
    opts: &TraceOptions,
) -> Vec<u64> {
    let f = tracer.render(cam, opts, &|_| {}).unwrap();
    f.radiance_w_m2_sr
        .iter()
        .map(|x| x.to_bits())
        .chain(
            f.truth
                .iter()
                .map(|s| u64::from(s.sky_view_factor.to_bits())),
        )
        .collect()
}

#[test]
fn images_are_bit_identical_at_one_and_several_threads() {
    let tracer = hot_plate_tracer();
    let cam = nadir([-3.0, 0.37, 30.0], [24, 16], 40.0);
    let opts = TraceOptions {
        supersampling: 2,
        sky_view_rays: 16,
        seed: 3,
        ..TraceOptions::default()
    };
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap()
        .install(|| render_all(&tracer, &cam, &opts));
    let four = rayon::ThreadPoolBuilder::new()
        .num_threads(4)
        .build()
        .unwrap()
        .install(|| render_all(&tracer, &cam, &opts));
    assert_eq!(one, four);
}

#[test]
fn a_scene_500_km_from_the_origin_gives_the_same_image() {
    let mats = MaterialLibrary {
        materials: vec![
            material(1, vec![(0.0, 0.9), (90.0, 0.3)], 0.6),
            material(2, vec![(0.0, 0.95)], 0.0),
        ],
    };
    let build = |off: [f64; 3]| {
        let shift = |m: Mesh| -> Mesh {
            (
                m.0.iter()
                    .map(|p| [p[0] + off[0], p[1] + off[1], p[2] + off[2]])
                    .collect(),
                m.1,
            )
        };
        let sc = scene(&[
            (shift(ground_quad([-3.1, -2.7], [3.3, 2.9], 0.0)), 1, 295.0),
            (
                shift(box_mesh([-0.7, -0.3, 0.0], [0.4, 0.6, 0.83])),
                2,
                315.0,
            ),
        ]);
        let tracer = Tracer::new(&sc, &mats, TotalRadiance, TEST_AIR).unwrap();
        let cam = Camera::from_view(&View::LookAt {
            position_m: [off[0] + 4.1, off[1] - 6.3, off[2] + 3.7],
            target_m: [off[0], off[1], off[2]],
            up: [0.0, 0.0, 1.0],
            pixels: [48, 32],
            fov_deg: [60.0, 40.0],
            gain_dc_per_k: None,
        })
        .unwrap();
        tracer
            .render(&cam, &TraceOptions::default(), &|_| {})
            .unwrap()
    };
    let a = build([0.0; 3]);
    let b = build([500_000.0, -500_000.0, 0.0]);
    let mut hits = 0;
    for ((sa, sb), (la, lb)) in a
        .truth
        .iter()
        .zip(&b.truth)
        .zip(a.radiance_w_m2_sr.iter().zip(&b.radiance_w_m2_sr))
    {
        assert_eq!(sa.primary_material, sb.primary_material);
        assert_eq!(sa.secondary_material, sb.secondary_material);
        assert!(close(*la, *lb, 1e-9));
        hits += usize::from(sa.primary_material != 0);
    }
    assert!(hits > 500, "the view should mostly see the scene: {hits}");
}

#[test]
fn two_views_of_the_same_scene_agree_where_they_must() {
    // A Lambertian blackbody-like plate (ε flat): the same radiance from any direction in a
    // vacuum; and a legacy view equal to a look-at view gives the same image.
    let mats = MaterialLibrary {
        materials: vec![material(1, vec![(0.0, 0.93), (90.0, 0.93)], 0.0)],
    };
    let sc = scene(&[(ground_quad([-50.0, -50.0], [50.0, 50.0], 0.0), 1, 305.0)]);
    let tracer = Tracer::new(
        &sc,
        &mats,
        TotalRadiance,
        Vacuum {
            sky_radiance_w_m2_sr: 12.0,
        },
    )
    .unwrap();
    let a = one_pixel([0.2, -20.0, 15.0], [0.2, 0.0, 0.0]);
    let b = one_pixel([-17.0, 3.0, 40.0], [0.1, 0.3, 0.0]);
    let sa = tracer.probe(&a, &TraceOptions::default(), 0, 0).unwrap();
    let sb = tracer.probe(&b, &TraceOptions::default(), 0, 0).unwrap();
    assert!(close(
        sa.radiance_w_m2_sr,
        0.93 * lt(305.0) + 0.07 * 12.0,
        1e-12
    ));
    assert!(close(sa.radiance_w_m2_sr, sb.radiance_w_m2_sr, 1e-12));

    let pos = [13.0, -30.0, 9.0];
    let target = [0.5, 0.2, 0.0];
    let look = Camera::from_view(&View::LookAt {
        position_m: pos,
        target_m: target,
        up: [0.0, 0.0, 1.0],
        pixels: [20, 12],
        fov_deg: [50.0, 30.0],
        gain_dc_per_k: None,
    })
    .unwrap();
    let legacy = Camera::from_view(&View::Legacy {
        position_m: pos,
        pixels: [20, 12],
        omega_phi_kappa_deg: irsig_tracer::look_at_omega_phi_kappa_deg(pos.into(), target.into()),
        fov_deg: [50.0, 30.0],
        gain_dc_per_k: None,
    })
    .unwrap();
    let fa = tracer
        .render(&look, &TraceOptions::default(), &|_| {})
        .unwrap();
    let fb = tracer
        .render(&legacy, &TraceOptions::default(), &|_| {})
        .unwrap();
    for (x, y) in fa.radiance_w_m2_sr.iter().zip(&fb.radiance_w_m2_sr) {
        assert!(close(*x, *y, 1e-12));
    }
}

#[test]
fn bad_input_is_refused_with_a_reason() {
    let mats = MaterialLibrary {
        materials: vec![material(1, vec![(0.0, 0.9)], 0.0)],
    };
    let mut sc = scene(&[(ground_quad([0.0, 0.0], [1.0, 1.0], 0.0), 7, 300.0)]);
    let err = Tracer::new(&sc, &mats, TotalRadiance, Vacuum::default()).unwrap_err();
    assert!(err.to_string().contains("material 7"), "{err}");
    sc.facets.clear();
    assert!(Tracer::new(&sc, &mats, TotalRadiance, Vacuum::default()).is_err());
    let sc = scene(&[(ground_quad([0.0, 0.0], [1.0, 1.0], 0.0), 1, 300.0)]);
    let tracer = Tracer::new(&sc, &mats, TotalRadiance, Vacuum::default()).unwrap();
    let cam = nadir([0.0, 0.0, 10.0], [4, 4], 10.0);
    assert!(tracer.probe(&cam, &TraceOptions::default(), 4, 0).is_err());
    let opts = TraceOptions {
        supersampling: 0,
        ..TraceOptions::default()
    };
    assert!(tracer.render(&cam, &opts, &|_| {}).is_err());
}

#[test]
fn a_mirror_out_of_bounces_reflects_the_ground_it_points_at_not_the_hemispheric_sky() {
    // A perfect mirror (ε = 0) leaning 30° forward from vertical at y = 10, seen level from
    // 5 m up: its reflection points 60° below the horizon, at the terrain (290 K,
    // ε = 0.9). Traced (1 bounce) and untraced (0 bounces) it must see the terrain, whose
    // leaving radiance is 0.9·L_T(290 K) + 0.1·L_d (the test air's hemispheric sky).
    let mats = MaterialLibrary {
        materials: vec![material(1, vec![(0.0, 0.0), (90.0, 0.0)], 1.0)],
    };
    let (s30, c30) = (30_f64.to_radians().sin(), 30_f64.to_radians().cos());
    // The mirror's corners: bottom edge at y = 10, z = 0; top edge leaning towards the
    // camera (−y).
    let corner = |x: f64, up: f64| [x, 10.0 - up * s30, up * c30];
    let mesh: Mesh = (
        vec![
            corner(-20.0, 0.0),
            corner(20.0, 0.0),
            corner(20.0, 20.0),
            corner(-20.0, 20.0),
        ],
        vec![[0, 1, 2], [0, 2, 3]],
    );
    let sc = scene(&[(mesh, 1, 300.0)]);
    let tracer = Tracer::new(&sc, &mats, TotalRadiance, TEST_AIR).unwrap();
    let cam = one_pixel([0.3, 0.0, 5.0], [0.3, 10.0, 5.0]);
    let terrain = 0.9 * lt(290.0) + 0.1 * SKY_HEMI;
    for bounces in [0, 1] {
        let options = TraceOptions {
            specular_bounces: bounces,
            ..TraceOptions::default()
        };
        let s = tracer.probe(&cam, &options, 0, 0).unwrap();
        assert_eq!(s.event, Event::SpecularEscapes, "{bounces}: {s}");
        // The reflected ray: incidence 30° off the tilted normal, 60° below the horizon.
        assert!((s.reflected_zenith_deg - 150.0).abs() < 1e-6, "{s}");
        assert!(
            close(s.specular_incident_w_m2_sr, terrain, 1e-12),
            "{bounces}: {s}"
        );
    }
}
