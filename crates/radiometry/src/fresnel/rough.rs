//! Directional emissivity of a rough dielectric: Fresnel facets with Gaussian slopes.
//!
//! The surface is a random field of smooth facets whose slopes `(z_x, z_y)` are Gaussian,
//! isotropic, of mean-square slope `σ² = ⟨z_x² + z_y²⟩` (Cox & Munk 1954's parameter; each
//! component has variance `σ²/2`). Seen from a direction `v` at `θ` from the mean normal, a
//! facet of slope `z` and normal `n` fills a share of the view proportional to its
//! projected area `(cos θ − z·v_h) P(z)` (zero where it faces away), and its emissivity is
//! Fresnel's at its local angle `χ`, `cos χ = n·v`: the facet model of Masuda, Takashima &
//! Takayama (1988, *Remote Sens. Environ.* 24, 313). Masking of the view by other facets
//! follows Smith (1967, *IEEE Trans. Antennas Propag.* 15, 668): in his uncorrelated form
//! it removes the same share of every facet, so it drops out of the average once the
//! average is taken over the visible projected area, which is how it is taken here (the
//! normalisation that keeps ε ≤ 1 at grazing views, where Masuda's `1/cos θ` does not).
//! What a facet reflects comes from the sky only where the reflected ray escapes the
//! surface, with Smith's probability `1/(1 + Λ(θ_r))` (0 for a ray reflected downward);
//! the rest meets another facet, taken as black: one reflection, as Wu & Smith (1997,
//! *Appl. Opt.* 36, 2609) add it to Masuda's model. So
//!
//! ```text
//! ε(θ) = ⟨ ε_f(χ) + (1 − ε_f(χ)) (1 − S(θ_r)) ⟩_visible,
//! S(θ_r) = 1 / (1 + Λ(ν)),  Λ(ν) = ½ (e^(−ν²)/(ν √π) − erfc ν),  ν = cot θ_r / σ.
//! ```
//!
//! A body that scatters what the interface lets in (a soil's grains, a canopy's leaves,
//! paint's pigment) returns a share `ρ_d` of it diffusely: the specular microfacet lobe
//! over a Lambertian body of Torrance & Sparrow (1967, *J. Opt. Soc. Am.* 57, 1105) and
//! Cook & Torrance (1982, *ACM Trans. Graph.* 1, 7), which makes the emissivity
//! `(1 − ρ_d) ε(θ)`, a loss that does not depend on angle. `ρ_d = 0` (the default) is a
//! bulk dielectric such as water.
//!
//! `σ = 0` and `ρ_d = 0` is the smooth surface (Fresnel's table exactly). The operator is linear in the
//! facet emissivity `ε_f(χ)`, so the band average of the rough surface is the rough
//! average of the band-averaged smooth facet ([`rough_band_emissivity_table`]). The
//! black second facet overstates ε by at most `(1 − ε_f)²` of the blocked share (≤ 0.002
//! for a facet of ε_f ≥ 0.95).
//!
//! The average is a product rule in polar slope coordinates: the slope magnitude `x = |z|/σ`
//! (weight `2x e^(−x²)`) by Gauss–Legendre on `[0, x₀]` and `[x₀, 6.5]`, split at
//! `x₀ = cot θ / σ` where facets start to face away, and the azimuth by Gauss–Legendre
//! over the visible arc only, so that no node straddles the horizon of a facet.

use crate::band::{Band, gauss_legendre};
use crate::emissivity::EmissivityTable;
use crate::error::{RadiometryError, RadiometryErrorKind};

use super::{ComplexIndex, IndexTable, band_emissivity_table, check_angles};

/// The largest RMS slope accepted: a mean facet tilt of 84° (the model's limit, which a
/// material's `rms_slope` is held to as well).
pub use irsig_model::limits::MAX_RMS_SLOPE;

/// Slope magnitudes beyond this many σ carry less than e^(−42) of the surface.
const X_MAX: f64 = 6.5;

/// Nodes per piece of the slope-magnitude rule and of the azimuth rule.
const RADIAL_NODES: usize = 32;
const AZIMUTH_NODES: usize = 32;

/// A rough surface: isotropic Gaussian facet slopes of RMS slope `σ`
/// (`σ² = ⟨z_x² + z_y²⟩`, dimensionless: the tangent of the facets' tilt; 0 is smooth).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RoughSurface {
    rms_slope: f64,
    diffuse_reflectance: f64,
}

/// One facet class of the view average: its share of the visible projected area, its
/// local angle of emission (deg) and the probability that its reflected ray escapes.
#[derive(Debug, Clone, Copy)]
struct Facet {
    weight: f64,
    local_deg: f64,
    escape: f64,
}

impl RoughSurface {
    /// A surface of RMS slope `rms_slope` (dimensionless, `0 ≤ σ ≤` [`MAX_RMS_SLOPE`]).
    ///
    /// # Errors
    /// [`RadiometryErrorKind::InvalidParameter`] for a slope that is not finite, negative
    /// or above [`MAX_RMS_SLOPE`].
    pub fn new(rms_slope: f64) -> Result<Self, RadiometryError> {
        if !(rms_slope.is_finite() && (0.0..=MAX_RMS_SLOPE).contains(&rms_slope)) {
            return Err(RadiometryError::new(
                RadiometryErrorKind::InvalidParameter,
                format!(
                    "the RMS slope must be a number from 0 (smooth) to {MAX_RMS_SLOPE}, found {rms_slope}"
                ),
            ));
        }
        Ok(Self {
            rms_slope,
            diffuse_reflectance: 0.0,
        })
    }

    /// The same surface over a body that returns the share `diffuse_reflectance` (0 to
    /// below 1) of what enters it diffusely: its emissivity is `1 − ρ_d` times the
    /// interface's.
    ///
    /// # Errors
    /// [`RadiometryErrorKind::InvalidParameter`] for a share that is not finite or lies
    /// outside [0, 1).
    pub fn with_diffuse_reflectance(
        self,
        diffuse_reflectance: f64,
    ) -> Result<Self, RadiometryError> {
        if !(diffuse_reflectance.is_finite() && (0.0..1.0).contains(&diffuse_reflectance)) {
            return Err(RadiometryError::new(
                RadiometryErrorKind::InvalidParameter,
                format!(
                    "the diffuse reflectance must be a number from 0 to below 1, found {diffuse_reflectance}"
                ),
            ));
        }
        Ok(Self {
            diffuse_reflectance,
            ..self
        })
    }

    /// The RMS slope `σ`.
    #[must_use]
    pub fn rms_slope(&self) -> f64 {
        self.rms_slope
    }

    /// The diffuse reflectance `ρ_d` of the body under the facets.
    #[must_use]
    pub fn diffuse_reflectance(&self) -> f64 {
        self.diffuse_reflectance
    }

    /// The directional emissivity seen at `view_deg` from the mean normal (0–90°) of a
    /// surface whose facets have the smooth emissivity `facet(χ)` at local angle `χ` (deg,
    /// 0–90), times `1 − ρ_d`. A smooth surface with no diffuse body returns
    /// `facet(view_deg)`; NaN gives NaN.
    #[must_use]
    pub fn emissivity_with(&self, view_deg: f64, facet: impl Fn(f64) -> f64) -> f64 {
        self.view(view_deg).emissivity_with(facet)
    }

    /// The directional emissivity at `view_deg` of facets of constant index `index`.
    #[must_use]
    pub fn emissivity(&self, index: ComplexIndex, view_deg: f64) -> f64 {
        self.emissivity_with(view_deg, |chi| index.emissivity(chi))
    }

    /// The surface seen at `view_deg`, its facet classes found once: what a spectrum of
    /// many indices seen from one angle shares ([`RoughView::emissivity`] gives what
    /// [`Self::emissivity`] gives, bit for bit).
    #[must_use]
    pub fn view(&self, view_deg: f64) -> RoughView {
        let view = view_deg.abs().min(90.0);
        let facets = if view_deg.is_nan() || self.rms_slope == 0.0 {
            Vec::new()
        } else {
            self.facets(view)
        };
        RoughView {
            surface: *self,
            view_deg: if view_deg.is_nan() { f64::NAN } else { view },
            facets,
        }
    }

    /// The facet classes of the view at `view_deg` (0–90°), weights summing to 1.
    fn facets(&self, view_deg: f64) -> Vec<Facet> {
        let sigma = self.rms_slope;
        let theta = view_deg.to_radians();
        let (sin_t, cos_t) = theta.sin_cos();
        // Facets steeper than cot θ can face away from the view.
        let x0 = if sin_t > 0.0 {
            (cos_t / sin_t / sigma).min(X_MAX)
        } else {
            X_MAX
        };
        let rule = gauss_legendre(RADIAL_NODES);
        let arc = gauss_legendre(AZIMUTH_NODES);
        let mut out = Vec::with_capacity(2 * RADIAL_NODES * AZIMUTH_NODES);
        let mut total = 0.0;
        for (a, b) in [(0.0, x0), (x0, X_MAX)] {
            if b <= a {
                continue;
            }
            let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
            for &(u, wu) in &rule {
                let x = mid + half * u;
                let t = sigma * x;
                // Slope-magnitude density 2x e^(−x²) (Rayleigh in x).
                let radial = half * wu * 2.0 * x * (-x * x).exp();
                // Visible azimuths (relative to the view's): cos φ < cot θ / t.
                let phi_min = if t * sin_t <= cos_t {
                    0.0
                } else {
                    (cos_t / (t * sin_t)).clamp(-1.0, 1.0).acos()
                };
                let (pm, ph) = (
                    0.5 * (phi_min + std::f64::consts::PI),
                    0.5 * (std::f64::consts::PI - phi_min),
                );
                let norm = (1.0 + t * t).sqrt();
                for &(v, wv) in &arc {
                    let phi = pm + ph * v;
                    // Projected area per unit horizontal area: cos θ − z·v_h.
                    let projected = cos_t - t * sin_t * phi.cos();
                    if projected <= 0.0 {
                        continue;
                    }
                    let weight = radial * ph * wv * projected;
                    let cos_local = (projected / norm).min(1.0);
                    // Reflected ray r = 2(n·v)n − v; its cosine from the mean normal.
                    let cos_reflected = 2.0 * cos_local / norm - cos_t;
                    let escape = smith_escape(cos_reflected, sigma);
                    out.push(Facet {
                        weight,
                        local_deg: cos_local.acos().to_degrees(),
                        escape,
                    });
                    total += weight;
                }
            }
        }
        if total > 0.0 {
            for f in &mut out {
                f.weight /= total;
            }
        }
        out
    }
}

/// Smith's (1967) probability that a ray leaving the surface at `cos θ_r` from the mean
/// normal is not blocked by the surface, for Gaussian slopes of RMS slope `sigma > 0`:
/// `1/(1 + Λ(ν))`, `ν = cot θ_r / σ`; 0 for a ray going down. Also the shadowing of the
/// tracer's specular lobe (`irsig_tracer`'s sun glint), so that both describe one surface.
#[must_use]
pub fn smith_escape(cos_reflected: f64, sigma: f64) -> f64 {
    if cos_reflected <= 0.0 {
        return 0.0;
    }
    if cos_reflected >= 1.0 {
        return 1.0;
    }
    let sin_r = (1.0 - cos_reflected * cos_reflected).sqrt();
    let nu = cos_reflected / sin_r / sigma;
    // Λ(ν) falls as e^(−ν²)/ν³: nothing is blocked past ν = 26.
    if nu > 26.0 {
        return 1.0;
    }
    let lambda = 0.5 * ((-nu * nu).exp() / (nu * std::f64::consts::PI.sqrt()) - libm::erfc(nu));
    1.0 / (1.0 + lambda.max(0.0))
}

/// The angular emissivity table of a rough surface of constant facet index `index`.
///
/// # Errors
/// As [`super::emissivity_table`].
pub fn rough_emissivity_table(
    index: ComplexIndex,
    surface: RoughSurface,
    angles_deg: &[f64],
) -> Result<EmissivityTable, RadiometryError> {
    check_angles(angles_deg)?;
    let values = angles_deg
        .iter()
        .map(|&a| surface.emissivity(index, a))
        .collect();
    EmissivityTable::new(angles_deg.to_vec(), values)
}

/// A rough surface seen from one angle ([`RoughSurface::view`]).
#[derive(Debug, Clone)]
pub struct RoughView {
    surface: RoughSurface,
    /// 0–90°, or NaN.
    view_deg: f64,
    /// Empty for a smooth surface.
    facets: Vec<Facet>,
}

impl RoughView {
    /// As [`RoughSurface::emissivity_with`] at this view.
    #[must_use]
    pub fn emissivity_with(&self, facet: impl Fn(f64) -> f64) -> f64 {
        if self.view_deg.is_nan() {
            return f64::NAN;
        }
        let interface = if self.surface.rms_slope == 0.0 {
            facet(self.view_deg).clamp(0.0, 1.0)
        } else {
            self.facets
                .iter()
                .map(|f| {
                    let e = facet(f.local_deg).clamp(0.0, 1.0);
                    f.weight * (e + (1.0 - e) * (1.0 - f.escape))
                })
                .sum::<f64>()
                .clamp(0.0, 1.0)
        };
        (1.0 - self.surface.diffuse_reflectance) * interface
    }

    /// As [`RoughSurface::emissivity`] at this view, each facet class's emissivity read
    /// from `table` (within 1e-6 of [`Self::emissivity`]).
    #[must_use]
    pub fn emissivity_from(&self, table: &FacetTable) -> f64 {
        self.emissivity_with(|chi| table.at(chi))
    }

    /// As [`RoughSurface::emissivity`] at this view.
    #[must_use]
    pub fn emissivity(&self, index: ComplexIndex) -> f64 {
        self.emissivity_with(|chi| index.emissivity(chi))
    }
}

/// Step (deg) of the band-averaged smooth facet table the rough average reads.
const FACET_STEP_DEG: f64 = 0.05;

/// Step (deg) of a [`FacetTable`]. Read by lines, 0.05° left 2e-6 near grazing on nearly
/// smooth water (σ 0.02 at 85°) and 0.01° still 1.6e-6 on a metal at 89.9°; read by cubics,
/// 0.05° is within 1e-7 on both (tested).
const FACET_TABLE_STEP_DEG: f64 = 0.05;

/// A smooth facet's emissivity of one index against its local angle, on a uniform
/// [`FACET_TABLE_STEP_DEG`] grid from 0° to 90°, read by cubic interpolation: a rough
/// surface's emissivities at many views then cost 1,801 Fresnel evaluations, not one per facet class
/// of every view (about a thousand each). The interpolation is within 1e-6 of the Fresnel
/// equations for the indices of the thermal infrared, dielectrics to metals, up to 89.9°
/// (tested: within 1e-7).
#[derive(Debug, Clone)]
pub struct FacetTable {
    values: Vec<f64>,
}

impl FacetTable {
    /// The table of `index`'s unpolarised emissivity.
    #[must_use]
    pub fn new(index: ComplexIndex) -> Self {
        let steps = (90.0 / FACET_TABLE_STEP_DEG).round() as usize;
        Self {
            values: (0..=steps)
                .map(|i| index.emissivity(i as f64 * FACET_TABLE_STEP_DEG))
                .collect(),
        }
    }

    /// The emissivity at `chi_deg` (its magnitude, 90° and beyond the last value; NaN
    /// gives NaN).
    #[must_use]
    pub fn at(&self, chi_deg: f64) -> f64 {
        if chi_deg.is_nan() {
            return f64::NAN;
        }
        let x = chi_deg.abs() / FACET_TABLE_STEP_DEG;
        let last = self.values.len() - 1;
        if x >= last as f64 {
            return self.values[last];
        }
        // Catmull-Rom cubic through the four nearest values (one-sided at the ends): its
        // error falls with the step's fourth power where a line's falls with its square.
        let i = x.floor() as usize;
        let f = x - i as f64;
        let v = &self.values;
        let (p1, p2) = (v[i], v[i + 1]);
        let p0 = if i > 0 { v[i - 1] } else { 2.0 * p1 - p2 };
        let p3 = if i + 2 <= last {
            v[i + 2]
        } else {
            2.0 * p2 - p1
        };
        let a = -0.5 * p0 + 1.5 * p1 - 1.5 * p2 + 0.5 * p3;
        let b = p0 - 2.5 * p1 + 2.0 * p2 - 0.5 * p3;
        let c = 0.5 * (p2 - p0);
        ((a * f + b) * f + c) * f + p1
    }
}

/// The band-averaged angular emissivity table of a rough surface whose facets have the
/// index table `table`: [`band_emissivity_table`] of the smooth facet on a 0.05° grid,
/// then the rough average of that (the average is linear in the facet emissivity, so
/// this is the band average of the rough surface; the grid's linear interpolation adds
/// under 1e-6).
///
/// # Errors
/// As [`band_emissivity_table`].
pub fn rough_band_emissivity_table(
    table: &IndexTable,
    band: &Band,
    temperature_k: f64,
    surface: RoughSurface,
    angles_deg: &[f64],
) -> Result<EmissivityTable, RadiometryError> {
    check_angles(angles_deg)?;
    let steps = (90.0 / FACET_STEP_DEG).round() as usize;
    let fine: Vec<f64> = (0..=steps).map(|i| i as f64 * FACET_STEP_DEG).collect();
    let smooth = band_emissivity_table(table, band, temperature_k, &fine)?;
    let values = angles_deg
        .iter()
        .map(|&a| surface.emissivity_with(a, |chi| smooth.at(chi)))
        .collect();
    EmissivityTable::new(angles_deg.to_vec(), values)
}

#[cfg(test)]
#[allow(clippy::float_cmp)] // exact limits (1, 0, the smooth table) are the point
mod tests {
    use super::*;

    #[test]
    fn weights_sum_to_one_and_the_smooth_limit_is_fresnel() {
        let glass = ComplexIndex::new(1.5, 0.0).unwrap();
        for sigma in [0.01, 0.3, 1.0, 5.0] {
            let s = RoughSurface::new(sigma).unwrap();
            for view in [0.0, 30.0, 60.0, 85.0, 90.0] {
                let sum: f64 = s.facets(view).iter().map(|f| f.weight).sum();
                assert!((sum - 1.0).abs() < 1e-12, "{sigma} {view}: {sum}");
            }
        }
        // A nearly smooth surface is Fresnel's, grazing excepted.
        let s = RoughSurface::new(1e-3).unwrap();
        for view in [0.0, 20.0, 45.0, 70.0, 80.0] {
            let (r, f) = (s.emissivity(glass, view), glass.emissivity(view));
            assert!((r - f).abs() < 2e-4, "{view}: {r} vs {f}");
        }
        let smooth = RoughSurface::new(0.0).unwrap();
        assert_eq!(smooth.emissivity(glass, 60.0), glass.emissivity(60.0));
    }

    #[test]
    fn smith_shadowing_has_its_limits() {
        // Straight up nothing is blocked, downward everything; Λ(ν) is Smith's closed
        // form: at ν = 1, ½(e^(−1)/√π − erfc 1) = 0.0264.
        assert_eq!(smith_escape(1.0, 0.5), 1.0);
        assert_eq!(smith_escape(-0.1, 0.5), 0.0);
        let cos_r = std::f64::consts::FRAC_1_SQRT_2; // cot θ_r = 1
        let lambda = 0.5 * ((-1.0_f64).exp() / std::f64::consts::PI.sqrt() - 0.157_299_207);
        assert!((smith_escape(cos_r, 1.0) - 1.0 / (1.0 + lambda)).abs() < 1e-8);
        // Grazing: Λ grows without bound.
        assert!(smith_escape(1e-6, 0.5) < 1e-4);
    }

    #[test]
    fn the_rule_has_converged() {
        // Against the same average with four times the nodes in each direction, done by
        // brute force on a fine grid of slopes (independent of the split rule).
        let glass = ComplexIndex::new(1.5, 0.0).unwrap();
        for sigma in [0.2, 0.7, 2.0] {
            let s = RoughSurface::new(sigma).unwrap();
            for view in [0.0, 40.0, 70.0, 85.0, 89.0] {
                let quad = s.emissivity(glass, view);
                let brute = brute_force(glass, sigma, view);
                assert!(
                    (quad - brute).abs() < 2e-4,
                    "σ {sigma} θ {view}: {quad} vs {brute}"
                );
            }
        }
    }

    /// The same average by the midpoint rule on a 1200 × 1200 grid of slopes (z_x, z_y)
    /// over ±6σ/√2 per component.
    fn brute_force(index: ComplexIndex, sigma: f64, view_deg: f64) -> f64 {
        let (sin_t, cos_t) = view_deg.to_radians().sin_cos();
        let n = 1200;
        let half = 6.0 * sigma / std::f64::consts::SQRT_2;
        let h = 2.0 * half / f64::from(n);
        let (mut num, mut den) = (0.0, 0.0);
        for i in 0..n {
            let zx = -half + (f64::from(i) + 0.5) * h;
            for j in 0..n {
                let zy = -half + (f64::from(j) + 0.5) * h;
                let p = (-(zx * zx + zy * zy) / (sigma * sigma)).exp();
                // View along +x: n ∝ (−z_x, −z_y, 1), v = (sin θ, 0, cos θ).
                let projected = cos_t - zx * sin_t;
                if projected <= 0.0 {
                    continue;
                }
                let norm = (1.0 + zx * zx + zy * zy).sqrt();
                let cos_local = (projected / norm).min(1.0);
                let e = index.emissivity(cos_local.acos().to_degrees());
                let escape = smith_escape(2.0 * cos_local / norm - cos_t, sigma);
                num += p * projected * (e + (1.0 - e) * (1.0 - escape));
                den += p * projected;
            }
        }
        num / den
    }

    #[test]
    fn a_facet_table_gives_the_rough_emissivity_within_a_millionth() {
        // Water, glass, a strong absorber, a metal, and an index below 1.
        let indices = [
            (1.2, 0.05),
            (1.5, 0.0),
            (2.4, 1.6),
            (12.0, 40.0),
            (0.6, 0.3),
        ];
        for (n, k) in indices {
            let index = ComplexIndex::new(n, k).unwrap();
            let table = FacetTable::new(index);
            for sigma in [0.02, 0.105, 0.5, 2.0] {
                let surface = RoughSurface::new(sigma).unwrap();
                for view in [0.0, 30.0, 60.0, 75.0, 85.0, 89.0, 89.9, 90.0] {
                    let v = surface.view(view);
                    let (direct, read) = (v.emissivity(index), v.emissivity_from(&table));
                    assert!(
                        (direct - read).abs() < 1e-6,
                        "N = {n} + {k}i, sigma {sigma}, {view} deg: {direct} against {read}"
                    );
                }
            }
            assert!(table.at(f64::NAN).is_nan());
            assert_eq!(table.at(90.0), table.at(120.0));
            assert_eq!(table.at(0.0), index.emissivity(0.0));
        }
    }

    #[test]
    fn bad_slopes_are_refused() {
        for s in [-0.1, f64::NAN, f64::INFINITY, 10.5] {
            let e = RoughSurface::new(s).unwrap_err();
            assert_eq!(e.kind, RadiometryErrorKind::InvalidParameter);
        }
        let s = RoughSurface::new(0.3).unwrap();
        for r in [-0.01, 1.0, f64::NAN] {
            assert!(s.with_diffuse_reflectance(r).is_err());
        }
        // The diffuse body scales every angle alike.
        let glass = ComplexIndex::new(1.5, 0.0).unwrap();
        let body = s.with_diffuse_reflectance(0.04).unwrap();
        for a in [0.0, 50.0, 85.0] {
            assert!((body.emissivity(glass, a) - 0.96 * s.emissivity(glass, a)).abs() < 1e-15);
        }
    }
}
