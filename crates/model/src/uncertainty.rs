//! The uncertainties a user declares for a scene's inputs, from which the tracer's error
//! budget gives each pixel a standard deviation of apparent temperature per source (thesis
//! §5.1 works such a budget out by hand: thermistors, emissivity, shape factor, one bounce).

use serde::{Deserialize, Serialize};

use crate::error::{ModelError, check_range};
use crate::material::MaterialId;

/// Which facets an uncertainty is about.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub enum Facets {
    /// Every facet.
    All,
    /// The facets of this material.
    Material(MaterialId),
    /// The facets of the raw scene's object of this name.
    Object(String),
}

/// A kinetic-temperature uncertainty.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TemperatureUncertainty {
    /// Whose temperature.
    pub facets: Facets,
    /// One standard deviation, K.
    pub sigma_k: f64,
}

/// An emissivity uncertainty, absolute (0.01: ε ± 0.01 at every angle).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EmissivityUncertainty {
    /// The material.
    pub material: MaterialId,
    /// One standard deviation of ε.
    pub sigma: f64,
}

/// The declared uncertainties of a run's inputs (canonical RON,
/// `formats/canonical/uncertainties.md`). The last entry naming a facet wins.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Uncertainties {
    /// Kinetic temperatures.
    #[serde(default)]
    pub temperature: Vec<TemperatureUncertainty>,
    /// Emissivities.
    #[serde(default)]
    pub emissivity: Vec<EmissivityUncertainty>,
    /// Relative standard deviation of the atmosphere's transmission (0.02: τ ± 2 %).
    #[serde(default)]
    pub transmission_relative: f64,
    /// Relative standard deviation of the atmosphere's path and sky radiance.
    #[serde(default)]
    pub path_radiance_relative: f64,
}

impl Uncertainties {
    /// Checks that every standard deviation is finite and not negative, and relative ones
    /// at most 1. (Whether an emissivity's ± leaves [0, 1] depends on the material library:
    /// [`Uncertainties::check_emissivity`].)
    ///
    /// # Errors
    /// The first rule broken.
    pub fn validate(&self) -> Result<(), ModelError> {
        for (i, t) in self.temperature.iter().enumerate() {
            check_range(
                || format!("temperature[{i}].sigma_k"),
                t.sigma_k,
                0.0,
                f64::MAX,
            )?;
        }
        for (i, e) in self.emissivity.iter().enumerate() {
            check_range(|| format!("emissivity[{i}].sigma"), e.sigma, 0.0, 1.0)?;
        }
        check_range(
            || "transmission_relative".into(),
            self.transmission_relative,
            0.0,
            1.0,
        )?;
        check_range(
            || "path_radiance_relative".into(),
            self.path_radiance_relative,
            0.0,
            1.0,
        )
    }

    /// Checks that ε ± σ stays within [0, 1] for each material: `emissivity(id)` gives its
    /// table's ε at normal incidence and its largest ε (the grazing end, where every table
    /// falls to 0, is left out: there the reflectance, not ε, carries the error).
    ///
    /// # Errors
    /// The first entry whose ± leaves [0, 1], or that names no material, at its path.
    pub fn check_emissivity(
        &self,
        emissivity: impl Fn(MaterialId) -> Option<(f64, f64)>,
    ) -> Result<(), ModelError> {
        for (i, e) in self.emissivity.iter().enumerate() {
            let path = || format!("emissivity[{i}]");
            let Some((lo, hi)) = emissivity(e.material) else {
                return Err(ModelError::new(
                    format!("{}.material", path()),
                    crate::error::ModelErrorKind::Other(format!(
                        "material {} is not in the material library",
                        e.material.0
                    )),
                ));
            };
            if lo - e.sigma < 0.0 || hi + e.sigma > 1.0 {
                return Err(ModelError::new(
                    format!("{}.sigma", path()),
                    crate::error::ModelErrorKind::Other(format!(
                        "ε of material {} is {lo} at normal incidence and at most {hi}: ± {} \
                         leaves [0, 1]",
                        e.material.0, e.sigma
                    )),
                ));
            }
        }
        Ok(())
    }

    /// The temperature σ of a facet of material `material` in object `object`, K.
    #[must_use]
    pub fn temperature_sigma_k(&self, material: MaterialId, object: &str) -> f64 {
        self.temperature_entry(material, object)
            .map_or(0.0, |i| self.temperature[i].sigma_k)
    }

    /// The index of the temperature entry that governs a facet of material `material` in
    /// object `object` (the last naming it), if any. Each entry is one input of the error
    /// budget: every facet it governs is off by the same error, so their sensitivities add
    /// before the σ multiplies them (a correlated input, GUM §5.2).
    #[must_use]
    pub fn temperature_entry(&self, material: MaterialId, object: &str) -> Option<usize> {
        self.temperature.iter().rposition(|t| match &t.facets {
            Facets::All => true,
            Facets::Material(m) => *m == material,
            Facets::Object(o) => o == object,
        })
    }

    /// The emissivity σ of material `material`.
    #[must_use]
    pub fn emissivity_sigma(&self, material: MaterialId) -> f64 {
        self.emissivity_entry(material)
            .map_or(0.0, |i| self.emissivity[i].sigma)
    }

    /// The index of the emissivity entry that governs material `material` (the last naming
    /// it), if any: one correlated input, as [`Self::temperature_entry`]'s.
    #[must_use]
    pub fn emissivity_entry(&self, material: MaterialId) -> Option<usize> {
        self.emissivity.iter().rposition(|e| e.material == material)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_last_entry_naming_a_facet_wins() {
        let u = Uncertainties {
            temperature: vec![
                TemperatureUncertainty {
                    facets: Facets::All,
                    sigma_k: 0.1,
                },
                TemperatureUncertainty {
                    facets: Facets::Object("panel".into()),
                    sigma_k: 1.5,
                },
            ],
            ..Uncertainties::default()
        };
        assert!((u.temperature_sigma_k(MaterialId(1), "panel") - 1.5).abs() < 1e-12);
        assert!((u.temperature_sigma_k(MaterialId(1), "pool") - 0.1).abs() < 1e-12);
        assert!(u.emissivity_sigma(MaterialId(1)).abs() < 1e-12);
        assert_eq!(u.temperature_entry(MaterialId(1), "panel"), Some(1));
        assert_eq!(u.temperature_entry(MaterialId(1), "pool"), Some(0));
        assert_eq!(u.emissivity_entry(MaterialId(1)), None);
        assert_eq!(
            Uncertainties::default().temperature_entry(MaterialId(1), "pool"),
            None
        );
    }

    #[test]
    fn an_emissivity_that_would_leave_0_1_is_refused() {
        let u = Uncertainties {
            emissivity: vec![EmissivityUncertainty {
                material: MaterialId(2),
                sigma: 0.05,
            }],
            ..Uncertainties::default()
        };
        assert!(u.validate().is_ok());
        assert!(u.check_emissivity(|_| Some((0.5, 0.9))).is_ok());
        let e = u.check_emissivity(|_| Some((0.0, 0.97))).unwrap_err();
        assert_eq!(e.path, "emissivity[0].sigma");
        assert!(u.check_emissivity(|_| None).is_err());
        let bad = Uncertainties {
            transmission_relative: -0.1,
            ..Uncertainties::default()
        };
        assert!(bad.validate().is_err());
    }
}
