//! A loads table (clear sky, one day of the year) taken to another day and under clouds:
//! the named approximations a thermal run makes when its sunlight comes from LOWTRAN7 and
//! its clouds from a weather record.
//!
//! - **The day.** The sun's irradiance follows the inverse square of the Earth–Sun
//!   distance, whose factor `(r₀/r)²` is Spencer's (1971, "Fourier series representation of
//!   the position of the Sun", Search 2(5), 172) series in the day angle
//!   `Γ = 2π (d − 1)/365`: `1.000110 + 0.034221 cos Γ + 0.001280 sin Γ + 0.000719 cos 2Γ +
//!   0.000077 sin 2Γ` (±3.4 % over the year, within 0.1 % of the orbit's). A table made for
//!   day `d₀` is scaled by the ratio of the two days' factors; the atmosphere's path is the
//!   table's.
//! - **Clouds.** Kasten & Czeplak (1980, "Solar and terrestrial radiation dependent on the
//!   amount and type of cloud", Solar Energy 24, 177–189, their Hamburg fits): with a cloud
//!   fraction `N` (0–1), the global horizontal irradiance is `G = G_clear (1 − 0.75 N^3.4)`
//!   and its diffuse share `D/G = 0.3 + 0.7 N²`; the beam is the rest. Fitted to ten years
//!   of hourly data at one site, all cloud types together: its error on a given hour is tens
//!   of per cent, and it is meant for what a weather record of cloud cover can give.
//! - **The sky's longwave at another air temperature.** The table's longwave is its model
//!   atmosphere's, whose air at the ground is the table's `air_temperature_k`. At a moment
//!   whose air is `T`, the sky keeps the table's effective emissivity
//!   `ε = E_LW / (σ T_table⁴)` and radiates `ε σ T⁴`; clouds, a fraction `c`, add
//!   Crawford & Duchon's (1999) term, `(c + (1 − c) ε) σ T⁴`.

use irsig_model::loads::BroadbandLoads;

use super::SunLoads;

/// The Stefan–Boltzmann constant, W m⁻² K⁻⁴ (CODATA 2018).
const SIGMA_W_M2_K4: f64 = 5.670_374_419e-8;

/// The sky's longwave irradiance on a horizontal surface, W m⁻², under air at `air_k` and a
/// cloud fraction `cloud` (0–1, clamped), from `table`'s effective emissivity.
#[must_use]
pub fn longwave_w_m2(table: &BroadbandLoads, air_k: f64, cloud: f64) -> f64 {
    let effective = table.longwave_down_w_m2 / (SIGMA_W_M2_K4 * table.air_temperature_k.powi(4));
    let c = cloud.clamp(0.0, 1.0);
    (c + (1.0 - c) * effective) * SIGMA_W_M2_K4 * air_k.powi(4)
}

/// `(r₀/r)²`, the Earth–Sun distance's factor on the sun's irradiance on day `day` (1–366)
/// of the year (Spencer 1971).
#[must_use]
pub fn earth_sun_factor(day: u16) -> f64 {
    let g = std::f64::consts::TAU * (f64::from(day) - 1.0) / 365.0;
    1.000_110
        + 0.034_221 * g.cos()
        + 0.001_280 * g.sin()
        + 0.000_719 * (2.0 * g).cos()
        + 0.000_077 * (2.0 * g).sin()
}

/// Clear-sky `loads` under a cloud fraction `cloud` (0–1, clamped) with the sun's zenith
/// cosine `cos_z` (Kasten & Czeplak 1980).
#[must_use]
pub fn clouded(loads: SunLoads, cos_z: f64, cloud: f64) -> SunLoads {
    let n = cloud.clamp(0.0, 1.0);
    if n <= 0.0 {
        return loads;
    }
    let global = loads.global_horizontal_w_m2 * (1.0 - 0.75 * n.powf(3.4));
    let diffuse = global * (0.3 + 0.7 * n * n);
    let direct = if cos_z > 1e-6 {
        ((global - diffuse) / cos_z).max(0.0)
    } else {
        0.0
    };
    SunLoads {
        direct_normal_w_m2: direct,
        diffuse_horizontal_w_m2: diffuse,
        global_horizontal_w_m2: direct * cos_z.max(0.0) + diffuse,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_distance_factor_against_the_orbit() {
        // Perihelion (early January) at 0.98329 AU and aphelion (early July) at 1.01671 AU:
        // (1/r)² = 1.03427 and 0.96737.
        let (near, far) = (1.0 / 0.98329_f64.powi(2), 1.0 / 1.01671_f64.powi(2));
        let max = (1..=366).map(earth_sun_factor).fold(0.0, f64::max);
        let min = (1..=366).map(earth_sun_factor).fold(2.0, f64::min);
        assert!((max - near).abs() < 1e-3, "{max} against {near}");
        assert!((min - far).abs() < 1e-3, "{min} against {far}");
        assert!(earth_sun_factor(3) > 1.03 && earth_sun_factor(185) < 0.97);
        // Over a year, the mean of (a/r)² is 1/√(1 − e²) = 1.00014 for e = 0.0167.
        let mean: f64 = (1..=365).map(earth_sun_factor).sum::<f64>() / 365.0;
        assert!((mean - 1.000_14).abs() < 1e-4, "{mean}");
    }

    #[test]
    fn clouds_by_hand() {
        let clear = SunLoads {
            direct_normal_w_m2: 800.0,
            diffuse_horizontal_w_m2: 100.0,
            global_horizontal_w_m2: 800.0 * 0.8 + 100.0,
        };
        assert_eq!(clouded(clear, 0.8, 0.0), clear);
        // Overcast: G = 740 · 0.25 = 185, all of it diffuse (0.3 + 0.7 = 1), no beam.
        let o = clouded(clear, 0.8, 1.0);
        assert!((o.global_horizontal_w_m2 - 185.0).abs() < 1e-9);
        assert!((o.diffuse_horizontal_w_m2 - 185.0).abs() < 1e-9);
        assert!(o.direct_normal_w_m2.abs() < 1e-9);
        // Half cloud: G = 740 (1 − 0.75 · 0.5^3.4) = 740 · 0.92894 = 687.4; D = 0.475 G.
        let h = clouded(clear, 0.8, 0.5);
        let g = 740.0 * (1.0 - 0.75 * 0.5_f64.powf(3.4));
        assert!((h.global_horizontal_w_m2 - g).abs() < 1e-9);
        assert!((h.diffuse_horizontal_w_m2 - 0.475 * g).abs() < 1e-9);
    }
}
