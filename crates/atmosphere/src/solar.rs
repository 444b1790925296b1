//! Direct sunlight from a spectral atmosphere's `solar` table: the irradiance
//! the sun's beam brings to a surface at altitude `h` whose normal is `θ_i` from the sun,
//! over a band or sub-band with a response `w(λ)`:
//!
//! `E(h, n) = cos θ_i ∫ w(λ) E_toa(λ) τ_sun(λ, h) dλ` W m⁻², and 0 when `cos θ_i ≤ 0`.
//!
//! The integral is [`BandQuadrature`]'s, the rule every band value of a spectral
//! atmosphere is made with (the trapezoid in wavelength over the grid's points inside the
//! band, closed at each edge by a point linear in the grid's variable; a density per cm⁻¹
//! converted to per µm first, `E_λ = E_ν ν² / 10⁴`), so a sub-band's sunlight and its
//! atmosphere are integrated alike. Between the table's altitudes the band integral is
//! linear in altitude, as the sky table's rows are (linear interpolation commutes with the
//! quadrature: interpolating the spectra first gives the same number); outside them it is
//! the nearest row's. The sun's beam is taken as parallel: one zenith angle at every
//! altitude of the scene.
//!
//! A table of several suns (`SpectralSolar::further_suns`, one build for a whole day)
//! holds the band integral at each of its zenith angles; the beam of a sun between them
//! ([`DirectSun::at_zenith`]) is interpolated at each altitude by a monotone cubic in the
//! logarithm of the beam against the relative air mass (Kasten & Young 1989,
//! [`crate::loads::kasten_young_air_mass`]): Beer's law `E = E_toa e^{−k m}` makes that
//! nearly a line, and the cubic follows the curvature that band saturation and the band's
//! mix of absorbers give it, never overshooting the rows around it. The error against
//! LOWTRAN7 run for the sun itself is measured in `tests/tests/solar_day.rs` and tabled in
//! `docs/accuracy.md` ("One atmosphere for a day's suns"). A sun outside the table's
//! zenith angles is refused, naming them: the beam is not extrapolated.
//!
//! Axes are the scene's: +Z up, unit vectors not required (they are normalised).

use irsig_model::{SpectralAtmosphere, SpectralSolar};

use crate::error::{AtmosphereError, AtmosphereErrorKind};
use crate::interp;
use crate::loads::kasten_young_air_mass;
use crate::spectral::BandQuadrature;

/// How far, degrees, a direction given for the sun may lie from the table's zenith angle:
/// the 0.001° a deck holds, and a little for the arithmetic that made the vector.
pub const ZENITH_TOLERANCE_DEG: f64 = 1.1e-3;

/// Below this, W m⁻², an interpolated beam is none: the logarithm of a beam of 0 is
/// taken at this floor, so that a row the air makes opaque pulls its neighbours down
/// without an infinity, and what comes back at the floor (to twice it) is 0 again.
const BEAM_FLOOR_W_M2: f64 = 1e-30;

/// The direct solar irradiance of one band at each altitude of a `solar` table, for each
/// of its suns.
#[derive(Debug, Clone, PartialEq)]
pub struct DirectSun {
    /// The suns' zenith angles, degrees, increasing; one for a one-sun table.
    zenith_deg: Vec<f64>,
    altitude_m: Vec<f64>,
    /// `∫ w E_toa τ_sun(h_k) dλ` on a surface normal to the beam, W m⁻²,
    /// `[zenith][altitude]`.
    normal_w_m2: Vec<f64>,
    /// `∫ w E_toa dλ`, W m⁻².
    extraterrestrial_w_m2: f64,
}

fn sun_error(message: String) -> AtmosphereError {
    AtmosphereErrorKind::Solar(message).into()
}

fn unit(name: &str, v: [f64; 3]) -> Result<[f64; 3], AtmosphereError> {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if !(n.is_finite() && n > 0.0) {
        return Err(sun_error(format!(
            "the {name} {v:?} is not a direction: expected a finite vector of non-zero length"
        )));
    }
    Ok([v[0] / n, v[1] / n, v[2] / n])
}

impl DirectSun {
    /// The band `[lo_um, hi_um]` with response `weight(λ in µm)` of `spectral`'s `solar`
    /// table, at each of its suns.
    ///
    /// # Errors
    /// An atmosphere without a `solar` table (a night atmosphere), a table whose spectra
    /// do not fit the grid, or a band [`BandQuadrature::new`] refuses (outside the grid,
    /// a response negative, not finite or zero everywhere).
    pub fn new(
        spectral: &SpectralAtmosphere,
        lo_um: f64,
        hi_um: f64,
        weight: impl Fn(f64) -> f64,
    ) -> Result<Self, AtmosphereError> {
        let solar: &SpectralSolar = spectral.solar.as_ref().ok_or_else(|| {
            AtmosphereError::from(AtmosphereErrorKind::MissingTable {
                model: "direct sun",
                table: "solar",
                instead: "build the atmosphere from a plan with a sun (its zenith angle and day of the year)",
            })
        })?;
        let n = spectral.grid.points.len();
        let rows = solar.altitude_m.len();
        let zenith_deg = solar.zeniths_deg();
        let fits = |row: usize| solar.transmission_of(row).map(<[f32]>::len) == Some(rows * n);
        if rows == 0
            || solar.extraterrestrial_w_m2_per_unit.len() != n
            || !(0..zenith_deg.len()).all(fits)
        {
            return Err(sun_error(format!(
                "invalid atmosphere: `solar`: expected one extraterrestrial spectrum and {rows} transmittance spectra of {n} points per sun, found {} and {} values (the first sun's)",
                solar.extraterrestrial_w_m2_per_unit.len(),
                solar.transmission.len()
            )));
        }
        if let Some(k) = (1..zenith_deg.len())
            .find(|&k| !(zenith_deg[k] > zenith_deg[k - 1] && zenith_deg[k] < 90.0))
        {
            return Err(sun_error(format!(
                "invalid atmosphere: `solar`: expected the suns' zenith angles increasing \
                 to below 90 deg, found {zenith_deg:?} (row {k})"
            )));
        }
        let q = BandQuadrature::new(&spectral.grid, lo_um, hi_um, weight)?;
        let etoa = &solar.extraterrestrial_w_m2_per_unit;
        let normal_w_m2 = (0..zenith_deg.len())
            .filter_map(|row| solar.transmission_of(row))
            .flat_map(|t| t.chunks_exact(n))
            .map(|tau| q.integral(|i| f64::from(etoa[i]) * f64::from(tau[i])))
            .collect();
        Ok(Self {
            zenith_deg,
            altitude_m: solar.altitude_m.clone(),
            normal_w_m2,
            extraterrestrial_w_m2: q.integral(|i| f64::from(etoa[i])),
        })
    }

    /// The suns' zenith angles the table was made for, degrees, increasing.
    #[must_use]
    pub fn zeniths_deg(&self) -> &[f64] {
        &self.zenith_deg
    }

    /// The band's extraterrestrial irradiance on a surface normal to the beam, W m⁻².
    #[must_use]
    pub fn extraterrestrial_w_m2(&self) -> f64 {
        self.extraterrestrial_w_m2
    }

    /// The band's direct irradiance of the table's first sun on a surface facing it at
    /// `altitude_m` above the ground, W m⁻²: linear in altitude between the table's rows,
    /// the nearest row's outside them (NaN for a NaN altitude). For another sun of a table
    /// of several, [`DirectSun::at_zenith`] first.
    #[must_use]
    pub fn normal_w_m2(&self, altitude_m: f64) -> f64 {
        let rows = self.altitude_m.len();
        interp::linear(&self.altitude_m, &self.normal_w_m2[..rows], altitude_m)
    }

    /// The beam of the sun `zenith_deg` from the zenith, as a table of that one sun.
    ///
    /// A one-sun table is its own sun's, unchanged, within [`ZENITH_TOLERANCE_DEG`]. A
    /// table of several is interpolated between its suns at each altitude (the module's
    /// documentation), for a sun from the first zenith angle to the last (each end
    /// widened by [`ZENITH_TOLERANCE_DEG`], the end row's there).
    ///
    /// # Errors
    /// A zenith angle that is not finite, or outside the table's suns (it names them).
    pub fn at_zenith(&self, zenith_deg: f64) -> Result<Self, AtmosphereError> {
        let (first, last) = (
            self.zenith_deg[0],
            self.zenith_deg[self.zenith_deg.len() - 1],
        );
        let within = zenith_deg.is_finite()
            && zenith_deg >= first - ZENITH_TOLERANCE_DEG
            && zenith_deg <= last + ZENITH_TOLERANCE_DEG;
        if !within {
            return Err(sun_error(if self.zenith_deg.len() == 1 {
                format!(
                    "the direction to the sun is {zenith_deg:.4} deg from the zenith, but the atmosphere's solar table is for a sun at {first} deg: build the atmosphere for this sun"
                )
            } else {
                format!(
                    "the direction to the sun is {zenith_deg:.4} deg from the zenith, but the atmosphere's solar table holds suns from {first} to {last} deg: build the atmosphere for suns that cover this one"
                )
            }));
        }
        if self.zenith_deg.len() == 1 {
            return Ok(self.clone());
        }
        let z = zenith_deg.clamp(first, last);
        let air_mass: Vec<f64> = self
            .zenith_deg
            .iter()
            .map(|&r| kasten_young_air_mass(r))
            .collect();
        let m = kasten_young_air_mass(z);
        let rows = self.altitude_m.len();
        let normal_w_m2 = (0..rows)
            .map(|k| {
                let log_beam: Vec<f64> = self
                    .normal_w_m2
                    .iter()
                    .skip(k)
                    .step_by(rows)
                    .map(|&e| e.max(BEAM_FLOOR_W_M2).ln())
                    .collect();
                let e = interp::monotone_cubic(&air_mass, &log_beam, m).exp();
                // The floor back through `ln` and `exp` is a hair above it.
                if e < 2.0 * BEAM_FLOOR_W_M2 { 0.0 } else { e }
            })
            .collect();
        Ok(Self {
            zenith_deg: vec![zenith_deg],
            altitude_m: self.altitude_m.clone(),
            normal_w_m2,
            extraterrestrial_w_m2: self.extraterrestrial_w_m2,
        })
    }

    /// The band's direct irradiance, W m⁻², on a surface at `altitude_m` whose outward
    /// normal is `normal`, with the sun in direction `to_sun` (both in the scene's axes,
    /// +Z up): `cos θ_i` times the beam of that sun ([`DirectSun::at_zenith`]), 0 for a
    /// surface facing away.
    ///
    /// # Errors
    /// A vector that is not finite or of zero length; a sun whose direction is outside the
    /// table's suns ([`DirectSun::at_zenith`]); an altitude that is not finite.
    pub fn irradiance_w_m2(
        &self,
        altitude_m: f64,
        normal: [f64; 3],
        to_sun: [f64; 3],
    ) -> Result<f64, AtmosphereError> {
        if !altitude_m.is_finite() {
            return Err(sun_error(format!(
                "a surface at altitude {altitude_m} m: expected a finite altitude"
            )));
        }
        let n = unit("surface normal", normal)?;
        let s = unit("direction to the sun", to_sun)?;
        let zenith = s[2].clamp(-1.0, 1.0).acos().to_degrees();
        let sun = self.at_zenith(zenith)?;
        let cos_i = n[0] * s[0] + n[1] * s[1] + n[2] * s[2];
        if cos_i <= 0.0 {
            return Ok(0.0);
        }
        Ok(cos_i * sun.normal_w_m2(altitude_m))
    }
}

#[cfg(test)]
#[allow(clippy::float_cmp)] // exact zeros and values built to be exact
mod tests {
    use super::*;
    use irsig_model::{ProfileLevel, SpectralAxis, SpectralGrid};

    /// A wavelength grid 3–5 µm every 0.5 µm; E_toa = 10 W m-2 um-1 flat; τ 0.5 at 0 m and
    /// 0.75 at 300 m, flat (numbers exact in `f32`).
    fn atmosphere() -> SpectralAtmosphere {
        let n = 5;
        SpectralAtmosphere {
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
            slant: None,
            solar: Some(SpectralSolar {
                zenith_deg: 60.0,
                day_of_year: 172,
                altitude_m: vec![0.0, 300.0],
                extraterrestrial_w_m2_per_unit: vec![10.0; n],
                transmission: [vec![0.5_f32; n], vec![0.75; n]].concat(),
                relative_azimuth_deg: Vec::new(),
                path_scattered_w_m2_sr_per_unit: Vec::new(),
                sky_scattered_w_m2_sr_per_unit: Vec::new(),
                further_suns: Vec::new(),
                apparent_zenith_deg: Vec::new(),
                phase: None,
            }),
            slabs: Vec::new(),
        }
    }

    fn to_sun(zenith_deg: f64, azimuth_deg: f64) -> [f64; 3] {
        let (z, a) = (zenith_deg.to_radians(), azimuth_deg.to_radians());
        [z.sin() * a.sin(), z.sin() * a.cos(), z.cos()]
    }

    #[test]
    fn a_plate_gets_the_beam_times_its_cosine_and_nothing_facing_away() {
        let atm = atmosphere();
        atm.validate().unwrap();
        let sun = DirectSun::new(&atm, 3.0, 5.0, |_| 1.0).unwrap();
        // 2 um × 10 W m-2 um-1 at the top.
        assert!((sun.extraterrestrial_w_m2() - 20.0).abs() < 1e-12);
        assert!((sun.normal_w_m2(0.0) - 10.0).abs() < 1e-12);
        assert!((sun.normal_w_m2(300.0) - 15.0).abs() < 1e-12);
        // Linear between the rows, the nearest row outside them.
        assert!((sun.normal_w_m2(150.0) - 12.5).abs() < 1e-12);
        assert!((sun.normal_w_m2(1000.0) - 15.0).abs() < 1e-12);
        let s = to_sun(60.0, 135.0);
        // A horizontal plate: cos 60° = 1/2.
        let flat = sun.irradiance_w_m2(0.0, [0.0, 0.0, 1.0], s).unwrap();
        assert!((flat - 5.0).abs() < 1e-12, "{flat}");
        // A plate tilted to face the sun gets the whole beam; one facing away nothing.
        let facing = sun.irradiance_w_m2(300.0, s, s).unwrap();
        assert!((facing - 15.0).abs() < 1e-12, "{facing}");
        assert_eq!(
            sun.irradiance_w_m2(0.0, [-s[0], -s[1], -s[2]], s).unwrap(),
            0.0
        );
        assert_eq!(sun.irradiance_w_m2(0.0, [0.0, 0.0, -1.0], s).unwrap(), 0.0);
        // Edge-on: 0 too.
        let edge = [s[1], -s[0], 0.0];
        assert!(sun.irradiance_w_m2(0.0, edge, s).unwrap().abs() < 1e-12);
        // A half band gets half.
        let half = DirectSun::new(&atm, 3.0, 4.0, |_| 1.0).unwrap();
        assert!((half.normal_w_m2(0.0) - 5.0).abs() < 1e-12);
    }

    #[test]
    fn a_wavenumber_grid_converts_the_irradiance_to_per_micrometre() {
        // E_ν = 1 W m-2 per cm-1 flat from 2000 to 2500 cm-1 (4-5 um), τ = 1: the band
        // integral is the wavenumber span, 500, to the trapezoid's error in λ.
        let mut atm = atmosphere();
        let points: Vec<f64> = (0..=100).map(|i| 2000.0 + 5.0 * f64::from(i)).collect();
        let n = points.len();
        atm.grid = SpectralGrid {
            axis: SpectralAxis::WavenumberPerCm,
            points,
        };
        atm.level_transmission = vec![0.5; n];
        atm.level_path_radiance_w_m2_sr_per_unit = vec![0.1; n];
        atm.sky_radiance_w_m2_sr_per_unit = vec![0.1; n];
        atm.solar = Some(SpectralSolar {
            zenith_deg: 0.0,
            day_of_year: 1,
            altitude_m: vec![0.0],
            extraterrestrial_w_m2_per_unit: vec![1.0; n],
            transmission: vec![1.0; n],
            relative_azimuth_deg: Vec::new(),
            path_scattered_w_m2_sr_per_unit: Vec::new(),
            sky_scattered_w_m2_sr_per_unit: Vec::new(),
            further_suns: Vec::new(),
            apparent_zenith_deg: Vec::new(),
            phase: None,
        });
        atm.validate().unwrap();
        let sun = DirectSun::new(&atm, 4.0, 5.0, |_| 1.0).unwrap();
        assert!((sun.normal_w_m2(0.0) / 500.0 - 1.0).abs() < 1e-4);
        let up = sun.irradiance_w_m2(0.0, [0.0, 0.0, 2.0], [0.0, 0.0, 1.0]);
        assert!((up.unwrap() - sun.normal_w_m2(0.0)).abs() < 1e-12);
    }

    #[test]
    fn no_table_another_sun_and_bad_vectors_are_refused() {
        let mut atm = atmosphere();
        let sun = DirectSun::new(&atm, 3.0, 5.0, |_| 1.0).unwrap();
        let up = [0.0, 0.0, 1.0];
        let e = sun
            .irradiance_w_m2(0.0, up, to_sun(30.0, 0.0))
            .unwrap_err()
            .to_string();
        assert!(e.contains("30.0000 deg") && e.contains("60 deg"), "{e}");
        for bad in [[0.0; 3], [f64::NAN, 0.0, 1.0], [f64::INFINITY, 0.0, 0.0]] {
            assert!(sun.irradiance_w_m2(0.0, bad, to_sun(60.0, 0.0)).is_err());
            assert!(sun.irradiance_w_m2(0.0, up, bad).is_err());
        }
        assert!(
            sun.irradiance_w_m2(f64::NAN, up, to_sun(60.0, 0.0))
                .is_err()
        );
        assert!(DirectSun::new(&atm, 2.0, 5.0, |_| 1.0).is_err());
        if let Some(s) = atm.solar.as_mut() {
            s.transmission.pop();
        }
        let e = DirectSun::new(&atm, 3.0, 5.0, |_| 1.0).unwrap_err();
        assert!(e.to_string().contains("solar"), "{e}");
        atm.solar = None;
        let e = DirectSun::new(&atm, 3.0, 5.0, |_| 1.0)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("`solar`") && e.contains("a plan with a sun"),
            "{e}"
        );
    }

    /// Beer's law along Kasten & Young's (1989) relative air mass, written out from the
    /// paper: `m = 1 / (cos z + 0.50572 (96.07995 − z)^−1.6364)`.
    fn beer(k: f64, zenith_deg: f64) -> f64 {
        let m =
            1.0 / (zenith_deg.to_radians().cos() + 0.50572 * (96.07995 - zenith_deg).powf(-1.6364));
        (-k * m).exp()
    }

    /// The test atmosphere with suns at `zeniths`, each beam Beer's law with optical depth
    /// 0.4 at the ground and 0.1 at 300 m, flat over the band.
    fn day(zeniths: &[f64]) -> SpectralAtmosphere {
        let mut atm = atmosphere();
        let beam = |z: f64| -> Vec<f32> {
            [vec![beer(0.4, z) as f32; 5], vec![beer(0.1, z) as f32; 5]].concat()
        };
        if let Some(s) = atm.solar.as_mut() {
            s.zenith_deg = zeniths[0];
            s.transmission = beam(zeniths[0]);
            s.further_suns = zeniths[1..]
                .iter()
                .map(|&zenith_deg| irsig_model::SolarBeam {
                    zenith_deg,
                    transmission: beam(zenith_deg),
                    path_scattered_w_m2_sr_per_unit: Vec::new(),
                    sky_scattered_w_m2_sr_per_unit: Vec::new(),
                })
                .collect();
        }
        atm.validate().unwrap();
        atm
    }

    #[test]
    fn a_sun_between_rows_gets_beers_law_where_the_rows_follow_it() {
        let atm = day(&[0.0, 20.0, 40.0, 60.0, 75.0, 85.0, 89.0]);
        let sun = DirectSun::new(&atm, 3.0, 5.0, |_| 1.0).unwrap();
        assert_eq!(sun.zeniths_deg(), [0.0, 20.0, 40.0, 60.0, 75.0, 85.0, 89.0]);
        // 2 um x 10 W m-2 um-1 at the top, times τ: ln E is a line in the air mass, which
        // the cubic holds exactly; the rest is the f32 rounding of the rows' τ.
        for z in [0.0, 7.5, 33.3, 50.0, 68.0, 80.0, 87.0, 88.5, 89.0] {
            let at = sun.at_zenith(z).unwrap();
            assert_eq!(at.zeniths_deg(), [z]);
            for (h, k) in [(0.0, 0.4), (300.0, 0.1), (150.0, f64::NAN)] {
                let want = if k.is_nan() {
                    10.0 * (beer(0.4, z) + beer(0.1, z))
                } else {
                    20.0 * beer(k, z)
                };
                let got = at.normal_w_m2(h);
                assert!(
                    (got / want - 1.0).abs() < 2e-6,
                    "{z} deg, {h} m: {got} vs {want}"
                );
            }
        }
        // The plate's cosine on top, the sun's zenith from its direction.
        let s = to_sun(50.0, 200.0);
        let flat = sun.irradiance_w_m2(0.0, [0.0, 0.0, 1.0], s).unwrap();
        let want = 50_f64.to_radians().cos() * 20.0 * beer(0.4, 50.0);
        assert!((flat / want - 1.0).abs() < 2e-6, "{flat} vs {want}");
        // At a row, that row's beam exactly.
        let row = sun.at_zenith(60.0).unwrap();
        let direct = DirectSun::new(&day(&[60.0]), 3.0, 5.0, |_| 1.0).unwrap();
        assert!((row.normal_w_m2(0.0) / direct.normal_w_m2(0.0) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn a_sun_outside_the_rows_is_refused_naming_them_and_one_sun_is_as_before() {
        let atm = day(&[20.0, 40.0, 60.0]);
        let sun = DirectSun::new(&atm, 3.0, 5.0, |_| 1.0).unwrap();
        for z in [19.99, 60.01, 0.0, 89.0, f64::NAN] {
            let e = sun.at_zenith(z).unwrap_err().to_string();
            assert!(e.contains("from 20 to 60 deg"), "{z}: {e}");
        }
        let e = sun
            .irradiance_w_m2(0.0, [0.0, 0.0, 1.0], to_sun(10.0, 0.0))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("10.0000 deg") && e.contains("from 20 to 60 deg"),
            "{e}"
        );
        // Within the tolerance of an end: that end's beam.
        let edge = sun.at_zenith(60.0 + 0.5 * ZENITH_TOLERANCE_DEG).unwrap();
        let end = sun.at_zenith(60.0).unwrap();
        assert_eq!(edge.normal_w_m2(0.0), end.normal_w_m2(0.0));
        // A one-sun table is its sun's, bit for bit, and refused elsewhere as before.
        let one = DirectSun::new(&atmosphere(), 3.0, 5.0, |_| 1.0).unwrap();
        assert_eq!(one.at_zenith(60.0 + 1e-3).unwrap(), one);
        let e = one.at_zenith(61.0).unwrap_err().to_string();
        assert!(e.contains("for a sun at 60 deg"), "{e}");
    }

    #[test]
    fn an_opaque_row_gives_no_beam_and_pulls_its_neighbours_down_without_a_nan() {
        let mut atm = day(&[30.0, 60.0, 89.0]);
        if let Some(s) = atm.solar.as_mut() {
            s.further_suns[1].transmission = vec![0.0; 10];
        }
        let sun = DirectSun::new(&atm, 3.0, 5.0, |_| 1.0).unwrap();
        assert_eq!(sun.at_zenith(89.0).unwrap().normal_w_m2(0.0), 0.0);
        let near = sun.at_zenith(88.0).unwrap().normal_w_m2(0.0);
        let above = sun.at_zenith(60.0).unwrap().normal_w_m2(0.0);
        assert!(
            near.is_finite() && near >= 0.0 && near < above,
            "{near} {above}"
        );
        // A table whose further sun's spectra do not fit is refused.
        if let Some(s) = atm.solar.as_mut() {
            s.further_suns[0].transmission.pop();
        }
        assert!(DirectSun::new(&atm, 3.0, 5.0, |_| 1.0).is_err());
    }
}
