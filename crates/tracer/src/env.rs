//! What the tracer needs from the atmosphere, as a small trait (the band comes in through
//! `irsig_radiometry::BandModel`).
//!
//! `irsig-atmosphere` provides the real models: [`PrecomputedAtmosphere`] (its sky
//! precomputed per altitude, what a renderer wants) and [`AtmosphereModel`] (every query
//! computed afresh). [`Vacuum`] is an exact closed form for tests and quick looks (no
//! atmosphere, a uniform sky).

use irsig_atmosphere::scattered::ScatteredSunlight;
use irsig_atmosphere::slab::SlabPaths;
use irsig_atmosphere::{
    AtmosphereModel, PathTerms, PrecomputedAtmosphere, critical_nadir_angle_deg,
};

/// The atmosphere as the tracer uses it. Altitudes are above the ground (z = 0), metres.
pub trait Atmosphere: Sync {
    /// The path between a sensor at `sensor_altitude_m` and a point at
    /// `target_altitude_m`, `range_m` apart (both ends of the path count).
    fn path(&self, sensor_altitude_m: f64, target_altitude_m: f64, range_m: f64) -> PathTerms;
    /// Sky radiance reaching an observer at `observer_altitude_m` from zenith angle
    /// `zenith_deg` (0 straight up; beyond 90 below the local horizontal but above the
    /// Earth's limb), W m⁻² sr⁻¹.
    fn sky_radiance(&self, observer_altitude_m: f64, zenith_deg: f64) -> f64;
    /// The cosine-weighted hemispheric sky radiance at `observer_altitude_m` (thesis eq. 5),
    /// W m⁻² sr⁻¹.
    fn sky_hemispheric(&self, observer_altitude_m: f64) -> f64;
    /// Rays leaving the sensor closer to nadir than this angle (degrees) meet the Earth
    /// (thesis Figure 7, spherical Earth).
    fn critical_nadir_angle_deg(&self, sensor_altitude_m: f64) -> f64 {
        critical_nadir_angle_deg(sensor_altitude_m)
    }
    /// The atmosphere model underneath, when the path terms are an
    /// [`AtmosphereModel`]'s: then sub-bands whose models share grids locate each path
    /// once ([`AtmosphereModel::locate_path`]) and evaluate it in each.
    fn model(&self) -> Option<&AtmosphereModel> {
        None
    }
    /// By day, the sunlight scattered into the paths and the sky, which depends on a
    /// line of sight's azimuth from the sun as well as its angle: added to `path`,
    /// `sky_radiance` and `sky_hemispheric` (which hold the air's own emission) wherever
    /// the tracer has the direction ([`crate::shade`]). `None`, the default, at night and
    /// without scattered tables: then nothing is computed or added.
    fn scattered(&self) -> Option<&ScatteredSunlight> {
        None
    }
    /// The slab tables (`irsig_atmosphere::slab`), when the atmosphere has them: `path`
    /// already gives their τ and thermal path radiance where they cover a path; by day the
    /// sunlight scattered into such a path is theirs too ([`crate::day`]). `None`, the
    /// default, without them.
    fn slabs(&self) -> Option<&SlabPaths> {
        None
    }
}

impl Atmosphere for PrecomputedAtmosphere {
    fn path(&self, sensor_altitude_m: f64, target_altitude_m: f64, range_m: f64) -> PathTerms {
        PrecomputedAtmosphere::path(self, sensor_altitude_m, target_altitude_m, range_m)
    }
    fn sky_radiance(&self, observer_altitude_m: f64, zenith_deg: f64) -> f64 {
        PrecomputedAtmosphere::sky_radiance(self, observer_altitude_m, zenith_deg)
    }
    fn sky_hemispheric(&self, observer_altitude_m: f64) -> f64 {
        PrecomputedAtmosphere::sky_hemispheric(self, observer_altitude_m)
    }
    fn model(&self) -> Option<&AtmosphereModel> {
        // With slab tables the path terms are not the model's alone: each sub-band's
        // `path` decides (the shared-grid shortcut would pass them by).
        match PrecomputedAtmosphere::slabs(self) {
            Some(_) => None,
            None => Some(PrecomputedAtmosphere::model(self)),
        }
    }
    fn scattered(&self) -> Option<&ScatteredSunlight> {
        PrecomputedAtmosphere::scattered(self)
    }
    fn slabs(&self) -> Option<&SlabPaths> {
        PrecomputedAtmosphere::slabs(self)
    }
}

/// Every query computed afresh: exact, but a sky ray past 83° fits a quadratic and the
/// hemispheric sky integrates eq. 5 per call. Renderers want [`PrecomputedAtmosphere`].
impl Atmosphere for AtmosphereModel {
    fn path(&self, sensor_altitude_m: f64, target_altitude_m: f64, range_m: f64) -> PathTerms {
        AtmosphereModel::path(self, sensor_altitude_m, target_altitude_m, range_m)
    }
    fn sky_radiance(&self, observer_altitude_m: f64, zenith_deg: f64) -> f64 {
        AtmosphereModel::sky_radiance(self, observer_altitude_m, zenith_deg)
    }
    fn sky_hemispheric(&self, observer_altitude_m: f64) -> f64 {
        AtmosphereModel::sky_hemispheric(self, observer_altitude_m).radiance_w_m2_sr
    }
    fn model(&self) -> Option<&AtmosphereModel> {
        Some(self)
    }
}

/// No atmosphere: τ = 1, no path radiance, and a sky of uniform radiance.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Vacuum {
    /// Radiance of the sky in every direction, W m⁻² sr⁻¹ (0 for cold space).
    pub sky_radiance_w_m2_sr: f64,
}

impl Atmosphere for Vacuum {
    fn path(&self, _: f64, _: f64, _: f64) -> PathTerms {
        PathTerms::VACUUM
    }
    fn sky_radiance(&self, _: f64, _: f64) -> f64 {
        self.sky_radiance_w_m2_sr
    }
    fn sky_hemispheric(&self, _: f64) -> f64 {
        self.sky_radiance_w_m2_sr
    }
}
