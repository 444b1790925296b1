//! Convection from a surface to the outdoor air: named, cited correlations.

use irsig_model::thermal::Roughness;

/// How a facet's surface faces the sky and the wind.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Orientation {
    /// The facet's outward normal · up, −1 (facing down) to 1 (facing up); 0 for a
    /// vertical wall. Sets the natural-convection regime of [`Convection::Doe2`].
    pub cos_tilt: f64,
    /// Whether the wind blows onto the facet (its outward normal within 100° of the
    /// direction the wind comes from, as EnergyPlus defines it) rather than it lying in
    /// the lee.
    pub windward: bool,
}

/// The convective heat transfer coefficient `h` (W m⁻² K⁻¹) between a surface and the
/// outdoor air, the flux being `h (T_s − T_air)`. `V` is the wind speed at the facet, m/s
/// (the tool gives the local wind speed; the correlations were fitted to wind near the
/// surface's height).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Convection {
    /// A given coefficient, for tests and for users who know `h` (0 for none; a very large
    /// one ties the surface to the air temperature).
    Fixed {
        /// The coefficient, W m⁻² K⁻¹, 0 to 1e12.
        h_w_m2_k: f64,
    },
    /// `h = 5.7 + 3.8 V`: McAdams (1954, *Heat Transmission*, 3rd ed.) from Jürges'
    /// wind-tunnel measurements on a heated 0.5 m square plate, as Duffie & Beckman give it
    /// (*Solar Engineering of Thermal Processes*, §3.15). Jürges' measurements cover wind
    /// speeds up to about 5 m/s, the range usually quoted with it; above that it is
    /// extrapolated. Independent of the surface's size, tilt and temperature, and, Duffie &
    /// Beckman note, probably including some free convection and radiation, so it
    /// overestimates pure convection somewhat.
    McAdams,
    /// The DOE-2 exterior correlation as the EnergyPlus Engineering Reference gives it
    /// ("Outside Surface Heat Balance", DOE-2 model; after Yazdanian & Klems 1994, ASHRAE
    /// Trans. 100(1) 1087, and DOE-2.1E):
    /// `h = h_n + R_f (√(h_n² + (a V^b)²) − h_n)`, with `a = 3.26`, `b = 0.89` windward and
    /// `a = 3.55`, `b = 0.617` leeward (the MoWITT smooth-surface forced coefficients),
    /// `R_f` the roughness multiplier ([`Roughness::multiplier`]), and `h_n` the natural
    /// convection of TARP (Walton 1983, NBSIR 83-2655, pp. 79–80), from `ΔT = T_s − T_air`
    /// and the tilt Σ (`cos Σ` = [`Orientation::cos_tilt`]):
    /// `h_n = 9.482 |ΔT|^⅓ / (7.238 − |cos Σ|)` where the flow is unstable (a warm surface
    /// facing up, a cool one facing down: `ΔT · cos Σ > 0`),
    /// `h_n = 1.810 |ΔT|^⅓ / (1.382 + |cos Σ|)` where it is stable, and
    /// `h_n = 1.31 |ΔT|^⅓` (ASHRAE, vertical surfaces) for a vertical surface or `ΔT = 0`.
    /// The coefficients were checked against EnergyPlus' source (`ConvectionCoefficients.cc`:
    /// `CalcMoWITTForcedWindward`, `CalcMoWITTForcedLeeward`, `CalcDOE2Forced`,
    /// `CalcASHRAETARPNatural`). Fitted to a building's walls and windows for wind speeds up
    /// to about 10 m/s.
    Doe2,
}

/// The exponent of the natural-convection correlations, `h_n ∝ |ΔT|^⅓`.
const ONE_THIRD: f64 = 1.0 / 3.0;

impl Convection {
    /// The coefficient for a surface at `surface_k` in air at `air_k` with wind
    /// `wind_speed_m_s`, W m⁻² K⁻¹. For reports and checks; the solver uses the same code.
    #[must_use]
    pub fn coefficient_w_m2_k(
        &self,
        roughness: Roughness,
        orientation: Orientation,
        wind_speed_m_s: f64,
        surface_k: f64,
        air_k: f64,
    ) -> f64 {
        ConvectionAt::new(
            *self,
            roughness,
            orientation,
            wind_speed_m_s,
            &mut ForcedCache::default(),
        )
        .eval(surface_k - air_k)
        .h
    }

    /// Whether the coefficient is usable: a finite, non-negative given `h`.
    pub(crate) fn is_valid(&self) -> bool {
        match *self {
            Self::Fixed { h_w_m2_k } => (0.0..=1e12).contains(&h_w_m2_k),
            Self::McAdams | Self::Doe2 => true,
        }
    }
}

/// The last MoWITT forced coefficients `a V^b` computed, windward and leeward, by wind
/// speed: facets stepped together share the weather's wind, and `powf` is much of a
/// step's cost.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ForcedCache {
    /// `(V's bits, a V^b)`, windward then leeward; NaN's bits match no validated wind.
    entries: [(u64, f64); 2],
}

impl Default for ForcedCache {
    fn default() -> Self {
        Self {
            entries: [(f64::NAN.to_bits(), 0.0); 2],
        }
    }
}

impl ForcedCache {
    /// `a V^b` for the side of the wind the facet is on: `a = 3.26, b = 0.89` windward,
    /// `a = 3.55, b = 0.617` leeward.
    fn forced_smooth(&mut self, windward: bool, wind_speed_m_s: f64) -> f64 {
        let slot = &mut self.entries[usize::from(!windward)];
        if slot.0 != wind_speed_m_s.to_bits() {
            let (a, b) = if windward {
                (3.26, 0.89)
            } else {
                (3.55, 0.617)
            };
            *slot = (wind_speed_m_s.to_bits(), a * wind_speed_m_s.powf(b));
        }
        slot.1
    }
}

/// A correlation with the wind and the facet fixed: all that does not depend on the
/// surface temperature is computed once per set of loads.
#[derive(Debug, Clone, Copy)]
pub(crate) enum ConvectionAt {
    /// `h` independent of the surface temperature.
    Constant(f64),
    /// DOE-2 with its forced part and natural-convection constants resolved.
    Doe2 {
        /// `a V^b`, the smooth-surface forced coefficient.
        forced_smooth: f64,
        /// `R_f`.
        roughness_multiplier: f64,
        /// `h_n / |ΔT|^⅓` where the surface is warmer than the air.
        natural_warmer: f64,
        /// `h_n / |ΔT|^⅓` where the surface is cooler than the air.
        natural_cooler: f64,
    },
}

/// The coefficient and what Newton's method needs of it at one surface temperature.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ConvectionEval {
    /// `h`, W m⁻² K⁻¹.
    pub h: f64,
    /// `d(h ΔT)/dT_s = h + ΔT dh/dT_s`, W m⁻² K⁻¹: finite at `ΔT = 0`.
    pub flux_derivative: f64,
    /// `ΔT · dh/dT_s`, W m⁻² K⁻¹: finite at `ΔT = 0` (where `dh/dT_s` itself is not under
    /// DOE-2).
    pub delta_dh_dt: f64,
}

impl ConvectionEval {
    /// `dh/dT_s`, W m⁻² K⁻², at `delta_k = T_s − T_air`; taken as 0 at `ΔT = 0`, where
    /// DOE-2's is infinite.
    #[inline]
    pub(crate) fn dh_dt(&self, delta_k: f64) -> f64 {
        if delta_k == 0.0 {
            0.0
        } else {
            self.delta_dh_dt / delta_k
        }
    }
}

impl ConvectionAt {
    pub(crate) fn new(
        convection: Convection,
        roughness: Roughness,
        orientation: Orientation,
        wind_speed_m_s: f64,
        cache: &mut ForcedCache,
    ) -> Self {
        match convection {
            Convection::Fixed { h_w_m2_k } => Self::Constant(h_w_m2_k),
            Convection::McAdams => Self::Constant(5.7 + 3.8 * wind_speed_m_s),
            Convection::Doe2 => {
                let c = orientation.cos_tilt.clamp(-1.0, 1.0);
                let unstable = 9.482 / (7.238 - c.abs());
                let stable = 1.810 / (1.382 + c.abs());
                let (natural_warmer, natural_cooler) = if c > 0.0 {
                    (unstable, stable)
                } else if c < 0.0 {
                    (stable, unstable)
                } else {
                    (1.31, 1.31)
                };
                Self::Doe2 {
                    forced_smooth: cache.forced_smooth(orientation.windward, wind_speed_m_s),
                    roughness_multiplier: roughness.multiplier(),
                    natural_warmer,
                    natural_cooler,
                }
            }
        }
    }

    /// `h` and its derivatives at `delta_k = T_s − T_air`.
    #[inline]
    pub(crate) fn eval(&self, delta_k: f64) -> ConvectionEval {
        match *self {
            Self::Constant(h) => ConvectionEval {
                h,
                flux_derivative: h,
                delta_dh_dt: 0.0,
            },
            Self::Doe2 {
                forced_smooth,
                roughness_multiplier,
                natural_warmer,
                natural_cooler,
            } => {
                let c = if delta_k > 0.0 {
                    natural_warmer
                } else if delta_k < 0.0 {
                    natural_cooler
                } else {
                    1.31
                };
                let hn = c * cbrt(delta_k.abs());
                let s = (hn * hn + forced_smooth * forced_smooth).sqrt();
                let h = hn + roughness_multiplier * (s - hn);
                let dh_dhn = if s > 0.0 {
                    1.0 + roughness_multiplier * (hn / s - 1.0)
                } else {
                    1.0
                };
                // ΔT · dh_n/dT = h_n / 3, so the flux's derivative has no singularity.
                let delta_dh_dt = dh_dhn * hn * ONE_THIRD;
                let flux_derivative = h + delta_dh_dt;
                ConvectionEval {
                    h,
                    flux_derivative,
                    delta_dh_dt,
                }
            }
        }
    }
}

/// The cube root of `x ≥ 0` to 1e-14 relative (far below what a convection correlation
/// knows): a first guess within 3 % from the exponent bits (the bits divided by 3 plus
/// Kahan's constant) refined by two Halley steps (`y ← y (y³ + 2x) / (2y³ + x)`, cubic
/// convergence: 2e-5, then 7e-15). `std`'s `cbrt` is a software routine on this target and
/// was a fifth of a step's cost.
#[inline]
fn cbrt(x: f64) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    // The guess is within a few per cent for normal numbers, and Halley's steps recover
    // from a poor guess for the subnormal ones (|ΔT| below 1e-308 K).
    let mut y = f64::from_bits(x.to_bits() / 3 + 0x2A9F_7893_782D_A1CE);
    for _ in 0..2 {
        let y3 = y * y * y;
        y *= (y3 + 2.0 * x) / (2.0 * y3 + x);
    }
    y
}

#[cfg(test)]
mod tests {
    use super::*;

    fn wall(windward: bool) -> Orientation {
        Orientation {
            cos_tilt: 0.0,
            windward,
        }
    }

    #[test]
    fn the_cube_root_is_within_1e_14() {
        let mut x = 1e-12;
        while x < 1e6 {
            let (got, want) = (cbrt(x), x.cbrt());
            assert!((got - want).abs() <= 1e-14 * want, "{x}: {got} vs {want}");
            x *= 1.013;
        }
        assert_eq!(cbrt(0.0).to_bits(), 0f64.to_bits());
        assert!((cbrt(27.0) - 3.0).abs() <= 3e-14);
    }

    #[test]
    fn mcadams_by_hand() {
        let h =
            Convection::McAdams.coefficient_w_m2_k(Roughness::Rough, wall(true), 3.0, 310.0, 300.0);
        assert!((h - 17.1).abs() < 1e-12, "{h}");
    }

    #[test]
    fn doe2_by_hand() {
        // A vertical wall 8 K above the air, 3 m/s onto it, medium rough (R_f = 1.52):
        // h_n = 1.31 · 8^⅓ = 2.62; a V^b = 3.26 · 3^0.89 = 8.66673;
        // √(2.62² + 8.66673²) = 9.05410; h = 2.62 + 1.52 (9.05410 − 2.62) = 12.39983.
        let h = Convection::Doe2.coefficient_w_m2_k(
            Roughness::MediumRough,
            wall(true),
            3.0,
            308.0,
            300.0,
        );
        assert!((h - 12.39983).abs() < 1e-4, "{h}");
        // Leeward: 3.55 · 3^0.617 = 6.99217; √(2.62² + 6.99217²) = 7.46692;
        // h = 2.62 + 1.52 · 4.84692 = 9.98732.
        let h = Convection::Doe2.coefficient_w_m2_k(
            Roughness::MediumRough,
            wall(false),
            3.0,
            308.0,
            300.0,
        );
        assert!((h - 9.98732).abs() < 1e-4, "{h}");
        // A roof facing up, 27 K warmer than still air (unstable): 9.482 · 3 / 6.238 =
        // 4.56012; a cool roof (stable): 1.810 · 3 / 2.382 = 2.27960.
        let up = Orientation {
            cos_tilt: 1.0,
            windward: true,
        };
        let warm = Convection::Doe2.coefficient_w_m2_k(Roughness::Smooth, up, 0.0, 327.0, 300.0);
        assert!((warm - 4.56012).abs() < 1e-5, "{warm}");
        let cool = Convection::Doe2.coefficient_w_m2_k(Roughness::Smooth, up, 0.0, 273.0, 300.0);
        assert!((cool - 2.27960).abs() < 1e-5, "{cool}");
        // Facing down, the regimes swap.
        let down = Orientation {
            cos_tilt: -1.0,
            windward: true,
        };
        let warm = Convection::Doe2.coefficient_w_m2_k(Roughness::Smooth, down, 0.0, 327.0, 300.0);
        assert!((warm - 2.27960).abs() < 1e-5, "{warm}");
    }

    #[test]
    fn the_flux_derivative_matches_a_difference_quotient() {
        for windward in [true, false] {
            for cos_tilt in [-1.0, -0.3, 0.0, 0.7, 1.0] {
                for wind in [0.0, 0.5, 7.0] {
                    let at = ConvectionAt::new(
                        Convection::Doe2,
                        Roughness::VeryRough,
                        Orientation { cos_tilt, windward },
                        wind,
                        &mut ForcedCache::default(),
                    );
                    for dt in [-30.0, -0.7, 0.4, 12.0] {
                        let e = at.eval(dt);
                        let step = 1e-6;
                        let q = |d: f64| at.eval(d).h * d;
                        let numeric = (q(dt + step) - q(dt - step)) / (2.0 * step);
                        assert!(
                            (e.flux_derivative - numeric).abs() < 1e-6 * (1.0 + numeric.abs()),
                            "{cos_tilt} {wind} {dt}: {} vs {numeric}",
                            e.flux_derivative
                        );
                        let h = |d: f64| at.eval(d).h;
                        let numeric = (h(dt + step) - h(dt - step)) / (2.0 * step);
                        assert!((e.dh_dt(dt) - numeric).abs() < 1e-5 * (1.0 + numeric.abs()));
                    }
                    // At ΔT = 0 the flux's derivative is h itself.
                    let e = at.eval(0.0);
                    assert!(e.flux_derivative.is_finite() && e.h >= 0.0);
                }
            }
        }
    }
}
