//! Small numeric helpers over the tables' linear interpolation
//! (`irsig_model::interp`): monotone cubic and bilinear interpolation, the Appendix E
//! quadratic least-squares fit, and the eq. 5 hemispheric integral of a piecewise-linear
//! L(θ).

pub(crate) use irsig_model::interp::{linear, locate};

/// Monotone piecewise-cubic Hermite interpolation of `ys` over `xs` at `x`, clamped at
/// both ends (Fritsch & Carlson 1980, with the weighted harmonic-mean slopes of Fritsch &
/// Butland 1984; the ends take their interval's secant). It passes through every node,
/// follows a curve that bends between them (the sky's rise toward the horizon, which
/// linear interpolation overestimates), and never overshoots: between two nodes it stays
/// between their values, and where the data are monotone so is the curve. Local: a value
/// depends on four nodes. Fewer than three nodes: linear.
pub(crate) fn monotone_cubic(xs: &[f64], ys: &[f64], x: f64) -> f64 {
    let n = xs.len().min(ys.len());
    if n < 3 {
        return linear(xs, ys, x);
    }
    let (i, f) = locate(&xs[..n], x);
    monotone_cubic_located(xs, ys, i, f)
}

/// [`monotone_cubic`] at a point already located in `xs` (`(i, f)` of [`locate`]).
pub(crate) fn monotone_cubic_located(xs: &[f64], ys: &[f64], i: usize, f: f64) -> f64 {
    let n = xs.len().min(ys.len());
    if n < 3 {
        return match (ys.get(i), ys.get(i + 1)) {
            (Some(&a), Some(&b)) => a + f * (b - a),
            (Some(&a), None) => a,
            _ => f64::NAN,
        };
    }
    if f.is_nan() {
        return f64::NAN;
    }
    let secant = |k: usize| (ys[k + 1] - ys[k]) / (xs[k + 1] - xs[k]);
    let slope = |k: usize| -> f64 {
        if k == 0 {
            return secant(0);
        }
        if k == n - 1 {
            return secant(n - 2);
        }
        let (d0, d1) = (secant(k - 1), secant(k));
        if d0 * d1 <= 0.0 {
            return 0.0;
        }
        let (h0, h1) = (xs[k] - xs[k - 1], xs[k + 1] - xs[k]);
        let (w0, w1) = (2.0 * h1 + h0, h1 + 2.0 * h0);
        (w0 + w1) / (w0 / d0 + w1 / d1)
    };
    let h = xs[i + 1] - xs[i];
    let (f2, f3) = (f * f, f * f * f);
    let h00 = 2.0 * f3 - 3.0 * f2 + 1.0;
    let h10 = f3 - 2.0 * f2 + f;
    let h01 = -2.0 * f3 + 3.0 * f2;
    let h11 = f3 - f2;
    h00 * ys[i] + h10 * h * slope(i) + h01 * ys[i + 1] + h11 * h * slope(i + 1)
}

/// Where a point lies in a grid of rows `xs` and columns `ys`: located once, for the
/// bilinear interpolation of several tables on that grid, clamped at the edges.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Cell {
    i: usize,
    fx: f64,
    j: usize,
    fy: f64,
    rows: usize,
}

impl Cell {
    pub(crate) fn locate(xs: &[f64], ys: &[f64], x: f64, y: f64) -> Self {
        let (i, fx) = locate(xs, x);
        let (j, fy) = locate(ys, y);
        Self {
            i,
            fx,
            j,
            fy,
            rows: xs.len(),
        }
    }

    /// The table `zs[row][col]` at the cell: a monotone cubic along each row (across the
    /// columns `ys` the cell was located in), then linear between the two rows.
    pub(crate) fn cubic_in_columns(&self, ys: &[f64], zs: &[Vec<f64>]) -> f64 {
        self.cubic_in_rows(ys, |k| zs.get(k).map(Vec::as_slice))
    }

    /// As [`Cell::cubic_in_columns`], the rows given by `zs` (`None` past the last), for a
    /// table whose rows are made on first use.
    pub(crate) fn cubic_in_rows<'a>(
        &self,
        ys: &[f64],
        zs: impl Fn(usize) -> Option<&'a [f64]>,
    ) -> f64 {
        let row =
            |k: usize| zs(k).map_or(f64::NAN, |r| monotone_cubic_located(ys, r, self.j, self.fy));
        if self.rows < 2 {
            return row(0);
        }
        let a = row(self.i);
        let b = row(self.i + 1);
        a + self.fx * (b - a)
    }
}

/// The least-squares quadratic `y = a + b x + c x²` through the points (thesis Appendix E,
/// eq. E1–E2: `B = (XᵀX)⁻¹ XᵀY`). `x` is centred on its mean before fitting so the normal
/// equations stay well conditioned for angles in degrees. Returns a closure-free
/// [`Quadratic`]; `None` with fewer than three distinct points.
pub(crate) fn fit_quadratic(points: &[(f64, f64)]) -> Option<Quadratic> {
    if points.len() < 3 {
        return None;
    }
    let n = points.len() as f64;
    let x0 = points.iter().map(|p| p.0).sum::<f64>() / n;
    let mut s = [0.0_f64; 5];
    let mut t = [0.0_f64; 3];
    for &(x, y) in points {
        let u = x - x0;
        let mut p = 1.0;
        for sk in &mut s {
            *sk += p;
            p *= u;
        }
        t[0] += y;
        t[1] += y * u;
        t[2] += y * u * u;
    }
    let m = [[s[0], s[1], s[2]], [s[1], s[2], s[3]], [s[2], s[3], s[4]]];
    let det = det3(&m);
    if det.abs() < 1e-12 * s[4].max(1.0) * s[2].max(1.0) {
        return None;
    }
    let mut coef = [0.0; 3];
    for (k, c) in coef.iter_mut().enumerate() {
        let mut mk = m;
        for (row, tv) in mk.iter_mut().zip(t) {
            row[k] = tv;
        }
        *c = det3(&mk) / det;
    }
    Some(Quadratic { x0, coef })
}

fn det3(m: &[[f64; 3]; 3]) -> f64 {
    m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
}

/// A fitted quadratic in `x - x0`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Quadratic {
    x0: f64,
    coef: [f64; 3],
}

impl Quadratic {
    pub(crate) fn at(&self, x: f64) -> f64 {
        let u = x - self.x0;
        self.coef[0] + u * (self.coef[1] + u * self.coef[2])
    }
}

/// Thesis eq. 5 for a radiance that is piecewise linear in zenith angle θ (degrees) over
/// `[0°, 90°]`: `L_hemi = (1/π)∫∫ L cosθ dΩ = ∫₀^{π/2} L(θ) sin 2θ dθ`, integrated exactly
/// segment by segment. Below the first and above the last angle the end values hold.
pub(crate) fn hemispheric(angles_deg: &[f64], radiance: &[f64]) -> f64 {
    let (Some(&first), Some(&last)) = (radiance.first(), radiance.last()) else {
        return 0.0;
    };
    let n = angles_deg.len().min(radiance.len());
    Hemispheric::new(&angles_deg[..n]).integrate(first, last, radiance)
}

/// [`hemispheric`] over fixed angles: the knots and their sines and cosines made once, for
/// the many radiances on the same angles (every level of every sub-band's sky).
#[derive(Debug, Clone)]
pub(crate) struct Hemispheric {
    /// The knots, radians: 0, the angles strictly between 0° and 90°, then π/2.
    knots: Vec<f64>,
    /// sin 2θ and cos 2θ at each knot: each is an end of two segments.
    trig: Vec<(f64, f64)>,
    /// Which angle each knot between the ends is.
    inner: Vec<usize>,
}

impl Hemispheric {
    /// The rule for radiances at `angles_deg`.
    pub(crate) fn new(angles_deg: &[f64]) -> Self {
        let mut knots = Vec::with_capacity(angles_deg.len() + 2);
        let mut inner = Vec::with_capacity(angles_deg.len());
        knots.push(0.0);
        for (k, &a) in angles_deg.iter().enumerate() {
            if a > 0.0 && a < 90.0 {
                knots.push(a.to_radians());
                inner.push(k);
            }
        }
        knots.push(std::f64::consts::FRAC_PI_2);
        let trig = knots.iter().map(|&t| (2.0 * t).sin_cos()).collect();
        Self { knots, trig, inner }
    }

    /// Eq. 5 of `radiance`, one value per angle of the rule (0 for none).
    pub(crate) fn of(&self, radiance: &[f64]) -> f64 {
        match (radiance.first(), radiance.last()) {
            (Some(&first), Some(&last)) => self.integrate(first, last, radiance),
            _ => 0.0,
        }
    }

    /// Eq. 5 of `radiance` (at least one value per angle of the rule), `first` held from
    /// 0° and `last` to 90°.
    fn integrate(&self, first: f64, last: f64, radiance: &[f64]) -> f64 {
        let end = self.knots.len() - 1;
        let value = |i: usize| {
            if i == 0 {
                first
            } else if i == end {
                last
            } else {
                radiance[self.inner[i - 1]]
            }
        };
        let mut sum = 0.0;
        for (i, s) in self.trig.windows(2).enumerate() {
            let (t0, t1) = (self.knots[i], self.knots[i + 1]);
            let (l0, l1) = (value(i), value(i + 1));
            if t1 <= t0 {
                continue;
            }
            let slope = (l1 - l0) / (t1 - t0);
            // ∫ sin2θ dθ = -cos2θ/2 ;  ∫ (θ - t0) sin2θ dθ = -(θ - t0)cos2θ/2 + sin2θ/4
            let a = |(_, cos2t): (f64, f64)| -cos2t / 2.0;
            let b = |t: f64, (sin2t, cos2t): (f64, f64)| -(t - t0) * cos2t / 2.0 + sin2t / 4.0;
            sum += l0 * (a(s[1]) - a(s[0])) + slope * (b(t1, s[1]) - b(t0, s[0]));
        }
        sum
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn quadratic_fit_recovers_an_exact_parabola() {
        let pts: Vec<_> = (60..=83)
            .map(|x| {
                (
                    f64::from(x),
                    2.0 - 0.5 * f64::from(x) + 0.01 * f64::from(x * x),
                )
            })
            .collect();
        let q = fit_quadratic(&pts).unwrap();
        for x in [60.0, 83.0, 90.0, 95.0] {
            assert_relative_eq!(q.at(x), 2.0 - 0.5 * x + 0.01 * x * x, max_relative = 1e-9);
        }
        assert!(fit_quadratic(&pts[..2]).is_none());
    }

    #[test]
    fn hemispheric_of_a_constant_is_the_constant() {
        assert_relative_eq!(
            hemispheric(&[0.0, 45.0, 90.0], &[7.0, 7.0, 7.0]),
            7.0,
            max_relative = 1e-12
        );
    }

    #[test]
    fn hemispheric_of_a_linear_ramp_matches_the_closed_form() {
        // L(θ) = θ (radians): ∫₀^{π/2} θ sin2θ dθ = π/4.
        let a: Vec<f64> = (0..=90).map(f64::from).collect();
        let l: Vec<f64> = a.iter().map(|d| d.to_radians()).collect();
        assert_relative_eq!(
            hemispheric(&a, &l),
            std::f64::consts::FRAC_PI_4,
            max_relative = 1e-12
        );
    }

    #[test]
    fn monotone_cubic_is_exact_on_nodes_and_for_a_cubic_it_can_hold() {
        // Nodes of y = x³ on 1..5 (convex, increasing): every node returned exactly, the
        // curve between them below the chord (as the cubic is) and never outside the
        // interval's values.
        let xs = [1.0, 2.0, 3.0, 4.0, 5.0];
        let ys: Vec<f64> = xs.iter().map(|x: &f64| x.powi(3)).collect();
        for (x, y) in xs.iter().zip(&ys) {
            assert_relative_eq!(monotone_cubic(&xs, &ys, *x), *y);
        }
        for k in 0..40 {
            let x = 1.0 + 0.1 * f64::from(k);
            let v = monotone_cubic(&xs, &ys, x);
            let lin = linear(&xs, &ys, x);
            assert!(v <= lin + 1e-12, "{x}: {v} above the chord {lin}");
            // Within 4 % of x³ away from the one-sided first interval.
            if x >= 2.0 {
                assert!((v / x.powi(3) - 1.0).abs() < 0.04, "{x}: {v}");
            }
        }
        assert_relative_eq!(monotone_cubic(&xs, &ys, 0.0), 1.0);
        assert_relative_eq!(monotone_cubic(&xs, &ys, 9.0), 125.0);
        assert!(monotone_cubic(&xs, &ys, f64::NAN).is_nan());
    }

    #[test]
    // Flat data must give exactly flat values: equality is the point.
    #[allow(clippy::float_cmp)]
    fn monotone_cubic_does_not_overshoot_a_step() {
        // A step: linear or natural splines ring; a monotone cubic stays in [0, 1] and flat
        // where the data are flat.
        let xs = [0.0, 1.0, 2.0, 3.0, 4.0];
        let ys = [0.0, 0.0, 1.0, 1.0, 1.0];
        for k in 0..=40 {
            let x = 0.1 * f64::from(k);
            let v = monotone_cubic(&xs, &ys, x);
            assert!((0.0..=1.0).contains(&v), "{x}: {v}");
            if x <= 1.0 {
                assert_eq!(v, 0.0);
            }
            if x >= 2.0 {
                assert_eq!(v, 1.0);
            }
        }
        // Two nodes: the line.
        assert_relative_eq!(monotone_cubic(&[0.0, 2.0], &[1.0, 3.0], 1.0), 2.0);
    }
}
