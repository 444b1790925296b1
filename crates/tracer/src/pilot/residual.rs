//! What the most accurate settings on offer leave in each class: their own residual, which
//! decides whether a class can be guaranteed at all, read from the rate at which each
//! convergence sequence converges ([`super::rate`]: the bounces' geometric tail, the Monte
//! Carlo error's power of the samples), and the standard error above which a pixel refined
//! to the cap is not guaranteed.

use super::measure::Measured;
use super::rate::{self, NoRate, Step, Tail};
use super::space::PilotSpace;
use super::stats::{confident_rank, order_statistic};

/// |N(0, 1)| is below this with probability 0.9.
pub(crate) const P90_OF_NORMAL: f64 = 1.645;

/// The standard error above which a pixel refined to the cap is not guaranteed at
/// `tolerance_k` when its class may carry a bias of `bias_k`, K: its error, that bias
/// and a normal of that σ, then exceeds the tolerance more often than one time in ten
/// (a refined pixel's need, as the pilot holds its classes to). 0 when the bias alone
/// takes the tolerance. A decision written before it recorded this took the bias as the
/// deterministic models' whole share of the tolerance.
#[must_use]
pub fn ungranted_sigma_k(tolerance_k: f64, bias_k: f64) -> f64 {
    ((tolerance_k - bias_k) / P90_OF_NORMAL).max(0.0)
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

/// What the most accurate settings on offer leave in one class, and how it was read.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct Residual {
    /// The whole, K: the bounces' tail at its 90th percentile plus 1.645 σ of the Monte
    /// Carlo error.
    pub(crate) k: f64,
    /// The bounces' tail at the class's 90th percentile (at the pilot's confidence), K.
    pub(crate) bounces_k: f64,
    /// The Monte Carlo standard error of the most sky-view and shadow rays, K.
    pub(crate) sampling_sigma_k: f64,
    /// Where the bounces' rate was not estimated at some of the class's points: how many,
    /// and why (empty when it was at every point).
    pub(crate) note: String,
}

impl Residual {
    /// The parts as a refusal or a class's report names them: `: bounces 0.012 K beyond
    /// the most, sampling σ 0.031 K; <the note>`.
    pub(crate) fn parts(&self) -> String {
        let mut s = format!(
            ": bounces {:.3} K beyond the most, sampling σ {:.3} K",
            self.bounces_k, self.sampling_sigma_k
        );
        if !self.note.is_empty() {
            s.push_str("; ");
            s.push_str(&self.note);
        }
        s
    }
}

/// What the most bounces on offer leave at one point whose apparent temperature at each
/// limit of `bounces` (the most first) is `by_bounces_k`: the geometric tail of its last
/// two steps ([`rate::geometric_tail`]), each step's length its bounces.
fn bounce_tail(bounces: &[u32], by_bounces_k: &[f64]) -> Tail {
    let steps: Vec<Step> = (0..by_bounces_k.len().saturating_sub(1).min(2))
        .rev()
        .map(|i| {
            let length = bounces
                .get(i)
                .zip(bounces.get(i + 1))
                .map_or(1, |(a, b)| a.saturating_sub(*b).max(1));
            Step::exact(by_bounces_k[i] - by_bounces_k[i + 1], f64::from(length))
        })
        .collect();
    rate::geometric_tail(&steps)
}

/// The reasons the rate was not estimated at some of `total` points, counted: `rate not
/// estimated at 3 of 24 points (the last two steps change sign: 2; …)`, empty when none.
fn describe_misses(misses: &[NoRate], total: usize) -> String {
    if misses.is_empty() {
        return String::new();
    }
    let kinds = [
        NoRate::SignChange,
        NoRate::NotConverging,
        NoRate::WithinSigma,
        NoRate::TooFewSteps,
    ];
    let counted: Vec<String> = kinds
        .iter()
        .filter_map(|&k| {
            let n = misses.iter().filter(|&&m| m == k).count();
            (n > 0).then(|| format!("{}: {n}", k.describe()))
        })
        .collect();
    format!(
        "bounces' rate not estimated at {} of {total} points ({}), their last step kept as \
         the bound",
        misses.len(),
        counted.join("; ")
    )
}

/// The most accurate settings' own residual in each class of `by_class` (the indices of its
/// sample points in `measured`): the bounces' geometric tail beyond the most on offer at
/// its 90th percentile (at the pilot's confidence), and 1.645 σ of the sky-view and shadow
/// rays' Monte Carlo error at their most samples, the two independent.
pub(crate) fn residuals<S>(
    space: &PilotSpace<S>,
    measured: &[Measured],
    by_class: &[Vec<usize>],
) -> Vec<Residual> {
    let sky_counts: Vec<u32> = space
        .sky_view_rays
        .iter()
        .copied()
        .filter(|&n| n > 0)
        .collect();
    let shadow_counts: Vec<u32> = space.sun.as_ref().map_or_else(Vec::new, |s| {
        s.shadow_rays.iter().copied().filter(|&n| n > 1).collect()
    });
    by_class
        .iter()
        .map(|points| {
            let mut misses = Vec::new();
            let mut tails: Vec<f64> = points
                .iter()
                .map(|&i| {
                    let t = bounce_tail(&space.bounces, &measured[i].by_bounces_k);
                    if let Err(why) = t.rate {
                        misses.push(why);
                    }
                    t.tail_k
                })
                .collect();
            // One bounce limit on offer is no sequence: nothing to say about its rate.
            if space.bounces.len() < 2 {
                misses.clear();
            }
            let rank = confident_rank(tails.len(), 90.0);
            let bounces_k = order_statistic(&mut tails, rank);
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
            let sampling_sigma_k = sky.hypot(shadow);
            Residual {
                k: bounces_k + P90_OF_NORMAL * sampling_sigma_k,
                bounces_k,
                sampling_sigma_k,
                note: describe_misses(&misses, points.len()),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_point_whose_bounces_converge_geometrically_leaves_the_geometric_tail() {
        // Each bounce j adds c·0.5^j: at limit b the temperature is T∞ − c·0.5^b (the
        // sum beyond b), so 8 bounces leave c·0.5⁸, 1/15 of their last step from 4.
        let (t_inf, c) = (300.0, 2.0);
        let bounces: [u32; 5] = [8, 4, 2, 1, 0];
        let by: Vec<f64> = bounces
            .iter()
            .map(|&b| t_inf - c * 0.5_f64.powf(f64::from(b)))
            .collect();
        let t = bounce_tail(&bounces, &by);
        assert!((t.tail_k - c * 0.5_f64.powi(8)).abs() < 1e-9, "{t:?}");
        assert!(t.tail_k < (by[0] - by[1]).abs() / 10.0);
    }

    #[test]
    fn a_point_whose_bounces_alternate_keeps_its_last_step() {
        // A mirror between a hot and a cold surface: each further bounce swings the other way.
        let by = [300.5, 300.0, 301.0, 299.0, 310.0];
        let t = bounce_tail(&[8, 4, 2, 1, 0], &by);
        assert_eq!(t.rate, Err(NoRate::SignChange));
        assert!((t.tail_k - 0.5).abs() < 1e-12);
        // One limit on offer: nothing to extrapolate, nothing measured.
        let t = bounce_tail(&[8], &[300.0]);
        assert_eq!(t.rate, Err(NoRate::TooFewSteps));
        assert!(t.tail_k.abs() < 1e-300);
    }

    #[test]
    fn the_points_whose_rate_is_not_estimated_are_counted_by_reason() {
        assert_eq!(describe_misses(&[], 24), "");
        let note = describe_misses(
            &[
                NoRate::SignChange,
                NoRate::NotConverging,
                NoRate::SignChange,
            ],
            24,
        );
        assert!(
            note.starts_with("bounces' rate not estimated at 3 of 24 points"),
            "{note}"
        );
        assert!(note.contains("the last two steps change sign: 2"), "{note}");
        assert!(
            note.contains("not smaller than the one before: 1"),
            "{note}"
        );
    }
}
