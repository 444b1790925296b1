//! What building the BVH in chunks trades, for one scene and one chunk size a run (so that
//! GNU time's peak resident memory is the build's): the time to build the tracer's geometry
//! (`Geometry::with_chunks`: re-centring, the chunks' obvhs builds, the top level, the
//! 96-byte records), on rayon's threads, and the primary rays through it on one thread
//! (f64 clip, watertight test, f64 refinement), each the fastest of ROUNDS.
//!
//! `cargo run --release -p irsig-tracer --example bvh_chunks SCENE CHUNK [ROUNDS]`
//!
//! SCENE is `sphere` (the shade profile's 1M-triangle sphere over a ground quad, seen by
//! its 1024² camera) or `terrain` (the ThRend side-by-side's 999,698-triangle terrain and
//! box, its 1024² camera); CHUNK the most triangles a chunk holds, or `whole` for one BVH.
//! `scripts/bench/bvh-chunks.sh` runs every pair.

use std::time::Instant;

use irsig_tracer::geometry::Geometry;
use irsig_tracer::testing::{
    bench_camera, bench_scene, bench_terrain, bench_terrain_camera, geometry_pass,
    primary_directions,
};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let (Some(scene), Some(chunk)) = (args.get(1), args.get(2)) else {
        eprintln!("usage: bvh_chunks sphere|terrain CHUNK|whole [ROUNDS]");
        std::process::exit(2);
    };
    let chunk_max = if chunk == "whole" {
        usize::MAX
    } else {
        chunk
            .parse()
            .expect("CHUNK: a number of triangles or `whole`")
    };
    let rounds: u32 = args.get(3).and_then(|a| a.parse().ok()).unwrap_or(3);
    let (mesh, camera) = match scene.as_str() {
        "sphere" => (bench_scene(2), bench_camera(1024)),
        "terrain" => (bench_terrain(), bench_terrain_camera(1024)),
        _ => panic!("SCENE: sphere or terrain"),
    };
    let triangle = |i: usize| mesh.1[i].map(|v| glam::DVec3::from(mesh.0[v as usize]));
    let directions = primary_directions(&camera);
    let (mut build, mut ray, mut hits, mut chunks) = (f64::INFINITY, f64::INFINITY, 0, 0);
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("a thread pool");
    for _ in 0..rounds {
        let t = Instant::now();
        let geometry = Geometry::with_chunks(mesh.1.len(), triangle, |_| (), chunk_max);
        build = build.min(t.elapsed().as_secs_f64());
        chunks = geometry.chunks();
        one.install(|| {
            let _ = geometry_pass(&geometry, camera.position_m, &directions);
            let t = Instant::now();
            hits = geometry_pass(&geometry, camera.position_m, &directions);
            ray = ray.min(t.elapsed().as_secs_f64() * 1e9 / directions.len() as f64);
        });
    }
    println!(
        "{scene} {chunk}: {} triangles, {chunks} chunks, build {build:.3} s on {} threads, \
         rays {ray:.0} ns, {hits} hits",
        mesh.1.len(),
        rayon::current_num_threads()
    );
}
