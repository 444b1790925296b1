//! Fresnel emissivity against physics: the normal-incidence closed form, grazing
//! incidence, Brewster's angle, the large-|N| (metal) asymptotes, Dunkle's closed-form
//! hemispherical emissivity of a dielectric, energy conservation and no NaN for any finite
//! input; and the band-averaged water table against the shared Hale & Querry reference.

#![allow(clippy::float_cmp)] // exact values (ε(90°) = 0) are the point of some checks

use irsig_radiometry::fresnel::{
    ComplexIndex, IndexTable, band_emissivity_table, band_mean_index, emissivity_table,
};
use irsig_radiometry::{Band, RadiometryErrorKind, SensorResponse};
use proptest::prelude::*;

use crate::common::water::{dunkle_hemispherical, water};

fn index(n: f64, k: f64) -> ComplexIndex {
    ComplexIndex::new(n, k).unwrap()
}

#[test]
fn normal_incidence_matches_the_closed_form() {
    for n in [0.05, 0.5, 1.0, 1.2, 1.33, 2.4, 4.0, 25.0, 1e3] {
        for k in [0.0, 0.05, 0.37, 1.0, 10.0, 90.0, 1e3] {
            let expected = 1.0 - ((n - 1.0) * (n - 1.0) + k * k) / ((n + 1.0) * (n + 1.0) + k * k);
            let e = index(n, k).polarised_emissivity(0.0);
            // At normal incidence s and p are the same wave.
            assert!(
                (e.s - expected).abs() < 1e-14,
                "n {n} k {k}: {} vs {expected}",
                e.s
            );
            assert!(
                (e.p - expected).abs() < 1e-14,
                "n {n} k {k}: {} vs {expected}",
                e.p
            );
        }
    }
}

#[test]
fn grazing_incidence_emits_nothing() {
    for (n, k) in [(1.33, 0.0), (1.2, 0.05), (25.0, 90.0), (0.3, 2.0)] {
        let i = index(n, k);
        assert_eq!(i.emissivity(90.0), 0.0);
        assert_eq!(
            i.reflectance(90.0),
            irsig_radiometry::fresnel::Polarised { s: 1.0, p: 1.0 }
        );
        // And continuously so: ε → 0 as θ → 90° (linearly in cos θ).
        let near = i.emissivity(90.0 - 1e-6);
        assert!(near > 0.0 && near < 1e-6, "n {n} k {k}: {near}");
    }
}

#[test]
fn brewster_angle_has_no_p_reflection() {
    // tan θ_B = n for k = 0, on both sides of n = 1 (two branches of the algebra).
    for n in [0.5, 0.9, 1.2, 1.333, 1.5, 2.4, 4.0, 100.0] {
        let theta_b = f64::atan(n).to_degrees();
        let r = index(n, 0.0).reflectance(theta_b);
        assert!(r.p < 1e-24, "n {n}: R_p = {} at {theta_b}°", r.p);
        assert!(r.s > 0.0);
        // And nowhere else: R_p grows on either side.
        assert!(index(n, 0.0).reflectance(theta_b - 1.0).p > r.p);
        assert!(index(n, 0.0).reflectance(theta_b + 1.0).p > r.p);
    }
}

#[test]
fn a_metal_has_low_emissivity_following_the_large_index_asymptotes() {
    // Aluminium near 10 µm: n ≈ 25, k ≈ 90 (Ordal et al. 1983, Appl. Opt. 22, 1099,
    // rounded; the test needs only "a high-k metal").
    let al = index(25.0, 90.0);
    let normal = 4.0 * 25.0 / (26.0 * 26.0 + 90.0 * 90.0); // 0.0114
    let table = emissivity_table(al, &(0..=90).map(f64::from).collect::<Vec<_>>()).unwrap();
    assert!(table.hemispherical() < 0.03, "{}", table.hemispherical());
    for theta in [0.0_f64, 20.0, 40.0, 60.0, 70.0] {
        // For |N| cos θ ≫ 1: ε_s ≈ ε_n cos θ, ε_p ≈ ε_n / cos θ (Born & Wolf §14.2); the
        // neglected terms are O(1/(|N| cos θ)) ≤ 3 % here.
        let c = theta.to_radians().cos();
        let e = al.polarised_emissivity(theta);
        assert!(
            (e.s / (normal * c) - 1.0).abs() < 0.03,
            "{theta}: s {}",
            e.s
        );
        assert!(
            (e.p / (normal / c) - 1.0).abs() < 0.03,
            "{theta}: p {}",
            e.p
        );
        assert!(e.mean() < 0.05);
        // Small ε is computed directly, not as 1 − R: the two routes still agree.
        let r = al.reflectance(theta);
        assert!((e.s + r.s - 1.0).abs() < 1e-15 && (e.p + r.p - 1.0).abs() < 1e-15);
    }
}

#[test]
fn a_fine_table_integrates_to_dunkles_hemispherical_emissivity() {
    // 0.05° steps: linear interpolation of ε(θ) costs < 1e-6 (the error scales as step²:
    // 4.5e-7 at 0.1° for n = 1.333, docs/accuracy.md, so ~1.1e-7 here); the hemispherical
    // integral of the interpolant itself is exact.
    let angles: Vec<f64> = (0..=1800).map(|i| f64::from(i) * 0.05).collect();
    for n in [1.2, 1.333, 1.5, 2.4, 4.0] {
        let table = emissivity_table(index(n, 0.0), &angles).unwrap();
        let (ours, exact) = (table.hemispherical(), dunkle_hemispherical(n));
        assert!((ours - exact).abs() < 1e-6, "n {n}: {ours} vs {exact}");
    }
}

#[test]
fn invalid_indices_are_clear_errors() {
    for (n, k) in [
        (0.0, 0.0),
        (-1.2, 0.0),
        (f64::NAN, 0.0),
        (f64::INFINITY, 0.0),
        (1.2, -0.01),
        (1.2, f64::NAN),
        (1.2, f64::INFINITY),
    ] {
        let e = ComplexIndex::new(n, k).unwrap_err();
        assert_eq!(e.kind, RadiometryErrorKind::InvalidRefractiveIndex);
        let shown = e.to_string();
        assert!(shown.contains("invalid refractive index"), "{shown}");
        let culprit = if n.is_finite() && n > 0.0 { k } else { n };
        assert!(shown.contains(&culprit.to_string()), "{shown}");
    }
    let e = IndexTable::new(vec![8.0, 9.0], &[1.2, 1.3], &[0.0, -0.1]).unwrap_err();
    assert!(e.to_string().contains("row 2"), "{e}");
    assert!(IndexTable::new(vec![9.0, 8.0], &[1.2, 1.3], &[0.0, 0.0]).is_err());
    assert!(IndexTable::new(vec![8.0], &[1.2], &[0.0]).is_err());
    assert!(emissivity_table(index(1.2, 0.0), &[0.0, 91.0]).is_err());
    assert!(emissivity_table(index(1.2, 0.0), &[10.0, 5.0]).is_err());
    assert!(emissivity_table(index(1.2, 0.0), &[]).is_err());
}

fn finite_positive() -> impl Strategy<Value = f64> {
    proptest::num::f64::POSITIVE | proptest::num::f64::NORMAL | proptest::num::f64::SUBNORMAL
}

proptest! {
    #[test]
    fn energy_is_conserved_for_extreme_indices(
        log_n in -300.0f64..300.0,
        log_k in -300.0f64..300.0,
        k_zero in proptest::bool::ANY,
        angle in 0.0f64..90.0,
    ) {
        let n = 10f64.powf(log_n);
        let k = if k_zero { 0.0 } else { 10f64.powf(log_k) };
        let i = index(n, k);
        let r = i.reflectance(angle);
        let e = i.polarised_emissivity(angle);
        for (rv, ev) in [(r.s, e.s), (r.p, e.p)] {
            prop_assert!((0.0..=1.0).contains(&rv), "R = {rv} for n {n} k {k} at {angle}");
            prop_assert!((0.0..=1.0).contains(&ev), "ε = {ev} for n {n} k {k} at {angle}");
            // |r|² by hypot and 1 − |r|² by 4 Re(a b̄) / |a + b|² are different algebra.
            prop_assert!((rv + ev - 1.0).abs() < 1e-12, "R {rv} + ε {ev} for n {n} k {k} at {angle}");
        }
    }

    #[test]
    fn no_nan_for_any_finite_input(
        n in finite_positive(),
        k in prop_oneof![finite_positive(), Just(0.0), Just(f64::MAX)],
        angle in proptest::num::f64::NORMAL | proptest::num::f64::ZERO | proptest::num::f64::SUBNORMAL,
    ) {
        let i = index(n, k);
        let r = i.reflectance(angle);
        let e = i.polarised_emissivity(angle);
        for v in [r.s, r.p, e.s, e.p] {
            prop_assert!((0.0..=1.0).contains(&v), "{v} for n {n} k {k} at {angle}");
        }
    }

    #[test]
    fn no_nan_at_the_largest_and_smallest_values(
        n in prop_oneof![Just(f64::MAX), Just(f64::MIN_POSITIVE), Just(5e-324), Just(1.0)],
        k in prop_oneof![Just(f64::MAX), Just(f64::MIN_POSITIVE), Just(5e-324), Just(0.0), Just(1.0)],
        angle in prop_oneof![Just(0.0), Just(45.0), Just(89.999_999), Just(90.0), Just(-30.0), Just(1e300)],
    ) {
        let i = index(n, k);
        for v in [i.reflectance(angle).s, i.reflectance(angle).p, i.emissivity(angle)] {
            prop_assert!((0.0..=1.0).contains(&v), "{v} for n {n} k {k} at {angle}");
        }
    }
}

fn reference_ems() -> Vec<(f64, f64)> {
    // The repository's copy of shared/reference/materials/water-hale-querry.ems (same
    // sha256, formats/legacy/samples/README.md).
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../formats/legacy/samples/water-hale-querry.ems"
    );
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .map(|l| {
            let (a, e) = l.split_once(' ').unwrap();
            (a.parse().unwrap(), e.parse().unwrap())
        })
        .collect()
}

#[test]
fn water_band_table_matches_the_hale_querry_reference() {
    let reference = reference_ems();
    let angles: Vec<f64> = reference.iter().map(|r| r.0).collect();
    let ours = band_emissivity_table(&water(), &Band::default(), 300.0, &angles).unwrap();
    let worst = ours
        .emissivity()
        .iter()
        .zip(&reference)
        .map(|(a, b)| (a - b.1).abs())
        .fold(0.0, f64::max);
    // The file prints 6 decimals (±5e-7) of a 0.0005 µm trapezoid rule (error ~1e-9,
    // next test) of the same physics; measured worst 4.2e-7.
    assert!(worst < 6e-7, "max |ours − reference| = {worst}");
}

#[test]
fn monochromatic_water_at_10_5_um_matches_the_reference_columns() {
    // shared/reference/materials/README.md, 10.5 µm columns (N = 1.185 + 0.0662 i):
    // (angle, ε, ε_s, ε_p), 6 decimals, computed there with numpy's complex arithmetic.
    let rows = [
        (0.0, 0.991_921, 0.991_921, 0.991_921),
        (30.0, 0.991_350, 0.987_034, 0.995_665),
        (50.0, 0.984_025, 0.968_122, 0.999_927),
        (70.0, 0.908_970, 0.861_550, 0.956_390),
        (85.0, 0.466_906, 0.406_281, 0.527_530),
    ];
    let w = index(1.185, 0.0662);
    for (a, e, es, ep) in rows {
        let p = w.polarised_emissivity(a);
        assert!((w.emissivity(a) - e).abs() < 6e-7, "{a}");
        assert!(
            (p.s - es).abs() < 6e-7 && (p.p - ep).abs() < 6e-7,
            "{a}: {p:?}"
        );
    }
}

/// Planck spectral radiance, relative units (constants typed again on purpose).
fn planck_relative(lambda_um: f64, t_k: f64) -> f64 {
    let c2_um_k = 6.626_070_15e-34 * 299_792_458.0 / 1.380_649e-23 * 1e6;
    1.0 / lambda_um.powi(5) / (c2_um_k / (lambda_um * t_k)).exp_m1()
}

#[test]
fn band_quadrature_agrees_with_a_fine_trapezoid_rule() {
    // An independent integral: trapezoid rule on a 0.0005 µm grid (12001 points, as the
    // reference generator), which has knots at every tabulated wavelength.
    let table = water();
    let angles = [0.0, 45.0, 75.0, 85.0, 89.0];
    let ours = band_emissivity_table(&table, &Band::default(), 300.0, &angles).unwrap();
    for (i, &a) in angles.iter().enumerate() {
        let (mut num, mut den) = (0.0, 0.0);
        for j in 0..=12_000 {
            let l = 8.0 + 0.0005 * f64::from(j);
            let w = if j == 0 || j == 12_000 { 0.5 } else { 1.0 } * planck_relative(l, 300.0);
            num += w * table.at(l).emissivity(a);
            den += w;
        }
        let trapezoid = num / den;
        assert!((ours.emissivity()[i] - trapezoid).abs() < 1e-8, "{a}°");
    }
}

#[test]
fn a_narrow_response_gives_the_monochromatic_emissivity() {
    // The band average tends to ε(λ0, θ) as the response narrows around λ0 = 10.5 µm
    // (±1e-5 µm: the kink of the interpolated k there shifts the mean k by ~5e-8).
    let srf = SensorResponse::new(vec![10.499_99, 10.5, 10.500_01], vec![0.0, 1.0, 0.0]).unwrap();
    let band = Band::default().with_response(&srf).unwrap();
    let angles = [0.0, 60.0, 85.0];
    let ours = band_emissivity_table(&water(), &band, 300.0, &angles).unwrap();
    for (i, &a) in angles.iter().enumerate() {
        let mono = index(1.185, 0.0662).emissivity(a);
        assert!((ours.emissivity()[i] - mono).abs() < 1e-6, "{a}°");
    }
}

#[test]
fn a_constant_table_gives_the_constant_index_at_any_temperature() {
    let table = IndexTable::new(vec![7.0, 15.0], &[1.4, 1.4], &[0.2, 0.2]).unwrap();
    let angles: Vec<f64> = (0..=18).map(|i| f64::from(i) * 5.0).collect();
    let constant = emissivity_table(index(1.4, 0.2), &angles).unwrap();
    for t in [3.0, 300.0, 5000.0] {
        let banded = band_emissivity_table(&table, &Band::default(), t, &angles).unwrap();
        for (a, b) in banded.emissivity().iter().zip(constant.emissivity()) {
            assert!((a - b).abs() < 1e-14, "{t} K");
        }
        let mean = band_mean_index(&table, &Band::default(), t).unwrap();
        assert!((mean.n() - 1.4).abs() < 1e-14 && (mean.k() - 0.2).abs() < 1e-14);
    }
}

#[test]
fn the_band_average_refuses_what_it_cannot_do() {
    let w = water();
    let angles = [0.0, 45.0];
    let wide = Band::new(7.0, 14.0).unwrap();
    let e = band_emissivity_table(&w, &wide, 300.0, &angles).unwrap_err();
    assert_eq!(e.kind, RadiometryErrorKind::InvalidRefractiveIndex);
    assert!(e.to_string().contains("7–14 µm"), "{e}");
    // A weighting at 1e-300 K or 1e308 K was accepted: no source is that cold or that hot.
    for t in [
        0.0,
        -5.0,
        f64::NAN,
        f64::INFINITY,
        1e-300,
        0.999,
        10_000.001,
        1e308,
    ] {
        let e = band_emissivity_table(&w, &Band::default(), t, &angles).unwrap_err();
        assert_eq!(e.kind, RadiometryErrorKind::InvalidTemperature);
        assert!(e.to_string().contains("from 1 to 10000 K"), "{e}");
    }
    // A response that ends inside the table is fine even if the band does not.
    let srf = SensorResponse::new(vec![8.5, 10.0, 12.0], vec![0.0, 1.0, 0.0]).unwrap();
    let band = Band::new(7.0, 14.0).unwrap().with_response(&srf).unwrap();
    assert!(band_emissivity_table(&w, &band, 300.0, &angles).is_ok());
    // The coldest and hottest weightings stay finite and inside [0, 1].
    for t in [1.0, 10_000.0] {
        let t = band_emissivity_table(&w, &Band::default(), t, &angles).unwrap();
        assert!(t.emissivity().iter().all(|e| (0.0..=1.0).contains(e)));
    }
}

#[test]
fn a_million_row_index_table_is_averaged_on_a_bounded_rule_that_keeps_its_accuracy() {
    // A million rows of n, k cost about 1 ms per row (8 nodes per row, each at every
    // angle): 100,000 rows took 95 s. The rule now takes at most 1,024 pieces over the band,
    // thinning a denser table's breakpoints. The same smooth index given by 2,000 rows (a
    // rule of its own rows, untouched) and by a million gives the same table.
    let index = |count: usize| {
        let (lo, hi) = (7.9, 14.1);
        let w: Vec<f64> = (0..count)
            .map(|i| lo + (hi - lo) * i as f64 / (count - 1) as f64)
            .collect();
        let n: Vec<f64> = w.iter().map(|x| 1.3 + 0.1 * x.sin()).collect();
        let k: Vec<f64> = w.iter().map(|x| 0.05 + 0.02 * x.cos()).collect();
        IndexTable::new(w, &n, &k).unwrap()
    };
    let angles = [0.0, 45.0, 80.0, 90.0];
    let sparse = band_emissivity_table(&index(2_000), &Band::default(), 300.0, &angles).unwrap();
    let dense = band_emissivity_table(&index(1_000_000), &Band::default(), 300.0, &angles).unwrap();
    for (s, d) in sparse.emissivity().iter().zip(dense.emissivity()) {
        assert!((s - d).abs() < 1e-7, "{s} vs {d}");
    }
}
