//! The tolerance pilot: which models does this scene, seen from this view, need so that
//! its apparent temperatures stay within a tolerance in kelvin of irsig's most accurate
//! settings, in every population of pixels and over the frame?
//!
//! 1. **A census** ([`classes`]): every pixel's centre ray is traced once, cheaply, and the
//!    pixels are sorted into classes (first event, material, grazing, horizon); thin
//!    facets are probed densely for sub-pixel populations; the edges and thin pixels are
//!    the candidates for refinement.
//! 2. **A stratified sample** of points, a floor in every class, each measured under every
//!    setting of every model against the most accurate ([`measure`]), with the most
//!    accurate settings' own residual from the last step of each convergence sequence.
//! 3. **The choice** ([`choose`]): the cheapest combination whose error holds within half
//!    the tolerance in every class (its 90th percentile) and over the frame (the
//!    percentile asked for); a class whose most accurate settings do not converge that far
//!    is not guaranteed.
//! 4. **Refinement** takes the other half: edge and thin pixels are refined to a standard
//!    error ([`crate::refine`]) small enough that a refined pixel's error exceeds half the
//!    tolerance in few enough pixels for the percentile; a trial refines some candidates
//!    to measure what that costs and how many reach the cap.
//! 5. Pixels the decision cannot guarantee (classes it cannot afford, pixels predicted to
//!    cap) must stay under [`NOT_GUARANTEED_MAX`] of the frame, or the tolerance is
//!    refused before tracing, with the floor that can be reached and its cost.
//!
//! Everything is seeded and counted, never timed, so the same inputs give the same
//! decision and the same image on every run.

mod choose;
mod classes;
mod measure;
mod stats;
mod sun;

use irsig_atmosphere::{ModelKind, SubBandCount};
use irsig_model::decision::{
    ClassReport, Decision, ErrorEstimate, ModelChoice, SamplingReport, SwitchableModel,
};
use irsig_radiometry::BandModel;
use rand::{SeedableRng, seq::SliceRandom};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

pub use classes::{CLASS_FLOOR, GRAZING_DEG, HORIZON_DEG, PixelClass};
pub use stats::CONFIDENCE;

use crate::camera::Camera;
use crate::env::Atmosphere;
use crate::error::{TraceError, TraceErrorKind};
use crate::path::{Diffuse, Escape, HemiRay, Mirror, Path};
use crate::path_table::PathTermsMode;
use crate::refine::Refinement;
use crate::tile::Tile;
use crate::tracer::{BandSet, EDGE_SIDE, TraceOptions, Tracer};
use choose::{Combo, Counts, MODELS};
use classes::Census;
use measure::{Measured, Sets};
use stats::{NORMAL_TAILS, confident_rank, order_statistic, weighted_percentile};

/// The share of the tolerance the deterministic models may take; refinement has the rest.
pub const DETERMINISTIC_SHARE: f64 = 0.5;
/// A pixel whose centre differs from a neighbour's by more than this share of the
/// tolerance is refined.
pub const EDGE_SHARE: f64 = 0.5;
/// The share of the frame's pixels whose refinement may leave more than its half of the
/// tolerance (the rest of the percentile's tail is the deterministic models').
const SAMPLING_EXCEEDANCE: f64 = 0.005;
/// The most of the frame a decision may leave not guaranteed.
pub const NOT_GUARANTEED_MAX: f64 = 0.005;
/// The largest side of a refinement level on offer ([`crate::refine::MAX_SIDE`]).
pub const REFINE_MAX_SIDE: u32 = crate::refine::MAX_SIDE;
/// The side a thin candidate's refinement starts at.
pub const REFINE_THIN_SIDE: u32 = 8;
/// Candidates refined in the trial, at most (and about one in twenty of them).
const TRIAL_MAX: usize = 48;

/// How many rays a pixel gets.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Supersample {
    /// `n × n` rays in every pixel (`1`: the centre ray only).
    Every(u32),
    /// `n × n` rays only where the centre differs from a neighbour's by more than the
    /// tolerance (adaptive supersampling, thesis §3.3.4).
    Adaptive(u32),
    /// Edge and thin pixels refined to a standard error, in levels up to side `n`
    /// ([`crate::refine`]): what a tolerance renders with.
    Refine(u32),
}

impl Supersample {
    /// The setting as the decision names it: `1`, `4`, `adaptive-4`, `refine-32`.
    #[must_use]
    pub fn name(self) -> String {
        match self {
            Self::Every(n) => n.to_string(),
            Self::Adaptive(n) => format!("adaptive-{n}"),
            Self::Refine(n) => format!("refine-{n}"),
        }
    }
}

impl std::fmt::Display for Supersample {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.name())
    }
}

impl std::str::FromStr for Supersample {
    type Err = String;

    /// `N` or `adaptive-N`, N from 1 to 64, or `refine-N`, N from 1 to
    /// [`crate::refine::MAX_SIDE`].
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let (make, n): (fn(u32) -> Self, &str) = if let Some(n) = s.strip_prefix("adaptive-") {
            (Self::Adaptive, n)
        } else if let Some(n) = s.strip_prefix("refine-") {
            (Self::Refine, n)
        } else {
            (Self::Every, s)
        };
        let largest = if s.starts_with("refine-") {
            crate::refine::MAX_SIDE
        } else {
            64
        };
        n.parse()
            .ok()
            .filter(|n| (1..=largest).contains(n))
            .map(make)
            .ok_or_else(|| {
                format!(
                    "expected N (N x N rays per pixel, 1 to 64), adaptive-N or refine-N (N \
                     from 1 to {}), found `{s}`",
                    crate::refine::MAX_SIDE
                )
            })
    }
}

/// A band set the pilot may choose: an atmosphere model over some sub-bands.
#[derive(Debug)]
pub struct BandChoice<S> {
    /// The atmosphere model.
    pub atmosphere: ModelKind,
    /// The sub-bands (1 for the band model).
    pub sub_bands: SubBandCount,
    /// The set, built for the tracer's scene ([`Tracer::band_set`]).
    pub set: BandSet<S>,
    /// What one exact path-terms call costs in one of its sub-bands, ns (BENCHMARKS.md:
    /// `table` 880, `layered` 830, `thesis` 92, `none` 5).
    pub path_call_ns: f64,
    /// What precomputing the sky for one of its sub-bands costs a rendering, ns.
    pub sky_ns: f64,
}

/// What the pilot may choose from. Each list is ordered from the most accurate setting
/// (the reference, first) to the cheapest; a model with one entry is fixed (pinned, or one
/// that cannot matter), and `reasons` says why.
#[derive(Debug)]
pub struct PilotSpace<S> {
    /// Every (atmosphere, sub-bands) pair the pilot needs: the reference pair, each
    /// sub-band count at the reference atmosphere, and each atmosphere in the band model
    /// (`1`), the reference atmosphere's band model included: every model but the
    /// sub-bands is measured in it (see [`Tracer::pilot`]). Where an atmosphere has no band
    /// model here, it is measured at the reference sub-bands.
    pub bands: Vec<BandChoice<S>>,
    /// Atmosphere models, reference first.
    pub atmospheres: Vec<ModelKind>,
    /// Sub-band counts, reference first.
    pub sub_bands: Vec<SubBandCount>,
    /// Specular bounces, reference (most) first.
    pub bounces: Vec<u32>,
    /// Sky-view rays per diffuse hit, reference first; 0 is the thesis's F = 1.
    pub sky_view_rays: Vec<u32>,
    /// Rays per pixel, reference first (with a tolerance: refinement alone, unless
    /// pinned).
    pub supersampling: Vec<Supersample>,
    /// Path terms, reference (`Exact`) first.
    pub path_terms: Vec<PathTermsMode>,
    /// Models whose setting is fixed, and why (pinned by the user, or cannot matter here).
    pub reasons: Vec<(SwitchableModel, String)>,
    /// Models the user pinned.
    pub pinned: Vec<SwitchableModel>,
    /// With a sun (the tracer's, [`Tracer::with_sun`]; each band set then carries its
    /// beams, [`Tracer::lit_band_set`]): whether it may be switched off, and the shadow
    /// rays on offer. `None`: a night, and the decision names no sun.
    pub sun: Option<SunOffer<S>>,
}

/// What the pilot may choose for the sun.
#[derive(Debug)]
pub struct SunOffer<S> {
    /// The sun's settings, reference first: `true` on, `false` off.
    pub lit: Vec<bool>,
    /// Shadow rays per facet hit, reference (most) first; each count four times the next
    /// (but 1, the disk's centre), so that the sequence measures what the most leave.
    pub shadow_rays: Vec<u32>,
    /// The band model's set at the reference atmosphere without the sun
    /// ([`Tracer::band_set`]): what `off` is evaluated with.
    pub dark: BandSet<S>,
}

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

/// What the trial of refinement found.
#[derive(Debug, Clone, Default)]
struct Trial {
    pixels: usize,
    paths_per_candidate: f64,
    capped_share: f64,
    /// The standard error each capped pixel stopped at, K.
    capped_sigma_k: Vec<f64>,
    /// The largest standard error of a trial pixel, K.
    worst_sigma_k: f64,
}

impl<B: BandModel, A: Atmosphere> Tracer<B, A> {
    /// Runs the pilot on `camera`'s frame with a sample of about `points` points and
    /// chooses, for each model of `space`, the cheapest setting whose combination keeps
    /// the apparent temperatures within `tolerance_k` of the most accurate settings in
    /// every class and at `percentile` of the frame's pixels (the module's rules).
    ///
    /// # Errors
    /// A space without its reference band set, a tolerance or percentile out of range, or
    /// a tolerance the models on offer cannot reach in this frame
    /// ([`TraceErrorKind::Unreachable`], with the reachable floor).
    pub fn pilot<S: Atmosphere>(
        &self,
        camera: &Camera,
        space: &PilotSpace<S>,
        tolerance_k: f64,
        percentile: f64,
        points: u32,
        seed: u64,
    ) -> Result<Piloted, TraceError> {
        let bad = |m: String| TraceError::new(TraceErrorKind::InvalidOptions(m));
        irsig_model::decision::check_tolerance(tolerance_k, "tolerance")
            .map_err(|e| bad(e.to_string()))?;
        irsig_model::decision::check_percentile(percentile, "percentile")
            .map_err(|e| bad(e.to_string()))?;
        let find = |atmosphere: ModelKind, sub_bands: SubBandCount| {
            space
                .bands
                .iter()
                .position(|b| b.atmosphere == atmosphere && b.sub_bands == sub_bands)
        };
        let (Some(&ref_atm), Some(&ref_sb)) = (space.atmospheres.first(), space.sub_bands.first())
        else {
            return Err(bad(
                "the pilot needs at least one atmosphere and one sub-band count".into(),
            ));
        };
        let reference = find(ref_atm, ref_sb).ok_or_else(|| {
            bad(format!(
                "no band set for atmosphere {ref_atm}, sub-bands {ref_sb}"
            ))
        })?;
        let band_model = find(ref_atm, SubBandCount::BAND).unwrap_or(reference);
        let atm_sets = space
            .atmospheres
            .iter()
            .map(|&a| {
                find(a, SubBandCount::BAND)
                    .or_else(|| find(a, ref_sb))
                    .ok_or_else(|| bad(format!("no band set for {a}")))
            })
            .collect::<Result<Vec<_>, _>>()?;
        let sb_sets = space
            .sub_bands
            .iter()
            .map(|&k| {
                find(ref_atm, k).ok_or_else(|| bad(format!("no band set for {ref_atm}, {k}")))
            })
            .collect::<Result<Vec<_>, _>>()?;
        if space.bounces.is_empty()
            || space.sky_view_rays.is_empty()
            || space.supersampling.is_empty()
            || space.path_terms.is_empty()
        {
            return Err(bad("every model needs at least one setting".into()));
        }
        let fc = self.frame_consts_with(
            camera,
            false,
            Tile::whole(camera.pixels[0], camera.pixels[1]),
        );
        let table = space
            .path_terms
            .contains(&PathTermsMode::Tabulated)
            .then(|| self.path_table(camera, &space.bands[band_model].set));
        let edge_k = tolerance_k * EDGE_SHARE;
        let det_k = tolerance_k * DETERMINISTIC_SHARE;
        let census = self.census(
            &fc,
            &space.bands[band_model].set,
            edge_k,
            points as usize,
            seed,
        );
        let inverse = self.inverse_table();
        let sets = Sets {
            reference,
            band_model,
            atmospheres: &atm_sets,
            sub_bands: &sb_sets,
            table: table.as_ref(),
        };
        let measured: Vec<Measured> = census
            .points
            .par_iter()
            .map(|p| {
                let candidate = census.candidate[p.pixel as usize];
                self.measure(&fc, space, &sets, &inverse, seed, p, candidate)
            })
            .collect();
        let mut by_class: Vec<Vec<usize>> = vec![Vec::new(); census.classes.len()];
        for (i, p) in census.points.iter().enumerate() {
            by_class[p.class].push(i);
        }
        // The most accurate settings' own residual in each class: the bounces' last step at
        // its 90th percentile, and the sky-view rays' Monte Carlo error at its 90th.
        let sky_counts: Vec<u32> = space
            .sky_view_rays
            .iter()
            .copied()
            .filter(|&n| n > 0)
            .collect();
        let shadow_counts: Vec<u32> = space.sun.as_ref().map_or_else(Vec::new, |s| {
            s.shadow_rays.iter().copied().filter(|&n| n > 1).collect()
        });
        let residual: Vec<f64> = by_class
            .iter()
            .map(|points| {
                let mut steps: Vec<f64> =
                    points.iter().map(|&i| measured[i].bounce_step_k).collect();
                let rank = confident_rank(steps.len(), 90.0);
                let bounces = order_statistic(&mut steps, rank);
                let sky = monte_carlo_sigma_k(
                    &sky_counts,
                    points.iter().map(|&i| measured[i].by_sky_view_k.as_slice()),
                );
                // The most shadow rays' own sampling error, independent of the sky's.
                let shadow = monte_carlo_sigma_k(
                    &shadow_counts,
                    points
                        .iter()
                        .map(|&i| measured[i].by_shadow_rays_k.as_slice()),
                );
                bounces + P90_OF_NORMAL * sky.hypot(shadow)
            })
            .collect();
        let guaranteed: Vec<bool> = residual.iter().map(|&r| r <= det_k).collect();

        let mut counts = Counts::of(
            &census,
            &measured,
            self.geometry.triangles(),
            space.bounces.len(),
        );
        let lens = [
            space.atmospheres.len(),
            space.bounces.len(),
            space.sky_view_rays.len(),
            space.supersampling.len(),
            space.path_terms.len(),
            space.sub_bands.len(),
            space.sun.as_ref().map_or(1, |s| s.lit.len()),
            space.sun.as_ref().map_or(1, |s| s.shadow_rays.len()),
        ];
        if space
            .sun
            .as_ref()
            .is_some_and(|s| s.lit.is_empty() || s.shadow_rays.is_empty())
        {
            return Err(bad("every model needs at least one setting".into()));
        }
        let mut best: Option<(f64, Combo, choose::Verdict)> = None;
        let mut combo: Combo = [0; MODELS];
        loop {
            if let Some(v) = choose::holds(
                &census,
                &measured,
                &by_class,
                &guaranteed,
                &combo,
                tolerance_k,
                det_k,
                percentile,
            ) {
                let c = choose::cost(space, &counts, &combo);
                // At equal cost (a model that changes nothing here), the cheaper settings.
                let cheaper = |b: &Combo| combo.iter().sum::<usize>() > b.iter().sum::<usize>();
                if best.is_none_or(|(bc, b, _)| c < bc * (1.0 - 1e-12) || (c <= bc && cheaper(&b)))
                {
                    best = Some((c, combo, v));
                }
            }
            if !next_combo(&mut combo, &lens) {
                break;
            }
        }
        let reference_combo: Combo = [0; MODELS];
        let (chosen_combo, verdict) = match best {
            Some((_, c, v)) => (c, v),
            None => {
                // Only a pinned model can keep the most accurate settings from holding
                // (against themselves every other error is 0): its error is the user's.
                let v = frame_verdict(
                    &census,
                    &measured,
                    &guaranteed,
                    &reference_combo,
                    percentile,
                );
                (reference_combo, v)
            }
        };

        // Refinement: its target from the share of candidates, its cost from a trial.
        let supersampling = space.supersampling[chosen_combo[3]];
        let candidate_share = census.candidate_share();
        let (z, refinement) = match supersampling {
            Supersample::Refine(max_side) => {
                let z = NORMAL_TAILS
                    .iter()
                    .find(|(q, _)| q * candidate_share <= SAMPLING_EXCEEDANCE)
                    .map_or(NORMAL_TAILS[NORMAL_TAILS.len() - 1].1, |&(_, z)| z);
                let r = Refinement {
                    target_k: (tolerance_k - det_k) / z,
                    edge_k,
                    max_side,
                    thin_side: REFINE_THIN_SIDE.min(max_side),
                };
                (z, Some(r))
            }
            _ => (0.0, None),
        };
        let chosen_options = TraceOptions {
            specular_bounces: space.bounces[chosen_combo[1]],
            sky_view_rays: space.sky_view_rays[chosen_combo[2]],
            supersampling: 1,
            adaptive_threshold_k: None,
            seed,
            truth: false,
        };
        let trial = match &refinement {
            Some(r) => self.trial(&fc, &census, &chosen_options, r, seed),
            None => Trial::default(),
        };
        if trial.pixels > 0 {
            counts.paths_per_candidate = trial.paths_per_candidate;
        }

        // What is not guaranteed, and whether that is too much.
        let class_share = |c: usize| census.classes[c].share;
        let unguaranteed_classes: f64 = (0..census.classes.len())
            .filter(|&c| !guaranteed[c])
            .map(class_share)
            .sum();
        // A capped pixel is not guaranteed when its error exceeds refinement's half of the
        // tolerance more often than one time in ten.
        let unsure_sigma_k = ungranted_sigma_k(tolerance_k);
        let unsure = trial
            .capped_sigma_k
            .iter()
            .filter(|&&s| s > unsure_sigma_k)
            .count();
        let capped_share = candidate_share * unsure as f64 / trial.pixels.max(1) as f64;
        let not_guaranteed = unguaranteed_classes + capped_share;
        let cost_of = |c: &Combo| choose::cost(space, &counts, c);
        if not_guaranteed > NOT_GUARANTEED_MAX {
            let mut thresholds: Vec<(f64, f64)> = (0..census.classes.len())
                .filter(|&c| !guaranteed[c])
                .map(|c| (residual[c] / DETERMINISTIC_SHARE, class_share(c)))
                .collect();
            let per_capped = candidate_share / trial.pixels.max(1) as f64;
            thresholds.extend(
                trial
                    .capped_sigma_k
                    .iter()
                    .map(|&s| (s * P90_OF_NORMAL / (1.0 - DETERMINISTIC_SHARE), per_capped)),
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
                        "{} ({:.2} % of the frame: the most accurate settings on offer leave {:.3} K)",
                        self.class_name(&census.classes[c].class, census.classes[c].sub_pixel),
                        100.0 * class_share(c),
                        residual[c]
                    )
                })
                .collect();
            let mut why = named.join("; ");
            if capped_share > 0.0 {
                if !why.is_empty() {
                    why.push_str("; ");
                }
                why.push_str(&format!(
                    "{:.2} % of the frame's pixels would reach the cap of refinement ({} x {} \
                     rays, 8 rounds) with a standard error above {unsure_sigma_k:.4} K",
                    100.0 * capped_share,
                    refinement.map_or(0, |r| r.max_side),
                    refinement.map_or(0, |r| r.max_side),
                ));
            }
            let cpu_s = cost_of(&reference_combo) / 1e9;
            return Err(TraceError::new(TraceErrorKind::Unreachable(format!(
                "a tolerance of {tolerance_k} K cannot be kept in this frame: {:.2} % of its \
                 pixels would not be guaranteed (at most {:.1} % may be): {why}. The reachable \
                 floor is about {floor:.3} K, at about {cpu_s:.0} CPU-seconds with the most \
                 accurate settings on offer",
                100.0 * not_guaranteed,
                100.0 * NOT_GUARANTEED_MAX
            ))));
        }

        let chosen_cost = cost_of(&chosen_combo);
        let reference_cost = cost_of(&reference_combo);
        let choices = self.model_choices(
            space,
            &census,
            &measured,
            &guaranteed,
            chosen_combo,
            percentile,
            &lens,
            &|c| cost_of(c) / reference_cost,
        );
        let classes = self.class_reports(
            &census,
            &measured,
            &by_class,
            &residual,
            &guaranteed,
            &chosen_combo,
            det_k,
        );
        let sampling_allowance = refinement.map_or(0.0, |r| z * r.target_k);
        let sampling = refinement.map(|r| SamplingReport {
            target_k: r.target_k,
            edge_k: r.edge_k,
            max_side: r.max_side,
            candidates_share: candidate_share,
            paths_per_candidate: counts.paths_per_candidate,
            capped_share: trial.capped_share,
            trial_pixels: trial.pixels as u32,
        });
        let decision = Decision {
            tolerance_k,
            percentile,
            choices,
            predicted: ErrorEstimate {
                percentile_k: verdict.frame_k
                    + if candidate_share > 0.0 {
                        sampling_allowance
                    } else {
                        0.0
                    },
                max_k: verdict.worst_k + 3.0 * trial.worst_sigma_k,
            },
            relative_cost: chosen_cost / reference_cost,
            pilot_pixels: census.points.len() as u32,
            relative_to: format!(
                "irsig's most accurate settings on offer, with the given inputs: {}",
                self.reference_names(space)
            ),
            classes,
            sampling,
            not_guaranteed_share: not_guaranteed,
            data_error_k: None,
        };
        Ok(Piloted {
            chosen: Chosen {
                atmosphere: space.atmospheres[chosen_combo[0]],
                bounces: space.bounces[chosen_combo[1]],
                sky_view_rays: space.sky_view_rays[chosen_combo[2]],
                supersampling,
                path_terms: space.path_terms[chosen_combo[4]],
                sub_bands: space.sub_bands[chosen_combo[5]],
                refinement,
                sun: space.sun.as_ref().map(|s| SunChosen {
                    lit: s.lit[chosen_combo[6]],
                    shadow_rays: s.shadow_rays[chosen_combo[7]],
                }),
            },
            decision,
        })
    }

    /// Refines some of the census's candidates with the chosen settings: about one in
    /// twenty, at least 8 (all of fewer) and at most [`TRIAL_MAX`], seeded. A pixel refined
    /// here is refined exactly so in the rendering (its rays are its own).
    fn trial(
        &self,
        fc: &crate::tracer::FrameConsts<'_>,
        census: &Census,
        options: &TraceOptions,
        refinement: &Refinement,
        seed: u64,
    ) -> Trial {
        let camera = fc.camera();
        let w = camera.pixels[0];
        let mut candidates: Vec<u32> = census
            .candidate
            .iter()
            .enumerate()
            .filter(|&(_, &c)| c)
            .map(|(i, _)| i as u32)
            .collect();
        if candidates.is_empty() {
            return Trial::default();
        }
        let n = (candidates.len() / 20)
            .max(8.min(candidates.len()))
            .min(TRIAL_MAX);
        let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x7472_6961_6c00_0000);
        let (picked, _) = candidates.partial_shuffle(&mut rng, n);
        picked.sort_unstable();
        let inverse = self.inverse_table();
        let thin_contrast_k = self.contrast_bound_k();
        let results: Vec<crate::refine::PixelSampling> = picked
            .par_iter()
            .map(|&i| {
                let (col, row) = (i % w, i / w);
                let thin = census.thin[i as usize];
                let start = if thin {
                    refinement.thin_side
                } else {
                    EDGE_SIDE.min(refinement.max_side)
                };
                let hide = if thin {
                    thin_contrast_k
                } else {
                    census.contrast[i as usize]
                };
                let mut path = Path::default();
                self.refine_pixel::<false>(
                    fc,
                    options,
                    refinement,
                    &inverse,
                    (col, row),
                    start,
                    hide,
                    &mut path,
                )
                .1
            })
            .collect();
        let pixels = results.len();
        let capped: Vec<f64> = results
            .iter()
            .filter(|s| s.capped)
            .map(|s| f64::from(s.sigma_k))
            .collect();
        Trial {
            pixels,
            paths_per_candidate: results.iter().map(|s| f64::from(s.rays)).sum::<f64>()
                / pixels as f64,
            capped_share: capped.len() as f64 / pixels as f64,
            capped_sigma_k: capped,
            worst_sigma_k: results
                .iter()
                .map(|s| f64::from(s.sigma_k))
                .fold(0.0, f64::max),
        }
    }

    /// A class as people read it: `glass (specular-hits-facet, grazing)`.
    fn class_name(&self, class: &PixelClass, sub_pixel: bool) -> String {
        let mut name = self.material_name(class);
        let mut notes = vec![class.event.name()];
        if class.grazing {
            notes.push("grazing");
        }
        if class.horizon {
            notes.push("near the horizon");
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
    fn reference_names<S>(&self, space: &PilotSpace<S>) -> String {
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
    fn model_choices<S>(
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
    fn class_reports(
        &self,
        census: &Census,
        measured: &[Measured],
        by_class: &[Vec<usize>],
        residual: &[f64],
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
                    + (residual[c] / P90_OF_NORMAL).powi(2);
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
                        "the most accurate settings on offer leave {:.4} K here (more than half \
                         the tolerance, {det_k:.4} K)",
                        residual[c]
                    )
                };
                ClassReport {
                    event: k.class.event.name().to_owned(),
                    material: k.class.material,
                    name: self.material_name(&k.class),
                    grazing: k.class.grazing,
                    horizon: k.class.horizon,
                    sub_pixel: k.sub_pixel,
                    share: k.share.clamp(0.0, 1.0),
                    samples: k.samples as u32,
                    error: ErrorEstimate {
                        percentile_k: p90,
                        max_k: worst,
                    },
                    rms_k: ms.sqrt(),
                    residual_k: residual[c],
                    guaranteed: guaranteed[c],
                    why,
                }
            })
            .collect()
    }
}

/// The frame's verdict on `combo` whether or not it holds (for a pinned model's own
/// error).
fn frame_verdict(
    census: &Census,
    measured: &[Measured],
    guaranteed: &[bool],
    combo: &Combo,
    percentile: f64,
) -> choose::Verdict {
    let mut weighted: Vec<(f64, f64)> = census
        .points
        .iter()
        .zip(measured)
        .filter(|(p, _)| guaranteed[p.class])
        .map(|(p, m)| (choose::bound(m, combo), census.classes[p.class].weight()))
        .collect();
    let worst_k = weighted.iter().map(|v| v.0).fold(0.0, f64::max);
    choose::Verdict {
        frame_k: weighted_percentile(&mut weighted, choose::stricter(percentile)),
        worst_k,
    }
}

/// |N(0, 1)| is below this with probability 0.9.
const P90_OF_NORMAL: f64 = 1.645;

/// The standard error above which a pixel refined to the cap is not guaranteed at
/// `tolerance_k`, K: its error then exceeds refinement's share of the tolerance more
/// often than one time in ten.
#[must_use]
pub fn ungranted_sigma_k(tolerance_k: f64) -> f64 {
    tolerance_k * (1.0 - DETERMINISTIC_SHARE) / P90_OF_NORMAL
}

/// The standard error of a Monte Carlo estimate (sky-view rays, shadow rays) at the most
/// samples on offer (`counts[0]`, each count four times the next), K, over a class's
/// `points` (each point's apparent temperature at every count): each count's estimate is
/// independent, so the mean square difference of neighbouring counts is the sum of their
/// variances; with σ_N = c·N^(−a), the two differences give `a` (clamped to 0.5, plain
/// Monte Carlo, and 1), and the first gives σ at the most samples. With two counts, `a` is
/// taken as 0.5, the slowest; with fewer, 0.
fn monte_carlo_sigma_k<'a>(counts: &[u32], points: impl Iterator<Item = &'a [f64]>) -> f64 {
    if counts.len() < 2 {
        return 0.0;
    }
    let (mut d01, mut d12, mut n) = (0.0, 0.0, 0.0);
    for t in points {
        if t.len() < 2 {
            continue;
        }
        d01 += (t[0] - t[1]).powi(2);
        if t.len() > 2 {
            d12 += (t[1] - t[2]).powi(2);
        }
        n += 1.0;
    }
    if n == 0.0 {
        return 0.0;
    }
    let (d01, d12) = (d01 / n, d12 / n);
    // σ_1/σ_0 = (N_0/N_1)^a.
    let ratio_counts = f64::from(counts[0]) / f64::from(counts[1]);
    let a = if counts.len() > 2 && d01 > 0.0 && d12 > 0.0 {
        let ratio_next = f64::from(counts[1]) / f64::from(counts[2]);
        // d12/d01 = (σ1² + σ2²)/(σ0² + σ1²); with one ratio r between steps it is r^(2a).
        let r = (d12 / d01).sqrt();
        (r.ln() / ratio_next.ln()).clamp(0.5, 1.0)
    } else {
        0.5
    };
    let k = ratio_counts.powf(a);
    (d01 / (1.0 + k * k)).sqrt()
}

/// Steps `combo` to the next combination (an odometer over the lists); false after the
/// last.
fn next_combo(combo: &mut Combo, lens: &[usize; MODELS]) -> bool {
    for m in 0..MODELS {
        combo[m] += 1;
        if combo[m] < lens[m] {
            return true;
        }
        combo[m] = 0;
    }
    false
}

impl Path {
    /// This path with at most `bounces` specular bounces, into `out`: what a rendering with
    /// that limit records (the last facet reflects its untraced environment).
    pub(crate) fn truncated(&self, bounces: u32, out: &mut Path) {
        out.primary = self.primary;
        out.rays.clone_from(&self.rays);
        out.nodes.clear();
        let keep = (bounces as usize + 1).min(self.nodes.len());
        out.nodes.extend_from_slice(&self.nodes[..keep]);
        if let Some(last) = out.nodes.last_mut()
            && keep == bounces as usize + 1
            && last.mirror.is_some()
        {
            last.mirror = Some(Mirror::Untraced(last.environment));
        }
    }

    /// This path with only the first `n` of its first facet's sky-view rays (0: F = 1).
    pub(crate) fn with_sky_rays(&self, n: u32, out: &mut Path) {
        out.clone_from(self);
        if let Some(node) = out.nodes.first_mut()
            && let Some(Diffuse::Rays { start, count, .. }) = node.diffuse
        {
            let n = n.min(count);
            node.diffuse = Some(if n == 0 {
                Diffuse::Hemispheric
            } else {
                let rays = &self.rays[start as usize..(start + n) as usize];
                let sky = rays
                    .iter()
                    .filter(|r| matches!(r, HemiRay::Escaped(Escape::Sky { zenith_deg, .. }) if *zenith_deg <= 90.0))
                    .count() as u32;
                Diffuse::Rays {
                    start,
                    count: n,
                    sky,
                }
            });
        }
    }

    /// Whether its first facet cast sky-view rays.
    pub(crate) fn has_sky_view_rays(&self) -> bool {
        self.nodes
            .first()
            .is_some_and(|n| matches!(n.diffuse, Some(Diffuse::Rays { count, .. }) if count > 0))
    }

    /// Reflection rays this path traced within `bounces` bounces.
    pub(crate) fn reflection_rays(&self, bounces: u32) -> u32 {
        let traced = self
            .nodes
            .iter()
            .take(bounces as usize)
            .filter(|n| matches!(n.mirror, Some(Mirror::Next | Mirror::Escaped(_))))
            .count();
        traced as u32
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn supersampling_settings_round_trip() {
        for s in [
            Supersample::Every(1),
            Supersample::Every(4),
            Supersample::Adaptive(2),
            Supersample::Refine(32),
        ] {
            assert_eq!(s.name().parse::<Supersample>(), Ok(s));
        }
        assert!("refine-0".parse::<Supersample>().is_err());
        assert!("refine-128".parse::<Supersample>().is_ok());
        assert!("refine-129".parse::<Supersample>().is_err());
        assert!("65".parse::<Supersample>().is_err());
        assert!("refined-4".parse::<Supersample>().is_err());
    }

    #[test]
    fn combinations_are_counted_like_an_odometer() {
        let lens = [2, 1, 3, 1, 1, 2, 1, 1];
        let mut combo = [0; MODELS];
        let mut n = 1;
        while next_combo(&mut combo, &lens) {
            n += 1;
        }
        assert_eq!(n, 12);
        assert_eq!(combo, [0; MODELS]);
    }
}
