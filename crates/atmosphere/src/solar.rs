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
//! Axes are the scene's: +Z up, unit vectors not required (they are normalised).

use irsig_model::{SpectralAtmosphere, SpectralSolar};

use crate::error::{AtmosphereError, AtmosphereErrorKind};
use crate::interp;
use crate::spectral::BandQuadrature;

/// How far, degrees, a direction given for the sun may lie from the table's zenith angle:
/// the 0.001° a deck holds, and a little for the arithmetic that made the vector.
pub const ZENITH_TOLERANCE_DEG: f64 = 1.1e-3;

/// The direct solar irradiance of one band at each altitude of a `solar` table.
#[derive(Debug, Clone, PartialEq)]
pub struct DirectSun {
    zenith_deg: f64,
    altitude_m: Vec<f64>,
    /// `∫ w E_toa τ_sun(h_k) dλ` on a surface normal to the beam, W m⁻², per altitude.
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
    /// table.
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
        if rows == 0
            || solar.extraterrestrial_w_m2_per_unit.len() != n
            || solar.transmission.len() != rows * n
        {
            return Err(sun_error(format!(
                "invalid atmosphere: `solar`: expected one extraterrestrial spectrum and {rows} transmittance spectra of {n} points, found {} and {} values",
                solar.extraterrestrial_w_m2_per_unit.len(),
                solar.transmission.len()
            )));
        }
        let q = BandQuadrature::new(&spectral.grid, lo_um, hi_um, weight)?;
        let etoa = &solar.extraterrestrial_w_m2_per_unit;
        let normal_w_m2 = solar
            .transmission
            .chunks_exact(n)
            .map(|tau| q.integral(|i| f64::from(etoa[i]) * f64::from(tau[i])))
            .collect();
        Ok(Self {
            zenith_deg: solar.zenith_deg,
            altitude_m: solar.altitude_m.clone(),
            normal_w_m2,
            extraterrestrial_w_m2: q.integral(|i| f64::from(etoa[i])),
        })
    }

    /// The sun's zenith angle the table was made for, degrees.
    #[must_use]
    pub fn zenith_deg(&self) -> f64 {
        self.zenith_deg
    }

    /// The band's extraterrestrial irradiance on a surface normal to the beam, W m⁻².
    #[must_use]
    pub fn extraterrestrial_w_m2(&self) -> f64 {
        self.extraterrestrial_w_m2
    }

    /// The band's direct irradiance on a surface facing the sun at `altitude_m` above the
    /// ground, W m⁻²: linear in altitude between the table's rows, the nearest row's
    /// outside them (NaN for a NaN altitude).
    #[must_use]
    pub fn normal_w_m2(&self, altitude_m: f64) -> f64 {
        interp::linear(&self.altitude_m, &self.normal_w_m2, altitude_m)
    }

    /// The band's direct irradiance, W m⁻², on a surface at `altitude_m` whose outward
    /// normal is `normal`, with the sun in direction `to_sun` (both in the scene's axes,
    /// +Z up): `cos θ_i` times [`DirectSun::normal_w_m2`], 0 for a surface facing away.
    ///
    /// # Errors
    /// A vector that is not finite or of zero length; a sun whose direction is more than
    /// [`ZENITH_TOLERANCE_DEG`] from the table's zenith angle (the table holds the beam
    /// for that sun only); an altitude that is not finite.
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
        if (zenith - self.zenith_deg).abs() > ZENITH_TOLERANCE_DEG {
            return Err(sun_error(format!(
                "the direction to the sun is {zenith:.4} deg from the zenith, but the atmosphere's solar table is for a sun at {} deg: build the atmosphere for this sun",
                self.zenith_deg
            )));
        }
        let cos_i = n[0] * s[0] + n[1] * s[1] + n[2] * s[2];
        if cos_i <= 0.0 {
            return Ok(0.0);
        }
        Ok(cos_i * self.normal_w_m2(altitude_m))
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
}
