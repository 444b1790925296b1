//! The sky's longwave irradiance when nothing measured or computed gives it: a named
//! parameterisation from the air at screen level.
//!
//! Clear sky: Prata (1996, "A new long-wave formula for estimating downward clear-sky
//! radiation at the surface", Q. J. R. Meteorol. Soc. 122, 1127–1151, eq. 21), an
//! effective emissivity from the precipitable water `w = 46.5 e / T` (g cm⁻², `e` the
//! vapour pressure in hPa, `T` the air temperature in K):
//! `ε_clear = 1 − (1 + w) exp(−√(1.2 + 3w))`. Prata gives its error against radiosonde
//! computations as about 10 W m⁻² (rms).
//!
//! Clouds: Crawford & Duchon (1999, "An improved parameterization for estimating effective
//! atmospheric emissivity for use in calculating daytime downwelling longwave radiation",
//! J. Appl. Meteorol. 38, 474–480, eq. 4): `ε = c + (1 − c) ε_clear`, `c` the cloud
//! fraction, as if the clouds were blackbodies at the air's temperature.
//!
//! `E = ε σ T⁴` on a horizontal surface.

use crate::latent::saturation_vapour_pressure_pa;
use crate::surface::STEFAN_BOLTZMANN_W_M2_K4;

/// Prata's clear-sky effective emissivity for air at `air_k` with vapour pressure
/// `vapour_pressure_pa`.
#[must_use]
pub fn prata_clear_sky_emissivity(air_k: f64, vapour_pressure_pa: f64) -> f64 {
    let w = 46.5 * (vapour_pressure_pa / 100.0) / air_k;
    1.0 - (1.0 + w) * (-(1.2 + 3.0 * w).sqrt()).exp()
}

/// The sky's longwave irradiance on a horizontal surface, W m⁻², from the air's
/// temperature and dew point (K) and the cloud fraction (0 to 1, clamped): Prata's clear
/// sky with Crawford & Duchon's clouds.
#[must_use]
pub fn clear_sky_longwave_w_m2(air_k: f64, dew_point_k: f64, cloud_fraction: f64) -> f64 {
    let (e, _) = saturation_vapour_pressure_pa(dew_point_k);
    let clear = prata_clear_sky_emissivity(air_k, e);
    let c = cloud_fraction.clamp(0.0, 1.0);
    (c + (1.0 - c) * clear) * STEFAN_BOLTZMANN_W_M2_K4 * air_k.powi(4)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn prata_by_hand() {
        // 15 °C air with 10 hPa of vapour: w = 46.5 · 10 / 288.15 = 1.6137 g/cm²,
        // √(1.2 + 4.8412) = 2.4579, e^−2.4579 = 0.085616, 1 − 2.6137 · 0.085616 = 0.77622;
        // E = 0.77622 · σ · 288.15⁴ = 0.77622 · 390.91 = 303.44 W/m².
        let eps = prata_clear_sky_emissivity(288.15, 1000.0);
        assert!((eps - 0.776_22).abs() < 1e-5, "{eps}");
        // The dew point whose saturation pressure is 10 hPa (Alduchov & Eskridge):
        // t = 243.04 x / (17.625 − x), x = ln(1000/610.94) = 0.49275: 6.9903 °C.
        let e = clear_sky_longwave_w_m2(288.15, 273.15 + 6.990_30, 0.0);
        assert!((e - 303.44).abs() < 0.01, "{e}");
    }

    #[test]
    fn overcast_is_a_blackbody_at_the_air_and_dry_air_emits_least() {
        let overcast = clear_sky_longwave_w_m2(280.0, 270.0, 1.0);
        let black = STEFAN_BOLTZMANN_W_M2_K4 * 280.0_f64.powi(4);
        assert!((overcast - black).abs() < 1e-9);
        // Drier air, a lower emissivity: monotone in the vapour pressure.
        let mut last = 0.0;
        for e in [10.0, 100.0, 500.0, 1000.0, 3000.0] {
            let eps = prata_clear_sky_emissivity(290.0, e);
            assert!(eps > last && eps < 1.0, "{e}: {eps}");
            last = eps;
        }
    }
}
