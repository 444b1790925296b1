//! What the tolerance pilot chose for a frame, and why: the models it could switch, the
//! setting it chose for each, the error each costs against the most accurate setting
//! (kelvin of apparent temperature, at a percentile of the pilot's pixels and at worst),
//! and what each costs. The tracer writes it beside its outputs (`.decision.ron`); the run
//! report reads it; a tile or a later run can apply it again instead of piloting anew.

use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Serialize};

use crate::error::{ModelError, ModelErrorKind, check_range};

/// A model of the radiance equation that has cheaper and dearer settings.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SwitchableModel {
    /// The atmosphere model: `table`, `layered`, `thesis`.
    Atmosphere,
    /// Specular bounces per path: 0, 1, 2, …
    Bounces,
    /// Sky-view (shape factor) rays per diffuse hit: 0 (F = 1) or N.
    SkyView,
    /// Rays per pixel: 1 (the centre), N × N, or adaptive (N × N where the image has an
    /// edge).
    Supersampling,
    /// Path terms of facet hits: `exact` or `tabulated`.
    PathTerms,
    /// Sub-bands the radiance is summed over: 1 (the band model), K, or `full`.
    SubBands,
    /// The sun's direct beam (shadow rays, diffuse reflection, glint): `on` or `off`.
    /// Only a sunlit frame's decision has it.
    Sun,
    /// Shadow rays per facet hit toward the sun's disk: 1 (its centre), 4, 16, 64. Only a
    /// sunlit frame's decision has it.
    ShadowRays,
}

impl SwitchableModel {
    /// Every model, in the order they are listed to users.
    pub const ALL: [Self; 8] = [
        Self::Atmosphere,
        Self::Bounces,
        Self::SkyView,
        Self::Supersampling,
        Self::PathTerms,
        Self::SubBands,
        Self::Sun,
        Self::ShadowRays,
    ];
    /// Their names, in the same order.
    pub const NAMES: [&'static str; 8] = [
        "atmosphere",
        "bounces",
        "sky-view",
        "supersampling",
        "path-terms",
        "sub-bands",
        "sun",
        "shadow-rays",
    ];

    /// The name used in files and on command lines.
    #[must_use]
    pub fn name(self) -> &'static str {
        Self::NAMES[self as usize]
    }
}

impl fmt::Display for SwitchableModel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl SwitchableModel {
    /// Whether `setting` is spelt as a setting of this model (the decision page's forms;
    /// the ranges of numbers are the tracer's to judge): `table`, `layered`, `thesis`; a
    /// count; `N`, `adaptive-N` or `refine-N`; `exact`, `tabulated`; `1`, `K`, `full`;
    /// `on`, `off`.
    ///
    /// # Errors
    /// What the setting should look like.
    pub fn check_setting(self, setting: &str) -> Result<(), String> {
        let count = |s: &str| s.parse::<u32>().is_ok();
        let ok = match self {
            Self::Atmosphere => ["table", "layered", "thesis"].contains(&setting),
            Self::Bounces | Self::SkyView | Self::ShadowRays => count(setting),
            Self::Supersampling => {
                let n = setting
                    .strip_prefix("adaptive-")
                    .or_else(|| setting.strip_prefix("refine-"))
                    .unwrap_or(setting);
                count(n)
            }
            Self::PathTerms => ["exact", "tabulated"].contains(&setting),
            Self::SubBands => setting == "full" || count(setting),
            Self::Sun => ["on", "off"].contains(&setting),
        };
        if ok {
            return Ok(());
        }
        let expected = match self {
            Self::Atmosphere => "table, layered or thesis",
            Self::Bounces => "a number of bounces",
            Self::SkyView => "a number of sky-view rays",
            Self::ShadowRays => "a number of shadow rays",
            Self::Supersampling => "N, adaptive-N or refine-N",
            Self::PathTerms => "exact or tabulated",
            Self::SubBands => "1, a number of sub-bands, or full",
            Self::Sun => "on or off",
        };
        Err(format!(
            "`{setting}` is no setting of {self}: expected {expected}"
        ))
    }
}

/// What a class's `event` may be: what its pixels' centre rays met first.
pub const CLASS_EVENTS: [&str; 5] = [
    "sky",
    "terrain",
    "diffuse",
    "specular-escapes",
    "specular-hits-facet",
];

/// The most of a frame's pixels a decision may leave not guaranteed: 0.5 %. A pilot that
/// cannot guarantee more refuses the tolerance.
pub const NOT_GUARANTEED_MAX: f64 = 0.005;

/// The largest error in kelvin a decision may state: no rendering is off by more than the
/// hottest apparent temperature a scene holds, the sun's disk seen in a mirror (below the
/// photosphere's 5,778 K).
pub const MAX_ERROR_K: f64 = 10_000.0;

/// A name that is not one of the [`SwitchableModel`]s.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error(
    "unknown model `{0}`: expected one of atmosphere, bounces, sky-view, supersampling, path-terms, sub-bands, sun, shadow-rays"
)]
pub struct UnknownModel(pub String);

impl FromStr for SwitchableModel {
    type Err = UnknownModel;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or_else(|| UnknownModel(s.to_owned()))
    }
}

/// An error estimated over the pilot's pixels, kelvin of apparent temperature.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ErrorEstimate {
    /// At the decision's percentile of the pilot's pixels, K.
    pub percentile_k: f64,
    /// The largest over the pilot's pixels, K.
    pub max_k: f64,
}

/// The setting chosen for one model.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModelChoice {
    /// Which model.
    pub model: SwitchableModel,
    /// The setting, as the command line spells it (`table`, `1`, `0`, `2`, `adaptive`,
    /// `exact`, `16`).
    pub setting: String,
    /// The most accurate setting the pilot compared it with.
    pub reference: String,
    /// Set by the user (`--pin`): the pilot did not choose it.
    pub pinned: bool,
    /// Its error against the reference setting, the other models at theirs.
    pub error: ErrorEstimate,
    /// Its cost relative to the reference setting's, the other models at theirs (1: as
    /// dear; 0.1: a tenth).
    pub relative_cost: f64,
    /// Why this setting: a model that cannot matter for this scene says so here.
    pub reason: String,
}

/// One population of the frame's pixels as the pilot sampled it (its class: what the
/// centre ray met first, the material, a grazing angle, the horizon), the error of the
/// chosen settings in it, and whether the decision holds there.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ClassReport {
    /// What the ray met first: `sky`, `terrain`, `diffuse`, `specular-escapes`,
    /// `specular-hits-facet`.
    pub event: String,
    /// The material id of the facet met (0: none).
    pub material: u16,
    /// The material's name, or `sky` or `terrain`.
    pub name: String,
    /// The facet is met more than 75° from its normal.
    pub grazing: bool,
    /// The ray looks within 5° of the horizon.
    pub horizon: bool,
    /// Its reflection meets a facet that reflects specularly too (a mirror seen in a
    /// mirror, where the bounces' cut lies). Absent in decisions written before it: false.
    #[serde(default)]
    pub mirror_in_mirror: bool,
    /// Only a sub-pixel probe found it: no pixel's centre ray meets it.
    pub sub_pixel: bool,
    /// Its share of the frame's pixels, 0 to 1.
    pub share: f64,
    /// Points the pilot measured in it.
    pub samples: u32,
    /// The chosen settings' error in it against the most accurate, K: at its 90th
    /// percentile (an upper bound with 95 % confidence), and at worst.
    pub error: ErrorEstimate,
    /// The root-mean-square of that error and of the most accurate settings' own residual,
    /// K: the error budget's σ of the model for its pixels.
    pub rms_k: f64,
    /// How far the most accurate settings on offer are from converged here (the last
    /// step of each convergence sequence), K, at its 90th percentile.
    pub residual_k: f64,
    /// The decision holds for its pixels.
    pub guaranteed: bool,
    /// Why it does or does not.
    pub why: String,
}

/// What refinement of pixels to a standard error is predicted to do in a frame.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SamplingReport {
    /// The standard error a refined pixel is refined to, K.
    pub target_k: f64,
    /// A pixel whose centre differs from a neighbour's by more than this is refined, K.
    pub edge_k: f64,
    /// The largest side of a level (rays per round: its square).
    pub max_side: u32,
    /// The share of the frame's pixels refined (edges and thin facets), 0 to 1.
    pub candidates_share: f64,
    /// Paths traced per refined pixel, from the trial.
    pub paths_per_candidate: f64,
    /// The share of the refined pixels predicted to reach the largest side above the
    /// target, 0 to 1 (marked as not guaranteed).
    pub capped_share: f64,
    /// Pixels refined in the trial.
    pub trial_pixels: u32,
    /// A refined pixel that reaches the largest side with a standard error above this is
    /// not guaranteed, K: the bias its class may carry under the chosen settings plus
    /// 1.645 times it would pass the tolerance. Absent in decisions written before it:
    /// then the bias is taken as half the tolerance, the deterministic models' share.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub unsure_sigma_k: Option<f64>,
}

/// What the pilot chose for a frame, with what it predicts and what it cost.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Decision {
    /// The tolerance asked for, K.
    pub tolerance_k: f64,
    /// The percentile of pixels the tolerance applies to, (0, 100].
    pub percentile: f64,
    /// One choice per model, in [`SwitchableModel::ALL`] order.
    pub choices: Vec<ModelChoice>,
    /// The predicted error of the chosen combination against a converged rendering: per
    /// pixel the sum of the models' errors against the all-reference render plus what the
    /// all-reference settings leave, a refined pixel's with its sampling noise.
    pub predicted: ErrorEstimate,
    /// The chosen combination's estimated cost relative to the all-reference render's.
    pub relative_cost: f64,
    /// Pixels the pilot traced.
    pub pilot_pixels: u32,
    /// What the tolerance is measured against: irsig's most accurate settings on offer,
    /// with the given inputs.
    #[serde(default)]
    pub relative_to: String,
    /// The populations of pixels sampled, and whether the decision holds for each.
    #[serde(default)]
    pub classes: Vec<ClassReport>,
    /// Refinement to a standard error, when the frame is refined.
    #[serde(default)]
    pub sampling: Option<SamplingReport>,
    /// The share of the frame's pixels the decision does not guarantee (classes it cannot
    /// afford, pixels predicted to cap), 0 to 1.
    #[serde(default)]
    pub not_guaranteed_share: f64,
    /// The inputs' own error that no setting removes: the atmosphere data's, over the
    /// frame's view paths, when its tables record it. It belongs to the error budget, not
    /// to the tolerance.
    #[serde(default)]
    pub data_error: Option<DataErrorSummary>,
    /// One number for the whole frame (the largest of the slant paths' and the sky's
    /// residuals), what decisions held before [`Self::data_error`]: read from such files so
    /// that they still apply, never written.
    #[serde(default, skip_serializing)]
    pub data_error_k: Option<f64>,
}

/// The atmosphere data's own error over a frame's pixels (the truth EXR's
/// `atmosphere_data_error`, summarised): bounds of measured errors, K.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DataErrorSummary {
    /// The 99th percentile over the pixels, K.
    pub p99_k: f64,
    /// The largest, K.
    pub max_k: f64,
    /// The share of pixels with no number (past the widest row in a band never measured
    /// there), 0 to 1.
    #[serde(default)]
    pub unmeasured_share: f64,
}

impl Decision {
    /// The choice for `model`, if the decision has one.
    #[must_use]
    pub fn choice(&self, model: SwitchableModel) -> Option<&ModelChoice> {
        self.choices.iter().find(|c| c.model == model)
    }

    /// Checks the numbers: a positive tolerance, a percentile in (0, 100], finite errors
    /// and costs, each model at most once.
    ///
    /// # Errors
    /// The first rule broken.
    pub fn validate(&self) -> Result<(), ModelError> {
        check_tolerance(self.tolerance_k, "tolerance_k")?;
        check_percentile(self.percentile, "percentile")?;
        for (i, c) in self.choices.iter().enumerate() {
            let p = |f: &str| format!("choices[{i}].{f}");
            for (field, setting) in [("setting", &c.setting), ("reference", &c.reference)] {
                c.model
                    .check_setting(setting)
                    .map_err(|m| ModelError::new(p(field), ModelErrorKind::Other(m)))?;
            }
            check_range(
                || p("error.percentile_k"),
                c.error.percentile_k,
                0.0,
                MAX_ERROR_K,
            )?;
            check_range(|| p("error.max_k"), c.error.max_k, 0.0, MAX_ERROR_K)?;
            check_range(|| p("relative_cost"), c.relative_cost, 0.0, f64::MAX)?;
            if self.choices[..i].iter().any(|o| o.model == c.model) {
                return Err(ModelError::new(
                    p("model"),
                    ModelErrorKind::Duplicate(c.model.name().to_owned()),
                ));
            }
        }
        check_range(
            || "predicted.percentile_k".into(),
            self.predicted.percentile_k,
            0.0,
            MAX_ERROR_K,
        )?;
        check_range(
            || "predicted.max_k".into(),
            self.predicted.max_k,
            0.0,
            MAX_ERROR_K,
        )?;
        for (i, c) in self.classes.iter().enumerate() {
            let p = |f: &str| format!("classes[{i}].{f}");
            if !CLASS_EVENTS.contains(&c.event.as_str()) {
                return Err(ModelError::new(
                    p("event"),
                    ModelErrorKind::Other(format!(
                        "`{}`: expected one of {}",
                        c.event,
                        CLASS_EVENTS.join(", ")
                    )),
                ));
            }
            check_range(|| p("share"), c.share, 0.0, 1.0)?;
            check_range(
                || p("error.percentile_k"),
                c.error.percentile_k,
                0.0,
                MAX_ERROR_K,
            )?;
            check_range(|| p("error.max_k"), c.error.max_k, 0.0, MAX_ERROR_K)?;
            check_range(|| p("rms_k"), c.rms_k, 0.0, MAX_ERROR_K)?;
            check_range(|| p("residual_k"), c.residual_k, 0.0, MAX_ERROR_K)?;
        }
        if let Some(s) = &self.sampling {
            check_range(
                || "sampling.target_k".into(),
                s.target_k,
                f64::MIN_POSITIVE,
                f64::MAX,
            )?;
            check_range(
                || "sampling.edge_k".into(),
                s.edge_k,
                f64::MIN_POSITIVE,
                f64::MAX,
            )?;
            check_range(
                || "sampling.max_side".into(),
                f64::from(s.max_side),
                1.0,
                128.0,
            )?;
            check_range(
                || "sampling.candidates_share".into(),
                s.candidates_share,
                0.0,
                1.0,
            )?;
            check_range(|| "sampling.capped_share".into(), s.capped_share, 0.0, 1.0)?;
            if let Some(u) = s.unsure_sigma_k {
                check_range(|| "sampling.unsure_sigma_k".into(), u, 0.0, f64::MAX)?;
            }
            check_range(
                || "sampling.paths_per_candidate".into(),
                s.paths_per_candidate,
                0.0,
                f64::MAX,
            )?;
        }
        check_range(
            || "not_guaranteed_share".into(),
            self.not_guaranteed_share,
            0.0,
            NOT_GUARANTEED_MAX,
        )?;
        if let Some(sigma) = self.data_error_k {
            check_range(|| "data_error_k".into(), sigma, 0.0, MAX_ERROR_K)?;
        }
        if let Some(d) = &self.data_error {
            check_range(|| "data_error.p99_k".into(), d.p99_k, 0.0, MAX_ERROR_K)?;
            check_range(|| "data_error.max_k".into(), d.max_k, 0.0, MAX_ERROR_K)?;
            check_range(
                || "data_error.unmeasured_share".into(),
                d.unmeasured_share,
                0.0,
                1.0,
            )?;
        }
        check_range(|| "relative_cost".into(), self.relative_cost, 0.0, f64::MAX)
    }
}

/// A tolerance must be finite and above 0 K.
///
/// # Errors
/// Zero, negative or not finite, at `path`.
pub fn check_tolerance(tolerance_k: f64, path: &str) -> Result<(), ModelError> {
    if tolerance_k.is_finite() && tolerance_k > 0.0 {
        Ok(())
    } else {
        Err(ModelError::new(
            path,
            ModelErrorKind::Other(format!(
                "a tolerance of {tolerance_k} K: expected a finite number of kelvin above 0"
            )),
        ))
    }
}

/// A percentile must lie in (0, 100].
///
/// # Errors
/// Outside it, or not finite, at `path`.
pub fn check_percentile(percentile: f64, path: &str) -> Result<(), ModelError> {
    if percentile > 0.0 && percentile <= 100.0 {
        Ok(())
    } else {
        Err(ModelError::new(
            path,
            ModelErrorKind::Other(format!(
                "a percentile of {percentile}: expected more than 0 and at most 100"
            )),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn model_names_round_trip() {
        for m in SwitchableModel::ALL {
            assert_eq!(m.name().parse::<SwitchableModel>(), Ok(m));
        }
        assert!("bounce".parse::<SwitchableModel>().is_err());
    }

    #[test]
    fn tolerances_and_percentiles_are_checked() {
        assert!(check_tolerance(0.1, "t").is_ok());
        for bad in [0.0, -0.1, f64::NAN, f64::INFINITY] {
            assert!(check_tolerance(bad, "t").is_err(), "{bad}");
        }
        assert!(check_percentile(100.0, "p").is_ok());
        assert!(check_percentile(0.5, "p").is_ok());
        for bad in [0.0, -1.0, 100.5, f64::NAN] {
            assert!(check_percentile(bad, "p").is_err(), "{bad}");
        }
    }

    #[test]
    fn the_pages_rules_on_classes_shares_errors_and_settings_are_kept() {
        // `not_guaranteed_share: 0.5` (the page: at most 0.005), `event: "bogus"`,
        // `data_error_k: Some(1e308)` and a sun `maybe` (which the tracer refuses) were read.
        let good = || Decision {
            tolerance_k: 0.3,
            percentile: 99.0,
            choices: vec![ModelChoice {
                model: SwitchableModel::Sun,
                setting: "on".into(),
                reference: "on".into(),
                pinned: false,
                error: ErrorEstimate::default(),
                relative_cost: 1.0,
                reason: String::new(),
            }],
            classes: vec![ClassReport {
                event: "specular-hits-facet".into(),
                material: 1,
                name: "pool".into(),
                grazing: false,
                horizon: false,
                mirror_in_mirror: false,
                sub_pixel: false,
                share: 1.0,
                samples: 16,
                error: ErrorEstimate::default(),
                rms_k: 0.1,
                residual_k: 0.0,
                guaranteed: true,
                why: String::new(),
            }],
            not_guaranteed_share: NOT_GUARANTEED_MAX,
            data_error_k: Some(0.004),
            data_error: Some(DataErrorSummary {
                p99_k: 0.05,
                max_k: 0.2,
                unmeasured_share: 0.0,
            }),
            ..Decision::default()
        };
        good().validate().unwrap();
        type Break = dyn Fn(&mut Decision);
        let cases: [(&Break, &str); 7] = [
            (&|d| d.not_guaranteed_share = 0.5, "not_guaranteed_share"),
            (
                &|d| d.data_error.as_mut().unwrap().max_k = f64::NAN,
                "data_error.max_k",
            ),
            (&|d| d.classes[0].event = "bogus".into(), "classes[0].event"),
            (&|d| d.data_error_k = Some(1e308), "data_error_k"),
            (
                &|d| d.choices[0].setting = "maybe".into(),
                "choices[0].setting",
            ),
            (
                &|d| d.choices[0].reference = "yes".into(),
                "choices[0].reference",
            ),
            (&|d| d.predicted.max_k = 1e300, "predicted.max_k"),
        ];
        for (break_it, path) in cases {
            let mut d = good();
            break_it(&mut d);
            assert_eq!(d.validate().unwrap_err().path, path);
        }
        // Every model's own forms are settings of it.
        for (model, setting) in [
            (SwitchableModel::Atmosphere, "thesis"),
            (SwitchableModel::Supersampling, "adaptive-4"),
            (SwitchableModel::Supersampling, "refine-8"),
            (SwitchableModel::SubBands, "full"),
            (SwitchableModel::SubBands, "16"),
            (SwitchableModel::PathTerms, "tabulated"),
            (SwitchableModel::ShadowRays, "64"),
        ] {
            model.check_setting(setting).unwrap();
        }
    }
}
