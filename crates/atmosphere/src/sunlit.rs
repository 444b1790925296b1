//! Path and sky radiance by day: a spectral atmosphere's thermal slant and sky
//! tables plus the sunlight single-scattered into the same paths (its `solar` table's
//! scattered spectra, LOWTRAN7's IEMSCT = 2), over a band or sub-band with a response
//! `w(λ)`:
//!
//! `L(h, θ, φ) = ∫ w(λ) [L_thermal(λ, h, θ) + L_scattered(λ, h, θ, φ)] dλ` W m⁻² sr⁻¹,
//!
//! where `h` is the observer's altitude, `θ` the nadir angle of a slant path (down to the
//! ground) or the zenith angle of a sky path (up to space), and `φ` the azimuth of the
//! line of sight from the sun's vertical plane. The scattered light is symmetric about that
//! plane: any azimuth is folded into 0–180° (0 looking toward the sun's azimuth).
//!
//! Each term is integrated over the band first, by [`BandQuadrature`]'s rule (as every
//! band value of a spectral atmosphere), then interpolated: by a monotone cubic in
//! azimuth and in angle (the scattered light's rise toward the sun and the horizon bends
//! between rows) and linearly in altitude, for slant and sky paths alike (within the
//! boundary layer, where the aerosol is mixed, the scattered sky above an observer falls
//! almost linearly as the observer rises: LOWTRAN7's 3.4–4.1 µm rural 10 km sky at 650 m
//! is 1.5 % above the line between 300 m and 1 km, and 7.8 % above their geometric mean;
//! a monotone cubic through 0, 300 m and 1 km was 1.8 % off the thermal sky there);
//! outside the tables the nearest row is used.
//! The error of this interpolation against LOWTRAN7 at paths between the rows is measured
//! in `tests/tests/sunlit.rs` and tabled in `docs/accuracy.md`.
//!
//! A table of several suns (one build for a day) is read for one sun at a time
//! ([`SunlitPaths::at_zenith`]): its scattered band values are interpolated between the
//! suns node by node first (`between`), then as a one-sun table's.

use irsig_model::SpectralAtmosphere;

use crate::error::{AtmosphereError, AtmosphereErrorKind};
use crate::interp;
use crate::spectral::BandQuadrature;

mod between;

/// A path's radiance by day, W m⁻² sr⁻¹ over the band, by its two sources.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SunlitRadiance {
    /// The air's own emission along the path.
    pub thermal_w_m2_sr: f64,
    /// Sunlight scattered once into the line of sight along the path.
    pub scattered_w_m2_sr: f64,
}

impl SunlitRadiance {
    /// Both together, W m⁻² sr⁻¹.
    #[must_use]
    pub fn total_w_m2_sr(&self) -> f64 {
        self.thermal_w_m2_sr + self.scattered_w_m2_sr
    }
}

/// One table of band values on altitude × angle × azimuth.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Table {
    pub(crate) altitude_m: Vec<f64>,
    pub(crate) angle_deg: Vec<f64>,
    /// `[altitude][angle][azimuth]`; one azimuth for the thermal tables.
    pub(crate) values: Vec<f64>,
    pub(crate) azimuths: usize,
}

impl Table {
    /// The value at `(altitude, angle)` row `k` of altitude, interpolated in azimuth and
    /// angle. Only the (at most four) angle rows the monotone cubic reads are interpolated
    /// in azimuth: the slopes at the two nodes around the angle depend on their neighbours
    /// alone, so the window gives the whole row's value, bit for bit, without allocating.
    pub(crate) fn at_altitude_row(
        &self,
        k: usize,
        azimuth_deg: &[f64],
        angle_deg: f64,
        az: f64,
    ) -> f64 {
        let na = self.angle_deg.len();
        let at = |j: usize| {
            let start = (k * na + j) * self.azimuths;
            let ys = &self.values[start..start + self.azimuths];
            if self.azimuths == 1 {
                ys[0]
            } else {
                interp::monotone_cubic(azimuth_deg, ys, az)
            }
        };
        if na < 3 {
            let row = [at(0), if na > 1 { at(1) } else { 0.0 }];
            return interp::monotone_cubic(&self.angle_deg, &row[..na], angle_deg);
        }
        let (i, f) = interp::locate(&self.angle_deg, angle_deg);
        let (lo, hi) = (i.saturating_sub(1), (i + 3).min(na));
        let mut row = [0.0; 4];
        for (slot, j) in row.iter_mut().zip(lo..hi) {
            *slot = at(j);
        }
        interp::monotone_cubic_located(&self.angle_deg[lo..hi], &row[..hi - lo], i - lo, f)
    }

    pub(crate) fn value(
        &self,
        azimuth_deg: &[f64],
        altitude_m: f64,
        angle_deg: f64,
        az: f64,
    ) -> f64 {
        let nh = self.altitude_m.len();
        let (k, f) = interp::locate(&self.altitude_m, altitude_m);
        let a = self.at_altitude_row(k, azimuth_deg, angle_deg, az);
        if nh < 2 || f == 0.0 {
            return a;
        }
        let b = self.at_altitude_row(k + 1, azimuth_deg, angle_deg, az);
        irsig_model::interp::lerp(a, b, f)
    }
}

/// The band's slant and sky radiance by day, thermal and scattered, on a spectral
/// atmosphere's slant and sky nodes.
#[derive(Debug, Clone, PartialEq)]
pub struct SunlitPaths {
    zenith_deg: f64,
    azimuth_deg: Vec<f64>,
    path_thermal: Table,
    path_scattered: Table,
    sky_thermal: Table,
    sky_scattered: Table,
}

pub(crate) fn missing(table: &'static str, instead: &'static str) -> AtmosphereError {
    AtmosphereErrorKind::MissingTable {
        model: "sunlit paths",
        table,
        instead,
    }
    .into()
}

/// Folds any azimuth from the sun's, degrees, into 0–180 (the scattered light is
/// symmetric about the sun's vertical plane). NaN stays NaN.
#[must_use]
pub fn fold_azimuth_deg(azimuth_deg: f64) -> f64 {
    let a = azimuth_deg.rem_euclid(360.0);
    if a > 180.0 { 360.0 - a } else { a }
}

impl SunlitPaths {
    /// The band `[lo_um, hi_um]` with response `weight(λ in µm)` of `spectral`'s slant
    /// tables and its `solar` table's scattered sunlight, for the table's first sun
    /// (`solar.zenith_deg`; [`Self::at_zenith`] for another of a day's table).
    ///
    /// # Errors
    /// An atmosphere without slant tables, without a `solar` table or whose `solar`
    /// table has no scattered-sunlight tables (a plan's sun without relative azimuths);
    /// tables whose sizes do not fit; a band [`BandQuadrature::new`] refuses.
    pub fn new(
        spectral: &SpectralAtmosphere,
        lo_um: f64,
        hi_um: f64,
        weight: impl Fn(f64) -> f64,
    ) -> Result<Self, AtmosphereError> {
        let zenith_deg = spectral.solar.as_ref().map_or(0.0, |s| s.zenith_deg);
        Self::at_zenith(spectral, lo_um, hi_um, weight, zenith_deg)
    }

    /// As [`Self::new`], for the sun `zenith_deg` (geometric) from the zenith. A one-sun
    /// table is its sun's whatever the angle (the caller checks the sun against it, as it
    /// does the beam's); a table of several suns is interpolated between them (the
    /// module's documentation), and a sun outside them is refused.
    ///
    /// # Errors
    /// As [`Self::new`]; with several suns, a zenith angle outside them.
    pub fn at_zenith(
        spectral: &SpectralAtmosphere,
        lo_um: f64,
        hi_um: f64,
        weight: impl Fn(f64) -> f64,
        zenith_deg: f64,
    ) -> Result<Self, AtmosphereError> {
        let slant = spectral.slant.as_ref().ok_or_else(|| {
            missing(
                "slant",
                "build the atmosphere from a plan (irsig-atmos plan/build)",
            )
        })?;
        let solar = spectral.solar.as_ref().ok_or_else(|| {
            missing(
                "solar",
                "build the atmosphere from a plan with a sun and the sunlight it scatters",
            )
        })?;
        if solar.relative_azimuth_deg.is_empty() {
            return Err(missing(
                "solar.relative_azimuth_deg",
                "build the atmosphere from a plan whose sun has relative azimuths (a plan with the sunlight the sun scatters has them)",
            ));
        }
        spectral.validate()?;
        let n = spectral.grid.points.len();
        let q = BandQuadrature::new(&spectral.grid, lo_um, hi_um, weight)?;
        let band = |values: &[f32]| -> Vec<f64> {
            values.chunks_exact(n).map(|s| q.radiance(s)).collect()
        };
        let na = solar.relative_azimuth_deg.len();
        let table =
            |altitude_m: &[f64], angle_deg: &[f64], values: Vec<f64>, azimuths: usize| Table {
                altitude_m: altitude_m.to_vec(),
                angle_deg: angle_deg.to_vec(),
                values,
                azimuths,
            };
        let (zenith_deg, path_scattered, sky_scattered) = if solar.further_suns.is_empty() {
            (
                solar.zenith_deg,
                band(&solar.path_scattered_w_m2_sr_per_unit),
                band(&solar.sky_scattered_w_m2_sr_per_unit),
            )
        } else {
            let (path, sky) = between::scattered_between(solar, slant, zenith_deg, &band)?;
            (zenith_deg, path, sky)
        };
        Ok(Self {
            zenith_deg,
            azimuth_deg: solar.relative_azimuth_deg.clone(),
            path_thermal: table(
                &slant.altitude_m,
                &slant.nadir_deg,
                band(&slant.path_radiance_w_m2_sr_per_unit),
                1,
            ),
            path_scattered: table(&slant.altitude_m, &slant.nadir_deg, path_scattered, na),
            sky_thermal: table(
                &slant.sky_altitude_m,
                &slant.sky_zenith_deg,
                band(&slant.sky_radiance_w_m2_sr_per_unit),
                1,
            ),
            sky_scattered: table(&solar.altitude_m, &slant.sky_zenith_deg, sky_scattered, na),
        })
    }

    /// The scattered-sunlight tables alone: the slant paths' and the sky's (each with
    /// its azimuths from the sun), and those azimuths, degrees.
    pub(crate) fn into_scattered(self) -> (Table, Table, Vec<f64>) {
        (self.path_scattered, self.sky_scattered, self.azimuth_deg)
    }

    /// The sun's zenith angle the tables were made (or interpolated) for, degrees.
    #[must_use]
    pub fn sun_zenith_deg(&self) -> f64 {
        self.zenith_deg
    }

    /// The slant path from `altitude_m` down to the ground, `nadir_deg` from straight
    /// down, its line of sight `azimuth_deg` from the sun's azimuth (any sign or turn).
    #[must_use]
    pub fn path_radiance(
        &self,
        altitude_m: f64,
        nadir_deg: f64,
        azimuth_deg: f64,
    ) -> SunlitRadiance {
        let az = fold_azimuth_deg(azimuth_deg);
        SunlitRadiance {
            thermal_w_m2_sr: self.path_thermal.value(&[0.0], altitude_m, nadir_deg, 0.0),
            scattered_w_m2_sr: self.path_scattered.value(
                &self.azimuth_deg,
                altitude_m,
                nadir_deg,
                az,
            ),
        }
    }

    /// The sky seen from `altitude_m`, `zenith_deg` from straight up, `azimuth_deg` from
    /// the sun's azimuth (any sign or turn).
    #[must_use]
    pub fn sky_radiance(
        &self,
        altitude_m: f64,
        zenith_deg: f64,
        azimuth_deg: f64,
    ) -> SunlitRadiance {
        let az = fold_azimuth_deg(azimuth_deg);
        SunlitRadiance {
            thermal_w_m2_sr: self.sky_thermal.value(&[0.0], altitude_m, zenith_deg, 0.0),
            scattered_w_m2_sr: self.sky_scattered.value(
                &self.azimuth_deg,
                altitude_m,
                zenith_deg,
                az,
            ),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn azimuths_fold_onto_the_half_circle_about_the_suns_plane() {
        for (a, want) in [
            (0.0, 0.0),
            (30.0, 30.0),
            (-30.0, 30.0),
            (180.0, 180.0),
            (190.0, 170.0),
            (-190.0, 170.0),
            (390.0, 30.0),
            (720.0, 0.0),
        ] {
            assert!((fold_azimuth_deg(a) - want).abs() < 1e-12, "{a}");
        }
        assert!(fold_azimuth_deg(f64::NAN).is_nan());
    }

    #[test]
    fn a_table_gives_its_rows_on_the_nodes_and_a_plane_between_them() {
        // v = 2 h + 3 θ + 5 φ: the monotone cubic and the linear rule reproduce a linear
        // function exactly.
        let (h, th, az) = (
            [0.0, 100.0, 300.0],
            [0.0, 10.0, 30.0, 40.0],
            [0.0, 45.0, 90.0, 180.0],
        );
        let mut values = Vec::new();
        for &a in &h {
            for &t in &th {
                for &p in &az {
                    values.push(2.0 * a + 3.0 * t + 5.0 * p);
                }
            }
        }
        let t = Table {
            altitude_m: h.to_vec(),
            angle_deg: th.to_vec(),
            values,
            azimuths: az.len(),
        };
        assert!((t.value(&az, 100.0, 10.0, 45.0) - (200.0 + 30.0 + 225.0)).abs() < 1e-9);
        let v = t.value(&az, 150.0, 17.0, 60.0);
        assert!((v - (300.0 + 51.0 + 300.0)).abs() < 1e-9, "{v}");
        // Outside: the nearest row.
        let v = t.value(&az, 400.0, 50.0, 60.0);
        assert!((v - (600.0 + 120.0 + 300.0)).abs() < 1e-9, "{v}");
    }
}
