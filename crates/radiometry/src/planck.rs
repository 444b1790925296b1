//! The Planck integral over a wavelength interval, in closed form (series), for a flat
//! (SRF = 1) band.
//!
//! With `x = c2 / (λ T)` the band radiance over `[λ1, λ2]` is
//!
//! ```text
//! L(T) = c1L T^4 / c2^4 · [P(x1) − P(x2)],   P(x) = ∫_0^x t^3 / (e^t − 1) dt,
//! x1 = c2 / (λ1 T) > x2 = c2 / (λ2 T).
//! ```
//!
//! `P` is evaluated by one of two convergent series, whichever converges fast at `x`:
//!
//! - for `x ≥ 2`, the exponential series of the tail
//!   `∫_x^∞ t^3/(e^t−1) dt = Σ_{n≥1} e^{−nx} (x^3/n + 3x^2/n^2 + 6x/n^3 + 6/n^4)`
//!   (at most ~20 terms, one `exp` in all);
//! - for `x < 2`, the Bernoulli series `P(x) = x^3 Q(x)`, `Q(x) = Σ B_n x^n / ((n+3) n!)`,
//!   which converges for `x < 2π` (ratio of successive even terms about `(x/2π)^2 ≤ 0.1`).
//!
//! Keeping `x^3` factored out of `Q` lets the hot (small-`x`) branch be written as
//! `c1L/c2 · T · Q(x)/λ^3`, which does not overflow until the radiance itself does.
//! The test suite checks both branches against adaptive quadrature of the Planck function.

use crate::constants::{C1L_W_M2_SR, C2_M_K};

/// Where the evaluation switches from the Bernoulli series to the exponential tail series.
const SERIES_SWITCH_X: f64 = 2.0;

/// `P(∞) = π^4 / 15`.
const P_INFINITY: f64 =
    std::f64::consts::PI * std::f64::consts::PI * std::f64::consts::PI * std::f64::consts::PI
        / 15.0;

/// Coefficients `a_n = B_n / ((n+3) n!)` of `Q(x) = Σ a_n x^n`, for n = 0, 1, 2, 4, 6, ..., 40
/// (B_1 = −1/2; odd Bernoulli numbers beyond B_1 vanish). Computed exactly with rationals
/// and rounded to f64.
const Q_ODD_1: f64 = -0.125;
const Q_EVEN: [f64; 21] = [
    0.333_333_333_333_333_3,
    0.016_666_666_666_666_666,
    -0.000_198_412_698_412_698_4,
    3.674_309_229_864_785_5e-6,
    -7.515_632_515_632_516e-8,
    1.605_904_383_682_161_5e-9,
    -3.522_793_425_791_662e-11,
    7.872_080_312_167_458e-13,
    -1.784_042_261_222_412e-14,
    4.088_600_979_179_926e-16,
    -9.455_950_863_295_921e-18,
    2.203_601_131_344_092e-19,
    -5.168_320_254_004_638_5e-21,
    1.218_864_496_423_954_2e-22,
    -2.888_231_428_076_628e-24,
    6.872_583_188_902_07e-26,
    -1.641_368_762_534_915e-27,
    3.932_898_582_742_878_4e-29,
    -9.451_269_078_629_001e-31,
    2.277_252_257_828_059_7e-32,
    -5.500_052_129_536_348e-34,
];

/// `Q(x) = P(x)/x^3` and `S(x) = Q(x) − x Q'(x)` (the derivative term), for `0 ≤ x < 2`.
fn q_and_s(x: f64) -> (f64, f64) {
    // Sum the even part from the smallest term up (Horner in x^2), then add the odd term.
    let x2 = x * x;
    let mut q = 0.0;
    let mut s = 0.0;
    for (i, &a) in Q_EVEN.iter().enumerate().rev() {
        // Term index n = 2i; in S it is weighted by (1 − n).
        let n = 2.0 * i as f64;
        q = q * x2 + a;
        s = s * x2 + a * (1.0 - n);
    }
    // Odd term n = 1 has weight (1 − 1) = 0 in S.
    (q + Q_ODD_1 * x, s)
}

/// The tail `∫_x^∞ t^3/(e^t − 1) dt` and the integrand `x^4/(e^x − 1)`... both scaled to be
/// safe for any `x ≥ 2`; returns `(tail, x^4 / (e^x − 1))`.
fn tail_and_edge(x: f64) -> (f64, f64) {
    let e = (-x).exp();
    if e == 0.0 {
        // exp underflowed: both are below the smallest subnormal times a polynomial; also
        // avoids 0 · ∞ when x^3 overflows.
        return (0.0, 0.0);
    }
    let x2 = x * x;
    let x3 = x2 * x;
    let mut en = e;
    let mut sum = 0.0;
    let mut n = 1.0_f64;
    loop {
        let inv = 1.0 / n;
        let term = en * inv * (x3 + inv * (3.0 * x2 + inv * (6.0 * x + 6.0 * inv)));
        sum += term;
        if term <= 1e-17 * sum || n >= 60.0 {
            break;
        }
        en *= e;
        n += 1.0;
    }
    // x^4/(e^x − 1) = x^4 e^{−x} / (1 − e^{−x}); 1 − e^{−x} ≥ 1 − e^{−2} here.
    let edge = x3 * x * e / (1.0 - e);
    (sum, edge)
}

/// Band radiance (W m^-2 sr^-1) and its temperature derivative (W m^-2 sr^-1 K^-1) of a
/// blackbody at `t_k` over `[lambda1_m, lambda2_m]`, SRF = 1. `t_k` must be positive and
/// finite and `0 < lambda1_m < lambda2_m`; the radiance saturates at `f64::MAX`.
/// Planck's spectral radiance at one wavelength, W m⁻² sr⁻¹ µm⁻¹:
/// `c1L / (λ⁵ (exp(c2 / (λ T)) − 1))`, 0 for `T ≤ 0`. For weighting spectral quantities by
/// a blackbody (a sub-band's transmittance as its target sees it), not for band radiances,
/// which [`crate::Band`] integrates.
#[must_use]
pub fn spectral_radiance_per_um(wavelength_um: f64, t_k: f64) -> f64 {
    if t_k <= 0.0 {
        return 0.0;
    }
    let l = wavelength_um * 1e-6;
    C1L_W_M2_SR / (l.powi(5) * (C2_M_K / (l * t_k)).exp_m1()) * 1e-6
}

pub(crate) fn flat_band(lambda1_m: f64, lambda2_m: f64, t_k: f64) -> (f64, f64) {
    let x1 = C2_M_K / (lambda1_m * t_k);
    let x2 = C2_M_K / (lambda2_m * t_k);
    if x1 < SERIES_SWITCH_X {
        // Hot: both ends on the Bernoulli series, written without T^4 (see module docs).
        let (q1, s1) = q_and_s(x1);
        let (q2, s2) = q_and_s(x2);
        let inv1 = 1.0 / (lambda1_m * lambda1_m * lambda1_m);
        let inv2 = 1.0 / (lambda2_m * lambda2_m * lambda2_m);
        let k = C1L_W_M2_SR / C2_M_K;
        let radiance = k * t_k * (q1 * inv1 - q2 * inv2);
        let derivative = k * (s1 * inv1 - s2 * inv2);
        return (radiance.min(f64::MAX), derivative);
    }
    // Here T ≤ c2/(2 λ1): T^4 cannot overflow.
    let (tail1, edge1) = tail_and_edge(x1);
    let difference;
    let edge2;
    if x2 >= SERIES_SWITCH_X {
        let (tail2, e2) = tail_and_edge(x2);
        difference = tail2 - tail1;
        edge2 = e2;
    } else {
        let (q2, _) = q_and_s(x2);
        let x2_cubed = x2 * x2 * x2;
        difference = (P_INFINITY - tail1) - x2_cubed * q2;
        // x^4/(e^x − 1) for x < 2, with expm1 for accuracy as x → 0.
        edge2 = x2_cubed * x2 / x2.exp_m1();
    }
    let t3 = t_k * t_k * t_k;
    let scale = C1L_W_M2_SR / (C2_M_K * C2_M_K * C2_M_K * C2_M_K);
    let radiance = scale * t3 * t_k * difference;
    // d/dT of T^4 [P(x1) − P(x2)] with dx/dT = −x/T.
    let derivative = scale * t3 * (4.0 * difference - edge1 + edge2);
    (radiance, derivative)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_spectral_radiance_integrates_to_the_band_and_peaks_at_wiens_wavelength() {
        // Simpson over 8-14 um against the closed-form band.
        let n = 2000;
        let h = 6.0 / f64::from(n);
        let mut s = spectral_radiance_per_um(8.0, 300.0) + spectral_radiance_per_um(14.0, 300.0);
        for i in 1..n {
            let w = if i % 2 == 1 { 4.0 } else { 2.0 };
            s += w * spectral_radiance_per_um(8.0 + h * f64::from(i), 300.0);
        }
        let band = flat_band(8e-6, 14e-6, 300.0).0;
        assert!(
            (s * h / 3.0 / band - 1.0).abs() < 1e-10,
            "{} vs {band}",
            s * h / 3.0
        );
        // Wien: λ_max T = 2897.77 um K.
        let peak = 2_897.771_955 / 300.0;
        let at = |l: f64| spectral_radiance_per_um(l, 300.0);
        assert!(at(peak) > at(peak - 0.01) && at(peak) > at(peak + 0.01));
        assert!(spectral_radiance_per_um(10.0, 0.0).abs() < f64::MIN_POSITIVE);
    }

    /// P(x) by composite Simpson on a fine grid: an independent check of both series near
    /// the switch point, where either could be off.
    fn p_simpson(x: f64) -> f64 {
        let n = 20_000;
        let h = x / f64::from(n);
        let f = |t: f64| {
            if t == 0.0 {
                0.0
            } else {
                t * t * t / t.exp_m1()
            }
        };
        let mut sum = f(0.0) + f(x);
        for i in 1..n {
            let w = if i % 2 == 1 { 4.0 } else { 2.0 };
            sum += w * f(h * f64::from(i));
        }
        sum * h / 3.0
    }

    #[test]
    fn both_series_agree_with_quadrature_across_the_switch() {
        for &x in &[0.01, 0.5, 1.0, 1.9, 1.999, 2.0, 2.001, 3.0, 6.0, 20.0] {
            let series = if x < SERIES_SWITCH_X {
                x * x * x * q_and_s(x).0
            } else {
                P_INFINITY - tail_and_edge(x).0
            };
            let reference = p_simpson(x);
            assert!(
                (series / reference - 1.0).abs() < 1e-12,
                "x = {x}: series {series}, quadrature {reference}"
            );
        }
    }
}
