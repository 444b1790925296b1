//! [`RadianceTable`]: band radiance tabulated at a fixed temperature step and linearly
//! interpolated, the way the 1990 code used its `.rtt` file (thesis §3.1, Figure 9).

use crate::band::Band;
use crate::error::{RadiometryError, RadiometryErrorKind};

/// `L(T)` tabulated from `from_k` in steps of `step_k`, linearly interpolated; outside the
/// table it falls back to the exact [`Band::radiance`].
///
/// This exists to measure what the 1990 `.rtt` lookup costs against the exact integral
/// (`docs/accuracy.md`): linear interpolation of the convex `L(T)` always overestimates,
/// by at most `step² · max L'' / 8`.
///
/// ```
/// use irsig_radiometry::{Band, RadianceTable};
/// let band = Band::default();
/// let table = RadianceTable::new(&band, 200.0, 350.0, 1.0)?;
/// let (exact, tabulated) = (band.radiance(300.5), table.radiance(300.5));
/// assert!(tabulated >= exact && (tabulated - exact) / band.radiance_derivative(300.5) < 3e-3);
/// # Ok::<(), irsig_radiometry::RadiometryError>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct RadianceTable {
    band: Band,
    from_k: f64,
    step_k: f64,
    inverse_step: f64,
    radiance_w_m2_sr: Vec<f64>,
}

impl RadianceTable {
    /// Tabulates `band` at `from_k, from_k + step_k, …` up to and including `to_k`
    /// (the last row is the first at or beyond `to_k`).
    ///
    /// # Errors
    /// [`RadiometryErrorKind::InvalidTemperature`] unless `0 ≤ from_k < to_k`, both finite,
    /// `step_k > 0`, and the table has at most 10^7 rows.
    pub fn new(band: &Band, from_k: f64, to_k: f64, step_k: f64) -> Result<Self, RadiometryError> {
        let rows = ((to_k - from_k) / step_k).ceil() + 1.0;
        let valid = from_k.is_finite()
            && to_k.is_finite()
            && from_k >= 0.0
            && to_k > from_k
            && step_k.is_finite()
            && step_k > 0.0
            && rows <= 1e7;
        if !valid {
            return Err(RadiometryError::new(
                RadiometryErrorKind::InvalidTemperature,
                format!(
                    "a radiance table needs 0 ≤ from < to (K), a step > 0 and at most 1e7 rows, found {from_k} to {to_k} in steps of {step_k}"
                ),
            ));
        }
        let radiance_w_m2_sr = (0..rows as usize)
            .map(|i| band.radiance(from_k + step_k * i as f64))
            .collect();
        Ok(Self {
            band: band.clone(),
            from_k,
            step_k,
            inverse_step: 1.0 / step_k,
            radiance_w_m2_sr,
        })
    }

    /// The tabulated radiances, W m^-2 sr^-1, from `from_k` in steps of `step_k`.
    #[must_use]
    pub fn radiance_w_m2_sr(&self) -> &[f64] {
        &self.radiance_w_m2_sr
    }

    /// `L(t_k)` interpolated linearly between the two rows around it, W m^-2 sr^-1; the
    /// exact band radiance outside the table; NaN for NaN.
    #[must_use]
    pub fn radiance(&self, t_k: f64) -> f64 {
        let x = (t_k - self.from_k) * self.inverse_step;
        // NaN fails the first comparison and goes to the exact path, which returns NaN.
        if x >= 0.0 {
            #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
            // x ≥ 0, finite below
            let i = x as usize;
            if let (Some(&a), Some(&b)) = (
                self.radiance_w_m2_sr.get(i),
                self.radiance_w_m2_sr.get(i + 1),
            ) {
                let f = x - i as f64;
                return a + (b - a) * f;
            }
            #[allow(clippy::float_cmp)] // the last row itself
            if x == (self.radiance_w_m2_sr.len() - 1) as f64 {
                return self.radiance_w_m2_sr.last().copied().unwrap_or(f64::NAN);
            }
        }
        self.band.radiance(t_k)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_are_exact_and_between_them_the_error_is_under_the_bound() {
        let band = Band::default();
        let table = RadianceTable::new(&band, 200.0, 350.0, 5.0).unwrap();
        for i in 0..=30 {
            let t = 200.0 + 5.0 * f64::from(i);
            assert!(
                (table.radiance(t) / band.radiance(t) - 1.0).abs() < 1e-15,
                "{t}"
            );
        }
        // Linear interpolation error bound h² max|L''| / 8; L'' by central differences.
        let second = |t: f64| {
            let d = 1e-2;
            (band.radiance(t + d) - 2.0 * band.radiance(t) + band.radiance(t - d)) / (d * d)
        };
        let max_second = (0..=150)
            .map(|i| second(200.0 + f64::from(i)))
            .fold(0.0, f64::max);
        let bound = 25.0 * max_second / 8.0;
        for i in 0..1500 {
            let t = 200.0 + 0.1 * f64::from(i) + 0.037;
            let err = table.radiance(t) - band.radiance(t);
            assert!(
                err >= -1e-12 && err <= bound * 1.001,
                "{t}: {err} vs {bound}"
            );
        }
        // Outside: exact.
        assert!((table.radiance(400.0) - band.radiance(400.0)).abs() < 1e-12);
        assert!((table.radiance(100.0) - band.radiance(100.0)).abs() < 1e-12);
        assert!(table.radiance(f64::NAN).is_nan());
    }

    #[test]
    fn bad_ranges_are_refused() {
        let band = Band::default();
        assert!(RadianceTable::new(&band, 300.0, 200.0, 1.0).is_err());
        assert!(RadianceTable::new(&band, 200.0, 300.0, 0.0).is_err());
        assert!(RadianceTable::new(&band, 200.0, 300.0, f64::NAN).is_err());
        assert!(RadianceTable::new(&band, 0.0, 1e9, 1e-3).is_err());
    }
}
