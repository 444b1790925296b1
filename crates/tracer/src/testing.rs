//! Closed test meshes for the tracer's tests and benchmarks (vertex list plus
//! counter-clockwise-outward triangles, metres). The project's scene generators live in
//! `irsig-scene`; these exist so the tracer can be tested on its own.

use crate::vec::V3;

/// A closed mesh: vertex positions and triangles as vertex indices.
pub type Mesh = (Vec<V3>, Vec<[u32; 3]>);

/// A closed UV sphere with `2 · segments · (rings − 1)` triangles, poles as single
/// vertices, wound counter-clockwise seen from outside. `rings ≥ 2`, `segments ≥ 3`.
#[must_use]
pub fn uv_sphere(centre: V3, radius: f64, rings: u32, segments: u32) -> Mesh {
    let rings = rings.max(2);
    let segments = segments.max(3);
    let mut v = vec![[centre[0], centre[1], centre[2] + radius]];
    for i in 1..rings {
        let theta = std::f64::consts::PI * f64::from(i) / f64::from(rings);
        for j in 0..segments {
            let phi = std::f64::consts::TAU * f64::from(j) / f64::from(segments);
            v.push([
                centre[0] + radius * theta.sin() * phi.cos(),
                centre[1] + radius * theta.sin() * phi.sin(),
                centre[2] + radius * theta.cos(),
            ]);
        }
    }
    v.push([centre[0], centre[1], centre[2] - radius]);
    let south = (v.len() - 1) as u32;
    let ring = |i: u32, j: u32| 1 + (i - 1) * segments + (j % segments);
    let mut f = Vec::new();
    for j in 0..segments {
        f.push([0, ring(1, j), ring(1, j + 1)]);
    }
    for i in 1..rings - 1 {
        for j in 0..segments {
            let (a, b, c, d) = (
                ring(i, j),
                ring(i, j + 1),
                ring(i + 1, j),
                ring(i + 1, j + 1),
            );
            f.push([a, c, d]);
            f.push([a, d, b]);
        }
    }
    for j in 0..segments {
        f.push([south, ring(rings - 1, j + 1), ring(rings - 1, j)]);
    }
    (v, f)
}

/// An axis-aligned box from `lo` to `hi` as 12 triangles, normals outward.
#[must_use]
pub fn box_mesh(lo: V3, hi: V3) -> Mesh {
    let p = |i: u32| {
        [
            if i & 1 == 0 { lo[0] } else { hi[0] },
            if i & 2 == 0 { lo[1] } else { hi[1] },
            if i & 4 == 0 { lo[2] } else { hi[2] },
        ]
    };
    let v = (0..8).map(p).collect();
    // Each face as a quad counter-clockwise from outside.
    let quads = [
        [0, 2, 3, 1], // z = lo
        [4, 5, 7, 6], // z = hi
        [0, 1, 5, 4], // y = lo
        [2, 6, 7, 3], // y = hi
        [0, 4, 6, 2], // x = lo
        [1, 3, 7, 5], // x = hi
    ];
    let f = quads
        .iter()
        .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
        .collect();
    (v, f)
}

/// A flat rectangle in the plane z = `z` from `lo` to `hi` (x, y), facing +z, as two
/// triangles.
#[must_use]
pub fn ground_quad(lo: [f64; 2], hi: [f64; 2], z: f64) -> Mesh {
    (
        vec![
            [lo[0], lo[1], z],
            [hi[0], lo[1], z],
            [hi[0], hi[1], z],
            [lo[0], hi[1], z],
        ],
        vec![[0, 1, 2], [0, 2, 3]],
    )
}

/// The triangles of a mesh as vertex triples.
#[must_use]
pub fn triangles(mesh: &Mesh) -> Vec<[V3; 3]> {
    mesh.1
        .iter()
        .map(|f| f.map(|i| mesh.0[i as usize]))
        .collect()
}
