//! A pixel's error, predicted from the pilot's points against a converged rendering.
//!
//! A point's error under a combination is its bound (the sum of its models' errors against
//! the most accurate settings, [`super::choose::bound`]) plus its class's residual, what the
//! most accurate settings themselves leave ([`super::residual`]). A pixel that is not a
//! refinement candidate is rendered by its centre ray, the very ray the point measured, so
//! its error is the point's: the sky-view rays' noise is in the point's measured error as
//! one draw of it, and it averages away only over the rays of a refined pixel. A refined
//! pixel's error is a mean over its rays: refinement stops it at a standard error of at
//! most its target σ (the random part, shrinking as 1/√n with its rays), while the bias of
//! the deterministic models and of the residual does not shrink and is carried whole.
//!
//! So a class is held to the tolerance at its 90th percentile (at the pilot's confidence,
//! [`super::stats::confident_rank`]) with each point's need, the 90th percentile of its
//! pixel's error ([`need_k`]), refinement's target σ standing for its standard error's
//! geometric part and the centre's sky-view noise over √8 for the rest; and
//! the frame's percentile is predicted from the mixture of centre pixels, off by their bias
//! and a normal of their class's Monte Carlo error, and refined pixels, off by their bias
//! and a Student's t of the standard errors refinement left the trial's pixels at
//! ([`RefinedSpread`]), evaluated at a percentile halfway to 100, for the pilot's own
//! sample ([`super::choose::stricter`]). The target is a ceiling on the geometric part
//! only: most pixels stop well under it (a level's rays divide it by 2.8 or more), while
//! the sky-view rays' noise, which refinement's stopping test leaves out, can take a pixel
//! over it; the trial measured both.

use super::choose::{self, Combo, Pixels};
use super::classes::Census;
use super::measure::Measured;
use super::residual::{P90_OF_NORMAL, Residual};
use super::space::{PilotSpace, Supersample};
use super::stats::{confident_rank, order_statistic, student_t_upper};
use crate::refine::ROUNDS;

/// What the pilot knows of each point's pixel and each class beyond the models' errors.
#[derive(Debug, Clone)]
pub(crate) struct PixelTerms {
    /// Each class's residual, K ([`Residual::k`]).
    pub(crate) residual_k: Vec<f64>,
    /// Each class's residual's deterministic part, K ([`Residual::bounces_k`]).
    pub(crate) bounces_k: Vec<f64>,
    /// Each class's Monte Carlo standard error at the most rays on offer, K
    /// ([`Residual::sampling_sigma_k`]).
    pub(crate) sampling_sigma_k: Vec<f64>,
    /// What of that noise each class's refined pixels keep, K ([`refined_noise_k`]).
    pub(crate) refined_noise_k: Vec<f64>,
    /// Refinement's target σ as a share of the tolerance (0 without refinement).
    pub(crate) target_share: f64,
    /// Each point's pixel is refined: a refinement candidate, with refinement on offer.
    pub(crate) candidate: Vec<bool>,
    /// The smallest tolerance at which the most accurate settings hold each class
    /// ([`class_floor_k`]), K.
    pub(crate) class_floor_k: Vec<f64>,
}

impl PixelTerms {
    /// The terms of `census`'s points and classes (`by_class`: each class's points) with
    /// the classes' `residual`; refinement's target σ is `target_share` of the tolerance
    /// ([`super::trial::refinement_for`]: it depends on the share of candidates, not on the
    /// tolerance).
    pub(crate) fn of<S>(
        space: &PilotSpace<S>,
        census: &Census,
        by_class: &[Vec<usize>],
        residual: &[Residual],
        target_share: f64,
    ) -> Self {
        let residual_k: Vec<f64> = residual.iter().map(|r| r.k).collect();
        let bounces_k: Vec<f64> = residual.iter().map(|r| r.bounces_k).collect();
        let sampling_sigma_k: Vec<f64> = residual.iter().map(|r| r.sampling_sigma_k).collect();
        let refined_noise: Vec<f64> = sampling_sigma_k
            .iter()
            .map(|&s| refined_noise_k(s))
            .collect();
        let refines = space
            .supersampling
            .iter()
            .any(|s| matches!(s, Supersample::Refine(_)));
        let candidate: Vec<bool> = census
            .points
            .iter()
            .map(|p| {
                refines
                    && usize::try_from(p.pixel)
                        .ok()
                        .and_then(|i| census.candidate.get(i))
                        == Some(&true)
            })
            .collect();
        let class_floor_k = by_class
            .iter()
            .enumerate()
            .map(|(c, points)| {
                let candidates = points.iter().filter(|&&i| candidate[i]).count();
                class_floor_k(
                    residual_k[c],
                    (bounces_k[c], refined_noise[c]),
                    points.len(),
                    candidates,
                    target_share,
                )
            })
            .collect();
        Self {
            residual_k,
            bounces_k,
            sampling_sigma_k,
            refined_noise_k: refined_noise,
            target_share,
            candidate,
            class_floor_k,
        }
    }

    /// Whether each class is guaranteed at `tolerance_k`: its floor within it.
    pub(crate) fn guaranteed(&self, tolerance_k: f64) -> Vec<bool> {
        self.class_floor_k
            .iter()
            .map(|&f| f <= tolerance_k)
            .collect()
    }

    /// The bias a refined pixel that reaches refinement's cap may carry under a
    /// combination whose bound at point i is `bound(i)`, K: the largest, over the
    /// guaranteed classes of `by_class`, of the class's bound at its 90th percentile (at
    /// the pilot's confidence) plus its bounces' tail. The trial does not know its pixels'
    /// classes, so each is given the largest.
    pub(crate) fn capped_bias_k(
        &self,
        by_class: &[Vec<usize>],
        guaranteed: &[bool],
        bound: impl Fn(usize) -> f64,
    ) -> f64 {
        let mut bounds = Vec::new();
        by_class
            .iter()
            .enumerate()
            .filter(|&(c, points)| guaranteed[c] && !points.is_empty())
            .map(|(c, points)| {
                bounds.clear();
                bounds.extend(points.iter().map(|&i| bound(i)));
                let rank = confident_rank(bounds.len(), 90.0);
                order_statistic(&mut bounds, rank) + self.bounces_k[c]
            })
            .fold(0.0, f64::max)
    }

    /// What the choice holds each class's pixels with.
    pub(crate) fn pixels(&self) -> Pixels<'_> {
        Pixels {
            residual_k: &self.residual_k,
            bounces_k: &self.bounces_k,
            refined_noise_k: &self.refined_noise_k,
            target_share: self.target_share,
            candidate: &self.candidate,
        }
    }

    /// The frame's `percentile` of |ΔT| under `combo` against a converged rendering
    /// ([`frame_percentile_k`], at [`choose::stricter`]): each `guaranteed` point's bias its
    /// bound and its class's bounces' tail, a centre pixel with a normal of its class's
    /// Monte Carlo error at the most rays (the class's residual holds it at its 90th
    /// percentile; the frame's percentile reaches further into it), a refined one with the
    /// `spread` of refinement's rays about it.
    pub(crate) fn frame_percentile_k(
        &self,
        (census, measured, guaranteed): (&Census, &[Measured], &[bool]),
        combo: &Combo,
        spread: RefinedSpread<'_>,
        percentile: f64,
    ) -> f64 {
        let points: Vec<FramePoint> = census
            .points
            .iter()
            .zip(measured)
            .enumerate()
            .filter(|(_, (p, _))| guaranteed[p.class])
            .map(|(i, (p, m))| {
                let candidate = self.candidate[i];
                FramePoint {
                    bias_k: choose::bound(m, combo) + self.bounces_k[p.class],
                    sigma_k: if candidate {
                        0.0
                    } else {
                        self.sampling_sigma_k[p.class]
                    },
                    weight: census.classes[p.class].weight(),
                    candidate,
                }
            })
            .collect();
        frame_percentile_k(&points, spread, choose::stricter(percentile))
    }
}

/// The smallest tolerance the frame's predicted percentile keeps, K: the fixed point of
/// `predict_at(F) = F`, where `predict_at(F)` is the percentile predicted at a tolerance of
/// F. The geometric part of refinement's standard errors is a share of the tolerance and
/// the rest (the sky-view rays' noise in them, a capped pixel's, every bias) does not
/// depend on it ([`super::trial::Trial::sigmas_scaled_k`]), so `predict_at` grows more
/// slowly than F and the iteration from
/// `tolerance_k` converges (to a relative 1e-4 here, in at most 64 steps).
pub(crate) fn reachable_floor_k(tolerance_k: f64, predict_at: impl Fn(f64) -> f64) -> f64 {
    let mut f = tolerance_k;
    for _ in 0..64 {
        let next = predict_at(f);
        if !next.is_finite() {
            return next;
        }
        if (next - f).abs() <= 1e-4 * f {
            return next;
        }
        f = next;
    }
    f
}

/// What one point of a class needs of the tolerance, K: the 90th percentile of its pixel's
/// error. A centre pixel's is its bias `bias_k` (the bound plus its class's whole
/// residual, the Monte Carlo noise of the most rays in it); a refined pixel's is its bias
/// `refined_bias_k` (the bound plus the residual's deterministic part) plus 1.645 times
/// its standard error: refinement's target σ `target_k` for the geometric part, which the
/// stopping test holds, in quadrature with the sky-view rays' noise `refined_noise_k`,
/// which it does not ([`refined_noise_k`]).
pub(crate) fn need_k(
    bias_k: f64,
    refined_bias_k: f64,
    candidate: bool,
    target_k: f64,
    refined_noise_k: f64,
) -> f64 {
    if candidate {
        refined_bias_k + P90_OF_NORMAL * target_k.hypot(refined_noise_k)
    } else {
        bias_k
    }
}

/// The sky-view and shadow rays' noise left in a refined pixel of a class whose centre
/// pixels have `sampling_sigma_k` of it, K: every round of a level samples the hemisphere
/// with at least the centre's rays ([`crate::refine::level_sky_view_rays`]), and the
/// pixel is the mean of [`ROUNDS`] rounds, so at most σ/√ROUNDS (less where refinement
/// goes on to finer levels).
pub(crate) fn refined_noise_k(sampling_sigma_k: f64) -> f64 {
    sampling_sigma_k / (ROUNDS as f64).sqrt()
}

/// Whether a class whose points need `needs` ([`need_k`]) holds at `tolerance_k`: their
/// 90th percentile, at the pilot's confidence, within it.
pub(crate) fn class_holds(needs: &mut [f64], tolerance_k: f64) -> bool {
    let rank = confident_rank(needs.len(), 90.0);
    needs.is_empty() || order_statistic(needs, rank) <= tolerance_k
}

/// The smallest tolerance at which a class is held by the most accurate settings: each of
/// its points holds from its own threshold, and the class from the confident 90th
/// percentile's rank of those thresholds (`candidates` of its `points` refined). A centre
/// pixel's threshold is its class's residual `residual_k`. A refined pixel's is the T at
/// which its need ([`need_k`]) is T: the residual's deterministic part `bounces_k` = b plus
/// a = 1.645 times the standard error √((sT)² + ν²), refinement's target σ being a fixed
/// share s = `target_share` of the tolerance and ν the sky-view rays' noise
/// `refined_noise_k`. Squared, (1 − a²s²)T² − 2bT + b² − a²ν² = 0, whose larger root is
/// T = (b + a·√(s²b² + (1 − a²s²)ν²)) / (1 − a²s²); b/(1 − as) without noise. With
/// a·s ≥ 1 the target alone is the tolerance: never held.
pub(crate) fn class_floor_k(
    residual_k: f64,
    (bounces_k, refined_noise_k): (f64, f64),
    points: usize,
    candidates: usize,
    target_share: f64,
) -> f64 {
    let rank = confident_rank(points, 90.0);
    let a = P90_OF_NORMAL;
    let (b, s, nu) = (bounces_k, target_share, refined_noise_k);
    let d = 1.0 - a * a * s * s;
    let refined_k = if d > 0.0 {
        (b + a * (s * s * b * b + d * nu * nu).sqrt()) / d
    } else {
        f64::INFINITY
    };
    let mut thresholds: Vec<f64> = (0..points)
        .map(|i| {
            if i < candidates {
                refined_k
            } else {
                residual_k
            }
        })
        .collect();
    order_statistic(&mut thresholds, rank)
}

/// P(|b + N(0, σ²)| > x): a pixel of bias `b` and normal error of σ `sigma_k` off by
/// more than `x`.
fn exceedance(bias_k: f64, sigma_k: f64, x: f64) -> f64 {
    if sigma_k <= 0.0 {
        return f64::from(u8::from(bias_k.abs() > x));
    }
    let upper = |z: f64| 0.5 * libm::erfc(z / std::f64::consts::SQRT_2);
    upper((x - bias_k) / sigma_k) + upper((x + bias_k) / sigma_k)
}

/// The one-sided 95 % point of the standard normal: the pilot's confidence
/// ([`super::stats::CONFIDENCE`]) in a mean over the trial's pixels.
const CONFIDENT_Z: f64 = 1.645;

/// How refined pixels spread about their bias: the standard errors refinement left the
/// trial's pixels at ([`super::trial::Trial::sigmas_k`]), each standing for an equal
/// share of the frame's refined pixels.
///
/// A pixel's mean is off by its standard error times a Student's t of `ROUNDS − 1`
/// degrees of freedom, its σ being estimated from its level's [`ROUNDS`] rounds; the
/// refined pixels' share beyond `x` is the mean of the trial's shares, plus 1.645 times
/// that mean's standard error over the trial's pixels (a trial of a few dozen pixels reads
/// the upper tail of their σ loosely).
#[derive(Debug, Clone, Copy)]
pub(crate) struct RefinedSpread<'a> {
    pub(crate) sigmas_k: &'a [f64],
}

impl RefinedSpread<'_> {
    /// The share of refined pixels of bias `bias_k` off by more than `x`, at the pilot's
    /// confidence.
    fn exceedance(&self, bias_k: f64, x: f64) -> f64 {
        let one = |s: f64| {
            if s <= 0.0 {
                return exceedance(bias_k, 0.0, x);
            }
            let dof = ROUNDS as u32 - 1;
            student_t_upper((x - bias_k) / s, dof) + student_t_upper((x + bias_k) / s, dof)
        };
        match self.sigmas_k {
            [] => exceedance(bias_k, 0.0, x),
            [s] => one(*s),
            sigmas => {
                // Welford's running mean and sum of squared deviations: exact when the
                // trial's shares agree.
                let (mut mean, mut m2) = (0.0, 0.0);
                for (k, &s) in sigmas.iter().enumerate() {
                    let e = one(s);
                    let delta = e - mean;
                    mean += delta / (k + 1) as f64;
                    m2 += delta * (e - mean);
                }
                let n = sigmas.len() as f64;
                let sd = (m2 / (n - 1.0)).max(0.0).sqrt();
                (mean + CONFIDENT_Z * sd / n.sqrt()).min(1.0)
            }
        }
    }

    /// The widest standard error, K.
    fn widest_k(&self) -> f64 {
        self.sigmas_k.iter().copied().fold(0.0, f64::max)
    }
}

/// One point of the frame's prediction.
#[derive(Debug, Clone, Copy)]
pub(crate) struct FramePoint {
    /// Its bias, K (≥ 0).
    pub(crate) bias_k: f64,
    /// A centre pixel's normal error about its bias, K (a refined pixel's is the
    /// [`RefinedSpread`]).
    pub(crate) sigma_k: f64,
    /// The pixels it stands for.
    pub(crate) weight: f64,
    /// Its pixel is refined.
    pub(crate) candidate: bool,
}

/// The frame's `percentile` of |ΔT| predicted from `points` ([`self`]): the smallest `x`
/// whose weighted share of exceedance is at most `1 − percentile/100`, a centre pixel off
/// by its bias and a normal of its σ, a refined one by its bias and the `spread`, by
/// bisection (0 for no points).
pub(crate) fn frame_percentile_k(
    points: &[FramePoint],
    spread: RefinedSpread<'_>,
    percentile: f64,
) -> f64 {
    let total: f64 = points.iter().map(|p| p.weight).sum();
    if points.is_empty() || total <= 0.0 {
        return 0.0;
    }
    let allowed = (1.0 - percentile / 100.0).max(0.0);
    let over = |x: f64| {
        points
            .iter()
            .map(|p| {
                let e = if p.candidate {
                    spread.exceedance(p.bias_k, x)
                } else {
                    exceedance(p.bias_k, p.sigma_k, x)
                };
                p.weight * e
            })
            .sum::<f64>()
            / total
    };
    let worst = points.iter().map(|p| p.bias_k).fold(0.0, f64::max);
    let widest = points
        .iter()
        .map(|p| p.sigma_k)
        .fold(spread.widest_k(), f64::max);
    let (mut lo, mut hi) = (0.0, worst + 12.0 * widest);
    if over(lo) <= allowed {
        return 0.0;
    }
    // t's tails are wide: widen the bracket until it holds (a percentile of 99.999 and
    // more may need it).
    for _ in 0..60 {
        if over(hi) <= allowed {
            break;
        }
        lo = hi;
        hi *= 2.0;
    }
    // 60 halvings take the bracket to 2⁻⁶⁰ of its width.
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if over(mid) <= allowed {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    hi
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_reachable_floor_is_where_the_prediction_meets_the_tolerance() {
        // A centre part a = 0.09 K that no tolerance changes, and refinement's part 0.4·F:
        // in quadrature F = a/√(1 − 0.16) = 0.0982 K.
        let predict_at = |f: f64| 0.09_f64.hypot(0.4 * f);
        let floor = reachable_floor_k(0.05, predict_at);
        assert!((floor - 0.09 / 0.84_f64.sqrt()).abs() < 1e-5, "{floor}");
        // From above too, and a prediction that is the tolerance already.
        assert!((reachable_floor_k(1.0, predict_at) - floor).abs() < 1e-5);
        assert!((reachable_floor_k(0.2, |_| 0.2) - 0.2).abs() < 1e-12);
    }

    #[test]
    fn a_class_holds_from_the_rank_of_its_points_thresholds() {
        // 24 points (a class's floor): the confident 90th percentile is the largest. All
        // centre pixels: the residual.
        assert!((class_floor_k(0.2, (0.05, 0.0), 24, 0, 0.2) - 0.2).abs() < 1e-15);
        // One refined point of deterministic part 0.05 K, σ_t = 0.2 T: it holds from
        // 0.05/(1 − 1.645·0.2) = 0.07452… K, under the centre pixels' 0.2 K.
        assert!((class_floor_k(0.2, (0.05, 0.0), 24, 1, 0.2) - 0.2).abs() < 1e-15);
        let refined = 0.05 / (1.0 - 1.645 * 0.2);
        assert!((class_floor_k(0.2, (0.05, 0.0), 24, 24, 0.2) - refined).abs() < 1e-12);
        // A deterministic part larger than the whole centre residual decides where it is
        // the largest.
        assert!((class_floor_k(0.1, (0.1, 0.0), 24, 1, 0.2) - 0.1 / (1.0 - 0.329)).abs() < 1e-12);
        // A target σ no smaller than the tolerance over 1.645: never held.
        assert!(class_floor_k(0.1, (0.1, 0.0), 24, 24, 0.7).is_infinite());
        // Nothing measured: nothing to add.
        assert!((class_floor_k(0.0, (0.0, 0.0), 0, 0, 0.2)).abs() < 1e-15);
    }

    #[test]
    fn a_capped_pixel_may_carry_the_largest_bias_of_a_guaranteed_class() {
        // Three classes of 24 points (the confident 90th percentile is the largest): bounds
        // up to 0.03 K with a bounces' tail of 0.01 K; up to 0.02 K with 0.025 K; and one
        // not guaranteed, up to 0.5 K, which no capped pixel is held to.
        let terms = PixelTerms {
            residual_k: vec![0.0; 3],
            bounces_k: vec![0.01, 0.025, 0.0],
            sampling_sigma_k: vec![0.0; 3],
            refined_noise_k: vec![0.0; 3],
            target_share: 0.2,
            candidate: vec![false; 72],
            class_floor_k: vec![0.0; 3],
        };
        let by_class: Vec<Vec<usize>> = (0..3).map(|c| (24 * c..24 * c + 24).collect()).collect();
        let largest = [0.03, 0.02, 0.5];
        let bound = |i: usize| largest[i / 24] * (i % 24 + 1) as f64 / 24.0;
        let bias = terms.capped_bias_k(&by_class, &[true, true, false], bound);
        assert!((bias - 0.045).abs() < 1e-12, "{bias}");
        // The most accurate settings' bounds are 0: the bounces' tails alone.
        let bias = terms.capped_bias_k(&by_class, &[true, true, false], |_| 0.0);
        assert!((bias - 0.025).abs() < 1e-12, "{bias}");
        // Nothing guaranteed: no bias.
        assert!(terms.capped_bias_k(&by_class, &[false; 3], bound).abs() < 1e-15);
        // The σ above which such a pixel is not guaranteed at 0.1 K: (0.1 − 0.045)/1.645,
        // by hand 0.033435 K; none when the bias takes the tolerance; and the deterministic
        // share taken whole is the half of the tolerance over 1.645.
        let u = super::super::ungranted_sigma_k(0.1, 0.045);
        assert!((u - 0.033_435).abs() < 1e-6, "{u}");
        assert!(super::super::ungranted_sigma_k(0.1, 0.2).abs() < 1e-15);
        assert!((super::super::ungranted_sigma_k(0.1, 0.05) - 0.05 / 1.645).abs() < 1e-15);
    }

    #[test]
    fn a_refined_pixels_sky_view_noise_raises_its_class_floor() {
        // No deterministic part, σ_t = 0.2 T, noise 0.05 K: T = 1.645·√((0.2 T)² + 0.05²),
        // so T² (1 − 1.645²·0.04) = 1.645²·0.0025 and T = 0.08225 / √0.891759 = 0.08710 K
        // (by hand), where the target alone would hold from 0.
        let floor = class_floor_k(0.0, (0.0, 0.05), 24, 24, 0.2);
        assert!((floor - 0.087_10).abs() < 1e-5, "{floor}");
        // With a deterministic part too: the floor is where the need, which adds the two
        // standard errors in quadrature, meets the tolerance (found here by bisection).
        let (b, nu, s) = (0.03, 0.04, 0.25);
        let (mut lo, mut hi) = (b, 10.0);
        for _ in 0..200 {
            let t = 0.5 * (lo + hi);
            if need_k(f64::NAN, b, true, s * t, nu) > t {
                lo = t;
            } else {
                hi = t;
            }
        }
        let floor = class_floor_k(1.0, (b, nu), 24, 24, s);
        assert!((floor - lo).abs() < 1e-9, "{floor} against {lo}");
        // It is more than either alone would need.
        assert!(floor > class_floor_k(1.0, (b, 0.0), 24, 24, s));
        assert!(floor > class_floor_k(1.0, (0.0, nu), 24, 24, s));
        // The noise left after ROUNDS rounds of at least the centre's rays.
        assert!((refined_noise_k(0.08) - 0.08 / 8.0_f64.sqrt()).abs() < 1e-15);
    }

    #[test]
    fn a_class_holds_when_its_needs_at_the_90th_percentile_are_within_the_tolerance() {
        let mut needs: Vec<f64> = (0..24).map(|_| need_k(0.3, 0.0, false, 0.1, 0.0)).collect();
        assert!(class_holds(&mut needs, 0.5));
        // One refined point of deterministic part 0.3 K needs 0.3 + 1.645·0.15 > 0.5: the
        // largest of 24 decides.
        needs[3] = need_k(0.0, 0.3, true, 0.15, 0.0);
        assert!(!class_holds(&mut needs, 0.5));
        assert!(class_holds(&mut [], 0.1));
    }

    #[test]
    fn exceedance_is_the_two_tails_of_a_shifted_normal() {
        // No bias: P(|N| > 1.96σ) = 0.05 (standard tables).
        assert!((exceedance(0.0, 0.1, 0.196) - 0.05).abs() < 1e-4);
        // Bias 1σ, x = 1σ: P(N > 0) + P(N < −2) = 0.5 + 0.02275.
        assert!((exceedance(0.1, 0.1, 0.1) - 0.52275).abs() < 1e-4);
        assert!((exceedance(0.2, 0.0, 0.1) - 1.0).abs() < 1e-15);
        assert!(exceedance(0.05, 0.0, 0.1).abs() < 1e-15);
    }

    #[test]
    fn a_refined_pixel_is_off_by_a_student_t_of_its_standard_error() {
        let spread = |sigmas_k| RefinedSpread { sigmas_k };
        // No bias: P(|t₇| > 2.3646) = 0.05 (standard tables).
        let one = spread(&[0.1]).exceedance(0.0, 0.23646);
        assert!((one - 0.05).abs() < 1e-4, "{one}");
        // Bias 1σ, x = 1σ: P(t₇ > 0) + P(t₇ < −2) = 0.5 + 0.04281 (by quadrature of the
        // density, mpmath).
        let biased = spread(&[0.1]).exceedance(0.1, 0.1);
        assert!((biased - 0.542_81).abs() < 1e-4, "{biased}");
        // Trial pixels that agree add no uncertainty of their mean.
        let same = spread(&[0.1; 16]).exceedance(0.0, 0.23646);
        assert!((same - one).abs() < 1e-12, "{same}");
        // Two that differ, σ 0 and 0.1 K: shares 0 and 0.05, mean 0.025, their standard
        // deviation 0.035355, so 0.025 + 1.645 · 0.035355/√2 = 0.066125.
        let two = spread(&[0.0, 0.1]).exceedance(0.0, 0.23646);
        assert!((two - 0.066_125).abs() < 1e-4, "{two}");
        // None, or no spread: the bias alone.
        assert!((spread(&[]).exceedance(0.2, 0.1) - 1.0).abs() < 1e-15);
        assert!(spread(&[0.0]).exceedance(0.05, 0.1).abs() < 1e-15);
    }

    #[test]
    fn the_frame_percentile_of_biased_pixels_is_their_percentile() {
        // 100 equal points of bias 0.01·i: the 95th percentile leaves 5 above, 0.95.
        let points: Vec<FramePoint> = (1..=100)
            .map(|i| FramePoint {
                bias_k: 0.01 * f64::from(i),
                sigma_k: 0.0,
                weight: 1.0,
                candidate: false,
            })
            .collect();
        let p = frame_percentile_k(&points, RefinedSpread { sigmas_k: &[0.3] }, 95.0);
        assert!((p - 0.95).abs() < 1e-6, "{p}");
    }

    #[test]
    fn the_frame_percentile_of_refined_pixels_is_that_of_their_noise() {
        let spread = RefinedSpread { sigmas_k: &[0.1] };
        // Every pixel refined, no bias, σ 0.1 K: the 99th percentile of |t₇| is 3.4995σ
        // (standard tables).
        let points = [FramePoint {
            bias_k: 0.0,
            sigma_k: 0.0,
            weight: 3.0,
            candidate: true,
        }];
        let p = frame_percentile_k(&points, spread, 99.0);
        assert!((p - 0.349_95).abs() < 1e-4, "{p}");
        // Half the frame refined: 1 % of the frame over x is 2 % of the refined half,
        // |t₇| > 2.998σ.
        let mixed = [
            points[0],
            FramePoint {
                bias_k: 0.0,
                sigma_k: 0.0,
                weight: 3.0,
                candidate: false,
            },
        ];
        let p = frame_percentile_k(&mixed, spread, 99.0);
        assert!((p - 0.2998).abs() < 1e-4, "{p}");
        // The other half centre pixels with a normal error of 0.12 K: x with half of t₇'s
        // two tails at x/0.1 plus half of the normal's at x/0.12 equal to 1 %, 0.32730 K
        // (solved with mpmath's quadrature of t₇'s density and erfc).
        let noisy = [
            points[0],
            FramePoint {
                sigma_k: 0.12,
                ..mixed[1]
            },
        ];
        let p = frame_percentile_k(&noisy, spread, 99.0);
        assert!((p - 0.327_30).abs() < 1e-4, "{p}");
        // A percentile far in t's tails, past the first bracket of 12σ: 10⁻⁶ of the frame
        // over x is |t₇| > 15.767σ (by quadrature of the density, mpmath).
        let far = frame_percentile_k(&points, spread, 99.9999);
        assert!((far - 1.5767).abs() < 1e-3, "{far}");
        assert!(frame_percentile_k(&[], spread, 99.0).abs() < 1e-15);
    }
}
