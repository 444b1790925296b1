//! The sunlight's own view-path transmittance (`SunBeam::with_path_transmission`): through
//! an air of grey transmittance τ and no emission of its own, a Lambertian plate's sunlight
//! reaches the sensor through the beam's `τ_sun(τ)` and its emission through τ, by hand;
//! without the pairs both go through τ, as before; the terrain beyond the scene likewise;
//! and the sun's truth (`sun_share`) says the same.

use crate::air::FnAir;
use irsig_atmosphere::PathTerms;
use irsig_model::{MaterialLibrary, RawScene, View};
use irsig_radiometry::{BandModel, TotalRadiance};
use irsig_tracer::testing::{Mesh, grey_materials, ground_quad, raw_scene};
use irsig_tracer::{Camera, DVec3, Sun, SunBeam, TraceOptions, Tracer};

/// Direct normal irradiance of the test sun, W m⁻².
const E_N: f64 = 800.0;
/// The sun's zenith angle, degrees.
const ZENITH_DEG: f64 = 30.0;
const T_K: f64 = 300.0;
/// The air's transmittance of every path, and the sunlight's of the same paths.
const TAU: f64 = 0.6;
const TAU_SUN: f64 = 0.8;

/// An air of transmittance [`TAU`] on every path that emits nothing, under a black sky.
const GREY: FnAir = FnAir {
    path: |_, _, _| PathTerms {
        transmission: TAU,
        path_radiance_w_m2_sr: 0.0,
    },
    sky: |_, _| 0.0,
    hemispheric: |_| 0.0,
};

fn sun(pairs: Option<Vec<[f64; 2]>>) -> Sun {
    let z = ZENITH_DEG.to_radians();
    let beam = SunBeam::uniform(E_N).unwrap();
    let beam = match pairs {
        Some(p) => beam.with_path_transmission(p).unwrap(),
        None => beam,
    };
    Sun::new(DVec3::new(z.sin(), 0.0, z.cos()), vec![beam])
}

fn tracer(scene: &RawScene, materials: &MaterialLibrary) -> Tracer<TotalRadiance, FnAir> {
    Tracer::new(scene, materials, TotalRadiance, GREY).unwrap()
}

fn plate(z: f64) -> Mesh {
    ground_quad([-20.0, -20.0], [20.0, 20.0], z)
}

fn looking_down(above: [f64; 3]) -> Camera {
    Camera::from_view(&View::Legacy {
        position_m: above,
        pixels: [3, 3],
        omega_phi_kappa_deg: [0.0, 0.0, 0.0],
        fov_deg: [1.0, 1.0],
        gain_dc_per_k: None,
    })
    .unwrap()
}

#[test]
fn a_plates_sunlight_goes_through_the_sunlights_own_transmittance() {
    const EPS: f64 = 0.3;
    let scene = raw_scene(&[(&plate(1.0), 1, T_K)]);
    let materials = grey_materials(&[(1, EPS, 0.0)]);
    let camera = looking_down([0.0, 0.0, 100.0]);
    let options = TraceOptions::default();
    let emitted = TAU * EPS * TotalRadiance.radiance(T_K);
    let sunlight = (1.0 - EPS) * E_N * ZENITH_DEG.to_radians().cos() / std::f64::consts::PI;
    // τ = 0.6 lies between the pairs (0.5, 0.7) and (0.7, 0.9): τ_sun = 0.8 by hand.
    let pairs = vec![[0.2, 0.3], [0.5, 0.7], [0.7, 0.9]];
    for (given, tau_sun) in [(None, TAU), (Some(pairs), TAU_SUN)] {
        let frame = tracer(&scene, &materials)
            .with_sun(Some(sun(given)))
            .unwrap()
            .render(&camera, &options, &|_| {})
            .unwrap();
        let expected = emitted + tau_sun * sunlight;
        for (p, &l) in frame.radiance_w_m2_sr.iter().enumerate() {
            assert!(
                (l / expected - 1.0).abs() < 1e-12,
                "τ_sun {tau_sun}, pixel {p}: {l} against {expected} by hand"
            );
            // With one sub-band the truth's τ is the path's, and the sun's share holds the
            // sunlight's own.
            let t = &frame.truth[p];
            assert!((f64::from(t.transmission) - TAU).abs() < 1e-7);
            let share = f64::from(frame.sun[p].sun_share);
            assert!((share - tau_sun * sunlight / l).abs() < 1e-6, "{share}");
        }
    }
}

#[test]
fn the_terrains_sunlight_goes_through_the_sunlights_own_transmittance() {
    let mut scene = raw_scene(&[(&plate(1.0), 1, T_K)]);
    scene.terrain.emissivity = 0.85;
    let materials = grey_materials(&[(1, 0.9, 0.0)]);
    // Straight down 50 m beside the plate: the terrain.
    let camera = looking_down([50.0, 0.0, 100.0]);
    let options = TraceOptions::default();
    let night = tracer(&scene, &materials)
        .render(&camera, &options, &|_| {})
        .unwrap();
    let day = tracer(&scene, &materials)
        .with_sun(Some(sun(Some(vec![[TAU, TAU_SUN]]))))
        .unwrap()
        .render(&camera, &options, &|_| {})
        .unwrap();
    let expected =
        TAU_SUN * (1.0 - 0.85) * E_N * ZENITH_DEG.to_radians().cos() / std::f64::consts::PI;
    for (d, n) in day.radiance_w_m2_sr.iter().zip(&night.radiance_w_m2_sr) {
        assert!(
            ((d - n) / expected - 1.0).abs() < 1e-9,
            "{} vs {expected}",
            d - n
        );
    }
}

#[test]
fn the_sunlights_transmittance_runs_from_dark_to_clear_between_its_pairs() {
    let beam = SunBeam::uniform(1.0)
        .unwrap()
        .with_path_transmission(vec![[0.2, 0.4], [0.6, 0.8]])
        .unwrap();
    // (0, 0) and (1, 1) close the ends; linear in τ between.
    for (tau, by_hand) in [
        (0.0, 0.0),
        (0.1, 0.2),
        (0.2, 0.4),
        (0.4, 0.6),
        (0.6, 0.8),
        (0.8, 0.9),
        (1.0, 1.0),
    ] {
        let got = beam.sunlit_transmission(tau);
        assert!(
            (got - by_hand).abs() < 1e-12,
            "τ {tau}: {got} against {by_hand}"
        );
    }
    // Without pairs, and outside 0-1 (never a path's), τ itself.
    let plain = SunBeam::uniform(1.0).unwrap();
    assert_eq!(plain.sunlit_transmission(0.37).to_bits(), 0.37f64.to_bits());
    assert!(beam.sunlit_transmission(f64::NAN).is_nan());
    // Pairs out of range or out of order are refused.
    for bad in [
        vec![[0.5, 1.2]],
        vec![[-0.1, 0.0]],
        vec![[0.5, f64::NAN]],
        vec![[0.5, 0.6], [0.5, 0.7]],
        vec![[0.6, 0.6], [0.5, 0.7]],
    ] {
        assert!(
            SunBeam::uniform(1.0)
                .unwrap()
                .with_path_transmission(bad.clone())
                .is_err(),
            "{bad:?}"
        );
    }
}
