//! Closest hits of a packet of rays from one point (a frame's primary rays), traversed
//! together through obvhs's nodes: a node's child boxes are decoded once for the packet
//! and tested against each ray still alive in it, eight lanes at a time, and where few
//! rays are left each goes on alone from that node, through obvhs's own `traverse!`. Every
//! ray gets the hit [`Geometry::closest_hit`] gives it, bit for bit: the same f64 clip and
//! start, the same watertight test and ties, the same refinement; only the order in which
//! boxes are opened differs, and no box that could hold the closest hit or a tie with it is
//! passed over (BENCHMARKS.md, "traversal against Embree", measures what it saves).

use glam::{UVec2, Vec3A};
use obvhs::cwbvh::CwBvh;
use obvhs::ray::Ray;

use super::{Geometry, Hit, Shear, axes};
use crate::vec::V3;

/// Rays per packet: 64 consecutive pixels of a row traverse as well as an 8 × 8 tile.
pub const PACKET: usize = 64;

/// Live rays at or below which a packet's rays go on alone from a node: on the
/// 1M-triangle sphere, 4 gave 122-131 ns a ray, 8 118-122, 16 114-121 and 32 115-124
/// (bare obvhs, the traversal example).
const ALONE: u32 = 16;

/// A packet's rays, lane by lane: as the node test reads them, f32 origin (each ray starts
/// just before the scene's box, so origins differ), reciprocal direction and how far each
/// may still go (its best hit so far plus the tie slack, or its end); and the rest of each
/// ray (`None`: no ray in that lane, or one that misses the scene's box).
struct Lanes {
    origin: [[f32; PACKET]; 3],
    inv: [[f32; PACKET]; 3],
    t_max: [f32; PACKET],
    lane: [Option<Lane>; PACKET],
}

impl Lanes {
    /// Which lanes of `mask` enter the box `[lo, hi]` before they end, and the nearest
    /// entry among them. The entry is clamped to obvhs's 1e-4, as its node test clamps it.
    #[inline(always)]
    fn enter(&self, lo: Vec3A, hi: Vec3A, mask: u64) -> (u64, f32) {
        let (mut enter, mut nearest) = (0_u64, f32::INFINITY);
        for group in 0..PACKET / 8 {
            let live = (mask >> (group * 8)) & 0xff;
            if live == 0 {
                continue;
            }
            let lanes = group * 8..group * 8 + 8;
            let eight =
                |a: &[f32; PACKET]| -> [f32; 8] { a[lanes.clone()].try_into().unwrap_or([0.0; 8]) };
            let (ox, oy, oz) = (
                eight(&self.origin[0]),
                eight(&self.origin[1]),
                eight(&self.origin[2]),
            );
            let (ix, iy, iz) = (
                eight(&self.inv[0]),
                eight(&self.inv[1]),
                eight(&self.inv[2]),
            );
            let t_max = eight(&self.t_max);
            let mut entry = [0.0_f32; 8];
            let mut hit = [false; 8];
            for j in 0..8 {
                let (ax, bx) = ((lo.x - ox[j]) * ix[j], (hi.x - ox[j]) * ix[j]);
                let (ay, by) = ((lo.y - oy[j]) * iy[j], (hi.y - oy[j]) * iy[j]);
                let (az, bz) = ((lo.z - oz[j]) * iz[j], (hi.z - oz[j]) * iz[j]);
                let t0 = ax.min(bx).max(ay.min(by)).max(az.min(bz)).max(1e-4);
                let t1 = ax.max(bx).min(ay.max(by)).min(az.max(bz)).min(t_max[j]);
                entry[j] = t0;
                hit[j] = t0 <= t1;
            }
            for j in 0..8 {
                if hit[j] && live >> j & 1 == 1 {
                    enter |= 1 << (group * 8 + j);
                    nearest = nearest.min(entry[j]);
                }
            }
        }
        (enter, nearest)
    }
}

/// Where a packet's traversal goes next: an inner node, or a leaf's triangles, with the
/// lanes that enter it.
#[derive(Clone, Copy)]
enum Next {
    Node(u32),
    Leaf { first: u32, count: u32 },
}

/// Traverses `bvh` from node 0 with the lanes of `mask`, nearest boxes first: `leaf(lanes,
/// triangle, lanes entering)` for each leaf triangle, `alone(lanes, node, lane)` for each
/// lane once at most `threshold` are alive (0: never).
fn traverse(
    bvh: &CwBvh,
    lanes: &mut Lanes,
    mask: u64,
    threshold: u32,
    stack: &mut Vec<(Next, u64)>,
    leaf: &mut impl FnMut(&mut Lanes, u32, u64),
    alone: &mut impl FnMut(&mut Lanes, u32, usize),
) {
    stack.clear();
    stack.push((Next::Node(0), mask));
    while let Some((next, mask)) = stack.pop() {
        match next {
            Next::Leaf { first, count } => {
                for triangle in first..first + count {
                    leaf(lanes, triangle, mask);
                }
            }
            Next::Node(index) if mask.count_ones() <= threshold => {
                let mut m = mask;
                while m != 0 {
                    let k = m.trailing_zeros() as usize;
                    m &= m - 1;
                    alone(lanes, index, k);
                }
            }
            Next::Node(index) => {
                let node = &bvh.nodes[index as usize];
                let (extent, base) = (node.compute_extent(), Vec3A::from(node.p));
                let mut children = [(0.0_f32, Next::Node(0), 0_u64); 8];
                let mut n = 0;
                for child in (0..8).filter(|&c| !node.is_child_empty(c)) {
                    let lo = Vec3A::new(
                        f32::from(node.child_min_x[child]),
                        f32::from(node.child_min_y[child]),
                        f32::from(node.child_min_z[child]),
                    ) * extent
                        + base;
                    let hi = Vec3A::new(
                        f32::from(node.child_max_x[child]),
                        f32::from(node.child_max_y[child]),
                        f32::from(node.child_max_z[child]),
                    ) * extent
                        + base;
                    let (enter, nearest) = lanes.enter(lo, hi, mask);
                    if enter == 0 {
                        continue;
                    }
                    let next = if node.is_leaf(child) {
                        let (first, count) = node.child_primitives(child);
                        Next::Leaf { first, count }
                    } else {
                        Next::Node(node.child_node_index(child))
                    };
                    children[n] = (nearest, next, enter);
                    n += 1;
                }
                // Farthest first onto the stack, so that the nearest is opened first.
                let children = &mut children[..n];
                children.sort_unstable_by(|a, b| b.0.total_cmp(&a.0));
                stack.extend(children.iter().map(|&(_, next, enter)| (next, enter)));
            }
        }
    }
}

/// One lane of a packet: its obvhs ray and shear, its shift along the f64 ray, its f32
/// admissible range, and its best candidate (f32 distance, facet, record slot).
#[derive(Clone, Copy)]
struct Lane {
    ray: Ray,
    shear: Shear,
    shift: f64,
    t_min: f32,
    best: (f32, u32, usize),
}

impl<P: Copy + Send + Sync> Geometry<P> {
    /// The closest facet along each ray `origin + t·dirs[k]` (local metres, unit
    /// directions) with `0 < t`, into `hits[k]`: for every ray what
    /// [`Self::closest_hit`]`(origin, dirs[k], 0.0, f64::INFINITY, None)` gives, found for
    /// up to [`PACKET`] rays at a time.
    ///
    /// # Panics
    /// If `hits` and `dirs` differ in length.
    pub fn closest_hits(&self, origin: V3, dirs: &[V3], hits: &mut [Option<Hit<P>>]) {
        assert_eq!(dirs.len(), hits.len(), "a hit for every direction");
        let mut stack = Vec::with_capacity(4 * PACKET);
        for (dirs, hits) in dirs.chunks(PACKET).zip(hits.chunks_mut(PACKET)) {
            self.packet(origin, dirs, hits, &mut stack);
        }
    }

    /// [`Self::closest_hits`] of at most [`PACKET`] rays.
    fn packet(
        &self,
        origin: V3,
        dirs: &[V3],
        hits: &mut [Option<Hit<P>>],
        stack: &mut Vec<(Next, u64)>,
    ) {
        let mut lanes = Lanes {
            origin: [[0.0; PACKET]; 3],
            inv: [[0.0; PACKET]; 3],
            t_max: [f32::NEG_INFINITY; PACKET],
            lane: [None; PACKET],
        };
        let mut mask = 0_u64;
        let mut class = None;
        let mut mixed = false;
        for (k, &dir) in dirs.iter().enumerate() {
            hits[k] = None;
            let Some((t0, t1)) = self.clip(origin, dir, 0.0, f64::INFINITY) else {
                continue;
            };
            let (ray, shift, t_min, t_max) = self.prepare(origin, dir, t0, t1);
            let axes = axes(ray.direction);
            mixed |= class.is_some_and(|c| c != axes);
            class = Some(axes);
            for axis in 0..3 {
                lanes.origin[axis][k] = ray.origin[axis];
                lanes.inv[axis][k] = ray.inv_direction[axis];
            }
            lanes.t_max[k] = t_max;
            lanes.lane[k] = Some(Lane {
                ray,
                // Made for the packet's axis permutation in `packet_candidates`.
                shear: Shear {
                    org: ray.origin,
                    s: Vec3A::ZERO,
                },
                shift,
                t_min,
                best: (f32::INFINITY, u32::MAX, 0),
            });
            mask |= 1 << k;
        }
        if mask == 0 {
            return;
        }
        if mixed {
            // Rays of different dominant axes (a packet across a line of the image where
            // the dominant axis changes): each alone, as ever.
            for (k, &dir) in dirs.iter().enumerate() {
                hits[k] = self.closest_hit(origin, dir, 0.0, f64::INFINITY, None);
            }
            return;
        }
        let Some(first) = lanes.lane.iter().flatten().next().map(|l| l.ray.direction) else {
            return;
        };
        with_axes!(first, self.packet_candidates(&mut lanes, mask, stack));
        for (k, l) in lanes.lane.iter().enumerate() {
            if let Some(l) = l
                && l.best.0.is_finite()
            {
                hits[k] = Some(self.refine(
                    l.best.2,
                    l.best.1,
                    origin,
                    dirs[k],
                    f64::from(l.best.0) + l.shift,
                ));
            }
        }
    }

    /// Every lane's best candidate, the packet's rays all of axis permutation `KX KY KZ`.
    fn packet_candidates<const KX: usize, const KY: usize, const KZ: usize>(
        &self,
        lanes: &mut Lanes,
        mask: u64,
        stack: &mut Vec<(Next, u64)>,
    ) {
        for l in lanes.lane.iter_mut().flatten() {
            l.shear = Shear::new::<KX, KY, KZ>(l.ray.origin, l.ray.direction);
        }
        let Some(top) = &self.bvh.top else {
            self.chunk_packet::<KX, KY, KZ>(0, lanes, mask, stack);
            return;
        };
        // The chunks the packet meets, nearest entry first.
        let mut met: Vec<(f32, u64, u32)> = Vec::new();
        traverse(
            top,
            lanes,
            mask,
            0,
            stack,
            &mut |lanes, triangle, enter| {
                let chunk = top.primitive_indices[triangle as usize];
                let aabb = &self.bvh.chunks[chunk as usize].total_aabb;
                let (enter, nearest) = lanes.enter(aabb.min, aabb.max, enter);
                if enter != 0 {
                    met.push((nearest, enter, chunk));
                }
            },
            &mut |_, _, _| {},
        );
        met.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.2.cmp(&b.2)));
        for (_, enter, chunk) in met {
            self.chunk_packet::<KX, KY, KZ>(chunk as usize, lanes, enter, stack);
        }
    }

    /// The lanes of `mask` through chunk `chunk`.
    fn chunk_packet<const KX: usize, const KY: usize, const KZ: usize>(
        &self,
        chunk: usize,
        lanes: &mut Lanes,
        mask: u64,
        stack: &mut Vec<(Next, u64)>,
    ) {
        let bvh = &self.bvh.chunks[chunk];
        let first = self.bvh.first[chunk] as usize;
        traverse(
            bvh,
            lanes,
            mask,
            ALONE,
            stack,
            &mut |lanes, triangle, enter| {
                let mut m = enter;
                while m != 0 {
                    let k = m.trailing_zeros() as usize;
                    m &= m - 1;
                    self.try_slot::<KX, KY, KZ>(lanes, k, first + triangle as usize);
                }
            },
            &mut |lanes, node, k| {
                let Some(l) = lanes.lane[k] else {
                    return;
                };
                // obvhs's own traversal from `node` on: a group of one child, the node.
                let mut ray = l.ray;
                ray.tmax = lanes.t_max[k];
                let mut state = bvh.new_traversal(ray.direction);
                state.current_group = UVec2::new(node, 0x8000_0000);
                let mut n;
                obvhs::traverse!(bvh, n, state, n.intersect_ray(&ray, state.oct_inv4), {
                    self.try_slot::<KX, KY, KZ>(lanes, k, first + state.primitive_id as usize);
                    ray.tmax = lanes.t_max[k];
                });
            },
        );
    }

    /// Lane `k`'s test of the triangle in record slot `slot`: the single ray's test and tie
    /// rule ([`Geometry::closest_candidate`]), and the lane shortened as the single ray is.
    #[inline(always)]
    fn try_slot<const KX: usize, const KY: usize, const KZ: usize>(
        &self,
        lanes: &mut Lanes,
        k: usize,
        slot: usize,
    ) {
        let Some(l) = lanes.lane[k].as_mut() else {
            return;
        };
        let tri = &self.tris[slot];
        let t = l
            .shear
            .intersect::<KX, KY, KZ>(&tri.v, l.t_min, lanes.t_max[k]);
        if t.total_cmp(&l.best.0)
            .then(tri.facet.cmp(&l.best.1))
            .is_lt()
        {
            l.best = (t, tri.facet, slot);
        }
        let t = t + self.tie_slack;
        if t < lanes.t_max[k] {
            lanes.t_max[k] = t;
        }
    }
}
