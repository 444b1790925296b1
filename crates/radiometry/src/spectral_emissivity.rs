//! A spectral emissivity ε(λ) averaged over a band: the single value whose product with
//! the band radiance `L(T)` is the radiance the surface emits in the band at `T`.

use irsig_model::interp;

use crate::planck_weights;
use crate::{Band, RadiometryError, RadiometryErrorKind};

/// The band average of a spectral emissivity (linear between its samples):
///
/// ```text
/// ε̄ = ∫ ε(λ) S(λ) B_λ(λ, T) dλ / ∫ S(λ) B_λ(λ, T) dλ   over [λmin, λmax] of `band`,
/// ```
///
/// `S` the band's response (1 when flat), `B_λ` Planck's radiance at `temperature_k`,
/// by Gauss–Legendre quadrature on every piece between the band's limits, the curve's
/// wavelengths and the response's ([`crate::planck_weights`]).
///
/// # Errors
/// - [`RadiometryErrorKind::InvalidEmissivity`]: the curve has fewer than two samples,
///   lengths differ, or it does not cover the band where the response is not zero (it is
///   not extrapolated); the message says what it covers and what is needed.
/// - [`RadiometryErrorKind::InvalidTemperature`] unless `temperature_k` is within
///   [`irsig_model::limits::PLANCK_WEIGHTING_K`].
/// - [`RadiometryErrorKind::InvalidResponse`] when the weights are zero across the band.
pub fn band_average_emissivity(
    wavelength_um: &[f64],
    emissivity: &[f64],
    band: &Band,
    temperature_k: f64,
) -> Result<f64, RadiometryError> {
    let values = band_average_emissivities(wavelength_um, &[emissivity], band, temperature_k)?;
    Ok(values[0])
}

/// [`band_average_emissivity`] of several curves on the same wavelengths (the columns of
/// an angular table, one per angle), the quadrature's nodes found once: each value is the
/// one [`band_average_emissivity`] gives for its curve.
///
/// # Errors
/// As [`band_average_emissivity`], for the first curve that has one.
pub fn band_average_emissivities(
    wavelength_um: &[f64],
    curves: &[&[f64]],
    band: &Band,
    temperature_k: f64,
) -> Result<Vec<f64>, RadiometryError> {
    let bad = |m: String| RadiometryError::new(RadiometryErrorKind::InvalidEmissivity, m);
    for emissivity in curves {
        if wavelength_um.len() < 2 || wavelength_um.len() != emissivity.len() {
            return Err(bad(format!(
                "a spectral emissivity needs at least two samples and one emissivity per \
                 wavelength ({} wavelengths, {} emissivities)",
                wavelength_um.len(),
                emissivity.len()
            )));
        }
    }
    if curves.is_empty() {
        return Ok(Vec::new());
    }
    let nodes = planck_weights::nodes(band, temperature_k, wavelength_um, |lo, hi| {
        let (first, last) = (wavelength_um[0], wavelength_um[wavelength_um.len() - 1]);
        if first > lo || last < hi {
            return Err(bad(format!(
                "the spectral emissivity covers {first}–{last} µm but the band needs \
                 {lo}–{hi} µm (it is not extrapolated)"
            )));
        }
        Ok(())
    })?;
    Ok(curves
        .iter()
        .map(|emissivity| {
            let eps_at = |l: f64| {
                let (k, t) = interp::locate(wavelength_um, l);
                interp::lerp(emissivity[k], emissivity[k + 1], t)
            };
            let (num, den) = nodes.iter().fold((0.0, 0.0), |(num, den), n| {
                (num + n.weight * eps_at(n.wavelength_um), den + n.weight)
            });
            (num / den).clamp(0.0, 1.0)
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spectral_radiance_per_um;

    /// ∫ B dλ over [a, b] by composite Simpson (2000 intervals), the test's own sum.
    fn planck_integral(a: f64, b: f64, t: f64) -> f64 {
        let n = 2000;
        let h = (b - a) / f64::from(n);
        let mut s = spectral_radiance_per_um(a, t) + spectral_radiance_per_um(b, t);
        for i in 1..n {
            let w = if i % 2 == 1 { 4.0 } else { 2.0 };
            s += w * spectral_radiance_per_um(a + h * f64::from(i), t);
        }
        s * h / 3.0
    }

    #[test]
    fn curves_averaged_together_are_each_averaged_as_alone() {
        // The step of the test below and a constant on the same wavelengths: the step's
        // Planck shares (Simpson's sums) and the constant itself, each bit for bit what
        // `band_average_emissivity` gives it.
        let w = [7.0, 10.0, 10.000_001, 15.0];
        let step = [0.5, 0.5, 0.9, 0.9];
        let constant = [0.7; 4];
        let band = Band::new(8.0, 14.0).unwrap();
        let both = band_average_emissivities(&w, &[&step, &constant], &band, 300.0).unwrap();
        let (lo, hi) = (
            planck_integral(8.0, 10.0, 300.0),
            planck_integral(10.0, 14.0, 300.0),
        );
        assert!((both[0] - (0.5 * lo + 0.9 * hi) / (lo + hi)).abs() < 1e-7);
        assert!((both[1] - 0.7).abs() < 1e-12);
        for (curve, value) in [(&step, both[0]), (&constant, both[1])] {
            let alone = band_average_emissivity(&w, curve, &band, 300.0).unwrap();
            assert_eq!(alone.to_bits(), value.to_bits());
        }
        // A curve of the wrong length is refused, whichever it is.
        let short = [0.7; 3];
        assert!(band_average_emissivities(&w, &[&step, &short], &band, 300.0).is_err());
    }

    #[test]
    fn a_step_averages_to_the_planck_shares_of_its_two_sides() {
        // ε = 0.5 below 10 µm and 0.9 above (the step between 10 and 10.000001 µm):
        // ε̄ = (0.5 ∫₈¹⁰ B + 0.9 ∫₁₀¹⁴ B) / ∫₈¹⁴ B.
        let w = [7.0, 10.0, 10.000_001, 15.0];
        let e = [0.5, 0.5, 0.9, 0.9];
        let band = Band::new(8.0, 14.0).unwrap();
        for t in [250.0, 300.0, 350.0] {
            let (lo, hi) = (
                planck_integral(8.0, 10.0, t),
                planck_integral(10.0, 14.0, t),
            );
            let expected = (0.5 * lo + 0.9 * hi) / (lo + hi);
            let got = band_average_emissivity(&w, &e, &band, t).unwrap();
            assert!((got - expected).abs() < 1e-7, "{t} K: {got} vs {expected}");
        }
        // A constant curve averages to itself; a sub-band of one side is that side.
        let sub = Band::new(10.5, 12.0).unwrap();
        assert!((band_average_emissivity(&w, &e, &sub, 300.0).unwrap() - 0.9).abs() < 1e-12);
    }

    #[test]
    fn a_curve_short_of_the_band_is_refused() {
        let band = Band::new(8.0, 14.0).unwrap();
        let err = band_average_emissivity(&[8.5, 14.0], &[0.9, 0.9], &band, 300.0).unwrap_err();
        assert!(err.to_string().contains("8.5–14 µm"), "{err}");
        assert!(err.to_string().contains("8–14 µm"), "{err}");
        assert!(band_average_emissivity(&[8.0], &[0.9], &band, 300.0).is_err());
        assert!(band_average_emissivity(&[8.0, 14.0], &[0.9, 0.9], &band, f64::NAN).is_err());
    }
}
