//! The sun's direct beam: what the tracer needs to light its facets with it.
//!
//! A [`Sun`] is a direction, an angular radius and, per sub-band, the beam's irradiance on a
//! surface normal to it as a function of altitude ([`SunBeam`]). The tracer knows no dates,
//! no solar tables and no LOWTRAN: whoever builds the tracer fills these in (the
//! atmosphere's `DirectSun` gives the beam of a band at its table's altitudes, its
//! `SunPosition` the direction).
//!
//! What the tracer does with it ([`crate::Tracer::with_sun`]), at every facet of a path
//! (the first hit and the facets of its specular bounces; not the facets sky-view rays
//! meet, whose reflected light stays the hemispheric sky's):
//!
//! * **Diffuse part.** The diffuse share `1 − s` of the reflectance `r = 1 − ε(θ)` is
//!   Lambertian (BRDF `r/π`), so the sun adds `r·(1 − s)·E_n·cos θ_i·V/π` to the
//!   surface-leaving radiance, with `E_n` the beam's normal irradiance at the hit's
//!   altitude, `θ_i` the angle between the sun and the normal of the side of the facet the
//!   ray sees (0 when the sun is behind it) and `V` the fraction of the sun that shadow rays
//!   find unoccluded. One shadow ray ([`Sun::shadow_rays`] = 1) goes to the disk's centre;
//!   more sample the disk uniformly by solid angle, stratified, each weighted by its own
//!   `cos θ_i`, for soft shadow edges. A shadow ray below the horizontal is blocked by
//!   the ground. In the equation the sun's term joins the diffuse incident radiance as
//!   `E_n·cos θ_i·V/π`, the radiance of a uniform sky that would give the same irradiance.
//! * **Specular part, smooth.** A material without an RMS slope (or with 0) is an ideal
//!   mirror: where its reflection ray leaves the scene toward the sky (or, the bounces
//!   spent, would do so) within the sun's disk, it reflects the disk's radiance
//!   `E_n/Ω_sun`, `Ω_sun = 2π(1 − cos α)` for the angular radius α, a uniform disk. This is
//!   the glint; it joins the specular incident radiance. A mirror ray that hits a facet
//!   brings that facet's leaving radiance, sunlit or not, as before.
//! * **Specular part, rough.** A material with an RMS facet slope `σ > 0` reflects the sun
//!   through a Cook–Torrance lobe (Beckmann slopes of RMS `σ`, Smith's shadowing) scaled so
//!   that its directional-hemispherical reflectance at the viewing angle is `s·r(θ_o)`
//!   ([`crate::lobe`], which states the non-reciprocity this implies). Its glint is the
//!   lobe integrated over the disk by a fixed rule (no random numbers), times `V`, the
//!   fraction of the facet's shadow rays that reach the sun (a facet with no diffuse part
//!   casts them for this, from the pixel's sun stream, only where the lobe reaches the
//!   disk). It tends to the smooth glint as `σ → 0` and to the point sun's `f·cos θ_i·E_n`
//!   for `σ` well above the disk's `α`. The rest of the environment (sky, terrain, facets)
//!   is still reflected along the mirror direction alone: the lobe is the sun's only.
//! * **Terrain background.** The terrain beyond the scene is flat and unshadowed: it
//!   reflects `(1 − ε)·E_n(0)·cos θ_sun/π` more, `θ_sun` the sun's zenith angle.
//!
//! Both reflectances are taken at the viewing angle's `ε(θ)`, as the sky's are. The sun's
//! terms are summed per sub-band like every other surface-leaving term, and carried to the
//! sensor through the view path's transmittance *for sunlight*
//! ([`SunBeam::sunlit_transmission`]): a sub-band's τ is an average over its wavelengths
//! weighted by what the atmosphere was collapsed for (the emission), and the sunlight that
//! reaches the ground has already lost the wavelengths the view path absorbs (both paths
//! are opaque in the same CO₂ and water bands), so its own weighted average of the same
//! path is higher: through 1 km in 3–5 µm, 0.856 against 0.677. Without that map the
//! sunlight is the emission's τ times it, as before. No sun (the default) traces and sums
//! exactly what it did before.

use irsig_model::interp::{lerp, linear};

use crate::error::{TraceError, TraceErrorKind};
use glam::DVec3;

/// The sun's angular radius seen from the Earth at its mean distance (the orbit's
/// semi-major axis), degrees (0.533° across). On a given day it is this times `r₀/r`, 0.2711°
/// at perihelion and 0.2622° at aphelion: whoever builds the tracer knows the day and sets
/// [`Sun::angular_radius_deg`].
pub const SUN_ANGULAR_RADIUS_DEG: f64 = 0.2666;

/// Most shadow rays per hit [`Sun::shadow_rays`] accepts.
pub const MAX_SHADOW_RAYS: u32 = 1 << 16;

fn invalid(message: String) -> TraceError {
    TraceError::new(TraceErrorKind::InvalidOptions(message))
}

/// The direct beam of one sub-band: its irradiance on a surface normal to the beam, W m⁻²,
/// at a few altitudes above the ground, linear in altitude between them and the nearest
/// one's outside them.
///
/// It also carries the sub-band's transmittance of a view path for the sunlight, as a
/// function of the sub-band's own τ of the same path ([`SunBeam::with_path_transmission`]).
#[derive(Debug, Clone, PartialEq)]
pub struct SunBeam {
    altitude_m: Vec<f64>,
    normal_w_m2: Vec<f64>,
    /// `(τ, τ_sun)` pairs, τ strictly increasing; empty: `τ_sun = τ`.
    path_transmission: Vec<[f64; 2]>,
}

impl SunBeam {
    /// The beam whose normal irradiance is `normal_w_m2[k]` W m⁻² at `altitude_m[k]` metres
    /// above the ground.
    ///
    /// # Errors
    /// No altitude, lists of different lengths, altitudes not finite or not increasing, an
    /// irradiance negative or not finite.
    pub fn new(altitude_m: Vec<f64>, normal_w_m2: Vec<f64>) -> Result<Self, TraceError> {
        if altitude_m.is_empty() || altitude_m.len() != normal_w_m2.len() {
            return Err(invalid(format!(
                "sun beam: {} altitudes and {} irradiances: expected the same number, at \
                 least one",
                altitude_m.len(),
                normal_w_m2.len()
            )));
        }
        if altitude_m.iter().any(|h| !h.is_finite()) || altitude_m.windows(2).any(|w| w[1] <= w[0])
        {
            return Err(invalid(format!(
                "sun beam: altitudes {altitude_m:?} m: expected finite and increasing"
            )));
        }
        if let Some(e) = normal_w_m2.iter().find(|e| !(e.is_finite() && **e >= 0.0)) {
            return Err(invalid(format!(
                "sun beam: normal irradiance {e} W m-2: expected finite and not negative"
            )));
        }
        Ok(Self {
            altitude_m,
            normal_w_m2,
            path_transmission: Vec::new(),
        })
    }

    /// This beam with `pairs` as the view path's transmittance for the sunlight: `(τ,
    /// τ_sun)`, the sub-band's transmittance of a path as its atmosphere gives it and the
    /// same path's weighted by the sunlight at the ground, for paths that span the scene's.
    /// Between two pairs `τ_sun` is linear in `τ`; outside them it is taken to `(0, 0)` and
    /// `(1, 1)` (an opaque path passes no sunlight, a clear one all of it).
    ///
    /// # Errors
    /// A pair not finite or outside 0–1, or τ not strictly increasing.
    pub fn with_path_transmission(mut self, pairs: Vec<[f64; 2]>) -> Result<Self, TraceError> {
        if let Some(p) = pairs
            .iter()
            .find(|p| !p.iter().all(|v| v.is_finite() && (0.0..=1.0).contains(v)))
        {
            return Err(invalid(format!(
                "sun beam: path transmittance pair {p:?}: expected two values of 0 to 1"
            )));
        }
        if pairs.windows(2).any(|w| w[1][0] <= w[0][0]) {
            return Err(invalid(
                "sun beam: path transmittance pairs: expected τ strictly increasing".into(),
            ));
        }
        self.path_transmission = pairs;
        Ok(self)
    }

    /// The view path's transmittance for the sunlight, given the sub-band's `tau` of the
    /// path: `tau` itself without pairs.
    #[must_use]
    pub fn sunlit_transmission(&self, tau: f64) -> f64 {
        let p = &self.path_transmission;
        if p.is_empty() || !(0.0..=1.0).contains(&tau) {
            return tau;
        }
        let k = p.partition_point(|q| q[0] <= tau);
        let (lo, hi) = (
            if k == 0 { [0.0, 0.0] } else { p[k - 1] },
            if k == p.len() { [1.0, 1.0] } else { p[k] },
        );
        if hi[0] <= lo[0] {
            return lo[1];
        }
        lerp(lo[1], hi[1], (tau - lo[0]) / (hi[0] - lo[0]))
    }

    /// A beam of `normal_w_m2` W m⁻² at every altitude (no atmosphere, or a test).
    ///
    /// # Errors
    /// An irradiance negative or not finite.
    pub fn uniform(normal_w_m2: f64) -> Result<Self, TraceError> {
        Self::new(vec![0.0], vec![normal_w_m2])
    }

    /// The normal irradiance at `altitude_m` above the ground, W m⁻².
    #[must_use]
    pub fn normal_w_m2(&self, altitude_m: f64) -> f64 {
        let (h, e) = (&self.altitude_m, &self.normal_w_m2);
        let last = h.len() - 1;
        // A NaN altitude reads the first row rather than panicking.
        if altitude_m.is_nan() || altitude_m <= h[0] {
            return e[0];
        }
        // The top row exactly: `linear` there gives `e[last − 1] + (e[last] − e[last − 1])`,
        // which can differ from it in the last bit.
        if altitude_m >= h[last] {
            return e[last];
        }
        linear(h, e, altitude_m)
    }
}

/// The sun as the tracer takes it ([`crate::Tracer::with_sun`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Sun {
    /// Direction toward the sun's centre in the scene's axes (x east, y north, z up); need
    /// not be a unit vector.
    pub to_sun: DVec3,
    /// The disk's angular radius, degrees ([`SUN_ANGULAR_RADIUS_DEG`]).
    pub angular_radius_deg: f64,
    /// Shadow rays per facet hit: 1 aims at the disk's centre (hard shadows); more sample
    /// the disk (soft edges).
    pub shadow_rays: u32,
    /// The beam in each of the tracer's sub-bands, in their order.
    pub beams: Vec<SunBeam>,
}

impl Sun {
    /// A sun toward `to_sun` with the mean angular radius and one shadow ray per hit.
    #[must_use]
    pub fn new(to_sun: DVec3, beams: Vec<SunBeam>) -> Self {
        Self {
            to_sun,
            angular_radius_deg: SUN_ANGULAR_RADIUS_DEG,
            shadow_rays: 1,
            beams,
        }
    }

    /// The geometry the tracer traces with, checked.
    pub(crate) fn geometry(&self) -> Result<SunGeometry, TraceError> {
        let v = self.to_sun;
        let n = v.dot(v).sqrt();
        if !(n.is_finite() && n > 0.0) {
            return Err(invalid(format!(
                "sun direction {v:?}: expected a finite vector of non-zero length"
            )));
        }
        let a = self.angular_radius_deg;
        if !(a > 0.0 && a <= 10.0) {
            return Err(invalid(format!(
                "sun angular radius {a}°: expected above 0 and at most 10"
            )));
        }
        if self.shadow_rays == 0 || self.shadow_rays > MAX_SHADOW_RAYS {
            return Err(invalid(format!(
                "sun shadow rays {}: expected 1 to {MAX_SHADOW_RAYS}",
                self.shadow_rays
            )));
        }
        let to_sun = v * (1.0 / n);
        let cos_radius = a.to_radians().cos();
        // 1 − cos α without cancellation.
        let one_minus_cos = 2.0 * (a.to_radians() / 2.0).sin().powi(2);
        let (t, b) = to_sun.any_orthonormal_pair();
        Ok(SunGeometry {
            to_sun,
            tangent: t,
            bitangent: b,
            cos_radius,
            sin_radius: a.to_radians().sin(),
            one_minus_cos,
            inverse_solid_angle_per_sr: 1.0 / (std::f64::consts::TAU * one_minus_cos),
            shadow_rays: self.shadow_rays,
        })
    }
}

/// The sun's geometry, ready to trace.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SunGeometry {
    /// Unit vector toward the disk's centre.
    pub(crate) to_sun: DVec3,
    /// With `to_sun`, an orthonormal basis.
    pub(crate) tangent: DVec3,
    pub(crate) bitangent: DVec3,
    /// Cosine of the angular radius: a direction `d` lies in the disk when
    /// `d·to_sun ≥ cos_radius`.
    pub(crate) cos_radius: f64,
    /// `sin α`: a facet whose normal makes more than 90° + α with `to_sun` sees none of
    /// the disk.
    pub(crate) sin_radius: f64,
    /// `1 − cos α`.
    pub(crate) one_minus_cos: f64,
    /// `1/Ω_sun`, sr⁻¹: a uniform disk's radiance per unit of normal irradiance.
    pub(crate) inverse_solid_angle_per_sr: f64,
    pub(crate) shadow_rays: u32,
}

impl SunGeometry {
    /// The direction of the disk at `(u1, u2)` in the unit square, uniform in solid angle
    /// over the disk.
    pub(crate) fn disk_direction(&self, u1: f64, u2: f64) -> DVec3 {
        let cos_t = 1.0 - u1 * self.one_minus_cos;
        let sin_t = (u1 * self.one_minus_cos * (2.0 - u1 * self.one_minus_cos))
            .max(0.0)
            .sqrt();
        let phi = std::f64::consts::TAU * u2;
        let (s, c) = phi.sin_cos();
        let t = self.tangent;
        let b = self.bitangent;
        let d = self.to_sun;
        d * cos_t + (t * c + b * s) * sin_t
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn beam_is_linear_between_altitudes_and_flat_outside() {
        let b = SunBeam::new(vec![0.0, 1000.0, 3000.0], vec![10.0, 20.0, 40.0]).unwrap();
        assert_eq!(b.normal_w_m2(-5.0).to_bits(), 10.0f64.to_bits());
        assert_eq!(b.normal_w_m2(0.0).to_bits(), 10.0f64.to_bits());
        assert!((b.normal_w_m2(500.0) - 15.0).abs() < 1e-12);
        assert!((b.normal_w_m2(2000.0) - 30.0).abs() < 1e-12);
        assert_eq!(b.normal_w_m2(1000.0).to_bits(), 20.0f64.to_bits());
        assert_eq!(b.normal_w_m2(1e9).to_bits(), 40.0f64.to_bits());
        assert_eq!(b.normal_w_m2(f64::NAN).to_bits(), 10.0f64.to_bits());
    }

    #[test]
    fn bad_beams_and_suns_are_refused() {
        assert!(SunBeam::new(vec![], vec![]).is_err());
        assert!(SunBeam::new(vec![0.0, 0.0], vec![1.0, 1.0]).is_err());
        assert!(SunBeam::new(vec![0.0], vec![1.0, 2.0]).is_err());
        assert!(SunBeam::uniform(-1.0).is_err());
        assert!(SunBeam::uniform(f64::NAN).is_err());
        let ok = Sun::new(DVec3::new(0.0, 0.0, 1.0), vec![]);
        assert!(ok.geometry().is_ok());
        for bad in [
            Sun::new(DVec3::splat(0.0), vec![]),
            Sun::new(DVec3::new(f64::INFINITY, 0.0, 1.0), vec![]),
            Sun {
                angular_radius_deg: 0.0,
                ..ok.clone()
            },
            Sun {
                shadow_rays: 0,
                ..ok.clone()
            },
        ] {
            assert!(bad.geometry().is_err(), "{bad:?}");
        }
    }

    #[test]
    fn disk_directions_are_unit_and_inside_the_disk() {
        let sun = Sun::new(DVec3::new(1.0, 2.0, 3.0), vec![])
            .geometry()
            .unwrap();
        // Ω of a cap of half-angle α: 2π(1 − cos α); for 0.2666° about 6.80e-5 sr.
        let a = SUN_ANGULAR_RADIUS_DEG.to_radians();
        let omega = std::f64::consts::TAU * (1.0 - a.cos());
        assert!((sun.inverse_solid_angle_per_sr * omega - 1.0).abs() < 1e-6);
        assert!((omega - 6.80e-5).abs() < 0.01e-5);
        for (u1, u2) in [(0.0, 0.3), (0.5, 0.7), (1.0, 0.0), (0.999, 0.5)] {
            let d = sun.disk_direction(u1, u2);
            assert!((d.dot(d) - 1.0).abs() < 1e-12);
            let c = d.dot(sun.to_sun);
            assert!(c >= sun.cos_radius - 1e-12, "{u1} {u2}: {c}");
            // u1 is the solid-angle fraction: the angle from the centre is
            // arccos(1 − u1(1 − cos α)).
            let expected = (1.0 - u1 * (1.0 - a.cos())).acos();
            assert!((c.clamp(-1.0, 1.0).acos() - expected).abs() < 1e-7);
        }
    }
}
