//! The atmosphere data's error of each pixel ([`Layer::AtmosphereDataError`]), K: how far
//! the atmosphere's tables may put the pixel's apparent temperature, from the recorded
//! residual of the table region its centre ray's paths read
//! ([`irsig_atmosphere::data_error`]).
//!
//! A pixel that sees the sky reads the sky table: its error is the sky's record from the
//! observer's altitude at the ray's zenith angle. A pixel that sees a surface (a facet or
//! the terrain) reads the slant table along its view path, by the path's nadir angle and
//! the observer's altitude, and adds the sky the surface reflects: the reflected sky
//! reaches the sensor as `(1 − ε)·τ·L_sky` at most (the surface's reflectance is `1 − ε`
//! for an opaque surface, Kirchhoff's law, and the path passes `τ` of it), so an error
//! `δL_sky` of the sky radiance moves the sensor's by at most `(1 − ε)·τ·δL_sky`, where
//! `δL_sky` is the sky's record over the whole hemisphere above the surface (it may
//! reflect any direction). In apparent temperature that is `(1 − ε)·τ·sky_k` times
//! `B′(T_sky)/B′(T_pixel)`, the ratio of the band's dB/dT at the sky's brightness and at
//! the pixel's apparent temperature; the ratio is at most 1 wherever the sky is no warmer
//! than the pixel (dB/dT grows with temperature), and it is taken as 1. The two errors
//! are added, not root-sum-squared: each is a bound, and their signs are not known.
//!
//! [`Layer::AtmosphereDataError`]: irsig_model::truth::Layer::AtmosphereDataError

use irsig_atmosphere::data_error::DataError;
use irsig_model::decision::DataErrorSummary;
use irsig_radiometry::BandModel;
use rayon::prelude::*;

use crate::camera::Camera;
use crate::env::Atmosphere;
use crate::tile::Tile;
use crate::tracer::{Event, Tracer, TruthPixel};
use glam::DVec3;

/// The data error of a path from an observer `observer_m` above the ground along the unit
/// direction `dir` to a surface `range_m` away, K (`None`: past the widest row in a band
/// never measured there). A path looking up (a facet above the observer) is read from
/// its upper end down, as the slant table reads it.
#[must_use]
pub fn view_path_k(data: &DataError, observer_m: f64, dir: DVec3, range_m: f64) -> Option<f64> {
    let nadir_deg = (-dir[2]).clamp(-1.0, 1.0).acos().to_degrees();
    if nadir_deg <= 90.0 {
        data.ground_path_k(observer_m, nadir_deg)
    } else {
        let range_m = if range_m.is_finite() { range_m } else { 0.0 };
        data.ground_path_k(observer_m + range_m * dir[2], 180.0 - nadir_deg)
    }
}

/// The data error of one pixel whose centre ray left an observer `observer_m` above the
/// ground along `dir` and met what `truth` records, K (NaN: not measured). See the
/// module's doc for the reflected sky's share.
#[must_use]
pub fn pixel_k(data: &DataError, observer_m: f64, dir: DVec3, truth: &TruthPixel) -> f64 {
    if truth.event == Event::Sky {
        return data.sky_k(observer_m, zenith_deg(dir));
    }
    let Some(view) = view_path_k(data, observer_m, dir, f64::from(truth.range_m)) else {
        return f64::NAN;
    };
    let share = f64::from((1.0 - truth.emissivity) * truth.transmission);
    // An unknown share counts whole.
    let share = if share.is_finite() {
        share.clamp(0.0, 1.0)
    } else {
        1.0
    };
    let range_m = f64::from(truth.range_m);
    let surface_m = if range_m.is_finite() {
        (observer_m + range_m * dir[2]).max(0.0)
    } else {
        0.0
    };
    view + share * data.hemisphere_sky_k(surface_m)
}

/// The zenith angle of the unit direction `dir`, degrees.
fn zenith_deg(dir: DVec3) -> f64 {
    dir[2].clamp(-1.0, 1.0).acos().to_degrees()
}

/// The frame summary of a data-error layer: its 99th percentile and largest value over
/// the pixels that have one, and the share that has none.
#[must_use]
pub fn summary(layer_k: &[f32]) -> DataErrorSummary {
    let mut known: Vec<f32> = layer_k.iter().copied().filter(|v| v.is_finite()).collect();
    let unmeasured = layer_k.len() - known.len();
    known.sort_unstable_by(f32::total_cmp);
    // The nearest-rank percentile: the value at or below which 99 % of the pixels lie.
    let p99 = if known.is_empty() {
        0.0
    } else {
        let rank = (0.99 * known.len() as f64).ceil() as usize;
        f64::from(known[rank.clamp(1, known.len()) - 1])
    };
    DataErrorSummary {
        p99_k: p99,
        max_k: known.last().map_or(0.0, |&v| f64::from(v)),
        unmeasured_share: unmeasured as f64 / layer_k.len().max(1) as f64,
    }
}

impl<B: BandModel, A: Atmosphere> Tracer<B, A> {
    /// The data error of each pixel of `camera`'s `window` whose centre rays met what
    /// `truth` records (row-major in the window), K, as the truth EXR stores it.
    #[must_use]
    pub fn data_error_layer(
        &self,
        data: &DataError,
        camera: &Camera,
        window: Tile,
        truth: &[TruthPixel],
    ) -> Vec<f32> {
        let observer_m = camera.position_m[2].max(0.0);
        let width = window.width.max(1) as usize;
        truth
            .par_iter()
            .enumerate()
            .map(|(i, t)| {
                let (column, row) = ((i % width) as u32, (i / width) as u32);
                let dir = camera.pixel_direction(window.x + column, window.y + row);
                pixel_k(data, observer_m, dir, t) as f32
            })
            .collect()
    }

    /// The data error of the view paths of `camera`'s pixels in `window`, summarised,
    /// before the frame is traced (what a decision records): each centre ray followed to
    /// its first facet (or the terrain below the horizon, or the sky above it), the view
    /// path's error alone. The sky a surface reflects adds up to `(1 − ε)·τ` times the
    /// sky's record over the hemisphere per pixel; the truth layer
    /// ([`Self::data_error_layer`]) holds it.
    #[must_use]
    pub fn data_error_census(
        &self,
        data: &DataError,
        camera: &Camera,
        window: Tile,
    ) -> DataErrorSummary {
        let observer_m = camera.position_m[2].max(0.0);
        let horizon_deg = self
            .bands
            .bands
            .first()
            .map_or(90.0, |b| b.atmosphere.critical_nadir_angle_deg(observer_m));
        let origin = self.geometry.to_local(camera.position_m);
        let columns = window.x..window.x + window.width;
        let layer: Vec<f32> = (window.y..window.y + window.height)
            .into_par_iter()
            .flat_map_iter(|row| {
                columns.clone().map(move |column| {
                    let dir = camera.pixel_direction(column, row);
                    let nadir_deg = (-dir[2]).clamp(-1.0, 1.0).acos().to_degrees();
                    let hit = self
                        .geometry
                        .closest_hit(origin, dir, 0.0, f64::INFINITY, None)
                        .map(|h| h.distance_m);
                    let k = match hit {
                        Some(range_m) => view_path_k(data, observer_m, dir, range_m),
                        None if nadir_deg < horizon_deg => {
                            view_path_k(data, observer_m, dir, f64::INFINITY)
                        }
                        None => Some(data.sky_k(observer_m, zenith_deg(dir))),
                    };
                    k.map_or(f32::NAN, |k| k as f32)
                })
            })
            .collect();
        summary(&layer)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use irsig_model::InterpolationResidual;

    const RESIDUAL: InterpolationResidual = InterpolationResidual {
        slant_k: 0.05,
        grazing_k: 0.2,
        sky_k: 0.5,
    };

    /// An atmosphere that is not a built-in: its residual answers every region but past
    /// the widest row.
    fn data() -> DataError {
        DataError::new(RESIDUAL, 88.0, "my-own", [8.0, 14.0])
    }

    fn us_std() -> DataError {
        DataError::new(RESIDUAL, 88.0, "us-std-1976", [8.0, 14.0])
    }

    fn truth(event: Event, emissivity: f32, transmission: f32) -> TruthPixel {
        TruthPixel {
            event,
            primary_material: 1,
            secondary_material: 0,
            range_m: 100.0,
            cos_incidence: 1.0,
            temperature_k: 300.0,
            emissivity,
            transmission,
            path_radiance_w_m2_sr: 0.0,
            sky_view_factor: 1.0,
            facet: 0,
            temperature_sensitivity: 0.0,
            emissivity_sensitivity: 0.0,
        }
    }

    /// A unit direction `nadir_deg` from nadir.
    fn dir(nadir_deg: f64) -> DVec3 {
        let a = nadir_deg.to_radians();
        DVec3::new(a.sin(), 0.0, -a.cos())
    }

    #[test]
    fn a_pixel_adds_the_reflected_sky_to_its_view_path() {
        let d = data();
        // A blackbody reflects nothing: the view path's residual alone.
        let black = truth(Event::Diffuse, 1.0, 0.9);
        assert!((pixel_k(&d, 300.0, dir(0.0), &black) - 0.05).abs() < 1e-9);
        assert!((pixel_k(&d, 300.0, dir(85.0), &black) - 0.2).abs() < 1e-9);
        // ε = 0.9 through τ = 0.8: 0.05 + 0.1·0.8·0.5 = 0.09 K.
        let grey = truth(Event::Diffuse, 0.9, 0.8);
        assert!((pixel_k(&d, 300.0, dir(30.0), &grey) - 0.09).abs() < 1e-6);
        // A perfect mirror in vacuum: the whole sky's error.
        let mirror = truth(Event::SpecularEscapes, 0.0, 1.0);
        assert!((pixel_k(&d, 300.0, dir(30.0), &mirror) - 0.55).abs() < 1e-9);
    }

    #[test]
    fn a_sky_pixel_has_the_sky_residual_at_any_zenith() {
        let d = data();
        let sky = truth(Event::Sky, f32::NAN, f32::NAN);
        for zenith in [0.0, 45.0, 90.0] {
            assert!((pixel_k(&d, 1700.0, dir(180.0 - zenith), &sky) - 0.5).abs() < 1e-12);
        }
    }

    #[test]
    fn a_built_in_reads_the_sky_where_the_ray_looks_and_the_reflected_sky_where_it_lands() {
        let d = us_std();
        let sky = truth(Event::Sky, f32::NAN, f32::NAN);
        // From 1.7 km straight up and 5° above the horizontal: the cells of that altitude
        // at 0° and 85° from the zenith.
        assert_eq!(
            pixel_k(&d, 1700.0, dir(180.0), &sky).to_bits(),
            d.sky_k(1700.0, 0.0).to_bits()
        );
        assert_eq!(
            pixel_k(&d, 1700.0, dir(95.0), &sky).to_bits(),
            d.sky_k(1700.0, 85.0).to_bits()
        );
        assert_ne!(
            d.sky_k(1700.0, 0.0).to_bits(),
            d.sky_k(975.0, 0.0).to_bits()
        );
        // A perfect mirror 100 m down a path 60° from nadir, from 1025 m: it lies at
        // 975 m, and reflects that altitude's sky from any direction.
        let mirror = truth(Event::SpecularEscapes, 0.0, 1.0);
        let expected = d.ground_path_k(1025.0, 60.0).unwrap() + d.hemisphere_sky_k(975.0);
        assert!((pixel_k(&d, 1025.0, dir(60.0), &mirror) - expected).abs() < 1e-9);
        assert_ne!(
            d.hemisphere_sky_k(975.0).to_bits(),
            d.hemisphere_sky_k(1025.0).to_bits()
        );
    }

    #[test]
    fn past_the_widest_row_the_measured_cost_answers() {
        let d = us_std();
        let terrain = truth(Event::Terrain, 1.0, 0.5);
        // us-std-1976 from 300 m at 89°: the cells 88.75° (0.782) and 89° (1.303).
        assert!((pixel_k(&d, 300.0, dir(89.0), &terrain) - 1.303).abs() < 1e-9);
        // 3-5 um has its own measurement: 0.621 K there.
        let mwir = DataError::new(RESIDUAL, 88.0, "us-std-1976", [3.0, 5.0]);
        assert!((pixel_k(&mwir, 300.0, dir(89.0), &terrain) - 0.621).abs() < 1e-9);
        // Unmeasured in 1-3 um: NaN, never a made-up number.
        let swir = DataError::new(RESIDUAL, 88.0, "us-std-1976", [1.0, 3.0]);
        assert!(pixel_k(&swir, 300.0, dir(89.0), &terrain).is_nan());
    }

    #[test]
    fn a_facet_above_the_observer_is_read_from_its_upper_end() {
        let d = data();
        // 100 m away 5° above the horizontal: read down from its top at 85° from nadir,
        // in the grazing rows.
        let up = dir(95.0);
        assert_eq!(view_path_k(&d, 5.0, up, 100.0), Some(0.2));
        assert_eq!(view_path_k(&d, 5.0, dir(150.0), 100.0), Some(0.05));
    }

    #[test]
    fn the_summary_takes_the_nearest_rank_and_counts_the_unmeasured() {
        let mut layer: Vec<f32> = (1..=100).map(|k| k as f32 / 100.0).collect();
        layer.push(f32::NAN);
        let s = summary(&layer);
        assert!((s.p99_k - 0.99).abs() < 1e-6);
        assert!((s.max_k - 1.0).abs() < 1e-6);
        assert!((s.unmeasured_share - 1.0 / 101.0).abs() < 1e-12);
        let empty = summary(&[]);
        assert_eq!(
            (empty.p99_k, empty.max_k, empty.unmeasured_share),
            (0.0, 0.0, 0.0)
        );
    }
}
