//! The error budget's partial derivatives against finite differences: the probe's
//! ∂L/∂T and ∂L/∂ε of a specular plate mirroring a warm wall under a made-up atmosphere,
//! against re-traced radiances with the temperature and the emissivity nudged.

use crate::air::BUDGET_AIR;
use irsig_model::{MaterialLibrary, RawScene, View};
use irsig_radiometry::Band;
use irsig_tracer::testing::{box_mesh, grey_materials, ground_quad, raw_scene};
use irsig_tracer::{Camera, Sample, TraceOptions, Tracer};

fn scene(plate_k: f64) -> RawScene {
    let plate = ground_quad([-20.0, -20.0], [20.0, 20.0], 0.0);
    let wall = box_mesh([-30.0, 25.0, 0.0], [30.0, 27.0, 40.0]);
    raw_scene(&[(&plate, 1, plate_k), (&wall, 2, 330.0)])
}

fn materials(plate_eps: f64, specular: f64) -> MaterialLibrary {
    grey_materials(&[(1, plate_eps, specular), (2, 0.9, 0.0)])
}

fn probe(scene: &RawScene, materials: &MaterialLibrary) -> Sample {
    let tracer = Tracer::new(scene, materials, Band::default(), BUDGET_AIR).unwrap();
    let camera = Camera::from_view(&View::LookAt {
        position_m: [0.0, -60.0, 30.0],
        target_m: [0.0, 0.0, 0.0],
        up: [0.0, 0.0, 1.0],
        pixels: [1, 1],
        fov_deg: [0.01, 0.01],
        gain_dc_per_k: None,
    })
    .unwrap();
    tracer
        .probe(&camera, &TraceOptions::default(), 0, 0)
        .unwrap()
}

#[test]
fn partials_agree_with_finite_differences() {
    for specular in [0.0, 0.6, 1.0] {
        let s = probe(&scene(300.0), &materials(0.8, specular));
        // A central difference: the radiance is smooth in both.
        let (dt, de) = (0.01, 1e-4);
        let l = |t: f64, e: f64| probe(&scene(t), &materials(e, specular)).radiance_w_m2_sr;
        let by_t = (l(300.0 + dt, 0.8) - l(300.0 - dt, 0.8)) / (2.0 * dt);
        let by_e = (l(300.0, 0.8 + de) - l(300.0, 0.8 - de)) / (2.0 * de);
        assert!(
            (s.temperature_sensitivity / by_t - 1.0).abs() < 1e-6,
            "specular {specular}: dL/dT {} against {by_t}",
            s.temperature_sensitivity
        );
        assert!(
            (s.emissivity_sensitivity / by_e - 1.0).abs() < 1e-6,
            "specular {specular}: dL/deps {} against {by_e}",
            s.emissivity_sensitivity
        );
        // By hand: ∂L/∂T = τ·ε·dL_T/dT.
        let band = Band::default();
        let hand = s.transmission * 0.8 * band.radiance_derivative(300.0);
        assert!(
            (s.temperature_sensitivity / hand - 1.0).abs() < 1e-12,
            "{s}"
        );
    }
}

/// The plate (diffuse) and the wall, both `dt` warmer than 300 and 330 K.
fn nudged(dt: f64) -> RawScene {
    let plate = ground_quad([-20.0, -20.0], [20.0, 20.0], 0.0);
    let wall = box_mesh([-30.0, 25.0, 0.0], [30.0, 27.0, 40.0]);
    raw_scene(&[(&plate, 1, 300.0 + dt), (&wall, 2, 330.0 + dt)])
}

#[test]
fn a_refined_pixels_sensitivity_is_the_mean_of_its_samples() {
    // A coarse view across the plate's far edge and the wall: pixels that straddle it are
    // refined, and their ∂L/∂T must be that of the mean radiance they report (every
    // facet's temperature moved together: each sample's sensitivity is to the facet it
    // met), not their centre ray's.
    let camera = Camera::from_view(&View::LookAt {
        position_m: [0.0, -60.0, 30.0],
        target_m: [0.0, 25.0, 2.0],
        up: [0.0, 0.0, 1.0],
        pixels: [16, 12],
        fov_deg: [20.0, 15.0],
        gain_dc_per_k: None,
    })
    .unwrap();
    let refinement = irsig_tracer::Refinement {
        target_k: 0.05,
        edge_k: 1.0,
        max_side: 64,
        thin_side: 8,
    };
    let frame = |dt: f64| {
        let materials = materials(0.8, 0.0);
        Tracer::new(&nudged(dt), &materials, Band::default(), BUDGET_AIR)
            .unwrap()
            .with_refinement(Some(refinement))
            .unwrap()
            .render(&camera, &TraceOptions::default(), &|_| {})
            .unwrap()
    };
    let dt = 0.01;
    let (base, up, down) = (frame(0.0), frame(dt), frame(-dt));
    let (mut compared, mut mixed) = (0, 0);
    for i in 0..base.radiance_w_m2_sr.len() {
        let s = &base.sampling[i];
        // A refined pixel whose levels were the same in the three renderings (its rays
        // the same), so that the difference is of one estimator.
        if s.rays <= 1 || up.sampling[i].rays != s.rays || down.sampling[i].rays != s.rays {
            continue;
        }
        let by_t = (up.radiance_w_m2_sr[i] - down.radiance_w_m2_sr[i]) / (2.0 * dt);
        let centre = base.truth[i].temperature_sensitivity;
        assert!(
            (f64::from(s.temperature_sensitivity) / by_t - 1.0).abs() < 1e-4,
            "pixel {i}: {} against {by_t} (the centre ray's {centre})",
            s.temperature_sensitivity
        );
        compared += 1;
        // A pixel of plate and wall: its centre ray's sensitivity is one of theirs.
        mixed += usize::from((f64::from(centre) / by_t - 1.0).abs() > 0.05);
    }
    assert!(compared >= 4, "only {compared} refined pixels compared");
    assert!(
        mixed >= 2,
        "only {mixed} of {compared} refined pixels mix plate and wall"
    );
}
