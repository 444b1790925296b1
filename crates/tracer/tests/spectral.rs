//! The radiance equation summed over sub-bands against a hand computation: a grey plate
//! under an atmosphere that differs from sub-band to sub-band, the band-integrated truth
//! terms, material emissivities per sub-band, and the sky and terrain misses.

use irsig_atmosphere::PathTerms;
use irsig_model::View;
use irsig_radiometry::{Band, EmissivityTable};
use irsig_tracer::testing::{grey_materials, ground_quad, raw_scene};
use irsig_tracer::{Atmosphere, Camera, Event, PathTermsMode, SubBand, TraceOptions, Tracer};

/// An atmosphere in closed form: τ = exp(−k·range), path radiance (1 − τ)·L_air, a uniform
/// sky.
#[derive(Debug, Clone, Copy)]
struct Air {
    per_km: f64,
    l_air: f64,
    sky: f64,
}

impl Atmosphere for Air {
    fn path(&self, _: f64, _: f64, range_m: f64) -> PathTerms {
        let t = (-self.per_km * range_m / 1000.0).exp();
        PathTerms {
            transmission: t,
            path_radiance_w_m2_sr: (1.0 - t) * self.l_air,
        }
    }
    fn sky_radiance(&self, _: f64, _: f64) -> f64 {
        self.sky
    }
    fn sky_hemispheric(&self, _: f64) -> f64 {
        self.sky
    }
}

const EDGES_UM: [f64; 4] = [8.0, 10.0, 12.0, 14.0];
const AIRS: [Air; 3] = [
    Air {
        per_km: 0.3,
        l_air: 12.0,
        sky: 9.0,
    },
    Air {
        per_km: 0.05,
        l_air: 20.0,
        sky: 3.0,
    },
    Air {
        per_km: 0.2,
        l_air: 15.0,
        sky: 6.0,
    },
];

fn sub_bands(emissivity: Option<[f64; 3]>) -> Vec<SubBand<Band, Air>> {
    (0..3)
        .map(|k| SubBand {
            band: Band::new(EDGES_UM[k], EDGES_UM[k + 1]).unwrap(),
            atmosphere: AIRS[k],
            emissivity: emissivity
                .map(|e| vec![EmissivityTable::new(vec![0.0, 90.0], vec![e[k], e[k]]).unwrap()]),
        })
        .collect()
}

fn plate_tracer(emissivity: Option<[f64; 3]>) -> Tracer<Band, Air> {
    let plate = ground_quad([-10.0, -10.0], [10.0, 10.0], 0.0);
    let scene = raw_scene(&[(&plate, 1, 300.0)]);
    let materials = grey_materials(&[(1, 0.9, 0.0)]);
    Tracer::with_sub_bands(&scene, &materials, Band::default(), sub_bands(emissivity)).unwrap()
}

fn camera(target: [f64; 3]) -> Camera {
    Camera::from_view(&View::LookAt {
        position_m: [0.0, 0.0, 1000.0],
        target_m: target,
        up: [0.0, 1.0, 0.0],
        pixels: [1, 1],
        fov_deg: [0.01, 0.01],
        gain_dc_per_k: None,
    })
    .unwrap()
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * b.abs()
}

#[test]
fn a_grey_plate_is_the_sum_of_its_sub_bands() {
    let tracer = plate_tracer(None);
    assert_eq!(tracer.sub_bands(), 3);
    let s = tracer
        .probe(&camera([0.0, 0.0, 0.0]), &TraceOptions::default(), 0, 0)
        .unwrap();
    assert_eq!(s.event, Event::Diffuse);
    let mut expected = 0.0;
    let (mut leaving, mut path_radiance, mut blackbody) = (0.0, 0.0, 0.0);
    for k in 0..3 {
        let l_t = Band::new(EDGES_UM[k], EDGES_UM[k + 1])
            .unwrap()
            .radiance(300.0);
        let air = AIRS[k];
        let t = (-air.per_km).exp(); // 1 km straight down
        let l_s = 0.9 * l_t + 0.1 * air.sky;
        expected += t * l_s + (1.0 - t) * air.l_air;
        leaving += l_s;
        path_radiance += (1.0 - t) * air.l_air;
        blackbody += l_t;
    }
    assert!(
        close(s.radiance_w_m2_sr, expected),
        "{s}\nexpected {expected}"
    );
    // The band-integrated terms: radiances add; ε and τ are the weighted means that keep
    // the equation true.
    assert!(close(s.blackbody_w_m2_sr, blackbody), "{s}");
    assert!(
        close(s.blackbody_w_m2_sr, Band::default().radiance(300.0)),
        "{s}"
    );
    assert!(close(s.surface_leaving_w_m2_sr, leaving), "{s}");
    assert!(close(s.path_radiance_w_m2_sr, path_radiance), "{s}");
    assert!((s.emissivity - 0.9).abs() < 1e-12, "{s}");
    assert!(close(
        s.transmission * s.surface_leaving_w_m2_sr + s.path_radiance_w_m2_sr,
        s.radiance_w_m2_sr
    ));
    // A one-band τ of the mean would not do: the sub-bands' τ differ by a factor 1.3.
    let tau_of_mean: f64 = AIRS.iter().map(|a| (-a.per_km).exp()).sum::<f64>() / 3.0;
    assert!((s.transmission - tau_of_mean).abs() > 1e-3, "{s}");
}

#[test]
fn each_sub_band_uses_its_own_emissivity() {
    let eps = [0.5, 0.9, 0.7];
    let tracer = plate_tracer(Some(eps));
    let s = tracer
        .probe(&camera([0.0, 0.0, 0.0]), &TraceOptions::default(), 0, 0)
        .unwrap();
    let (mut expected, mut emitted, mut blackbody) = (0.0, 0.0, 0.0);
    for k in 0..3 {
        let l_t = Band::new(EDGES_UM[k], EDGES_UM[k + 1])
            .unwrap()
            .radiance(300.0);
        let air = AIRS[k];
        let t = (-air.per_km).exp();
        expected += t * (eps[k] * l_t + (1.0 - eps[k]) * air.sky) + (1.0 - t) * air.l_air;
        emitted += eps[k] * l_t;
        blackbody += l_t;
    }
    assert!(close(s.radiance_w_m2_sr, expected), "{s}");
    assert!(close(s.emissivity, emitted / blackbody), "{s}");
    // A list of tables that does not match the library is refused.
    let mut bands = sub_bands(Some(eps));
    bands[1].emissivity = Some(Vec::new());
    let plate = ground_quad([-10.0, -10.0], [10.0, 10.0], 0.0);
    let scene = raw_scene(&[(&plate, 1, 300.0)]);
    let materials = grey_materials(&[(1, 0.9, 0.0)]);
    assert!(Tracer::with_sub_bands(&scene, &materials, Band::default(), bands).is_err());
    assert!(
        Tracer::<Band, Air>::with_sub_bands(&scene, &materials, Band::default(), vec![]).is_err()
    );
}

#[test]
fn misses_and_tabulated_paths_are_summed_too() {
    let tracer = plate_tracer(None);
    // Straight up from 1 km: the sky of every sub-band.
    let up = Camera::from_view(&View::LookAt {
        position_m: [0.0, 0.0, 1000.0],
        target_m: [0.0, 0.0, 2000.0],
        up: [0.0, 1.0, 0.0],
        pixels: [1, 1],
        fov_deg: [0.01, 0.01],
        gain_dc_per_k: None,
    })
    .unwrap();
    let s = tracer.probe(&up, &TraceOptions::default(), 0, 0).unwrap();
    assert_eq!(s.event, Event::Sky);
    assert!(close(s.radiance_w_m2_sr, 9.0 + 3.0 + 6.0), "{s}");
    // 45° down, away from the plate: the scene's (default) terrain, through the path to a
    // flat ground 1414 m away.
    let s = tracer
        .probe(&camera([1000.0, 0.0, 0.0]), &TraceOptions::default(), 0, 0)
        .unwrap();
    assert_eq!(s.event, Event::Terrain, "{s}");
    let terrain = irsig_model::RawScene::default().terrain;
    let mut expected = 0.0;
    for k in 0..3 {
        let l_t = Band::new(EDGES_UM[k], EDGES_UM[k + 1])
            .unwrap()
            .radiance(terrain.temperature_k);
        let air = AIRS[k];
        let t = (-air.per_km * 2.0_f64.sqrt()).exp();
        let leaving = terrain.emissivity * l_t + (1.0 - terrain.emissivity) * air.sky;
        expected += t * leaving + (1.0 - t) * air.l_air;
    }
    assert!(
        (s.radiance_w_m2_sr - expected).abs() < 1e-9 * expected,
        "{s}"
    );
    // Tabulated path terms read every sub-band's own table.
    let tabulated = plate_tracer(None).with_path_terms(PathTermsMode::Tabulated);
    let exact = tracer
        .probe(&camera([3.0, 2.0, 0.0]), &TraceOptions::default(), 0, 0)
        .unwrap();
    let table = tabulated
        .probe(&camera([3.0, 2.0, 0.0]), &TraceOptions::default(), 0, 0)
        .unwrap();
    assert!(
        (exact.radiance_w_m2_sr - table.radiance_w_m2_sr).abs() < 1e-6 * exact.radiance_w_m2_sr,
        "{exact}\n{table}"
    );
}
