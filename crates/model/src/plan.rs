//! The plan of an atmosphere build: which paths a radiative-transfer code must run for a
//! scene (`irsig-atmos plan` writes it, `irsig-atmos build` reads it). Every path goes
//! from an observer altitude either down to the paths' lower end (slant paths, nadir
//! angle) or up to space (sky paths, zenith angle); altitudes are above the scene's
//! lowest point, which is the ground of the radiative-transfer model.

use serde::{Deserialize, Serialize};

use crate::RadiosondeLevel;
use crate::error::{ModelError, ModelErrorKind, check_increasing, check_range};

/// The model atmosphere the runs use.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum PlanModel {
    /// A LOWTRAN7 standard model: 1 tropical, 2 mid-latitude summer, 3 mid-latitude
    /// winter, 4 sub-arctic summer, 5 sub-arctic winter, 6 US Standard 1976.
    Standard(u8),
    /// A radiosonde (LOWTRAN7's user-defined model, MODEL = 7); its first level is the
    /// ground. Above its last level the US Standard 1976 model continues.
    Radiosonde(Vec<RadiosondeLevel>),
}

/// The paths of an atmosphere build, as node lists; the paths themselves are derived from
/// them (`irsig_atmosphere::plan::paths`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AtmospherePlan {
    /// The atmosphere's name.
    pub name: String,
    /// The model atmosphere.
    pub model: PlanModel,
    /// The spectral range and step, cm⁻¹: `[v1, v2, dv]`.
    pub wavenumber_per_cm: [f64; 3],
    /// The altitude slant paths stop at, metres (LOWTRAN adds a ground's emission to a
    /// path that ends at 0 m, so the paths end 1 m up).
    pub path_end_m: f64,
    /// The observers the plan was made for: heights above the scene's lowest point, metres.
    pub observers_m: Vec<f64>,
    /// Altitudes of the vertical profile (paths straight down), metres, increasing.
    pub levels_m: Vec<f64>,
    /// The observer altitude of the `.cor` fit's paths, metres.
    pub correction_altitude_m: f64,
    /// The nadir angles of the `.cor` fit's paths, degrees, from 0.
    pub correction_nadir_deg: Vec<f64>,
    /// Zenith angles of the sky seen from the ground, degrees.
    pub ground_sky_zenith_deg: Vec<f64>,
    /// Zenith angles and weights of the hemispheric sky's quadrature (from the ground):
    /// `L_hemi = Σ w_i L(θ_i)`.
    pub hemispheric: Vec<(f64, f64)>,
    /// Observer altitudes of the slant table, metres, increasing.
    pub slant_altitude_m: Vec<f64>,
    /// Nadir angles of the slant table, degrees, increasing.
    pub slant_nadir_deg: Vec<f64>,
    /// Observer altitudes of the sky table, metres, increasing.
    pub sky_altitude_m: Vec<f64>,
    /// Zenith angles of the sky table, degrees, increasing.
    pub sky_zenith_deg: Vec<f64>,
}

impl AtmospherePlan {
    /// Checks the node lists: altitudes not negative and increasing, angles within their
    /// ranges and increasing, a sensible spectral range, a known model.
    ///
    /// # Errors
    /// The first rule broken.
    pub fn validate(&self) -> Result<(), ModelError> {
        let [v1, v2, dv] = self.wavenumber_per_cm;
        if !(v1 > 0.0 && v2 > v1 && dv > 0.0 && v2 <= 50_000.0) {
            return Err(ModelError::new(
                "wavenumber_per_cm",
                ModelErrorKind::Other(format!(
                    "expected 0 < v1 < v2 <= 50000 cm-1 and dv > 0, found [{v1}, {v2}, {dv}]"
                )),
            ));
        }
        if let PlanModel::Standard(m) = self.model
            && !(1..=6).contains(&m)
        {
            return Err(ModelError::new(
                "model",
                ModelErrorKind::Other(format!("expected a standard model 1 to 6, found {m}")),
            ));
        }
        if let PlanModel::Radiosonde(levels) = &self.model {
            if levels.len() < 2 {
                return Err(ModelError::new(
                    "model",
                    ModelErrorKind::Other("a radiosonde needs at least 2 levels".into()),
                ));
            }
            check_increasing(
                |i| format!("model.Radiosonde[{i}].altitude_m"),
                levels.iter().map(|l| l.altitude_m),
            )?;
        }
        check_range(|| "path_end_m".into(), self.path_end_m, 0.0, f64::MAX)?;
        let axes: [(&str, &Vec<f64>, f64); 7] = [
            ("levels_m", &self.levels_m, f64::MAX),
            ("correction_nadir_deg", &self.correction_nadir_deg, 89.999),
            ("ground_sky_zenith_deg", &self.ground_sky_zenith_deg, 90.0),
            ("slant_altitude_m", &self.slant_altitude_m, f64::MAX),
            ("slant_nadir_deg", &self.slant_nadir_deg, 89.999),
            ("sky_altitude_m", &self.sky_altitude_m, f64::MAX),
            ("sky_zenith_deg", &self.sky_zenith_deg, 90.0),
        ];
        for (name, axis, max) in axes {
            if axis.is_empty() {
                return Err(ModelError::new(name, ModelErrorKind::Empty));
            }
            for (i, &v) in axis.iter().enumerate() {
                check_range(|| format!("{name}[{i}]"), v, 0.0, max)?;
            }
            check_increasing(|i| format!("{name}[{i}]"), axis.iter().copied())?;
        }
        if self.slant_altitude_m[0] <= self.path_end_m || self.levels_m[0] <= self.path_end_m {
            return Err(ModelError::new(
                "slant_altitude_m",
                ModelErrorKind::Other(format!(
                    "every observer altitude must be above the paths' end ({} m)",
                    self.path_end_m
                )),
            ));
        }
        for (i, &(z, w)) in self.hemispheric.iter().enumerate() {
            check_range(|| format!("hemispheric[{i}].zenith_deg"), z, 0.0, 90.0)?;
            check_range(|| format!("hemispheric[{i}].weight"), w, 0.0, f64::MAX)?;
        }
        Ok(())
    }
}
