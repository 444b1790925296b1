//! The named spectra: how a wave's spatial frequency is drawn for each, and the
//! correlation function each gives.
//!
//! A stationary random field with correlation function `C(r)` is, by the Wiener–Khinchin
//! theorem, a superposition of plane waves whose wave vectors are distributed as the
//! field's normalised power spectral density `S(k)`: `C(r) = E[cos(k·r)]` for `k ~ S`
//! (Shinozuka & Deodatis 1991, "Simulation of stochastic processes by spectral
//! representation"). So a field of a named spectrum needs only the distribution of
//! `|k|` for an isotropic `S` (directions uniform on the sphere). Lengths are made
//! dimensionless by the correlation length `ℓ`: `x = |k|·ℓ`.

use irsig_model::texture::{CorrelationLength, FieldSpectrum};

/// The spectrum's shape in units of its length scale.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Shape {
    /// `C(r) = exp(−r²/ℓ²)`: each component of `k·ℓ` normal with variance 2, so
    /// `|k|·ℓ/√2` follows the χ distribution of 3 degrees of freedom.
    Gaussian,
    /// `C(r) = exp(−r/ℓ)`: `S(k) ∝ (1 + k²ℓ²)⁻²` in 3-D (the multivariate Cauchy
    /// distribution, whose characteristic function is `exp(−|r|/ℓ)`); the radial CDF of
    /// `x = |k|·ℓ` is `(2/π)(atan x − x/(1 + x²))`.
    Exponential,
    /// `|k|` log-uniform between `k_min` and `k_max` (rad m⁻¹): equal variance per octave.
    OneOverF { k_min: f64, k_max: f64 },
}

impl Shape {
    /// The shape and its per-axis length scale, m (1 for 1/f, whose range is in metres).
    pub(crate) fn of(spectrum: &FieldSpectrum) -> (Self, [f64; 3]) {
        match spectrum {
            FieldSpectrum::Gaussian {
                correlation_length_m,
            } => (Self::Gaussian, correlation_length_m.per_axis_m()),
            FieldSpectrum::Exponential {
                correlation_length_m,
            } => (Self::Exponential, correlation_length_m.per_axis_m()),
            FieldSpectrum::OneOverF {
                shortest_m,
                longest_m,
            } => (
                Self::OneOverF {
                    k_min: std::f64::consts::TAU / longest_m,
                    k_max: std::f64::consts::TAU / shortest_m,
                },
                [1.0; 3],
            ),
        }
    }

    /// The radial quantile: the `|k|` (times the length scale) below which a share `u` of
    /// the spectrum's variance lies, `0 < u < 1`.
    pub(crate) fn radial_quantile(self, u: f64) -> f64 {
        match self {
            Self::Gaussian => std::f64::consts::SQRT_2 * invert_increasing(chi3_cdf, u, 0.0, 40.0),
            Self::Exponential => invert_increasing(cauchy3_cdf, u, 0.0, 1e12),
            Self::OneOverF { k_min, k_max } => k_min * (k_max / k_min).powf(u),
        }
    }

    /// `C(r)` at the dimensionless separation `r` (metres for 1/f, else in units of the
    /// length scale).
    pub(crate) fn correlation(self, r: f64) -> f64 {
        match self {
            Self::Gaussian => (-r * r).exp(),
            Self::Exponential => (-r).exp(),
            Self::OneOverF { k_min, k_max } => {
                // C(r) = ∫ p(k) sin(kr)/(kr) dk, p(k) = 1/(k ln(k_max/k_min)): the
                // isotropic average of cos(k·r), integrated in ln k by Simpson's rule on
                // a grid fine enough for the fastest oscillation over the range.
                let (a, b) = (k_min.ln(), k_max.ln());
                let n = (((b - a) * (k_max * r).max(1.0) * 8.0).ceil() as usize).clamp(64, 1 << 20);
                let n = n + n % 2;
                let h = (b - a) / n as f64;
                let f = |s: f64| sinc(s.exp() * r);
                let mut sum = f(a) + f(b);
                for i in 1..n {
                    sum += f(a + h * i as f64) * if i % 2 == 1 { 4.0 } else { 2.0 };
                }
                sum * h / 3.0 / (b - a)
            }
        }
    }
}

/// `sin x / x`, 1 at 0.
fn sinc(x: f64) -> f64 {
    if x.abs() < 1e-8 { 1.0 } else { x.sin() / x }
}

/// The CDF of the χ distribution with 3 degrees of freedom (the length of a standard
/// normal 3-vector): `erf(y/√2) − √(2/π)·y·exp(−y²/2)`.
fn chi3_cdf(y: f64) -> f64 {
    libm::erf(y / std::f64::consts::SQRT_2)
        - (2.0 / std::f64::consts::PI).sqrt() * y * (-0.5 * y * y).exp()
}

/// The radial CDF of the 3-D Cauchy spectrum, `(2/π)(atan x − x/(1 + x²))`.
fn cauchy3_cdf(x: f64) -> f64 {
    std::f64::consts::FRAC_2_PI * (x.atan() - x / (1.0 + x * x))
}

/// The `x` in `[lo, hi]` where the increasing `f` reaches `u`, by bisection (to the last
/// bit, a fixed number of steps: deterministic).
fn invert_increasing(f: fn(f64) -> f64, u: f64, mut lo: f64, mut hi: f64) -> f64 {
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if f(mid) < u {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// The correlation `C` the spectrum gives between two points `separation_m` apart:
/// the isotropic `C` at the separation stretched by the per-axis lengths.
#[must_use]
pub fn correlation(spectrum: &FieldSpectrum, separation_m: [f64; 3]) -> f64 {
    let (shape, lengths) = Shape::of(spectrum);
    let r = separation_m
        .iter()
        .zip(lengths)
        .map(|(d, l)| (d / l) * (d / l))
        .sum::<f64>()
        .sqrt();
    shape.correlation(r)
}

/// The correlation length along the unit `direction`, m: the separation at which the
/// correlation falls to 1/e. For a Gaussian or exponential spectrum this is `ℓ` along an
/// axis; for 1/f it follows from the range (found by bisection on [`correlation`]).
#[must_use]
pub fn correlation_length_m(spectrum: &FieldSpectrum, direction: [f64; 3]) -> f64 {
    let norm = direction.iter().map(|d| d * d).sum::<f64>().sqrt();
    let unit = direction.map(|d| d / norm);
    let at = |r: f64| correlation(spectrum, unit.map(|d| d * r));
    let target = (-1.0f64).exp();
    // Bracket the crossing, then bisect.
    let mut hi = match spectrum {
        FieldSpectrum::OneOverF { shortest_m, .. } => *shortest_m,
        FieldSpectrum::Gaussian {
            correlation_length_m,
        }
        | FieldSpectrum::Exponential {
            correlation_length_m,
        } => match correlation_length_m {
            CorrelationLength::Isotropic(l) => *l,
            CorrelationLength::PerAxis(x, y, z) => x.min(*y).min(*z),
        },
    };
    let mut lo = 0.0;
    while at(hi) > target && hi < 1e12 {
        lo = hi;
        hi *= 2.0;
    }
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if at(mid) > target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_radial_cdfs_are_distributions() {
        // Both start at 0 and reach 1; the χ₃ median is 1.5382 (tables of the χ
        // distribution: √(median of χ²₃) = √2.36597).
        assert!(chi3_cdf(0.0).abs() < 1e-15);
        assert!((chi3_cdf(40.0) - 1.0).abs() < 1e-15);
        assert!((chi3_cdf(2.36597f64.sqrt()) - 0.5).abs() < 1e-5);
        assert!(cauchy3_cdf(0.0).abs() < 1e-15);
        assert!((cauchy3_cdf(1e9) - 1.0).abs() < 1e-8);
        // (2/π)(π/4 − 1/2) at x = 1.
        let at_one = std::f64::consts::FRAC_2_PI * (std::f64::consts::FRAC_PI_4 - 0.5);
        assert!((cauchy3_cdf(1.0) - at_one).abs() < 1e-15);
        assert!((Shape::Exponential.radial_quantile(at_one) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn the_gaussian_and_exponential_lengths_are_their_1_over_e_points() {
        let iso = |l| CorrelationLength::Isotropic(l);
        let g = FieldSpectrum::Gaussian {
            correlation_length_m: iso(0.7),
        };
        let e = FieldSpectrum::Exponential {
            correlation_length_m: CorrelationLength::PerAxis(2.0, 0.5, 1.0),
        };
        assert!((correlation_length_m(&g, [1.0, 1.0, 0.0]) - 0.7).abs() < 1e-9);
        assert!((correlation_length_m(&e, [1.0, 0.0, 0.0]) - 2.0).abs() < 1e-9);
        assert!((correlation_length_m(&e, [0.0, 3.0, 0.0]) - 0.5).abs() < 1e-9);
        assert!((correlation(&g, [0.0; 3]) - 1.0).abs() < 1e-15);
    }

    #[test]
    fn the_one_over_f_correlation_follows_its_closed_form() {
        // C(r) = [sin a/a − sin b/b + Ci(b) − Ci(a)] / ln(k_max/k_min), a = k_min r,
        // b = k_max r; for a, b ≪ 1 the series of Ci gives C ≈ 1 − r²(k_max² − k_min²)
        // / (12 ln(k_max/k_min)) (the isotropic average of cos is 1 − k²r²/6 + …).
        let s = FieldSpectrum::OneOverF {
            shortest_m: 1.0,
            longest_m: 100.0,
        };
        let (k_min, k_max) = (std::f64::consts::TAU / 100.0, std::f64::consts::TAU);
        let r = 1e-3;
        let expected = 1.0 - r * r * (k_max * k_max - k_min * k_min) / (12.0 * 100f64.ln());
        assert!((correlation(&s, [r, 0.0, 0.0]) - expected).abs() < 1e-9);
        // Far beyond the longest wavelength the correlation has gone.
        assert!(correlation(&s, [1e4, 0.0, 0.0]).abs() < 1e-2);
        let l = correlation_length_m(&s, [0.0, 0.0, 1.0]);
        assert!(l > 1.0 && l < 100.0, "{l}");
        assert!((correlation(&s, [l, 0.0, 0.0]) - (-1.0f64).exp()).abs() < 1e-9);
    }
}
