use super::*;
use crate::testing::{Mesh, box_mesh, uv_sphere};

fn tris(mesh: &Mesh) -> Vec<[DVec3; 3]> {
    crate::testing::triangles(mesh)
}

/// The geometry of triangles given as coordinate arrays, m.
fn of_arrays(triangles: &[[[f64; 3]; 3]]) -> Geometry {
    Geometry::new(
        &triangles
            .iter()
            .map(|t| t.map(DVec3::from))
            .collect::<Vec<_>>(),
    )
}

/// Directions spread over the sphere (a Fibonacci lattice).
fn directions(n: usize) -> Vec<DVec3> {
    let golden = std::f64::consts::PI * (3.0 - 5.0_f64.sqrt());
    (0..n)
        .map(|i| {
            let z = 1.0 - 2.0 * (i as f64 + 0.5) / n as f64;
            let r = (1.0 - z * z).sqrt();
            let phi = golden * i as f64;
            DVec3::new(r * phi.cos(), r * phi.sin(), z)
        })
        .collect()
}

#[test]
fn rays_at_shared_edges_and_vertices_of_closed_meshes_never_leak() {
    // A finely tessellated sphere: aim at every vertex and every edge midpoint.
    let sphere = uv_sphere([0.3, -0.2, 1.0], 2.0, 48, 96);
    let geometry = Geometry::new(&tris(&sphere));
    let vertex = |i: u32| DVec3::from(sphere.0[i as usize]);
    let mut targets: Vec<DVec3> = sphere.0.iter().map(|&p| DVec3::from(p)).collect();
    for f in &sphere.1 {
        for k in 0..3 {
            let (a, b) = (vertex(f[k]), vertex(f[(k + 1) % 3]));
            targets.push((a + b) * 0.5);
        }
    }
    // Rays towards an edge from outside can only miss through a crack.
    let dirs = directions(24);
    let centre = geometry.to_local(DVec3::new(0.3, -0.2, 1.0));
    let mut leaks = 0;
    for &p in &targets {
        for &d in &dirs {
            let pl = geometry.to_local(p);
            // Only directions that enter the sphere at this point (from outside).
            let outward = (pl - centre).normalize();
            if outward.dot(d) > -0.05 {
                continue;
            }
            let origin = pl - d * 10.0;
            if geometry
                .closest_hit(origin, d, 0.0, f64::INFINITY, None)
                .is_none()
            {
                leaks += 1;
            }
        }
    }
    assert_eq!(leaks, 0, "rays leaked through the sphere's shared edges");

    // A box: its faces' diagonals and its edges and corners are shared edges.
    let cube = box_mesh([-1.0, -2.0, 0.0], [1.5, 0.5, 3.0]);
    let geometry = Geometry::new(&tris(&cube));
    let mut targets = Vec::new();
    for f in &cube.1 {
        let [a, b, c] = f.map(|i| DVec3::from(cube.0[i as usize]));
        for t in [0.0, 0.25, 0.5, 0.75, 1.0] {
            targets.push(a * (1.0 - t) + b * t);
            targets.push(b * (1.0 - t) + c * t);
            targets.push(c * (1.0 - t) + a * t);
        }
    }
    // Every ray that passes through a target point and on into the solid's interior
    // must hit: a miss is a crack. (A ray that only touches a corner or runs along an
    // edge outside the solid may legitimately miss after rounding.)
    let dirs = directions(64);
    let mut leaks = 0;
    let (lo, hi) = ([-1.0, -2.0, 0.0], [1.5, 0.5, 3.0]);
    for &p in &targets {
        for &d in &dirs {
            let q = p + d * 1e-3;
            if !(0..3).all(|k| q[k] > lo[k] + 1e-9 && q[k] < hi[k] - 1e-9) {
                continue;
            }
            let origin = geometry.to_local(p) - d * 20.0;
            if geometry
                .closest_hit(origin, d, 0.0, f64::INFINITY, None)
                .is_none()
            {
                leaks += 1;
            }
        }
    }
    assert_eq!(leaks, 0, "rays leaked through the box's shared edges");
}

#[test]
fn chunks_find_the_hits_one_bvh_finds() {
    // A sphere over two ground triangles far larger than its facets, and a box: chunks
    // of 16 triangles make hundreds, more than a ray gathers before it visits them.
    let sphere = uv_sphere([0.0, 0.0, 3.0], 2.0, 24, 48);
    let mut t = tris(&sphere);
    t.extend(tris(&box_mesh([3.0, -1.0, 0.0], [4.0, 1.0, 2.5])));
    t.push([
        DVec3::new(-50.0, -50.0, 0.0),
        DVec3::new(50.0, -50.0, 0.0),
        DVec3::new(50.0, 50.0, 0.0),
    ]);
    t.push([
        DVec3::new(-50.0, -50.0, 0.0),
        DVec3::new(50.0, 50.0, 0.0),
        DVec3::new(-50.0, 50.0, 0.0),
    ]);
    let whole = Geometry::with_chunks(t.len(), |i| t[i], |i| i, usize::MAX);
    let chunked = Geometry::with_chunks(t.len(), |i| t[i], |i| i, 16);
    assert_eq!(whole.bvh.chunks.len(), 1);
    assert!(
        chunked.bvh.chunks.len() > 2 * PENDING,
        "{}",
        chunked.bvh.chunks.len()
    );
    assert_eq!(chunked.bvh.first.len(), chunked.bvh.chunks.len());
    let mut hits = 0;
    for origin in [
        [12.0, -9.0, 7.0],
        [0.0, 0.0, 3.0],
        [-6.0, 1.0, 0.5],
        [3.5, 0.0, 1.0],
    ] {
        for d in directions(2000) {
            let o = whole.to_local(DVec3::from(origin));
            let a = whole.closest_hit(o, d, 0.0, f64::INFINITY, None);
            let b = chunked.closest_hit(o, d, 0.0, f64::INFINITY, None);
            assert_eq!(a, b, "from {origin:?} along {d:?}");
            hits += usize::from(a.is_some());
            for t_max in [1.0, 4.0, 30.0] {
                assert_eq!(
                    whole.occluded(o, d, 0.0, t_max, None),
                    chunked.occluded(o, d, 0.0, t_max, None),
                    "from {origin:?} along {d:?} to {t_max}"
                );
            }
        }
    }
    assert!(hits > 4000, "{hits} hits");
}

#[test]
fn distances_points_and_normals_are_right() {
    // The unit square at z = 2 (two triangles), seen from above and below.
    let quad = box_mesh([0.0, 0.0, 2.0], [1.0, 1.0, 2.0 + 1e-3]);
    let geometry = Geometry::new(&tris(&quad));
    let o = geometry.to_local(DVec3::new(0.3, 0.4, 10.0));
    let hit = geometry
        .closest_hit(o, DVec3::new(0.0, 0.0, -1.0), 0.0, f64::INFINITY, None)
        .unwrap();
    assert!((hit.distance_m - (10.0 - 2.001)).abs() < 1e-12);
    assert!((hit.cos_incidence - 1.0).abs() < 1e-12);
    assert!(hit.normal[2] > 0.999);
    let w = geometry.to_world(hit.point_local);
    assert!((w[0] - 0.3).abs() < 1e-12 && (w[2] - 2.001).abs() < 1e-12);
    // t_max before the surface: no hit; occlusion agrees.
    assert!(
        geometry
            .closest_hit(o, DVec3::new(0.0, 0.0, -1.0), 0.0, 7.0, None)
            .is_none()
    );
    assert!(!geometry.occluded(o, DVec3::new(0.0, 0.0, -1.0), 0.0, 7.0, None));
    assert!(geometry.occluded(o, DVec3::new(0.0, 0.0, -1.0), 0.0, 8.5, None));
    // Missing the bounds entirely.
    assert!(!geometry.occluded(o, DVec3::new(0.0, 0.0, 1.0), 0.0, f64::INFINITY, None));
}

#[test]
fn back_faces_are_hit_and_reported() {
    // One triangle facing +z, seen from below.
    let geometry = of_arrays(&[[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]]);
    let o = geometry.to_local(DVec3::new(0.2, 0.2, -5.0));
    let hit = geometry
        .closest_hit(o, DVec3::new(0.0, 0.0, 1.0), 0.0, f64::INFINITY, None)
        .unwrap();
    assert!(hit.back_face);
    assert!(hit.normal[2] < -0.999, "normal faces the ray");
    let o = geometry.to_local(DVec3::new(0.2, 0.2, 5.0));
    let hit = geometry
        .closest_hit(o, DVec3::new(0.0, 0.0, -1.0), 0.0, f64::INFINITY, None)
        .unwrap();
    assert!(!hit.back_face);
}

#[test]
fn grazing_rays_at_89_9_degrees_hit_with_the_right_angle() {
    // A 10 m x 10 m plate; rays 89.9° from its normal.
    let plate = [
        [[0.0, 0.0, 0.0], [10.0, 0.0, 0.0], [10.0, 10.0, 0.0]],
        [[0.0, 0.0, 0.0], [10.0, 10.0, 0.0], [0.0, 10.0, 0.0]],
    ];
    let geometry = of_arrays(&plate);
    let theta = 89.9_f64.to_radians();
    let d = DVec3::new(theta.sin(), 0.0, -theta.cos());
    // Aim at (5, 5, 0) from 100 m back along the ray.
    let target = DVec3::new(5.0, 5.0, 0.0);
    let o = geometry.to_local(target - d * 100.0);
    let hit = geometry
        .closest_hit(o, d, 0.0, f64::INFINITY, None)
        .unwrap();
    let angle = hit.cos_incidence.acos().to_degrees();
    assert!((angle - 89.9).abs() < 1e-9, "{angle}");
    let w = geometry.to_world(hit.point_local);
    assert!((w[0] - 5.0).abs() < 1e-9 && w[2].abs() < 1e-12, "{w:?}");
    assert!((hit.distance_m - 100.0).abs() < 1e-9);
}

#[test]
fn a_sensor_12_km_away_resolves_centimetre_detail() {
    // Two 1 cm squares 1 cm apart at the far end of a 12 km line of sight.
    let mut t = Vec::new();
    for (x0, z) in [(0.0, 0.0), (0.02, 0.001)] {
        let q = box_mesh([x0, 0.0, z], [x0 + 0.01, 0.01, z + 1e-4]);
        t.extend(tris(&q));
    }
    let geometry = Geometry::new(&t);
    let sensor = DVec3::new(5000.0, -6000.0, 9000.0);
    for (x, expect_hit) in [
        (0.005, true),
        (0.015, false),
        (0.025, true),
        (0.0095, true),
        (0.0105, false),
    ] {
        let target = DVec3::new(x, 0.005, 0.0);
        let d = (target - sensor).normalize();
        let o = geometry.to_local(sensor);
        let hit = geometry.closest_hit(o, d, 0.0, f64::INFINITY, None);
        assert_eq!(hit.is_some(), expect_hit, "x = {x}");
        if let Some(h) = hit {
            let w = geometry.to_world(h.point_local);
            // The hit point lies on the square's top face within 1e-6 m... [x, y]
            // within a micrometre of where the ray crosses that face.
            assert!((w[1] - 0.005).abs() < 1e-3, "{w:?}");
        }
    }
}

#[test]
fn facets_far_smaller_and_far_larger_than_the_scene_scale_are_hit() {
    // A 50 km ground triangle and a 1 mm triangle above it.
    let t = vec![
        [
            [-25_000.0, -25_000.0, 0.0],
            [25_000.0, -25_000.0, 0.0],
            [0.0, 25_000.0, 0.0],
        ],
        [[0.0, 0.0, 1.0], [0.001, 0.0, 1.0], [0.0, 0.001, 1.0]],
    ];
    let geometry = of_arrays(&t);
    let down = DVec3::NEG_Z;
    let hit = geometry
        .closest_hit(
            geometry.to_local(DVec3::new(0.0002, 0.0002, 100.0)),
            down,
            0.0,
            f64::INFINITY,
            None,
        )
        .unwrap();
    assert_eq!(hit.facet, 1);
    let hit = geometry
        .closest_hit(
            geometry.to_local(DVec3::new(0.002, 0.002, 100.0)),
            down,
            0.0,
            f64::INFINITY,
            None,
        )
        .unwrap();
    assert_eq!(hit.facet, 0);
    assert!((hit.distance_m - 100.0).abs() < 1e-9);
}

#[test]
fn secondary_rays_skip_their_own_facet_and_see_near_neighbours() {
    // Floor and a wall 0.5 mm away across a corner: a ray from the floor towards the
    // wall must hit it although it is far closer than obvhs's 1e-4 clamp... 0.5 mm is
    // 5e-4 m; also test 5e-5 m.
    for gap in [5e-4, 5e-5] {
        let t = vec![
            [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
            [[gap, -1.0, -1.0], [gap, 1.0, -1.0], [gap, 0.0, 1.0]],
        ];
        let geometry = of_arrays(&t);
        let p = geometry.to_local(DVec3::new(0.0, 0.2, 0.0));
        let d = DVec3::new(1.0, 0.0, 0.0001).normalize();
        let hit = geometry.closest_hit(p, d, geometry.surface_epsilon_m(), f64::INFINITY, Some(0));
        let hit = hit.unwrap_or_else(|| panic!("gap {gap}: missed"));
        assert_eq!(hit.facet, 1);
        assert!((hit.distance_m - gap).abs() < 1e-9);
    }
}
