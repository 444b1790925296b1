//! The scattered sunlight of a sun between a day table's suns.
//!
//! A table of several suns (`SpectralSolar::further_suns`, one build for a whole day)
//! holds the scattered-sunlight spectra of each sun on the same nodes. A sun between them
//! is given, at every node (altitude, angle, azimuth from the sun), the band value of the
//! rows around it interpolated by a monotone cubic in the logarithm of the value against
//! the Kasten & Young (1989) relative air mass, as the direct beam is
//! (`crate::solar::DirectSun::at_zenith`).
//!
//! Why that interpolant: single-scattered sunlight is the sun's beam at each scattering
//! point, `E_toa e^{−k m}` with the air mass `m` of the path down to it, times the phase
//! function at the node's scattering angle and the path's transmittance onward. The
//! scattering angle of a fixed line of sight moves with the sun, and near the sun the
//! aerosol's forward peak halves the radiance in 5°: so when the table holds the phase
//! function the build measured (`SpectralSolar::phase`, LOWTRAN7's own at its tabulated
//! angles, interpolated between them as LOWTRAN7 does, the logarithm linear in the
//! angle), each row's value is divided by it at that row's scattering angle first, and
//! the result multiplied by it at the sun's own. What is left is the beam and the
//! transmittances: the logarithm against air mass makes the beam, which changes fastest
//! toward the horizon, nearly a line, and the cubic follows the rest, never overshooting
//! the rows around it (so never below 0). A slant node takes the phase function measured
//! at the solar table's altitude nearest its observer, a sky node its own altitude's. The
//! cubic is local: the value between rows `i` and `i + 1` uses rows `i − 1` to `i + 2`
//! only, and only those are integrated over the band. Its error against LOWTRAN7 run for
//! the sun itself is measured in `tests/tests/scattered_day.rs` and tabled in
//! `docs/accuracy.md` ("A day's scattered sunlight").

use irsig_model::{SolarPhase, SpectralSlantTables, SpectralSolar};

use crate::error::{AtmosphereError, AtmosphereErrorKind};
use crate::interp;
use crate::loads::kasten_young_air_mass;
use crate::solar::ZENITH_TOLERANCE_DEG;

/// Below this, W m⁻² sr⁻¹, an interpolated scattered radiance is none: the logarithm of 0
/// is taken at this floor (as the beam's), so that a row with none pulls its neighbours
/// down without an infinity, and what comes back at the floor (to twice it) is 0 again.
const SCATTERED_FLOOR_W_M2_SR: f64 = 1e-30;

/// The scattered spectra (slant paths, sky) of row `row` of `solar`'s suns.
fn row_spectra(solar: &SpectralSolar, row: usize) -> Option<(&[f32], &[f32])> {
    match row {
        0 => Some((
            &solar.path_scattered_w_m2_sr_per_unit,
            &solar.sky_scattered_w_m2_sr_per_unit,
        )),
        _ => solar.further_suns.get(row - 1).map(|b| {
            (
                b.path_scattered_w_m2_sr_per_unit.as_slice(),
                b.sky_scattered_w_m2_sr_per_unit.as_slice(),
            )
        }),
    }
}

/// The angle between a line of sight `los_zenith_deg` from straight up and
/// `azimuth_deg` from the sun's vertical plane and a sun `sun_zenith_deg` from the zenith,
/// degrees.
fn scattering_angle_deg(los_zenith_deg: f64, azimuth_deg: f64, sun_zenith_deg: f64) -> f64 {
    let (l, a, s) = (
        los_zenith_deg.to_radians(),
        azimuth_deg.to_radians(),
        sun_zenith_deg.to_radians(),
    );
    (l.cos() * s.cos() + l.sin() * s.sin() * a.cos())
        .clamp(-1.0, 1.0)
        .acos()
        .to_degrees()
}

/// A table's measured phase function in one band: the natural logarithm of the band value
/// at each altitude and angle, `[altitude][angle]`.
struct Phase<'a> {
    angles: &'a [f64],
    log: Vec<Vec<f64>>,
}

impl<'a> Phase<'a> {
    /// `phase`'s band values over `altitudes` altitudes; none when any is not positive
    /// (a band the aerosol does not scatter in: the nodes are interpolated as they are).
    fn new(
        phase: &'a SolarPhase,
        altitudes: usize,
        band: &dyn Fn(&[f32]) -> Vec<f64>,
    ) -> Option<Self> {
        let values = band(&phase.scattered_w_m2_sr_per_unit_per_m);
        let per = phase.scattering_deg.len();
        if per < 2
            || values.len() != altitudes * per
            || !values.iter().all(|&v| v > 0.0 && v.is_finite())
        {
            return None;
        }
        Some(Self {
            angles: &phase.scattering_deg,
            log: values
                .chunks_exact(per)
                .map(|c| c.iter().map(|v| v.ln()).collect())
                .collect(),
        })
    }

    /// The logarithm of the phase function at `angle_deg` in the layer of altitude
    /// `altitude`: linear in the angle between the measured angles, as LOWTRAN7
    /// interpolates its own.
    fn log_at(&self, altitude: usize, angle_deg: f64) -> f64 {
        interp::linear(self.angles, &self.log[altitude], angle_deg)
    }
}

/// Where each node of a table lies: its line of sight's zenith angle, its azimuth from the
/// sun, and the altitude of the phase function it takes.
#[derive(Debug, Clone, Copy)]
struct Node {
    los_zenith_deg: f64,
    azimuth_deg: f64,
    phase_altitude: usize,
}

/// The nodes of the slant paths' and the sky's scattered-sunlight tables, in their order.
fn nodes(solar: &SpectralSolar, slant: &SpectralSlantTables) -> (Vec<Node>, Vec<Node>) {
    let nearest = |h: f64| {
        (0..solar.altitude_m.len())
            .min_by(|&a, &b| {
                (solar.altitude_m[a] - h)
                    .abs()
                    .total_cmp(&(solar.altitude_m[b] - h).abs())
            })
            .unwrap_or(0)
    };
    let mut path = Vec::new();
    for &h in &slant.altitude_m {
        for &n in &slant.nadir_deg {
            for &az in &solar.relative_azimuth_deg {
                path.push(Node {
                    los_zenith_deg: 180.0 - n,
                    azimuth_deg: az,
                    phase_altitude: nearest(h),
                });
            }
        }
    }
    let mut sky = Vec::new();
    for a in 0..solar.altitude_m.len() {
        for &z in &slant.sky_zenith_deg {
            for &az in &solar.relative_azimuth_deg {
                sky.push(Node {
                    los_zenith_deg: z,
                    azimuth_deg: az,
                    phase_altitude: a,
                });
            }
        }
    }
    (path, sky)
}

/// The band values of the scattered sunlight (slant paths, sky) of a sun `zenith_deg`
/// from the zenith, from `solar`'s table of several suns on `slant`'s nodes, each row's
/// spectra reduced to band values by `band` (one value per spectrum).
///
/// # Errors
/// A zenith angle that is not finite or lies outside the table's suns (each end widened
/// by [`ZENITH_TOLERANCE_DEG`]): the scattered sunlight is not extrapolated; a further sun
/// without scattered spectra (a table the model's validation refuses).
pub(crate) fn scattered_between(
    solar: &SpectralSolar,
    slant: &SpectralSlantTables,
    zenith_deg: f64,
    band: &dyn Fn(&[f32]) -> Vec<f64>,
) -> Result<(Vec<f64>, Vec<f64>), AtmosphereError> {
    let zeniths = solar.zeniths_deg();
    let (first, last) = (zeniths[0], zeniths[zeniths.len() - 1]);
    if !(zenith_deg.is_finite()
        && zenith_deg >= first - ZENITH_TOLERANCE_DEG
        && zenith_deg <= last + ZENITH_TOLERANCE_DEG)
    {
        return Err(AtmosphereErrorKind::Solar(format!(
            "the sun is {zenith_deg:.4} deg from the zenith, but the atmosphere's \
             scattered-sunlight tables hold suns from {first} to {last} deg (interpolated \
             between them, not beyond): build the atmosphere for suns that cover this one"
        ))
        .into());
    }
    let sun = zenith_deg.clamp(first, last);
    let air_mass: Vec<f64> = zeniths.iter().map(|&z| kasten_young_air_mass(z)).collect();
    let (i, f) = interp::locate(&air_mass, kasten_young_air_mass(sun));
    let lo = i.saturating_sub(1);
    let hi = (i + 2).min(zeniths.len() - 1);
    let mut path_rows = Vec::with_capacity(hi - lo + 1);
    let mut sky_rows = Vec::with_capacity(hi - lo + 1);
    for (row, zenith) in zeniths.iter().enumerate().take(hi + 1).skip(lo) {
        let (path, sky) = row_spectra(solar, row)
            .filter(|(p, s)| !(p.is_empty() || s.is_empty()))
            .ok_or_else(|| {
                AtmosphereError::from(AtmosphereErrorKind::Solar(format!(
                    "the sun at {zenith} deg of the atmosphere's solar table has no \
                     scattered-sunlight spectra: every sun of a table with relative azimuths \
                     must hold them"
                )))
            })?;
        path_rows.push(band(path));
        sky_rows.push(band(sky));
    }
    let phase = solar
        .phase
        .as_ref()
        .and_then(|p| Phase::new(p, solar.altitude_m.len(), band));
    let (path_nodes, sky_nodes) = nodes(solar, slant);
    let xs = &air_mass[lo..=hi];
    let suns = &zeniths[lo..=hi];
    let between = |rows: &[Vec<f64>], nodes: &[Node]| -> Vec<f64> {
        let count = rows.iter().map(Vec::len).min().unwrap_or(0);
        (0..count)
            .map(|k| {
                // The phase function's logarithm at each row's scattering angle and at the
                // sun's, where the node has a place and every row some light.
                let lit = rows.iter().all(|r| r[k] > SCATTERED_FLOOR_W_M2_SR);
                let factor = |z: f64| match (&phase, nodes.get(k)) {
                    (Some(p), Some(n)) if lit => p.log_at(
                        n.phase_altitude,
                        scattering_angle_deg(n.los_zenith_deg, n.azimuth_deg, z),
                    ),
                    _ => 0.0,
                };
                let log: Vec<f64> = rows
                    .iter()
                    .zip(suns)
                    .map(|(r, &z)| r[k].max(SCATTERED_FLOOR_W_M2_SR).ln() - factor(z))
                    .collect();
                let v = (interp::monotone_cubic_located(xs, &log, i - lo, f) + factor(sun)).exp();
                if v < 2.0 * SCATTERED_FLOOR_W_M2_SR {
                    0.0
                } else {
                    v
                }
            })
            .collect()
    };
    Ok((
        between(&path_rows, &path_nodes),
        between(&sky_rows, &sky_nodes),
    ))
}

#[cfg(test)]
#[allow(clippy::float_cmp)] // rows copied, not computed
mod tests {
    use irsig_model::{
        ProfileLevel, SolarBeam, SpectralAtmosphere, SpectralAxis, SpectralGrid,
        SpectralSlantTables,
    };

    use crate::sunlit::SunlitPaths;

    /// Kasten & Young's (1989) relative air mass, written out from the paper:
    /// `m = 1 / (cos z + 0.50572 (96.07995 − z)^−1.6364)`.
    fn air_mass(zenith_deg: f64) -> f64 {
        1.0 / (zenith_deg.to_radians().cos() + 0.50572 * (96.07995 - zenith_deg).powf(-1.6364))
    }

    /// Scattered sunlight that follows the beam to each scattering point, Beer's law in
    /// the air mass: `c e^{−k m}`, flat over the band, W m⁻² sr⁻¹ per µm.
    fn beer(c: f64, k: f64, zenith_deg: f64) -> f64 {
        c * (-k * air_mass(zenith_deg)).exp()
    }

    /// A 3–5 µm atmosphere (5 points) with one slant node (1 km, nadir 0), one sky node
    /// (0 m, zenith 0), two azimuths, and suns at `zeniths` whose scattered sunlight is
    /// [`beer`]: slant `0.02 e^{−0.3 m}` at azimuth 0 and `0.01 e^{−0.5 m}` at 180, sky
    /// `0.04 e^{−0.2 m}` and 0 (none at all: an opaque node).
    fn day(zeniths: &[f64]) -> SpectralAtmosphere {
        let n = 5;
        let spectra = |values: &[f64]| -> Vec<f32> {
            values
                .iter()
                .flat_map(|&v| std::iter::repeat_n(v as f32, n))
                .collect()
        };
        let path = |z: f64| spectra(&[beer(0.02, 0.3, z), beer(0.01, 0.5, z)]);
        let sky = |z: f64| spectra(&[beer(0.04, 0.2, z), 0.0]);
        let atm = SpectralAtmosphere {
            name: "t".into(),
            source: "test".into(),
            grid: SpectralGrid {
                axis: SpectralAxis::WavelengthUm,
                points: vec![3.0, 3.5, 4.0, 4.5, 5.0],
            },
            levels: vec![ProfileLevel {
                altitude_asl_m: 1000.0,
                temperature_k: 281.0,
                altitude_m: 1000.0,
            }],
            level_transmission: vec![0.5; n],
            level_path_radiance_w_m2_sr_per_unit: vec![0.1; n],
            transmission_correction: None,
            sky_zenith_deg: vec![0.0],
            sky_radiance_w_m2_sr_per_unit: vec![0.1; n],
            sky_hemispheric_w_m2_sr_per_unit: None,
            radiosonde: vec![],
            slant: Some(SpectralSlantTables {
                altitude_m: vec![1000.0],
                nadir_deg: vec![0.0],
                ground_m: None,
                transmission: vec![0.5; n],
                path_radiance_w_m2_sr_per_unit: vec![0.1; n],
                sky_altitude_m: vec![0.0],
                sky_zenith_deg: vec![0.0],
                sky_radiance_w_m2_sr_per_unit: vec![0.1; n],
                interpolation_residual: None,
            }),
            solar: Some(irsig_model::SpectralSolar {
                zenith_deg: zeniths[0],
                day_of_year: 172,
                altitude_m: vec![0.0],
                extraterrestrial_w_m2_per_unit: vec![10.0; n],
                transmission: vec![0.5; n],
                relative_azimuth_deg: vec![0.0, 180.0],
                path_scattered_w_m2_sr_per_unit: path(zeniths[0]),
                sky_scattered_w_m2_sr_per_unit: sky(zeniths[0]),
                further_suns: zeniths[1..]
                    .iter()
                    .map(|&z| SolarBeam {
                        zenith_deg: z,
                        transmission: vec![0.5; n],
                        path_scattered_w_m2_sr_per_unit: path(z),
                        sky_scattered_w_m2_sr_per_unit: sky(z),
                    })
                    .collect(),
                apparent_zenith_deg: Vec::new(),
                phase: None,
            }),
            slabs: Vec::new(),
        };
        atm.validate().unwrap();
        atm
    }

    /// The band value of a flat spectrum `v` over 3–5 µm.
    fn band(v: f64) -> f64 {
        2.0 * v
    }

    #[test]
    fn a_sun_between_rows_gets_beers_law_and_its_own_row_exactly() {
        let rows = [0.0, 20.0, 40.0, 60.0, 75.0, 85.0, 89.0];
        let atm = day(&rows);
        for z in [0.0, 7.5, 33.3, 60.0, 71.2, 84.0, 88.9, 89.0] {
            let s = SunlitPaths::at_zenith(&atm, 3.0, 5.0, |_| 1.0, z).unwrap();
            assert_eq!(s.sun_zenith_deg(), z);
            // Linear in the logarithm against the air mass: the cubic's slopes are the
            // secants, and it is the line, to rounding (f32 spectra).
            for (got, want) in [
                (
                    s.path_radiance(1000.0, 0.0, 0.0).scattered_w_m2_sr,
                    beer(0.02, 0.3, z),
                ),
                (
                    s.path_radiance(1000.0, 0.0, 180.0).scattered_w_m2_sr,
                    beer(0.01, 0.5, z),
                ),
                (
                    s.sky_radiance(0.0, 0.0, 0.0).scattered_w_m2_sr,
                    beer(0.04, 0.2, z),
                ),
            ] {
                assert!((got - band(want)).abs() < 1e-6 * band(want), "{z}: {got}");
            }
            // A node with no scattered sunlight at any sun has none between them.
            assert_eq!(s.sky_radiance(0.0, 0.0, 180.0).scattered_w_m2_sr, 0.0);
        }
        // The thermal part is the slant table's, whatever the sun.
        let a = SunlitPaths::at_zenith(&atm, 3.0, 5.0, |_| 1.0, 50.0).unwrap();
        assert_eq!(
            a.path_radiance(1000.0, 0.0, 0.0).thermal_w_m2_sr,
            band(f64::from(0.1_f32))
        );
        // `new` is the first sun's.
        let first = SunlitPaths::new(&atm, 3.0, 5.0, |_| 1.0).unwrap();
        assert_eq!(
            first,
            SunlitPaths::at_zenith(&atm, 3.0, 5.0, |_| 1.0, 0.0).unwrap()
        );
    }

    /// The logarithm of a peaked phase function at `theta_deg`: down by 0.16 a degree over
    /// the first 10° (LOWTRAN7's rural aerosol in 3.4–4.1 µm falls so near the sun), then
    /// by 0.01. Linear between [`PEAK_ANGLES`], as LOWTRAN7's between its angles.
    fn log_peak(theta_deg: f64) -> f64 {
        if theta_deg <= 10.0 {
            -0.16 * theta_deg
        } else {
            -1.6 - 0.01 * (theta_deg - 10.0)
        }
    }

    const PEAK_ANGLES: [f64; 4] = [0.0, 5.0, 10.0, 180.0];

    /// The angle between a line of sight 60° from the zenith, `azimuth_deg` from the sun's
    /// vertical plane, and the sun `zenith_deg` from the zenith.
    fn from_sun(azimuth_deg: f64, zenith_deg: f64) -> f64 {
        let (l, a, s) = (
            60_f64.to_radians(),
            azimuth_deg.to_radians(),
            zenith_deg.to_radians(),
        );
        (l.cos() * s.cos() + l.sin() * s.sin() * a.cos())
            .clamp(-1.0, 1.0)
            .acos()
            .to_degrees()
    }

    /// [`day`] with its sky node looking up 60° from the zenith, whose sunlight is Beer's
    /// law times [`log_peak`]'s phase function at its scattering angle (toward the sun's
    /// azimuth and away from it), and with that phase function measured when `measured`.
    fn peaked_day(zeniths: &[f64], measured: bool) -> SpectralAtmosphere {
        let n = 5;
        let spectra = |values: &[f64]| -> Vec<f32> {
            values
                .iter()
                .flat_map(|&v| std::iter::repeat_n(v as f32, n))
                .collect()
        };
        let sky = |z: f64| {
            spectra(&[
                beer(0.04, 0.2, z) * log_peak(from_sun(0.0, z)).exp(),
                beer(0.04, 0.2, z) * log_peak(from_sun(180.0, z)).exp(),
            ])
        };
        let mut atm = day(zeniths);
        atm.slant.as_mut().unwrap().sky_zenith_deg = vec![60.0];
        let s = atm.solar.as_mut().unwrap();
        s.sky_scattered_w_m2_sr_per_unit = sky(s.zenith_deg);
        for b in &mut s.further_suns {
            b.sky_scattered_w_m2_sr_per_unit = sky(b.zenith_deg);
        }
        if measured {
            let per_m: Vec<f64> = PEAK_ANGLES
                .iter()
                .map(|&t| 3e-6 * log_peak(t).exp())
                .collect();
            s.phase = Some(irsig_model::SolarPhase {
                scattering_deg: PEAK_ANGLES.to_vec(),
                scattered_w_m2_sr_per_unit_per_m: spectra(&per_m),
            });
        }
        atm.validate().unwrap();
        atm
    }

    #[test]
    fn a_sun_crossing_a_line_of_sight_is_followed_through_the_measured_phase_function() {
        let rows = [40.0, 45.0, 50.0, 55.0, 60.0, 65.0, 70.0, 75.0];
        let (with, without) = (peaked_day(&rows, true), peaked_day(&rows, false));
        let mut worst_without = 0.0_f64;
        for z in [41.2, 47.3, 57.5, 58.0, 59.9, 60.0, 61.0, 63.1, 72.2, 75.0] {
            for az in [0.0, 180.0] {
                let want = band(beer(0.04, 0.2, z) * log_peak(from_sun(az, z)).exp());
                let got = SunlitPaths::at_zenith(&with, 3.0, 5.0, |_| 1.0, z)
                    .unwrap()
                    .sky_radiance(0.0, 60.0, az)
                    .scattered_w_m2_sr;
                // Beer's law is a line in the logarithm against air mass, the peak
                // divided out: exact, to rounding (f32 spectra).
                assert!((got - want).abs() < 1e-5 * want, "{z} {az}: {got} {want}");
                let plain = SunlitPaths::at_zenith(&without, 3.0, 5.0, |_| 1.0, z)
                    .unwrap()
                    .sky_radiance(0.0, 60.0, az)
                    .scattered_w_m2_sr;
                worst_without = worst_without.max((plain - want).abs() / want);
            }
        }
        // Without it, the sun crossing the line of sight between rows is missed.
        assert!(worst_without > 0.1, "{worst_without}");
        // A phase function with no light at some angle (a band the air does not scatter
        // in) divides nothing out: the nodes are interpolated as they are.
        let mut dark = with.clone();
        let p = dark.solar.as_mut().unwrap().phase.as_mut().unwrap();
        p.scattered_w_m2_sr_per_unit_per_m[..5].fill(0.0);
        dark.validate().unwrap();
        for z in [47.3, 61.0] {
            let read = |atm: &SpectralAtmosphere| {
                SunlitPaths::at_zenith(atm, 3.0, 5.0, |_| 1.0, z)
                    .unwrap()
                    .sky_radiance(0.0, 60.0, 0.0)
            };
            assert_eq!(read(&dark), read(&without), "{z}");
        }
        // A slant node straight down is 180 deg less the sun's angle from the sun, and
        // takes the same division (its sunlight is Beer's law alone: the factor cancels
        // only where the rows carry it, so it is checked to be followed, not exact).
        let s = SunlitPaths::at_zenith(&with, 3.0, 5.0, |_| 1.0, 52.5).unwrap();
        let got = s.path_radiance(1000.0, 0.0, 0.0).scattered_w_m2_sr;
        let want = band(beer(0.02, 0.3, 52.5));
        assert!((got - want).abs() < 1e-3 * want, "{got} {want}");
    }

    #[test]
    fn a_sun_outside_the_rows_is_refused_and_one_sun_is_its_own() {
        let atm = day(&[20.0, 40.0, 60.0]);
        for z in [19.99, 60.01, f64::NAN, 90.0] {
            let e = SunlitPaths::at_zenith(&atm, 3.0, 5.0, |_| 1.0, z)
                .unwrap_err()
                .to_string();
            assert!(e.contains("from 20 to 60"), "{z}: {e}");
        }
        // Within the tolerance of an end: that end's row.
        let edge = SunlitPaths::at_zenith(&atm, 3.0, 5.0, |_| 1.0, 60.0005).unwrap();
        let end = SunlitPaths::at_zenith(&atm, 3.0, 5.0, |_| 1.0, 60.0).unwrap();
        assert_eq!(
            edge.path_radiance(1000.0, 0.0, 0.0),
            end.path_radiance(1000.0, 0.0, 0.0)
        );
        // Two rows: linear in the logarithm, still Beer's law.
        let two = day(&[20.0, 60.0]);
        let s = SunlitPaths::at_zenith(&two, 3.0, 5.0, |_| 1.0, 45.0).unwrap();
        let got = s.path_radiance(1000.0, 0.0, 0.0).scattered_w_m2_sr;
        let want = band(beer(0.02, 0.3, 45.0));
        assert!((got - want).abs() < 1e-6 * want, "{got} {want}");
        // A one-sun table is its sun's at any angle (the caller checks the sun, as for
        // the beam), as it was.
        let one = day(&[30.0]);
        let a = SunlitPaths::at_zenith(&one, 3.0, 5.0, |_| 1.0, 70.0).unwrap();
        assert_eq!(a, SunlitPaths::new(&one, 3.0, 5.0, |_| 1.0).unwrap());
        assert_eq!(a.sun_zenith_deg(), 30.0);
    }
}
