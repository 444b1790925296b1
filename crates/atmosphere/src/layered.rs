//! The `layered` model: thesis eq. 8–9 layer by layer, between any two altitudes.
//!
//! The `.atm` table gives, at each level, the vertical band transmittance from the ground
//! `τ(h)` and the nadir path radiance `L_u(h)`. Band-mean transmittance is not
//! exponential in air mass (reference README caveat 4: Beer's law `τ(0)^secθ` gives 0.318
//! at 80° from 1 km where LOWTRAN7 gives 0.563), so the layers are not treated as
//! grey slabs. Instead the band follows a curve of growth `τ(u) = exp(−u^p)` in an
//! absorber coordinate `u`: the vertical path from the ground to `h` holds
//! `W(h) = (−ln τ(h))^(1/p)`, a slant path at air mass `m` between `h₁` and `h₂` holds
//! `m·|W(h₂) − W(h₁)|`. `p = 1` is Beer's law; `p = ½` the strong-line limit.
//! `p` is fitted to the `.cor` angular correction at the altitude it was fitted at
//! (0.59 for US Std 1976, 0.55 for mid-latitude winter); without one it is
//! [`DEFAULT_CURVE_OF_GROWTH_EXPONENT`]. The fitted `p` also predicts LOWTRAN7's
//! transmittance between two altitudes above the ground to ±0.005 (docs/accuracy.md),
//! where the ratio `τ(h₂)/τ(h₁)` errs by 0.09.
//!
//! Path radiance uses the cumulative form of eq. 8, which needs no multiplicative layer
//! transmittances: `L = Σᵢ Bᵢ [τ(observer → near side of layer i) − τ(observer → far
//! side)]`. The layer radiances `Bᵢ` are the ones the `.atm` implies: solved level by
//! level so that the model reproduces the table's nadir `L_u(h)` exactly. (They come out
//! 1–7 % below the band radiance of the layer's air temperature, because the band's
//! opaque edges, where the layers emit, sit where the Planck function is low; using
//! `L(T)` instead biases the apparent temperature by +0.3 to +0.5 K.)

use irsig_model::Atmosphere;

use crate::PathTerms;
use crate::error::{AtmosphereError, AtmosphereErrorKind};
use crate::interp::locate;

/// The curve-of-growth exponent used when the atmosphere has no `.cor` fitted at a known
/// altitude: the fits to the `.cor` of the two built-in LOWTRAN7 8–14 µm atmospheres give
/// 0.59 (US Std 1976) and 0.55 (mid-latitude winter).
pub const DEFAULT_CURVE_OF_GROWTH_EXPONENT: f64 = 0.6;

/// Paths whose ends differ by less than this in altitude (metres) are treated as lying in
/// a slab of this thickness around their mid altitude, so horizontal paths keep a finite
/// air mass (`range / MIN_DH_M`) and the result is continuous in the elevation angle.
const MIN_DH_M: f64 = 1e-3;

/// Where a straight path runs in the plane-parallel atmosphere.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Slant {
    /// Altitude of the end the radiance is seen from, metres above the ground.
    pub observer_m: f64,
    /// Altitude of the other end.
    pub other_m: f64,
    /// Path length over altitude difference (`secθ`), ≥ 1.
    pub airmass: f64,
}

impl Slant {
    /// The path from an observer at `observer_m` to a point at `other_m`, `range_m` away.
    /// Altitudes below the ground are taken as the ground; a range shorter than the
    /// altitude difference as the altitude difference. `None` for a path of zero length.
    pub(crate) fn new(observer_m: f64, other_m: f64, range_m: f64) -> Option<Self> {
        let a = observer_m.max(0.0);
        let b = other_m.max(0.0);
        let dh = (a - b).abs();
        let range = range_m.max(dh);
        if range <= 0.0 || range.is_nan() || dh.is_nan() {
            return None;
        }
        if dh >= MIN_DH_M {
            return Some(Self {
                observer_m: a,
                other_m: b,
                airmass: range / dh,
            });
        }
        let lo = (0.5 * (a + b) - 0.5 * MIN_DH_M).max(0.0);
        let hi = lo + MIN_DH_M;
        let (observer_m, other_m) = if a >= b { (hi, lo) } else { (lo, hi) };
        Some(Self {
            observer_m,
            other_m,
            airmass: range / MIN_DH_M,
        })
    }

    /// The nadir (or, looking up, zenith) angle of the path in degrees.
    pub(crate) fn angle_deg(&self) -> f64 {
        (1.0 / self.airmass).clamp(0.0, 1.0).acos().to_degrees()
    }

    pub(crate) fn lo(&self) -> f64 {
        self.observer_m.min(self.other_m)
    }

    pub(crate) fn hi(&self) -> f64 {
        self.observer_m.max(self.other_m)
    }
}

/// A slant path located among a profile's levels ([`Profile::walk`]): the same for every
/// profile on those levels, so the sub-bands of one atmosphere search once per path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Walk {
    airmass: f64,
    looking_down: bool,
    lo: f64,
    hi: f64,
    /// `locate(z_m, lo)` and `locate(z_m, hi)`.
    lo_at: (usize, f64),
    hi_at: (usize, f64),
}

/// The vertical profile both the `thesis` and `layered` models read: levels from the
/// ground (a level at 0 m with τ = 1 and L_u = 0 is added), the absorber coordinate and
/// the layer radiances.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Profile {
    /// Level altitudes above the ground, metres, from 0.
    pub z_m: Vec<f64>,
    /// Vertical transmittance from the ground at each level.
    pub tau: Vec<f64>,
    /// Nadir path radiance at each level, W m⁻² sr⁻¹.
    pub lu: Vec<f64>,
    /// Absorber coordinate `W = (−ln τ)^(1/p)` at each level.
    pub w: Vec<f64>,
    /// `b[i]`: effective radiance of the layer between levels `i − 1` and `i` (`b[0]` is a
    /// copy of `b[1]`), W m⁻² sr⁻¹.
    pub b: Vec<f64>,
    /// Curve-of-growth exponent.
    pub p: f64,
    /// Largest layer radiance, an upper bound on any path radiance.
    pub b_max: f64,
}

impl Profile {
    pub(crate) fn new(atm: &Atmosphere) -> Result<Self, AtmosphereError> {
        Self::with_exponent(atm, None)
    }

    /// The profile with the curve-of-growth exponent `p` given, or fitted when `None`.
    pub(crate) fn with_exponent(atm: &Atmosphere, p: Option<f64>) -> Result<Self, AtmosphereError> {
        atm.validate()?;
        let mut z_m = vec![0.0];
        let mut tau = vec![1.0];
        let mut lu = vec![0.0];
        for (i, l) in atm.levels.iter().enumerate() {
            let below = tau.last().copied().unwrap_or(1.0);
            if l.transmission > below {
                return Err(AtmosphereErrorKind::TransmissionIncreases {
                    level: i,
                    value: l.transmission,
                    below,
                }
                .into());
            }
            if l.altitude_m <= 0.0 {
                // A level at the ground itself carries nothing beyond the implicit one.
                continue;
            }
            z_m.push(l.altitude_m);
            tau.push(l.transmission);
            lu.push(l.path_radiance_w_m2_sr);
        }
        let p = p.unwrap_or_else(|| curve_of_growth_exponent(atm, &z_m, &tau));
        // τ = 0 would make the optical depth infinite; 1e-300 keeps it finite (690).
        let w: Vec<f64> = tau
            .iter()
            .map(|&t| (-t.max(1e-300).ln()).max(0.0).powf(1.0 / p))
            .collect();
        let mut b = vec![0.0; z_m.len()];
        let t = |u: f64| (-u.abs().powf(p)).exp();
        for k in 1..z_m.len() {
            let mut seen = 0.0;
            for i in 1..k {
                seen += b[i] * (t(w[k] - w[i]) - t(w[k] - w[i - 1]));
            }
            let emissivity = 1.0 - t(w[k] - w[k - 1]);
            b[k] = if emissivity > 1e-12 {
                ((lu[k] - seen) / emissivity).max(0.0)
            } else {
                // A transparent layer: its radiance never matters.
                b[k - 1]
            };
        }
        if b.len() > 1 {
            b[0] = b[1];
        }
        let b_max = b.iter().copied().fold(0.0, f64::max);
        Ok(Self {
            z_m,
            tau,
            lu,
            w,
            b,
            p,
            b_max,
        })
    }

    fn transmittance(&self, u: f64) -> f64 {
        (-u.abs().powf(self.p)).exp()
    }

    /// Absorber coordinate at altitude `z` (linear between levels, constant above the
    /// top level: no absorber is known there).
    pub(crate) fn w_at(&self, z: f64) -> f64 {
        let (i, f) = locate(&self.z_m, z);
        match (self.w.get(i), self.w.get(i + 1)) {
            (Some(&a), Some(&b)) => irsig_model::interp::lerp(a, b, f),
            (Some(&a), None) => a,
            _ => 0.0,
        }
    }

    /// The layered path terms (eq. 8–9 in cumulative form) for a slant path.
    pub(crate) fn path(&self, s: &Slant) -> PathTerms {
        self.along(&self.walk(s))
    }

    /// Where the ends of `s` lie among the levels: the grid search of [`Profile::path`],
    /// valid for every profile on the same levels (the sub-bands of one atmosphere).
    pub(crate) fn walk(&self, s: &Slant) -> Walk {
        Walk {
            airmass: s.airmass,
            looking_down: s.observer_m >= s.other_m,
            lo: s.lo(),
            hi: s.hi(),
            lo_at: locate(&self.z_m, s.lo()),
            hi_at: locate(&self.z_m, s.hi()),
        }
    }

    /// Absorber coordinate at a located altitude ([`Profile::w_at`] without the search).
    fn w_located(&self, (i, f): (usize, f64)) -> f64 {
        match (self.w.get(i), self.w.get(i + 1)) {
            (Some(&a), Some(&b)) => irsig_model::interp::lerp(a, b, f),
            (Some(&a), None) => a,
            _ => 0.0,
        }
    }

    /// The layered path terms along a located path.
    ///
    /// Every transmittance is taken from the observer, so the observer's own end is 1 and
    /// the far end is the path's transmission: each is computed once (a path inside one
    /// layer, the common case near the ground, costs one curve-of-growth evaluation).
    pub(crate) fn along(&self, walk: &Walk) -> PathTerms {
        self.along_with_depth(walk).0
    }

    /// [`Profile::along`] and the path's optical depth `u^p` (its transmission is
    /// `exp(−depth)`), for a model that scales the depth without taking a logarithm.
    pub(crate) fn along_with_depth(&self, walk: &Walk) -> (PathTerms, f64) {
        let m = walk.airmass;
        let (lo, hi) = (walk.lo, walk.hi);
        let (w_lo, w_hi) = (self.w_located(walk.lo_at), self.w_located(walk.hi_at));
        let u_total = m * (w_hi - w_lo);
        let depth = u_total.abs().powf(self.p);
        let transmission = (-depth).exp();
        let w_obs = if walk.looking_down { w_hi } else { w_lo };
        // Exact comparisons: a transmittance is reused only where it would be computed from
        // the very same argument.
        #[allow(clippy::float_cmp)]
        let to_observer = |w_z: f64| {
            let u = m * (w_obs - w_z);
            if u == 0.0 {
                // exp(−0^p), exactly.
                1.0
            } else if u.abs() == u_total.abs() {
                transmission
            } else {
                self.transmittance(u)
            }
        };
        let n = self.z_m.len();
        // A level's own location, as `locate` finds it (the top level is the end of the
        // last interval).
        let level = |k: usize| {
            if k + 1 >= n {
                (n.saturating_sub(2), 1.0)
            } else {
                (k, 0.0)
            }
        };
        let mut radiance = 0.0;
        let mut z0 = lo;
        let top = self.z_m.last().copied().unwrap_or(0.0);
        // Walk the pieces of the path between level boundaries, bottom to top. The
        // transmittance from the observer to a boundary is computed once: each boundary
        // ends one piece and starts the next.
        let mut i = walk.lo_at.0;
        let mut t0 = to_observer(w_lo);
        while z0 < hi && z0 < top {
            let next = self.z_m.get(i + 1).copied().unwrap_or(top);
            let (z1, at) = if hi <= next {
                (hi, walk.hi_at)
            } else {
                (next, level(i + 1))
            };
            let t1 = to_observer(self.w_located(at));
            if z1 > z0 {
                let (t_near, t_far) = if walk.looking_down {
                    (t1, t0)
                } else {
                    (t0, t1)
                };
                radiance += self.b.get(i + 1).copied().unwrap_or(0.0) * (t_near - t_far);
            }
            t0 = t1;
            z0 = z1;
            i += 1;
            if i + 1 >= n {
                break;
            }
        }
        let terms = PathTerms {
            transmission: transmission.clamp(0.0, 1.0),
            path_radiance_w_m2_sr: radiance.max(0.0),
        };
        (terms, depth)
    }

    /// Sky radiance from `h` at air mass `m` (zenith angle θ, `m = secθ`), given the sky
    /// `ground_sky` seen from the ground at that angle.
    ///
    /// The profile ends at its top level; the air above it is one more layer, with the
    /// top layer's radiance and the absorber amount that makes the model reproduce the
    /// ground sky at this angle. Seen from `h`, the sky is the profile's layers above `h`
    /// plus that layer, each through the curve of growth from `h`. Subtracting the air
    /// below `h` from the ground sky with band-mean terms instead, `(L_d − L_up)/τ`,
    /// over-subtracts (the low air emits in the same opaque parts of the band that hide
    /// the sky above it) and is 20–60 % low.
    pub(crate) fn sky(&self, h: f64, m: f64, ground_sky: f64) -> f64 {
        let top = self.z_m.last().copied().unwrap_or(0.0);
        let w_top = self.w.last().copied().unwrap_or(0.0);
        let b_top = self.b.last().copied().unwrap_or(0.0);
        let known = |from: f64| {
            Slant::new(from, top, (top - from).max(0.0) * m)
                .map_or(0.0, |s| self.path(&s).path_radiance_w_m2_sr)
        };
        let residual = ground_sky - known(0.0);
        let t_top = self.transmittance(m * w_top);
        // Absorber coordinate of "space" along this direction.
        let w_space = if residual <= 0.0 || b_top <= 0.0 {
            w_top
        } else {
            let t_space = t_top - residual / b_top;
            if t_space <= 1e-300 {
                f64::INFINITY
            } else {
                ((-t_space.ln()).powf(1.0 / self.p) / m).max(w_top)
            }
        };
        let h = h.min(top);
        let w_h = self.w_at(h);
        let above = b_top
            * (self.transmittance(m * (w_top - w_h))
                - if w_space.is_finite() {
                    self.transmittance(m * (w_space - w_h))
                } else {
                    0.0
                });
        (known(h) + above).max(0.0)
    }

    /// Vertical transmittance from the ground at `z`, linear between levels.
    pub(crate) fn tau_at(&self, z: f64) -> f64 {
        crate::interp::linear(&self.z_m, &self.tau, z)
    }

    /// Nadir path radiance at `z`, linear between levels.
    pub(crate) fn lu_at(&self, z: f64) -> f64 {
        crate::interp::linear(&self.z_m, &self.lu, z)
    }
}

/// Fits `p` of `τ = exp(−(m·W)^p)` to the `.cor` correction at the altitude it was fitted
/// at: `ln(δ(θ)/δ(0)) = p·ln secθ` with `δ(θ) = −ln(τ_ref·c(θ)/c(0))`, θ = 5…80°, least
/// squares through the origin. The result is held to [0.3, 1] (between beyond the
/// strong-line limit and Beer's law).
fn curve_of_growth_exponent(atm: &Atmosphere, z_m: &[f64], tau: &[f64]) -> f64 {
    let (Some(c), Some(h_ref)) = (
        atm.transmission_correction,
        atm.transmission_correction_altitude_m,
    ) else {
        return DEFAULT_CURVE_OF_GROWTH_EXPONENT;
    };
    let tau_ref = crate::interp::linear(z_m, tau, h_ref);
    let d_ref = -tau_ref.ln();
    let poly = |sec: f64| c[0] + c[1] * sec + c[2] * sec * sec;
    let c0 = poly(1.0);
    if !(d_ref > 1e-6 && c0 > 0.0) {
        return DEFAULT_CURVE_OF_GROWTH_EXPONENT;
    }
    let (mut sxy, mut sxx) = (0.0, 0.0);
    for k in 1..=16 {
        let sec = 1.0 / (f64::from(k) * 5.0).to_radians().cos();
        let ratio = poly(sec) / c0;
        if !(ratio > 0.0 && ratio < 1.0) {
            continue;
        }
        let d = d_ref - ratio.ln();
        let x = sec.ln();
        sxy += x * (d / d_ref).ln();
        sxx += x * x;
    }
    let p = sxy / sxx;
    if p.is_finite() {
        p.clamp(0.3, 1.0)
    } else {
        DEFAULT_CURVE_OF_GROWTH_EXPONENT
    }
}
