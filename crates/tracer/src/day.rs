//! By day: the sunlight the atmosphere scatters ([`Atmosphere::scattered`]) added where
//! the radiance equation reads the sky or a path. Each helper gives the night's value
//! itself, with nothing computed, when the atmosphere has no scattered sunlight.

use irsig_atmosphere::PathTerms;

use crate::env::Atmosphere;
use crate::path::Escape;
use crate::tracer::BandData;
use glam::DVec3;

/// The sunlight in what arrives along a ray that left the scene (`shade::escaped`): the
/// scattered sky's, or the sunlit terrain's.
#[inline]
pub(crate) fn escaped_sunlight<A: Atmosphere>(b: &BandData<A>, e: Escape) -> f64 {
    match e {
        Escape::Sky {
            alt_m,
            zenith_deg,
            dir,
        } => scattered_sky(b, alt_m, zenith_deg, dir),
        Escape::Terrain => b.terrain_solar,
    }
}

/// The sky seen from `alt_m` at `zenith_deg` along `dir` in sub-band `b`: the air's own
/// radiance, and by day the sunlight it scatters ([`Atmosphere::scattered`]).
#[inline]
pub(crate) fn sky<A: Atmosphere>(b: &BandData<A>, alt_m: f64, zenith_deg: f64, dir: DVec3) -> f64 {
    let thermal = b.atmosphere.sky_radiance(alt_m, zenith_deg);
    match b.atmosphere.scattered() {
        None => thermal,
        Some(s) => thermal + s.sky(alt_m, zenith_deg, dir.to_array()),
    }
}

/// The scattered sunlight in [`sky`] (0 at night).
#[inline]
pub(crate) fn scattered_sky<A: Atmosphere>(
    b: &BandData<A>,
    alt_m: f64,
    zenith_deg: f64,
    dir: DVec3,
) -> f64 {
    b.atmosphere
        .scattered()
        .map_or(0.0, |s| s.sky(alt_m, zenith_deg, dir.to_array()))
}

/// The hemispheric sky at `alt_m` in sub-band `b` (thesis eq. 5): the air's own, and by
/// day the scattered sunlight's.
#[inline]
pub(crate) fn sky_hemispheric<A: Atmosphere>(b: &BandData<A>, alt_m: f64) -> f64 {
    let thermal = b.atmosphere.sky_hemispheric(alt_m);
    match b.atmosphere.scattered() {
        None => thermal,
        Some(s) => thermal + s.sky_hemispheric(alt_m),
    }
}

/// The scattered sunlight in [`sky_hemispheric`] (0 at night).
#[inline]
pub(crate) fn scattered_hemispheric<A: Atmosphere>(b: &BandData<A>, alt_m: f64) -> f64 {
    b.atmosphere
        .scattered()
        .map_or(0.0, |s| s.sky_hemispheric(alt_m))
}

/// The path terms `p` of the view path from the sensor at `sensor_m` along `dir` to a
/// point at `target_m`, by day with the sunlight scattered into it added to its radiance
/// (the slab tables' where they cover the path, `irsig_atmosphere::slab`; else the
/// difference of two paths, `irsig_atmosphere::scattered`), and that sunlight; at night
/// `p` itself and 0.
#[inline]
pub(crate) fn lit_path<A: Atmosphere>(
    b: &BandData<A>,
    p: PathTerms,
    sensor_m: f64,
    target_m: f64,
    dir: DVec3,
) -> (PathTerms, f64) {
    match b.atmosphere.scattered() {
        None => (p, 0.0),
        Some(s) => {
            let slab = b.atmosphere.slabs().and_then(|t| {
                let cell = t.covers_along(sensor_m, target_m, dir[2])?;
                t.scattered(&cell, s.relative_azimuth_deg(dir.to_array()))
            });
            let scattered =
                slab.unwrap_or_else(|| s.path(sensor_m, target_m, p.transmission, dir.to_array()));
            (
                PathTerms {
                    path_radiance_w_m2_sr: p.path_radiance_w_m2_sr + scattered,
                    ..p
                },
                scattered,
            )
        }
    }
}
