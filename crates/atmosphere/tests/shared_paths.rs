//! A spectral rendering locates each path once and evaluates it in every sub-band
//! (`AtmosphereModel::locate_path`, `path_along`). The sub-bands of one spectral
//! atmosphere share their grids, and a path located by one must give every other exactly
//! the terms its own `path` gives: a shortcut, never a different answer.

use irsig_atmosphere::{
    AtmosphereModel, BUILTIN_NAMES, Collapser, ModelKind, SubBandCount, builtin, builtin_spectral,
    sub_band_edges,
};

/// The models of `kind` over the 16 sub-bands of a built-in's 8–14 µm.
fn sub_band_models(name: &str, kind: ModelKind) -> Vec<AtmosphereModel> {
    let spectral = builtin_spectral(name).unwrap();
    let edges = sub_band_edges(
        &spectral.grid,
        8.0,
        14.0,
        SubBandCount::Count(16),
        |_, _| 1.0,
    )
    .unwrap();
    let collapser = Collapser::new(&spectral).unwrap();
    edges
        .windows(2)
        .map(|w| {
            let atm = collapser.collapse(w[0], w[1], |_| 1.0).unwrap();
            AtmosphereModel::new(&atm, kind).unwrap()
        })
        .collect()
}

/// Paths that cross no level, several, the top of the profile, run horizontally, look up,
/// graze, have no length, or are not finite.
const PATHS: [(f64, f64, f64); 14] = [
    (5.0, 1.0, 22.7),
    (5.0, 0.0, 5.0),
    (1000.0, 0.0, 1000.0),
    (3000.0, 0.0, 57_322.0),
    (300.0, 2.0, 2500.0),
    (2.0, 300.0, 2500.0),
    (0.0, 12_000.0, 30_000.0),
    (15_000.0, 20_000.0, 9000.0),
    (100.0, 100.0, 5000.0),
    (50.0, 50.0, 1.0),
    (4.77, 0.0, 8.61),
    (7.0, 7.0, 0.0),
    (f64::NAN, 0.0, 10.0),
    (10.0, 0.0, f64::INFINITY),
];

fn bits(p: irsig_atmosphere::PathTerms) -> (u64, u64) {
    (p.transmission.to_bits(), p.path_radiance_w_m2_sr.to_bits())
}

#[test]
fn a_path_located_once_gives_every_sub_band_its_own_terms_bit_for_bit() {
    for name in BUILTIN_NAMES {
        for kind in [ModelKind::Table, ModelKind::Layered] {
            let models = sub_band_models(name, kind);
            let first = &models[0];
            for m in &models {
                assert!(first.shares_path_grids(m), "{name} {kind}");
            }
            for (sensor, target, range) in PATHS {
                let located = first.locate_path(sensor, target, range);
                for (k, m) in models.iter().enumerate() {
                    let own = m.path(sensor, target, range);
                    let shared = m.path_along(&located);
                    assert_eq!(
                        bits(shared),
                        bits(own),
                        "{name} {kind} sub-band {k}, path ({sensor}, {target}, {range}): \
                         {shared:?} located once, {own:?} on its own"
                    );
                }
            }
        }
    }
}

#[test]
fn grids_that_differ_are_told_apart_and_another_kind_locates_again() {
    // The same atmosphere with a level fewer does not share; the other kinds locate other
    // things, so a path located by `table` is located again by each.
    let atm = builtin("us-std-1976").unwrap();
    let a = AtmosphereModel::new(&atm, ModelKind::Table).unwrap();
    let mut fewer = atm.clone();
    fewer.levels.remove(3);
    let b = AtmosphereModel::new(&fewer, ModelKind::Table).unwrap();
    let layered = AtmosphereModel::new(&atm, ModelKind::Layered).unwrap();
    let thesis = AtmosphereModel::new(&atm, ModelKind::Thesis).unwrap();
    let none = AtmosphereModel::new(&atm, ModelKind::None).unwrap();
    assert!(!a.shares_path_grids(&b));
    assert!(!a.shares_path_grids(&layered));
    assert!(!layered.shares_path_grids(&thesis));
    assert!(a.shares_path_grids(&a));
    for (sensor, target, range) in PATHS {
        let located = a.locate_path(sensor, target, range);
        for m in [&layered, &thesis, &none] {
            assert_eq!(
                bits(m.path_along(&located)),
                bits(m.path(sensor, target, range)),
                "{} path ({sensor}, {target}, {range})",
                m.kind()
            );
        }
    }
}
