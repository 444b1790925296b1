//! The spectral atmosphere: transmittance, path radiance and sky radiance on a spectral
//! grid, at the nodes the band [`Atmosphere`](crate::Atmosphere) holds band values at, so
//! that a band atmosphere for any band and sensor response can be made from it
//! (`irsig_atmosphere::collapse`).
//!
//! Spectra are single precision (`f32`): the radiative-transfer codes compute in single
//! precision and print 3 to 8 digits, and the two built-ins stay small. Each table of
//! spectra is one flat vector, spectrum after spectrum, `values[k * n + i]` for spectrum
//! `k` at grid point `i` of `n`.

use serde::{Deserialize, Serialize};

use crate::RadiosondeLevel;
use crate::atmosphere::check_radiosonde;
use crate::error::{ModelError, ModelErrorKind, check_finite, check_increasing, check_range};

/// What the spectral grid's numbers are.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SpectralAxis {
    /// Wavenumber in cm⁻¹; spectral radiances are W m⁻² sr⁻¹ per cm⁻¹.
    WavenumberPerCm,
    /// Wavelength in µm; spectral radiances are W m⁻² sr⁻¹ per µm.
    WavelengthUm,
}

impl SpectralAxis {
    /// The unit of the grid's numbers.
    #[must_use]
    pub fn unit(self) -> &'static str {
        match self {
            Self::WavenumberPerCm => "cm-1",
            Self::WavelengthUm => "um",
        }
    }

    /// The unit of a spectral radiance on this grid.
    #[must_use]
    pub fn radiance_unit(self) -> &'static str {
        match self {
            Self::WavenumberPerCm => "W m-2 sr-1 (cm-1)-1",
            Self::WavelengthUm => "W m-2 sr-1 um-1",
        }
    }
}

/// The spectral grid: its axis and its points, strictly increasing.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpectralGrid {
    /// Wavenumber or wavelength.
    pub axis: SpectralAxis,
    /// The points, in the axis's unit, positive and strictly increasing.
    pub points: Vec<f64>,
}

/// One level of the vertical profile (the non-spectral columns of the `.atm`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ProfileLevel {
    /// Altitude above sea level, metres.
    pub altitude_asl_m: f64,
    /// Air temperature, kelvin.
    pub temperature_k: f64,
    /// Altitude above the ground, metres.
    pub altitude_m: f64,
}

/// Spectral transmittance at the angles the `.cor` polynomial (thesis eq. 10) is fitted
/// to: a band atmosphere's `transmission_correction` is the least-squares fit of the band
/// means at these angles.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CorrectionPaths {
    /// The observer altitude of the paths, metres.
    pub altitude_m: f64,
    /// Nadir angles, degrees, increasing from 0 (the first must be 0: the fit is of
    /// τ(θ)/τ(0)) and below 90.
    pub nadir_deg: Vec<f64>,
    /// Transmittance down to the ground, one spectrum per angle.
    pub transmission: Vec<f32>,
}

/// The `table` model's slant paths, spectrally: grids as in
/// [`SlantTables`](crate::SlantTables), each node a spectrum.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpectralSlantTables {
    /// Observer altitudes above the ground, metres, increasing.
    pub altitude_m: Vec<f64>,
    /// Nadir angles at the observer, degrees, increasing within 0 to below 90.
    pub nadir_deg: Vec<f64>,
    /// The paths' lower end, metres, when it is not the ground (LOWTRAN's stop 1 m up).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ground_m: Option<f64>,
    /// Transmittance, `[altitude][angle]` spectra.
    pub transmission: Vec<f32>,
    /// Path radiance, W m⁻² sr⁻¹ per grid unit, `[altitude][angle]` spectra.
    pub path_radiance_w_m2_sr_per_unit: Vec<f32>,
    /// Observer altitudes of the sky table, metres, increasing.
    pub sky_altitude_m: Vec<f64>,
    /// Zenith angles of the sky table, degrees, increasing within 0 to 90.
    pub sky_zenith_deg: Vec<f64>,
    /// Sky radiance (observer to space), W m⁻² sr⁻¹ per grid unit, `[altitude][angle]`
    /// spectra.
    pub sky_radiance_w_m2_sr_per_unit: Vec<f32>,
    /// The interpolation error between these rows, as measured when they were placed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub interpolation_residual: Option<crate::InterpolationResidual>,
}

/// The sun's direct beam, from LOWTRAN7's direct solar irradiance runs (IEMSCT = 3, one
/// per altitude): the irradiance at the top of the atmosphere and the transmittance from
/// there down to each altitude along the sun's direction. The direct irradiance on a
/// surface normal to the beam at altitude `h` is `E_toa(ν) τ(ν, h)`; on a surface whose
/// normal is `θ_i` from the sun, that times `cos θ_i` (`irsig_atmosphere::solar`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpectralSolar {
    /// The sun's geometric zenith angle at the scene, degrees, from 0 to below 90: the
    /// direction the sun is in (NREL's SPA without refraction), the angle a trace looks
    /// its beam up by. LOWTRAN7 runs the beam at the apparent angle whose refracted ray
    /// leaves the atmosphere toward it (`apparent_zenith_deg`).
    pub zenith_deg: f64,
    /// Day of the year, 1–366: the Earth–Sun distance `extraterrestrial…` is for.
    pub day_of_year: u16,
    /// Altitudes above the ground, metres, increasing.
    pub altitude_m: Vec<f64>,
    /// The extraterrestrial solar irradiance on a surface normal to the beam, at the day's
    /// Earth–Sun distance (LOWTRAN7's own solar spectrum), W m⁻² per grid unit, one
    /// spectrum.
    pub extraterrestrial_w_m2_per_unit: Vec<f32>,
    /// Transmittance from the top of the atmosphere down to each altitude along the sun's
    /// direction, one spectrum per altitude.
    pub transmission: Vec<f32>,
    /// Azimuths of a line of sight from the sun's vertical plane, degrees, increasing
    /// within 0 (looking toward the sun's azimuth) to 180 (away from it): the scattered
    /// sunlight is symmetric about that plane. Empty: no scattered-sunlight tables.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub relative_azimuth_deg: Vec<f64>,
    /// Sunlight single-scattered into each slant path of `slant` (LOWTRAN7's IEMSCT = 2
    /// `SCATTERED RADIANCE`), W m⁻² sr⁻¹ per grid unit, `[altitude][nadir][azimuth]`
    /// spectra on `slant.altitude_m`, `slant.nadir_deg` and `relative_azimuth_deg`; added
    /// to the slant table's thermal path radiance by day.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub path_scattered_w_m2_sr_per_unit: Vec<f32>,
    /// Sunlight single-scattered into the sky paths, W m⁻² sr⁻¹ per grid unit,
    /// `[altitude][zenith][azimuth]` spectra on this table's `altitude_m` (finer than the
    /// thermal sky's: the scattered sky changes faster with altitude),
    /// `slant.sky_zenith_deg` and `relative_azimuth_deg`; added to the sky table's thermal
    /// radiance by day.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub sky_scattered_w_m2_sr_per_unit: Vec<f32>,
    /// Further suns of the same day, their zenith angles increasing above `zenith_deg`,
    /// each with its direct beam's transmittance on `altitude_m`: one build then serves
    /// every sun of a day, the tracer interpolating between the rows
    /// (`irsig_atmosphere::solar`). Empty: the table is for the sun at `zenith_deg` alone.
    /// With scattered-sunlight tables (`relative_azimuth_deg` not empty), each further sun
    /// holds its own, on the same nodes, and the tracer interpolates those between the
    /// suns too (`irsig_atmosphere::scattered`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub further_suns: Vec<SolarBeam>,
    /// The apparent zenith angle each beam was run at, degrees, `[sun][altitude]` over
    /// [`Self::zeniths_deg`] and `altitude_m`: LOWTRAN7's card 3 ANGLE, the zenith angle
    /// at that altitude of the refracted ray that leaves the atmosphere toward the sun's
    /// geometric zenith (ANGLE + BENDING = the sun's angle, to 0.002°;
    /// `irsig_atmosphere::refraction`). At most the sun's angle. Empty: every beam was run
    /// at its sun's own angle (a sun bent less than 0.03°, or a table built before the
    /// beams were refracted).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub apparent_zenith_deg: Vec<f64>,
    /// The sunlight the air scatters by scattering angle, as LOWTRAN7 scatters it (its
    /// aerosols' phase functions), measured by the build for a table of several suns with
    /// scattered-sunlight tables. A sun between the rows divides each node's scattered
    /// sunlight by it before interpolating, and multiplies back
    /// (`irsig_atmosphere::sunlit`). None: the nodes are interpolated as they are.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub phase: Option<SolarPhase>,
}

/// The sunlight single-scattered by a short path at each scattering angle, per metre of
/// path: the shape of the phase function LOWTRAN7 applies in the layer above each altitude
/// of a [`SpectralSolar`] table (`altitude_m`), for one sun (its beam's strength is a
/// factor common to every angle, which a ratio of two angles cancels).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolarPhase {
    /// Scattering angles, degrees, increasing within 0 to 180.
    pub scattering_deg: Vec<f64>,
    /// W m⁻² sr⁻¹ per grid unit per metre, `[altitude][angle]` spectra on the table's
    /// `altitude_m` and `scattering_deg`.
    pub scattered_w_m2_sr_per_unit_per_m: Vec<f32>,
}

/// The direct beam of one more sun of a [`SpectralSolar`] table: its zenith angle and the
/// transmittance from the top of the atmosphere down to each of the table's altitudes
/// along its direction; when the table has scattered-sunlight tables, this sun's too.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolarBeam {
    /// The sun's zenith angle at the scene, degrees, below 90 and above the previous row's.
    pub zenith_deg: f64,
    /// Transmittance from the top of the atmosphere down to each altitude of the table,
    /// one spectrum per altitude (LOWTRAN7's direct solar irradiance runs, IEMSCT = 3).
    pub transmission: Vec<f32>,
    /// The sunlight this sun scatters into the slant paths, as
    /// [`SpectralSolar::path_scattered_w_m2_sr_per_unit`] holds the first sun's (same
    /// nodes and azimuths); empty when the table has no scattered-sunlight tables.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub path_scattered_w_m2_sr_per_unit: Vec<f32>,
    /// The sunlight this sun scatters into the sky paths, as
    /// [`SpectralSolar::sky_scattered_w_m2_sr_per_unit`] holds the first sun's; empty when
    /// the table has no scattered-sunlight tables.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub sky_scattered_w_m2_sr_per_unit: Vec<f32>,
}

impl SpectralSolar {
    /// The table's sun zenith angles, degrees, increasing: `zenith_deg`, then each further
    /// sun's.
    #[must_use]
    pub fn zeniths_deg(&self) -> Vec<f64> {
        std::iter::once(self.zenith_deg)
            .chain(self.further_suns.iter().map(|b| b.zenith_deg))
            .collect()
    }

    /// The transmittance spectra (one per altitude) of zenith row `row` of
    /// [`Self::zeniths_deg`]; `None` past the last row.
    #[must_use]
    pub fn transmission_of(&self, row: usize) -> Option<&[f32]> {
        match row {
            0 => Some(&self.transmission),
            _ => self
                .further_suns
                .get(row - 1)
                .map(|b| b.transmission.as_slice()),
        }
    }
}

/// One direction of an observer's slabs (down to targets below it, or up to targets above
/// it): LOWTRAN7 run from the observer to each target altitude at each angle.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpectralSlabTable {
    /// Target altitudes above the ground, metres, increasing; one of them is the
    /// observer's own (the path of no length: τ = 1, no radiance), the last down, the first
    /// up.
    pub target_m: Vec<f64>,
    /// Nadir angles (down) or zenith angles (up) at the observer, degrees, increasing
    /// within 0 to below 90.
    pub angle_deg: Vec<f64>,
    /// Transmittance from the observer to the target, `[target][angle]` spectra.
    pub transmission: Vec<f32>,
    /// The air's own path radiance, W m⁻² sr⁻¹ per grid unit, `[target][angle]` spectra.
    pub path_radiance_w_m2_sr_per_unit: Vec<f32>,
    /// By day, sunlight single-scattered into the slab (LOWTRAN7's IEMSCT = 2), W m⁻² sr⁻¹
    /// per grid unit, `[target][angle][azimuth]` spectra on `solar.relative_azimuth_deg`;
    /// empty at night.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub scattered_w_m2_sr_per_unit: Vec<f32>,
}

/// The slabs of one observer (`AtmospherePlan::slabs`): paths that end above the ground.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpectralSlab {
    /// The observer's altitude above the ground, metres.
    pub observer_m: f64,
    /// Slabs down to targets below the observer (angles: nadir), if any.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub down: Option<SpectralSlabTable>,
    /// Slabs up to targets above the observer (angles: zenith), if any.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub up: Option<SpectralSlabTable>,
}

/// An atmosphere on a spectral grid: the canonical spectral atmosphere file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpectralAtmosphere {
    /// A short name (`us-std-1976`).
    pub name: String,
    /// Where the numbers come from (model, version, settings).
    pub source: String,
    /// The spectral grid.
    pub grid: SpectralGrid,
    /// The vertical profile, altitudes increasing.
    pub levels: Vec<ProfileLevel>,
    /// Transmittance of the vertical path from each level down to the ground, one
    /// spectrum per level.
    pub level_transmission: Vec<f32>,
    /// Path radiance seen from each level looking straight down (atmospheric emission
    /// only), W m⁻² sr⁻¹ per grid unit, one spectrum per level.
    pub level_path_radiance_w_m2_sr_per_unit: Vec<f32>,
    /// The paths the `.cor` polynomial is fitted to, if any.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub transmission_correction: Option<CorrectionPaths>,
    /// Zenith angles of the sky seen from the ground, degrees, increasing within 0 to 90.
    pub sky_zenith_deg: Vec<f64>,
    /// Sky radiance seen from the ground, W m⁻² sr⁻¹ per grid unit, one spectrum per angle.
    pub sky_radiance_w_m2_sr_per_unit: Vec<f32>,
    /// The hemispheric (cosine-weighted) sky radiance seen from the ground (thesis eq. 5),
    /// W m⁻² sr⁻¹ per grid unit, one spectrum, if given.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sky_hemispheric_w_m2_sr_per_unit: Option<Vec<f32>>,
    /// The radiosonde the profile came from, if any.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub radiosonde: Vec<RadiosondeLevel>,
    /// Slant-path tables for the `table` model, if any.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub slant: Option<SpectralSlantTables>,
    /// The sun's direct beam, for a daylight atmosphere; none at night.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub solar: Option<SpectralSolar>,
    /// Slabs that end above the ground, one entry per observer, observers increasing;
    /// empty: none (the view paths to facets above the ground are the models' own).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub slabs: Vec<SpectralSlab>,
}

/// The largest spectral radiance or irradiance a table may hold, W m⁻² (sr⁻¹) per cm⁻¹ or
/// per µm: 10⁹. The Sun's surface (5,772 K) peaks near 2.6 × 10⁷ W m⁻² sr⁻¹ µm⁻¹ and
/// 1.2 × 10³ per cm⁻¹, and no atmosphere's path or sky, nor sunlight scattered into it,
/// comes near; a larger value (10³⁸, say) is an edit or an overflow, and would make the
/// band integrals and the sensor's counts infinite far from the file that caused it.
pub const SPECTRAL_FLUX_MAX: f64 = 1e9;

fn check_spectra(
    path: &str,
    values: &[f32],
    count: usize,
    n: usize,
    max: f64,
) -> Result<(), ModelError> {
    if values.len() != count * n {
        return Err(ModelError::new(
            path,
            ModelErrorKind::Other(format!(
                "expected {count} spectra of {n} points ({} values), found {} values",
                count * n,
                values.len()
            )),
        ));
    }
    if let Some(i) = values
        .iter()
        .position(|&v| !(v.is_finite() && v >= 0.0 && f64::from(v) <= max))
    {
        let v = values[i];
        let what = if max <= 1.0 {
            "a transmittance from 0 to 1"
        } else if path.contains("irradiance") || path.contains("extraterrestrial") {
            "an irradiance from 0 to 1e9"
        } else {
            "a radiance from 0 to 1e9"
        };
        return Err(ModelError::new(
            format!("{path}[{}][{}]", i / n.max(1), i % n.max(1)),
            ModelErrorKind::Other(format!("expected {what}, found {v}")),
        ));
    }
    Ok(())
}

fn check_axis(path: &str, axis: &[f64], max: f64) -> Result<(), ModelError> {
    if axis.is_empty() {
        return Err(ModelError::new(path, ModelErrorKind::Empty));
    }
    for (i, &v) in axis.iter().enumerate() {
        check_range(|| format!("{path}[{i}]"), v, 0.0, max)?;
    }
    check_increasing(|i| format!("{path}[{i}]"), axis.iter().copied())
}

/// The observer's own row of a slab table is the path of no length: τ = 1 and no radiance
/// (path or scattered), exactly, as the plan's assembly copies it.
fn check_observer_row(
    path: &dyn Fn(&str) -> String,
    t: &SpectralSlabTable,
    row: usize,
    n: usize,
    azimuths: usize,
) -> Result<(), ModelError> {
    let angles = t.angle_deg.len();
    let spectra = |values: &[f32], per: usize| -> Vec<(usize, f32)> {
        let start = row * angles * per * n;
        values
            .get(start..start + angles * per * n)
            .unwrap_or_default()
            .iter()
            .copied()
            .enumerate()
            .map(|(i, v)| (start + i, v))
            .collect()
    };
    // Exactly 1 and 0: the values are copied, not computed.
    #[allow(clippy::float_cmp)]
    let bad_tau = spectra(&t.transmission, 1)
        .into_iter()
        .find(|&(_, v)| v != 1.0);
    if let Some((i, v)) = bad_tau {
        return Err(ModelError::new(
            path(&format!("transmission[{}][{}]", i / n, i % n)),
            ModelErrorKind::Other(format!(
                "expected 1 on the observer's own row (target {row}, the path of no length), \
                 found {v}"
            )),
        ));
    }
    for (field, values, per) in [
        (
            "path_radiance_w_m2_sr_per_unit",
            &t.path_radiance_w_m2_sr_per_unit,
            1,
        ),
        (
            "scattered_w_m2_sr_per_unit",
            &t.scattered_w_m2_sr_per_unit,
            azimuths,
        ),
    ] {
        if let Some((i, v)) = spectra(values, per).into_iter().find(|&(_, v)| v != 0.0) {
            return Err(ModelError::new(
                path(&format!("{field}[{}][{}]", i / n, i % n)),
                ModelErrorKind::Other(format!(
                    "expected 0 on the observer's own row (target {row}, the path of no \
                     length), found {v}"
                )),
            ));
        }
    }
    Ok(())
}

/// The apparent zenith angles of a solar table's beams: none, or one per sun and altitude,
/// each from 0 to its sun's geometric angle (refraction lifts a sun, never lowers it).
fn check_apparent_zeniths(s: &SpectralSolar) -> Result<(), ModelError> {
    if s.apparent_zenith_deg.is_empty() {
        return Ok(());
    }
    let zeniths = s.zeniths_deg();
    let n = s.altitude_m.len();
    if s.apparent_zenith_deg.len() != zeniths.len() * n {
        return Err(ModelError::new(
            "solar.apparent_zenith_deg",
            ModelErrorKind::Other(format!(
                "expected one angle per sun and altitude ({} x {n}), or none, found {}",
                zeniths.len(),
                s.apparent_zenith_deg.len()
            )),
        ));
    }
    for (k, &a) in s.apparent_zenith_deg.iter().enumerate() {
        let z = zeniths[k / n.max(1)];
        if !(a.is_finite() && (0.0..=z).contains(&a)) {
            return Err(ModelError::new(
                format!("solar.apparent_zenith_deg[{k}]"),
                ModelErrorKind::Other(format!(
                    "expected an apparent zenith angle from 0 to its sun's geometric {z} deg \
                     (refraction lifts a sun), found {a}"
                )),
            ));
        }
    }
    Ok(())
}

/// The further suns of a solar table: zenith angles increasing above the first sun's and
/// below 90°, each beam one spectrum per altitude, and no scattered-sunlight tables beside
/// them (those hold one sun's light).
fn check_further_suns(s: &SpectralSolar, n: usize) -> Result<(), ModelError> {
    let mut previous = s.zenith_deg;
    for (i, b) in s.further_suns.iter().enumerate() {
        let z = b.zenith_deg;
        if !(z.is_finite() && z > previous && z < 90.0) {
            return Err(ModelError::new(
                format!("solar.further_suns[{i}].zenith_deg"),
                ModelErrorKind::Other(format!(
                    "expected a zenith angle above the previous sun's ({previous} deg) and \
                     below 90 deg, found {z}"
                )),
            ));
        }
        previous = z;
        check_spectra(
            &format!("solar.further_suns[{i}].transmission"),
            &b.transmission,
            s.altitude_m.len(),
            n,
            1.0,
        )?;
    }
    check_apparent_zeniths(s)
}

/// The scattered-sunlight spectra of every sun of `s` (the first sun's fields, then each
/// further sun's): with relative azimuths, one spectrum per slant node and azimuth and one
/// per sun altitude, sky zenith and azimuth, each sun alike (the tracer interpolates
/// between the suns node by node); without, none.
fn check_scattered(
    s: &SpectralSolar,
    slant: Option<&SpectralSlantTables>,
    n: usize,
) -> Result<(), ModelError> {
    let suns = std::iter::once((
        "solar.".to_owned(),
        &s.path_scattered_w_m2_sr_per_unit,
        &s.sky_scattered_w_m2_sr_per_unit,
    ))
    .chain(s.further_suns.iter().enumerate().map(|(i, b)| {
        (
            format!("solar.further_suns[{i}]."),
            &b.path_scattered_w_m2_sr_per_unit,
            &b.sky_scattered_w_m2_sr_per_unit,
        )
    }));
    if s.relative_azimuth_deg.is_empty() {
        for (prefix, path, sky) in suns {
            if !(path.is_empty() && sky.is_empty()) {
                return Err(ModelError::new(
                    format!("{prefix}path_scattered_w_m2_sr_per_unit"),
                    ModelErrorKind::Other(
                        "scattered-sunlight spectra without their relative azimuths \
                         (solar.relative_azimuth_deg)"
                            .into(),
                    ),
                ));
            }
        }
        return Ok(());
    }
    check_axis("solar.relative_azimuth_deg", &s.relative_azimuth_deg, 180.0)?;
    let Some(sl) = slant else {
        return Err(ModelError::new(
            "solar.relative_azimuth_deg",
            ModelErrorKind::Other(
                "scattered-sunlight tables lie on the slant tables' nodes: expected a `slant` table"
                    .into(),
            ),
        ));
    };
    let na = s.relative_azimuth_deg.len();
    for (prefix, path, sky) in suns {
        check_spectra(
            &format!("{prefix}path_scattered_w_m2_sr_per_unit"),
            path,
            sl.altitude_m.len() * sl.nadir_deg.len() * na,
            n,
            SPECTRAL_FLUX_MAX,
        )?;
        check_spectra(
            &format!("{prefix}sky_scattered_w_m2_sr_per_unit"),
            sky,
            s.altitude_m.len() * sl.sky_zenith_deg.len() * na,
            n,
            SPECTRAL_FLUX_MAX,
        )?;
    }
    Ok(())
}

/// Checks the transmission correction: its altitude, its angles (at least 3, from 0) and
/// its τ spectra on a grid of `n`.
fn check_correction(c: &CorrectionPaths, n: usize) -> Result<(), ModelError> {
    check_range(
        || "transmission_correction.altitude_m".into(),
        c.altitude_m,
        0.0,
        f64::MAX,
    )?;
    check_axis("transmission_correction.nadir_deg", &c.nadir_deg, 89.999)?;
    if c.nadir_deg[0] != 0.0 || c.nadir_deg.len() < 3 {
        return Err(ModelError::new(
            "transmission_correction.nadir_deg",
            ModelErrorKind::Other(
                "expected at least 3 angles starting at 0 (the fit is of τ(θ)/τ(0) against 1, secθ, sec²θ)"
                    .into(),
            ),
        ));
    }
    check_spectra(
        "transmission_correction.transmission",
        &c.transmission,
        c.nadir_deg.len(),
        n,
        1.0,
    )
}

/// Checks the slant tables: their axes, the ground below their lowest altitude, and their
/// spectra on a grid of `n`.
fn check_slant(s: &SpectralSlantTables, n: usize) -> Result<(), ModelError> {
    check_axis("slant.altitude_m", &s.altitude_m, f64::MAX)?;
    check_axis("slant.nadir_deg", &s.nadir_deg, 89.999)?;
    check_axis("slant.sky_altitude_m", &s.sky_altitude_m, f64::MAX)?;
    check_axis("slant.sky_zenith_deg", &s.sky_zenith_deg, 90.0)?;
    if let Some(g) = s.ground_m
        && !(g >= 0.0 && g < s.altitude_m[0])
    {
        return Err(ModelError::new(
            "slant.ground_m",
            ModelErrorKind::Other(format!(
                "expected 0 m or more and below the lowest altitude ({} m), found {g}",
                s.altitude_m[0]
            )),
        ));
    }
    let paths = s.altitude_m.len() * s.nadir_deg.len();
    check_spectra("slant.transmission", &s.transmission, paths, n, 1.0)?;
    check_spectra(
        "slant.path_radiance_w_m2_sr_per_unit",
        &s.path_radiance_w_m2_sr_per_unit,
        paths,
        n,
        SPECTRAL_FLUX_MAX,
    )?;
    check_spectra(
        "slant.sky_radiance_w_m2_sr_per_unit",
        &s.sky_radiance_w_m2_sr_per_unit,
        s.sky_altitude_m.len() * s.sky_zenith_deg.len(),
        n,
        SPECTRAL_FLUX_MAX,
    )
}

/// Checks the sun: its zenith angle and day, its altitudes, its spectra on a grid of `n`,
/// the further suns' and the scattered sunlight's (on the `slant` tables' nodes).
fn check_solar(
    s: &SpectralSolar,
    slant: Option<&SpectralSlantTables>,
    n: usize,
) -> Result<(), ModelError> {
    let z = s.zenith_deg;
    if !(z.is_finite() && (0.0..90.0).contains(&z)) {
        return Err(ModelError::new(
            "solar.zenith_deg",
            ModelErrorKind::Other(format!(
                "expected the sun's zenith angle from 0 to below 90 deg, found {z}"
            )),
        ));
    }
    if !(1..=366).contains(&s.day_of_year) {
        return Err(ModelError::new(
            "solar.day_of_year",
            ModelErrorKind::Other(format!(
                "expected a day of the year from 1 to 366, found {}",
                s.day_of_year
            )),
        ));
    }
    check_axis("solar.altitude_m", &s.altitude_m, f64::MAX)?;
    check_spectra(
        "solar.extraterrestrial_w_m2_per_unit",
        &s.extraterrestrial_w_m2_per_unit,
        1,
        n,
        SPECTRAL_FLUX_MAX,
    )?;
    check_spectra(
        "solar.transmission",
        &s.transmission,
        s.altitude_m.len(),
        n,
        1.0,
    )?;
    check_further_suns(s, n)?;
    check_scattered(s, slant, n)?;
    check_phase(s, n)
}

/// The measured phase function of a solar table, when it has one: scattering angles
/// increasing within 0–180°, one spectrum per altitude and angle, and only beside
/// scattered-sunlight tables (it serves their interpolation alone).
fn check_phase(s: &SpectralSolar, n: usize) -> Result<(), ModelError> {
    let Some(p) = &s.phase else {
        return Ok(());
    };
    if s.relative_azimuth_deg.is_empty() {
        return Err(ModelError::new(
            "solar.phase",
            ModelErrorKind::Other(
                "a phase function without scattered-sunlight tables (solar.relative_azimuth_deg)"
                    .into(),
            ),
        ));
    }
    check_axis("solar.phase.scattering_deg", &p.scattering_deg, 180.0)?;
    check_spectra(
        "solar.phase.scattered_w_m2_sr_per_unit_per_m",
        &p.scattered_w_m2_sr_per_unit_per_m,
        s.altitude_m.len() * p.scattering_deg.len(),
        n,
        SPECTRAL_FLUX_MAX,
    )
}

impl SpectralAtmosphere {
    /// Checks the grid (at least 2 points, positive, strictly increasing), the profile
    /// (altitudes increasing, temperatures above 0 K), every table's shape, τ within 0–1,
    /// radiances finite and not negative, and angles within their ranges.
    ///
    /// # Errors
    /// The first rule broken, with the path of the field.
    pub fn validate(&self) -> Result<(), ModelError> {
        let n = self.grid.points.len();
        self.validate_grid()?;
        self.validate_levels(n)?;
        if let Some(c) = &self.transmission_correction {
            check_correction(c, n)?;
        }
        self.validate_sky(n)?;
        check_radiosonde(&self.radiosonde)?;
        if let Some(s) = &self.slant {
            check_slant(s, n)?;
        }
        if let Some(s) = &self.solar {
            check_solar(s, self.slant.as_ref(), n)?;
        }
        self.validate_slabs(n)
    }

    /// Checks the grid: at least 2 points, finite, the first positive, strictly increasing.
    fn validate_grid(&self) -> Result<(), ModelError> {
        let n = self.grid.points.len();
        if n < 2 {
            return Err(ModelError::new(
                "grid.points",
                ModelErrorKind::Other(format!("expected at least 2 points, found {n}")),
            ));
        }
        check_finite(|| "grid.points".into(), &self.grid.points)?;
        if self.grid.points[0] <= 0.0 {
            return Err(ModelError::new(
                "grid.points[0]",
                ModelErrorKind::Other(format!(
                    "expected a positive {}, found {}",
                    self.grid.axis.unit(),
                    self.grid.points[0]
                )),
            ));
        }
        check_increasing(
            |i| format!("grid.points[{i}]"),
            self.grid.points.iter().copied(),
        )
    }

    /// Checks the profile's levels and their vertical paths' spectra on a grid of `n`.
    fn validate_levels(&self, n: usize) -> Result<(), ModelError> {
        if self.levels.is_empty() {
            return Err(ModelError::new("levels", ModelErrorKind::Empty));
        }
        for (i, l) in self.levels.iter().enumerate() {
            let p = |f: &str| format!("levels[{i}].{f}");
            check_finite(|| p("altitude_asl_m"), &[l.altitude_asl_m])?;
            check_range(|| p("altitude_m"), l.altitude_m, 0.0, f64::MAX)?;
            check_range(|| p("temperature_k"), l.temperature_k, 0.0, f64::MAX)?;
        }
        check_increasing(
            |i| format!("levels[{i}].altitude_m"),
            self.levels.iter().map(|l| l.altitude_m),
        )?;
        let nl = self.levels.len();
        check_spectra("level_transmission", &self.level_transmission, nl, n, 1.0)?;
        check_spectra(
            "level_path_radiance_w_m2_sr_per_unit",
            &self.level_path_radiance_w_m2_sr_per_unit,
            nl,
            n,
            SPECTRAL_FLUX_MAX,
        )
    }

    /// Checks the ground's sky: its zenith angles, its radiances and their hemispheric mean.
    fn validate_sky(&self, n: usize) -> Result<(), ModelError> {
        check_axis("sky_zenith_deg", &self.sky_zenith_deg, 90.0)?;
        check_spectra(
            "sky_radiance_w_m2_sr_per_unit",
            &self.sky_radiance_w_m2_sr_per_unit,
            self.sky_zenith_deg.len(),
            n,
            SPECTRAL_FLUX_MAX,
        )?;
        if let Some(h) = &self.sky_hemispheric_w_m2_sr_per_unit {
            check_spectra(
                "sky_hemispheric_w_m2_sr_per_unit",
                h,
                1,
                n,
                SPECTRAL_FLUX_MAX,
            )?;
        }
        Ok(())
    }

    fn validate_slabs(&self, n: usize) -> Result<(), ModelError> {
        let azimuths = self
            .solar
            .as_ref()
            .map_or(0, |s| s.relative_azimuth_deg.len());
        check_increasing(
            |i| format!("slabs[{i}].observer_m"),
            self.slabs.iter().map(|s| s.observer_m),
        )?;
        for (i, slab) in self.slabs.iter().enumerate() {
            let o = slab.observer_m;
            check_range(|| format!("slabs[{i}].observer_m"), o, 0.0, f64::MAX)?;
            if slab.down.is_none() && slab.up.is_none() {
                return Err(ModelError::new(
                    format!("slabs[{i}]"),
                    ModelErrorKind::Other(
                        "expected a `down` or an `up` table, found neither".into(),
                    ),
                ));
            }
            for (dir, table) in [("down", &slab.down), ("up", &slab.up)] {
                let Some(t) = table else { continue };
                let path = |f: &str| format!("slabs[{i}].{dir}.{f}");
                check_axis(&path("target_m"), &t.target_m, f64::MAX)?;
                check_axis(&path("angle_deg"), &t.angle_deg, 89.999)?;
                let (own, wrong) = if dir == "down" {
                    (
                        t.target_m[t.target_m.len() - 1],
                        t.target_m.iter().position(|&x| x > o),
                    )
                } else {
                    (t.target_m[0], t.target_m.iter().position(|&x| x < o))
                };
                if let Some(k) = wrong {
                    return Err(ModelError::new(
                        path(&format!("target_m[{k}]")),
                        ModelErrorKind::Other(format!(
                            "expected a target {} the observer at {o} m, found {}",
                            if dir == "down" {
                                "at or below"
                            } else {
                                "at or above"
                            },
                            t.target_m[k]
                        )),
                    ));
                }
                // The row is the observer's value copied, not computed: equal bit for bit.
                #[allow(clippy::float_cmp)]
                let elsewhere = own != o;
                if elsewhere || t.target_m.len() < 2 {
                    return Err(ModelError::new(
                        path("target_m"),
                        ModelErrorKind::Other(format!(
                            "expected the observer's own altitude ({o} m) as the {} row and at \
                             least one other, found {:?}",
                            if dir == "down" { "last" } else { "first" },
                            t.target_m
                        )),
                    ));
                }
                let count = t.target_m.len() * t.angle_deg.len();
                check_spectra(&path("transmission"), &t.transmission, count, n, 1.0)?;
                check_spectra(
                    &path("path_radiance_w_m2_sr_per_unit"),
                    &t.path_radiance_w_m2_sr_per_unit,
                    count,
                    n,
                    SPECTRAL_FLUX_MAX,
                )?;
                let scattered = &t.scattered_w_m2_sr_per_unit;
                if azimuths > 0 || !scattered.is_empty() {
                    check_spectra(
                        &path("scattered_w_m2_sr_per_unit"),
                        scattered,
                        count * azimuths,
                        n,
                        SPECTRAL_FLUX_MAX,
                    )?;
                }
                let row = if dir == "down" {
                    t.target_m.len() - 1
                } else {
                    0
                };
                check_observer_row(&path, t, row, n, azimuths)?;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests;
