//! The phase-function runs of a day's table: the sunlight a short path scatters at each
//! scattering angle, so that a sun between the table's rows can be interpolated at its
//! own scattering angle (`crate::sunlit::between`).
//!
//! Why: a scattered-sunlight node is a fixed line of sight, and as the sun moves between
//! two rows the node's scattering angle moves with it. Near the sun the aerosol's forward
//! peak makes the node's radiance fall by half in 5° (LOWTRAN7's rural aerosol in
//! 3.4–4.1 µm: 0.234 W m⁻² sr⁻¹ on the sun, 0.106 at 5° from it, on a sky path from the
//! ground at zenith 60°), and no interpolation in the sun's angle alone follows that. A
//! single-scattered radiance is the phase function at the node's scattering angle times a
//! factor that varies smoothly with the sun (its beam down to each scattering point and the
//! path's transmittance onward), so the build measures the phase function's shape and the
//! interpolation divides it out.
//!
//! How: at each altitude of the solar table, a slab 100 m thick above it is run with a sun
//! 45° from the zenith ([`SUN_ZENITH_DEG`]), its line of sight in the sun's vertical plane
//! at the angle that puts the scattering angle at one of LOWTRAN7's own phase-function
//! angles ([`SCATTERING_DEG`], between which LOWTRAN7 interpolates the logarithm
//! linearly). With the sun at 45°, every scattering angle is reached by a line of sight
//! within 45° of the vertical: the path is at most 141 m long and its air is the layer's.
//! The scattered radiance divided by the path's length is the layer's phase function
//! times a factor common to every angle (the beam's strength there).

use irsig_model::{AtmospherePlan, SolarPhase};

use super::Path;

/// The scattering angles of LOWTRAN7's tabulated aerosol phase functions, degrees
/// (LOWTRAN7's `ANG`, in `PHASEF`): a phase function measured at these and interpolated as
/// LOWTRAN7 interpolates it is LOWTRAN7's own in each layer.
pub const SCATTERING_DEG: [f64; 34] = [
    0.0, 2.0, 4.0, 6.0, 8.0, 10.0, 12.0, 16.0, 20.0, 24.0, 28.0, 32.0, 36.0, 40.0, 50.0, 60.0,
    70.0, 80.0, 90.0, 100.0, 110.0, 120.0, 125.0, 130.0, 135.0, 140.0, 145.0, 150.0, 155.0, 160.0,
    165.0, 170.0, 175.0, 180.0,
];

/// The sun's zenith angle of the phase-function runs, degrees: any scattering angle is then
/// reached by a line of sight within 45° of the vertical.
pub const SUN_ZENITH_DEG: f64 = 45.0;

/// The thickness of the layer a phase-function run crosses, metres.
pub const LAYER_M: f64 = 100.0;

/// The slab of one phase-function run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PhaseSlab {
    /// Observer altitude, metres.
    pub observer_m: f64,
    /// Target altitude, metres.
    pub target_m: f64,
    /// Zenith angle of the line of sight at the observer, degrees (above 90: down).
    pub zenith_deg: f64,
    /// Azimuth of the line of sight from the sun's vertical plane, degrees: 0 or 180.
    pub azimuth_deg: f64,
    /// The slab's length, metres.
    pub length_m: f64,
}

/// The slab that scatters the sun at [`SUN_ZENITH_DEG`] by `scattering_deg` (0–180) into
/// the layer above `altitude_m` (or above the paths' end `path_end_m`, when higher).
///
/// The line of sight lies in the sun's vertical plane. Looking up at zenith ζ toward the
/// sun's azimuth, the angle is |ζ − 45°|; away from it, ζ + 45°. Looking down at nadir n
/// toward the sun's azimuth, 135° − n; away from it, 135° + n.
#[must_use]
pub fn slab(altitude_m: f64, scattering_deg: f64, path_end_m: f64) -> PhaseSlab {
    let z = SUN_ZENITH_DEG;
    let t = scattering_deg.clamp(0.0, 180.0);
    let (up, angle, azimuth_deg) = if t <= z {
        (true, z - t, 0.0)
    } else if t <= 90.0 {
        (true, t - z, 180.0)
    } else if t <= 180.0 - z {
        (false, 180.0 - z - t, 0.0)
    } else {
        (false, t - (180.0 - z), 180.0)
    };
    let bottom = altitude_m.max(path_end_m);
    let top = bottom + LAYER_M;
    let length_m = LAYER_M / angle.to_radians().cos();
    if up {
        PhaseSlab {
            observer_m: bottom,
            target_m: top,
            zenith_deg: angle,
            azimuth_deg,
            length_m,
        }
    } else {
        PhaseSlab {
            observer_m: top,
            target_m: bottom,
            zenith_deg: 180.0 - angle,
            azimuth_deg,
            length_m,
        }
    }
}

/// The layer bottoms and scattering angles of `plan`'s phase-function runs,
/// `[altitude][angle]` over the sun's altitudes and [`SCATTERING_DEG`]: none without a sun
/// that has relative azimuths (scattered sunlight) and further suns to interpolate between.
fn runs(plan: &AtmospherePlan) -> Vec<(f64, f64)> {
    let Some(sun) = plan
        .sun
        .as_ref()
        .filter(|s| !(s.relative_azimuth_deg.is_empty() || s.further_zenith_deg.is_empty()))
    else {
        return Vec::new();
    };
    sun.altitude_m
        .iter()
        .flat_map(|&altitude_m| SCATTERING_DEG.iter().map(move |&t| (altitude_m, t)))
        .collect()
}

/// The phase-function runs of `plan` ([`runs`]).
#[must_use]
pub fn phase_paths(plan: &AtmospherePlan) -> Vec<Path> {
    runs(plan)
        .into_iter()
        .map(|(altitude_m, scattering_deg)| Path::Phase {
            altitude_m,
            scattering_deg,
        })
        .collect()
}

/// The solar table's phase function from the runs' scattered spectra (`scattered`, W m⁻²
/// sr⁻¹ per grid unit), each divided by its slab's length; none when the plan does not
/// run it.
pub(super) fn assemble(
    plan: &AtmospherePlan,
    scattered: &dyn Fn(Path) -> Vec<f32>,
) -> Option<SolarPhase> {
    let runs = runs(plan);
    if runs.is_empty() {
        return None;
    }
    let mut values = Vec::new();
    for (altitude_m, scattering_deg) in runs {
        let length = slab(altitude_m, scattering_deg, plan.path_end_m).length_m;
        let spectrum = scattered(Path::Phase {
            altitude_m,
            scattering_deg,
        });
        #[allow(clippy::cast_possible_truncation)] // spectra are f32
        values.extend(spectrum.iter().map(|&v| (f64::from(v) / length) as f32));
    }
    Some(SolarPhase {
        scattering_deg: SCATTERING_DEG.to_vec(),
        scattered_w_m2_sr_per_unit_per_m: values,
    })
}

#[cfg(test)]
#[allow(clippy::float_cmp)] // altitudes in whole metres, sums exact
mod tests {
    use super::*;

    /// The scattering angle between a line of sight `zenith_deg` from straight up,
    /// `azimuth_deg` from the sun's vertical plane, and the sun 45° from the zenith: the
    /// spherical law of cosines, written apart from [`slab`]'s cases.
    fn angle(zenith_deg: f64, azimuth_deg: f64) -> f64 {
        let (l, a, s) = (
            zenith_deg.to_radians(),
            azimuth_deg.to_radians(),
            SUN_ZENITH_DEG.to_radians(),
        );
        (l.cos() * s.cos() + l.sin() * s.sin() * a.cos())
            .clamp(-1.0, 1.0)
            .acos()
            .to_degrees()
    }

    #[test]
    fn every_scattering_angle_is_reached_by_a_short_slab_in_its_layer() {
        for t in SCATTERING_DEG
            .into_iter()
            .chain([1.0, 44.9, 45.1, 90.5, 135.5, 179.9])
        {
            for altitude in [0.0, 1000.0, 12_345.0] {
                let s = slab(altitude, t, 1.0);
                let got = angle(s.zenith_deg, s.azimuth_deg);
                assert!((got - t).abs() < 1e-9, "{t}: {s:?} scatters by {got}");
                let (lo, hi) = (s.observer_m.min(s.target_m), s.observer_m.max(s.target_m));
                assert_eq!(lo, altitude.max(1.0), "{t}: {s:?}");
                assert_eq!(hi - lo, LAYER_M, "{t}: {s:?}");
                // Down when the line of sight points below the horizon.
                assert_eq!(s.zenith_deg > 90.0, s.observer_m > s.target_m, "{t}: {s:?}");
                // Within 45 deg of the vertical: at most √2 × the layer.
                let tilt = s.zenith_deg.min(180.0 - s.zenith_deg);
                assert!(tilt <= 45.0 + 1e-9, "{t}: {s:?}");
                let want = LAYER_M / tilt.to_radians().cos();
                assert!((s.length_m - want).abs() < 1e-9, "{t}: {s:?}");
            }
        }
    }
}
