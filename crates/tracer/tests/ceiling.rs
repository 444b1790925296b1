//! An observer above the top of the atmosphere's data is refused, never served by the top
//! level: the built-ins' profile levels and sky rows stop at 10 km (the altitudes
//! scripts/atmosphere/regen.py ran LOWTRAN7 for), and from 30 km the top level stood in
//! for the air above it: +3 K at nadir and a sky 29 K too warm. At the top itself the
//! frame is traced, with the `table` and the `layered` model alike.

// Altitudes are copied from the tables and the camera, never computed: equality is exact.
#![allow(clippy::float_cmp)]

use irsig_atmosphere::{AtmosphereModel, BUILTIN_NAMES, ModelKind, PrecomputedAtmosphere, builtin};
use irsig_model::View;
use irsig_radiometry::Band;
use irsig_tracer::testing::{grey_materials, ground_quad, raw_scene};
use irsig_tracer::{Camera, TraceErrorKind, TraceOptions, Tracer};

/// The probe of the one pixel looking straight down from `altitude_m` onto a grey quad.
fn probe(
    atmosphere: &str,
    kind: ModelKind,
    altitude_m: f64,
) -> Result<irsig_tracer::Sample, irsig_tracer::TraceError> {
    let quad = ground_quad([-100.0, -100.0], [100.0, 100.0], 0.0);
    let scene = raw_scene(&[(&quad, 1, 300.0)]);
    let materials = grey_materials(&[(1, 0.95, 0.0)]);
    let model = AtmosphereModel::new(&builtin(atmosphere).unwrap(), kind).unwrap();
    let air = PrecomputedAtmosphere::new(model, altitude_m);
    let tracer = Tracer::new(&scene, &materials, Band::default(), air).unwrap();
    let camera = Camera::from_view(&View::LookAt {
        position_m: [0.0, 0.0, altitude_m],
        target_m: [0.0, 0.0, 0.0],
        up: [0.0, 1.0, 0.0],
        pixels: [1, 1],
        fov_deg: [1e-4, 1e-4],
        gain_dc_per_k: None,
    })
    .unwrap();
    tracer.probe(&camera, &TraceOptions::default(), 0, 0)
}

#[test]
fn a_camera_above_the_tables_top_row_is_refused_with_the_way_out() {
    for name in BUILTIN_NAMES {
        let model = AtmosphereModel::new(&builtin(name).unwrap(), ModelKind::Table).unwrap();
        assert_eq!(model.observer_ceiling_m(), Some(10_000.0), "{name}");
        probe(name, ModelKind::Table, 10_000.0)
            .unwrap_or_else(|e| panic!("{name} from its top row: {e}"));
        for altitude_m in [10_600.0, 30_000.0] {
            let e = probe(name, ModelKind::Table, altitude_m).unwrap_err();
            assert!(
                matches!(
                    e.kind,
                    TraceErrorKind::ObserverAboveAtmosphere { observer_m, ceiling_m }
                        if observer_m == altitude_m && ceiling_m == 10_000.0
                ),
                "{name} from {altitude_m} m: {e}"
            );
            let said = e.to_string();
            assert!(said.contains("10000 m"), "{said}");
            assert!(said.contains("irsig-atmos plan"), "{said}");
        }
    }
    // The layered model over the same profile stops where it does.
    let layered = AtmosphereModel::new(&builtin("tropical").unwrap(), ModelKind::Layered);
    assert_eq!(layered.unwrap().observer_ceiling_m(), Some(10_000.0));
    probe("tropical", ModelKind::Layered, 10_000.0).unwrap();
    assert!(probe("tropical", ModelKind::Layered, 30_000.0).is_err());
}
