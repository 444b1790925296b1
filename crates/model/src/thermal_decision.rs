//! What `irsig-therm --tolerance` chose, and why: each named model's setting, its error
//! against the most accurate setting on offer (the others at theirs), its cost, and how
//! the chosen set measured against a converged solve on the pilot's facets.

use serde::{Deserialize, Serialize};

use crate::error::{ModelError, ModelErrorKind, check_range};

/// The choice for one model.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ThermalChoice {
    /// The model (`time step`, `cells`, `shadow samples`, `hemisphere rays`, `exchange`,
    /// `spin-up`).
    pub model: String,
    /// The setting chosen, as its flag spells it.
    pub setting: String,
    /// The most accurate setting on offer, the reference.
    pub reference: String,
    /// The chosen setting's error against the reference, the other models at theirs: the
    /// 99th percentile over the pilot's facets and moments, K.
    pub error_k: f64,
    /// Its cost relative to the reference's, the other models at theirs.
    pub relative_cost: f64,
}

/// A spread the tolerance does not choose away: two physical models, or the start, and
/// how far apart they leave the facets (99th percentile, K).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ThermalSpread {
    /// What was compared (`convection: doe2 against mcadams`).
    pub what: String,
    /// The 99th percentile of the difference over the pilot's facets and moments, K.
    pub p99_k: f64,
    /// The largest difference, K.
    pub max_k: f64,
}

/// The decision.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ThermalDecision {
    /// The tolerance asked for, K.
    pub tolerance_k: f64,
    /// The facets of the scene, and how many the pilot solved.
    pub facets: u64,
    /// The pilot's facets.
    pub pilot_facets: u64,
    /// Every model's choice.
    pub models: Vec<ThermalChoice>,
    /// The sum of the chosen settings' errors, K: the prediction.
    pub predicted_k: f64,
    /// The chosen set against the reference set, all at once: the 99th percentile and the
    /// largest difference over the pilot's facets and moments, K.
    pub measured_p99_k: f64,
    /// The largest difference, K.
    pub measured_max_k: f64,
    /// The chosen set's cost relative to the reference set's.
    pub relative_cost: f64,
    /// What the tolerance does not decide, measured.
    pub spreads: Vec<ThermalSpread>,
}

impl ThermalDecision {
    /// Checks every number.
    ///
    /// # Errors
    /// The first rule broken.
    pub fn validate(&self) -> Result<(), ModelError> {
        check_range(|| "tolerance_k".into(), self.tolerance_k, 1e-6, 1e3)?;
        if self.models.is_empty() {
            return Err(ModelError::new("models", ModelErrorKind::Empty));
        }
        for (i, m) in self.models.iter().enumerate() {
            check_range(|| format!("models[{i}].error_k"), m.error_k, 0.0, 1e4)?;
            check_range(
                || format!("models[{i}].relative_cost"),
                m.relative_cost,
                0.0,
                1e6,
            )?;
        }
        for (path, v) in [
            ("predicted_k", self.predicted_k),
            ("measured_p99_k", self.measured_p99_k),
            ("measured_max_k", self.measured_max_k),
            ("relative_cost", self.relative_cost),
        ] {
            check_range(|| path.into(), v, 0.0, 1e6)?;
        }
        for (i, s) in self.spreads.iter().enumerate() {
            check_range(|| format!("spreads[{i}].p99_k"), s.p99_k, 0.0, 1e4)?;
            check_range(|| format!("spreads[{i}].max_k"), s.max_k, 0.0, 1e4)?;
        }
        Ok(())
    }
}
