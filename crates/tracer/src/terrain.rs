//! The terrain background: what a ray that leaves the scene below the horizon meets. It
//! is flat (horizontal, at altitude 0), unshadowed and of one temperature
//! ([`irsig_model::Terrain`]), with either one emissivity at every angle or a material of
//! the library.
//!
//! * **A constant emissivity** `ε`: the surface-leaving radiance is `ε·L_T + (1 − ε)·L_d(0)`
//!   in every direction (the hemispheric sky reflected), with a sun the beam's diffuse
//!   `(1 − ε)·E_n(0)·cos θ_sun/π` more: one number per sub-band.
//! * **A material**: the ray from the sensor meets the terrain at the incidence angle its
//!   nadir angle gives, and the terrain's radiance is that of a horizontal facet of the
//!   material at altitude 0 seen along that ray with no other facet in the way: the
//!   material's ε(θ) in the sub-band, its specular share reflecting the sky along the
//!   mirror direction (and the sun's glint, where the mirror direction or the material's
//!   lobe meets the disk), its diffuse share the hemispheric sky and the sun's unshadowed
//!   beam ([`crate::shade`]'s `surface_terms` for a node with the hemispheric diffuse
//!   model). A ground plane of the material inside the scene and the terrain beyond its
//!   edge then have the same radiance at the same angle and temperature. A reflection or
//!   a sky-view ray that reaches the terrain from a facet sees it at an angle the tracer
//!   does not keep: there the terrain is the constant case with the material's
//!   hemispherical emissivity `ε_h = 2∫ε(θ)·cos θ·sin θ dθ` (the form of thesis eq. 5;
//!   `EmissivityTable::hemispherical`), the mean a diffuse view of it weighs.

use std::f64::consts::FRAC_1_PI;

use irsig_radiometry::BandModel;

use crate::day::{escaped_sunlight, scattered_hemispheric, sky_hemispheric};
use crate::env::Atmosphere;
use crate::path::{Mirror, glint_per_sr};
use crate::shade::escaped;
use crate::sun::{SunBeam, SunGeometry};
use crate::tracer::{BandData, Tracer};
use glam::DVec3;

/// The terrain's surface-leaving terms in one sub-band, along one ray.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct TerrainTerms {
    /// ε at the ray's incidence.
    pub(crate) emissivity: f64,
    /// The surface-leaving radiance, W m⁻² sr⁻¹.
    pub(crate) leaving: f64,
    /// The sunlight in it, W m⁻² sr⁻¹ (0 at night).
    pub(crate) solar: f64,
}

/// The constant terrain's surface-leaving radiance in sub-band `b`, W m⁻² sr⁻¹:
/// `ε·L_T + (1 − ε)·L_d(0)`, and with a sun or by day its sunlight ([`solar`]) more.
pub(crate) fn leaving<A: Atmosphere>(
    eps: f64,
    b: &BandData<A>,
    sun: Option<(&SunBeam, &SunGeometry)>,
) -> f64 {
    let night = eps * b.terrain_blackbody + (1.0 - eps) * b.atmosphere.sky_hemispheric(0.0);
    if sun.is_none() && b.atmosphere.scattered().is_none() {
        return night;
    }
    night + solar(eps, b, sun)
}

/// The sunlight in the constant terrain's surface-leaving radiance in one sub-band,
/// W m⁻² sr⁻¹: the beam's `(1 − ε)·E_n(0)·cos θ_sun/π`, and by day the scattered sky's
/// `(1 − ε)·L_d,scattered(0)` (0 without either).
pub(crate) fn solar<A: Atmosphere>(
    eps: f64,
    b: &BandData<A>,
    sun: Option<(&SunBeam, &SunGeometry)>,
) -> f64 {
    let direct = sun.map_or(0.0, |(beam, geometry)| {
        let cos_zenith = geometry.to_sun[2].max(0.0);
        (1.0 - eps) * beam.normal_w_m2(0.0) * cos_zenith * FRAC_1_PI
    });
    match b.atmosphere.scattered() {
        None => direct,
        Some(s) => direct + (1.0 - eps) * s.sky_hemispheric(0.0),
    }
}

impl<B: BandModel, A: Atmosphere> Tracer<B, A> {
    /// The emissivity the constant terrain terms of sub-band `b` use: the terrain's own, or
    /// its material's hemispherical emissivity in `b`.
    pub(crate) fn terrain_emissivity<S>(&self, b: &BandData<S>) -> f64 {
        match self.terrain_slot {
            None => self.terrain.emissivity,
            Some(slot) => b.emissivity[usize::from(slot)].hemispherical(),
        }
    }

    /// The terrain's terms in sub-band `b` along the ray `dir` (unit) from the sensor that
    /// met it: with a material, as a horizontal facet of it at altitude 0 in full sun
    /// would have them; without, the constant ones.
    pub(crate) fn terrain_terms<S: Atmosphere>(&self, b: &BandData<S>, dir: DVec3) -> TerrainTerms {
        let Some(slot) = self.terrain_slot else {
            let eps = self.terrain.emissivity;
            return TerrainTerms {
                emissivity: eps,
                leaving: b.terrain_leaving,
                solar: b.terrain_solar,
            };
        };
        let slot = usize::from(slot);
        let m = &self.materials[slot];
        let sfrac = m.specular_fraction;
        let eps = b.emissivity[slot].at_cos((-dir[2]).clamp(0.0, 1.0));
        // The mirror direction about the up normal leaves toward the sky from altitude 0.
        let refl = DVec3::new(dir.x, dir.y, -dir.z);
        let sky = self.escape(refl, 0.0);
        let (mut specular, mut diffuse) = (escaped(b, sky), sky_hemispheric(b, 0.0));
        let (mut specular_sun, mut diffuse_sun) =
            (escaped_sunlight(b, sky), scattered_hemispheric(b, 0.0));
        if let (Some(beam), Some(geometry)) = (&b.sun, &self.sun) {
            let e = beam.normal_w_m2(0.0);
            let beam_diffuse = e * geometry.to_sun[2].max(0.0) * FRAC_1_PI;
            let glint = e * match &m.lobe {
                Some(lobe) => lobe.glint_per_sr(geometry, DVec3::Z, -dir),
                None if sfrac > 0.0 => glint_per_sr(geometry, refl, Mirror::Escaped(sky)),
                None => 0.0,
            };
            specular += glint;
            specular_sun += glint;
            diffuse += beam_diffuse;
            diffuse_sun += beam_diffuse;
        }
        let reflected = sfrac * specular + (1.0 - sfrac) * diffuse;
        TerrainTerms {
            emissivity: eps,
            leaving: eps * b.terrain_blackbody + (1.0 - eps) * reflected,
            solar: (1.0 - eps) * (sfrac * specular_sun + (1.0 - sfrac) * diffuse_sun),
        }
    }
}
