//! [`EmissivityTable`]: angular (directional) band emissivity, linearly interpolated
//! (thesis §3.2.2, the `.ems` table), and its hemispherical mean (eq. 5 form).

use irsig_model::interp;

use crate::error::{RadiometryError, RadiometryErrorKind};

/// Emissivity against the angle from the surface normal (deg), rotationally symmetric,
/// linearly interpolated between tabulated angles and held constant beyond the first and
/// last ones.
///
/// ```
/// use irsig_radiometry::EmissivityTable;
/// let ems = EmissivityTable::new(vec![0.0, 60.0, 90.0], vec![0.98, 0.94, 0.0])?;
/// assert!((ems.at(30.0) - 0.96).abs() < 1e-12);
/// assert!((ems.at(75.0) - 0.47).abs() < 1e-12);
/// # Ok::<(), irsig_radiometry::RadiometryError>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct EmissivityTable {
    angle_deg: Vec<f64>,
    emissivity: Vec<f64>,
    /// [`Self::at_cos`] returns the first emissivity without an arc cosine for cosines at
    /// or above this (−∞ for a table flat at every angle).
    flat_from_cos: f64,
}

impl EmissivityTable {
    /// A table from matching columns: angles in degrees from the normal (0–90, strictly
    /// increasing) and emissivities in [0, 1].
    ///
    /// # Errors
    /// [`RadiometryErrorKind::InvalidEmissivity`] for an empty table, columns of different
    /// lengths, an angle outside 0–90° or not increasing, or an emissivity outside [0, 1]
    /// (NaN included).
    pub fn new(angle_deg: Vec<f64>, emissivity: Vec<f64>) -> Result<Self, RadiometryError> {
        let bad = |m: String| {
            Err(RadiometryError::new(
                RadiometryErrorKind::InvalidEmissivity,
                m,
            ))
        };
        if angle_deg.len() != emissivity.len() {
            return bad(format!(
                "{} angles but {} emissivities",
                angle_deg.len(),
                emissivity.len()
            ));
        }
        if angle_deg.is_empty() {
            return bad("the table is empty".to_owned());
        }
        for (i, (&a, &e)) in angle_deg.iter().zip(&emissivity).enumerate() {
            if !(0.0..=90.0).contains(&a) {
                return bad(format!("row {}: angle must be 0–90 deg, found {a}", i + 1));
            }
            if !(0.0..=1.0).contains(&e) {
                return bad(format!(
                    "row {}: emissivity must be in [0, 1], found {e}",
                    i + 1
                ));
            }
        }
        for (i, pair) in angle_deg.windows(2).enumerate() {
            let &[a, b] = pair else { continue };
            if b <= a {
                return bad(format!(
                    "angles must increase: row {} ({b} deg) follows {a} deg",
                    i + 2
                ));
            }
        }
        let flat_from_cos = flat_from_cos(&angle_deg, &emissivity);
        Ok(Self {
            angle_deg,
            emissivity,
            flat_from_cos,
        })
    }

    /// A table with the same emissivity at every angle (a grey Lambertian emitter).
    ///
    /// # Errors
    /// [`RadiometryErrorKind::InvalidEmissivity`] if `emissivity` is outside [0, 1].
    pub fn constant(emissivity: f64) -> Result<Self, RadiometryError> {
        Self::new(vec![0.0], vec![emissivity])
    }

    /// The tabulated angles, deg.
    #[must_use]
    pub fn angle_deg(&self) -> &[f64] {
        &self.angle_deg
    }

    /// The tabulated emissivities.
    #[must_use]
    pub fn emissivity(&self) -> &[f64] {
        &self.emissivity
    }

    /// Emissivity at `angle_deg` from the normal. The table is symmetric about the
    /// normal, so a negative angle is read as its magnitude; angles beyond 90° (a ray
    /// from behind the surface, possible from rounding at grazing incidence) read as 90°.
    /// NaN gives NaN.
    #[must_use]
    pub fn at(&self, angle_deg: f64) -> f64 {
        if angle_deg.is_nan() {
            return f64::NAN;
        }
        let a = angle_deg.abs().min(90.0);
        let xs = &self.angle_deg;
        let ys = &self.emissivity;
        let (Some(&first), Some(&last), Some(&y_first), Some(&y_last)) =
            (xs.first(), xs.last(), ys.first(), ys.last())
        else {
            return f64::NAN;
        };
        if a <= first {
            return y_first;
        }
        if a >= last {
            return y_last;
        }
        let i = interp::interval(xs, a);
        interp::between((xs[i], ys[i]), (xs[i + 1], ys[i + 1]), a)
    }

    /// [`Self::at`] the angle whose cosine is `cos_incidence`, with the same result bit for
    /// bit, but without computing the angle where the table is flat from the normal out to
    /// it: for a grey table, at every angle. The arc cosine costs about 12 ns, a tenth of
    /// a primary ray's whole shading cost, so a scene of grey materials does not pay it.
    #[must_use]
    pub fn at_cos(&self, cos_incidence: f64) -> f64 {
        if cos_incidence >= self.flat_from_cos {
            self.emissivity[0]
        } else {
            self.at(cos_incidence.acos().to_degrees())
        }
    }

    /// Hemispherical emissivity: the cosine-weighted mean over the hemisphere (the form of
    /// thesis eq. 5, normalised by π),
    /// `ε_h = 2 ∫_0^{π/2} ε(θ) cos θ sin θ dθ`,
    /// integrated exactly for the piecewise-linear interpolant this table defines
    /// (constant beyond its first and last angles).
    #[must_use]
    pub fn hemispherical(&self) -> f64 {
        // Breakpoints: 0, the tabulated angles, 90; ε is linear in θ between them.
        let mut knots: Vec<f64> = Vec::with_capacity(self.angle_deg.len() + 2);
        knots.push(0.0);
        knots.extend(
            self.angle_deg
                .iter()
                .copied()
                .filter(|&a| a > 0.0 && a < 90.0),
        );
        knots.push(90.0);
        let mut total = 0.0;
        for pair in knots.windows(2) {
            let &[a_deg, b_deg] = pair else { continue };
            let (a, b) = (a_deg.to_radians(), b_deg.to_radians());
            let (ea, eb) = (self.at(a_deg), self.at(b_deg));
            // ε(θ) = ea + s (θ − a). Antiderivatives of 2 sinθ cosθ = sin 2θ:
            // ∫ sin 2θ dθ = −cos 2θ / 2, ∫ θ sin 2θ dθ = −θ cos 2θ / 2 + sin 2θ / 4.
            let slope = (eb - ea) / (b - a);
            let f0 = |t: f64| -(2.0 * t).cos() / 2.0;
            let f1 = |t: f64| -t * (2.0 * t).cos() / 2.0 + (2.0 * t).sin() / 4.0;
            let zeroth = f0(b) - f0(a);
            let first = f1(b) - f1(a) - a * zeroth;
            total += ea * zeroth + slope * first;
        }
        total
    }
}

/// The cosine above which the table gives its first emissivity: the table is flat from 0°
/// out to the last angle θ_f of the run of equal emissivities it starts with (or out to 90°
/// and beyond if that run is the whole table). The threshold is cos θ_f + 1e-12: the arc
/// cosine of any cosine at or above it is at least 1e-12 rad below θ_f (|d acos/dc| ≥ 1),
/// far beyond the ~1e-16 rad rounding of `acos` and of the conversion to degrees, so
/// [`EmissivityTable::at`] would land in the flat run too and return the same value.
fn flat_from_cos(angle_deg: &[f64], emissivity: &[f64]) -> f64 {
    let first = emissivity[0];
    let run = emissivity
        .iter()
        .take_while(|e| e.to_bits() == first.to_bits())
        .count();
    if run == emissivity.len() {
        return f64::NEG_INFINITY;
    }
    angle_deg[run - 1].to_radians().cos() + 1e-12
}

#[cfg(test)]
#[allow(clippy::float_cmp)] // exact values are the point of these checks
mod tests {
    use super::*;

    #[test]
    fn a_constant_table_has_that_hemispherical_emissivity() {
        for e in [0.0, 0.5, 0.95, 1.0] {
            let t = EmissivityTable::constant(e).unwrap();
            assert!((t.hemispherical() - e).abs() < 1e-15, "{e}");
        }
    }

    #[test]
    fn hemispherical_matches_fine_midpoint_quadrature() {
        let t = EmissivityTable::new(
            vec![0.0, 20.0, 45.0, 70.0, 85.0, 90.0],
            vec![0.99, 0.985, 0.97, 0.88, 0.42, 0.0],
        )
        .unwrap();
        let n = 200_000;
        let h = std::f64::consts::FRAC_PI_2 / f64::from(n);
        let midpoint: f64 = (0..n)
            .map(|i| {
                let th = (f64::from(i) + 0.5) * h;
                2.0 * t.at(th.to_degrees()) * th.cos() * th.sin() * h
            })
            .sum();
        assert!((t.hemispherical() - midpoint).abs() < 1e-9);
    }

    #[test]
    fn at_cos_is_at_of_the_arc_cosine_bit_for_bit() {
        let tables = [
            EmissivityTable::constant(0.93).unwrap(),
            // Flat out to 40°, then falling: the flat run's end is where a shortcut could
            // go wrong.
            EmissivityTable::new(vec![0.0, 20.0, 40.0, 80.0], vec![0.95, 0.95, 0.95, 0.6]).unwrap(),
            EmissivityTable::new(vec![10.0, 80.0], vec![0.9, 0.5]).unwrap(),
            EmissivityTable::new(vec![0.0, 90.0], vec![0.99, 0.0]).unwrap(),
        ];
        let c40 = 40.0_f64.to_radians().cos();
        let mut cosines: Vec<f64> = (0..=10_000).map(|i| f64::from(i) / 10_000.0).collect();
        // Around the end of the flat run, in steps of a few ulps and of the 1e-12 margin.
        for k in -2000..=2000 {
            cosines.push(c40 + f64::from(k) * 1e-15);
            cosines.push(c40 + f64::from(k) * 1e-13);
        }
        cosines.extend([0.0, -0.0, 1.0, 1e-300, -1e-300]);
        for t in &tables {
            for &c in &cosines {
                let want = t.at(c.acos().to_degrees());
                assert_eq!(t.at_cos(c).to_bits(), want.to_bits(), "cos {c}");
            }
            assert!(t.at_cos(f64::NAN).is_nan());
        }
    }

    #[test]
    fn extremes_of_angle() {
        let t = EmissivityTable::new(vec![10.0, 80.0], vec![0.9, 0.5]).unwrap();
        assert_eq!(t.at(0.0), 0.9);
        assert_eq!(t.at(90.0), 0.5);
        assert_eq!(t.at(-45.0), t.at(45.0));
        assert_eq!(t.at(1e300), 0.5);
        assert!(t.at(f64::NAN).is_nan());
    }

    #[test]
    fn bad_tables_are_refused() {
        assert!(EmissivityTable::new(vec![], vec![]).is_err());
        assert!(EmissivityTable::new(vec![0.0, 0.0], vec![0.9, 0.9]).is_err());
        assert!(EmissivityTable::new(vec![0.0, 91.0], vec![0.9, 0.9]).is_err());
        assert!(EmissivityTable::new(vec![0.0], vec![1.5]).is_err());
        assert!(EmissivityTable::new(vec![0.0], vec![f64::NAN]).is_err());
        assert!(EmissivityTable::new(vec![0.0, 10.0], vec![0.9]).is_err());
    }
}
