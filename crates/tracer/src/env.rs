//! What the tracer needs from radiometry and from the atmosphere, as two small traits.
//!
//! The project's `irsig-radiometry` (`Band`) and `irsig-atmosphere` (`AtmosphereModel`)
//! provide the real models; the tools adapt them to these traits. The implementations
//! here are exact closed forms for tests and quick looks: [`TotalRadiance`] (the whole
//! spectrum, σT⁴/π) and [`Vacuum`] (no atmosphere, a uniform sky).

/// Band radiance of a blackbody and its inverse.
pub trait Radiometry: Sync {
    /// Band radiance of a blackbody at `temperature_k`, W m⁻² sr⁻¹.
    fn radiance(&self, temperature_k: f64) -> f64;
    /// dL/dT at `temperature_k`, W m⁻² sr⁻¹ K⁻¹.
    fn radiance_derivative(&self, temperature_k: f64) -> f64;
    /// The blackbody temperature in kelvin whose band radiance is `radiance_w_m2_sr`
    /// (the apparent temperature).
    fn temperature(&self, radiance_w_m2_sr: f64) -> f64;
}

/// Transmission and path radiance of one line of sight.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathTerms {
    /// Band transmittance of the path, 0 to 1.
    pub transmission: f64,
    /// Band path (upwelled) radiance added along the path, W m⁻² sr⁻¹.
    pub path_radiance_w_m2_sr: f64,
}

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
    fn critical_nadir_angle_deg(&self, sensor_altitude_m: f64) -> f64;
}

/// The whole-spectrum band: `L(T) = σT⁴/π`, exact inverse. For tests and for comparing
/// with hand computation.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct TotalRadiance;

/// Stefan–Boltzmann constant, W m⁻² K⁻⁴ (CODATA 2018, exact).
const SIGMA: f64 = 5.670_374_419e-8;

impl Radiometry for TotalRadiance {
    fn radiance(&self, temperature_k: f64) -> f64 {
        SIGMA * temperature_k.powi(4) / std::f64::consts::PI
    }
    fn radiance_derivative(&self, temperature_k: f64) -> f64 {
        4.0 * SIGMA * temperature_k.powi(3) / std::f64::consts::PI
    }
    fn temperature(&self, radiance_w_m2_sr: f64) -> f64 {
        if radiance_w_m2_sr <= 0.0 {
            0.0
        } else {
            (radiance_w_m2_sr * std::f64::consts::PI / SIGMA).powf(0.25)
        }
    }
}

/// Mean Earth radius used for the horizon and for the range to the ground, metres.
pub const EARTH_RADIUS_M: f64 = 6_371_000.0;

/// No atmosphere: τ = 1, no path radiance, and a sky of uniform radiance.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Vacuum {
    /// Radiance of the sky in every direction, W m⁻² sr⁻¹ (0 for cold space).
    pub sky_radiance_w_m2_sr: f64,
}

impl Atmosphere for Vacuum {
    fn path(&self, _: f64, _: f64, _: f64) -> PathTerms {
        PathTerms {
            transmission: 1.0,
            path_radiance_w_m2_sr: 0.0,
        }
    }
    fn sky_radiance(&self, _: f64, _: f64) -> f64 {
        self.sky_radiance_w_m2_sr
    }
    fn sky_hemispheric(&self, _: f64) -> f64 {
        self.sky_radiance_w_m2_sr
    }
    fn critical_nadir_angle_deg(&self, sensor_altitude_m: f64) -> f64 {
        critical_nadir_angle_deg(sensor_altitude_m)
    }
}

/// The nadir angle of the Earth's limb seen from `altitude_m` above a spherical Earth of
/// radius [`EARTH_RADIUS_M`] (thesis Figure 7): `asin(R / (R + h))`, 90° at the ground.
#[must_use]
pub fn critical_nadir_angle_deg(altitude_m: f64) -> f64 {
    let h = altitude_m.max(0.0);
    (EARTH_RADIUS_M / (EARTH_RADIUS_M + h)).asin().to_degrees()
}

/// Distance in metres from a point at `altitude_m` along a ray `nadir_deg` from nadir to a
/// spherical Earth's surface, or `None` when the ray misses it.
#[must_use]
pub fn range_to_ground_m(altitude_m: f64, nadir_deg: f64) -> Option<f64> {
    range_to_ground_from_cos_m(altitude_m, nadir_deg.to_radians().cos())
}

/// [`range_to_ground_m`] for a ray whose nadir angle has cosine `cos_nadir` (the negated
/// z of a unit direction: no angle needed).
#[must_use]
pub fn range_to_ground_from_cos_m(altitude_m: f64, cos_nadir: f64) -> Option<f64> {
    let h = altitude_m.max(0.0);
    let r0 = EARTH_RADIUS_M + h;
    // |o + t d|² = R² with o = (0, r0), d·o/|o| = −cos(nadir).
    let c = cos_nadir;
    let b = -r0 * c;
    let disc = b * b - (r0 * r0 - EARTH_RADIUS_M * EARTH_RADIUS_M);
    if disc < 0.0 || c <= 0.0 {
        return None;
    }
    // The nearer root, computed without cancellation: t = (r0² − R²) / (−b + √disc).
    let t = (h * (2.0 * EARTH_RADIUS_M + h)) / (-b + disc.sqrt());
    Some(t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn total_radiance_round_trips() {
        for t in [3.0, 77.0, 300.0, 1500.0] {
            let l = TotalRadiance.radiance(t);
            assert!((TotalRadiance.temperature(l) - t).abs() < 1e-9 * t);
        }
        // σ·300⁴/π by hand: 5.670374419e-8 · 8.1e9 = 459.3003; / π = 146.1995.
        assert!((TotalRadiance.radiance(300.0) - 146.199_5).abs() < 1e-3);
    }

    #[test]
    fn horizon_and_ground_range() {
        assert!((critical_nadir_angle_deg(0.0) - 90.0).abs() < 1e-12);
        // From 700 m the horizon dips by acos(R/(R+h)) ≈ 0.849°.
        let dip = 90.0 - critical_nadir_angle_deg(700.0);
        assert!((dip - (6_371_000.0_f64 / 6_371_700.0).acos().to_degrees()).abs() < 1e-9);
        assert!((dip - 0.849).abs() < 1e-3);
        // Straight down: the altitude; 60° from nadir: about h / cos 60° (curvature tiny).
        assert!((range_to_ground_m(700.0, 0.0).unwrap() - 700.0).abs() < 1e-6);
        // 60° from nadir: h / cos 60° = 1400 m on a flat Earth; the curved ground falls away
        // by about t²·sin²60°/(2R) ≈ 0.115 m, lengthening the path by that / cos 60°.
        let r = range_to_ground_m(700.0, 60.0).unwrap();
        assert!((r - 1400.23).abs() < 0.01, "{r}");
        // The same by the cosine the tracer passes: cos 60° = 0.5.
        let r = range_to_ground_from_cos_m(700.0, 0.5).unwrap();
        assert!((r - 1400.23).abs() < 0.01, "{r}");
        assert!(range_to_ground_from_cos_m(700.0, 0.0).is_none());
        assert!(range_to_ground_m(700.0, 89.5).is_none());
        assert!(range_to_ground_m(700.0, 120.0).is_none());
    }
}
