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
//! pixel's error ([`need_k`]); and the frame's percentile is predicted from the mixture of
//! biased centre pixels and refined pixels whose error is their bias plus a normal of the
//! target σ (evaluated at a percentile halfway to 100, for the pilot's own sample,
//! [`super::choose::stricter`]).

use super::choose::{self, Combo, Pixels};
use super::classes::Census;
use super::measure::Measured;
use super::residual::{P90_OF_NORMAL, Residual};
use super::space::{PilotSpace, Supersample};
use super::stats::{confident_rank, order_statistic};

/// What the pilot knows of each point's pixel and each class beyond the models' errors.
#[derive(Debug, Clone)]
pub(crate) struct PixelTerms {
    /// Each class's residual, K ([`Residual::k`]).
    pub(crate) residual_k: Vec<f64>,
    /// Each class's residual's deterministic part, K ([`Residual::bounces_k`]).
    pub(crate) bounces_k: Vec<f64>,
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
                    bounces_k[c],
                    points.len(),
                    candidates,
                    target_share,
                )
            })
            .collect();
        Self {
            residual_k,
            bounces_k,
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

    /// What the choice holds each class's pixels with.
    pub(crate) fn pixels(&self) -> Pixels<'_> {
        Pixels {
            residual_k: &self.residual_k,
            bounces_k: &self.bounces_k,
            target_share: self.target_share,
            candidate: &self.candidate,
        }
    }

    /// The frame's `percentile` of |ΔT| under `combo` against a converged rendering
    /// ([`frame_percentile_k`], at [`choose::stricter`]): each `guaranteed` point's bias its
    /// bound and its class's residual, a refined one's its bound and the residual's
    /// deterministic part with a normal of `target_k`.
    pub(crate) fn frame_percentile_k(
        &self,
        (census, measured, guaranteed): (&Census, &[Measured], &[bool]),
        combo: &Combo,
        target_k: f64,
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
                let residual = if candidate {
                    &self.bounces_k
                } else {
                    &self.residual_k
                };
                FramePoint {
                    bias_k: choose::bound(m, combo) + residual[p.class],
                    weight: census.classes[p.class].weight(),
                    candidate,
                }
            })
            .collect();
        frame_percentile_k(&points, target_k, choose::stricter(percentile))
    }
}

/// What one point of a class needs of the tolerance, K: the 90th percentile of its pixel's
/// error. A centre pixel's is its bias `bias_k` (the bound plus its class's whole
/// residual, the Monte Carlo noise of the most rays in it); a refined pixel's is its bias
/// `refined_bias_k` (the bound plus the residual's deterministic part: the sky-view rays'
/// noise is averaged into refinement's own standard error) plus 1.645 times refinement's
/// target σ `target_k`.
pub(crate) fn need_k(bias_k: f64, refined_bias_k: f64, candidate: bool, target_k: f64) -> f64 {
    if candidate {
        refined_bias_k + P90_OF_NORMAL * target_k
    } else {
        bias_k
    }
}

/// Whether a class whose points need `needs` ([`need_k`]) holds at `tolerance_k`: their
/// 90th percentile, at the pilot's confidence, within it.
pub(crate) fn class_holds(needs: &mut [f64], tolerance_k: f64) -> bool {
    let rank = confident_rank(needs.len(), 90.0);
    needs.is_empty() || order_statistic(needs, rank) <= tolerance_k
}

/// The smallest tolerance at which a class is held by the most accurate settings: each of
/// its points holds from its own threshold (a centre pixel's its class's residual
/// `residual_k`, a refined pixel's the residual's deterministic part `bounces_k` over
/// `1 − 1.645·σ_t/T`, refinement's target σ being a fixed share `target_share` of the
/// tolerance), and the class from the confident 90th percentile's rank of those thresholds
/// (`candidates` of its `points` refined).
pub(crate) fn class_floor_k(
    residual_k: f64,
    bounces_k: f64,
    points: usize,
    candidates: usize,
    target_share: f64,
) -> f64 {
    let rank = confident_rank(points, 90.0);
    let refined = 1.0 - P90_OF_NORMAL * target_share;
    let refined_k = if refined > 0.0 {
        bounces_k / refined
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

/// P(|b + N(0, σ²)| > x): a refined pixel of bias `b` and standard error `sigma_k` off by
/// more than `x`.
fn exceedance(bias_k: f64, sigma_k: f64, x: f64) -> f64 {
    if sigma_k <= 0.0 {
        return f64::from(u8::from(bias_k.abs() > x));
    }
    let upper = |z: f64| 0.5 * libm::erfc(z / std::f64::consts::SQRT_2);
    upper((x - bias_k) / sigma_k) + upper((x + bias_k) / sigma_k)
}

/// One point of the frame's prediction.
#[derive(Debug, Clone, Copy)]
pub(crate) struct FramePoint {
    /// Its bias, K (≥ 0).
    pub(crate) bias_k: f64,
    /// The pixels it stands for.
    pub(crate) weight: f64,
    /// Its pixel is refined (to a standard error of the target σ).
    pub(crate) candidate: bool,
}

/// The frame's `percentile` of |ΔT| predicted from `points` ([`self`]): the smallest `x`
/// whose weighted share of exceedance is at most `1 − percentile/100`, each refined point
/// with its bias and a normal of `sigma_k`, by bisection (0 for no points).
pub(crate) fn frame_percentile_k(points: &[FramePoint], sigma_k: f64, percentile: f64) -> f64 {
    let total: f64 = points.iter().map(|p| p.weight).sum();
    if points.is_empty() || total <= 0.0 {
        return 0.0;
    }
    let allowed = (1.0 - percentile / 100.0).max(0.0);
    let over = |x: f64| {
        points
            .iter()
            .map(|p| {
                let s = if p.candidate { sigma_k } else { 0.0 };
                p.weight * exceedance(p.bias_k, s, x)
            })
            .sum::<f64>()
            / total
    };
    let worst = points.iter().map(|p| p.bias_k).fold(0.0, f64::max);
    let (mut lo, mut hi) = (0.0, worst + 12.0 * sigma_k.max(0.0));
    if over(lo) <= allowed {
        return 0.0;
    }
    for _ in 0..80 {
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
    fn a_class_holds_from_the_rank_of_its_points_thresholds() {
        // 24 points (a class's floor): the confident 90th percentile is the largest. All
        // centre pixels: the residual.
        assert!((class_floor_k(0.2, 0.05, 24, 0, 0.2) - 0.2).abs() < 1e-15);
        // One refined point of deterministic part 0.05 K, σ_t = 0.2 T: it holds from
        // 0.05/(1 − 1.645·0.2) = 0.07452… K, under the centre pixels' 0.2 K.
        assert!((class_floor_k(0.2, 0.05, 24, 1, 0.2) - 0.2).abs() < 1e-15);
        let refined = 0.05 / (1.0 - 1.645 * 0.2);
        assert!((class_floor_k(0.2, 0.05, 24, 24, 0.2) - refined).abs() < 1e-12);
        // A deterministic part larger than the whole centre residual decides where it is
        // the largest.
        assert!((class_floor_k(0.1, 0.1, 24, 1, 0.2) - 0.1 / (1.0 - 0.329)).abs() < 1e-12);
        // A target σ no smaller than the tolerance over 1.645: never held.
        assert!(class_floor_k(0.1, 0.1, 24, 24, 0.7).is_infinite());
        // Nothing measured: nothing to add.
        assert!((class_floor_k(0.0, 0.0, 0, 0, 0.2)).abs() < 1e-15);
    }

    #[test]
    fn a_class_holds_when_its_needs_at_the_90th_percentile_are_within_the_tolerance() {
        let mut needs: Vec<f64> = (0..24).map(|_| need_k(0.3, 0.0, false, 0.1)).collect();
        assert!(class_holds(&mut needs, 0.5));
        // One refined point of deterministic part 0.3 K needs 0.3 + 1.645·0.15 > 0.5: the
        // largest of 24 decides.
        needs[3] = need_k(0.0, 0.3, true, 0.15);
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
    fn the_frame_percentile_of_biased_pixels_is_their_percentile() {
        // 100 equal points of bias 0.01·i: the 95th percentile leaves 5 above, 0.95.
        let points: Vec<FramePoint> = (1..=100)
            .map(|i| FramePoint {
                bias_k: 0.01 * f64::from(i),
                weight: 1.0,
                candidate: false,
            })
            .collect();
        let p = frame_percentile_k(&points, 0.3, 95.0);
        assert!((p - 0.95).abs() < 1e-6, "{p}");
    }

    #[test]
    fn the_frame_percentile_of_refined_pixels_is_that_of_their_noise() {
        // Every pixel refined, no bias, σ 0.1 K: the 99th percentile of |N| is 2.576σ.
        let points = [FramePoint {
            bias_k: 0.0,
            weight: 3.0,
            candidate: true,
        }];
        let p = frame_percentile_k(&points, 0.1, 99.0);
        assert!((p - 0.2576).abs() < 1e-3, "{p}");
        // Half the frame refined: 1 % of the frame over x is 2 % of the refined half,
        // |N| > 2.326σ.
        let mixed = [
            points[0],
            FramePoint {
                bias_k: 0.0,
                weight: 3.0,
                candidate: false,
            },
        ];
        let p = frame_percentile_k(&mixed, 0.1, 99.0);
        assert!((p - 0.2326).abs() < 1e-3, "{p}");
        assert!(frame_percentile_k(&[], 0.1, 99.0).abs() < 1e-15);
    }
}
