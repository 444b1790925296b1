//! Latent heat of a wet surface: evaporation, and condensation below the dew point.
//!
//! The model: the wet share `f_w` of the surface is a film of liquid water at the surface
//! temperature `T_s`. Water vapour leaves it at the rate the Chilton–Colburn (Lewis)
//! analogy gives from the convective heat transfer coefficient `h` (Incropera & DeWitt,
//! *Fundamentals of Heat and Mass Transfer*, 6th ed., §6.7.2, eq. 6.60 with `n = 1/3`):
//! `h_m = h / (ρ c_p Le^⅔)`, so the mass flux is `ρ h_m (q_s − q_a)` in specific humidity,
//! with `q ≈ 0.622 e / p` (Monteith & Unsworth, *Principles of Environmental Physics*,
//! 4th ed., §3.1.2: the form behind the psychrometric constant). The latent heat flux is
//! `f_w · h / (c_p Le^⅔) · 0.622 (e_s(T_s) − e_a) / p · L_v(T_s)`, positive when water
//! evaporates (heat leaves the surface), negative when it condenses on a surface below the
//! dew point.
//!
//! - `e_s(T)`: saturation vapour pressure over liquid water, Alduchov & Eskridge (1996,
//!   J. Appl. Meteor. 35, 601–609, their AERK form):
//!   `e_s = 610.94 exp(17.625 t / (t + 243.04))` Pa, `t` in °C; fitted for −40 to 50 °C.
//!   `e_a = e_s(T_dew)`, the air's vapour pressure from its dew point.
//! - `L_v(T) = 1.91846e6 (T / (T − 33.91))²` J kg⁻¹, Henderson-Sellers (1984, Q. J. R.
//!   Meteorol. Soc. 110, 1186–1190), fitted for about −20 to 40 °C (2.501 MJ/kg at 0 °C).
//! - `c_p = 1005` J kg⁻¹ K⁻¹ (dry air, Incropera Table A.4; moist air's differs by under
//!   2 %), `Le = α / D_AB = 0.865` for water vapour in air near 300 K (`α` of air
//!   22.5e-6 m²/s, Table A.4; `D_AB` 0.26e-4 m²/s, Table A.8).
//!
//! Limits, stated: the wet share stays wet (no drying out, no puddle depth, no
//! rain); no freezing or frost (below 0 °C the film is supercooled water); the vapour
//! pressure formulas are held at their values at −100 °C and 100 °C outside that range,
//! where liquid water on a surface at one atmosphere is not meant; the surface's own
//! heat capacity is its wall's.

/// `0.622`: the ratio of the molar masses of water and dry air, `M_w / M_d`.
const EPSILON: f64 = 0.622;
/// Specific heat of dry air at constant pressure, J kg⁻¹ K⁻¹.
const CP_AIR_J_KG_K: f64 = 1005.0;
/// Lewis number of water vapour in air, `α / D_AB`.
const LEWIS: f64 = 0.865;
/// The lowest and highest temperatures at which the vapour pressure and latent heat are
/// evaluated; outside, they are held.
const CLAMP_MIN_K: f64 = 173.15;
const CLAMP_MAX_K: f64 = 373.15;
const CELSIUS_ZERO_K: f64 = 273.15;

/// Saturation vapour pressure over liquid water, Pa, and its derivative in T, Pa K⁻¹
/// (Alduchov & Eskridge 1996), held outside −100 to 100 °C.
#[must_use]
pub fn saturation_vapour_pressure_pa(temperature_k: f64) -> (f64, f64) {
    let clamped = temperature_k.clamp(CLAMP_MIN_K, CLAMP_MAX_K);
    let t = clamped - CELSIUS_ZERO_K;
    let denominator = t + 243.04;
    let e = 610.94 * (17.625 * t / denominator).exp();
    let de = if (CLAMP_MIN_K..=CLAMP_MAX_K).contains(&temperature_k) {
        e * 17.625 * 243.04 / (denominator * denominator)
    } else {
        0.0
    };
    (e, de)
}

/// Latent heat of vaporisation of water, J kg⁻¹, and its derivative in T, J kg⁻¹ K⁻¹
/// (Henderson-Sellers 1984), held outside −100 to 100 °C.
#[must_use]
pub fn latent_heat_j_kg(temperature_k: f64) -> (f64, f64) {
    const A_K: f64 = 33.91;
    let clamped = temperature_k.clamp(CLAMP_MIN_K, CLAMP_MAX_K);
    let ratio = clamped / (clamped - A_K);
    let l = 1.918_46e6 * ratio * ratio;
    let dl = if (CLAMP_MIN_K..=CLAMP_MAX_K).contains(&temperature_k) {
        -2.0 * l * A_K / (clamped * (clamped - A_K))
    } else {
        0.0
    };
    (l, dl)
}

/// The latent model with the air's state fixed, for one set of loads.
#[derive(Debug, Clone, Copy)]
pub(crate) struct LatentAt {
    /// `f_w · 0.622 / (p c_p Le^⅔)`, so that the flux is `coefficient · h · L_v ·
    /// (e_s − e_a)`; 0 for a dry surface.
    coefficient: f64,
    /// The air's vapour pressure `e_a`, Pa.
    vapour_pressure_air_pa: f64,
}

/// The latent heat flux and its derivative at one surface temperature.
#[derive(Debug, Clone, Copy)]
pub(crate) struct LatentEval {
    /// W m⁻², positive for evaporation.
    pub flux_w_m2: f64,
    /// Its derivative in the surface temperature, W m⁻² K⁻¹.
    pub derivative_w_m2_k: f64,
}

impl LatentAt {
    pub(crate) fn new(wet_fraction: f64, dew_point_k: f64, pressure_pa: f64) -> Self {
        if wet_fraction == 0.0 {
            return Self {
                coefficient: 0.0,
                vapour_pressure_air_pa: 0.0,
            };
        }
        let le_two_thirds = LEWIS.powf(2.0 / 3.0);
        Self {
            coefficient: wet_fraction * EPSILON / (pressure_pa * CP_AIR_J_KG_K * le_two_thirds),
            vapour_pressure_air_pa: saturation_vapour_pressure_pa(dew_point_k).0,
        }
    }

    pub(crate) fn is_dry(&self) -> bool {
        self.coefficient == 0.0
    }

    /// The flux at `surface_k` given the convective coefficient `h` and `dh/dT_s` there.
    #[inline]
    pub(crate) fn eval(&self, surface_k: f64, h: f64, dh_dt: f64) -> LatentEval {
        if self.is_dry() {
            return LatentEval {
                flux_w_m2: 0.0,
                derivative_w_m2_k: 0.0,
            };
        }
        let (es, des) = saturation_vapour_pressure_pa(surface_k);
        let (l, dl) = latent_heat_j_kg(surface_k);
        let deficit = es - self.vapour_pressure_air_pa;
        LatentEval {
            flux_w_m2: self.coefficient * h * l * deficit,
            derivative_w_m2_k: self.coefficient
                * (dh_dt * l * deficit + h * (dl * deficit + l * des)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vapour_pressure_against_tabulated_values() {
        // Saturation over water (CRC Handbook / WMO tables): 611.2 Pa at 0 °C, 2339 Pa at
        // 20 °C, 4246 Pa at 30 °C, 12 350 Pa at 50 °C; the AERK fit is within 0.4 % here.
        for (t_c, want) in [
            (0.0, 611.2),
            (20.0, 2339.0),
            (30.0, 4246.0),
            (50.0, 12_350.0),
        ] {
            let (e, _) = saturation_vapour_pressure_pa(t_c + 273.15);
            assert!((e / want - 1.0).abs() < 4e-3, "{t_c} °C: {e} vs {want}");
        }
        // Held, finite and positive at the extremes.
        for t in [1.0, 50.0, 1500.0, 5000.0] {
            let (e, de) = saturation_vapour_pressure_pa(t);
            assert!(e.is_finite() && e >= 0.0 && de == 0.0, "{t}: {e} {de}");
        }
    }

    #[test]
    fn latent_heat_against_tabulated_values() {
        // Steam tables: 2501 kJ/kg at 0 °C, 2454 kJ/kg at 20 °C, 2406 kJ/kg at 40 °C.
        for (t_c, want) in [(0.0, 2.501e6), (20.0, 2.454e6), (40.0, 2.406e6)] {
            let (l, _) = latent_heat_j_kg(t_c + 273.15);
            assert!((l / want - 1.0).abs() < 3e-3, "{t_c} °C: {l} vs {want}");
        }
    }

    #[test]
    fn derivatives_match_difference_quotients() {
        for t in [250.0, 290.0, 330.0] {
            let step = 1e-4;
            let (_, de) = saturation_vapour_pressure_pa(t);
            let numeric = (saturation_vapour_pressure_pa(t + step).0
                - saturation_vapour_pressure_pa(t - step).0)
                / (2.0 * step);
            assert!((de / numeric - 1.0).abs() < 1e-7);
            let (_, dl) = latent_heat_j_kg(t);
            let numeric =
                (latent_heat_j_kg(t + step).0 - latent_heat_j_kg(t - step).0) / (2.0 * step);
            assert!((dl / numeric - 1.0).abs() < 1e-6);
        }
    }

    #[test]
    fn a_wet_surface_by_hand() {
        // Fully wet, 25 °C surface, air with a 10 °C dew point at 101 325 Pa, h = 10:
        // e_s(25 °C) = 3161.7 Pa, e_a = e_s(10 °C) = 1226.0 Pa, L_v(25 °C) = 2.4424e6 J/kg,
        // Le^⅔ = 0.90784: 10 / (1005 · 0.90784) · 0.622 · 1935.7 / 101325 · 2.4424e6
        // = 318.1 W/m².
        let latent = LatentAt::new(1.0, 283.15, 101_325.0);
        let e = latent.eval(298.15, 10.0, 0.0);
        assert!((e.flux_w_m2 - 318.1).abs() < 0.1, "{}", e.flux_w_m2);
        // Below the dew point it condenses: the flux turns negative.
        assert!(latent.eval(280.0, 10.0, 0.0).flux_w_m2 < 0.0);
        // Half wet, half the flux.
        let half = LatentAt::new(0.5, 283.15, 101_325.0).eval(298.15, 10.0, 0.0);
        assert!((half.flux_w_m2 - 0.5 * e.flux_w_m2).abs() < 1e-9);
    }
}
