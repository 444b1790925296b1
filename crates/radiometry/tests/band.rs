//! Band radiance, its derivative and inverse: against independent methods (adaptive
//! quadrature of the Planck function, the mpmath-made `.rtt`, finite differences), round
//! trips, extremes and properties (Wien's displacement law).

#![allow(clippy::float_cmp)] // exact results (0 K, 0 W, saturation) are asserted exactly

use irsig_radiometry::{Band, SensorResponse};
use proptest::prelude::*;

// CODATA 2018, typed here again on purpose: the test must not share the library's numbers.
const H: f64 = 6.626_070_15e-34;
const C: f64 = 299_792_458.0;
const K: f64 = 1.380_649e-23;

/// Spectral radiance per unit wavelength, W m^-2 sr^-1 m^-1.
fn planck(lambda_m: f64, t_k: f64) -> f64 {
    2.0 * H * C * C / lambda_m.powi(5) / (H * C / (lambda_m * K * t_k)).exp_m1()
}

/// Adaptive Gauss–Kronrod (G7/K15, the QUADPACK constants): an interval is accepted when
/// the 7- and 15-point results agree (see below), otherwise it is halved.
fn adaptive_kronrod(f: &dyn Fn(f64) -> f64, a: f64, b: f64, tol: f64, depth: u32) -> f64 {
    const XK: [f64; 8] = [
        0.991_455_371_120_812_6,
        0.949_107_912_342_758_5,
        0.864_864_423_359_769_1,
        0.741_531_185_599_394_4,
        0.586_087_235_467_691_1,
        0.405_845_151_377_397_2,
        0.207_784_955_007_898_5,
        0.0,
    ];
    const WK: [f64; 8] = [
        0.022_935_322_010_529_22,
        0.063_092_092_629_978_55,
        0.104_790_010_322_250_2,
        0.140_653_259_715_525_9,
        0.169_004_726_639_267_9,
        0.190_350_578_064_785_4,
        0.204_432_940_075_298_9,
        0.209_482_141_084_728,
    ];
    const WG: [f64; 4] = [
        0.129_484_966_168_869_7,
        0.279_705_391_489_276_7,
        0.381_830_050_505_118_9,
        0.417_959_183_673_469_4,
    ];
    let c = 0.5 * (a + b);
    let h = 0.5 * (b - a);
    let mut kronrod = 0.0;
    let mut gauss = 0.0;
    for i in 0..8 {
        let pair = if XK[i] == 0.0 {
            f(c)
        } else {
            f(c - h * XK[i]) + f(c + h * XK[i])
        };
        kronrod += WK[i] * pair;
        if i % 2 == 1 {
            gauss += WG[i / 2] * pair;
        }
    }
    kronrod *= h;
    gauss *= h;
    // Accept when G7 and K15 agree to `tol`, or to 1e-7 relative: K15 is exact to degree 23
    // against G7's 13, so its own error is then ~1e-12 relative or less for these smooth
    // integrands.
    let diff = (kronrod - gauss).abs();
    if depth == 0 || diff <= tol || diff <= 1e-7 * kronrod.abs() {
        return kronrod;
    }
    adaptive_kronrod(f, a, c, tol / 2.0, depth - 1)
        + adaptive_kronrod(f, c, b, tol / 2.0, depth - 1)
}

/// Band radiance by adaptive quadrature, relative tolerance ~1e-13.
fn reference_radiance(l1_um: f64, l2_um: f64, t_k: f64, srf: &dyn Fn(f64) -> f64) -> f64 {
    let f = |l: f64| srf(l * 1e6) * planck(l, t_k);
    let (a, b) = (l1_um * 1e-6, l2_um * 1e-6);
    // A coarse pass sets the scale of the absolute tolerance.
    let rough = adaptive_kronrod(&f, a, b, 0.0, 6);
    if rough <= 0.0 {
        return 0.0;
    }
    adaptive_kronrod(&f, a, b, rough * 1e-14, 40)
}

#[test]
fn flat_band_matches_adaptive_quadrature_to_1e_10_from_3_k_to_5000_k() {
    let band = Band::default();
    let mut worst: f64 = 0.0;
    for &t in &[
        3.0, 5.0, 10.0, 30.0, 77.0, 150.0, 200.0, 250.0, 273.15, 300.0, 350.0, 420.0, 514.0, 515.0,
        700.0, 899.0, 900.0, 1000.0, 1800.0, 3000.0, 5000.0,
    ] {
        let lib = band.radiance(t);
        let reference = reference_radiance(8.0, 14.0, t, &|_| 1.0);
        let rel = (lib / reference - 1.0).abs();
        worst = worst.max(rel);
        assert!(rel <= 1e-10, "T = {t}: {lib} vs {reference} (rel {rel:e})");
    }
    eprintln!("worst relative error, flat band vs quadrature: {worst:e}");
}

#[test]
fn other_flat_bands_match_quadrature() {
    for &(l1, l2) in &[(3.0, 5.0), (0.4, 0.7), (10.0, 10.5), (1.0, 100.0)] {
        let band = Band::new(l1, l2).unwrap();
        for &t in &[50.0, 300.0, 1500.0, 6000.0] {
            let reference = reference_radiance(l1, l2, t, &|_| 1.0);
            if reference < 1e-280 {
                continue;
            }
            let rel = (band.radiance(t) / reference - 1.0).abs();
            assert!(rel <= 1e-10, "{l1}-{l2} µm, T = {t}: rel {rel:e}");
        }
    }
}

#[test]
fn a_response_table_matches_quadrature_from_50_k() {
    let srf = SensorResponse::new(
        vec![7.5, 8.0, 9.0, 10.5, 12.0, 13.0, 14.5],
        vec![0.0, 0.4, 0.9, 1.0, 0.8, 0.3, 0.0],
    )
    .unwrap();
    let band = Band::default().with_response(&srf).unwrap();
    for &t in &[50.0, 100.0, 200.0, 300.0, 400.0, 1000.0, 5000.0] {
        let reference = reference_radiance(8.0, 14.0, t, &|l| srf.at(l));
        let rel = (band.radiance(t) / reference - 1.0).abs();
        assert!(rel <= 1e-10, "T = {t}: rel {rel:e}");
    }
}

/// The 15-point Kronrod rule on `[a, b]` (its nodes and weights above), once.
fn kronrod_15(f: &dyn Fn(f64) -> f64, a: f64, b: f64) -> f64 {
    adaptive_kronrod(f, a, b, f64::INFINITY, 0)
}

/// A measured-looking response of `rows` rows from `from` to `to` µm: jagged, every value
/// from a linear congruential sequence in [0, 1).
fn jagged_response(rows: usize, from: f64, to: f64) -> (Vec<f64>, Vec<f64>) {
    let mut state: u64 = 12_345;
    let wavelength_um = (0..rows)
        .map(|i| from + (to - from) * i as f64 / (rows - 1) as f64)
        .collect();
    let response = (0..rows)
        .map(|_| {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1);
            (state >> 11) as f64 / (1u64 << 53) as f64
        })
        .collect();
    (wavelength_um, response)
}

/// ∫ SRF·B over [lo, hi], row by row: the response is linear across each row's interval,
/// which is short enough for one Kronrod rule to be exact to rounding.
fn per_row_reference(w: &[f64], r: &[f64], lo: f64, hi: f64, t_k: f64) -> f64 {
    let mut sum = 0.0;
    for i in 0..w.len() - 1 {
        let (a, b) = (w[i].max(lo), w[i + 1].min(hi));
        if b <= a {
            continue;
        }
        let (w0, w1, r0, r1) = (w[i], w[i + 1], r[i], r[i + 1]);
        let f = |l: f64| {
            let um = l * 1e6;
            (r0 + (r1 - r0) * (um - w0) / (w1 - w0)) * planck(l, t_k)
        };
        sum += kronrod_15(&f, a * 1e-6, b * 1e-6);
    }
    sum
}

#[test]
fn a_response_of_many_rows_costs_few_nodes_and_keeps_its_accuracy() {
    // A 100,000-row response gave 400,000 nodes: every L(T) cost as many exponentials, and
    // the tracer's --tolerance pilot took 81 s on a 16 × 12 image. The nodes of each 1 µm
    // are now the 8-point Gauss rule of the measure they make.
    for rows in [10_000, 100_000] {
        let (w, r) = jagged_response(rows, 7.9, 14.1);
        let srf = SensorResponse::new(w.clone(), r.clone()).unwrap();
        let band = Band::default().with_response(&srf).unwrap();
        // Cells of at most 1 µm, two of them longer than 1 µm together: 13 over 6 µm.
        assert!(
            band.quadrature_nodes() <= 8 * 13,
            "{rows} rows: {} nodes",
            band.quadrature_nodes()
        );
        for t in [50.0, 100.0, 200.0, 300.0, 1000.0, 5000.0] {
            let reference = per_row_reference(&w, &r, 8.0, 14.0, t);
            let rel = (band.radiance(t) / reference - 1.0).abs();
            assert!(rel <= 1e-10, "{rows} rows, T = {t}: rel {rel:e}");
        }
        // Still strictly increasing, so the inverse is exact.
        for t in [60.0, 250.0, 3000.0] {
            assert!((band.temperature(band.radiance(t)) - t).abs() < 1e-6);
        }
    }
}

#[test]
fn a_response_is_refused_outside_the_physical_range() {
    // `1e-300 1` / `1e300 1` cut into 1 µm pieces allocated until the kernel ended the
    // process; responses of 1e308 gave a band radiance of 1.797693e308.
    for (w, r, says) in [
        (
            vec![1e-300, 1e300],
            vec![1.0, 1.0],
            "wavelength must be 0.2–1000 µm",
        ),
        (
            vec![1e-10, 1e10],
            vec![1.0, 1.0],
            "wavelength must be 0.2–1000 µm",
        ),
        (vec![0.1, 8.0], vec![1.0, 1.0], "found 0.1"),
        (vec![8.0, 1001.0], vec![1.0, 1.0], "found 1001"),
        (
            vec![8.0, 14.0],
            vec![1e308, 1e308],
            "response must be 0–1e6",
        ),
        (
            vec![8.0, 14.0],
            vec![1.0, f64::NAN],
            "response must be 0–1e6",
        ),
    ] {
        let e = SensorResponse::new(w, r).unwrap_err();
        assert!(e.to_string().contains(says), "{e}");
    }
    // The ends of the range, and the largest response, are accepted.
    let srf = SensorResponse::new(vec![0.2, 1000.0], vec![1e6, 1e6]).unwrap();
    let band = Band::new(0.2, 1000.0).unwrap().with_response(&srf).unwrap();
    assert!(band.quadrature_nodes() <= 8 * 2000);
    assert!(band.radiance(300.0).is_finite() && band.radiance(1e4).is_finite());
    let e = Band::default()
        .with_response_quadrature(&srf, 8, 1e-300)
        .unwrap_err();
    assert!(e.to_string().contains("at least 0.01"), "{e}");
}

#[test]
fn a_flat_response_table_reproduces_the_series() {
    // Quadrature path against the closed-form path: two independent methods in the library.
    let flat = SensorResponse::new(vec![8.0, 14.0], vec![1.0, 1.0]).unwrap();
    let quad = Band::default().with_response(&flat).unwrap();
    let series = Band::default();
    for t in (50..=5000).step_by(50) {
        let t = f64::from(t);
        let rel = (quad.radiance(t) / series.radiance(t) - 1.0).abs();
        assert!(rel <= 1e-10, "T = {t}: rel {rel:e}");
        let rel_d = (quad.radiance_derivative(t) / series.radiance_derivative(t) - 1.0).abs();
        assert!(rel_d <= 1e-9, "T = {t}: derivative rel {rel_d:e}");
    }
}

#[test]
fn matches_the_reference_rtt_to_its_12_digits() {
    // The reference `.rtt` (the shared LOWTRAN7 reference set's, byte for byte; sha256
    // 4d32cab5…c655), as the built-in atmosphere's data keeps it.
    let text = include_str!("../../atmosphere/data/lowtran/us-std-1976/us-std-1976.rtt");
    let band = Band::default();
    let mut rows = 0;
    for line in text.lines() {
        let mut cols = line.split_whitespace();
        let t: f64 = cols.next().unwrap().parse().unwrap();
        let l_w_cm2: f64 = cols.next().unwrap().parse().unwrap();
        let l_si = l_w_cm2 * 1e4;
        let rel = (band.radiance(t) / l_si - 1.0).abs();
        // 12 significant digits: rounding error at most 5e-12 relative.
        assert!(
            rel < 6e-12,
            "T = {t}: {} vs {l_si} (rel {rel:e})",
            band.radiance(t)
        );
        rows += 1;
    }
    assert_eq!(rows, 151);
}

#[test]
fn the_known_value_at_300_k() {
    // .rtt row "300 5.49335...e-03" W cm^-2 sr^-1 → 54.9335 W m^-2 sr^-1.
    assert!((Band::default().radiance(300.0) - 54.9335).abs() < 5e-5);
}

#[test]
fn round_trip_is_within_1e_6_k_from_3_k_to_5000_k() {
    for band in [
        Band::default(),
        Band::default()
            .with_response(
                &SensorResponse::new(vec![8.0, 9.0, 12.0, 14.0], vec![0.2, 1.0, 0.9, 0.1]).unwrap(),
            )
            .unwrap(),
    ] {
        let mut worst: f64 = 0.0;
        // Dense sweep: 3 K to 5000 K in steps of 0.25 K, plus log-spaced points below 50 K.
        let mut temps: Vec<f64> = (12..=20_000).map(|i| f64::from(i) * 0.25).collect();
        temps.extend((0..200).map(|i| 3.0 * (50.0_f64 / 3.0).powf(f64::from(i) / 200.0)));
        for t in temps {
            let back = band.temperature(band.radiance(t));
            let err = (back - t).abs();
            worst = worst.max(err);
            assert!(
                err < 1e-6,
                "T = {t}: got {back} (srf: {})",
                band.has_response()
            );
        }
        eprintln!("worst round-trip error: {worst:e} K");
    }
}

#[test]
fn derivative_matches_central_differences() {
    let band = Band::default();
    for &t in &[5.0, 50.0, 200.0, 300.0, 514.0, 600.0, 900.0, 2000.0, 1e5] {
        // Richardson-extrapolated central differences: truncation error O(h^4).
        let h = t * 1e-4;
        let cd = |h: f64| (band.radiance(t + h) - band.radiance(t - h)) / (2.0 * h);
        let fd = (4.0 * cd(h / 2.0) - cd(h)) / 3.0;
        let d = band.radiance_derivative(t);
        assert!((d / fd - 1.0).abs() < 1e-8, "T = {t}: {d} vs {fd}");
    }
}

#[test]
fn non_positive_radiance_gives_zero_kelvin_and_non_positive_temperature_zero_radiance() {
    let band = Band::default();
    assert_eq!(band.temperature(0.0), 0.0);
    assert_eq!(band.temperature(-1.0), 0.0);
    assert_eq!(band.temperature(f64::MIN), 0.0);
    assert_eq!(band.radiance(0.0), 0.0);
    assert_eq!(band.radiance(-300.0), 0.0);
    assert_eq!(band.radiance_derivative(-300.0), 0.0);
    assert!(band.temperature(f64::NAN).is_nan());
    assert!(band.radiance(f64::NAN).is_nan());
}

#[test]
fn extremes_stay_finite_and_ordered() {
    let band = Band::default();
    // Rayleigh–Jeans limit: L ≈ (c1L/c2) T ∫ λ^-4 dλ = 2 c k T (λ1^-3 − λ2^-3)/3.
    let t = 1e12;
    let rj = 2.0 * C * K * t * ((8e-6_f64).powi(-3) - (14e-6_f64).powi(-3)) / 3.0;
    assert!((band.radiance(t) / rj - 1.0).abs() < 1e-6);
    assert_eq!(band.radiance(f64::MAX), f64::MAX);
    assert!(band.temperature(f64::MAX).is_finite());
    assert!((band.temperature(band.radiance(1e12)) / 1e12 - 1.0).abs() < 1e-12);
    // Below ~1.4 K the 8–14 µm radiance underflows f64 altogether.
    assert_eq!(band.radiance(0.5), 0.0);
    assert!(band.radiance(3.0) > 0.0);
    assert!(band.temperature(f64::MIN_POSITIVE) > 0.0);
    assert!(band.temperature(5e-324) > 0.0);
}

proptest! {
    #[test]
    fn no_nan_inf_or_panic_for_any_finite_input(t in proptest::num::f64::NORMAL | proptest::num::f64::SUBNORMAL | proptest::num::f64::ZERO) {
        let band = Band::default();
        let l = band.radiance(t);
        prop_assert!(l.is_finite() && l >= 0.0);
        let d = band.radiance_derivative(t);
        prop_assert!(d.is_finite() && d >= 0.0);
        let back = band.temperature(t);
        prop_assert!(back.is_finite() && back >= 0.0);
    }

    #[test]
    fn no_nan_inf_or_panic_with_a_response(t in proptest::num::f64::NORMAL | proptest::num::f64::SUBNORMAL | proptest::num::f64::ZERO) {
        let srf = SensorResponse::new(vec![9.0, 10.0, 11.0], vec![0.5, 1.0, 0.5]).unwrap();
        let band = Band::default().with_response(&srf).unwrap();
        let l = band.radiance(t);
        prop_assert!(l.is_finite() && l >= 0.0);
        let d = band.radiance_derivative(t);
        prop_assert!(d.is_finite() && d >= 0.0);
        let back = band.temperature(t);
        prop_assert!(back.is_finite() && back >= 0.0);
    }

    #[test]
    fn radiance_increases_with_temperature(t in 2.0f64..1e6, f in 1.0001f64..2.0) {
        let band = Band::default();
        prop_assert!(band.radiance(t * f) > band.radiance(t));
    }

    /// Wien's displacement law: scanning the spectrum with a narrow triangular response
    /// (0.04 µm wide), the hotter body peaks at the shorter wavelength, and each peak is
    /// where b / T puts it (b = 2897.77 µm K) to within the scan step.
    #[test]
    fn wien_hotter_body_peaks_at_shorter_wavelength(t1 in 200.0f64..900.0, ratio in 1.2f64..3.0) {
        let t2 = t1 * ratio;
        let peak = |t: f64| {
            let mut best = (0.0, f64::MIN);
            let mut centre = 0.5;
            while centre < 20.0 {
                let srf = SensorResponse::new(
                    vec![centre - 0.02, centre, centre + 0.02],
                    vec![0.0, 1.0, 0.0],
                ).unwrap();
                let band = Band::new(centre - 0.02, centre + 0.02).unwrap().with_response(&srf).unwrap();
                let l = band.radiance(t);
                if l > best.1 {
                    best = (centre, l);
                }
                centre += 0.02;
            }
            best.0
        };
        let (p1, p2) = (peak(t1), peak(t2));
        prop_assert!(p2 < p1, "T1 {t1} peaks at {p1} µm, T2 {t2} at {p2} µm");
        prop_assert!((p1 - 2897.771955 / t1).abs() < 0.03);
        prop_assert!((p2 - 2897.771955 / t2).abs() < 0.03);
    }
}
