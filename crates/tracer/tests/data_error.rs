//! The atmosphere data's error per pixel on whole frames of a built-in: a frame with no sky
//! and no horizon records its slant rows' residual (plus the little sky its ground
//! reflects), not the sky's, which is ten times larger; a frame of sky records the sky's
//! cell for its altitude and angles; a frame at the horizon records what the last degrees
//! were measured to cost.

use irsig_atmosphere::data_error::DataError;
use irsig_atmosphere::{AtmosphereModel, ModelKind, PrecomputedAtmosphere, builtin};
use irsig_model::View;
use irsig_radiometry::Band;
use irsig_tracer::testing::{grey_materials, ground_quad, raw_scene};
use irsig_tracer::{Camera, Event, Frame, Tile, TraceOptions, Tracer};

/// A frame of 24 × 24 pixels seen from `altitude_m` toward `target_m`, `fov_deg` wide,
/// over a ground quad of emissivity `emissivity` 60 km on a side, in us-std-1976's table
/// model; its data error, the layer and the census, and the frame.
fn traced(
    altitude_m: f64,
    target_m: [f64; 3],
    fov_deg: f64,
    emissivity: f64,
) -> (
    DataError,
    Vec<f32>,
    irsig_model::decision::DataErrorSummary,
    Frame,
) {
    let quad = ground_quad([-30_000.0, -30_000.0], [30_000.0, 30_000.0], 0.0);
    let scene = raw_scene(&[(&quad, 1, 290.0)]);
    let materials = grey_materials(&[(1, emissivity, 0.0)]);
    let model = AtmosphereModel::new(&builtin("us-std-1976").unwrap(), ModelKind::Table).unwrap();
    let data = model.data_error().expect("a built-in records its residual");
    let air = PrecomputedAtmosphere::new(model, altitude_m.max(3000.0));
    let tracer = Tracer::new(&scene, &materials, Band::default(), air).unwrap();
    let camera = Camera::from_view(&View::LookAt {
        position_m: [0.0, 0.0, altitude_m],
        target_m,
        // Looking along the vertical, y is up in the image; else z.
        up: if target_m[0].hypot(target_m[1]) < 1.0 {
            [0.0, 1.0, 0.0]
        } else {
            [0.0, 0.0, 1.0]
        },
        pixels: [24, 24],
        fov_deg: [fov_deg, fov_deg],
        gain_dc_per_k: None,
    })
    .unwrap();
    let options = TraceOptions {
        truth: true,
        ..TraceOptions::default()
    };
    let frame = tracer.render(&camera, &options, &|_| {}).unwrap();
    let whole = Tile::whole(24, 24);
    let layer = tracer.data_error_layer(&data, &camera, whole, &frame.truth);
    let census = tracer.data_error_census(&data, &camera, whole);
    (data, layer, census, frame)
}

#[test]
fn a_sky_free_frame_from_1_7_km_records_the_slant_residual_not_the_skys() {
    let r = builtin("us-std-1976")
        .unwrap()
        .slant
        .unwrap()
        .interpolation_residual
        .unwrap();
    // Straight down, 60° wide: every path within 30° of nadir, no sky, no horizon.
    let (_, layer, census, frame) = traced(1700.0, [0.0, 0.0, 0.0], 60.0, 1.0);
    assert!(frame.truth.iter().all(|t| t.event == Event::Diffuse));
    // A blackbody ground reflects no sky: the near rows' residual alone.
    for &k in &layer {
        assert!((f64::from(k) - r.slant_k).abs() < 1e-6, "{k} K");
    }
    assert!((census.p99_k - r.slant_k).abs() < 1e-6, "{census:?}");
    assert!((census.max_k - r.slant_k).abs() < 1e-6, "{census:?}");
    assert!(
        census.max_k < r.sky_k / 5.0,
        "{census:?} against sky {}",
        r.sky_k
    );
    // A grey ground (ε 0.9) reflects a tenth of the sky, through the path's τ < 1: the
    // sky's record over the hemisphere above the ground, a cell far below the residual.
    let (data, grey, census, frame) = traced(1700.0, [0.0, 0.0, 0.0], 60.0, 0.9);
    let sky = data.hemisphere_sky_k(0.0);
    assert!(sky < r.sky_k / 5.0, "{sky} K against {} K", r.sky_k);
    for (&k, t) in grey.iter().zip(&frame.truth) {
        let expected = r.slant_k + 0.1 * f64::from(t.transmission) * sky;
        assert!(
            (f64::from(k) - expected).abs() < 1e-4,
            "{k} K, {expected} K"
        );
        assert!(f64::from(k) < r.slant_k + 0.1 * sky);
    }
    // The census is the view paths': the reflected sky is the layer's.
    assert!((census.p99_k - r.slant_k).abs() < 1e-6, "{census:?}");
}

#[test]
fn a_frame_of_sky_records_the_skys_cell_not_its_residual() {
    let r = builtin("us-std-1976")
        .unwrap()
        .slant
        .unwrap()
        .interpolation_residual
        .unwrap();
    // Straight up from 100 m, 30° wide: every ray within 22° of the zenith, one cell of
    // the sky's record (0–950 m, 0–60°), a fifth of the residual or less.
    let (data, layer, census, frame) = traced(100.0, [0.0, 0.0, 10_000.0], 30.0, 1.0);
    assert!(frame.truth.iter().all(|t| t.event == Event::Sky));
    let cell = data.sky_k(100.0, 0.0);
    assert!(cell < r.sky_k / 5.0, "{cell} K against {} K", r.sky_k);
    assert!(layer.iter().all(|&k| (f64::from(k) - cell).abs() < 1e-6));
    assert!((census.max_k - cell).abs() < 1e-6, "{census:?}");
    // From 9 km, above the densest rows, the sky's record is larger.
    let (data, high, _, _) = traced(9000.0, [0.0, 0.0, 20_000.0], 30.0, 1.0);
    let cell_high = data.sky_k(9000.0, 0.0);
    assert!(cell_high > 2.0 * cell, "{cell_high} K against {cell} K");
    assert!(
        high.iter()
            .all(|&k| (f64::from(k) - cell_high).abs() < 1e-6)
    );
}

#[test]
fn a_frame_at_the_horizon_records_the_last_degrees_measured_cost() {
    // From 300 m toward the ground 88.75° from nadir (the horizon is at 89.44°), 1° wide:
    // paths from 88.25° to 89.25°, most past the widest row (88°).
    let reach = 300.0 * 88.75_f64.to_radians().tan();
    let (data, layer, census, frame) = traced(300.0, [0.0, reach, 0.0], 1.0, 1.0);
    // The quad, or past its edge the terrain: every path ends at the ground.
    assert!(frame.truth.iter().all(|t| t.event != Event::Sky));
    // us-std-1976 from 300 m: 0.459 K at 88.5°, 2.160 K at 89.25° (docs/accuracy.md).
    let (lo, hi) = layer
        .iter()
        .fold((f32::MAX, 0.0_f32), |(lo, hi), &k| (lo.min(k), hi.max(k)));
    assert!(f64::from(lo) >= 0.459 - 1e-6, "{lo}");
    assert!((f64::from(hi) - 2.160).abs() < 1e-6, "{hi}");
    assert!((census.max_k - 2.160).abs() < 1e-6, "{census:?}");
    // Far above the grazing rows' residual.
    assert!(census.p99_k > 5.0 * data.residual().grazing_k, "{census:?}");
}
