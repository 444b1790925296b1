//! The tolerance pilot: which models does this scene, seen from this view, need so that
//! its apparent temperatures stay within a tolerance in kelvin of irsig's most accurate
//! settings, in every population of pixels and over the frame?
//!
//! 1. **A census** ([`classes`]): every pixel's centre ray is traced once, cheaply, and the
//!    pixels are sorted into classes (first event, material, grazing, horizon); thin
//!    facets are probed densely for sub-pixel populations; the edges and thin pixels are
//!    the candidates for refinement.
//! 2. **A stratified sample** of points, a floor in every class, each measured under every
//!    setting of every model of the [`PilotSpace`] ([`space`]) against the most accurate
//!    ([`measure`]; the sun's two models, [`sun`]; a path as a cheaper setting would have
//!    traced it, [`paths`]), with the most accurate settings' own residual from the rate
//!    of each convergence sequence ([`residual`], [`rate`]).
//! 3. **The choice** ([`choose`]: whether a combination holds, and its cost; [`search`]:
//!    every combination tried): the cheapest combination whose error holds within half
//!    the tolerance in every class (its 90th percentile) and over the frame (the
//!    percentile asked for); a class whose most accurate settings do not converge that far
//!    is not guaranteed.
//! 4. **Refinement** takes the other half ([`trial`]): edge and thin pixels are refined to
//!    a standard error ([`crate::refine`]) small enough that a refined pixel's error
//!    exceeds half the tolerance in few enough pixels for the percentile; a trial refines
//!    some candidates to measure what that costs and how many reach the cap. With it the
//!    frame's percentile of |ΔT| against a converged rendering is predicted
//!    ([`predict`]); where the cheapest combination leaves that over the tolerance (the
//!    most rays' own noise, in classes whose 90th percentile holds) or leaves too many
//!    capped pixels unsure (item 5), the cheapest dearer combination that holds, is
//!    predicted within it and leaves few enough is taken.
//! 5. Pixels the decision cannot guarantee (classes it cannot afford, pixels predicted to
//!    reach the cap with their class's bias and 1.645 σ over the tolerance) must stay
//!    under [`NOT_GUARANTEED_MAX`] of the frame, and the frame's predicted percentile
//!    within the tolerance, or the tolerance is refused before tracing, with the floor
//!    that can be reached and its cost; else the [`Decision`] records the settings, their
//!    errors and reasons ([`report`]).
//!
//! Everything is seeded and counted, never timed, so the same inputs give the same
//! decision and the same image on every run.

mod choose;
mod classes;
mod measure;
mod paths;
mod predict;
mod rate;
mod report;
mod residual;
mod search;
mod space;
mod stats;
mod sun;
mod trial;

use irsig_model::decision::{Decision, ErrorEstimate, SamplingReport};
use irsig_radiometry::BandModel;
use rayon::prelude::*;

pub use classes::{CLASS_FLOOR, GRAZING_DEG, HORIZON_DEG, PixelClass};
pub use report::{Chosen, Piloted, SunChosen, refinement_of};
pub use residual::ungranted_sigma_k;
pub use space::{BandChoice, PilotSpace, SunOffer, Supersample};
pub use stats::CONFIDENCE;

use crate::camera::Camera;
use crate::env::Atmosphere;
use crate::error::{TraceError, TraceErrorKind};
use crate::path_table::PathTermsMode;
use crate::tile::Tile;
use crate::tracer::{FrameConsts, TraceOptions, Tracer};
use choose::{Combo, Counts, MODELS};
use classes::Census;
use measure::{Measured, Sets};
use report::Shortfall;
use trial::Trial;

/// The share of the tolerance the deterministic models may take; refinement has the rest.
pub const DETERMINISTIC_SHARE: f64 = 0.5;
/// A pixel whose centre differs from a neighbour's by more than this share of the
/// tolerance is refined.
pub const EDGE_SHARE: f64 = 0.5;
/// The share of the frame's pixels whose refinement may leave more than its half of the
/// tolerance (the rest of the percentile's tail is the deterministic models').
pub(crate) const SAMPLING_EXCEEDANCE: f64 = 0.005;
/// The most of the frame a decision may leave not guaranteed.
pub const NOT_GUARANTEED_MAX: f64 = irsig_model::decision::NOT_GUARANTEED_MAX;
/// The largest side of a refinement level on offer ([`crate::refine::MAX_SIDE`]).
pub const REFINE_MAX_SIDE: u32 = crate::refine::MAX_SIDE;
/// The side a thin candidate's refinement starts at.
pub const REFINE_THIN_SIDE: u32 = 8;
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
        let indices = checked_indices(space, tolerance_k, percentile)?;
        let band_model = &space.bands[indices.band_model].set;
        let fc = self.frame_consts_with(
            camera,
            false,
            Tile::whole(camera.pixels[0], camera.pixels[1]),
        );
        let table = space
            .path_terms
            .contains(&PathTermsMode::Tabulated)
            .then(|| self.path_table(camera, band_model));
        let edge_k = tolerance_k * EDGE_SHARE;
        let det_k = tolerance_k * DETERMINISTIC_SHARE;

        // 1. The census, 2. each sample point measured under every setting.
        let census = self.census(&fc, band_model, edge_k, points as usize, seed);
        let sets = Sets {
            reference: indices.reference,
            band_model: indices.band_model,
            atmospheres: &indices.atmospheres,
            sub_bands: &indices.sub_bands,
            table: table.as_ref(),
        };
        let measured = self.measure_all(&fc, space, &sets, &census, seed);
        let by_class = census.points_by_class();
        let residual = residual::residuals(space, &measured, &by_class);
        let target_share = trial::target_share(census.candidate_share());
        let terms = predict::PixelTerms::of(space, &census, &by_class, &residual, target_share);
        let guaranteed = terms.guaranteed(tolerance_k);
        let pixels = terms.pixels();

        // 3. The cheapest combination that holds.
        let lens = search::lens(space);
        let (mut counts, holding) = self.holding(
            space,
            (&census, &measured, &by_class),
            (&guaranteed, pixels, &lens),
            [tolerance_k, det_k, percentile],
        );
        let reference_combo: Combo = [0; MODELS];

        // 4. Refinement: its target from the share of candidates, its cost from a trial; the
        // frame's percentile predicted.
        let at = (&census, measured.as_slice(), guaranteed.as_slice());
        let predict = |combo: &Combo, sigmas_k: &[f64]| {
            let spread = predict::RefinedSpread { sigmas_k };
            terms.frame_percentile_k(at, combo, spread, percentile)
        };
        // A capped pixel is not guaranteed where the bias its class may carry under the
        // combination and its σ take it past the tolerance (`residual::ungranted_sigma_k`).
        let capped_bias_k = |combo: &Combo| {
            terms.capped_bias_k(&by_class, &guaranteed, |i| {
                choose::bound(&measured[i], combo)
            })
        };
        let unsure_sigma_k = |combo: &Combo| ungranted_sigma_k(tolerance_k, capped_bias_k(combo));
        let shortfall_of = |combo: &Combo, trial: &Trial| {
            Shortfall::of(&census, &guaranteed, trial, unsure_sigma_k(combo))
        };
        let Choice {
            combo: chosen_combo,
            verdict,
            refinement,
            trial,
            predicted_k,
        } = self.choice_for_frame(
            &fc,
            space,
            &census,
            FrameSearch {
                holding: &holding,
                counts: &counts,
                cheapest: search::cheapest(&holding, &census, &measured, &guaranteed),
                predict: &predict,
                keeps_cap: &|c, t| shortfall_of(c, t).total() <= NOT_GUARANTEED_MAX,
            },
            [tolerance_k, det_k, edge_k],
            seed,
        );
        counts.take_trial(&trial);

        // 5. What is not guaranteed, and whether that is too much.
        let shortfall = shortfall_of(&chosen_combo, &trial);
        let not_guaranteed = shortfall.total();
        let cost_of = |c: &Combo| choose::cost(space, &counts, c);
        if not_guaranteed > NOT_GUARANTEED_MAX {
            return Err(self.unreachable(
                &census,
                &residual,
                &terms.class_floor_k,
                &guaranteed,
                &trial,
                (&shortfall, capped_bias_k(&reference_combo)),
                refinement,
                tolerance_k,
                cost_of(&reference_combo) / 1e9,
            ));
        }
        if predicted_k > tolerance_k {
            let cpu_s = cost_of(&reference_combo) / 1e9;
            let over = [tolerance_k, percentile, predicted_k];
            return Err(frame_unreachable(&predict, &trial, over, cpu_s));
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
            &terms.class_floor_k,
            &guaranteed,
            &chosen_combo,
            det_k,
        );
        let decision = Decision {
            tolerance_k,
            percentile,
            choices,
            predicted: ErrorEstimate {
                percentile_k: predicted_k,
                max_k: verdict.worst_k + 3.0 * trial.worst_sigma_k(),
            },
            relative_cost: chosen_cost / reference_cost,
            pilot_pixels: census.points.len() as u32,
            relative_to: format!(
                "irsig's most accurate settings on offer, with the given inputs: {}",
                self.reference_names(space)
            ),
            classes,
            sampling: sampling_report(refinement, &census, &counts, &trial, &shortfall),
            not_guaranteed_share: not_guaranteed,
            data_error: None,
            data_error_k: None,
        };
        Ok(Piloted {
            chosen: chosen(space, &chosen_combo, refinement),
            decision,
        })
    }
}

impl<B: BandModel, A: Atmosphere> Tracer<B, A> {
    /// Every sample point of the census measured under every setting of `space`.
    fn measure_all<S: Atmosphere>(
        &self,
        fc: &FrameConsts<'_>,
        space: &PilotSpace<S>,
        sets: &Sets<'_>,
        census: &Census,
        seed: u64,
    ) -> Vec<Measured> {
        let inverse = self.inverse_table();
        census
            .points
            .par_iter()
            .map(|p| {
                let candidate = census.candidate[p.pixel as usize];
                self.measure(fc, space, sets, &inverse, seed, p, candidate)
            })
            .collect()
    }

    /// What the census and the measurement count of the work, and every combination that
    /// holds in the guaranteed classes and over the frame (`[tolerance, deterministic
    /// share, percentile]`).
    fn holding<S: Sync>(
        &self,
        space: &PilotSpace<S>,
        (census, measured, by_class): (&Census, &[Measured], &[Vec<usize>]),
        (guaranteed, pixels, lens): (&[bool], choose::Pixels<'_>, &[usize; MODELS]),
        [tolerance_k, det_k, percentile]: [f64; 3],
    ) -> (Counts, search::Holding) {
        let counts = Counts::of(
            census,
            measured,
            self.geometry.triangles(),
            space.bounces.len(),
        );
        let holding = search::holding(
            space,
            &counts,
            census,
            measured,
            by_class,
            guaranteed,
            pixels,
            lens,
            tolerance_k,
            det_k,
            percentile,
        );
        (counts, holding)
    }

    /// The cheapest combination that holds in every class (`search.cheapest`), its
    /// refinement and trial, and the frame's percentile predicted with the trial's σ's;
    /// where that is over the tolerance (the most rays' own noise, in classes whose 90th
    /// percentile holds), the cheapest dearer combination predicted within it, with a
    /// trial of its own (whose prediction may again be over); else the cheapest, over it
    /// (`[tolerance, deterministic share, edge share]`, K).
    fn choice_for_frame<S>(
        &self,
        fc: &FrameConsts<'_>,
        space: &PilotSpace<S>,
        census: &Census,
        search: FrameSearch<'_>,
        limits: [f64; 3],
        seed: u64,
    ) -> Choice {
        let FrameSearch {
            holding,
            counts,
            cheapest: (combo, verdict),
            predict,
            keeps_cap,
        } = search;
        let (refinement, trial) = self.refinement_trial(fc, space, census, &combo, limits, seed);
        let predicted_k = predict(&combo, &trial.sigmas_k);
        let cheapest = Choice {
            combo,
            verdict,
            refinement,
            trial,
            predicted_k,
        };
        if predicted_k <= limits[0] && keeps_cap(&cheapest.combo, &cheapest.trial) {
            return cheapest;
        }
        let cost = choose::cost(space, counts, &combo);
        let within = holding.dearer_than(cost).into_iter().find(|(c, _)| {
            predict(c, &cheapest.trial.sigmas_k) <= limits[0] && keeps_cap(c, &cheapest.trial)
        });
        match within {
            Some((combo, verdict)) => {
                let (refinement, trial) =
                    self.refinement_trial(fc, space, census, &combo, limits, seed);
                let predicted_k = predict(&combo, &trial.sigmas_k);
                Choice {
                    combo,
                    verdict,
                    refinement,
                    trial,
                    predicted_k,
                }
            }
            None => cheapest,
        }
    }

    /// Refinement for the chosen combination: its target from the share of candidates
    /// (`[tolerance, deterministic share, edge share]`, K) and its cost from a trial.
    fn refinement_trial<S>(
        &self,
        fc: &FrameConsts<'_>,
        space: &PilotSpace<S>,
        census: &Census,
        combo: &Combo,
        [tolerance_k, det_k, edge_k]: [f64; 3],
        seed: u64,
    ) -> (Option<crate::refine::Refinement>, Trial) {
        let supersampling = space.supersampling[combo[3]];
        let (_, refinement) = trial::refinement_for(
            supersampling,
            census.candidate_share(),
            tolerance_k,
            det_k,
            edge_k,
        );
        let chosen_options = TraceOptions {
            specular_bounces: space.bounces[combo[1]],
            sky_view_rays: space.sky_view_rays[combo[2]],
            supersampling: 1,
            adaptive_threshold_k: None,
            seed,
            truth: false,
        };
        let trial = match &refinement {
            Some(r) => self.trial(fc, census, &chosen_options, r, seed),
            None => Trial::default(),
        };
        (refinement, trial)
    }
}

/// What the frame's choice reads: every combination that holds, the counts that price
/// them, the cheapest and its verdict, and the frame's percentile predicted for a
/// combination with a trial's σ's, K.
struct FrameSearch<'a> {
    holding: &'a search::Holding,
    counts: &'a Counts,
    cheapest: (Combo, choose::Verdict),
    predict: &'a dyn Fn(&Combo, &[f64]) -> f64,
    /// Whether a combination, with a trial's capped pixels, leaves no more of the frame
    /// than [`NOT_GUARANTEED_MAX`] not guaranteed.
    keeps_cap: &'a dyn Fn(&Combo, &Trial) -> bool,
}

/// A combination chosen for the frame, with its verdict, refinement, trial and the frame's
/// predicted percentile, K.
struct Choice {
    combo: Combo,
    verdict: choose::Verdict,
    refinement: Option<crate::refine::Refinement>,
    trial: Trial,
    predicted_k: f64,
}

/// The refusal of a frame predicted at `predicted` over the tolerance
/// (`[tolerance, percentile, predicted]`, K and %), with the floor where the most accurate
/// settings' prediction meets the tolerance: `predict`ed at a tolerance F with the trial's
/// σ's scaled by F over the tolerance (refinement's target is a share of it).
fn frame_unreachable(
    predict: &dyn Fn(&Combo, &[f64]) -> f64,
    trial: &Trial,
    [tolerance_k, percentile, predicted_k]: [f64; 3],
    cpu_s: f64,
) -> TraceError {
    let reference: Combo = [0; MODELS];
    let floor_k = predict::reachable_floor_k(tolerance_k, |f| {
        predict(&reference, &trial.sigmas_scaled_k(f / tolerance_k))
    });
    report::unreachable_frame(
        [tolerance_k, percentile],
        predicted_k,
        predict(&reference, &trial.sigmas_k),
        floor_k,
        cpu_s,
    )
}

/// What the decision records of refinement, where there is any.
fn sampling_report(
    refinement: Option<crate::refine::Refinement>,
    census: &Census,
    counts: &Counts,
    trial: &Trial,
    shortfall: &Shortfall,
) -> Option<SamplingReport> {
    refinement.map(|r| SamplingReport {
        target_k: r.target_k,
        edge_k: r.edge_k,
        max_side: r.max_side,
        candidates_share: census.candidate_share(),
        paths_per_candidate: counts.paths_per_candidate,
        capped_share: trial.capped_share,
        trial_pixels: trial.pixels as u32,
        unsure_sigma_k: Some(shortfall.unsure_sigma_k),
    })
}

/// The space's band-set indices, once the tolerance, the percentile and every model's
/// settings are checked.
fn checked_indices<S>(
    space: &PilotSpace<S>,
    tolerance_k: f64,
    percentile: f64,
) -> Result<space::SetIndices, TraceError> {
    let bad = |m: String| TraceError::new(TraceErrorKind::InvalidOptions(m));
    irsig_model::decision::check_tolerance(tolerance_k, "tolerance")
        .map_err(|e| bad(e.to_string()))?;
    irsig_model::decision::check_percentile(percentile, "percentile")
        .map_err(|e| bad(e.to_string()))?;
    let indices = space.set_indices()?;
    if space.bounces.is_empty()
        || space.sky_view_rays.is_empty()
        || space.supersampling.is_empty()
        || space.path_terms.is_empty()
        || space
            .sun
            .as_ref()
            .is_some_and(|s| s.lit.is_empty() || s.shadow_rays.is_empty())
    {
        return Err(bad("every model needs at least one setting".into()));
    }
    Ok(indices)
}

/// The settings of a combination of the space's models, with refinement's.
fn chosen<S>(
    space: &PilotSpace<S>,
    combo: &Combo,
    refinement: Option<crate::refine::Refinement>,
) -> Chosen {
    Chosen {
        atmosphere: space.atmospheres[combo[0]],
        bounces: space.bounces[combo[1]],
        sky_view_rays: space.sky_view_rays[combo[2]],
        supersampling: space.supersampling[combo[3]],
        path_terms: space.path_terms[combo[4]],
        sub_bands: space.sub_bands[combo[5]],
        refinement,
        sun: space.sun.as_ref().map(|s| SunChosen {
            lit: s.lit[combo[6]],
            shadow_rays: s.shadow_rays[combo[7]],
        }),
    }
}
