//! `irsig-atmosphere`'s model as the tracer's [`Atmosphere`]: the sky is precomputed as
//! [`SkyView`]s on a grid of observer altitudes spanning the scene and the sensors, so a
//! ray costs a table lookup instead of an integration.

use irsig_atmosphere::{AtmosphereModel, SkyView};
use irsig_tracer::{Atmosphere, PathTerms};

/// An atmosphere model with its sky precomputed between two altitudes.
#[derive(Debug)]
pub struct Precomputed {
    model: AtmosphereModel,
    /// `(altitude_m, sky view, hemispheric radiance)`, altitudes increasing.
    levels: Vec<(f64, SkyView, f64)>,
    /// Warnings the model raised (a given hemispheric sky that disagrees with eq. 5).
    pub warnings: Vec<String>,
}

/// Altitude levels of the precomputed sky.
const LEVELS: usize = 33;

impl Precomputed {
    /// Precomputes the sky at [`LEVELS`] altitudes from the ground to `max_altitude_m`.
    #[must_use]
    pub fn new(model: AtmosphereModel, max_altitude_m: f64) -> Self {
        let top = max_altitude_m.max(1.0);
        let mut warnings = Vec::new();
        let levels = (0..LEVELS)
            .map(|i| {
                let h = top * i as f64 / (LEVELS - 1) as f64;
                let hemi = model.sky_hemispheric(h);
                if let Some(w) = hemi.warning {
                    if !warnings.contains(&w) {
                        warnings.push(w);
                    }
                }
                (h, model.sky_view(h), hemi.radiance_w_m2_sr)
            })
            .collect();
        Self {
            model,
            levels,
            warnings,
        }
    }

    /// The two levels around `altitude_m` and the weight of the upper one.
    fn bracket(&self, altitude_m: f64) -> (usize, usize, f64) {
        let n = self.levels.len();
        let top = self.levels[n - 1].0;
        let x = (altitude_m.max(0.0) / top * (n - 1) as f64).min((n - 1) as f64);
        let i = (x.floor() as usize).min(n - 2);
        (i, i + 1, x - i as f64)
    }
}

impl Atmosphere for Precomputed {
    fn path(&self, sensor_altitude_m: f64, target_altitude_m: f64, range_m: f64) -> PathTerms {
        let p = self
            .model
            .path(sensor_altitude_m, target_altitude_m, range_m);
        PathTerms {
            transmission: p.transmission,
            path_radiance_w_m2_sr: p.path_radiance_w_m2_sr,
        }
    }
    fn sky_radiance(&self, observer_altitude_m: f64, zenith_deg: f64) -> f64 {
        let (a, b, w) = self.bracket(observer_altitude_m);
        (1.0 - w) * self.levels[a].1.radiance(zenith_deg)
            + w * self.levels[b].1.radiance(zenith_deg)
    }
    fn sky_hemispheric(&self, observer_altitude_m: f64) -> f64 {
        let (a, b, w) = self.bracket(observer_altitude_m);
        (1.0 - w) * self.levels[a].2 + w * self.levels[b].2
    }
    fn critical_nadir_angle_deg(&self, sensor_altitude_m: f64) -> f64 {
        self.model.critical_nadir_angle_deg(sensor_altitude_m)
    }
}
