//! The statistics the pilot reads its samples with: distribution-free upper bounds on a
//! percentile from a random sample (binomial order statistics), and weighted percentiles of
//! a stratified sample.

/// The confidence with which the pilot's estimate of a percentile bounds the image's own.
pub const CONFIDENCE: f64 = 0.95;

/// The 1-based rank of the order statistic of `n` samples that is at least the
/// population's `percentile` with probability [`CONFIDENCE`]: the smallest `k` with
/// P(X ≤ k − 1) ≥ CONFIDENCE, X ~ Binomial(n, percentile/100) being the count of samples
/// below the population's percentile (distribution-free; any continuous distribution).
/// `n` when even the largest sample is not enough, and for the 100th percentile.
pub(crate) fn confident_rank(n: usize, percentile: f64) -> usize {
    let q = percentile / 100.0;
    if n == 0 || q >= 1.0 {
        return n;
    }
    // P(X = j) in logs, from j = 0 up: ln C(n, j) + j ln q + (n − j) ln(1 − q).
    let (ln_q, ln_1q) = (q.ln(), (1.0 - q).ln());
    let mut ln_choose = 0.0;
    let mut cumulative = 0.0;
    for j in 0..n {
        if j > 0 {
            ln_choose += ((n - j + 1) as f64).ln() - (j as f64).ln();
        }
        cumulative += (ln_choose + j as f64 * ln_q + (n - j) as f64 * ln_1q).exp();
        if cumulative >= CONFIDENCE {
            return j + 1;
        }
    }
    n
}

/// The `rank`-th smallest of `values` (1-based, clamped to them; 0 for none), by
/// selection.
pub(crate) fn order_statistic(values: &mut [f64], rank: usize) -> f64 {
    if values.is_empty() {
        return 0.0;
    }
    let k = rank.clamp(1, values.len()) - 1;
    *values.select_nth_unstable_by(k, f64::total_cmp).1
}

/// The `percentile` of a weighted sample `(value, weight)`: the smallest value whose
/// cumulative weight reaches `percentile`% of the total (0 for none). A stratified sample
/// weighs each of its points by the pixels it stands for.
pub(crate) fn weighted_percentile(values: &mut [(f64, f64)], percentile: f64) -> f64 {
    let total: f64 = values.iter().map(|v| v.1).sum();
    if values.is_empty() || total <= 0.0 {
        return 0.0;
    }
    values.sort_by(|a, b| a.0.total_cmp(&b.0));
    let goal = total * (percentile / 100.0).min(1.0);
    let mut cumulative = 0.0;
    for &(v, w) in values.iter() {
        cumulative += w;
        if cumulative >= goal * (1.0 - 1e-12) {
            return v;
        }
    }
    values.last().map_or(0.0, |v| v.0)
}

/// The two-sided standard-normal quantiles the refinement target is chosen from: `(q, z)`
/// with P(|N(0, 1)| > z) = q (standard tables).
pub(crate) const NORMAL_TAILS: [(f64, f64); 5] = [
    (0.05, 1.960),
    (0.02, 2.326),
    (0.01, 2.576),
    (0.005, 2.807),
    (0.0027, 3.0),
];

/// P(T > z) for Student's t with `dof` degrees of freedom, `dof` odd: the closed form of
/// Abramowitz & Stegun 26.7.3, P(|T| ≤ t) = (2/π)·[θ + sin θ·(cos θ + (2/3)·cos³ θ + … +
/// (2·4·…·(ν−3))/(1·3·…·(ν−2))·cos^(ν−2) θ)], θ = atan(t/√ν). What a mean is off by, in
/// units of its standard error estimated from `dof + 1` independent rounds.
pub(crate) fn student_t_upper(z: f64, dof: u32) -> f64 {
    debug_assert!(
        dof % 2 == 1,
        "the closed form is for odd degrees of freedom"
    );
    if z.is_nan() {
        return f64::NAN;
    }
    let theta = (z.abs() / f64::from(dof).sqrt()).atan();
    let (sin, cos) = theta.sin_cos();
    // The bracket's series: none for one degree of freedom, else cos θ and its terms.
    let (mut term, mut series) = (cos, if dof > 1 { cos } else { 0.0 });
    let mut k = 3;
    while k < dof {
        term *= f64::from(k - 1) / f64::from(k) * cos * cos;
        series += term;
        k += 2;
    }
    let within = std::f64::consts::FRAC_2_PI * (theta + sin * series);
    let upper = 0.5 * (1.0 - within).max(0.0);
    if z >= 0.0 { upper } else { 1.0 - upper }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    #[test]
    fn order_statistics_are_those_of_the_sorted_values() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let values: Vec<f64> = (0..1000).map(|_| rng.random::<f64>()).collect();
        let mut sorted = values.clone();
        sorted.sort_by(f64::total_cmp);
        for rank in [1, 5, 500, 995, 1000] {
            let v = order_statistic(&mut values.clone(), rank);
            assert_eq!(v.to_bits(), sorted[rank - 1].to_bits());
        }
        // Clamped to the values, and none gives 0.
        let bits = |rank| order_statistic(&mut values.clone(), rank).to_bits();
        assert_eq!(bits(0), sorted[0].to_bits());
        assert_eq!(bits(5000), sorted[999].to_bits());
        assert_eq!(order_statistic(&mut [], 3).to_bits(), 0.0_f64.to_bits());
    }

    #[test]
    fn confident_ranks_are_binomial_order_statistics() {
        // 299 samples: the largest bounds the 99th percentile with 95 % confidence
        // (1 − 0.99^299 = 0.95046), 298 do not (1 − 0.99^298 = 0.94996).
        assert_eq!(confident_rank(299, 99.0), 299);
        assert_eq!(confident_rank(250, 99.0), 250);
        // 1024 samples: exceedances E ~ Binomial(1024, 0.01), P(E ≥ 5) = 0.9755 ≥ 0.95
        // and P(E ≥ 6) = 0.9423 < 0.95 (summed by hand), so the 5th largest, rank 1020.
        assert_eq!(confident_rank(1024, 99.0), 1020);
        // The median of 100 samples: P(X ≤ 58) = 0.9557, P(X ≤ 57) = 0.9334
        // (Binomial(100, 0.5), summed by hand), so rank 59.
        assert_eq!(confident_rank(100, 50.0), 59);
        // A class's floor of 24 samples: 0.9^24 = 0.080 > 0.05, so its 90th percentile is
        // bounded only by its largest.
        assert_eq!(confident_rank(24, 90.0), 24);
        assert_eq!(confident_rank(10, 100.0), 10);
        assert_eq!(confident_rank(0, 99.0), 0);
    }

    #[test]
    fn student_t_tails_are_the_tables() {
        // Two-sided quantiles of t with 7 degrees of freedom (standard tables): 2.3646 at
        // 0.05, 3.4995 at 0.01, 5.4079 at 0.001.
        for (z, tail) in [(2.3646, 0.025), (3.4995, 0.005), (5.4079, 0.0005)] {
            let p = student_t_upper(z, 7);
            assert!((p - tail).abs() < 2e-3 * tail, "{z}: {p}");
        }
        // One degree of freedom is Cauchy: P(T > 1) = 1/4. Three: P(T > 3.1824) = 0.025.
        assert!((student_t_upper(1.0, 1) - 0.25).abs() < 1e-15);
        assert!((student_t_upper(3.1824, 3) - 0.025).abs() < 1e-4);
        // Symmetric, a half at 0; with 201 degrees near the normal's 0.025 at 1.96 (0.025689 by
        // quadrature of the density, mpmath).
        assert!((student_t_upper(0.0, 7) - 0.5).abs() < 1e-15);
        assert!((student_t_upper(-2.3646, 7) - 0.975).abs() < 1e-4);
        assert!((student_t_upper(1.96, 201) - 0.025_689).abs() < 1e-5);
        assert!(student_t_upper(f64::INFINITY, 7).abs() < 1e-15);
    }

    #[test]
    fn weighted_percentiles_weigh_each_point_by_what_it_stands_for() {
        // 1 of weight 98, 2 and 3 of weight 1 each: the 98th percentile is 1, the 99th 2,
        // the 100th 3.
        let mut v = vec![(3.0, 1.0), (1.0, 98.0), (2.0, 1.0)];
        assert!((weighted_percentile(&mut v, 98.0) - 1.0).abs() < 1e-12);
        assert!((weighted_percentile(&mut v, 99.0) - 2.0).abs() < 1e-12);
        assert!((weighted_percentile(&mut v, 100.0) - 3.0).abs() < 1e-12);
        assert!(weighted_percentile(&mut [], 99.0).abs() < 1e-12);
    }
}
