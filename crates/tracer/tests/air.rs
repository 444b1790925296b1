//! One type for the closed-form atmospheres of several of these tests: each test keeps its
//! own functions, and the tracer's code is compiled for this type once, where a type per
//! test compiled it once per test (five types: this binary took 120 CPU-seconds to build
//! with them, 89 with this one).

use irsig_atmosphere::PathTerms;
use irsig_tracer::Atmosphere;

/// An atmosphere given by three functions: the path terms of (sensor altitude m, target
/// altitude m, range m); the sky radiance at (observer altitude m, zenith angle degrees);
/// the hemispheric sky at an observer altitude, W m⁻² sr⁻¹.
#[derive(Debug, Clone, Copy)]
pub struct FnAir {
    pub path: fn(f64, f64, f64) -> PathTerms,
    pub sky: fn(f64, f64) -> f64,
    pub hemispheric: fn(f64) -> f64,
}

impl Atmosphere for FnAir {
    fn path(&self, sensor_altitude_m: f64, target_altitude_m: f64, range_m: f64) -> PathTerms {
        (self.path)(sensor_altitude_m, target_altitude_m, range_m)
    }
    fn sky_radiance(&self, observer_altitude_m: f64, zenith_deg: f64) -> f64 {
        (self.sky)(observer_altitude_m, zenith_deg)
    }
    fn sky_hemispheric(&self, observer_altitude_m: f64) -> f64 {
        (self.hemispheric)(observer_altitude_m)
    }
}

/// The budget tests' air: `τ = e^{−2·10⁻⁴ r}` over a range `r` in metres, a path radiance of
/// `(1 − τ)·30`, a sky of `10 + 20 (z/90°)²` and a hemispheric sky of 18 W m⁻² sr⁻¹.
pub const BUDGET_AIR: FnAir = FnAir {
    path: |_, _, range_m| {
        let t = (-2e-4 * range_m).exp();
        PathTerms {
            transmission: t,
            path_radiance_w_m2_sr: (1.0 - t) * 30.0,
        }
    },
    sky: |_, zenith_deg| 10.0 + 20.0 * (zenith_deg / 90.0).powi(2),
    hemispheric: |_| 18.0,
};
