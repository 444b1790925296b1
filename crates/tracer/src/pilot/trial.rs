//! Refinement's half of the tolerance: the standard error edge and thin pixels are refined
//! to, and a trial that refines some of the census's candidates with the chosen settings to
//! price refinement and count the pixels that reach its cap.

use irsig_radiometry::BandModel;
use rand::{SeedableRng, seq::SliceRandom};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

use super::classes::Census;
use super::space::Supersample;
use super::stats::NORMAL_TAILS;
use super::{REFINE_THIN_SIDE, SAMPLING_EXCEEDANCE};
use crate::env::Atmosphere;
use crate::path::Path;
use crate::refine::{ROUNDS, Refinement};
use crate::tracer::{EDGE_SIDE, FrameConsts, TraceOptions, Tracer};

/// Candidates refined in the trial, at most (and about one in twenty of them).
const TRIAL_MAX: usize = 48;

/// Candidates refined in the trial, at least (all of fewer): the frame's prediction reads
/// the refined pixels' spread from the trial ([`super::predict::RefinedSpread`]), and
/// fewer pixels read the upper tail of their standard errors too loosely (with 8 to 21,
/// three cases of twenty generated ones were predicted under their measured error).
const TRIAL_MIN: usize = 32;

/// What the trial of refinement found.
#[derive(Debug, Clone, Default)]
pub(crate) struct Trial {
    pub pixels: usize,
    pub paths_per_candidate: f64,
    /// The paths a trial pixel traced at each side it visited, on average: `(side, paths)`,
    /// smallest side first (the sky-view rays of a path depend on its level's side).
    pub paths_by_side: Vec<(u32, f64)>,
    pub capped_share: f64,
    /// The standard error each capped pixel stopped at, K.
    pub capped_sigma_k: Vec<f64>,
    /// Every trial pixel's standard error as refinement left it, K: the sky-view rays'
    /// noise in it, capped pixels' included. What a refined pixel's error is predicted
    /// from ([`super::predict::RefinedSpread`]).
    pub sigmas_k: Vec<f64>,
    /// The geometric part of each of [`Trial::sigmas_k`], K
    /// ([`crate::refine::PixelSampling::geometric_sigma_k`]): what a target scales.
    pub geometric_sigmas_k: Vec<f64>,
    /// The target σ the trial refined to, K.
    pub target_k: f64,
}

impl Trial {
    /// The largest standard error of a trial pixel, K (0 with none).
    pub(crate) fn worst_sigma_k(&self) -> f64 {
        self.sigmas_k.iter().copied().fold(0.0, f64::max)
    }

    /// The trial's standard errors, K, as a refinement whose target is `scale` times this
    /// one's would leave them: the geometric part scaled (but a capped pixel's, over the
    /// target, which the cap and not the target set), the sky-view rays' noise (the rest,
    /// in quadrature) as it is.
    pub(crate) fn sigmas_scaled_k(&self, scale: f64) -> Vec<f64> {
        self.sigmas_k
            .iter()
            .zip(&self.geometric_sigmas_k)
            .map(|(&s, &g)| {
                let g = g.min(s);
                let scaled = if g > self.target_k { g } else { g * scale };
                (scaled * scaled + (s * s - g * g)).sqrt()
            })
            .collect()
    }
}

/// Refinement's target σ as a share of the tolerance, set by `candidate_share`, the share
/// of the frame's pixels that are candidates for it.
pub(crate) fn target_share(candidate_share: f64) -> f64 {
    refinement_for(
        Supersample::Refine(super::REFINE_MAX_SIDE),
        candidate_share,
        1.0,
        super::DETERMINISTIC_SHARE,
        super::EDGE_SHARE,
    )
    .1
    .map_or(0.0, |r| r.target_k)
}

/// The refinement `supersampling` asks for (`None` but for [`Supersample::Refine`]) and
/// the normal quantile its target was set with: the refined pixels' standard error such
/// that, with `candidate_share` of the frame refined, at most [`SAMPLING_EXCEEDANCE`] of
/// it leaves refinement's share of the tolerance (`tolerance_k - det_k`).
pub(crate) fn refinement_for(
    supersampling: Supersample,
    candidate_share: f64,
    tolerance_k: f64,
    det_k: f64,
    edge_k: f64,
) -> (f64, Option<Refinement>) {
    match supersampling {
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
    }
}

impl<B: BandModel, A: Atmosphere> Tracer<B, A> {
    /// Refines some of the census's candidates with the chosen settings: about one in
    /// twenty, at least [`TRIAL_MIN`] (all of fewer) and at most [`TRIAL_MAX`], seeded. A
    /// pixel refined here is refined exactly so in the rendering (its rays are its own).
    pub(crate) fn trial(
        &self,
        fc: &FrameConsts<'_>,
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
            .max(TRIAL_MIN.min(candidates.len()))
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
                self.refine_pixel::<false, ()>(
                    fc,
                    options,
                    refinement,
                    &inverse,
                    (col, row),
                    start,
                    hide,
                    &mut path,
                    &mut (),
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
        let mut paths_by_side: Vec<(u32, f64)> = Vec::new();
        for side in results
            .iter()
            .flat_map(|s| s.level_sides(refinement.max_side))
        {
            let paths = ROUNDS as f64 * f64::from(side) * f64::from(side) / pixels as f64;
            match paths_by_side.iter_mut().find(|(s, _)| *s == side) {
                Some((_, p)) => *p += paths,
                None => paths_by_side.push((side, paths)),
            }
        }
        paths_by_side.sort_by_key(|&(side, _)| side);
        Trial {
            pixels,
            paths_by_side,
            paths_per_candidate: results.iter().map(|s| f64::from(s.rays)).sum::<f64>()
                / pixels as f64,
            capped_share: capped.len() as f64 / pixels as f64,
            capped_sigma_k: capped,
            target_k: refinement.target_k,
            sigmas_k: results.iter().map(|s| f64::from(s.sigma_k)).collect(),
            geometric_sigmas_k: results
                .iter()
                .map(|s| f64::from(s.geometric_sigma_k))
                .collect(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_looser_target_scales_the_geometric_part_alone() {
        // Pixels of σ 0.05 K, all geometric; 0.05 K, 0.03 K of it geometric (0.04 K of
        // sky-view rays' noise); a capped one of 0.5 K, over the 0.1 K target.
        let trial = Trial {
            sigmas_k: vec![0.05, 0.05, 0.5],
            geometric_sigmas_k: vec![0.05, 0.03, 0.5],
            target_k: 0.1,
            ..Trial::default()
        };
        let s = trial.sigmas_scaled_k(2.0);
        assert!((s[0] - 0.1).abs() < 1e-12, "{s:?}");
        assert!((s[1] - (0.06_f64.powi(2) + 0.04_f64.powi(2)).sqrt()).abs() < 1e-12);
        assert!((s[2] - 0.5).abs() < 1e-12);
        for (a, b) in trial.sigmas_scaled_k(1.0).iter().zip(&trial.sigmas_k) {
            assert!((a - b).abs() < 1e-15, "{a} {b}");
        }
    }
}
