//! How many of a frame's view paths the slab tables (`irsig_atmosphere::slab`) leave to the
//! other models, and why: a fallback is never silent ([`Tracer::slab_census`]).
//!
//! The census follows each pixel's centre ray to its first event, as the frame does: a
//! facet's path is the slab tables' when they cover it; a path to the terrain (z = 0) or
//! the sky is the slant and sky tables' by design, and not counted. Reflections and
//! sky-view rays are not counted either: their paths start at a surface, never at a slab
//! table's observer.

use std::collections::BTreeMap;

use irsig_atmosphere::slab::SlabMiss;
use irsig_radiometry::BandModel;
use rayon::prelude::*;

use crate::camera::Camera;
use crate::env::Atmosphere;
use crate::tile::Tile;
use crate::tracer::Tracer;

/// What [`Tracer::slab_census`] found in one frame.
#[derive(Debug, Clone, PartialEq)]
pub struct SlabCensus {
    /// The camera's altitude above the ground, metres.
    pub camera_m: f64,
    /// The slab tables' observers, metres.
    pub observers_m: Vec<f64>,
    /// Pixels whose centre ray's first event is a facet.
    pub facet_paths: u64,
    /// Those the slab tables do not cover, by why.
    pub missed: BTreeMap<SlabMiss, u64>,
}

impl SlabCensus {
    /// The paths the tables do not cover.
    #[must_use]
    pub fn missed_paths(&self) -> u64 {
        self.missed.values().sum()
    }
}

impl<B: BandModel, A: Atmosphere> Tracer<B, A> {
    /// The census of the centre-ray view paths of `camera`'s pixels in `window` against
    /// the slab tables; `None` when the atmosphere has none. It costs one closest hit a
    /// pixel, a small share of a frame's rays.
    #[must_use]
    pub fn slab_census(&self, camera: &Camera, window: Tile) -> Option<SlabCensus> {
        let slabs = self.bands.bands.first()?.atmosphere.slabs()?;
        let camera_m = camera.position_m[2].max(0.0);
        let origin = self.geometry.to_local(camera.position_m);
        let columns = window.x..window.x + window.width;
        let per_row: Vec<(u64, Vec<SlabMiss>)> = (window.y..window.y + window.height)
            .into_par_iter()
            .map(|row| {
                let mut facets = 0;
                let mut missed = Vec::new();
                for column in columns.clone() {
                    let dir = camera.pixel_direction(column, row);
                    let Some(hit) =
                        self.geometry
                            .closest_hit(origin, dir, 0.0, f64::INFINITY, None)
                    else {
                        continue;
                    };
                    facets += 1;
                    let target_m = self.geometry.to_world(hit.point_local)[2].max(0.0);
                    missed.extend(slabs.why_not(camera_m, target_m, dir[2]));
                }
                (facets, missed)
            })
            .collect();
        let mut census = SlabCensus {
            camera_m,
            observers_m: slabs.observers_m(),
            facet_paths: 0,
            missed: BTreeMap::new(),
        };
        for (facets, missed) in per_row {
            census.facet_paths += facets;
            for m in missed {
                *census.missed.entry(m).or_default() += 1;
            }
        }
        Some(census)
    }
}
