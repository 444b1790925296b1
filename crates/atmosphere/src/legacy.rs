//! Conversion between the legacy DIRTRAN tables (thesis Figure 9) and the canonical
//! [`Atmosphere`], with the legacy units stated explicitly.
//!
//! The tables arrive here as numbers (the syntax is `irsig_formats::legacy`'s business):
//! `.atm` rows `h_asl T h τ L_u`, the `.cor` `a1 a2 a3`, `.dwr` rows `θ L_d` with the
//! hemispheric value as the row whose angle is `-1`, `.rtt` rows `T L`, `.rsd` rows
//! `h p T_°C dew-point depression`.

use irsig_model::{Atmosphere, AtmosphereLevel, ModelError, RadiosondeLevel, SlantTables};

/// The units the legacy numbers are in. DIRTRAN wrote km and W cm⁻² sr⁻¹ (Figure 9; the
/// thesis text once says W m⁻² sr⁻¹ for the `.rtt`, so the unit must always be stated).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LegacyUnits {
    /// Metres per legacy altitude unit (1000 for km).
    pub metres_per_altitude_unit: f64,
    /// W m⁻² sr⁻¹ per legacy radiance unit (1e4 for W cm⁻² sr⁻¹).
    pub si_per_radiance_unit: f64,
}

impl LegacyUnits {
    /// km and W cm⁻² sr⁻¹, as DIRTRAN wrote them (thesis Figure 9).
    pub const DIRTRAN: Self = Self {
        metres_per_altitude_unit: 1000.0,
        si_per_radiance_unit: 1e4,
    };
}

/// The DIRTRAN tables of one atmosphere, as numbers in legacy units.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct DirtranTables {
    /// `.atm` rows: altitude above sea level, temperature (K), altitude above the ground,
    /// vertical transmission, nadir upwelled radiance.
    pub atm: Vec<[f64; 5]>,
    /// `.cor` coefficients `a1 a2 a3`.
    pub cor: Option<[f64; 3]>,
    /// `.dwr` rows `(zenith angle in degrees, L_d)`; an angle of `-1` marks the
    /// hemispheric value.
    pub dwr: Vec<(f64, f64)>,
    /// `.rtt` rows `(temperature in K, band radiance)`.
    pub rtt: Vec<(f64, f64)>,
    /// `.rsd` rows: altitude, pressure (hPa), temperature (°C), dew-point depression (°C).
    pub rsd: Vec<[f64; 4]>,
}

/// What the canonical atmosphere needs beyond the tables.
#[derive(Debug, Clone, PartialEq)]
pub struct ConvertOptions {
    /// A short name for the atmosphere.
    pub name: String,
    /// Where the numbers come from.
    pub source: String,
    /// The band the tables were integrated over, µm.
    pub band_um: [f64; 2],
    /// The legacy units.
    pub units: LegacyUnits,
    /// The altitude in metres the `.cor` was fitted at, if known.
    pub cor_altitude_m: Option<f64>,
    /// Slant tables (already SI) to attach.
    pub slant: Option<SlantTables>,
}

/// Converts the tables to the canonical atmosphere and validates it.
///
/// # Errors
/// The first rule of [`Atmosphere::validate`] the result breaks (altitudes not increasing,
/// τ outside 0–1, angles outside 0–90° or not increasing, negative radiance), or a `.dwr`
/// with two hemispheric rows.
pub fn to_atmosphere(t: &DirtranTables, o: &ConvertOptions) -> Result<Atmosphere, ModelError> {
    let u = o.units;
    let levels = t
        .atm
        .iter()
        .map(|r| AtmosphereLevel {
            altitude_asl_m: r[0] * u.metres_per_altitude_unit,
            temperature_k: r[1],
            altitude_m: r[2] * u.metres_per_altitude_unit,
            transmission: r[3],
            path_radiance_w_m2_sr: r[4] * u.si_per_radiance_unit,
        })
        .collect();
    let mut sky = Vec::new();
    let mut hemi = None;
    for &(a, l) in &t.dwr {
        if (a + 1.0).abs() < 1e-9 {
            if hemi.is_some() {
                return Err(model_error(
                    "sky_hemispheric_w_m2_sr",
                    "the .dwr has more than one `-1` (hemispheric) row",
                ));
            }
            hemi = Some(l * u.si_per_radiance_unit);
        } else {
            sky.push((a, l * u.si_per_radiance_unit));
        }
    }
    let atm = Atmosphere {
        name: o.name.clone(),
        source: o.source.clone(),
        band_um: o.band_um,
        levels,
        transmission_correction: t.cor,
        transmission_correction_altitude_m: o.cor_altitude_m,
        sky,
        sky_hemispheric_w_m2_sr: hemi,
        radiosonde: t
            .rsd
            .iter()
            .map(|r| RadiosondeLevel {
                altitude_m: r[0] * u.metres_per_altitude_unit,
                pressure_hpa: r[1],
                temperature_k: r[2] + 273.15,
                dew_point_depression_k: r[3],
            })
            .collect(),
        band_radiance: t
            .rtt
            .iter()
            .map(|&(k, l)| (k, l * u.si_per_radiance_unit))
            .collect(),
        slant: o.slant.clone(),
    };
    atm.validate()?;
    Ok(atm)
}

/// Converts a canonical atmosphere back to DIRTRAN tables in `units`.
#[must_use]
pub fn from_atmosphere(a: &Atmosphere, units: LegacyUnits) -> DirtranTables {
    let (m, r) = (units.metres_per_altitude_unit, units.si_per_radiance_unit);
    let mut dwr: Vec<(f64, f64)> = a.sky.iter().map(|&(z, l)| (z, l / r)).collect();
    if let Some(h) = a.sky_hemispheric_w_m2_sr {
        dwr.push((-1.0, h / r));
    }
    DirtranTables {
        atm: a
            .levels
            .iter()
            .map(|l| {
                [
                    l.altitude_asl_m / m,
                    l.temperature_k,
                    l.altitude_m / m,
                    l.transmission,
                    l.path_radiance_w_m2_sr / r,
                ]
            })
            .collect(),
        cor: a.transmission_correction,
        dwr,
        rtt: a.band_radiance.iter().map(|&(k, l)| (k, l / r)).collect(),
        rsd: a
            .radiosonde
            .iter()
            .map(|s| {
                [
                    s.altitude_m / m,
                    s.pressure_hpa,
                    s.temperature_k - 273.15,
                    s.dew_point_depression_k,
                ]
            })
            .collect(),
    }
}

fn model_error(path: &str, message: &str) -> ModelError {
    // ModelError's constructor is crate-private to irsig-model; build it by value.
    ModelError {
        path: path.to_owned(),
        kind: irsig_model::ModelErrorKind::Other(message.to_owned()),
    }
}
