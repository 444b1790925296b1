//! Sky radiance: the angular `L_d(θ)` seen from the ground (the `.dwr`), the path radiance
//! from an observer above the ground to space, and the hemispheric value (eq. 5).

use std::sync::OnceLock;

use crate::interp::{Hemispheric, fit_quadratic, hemispheric, monotone_cubic};

/// Zenith angle (degrees) beyond which thesis Appendix E replaces computed sky radiance by
/// a least-squares quadratic fitted over [`APPENDIX_E_FIT_FROM_DEG`, this].
pub const APPENDIX_E_EXTRAPOLATE_FROM_DEG: f64 = 83.0;
/// Start of the Appendix E fitting window, degrees ("because of the data's linearity for
/// angles less than 60 degrees").
pub const APPENDIX_E_FIT_FROM_DEG: f64 = 60.0;

/// Relative disagreement between a given hemispheric sky radiance and eq. 5 applied to the
/// angular table above which [`HemisphericSky::warning`] is set. The 5° `.dwr` rows
/// interpolated linearly reproduce the reference tables' 32-point Gauss–Legendre value to
/// 0.2 %; 2 % means the two were not made from the same sky.
pub const HEMISPHERIC_TOLERANCE: f64 = 0.02;

/// The hemispheric (cosine-weighted) sky radiance an observer sees, W m⁻² sr⁻¹: what a
/// Lambertian facet with a sky-view factor of 1 reflects per unit reflectance (eq. 5–6).
#[derive(Debug, Clone, PartialEq)]
pub struct HemisphericSky {
    /// The value to use, W m⁻² sr⁻¹: the given one (scaled to the observer's altitude by
    /// the computed ratio) when the atmosphere has one, else the computed one.
    pub radiance_w_m2_sr: f64,
    /// The value the atmosphere gives (the `.dwr` row `-1`), at the ground, if any.
    pub given_w_m2_sr: Option<f64>,
    /// Eq. 5 applied to the model's angular sky radiance at the observer's altitude.
    pub computed_w_m2_sr: f64,
    /// Set when the given and the computed ground values disagree by more than
    /// [`HEMISPHERIC_TOLERANCE`]; a tool should print it.
    pub warning: Option<String>,
}

/// The `.dwr` table in SI.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct GroundSky {
    pub zenith_deg: Vec<f64>,
    pub radiance: Vec<f64>,
    pub given_hemispheric: Option<f64>,
}

impl GroundSky {
    /// The sky from the ground at `zenith_deg`: a monotone cubic through the rows
    /// (docs/accuracy.md: linear in angle was up to 0.48 K too warm between the 5° rows).
    pub(crate) fn at(&self, zenith_deg: f64) -> f64 {
        monotone_cubic(&self.zenith_deg, &self.radiance, zenith_deg.min(90.0))
    }

    pub(crate) fn computed_hemispheric(&self) -> f64 {
        hemispheric(&self.zenith_deg, &self.radiance)
    }
}

/// Radiance at `zenith_deg` of a sky known by `exact` up to 83°, extrapolated beyond by the
/// Appendix E quadratic fitted over 60–83° in 1° steps.
pub(crate) fn with_appendix_e(zenith_deg: f64, exact: impl Fn(f64) -> f64) -> f64 {
    if zenith_deg <= APPENDIX_E_EXTRAPOLATE_FROM_DEG {
        return exact(zenith_deg);
    }
    let points: Vec<(f64, f64)> = (60..=83)
        .map(|z| {
            let z = f64::from(z);
            (z, exact(z))
        })
        .collect();
    match fit_quadratic(&points) {
        Some(q) => q.at(zenith_deg).max(0.0),
        None => exact(APPENDIX_E_EXTRAPOLATE_FROM_DEG),
    }
}

/// Angular sky radiance precomputed for one observer altitude, for cheap lookups on a
/// tracer's hot path. Linear interpolation on a 0.25° grid from 0° to the largest zenith
/// angle that sees space (180° − the critical nadir angle).
#[derive(Debug, Clone, PartialEq)]
pub struct SkyView {
    observer_altitude_m: f64,
    step_deg: f64,
    radiance: Vec<f64>,
}

impl SkyView {
    pub(crate) fn build(
        observer_altitude_m: f64,
        max_zenith_deg: f64,
        f: impl Fn(f64) -> f64,
    ) -> Self {
        let step_deg = 0.25;
        let n = (max_zenith_deg / step_deg).ceil().max(1.0) as usize;
        let radiance = (0..=n)
            .map(|k| f((k as f64 * step_deg).min(max_zenith_deg)))
            .collect();
        Self {
            observer_altitude_m,
            step_deg,
            radiance,
        }
    }

    /// The observer altitude this view was computed for, metres.
    #[must_use]
    pub fn observer_altitude_m(&self) -> f64 {
        self.observer_altitude_m
    }

    /// Sky radiance at `zenith_deg` (clamped to 0° … the last angle that sees space),
    /// W m⁻² sr⁻¹.
    #[must_use]
    pub fn radiance(&self, zenith_deg: f64) -> f64 {
        let x = (zenith_deg / self.step_deg).max(0.0);
        let last = self.radiance.len().saturating_sub(1);
        // x ≥ 0: truncation is its floor, without a call to libm's `floor` (a sky ray's
        // lookup runs once per sub-band).
        let i = (x as usize).min(last.saturating_sub(1));
        let f = (x - i as f64).clamp(0.0, 1.0);
        match (self.radiance.get(i), self.radiance.get(i + 1)) {
            (Some(&a), Some(&b)) => irsig_model::interp::lerp(a, b, f),
            (Some(&a), None) => a,
            _ => 0.0,
        }
    }

    /// Eq. 5 over the upper hemisphere (0–90°), W m⁻² sr⁻¹.
    #[must_use]
    pub fn hemispheric(&self) -> f64 {
        let count = (0..self.radiance.len())
            .take_while(|&k| k as f64 * self.step_deg <= 90.0)
            .count();
        let radiance = &self.radiance[..count];
        // Every view is built on the same angles ([`SkyView::build`]): their rule is made
        // once (a plan precomputes hundreds of views: each level of each sub-band).
        static RULE: OnceLock<(f64, usize, Hemispheric)> = OnceLock::new();
        let (step, n, rule) = RULE.get_or_init(|| {
            let angles: Vec<f64> = (0..count).map(|k| k as f64 * self.step_deg).collect();
            (self.step_deg, count, Hemispheric::new(&angles))
        });
        #[allow(clippy::float_cmp)] // the same step, exactly, means the same angles
        if *step == self.step_deg && *n == count {
            rule.of(radiance)
        } else {
            let angles: Vec<f64> = (0..count).map(|k| k as f64 * self.step_deg).collect();
            hemispheric(&angles, radiance)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn views_on_the_same_angles_each_integrate_their_own_radiance() {
        // Eq. 5 of a constant is the constant; of L(θ) = θ in degrees, linear between the
        // knots and so integrated exactly, (180/π)∫θ sin 2θ dθ over [0, π/2] = 45.
        let seven = SkyView::build(0.0, 90.0, |_| 7.0);
        let three = SkyView::build(0.0, 90.0, |_| 3.0);
        let ramp = SkyView::build(2.0, 90.1, |z| z);
        assert!((seven.hemispheric() - 7.0).abs() < 1e-12);
        assert!((three.hemispheric() - 3.0).abs() < 1e-12);
        assert!((ramp.hemispheric() - 45.0).abs() < 1e-9);
        assert!((seven.hemispheric() - 7.0).abs() < 1e-12);
    }
}
