//! The terrain background near the horizon against the flat ground it stands for: a ray
//! that misses every facet but meets the Earth must get the path terms of a slant path to
//! the ground at its nadir angle, which is what LOWTRAN7 computes and what a facet lying at
//! z = 0 on the same ray gets. (Passing the curved-Earth range, 10 % longer at 87° from
//! 3 km, to the plane-parallel models gave τ 0.0821 where LOWTRAN7 gives 0.1099: −1.2 K.)
//! And a terrain of a material: at night it has the radiance a ground plane of that
//! material has at the same angle and temperature, so that the plane's edge shows no seam.

use irsig_atmosphere::{AtmosphereModel, ModelKind, PrecomputedAtmosphere, builtin};
use irsig_model::{Material, MaterialId, MaterialLibrary, Terrain, View};
use irsig_radiometry::Band;
use irsig_tracer::testing::{grey_materials, ground_quad, raw_scene};
use irsig_tracer::{Camera, Event, Sample, TraceOptions, Tracer, Vacuum};

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

/// Grass with an angular table (falling toward grazing incidence, as measured grass does)
/// and a small specular share, so that both the emission's angle and the mirror term
/// count. Illustrative values, not a measurement.
fn grass(id: u16) -> Material {
    Material {
        id: MaterialId(id),
        name: "grass".into(),
        emissivity: vec![
            (0.0, 0.98),
            (40.0, 0.975),
            (60.0, 0.96),
            (75.0, 0.92),
            (85.0, 0.8),
            (90.0, 0.0),
        ],
        specular_fraction: 0.1,
        source: "terrain test".into(),
        band_um: None,
        spectral: None,
        rms_slope: None,
        thermal: None,
        texture: None,
        maps: None,
    }
}

/// The two pixels of a camera 50 m up looking 70° from nadir along +y, 10⁻⁵° wide: one on
/// either side of a grass plane's edge, which runs along the view below the camera (x = 0,
/// the plane at x < 0). Both rays meet the ground at the same nadir angle (to 10⁻¹⁴ rad).
/// The terrain beyond the plane is at the plane's temperature, of `terrain`.
fn across_the_edge(terrain: Terrain) -> [Sample; 2] {
    const ALT_M: f64 = 50.0;
    let along = ALT_M * 70f64.to_radians().tan();
    let plane = ground_quad([-500.0, -500.0], [0.0, 2000.0], 0.0);
    let mut scene = raw_scene(&[(&plane, 2, 285.0)]);
    scene.terrain = terrain;
    let materials = MaterialLibrary {
        materials: vec![grass(2)],
    };
    let model = AtmosphereModel::new(&builtin("us-std-1976").unwrap(), ModelKind::Table).unwrap();
    let air = PrecomputedAtmosphere::new(model, ALT_M);
    let tracer = Tracer::new(&scene, &materials, Band::default(), air).unwrap();
    let camera = Camera::from_view(&View::LookAt {
        position_m: [0.0, 0.0, ALT_M],
        target_m: [0.0, along, 0.0],
        up: [0.0, 0.0, 1.0],
        pixels: [2, 1],
        fov_deg: [1e-5, 1e-5],
        gain_dc_per_k: None,
    })
    .unwrap();
    [0, 1].map(|c| {
        tracer
            .probe(&camera, &TraceOptions::default(), c, 0)
            .unwrap()
    })
}

/// The plane's pixel and the terrain's, in that order.
fn plane_and_terrain(samples: [Sample; 2]) -> (Sample, Sample) {
    let [a, b] = samples;
    let (plane, terrain) = if a.event == Event::Terrain {
        (b, a)
    } else {
        (a, b)
    };
    assert_eq!(terrain.event, Event::Terrain, "{terrain}");
    assert_eq!(plane.primary_material, 2, "{plane}");
    (plane, terrain)
}

#[test]
fn a_grass_terrain_meets_a_grass_plane_without_a_seam() {
    // The terrain of the plane's material: the same radiance at the same angle.
    let (plane, terrain) = plane_and_terrain(across_the_edge(Terrain {
        temperature_k: 285.0,
        emissivity: 1.0,
        material: Some(MaterialId(2)),
    }));
    let relative = |a: f64, b: f64| (a - b).abs() / b;
    assert!(
        relative(terrain.radiance_w_m2_sr, plane.radiance_w_m2_sr) < 1e-6,
        "terrain {} against the plane's {} W m⁻² sr⁻¹",
        terrain.radiance_w_m2_sr,
        plane.radiance_w_m2_sr
    );
    // ε(70°) between the table's 60° and 75°: 0.96 − 0.04·10/15.
    assert!((terrain.emissivity - (0.96 - 0.04 * 10.0 / 15.0)).abs() < 1e-6);
    assert!((terrain.emissivity - plane.emissivity).abs() < 1e-9);

    // The constant the terrain had before, grass at normal incidence: a seam of several
    // per cent of the radiance (ε 0.98 against 0.933 at 70°).
    let (plane, terrain) = plane_and_terrain(across_the_edge(Terrain {
        temperature_k: 285.0,
        emissivity: 0.98,
        material: None,
    }));
    assert!(
        relative(terrain.radiance_w_m2_sr, plane.radiance_w_m2_sr) > 0.01,
        "terrain {} against the plane's {}",
        terrain.radiance_w_m2_sr,
        plane.radiance_w_m2_sr
    );
}

#[test]
fn a_material_terrain_at_60_degrees_by_hand() {
    // In a vacuum under a uniform sky of 2 W m⁻² sr⁻¹, a terrain at 300 K of a material
    // with ε(60°) = 0.94 (a table point) and specular share 0.25, seen 60° from nadir:
    // L = ε·L_T + (1 − ε)·(s·L_sky + (1 − s)·L_sky) = 0.94·L_T + 0.06·2.
    // L_T, 8–14 µm at 300 K: Planck's law integrated by Simpson's rule over 2·10⁵
    // intervals (an independent script, CODATA 2018 constants): 54.93346 W m⁻² sr⁻¹.
    let want = 0.94 * 54.933_461 + 0.06 * 2.0;
    let mut material = grass(7);
    material.emissivity = vec![(0.0, 0.98), (60.0, 0.94), (90.0, 0.0)];
    material.specular_fraction = 0.25;
    let materials = MaterialLibrary {
        materials: vec![material],
    };
    // A quad far off the view, so that the scene has a facet.
    let quad = ground_quad([1000.0, 1000.0], [1001.0, 1001.0], 0.0);
    let mut scene = raw_scene(&[(&quad, 7, 300.0)]);
    scene.terrain = Terrain {
        temperature_k: 300.0,
        emissivity: 0.5,
        material: Some(MaterialId(7)),
    };
    let sky = Vacuum {
        sky_radiance_w_m2_sr: 2.0,
    };
    let tracer = Tracer::new(&scene, &materials, Band::default(), sky).unwrap();
    let alt_m = 10.0;
    let camera = Camera::from_view(&View::LookAt {
        position_m: [0.0, 0.0, alt_m],
        target_m: [0.0, -alt_m * 60f64.to_radians().tan(), 0.0],
        up: [0.0, 0.0, 1.0],
        pixels: [1, 1],
        fov_deg: [1e-4, 1e-4],
        gain_dc_per_k: None,
    })
    .unwrap();
    let s = tracer
        .probe(&camera, &TraceOptions::default(), 0, 0)
        .unwrap();
    assert_eq!(s.event, Event::Terrain, "{s}");
    assert!((s.emissivity - 0.94).abs() < 1e-9, "{s}");
    assert!(
        (s.radiance_w_m2_sr - want).abs() < 1e-5 * want,
        "{} against {want} by hand",
        s.radiance_w_m2_sr
    );

    // A material the library does not define is refused, naming it.
    scene.terrain.material = Some(MaterialId(8));
    let e = Tracer::new(&scene, &materials, Band::default(), sky).unwrap_err();
    assert!(e.to_string().contains("terrain's material is 8"), "{e}");
}
