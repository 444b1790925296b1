//! How many of a frame's view paths lie past the slant tables' widest nadir row, toward
//! the horizon, where the `table` model's correction fades to none and its error against
//! LOWTRAN7 grows to kelvins: never silent ([`Tracer::horizon_census`]).
//!
//! The census follows each pixel's centre ray to its first event, as the frame does, and
//! counts the paths to a facet or to the terrain (below the horizon); the sky's paths are
//! the sky tables', whose rows reach the horizon, and reflections start at a surface.

use irsig_radiometry::BandModel;
use rayon::prelude::*;

use crate::camera::Camera;
use crate::env::Atmosphere;
use crate::tile::Tile;
use crate::tracer::Tracer;

/// What [`Tracer::horizon_census`] found in one frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HorizonCensus {
    /// The camera's altitude above the ground, metres.
    pub camera_m: f64,
    /// The slant tables' widest nadir row, degrees.
    pub widest_row_deg: f64,
    /// Pixels whose centre ray's first event is a facet or the terrain.
    pub ground_paths: u64,
    /// Those past the widest row.
    pub beyond: u64,
    /// The largest nadir angle among them, degrees (0 when none).
    pub largest_nadir_deg: f64,
}

impl<B: BandModel, A: Atmosphere> Tracer<B, A> {
    /// The census of the centre-ray view paths of `camera`'s pixels in `window` against
    /// the slant tables' widest nadir row; `None` when the atmosphere's model has no slant
    /// tables. It costs an arc cosine a pixel, and a closest hit for each ray above the
    /// horizon.
    #[must_use]
    pub fn horizon_census(&self, camera: &Camera, window: Tile) -> Option<HorizonCensus> {
        let atmosphere = &self.bands.bands.first()?.atmosphere;
        let widest_row_deg = atmosphere.model()?.widest_nadir_row_deg()?;
        let camera_m = camera.position_m[2].max(0.0);
        let horizon_deg = atmosphere.critical_nadir_angle_deg(camera_m);
        let origin = self.geometry.to_local(camera.position_m);
        let columns = window.x..window.x + window.width;
        let per_row: Vec<(u64, u64, f64)> = (window.y..window.y + window.height)
            .into_par_iter()
            .map(|row| {
                let (mut ground, mut beyond, mut largest) = (0, 0, 0.0_f64);
                for column in columns.clone() {
                    let dir = camera.pixel_direction(column, row);
                    let nadir_deg = (-dir[2]).clamp(-1.0, 1.0).acos().to_degrees();
                    // Below the horizon a ray ends at a facet or the terrain alike: only a
                    // ray above it needs the scene to say whether a facet stops it.
                    let ends_low = nadir_deg < horizon_deg
                        || self
                            .geometry
                            .closest_hit(origin, dir, 0.0, f64::INFINITY, None)
                            .is_some();
                    if !ends_low {
                        continue;
                    }
                    ground += 1;
                    if nadir_deg > widest_row_deg + 1e-6 && nadir_deg < 90.0 {
                        beyond += 1;
                        largest = largest.max(nadir_deg);
                    }
                }
                (ground, beyond, largest)
            })
            .collect();
        let mut census = HorizonCensus {
            camera_m,
            widest_row_deg,
            ground_paths: 0,
            beyond: 0,
            largest_nadir_deg: 0.0,
        };
        for (ground, beyond, largest) in per_row {
            census.ground_paths += ground;
            census.beyond += beyond;
            census.largest_nadir_deg = census.largest_nadir_deg.max(largest);
        }
        Some(census)
    }
}
