//! Blackbody band radiance for the sensor stage's radiance ↔ temperature conversions.
//!
//! irsig-radiometry's `Band` is the project's band model; it was not yet on main when this
//! tool was written, so the tool carries this plain blackbody band (flat response between
//! two wavelengths) behind the sensor model's `BandConversion` trait. Swapping in
//! `irsig_radiometry::Band` changes only [`crate::run`].
//!
//! Planck's law integrated by composite Simpson's rule on 128 intervals (relative error
//! below 1e-8 for 3–20 µm bands at 150–1000 K: the integrand varies on micrometre scales);
//! temperature by Newton's method on L(T) with the analytic dL/dT.

use irsig_sensor_model::quantise::BandConversion;

/// First radiation constant for radiance, 2hc², W m² sr⁻¹ (CODATA 2018, exact).
const C1L: f64 = 1.191_042_972_397_188_4e-16;
/// Second radiation constant, hc/k, m K (CODATA 2018, exact).
const C2: f64 = 1.438_776_877_503_933_8e-2;
const INTERVALS: usize = 128;

/// A flat-response band from `min_m` to `max_m` (metres).
#[derive(Debug, Clone, Copy)]
pub struct PlanckBand {
    min_m: f64,
    max_m: f64,
}

impl PlanckBand {
    /// The band between two wavelengths in micrometres (0 < min < max, checked by the
    /// caller).
    #[must_use]
    pub fn new(min_um: f64, max_um: f64) -> Self {
        Self {
            min_m: min_um * 1e-6,
            max_m: max_um * 1e-6,
        }
    }

    /// Simpson's rule of `f(λ)` over the band.
    fn integrate(&self, f: impl Fn(f64) -> f64) -> f64 {
        let h = (self.max_m - self.min_m) / INTERVALS as f64;
        let mut sum = f(self.min_m) + f(self.max_m);
        for i in 1..INTERVALS {
            let w = if i % 2 == 1 { 4.0 } else { 2.0 };
            sum += w * f(self.min_m + h * i as f64);
        }
        sum * h / 3.0
    }
}

impl BandConversion for PlanckBand {
    fn radiance(&self, t_k: f64) -> f64 {
        if t_k <= 0.0 {
            return 0.0;
        }
        self.integrate(|l| C1L / l.powi(5) / (C2 / (l * t_k)).exp_m1())
    }

    fn radiance_derivative(&self, t_k: f64) -> f64 {
        if t_k <= 0.0 {
            return 0.0;
        }
        self.integrate(|l| {
            let x = C2 / (l * t_k);
            let e = x.exp();
            C1L / l.powi(5) * e * x / (t_k * (e - 1.0).powi(2))
        })
    }

    /// NaN for a radiance ≤ 0 or not finite (no blackbody temperature gives it).
    fn temperature(&self, radiance_w_m2_sr: f64) -> f64 {
        if !(radiance_w_m2_sr.is_finite() && radiance_w_m2_sr > 0.0) {
            return f64::NAN;
        }
        // Start from the temperature at which the band's mid-wavelength Wien
        // approximation gives this radiance, then Newton (L is convex and increasing).
        let mut t = 300.0;
        for _ in 0..60 {
            let l = self.radiance(t);
            let d = self.radiance_derivative(t);
            if d.is_nan() || d <= 0.0 {
                t *= 2.0;
                continue;
            }
            let step = (l - radiance_w_m2_sr) / d;
            // Never step below half the current temperature (L collapses quickly there).
            let next = (t - step).max(t / 2.0);
            if (next - t).abs() < 1e-10 * t {
                return next;
            }
            t = next;
        }
        t
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn band_radiance_matches_the_blackbody_fraction_tables() {
        // F(0→λT): F(2400 µm K) = 0.140 256, F(4200 µm K) = 0.516 046 (Planck integrals):
        // 8–14 µm at 300 K holds 0.375 79 of σT⁴/π = 146.19 W m^-2 sr^-1 = 54.94.
        let b = PlanckBand::new(8.0, 14.0);
        let l = b.radiance(300.0);
        assert!((l / 54.94 - 1.0).abs() < 1e-3, "{l}");
        let d = b.radiance_derivative(300.0);
        let numeric = (b.radiance(300.01) - b.radiance(299.99)) / 0.02;
        assert!((d / numeric - 1.0).abs() < 1e-6);
    }

    #[test]
    fn temperature_inverts_radiance_from_cold_to_hot() {
        let b = PlanckBand::new(8.0, 14.0);
        for t in [150.0, 220.0, 273.15, 300.0, 350.0, 600.0, 1000.0] {
            let back = b.temperature(b.radiance(t));
            assert!((back - t).abs() < 1e-6, "{t}: {back}");
        }
        assert!(b.temperature(0.0).is_nan() && b.temperature(-1.0).is_nan());
    }
}
