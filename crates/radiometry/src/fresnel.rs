//! Fresnel emissivity of a smooth, opaque surface from its complex refractive index
//! `N = n + i k`: the angular emissivity tables (`.ems`, thesis §3.2.2) that the tracer
//! interpolates, made from optical constants instead of measured by hand.
//!
//! For an interface from vacuum (or air, n = 1) into a medium of index `N`, at angle θ from
//! the normal (`c = cos θ`, `s = sin θ`), with `r = sqrt(N² − s²)` on the branch with
//! `Re r ≥ 0, Im r ≥ 0` (the transmitted wave decays into the medium):
//!
//! ```text
//! r_s = (c − r) / (c + r),        r_p = (N² c − r) / (N² c + r),
//! R_s = |r_s|²,  R_p = |r_p|²,    ε(θ) = 1 − (R_s + R_p) / 2   (Kirchhoff, opaque)
//! ```
//!
//! These are the full complex equations (Born & Wolf, *Principles of Optics*, §14.2),
//! not the `k = 0` simplification: `k` is what makes water's emissivity fall from 0.99 at
//! 10 µm to 0.97 at 13 µm, and what makes metals dark.
//!
//! # Numerics
//! Every Fresnel coefficient has the form `(a − b)/(a + b)` with `a` and `b` in the closed
//! right half-plane, so `|a + b|² ≥ |a|² + |b|²` and nothing cancels in the denominator.
//! The emissivity is computed as `1 − |a − b|²/|a + b|² = 4 Re(a b̄)/|a + b|²` rather than
//! as `1 − R`, which keeps its relative accuracy when `R → 1` (metals). For `|N| > 1` the
//! same ratios are rewritten with `u = r/N = sqrt(1 − (s/N)²)` (`r_s = (c/N − u)/(c/N + u)`,
//! `r_p = (N c − u)/(N c + u)`), so `N²` is never formed; magnitudes go through `hypot`.
//! Hence: no overflow, no NaN, `0 ≤ R ≤ 1`, for every finite valid `n`, `k` and angle.
//!
//! # Rough surfaces
//! [`RoughSurface`] averages these facet emissivities over Gaussian slopes of a given RMS
//! slope, with Smith's shadowing (Masuda et al. 1988; Wu & Smith 1997): a smooth
//! dielectric's emissivity falls to 0 at grazing, a rough one's stays near its normal
//! value to much larger angles, as field measurements of soils, sand and grass show
//! (`data/rough-surfaces.csv`, held by `tests/rough.rs`).

use num_complex::Complex64;
use rayon::prelude::*;

mod rough;
pub use rough::{
    FacetTable, MAX_RMS_SLOPE, RoughSurface, RoughView, rough_band_emissivity_table,
    rough_emissivity_table, smith_escape,
};

use irsig_model::interp;

use crate::band::Band;
use crate::emissivity::EmissivityTable;
use crate::error::{RadiometryError, RadiometryErrorKind};
use crate::planck_weights;

/// A complex refractive index `N = n + i k` (`n > 0`, `k ≥ 0`, both finite) of a medium
/// seen from vacuum or air.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ComplexIndex {
    n: f64,
    k: f64,
}

/// A pair of values for the two linear polarisations: `s` (electric field perpendicular to
/// the plane of incidence, TE) and `p` (parallel, TM).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Polarised {
    /// s (TE) polarisation.
    pub s: f64,
    /// p (TM) polarisation.
    pub p: f64,
}

impl Polarised {
    /// The unpolarised value, the mean of the two.
    #[must_use]
    pub fn mean(&self) -> f64 {
        0.5 * (self.s + self.p)
    }
}

impl ComplexIndex {
    /// `N = n + i k`.
    ///
    /// # Errors
    /// [`RadiometryErrorKind::InvalidRefractiveIndex`] unless `n` is finite and `> 0` and
    /// `k` is finite and `≥ 0` (NaN is neither). A negative `k` would be a gain medium,
    /// which Kirchhoff's law (ε = 1 − R) does not cover.
    pub fn new(n: f64, k: f64) -> Result<Self, RadiometryError> {
        if !(n.is_finite() && n > 0.0) {
            return Err(RadiometryError::new(
                RadiometryErrorKind::InvalidRefractiveIndex,
                format!("the real part n must be finite and > 0, found {n}"),
            ));
        }
        if !(k.is_finite() && k >= 0.0) {
            return Err(RadiometryError::new(
                RadiometryErrorKind::InvalidRefractiveIndex,
                format!("the extinction coefficient k must be finite and ≥ 0, found {k}"),
            ));
        }
        Ok(Self { n, k })
    }

    /// The real part `n`.
    #[must_use]
    pub fn n(&self) -> f64 {
        self.n
    }

    /// The extinction coefficient `k`.
    #[must_use]
    pub fn k(&self) -> f64 {
        self.k
    }

    /// The `(a, b)` pairs of `r = (a − b)/(a + b)` for s and p at `angle_deg` (< 90°),
    /// each pair scaled so its largest component is 1 (the ratios are homogeneous of
    /// degree 0 in `(a, b)`, and `hypot` then cannot overflow).
    fn coefficient_pairs(&self, angle_deg: f64) -> [(Complex64, Complex64); 2] {
        self.unscaled_pairs(angle_deg).map(|(a, b)| {
            let m = a.re.abs().max(a.im.abs()).max(b.re.abs()).max(b.im.abs());
            if m > 0.0 && m.is_finite() {
                (a / m, b / m)
            } else {
                (a, b)
            }
        })
    }

    fn unscaled_pairs(&self, angle_deg: f64) -> [(Complex64, Complex64); 2] {
        let theta = angle_deg.abs().to_radians();
        let (s, c) = theta.sin_cos();
        let big_n = Complex64::new(self.n, self.k);
        if self.n.hypot(self.k) <= 1.0 {
            // |N| ≤ 1: N² cannot overflow; r = sqrt(N² − s²), principal branch (Im N² ≥ 0,
            // so the square root lands in the first quadrant, as the physics needs).
            let n2 = big_n * big_n;
            let r = (n2 - s * s).sqrt();
            [(Complex64::new(c, 0.0), r), (n2 * c, r)]
        } else {
            // |N| > 1: divide through by N; 1/N scaled so |N|² never overflows.
            let m = self.n.max(self.k);
            let scaled = big_n / m;
            let inv_n = scaled.conj() / (scaled.norm_sqr() * m);
            let sn = inv_n * s;
            let u = (Complex64::new(1.0, 0.0) - sn * sn).sqrt();
            [(inv_n * c, u), (big_n * c, u)]
        }
    }

    /// Power reflectances `R_s = |r_s|²`, `R_p = |r_p|²` at `angle_deg` from the normal.
    /// The angle is read as its magnitude; 90° or more (grazing) gives 1 for both; NaN
    /// gives NaN.
    #[must_use]
    pub fn reflectance(&self, angle_deg: f64) -> Polarised {
        if angle_deg.is_nan() {
            return Polarised {
                s: f64::NAN,
                p: f64::NAN,
            };
        }
        if angle_deg.abs() >= 90.0 {
            return Polarised { s: 1.0, p: 1.0 };
        }
        let [s_pair, p_pair] = self.coefficient_pairs(angle_deg);
        let ratio = |(a, b): (Complex64, Complex64)| {
            let d = a + b;
            let den = d.re.hypot(d.im);
            if den.is_nan() || den <= 0.0 {
                // Both terms underflowed (|N| below ~1e-154 at normal incidence): the
                // limit N → 0 is a perfect reflector.
                return 1.0;
            }
            let e = a - b;
            let q = e.re.hypot(e.im) / den;
            (q * q).clamp(0.0, 1.0)
        };
        Polarised {
            s: ratio(s_pair),
            p: ratio(p_pair),
        }
    }

    /// Directional emissivities `ε_s = 1 − R_s`, `ε_p = 1 − R_p` at `angle_deg`, computed
    /// as `4 Re(a b̄)/|a + b|²` so they keep their relative accuracy when `R → 1`. The angle
    /// is read as its magnitude; 90° or more gives 0; NaN gives NaN.
    #[must_use]
    pub fn polarised_emissivity(&self, angle_deg: f64) -> Polarised {
        if angle_deg.is_nan() {
            return Polarised {
                s: f64::NAN,
                p: f64::NAN,
            };
        }
        if angle_deg.abs() >= 90.0 {
            return Polarised { s: 0.0, p: 0.0 };
        }
        let [s_pair, p_pair] = self.coefficient_pairs(angle_deg);
        let emissivity = |(a, b): (Complex64, Complex64)| {
            let d = a + b;
            let den = d.re.hypot(d.im);
            if den.is_nan() || den <= 0.0 {
                return 0.0;
            }
            // 4 Re(a b̄) / |a + b|², each factor divided by |a + b| first so no product
            // overflows.
            let cross = (a.re / den) * b.re + (a.im / den) * b.im;
            (4.0 * cross / den).clamp(0.0, 1.0)
        };
        Polarised {
            s: emissivity(s_pair),
            p: emissivity(p_pair),
        }
    }

    /// Unpolarised directional emissivity `ε(θ) = 1 − (R_s + R_p)/2` at `angle_deg`.
    #[must_use]
    pub fn emissivity(&self, angle_deg: f64) -> f64 {
        self.polarised_emissivity(angle_deg).mean()
    }
}

/// The complex refractive index against wavelength: `n` and `k` tabulated at increasing
/// wavelengths (µm), each interpolated linearly between them (as the Hale & Querry (1973)
/// tables are customarily used).
#[derive(Debug, Clone, PartialEq)]
pub struct IndexTable {
    wavelength_um: Vec<f64>,
    index: Vec<ComplexIndex>,
}

impl IndexTable {
    /// A table from matching columns.
    ///
    /// # Errors
    /// [`RadiometryErrorKind::InvalidRefractiveIndex`] for columns of different lengths,
    /// fewer than 2 rows, a wavelength that is not finite and positive or does not
    /// increase, or an invalid `n` or `k` (see [`ComplexIndex::new`]); the message names
    /// the row (1-based).
    pub fn new(wavelength_um: Vec<f64>, n: &[f64], k: &[f64]) -> Result<Self, RadiometryError> {
        let bad = |m: String| {
            Err(RadiometryError::new(
                RadiometryErrorKind::InvalidRefractiveIndex,
                m,
            ))
        };
        if wavelength_um.len() != n.len() || n.len() != k.len() {
            return bad(format!(
                "{} wavelengths, {} values of n and {} of k: the columns must match",
                wavelength_um.len(),
                n.len(),
                k.len()
            ));
        }
        if wavelength_um.len() < 2 {
            return bad(format!(
                "a wavelength table needs at least 2 rows, found {}",
                wavelength_um.len()
            ));
        }
        let mut index = Vec::with_capacity(n.len());
        for (i, ((&w, &n), &k)) in wavelength_um.iter().zip(n).zip(k).enumerate() {
            if !(w.is_finite() && w > 0.0) {
                return bad(format!(
                    "row {}: the wavelength must be a positive number of µm, found {w}",
                    i + 1
                ));
            }
            let one = ComplexIndex::new(n, k).map_err(|e| {
                RadiometryError::new(e.kind, format!("row {} ({w} µm): {}", i + 1, e.message))
            })?;
            index.push(one);
        }
        for (i, pair) in wavelength_um.windows(2).enumerate() {
            let &[a, b] = pair else { continue };
            if b <= a {
                return bad(format!(
                    "wavelengths must increase: row {} ({b} µm) follows {a} µm",
                    i + 2
                ));
            }
        }
        Ok(Self {
            wavelength_um,
            index,
        })
    }

    /// The tabulated wavelengths, µm.
    #[must_use]
    pub fn wavelength_um(&self) -> &[f64] {
        &self.wavelength_um
    }

    /// The tabulated indices.
    #[must_use]
    pub fn index(&self) -> &[ComplexIndex] {
        &self.index
    }

    /// `N` at `wavelength_um`, `n` and `k` each linearly interpolated; held at the end
    /// values outside the table (the band averaging refuses such wavelengths before it
    /// gets here).
    #[must_use]
    pub fn at(&self, wavelength_um: f64) -> ComplexIndex {
        let (i, f) = interp::locate(&self.wavelength_um, wavelength_um);
        let (a, b) = (self.index[i], self.index[i + 1]);
        // Convex combinations of valid values stay valid: n > 0, k ≥ 0.
        ComplexIndex {
            n: interp::lerp(a.n, b.n, f),
            k: interp::lerp(a.k, b.k, f),
        }
    }
}

/// The angular emissivity table of a smooth opaque surface of constant index `index`, at
/// the given angles (deg from the normal, 0–90, strictly increasing).
///
/// ```
/// use irsig_radiometry::fresnel::{ComplexIndex, emissivity_table};
/// let glass = ComplexIndex::new(1.5, 0.0)?;
/// let table = emissivity_table(glass, &[0.0, 45.0, 90.0])?;
/// // Normal incidence: 1 − ((n − 1)/(n + 1))² = 0.96.
/// assert!((table.emissivity()[0] - 0.96).abs() < 1e-15);
/// assert_eq!(table.emissivity()[2], 0.0);
/// # Ok::<(), irsig_radiometry::RadiometryError>(())
/// ```
///
/// # Errors
/// [`RadiometryErrorKind::InvalidEmissivity`] for an empty angle list or angles outside
/// 0–90° or not increasing.
pub fn emissivity_table(
    index: ComplexIndex,
    angles_deg: &[f64],
) -> Result<EmissivityTable, RadiometryError> {
    check_angles(angles_deg)?;
    let values = angles_deg.iter().map(|&a| index.emissivity(a)).collect();
    EmissivityTable::new(angles_deg.to_vec(), values)
}

/// The band-averaged angular emissivity table of a smooth opaque surface whose index
/// varies with wavelength:
///
/// ```text
/// ε(θ) = ∫ ε(λ, θ) S(λ) B_λ(λ, T) dλ / ∫ S(λ) B_λ(λ, T) dλ   over the band,
/// ```
///
/// with `S` the band's sensor response (1 when it has none) and `B_λ` the Planck spectral
/// radiance at `temperature_k`. This is the emissivity whose product with the band
/// radiance `L(T)` gives exactly the band radiance the surface emits at `T`, which is how
/// the tracer uses it; it is exact at that temperature only (for water the 280 K and
/// 320 K weightings differ by ±0.0002 near the normal, ±0.0015 at 80°; reference README).
///
/// The integral is Gauss–Legendre, 8 nodes on each piece between consecutive breakpoints
/// (band limits, the table's wavelengths, the response's wavelengths), pieces split to at
/// most 0.25 µm: the integrand is smooth on each piece (`n`, `k` and `S` are linear there),
/// so the rule converges fast (checked against a 0.0005 µm trapezoid rule in the tests). A
/// table of more than about a thousand rows over the band has its breakpoints thinned to
/// 1,024 pieces (`planck_weights`), so that a million rows cost what a thousand do.
///
/// # Errors
/// - [`RadiometryErrorKind::InvalidTemperature`] unless `temperature_k` is within
///   [`irsig_model::limits::PLANCK_WEIGHTING_K`].
/// - [`RadiometryErrorKind::InvalidRefractiveIndex`] when the table does not cover the
///   part of the band where the response is not zero (no extrapolation).
/// - [`RadiometryErrorKind::InvalidEmissivity`] for bad angles (see [`emissivity_table`]).
pub fn band_emissivity_table(
    table: &IndexTable,
    band: &Band,
    temperature_k: f64,
    angles_deg: &[f64],
) -> Result<EmissivityTable, RadiometryError> {
    check_angles(angles_deg)?;
    let nodes = spectral_nodes(table, band, temperature_k)?;
    let total: f64 = nodes.iter().map(|n| n.weight).sum();
    // One angle per task; each angle's sum runs over the nodes in order, so the table is
    // the same bit for bit at any thread count.
    let values = angles_deg
        .par_iter()
        .map(|&a| {
            let sum: f64 = nodes
                .iter()
                .map(|node| node.weight * node.index.emissivity(a))
                .sum();
            (sum / total).clamp(0.0, 1.0)
        })
        .collect();
    EmissivityTable::new(angles_deg.to_vec(), values)
}

/// The Planck- (and response-) weighted mean of `n` and of `k` over the band: the single
/// index a user might be tempted to use instead of [`band_emissivity_table`]. Exposed so
/// that the error of doing so can be measured (`docs/accuracy.md`).
///
/// # Errors
/// As [`band_emissivity_table`].
pub fn band_mean_index(
    table: &IndexTable,
    band: &Band,
    temperature_k: f64,
) -> Result<ComplexIndex, RadiometryError> {
    let nodes = spectral_nodes(table, band, temperature_k)?;
    let total: f64 = nodes.iter().map(|n| n.weight).sum();
    let n = nodes.iter().map(|x| x.weight * x.index.n).sum::<f64>() / total;
    let k = nodes.iter().map(|x| x.weight * x.index.k).sum::<f64>() / total;
    ComplexIndex::new(n, k)
}

fn check_angles(angles_deg: &[f64]) -> Result<(), RadiometryError> {
    // EmissivityTable::new checks the same rules; checking here first keeps a bad angle
    // list from costing a spectral integral, and names angles rather than table rows.
    let bad = |m: String| {
        Err(RadiometryError::new(
            RadiometryErrorKind::InvalidEmissivity,
            m,
        ))
    };
    if angles_deg.is_empty() {
        return bad("no angles given".to_owned());
    }
    for (i, &a) in angles_deg.iter().enumerate() {
        if !(0.0..=90.0).contains(&a) {
            return bad(format!("angle {}: must be 0–90 deg, found {a}", i + 1));
        }
    }
    for pair in angles_deg.windows(2) {
        let &[a, b] = pair else { continue };
        if b <= a {
            return bad(format!("angles must increase: {b} deg follows {a} deg"));
        }
    }
    Ok(())
}

/// One wavelength of the spectral integral: its weight (see [`crate::planck_weights`])
/// and the index there.
struct SpectralNode {
    weight: f64,
    index: ComplexIndex,
}

fn spectral_nodes(
    table: &IndexTable,
    band: &Band,
    temperature_k: f64,
) -> Result<Vec<SpectralNode>, RadiometryError> {
    let nodes = planck_weights::nodes(band, temperature_k, &table.wavelength_um, |lo, hi| {
        let (Some(&t_first), Some(&t_last)) =
            (table.wavelength_um.first(), table.wavelength_um.last())
        else {
            return Err(RadiometryError::new(
                RadiometryErrorKind::InvalidRefractiveIndex,
                "the index table is empty",
            ));
        };
        if t_first > lo || t_last < hi {
            return Err(RadiometryError::new(
                RadiometryErrorKind::InvalidRefractiveIndex,
                format!(
                    "the index table covers {t_first}–{t_last} µm but the band needs {lo}–{hi} \
                     µm; extend the table (it is not extrapolated)"
                ),
            ));
        }
        Ok(())
    })?;
    Ok(nodes
        .into_iter()
        .map(|n| SpectralNode {
            weight: n.weight,
            index: table.at(n.wavelength_um),
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn both_branches_agree_where_they_meet() {
        // |N| just below and above 1 take different algebra; the physics is continuous.
        let below = ComplexIndex::new(0.6, 0.799_999_999).unwrap();
        let above = ComplexIndex::new(0.6, 0.800_000_001).unwrap();
        for a in [0.0, 30.0, 60.0, 85.0, 89.9] {
            let (x, y) = (below.polarised_emissivity(a), above.polarised_emissivity(a));
            assert!((x.s - y.s).abs() < 1e-8 && (x.p - y.p).abs() < 1e-8, "{a}");
        }
    }

    #[test]
    fn interpolation_is_linear_in_n_and_k() {
        let t = IndexTable::new(vec![8.0, 10.0], &[1.2, 1.4], &[0.0, 0.2]).unwrap();
        let m = t.at(9.5);
        assert!((m.n() - 1.35).abs() < 1e-15 && (m.k() - 0.15).abs() < 1e-15);
    }
}
