//! What the pilot hands back ([`Piloted`]: the settings chosen and the [`Decision`] that
//! records them) and how the record is written: each model's choice and reason, each
//! class's report, and the error that refuses a tolerance the frame cannot be held to.

use irsig_atmosphere::{ModelKind, SubBandCount};
use irsig_model::decision::{
    ClassReport, Decision, ErrorEstimate, ModelChoice, SamplingReport, SwitchableModel,
};
use irsig_radiometry::BandModel;

use super::choose::{self, Combo, MODELS};
use super::classes::{Census, PixelClass};
use super::measure::Measured;
use super::residual::{P90_OF_NORMAL, Residual};
use super::space::{PilotSpace, Supersample};
use super::stats::{confident_rank, order_statistic, weighted_percentile};
use super::trial::Trial;
use super::{NOT_GUARANTEED_MAX, REFINE_THIN_SIDE};
use crate::env::Atmosphere;
use crate::error::{TraceError, TraceErrorKind};
use crate::path_table::PathTermsMode;
use crate::refine::Refinement;
use crate::tracer::{TraceOptions, Tracer};

/// What the pilot chose for the sun.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SunChosen {
    /// The sun lights the frame (`false`: it is left out, its effect within the
    /// tolerance).
    pub lit: bool,
    /// Shadow rays per facet hit.
    pub shadow_rays: u32,
}

/// The setting the pilot chose for each model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Chosen {
    /// The atmosphere model.
    pub atmosphere: ModelKind,
    /// Specular bounces per path.
    pub bounces: u32,
    /// Sky-view rays per diffuse hit.
    pub sky_view_rays: u32,
    /// Rays per pixel.
    pub supersampling: Supersample,
    /// Path terms of facet hits.
    pub path_terms: PathTermsMode,
    /// Sub-bands.
    pub sub_bands: SubBandCount,
    /// The refinement the frame is rendered with (with [`Supersample::Refine`]).
    pub refinement: Option<Refinement>,
    /// The sun's settings, when the frame has a sun.
    pub sun: Option<SunChosen>,
}

impl Chosen {
    /// `base` (its seed and truth kept) with the bounces, sky-view rays and supersampling
    /// chosen: `n × n` rays for [`Supersample::Every`], the same only where a centre
    /// differs from a neighbour's by more than `tolerance_k` for [`Supersample::Adaptive`],
    /// the centre ray for [`Supersample::Refine`], whose refinement the tracer takes
    /// instead (`Tracer::with_refinement` of [`Chosen::refinement`]).
    #[must_use]
    pub fn trace_options(&self, base: TraceOptions, tolerance_k: f64) -> TraceOptions {
        let (supersampling, adaptive_threshold_k) = match self.supersampling {
            Supersample::Every(n) => (n, None),
            Supersample::Adaptive(n) => (n, Some(tolerance_k)),
            Supersample::Refine(_) => (1, None),
        };
        TraceOptions {
            specular_bounces: self.bounces,
            sky_view_rays: self.sky_view_rays,
            supersampling,
            adaptive_threshold_k,
            ..base
        }
    }
}

/// What the pilot decided: the settings, and the decision that records them with their
/// errors, costs, classes and reasons (what is written beside the outputs).
#[derive(Debug, Clone)]
pub struct Piloted {
    /// The settings chosen.
    pub chosen: Chosen,
    /// Their record.
    pub decision: Decision,
}

/// The refinement a decision's sampling report describes, for its `refine-N` setting.
#[must_use]
pub fn refinement_of(report: &SamplingReport) -> Refinement {
    Refinement {
        target_k: report.target_k,
        edge_k: report.edge_k,
        max_side: report.max_side,
        thin_side: REFINE_THIN_SIDE.min(report.max_side),
    }
}

/// What a decision leaves not guaranteed, as shares of the frame.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Shortfall {
    /// In the classes the most accurate settings on offer cannot hold.
    pub classes: f64,
    /// Refined pixels predicted to stop at refinement's cap with a standard error above
    /// `unsure_sigma_k`.
    pub capped: f64,
    /// [`super::residual::ungranted_sigma_k`] at the tolerance and the chosen settings'
    /// bias, K.
    pub unsure_sigma_k: f64,
}

impl Shortfall {
    /// The shortfall of `census`'s classes that are not `guaranteed`, and of the candidates
    /// the trial predicts to reach the cap with a standard error above `unsure_sigma_k`
    /// ([`super::residual::ungranted_sigma_k`]: the bias a capped pixel may carry and a
    /// normal of its σ then exceed the tolerance more often than one time in ten).
    pub(crate) fn of(
        census: &Census,
        guaranteed: &[bool],
        trial: &Trial,
        unsure_sigma_k: f64,
    ) -> Self {
        let classes: f64 = (0..census.classes.len())
            .filter(|&c| !guaranteed[c])
            .map(|c| census.classes[c].share)
            .sum();
        let unsure = trial
            .capped_sigma_k
            .iter()
            .filter(|&&s| s > unsure_sigma_k)
            .count();
        let capped = census.candidate_share() * unsure as f64 / trial.pixels.max(1) as f64;
        Self {
            classes,
            capped,
            unsure_sigma_k,
        }
    }

    /// The whole share of the frame not guaranteed.
    pub(crate) fn total(&self) -> f64 {
        self.classes + self.capped
    }
}

impl<B: BandModel, A: Atmosphere> Tracer<B, A> {
    /// The error refusing `tolerance_k` when `shortfall` is more than
    /// [`NOT_GUARANTEED_MAX`]: what is not guaranteed, and the reachable floor (the smallest
    /// tolerance at which what stays above it is within the limit: a capped pixel's
    /// threshold the bias `capped_bias_k` the most accurate settings leave plus 1.645
    /// times its σ) at `cpu_s`, the most accurate settings' cost.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn unreachable(
        &self,
        census: &Census,
        residual: &[Residual],
        class_floor_k: &[f64],
        guaranteed: &[bool],
        trial: &Trial,
        (shortfall, capped_bias_k): (&Shortfall, f64),
        refinement: Option<Refinement>,
        tolerance_k: f64,
        cpu_s: f64,
    ) -> TraceError {
        let mut thresholds: Vec<(f64, f64)> = (0..census.classes.len())
            .filter(|&c| !guaranteed[c])
            .map(|c| (class_floor_k[c], census.classes[c].share))
            .collect();
        let per_capped = census.candidate_share() / trial.pixels.max(1) as f64;
        thresholds.extend(
            trial
                .capped_sigma_k
                .iter()
                .map(|&s| (capped_bias_k + s * P90_OF_NORMAL, per_capped)),
        );
        // The smallest tolerance at which what stays above it is within the limit.
        thresholds.sort_by(|a, b| b.0.total_cmp(&a.0));
        let mut above = 0.0;
        let mut floor = tolerance_k;
        for &(t, share) in &thresholds {
            if above + share > NOT_GUARANTEED_MAX {
                floor = t;
                break;
            }
            above += share;
        }
        let named: Vec<String> = (0..census.classes.len())
            .filter(|&c| !guaranteed[c])
            .map(|c| {
                format!(
                    "{} ({:.2} % of the frame: the most accurate settings on offer leave {:.3} K{})",
                    self.class_name(&census.classes[c].class, census.classes[c].sub_pixel),
                    100.0 * census.classes[c].share,
                    residual[c].k,
                    residual[c].parts()
                )
            })
            .collect();
        let mut why = named.join("; ");
        if shortfall.capped > 0.0 {
            if !why.is_empty() {
                why.push_str("; ");
            }
            why.push_str(&format!(
                "{:.2} % of the frame's pixels would reach the cap of refinement ({} x {} \
                 rays, 8 rounds) with a standard error above {:.4} K",
                100.0 * shortfall.capped,
                refinement.map_or(0, |r| r.max_side),
                refinement.map_or(0, |r| r.max_side),
                shortfall.unsure_sigma_k,
            ));
        }
        TraceError::new(TraceErrorKind::Unreachable(format!(
            "a tolerance of {tolerance_k} K cannot be kept in this frame: {:.2} % of its \
             pixels would not be guaranteed (at most {:.1} % may be): {why}. The reachable \
             floor is about {floor:.3} K, at about {cpu_s:.0} CPU-seconds with the most \
             accurate settings on offer",
            100.0 * shortfall.total(),
            100.0 * NOT_GUARANTEED_MAX
        )))
    }

    /// A class as people read it: `glass (specular-hits-facet, grazing)`.
    pub(super) fn class_name(&self, class: &PixelClass, sub_pixel: bool) -> String {
        let mut name = self.material_name(class);
        let mut notes = vec![class.event.name()];
        if class.grazing {
            notes.push("grazing");
        }
        if class.horizon {
            notes.push("near the horizon");
        }
        if class.mirror_in_mirror {
            notes.push("reflecting a mirror");
        }
        if sub_pixel {
            notes.push("sub-pixel");
        }
        name.push_str(&format!(" ({})", notes.join(", ")));
        name
    }

    fn material_name(&self, class: &PixelClass) -> String {
        match class.event {
            crate::tracer::Event::Sky => "sky".to_owned(),
            crate::tracer::Event::Terrain => "terrain".to_owned(),
            _ => self
                .materials
                .iter()
                .find(|m| m.id == class.material)
                .map_or_else(
                    || format!("material {}", class.material),
                    |m| m.name.clone(),
                ),
        }
    }

    /// The most accurate setting of each model, as the decision's `relative_to` names them.
    pub(super) fn reference_names<S>(&self, space: &PilotSpace<S>) -> String {
        let mut names = format!(
            "atmosphere {}, {} bounces, {} sky-view rays, {} sub-bands, {} path terms",
            space.atmospheres[0],
            space.bounces[0],
            space.sky_view_rays[0],
            space.sub_bands[0],
            space.path_terms[0].name()
        );
        if let Some(sun) = &space.sun {
            names.push_str(&format!(
                ", the sun {}, {} shadow rays",
                if sun.lit[0] { "on" } else { "off" },
                sun.shadow_rays[0]
            ));
        }
        names
    }

    /// The decision's record of each model's setting.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn model_choices<S>(
        &self,
        space: &PilotSpace<S>,
        census: &Census,
        measured: &[Measured],
        guaranteed: &[bool],
        chosen: Combo,
        percentile: f64,
        lens: &[usize; MODELS],
        relative_cost: &dyn Fn(&Combo) -> f64,
    ) -> Vec<ModelChoice> {
        let settings = |m: usize, i: usize| -> String {
            match m {
                0 => space.atmospheres[i].name().to_owned(),
                1 => space.bounces[i].to_string(),
                2 => space.sky_view_rays[i].to_string(),
                3 => space.supersampling[i].name(),
                4 => space.path_terms[i].name().to_owned(),
                5 => space.sub_bands[i].to_string(),
                6 => match space.sun.as_ref().map(|s| s.lit[i]) {
                    Some(false) => "off".to_owned(),
                    _ => "on".to_owned(),
                },
                _ => space
                    .sun
                    .as_ref()
                    .map_or(1, |s| s.shadow_rays[i])
                    .to_string(),
            }
        };
        let points = census.points.len();
        // The sun's two models only where there is a sun: a night's decision is as before.
        let models = if space.sun.is_some() { MODELS } else { 6 };
        SwitchableModel::ALL[..models]
            .iter()
            .enumerate()
            .map(|(m, &model)| {
                let i = chosen[m];
                let mut errors: Vec<(f64, f64)> = census
                    .points
                    .iter()
                    .zip(measured)
                    .filter(|(p, _)| guaranteed[p.class])
                    .map(|(p, s)| {
                        (
                            s.errors[m].get(i).copied().unwrap_or(0.0),
                            census.classes[p.class].weight(),
                        )
                    })
                    .collect();
                let max_k = errors.iter().map(|e| e.0).fold(0.0, f64::max);
                let mut alone = [0; MODELS];
                alone[m] = i;
                let inert = lens[m] > 1
                    && measured
                        .iter()
                        .all(|s| s.errors[m].iter().all(|&e| e == 0.0));
                let sun_reason =
                    self.sun_reason(space, census, measured, guaranteed, &chosen, m, percentile);
                let reason = space
                    .reasons
                    .iter()
                    .find(|(r, _)| *r == model)
                    .map(|(_, why)| why.clone())
                    .or(sun_reason)
                    .unwrap_or_else(|| match model {
                        SwitchableModel::Supersampling
                            if matches!(space.supersampling[i], Supersample::Refine(_)) =>
                        {
                            "edge and thin pixels refined to a standard error (see sampling)"
                                .to_owned()
                        }
                        _ if lens[m] == 1 => "the only setting on offer".to_owned(),
                        SwitchableModel::SkyView if inert => format!(
                            "the sky-view rays of the {points} pilot points met no facet: F = 1 \
                             is exact here"
                        ),
                        _ if inert => format!(
                            "every setting gave the {points} pilot points the same temperatures"
                        ),
                        _ if i == lens[m] - 1 => {
                            "the cheapest setting holds in every class".to_owned()
                        }
                        _ => "the cheapest combination that holds in every class".to_owned(),
                    });
                ModelChoice {
                    model,
                    setting: settings(m, i),
                    reference: settings(m, 0),
                    pinned: space.pinned.contains(&model),
                    error: ErrorEstimate {
                        percentile_k: weighted_percentile(&mut errors, percentile),
                        max_k,
                    },
                    relative_cost: relative_cost(&alone),
                    reason,
                }
            })
            .collect()
    }

    /// The decision's record of each class.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn class_reports(
        &self,
        census: &Census,
        measured: &[Measured],
        by_class: &[Vec<usize>],
        residual: &[Residual],
        class_floor_k: &[f64],
        guaranteed: &[bool],
        chosen: &Combo,
        det_k: f64,
    ) -> Vec<ClassReport> {
        census
            .classes
            .iter()
            .enumerate()
            .map(|(c, k)| {
                let mut bounds: Vec<f64> = by_class[c]
                    .iter()
                    .map(|&i| choose::bound(&measured[i], chosen))
                    .collect();
                let n = bounds.len().max(1) as f64;
                let ms = bounds.iter().map(|b| b * b).sum::<f64>() / n
                    + (residual[c].k / P90_OF_NORMAL).powi(2);
                let worst = bounds.iter().copied().fold(0.0, f64::max);
                let rank = confident_rank(bounds.len(), 90.0);
                let p90 = order_statistic(&mut bounds, rank);
                let why = if guaranteed[c] {
                    format!(
                        "the chosen settings hold its 90th percentile within {det_k:.4} K \
                         (half the tolerance)"
                    )
                } else {
                    format!(
                        "the most accurate settings on offer leave {:.4} K here{}: they hold \
                         it from a tolerance of {:.4} K",
                        residual[c].k,
                        residual[c].parts(),
                        class_floor_k[c]
                    )
                };
                ClassReport {
                    event: k.class.event.name().to_owned(),
                    material: k.class.material,
                    name: self.material_name(&k.class),
                    grazing: k.class.grazing,
                    horizon: k.class.horizon,
                    mirror_in_mirror: k.class.mirror_in_mirror,
                    sub_pixel: k.sub_pixel,
                    share: k.share.clamp(0.0, 1.0),
                    samples: k.samples as u32,
                    error: ErrorEstimate {
                        percentile_k: p90,
                        max_k: worst,
                    },
                    rms_k: ms.sqrt(),
                    residual_k: residual[c].k,
                    guaranteed: guaranteed[c],
                    why,
                }
            })
            .collect()
    }
}

/// The refusal of a frame whose predicted percentile is over the tolerance with every
/// combination that holds in its classes (`[tolerance, percentile]`): what the cheapest
/// and the most accurate settings are predicted at, the floor where the most accurate
/// settings' prediction meets the tolerance, and their cost in CPU-seconds.
pub(crate) fn unreachable_frame(
    [tolerance_k, percentile]: [f64; 2],
    predicted_k: f64,
    most_accurate_k: f64,
    floor_k: f64,
    cpu_s: f64,
) -> TraceError {
    TraceError::new(TraceErrorKind::Unreachable(format!(
        "a tolerance of {tolerance_k} K cannot be kept in this frame: its {percentile}th \
         percentile of |dT| is predicted at {predicted_k:.3} K with the cheapest settings that \
         hold in every class, and at {most_accurate_k:.3} K with the most accurate settings on \
         offer (what their own rays' noise and the bounces beyond them leave, with \
         refinement's). The reachable floor is about {floor_k:.3} K, at about {cpu_s:.0} \
         CPU-seconds with the most accurate settings on offer"
    )))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_chosen_options_keep_the_base_and_map_each_supersampling() {
        let chosen = |supersampling| Chosen {
            atmosphere: ModelKind::Table,
            bounces: 3,
            sky_view_rays: 16,
            supersampling,
            path_terms: PathTermsMode::Exact,
            sub_bands: SubBandCount::Count(4),
            refinement: None,
            sun: None,
        };
        let base = TraceOptions {
            specular_bounces: 0,
            sky_view_rays: 0,
            supersampling: 8,
            adaptive_threshold_k: Some(9.0),
            seed: 7,
            truth: false,
        };
        for (setting, rays, threshold) in [
            (Supersample::Every(4), 4, None),
            (Supersample::Adaptive(2), 2, Some(0.3)),
            (Supersample::Refine(32), 1, None),
        ] {
            let o = chosen(setting).trace_options(base, 0.3);
            assert_eq!((o.specular_bounces, o.sky_view_rays), (3, 16));
            assert_eq!((o.supersampling, o.adaptive_threshold_k), (rays, threshold));
            assert_eq!((o.seed, o.truth), (7, false));
        }
    }
}
