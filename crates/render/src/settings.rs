//! What a frame is rendered with: the tracer's options, the atmosphere model, the path
//! terms and the sub-bands; as asked for ([`SettingsRequest`], every model at its default
//! unless given) and as a decision of the tolerance pilot sets them.

use irsig_atmosphere::{ModelKind, SubBandCount};
use irsig_model::decision::{Decision, SwitchableModel};
use irsig_tracer::pilot::{Supersample, refinement_of};
use irsig_tracer::{PathTermsMode, Refinement, TraceOptions};

/// The models asked for, `None` where the default applies.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SettingsRequest {
    /// The atmosphere model [default: table].
    pub atmosphere_model: Option<ModelKind>,
    /// Specular bounces per path [default: 1, the thesis's].
    pub bounces: Option<u32>,
    /// Sky-view rays per diffuse hit [default: 0, F = 1 as in the thesis].
    pub sky_view_rays: Option<u32>,
    /// N for N × N rays per pixel [default: 1].
    pub supersample: Option<u32>,
    /// Adaptive supersampling's threshold, K.
    pub adaptive_threshold_k: Option<f64>,
    /// Seed of sky-view directions and sub-pixel jitter.
    pub seed: u64,
    /// Path terms of facet hits [default: exact].
    pub path_terms: Option<PathTermsMode>,
    /// Sub-bands [default: 1, the band model].
    pub sub_bands: Option<SubBandCount>,
}

/// The settings a frame is rendered with.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// The tracer's options.
    pub options: TraceOptions,
    /// The atmosphere model.
    pub kind: ModelKind,
    /// Path terms of facet hits.
    pub path_terms: PathTermsMode,
    /// Sub-bands the radiance is summed over.
    pub sub_bands: SubBandCount,
    /// Pixels refined to a standard error (a tolerance's sampling), instead of the options'
    /// supersampling.
    pub refinement: Option<Refinement>,
    /// By day, whether the sun lights the frame: `false` where a decision left it out
    /// (its effect within the tolerance). Without a sun it changes nothing.
    pub sun_lit: bool,
    /// By day, the shadow rays per hit a decision chose; `None`: the sun request's own.
    pub shadow_rays: Option<u32>,
}

impl Settings {
    /// The settings asked for, defaults where none was given.
    #[must_use]
    pub fn of(request: &SettingsRequest) -> Self {
        Self {
            options: TraceOptions {
                specular_bounces: request.bounces.unwrap_or(1),
                sky_view_rays: request.sky_view_rays.unwrap_or(0),
                supersampling: request.supersample.unwrap_or(1),
                adaptive_threshold_k: request.adaptive_threshold_k,
                seed: request.seed,
                truth: true,
            },
            kind: request.atmosphere_model.unwrap_or(ModelKind::Table),
            path_terms: request.path_terms.unwrap_or_default(),
            sub_bands: request.sub_bands.unwrap_or(SubBandCount::BAND),
            refinement: None,
            sun_lit: true,
            shadow_rays: None,
        }
    }

    /// These settings with a decision's choices applied.
    ///
    /// # Errors
    /// A choice that is not a setting of its model, or puts an option out of range: its
    /// index in `decision.choices` and why.
    pub fn with_decision(mut self, decision: &Decision) -> Result<Self, (usize, String)> {
        for (i, c) in decision.choices.iter().enumerate() {
            let bad = || {
                (
                    i,
                    format!(
                        "the decision's {}={} is not a setting of that model",
                        c.model, c.setting
                    ),
                )
            };
            match c.model {
                SwitchableModel::Atmosphere => {
                    self.kind = c.setting.parse().map_err(|_| bad())?;
                }
                SwitchableModel::Bounces => {
                    self.options.specular_bounces = c.setting.parse().map_err(|_| bad())?;
                }
                SwitchableModel::SkyView => {
                    self.options.sky_view_rays = c.setting.parse().map_err(|_| bad())?;
                }
                SwitchableModel::Supersampling => {
                    self.refinement = None;
                    let (n, adaptive) = match c.setting.parse::<Supersample>() {
                        Ok(Supersample::Every(n)) => (n, None),
                        Ok(Supersample::Adaptive(n)) => (n, Some(decision.tolerance_k)),
                        Ok(Supersample::Refine(n)) => {
                            let report = decision.sampling.as_ref().ok_or_else(|| {
                                (
                                    i,
                                    format!(
                                        "the decision's {}={} needs its `sampling` record \
                                         (the refinement's target)",
                                        c.model, c.setting
                                    ),
                                )
                            })?;
                            let r = Refinement {
                                max_side: n,
                                ..refinement_of(report)
                            };
                            r.validate().map_err(|e| {
                                (i, format!("the decision's {}={}: {e}", c.model, c.setting))
                            })?;
                            self.refinement = Some(r);
                            (1, None)
                        }
                        Err(_) => return Err(bad()),
                    };
                    self.options.supersampling = n;
                    self.options.adaptive_threshold_k = adaptive;
                }
                SwitchableModel::PathTerms => {
                    self.path_terms = c.setting.parse().map_err(|_| bad())?;
                }
                SwitchableModel::SubBands => {
                    self.sub_bands = c.setting.parse().map_err(|_| bad())?;
                }
                SwitchableModel::Sun => {
                    self.sun_lit = match c.setting.as_str() {
                        "on" => true,
                        "off" => false,
                        _ => return Err(bad()),
                    };
                }
                SwitchableModel::ShadowRays => {
                    let n: u32 = c.setting.parse().map_err(|_| bad())?;
                    if !(1..=irsig_tracer::sun::MAX_SHADOW_RAYS).contains(&n) {
                        return Err(bad());
                    }
                    self.shadow_rays = Some(n);
                }
            }
            self.options
                .validate()
                .map_err(|e| (i, format!("the decision's {}={}: {e}", c.model, c.setting)))?;
        }
        Ok(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use irsig_model::decision::{ErrorEstimate, ModelChoice};

    fn decision(choices: &[(SwitchableModel, &str)]) -> Decision {
        Decision {
            tolerance_k: 0.25,
            percentile: 99.0,
            choices: choices
                .iter()
                .map(|&(model, setting)| ModelChoice {
                    model,
                    setting: setting.into(),
                    reference: setting.into(),
                    pinned: false,
                    error: ErrorEstimate::default(),
                    relative_cost: 1.0,
                    reason: String::new(),
                })
                .collect(),
            predicted: ErrorEstimate::default(),
            relative_cost: 1.0,
            pilot_pixels: 1024,
            ..Decision::default()
        }
    }

    #[test]
    fn defaults_are_the_thesis_models() {
        let s = Settings::of(&SettingsRequest::default());
        assert_eq!(s.options.specular_bounces, 1);
        assert_eq!(s.options.sky_view_rays, 0);
        assert_eq!(s.options.supersampling, 1);
        assert_eq!(s.kind, ModelKind::Table);
        assert_eq!(s.path_terms, PathTermsMode::Exact);
        assert!(s.sub_bands.is_band());
    }

    #[test]
    fn a_decision_sets_every_model_and_adaptive_takes_its_tolerance() {
        let d = decision(&[
            (SwitchableModel::Atmosphere, "layered"),
            (SwitchableModel::Bounces, "2"),
            (SwitchableModel::SkyView, "16"),
            (SwitchableModel::Supersampling, "adaptive-4"),
            (SwitchableModel::PathTerms, "tabulated"),
            (SwitchableModel::SubBands, "full"),
        ]);
        let s = Settings::of(&SettingsRequest::default())
            .with_decision(&d)
            .unwrap();
        assert_eq!(s.kind, ModelKind::Layered);
        assert_eq!(s.options.specular_bounces, 2);
        assert_eq!(s.options.sky_view_rays, 16);
        assert_eq!(s.options.supersampling, 4);
        assert_eq!(s.options.adaptive_threshold_k, Some(0.25));
        assert_eq!(s.path_terms, PathTermsMode::Tabulated);
        assert_eq!(s.sub_bands, SubBandCount::Full);
        assert_eq!(s.refinement, None);
    }

    #[test]
    fn a_day_decision_sets_the_sun_and_a_night_one_leaves_it() {
        let d = decision(&[
            (SwitchableModel::Sun, "off"),
            (SwitchableModel::ShadowRays, "16"),
        ]);
        let s = Settings::of(&SettingsRequest::default())
            .with_decision(&d)
            .unwrap();
        assert!(!s.sun_lit);
        assert_eq!(s.shadow_rays, Some(16));
        // A decision of before the sun (no sun's choices): the sun as asked for.
        let s = Settings::of(&SettingsRequest::default())
            .with_decision(&decision(&[(SwitchableModel::Bounces, "1")]))
            .unwrap();
        assert!(s.sun_lit);
        assert_eq!(s.shadow_rays, None);
        for (model, bad) in [
            (SwitchableModel::Sun, "maybe"),
            (SwitchableModel::ShadowRays, "0"),
            (SwitchableModel::ShadowRays, "65537"),
        ] {
            let (i, why) = Settings::of(&SettingsRequest::default())
                .with_decision(&decision(&[(model, bad)]))
                .unwrap_err();
            assert_eq!(i, 0);
            assert!(why.contains("not a setting"), "{why}");
        }
    }

    #[test]
    fn refinement_takes_its_target_from_the_decisions_sampling_record() {
        let mut d = decision(&[(SwitchableModel::Supersampling, "refine-16")]);
        let (i, why) = Settings::of(&SettingsRequest::default())
            .with_decision(&d)
            .unwrap_err();
        assert_eq!(i, 0);
        assert!(why.contains("`sampling` record"), "{why}");
        d.sampling = Some(irsig_model::decision::SamplingReport {
            target_k: 0.05,
            edge_k: 0.125,
            max_side: 32,
            candidates_share: 0.1,
            paths_per_candidate: 300.0,
            capped_share: 0.0,
            trial_pixels: 48,
            unsure_sigma_k: None,
        });
        let s = Settings::of(&SettingsRequest::default())
            .with_decision(&d)
            .unwrap();
        let r = s.refinement.unwrap();
        assert_eq!((r.target_k, r.edge_k, r.max_side), (0.05, 0.125, 16));
        assert_eq!(s.options.supersampling, 1);
    }

    #[test]
    fn a_setting_its_model_lacks_is_named_by_its_index() {
        let d = decision(&[
            (SwitchableModel::Bounces, "1"),
            (SwitchableModel::SubBands, "many"),
        ]);
        let (i, why) = Settings::of(&SettingsRequest::default())
            .with_decision(&d)
            .unwrap_err();
        assert_eq!(i, 1);
        assert!(why.contains("sub-bands=many"), "{why}");
    }
}
