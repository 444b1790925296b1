//! Linear interpolation in a table: the one home of finding the interval that holds a
//! value and of the straight line through its two ends.
//!
//! A table's `xs` increase strictly. [`locate`] gives the interval and the fraction along
//! it, held to the table's ends; [`lerp`] and [`between`] are the line itself, in the two
//! forms the project's tables use. The forms are the same line but round differently in
//! the last bit: [`lerp`] scales the difference by a fraction computed once (and shared by
//! several columns of one row), [`between`] multiplies before it divides. Each table keeps
//! the form its outputs were made with, so that moving a table's code here changes no
//! output byte. What a table does outside its span (hold its ends, read zero, refuse) is
//! the table's own rule and stays with it.

/// Index `i` of the interval `[xs[i], xs[i + 1]]` holding `x` and the fraction along it,
/// with `x` held to the table: `(0, 0)` at or below the first entry, `(n − 2, 1)` at or
/// above the last. A node inside the table starts its interval, at fraction 0. A NaN `x`
/// gives a NaN fraction; fewer than two entries give `(0, 0)`.
#[must_use]
pub fn locate(xs: &[f64], x: f64) -> (usize, f64) {
    let n = xs.len();
    if n < 2 {
        return (0, 0.0);
    }
    let first = xs[0];
    let last = xs[n - 1];
    if x.is_nan() {
        return (0, f64::NAN);
    }
    if x <= first {
        return (0, 0.0);
    }
    if x >= last {
        return (n - 2, 1.0);
    }
    let i = interval(xs, x);
    let f = (x - xs[i]) / (xs[i + 1] - xs[i]);
    (i, f)
}

/// Index `i` of the interval `[xs[i], xs[i + 1]]` that holds `x`, the first or the last
/// interval for an `x` outside the table (and for NaN, the first). `xs` has at least two
/// entries. Tables are short (a few dozen rows, a few thousand for spectra): a binary
/// search is as fast as anything.
#[must_use]
pub fn interval(xs: &[f64], x: f64) -> usize {
    xs.partition_point(|&v| v <= x)
        .saturating_sub(1)
        .min(xs.len().saturating_sub(2))
}

/// `a + t·(b − a)`: the point a fraction `t` of the way from `a` to `b`.
#[inline]
#[must_use]
pub fn lerp(a: f64, b: f64, t: f64) -> f64 {
    a + t * (b - a)
}

/// The line through `(x0, y0)` and `(x1, y1)` at `x`, as `y0 + (y1 − y0)·(x − x0) / (x1 −
/// x0)`: the product before the quotient.
#[inline]
#[must_use]
pub fn between((x0, y0): (f64, f64), (x1, y1): (f64, f64), x: f64) -> f64 {
    y0 + (y1 - y0) * (x - x0) / (x1 - x0)
}

/// Linear interpolation of `ys` over `xs` at `x`, with `x` held to the table ([`locate`]);
/// NaN when `ys` is empty or `x` is NaN.
#[must_use]
pub fn linear(xs: &[f64], ys: &[f64], x: f64) -> f64 {
    let (i, f) = locate(xs, x);
    match (ys.get(i), ys.get(i + 1)) {
        (Some(&a), Some(&b)) => lerp(a, b, f),
        (Some(&a), None) => a,
        _ => f64::NAN,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn locate_holds_the_ends_and_starts_an_interval_at_its_node() {
        let xs = [0.0, 1.0, 3.0];
        assert_eq!(locate(&xs, -2.0), (0, 0.0));
        assert_eq!(locate(&xs, 0.0), (0, 0.0));
        assert_eq!(locate(&xs, 0.5), (0, 0.5));
        assert_eq!(locate(&xs, 1.0), (1, 0.0));
        assert_eq!(locate(&xs, 2.5), (1, 0.75));
        assert_eq!(locate(&xs, 3.0), (1, 1.0));
        assert_eq!(locate(&xs, 7.0), (1, 1.0));
        assert!(locate(&xs, f64::NAN).1.is_nan());
        assert_eq!(locate(&[4.0], 9.0), (0, 0.0));
        assert_eq!(locate(&[], 9.0), (0, 0.0));
    }

    #[test]
    fn interval_is_the_first_or_last_outside_the_table() {
        let xs = [0.0, 1.0, 3.0, 6.0];
        assert_eq!(interval(&xs, -1.0), 0);
        assert_eq!(interval(&xs, 1.0), 1);
        assert_eq!(interval(&xs, 2.9), 1);
        assert_eq!(interval(&xs, 6.0), 2);
        assert_eq!(interval(&xs, 60.0), 2);
        assert_eq!(interval(&xs, f64::NAN), 0);
    }

    #[test]
    fn linear_interpolates_and_holds_the_ends() {
        let xs = [0.0, 1.0, 3.0];
        let ys = [10.0, 20.0, 0.0];
        assert!((linear(&xs, &ys, 0.5) - 15.0).abs() < 1e-12);
        assert!((linear(&xs, &ys, 2.0) - 10.0).abs() < 1e-12);
        assert!((linear(&xs, &ys, -5.0) - 10.0).abs() < 1e-12);
        assert!(linear(&xs, &ys, 9.0).abs() < 1e-12);
        assert!((linear(&[1.0], &[7.0], 9.0) - 7.0).abs() < 1e-12);
        assert!(linear(&xs, &[], 0.5).is_nan());
        assert!(linear(&xs, &ys, f64::NAN).is_nan());
    }

    #[test]
    fn the_two_forms_are_one_line() {
        // Exact in binary: both forms give the hand value 2.5 + 0.75·(6.5 − 2.5) = 5.5.
        assert_eq!(lerp(2.5, 6.5, 0.75).to_bits(), 5.5_f64.to_bits());
        assert_eq!(
            between((1.0, 2.5), (3.0, 6.5), 2.5).to_bits(),
            5.5_f64.to_bits()
        );
        // Not bit for bit in general: over many random points they differ by at most a
        // couple of units in the last place, which is why each table keeps its form.
        let mut worst = 0.0_f64;
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..10_000 {
            let (x0, x1) = (next(), 1.0 + next());
            let (y0, y1) = (next() * 100.0, next() * 100.0);
            let x = x0 + next() * (x1 - x0);
            let a = lerp(y0, y1, (x - x0) / (x1 - x0));
            let b = between((x0, y0), (x1, y1), x);
            worst = worst.max((a - b).abs() / a.abs().max(b.abs()).max(1e-300));
        }
        assert!(worst < 1e-14, "the forms differ by {worst:e} relative");
    }
}
