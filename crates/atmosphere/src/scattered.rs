//! Sunlight single-scattered into the tracer's paths by day: what a sky ray, the
//! hemispheric sky and a view path gain from a spectral atmosphere's `solar` table
//! (LOWTRAN7's IEMSCT = 2 runs), over one band or sub-band, for a sun in a given direction.
//! The air's own emission stays the night model's; this is the part to add to it.
//!
//! Directions are unit vectors in the scene frame (x east, y north, z up) pointing away
//! from the observer; the azimuth of a line of sight from the sun's vertical plane is the
//! angle between its horizontal part and the sun's, 0–180° (the scattered light is
//! symmetric about that plane, [`crate::sunlit::fold_azimuth_deg`]). The tables are
//! interpolated as [`crate::sunlit::SunlitPaths`] interpolates them (monotone cubics in
//! azimuth and angle, linear in altitude; outside them the nearest row).
//!
//! - **Sky** ([`ScatteredSunlight::sky`]): the scattered sky table at the observer's
//!   altitude, the ray's zenith angle (beyond 90°, below the local horizontal, the 90° row)
//!   and its azimuth.
//! - **Hemispheric sky** ([`ScatteredSunlight::sky_hemispheric`]): thesis eq. 5 over the
//!   whole sky, `(1/π)∫∫ L cos z dΩ`, integrated over the interpolated table once per
//!   altitude row (midpoint rule in `sin² z` and in azimuth, 400 × 180 points; linear in
//!   altitude between rows, as the table is).
//! - **A view path** ([`ScatteredSunlight::path`]), the *difference of two paths*: in a
//!   plane-parallel atmosphere the light scattered into the line of sight at a point
//!   depends on its altitude and the line's direction only, so the path from the observer
//!   to a point `t` is the path from the observer to the ground (or to space, looking up)
//!   less the same direction's path from `t`, seen through the transmittance `τ` between:
//!   `L(o → t) = P(h_o, θ, φ) − τ·P(h_t, θ, φ)`. Below the slant table's lowest row `P`
//!   falls linearly to 0 at the paths' lower end (a path of no length scatters nothing).
//!   Its error against LOWTRAN7 run for the path itself is measured in
//!   `tests/tests/scattered_trace.rs` and tabled in `docs/accuracy.md`: within 1 % of the
//!   path radiance on long paths down, but up to +21 % of the scattered part on a short
//!   slab, most of it the formula's own (LOWTRAN7's band model does not multiply along a
//!   path; `scripts/accuracy/slab-additivity.py`), not the tables'. Where an atmosphere
//!   has slab tables that cover a path ([`crate::slab`]), the tracer takes its scattered
//!   light from them instead.

use irsig_model::SpectralAtmosphere;

use crate::error::AtmosphereError;
use crate::sunlit::{SunlitPaths, Table, fold_azimuth_deg};

/// Midpoints of the hemispheric integral in `sin² z` (zenith) and in azimuth over 0–180°.
const HEMI_ZENITH_STEPS: usize = 400;
const HEMI_AZIMUTH_STEPS: usize = 180;

/// The scattered sunlight of one band or sub-band, for a sun in one direction.
#[derive(Debug, Clone, PartialEq)]
pub struct ScatteredSunlight {
    /// The sun's horizontal direction, unit (x east, y north); `[0, 0]` for a sun at the
    /// zenith (every azimuth alike).
    sun_horizontal: [f64; 2],
    azimuth_deg: Vec<f64>,
    /// Slant paths down to `ground_m`, on the slant table's nodes.
    path: Table,
    ground_m: f64,
    /// Sky paths to space, on the solar table's altitudes and the sky table's zeniths.
    sky: Table,
    /// Eq. 5 of the scattered sky at each of `sky.altitude_m`, W m⁻² sr⁻¹.
    hemispheric: Vec<f64>,
}

impl ScatteredSunlight {
    /// The band `[lo_um, hi_um]` with response `weight(λ in µm)` of `spectral`'s scattered
    /// sunlight, for the sun toward `to_sun` (a direction in the scene frame; only its
    /// horizontal part is used, the zenith angle is the table's first sun's).
    ///
    /// # Errors
    /// An atmosphere without slant tables, a `solar` table or its scattered tables (a plan
    /// without `--sun-scattering`); tables whose sizes do not fit; a band
    /// [`BandQuadrature::new`] refuses.
    pub fn new(
        spectral: &SpectralAtmosphere,
        lo_um: f64,
        hi_um: f64,
        weight: impl Fn(f64) -> f64,
        to_sun: [f64; 3],
    ) -> Result<Self, AtmosphereError> {
        let zenith_deg = spectral.solar.as_ref().map_or(0.0, |s| s.zenith_deg);
        Self::at_sun(spectral, lo_um, hi_um, weight, to_sun, zenith_deg)
    }

    /// As [`Self::new`], for a sun `zenith_deg` (geometric, as the table's suns are) from
    /// the zenith: a day's table of several suns is interpolated between them
    /// ([`SunlitPaths::at_zenith`]); a one-sun table is its sun's.
    ///
    /// # Errors
    /// As [`Self::new`]; with several suns, a zenith angle outside them.
    pub fn at_sun(
        spectral: &SpectralAtmosphere,
        lo_um: f64,
        hi_um: f64,
        weight: impl Fn(f64) -> f64,
        to_sun: [f64; 3],
        zenith_deg: f64,
    ) -> Result<Self, AtmosphereError> {
        // The same band tables `SunlitPaths` reads, and refused alike when missing.
        let (path, sky, azimuth_deg) =
            SunlitPaths::at_zenith(spectral, lo_um, hi_um, weight, zenith_deg)?.into_scattered();
        let ground_m = spectral.slant.as_ref().and_then(|s| s.ground_m);
        let hemispheric = sky
            .altitude_m
            .iter()
            .map(|&h| hemispheric_of(&sky, &azimuth_deg, h))
            .collect();
        let horizontal = to_sun[0].hypot(to_sun[1]);
        let sun_horizontal = if horizontal > 0.0 && horizontal.is_finite() {
            [to_sun[0] / horizontal, to_sun[1] / horizontal]
        } else {
            [0.0, 0.0]
        };
        Ok(Self {
            sun_horizontal,
            azimuth_deg,
            path,
            ground_m: ground_m.unwrap_or(0.0),
            sky,
            hemispheric,
        })
    }

    /// The azimuth of the line of sight `dir` from the sun's vertical plane, 0–180°
    /// (0 for a vertical line or a sun at the zenith).
    #[must_use]
    pub fn relative_azimuth_deg(&self, dir: [f64; 3]) -> f64 {
        let [sx, sy] = self.sun_horizontal;
        let along = dir[0] * sx + dir[1] * sy;
        let across = dir[0] * sy - dir[1] * sx;
        fold_azimuth_deg(across.abs().atan2(along).to_degrees())
    }

    /// Sunlight scattered into the sky path from `altitude_m` along `dir`, whose zenith
    /// angle is `zenith_deg`, W m⁻² sr⁻¹.
    #[must_use]
    pub fn sky(&self, altitude_m: f64, zenith_deg: f64, dir: [f64; 3]) -> f64 {
        let az = self.relative_azimuth_deg(dir);
        self.sky
            .value(&self.azimuth_deg, altitude_m, zenith_deg, az)
    }

    /// The scattered sky's hemispheric (cosine-weighted, thesis eq. 5) radiance at
    /// `altitude_m`, W m⁻² sr⁻¹.
    #[must_use]
    pub fn sky_hemispheric(&self, altitude_m: f64) -> f64 {
        crate::interp::linear(&self.sky.altitude_m, &self.hemispheric, altitude_m)
    }

    /// Sunlight scattered into the view path from an observer at `observer_m` along `dir`
    /// to a point at `target_m`, whose transmittance is `transmission`, W m⁻² sr⁻¹: the
    /// difference of two paths (module documentation), never below 0.
    #[must_use]
    pub fn path(&self, observer_m: f64, target_m: f64, transmission: f64, dir: [f64; 3]) -> f64 {
        let az = self.relative_azimuth_deg(dir);
        let cos_zenith = dir[2].clamp(-1.0, 1.0);
        let value = if cos_zenith < 0.0 {
            let nadir = (-cos_zenith).acos().to_degrees();
            self.slant(observer_m, nadir, az) - transmission * self.slant(target_m, nadir, az)
        } else {
            let zenith = cos_zenith.acos().to_degrees();
            let s = |h: f64| self.sky.value(&self.azimuth_deg, h, zenith, az);
            s(observer_m) - transmission * s(target_m)
        };
        value.max(0.0)
    }

    /// The scattered light of the slant path from `altitude_m` down to the ground: the
    /// table, and below its lowest row a line to 0 at the paths' lower end.
    fn slant(&self, altitude_m: f64, nadir_deg: f64, az: f64) -> f64 {
        let lowest = self.path.altitude_m[0];
        if altitude_m >= lowest {
            return self
                .path
                .value(&self.azimuth_deg, altitude_m, nadir_deg, az);
        }
        if altitude_m <= self.ground_m || lowest <= self.ground_m {
            return 0.0;
        }
        let at_lowest = self.path.value(&self.azimuth_deg, lowest, nadir_deg, az);
        at_lowest * (altitude_m - self.ground_m) / (lowest - self.ground_m)
    }
}

/// Eq. 5 of `sky`'s interpolant at `altitude_m`: `(1/π)∫∫ L cos z dΩ = (1/π)∫₀^{2π}
/// ∫₀^1 L d(sin² z)/2 dφ`, by midpoints in `u = sin² z` and in azimuth over the half circle
/// (doubled: the sky is symmetric about the sun's plane).
fn hemispheric_of(sky: &Table, azimuth_deg: &[f64], altitude_m: f64) -> f64 {
    let mut sum = 0.0;
    for i in 0..HEMI_ZENITH_STEPS {
        let u = (i as f64 + 0.5) / HEMI_ZENITH_STEPS as f64;
        let zenith = u.sqrt().asin().to_degrees();
        for j in 0..HEMI_AZIMUTH_STEPS {
            let az = 180.0 * (j as f64 + 0.5) / HEMI_AZIMUTH_STEPS as f64;
            sum += sky.value(azimuth_deg, altitude_m, zenith, az);
        }
    }
    // (1/π)·2·π (azimuth: the half circle's mean times 2π, over π) · ½ (du) · mean.
    sum / (HEMI_ZENITH_STEPS * HEMI_AZIMUTH_STEPS) as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table(f: impl Fn(f64, f64, f64) -> f64) -> (Table, Vec<f64>) {
        let h = vec![0.0, 500.0];
        let th: Vec<f64> = (0..=18).map(|i| 5.0 * f64::from(i)).collect();
        let az = vec![0.0, 45.0, 90.0, 135.0, 180.0];
        let mut values = Vec::new();
        for &a in &h {
            for &t in &th {
                for &p in &az {
                    values.push(f(a, t, p));
                }
            }
        }
        let t = Table {
            altitude_m: h,
            angle_deg: th,
            values,
            azimuths: az.len(),
        };
        (t, az)
    }

    #[test]
    fn the_hemispheric_integral_of_a_uniform_sky_is_its_radiance() {
        let (t, az) = table(|h, _, _| 2.0 + h / 500.0);
        assert!((hemispheric_of(&t, &az, 0.0) - 2.0).abs() < 1e-12);
        assert!((hemispheric_of(&t, &az, 500.0) - 3.0).abs() < 1e-12);
    }

    #[test]
    fn the_hemispheric_integral_of_cos_z_and_of_cos_phi_are_the_closed_forms() {
        // L = cos z: (1/π)∫∫ cos² z dΩ = 2/3. The cubic in 5° rows follows cos z to ~1e-5.
        let (t, az) = table(|_, z, _| z.to_radians().cos());
        let v = hemispheric_of(&t, &az, 0.0);
        assert!((v - 2.0 / 3.0).abs() < 1e-4, "{v}");
        // L = 1 + cos φ: the cos φ part integrates to 0 over the circle; the rows 45° apart
        // bend it a little, symmetrically about 90°.
        let (t, az) = table(|_, _, p| 1.0 + p.to_radians().cos());
        let v = hemispheric_of(&t, &az, 0.0);
        assert!((v - 1.0).abs() < 1e-3, "{v}");
    }

    #[test]
    fn a_sight_line_is_measured_in_azimuth_from_the_suns_vertical_plane() {
        let (t, az) = table(|_, _, _| 1.0);
        let s = ScatteredSunlight {
            // The sun in the south-east: toward +x −y.
            sun_horizontal: [0.5_f64.sqrt(), -(0.5_f64.sqrt())],
            azimuth_deg: az,
            path: t.clone(),
            ground_m: 1.0,
            sky: t,
            hemispheric: vec![1.0, 1.0],
        };
        let d = |x: f64, y: f64| [x, y, -0.5];
        assert!(s.relative_azimuth_deg(d(1.0, -1.0)).abs() < 1e-9);
        assert!((s.relative_azimuth_deg(d(-1.0, 1.0)) - 180.0).abs() < 1e-9);
        assert!((s.relative_azimuth_deg(d(1.0, 1.0)) - 90.0).abs() < 1e-9);
        assert!((s.relative_azimuth_deg(d(-1.0, -1.0)) - 90.0).abs() < 1e-9);
        assert!((s.relative_azimuth_deg(d(1.0, 0.0)) - 45.0).abs() < 1e-9);
        assert!((s.relative_azimuth_deg(d(0.0, 1.0)) - 135.0).abs() < 1e-9);
        assert!(s.relative_azimuth_deg([0.0, 0.0, 1.0]).abs() < 1e-12);
    }

    #[test]
    fn a_path_is_the_difference_of_two_paths_and_zero_when_it_has_no_length() {
        // P(h) = h (per metre of altitude, any direction): from 500 m down to 200 m through
        // τ = 0.8 is 500 − 0.8·200; below the lowest row (0 m here is the row, so use a
        // table from 100 m) the line to 0 at the ground.
        let (mut t, az) = table(|h, _, _| h);
        t.altitude_m = vec![100.0, 500.0];
        t.values = t
            .values
            .chunks(t.azimuths * t.angle_deg.len())
            .zip([100.0, 500.0])
            .flat_map(|(c, h)| c.iter().map(move |_| h))
            .collect();
        let s = ScatteredSunlight {
            sun_horizontal: [1.0, 0.0],
            azimuth_deg: az,
            path: t.clone(),
            ground_m: 0.0,
            sky: t,
            hemispheric: vec![0.0, 0.0],
        };
        let down = [0.6, 0.0, -0.8];
        assert!((s.path(500.0, 200.0, 0.8, down) - (500.0 - 0.8 * 200.0)).abs() < 1e-9);
        assert!((s.path(500.0, 50.0, 0.8, down) - (500.0 - 0.8 * 50.0)).abs() < 1e-9);
        assert!(s.path(300.0, 300.0, 1.0, down).abs() < 1e-9);
        assert!((s.path(300.0, 0.0, 0.5, down) - 300.0).abs() < 1e-9);
    }
}
