//! The terrain background near the horizon against the flat ground it stands for: a ray
//! that misses every facet but meets the Earth must get the path terms of a slant path to
//! the ground at its nadir angle, which is what LOWTRAN7 computes and what a facet lying at
//! z = 0 on the same ray gets. (Passing the curved-Earth range, 10 % longer at 87° from
//! 3 km, to the plane-parallel models gave τ 0.0821 where LOWTRAN7 gives 0.1099: −1.2 K.)

use irsig_atmosphere::{AtmosphereModel, ModelKind, PrecomputedAtmosphere, builtin};
use irsig_model::View;
use irsig_radiometry::Band;
use irsig_tracer::testing::{grey_materials, ground_quad, raw_scene};
use irsig_tracer::{Camera, Event, Sample, TraceOptions, Tracer};

const ALTITUDE_M: f64 = 3000.0;
const NADIR_DEG: f64 = 87.0;

/// The probe of the one pixel looking `NADIR_DEG` from nadir from `ALTITUDE_M`, over a
/// ground quad centred `ground_at_m` along the view (far off the ray when it should miss).
fn probe(atmosphere: &str, ground_at_m: f64) -> Sample {
    let horizontal = ALTITUDE_M * NADIR_DEG.to_radians().tan();
    let quad = ground_quad(
        [-200.0, ground_at_m - 200.0],
        [200.0, ground_at_m + 200.0],
        0.0,
    );
    let scene = raw_scene(&[(&quad, 1, 300.0)]);
    let materials = grey_materials(&[(1, 0.95, 0.0)]);
    let model = AtmosphereModel::new(&builtin(atmosphere).unwrap(), ModelKind::Table).unwrap();
    let air = PrecomputedAtmosphere::new(model, ALTITUDE_M);
    let tracer = Tracer::new(&scene, &materials, Band::default(), air).unwrap();
    let camera = Camera::from_view(&View::LookAt {
        position_m: [0.0, 0.0, ALTITUDE_M],
        target_m: [0.0, horizontal, 0.0],
        up: [0.0, 0.0, 1.0],
        pixels: [1, 1],
        fov_deg: [1e-4, 1e-4],
        gain_dc_per_k: None,
    })
    .unwrap();
    tracer
        .probe(&camera, &TraceOptions::default(), 0, 0)
        .unwrap()
}

#[test]
fn terrain_near_the_horizon_gets_the_flat_grounds_slant_path() {
    let horizontal = ALTITUDE_M * NADIR_DEG.to_radians().tan();
    let flat_range = ALTITUDE_M / NADIR_DEG.to_radians().cos();
    for atmosphere in ["us-std-1976", "midlat-winter"] {
        let facet = probe(atmosphere, horizontal);
        assert_eq!(facet.event, Event::Diffuse, "{atmosphere}: {facet}");
        assert!((facet.range_m - flat_range).abs() < 1.0, "{facet}");
        // The quad 60 km off to the side: the ray misses it and meets the terrain.
        let terrain = probe(atmosphere, -60_000.0);
        assert_eq!(terrain.event, Event::Terrain, "{atmosphere}: {terrain}");
        // The curved ground is farther than the flat one: 63.3 km against 57.3 km.
        assert!(terrain.range_m > flat_range + 5000.0, "{terrain}");
        assert!(
            (terrain.transmission - facet.transmission).abs() < 1e-9,
            "{atmosphere}: terrain τ {} against the flat facet's {}",
            terrain.transmission,
            facet.transmission
        );
        assert!(
            (terrain.path_radiance_w_m2_sr - facet.path_radiance_w_m2_sr).abs() < 1e-9,
            "{atmosphere}"
        );
    }
    // LOWTRAN7's slant path from 3 km at 87° to the ground, US Standard 1976: τ 0.1099.
    let t = probe("us-std-1976", -60_000.0).transmission;
    assert!((t - 0.1099).abs() < 1e-3, "{t}");
}
