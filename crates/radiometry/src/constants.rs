//! Physical constants, CODATA 2018 (exact in the 2019 SI), and the two radiation constants
//! derived from them.

/// Planck constant, J s (exact).
pub const PLANCK_J_S: f64 = 6.626_070_15e-34;
/// Speed of light in vacuum, m s^-1 (exact).
pub const SPEED_OF_LIGHT_M_S: f64 = 299_792_458.0;
/// Boltzmann constant, J K^-1 (exact).
pub const BOLTZMANN_J_K: f64 = 1.380_649e-23;

/// First radiation constant for spectral radiance, `2 h c^2`, W m^2 sr^-1.
///
/// Spectral radiance per unit wavelength is `C1L / λ^5 / (exp(C2 / (λ T)) - 1)`.
pub const C1L_W_M2_SR: f64 = 2.0 * PLANCK_J_S * SPEED_OF_LIGHT_M_S * SPEED_OF_LIGHT_M_S;
/// Second radiation constant, `h c / k`, m K.
pub const C2_M_K: f64 = PLANCK_J_S * SPEED_OF_LIGHT_M_S / BOLTZMANN_J_K;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn derived_constants_match_codata_2018_values() {
        // CODATA 2018 lists c1L = 1.191 042 972e-16 W m^2 sr^-1 and c2 = 1.438 776 877e-2 m K
        // (both truncated, not rounded, in the table), so agree to the 10 digits given.
        assert!((C1L_W_M2_SR / 1.191_042_972e-16 - 1.0).abs() < 1e-9);
        assert!((C2_M_K / 1.438_776_877e-2 - 1.0).abs() < 1e-9);
    }
}
