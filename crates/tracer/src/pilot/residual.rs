//! What the most accurate settings on offer leave in each class: their own residual, which
//! decides whether a class can be guaranteed at all, and the standard error above which a
//! pixel refined to the cap is not guaranteed.

use super::DETERMINISTIC_SHARE;
use super::measure::Measured;
use super::space::PilotSpace;
use super::stats::{confident_rank, order_statistic};

/// |N(0, 1)| is below this with probability 0.9.
pub(crate) const P90_OF_NORMAL: f64 = 1.645;

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

/// The most accurate settings' own residual in each class of `by_class` (the indices of its
/// sample points in `measured`), K: the bounces' last step at its 90th percentile (at the
/// pilot's confidence), and 1.645 σ of the sky-view and shadow rays' Monte Carlo error at
/// their most samples, the two independent.
pub(crate) fn residuals<S>(
    space: &PilotSpace<S>,
    measured: &[Measured],
    by_class: &[Vec<usize>],
) -> Vec<f64> {
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
            let mut steps: Vec<f64> = points.iter().map(|&i| measured[i].bounce_step_k).collect();
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
        .collect()
}
