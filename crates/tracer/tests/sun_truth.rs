//! The sun's truth layers against hand computation: a plate in the sun
//! gets `E = E_n·cos θ_i` and a visible fraction 1; a roofed plate 0 and 0; a soft shadow's
//! edge the visible segment of the disk; a Lambertian plate's reflected sunlight is
//! `r·E/π` and the sun's share `τ·r·E/π / L`; the terrain's are its flat, unshadowed
//! ones; a mirror's truth says what reaches it without changing its radiance; a night frame
//! keeps no sun layers; and the layers do not depend on the thread count or the tile.

// Exact zeros and ones (a shadow, a whole disk) and f32 roundings: equality is exact.
#![allow(clippy::float_cmp)]

use crate::air::FnAir;
use irsig_atmosphere::PathTerms;
use irsig_model::truth::Layer;
use irsig_model::{MaterialLibrary, RawScene, View};
use irsig_radiometry::{BandModel, TotalRadiance};
use irsig_tracer::testing::{Mesh, box_mesh, grey_materials, ground_quad, raw_scene};
use irsig_tracer::{
    Atmosphere, Camera, DVec3, Frame, SUN_ANGULAR_RADIUS_DEG, Sun, SunBeam, Tile, TraceOptions,
    Tracer, Vacuum,
};

/// Direct normal irradiance of the test sun, W m⁻².
const E_N: f64 = 800.0;
/// The sun's zenith angle, degrees, in the +x half of the sky.
const ZENITH_DEG: f64 = 30.0;
const T_K: f64 = 300.0;
/// The grey air's transmission and path radiance (W m⁻² sr⁻¹), and its sky (W m⁻² sr⁻¹).
const TAU: f64 = 0.7;
const PATH_W_M2_SR: f64 = 12.0;
const SKY_W_M2_SR: f64 = 25.0;

/// Air of one transmission and one path radiance on every path, and a uniform sky.
const GREY_AIR: FnAir = FnAir {
    path: |_, _, _| PathTerms {
        transmission: TAU,
        path_radiance_w_m2_sr: PATH_W_M2_SR,
    },
    sky: |_, _| SKY_W_M2_SR,
    hemispheric: |_| SKY_W_M2_SR,
};

fn to_sun() -> [f64; 3] {
    let z = ZENITH_DEG.to_radians();
    [z.sin(), 0.0, z.cos()]
}

fn sun(shadow_rays: u32) -> Sun {
    Sun {
        shadow_rays,
        ..Sun::new(DVec3::from(to_sun()), vec![SunBeam::uniform(E_N).unwrap()])
    }
}

fn lit<A: Atmosphere>(
    scene: &RawScene,
    materials: &MaterialLibrary,
    air: A,
    shadow_rays: u32,
) -> Tracer<TotalRadiance, A> {
    Tracer::new(scene, materials, TotalRadiance, air)
        .unwrap()
        .with_sun(Some(sun(shadow_rays)))
        .unwrap()
}

fn plate(lo: [f64; 2], hi: [f64; 2], z: f64) -> Mesh {
    ground_quad(lo, hi, z)
}

fn looking_down(above: [f64; 3], pixels: u32) -> Camera {
    Camera::from_view(&View::Legacy {
        position_m: above,
        pixels: [pixels, pixels],
        omega_phi_kappa_deg: [0.0, 0.0, 0.0],
        fov_deg: [1.0, 1.0],
        gain_dc_per_k: None,
    })
    .unwrap()
}

fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * b.abs().max(1e-300)
}

#[test]
fn a_plate_in_the_sun_gets_e_n_cos_theta_and_reflects_r_e_over_pi() {
    let eps = 0.9;
    let scene = raw_scene(&[(&plate([-20.0, -20.0], [20.0, 20.0], 1.0), 1, T_K)]);
    let materials = grey_materials(&[(1, eps, 0.0)]);
    let cos_i = ZENITH_DEG.to_radians().cos();
    let e = E_N * cos_i;
    let reflected = (1.0 - eps) * e / std::f64::consts::PI;
    // The pixel's radiance by hand: τ·(ε·σT⁴/π + r·(L_sky + E/π)) + L_u.
    let l_t = TotalRadiance.radiance(T_K);
    let radiance =
        TAU * (eps * l_t + (1.0 - eps) * (SKY_W_M2_SR + e / std::f64::consts::PI)) + PATH_W_M2_SR;
    let camera = looking_down([0.0, 0.0, 100.0], 3);
    for rays in [1, 64] {
        let day = lit(&scene, &materials, GREY_AIR, rays);
        let s = day.probe(&camera, &TraceOptions::default(), 1, 1).unwrap();
        // Many rays weigh each point of the disk by its own cosine, within cos(θ ± α).
        let rel = if rays == 1 { 1e-12 } else { 5e-3 };
        assert!(close(s.solar_irradiance_w_m2, e, rel), "{s}");
        assert_eq!(s.sun_visible_fraction, 1.0, "{s}");
        assert!(close(s.reflected_solar_w_m2_sr, reflected, rel), "{s}");
        assert!(close(s.radiance_w_m2_sr, radiance, rel), "{s}");
        let share = TAU * reflected / radiance;
        assert!(close(s.sun_share, share, rel), "{s}");
        assert!(close(
            s.sun_share,
            TAU * s.reflected_solar_w_m2_sr / s.radiance_w_m2_sr,
            1e-12
        ));
        // The frame's layers are the probe's terms rounded to f32.
        let frame = day
            .render(&camera, &TraceOptions::default(), &|_| {})
            .unwrap();
        let layer = |l| frame.truth_layer(l).unwrap()[4];
        assert_eq!(
            layer(Layer::SolarIrradiance),
            s.solar_irradiance_w_m2 as f32
        );
        assert_eq!(layer(Layer::SunVisibleFraction), 1.0);
        assert_eq!(
            layer(Layer::ReflectedSolarRadiance),
            s.reflected_solar_w_m2_sr as f32
        );
        assert_eq!(layer(Layer::SunShare), s.sun_share as f32);
    }
}

#[test]
fn a_roofed_plate_gets_no_irradiance_and_sees_none_of_the_disk() {
    let x = 10.0 * ZENITH_DEG.to_radians().tan();
    let roof = plate([x - 3.0, -3.0], [x + 3.0, 3.0], 11.0);
    let scene = raw_scene(&[
        (&plate([-20.0, -20.0], [20.0, 20.0], 1.0), 1, T_K),
        (&roof, 1, T_K),
    ]);
    let materials = grey_materials(&[(1, 0.9, 0.0)]);
    let camera = looking_down([0.0, 0.0, 100.0], 3);
    for rays in [1, 16] {
        let s = lit(&scene, &materials, GREY_AIR, rays)
            .probe(&camera, &TraceOptions::default(), 1, 1)
            .unwrap();
        assert_eq!(s.solar_irradiance_w_m2, 0.0, "{s}");
        assert_eq!(s.sun_visible_fraction, 0.0, "{s}");
        assert_eq!(s.reflected_solar_w_m2_sr, 0.0, "{s}");
        assert_eq!(s.sun_share, 0.0, "{s}");
    }
}

#[test]
fn a_plate_facing_away_from_the_sun_sees_none_of_it() {
    // Facing down (its back to the camera is what the camera sees: one-sided, the normal
    // turned to the ray), lit from above: a plate seen from below has the sun behind it.
    let scene = raw_scene(&[(&plate([-20.0, -20.0], [20.0, 20.0], 10.0), 1, T_K)]);
    let materials = grey_materials(&[(1, 0.9, 0.0)]);
    let camera = Camera::from_view(&View::LookAt {
        position_m: [0.0, 0.0, 1.0],
        target_m: [0.0, 0.0, 10.0],
        up: [0.0, 1.0, 0.0],
        pixels: [3, 3],
        fov_deg: [1.0, 1.0],
        gain_dc_per_k: None,
    })
    .unwrap();
    let s = lit(&scene, &materials, Vacuum::default(), 16)
        .probe(&camera, &TraceOptions::default(), 1, 1)
        .unwrap();
    assert_eq!(s.solar_irradiance_w_m2, 0.0, "{s}");
    assert_eq!(s.sun_visible_fraction, 0.0, "{s}");
}

#[test]
fn a_soft_shadow_edge_sees_the_visible_segment_of_the_disk() {
    // The roof of the tracer's own edge test (tests/sun.rs): its edge, seen from the
    // plate's middle, cuts the disk along a chord α/2 from the centre, so the sun keeps
    // 1 − (R² acos(d/R) − d √(R² − d²))/(πR²) at d = R/2: 1 − (π/3 − √3/4)/π = 0.80450 of
    // its disk (uniform in solid angle: the visible fraction counts rays, no cosine).
    let a = SUN_ANGULAR_RADIUS_DEG.to_radians();
    let x_e = 10.0 * (ZENITH_DEG.to_radians() + a / 2.0).tan();
    let roof = plate([x_e, -500.0], [x_e + 500.0, 500.0], 11.0);
    let scene = raw_scene(&[
        (&plate([-20.0, -20.0], [20.0, 20.0], 1.0), 1, T_K),
        (&roof, 1, T_K),
    ]);
    let materials = grey_materials(&[(1, 0.9, 0.0)]);
    let camera = Camera::from_view(&View::Legacy {
        position_m: [0.0, 0.0, 100.0],
        pixels: [1, 1],
        omega_phi_kappa_deg: [0.0, 0.0, 0.0],
        fov_deg: [1e-3, 1e-3],
        gain_dc_per_k: None,
    })
    .unwrap();
    let kept = 1.0 - (std::f64::consts::FRAC_PI_3 - 3f64.sqrt() / 4.0) / std::f64::consts::PI;
    let day = lit(&scene, &materials, Vacuum::default(), 16384);
    let cos_z = ZENITH_DEG.to_radians().cos();
    for seed in 0..3 {
        let options = TraceOptions {
            seed,
            ..TraceOptions::default()
        };
        let s = day.probe(&camera, &options, 0, 0).unwrap();
        // 128 × 128 strata: the chord crosses about 2·128 of them, each off by at most
        // 1/16384, at random: σ ≈ √256·0.5/16384 = 5e-4; 2e-3 is four of it.
        assert!(
            (s.sun_visible_fraction - kept).abs() < 2e-3,
            "seed {seed}: {} vs {kept}",
            s.sun_visible_fraction
        );
        // The irradiance is the visible part weighted by its cosines, within cos(θ ± α).
        let ratio = s.solar_irradiance_w_m2 / (E_N * cos_z * kept);
        assert!((ratio - 1.0).abs() < 4e-3, "{ratio}");
    }
}

#[test]
fn the_terrain_has_the_flat_unshadowed_sun_and_the_sky_none() {
    let mut scene = raw_scene(&[(&plate([-1.0, -1.0], [1.0, 1.0], 1.0), 1, T_K)]);
    scene.terrain.emissivity = 0.85;
    let materials = grey_materials(&[(1, 0.9, 0.0)]);
    let day = lit(&scene, &materials, GREY_AIR, 1);
    let s = day
        .probe(
            &looking_down([50.0, 0.0, 100.0], 3),
            &TraceOptions::default(),
            1,
            1,
        )
        .unwrap();
    let e = E_N * ZENITH_DEG.to_radians().cos();
    let reflected = 0.15 * e / std::f64::consts::PI;
    assert!(close(s.solar_irradiance_w_m2, e, 1e-12), "{s}");
    assert_eq!(s.sun_visible_fraction, 1.0);
    assert!(close(s.reflected_solar_w_m2_sr, reflected, 1e-12), "{s}");
    assert!(
        close(s.sun_share, TAU * reflected / s.radiance_w_m2_sr, 1e-12),
        "{s}"
    );
    // Straight up: the sky, which holds no sunlight in this model.
    let up = Camera::from_view(&View::LookAt {
        position_m: [50.0, 0.0, 100.0],
        target_m: [50.0, 0.0, 200.0],
        up: [0.0, 1.0, 0.0],
        pixels: [1, 1],
        fov_deg: [1.0, 1.0],
        gain_dc_per_k: None,
    })
    .unwrap();
    let s = day.probe(&up, &TraceOptions::default(), 0, 0).unwrap();
    assert_eq!(s.sun_share, 0.0);
    assert!(s.solar_irradiance_w_m2.is_nan() && s.reflected_solar_w_m2_sr.is_nan());
}

#[test]
fn a_mirror_reflecting_a_sunlit_plate_carries_its_sunlight() {
    // A horizontal mirror (ε_m, wholly specular) seen from above at 45°: its reflection ray
    // meets a vertical Lambertian wall (ε_w) facing it and lit by a sun behind the mirror's
    // viewer... placed so that the sun shines on the wall's face: the mirror's reflected
    // sunlight is r_m times the wall's r_w·E_n·cos θ_w/π, and the mirror itself, whose
    // disk reflection misses the camera, gets E_n·cos θ_z (its truth-only shadow ray).
    let (eps_m, eps_w) = (0.1, 0.8);
    let mirror = plate([-5.0, -5.0], [5.0, 5.0], 0.0);
    // The wall at x = −20 facing +x (toward the sun, which stands in +x).
    let wall: Mesh = (
        vec![
            [-20.0, -50.0, -50.0],
            [-20.0, 50.0, -50.0],
            [-20.0, 50.0, 100.0],
            [-20.0, -50.0, 100.0],
        ],
        vec![[0, 2, 1], [0, 3, 2]],
    );
    let scene = raw_scene(&[(&mirror, 1, T_K), (&wall, 2, T_K)]);
    let materials = grey_materials(&[(1, eps_m, 1.0), (2, eps_w, 0.0)]);
    // The camera at +x, 45° up, looking at the mirror's centre: the reflection goes to −x
    // and up at 45°, meeting the wall at height 20 m.
    let camera = Camera::from_view(&View::LookAt {
        position_m: [10.0, 0.0, 10.0],
        target_m: [0.0, 0.0, 0.0],
        up: [0.0, 0.0, 1.0],
        pixels: [1, 1],
        fov_deg: [1e-3, 1e-3],
        gain_dc_per_k: None,
    })
    .unwrap();
    let z = ZENITH_DEG.to_radians();
    for rays in [1, 16] {
        let day = lit(&scene, &materials, Vacuum::default(), rays);
        let s = day.probe(&camera, &TraceOptions::default(), 0, 0).unwrap();
        let wall_solar = (1.0 - eps_w) * E_N * z.sin() / std::f64::consts::PI;
        let rel = if rays == 1 { 1e-12 } else { 1e-2 };
        assert!(
            close(s.reflected_solar_w_m2_sr, (1.0 - eps_m) * wall_solar, rel),
            "{rays}: {s}"
        );
        assert!(close(s.solar_irradiance_w_m2, E_N * z.cos(), rel), "{s}");
        assert_eq!(s.sun_visible_fraction, 1.0);
    }
}

/// The radiance and every truth vector of two frames alike, bit for bit.
fn same(a: &Frame, b: &Frame) -> bool {
    let bits = |f: &Frame| {
        f.radiance_w_m2_sr
            .iter()
            .map(|l| l.to_bits())
            .collect::<Vec<_>>()
    };
    bits(a) == bits(b)
        && format!("{:?}", a.truth) == format!("{:?}", b.truth)
        && format!("{:?}", a.sun) == format!("{:?}", b.sun)
}

fn busy_scene() -> (RawScene, MaterialLibrary, Camera) {
    // A box on a plate, a half-mirror plate, a pure mirror: every kind of node.
    let scene = raw_scene(&[
        (&plate([-20.0, -20.0], [20.0, 20.0], 1.0), 1, T_K),
        (&box_mesh([-2.0, -2.0, 1.0], [2.0, 2.0, 5.0]), 2, 320.0),
        (&plate([4.0, 4.0], [10.0, 10.0], 1.5), 3, 310.0),
    ]);
    let materials = grey_materials(&[(1, 0.9, 0.3), (2, 0.8, 0.0), (3, 0.1, 1.0)]);
    let camera = Camera::from_view(&View::LookAt {
        position_m: [30.0, 20.0, 25.0],
        target_m: [0.0, 0.0, 2.0],
        up: [0.0, 0.0, 1.0],
        pixels: [32, 32],
        fov_deg: [50.0, 50.0],
        gain_dc_per_k: None,
    })
    .unwrap();
    (scene, materials, camera)
}

#[test]
fn sun_truth_does_not_depend_on_the_thread_count_and_does_not_change_the_radiance() {
    let (scene, materials, camera) = busy_scene();
    let options = TraceOptions {
        sky_view_rays: 4,
        supersampling: 2,
        ..TraceOptions::default()
    };
    let day = lit(&scene, &materials, GREY_AIR, 9);
    let render = |threads, options: &TraceOptions| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| day.render(&camera, options, &|_| {}).unwrap())
    };
    let one = render(1, &options);
    assert_eq!(one.sun.len(), 32 * 32);
    assert!(same(&one, &render(3, &options)));
    // The mirror's truth-only shadow rays draw from their own stream: without truth, the
    // radiance is the same bit for bit.
    let bare = render(
        2,
        &TraceOptions {
            truth: false,
            ..options
        },
    );
    assert!(bare.sun.is_empty() && bare.truth.is_empty());
    let bits = |f: &Frame| {
        f.radiance_w_m2_sr
            .iter()
            .map(|l| l.to_bits())
            .collect::<Vec<_>>()
    };
    assert_eq!(bits(&bare), bits(&one));
    // Every value in range.
    for p in &one.sun {
        let v = p.sun_visible_fraction;
        assert!(v.is_nan() || (0.0..=1.0).contains(&v), "{p:?}");
        assert!((0.0..=1.0).contains(&p.sun_share), "{p:?}");
    }
}

#[test]
fn a_tile_and_adaptive_supersampling_keep_the_whole_frames_sun_truth() {
    let (scene, materials, camera) = busy_scene();
    let day = lit(&scene, &materials, GREY_AIR, 4);
    for options in [
        TraceOptions::default(),
        TraceOptions {
            supersampling: 2,
            adaptive_threshold_k: Some(0.5),
            ..TraceOptions::default()
        },
    ] {
        let whole = day.render(&camera, &options, &|_| {}).unwrap();
        let tile = Tile {
            x: 5,
            y: 7,
            width: 11,
            height: 9,
        };
        let part = day.render_tile(&camera, &options, tile, &|_| {}).unwrap();
        assert_eq!(part.sun.len(), 11 * 9);
        for r in 0..9 {
            for c in 0..11 {
                let w = whole.sun[(7 + r) * 32 + 5 + c];
                let p = part.sun[r * 11 + c];
                assert_eq!(format!("{w:?}"), format!("{p:?}"));
            }
        }
    }
}

#[test]
fn a_night_frame_keeps_no_sun_layers() {
    let (scene, materials, camera) = busy_scene();
    let night = Tracer::new(&scene, &materials, TotalRadiance, GREY_AIR).unwrap();
    let frame = night
        .render(&camera, &TraceOptions::default(), &|_| {})
        .unwrap();
    assert!(frame.sun.is_empty());
    for layer in Layer::SUN {
        assert!(frame.truth_layer(layer).is_none());
    }
    let s = night
        .probe(&camera, &TraceOptions::default(), 16, 16)
        .unwrap();
    assert!(s.sun_share.is_nan() && s.solar_irradiance_w_m2.is_nan());
}
