//! Broadband thermal loads at the ground: what a surface energy balance takes from the
//! atmosphere at each sun position of a day, and the plan of the radiative-transfer runs
//! that give them (`irsig-atmos plan --loads` writes a [`LoadsPlan`], `irsig-atmos build`
//! runs it and writes [`BroadbandLoads`]).
//!
//! Four numbers per moment: the direct normal solar irradiance (DNI, on a surface facing
//! the sun), the diffuse horizontal solar irradiance (DHI, the sky's scattered sunlight on a
//! horizontal surface), their sum on a horizontal surface (GHI = DNI cos z + DHI, derived)
//! and the downwelling longwave irradiance on a horizontal surface (E_LW, the sky's thermal
//! emission, which does not depend on the sun). Angles are degrees at the file boundary,
//! irradiances W m⁻².

use serde::{Deserialize, Serialize};

use crate::error::{ModelError, ModelErrorKind, check_increasing, check_range};
use crate::{PlanAerosol, PlanModel};

/// How far, relative, a quadrature's weights may sum from π sr (the cosine-weighted
/// hemisphere, `∫ cos θ dΩ`): a rule that misses it by more is not a hemisphere's.
pub const HEMISPHERE_WEIGHT_TOLERANCE: f64 = 0.01;

/// The sun of a loads plan: its zenith angle and the lines of sight of the sky's
/// scattered sunlight.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LoadsSun {
    /// The sun's zenith angle at the ground, degrees, 0 to below 90, multiples of 0.001°.
    pub zenith_deg: f64,
    /// The lines of sight whose scattered sunlight makes the DHI, and their weights:
    /// `(zenith_deg, azimuth_deg, weight_sr)`, the zenith angle 0–90° of the line of
    /// sight, its azimuth 0–180° from the sun's (the sky is symmetric about the sun's
    /// vertical plane), both multiples of 0.001°, and the weight in steradians, so that
    /// `DHI = Σ weight · L` for the scattered radiances `L` (W m⁻² sr⁻¹). The weights sum
    /// to π (a uniform sky of radiance L gives π L) within
    /// [`HEMISPHERE_WEIGHT_TOLERANCE`].
    pub diffuse: Vec<(f64, f64, f64)>,
}

/// The radiative-transfer runs of a day's broadband loads (`irsig_atmosphere::loads`
/// derives the paths and decks from it): for each sun zenith angle, one direct solar
/// irradiance run and one scattered-sunlight run per line of sight of `sun[k].diffuse`;
/// once, one thermal radiance run per line of sight of `longwave`. Every path starts at
/// the ground (LOWTRAN7's 0 km) and looks up.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LoadsPlan {
    /// The table's name.
    pub name: String,
    /// The model atmosphere.
    pub model: PlanModel,
    /// The aerosol of every run; none: no aerosol (LOWTRAN7's IHAZE 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub aerosol: Option<PlanAerosol>,
    /// The ground's albedo, 0 (black, the default) to 1, multiples of 0.01 (LOWTRAN7's
    /// SALB, `F7.2`): what the ground reflects back to the sky, which scatters some of it
    /// down again (multiple scattering only).
    #[serde(default)]
    pub ground_albedo: f64,
    /// Day of the year, 1–366 (LOWTRAN7's IDAY: the Earth–Sun distance).
    pub day_of_year: u16,
    /// The solar runs' spectral range and step, cm⁻¹: `(v1, v2, dv)`.
    pub solar_wavenumber_per_cm: [f64; 3],
    /// The thermal runs' spectral range and step, cm⁻¹: `(v1, v2, dv)`.
    pub thermal_wavenumber_per_cm: [f64; 3],
    /// The lines of sight of the longwave irradiance: `(zenith_deg, weight_sr)`, zenith
    /// angles 0 to below 90°, multiples of 0.001°, so that `E_LW = Σ weight · L`; the
    /// weights sum to π within [`HEMISPHERE_WEIGHT_TOLERANCE`].
    pub longwave: Vec<(f64, f64)>,
    /// The sun's positions, zenith angles increasing.
    pub sun: Vec<LoadsSun>,
}

/// A range `(v1, v2, dv)` in cm⁻¹ with 0 < v1 < v2 ≤ 50 000 (LOWTRAN7's spectra) and
/// 0 < dv ≤ v2 − v1.
fn check_wavenumbers(path: &str, [v1, v2, dv]: [f64; 3]) -> Result<(), ModelError> {
    if !(v1 > 0.0 && v2 > v1 && v2 <= 50_000.0 && dv > 0.0 && dv <= v2 - v1) {
        return Err(ModelError::new(
            path,
            ModelErrorKind::Other(format!(
                "expected 0 < v1 < v2 <= 50000 cm-1 and 0 < dv <= v2 - v1, found [{v1}, {v2}, {dv}]"
            )),
        ));
    }
    Ok(())
}

/// An angle a deck's `F10.3` holds exactly: a multiple of 0.001°.
fn check_thousandths(path: impl Fn() -> String, v: f64) -> Result<(), ModelError> {
    if (v * 1000.0 - (v * 1000.0).round()).abs() > 1e-6 {
        return Err(ModelError::new(
            path(),
            ModelErrorKind::Other(format!(
                "expected an angle in multiples of 0.001 deg (a deck holds 3 decimals), found {v}"
            )),
        ));
    }
    Ok(())
}

/// Weights that sum to π sr, within [`HEMISPHERE_WEIGHT_TOLERANCE`].
fn check_hemisphere(path: &str, sum_sr: f64) -> Result<(), ModelError> {
    let off = (sum_sr / std::f64::consts::PI - 1.0).abs();
    if off.is_nan() || off > HEMISPHERE_WEIGHT_TOLERANCE {
        return Err(ModelError::new(
            path,
            ModelErrorKind::Other(format!(
                "the weights sum to {sum_sr} sr: a rule for the cosine-weighted hemisphere sums \
                 to pi (3.14159) sr, within {} %",
                HEMISPHERE_WEIGHT_TOLERANCE * 100.0
            )),
        ));
    }
    Ok(())
}

/// A sun zenith angle: finite, 0 to below 90° (a sun at or below the horizon gives no
/// direct light, and LOWTRAN7 cannot make the path).
fn check_sun_zenith(path: impl Fn() -> String, z: f64) -> Result<(), ModelError> {
    if !(z.is_finite() && (0.0..90.0).contains(&z)) {
        return Err(ModelError::new(
            path(),
            ModelErrorKind::Other(format!(
                "expected the sun's zenith angle from 0 to below 90 deg (a sun at or below the \
                 horizon gives no direct light), found {z}"
            )),
        ));
    }
    Ok(())
}

fn check_day(path: &str, day: u16) -> Result<(), ModelError> {
    if !(1..=366).contains(&day) {
        return Err(ModelError::new(
            path,
            ModelErrorKind::Other(format!(
                "expected a day of the year from 1 to 366, found {day}"
            )),
        ));
    }
    Ok(())
}

impl LoadsPlan {
    /// Checks the model and aerosol (as an atmosphere plan's), the albedo (0–1, hundredths),
    /// the day (1–366), the two spectral ranges, every line of sight (angles in range and
    /// multiples of 0.001°, weights not negative, each rule summing to π sr within
    /// [`HEMISPHERE_WEIGHT_TOLERANCE`]) and the sun's zenith angles (at least one, 0 to
    /// below 90°, increasing, multiples of 0.001°).
    ///
    /// # Errors
    /// The first rule broken, with its path (`sun[2].diffuse[5]`).
    pub fn validate(&self) -> Result<(), ModelError> {
        self.model.validate()?;
        if let Some(a) = &self.aerosol {
            a.validate()?;
        }
        check_range(|| "ground_albedo".into(), self.ground_albedo, 0.0, 1.0)?;
        let a = self.ground_albedo * 100.0;
        if (a - a.round()).abs() > 1e-6 {
            return Err(ModelError::new(
                "ground_albedo",
                ModelErrorKind::Other(format!(
                    "expected an albedo in multiples of 0.01 (a deck holds 2 decimals), found {}",
                    self.ground_albedo
                )),
            ));
        }
        check_day("day_of_year", self.day_of_year)?;
        check_wavenumbers("solar_wavenumber_per_cm", self.solar_wavenumber_per_cm)?;
        check_wavenumbers("thermal_wavenumber_per_cm", self.thermal_wavenumber_per_cm)?;
        if self.longwave.is_empty() {
            return Err(ModelError::new("longwave", ModelErrorKind::Empty));
        }
        for (i, &(z, w)) in self.longwave.iter().enumerate() {
            check_range(|| format!("longwave[{i}].zenith_deg"), z, 0.0, 89.999)?;
            check_thousandths(|| format!("longwave[{i}].zenith_deg"), z)?;
            check_range(|| format!("longwave[{i}].weight_sr"), w, 0.0, f64::MAX)?;
        }
        check_hemisphere("longwave", self.longwave.iter().map(|n| n.1).sum())?;
        if self.sun.is_empty() {
            return Err(ModelError::new("sun", ModelErrorKind::Empty));
        }
        for (k, sun) in self.sun.iter().enumerate() {
            check_sun_zenith(|| format!("sun[{k}].zenith_deg"), sun.zenith_deg)?;
            check_thousandths(|| format!("sun[{k}].zenith_deg"), sun.zenith_deg)?;
            if sun.diffuse.is_empty() {
                return Err(ModelError::new(
                    format!("sun[{k}].diffuse"),
                    ModelErrorKind::Empty,
                ));
            }
            for (i, &(z, az, w)) in sun.diffuse.iter().enumerate() {
                let at = |f: &str| format!("sun[{k}].diffuse[{i}].{f}");
                check_range(|| at("zenith_deg"), z, 0.0, 90.0)?;
                check_thousandths(|| at("zenith_deg"), z)?;
                check_range(|| at("azimuth_deg"), az, 0.0, 180.0)?;
                check_thousandths(|| at("azimuth_deg"), az)?;
                check_range(|| at("weight_sr"), w, 0.0, f64::MAX)?;
            }
            check_hemisphere(
                &format!("sun[{k}].diffuse"),
                sun.diffuse.iter().map(|n| n.2).sum(),
            )?;
        }
        check_increasing(
            |k| format!("sun[{k}].zenith_deg"),
            self.sun.iter().map(|s| s.zenith_deg),
        )
    }
}

/// A day's broadband loads at the ground, one row per sun zenith angle (what
/// `irsig-atmos build` makes of a [`LoadsPlan`]). GHI is not stored: it is `DNI cos z +
/// DHI`. The longwave irradiance does not depend on the sun and is one number.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BroadbandLoads {
    /// The table's name (the plan's).
    pub name: String,
    /// How it was made: the program, the model, the aerosol, the spectral ranges, the
    /// quadratures, the runs.
    pub source: String,
    /// The model atmosphere, in words (`MODEL=6 (us-std-1976)`, or a radiosonde's levels).
    pub model: String,
    /// The aerosol of every run; none: no aerosol.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub aerosol: Option<PlanAerosol>,
    /// The ground's albedo the runs took (LOWTRAN7's SALB).
    pub ground_albedo: f64,
    /// Day of the year, 1–366.
    pub day_of_year: u16,
    /// The solar spectral range the irradiances are integrated over, cm⁻¹, `(v1, v2)`.
    pub solar_wavenumber_per_cm: [f64; 2],
    /// The thermal spectral range LOWTRAN7 gave the longwave over, cm⁻¹, `(v1, v2)`.
    pub thermal_wavenumber_per_cm: [f64; 2],
    /// The extraterrestrial solar irradiance on a surface facing the sun over the solar
    /// range, on `day_of_year`, W m⁻².
    pub extraterrestrial_normal_w_m2: f64,
    /// The sun's zenith angles, degrees, increasing, 0 to below 90.
    pub sun_zenith_deg: Vec<f64>,
    /// The direct normal irradiance at each zenith angle, W m⁻², at most the
    /// extraterrestrial.
    pub direct_normal_w_m2: Vec<f64>,
    /// The apparent zenith angle each direct beam was run at, degrees, one per
    /// `sun_zenith_deg` (which are geometric): LOWTRAN7's card 3 ANGLE, that of the
    /// refracted ray that leaves the atmosphere toward the sun (ANGLE + BENDING = the
    /// sun's angle, to 0.002°). Empty: every beam was run at its sun's own angle (suns
    /// bent less than 0.03°, or a table made before the beams were refracted).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub apparent_sun_zenith_deg: Vec<f64>,
    /// The diffuse horizontal irradiance at each zenith angle, W m⁻².
    pub diffuse_horizontal_w_m2: Vec<f64>,
    /// The downwelling longwave irradiance on a horizontal surface, W m⁻²: LOWTRAN7's
    /// over the thermal range plus `longwave_outside_range_w_m2`.
    pub longwave_down_w_m2: f64,
    /// The part of `longwave_down_w_m2` below the thermal range, W m⁻²: a blackbody at
    /// `air_temperature_k` (the lower atmosphere is opaque there).
    pub longwave_outside_range_w_m2: f64,
    /// The air temperature at the ground (the model's lowest level), K.
    pub air_temperature_k: f64,
    /// What a user should know: what lies outside the ranges, the quadratures' measured
    /// errors, runs moved off their node.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub notes: Vec<String>,
}

impl BroadbandLoads {
    /// Checks the day, the ranges (increasing, positive), the rows (one per zenith angle,
    /// zenith angles 0 to below 90° and increasing, irradiances finite and not negative,
    /// the direct at most the extraterrestrial), the longwave (its outside part not
    /// negative and at most the whole) and the air temperature (above 0 K).
    ///
    /// # Errors
    /// The first rule broken, with its path.
    pub fn validate(&self) -> Result<(), ModelError> {
        check_day("day_of_year", self.day_of_year)?;
        check_range(|| "ground_albedo".into(), self.ground_albedo, 0.0, 1.0)?;
        for (name, [v1, v2]) in [
            ("solar_wavenumber_per_cm", self.solar_wavenumber_per_cm),
            ("thermal_wavenumber_per_cm", self.thermal_wavenumber_per_cm),
        ] {
            if !(v1 > 0.0 && v2 > v1 && v2.is_finite()) {
                return Err(ModelError::new(
                    name,
                    ModelErrorKind::Other(format!("expected 0 < v1 < v2 cm-1, found [{v1}, {v2}]")),
                ));
            }
        }
        check_range(
            || "extraterrestrial_normal_w_m2".into(),
            self.extraterrestrial_normal_w_m2,
            0.0,
            f64::MAX,
        )?;
        let n = self.sun_zenith_deg.len();
        if n == 0 {
            return Err(ModelError::new("sun_zenith_deg", ModelErrorKind::Empty));
        }
        for (name, len) in [
            ("direct_normal_w_m2", self.direct_normal_w_m2.len()),
            (
                "diffuse_horizontal_w_m2",
                self.diffuse_horizontal_w_m2.len(),
            ),
        ] {
            if len != n {
                return Err(ModelError::new(
                    name,
                    ModelErrorKind::Other(format!(
                        "expected one value per sun zenith angle ({n}), found {len}"
                    )),
                ));
            }
        }
        for (k, &z) in self.sun_zenith_deg.iter().enumerate() {
            check_sun_zenith(|| format!("sun_zenith_deg[{k}]"), z)?;
        }
        check_increasing(
            |k| format!("sun_zenith_deg[{k}]"),
            self.sun_zenith_deg.iter().copied(),
        )?;
        if !self.apparent_sun_zenith_deg.is_empty() && self.apparent_sun_zenith_deg.len() != n {
            return Err(ModelError::new(
                "apparent_sun_zenith_deg",
                ModelErrorKind::Other(format!(
                    "expected one angle per sun zenith angle ({n}), or none, found {}",
                    self.apparent_sun_zenith_deg.len()
                )),
            ));
        }
        for (k, (&a, &z)) in self
            .apparent_sun_zenith_deg
            .iter()
            .zip(&self.sun_zenith_deg)
            .enumerate()
        {
            // Refraction lifts a sun: its apparent angle is at most its geometric one.
            check_range(|| format!("apparent_sun_zenith_deg[{k}]"), a, 0.0, z)?;
        }
        // The direct beam is the extraterrestrial one times a transmittance of at most 1
        // (LOWTRAN prints 1.0002 on metre-long paths: a part in 10^3 is allowed).
        let most = self.extraterrestrial_normal_w_m2 * 1.001;
        for (k, &e) in self.direct_normal_w_m2.iter().enumerate() {
            check_range(|| format!("direct_normal_w_m2[{k}]"), e, 0.0, most)?;
        }
        for (k, &e) in self.diffuse_horizontal_w_m2.iter().enumerate() {
            check_range(|| format!("diffuse_horizontal_w_m2[{k}]"), e, 0.0, f64::MAX)?;
        }
        check_range(
            || "longwave_down_w_m2".into(),
            self.longwave_down_w_m2,
            0.0,
            f64::MAX,
        )?;
        check_range(
            || "longwave_outside_range_w_m2".into(),
            self.longwave_outside_range_w_m2,
            0.0,
            self.longwave_down_w_m2,
        )?;
        if !(self.air_temperature_k.is_finite() && self.air_temperature_k > 0.0) {
            return Err(ModelError::new(
                "air_temperature_k",
                ModelErrorKind::Other(format!(
                    "expected a temperature above 0 K, found {}",
                    self.air_temperature_k
                )),
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::AerosolModel;

    fn plan() -> LoadsPlan {
        let pi = std::f64::consts::PI;
        LoadsPlan {
            name: "day".into(),
            model: PlanModel::Standard(6),
            aerosol: Some(PlanAerosol {
                model: AerosolModel::Rural,
                visibility_m: 23_000.0,
                wind_speed_m_s: None,
            }),
            ground_albedo: 0.2,
            day_of_year: 172,
            solar_wavenumber_per_cm: [2500.0, 35_720.0, 20.0],
            thermal_wavenumber_per_cm: [20.0, 3000.0, 20.0],
            longwave: vec![(30.0, 0.5 * pi), (60.0, 0.5 * pi)],
            sun: vec![
                LoadsSun {
                    zenith_deg: 0.0,
                    diffuse: vec![(45.0, 0.0, pi)],
                },
                LoadsSun {
                    zenith_deg: 30.5,
                    diffuse: vec![(10.0, 0.0, 0.25 * pi), (60.0, 180.0, 0.75 * pi)],
                },
            ],
        }
    }

    fn table() -> BroadbandLoads {
        BroadbandLoads {
            apparent_sun_zenith_deg: Vec::new(),
            name: "day".into(),
            source: "test".into(),
            model: "MODEL=6".into(),
            aerosol: None,
            ground_albedo: 0.0,
            day_of_year: 172,
            solar_wavenumber_per_cm: [2500.0, 35_720.0],
            thermal_wavenumber_per_cm: [20.0, 3000.0],
            extraterrestrial_normal_w_m2: 1311.0,
            sun_zenith_deg: vec![0.0, 30.0],
            direct_normal_w_m2: vec![990.0, 950.0],
            diffuse_horizontal_w_m2: vec![45.0, 44.0],
            longwave_down_w_m2: 281.0,
            longwave_outside_range_w_m2: 0.02,
            air_temperature_k: 288.2,
            notes: Vec::new(),
        }
    }

    #[test]
    fn every_rule_of_a_loads_plan_names_its_field() {
        plan().validate().unwrap();
        type Break = dyn Fn(&mut LoadsPlan);
        let cases: [(&Break, &str); 16] = [
            (&|p| p.model = PlanModel::Standard(9), "model"),
            (&|p| p.ground_albedo = 1.5, "ground_albedo"),
            (&|p| p.ground_albedo = 0.205, "ground_albedo"),
            (&|p| p.day_of_year = 0, "day_of_year"),
            (&|p| p.day_of_year = 367, "day_of_year"),
            (
                &|p| p.solar_wavenumber_per_cm = [35_720.0, 2500.0, 20.0],
                "solar_wavenumber_per_cm",
            ),
            (
                &|p| p.thermal_wavenumber_per_cm = [20.0, 3000.0, 0.0],
                "thermal_wavenumber_per_cm",
            ),
            (&|p| p.longwave.clear(), "longwave"),
            (&|p| p.longwave[1].0 = 90.0, "longwave[1].zenith_deg"),
            (&|p| p.longwave[1].1 = 3.0, "longwave"),
            (&|p| p.sun.clear(), "sun"),
            (&|p| p.sun[1].zenith_deg = 90.0, "sun[1].zenith_deg"),
            (&|p| p.sun[1].zenith_deg = f64::NAN, "sun[1].zenith_deg"),
            (&|p| p.sun[1].zenith_deg = 0.0, "sun[1].zenith_deg"),
            (
                &|p| p.sun[1].diffuse[0].1 = 181.0,
                "sun[1].diffuse[0].azimuth_deg",
            ),
            (&|p| p.sun[0].diffuse.clear(), "sun[0].diffuse"),
        ];
        for (break_it, field) in cases {
            let mut p = plan();
            break_it(&mut p);
            let e = p.validate().unwrap_err();
            assert_eq!(e.path, field, "{e}");
        }
        // A deck holds 0.001 deg: a node between is refused.
        let mut p = plan();
        p.sun[1].diffuse[1].0 = 60.0005;
        assert_eq!(
            p.validate().unwrap_err().path,
            "sun[1].diffuse[1].zenith_deg"
        );
        // A sun just above the horizon is a sun.
        let mut p = plan();
        p.sun[1].zenith_deg = 89.999;
        p.validate().unwrap();
    }

    #[test]
    fn a_table_has_one_row_per_zenith_and_no_more_sun_than_space_gives() {
        table().validate().unwrap();
        type Break = dyn Fn(&mut BroadbandLoads);
        // The apparent angles the beams ran at: one per sun, at most its geometric angle.
        let mut lifted = table();
        lifted.apparent_sun_zenith_deg = vec![0.0, 29.991];
        lifted.validate().unwrap();
        let cases: [(&Break, &str); 12] = [
            (
                &|t| t.apparent_sun_zenith_deg = vec![0.0],
                "apparent_sun_zenith_deg",
            ),
            (
                &|t| t.apparent_sun_zenith_deg = vec![0.0, 30.001],
                "apparent_sun_zenith_deg[1]",
            ),
            (&|t| t.day_of_year = 0, "day_of_year"),
            (&|t| t.sun_zenith_deg.clear(), "sun_zenith_deg"),
            (
                &|t| {
                    t.direct_normal_w_m2.pop();
                },
                "direct_normal_w_m2",
            ),
            (&|t| t.sun_zenith_deg[1] = 95.0, "sun_zenith_deg[1]"),
            (&|t| t.sun_zenith_deg = vec![30.0, 0.0], "sun_zenith_deg[1]"),
            (
                &|t| t.direct_normal_w_m2[0] = 1400.0,
                "direct_normal_w_m2[0]",
            ),
            (
                &|t| t.diffuse_horizontal_w_m2[1] = -1.0,
                "diffuse_horizontal_w_m2[1]",
            ),
            (
                &|t| t.longwave_outside_range_w_m2 = 300.0,
                "longwave_outside_range_w_m2",
            ),
            (&|t| t.air_temperature_k = 0.0, "air_temperature_k"),
            (
                &|t| t.solar_wavenumber_per_cm = [2500.0, 2500.0],
                "solar_wavenumber_per_cm",
            ),
        ];
        for (break_it, field) in cases {
            let mut t = table();
            break_it(&mut t);
            let e = t.validate().unwrap_err();
            assert_eq!(e.path, field, "{e}");
        }
    }
}
