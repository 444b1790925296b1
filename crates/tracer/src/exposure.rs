//! What each facet of a scene sees, for a heat balance: the share of it the sun reaches at
//! a moment, and what its hemisphere holds (sky, terrain, other facets). The thermal model
//! takes these as numbers; rays stay here.
//!
//! # The exposed side
//!
//! A facet's exposed side is the side its winding normal points to (counter-clockwise seen
//! from the front, as the raw scene defines it): the side a wall's surface layer faces.
//! Its back is the wall's back boundary, which the thermal model handles, so nothing here
//! looks behind a facet. Closed meshes are wound outward, so their facets' exposed sides
//! face the air.
//!
//! # Sample points
//!
//! A facet is cut into `k × k` congruent triangles (each edge in `k` parts) and sampled at
//! their centroids: `k²` points spread evenly over it, the same on every run. One point
//! (`k = 1`) is the facet's centroid.
//!
//! # The sun
//!
//! [`Exposure::sunlit_fraction`] is the share of a facet's sample points from which a ray
//! toward the sun's centre meets no facet: a point sun, whose shadow edges are sharp. A
//! facet whose exposed side faces away from the sun, or a sun at or below the horizontal,
//! gives 0. The cosine of incidence is not in it: the caller multiplies the beam by it.
//!
//! # The hemisphere
//!
//! [`Exposure::views`] casts cosine-weighted, stratified rays over each facet's exposed
//! hemisphere from its sample points in turn (Malley's method, as the tracer's sky-view
//! rays), each from a random stream of the facet's own (the seed and the facet index), so
//! that the result is the same at any thread count. The share of rays that meet a facet
//! estimates the view factor to it, the share that leave the scene upward the sky's, and
//! downward the terrain's (the flat ground beyond the scene). The three sum to 1. The
//! estimate's standard error is about `sqrt(F (1 − F) / N)` for N rays.

use glam::DVec3;
use irsig_model::RawScene;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

use crate::error::{TraceError, TraceErrorKind};
use crate::geometry::Geometry;

/// The most sample points per facet side ([`ExposureOptions::samples_per_side`]): 64² =
/// 4,096 points.
pub const MAX_SAMPLES_PER_SIDE: u32 = 64;
/// The most hemisphere rays per facet ([`Exposure::views`]).
pub const MAX_HEMISPHERE_RAYS: u32 = 1 << 16;

/// The scene's facets in a BVH, with each facet's frame, for exposure queries.
#[derive(Debug)]
pub struct Exposure {
    geometry: Geometry,
    frames: Vec<FacetFrame>,
}

/// A facet's place: its vertices (local metres, as the BVH holds them about its centre),
/// its unit winding normal and its area.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FacetFrame {
    /// The three vertices, local metres.
    pub vertices_local: [DVec3; 3],
    /// The unit normal of the exposed side.
    pub normal: DVec3,
    /// Area, m².
    pub area_m2: f64,
}

/// What a facet's exposed hemisphere holds, as cosine-weighted shares (view factors) that
/// sum to 1.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct FacetView {
    /// The share of the hemisphere that is open sky.
    pub sky: f64,
    /// The share that is the terrain beyond the scene (rays leaving below the horizontal).
    pub terrain: f64,
    /// The facets it sees and the share of each, by facet index, ascending.
    pub facets: Vec<(u32, f64)>,
}

/// The [`FacetView`]s of a list of facets, stored flat, in the list's order (the facets
/// seen are named by their index in the scene).
#[derive(Debug, Clone, PartialEq)]
pub struct ViewFactors {
    /// Per facet, the sky's share.
    pub sky: Vec<f32>,
    /// Per facet, the terrain's share.
    pub terrain: Vec<f32>,
    /// Where facet `i`'s entries start in `seen` and `share` (`i + 1`'s start is its end).
    pub start: Vec<u32>,
    /// The facets seen.
    pub seen: Vec<u32>,
    /// The share of each facet seen.
    pub share: Vec<f32>,
    /// The rays cast per facet.
    pub rays: u32,
}

impl ViewFactors {
    /// The `i`-th listed facet's facets seen and their shares.
    #[must_use]
    pub fn seen_by(&self, i: usize) -> (&[u32], &[f32]) {
        let (a, b) = (self.start[i] as usize, self.start[i + 1] as usize);
        (&self.seen[a..b], &self.share[a..b])
    }
}

/// How an exposure query samples a facet.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ExposureOptions {
    /// Sample points per facet side: `k²` points per facet, 1 to [`MAX_SAMPLES_PER_SIDE`].
    pub samples_per_side: u32,
}

impl Exposure {
    /// Builds the BVH over the scene's facets.
    ///
    /// # Errors
    /// A scene that breaks the data model's rules (empty, a degenerate facet, a NaN).
    pub fn new(scene: &RawScene) -> Result<Self, TraceError> {
        scene
            .validate()
            .map_err(|e| TraceError::new(TraceErrorKind::InvalidScene(e)))?;
        if scene.facets.is_empty() {
            return Err(TraceError::new(TraceErrorKind::InvalidOptions(
                "the scene has no facets: nothing to expose".into(),
            )));
        }
        let world = |i: usize| {
            scene.facets[i]
                .vertices
                .map(|v| DVec3::from(scene.positions_m[v as usize]))
        };
        let geometry = Geometry::new(&(0..scene.facets.len()).map(world).collect::<Vec<_>>());
        let frames = (0..scene.facets.len())
            .into_par_iter()
            .map(|i| {
                let v = world(i).map(|p| geometry.to_local(p));
                let cross = (v[1] - v[0]).cross(v[2] - v[0]);
                FacetFrame {
                    vertices_local: v,
                    normal: cross.normalize(),
                    area_m2: 0.5 * cross.length(),
                }
            })
            .collect();
        Ok(Self { geometry, frames })
    }

    /// The number of facets.
    #[must_use]
    pub fn facets(&self) -> usize {
        self.frames.len()
    }

    /// Facet `i`'s frame.
    #[must_use]
    pub fn frame(&self, i: usize) -> &FacetFrame {
        &self.frames[i]
    }

    /// Sample point `j` of `k²` on facet `i`, local metres: the centroid of the `j`-th of
    /// the `k × k` congruent triangles the facet is cut into.
    fn sample_point(&self, i: usize, j: u32, k: u32) -> DVec3 {
        let [a, b, c] = self.frames[i].vertices_local;
        let (u, v) = sub_triangle_centroid(j, k);
        a + (b - a) * u + (c - a) * v
    }

    /// The share of facet `i`'s `k²` sample points from which the sun, in the unit
    /// direction `to_sun` (scene frame, z up), is not hidden by any facet; 0 when the
    /// exposed side faces away from it or the sun is not above the horizontal.
    #[must_use]
    pub fn sunlit_fraction(&self, i: usize, to_sun: DVec3, options: ExposureOptions) -> f64 {
        let s = to_sun;
        let frame = &self.frames[i];
        if s.z <= 0.0 || frame.normal.dot(s) <= 0.0 {
            return 0.0;
        }
        let k = options.samples_per_side.clamp(1, MAX_SAMPLES_PER_SIDE);
        let eps = self.geometry.surface_epsilon_m();
        let lit = (0..k * k)
            .filter(|&j| {
                let p = self.sample_point(i, j, k);
                !self
                    .geometry
                    .occluded(p, to_sun, eps, f64::INFINITY, Some(i as u32))
            })
            .count();
        lit as f64 / f64::from(k * k)
    }

    /// [`Self::sunlit_fraction`] of each of `facets` (indices into the scene), in
    /// parallel; the same at any thread count.
    #[must_use]
    pub fn sunlit_fractions(
        &self,
        facets: &[u32],
        to_sun: DVec3,
        options: ExposureOptions,
    ) -> Vec<f32> {
        facets
            .par_iter()
            .map(|&i| self.sunlit_fraction(i as usize, to_sun, options) as f32)
            .collect()
    }

    /// What facet `i`'s exposed hemisphere holds, from `rays` cosine-weighted rays cast
    /// from its sample points (an equal share from each; with fewer rays than points, one
    /// from each of the first), drawn from the stream of `seed` and the facet.
    #[must_use]
    pub fn view(&self, i: usize, rays: u32, seed: u64, options: ExposureOptions) -> FacetView {
        let rays = rays.clamp(1, MAX_HEMISPHERE_RAYS);
        let k = options.samples_per_side.clamp(1, MAX_SAMPLES_PER_SIDE);
        let frame = &self.frames[i];
        let n = frame.normal;
        let (t, b) = n.any_orthonormal_pair();
        let eps = self.geometry.surface_epsilon_m();
        let mut rng =
            ChaCha8Rng::seed_from_u64(seed ^ (i as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15));
        let (mut sky, mut terrain) = (0u32, 0u32);
        let mut hits: Vec<u32> = Vec::new();
        // Each sample point casts its own share of the rays, stratified on its own: strata
        // shared across points would tie a point to a band of angles.
        let points = k * k;
        for j in 0..points.min(rays) {
            let own = rays / points + u32::from(j < rays % points);
            let m = f64::from(own).sqrt() as u32;
            let p = self.sample_point(i, j, k);
            for r in 0..own {
                let (xi1, xi2): (f64, f64) = (rng.random(), rng.random());
                let (u1, u2) = stratified(r, m, xi1, xi2);
                // Malley's method: uniform on the disc, projected up.
                let rad = u1.sqrt();
                let phi = std::f64::consts::TAU * u2;
                let d =
                    t * (rad * phi.cos()) + b * (rad * phi.sin()) + n * (1.0 - u1).max(0.0).sqrt();
                match self
                    .geometry
                    .closest_hit(p, d, eps, f64::INFINITY, Some(i as u32))
                {
                    Some(h) => hits.push(h.facet),
                    None if d.z >= 0.0 => sky += 1,
                    None => terrain += 1,
                }
            }
        }
        hits.sort_unstable();
        let per_ray = 1.0 / f64::from(rays);
        let mut facets: Vec<(u32, f64)> = Vec::new();
        for f in hits {
            match facets.last_mut() {
                Some((g, share)) if *g == f => *share += per_ray,
                _ => facets.push((f, per_ray)),
            }
        }
        FacetView {
            sky: f64::from(sky) * per_ray,
            terrain: f64::from(terrain) * per_ray,
            facets,
        }
    }

    /// [`Self::view`] of each of `facets` (indices into the scene), in parallel, in that
    /// order; the same at any thread count.
    ///
    /// # Errors
    /// More facet entries than a `u32` index holds (`rays` × facets above 4 × 10⁹).
    pub fn views(
        &self,
        facets: &[u32],
        rays: u32,
        seed: u64,
        options: ExposureOptions,
    ) -> Result<ViewFactors, TraceError> {
        let views: Vec<FacetView> = facets
            .par_iter()
            .map(|&i| self.view(i as usize, rays, seed, options))
            .collect();
        let entries: usize = views.iter().map(|v| v.facets.len()).sum();
        if u32::try_from(entries).is_err() {
            return Err(TraceError::new(TraceErrorKind::InvalidOptions(format!(
                "{entries} facet-to-facet view factors do not fit: use fewer hemisphere rays"
            ))));
        }
        let mut out = ViewFactors {
            sky: Vec::with_capacity(views.len()),
            terrain: Vec::with_capacity(views.len()),
            start: Vec::with_capacity(views.len() + 1),
            seen: Vec::with_capacity(entries),
            share: Vec::with_capacity(entries),
            rays: rays.clamp(1, MAX_HEMISPHERE_RAYS),
        };
        out.start.push(0);
        for v in views {
            out.sky.push(v.sky as f32);
            out.terrain.push(v.terrain as f32);
            for (f, s) in v.facets {
                out.seen.push(f);
                out.share.push(s as f32);
            }
            out.start.push(out.seen.len() as u32);
        }
        Ok(out)
    }
}

/// The barycentric coordinates `(u, v)` (the weights of the second and third vertex) of the
/// centroid of sub-triangle `j` of the `k²` a triangle is cut into by dividing each edge in
/// `k`. In units of `1/k`, the strip `a ≤ kv < a + 1` holds `k − a` upright sub-triangles,
/// corners `(b, a)`, `(b + 1, a)`, `(b, a + 1)`, and `k − a − 1` inverted ones, corners
/// `(b + 1, a)`, `(b, a + 1)`, `(b + 1, a + 1)`; strip `a = k − 1 − r` holds sub-triangles
/// `r²` to `(r + 1)² − 1`, upright and inverted in turn.
fn sub_triangle_centroid(j: u32, k: u32) -> (f64, f64) {
    let j = j % (k * k);
    let mut r = f64::from(j).sqrt() as u32;
    while r * r > j {
        r -= 1;
    }
    while (r + 1) * (r + 1) <= j {
        r += 1;
    }
    let q = j - r * r;
    let a = f64::from(k - 1 - r);
    let b = f64::from(q / 2);
    let (cu, cv) = if q % 2 == 0 {
        (b + 1.0 / 3.0, a + 1.0 / 3.0)
    } else {
        (b + 2.0 / 3.0, a + 2.0 / 3.0)
    };
    let k = f64::from(k);
    (cu / k, cv / k)
}

/// Sample `r`'s point in the unit square: an `m × m` grid of strata, each jittered by
/// `(xi1, xi2)`, then any remainder unstratified (the tracer's sky-view rule).
fn stratified(r: u32, m: u32, xi1: f64, xi2: f64) -> (f64, f64) {
    if r < m * m {
        (
            (f64::from(r % m) + xi1) / f64::from(m),
            (f64::from(r / m) + xi2) / f64::from(m),
        )
    } else {
        (xi1, xi2)
    }
}
