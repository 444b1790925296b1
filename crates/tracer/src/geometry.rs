//! Triangles in an obvhs CWBVH, intersected with the watertight test of Woop, Benthin and
//! Wald (2013, "Watertight Ray/Triangle Intersection", JCGT 2(1)).
//!
//! # Precision
//!
//! obvhs works in f32. The geometry is re-centred on the centre of its bounding box (in f64)
//! before it is rounded to f32, so a scene at map coordinates 500 km from the origin is
//! intersected exactly as the same scene at the origin. Every ray is also started, in f64,
//! just before it enters the scene's bounding box, so a sensor 12 km away does not lose
//! f32 digits to its distance. The closest hit is then refined in f64: distance, point and
//! angle come from the f64 plane of the hit triangle.
//!
//! The CWBVH node test clamps its entry distance to a fixed 1e-4 and ignores `ray.tmin`;
//! a primitive nearer than 1e-4 (metres) to the ray origin would be silently skipped. So
//! every ray handed to obvhs starts at least [`ORIGIN_BACKOFF_M`] *before* the first
//! distance it may hit, and the triangle callback enforces the real minimum distance
//! itself.
//!
//! # Back faces
//!
//! Facets are **two-sided**: a ray hits a triangle from either side. Meshes from OBJ and
//! glTF are often wound inconsistently, and a closed mesh is seen only from outside anyway;
//! dropping reversed hits (what the 1990 code did, silently) leaks rays through every
//! facet wound the wrong way. The normal used for angles and reflections is the
//! geometric normal turned to face the incoming ray; [`Hit::back_face`] says when that
//! needed a flip, so a tool can report inconsistent winding.

use glam::{UVec2, Vec3A};
use obvhs::{
    BvhBuildParams,
    aabb::Aabb,
    bvh2::reinsertion::ReinsertionOptimizer,
    cwbvh::{CwBvh, Traversal, builder::build_cwbvh, bvh2_to_cwbvh::bvh2_to_cwbvh},
    ploc::PlocBuilder,
    ray::Ray,
};
use rayon::prelude::*;

use glam::DVec3;

/// How far before the first admissible distance a ray handed to obvhs starts, in metres:
/// twice the CWBVH's fixed 1e-4 entry clamp.
pub const ORIGIN_BACKOFF_M: f64 = 2e-4;

/// The most triangles one chunk of the BVH build holds (see [`Bvh`]).
pub const CHUNK_TRIANGLES: usize = 1 << 14;

/// obvhs's build preset for every chunk. BENCHMARKS.md, "what obvhs's build presets
/// trade": at 1M triangles the very fast preset built in 0.62 s against the medium one's
/// 0.81 s and its primary rays were faster too (212 against 235 ns); at 100k they were 6 %
/// slower.
const BUILD: BvhBuildParams = BvhBuildParams::very_fast_build();

/// A closest hit, in world-relative f64 terms, with the caller's data for the facet hit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit<P = ()> {
    /// Index of the facet in the input triangle list (the raw scene's facet index).
    pub facet: u32,
    /// Distance from the ray origin in metres (the ray direction is a unit vector).
    pub distance_m: f64,
    /// The hit point in local (re-centred) coordinates, metres.
    pub point_local: DVec3,
    /// The unit facet normal turned towards the ray's origin.
    pub normal: DVec3,
    /// Cosine of the angle between the reversed ray and `normal`, 0 to 1.
    pub cos_incidence: f64,
    /// True when the ray arrived from the side opposite the facet's winding normal.
    pub back_face: bool,
    /// What the caller attached to the facet ([`Geometry::with_data`]).
    pub data: P,
}

/// Triangles in obvhs BVHs, re-centred, with each facet's f64 plane for refinement and the
/// caller's per-facet data `P` (the tracer keeps its radiometry there).
#[derive(Debug)]
pub struct Geometry<P = ()> {
    centre_m: DVec3,
    bvh: Bvh,
    /// Per triangle, in BVH order (chunk after chunk, each in its BVH's primitive order):
    /// what the traversal reads, then what a hit reads.
    tris: Vec<FacetRecord<P>>,
    bounds_local: [DVec3; 2],
    /// `bounds_local` grown by a margin for f32 rounding: the box rays are clipped to.
    padded_bounds_local: [DVec3; 2],
    radius_m: f64,
    /// How far past the nearest hit so far a ray's traversal goes on, metres: a few f32
    /// roundings at the scene's size.
    tie_slack: f32,
}

/// The scene's BVH, built by obvhs in chunks: the triangles are split into spatially
/// compact chunks of at most [`CHUNK_TRIANGLES`] ([`partition`]), each chunk gets a CWBVH
/// of its own (obvhs's PLOC, reinsertion and conversion, the chunks in parallel), and when
/// there are several, a top-level CWBVH over the chunks' boxes, one chunk per leaf, which
/// obvhs's traversal descends into (its `traverse!`, nested). A build whole held obvhs's
/// binary BVH and conversion table for every triangle at once (208 bytes each, the frame's
/// peak memory at 1M triangles), and its conversion ran on one thread; chunks hold that only
/// for the chunks being built, and build faster on one thread too, because a chunk's build
/// stays in cache. At 1M triangles rays through the chunks were 16 % faster on a terrain
/// and 13 % slower on a hollow sphere than through one BVH (BENCHMARKS.md, "tracer: the
/// BVH in chunks").
#[derive(Debug)]
struct Bvh {
    /// One CWBVH per chunk; its `primitive_indices` are emptied once the records hold the
    /// facets (a primitive id is the triangle's place in its chunk).
    chunks: Vec<CwBvh>,
    /// Where each chunk's triangles start in the records.
    first: Vec<u32>,
    /// Over the chunks' boxes, a chunk per leaf, when there are several chunks.
    top: Option<CwBvh>,
}

impl Bvh {
    /// Builds the chunks' BVHs, of at most `chunk_max` triangles each, over the triangles
    /// `triangle(i)` (local metres, f32) for `i` below `count`; returns it and the facet of
    /// every record slot, in BVH order.
    fn build(
        count: usize,
        triangle: &(impl Fn(usize) -> [Vec3A; 3] + Sync),
        chunk_max: usize,
    ) -> (Self, Vec<u32>) {
        debug_assert!(count > 0, "the caller has checked that there is a triangle");
        let mut items: Vec<Item> = (0..count)
            .into_par_iter()
            .map(|i| {
                let [a, b, c] = triangle(i);
                Item {
                    lo: a.min(b).min(c).to_array(),
                    hi: a.max(b).max(c).to_array(),
                    facet: i as u32,
                }
            })
            .collect();
        let mut sizes = Vec::new();
        partition(&mut items, chunk_max, &mut sizes);
        let (mut first, mut ranges) = (Vec::with_capacity(sizes.len()), Vec::new());
        let mut at = 0;
        for len in sizes {
            first.push(at as u32);
            ranges.push(at..at + len);
            at += len;
        }
        let mut chunks: Vec<CwBvh> = ranges
            .par_iter()
            .map(|r| chunk(&items[r.clone()]))
            .collect();
        drop(items);
        // The record slots in BVH order: each chunk's primitive order, as facets.
        let mut order = Vec::with_capacity(count);
        for c in &mut chunks {
            order.extend(c.primitive_indices.iter().copied());
            c.primitive_indices = Vec::new();
        }
        let top = (chunks.len() > 1).then(|| {
            let boxes: Vec<Aabb> = chunks.iter().map(|c| c.total_aabb).collect();
            build_cwbvh(
                &boxes,
                BvhBuildParams {
                    max_prims_per_leaf: 1,
                    ..BUILD
                },
                &mut std::time::Duration::default(),
            )
        });
        (Self { chunks, first, top }, order)
    }

    /// Runs `f(ray, slot)` on every record slot whose triangle the ray may hit, nearest
    /// boxes first; `f` returns the triangle's distance (+∞: missed), which shortens the ray
    /// to that distance plus `slack`, so that a triangle at the same distance (a tie) in a
    /// box the ray's rounding puts just beyond it is still tried.
    #[inline(always)]
    fn closest(&self, mut ray: Ray, slack: f32, mut f: impl FnMut(&Ray, usize) -> f32) {
        // One traversal state for every chunk the ray enters (a new one zeroes its stack).
        let mut inner = self.chunks[0].new_traversal(ray.direction);
        let Some(top) = &self.top else {
            self.chunk_closest(0, &mut inner, &mut ray, slack, &mut f);
            return;
        };
        // The chunks the top level finds are visited nearest first, by where the ray
        // enters each chunk's exact box: obvhs orders a node's children by octant, which
        // for chunks' large, overlapping boxes often put a farther chunk first.
        let mut pending = [(0.0_f32, 0_u32); PENDING];
        let mut n = 0;
        let mut state = top.new_traversal(ray.direction);
        let mut node;
        obvhs::traverse!(
            top,
            node,
            state,
            node.intersect_ray(&ray, state.oct_inv4),
            {
                let chunk = top.primitive_indices[state.primitive_id as usize];
                pending[n] = (entry(&self.chunks[chunk as usize].total_aabb, &ray), chunk);
                n += 1;
                if n == PENDING {
                    self.visit(&mut pending[..n], &mut inner, &mut ray, slack, &mut f);
                    n = 0;
                }
            }
        );
        self.visit(&mut pending[..n], &mut inner, &mut ray, slack, &mut f);
    }

    /// Traverses the chunks `pending` (entry distance, chunk) nearest first, while they
    /// start before the ray ends.
    #[inline(always)]
    fn visit(
        &self,
        pending: &mut [(f32, u32)],
        inner: &mut Traversal,
        ray: &mut Ray,
        slack: f32,
        f: &mut impl FnMut(&Ray, usize) -> f32,
    ) {
        pending.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
        for &(entry, chunk) in pending.iter() {
            if entry > ray.tmax {
                break;
            }
            inner.reinit(ray.direction);
            self.chunk_closest(chunk as usize, inner, ray, slack, f);
        }
    }

    #[inline(always)]
    fn chunk_closest(
        &self,
        chunk: usize,
        state: &mut Traversal,
        ray: &mut Ray,
        slack: f32,
        f: &mut impl FnMut(&Ray, usize) -> f32,
    ) {
        let bvh = &self.chunks[chunk];
        let first = self.first[chunk] as usize;
        let mut node;
        obvhs::traverse!(bvh, node, state, node.intersect_ray(ray, state.oct_inv4), {
            let t = f(ray, first + state.primitive_id as usize) + slack;
            if t < ray.tmax {
                ray.tmax = t;
            }
        });
    }

    /// True when `f(ray, slot)` is true for any record slot whose triangle the ray may hit;
    /// stops at the first.
    #[inline(always)]
    fn any(&self, ray: &Ray, mut f: impl FnMut(&Ray, usize) -> bool) -> bool {
        let mut inner = self.chunks[0].new_traversal(ray.direction);
        let Some(top) = &self.top else {
            return self.chunk_any(0, &mut inner, ray, &mut f);
        };
        let mut state = top.new_traversal(ray.direction);
        let mut node;
        let mut found = false;
        'found: {
            obvhs::traverse!(top, node, state, node.intersect_ray(ray, state.oct_inv4), {
                let chunk = top.primitive_indices[state.primitive_id as usize] as usize;
                inner.reinit(ray.direction);
                if self.chunk_any(chunk, &mut inner, ray, &mut f) {
                    found = true;
                    break 'found;
                }
            });
        }
        found
    }

    #[inline(always)]
    fn chunk_any(
        &self,
        chunk: usize,
        state: &mut Traversal,
        ray: &Ray,
        f: &mut impl FnMut(&Ray, usize) -> bool,
    ) -> bool {
        let bvh = &self.chunks[chunk];
        let first = self.first[chunk] as usize;
        let mut node;
        let mut found = false;
        'found: {
            obvhs::traverse!(bvh, node, state, node.intersect_ray(ray, state.oct_inv4), {
                if f(ray, first + state.primitive_id as usize) {
                    found = true;
                    break 'found;
                }
            });
        }
        found
    }
}

/// How many chunks the top level gathers before visiting them nearest first.
const PENDING: usize = 16;

/// Where `ray` enters `aabb`, or 0 where that is not a number (a direction component of 0
/// from an origin on one of the box's planes); never later than the true entry, to within
/// rounding.
#[inline(always)]
fn entry(aabb: &Aabb, ray: &Ray) -> f32 {
    let a = (aabb.min - ray.origin) * ray.inv_direction;
    let b = (aabb.max - ray.origin) * ray.inv_direction;
    let near = a.min(b);
    let t = near.x.max(near.y).max(near.z);
    if t.is_nan() { 0.0 } else { t }
}

/// A triangle as the partition moves it: its f32 box and its facet (28 bytes).
#[derive(Debug, Clone, Copy)]
struct Item {
    lo: [f32; 3],
    hi: [f32; 3],
    facet: u32,
}

impl Item {
    fn aabb(&self) -> Aabb {
        Aabb::new(Vec3A::from_array(self.lo), Vec3A::from_array(self.hi))
    }

    fn centre(&self, axis: usize) -> f32 {
        0.5 * (self.lo[axis] + self.hi[axis])
    }
}

/// Bins of [`partition`]'s surface-area heuristic.
const BINS: usize = 32;

/// Orders `items` into chunks of at most `max` triangles and appends their sizes to
/// `sizes`, in order: a group larger than `max` is split in two at the plane across the
/// longest axis of its centroids that the surface-area heuristic prefers among [`BINS`]
/// bins (the cost of the two halves, each its triangle count times its box's area),
/// recursively, the two halves in parallel. A median split would bind far-apart triangles
/// into one chunk (two ground triangles under an object gave every chunk they fell in the
/// ground's box, and rays through a sphere over it 1.6 times the time); the heuristic
/// gives large triangles chunks of their own. (Binning all three axes gave the same rays
/// on the sphere and the terrain of BENCHMARKS.md and cost 20 % more.) Deterministic:
/// bins are counts and box unions, exact whatever order threads merge them in, so the
/// chunks do not depend on the thread count.
fn partition(items: &mut [Item], max: usize, sizes: &mut Vec<usize>) {
    if items.len() <= max {
        sizes.push(items.len());
        return;
    }
    let bounds = |(lo, hi): ([f32; 3], [f32; 3]), item: &Item| {
        (
            std::array::from_fn(|k| lo[k].min(item.centre(k))),
            std::array::from_fn(|k| hi[k].max(item.centre(k))),
        )
    };
    let none = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
    let (lo, hi): ([f32; 3], [f32; 3]) = items
        .par_chunks(1 << 14)
        .map(|block| block.iter().fold(none, bounds))
        .reduce(
            || none,
            |a, b| {
                (
                    std::array::from_fn(|k| a.0[k].min(b.0[k])),
                    std::array::from_fn(|k| a.1[k].max(b.1[k])),
                )
            },
        );
    let extent: [f32; 3] = std::array::from_fn(|k| hi[k] - lo[k]);
    let axis = if extent[0] >= extent[1] && extent[0] >= extent[2] {
        0
    } else if extent[1] >= extent[2] {
        1
    } else {
        2
    };
    let scale = BINS as f32 / extent[axis];
    // Past the last bin (the largest centroid) lands in the last.
    let bin = |item: &Item| (((item.centre(axis) - lo[axis]) * scale) as usize).min(BINS - 1);
    // Per bin, how many centroids fall in it and their triangles' box.
    let empty = [(0_usize, Aabb::empty()); BINS];
    let bins = items
        .par_chunks(1 << 14)
        .map(|block| {
            let mut bins = empty;
            for item in block {
                let b = &mut bins[bin(item)];
                b.0 += 1;
                b.1 = b.1.union(&item.aabb());
            }
            bins
        })
        .reduce(
            || empty,
            |mut a, b| {
                for (x, y) in a.iter_mut().zip(&b) {
                    x.0 += y.0;
                    x.1 = x.1.union(&y.1);
                }
                a
            },
        );
    // The cheapest plane: (cost, first bin of the right half).
    let mut best = (f32::INFINITY, 0);
    let mut right = [0.0_f32; BINS];
    let mut acc = Aabb::empty();
    for b in (1..BINS).rev() {
        acc = acc.union(&bins[b].1);
        right[b] = acc.half_area();
    }
    let (mut acc, mut left_count) = (Aabb::empty(), 0);
    for b in 1..BINS {
        acc = acc.union(&bins[b - 1].1);
        left_count += bins[b - 1].0;
        let right_count = items.len() - left_count;
        if left_count == 0 || right_count == 0 {
            continue;
        }
        let cost = acc.half_area() * left_count as f32 + right[b] * right_count as f32;
        if cost < best.0 {
            best = (cost, b);
        }
    }
    let mid = if best.0.is_finite() {
        let mut left = 0;
        for k in 0..items.len() {
            if bin(&items[k]) < best.1 {
                items.swap(left, k);
                left += 1;
            }
        }
        left
    } else {
        // Every centroid in one place: any halves will do.
        items.len() / 2
    };
    let (a, b) = items.split_at_mut(mid);
    let mut right_sizes = Vec::new();
    rayon::join(
        || partition(a, max, sizes),
        || partition(b, max, &mut right_sizes),
    );
    sizes.extend(right_sizes);
}

/// One chunk's CWBVH over `items`, its primitive indices their facets.
fn chunk(items: &[Item]) -> CwBvh {
    let boxes: Vec<Aabb> = items.iter().map(Item::aabb).collect();
    // obvhs numbers a build's primitives 0..n (its conversion looks them up by that number).
    let mut bvh2 = PlocBuilder::with_capacity(boxes.len()).build(
        BUILD.ploc_search_distance,
        &boxes,
        (0..boxes.len() as u32).collect(),
        BUILD.sort_precision,
        BUILD.search_depth_threshold,
    );
    drop(boxes);
    ReinsertionOptimizer::default().run(&mut bvh2, BUILD.reinsertion_batch_ratio, None);
    let mut bvh = bvh2_to_cwbvh(&bvh2, BUILD.max_prims_per_leaf.clamp(1, 3), true, false);
    drop(bvh2);
    // obvhs reserves a node per primitive; a chunk uses about a tenth of them.
    bvh.nodes.shrink_to_fit();
    for p in &mut bvh.primitive_indices {
        *p = items[*p as usize].facet;
    }
    bvh
}

/// A triangle as the traversal and a hit read it: first its three f32 local vertices and
/// its input facet index (all a candidate reads: 40 bytes), then its plane in local f64
/// coordinates, unit winding normal `n` and `offset = n·a` for any vertex `a` (a point `p`
/// lies on it when `n·p = offset`), and the caller's data, which only a hit reads. Side by
/// side, so that a hit's plane usually arrives with its vertices: 96 bytes for the tracer's
/// 24-byte data, where a 64-byte line of vertices and another of plane and data were 128.
#[derive(Debug, Clone, Copy)]
#[repr(C)]
struct FacetRecord<P> {
    v: [[f32; 3]; 3],
    facet: u32,
    normal: DVec3,
    offset: f64,
    data: P,
}

/// Per-ray constants of the watertight test: the ray origin, and the paper's shear
/// `(Sx, Sy, −Sz)`. The paper's permutation of the axes (kz the dominant one, kx and ky
/// the others in winding order) is a type parameter of [`Shear::intersect`], so each
/// vertex costs one subtraction, two constant shuffles and one multiply-subtract: a
/// general 3 × 3 matrix product cost three broadcasts, three products and two sums. The
/// sheared coordinates are `A[kx] − Sx·A[kz]`, `A[ky] − Sy·A[kz]` and `Sz·A[kz]`,
/// rounded exactly as in the paper's scalar form.
#[derive(Clone, Copy)]
struct Shear {
    org: Vec3A,
    s: Vec3A,
}

/// The paper's axis permutation of a ray direction: the dominant axis kz, and whether kx
/// and ky are swapped to keep the sheared triangle's winding (`dir[kz] < 0`).
fn axes(dir: Vec3A) -> (usize, bool) {
    let a = dir.abs();
    let kz = if a.x > a.y {
        if a.x > a.z { 0 } else { 2 }
    } else if a.y > a.z {
        1
    } else {
        2
    };
    (kz, dir[kz] < 0.0)
}

impl Shear {
    fn new<const KX: usize, const KY: usize, const KZ: usize>(org: Vec3A, dir: Vec3A) -> Self {
        let sz = 1.0 / dir[KZ];
        Self {
            org,
            s: Vec3A::new(dir[KX] * sz, dir[KY] * sz, -sz),
        }
    }

    /// The ray parameter of the hit, or +∞. Two-sided; an edge or vertex shared by two
    /// triangles is hit by both (never by neither), which is what makes it watertight.
    #[inline(always)]
    fn intersect<const KX: usize, const KY: usize, const KZ: usize>(
        &self,
        v: &[[f32; 3]; 3],
        tmin: f32,
        tmax: f32,
    ) -> f32 {
        let shear = |p: [f32; 3]| {
            let d = Vec3A::from_array(p) - self.org;
            Vec3A::new(d[KX], d[KY], 0.0) - Vec3A::splat(d[KZ]) * self.s
        };
        let (a, b, c) = (shear(v[0]), shear(v[1]), shear(v[2]));
        let mut u = c.x * b.y - c.y * b.x;
        let mut vv = a.x * c.y - a.y * c.x;
        let mut w = b.x * a.y - b.y * a.x;
        if u == 0.0 || vv == 0.0 || w == 0.0 {
            // The paper's fallback: decide edge cases exactly in double precision.
            let (ax, ay, bx, by, cx, cy) = (
                f64::from(a.x),
                f64::from(a.y),
                f64::from(b.x),
                f64::from(b.y),
                f64::from(c.x),
                f64::from(c.y),
            );
            u = (cx * by - cy * bx) as f32;
            vv = (ax * cy - ay * cx) as f32;
            w = (bx * ay - by * ax) as f32;
        }
        if (u < 0.0 || vv < 0.0 || w < 0.0) && (u > 0.0 || vv > 0.0 || w > 0.0) {
            return f32::INFINITY;
        }
        let det = u + vv + w;
        if det == 0.0 {
            return f32::INFINITY;
        }
        let t = (u * a.z + vv * b.z + w * c.z) / det;
        if t > tmin && t <= tmax {
            t
        } else {
            f32::INFINITY
        }
    }
}

/// `$s.$m::<KX, KY, KZ>(args)` for the axis permutation of the ray direction `$dir`.
macro_rules! with_axes {
    ($dir:expr, $s:ident.$m:ident($($arg:expr),*)) => {
        match axes($dir) {
            (0, false) => $s.$m::<1, 2, 0>($($arg),*),
            (0, true) => $s.$m::<2, 1, 0>($($arg),*),
            (1, false) => $s.$m::<2, 0, 1>($($arg),*),
            (1, true) => $s.$m::<0, 2, 1>($($arg),*),
            (2, false) => $s.$m::<0, 1, 2>($($arg),*),
            _ => $s.$m::<1, 0, 2>($($arg),*),
        }
    };
}

impl Geometry {
    /// Builds the BVH over `triangles` (world metres, f64), with no data attached. The
    /// caller has checked that there is at least one triangle, that every number is finite
    /// and that no triangle is degenerate.
    #[must_use]
    pub fn new(triangles: &[[DVec3; 3]]) -> Self {
        Self::with_data(triangles.len(), |i| triangles[i], |_| ())
    }
}

impl<P: Copy + Send + Sync> Geometry<P> {
    /// Builds the BVH over the triangles `triangle(i)` (world metres, f64) for `i` below
    /// `count`, attaching `data(i)` to facet `i` (each [`Hit`] carries a copy). Both are
    /// read through functions rather than slices, so that a caller holding its triangles as
    /// indexed vertices (a raw scene) makes no copy of every facet that would live through
    /// the build. The caller has checked that there is at least one triangle, that every
    /// number is finite and that no triangle is degenerate.
    #[must_use]
    pub fn with_data(
        count: usize,
        triangle: impl Fn(usize) -> [DVec3; 3] + Sync,
        data: impl Fn(usize) -> P + Sync,
    ) -> Self {
        Self::with_chunks(count, triangle, data, CHUNK_TRIANGLES)
    }

    /// [`Self::with_data`] with chunks of at most `chunk_max` triangles (`usize::MAX`: one
    /// BVH over every triangle), for measuring what the chunk size trades.
    #[must_use]
    pub fn with_chunks(
        count: usize,
        triangle: impl Fn(usize) -> [DVec3; 3] + Sync,
        data: impl Fn(usize) -> P + Sync,
        chunk_max: usize,
    ) -> Self {
        // Exact whatever the order of the reduction: the same box at any thread count.
        let (lo, hi) = (0..count)
            .into_par_iter()
            .map(|i| {
                let [a, b, c] = triangle(i);
                let mut lo = a;
                let mut hi = a;
                for p in [b, c] {
                    for k in 0..3 {
                        lo[k] = lo[k].min(p[k]);
                        hi[k] = hi[k].max(p[k]);
                    }
                }
                (lo, hi)
            })
            .reduce(
                || (DVec3::INFINITY, DVec3::NEG_INFINITY),
                |(a_lo, a_hi), (b_lo, b_hi)| {
                    (
                        DVec3::from_array(std::array::from_fn(|k| a_lo[k].min(b_lo[k]))),
                        DVec3::from_array(std::array::from_fn(|k| a_hi[k].max(b_hi[k]))),
                    )
                },
            );
        let centre_m = (lo + hi) * 0.5;
        let to32 = |p: DVec3| [p[0] as f32, p[1] as f32, p[2] as f32];
        let local = |i: usize| triangle(i).map(|p| p - centre_m);
        let (bvh, order) = Bvh::build(
            count,
            &|i| local(i).map(|p| Vec3A::from_array(to32(p))),
            chunk_max,
        );
        let tris = order
            .par_iter()
            .map(|&i| {
                let [a, b, c] = local(i as usize);
                let normal = (b - a).cross(c - a).normalize();
                FacetRecord {
                    v: [to32(a), to32(b), to32(c)],
                    facet: i,
                    normal,
                    offset: normal.dot(a),
                    data: data(i as usize),
                }
            })
            .collect();
        let bounds_local = [lo - centre_m, hi - centre_m];
        let radius_m = 0.5 * (hi - lo).dot(hi - lo).sqrt();
        let pad = DVec3::splat(1e-6 * radius_m + 1e-6);
        Self {
            centre_m,
            bvh,
            tris,
            bounds_local,
            padded_bounds_local: [bounds_local[0] - pad, bounds_local[1] + pad],
            radius_m,
            tie_slack: (1e-6 * radius_m) as f32,
        }
    }

    /// The number of triangles.
    #[must_use]
    pub fn triangles(&self) -> usize {
        self.tris.len()
    }

    /// Calls `f` with every triangle's vertices in world metres (as the BVH holds them,
    /// rounded to f32 about the scene's centre), in no particular order.
    pub fn for_each_triangle(&self, mut f: impl FnMut([DVec3; 3])) {
        for r in &self.tris {
            f(r.v.map(|p| self.to_world(DVec3::from_array(p.map(f64::from)))));
        }
    }

    /// The world point (metres) the local coordinates are measured from.
    #[must_use]
    pub fn centre_m(&self) -> DVec3 {
        self.centre_m
    }

    /// The scene's bounding box in world metres, `[low corner, high corner]`.
    #[must_use]
    pub fn bounds_m(&self) -> [DVec3; 2] {
        self.bounds_local.map(|p| p + self.centre_m)
    }

    /// Half the diagonal of the scene's bounding box, metres.
    #[must_use]
    pub fn radius_m(&self) -> f64 {
        self.radius_m
    }

    /// World coordinates (metres) of a local point.
    #[must_use]
    pub fn to_world(&self, local: DVec3) -> DVec3 {
        local + self.centre_m
    }

    /// Local coordinates of a world point (metres).
    #[must_use]
    pub fn to_local(&self, world: DVec3) -> DVec3 {
        world - self.centre_m
    }

    /// The smallest distance a secondary ray from a surface point accepts, metres: a
    /// little above f32 rounding at the scene's size.
    #[must_use]
    pub fn surface_epsilon_m(&self) -> f64 {
        1e-6 * self.radius_m.max(1.0)
    }

    /// The part `[t0, t1]` of `[t_min, t_max]` along the ray inside the scene's bounds,
    /// padded for f32 rounding; `None` when the ray misses them.
    fn clip(&self, origin: DVec3, dir: DVec3, t_min: f64, t_max: f64) -> Option<(f64, f64)> {
        let (mut t0, mut t1) = (t_min, t_max);
        // Slabs of the padded box (this runs once per ray and showed in the profile, so
        // the padding is done once, in `new`). A zero direction component gives ±∞
        // distances: no constraint when the origin is inside that slab, an empty interval
        // when outside. An origin exactly on a padded plane gives a NaN: the comparisons
        // below (which compile to plain min/max instructions, where `f64::min` needs a NaN
        // check) then leave that bound as it was; nothing lies in the pad to be missed.
        for k in 0..3 {
            let inv = 1.0 / dir[k];
            let a = (self.padded_bounds_local[0][k] - origin[k]) * inv;
            let b = (self.padded_bounds_local[1][k] - origin[k]) * inv;
            let (near, far) = if a < b { (a, b) } else { (b, a) };
            if near > t0 {
                t0 = near;
            }
            if far < t1 {
                t1 = far;
            }
        }
        (t0 <= t1).then_some((t0, t1))
    }

    /// The obvhs ray for `[t0, t1]` of the f64 ray, started [`ORIGIN_BACKOFF_M`] before
    /// `t0`; returns the ray, its shift along the f64 ray, and the f32 admissible range.
    fn prepare(&self, origin: DVec3, dir: DVec3, t0: f64, t1: f64) -> (Ray, f64, f32, f32) {
        let shift = t0 - ORIGIN_BACKOFF_M.max(1e-7 * self.radius_m);
        let o = origin + dir * shift;
        let o32 = Vec3A::new(o[0] as f32, o[1] as f32, o[2] as f32);
        let d32 = Vec3A::new(dir[0] as f32, dir[1] as f32, dir[2] as f32);
        let tmin = (t0 - shift) as f32;
        let tmax = (t1 - shift) as f32;
        (Ray::new(o32, d32, 0.0, tmax), shift, tmin, tmax)
    }

    /// The closest facet along the ray `origin + t·dir` (local metres, `dir` a unit vector)
    /// with `t_min < t < t_max`, skipping facet `exclude` (the facet a secondary ray leaves).
    #[must_use]
    pub fn closest_hit(
        &self,
        origin: DVec3,
        dir: DVec3,
        t_min: f64,
        t_max: f64,
        exclude: Option<u32>,
    ) -> Option<Hit<P>> {
        let (t0, t1) = self.clip(origin, dir, t_min, t_max)?;
        let (ray, shift, tmin, tmax) = self.prepare(origin, dir, t0, t1);
        let exclude = exclude.unwrap_or(u32::MAX);
        let (t, facet, slot) = with_axes!(
            ray.direction,
            self.closest_candidate(ray, tmin, tmax, exclude)
        );
        if !t.is_finite() {
            return None;
        }
        Some(self.refine(slot, facet, origin, dir, f64::from(t) + shift))
    }

    /// The closest candidate of an obvhs ray whose axis permutation is `KX KY KZ`: f32
    /// distance, facet and BVH slot (distance +∞ when none).
    fn closest_candidate<const KX: usize, const KY: usize, const KZ: usize>(
        &self,
        ray: Ray,
        tmin: f32,
        tmax: f32,
        exclude: u32,
    ) -> (f32, u32, usize) {
        let shear = Shear::new::<KX, KY, KZ>(ray.origin, ray.direction);
        // Ties (a ray through an edge shared by two facets, or two facets in one plane) go
        // to the lower facet index, so the answer does not depend on the BVH's layout or
        // traversal order: the traversal goes on a little past the best distance so far
        // (the slack of f32 rounding at the scene's size), so that no box is passed over
        // for its rounding.
        let mut best = (f32::INFINITY, u32::MAX, 0);
        self.bvh.closest(ray, self.tie_slack, |r, id| {
            let tri = &self.tris[id];
            let facet = tri.facet;
            if facet == exclude {
                return f32::INFINITY;
            }
            let t = shear.intersect::<KX, KY, KZ>(&tri.v, tmin, r.tmax.min(tmax));
            if t.total_cmp(&best.0).then(facet.cmp(&best.1)).is_lt() {
                best = (t, facet, id);
            }
            t
        });
        best
    }

    /// How many chunks the BVH was built in.
    #[must_use]
    pub fn chunks(&self) -> usize {
        self.bvh.chunks.len()
    }

    /// True when any facet lies along the ray with `t_min < t < t_max`, skipping
    /// `exclude`. Cheaper than [`Self::closest_hit`]: traversal stops at the first hit.
    #[must_use]
    pub fn occluded(
        &self,
        origin: DVec3,
        dir: DVec3,
        t_min: f64,
        t_max: f64,
        exclude: Option<u32>,
    ) -> bool {
        let Some((t0, t1)) = self.clip(origin, dir, t_min, t_max) else {
            return false;
        };
        let (ray, _, tmin, tmax) = self.prepare(origin, dir, t0, t1);
        let exclude = exclude.unwrap_or(u32::MAX);
        with_axes!(ray.direction, self.any_candidate(ray, tmin, tmax, exclude))
    }

    /// True when an obvhs ray whose axis permutation is `KX KY KZ` hits any candidate.
    fn any_candidate<const KX: usize, const KY: usize, const KZ: usize>(
        &self,
        ray: Ray,
        tmin: f32,
        tmax: f32,
        exclude: u32,
    ) -> bool {
        let shear = Shear::new::<KX, KY, KZ>(ray.origin, ray.direction);
        self.bvh.any(&ray, |_, id| {
            let tri = &self.tris[id];
            tri.facet != exclude && shear.intersect::<KX, KY, KZ>(&tri.v, tmin, tmax) < tmax
        })
    }

    /// The f64 distance, point and facing normal of a hit found in f32.
    fn refine(&self, slot: usize, facet: u32, origin: DVec3, dir: DVec3, t_f32: f64) -> Hit<P> {
        let FacetRecord {
            normal: n,
            offset,
            data,
            ..
        } = self.tris[slot];
        let dn = dir.dot(n);
        // The f64 plane distance, unless the ray runs so close to parallel to the plane
        // that it is worse conditioned than the f32 distance from the watertight test.
        let t_plane = (offset - origin.dot(n)) / dn;
        let distance_m = if dn.abs() > 1e-6 && t_plane.is_finite() {
            t_plane
        } else {
            t_f32
        };
        let back_face = dn > 0.0;
        let normal = if back_face { -n } else { n };
        Hit {
            facet,
            distance_m,
            point_local: origin + dir * distance_m,
            normal,
            cos_incidence: dn.abs().min(1.0),
            back_face,
            data,
        }
    }
}

#[cfg(test)]
mod tests;
