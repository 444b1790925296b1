use serde::{Deserialize, Serialize};

use crate::error::{ModelError, ModelErrorKind, check_finite, check_increasing, check_range};

/// One altitude of the `.atm` table, in SI.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AtmosphereLevel {
    /// Altitude above sea level in metres (the radiosonde altitude).
    pub altitude_asl_m: f64,
    /// Air temperature at this altitude in kelvin.
    pub temperature_k: f64,
    /// Altitude above the ground in metres (the atmospheric model's altitude).
    pub altitude_m: f64,
    /// Band transmittance of the vertical path between the ground and this altitude, 0 to 1.
    pub transmission: f64,
    /// Band upwelled path radiance seen from this altitude looking straight down to the
    /// ground, in W m⁻² sr⁻¹ (atmospheric emission only, no ground term).
    pub path_radiance_w_m2_sr: f64,
}

/// One level of a radiosonde (`.rsd`), in SI.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RadiosondeLevel {
    /// Altitude in metres.
    pub altitude_m: f64,
    /// Pressure in hectopascals (= millibars).
    pub pressure_hpa: f64,
    /// Air temperature in kelvin.
    pub temperature_k: f64,
    /// Dew-point depression in kelvin.
    pub dew_point_depression_k: f64,
}

/// A radiosonde profile's rules (both atmosphere forms carry one): finite altitudes,
/// pressures and temperatures ≥ 0, dew-point depressions from 0 to below the temperature
/// (a dew point above absolute zero), altitudes increasing.
pub(crate) fn check_radiosonde(levels: &[RadiosondeLevel]) -> Result<(), ModelError> {
    for (i, r) in levels.iter().enumerate() {
        let p = |f: &str| format!("radiosonde[{i}].{f}");
        check_finite(|| p("altitude_m"), &[r.altitude_m])?;
        check_range(|| p("pressure_hpa"), r.pressure_hpa, 0.0, f64::MAX)?;
        check_range(|| p("temperature_k"), r.temperature_k, 0.0, f64::MAX)?;
        check_range(
            || p("dew_point_depression_k"),
            r.dew_point_depression_k,
            0.0,
            f64::MAX,
        )?;
        if r.dew_point_depression_k >= r.temperature_k {
            return Err(ModelError::new(
                p("dew_point_depression_k"),
                ModelErrorKind::Other(format!(
                    "a depression of {} K at {} K puts the dew point at or below absolute zero",
                    r.dew_point_depression_k, r.temperature_k
                )),
            ));
        }
    }
    check_increasing(
        |i| format!("radiosonde[{i}].altitude_m"),
        levels.iter().map(|r| r.altitude_m),
    )
}

/// Slant-path tables taken directly from an atmospheric model run at many angles: the
/// `table` atmosphere model. Grids increase strictly; values are row-major with the
/// altitude (outer) and the angle (inner) as axes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SlantTables {
    /// Observer altitudes above the ground, metres.
    pub altitude_m: Vec<f64>,
    /// Nadir angles at the observer, degrees, 0 (straight down) to below 90.
    pub nadir_deg: Vec<f64>,
    /// The altitude of the paths' lower end, metres, when it is not the ground itself:
    /// LOWTRAN's paths stop 1 m up (an end at 0 m makes it add a ground's emission), so the
    /// built-in tables hold paths to 1 m. `None`: to 0 m.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ground_m: Option<f64>,
    /// Band transmittance from the observer to the paths' lower end, `[altitude][angle]`.
    pub transmission: Vec<Vec<f64>>,
    /// Band path radiance from the paths' lower end to the observer, W m⁻² sr⁻¹,
    /// `[altitude][angle]`.
    pub path_radiance_w_m2_sr: Vec<Vec<f64>>,
    /// Observer altitudes for the sky table, metres.
    pub sky_altitude_m: Vec<f64>,
    /// Zenith angles for the sky table, degrees, 0 (straight up) to 90.
    pub sky_zenith_deg: Vec<f64>,
    /// Band path radiance from the observer to space, W m⁻² sr⁻¹, `[altitude][angle]`.
    pub sky_radiance_w_m2_sr: Vec<Vec<f64>>,
    /// How far the `table` model's interpolation between these rows is from the
    /// atmospheric model itself, as measured when the rows were placed, if known.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub interpolation_residual: Option<InterpolationResidual>,
}

/// The largest error the `table` model's interpolation between its rows was found to
/// make against the atmospheric model it was built from, at paths that are not rows (the
/// midpoints between neighbouring rows and the cells' centres), when the rows were placed
/// (`scripts/atmosphere/regen.py`). Errors are apparent temperatures, K: of blackbodies at
/// 260, 290 and 320 K seen through a path to the ground, or the sky's brightness
/// temperature, each summed over 16 sub-bands of flat 8–14 µm. A σ term of the data: what
/// a rendering's atmosphere may be off by between rows, beyond the models' own errors.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InterpolationResidual {
    /// Paths to the ground at nadir angles up to 80°, K.
    pub slant_k: f64,
    /// Paths to the ground beyond 80° up to the table's last angle, K.
    pub grazing_k: f64,
    /// The sky from every altitude of the sky table, 0–90° from the zenith, K.
    pub sky_k: f64,
}

/// Everything the DIRTRAN tables say about one atmosphere, in SI units: the canonical
/// atmosphere file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Atmosphere {
    /// A short name (`us-std-1976`).
    pub name: String,
    /// Where the numbers come from (model, version, settings).
    pub source: String,
    /// The band `[λ1, λ2]` in micrometres the tables were integrated over.
    pub band_um: [f64; 2],
    /// The `.atm` table, altitudes increasing.
    pub levels: Vec<AtmosphereLevel>,
    /// The `.cor` coefficients `a1 a2 a3` of `τ(θ) = τ(0)(a1 + a2 secθ + a3 sec²θ)`
    /// (thesis eq. 10), if given.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub transmission_correction: Option<[f64; 3]>,
    /// The observer altitude in metres the `.cor` coefficients were fitted at, if known
    /// (the reference LOWTRAN7 tables fit at 1000 m). The `.cor` format does not say it;
    /// models use it to scale the angular correction to other altitudes.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub transmission_correction_altitude_m: Option<f64>,
    /// The `.dwr` angular sky radiance: `(zenith_deg, radiance_w_m2_sr)` seen from the
    /// ground, zenith angles increasing within 0 to 90.
    pub sky: Vec<(f64, f64)>,
    /// The hemispheric (cosine-weighted) sky radiance in W m⁻² sr⁻¹ (`.dwr` row `-1`,
    /// thesis eq. 5 and 6), if given.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sky_hemispheric_w_m2_sr: Option<f64>,
    /// The `.rsd` radiosonde, if given.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub radiosonde: Vec<RadiosondeLevel>,
    /// The `.rtt` table: `(temperature_k, band_radiance_w_m2_sr)`, temperatures increasing.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub band_radiance: Vec<(f64, f64)>,
    /// Slant-path tables for the `table` model, if generated.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub slant: Option<SlantTables>,
}

impl Atmosphere {
    /// Checks the tables: altitudes increase, 0 ≤ τ ≤ 1, angles lie in 0–90° and increase,
    /// radiances and temperatures are not negative, the band is sensible.
    ///
    /// # Errors
    /// The first rule broken.
    pub fn validate(&self) -> Result<(), ModelError> {
        check_finite(|| "band_um".into(), &self.band_um)?;
        if !(self.band_um[0] > 0.0 && self.band_um[1] > self.band_um[0]) {
            return Err(ModelError::new(
                "band_um",
                ModelErrorKind::Other(format!(
                    "band [{}, {}] µm must have 0 < λ1 < λ2",
                    self.band_um[0], self.band_um[1]
                )),
            ));
        }
        if self.levels.is_empty() {
            return Err(ModelError::new("levels", ModelErrorKind::Empty));
        }
        for (i, l) in self.levels.iter().enumerate() {
            let p = |f: &str| format!("levels[{i}].{f}");
            check_finite(|| p("altitude_asl_m"), &[l.altitude_asl_m])?;
            check_range(|| p("altitude_m"), l.altitude_m, 0.0, f64::MAX)?;
            check_range(|| p("temperature_k"), l.temperature_k, 0.0, f64::MAX)?;
            if l.temperature_k <= 0.0 {
                // As the `.atm` it comes from: air at 0 K is no atmosphere.
                return Err(ModelError::new(
                    p("temperature_k"),
                    ModelErrorKind::Other(format!(
                        "expected a temperature above 0 K, found {}",
                        l.temperature_k
                    )),
                ));
            }
            check_range(|| p("transmission"), l.transmission, 0.0, 1.0)?;
            check_range(
                || p("path_radiance_w_m2_sr"),
                l.path_radiance_w_m2_sr,
                0.0,
                f64::MAX,
            )?;
        }
        check_increasing(
            |i| format!("levels[{i}].altitude_m"),
            self.levels.iter().map(|l| l.altitude_m),
        )?;
        check_increasing(
            |i| format!("levels[{i}].altitude_asl_m"),
            self.levels.iter().map(|l| l.altitude_asl_m),
        )?;
        if let Some(c) = &self.transmission_correction {
            check_finite(|| "transmission_correction".into(), c)?;
        }
        if let Some(h) = self.transmission_correction_altitude_m {
            check_range(
                || "transmission_correction_altitude_m".into(),
                h,
                0.0,
                f64::MAX,
            )?;
        }
        check_angle_table("sky", &self.sky)?;
        if let Some(h) = self.sky_hemispheric_w_m2_sr {
            check_range(|| "sky_hemispheric_w_m2_sr".into(), h, 0.0, f64::MAX)?;
        }
        check_radiosonde(&self.radiosonde)?;
        for (i, &(t, l)) in self.band_radiance.iter().enumerate() {
            check_range(
                || format!("band_radiance[{i}].temperature_k"),
                t,
                0.0,
                f64::MAX,
            )?;
            check_range(|| format!("band_radiance[{i}].radiance"), l, 0.0, f64::MAX)?;
        }
        check_increasing(
            |i| format!("band_radiance[{i}].temperature_k"),
            self.band_radiance.iter().map(|r| r.0),
        )?;
        // As the `.rtt` it comes from: band radiance never falls as the temperature rises,
        // else radiance to temperature has no single answer.
        for (i, w) in self.band_radiance.windows(2).enumerate() {
            if w[1].1 < w[0].1 {
                return Err(ModelError::new(
                    format!("band_radiance[{}].radiance", i + 1),
                    ModelErrorKind::Other(format!(
                        "expected a radiance of at least {} (the row before), found {}: band \
                         radiance never falls as the temperature rises",
                        w[0].1, w[1].1
                    )),
                ));
            }
        }
        if let Some(s) = &self.slant {
            s.validate()?;
        }
        Ok(())
    }
}

fn check_angle_table(name: &str, rows: &[(f64, f64)]) -> Result<(), ModelError> {
    if rows.is_empty() {
        return Err(ModelError::new(name, ModelErrorKind::Empty));
    }
    for (i, &(a, l)) in rows.iter().enumerate() {
        check_range(|| format!("{name}[{i}].angle_deg"), a, 0.0, 90.0)?;
        check_range(|| format!("{name}[{i}].radiance"), l, 0.0, f64::MAX)?;
    }
    check_increasing(
        |i| format!("{name}[{i}].angle_deg"),
        rows.iter().map(|r| r.0),
    )
}

impl SlantTables {
    /// Checks grid shapes, monotonic axes and value ranges.
    ///
    /// # Errors
    /// The first rule broken.
    pub fn validate(&self) -> Result<(), ModelError> {
        let grid = |name: &str, rows: &[Vec<f64>], n: usize, m: usize, max: f64| {
            if rows.len() != n || rows.iter().any(|r| r.len() != m) {
                return Err(ModelError::new(
                    format!("slant.{name}"),
                    ModelErrorKind::Other(format!("expected a {n}×{m} grid")),
                ));
            }
            for (i, r) in rows.iter().enumerate() {
                for (j, &v) in r.iter().enumerate() {
                    check_range(|| format!("slant.{name}[{i}][{j}]"), v, 0.0, max)?;
                }
            }
            Ok(())
        };
        for (name, axis, max) in [
            ("altitude_m", &self.altitude_m, f64::MAX),
            // Below 90°: a horizontal slant path never reaches the paths' lower end.
            ("nadir_deg", &self.nadir_deg, 89.999),
            ("sky_altitude_m", &self.sky_altitude_m, f64::MAX),
            ("sky_zenith_deg", &self.sky_zenith_deg, 90.0),
        ] {
            if axis.is_empty() {
                return Err(ModelError::new(
                    format!("slant.{name}"),
                    ModelErrorKind::Empty,
                ));
            }
            for (i, &v) in axis.iter().enumerate() {
                check_range(|| format!("slant.{name}[{i}]"), v, 0.0, max)?;
            }
            check_increasing(|i| format!("slant.{name}[{i}]"), axis.iter().copied())?;
        }
        if let Some(r) = &self.interpolation_residual {
            for (name, v) in [
                ("slant_k", r.slant_k),
                ("grazing_k", r.grazing_k),
                ("sky_k", r.sky_k),
            ] {
                check_range(
                    || format!("slant.interpolation_residual.{name}"),
                    v,
                    0.0,
                    f64::MAX,
                )?;
            }
        }
        if let Some(g) = self.ground_m {
            // Below the lowest observer altitude, so that every path has some air.
            let lowest = self.altitude_m[0];
            if !(g >= 0.0 && g < lowest) {
                return Err(ModelError::new(
                    "slant.ground_m",
                    ModelErrorKind::Other(format!(
                        "expected 0 m or more and below the lowest altitude ({lowest} m), found {g}"
                    )),
                ));
            }
        }
        let (n, m) = (self.altitude_m.len(), self.nadir_deg.len());
        grid("transmission", &self.transmission, n, m, 1.0)?;
        grid(
            "path_radiance_w_m2_sr",
            &self.path_radiance_w_m2_sr,
            n,
            m,
            f64::MAX,
        )?;
        grid(
            "sky_radiance_w_m2_sr",
            &self.sky_radiance_w_m2_sr,
            self.sky_altitude_m.len(),
            self.sky_zenith_deg.len(),
            f64::MAX,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn atmosphere() -> Atmosphere {
        Atmosphere {
            name: "t".into(),
            source: "test".into(),
            band_um: [8.0, 14.0],
            levels: vec![
                AtmosphereLevel {
                    altitude_asl_m: 50.0,
                    temperature_k: 287.8,
                    altitude_m: 50.0,
                    transmission: 0.964,
                    path_radiance_w_m2_sr: 1.519,
                },
                AtmosphereLevel {
                    altitude_asl_m: 100.0,
                    temperature_k: 287.5,
                    altitude_m: 100.0,
                    transmission: 0.946,
                    path_radiance_w_m2_sr: 2.282,
                },
            ],
            transmission_correction: Some([1.1, -0.11, 0.007]),
            transmission_correction_altitude_m: None,
            sky: vec![(0.0, 11.66), (90.0, 43.9)],
            sky_hemispheric_w_m2_sr: Some(15.13),
            radiosonde: vec![],
            band_radiance: vec![(200.0, 6.0), (201.0, 6.2)],
            slant: None,
        }
    }

    #[test]
    fn a_good_atmosphere_passes() {
        atmosphere().validate().unwrap();
    }

    #[test]
    fn transmission_above_one_and_falling_altitudes_are_rejected() {
        let mut a = atmosphere();
        a.levels[1].transmission = 1.01;
        assert_eq!(a.validate().unwrap_err().path, "levels[1].transmission");
        let mut a = atmosphere();
        a.levels[1].altitude_m = 10.0;
        a.levels[1].altitude_asl_m = 10.0;
        assert_eq!(a.validate().unwrap_err().path, "levels[1].altitude_m");
    }

    #[test]
    fn sky_angles_past_90_and_negative_radiance_are_rejected() {
        let mut a = atmosphere();
        a.sky.push((95.0, 40.0));
        assert!(a.validate().is_err());
        let mut a = atmosphere();
        a.sky[0].1 = -1.0;
        assert!(a.validate().is_err());
    }
}
