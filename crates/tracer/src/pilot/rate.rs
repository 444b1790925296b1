//! What a convergence sequence leaves beyond its last step, from the rate between its
//! steps: the geometric tail of Aitken's Δ² extrapolation (Aitken 1926, Proc. R. Soc.
//! Edinburgh 46, 289–305; Brezinski & Redivo Zaglia 1991, *Extrapolation Methods*, §1.5).
//! A sequence whose steps shrink by a constant ratio `r` leaves `d_last · r/(1 − r)` after
//! its last step `d_last`; with `r = 0.5` that is the last step itself, so the rule taken
//! before, "the last step bounds what is left", holds exactly at that rate, and is too
//! pessimistic for a faster one and too optimistic for a slower one.
//!
//! Where the rate cannot be read from the steps (fewer than two, a growing or
//! alternating sequence, steps within their own sampling error), the last step is kept as
//! the bound, with the reason ([`NoRate`]).

/// The normal quantile the steps' sampling error is taken at: the rate's upper end and the
/// last step's are read at 95 % one-sided.
pub(crate) const STEP_SIGMAS: f64 = 1.645;

/// One step of a convergence sequence: the change from a setting to the next more accurate
/// one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Step {
    /// The change, K (signed: a sequence that alternates is told by its signs).
    pub(crate) change_k: f64,
    /// The change's own sampling standard error, K (0 for a deterministic sequence).
    pub(crate) sigma_k: f64,
    /// The step's length in the sequence's own unit (bounces: 4 from 4 to 8 bounces), so
    /// that steps of unequal length share one rate per unit.
    pub(crate) length: f64,
}

impl Step {
    /// A step of a deterministic sequence (no sampling error) of `length` units.
    pub(crate) fn exact(change_k: f64, length: f64) -> Self {
        Self {
            change_k,
            sigma_k: 0.0,
            length,
        }
    }
}

/// Why a sequence's rate was not estimated: its last step is then the bound.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum NoRate {
    /// Fewer than two steps on offer.
    TooFewSteps,
    /// The last step is not smaller than the previous one allows for convergence (the
    /// ratio per unit would be 1 or more).
    NotConverging,
    /// A step is within its own sampling error: its size, and so the ratio, is noise.
    WithinSigma,
    /// The last two steps have opposite signs: the sequence oscillates, and a geometric
    /// tail of one sign does not describe it.
    SignChange,
}

impl NoRate {
    /// The reason as the decision writes it.
    pub(crate) fn describe(self) -> &'static str {
        match self {
            Self::TooFewSteps => "fewer than two steps on offer",
            Self::NotConverging => "the last step is not smaller than the one before",
            Self::WithinSigma => "the steps are within their own sampling error",
            Self::SignChange => "the last two steps change sign",
        }
    }
}

/// What is left beyond a sequence's last step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Tail {
    /// The remaining error, K: the geometric tail, or the last step as a bound.
    pub(crate) tail_k: f64,
    /// The ratio between successive steps of the last step's length (at its upper end),
    /// or why it was not estimated.
    pub(crate) rate: Result<f64, NoRate>,
}

/// The ratio `d_last/d_previous` of two successive steps of lengths `last` and `previous`
/// when each unit of the sequence changes it by `ρ` times the unit before:
/// `ρ^p (1 − ρ^l)/(1 − ρ^p)`, the sum over the later block of units over the sum over the
/// earlier. Every power in the numerator exceeds every power in the denominator, so the
/// ratio grows with `ρ`, from 0 to `l/p` at `ρ = 1`.
fn block_ratio(rho: f64, last: f64, previous: f64) -> f64 {
    if rho >= 1.0 {
        return last / previous;
    }
    rho.powf(previous) * (1.0 - rho.powf(last)) / (1.0 - rho.powf(previous))
}

/// The rate per unit `ρ` whose [`block_ratio`] is `ratio`, by bisection (`None` at or above
/// `l/p`, where no `ρ < 1` gives it).
fn rate_per_unit(ratio: f64, last: f64, previous: f64) -> Option<f64> {
    if !(ratio.is_finite() && ratio >= 0.0) || ratio >= last / previous {
        return None;
    }
    let (mut lo, mut hi) = (0.0_f64, 1.0_f64);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if block_ratio(mid, last, previous) < ratio {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some(0.5 * (lo + hi))
}

/// What `steps` (from the least accurate to the most: the last is the change into the
/// most accurate setting) leave beyond the last, K ([`self`]). The rate is read from the
/// last two at the upper end of their sampling error (the last step's size plus
/// [`STEP_SIGMAS`] σ, the previous one's minus), so noise makes the tail larger, never
/// smaller.
pub(crate) fn geometric_tail(steps: &[Step]) -> Tail {
    let bound = |last: &Step, why| Tail {
        tail_k: last.change_k.abs() + STEP_SIGMAS * last.sigma_k,
        rate: Err(why),
    };
    // A sequence that has stopped changing exactly has nothing left.
    if steps
        .last()
        .is_some_and(|l| l.change_k == 0.0 && l.sigma_k == 0.0)
    {
        return Tail {
            tail_k: 0.0,
            rate: Ok(0.0),
        };
    }
    let [.., previous, last] = steps else {
        return match steps.last() {
            Some(last) => bound(last, NoRate::TooFewSteps),
            None => Tail {
                tail_k: 0.0,
                rate: Err(NoRate::TooFewSteps),
            },
        };
    };
    let last_hi = last.change_k.abs() + STEP_SIGMAS * last.sigma_k;
    let previous_lo = previous.change_k.abs() - STEP_SIGMAS * previous.sigma_k;
    if last.change_k.abs() <= STEP_SIGMAS * last.sigma_k {
        return bound(last, NoRate::WithinSigma);
    }
    if previous_lo <= 0.0 {
        // A previous step of nothing, exactly, followed by a change: not converging.
        let why = if previous.sigma_k > 0.0 {
            NoRate::WithinSigma
        } else {
            NoRate::NotConverging
        };
        return bound(last, why);
    }
    if last.change_k.signum() != previous.change_k.signum() {
        return bound(last, NoRate::SignChange);
    }
    let (l, p) = (
        last.length.max(f64::MIN_POSITIVE),
        previous.length.max(f64::MIN_POSITIVE),
    );
    let Some(rho) = rate_per_unit(last_hi / previous_lo, l, p) else {
        return bound(last, NoRate::NotConverging);
    };
    // The units beyond the last step continue at ρ: their sum is ρ^l/(1 − ρ^l) times the
    // last step's (a geometric series of blocks of l units).
    let r = rho.powf(l);
    Tail {
        tail_k: last_hi * r / (1.0 - r),
        rate: Ok(r),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The steps of a sequence `x_n = x_∞ + c·r^n` (deterministic), from `n = 0`.
    fn geometric(c: f64, r: f64, n: usize) -> Vec<Step> {
        (1..=n)
            .map(|k| Step::exact(c * (r.powi(k as i32) - r.powi(k as i32 - 1)), 1.0))
            .collect()
    }

    #[test]
    fn a_geometric_sequence_at_half_leaves_its_last_step() {
        // x_n − x_∞ = c·0.5^n: after n = 5 the rest is c/32, the last step c/32 too.
        let t = geometric_tail(&geometric(2.0, 0.5, 5));
        assert!((t.rate.unwrap() - 0.5).abs() < 1e-9, "{t:?}");
        assert!((t.tail_k - 2.0 / 32.0).abs() < 1e-9, "{t:?}");
    }

    #[test]
    fn a_fast_sequence_leaves_a_fraction_of_its_last_step_and_a_slow_one_more() {
        // r = 0.1: rest c·0.1^4 against the last step c·0.9·0.1^3, 1/9 of it.
        let t = geometric_tail(&geometric(1.0, 0.1, 4));
        assert!((t.tail_k - 1e-4).abs() < 1e-12, "{t:?}");
        // r = 0.9: rest c·0.9^4, nine times the last step c·0.1·0.9^3.
        let t = geometric_tail(&geometric(1.0, 0.9, 4));
        assert!((t.tail_k - 0.9_f64.powi(4)).abs() < 1e-9, "{t:?}");
    }

    #[test]
    fn steps_of_unequal_length_share_one_rate_per_unit() {
        // Bounces 2 → 4 → 8 with each bounce adding 0.5 of the one before, c·0.5^j for
        // bounce j: the step to 4 is c(0.5³ + 0.5⁴), to 8 c(0.5⁵ + … + 0.5⁸), and the
        // rest beyond 8 is c·0.5⁸ (Σ_{j>8} 0.5^j).
        let c = 3.0;
        let sum = |a: i32, b: i32| (a..=b).map(|j| c * 0.5_f64.powi(j)).sum::<f64>();
        let steps = [Step::exact(sum(3, 4), 2.0), Step::exact(sum(5, 8), 4.0)];
        let t = geometric_tail(&steps);
        assert!((t.rate.unwrap() - 0.5_f64.powi(4)).abs() < 1e-9, "{t:?}");
        assert!((t.tail_k - c * 0.5_f64.powi(8)).abs() < 1e-9, "{t:?}");
    }

    #[test]
    fn a_sequence_that_does_not_shrink_is_not_estimated_and_keeps_its_last_step() {
        // Constant x_n (r = 1 from x_0): nothing changes, nothing is left.
        let t = geometric_tail(&geometric(1.0, 1.0, 3));
        assert!(t.tail_k.abs() < 1e-300, "{t:?}");
        // Growing steps, r = 1.5.
        let steps = geometric(1.0, 1.5, 3);
        let t = geometric_tail(&steps);
        assert_eq!(t.rate, Err(NoRate::NotConverging), "{t:?}");
        assert!((t.tail_k - steps[2].change_k.abs()).abs() < 1e-15);
        // Equal steps: r = 1.
        let t = geometric_tail(&[Step::exact(0.2, 1.0), Step::exact(0.2, 1.0)]);
        assert_eq!(t.rate, Err(NoRate::NotConverging));
        assert!((t.tail_k - 0.2).abs() < 1e-15);
        // Unequal lengths: 4 units changing twice what 2 did is a rate of 1 per unit.
        let t = geometric_tail(&[Step::exact(0.1, 2.0), Step::exact(0.2, 4.0)]);
        assert_eq!(t.rate, Err(NoRate::NotConverging));
    }

    #[test]
    fn noisy_steps_within_their_sigma_are_not_estimated() {
        // A last step of 0.01 K with σ 0.01 K: its size is noise.
        let t = geometric_tail(&[
            Step {
                change_k: 0.2,
                sigma_k: 0.01,
                length: 1.0,
            },
            Step {
                change_k: 0.01,
                sigma_k: 0.01,
                length: 1.0,
            },
        ]);
        assert_eq!(t.rate, Err(NoRate::WithinSigma));
        assert!((t.tail_k - (0.01 + STEP_SIGMAS * 0.01)).abs() < 1e-15);
        // A previous step within its σ: the ratio's denominator is noise.
        let t = geometric_tail(&[
            Step {
                change_k: 0.02,
                sigma_k: 0.05,
                length: 1.0,
            },
            Step::exact(0.01, 1.0),
        ]);
        assert_eq!(t.rate, Err(NoRate::WithinSigma));
        // An exact previous step of nothing, then a change: not converging.
        let t = geometric_tail(&[Step::exact(0.0, 1.0), Step::exact(0.01, 1.0)]);
        assert_eq!(t.rate, Err(NoRate::NotConverging));
    }

    #[test]
    fn sampling_error_makes_the_tail_larger_never_smaller() {
        let exact = geometric_tail(&[Step::exact(0.4, 1.0), Step::exact(0.2, 1.0)]);
        let noisy = geometric_tail(&[
            Step {
                change_k: 0.4,
                sigma_k: 0.02,
                length: 1.0,
            },
            Step {
                change_k: 0.2,
                sigma_k: 0.02,
                length: 1.0,
            },
        ]);
        assert!((exact.tail_k - 0.2).abs() < 1e-12);
        // (0.2 + 1.645·0.02)/(0.4 − 1.645·0.02) = 0.6350…, tail 0.2329 · r/(1 − r).
        let hi = 0.2 + STEP_SIGMAS * 0.02;
        let r = hi / (0.4 - STEP_SIGMAS * 0.02);
        assert!(
            (noisy.tail_k - hi * r / (1.0 - r)).abs() < 1e-9,
            "{noisy:?}"
        );
        assert!(noisy.tail_k > exact.tail_k);
    }

    #[test]
    fn an_alternating_or_short_sequence_is_not_estimated() {
        let t = geometric_tail(&[Step::exact(0.4, 1.0), Step::exact(-0.1, 1.0)]);
        assert_eq!(t.rate, Err(NoRate::SignChange));
        assert!((t.tail_k - 0.1).abs() < 1e-15);
        let t = geometric_tail(&[Step::exact(-0.3, 1.0)]);
        assert_eq!(t.rate, Err(NoRate::TooFewSteps));
        assert!((t.tail_k - 0.3).abs() < 1e-15);
        let t = geometric_tail(&[]);
        assert_eq!(t.rate, Err(NoRate::TooFewSteps));
        assert!(t.tail_k.abs() < 1e-300);
        // One step of nothing: nothing left.
        let t = geometric_tail(&[Step::exact(0.0, 1.0)]);
        assert!(t.tail_k.abs() < 1e-300 && t.rate.is_ok());
    }
}
