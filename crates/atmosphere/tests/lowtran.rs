//! The atmosphere models against LOWTRAN7's own slant paths (an independent computation:
//! the band model run along each path), as apparent-temperature error of a 300 K
//! blackbody. The bounds are the measured errors in docs/accuracy.md, rounded up; a model
//! change that makes any of them worse fails here.

// Truth rows are selected by the exact altitudes and angles written in the CSV.
#![allow(clippy::float_cmp)]

use crate::common;

use crate::common::lowtran::{Rtt, atmosphere, error_k, truth};
use irsig_atmosphere::{AtmosphereModel, ModelKind};

fn worst(name: &str, kind: ModelKind, rows: impl Fn(&common::lowtran::Truth) -> bool) -> f64 {
    let a = atmosphere(name);
    let model = AtmosphereModel::new(&a, kind).unwrap();
    let rtt = Rtt::new(&a);
    truth(name)
        .iter()
        .filter(|t| t.transmission.is_some() && rows(t))
        .map(|t| error_k(&model, &rtt, t, 300.0).abs())
        .fold(0.0, f64::max)
}

/// Every figure of a model's row of the summary table holds, at the precision it is
/// printed to (2 decimals: the largest error over both atmospheres rounds to it).
fn holds_summary_row(kind: ModelKind, printed_k: [f64; 6]) {
    for ((category, select), printed) in common::lowtran::SUMMARY_CATEGORIES.iter().zip(printed_k) {
        let e = ["us-std-1976", "midlat-winter"]
            .iter()
            .map(|name| worst(name, kind, select))
            .fold(0.0, f64::max);
        assert!(
            (e - printed).abs() <= 0.005 + 1e-9,
            "{kind} {category}: docs/accuracy.md prints {printed} K, the model is {e} K"
        );
    }
}

#[test]
fn table_model_holds_the_summary_row_of_docs_accuracy() {
    holds_summary_row(ModelKind::Table, [0.00, 0.01, 0.00, 0.26, 0.36, 0.74]);
}

#[test]
fn layered_model_holds_the_summary_row_of_docs_accuracy() {
    holds_summary_row(ModelKind::Layered, [0.21, 0.62, 2.77, 0.50, 0.36, 0.74]);
}

#[test]
fn table_model_matches_lowtran_on_its_grid_to_hundredths_of_a_kelvin() {
    // docs/accuracy.md: "on its rows it is within 0.06 K to 88°".
    for name in ["us-std-1976", "midlat-winter"] {
        let on_grid = |t: &common::lowtran::Truth| [300.0, 1000.0, 3000.0].contains(&t.observer_m);
        let e = worst(name, ModelKind::Table, |t| {
            t.kind == "ground" && t.angle_deg <= 88.0 && on_grid(t)
        });
        assert!(e < 0.06, "{name}: {e} K");
    }
}

#[test]
fn thesis_model_reproduces_its_own_fit_altitude_but_not_others() {
    for name in ["us-std-1976", "midlat-winter"] {
        let at_1km = worst(name, ModelKind::Thesis, |t| {
            t.kind == "ground" && t.observer_m == 1000.0 && t.angle_deg <= 30.0
        });
        assert!(at_1km < 0.7, "{name}: {at_1km} K");
        // eq. 11's secθ path radiance is far too high at 80° (README caveat 4).
        let at_80 = worst(name, ModelKind::Thesis, |t| {
            t.kind == "ground" && t.observer_m == 1000.0 && t.angle_deg == 80.0
        });
        assert!(at_80 > 3.0, "{name}: {at_80} K");
    }
}

#[test]
fn sky_from_above_the_ground_follows_lowtran() {
    // docs/accuracy.md: `table` within 0.05 % off its angle grid to 84° and 1.7 % to the
    // horizon (past it an extrapolation, held to 2 %); `thesis` and `layered` within
    // 1.2 % at 0.3 km, 2.2 % at 1 km and 7 % at 3 km up to 62.5°.
    for name in ["us-std-1976", "midlat-winter"] {
        let a = atmosphere(name);
        let table = AtmosphereModel::new(&a, ModelKind::Table).unwrap();
        let layered = AtmosphereModel::new(&a, ModelKind::Layered).unwrap();
        let thesis = AtmosphereModel::new(&a, ModelKind::Thesis).unwrap();
        for t in truth(name).iter().filter(|t| t.kind == "sky") {
            let rel = |m: &AtmosphereModel| {
                m.sky_radiance(t.observer_m, t.angle_deg) / t.radiance_w_m2_sr - 1.0
            };
            let table_bound = if t.angle_deg <= 84.0 { 0.0005 } else { 0.02 };
            assert!(
                rel(&table).abs() < table_bound,
                "{name} table {t:?}: {}",
                rel(&table)
            );
            if t.angle_deg <= 62.5 {
                let bound = match t.observer_m {
                    h if h <= 300.0 => 0.012,
                    h if h <= 1000.0 => 0.022,
                    _ => 0.07,
                };
                for (label, m) in [("layered", &layered), ("thesis", &thesis)] {
                    assert!(rel(m).abs() < bound, "{name} {label} {t:?}: {}", rel(m));
                }
            }
        }
    }
}
