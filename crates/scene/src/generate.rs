//! Closed triangle meshes with outward winding, for tests and benchmarks.

use irsig_model::{Facet, MaterialId, Object};

fn facet(vertices: [u32; 3], material: MaterialId) -> Facet {
    Facet {
        vertices,
        material,
        temperature_k: None,
        uv: None,
    }
}

/// A UV sphere of radius `radius_m` about the origin: `longitudes` (≥ 3) segments around
/// z and `latitudes` (≥ 2) bands from pole to pole, `2·longitudes·(latitudes − 1)`
/// triangles (fans at the poles, quads split in two between). Closed, every triangle
/// counter-clockwise seen from outside. Values below the minimum are raised to it.
#[must_use]
pub fn uv_sphere(radius_m: f64, longitudes: u32, latitudes: u32, material: MaterialId) -> Object {
    let n_lon = longitudes.max(3);
    let n_lat = latitudes.max(2);
    let mut positions_m = vec![[0.0, 0.0, radius_m]];
    for i in 1..n_lat {
        let theta = std::f64::consts::PI * f64::from(i) / f64::from(n_lat);
        for j in 0..n_lon {
            let phi = std::f64::consts::TAU * f64::from(j) / f64::from(n_lon);
            positions_m.push([
                radius_m * theta.sin() * phi.cos(),
                radius_m * theta.sin() * phi.sin(),
                radius_m * theta.cos(),
            ]);
        }
    }
    let south = u32::try_from(positions_m.len()).unwrap_or(u32::MAX);
    positions_m.push([0.0, 0.0, -radius_m]);
    // Ring r (0-based, from the north) vertex j.
    let at = |r: u32, j: u32| 1 + r * n_lon + j % n_lon;
    let mut facets = Vec::with_capacity(2 * (n_lon * (n_lat - 1)) as usize);
    for j in 0..n_lon {
        facets.push(facet([0, at(0, j), at(0, j + 1)], material));
    }
    for r in 0..n_lat - 2 {
        for j in 0..n_lon {
            let (a, b) = (at(r, j), at(r, j + 1));
            let (c, d) = (at(r + 1, j), at(r + 1, j + 1));
            facets.push(facet([a, c, d], material));
            facets.push(facet([a, d, b], material));
        }
    }
    for j in 0..n_lon {
        facets.push(facet(
            [south, at(n_lat - 2, j + 1), at(n_lat - 2, j)],
            material,
        ));
    }
    Object {
        name: "uv-sphere".into(),
        source: format!("irsig_scene::uv_sphere({radius_m}, {n_lon}, {n_lat})"),
        positions_m,
        facets,
    }
}

/// A height-field terrain block: the top surface `z = height(x, y)` over
/// `[0, size_m[0]] × [0, size_m[1]]` on a grid of `cells[0] × cells[1]` squares (each two
/// triangles), closed by four vertical walls down to `base_z_m` and a bottom fanned from
/// its centre. `2·nx·ny + 6·(nx + ny)` triangles, outward winding. `height` must stay
/// above `base_z_m`. Cell counts below 1 are raised to 1.
#[must_use]
pub fn terrain(
    size_m: [f64; 2],
    cells: [u32; 2],
    base_z_m: f64,
    height: impl Fn(f64, f64) -> f64,
    material: MaterialId,
) -> Object {
    let [nx, ny] = cells.map(|c| c.max(1));
    let x = |i: u32| size_m[0] * f64::from(i) / f64::from(nx);
    let y = |j: u32| size_m[1] * f64::from(j) / f64::from(ny);
    let mut positions_m = Vec::new();
    for j in 0..=ny {
        for i in 0..=nx {
            positions_m.push([x(i), y(j), height(x(i), y(j))]);
        }
    }
    let top = |i: u32, j: u32| j * (nx + 1) + i;
    let mut facets = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            let (a, b, c, d) = (top(i, j), top(i + 1, j), top(i + 1, j + 1), top(i, j + 1));
            facets.push(facet([a, b, c], material));
            facets.push(facet([a, c, d], material));
        }
    }
    // The boundary of the top, counter-clockwise seen from above.
    let mut ring: Vec<u32> = Vec::new();
    ring.extend((0..nx).map(|i| top(i, 0)));
    ring.extend((0..ny).map(|j| top(nx, j)));
    ring.extend((1..=nx).rev().map(|i| top(i, ny)));
    ring.extend((1..=ny).rev().map(|j| top(0, j)));
    let first_base = u32::try_from(positions_m.len()).unwrap_or(u32::MAX);
    for &t in &ring {
        let p = positions_m[t as usize];
        positions_m.push([p[0], p[1], base_z_m]);
    }
    let n = u32::try_from(ring.len()).unwrap_or(u32::MAX);
    for k in 0..n {
        let (t0, t1) = (ring[k as usize], ring[((k + 1) % n) as usize]);
        let (b0, b1) = (first_base + k, first_base + (k + 1) % n);
        // Walls face outward: going counter-clockwise around, outward is to the right.
        facets.push(facet([b0, b1, t1], material));
        facets.push(facet([b0, t1, t0], material));
    }
    let centre = u32::try_from(positions_m.len()).unwrap_or(u32::MAX);
    positions_m.push([size_m[0] / 2.0, size_m[1] / 2.0, base_z_m]);
    for k in 0..n {
        // The bottom faces down: clockwise seen from above.
        facets.push(facet(
            [centre, first_base + (k + 1) % n, first_base + k],
            material,
        ));
    }
    Object {
        name: "terrain".into(),
        source: format!("irsig_scene::terrain({size_m:?}, [{nx}, {ny}])"),
        positions_m,
        facets,
    }
}
