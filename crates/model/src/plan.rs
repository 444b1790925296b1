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

impl PlanModel {
    /// Checks the model: a standard model 1–6, or a radiosonde of at least 2 levels whose
    /// altitudes increase; paths name the field `model`.
    ///
    /// # Errors
    /// The first rule broken.
    pub fn validate(&self) -> Result<(), ModelError> {
        match self {
            PlanModel::Standard(m) if !(1..=6).contains(m) => Err(ModelError::new(
                "model",
                ModelErrorKind::Other(format!("expected a standard model 1 to 6, found {m}")),
            )),
            PlanModel::Standard(_) => Ok(()),
            PlanModel::Radiosonde(levels) => {
                if levels.len() < 2 {
                    return Err(ModelError::new(
                        "model",
                        ModelErrorKind::Other("a radiosonde needs at least 2 levels".into()),
                    ));
                }
                check_increasing(
                    |i| format!("model.Radiosonde[{i}].altitude_m"),
                    levels.iter().map(|l| l.altitude_m),
                )
            }
        }
    }
}

/// The sun of a daylight build: where it stands and the altitudes at which LOWTRAN7
/// computes its direct irradiance (IEMSCT = 3, one run per altitude).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlanSun {
    /// The sun's zenith angle at the scene, degrees, from 0 to below 90 (a sun at or below
    /// the horizon gives no direct light), in multiples of 0.001° (a deck's `F10.3`).
    pub zenith_deg: f64,
    /// Day of the year, 1–366 (LOWTRAN7's IDAY: the Earth–Sun distance that scales the
    /// extraterrestrial irradiance; 366 is a leap year's 31 December).
    pub day_of_year: u16,
    /// Altitudes of the direct solar irradiance table, metres above the scene's lowest
    /// point, increasing, whole metres.
    pub altitude_m: Vec<f64>,
    /// Azimuths of a line of sight from the sun's vertical plane, degrees, increasing
    /// within 0 (toward the sun's azimuth) to 180, multiples of 0.001°: each slant and sky
    /// path is run once more per azimuth in LOWTRAN7's IEMSCT = 2 for the sunlight it
    /// scatters. Empty: the direct beam only.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub relative_azimuth_deg: Vec<f64>,
    /// Further suns of the same day for the direct beam, zenith angles increasing above
    /// `zenith_deg`, below 90°, multiples of 0.001°: each is run at every altitude, and the
    /// build's solar table holds them all (`SpectralSolar::further_suns`). Empty: one sun.
    /// With relative azimuths, each sun also runs every sunlit path (not with slabs: a slab
    /// table holds one sun's scattered sunlight).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub further_zenith_deg: Vec<f64>,
}

impl PlanSun {
    /// The plan's sun zenith angles, degrees, increasing: `zenith_deg`, then the further
    /// suns'.
    #[must_use]
    pub fn zeniths_deg(&self) -> Vec<f64> {
        std::iter::once(self.zenith_deg)
            .chain(self.further_zenith_deg.iter().copied())
            .collect()
    }

    /// Checks the zenith angle (finite, 0 to below 90°, thousandths of a degree), the day
    /// (1–366) and the altitudes (not empty, not negative, increasing, whole metres); paths
    /// name the fields under `sun`.
    ///
    /// # Errors
    /// The first rule broken.
    pub fn validate(&self) -> Result<(), ModelError> {
        let z = self.zenith_deg;
        if !(z.is_finite() && (0.0..90.0).contains(&z)) {
            return Err(ModelError::new(
                "sun.zenith_deg",
                ModelErrorKind::Other(format!(
                    "expected the sun's zenith angle from 0 to below 90 deg (a sun at or below \
                     the horizon gives no direct light), found {z}"
                )),
            ));
        }
        if (z * 1000.0 - (z * 1000.0).round()).abs() > 1e-6 {
            return Err(ModelError::new(
                "sun.zenith_deg",
                ModelErrorKind::Other(format!(
                    "expected an angle in multiples of 0.001 deg (a deck holds 3 decimals), found {z}"
                )),
            ));
        }
        if !(1..=366).contains(&self.day_of_year) {
            return Err(ModelError::new(
                "sun.day_of_year",
                ModelErrorKind::Other(format!(
                    "expected a day of the year from 1 to 366, found {}",
                    self.day_of_year
                )),
            ));
        }
        if self.altitude_m.is_empty() {
            return Err(ModelError::new("sun.altitude_m", ModelErrorKind::Empty));
        }
        for (i, &h) in self.altitude_m.iter().enumerate() {
            check_range(|| format!("sun.altitude_m[{i}]"), h, 0.0, f64::MAX)?;
            if (h - h.round()).abs() > 1e-6 {
                return Err(ModelError::new(
                    format!("sun.altitude_m[{i}]"),
                    ModelErrorKind::Other(format!(
                        "expected a whole number of metres (a deck holds km to 3 decimals), found {h}"
                    )),
                ));
            }
        }
        check_increasing(
            |i| format!("sun.altitude_m[{i}]"),
            self.altitude_m.iter().copied(),
        )?;
        for (i, &a) in self.relative_azimuth_deg.iter().enumerate() {
            check_range(|| format!("sun.relative_azimuth_deg[{i}]"), a, 0.0, 180.0)?;
            if (a * 1000.0 - (a * 1000.0).round()).abs() > 1e-6 {
                return Err(ModelError::new(
                    format!("sun.relative_azimuth_deg[{i}]"),
                    ModelErrorKind::Other(format!(
                        "expected an angle in multiples of 0.001 deg (a deck holds 3 decimals), found {a}"
                    )),
                ));
            }
        }
        check_increasing(
            |i| format!("sun.relative_azimuth_deg[{i}]"),
            self.relative_azimuth_deg.iter().copied(),
        )?;
        self.validate_further()
    }

    fn validate_further(&self) -> Result<(), ModelError> {
        let mut previous = self.zenith_deg;
        for (i, &z) in self.further_zenith_deg.iter().enumerate() {
            let path = || format!("sun.further_zenith_deg[{i}]");
            if !(z.is_finite() && z > previous && z < 90.0) {
                return Err(ModelError::new(
                    path(),
                    ModelErrorKind::Other(format!(
                        "expected a zenith angle above the previous sun's ({previous} deg) and \
                         below 90 deg, found {z}"
                    )),
                ));
            }
            if (z * 1000.0 - (z * 1000.0).round()).abs() > 1e-6 {
                return Err(ModelError::new(
                    path(),
                    ModelErrorKind::Other(format!(
                        "expected an angle in multiples of 0.001 deg (a deck holds 3 decimals), found {z}"
                    )),
                ));
            }
            previous = z;
        }
        Ok(())
    }
}

/// One of LOWTRAN7's boundary-layer aerosol models (card 2's IHAZE). LOWTRAN's IHAZE 1
/// and 2 are both the rural model (they differ only in the default visibility irsig never
/// uses); its user-defined aerosol (7), fogs (8, 9) and Navy maritime model (3, whose
/// extinction depends on winds and an air-mass character) are not offered.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum AerosolModel {
    /// Rural (continental), IHAZE 1.
    Rural,
    /// Urban, IHAZE 5.
    Urban,
    /// Maritime (LOWTRAN 5's), IHAZE 4.
    Maritime,
    /// Tropospheric, IHAZE 6.
    Tropospheric,
    /// Desert, IHAZE 10: its extinction spectrum depends on the wind speed.
    Desert,
}

impl AerosolModel {
    /// Every model, with the name the command line and the plan's RON use.
    pub const ALL: [(Self, &'static str); 5] = [
        (Self::Rural, "rural"),
        (Self::Urban, "urban"),
        (Self::Maritime, "maritime"),
        (Self::Tropospheric, "tropospheric"),
        (Self::Desert, "desert"),
    ];

    /// LOWTRAN7's IHAZE (card 2).
    #[must_use]
    pub fn ihaze(self) -> i64 {
        match self {
            Self::Rural => 1,
            Self::Urban => 5,
            Self::Maritime => 4,
            Self::Tropospheric => 6,
            Self::Desert => 10,
        }
    }

    /// The command line's name of the model (`rural`).
    #[must_use]
    pub fn name(self) -> &'static str {
        Self::ALL
            .iter()
            .find(|(m, _)| *m == self)
            .map_or("?", |(_, n)| n)
    }
}

/// The largest meteorological range LOWTRAN7's aerosol profiles hold, metres: its
/// visibility counts the air's own (Rayleigh) extinction at 0.55 µm, 0.01159 km⁻¹ at sea
/// level (`VIS = 3.912/(EXT55 + 0.01159)` in its `MARINE` and `DESATT`), so beyond
/// 3.912/0.01159 km = 337.5 km the aerosol's extinction would be negative.
pub const MAX_VISIBILITY_M: f64 = 337_000.0;

/// The aerosol of every path of a build (LOWTRAN7's card 2).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlanAerosol {
    /// The boundary-layer aerosol model.
    pub model: AerosolModel,
    /// The meteorological range (visibility) at the ground, metres (LOWTRAN7's VIS, in
    /// km on the card): the range at which a black object's contrast falls to 2 %, so the
    /// ground's total extinction coefficient at 0.55 µm, aerosol and air, is 3.912/VIS
    /// (Koschmieder). Whole metres (a deck holds km to 3 decimals), above 0 and at most
    /// [`MAX_VISIBILITY_M`].
    pub visibility_m: f64,
    /// The desert model's wind speed at 10 m, m/s (LOWTRAN7's WSS), 0–30 (its tables'
    /// range); required with `Desert`, refused with the others.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wind_speed_m_s: Option<f64>,
}

impl PlanAerosol {
    /// Checks the visibility (finite, above 0, at most [`MAX_VISIBILITY_M`], whole
    /// metres) and the wind speed (given for the desert model only, 0–30 m/s); paths name
    /// the fields under `aerosol`.
    ///
    /// # Errors
    /// The first rule broken.
    pub fn validate(&self) -> Result<(), ModelError> {
        let v = self.visibility_m;
        if !(v.is_finite() && v > 0.0 && v <= MAX_VISIBILITY_M) {
            return Err(ModelError::new(
                "aerosol.visibility_m",
                ModelErrorKind::Other(format!(
                    "expected a meteorological range above 0 and at most {MAX_VISIBILITY_M} m \
                     (beyond it the air alone is clearer than that), found {v}"
                )),
            ));
        }
        if (v - v.round()).abs() > 1e-6 {
            return Err(ModelError::new(
                "aerosol.visibility_m",
                ModelErrorKind::Other(format!(
                    "expected a whole number of metres (a deck holds km to 3 decimals), found {v}"
                )),
            ));
        }
        match (self.model, self.wind_speed_m_s) {
            (AerosolModel::Desert, None) => Err(ModelError::new(
                "aerosol.wind_speed_m_s",
                ModelErrorKind::Other(
                    "the desert aerosol needs the wind speed at 10 m, m/s (0-30)".into(),
                ),
            )),
            (AerosolModel::Desert, Some(w)) => {
                check_range(|| "aerosol.wind_speed_m_s".into(), w, 0.0, 30.0)?;
                if (w * 1000.0 - (w * 1000.0).round()).abs() > 1e-6 {
                    return Err(ModelError::new(
                        "aerosol.wind_speed_m_s",
                        ModelErrorKind::Other(format!(
                            "expected a speed in multiples of 0.001 m/s (a deck holds 3 decimals), found {w}"
                        )),
                    ));
                }
                Ok(())
            }
            (m, Some(w)) => Err(ModelError::new(
                "aerosol.wind_speed_m_s",
                ModelErrorKind::Other(format!(
                    "a wind speed ({w} m/s) is used by the desert aerosol only, not by `{}`",
                    m.name()
                )),
            )),
            (_, None) => Ok(()),
        }
    }
}

/// LOWTRAN7 run for slabs that end above the ground: from each of the plan's observers to
/// target altitudes between the ground and the scene's top, so that a view path from an
/// observer to a facet above the ground takes its transmittance, thermal path radiance and
/// (by day) scattered sunlight from runs of such slabs (`irsig_atmosphere::slab`) instead of
/// the difference of two paths to the ground. For observer `o`, every target below it is
/// run at each of `nadir_deg` (ITYPE 2, H1 = `o`, H2 = the target, ANGLE = 180° − nadir)
/// and every target above it at each of `zenith_deg` (ANGLE = zenith); a target at `o`
/// itself is the path of no length (τ = 1, no radiance) and is not run. By day each slab
/// is run again at each of the sun's `relative_azimuth_deg` (IEMSCT = 2). An observer with
/// `b` targets below and `a` above costs `b·len(nadir_deg) + a·len(zenith_deg)` runs, times
/// `1 + len(sun.relative_azimuth_deg)` by day.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlanSlabs {
    /// Target altitudes, metres above the scene's lowest point, increasing, whole metres,
    /// above the paths' end.
    pub target_m: Vec<f64>,
    /// Nadir angles of the slabs down from an observer, degrees, increasing within 0 to
    /// 89.999, multiples of 0.001°.
    pub nadir_deg: Vec<f64>,
    /// Zenith angles of the slabs up from an observer, degrees, increasing within 0 to
    /// 89.999, multiples of 0.001°.
    pub zenith_deg: Vec<f64>,
}

impl PlanSlabs {
    /// The targets below `observer_m` and those above it (a target at it is neither).
    #[must_use]
    pub fn targets_of(&self, observer_m: f64) -> (Vec<f64>, Vec<f64>) {
        let below = self
            .target_m
            .iter()
            .copied()
            .filter(|&t| t < observer_m)
            .collect();
        let above = self
            .target_m
            .iter()
            .copied()
            .filter(|&t| t > observer_m)
            .collect();
        (below, above)
    }

    /// LOWTRAN7 runs of the slabs of one observer, thermal only (by day, times one plus
    /// the sun's azimuths).
    #[must_use]
    pub fn runs_of(&self, observer_m: f64) -> usize {
        let (below, above) = self.targets_of(observer_m);
        below.len() * self.nadir_deg.len() + above.len() * self.zenith_deg.len()
    }
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
    /// The sun, for a daylight build; none at night (no solar runs, as before).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sun: Option<PlanSun>,
    /// The aerosol of every path; none: no aerosol (LOWTRAN7's IHAZE 0), as before.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub aerosol: Option<PlanAerosol>,
    /// Slabs from each observer to targets above the ground; none: no slab runs, as
    /// before.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub slabs: Option<PlanSlabs>,
}

impl AtmospherePlan {
    /// Checks the node lists: altitudes not negative and increasing, angles within their
    /// ranges and increasing, every observer above the paths' end, altitudes whole metres
    /// and angles multiples of 0.001° (what the decks' `F10.3` fields of km and degrees
    /// hold exactly: a plan's node and its deck's path are then the same), a sensible
    /// spectral range, a known model.
    ///
    /// # Errors
    /// The first rule broken.
    pub fn validate(&self) -> Result<(), ModelError> {
        let [v1, v2, dv] = self.wavenumber_per_cm;
        // LOWTRAN7's spectra span 0 to 50000 cm-1; its finest step is 1 cm-1 (a finer one
        // asks for billions of spectral points from a hand-edited plan).
        if !(v1 > 0.0 && v2 > v1 && v2 <= 50_000.0 && (1.0..=v2 - v1).contains(&dv)) {
            return Err(ModelError::new(
                "wavenumber_per_cm",
                ModelErrorKind::Other(format!(
                    "expected 0 < v1 < v2 <= 50000 cm-1 and a step dv from 1 cm-1 (LOWTRAN7's \
                     finest) to v2 - v1, found [{v1}, {v2}, {dv}]"
                )),
            ));
        }
        self.model.validate()?;
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
        check_range(
            || "correction_altitude_m".into(),
            self.correction_altitude_m,
            0.0,
            f64::MAX,
        )?;
        for (i, &h) in self.observers_m.iter().enumerate() {
            check_range(|| format!("observers_m[{i}]"), h, 0.0, f64::MAX)?;
            if h <= self.path_end_m {
                return Err(ModelError::new(
                    format!("observers_m[{i}]"),
                    ModelErrorKind::Other(format!(
                        "an observer at {h} m is not above the paths' end ({} m): its slant \
                         paths would run up, or nowhere",
                        self.path_end_m
                    )),
                ));
            }
        }
        let whole = |path: String, v: f64| -> Result<(), ModelError> {
            if (v - v.round()).abs() > 1e-6 {
                return Err(ModelError::new(
                    path,
                    ModelErrorKind::Other(format!(
                        "expected a whole number of metres (a deck holds km to 3 decimals), found {v}"
                    )),
                ));
            }
            Ok(())
        };
        whole("path_end_m".into(), self.path_end_m)?;
        whole("correction_altitude_m".into(), self.correction_altitude_m)?;
        for (name, axis) in [
            ("observers_m", &self.observers_m),
            ("levels_m", &self.levels_m),
            ("slant_altitude_m", &self.slant_altitude_m),
            ("sky_altitude_m", &self.sky_altitude_m),
        ] {
            for (i, &v) in axis.iter().enumerate() {
                whole(format!("{name}[{i}]"), v)?;
            }
        }
        let thousandths = |path: String, v: f64| -> Result<(), ModelError> {
            if (v * 1000.0 - (v * 1000.0).round()).abs() > 1e-6 {
                return Err(ModelError::new(
                    path,
                    ModelErrorKind::Other(format!(
                        "expected an angle in multiples of 0.001 deg (a deck holds 3 decimals), found {v}"
                    )),
                ));
            }
            Ok(())
        };
        for (name, axis) in [
            ("correction_nadir_deg", &self.correction_nadir_deg),
            ("ground_sky_zenith_deg", &self.ground_sky_zenith_deg),
            ("slant_nadir_deg", &self.slant_nadir_deg),
            ("sky_zenith_deg", &self.sky_zenith_deg),
        ] {
            for (i, &v) in axis.iter().enumerate() {
                thousandths(format!("{name}[{i}]"), v)?;
            }
        }
        for (i, &(z, _)) in self.hemispheric.iter().enumerate() {
            thousandths(format!("hemispheric[{i}].zenith_deg"), z)?;
        }
        if let Some(sun) = &self.sun {
            sun.validate()?;
        }
        if let Some(aerosol) = &self.aerosol {
            aerosol.validate()?;
        }
        if let Some(slabs) = &self.slabs {
            self.validate_slabs(slabs)?;
        }
        Ok(())
    }

    fn validate_slabs(&self, slabs: &PlanSlabs) -> Result<(), ModelError> {
        // A slab table holds one sun's scattered sunlight (`SpectralSlabTable`).
        if let Some(sun) = self
            .sun
            .as_ref()
            .filter(|s| !(s.further_zenith_deg.is_empty() || s.relative_azimuth_deg.is_empty()))
        {
            return Err(ModelError::new(
                "slabs",
                ModelErrorKind::Other(format!(
                    "a slab table holds the scattered sunlight of one sun, and the plan's sun has \
                     {} zenith angles: plan slabs with one sun, or several suns without slabs",
                    1 + sun.further_zenith_deg.len()
                )),
            ));
        }
        if self.observers_m.is_empty() {
            return Err(ModelError::new(
                "slabs",
                ModelErrorKind::Other(
                    "slabs run from the plan's observers, and `observers_m` is empty".into(),
                ),
            ));
        }
        for (name, axis, max) in [
            ("slabs.target_m", &slabs.target_m, f64::MAX),
            ("slabs.nadir_deg", &slabs.nadir_deg, 89.999),
            ("slabs.zenith_deg", &slabs.zenith_deg, 89.999),
        ] {
            if axis.is_empty() {
                return Err(ModelError::new(name, ModelErrorKind::Empty));
            }
            for (i, &v) in axis.iter().enumerate() {
                check_range(|| format!("{name}[{i}]"), v, 0.0, max)?;
                let (scale, what) = if name == "slabs.target_m" {
                    (
                        1.0,
                        "a whole number of metres (a deck holds km to 3 decimals)",
                    )
                } else {
                    (
                        1000.0,
                        "an angle in multiples of 0.001 deg (a deck holds 3 decimals)",
                    )
                };
                if (v * scale - (v * scale).round()).abs() > 1e-6 {
                    return Err(ModelError::new(
                        format!("{name}[{i}]"),
                        ModelErrorKind::Other(format!("expected {what}, found {v}")),
                    ));
                }
            }
            check_increasing(|i| format!("{name}[{i}]"), axis.iter().copied())?;
        }
        if slabs.target_m[0] <= self.path_end_m {
            return Err(ModelError::new(
                "slabs.target_m[0]",
                ModelErrorKind::Other(format!(
                    "expected a target above the paths' end ({} m): slabs end above the \
                     ground, the slant table holds the paths to it; found {}",
                    self.path_end_m, slabs.target_m[0]
                )),
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The base plan of the malformed corpus (`tests/data/malformed/base/plan/plan.ron`).
    fn plan() -> AtmospherePlan {
        AtmospherePlan {
            name: "case".into(),
            model: PlanModel::Standard(1),
            wavenumber_per_cm: [710.0, 1250.0, 90.0],
            path_end_m: 1.0,
            observers_m: vec![1000.0],
            levels_m: vec![1000.0],
            correction_altitude_m: 1000.0,
            correction_nadir_deg: vec![0.0, 5.0, 10.0],
            ground_sky_zenith_deg: vec![0.0],
            hemispheric: vec![(41.234, 0.5)],
            slant_altitude_m: vec![1000.0],
            slant_nadir_deg: vec![0.0],
            sky_altitude_m: vec![0.0],
            sky_zenith_deg: vec![0.0],
            sun: None,
            aerosol: None,
            slabs: None,
        }
    }

    #[test]
    fn a_plans_step_is_one_lowtran7_can_take() {
        // 1 cm-1 is LOWTRAN7's finest step; a 1e-9 step would ask for 5e11 points.
        for (range, ok) in [
            ([710.0, 1250.0, 1.0], true),
            ([710.0, 1250.0, 540.0], true),
            ([710.0, 1250.0, 1e-9], false),
            ([710.0, 1250.0, 0.5], false),
            ([710.0, 1250.0, 541.0], false),
            ([1250.0, 710.0, 5.0], false),
            ([710.0, 1250.0, f64::NAN], false),
        ] {
            let mut p = plan();
            p.wavenumber_per_cm = range;
            let got = p.validate();
            assert_eq!(got.is_ok(), ok, "{range:?}: {got:?}");
            if let Err(e) = got {
                assert_eq!(e.path, "wavenumber_per_cm");
            }
        }
    }

    #[test]
    fn slabs_need_observers_and_ordered_whole_rows() {
        let ok = PlanSlabs {
            target_m: vec![100.0, 500.0, 1200.0],
            nadir_deg: vec![0.0, 30.0],
            zenith_deg: vec![10.0, 50.0],
        };
        let mut p = plan();
        p.slabs = Some(ok.clone());
        p.validate().unwrap();
        // The observer at 1 km: two targets below at 2 angles, one above at 2.
        assert_eq!(ok.runs_of(1000.0), 6);
        // At 500 m (a target itself, not run): one below and one above, 2 angles each.
        assert_eq!(ok.runs_of(500.0), 2 + 2);
        type Break = dyn Fn(&mut AtmospherePlan);
        let cases: [(&Break, &str); 8] = [
            (&|p| p.observers_m.clear(), "slabs"),
            (
                &|p| p.slabs.as_mut().unwrap().target_m = vec![500.0, 100.0],
                "slabs.target_m[1]",
            ),
            (
                &|p| p.slabs.as_mut().unwrap().target_m[1] = f64::NAN,
                "slabs.target_m[1]",
            ),
            (
                &|p| p.slabs.as_mut().unwrap().target_m[0] = 12.5,
                "slabs.target_m[0]",
            ),
            (
                &|p| p.slabs.as_mut().unwrap().target_m[0] = 1.0,
                "slabs.target_m[0]",
            ),
            (
                &|p| p.slabs.as_mut().unwrap().nadir_deg = vec![],
                "slabs.nadir_deg",
            ),
            (
                &|p| p.slabs.as_mut().unwrap().zenith_deg = vec![10.0, 90.0],
                "slabs.zenith_deg[1]",
            ),
            (
                &|p| p.slabs.as_mut().unwrap().nadir_deg = vec![0.0, 10.0005],
                "slabs.nadir_deg[1]",
            ),
        ];
        for (break_it, field) in cases {
            let mut p = plan();
            p.slabs = Some(ok.clone());
            break_it(&mut p);
            let e = p.validate().unwrap_err();
            assert_eq!(e.path, field, "{e}");
        }
    }

    #[test]
    fn every_rule_of_the_plan_page_is_checked() {
        plan().validate().unwrap();
        // An observer below the paths' end was built: its page says it is refused.
        let mut p = plan();
        p.observers_m = vec![0.5];
        let e = p.validate().unwrap_err();
        assert_eq!(e.path, "observers_m[0]", "{e}");
        p.observers_m = vec![1.0];
        assert_eq!(p.validate().unwrap_err().path, "observers_m[0]");
        // A deck holds km and degrees to 3 decimals: 12.5 m or 0.0005° would be run at
        // another node than the plan names.
        let mut p = plan();
        p.slant_altitude_m = vec![12.5];
        assert_eq!(p.validate().unwrap_err().path, "slant_altitude_m[0]");
        let mut p = plan();
        p.sky_zenith_deg = vec![0.0, 10.0005];
        assert_eq!(p.validate().unwrap_err().path, "sky_zenith_deg[1]");
        let mut p = plan();
        p.hemispheric = vec![(41.2345, 0.5)];
        assert_eq!(p.validate().unwrap_err().path, "hemispheric[0].zenith_deg");
        let mut p = plan();
        p.correction_altitude_m = f64::NAN;
        assert_eq!(p.validate().unwrap_err().path, "correction_altitude_m");
    }

    #[test]
    fn a_sun_at_or_below_the_horizon_or_on_no_day_is_refused() {
        let sun = PlanSun {
            zenith_deg: 30.0,
            day_of_year: 172,
            altitude_m: vec![0.0, 300.0],
            relative_azimuth_deg: vec![0.0, 90.0, 180.0],
            further_zenith_deg: Vec::new(),
        };
        let mut p = plan();
        p.sun = Some(sun.clone());
        p.validate().unwrap();
        for (z, day, alt, field) in [
            (90.0, 172, vec![0.0], "sun.zenith_deg"),
            (95.0, 172, vec![0.0], "sun.zenith_deg"),
            (-1.0, 172, vec![0.0], "sun.zenith_deg"),
            (f64::NAN, 172, vec![0.0], "sun.zenith_deg"),
            (30.0005, 172, vec![0.0], "sun.zenith_deg"),
            (30.0, 0, vec![0.0], "sun.day_of_year"),
            (30.0, 367, vec![0.0], "sun.day_of_year"),
            (30.0, 172, vec![], "sun.altitude_m"),
            (30.0, 172, vec![300.0, 0.0], "sun.altitude_m[1]"),
            (30.0, 172, vec![-1.0], "sun.altitude_m[0]"),
            (30.0, 172, vec![12.5], "sun.altitude_m[0]"),
        ] {
            p.sun = Some(PlanSun {
                zenith_deg: z,
                day_of_year: day,
                altitude_m: alt,
                relative_azimuth_deg: Vec::new(),
                further_zenith_deg: Vec::new(),
            });
            let e = p.validate().unwrap_err();
            assert_eq!(e.path, field, "{z} {day}: {e}");
        }
        p.sun = Some(PlanSun {
            zenith_deg: 89.999,
            day_of_year: 366,
            ..sun.clone()
        });
        p.validate().unwrap();
        for (az, field) in [
            (vec![-1.0], "sun.relative_azimuth_deg[0]"),
            (vec![0.0, 181.0], "sun.relative_azimuth_deg[1]"),
            (vec![90.0, 30.0], "sun.relative_azimuth_deg[1]"),
            (vec![30.0005], "sun.relative_azimuth_deg[0]"),
        ] {
            p.sun = Some(PlanSun {
                relative_azimuth_deg: az,
                ..sun.clone()
            });
            assert_eq!(p.validate().unwrap_err().path, field);
        }
        // Further suns: increasing above the first, below 90, in thousandths, and only
        // for the direct beam.
        let day = PlanSun {
            relative_azimuth_deg: Vec::new(),
            further_zenith_deg: vec![45.0, 89.999],
            ..sun.clone()
        };
        p.sun = Some(day.clone());
        p.validate().unwrap();
        assert_eq!(day.zeniths_deg(), [30.0, 45.0, 89.999]);
        for (further, field) in [
            (vec![30.0], "sun.further_zenith_deg[0]"),
            (vec![45.0, 40.0], "sun.further_zenith_deg[1]"),
            (vec![45.0, 90.0], "sun.further_zenith_deg[1]"),
            (vec![f64::NAN], "sun.further_zenith_deg[0]"),
            (vec![45.0005], "sun.further_zenith_deg[0]"),
        ] {
            p.sun = Some(PlanSun {
                further_zenith_deg: further,
                ..day.clone()
            });
            assert_eq!(p.validate().unwrap_err().path, field);
        }
        // Several suns with their scattered sunlight: each sun runs the sunlit paths. A
        // slab table holds one sun's: slabs beside them are refused.
        p.sun = Some(PlanSun {
            further_zenith_deg: vec![45.0],
            ..sun.clone()
        });
        p.validate().unwrap();
        p.observers_m = vec![5.0];
        p.slabs = Some(PlanSlabs {
            target_m: vec![2.0, 5.0],
            nadir_deg: vec![0.0],
            zenith_deg: vec![0.0],
        });
        assert_eq!(p.validate().unwrap_err().path, "slabs");
        p.sun = Some(sun.clone());
        p.validate().unwrap();
    }

    #[test]
    fn an_aerosol_without_a_visibility_in_range_or_with_a_wind_it_does_not_use_is_refused() {
        let ok = PlanAerosol {
            model: AerosolModel::Rural,
            visibility_m: 23_000.0,
            wind_speed_m_s: None,
        };
        let mut p = plan();
        p.aerosol = Some(ok.clone());
        p.validate().unwrap();
        for (model, vis, wind, field) in [
            (AerosolModel::Rural, 0.0, None, "aerosol.visibility_m"),
            (AerosolModel::Rural, -5.0, None, "aerosol.visibility_m"),
            (AerosolModel::Urban, f64::NAN, None, "aerosol.visibility_m"),
            (AerosolModel::Urban, 338_000.0, None, "aerosol.visibility_m"),
            (
                AerosolModel::Maritime,
                10_000.5,
                None,
                "aerosol.visibility_m",
            ),
            (
                AerosolModel::Desert,
                10_000.0,
                None,
                "aerosol.wind_speed_m_s",
            ),
            (
                AerosolModel::Desert,
                10_000.0,
                Some(31.0),
                "aerosol.wind_speed_m_s",
            ),
            (
                AerosolModel::Desert,
                10_000.0,
                Some(-1.0),
                "aerosol.wind_speed_m_s",
            ),
            (
                AerosolModel::Rural,
                10_000.0,
                Some(5.0),
                "aerosol.wind_speed_m_s",
            ),
        ] {
            p.aerosol = Some(PlanAerosol {
                model,
                visibility_m: vis,
                wind_speed_m_s: wind,
            });
            let e = p.validate().unwrap_err();
            assert_eq!(e.path, field, "{model:?} {vis} {wind:?}: {e}");
        }
        p.aerosol = Some(PlanAerosol {
            model: AerosolModel::Desert,
            visibility_m: 337_000.0,
            wind_speed_m_s: Some(30.0),
        });
        p.validate().unwrap();
        // LOWTRAN7's card 2 codes (its source's comment block on IHAZE).
        let codes: Vec<i64> = AerosolModel::ALL.iter().map(|(m, _)| m.ihaze()).collect();
        assert_eq!(codes, [1, 5, 4, 6, 10]);
    }
}
