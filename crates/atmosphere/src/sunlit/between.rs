//! The scattered sunlight of a sun between a day table's suns.
//!
//! A table of several suns (`SpectralSolar::further_suns`, one build for a whole day)
//! holds the scattered-sunlight spectra of each sun on the same nodes. A sun between them
//! is given, at every node (altitude, angle, azimuth from the sun), the band value of the
//! rows around it interpolated by a monotone cubic in the logarithm of the value against
//! the Kasten & Young (1989) relative air mass, as the direct beam is
//! (`crate::solar::DirectSun::at_zenith`). Why that interpolant: single-scattered sunlight
//! is the sun's beam at each scattering point, `E_toa e^{−k m}` with the air mass `m` of
//! the path down to it, times the phase function and the path's transmittance onward; the
//! logarithm against air mass makes the first factor, which changes fastest toward the
//! horizon, nearly a line, and the cubic follows what the scattering angle and the band's
//! saturation add, never overshooting the rows around it (so never below 0). The cubic is
//! local: the value between rows `i` and `i + 1` uses rows `i − 1` to `i + 2` only, and
//! only those are integrated over the band. Its error against LOWTRAN7 run for the sun
//! itself is measured in `tests/tests/scattered_day.rs` and tabled in
//! `docs/accuracy.md` ("A day's scattered sunlight").

use irsig_model::SpectralSolar;

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

/// The band values of the scattered sunlight (slant paths, sky) of a sun `zenith_deg`
/// from the zenith, from `solar`'s table of several suns, each row's spectra reduced to
/// band values by `band` (one value per spectrum).
///
/// # Errors
/// A zenith angle that is not finite or lies outside the table's suns (each end widened
/// by [`ZENITH_TOLERANCE_DEG`]): the scattered sunlight is not extrapolated; a further sun
/// without scattered spectra (a table the model's validation refuses).
pub(crate) fn scattered_between(
    solar: &SpectralSolar,
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
    let air_mass: Vec<f64> = zeniths.iter().map(|&z| kasten_young_air_mass(z)).collect();
    let m = kasten_young_air_mass(zenith_deg.clamp(first, last));
    let (i, f) = interp::locate(&air_mass, m);
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
    let xs = &air_mass[lo..=hi];
    let between = |rows: &[Vec<f64>]| -> Vec<f64> {
        let nodes = rows.iter().map(Vec::len).min().unwrap_or(0);
        (0..nodes)
            .map(|k| {
                let log: Vec<f64> = rows
                    .iter()
                    .map(|r| r[k].max(SCATTERED_FLOOR_W_M2_SR).ln())
                    .collect();
                let v = interp::monotone_cubic_located(xs, &log, i - lo, f).exp();
                if v < 2.0 * SCATTERED_FLOOR_W_M2_SR {
                    0.0
                } else {
                    v
                }
            })
            .collect()
    };
    Ok((between(&path_rows), between(&sky_rows)))
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
