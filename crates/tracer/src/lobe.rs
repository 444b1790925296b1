//! The specular lobe of a rough surface, for the sun's glint ([`crate::sun`]).
//!
//! A material with an RMS facet slope `σ > 0` (`Material::rms_slope`) reflects the sun's
//! disk through a Cook–Torrance specular BRDF (Cook & Torrance 1982, *ACM Trans. Graph.*
//! 1, 7) with the Beckmann distribution of isotropic Gaussian slopes, `σ² = ⟨z_x² + z_y²⟩`
//! (the slopes of the rough-surface emissivity, `irsig_radiometry::fresnel::RoughSurface`),
//! and Smith's uncorrelated shadowing `G = S(θ_i)·S(θ_o)` (the same `S`,
//! `irsig_radiometry::fresnel::smith_escape`):
//!
//! ```text
//! f(i, o) = s·r(θ_o) · D(h) G(i, o) / (4 cos θ_i cos θ_o) / A(θ_o),
//! A(θ_o)  = ∫ D(h) G(i, o) / (4 cos θ_i cos θ_o) cos θ_i dω_i,
//! ```
//!
//! the Fresnel factor of Cook–Torrance replaced by the scale `s·r(θ_o)/A(θ_o)`, so that the
//! lobe's directional-hemispherical reflectance at the viewing angle is the specular share
//! `s·r(θ_o)` of the material's table, `r = 1 − ε(θ_o)`, whatever the table: energy stays
//! consistent with the emissivity. `A(θ_o)` is the unscaled lobe's albedo, tabulated once
//! per material every 1° of `θ_o` and interpolated linearly. The price is reciprocity:
//! `f(i, o) ≠ f(o, i)` where `r(θ)/A(θ)` differs between the two angles, and so the
//! radiance reflected into all views of a beam at `θ_i` is `s·r·E·cos θ_i` only to the
//! extent that `A(θ_o)` is `A(θ_i)` over the lobe (docs/accuracy.md, "The specular lobe").
//!
//! The glint is the lobe integrated over the sun's disk (a uniform disk of solid angle
//! `Ω`), per unit of the beam's normal irradiance, `(1/Ω)∫_disk f cos θ_i dω_i`. In facet
//! slopes `p` (the slope of the half vector `h` of `i` and `o`) this is
//! `(1/Ω)∫_R P(p) W(p) d²p`, with `P(p) = e^(−|p|²/σ²)/(πσ²)` and the smooth weight
//! `W = G·(h·o)/(cos θ_h cos θ_o)`, over the region `R` of slopes that reflect the disk
//! into `o`: an ellipse (the disk's affine image, from its centre and four rim points;
//! its error is of order `α²`, 2e-5 for the sun's `α`). The rule is polar about the
//! slopes' peak `p = 0` with `u = e^(−ρ²/σ²)`, which makes `P(p) d²p = du dψ/2π`: the
//! Gaussian is integrated exactly and only `W` is sampled, [`DISK_U_NODES`]
//! Gauss–Legendre nodes in `u` between each ray's entry and exit of `R` times
//! [`DISK_PSI_NODES`] ray directions `ψ` (the trapezoid rule round the whole circle when
//! the peak is inside `R`, Gauss–Legendre in `sin` of the angle across `R`'s span when it
//! is outside). No randomness: a hit's glint is a fixed function of its geometry. As
//! `σ → 0` the rule gives `1/Ω` exactly where the mirror direction lies in the disk and 0
//! outside it (today's mirror glint), and for `σ ≫ α` the point sun `f(c, o) cos θ_c`.

use irsig_radiometry::fresnel::smith_escape;
use irsig_radiometry::gauss_legendre;

use crate::sun::SunGeometry;
use glam::DVec3;

/// Ray directions `ψ` of the disk rule (docs/accuracy.md, "The specular lobe").
pub const DISK_PSI_NODES: usize = 12;
/// Gauss–Legendre nodes in `u` along each ray of the disk rule.
pub const DISK_U_NODES: usize = 3;
/// Degrees of `θ_o` between the albedo table's rows.
const ALBEDO_STEP_DEG: f64 = 1.0;
/// Gauss–Legendre nodes per dimension (`u`, and `ψ` over a half circle) of the albedo.
const ALBEDO_NODES: usize = 64;
/// Views closer to the facet's plane than this cosine see no glint.
const MIN_COS_VIEW: f64 = 1e-6;
/// Slopes further than this many `σ` from the peak carry less than e^(−42) of it.
const FAR_SIGMAS: f64 = 6.5;

/// A material's specular lobe: its RMS slope and the unscaled lobe's albedo table.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Lobe {
    sigma: f64,
    /// `A(θ_o)` at `θ_o = k·ALBEDO_STEP_DEG`, k = 0 to 90, made on the first glint that
    /// needs it: 91 rows of a 64 × 64 rule cost tens of milliseconds per material, which a
    /// trace without a sun, or whose sun never meets the material, should not pay (a
    /// library of many rough materials would add them all to every trace).
    albedo: std::sync::OnceLock<Vec<f64>>,
    /// The disk rule's Gauss–Legendre nodes in `ψ` and in `u`, made once.
    psi_rule: Vec<(f64, f64)>,
    u_rule: Vec<(f64, f64)>,
}

/// A facet's frame: its normal (toward the viewer), two tangents, and the view.
struct Frame {
    n: DVec3,
    e1: DVec3,
    e2: DVec3,
    o: DVec3,
    cos_o: f64,
    /// `S(θ_o)/cos θ_o`.
    view_factor: f64,
}

impl Frame {
    fn new(n: DVec3, o: DVec3, sigma: f64) -> Self {
        let (e1, e2) = n.any_orthonormal_pair();
        let cos_o = n.dot(o).min(1.0);
        Self {
            n,
            e1,
            e2,
            o,
            cos_o,
            view_factor: smith_escape(cos_o, sigma) / cos_o,
        }
    }

    /// The slope of the half vector of the unit direction `w` and the view, or `None` where
    /// it does not face the normal.
    fn slope_of(&self, w: DVec3) -> Option<[f64; 2]> {
        let h = w + self.o;
        let hn = h.dot(self.n);
        if hn.is_nan() || hn <= 1e-12 * h.dot(h).sqrt() {
            return None;
        }
        Some([h.dot(self.e1) / hn, h.dot(self.e2) / hn])
    }

    /// `W(p) = G·(h·o)/(cos θ_h cos θ_o)`: what the lobe weighs the slope `p` by beside its
    /// Gaussian density (0 where the facet turns from the view or reflects below the mean
    /// surface).
    fn weight(&self, p: [f64; 2], sigma: f64) -> f64 {
        let h = (self.n + (self.e1 * p[0] + self.e2 * p[1])).normalize();
        let ho = h.dot(self.o);
        if ho <= 0.0 {
            return 0.0;
        }
        let i = h * (2.0 * ho) - self.o;
        let cos_i = i.dot(self.n);
        if cos_i <= 0.0 {
            return 0.0;
        }
        let cos_h = 1.0 / (1.0 + p[0] * p[0] + p[1] * p[1]).sqrt();
        smith_escape(cos_i, sigma) * self.view_factor * ho / cos_h
    }
}

impl Lobe {
    /// The lobe of RMS slope `sigma` (above 0, at most the model's limit); its albedo
    /// table is made when first needed.
    pub(crate) fn new(sigma: f64) -> Self {
        Self {
            sigma,
            albedo: std::sync::OnceLock::new(),
            psi_rule: gauss_legendre(DISK_PSI_NODES),
            u_rule: gauss_legendre(DISK_U_NODES),
        }
    }

    /// The albedo table, `A(θ_o)` every [`ALBEDO_STEP_DEG`] from 0° to 90°.
    pub(crate) fn albedo_table(&self) -> &[f64] {
        self.albedo.get_or_init(|| {
            let rows = (90.0 / ALBEDO_STEP_DEG).round() as usize + 1;
            let rule = gauss_legendre(ALBEDO_NODES);
            (0..rows)
                .map(|k| {
                    let theta = (k as f64 * ALBEDO_STEP_DEG).to_radians();
                    let cos_o = theta.cos().max(MIN_COS_VIEW);
                    albedo(self.sigma, cos_o, &rule)
                })
                .collect()
        })
    }

    /// The unscaled lobe's albedo `A(θ_o)` at the view cosine `cos_o`, interpolated.
    pub(crate) fn albedo_at(&self, cos_o: f64) -> f64 {
        let table = self.albedo_table();
        let deg = cos_o.clamp(0.0, 1.0).acos().to_degrees() / ALBEDO_STEP_DEG;
        let last = table.len() - 1;
        let k = (deg.floor() as usize).min(last - 1);
        let w = (deg - k as f64).clamp(0.0, 1.0);
        irsig_model::interp::lerp(table[k], table[k + 1], w)
    }

    /// The glint of the sun's disk in the view `o` (unit, toward the sensor) of a facet of
    /// unit normal `n` (the side the view sees), per unit of the beam's normal irradiance
    /// and of the specular share `s·r(θ_o)`, sr⁻¹, before the disk's visible fraction:
    /// `(1/Ω)∫_disk f cos θ_i dω_i / (s·r)`. 0 for a grazing view, a sun behind the facet
    /// or a disk far from the lobe.
    pub(crate) fn glint_per_sr(&self, sun: &SunGeometry, n: DVec3, o: DVec3) -> f64 {
        self.disk_integral(sun, n, o, DISK_PSI_NODES, DISK_U_NODES)
    }

    /// [`Self::glint_per_sr`] with `psi_nodes` × `u_nodes` nodes (for measuring the rule).
    pub(crate) fn disk_integral(
        &self,
        sun: &SunGeometry,
        n: DVec3,
        o: DVec3,
        psi_nodes: usize,
        u_nodes: usize,
    ) -> f64 {
        let sigma = self.sigma;
        if n.dot(o) <= MIN_COS_VIEW || n.dot(sun.to_sun) <= -sun.sin_radius {
            return 0.0;
        }
        let f = Frame::new(n, o, sigma);
        let (c, sa) = (sun.to_sun, sun.sin_radius);
        let ca = 1.0 - sun.one_minus_cos;
        let rim = |t: DVec3, sign: f64| (c * ca + t * (sign * sa)).normalize();
        let (Some(pc), Some(pt1), Some(pt0), Some(pb1), Some(pb0)) = (
            f.slope_of(c),
            f.slope_of(rim(sun.tangent, 1.0)),
            f.slope_of(rim(sun.tangent, -1.0)),
            f.slope_of(rim(sun.bitangent, 1.0)),
            f.slope_of(rim(sun.bitangent, -1.0)),
        ) else {
            return 0.0;
        };
        // The ellipse p_c + J v, |v| ≤ 1.
        let j = [
            [0.5 * (pt1[0] - pt0[0]), 0.5 * (pb1[0] - pb0[0])],
            [0.5 * (pt1[1] - pt0[1]), 0.5 * (pb1[1] - pb0[1])],
        ];
        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
        let reach = (j[0][0].powi(2) + j[0][1].powi(2) + j[1][0].powi(2) + j[1][1].powi(2)).sqrt();
        let dist = pc[0].hypot(pc[1]);
        if det.is_nan() || det.abs() <= 0.0 || dist - reach > FAR_SIGMAS * sigma {
            return 0.0;
        }
        let inv = [
            [j[1][1] / det, -j[0][1] / det],
            [-j[1][0] / det, j[0][0] / det],
        ];
        let apply = |m: [[f64; 2]; 2], v: [f64; 2]| {
            [
                m[0][0] * v[0] + m[0][1] * v[1],
                m[1][0] * v[0] + m[1][1] * v[1],
            ]
        };
        // The peak in the ellipse's own coordinates.
        let q = apply(inv, [-pc[0], -pc[1]]);
        let qq = q[0] * q[0] + q[1] * q[1];
        let made;
        let u_rule: &[(f64, f64)] = if u_nodes == DISK_U_NODES {
            &self.u_rule
        } else {
            made = gauss_legendre(u_nodes);
            &made
        };
        // ∫ W du along the ray of direction ψ, between its entry and exit of the ellipse.
        let along = |psi: f64| -> f64 {
            let d = [psi.cos(), psi.sin()];
            let a = apply(inv, d);
            let aa = a[0] * a[0] + a[1] * a[1];
            let aq = a[0] * q[0] + a[1] * q[1];
            let disc = aq * aq - aa * (qq - 1.0);
            if disc <= 0.0 {
                return 0.0;
            }
            let root = disc.sqrt();
            let r1 = ((-aq - root) / aa).max(0.0);
            let r2 = (-aq + root) / aa;
            if r2 <= r1 {
                return 0.0;
            }
            let s2 = sigma * sigma;
            let (u_in, u_out) = ((-r1 * r1 / s2).exp(), (-r2 * r2 / s2).exp());
            let half = 0.5 * (u_in - u_out);
            if half <= 0.0 {
                return 0.0;
            }
            let mid = 0.5 * (u_in + u_out);
            let mut sum = 0.0;
            for &(x, w) in u_rule {
                let u = mid + half * x;
                let rho = sigma * (-u.ln()).max(0.0).sqrt();
                sum += w * f.weight([rho * d[0], rho * d[1]], sigma);
            }
            sum * half
        };
        let integral = if qq < 1.0 {
            // The peak inside: every direction, a periodic integrand.
            let step = std::f64::consts::TAU / psi_nodes as f64;
            (0..psi_nodes)
                .map(|k| along((k as f64 + 0.5) * step))
                .sum::<f64>()
                * step
        } else {
            // The peak outside: the span between the two tangents, ψ = mid + half·sin φ
            // taking the square-root ends away.
            let beta = (1.0 / qq.sqrt()).asin();
            let back = [-q[0] / qq.sqrt(), -q[1] / qq.sqrt()];
            let tangent = |b: f64| {
                let (s, cs) = b.sin_cos();
                let v = [cs * back[0] - s * back[1], s * back[0] + cs * back[1]];
                let d = apply(j, v);
                d[1].atan2(d[0])
            };
            let centre = pc[1].atan2(pc[0]);
            let wrap = |x: f64| {
                let t = (x - centre + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU);
                t - std::f64::consts::PI
            };
            let (d1, d2) = (wrap(tangent(beta)), wrap(tangent(-beta)));
            let (lo, hi) = (d1.min(d2), d1.max(d2));
            let (mid, half) = (centre + 0.5 * (lo + hi), 0.5 * (hi - lo));
            let made;
            let psi_rule: &[(f64, f64)] = if psi_nodes == DISK_PSI_NODES {
                &self.psi_rule
            } else {
                made = gauss_legendre(psi_nodes);
                &made
            };
            psi_rule
                .iter()
                .map(|&(x, w)| {
                    let phi = x * std::f64::consts::FRAC_PI_2;
                    w * std::f64::consts::FRAC_PI_2
                        * phi.cos()
                        * half
                        * along(mid + half * phi.sin())
                })
                .sum()
        };
        let lobe = integral / std::f64::consts::TAU;
        (lobe * sun.inverse_solid_angle_per_sr / self.albedo_at(f.cos_o)).max(0.0)
    }
}

/// The unscaled lobe's albedo at `cos_o`: `∫ P(p) W(p) d²p` over every slope, polar with
/// `u = e^(−ρ²/σ²)`, `ψ` over the half circle on one side of the plane of incidence (the
/// lobe is symmetric about it) by the Gauss–Legendre `rule` in both.
fn albedo(sigma: f64, cos_o: f64, rule: &[(f64, f64)]) -> f64 {
    let n = DVec3::new(0.0, 0.0, 1.0);
    let o = DVec3::new((1.0 - cos_o * cos_o).max(0.0).sqrt(), 0.0, cos_o);
    let f = Frame::new(n, o, sigma);
    let mut total = 0.0;
    for &(xp, wp) in rule {
        let psi = std::f64::consts::FRAC_PI_2 * (xp + 1.0);
        let d = [psi.cos(), psi.sin()];
        // The tangents of `n.any_orthonormal_pair()` need not be x and y: rotate the slope
        // into them.
        let along: f64 = rule
            .iter()
            .map(|&(xu, wu)| {
                let u = 0.5 * (xu + 1.0);
                let rho = sigma * (-u.ln()).max(0.0).sqrt();
                let world = DVec3::new(rho * d[0], rho * d[1], 0.0);
                let p = [world.dot(f.e1), world.dot(f.e2)];
                0.5 * wu * f.weight(p, sigma)
            })
            .sum();
        total += std::f64::consts::FRAC_PI_2 * wp * along;
    }
    // Twice the half circle, over the 2π of P's polar measure.
    2.0 * total / std::f64::consts::TAU
}

/// The rough-surface glint rule ([`crate::lobe`]) alone, for its benchmark: a facet
/// facing up with rms slope `sigma`, lit by a sun at `sun_zenith_deg` (azimuth 0).
#[cfg(any(test, feature = "testing"))]
#[derive(Debug)]
pub struct LobeProbe {
    lobe: Lobe,
    sun: SunGeometry,
}

#[cfg(any(test, feature = "testing"))]
impl LobeProbe {
    /// The probe of slope `sigma` (rad, rms) under a sun at `sun_zenith_deg`.
    ///
    /// # Panics
    /// A zenith that makes no sun (not finite).
    #[must_use]
    pub fn new(sigma: f64, sun_zenith_deg: f64) -> Self {
        let z = sun_zenith_deg.to_radians();
        let sun = crate::Sun::new(DVec3::new(z.sin(), 0.0, z.cos()), Vec::new())
            .geometry()
            .expect("a finite zenith makes a sun");
        Self {
            lobe: Lobe::new(sigma),
            sun,
        }
    }

    /// The glint seen from the view at zenith `theta_deg`, azimuth `phi_deg` (the sun is at
    /// azimuth 0), sr⁻¹ per unit of `s·r·E_n`: one call of the rule, as a hit makes it.
    #[must_use]
    pub fn glint_per_sr(&self, theta_deg: f64, phi_deg: f64) -> f64 {
        let (t, p) = (theta_deg.to_radians(), phi_deg.to_radians());
        let view = DVec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos());
        self.lobe.glint_per_sr(&self.sun, DVec3::Z, view)
    }
}

#[cfg(test)]
#[path = "lobe_tests.rs"]
mod tests;
