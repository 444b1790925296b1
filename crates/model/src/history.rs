//! A per-facet temperature history: every facet's kinetic temperature at a list of times,
//! what `irsig-therm` writes beside the raw scenes it makes, with what made it.

use serde::{Deserialize, Serialize};

use crate::error::{ModelError, ModelErrorKind, check_increasing, check_range};
use crate::provenance::InputRecord;

/// The most values (times × facets) a history holds: 2³² (16 GiB of `f32`).
pub const MAX_HISTORY_VALUES: u64 = 1 << 32;

/// Facet temperatures over time.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TemperatureHistory {
    /// The times, seconds since 1970-01-01T00:00:00Z (UTC), strictly increasing.
    pub time_s: Vec<f64>,
    /// How many facets (the raw scene's, in its order).
    pub facets: u32,
    /// Facet `f`'s temperature at time `t` is `temperature_k[t · facets + f]`, K. Empty in
    /// a header whose table follows in binary.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub temperature_k: Vec<f32>,
    /// What made it.
    pub provenance: ThermalProvenance,
}

/// What a thermal run was made from and how: enough to run it again.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ThermalProvenance {
    /// irsig's version.
    pub irsig_version: String,
    /// Every input's role, name and SHA-256 (scene, materials, weather, loads table…).
    pub inputs: Vec<InputRecord>,
    /// The place: latitude (north positive) and longitude (east positive), degrees, and
    /// the ground's altitude above sea level, metres.
    pub site: (f64, f64, f64),
    /// When the solve started (the spin-up's start), seconds since 1970-01-01T00:00:00Z.
    pub start_s: f64,
    /// The time step, seconds.
    pub step_s: f64,
    /// Where the sunlight and the sky's longwave came from, in words ("the weather file's
    /// ghi, dni, dhi and horizontal infrared columns", "LOWTRAN7 loads table …").
    pub radiation: String,
    /// Each named model and its setting (`("convection", "doe2")`, `("nodes", "…")`), in
    /// the order the tool lists them.
    pub models: Vec<(String, String)>,
}

impl TemperatureHistory {
    /// The number of values the table must hold: times × facets.
    #[must_use]
    pub fn values(&self) -> u64 {
        self.time_s.len() as u64 * u64::from(self.facets)
    }

    /// Facet temperatures at time index `t`.
    #[must_use]
    pub fn at(&self, t: usize) -> &[f32] {
        let n = self.facets as usize;
        &self.temperature_k[t * n..(t + 1) * n]
    }

    /// Checks the times, the size and every temperature.
    ///
    /// # Errors
    /// The first rule broken.
    pub fn validate(&self) -> Result<(), ModelError> {
        if self.time_s.is_empty() {
            return Err(ModelError::new("time_s", ModelErrorKind::Empty));
        }
        for (i, &t) in self.time_s.iter().enumerate() {
            // SPA's years −2000 to 6000, with room.
            check_range(|| format!("time_s[{i}]"), t, -1.3e11, 1.3e11)?;
        }
        check_increasing(|i| format!("time_s[{i}]"), self.time_s.iter().copied())?;
        if self.facets == 0 {
            return Err(ModelError::new(
                "facets",
                ModelErrorKind::Other("a history of no facets".into()),
            ));
        }
        if self.values() > MAX_HISTORY_VALUES {
            return Err(ModelError::new(
                "facets",
                ModelErrorKind::Other(format!(
                    "{} times × {} facets is more than the {MAX_HISTORY_VALUES} values a \
                     history holds",
                    self.time_s.len(),
                    self.facets
                )),
            ));
        }
        if self.temperature_k.len() as u64 != self.values() {
            return Err(ModelError::new(
                "temperature_k",
                ModelErrorKind::Other(format!(
                    "{} temperatures for {} times × {} facets",
                    self.temperature_k.len(),
                    self.time_s.len(),
                    self.facets
                )),
            ));
        }
        for (i, &t) in self.temperature_k.iter().enumerate() {
            check_range(
                || format!("temperature_k[{i}]"),
                f64::from(t),
                0.0,
                f64::from(f32::MAX),
            )?;
        }
        let p = &self.provenance;
        check_range(|| "provenance.site.0".into(), p.site.0, -90.0, 90.0)?;
        check_range(|| "provenance.site.1".into(), p.site.1, -180.0, 360.0)?;
        check_range(|| "provenance.site.2".into(), p.site.2, -500.0, 9000.0)?;
        check_range(|| "provenance.step_s".into(), p.step_s, 1e-3, 86_400.0)?;
        check_range(|| "provenance.start_s".into(), p.start_s, -1.3e11, 1.3e11)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn history(times: Vec<f64>, facets: u32, temperatures: Vec<f32>) -> TemperatureHistory {
        TemperatureHistory {
            time_s: times,
            facets,
            temperature_k: temperatures,
            provenance: ThermalProvenance {
                irsig_version: "0".into(),
                inputs: vec![],
                site: (43.0, -77.0, 170.0),
                start_s: 0.0,
                step_s: 300.0,
                radiation: "test".into(),
                models: vec![],
            },
        }
    }

    #[test]
    fn a_row_per_time() {
        let h = history(vec![0.0, 300.0], 2, vec![290.0, 291.0, 292.0, 293.0]);
        assert!(h.validate().is_ok());
        assert_eq!(h.at(1), &[292.0, 293.0]);
    }

    #[test]
    fn size_times_and_values_are_checked() {
        let e = history(vec![0.0, 300.0], 2, vec![290.0; 3])
            .validate()
            .unwrap_err();
        assert_eq!(e.path, "temperature_k");
        let e = history(vec![0.0, 0.0], 1, vec![290.0; 2])
            .validate()
            .unwrap_err();
        assert_eq!(e.path, "time_s[1]");
        let e = history(vec![0.0], 1, vec![f32::NAN])
            .validate()
            .unwrap_err();
        assert_eq!(e.path, "temperature_k[0]");
        let e = history(vec![0.0], 1, vec![-1.0]).validate().unwrap_err();
        assert_eq!(e.path, "temperature_k[0]");
        let e = history(vec![0.0; 0], 1, vec![]).validate().unwrap_err();
        assert_eq!(e.path, "time_s");
    }
}
