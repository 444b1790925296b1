//! The `thesis` model: τ by the `.cor` polynomial (eq. 10), `L_u(θ) = L_u(0)·secθ`
//! (eq. 11), vertical values interpolated linearly in altitude.
//!
//! The 1990 code applied eq. 10 and 11 to the path from the sensor's altitude to the
//! ground. Here the path between a hit point and the sensor uses both ends: the vertical
//! terms of the slab between them are those of eq. 8–9 (`τ_v = τ(h_hi)/τ(h_lo)`,
//! `L_v = L_u(h_hi) − τ_v·L_u(h_lo)`), and the angular laws act on that slab:
//!
//! - eq. 10 is applied in optical-depth form. At the altitude the `.cor` was fitted at,
//!   with optical depth `δ_ref`, eq. 10 says a slant path to the ground has
//!   `δ(θ) = δ_ref − ln c(θ)`; that is `δ_ref·secθ·k(θ)` with
//!   `k(θ) = (δ_ref − ln c(θ)) / (δ_ref·secθ)`. Any slab then gets
//!   `δ = δ_v·secθ·k(θ)`. For a ground target seen from the fit altitude this is eq. 10
//!   exactly; for a short path (a camera 5 m up, 9 m away) it gives a transmission near 1
//!   instead of eq. 10's fixed `c(θ) ≈ 0.92`. When the fit altitude is unknown the
//!   sensor's own altitude is used, which is the 1990 behaviour (eq. 10 at every
//!   altitude).
//! - The `.cor` polynomial is only meaningful over the angles it was fitted on (0–80°
//!   for the reference tables); beyond 80° `k` holds its 80° value, so the slant optical
//!   depth keeps growing as secθ instead of following the polynomial's upturn.
//! - eq. 11 is `L = L_v·secθ`, bounded above by the warmest layer's radiance, which no
//!   path can exceed (eq. 11 is 2.3× too high at 80° from 1 km, README caveat 4).
//!
//! Paths whose ends are at nearly the same altitude (horizontal) take `δ_v·secθ` and
//! `L_v·secθ` as range × vertical gradient, so they are finite and continuous.

use irsig_model::Atmosphere;

use crate::PathTerms;
use crate::error::{AtmosphereError, AtmosphereErrorKind};
use crate::layered::{Profile, Slant};

/// Largest angle at which the `.cor` polynomial is evaluated, degrees.
const COR_MAX_DEG: f64 = 80.0;

#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Thesis {
    pub profile: Profile,
    cor: [f64; 3],
    /// Vertical optical depth at the `.cor` fit altitude, if known.
    d_ref: Option<f64>,
    /// Upper bound on path radiance, W m⁻² sr⁻¹.
    radiance_bound: f64,
}

impl Thesis {
    pub(crate) fn new(atm: &Atmosphere) -> Result<Self, AtmosphereError> {
        let profile = Profile::new(atm)?;
        let cor = atm
            .transmission_correction
            .ok_or(AtmosphereErrorKind::MissingTable {
                model: "thesis",
                table: "transmission_correction",
                instead: "the thesis model scales τ by the `.cor` polynomial (eq. 10): give the \
                          `.cor` when converting, or use the `layered` model (eq. 8-9)",
            })?;
        let d_ref = atm
            .transmission_correction_altitude_m
            .map(|h| -profile.tau_at(h).max(1e-300).ln());
        // The warmest air's band radiance, from the .rtt when given, else the largest
        // layer radiance the .atm implies.
        let t_max = atm
            .levels
            .iter()
            .map(|l| l.temperature_k)
            .fold(0.0, f64::max);
        let from_rtt = (atm.band_radiance.len() >= 2).then(|| {
            let t: Vec<f64> = atm.band_radiance.iter().map(|r| r.0).collect();
            let l: Vec<f64> = atm.band_radiance.iter().map(|r| r.1).collect();
            crate::interp::linear(&t, &l, t_max)
        });
        let radiance_bound = from_rtt.unwrap_or(profile.b_max).max(profile.b_max);
        Ok(Self {
            profile,
            cor,
            d_ref,
            radiance_bound,
        })
    }

    fn correction(&self, sec: f64) -> f64 {
        let [a1, a2, a3] = self.cor;
        a1 + a2 * sec + a3 * sec * sec
    }

    pub(crate) fn path(&self, s: &Slant) -> PathTerms {
        let (lo, hi) = (s.lo(), s.hi());
        let tau_lo = self.profile.tau_at(lo).max(1e-300);
        let tau_v = (self.profile.tau_at(hi) / tau_lo).clamp(0.0, 1.0);
        let d_v = -tau_v.max(1e-300).ln();
        let l_v = (self.profile.lu_at(hi) - tau_v * self.profile.lu_at(lo)).max(0.0);
        let sec = s.airmass;
        let sec_c = 1.0 / s.angle_deg().min(COR_MAX_DEG).to_radians().cos();
        let d_ref = self
            .d_ref
            .unwrap_or_else(|| -self.profile.tau_at(s.observer_m).max(1e-300).ln());
        let c = self.correction(sec_c);
        let k = if d_ref > 1e-9 && c > 0.0 {
            (d_ref - c.ln()) / (d_ref * sec_c)
        } else {
            1.0
        };
        let transmission = (-d_v * sec * k).exp().clamp(0.0, 1.0);
        let radiance = (l_v * sec).min(self.radiance_bound);
        PathTerms {
            transmission,
            path_radiance_w_m2_sr: radiance,
        }
    }
}
