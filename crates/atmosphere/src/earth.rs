//! The spherical Earth of the horizon (thesis Figure 7): which rays leaving a sensor meet
//! the ground, and how far away. Paths through the air are plane-parallel (the models'
//! business); only the horizon and the ground's range are curved.

/// Earth radius in metres used for the horizon: LOWTRAN7's (6371.23 km), so the horizon
/// agrees with the tables' own geometry.
pub const EARTH_RADIUS_M: f64 = 6_371_230.0;

/// The nadir angle in degrees of the horizon seen from `sensor_altitude_m` above a
/// spherical Earth (thesis Figure 7): rays closer to nadir than this hit the ground, rays
/// farther from it escape to space. `asin(R / (R + h))`; 90° at or below the ground.
/// Refraction is ignored (it lowers the horizon by about 0.1° at 1 km).
#[must_use]
pub fn critical_nadir_angle_deg(sensor_altitude_m: f64) -> f64 {
    let h = sensor_altitude_m.max(0.0);
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
    fn horizon_and_ground_range() {
        assert!((critical_nadir_angle_deg(0.0) - 90.0).abs() < 1e-12);
        // From 700 m the horizon dips by acos(R/(R+h)) ≈ 0.849°.
        let dip = 90.0 - critical_nadir_angle_deg(700.0);
        assert!(
            (dip - (EARTH_RADIUS_M / (EARTH_RADIUS_M + 700.0))
                .acos()
                .to_degrees())
            .abs()
                < 1e-9
        );
        assert!((dip - 0.849).abs() < 1e-3);
        // Straight down: the altitude.
        assert!((range_to_ground_m(700.0, 0.0).unwrap() - 700.0).abs() < 1e-6);
        // 60° from nadir: h / cos 60° = 1400 m on a flat Earth; the curved ground falls away
        // by about t²·sin²60°/(2R) ≈ 0.115 m, lengthening the path by that / cos 60°.
        let r = range_to_ground_m(700.0, 60.0).unwrap();
        assert!((r - 1400.23).abs() < 0.01, "{r}");
        // The same by the cosine: cos 60° = 0.5.
        let r = range_to_ground_from_cos_m(700.0, 0.5).unwrap();
        assert!((r - 1400.23).abs() < 0.01, "{r}");
        assert!(range_to_ground_from_cos_m(700.0, 0.0).is_none());
        assert!(range_to_ground_m(700.0, 89.5).is_none());
        assert!(range_to_ground_m(700.0, 120.0).is_none());
    }
}
