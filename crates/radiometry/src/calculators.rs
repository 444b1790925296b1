//! The closed-form calculations of thesis Appendices A and B, which tell a user which
//! models a scene needs: how many specular bounces matter, and how much the shape
//! (sky-view) factor matters.

use crate::band::Band;
use crate::error::{RadiometryError, RadiometryErrorKind};

/// An opaque, specular, isothermal surface: its band emissivity and kinetic temperature.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Surface {
    /// Band emissivity, 0–1; its reflectance is `1 − emissivity` (Kirchhoff).
    pub emissivity: f64,
    /// Kinetic temperature, K.
    pub temperature_k: f64,
}

impl Surface {
    fn validate(&self, what: &str) -> Result<(), RadiometryError> {
        check_fraction(self.emissivity, &format!("{what} emissivity"))?;
        check_temperature(self.temperature_k, &format!("{what} temperature"))
    }
}

fn check_fraction(value: f64, what: &str) -> Result<(), RadiometryError> {
    if (0.0..=1.0).contains(&value) {
        Ok(())
    } else {
        Err(RadiometryError::new(
            RadiometryErrorKind::InvalidParameter,
            format!("{what} must be in [0, 1], found {value}"),
        ))
    }
}

fn check_temperature(value: f64, what: &str) -> Result<(), RadiometryError> {
    if value.is_finite() && value >= 0.0 {
        Ok(())
    } else {
        Err(RadiometryError::new(
            RadiometryErrorKind::InvalidTemperature,
            format!("{what} must be a finite number of kelvin ≥ 0, found {value}"),
        ))
    }
}

/// Radiance (W m^-2 sr^-1) leaving `chain[0]` toward the sensor when the specular
/// reflection path is followed through `chain[1]`, `chain[2]`, ... (Appendix A,
/// Figure A-1). Element `i` of the result is the radiance counting `i` bounces, i.e. the
/// first `i + 1` surfaces; the path is cut after the last surface (as in the thesis's
/// program, which gives the last surface no reflected term).
///
/// The thesis's FORTRAN program `Bounce` computes exactly
/// `L(1) = e1·Lt1` and `L(I) = L(I−1) + Π_{i<I}(1 − e_i) · e_I · Lt_I`.
///
/// # Errors
/// [`RadiometryErrorKind::InvalidParameter`] for an emissivity outside [0, 1] and
/// [`RadiometryErrorKind::InvalidTemperature`] for a negative or non-finite temperature.
pub fn bounce_radiances(band: &Band, chain: &[Surface]) -> Result<Vec<f64>, RadiometryError> {
    for (i, s) in chain.iter().enumerate() {
        s.validate(&if i == 0 {
            "target".to_owned()
        } else {
            format!("background {i}")
        })?;
    }
    let mut out = Vec::with_capacity(chain.len());
    let mut radiance = 0.0;
    let mut reflectance_so_far = 1.0;
    for s in chain {
        radiance += reflectance_so_far * s.emissivity * band.radiance(s.temperature_k);
        reflectance_so_far *= 1.0 - s.emissivity;
        out.push(radiance);
    }
    Ok(out)
}

/// Apparent (brightness) temperatures, K, of a specular target seen after 0, 1, ...,
/// `max_bounces` bounces, every background surface having the same emissivity and
/// temperature (the thesis's Tables ).
///
/// # Errors
/// As [`bounce_radiances`].
pub fn bounce_temperatures(
    band: &Band,
    target: Surface,
    background: Surface,
    max_bounces: usize,
) -> Result<Vec<f64>, RadiometryError> {
    let mut chain = Vec::with_capacity(max_bounces + 1);
    chain.push(target);
    chain.extend(std::iter::repeat_n(background, max_bounces));
    Ok(bounce_radiances(band, &chain)?
        .into_iter()
        .map(|l| band.temperature(l))
        .collect())
}

/// Surface-leaving radiance of a diffuse object with a partial sky view (Appendix B,
/// Figure B-1; thesis eq. 6 without the atmosphere), W m^-2 sr^-1:
///
/// `L = ε L(T_obj) + (1 − ε) [F L_d + (1 − F) L(T_b)]`
///
/// where `L_d` is the hemispheric sky radiance (W m^-2 sr^-1), `F` the shape factor (the
/// fraction of the hemisphere that is sky) and `L(T_b)` the blackbody radiance of the
/// background.
///
/// # Errors
/// [`RadiometryErrorKind::InvalidParameter`] for an emissivity or shape factor outside
/// [0, 1] or a sky radiance that is negative or not finite;
/// [`RadiometryErrorKind::InvalidTemperature`] for a negative or non-finite temperature.
pub fn shape_factor_radiance(
    band: &Band,
    emissivity: f64,
    object_temperature_k: f64,
    background_temperature_k: f64,
    sky_radiance_w_m2_sr: f64,
    shape_factor: f64,
) -> Result<f64, RadiometryError> {
    check_fraction(emissivity, "emissivity")?;
    check_fraction(shape_factor, "shape factor")?;
    check_temperature(object_temperature_k, "object temperature")?;
    check_temperature(background_temperature_k, "background temperature")?;
    if !(sky_radiance_w_m2_sr.is_finite() && sky_radiance_w_m2_sr >= 0.0) {
        return Err(RadiometryError::new(
            RadiometryErrorKind::InvalidParameter,
            format!(
                "sky radiance must be finite and ≥ 0 W m^-2 sr^-1, found {sky_radiance_w_m2_sr}"
            ),
        ));
    }
    let object = band.radiance(object_temperature_k);
    let background = band.radiance(background_temperature_k);
    Ok(emissivity * object
        + (1.0 - emissivity)
            * (shape_factor * sky_radiance_w_m2_sr + (1.0 - shape_factor) * background))
}

/// The apparent temperature, K, of [`shape_factor_radiance`].
///
/// # Errors
/// As [`shape_factor_radiance`].
pub fn shape_factor_temperature(
    band: &Band,
    emissivity: f64,
    object_temperature_k: f64,
    background_temperature_k: f64,
    sky_radiance_w_m2_sr: f64,
    shape_factor: f64,
) -> Result<f64, RadiometryError> {
    shape_factor_radiance(
        band,
        emissivity,
        object_temperature_k,
        background_temperature_k,
        sky_radiance_w_m2_sr,
        shape_factor,
    )
    .map(|l| band.temperature(l))
}
