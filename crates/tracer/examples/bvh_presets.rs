//! What obvhs's build presets trade: build time against traversal, on the shade profile's
//! scene (a UV sphere over a ground quad; SIZE 0/1/2 = 1k/100k/1M triangles) seen by its
//! 128 × 128 camera.
//!
//! `cargo run --release -p irsig-tracer --example bvh_presets [SIZE] [ROUNDS]`
//!
//! For each preset in turn, ROUNDS times (interleaved, so that a busy machine slows every
//! preset alike): the build on rayon's threads (obvhs's own parallel build, as the tracer
//! calls it), then the primary rays through the BVH on one thread, timed on a second, warm
//! pass. Prints the fastest build and the fastest pass per preset: interference only adds
//! time, so the fastest is the stable figure.

use std::time::Instant;

use irsig_tracer::testing::{BareObvhs, bench_camera, bench_scene};
use obvhs::BvhBuildParams;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let size: usize = args.get(1).and_then(|a| a.parse().ok()).unwrap_or(2);
    let rounds: u32 = args.get(2).and_then(|a| a.parse().ok()).unwrap_or(3);
    let mesh = bench_scene(size);
    let camera = bench_camera(128);
    let presets: [(&str, BvhBuildParams); 5] = [
        ("fastest_build", BvhBuildParams::fastest_build()),
        (
            "very_fast_build (the tracer's)",
            BvhBuildParams::very_fast_build(),
        ),
        ("fast_build", BvhBuildParams::fast_build()),
        ("medium_build", BvhBuildParams::medium_build()),
        ("slow_build", BvhBuildParams::slow_build()),
    ];
    let centre = glam::DVec3::ZERO;
    let mut best = vec![(f64::INFINITY, f64::INFINITY, 0u64); presets.len()];
    for _ in 0..rounds {
        for (i, (_, params)) in presets.iter().enumerate() {
            let started = Instant::now();
            let bare = BareObvhs::with_params(&mesh, centre, *params);
            let build_s = started.elapsed().as_secs_f64();
            let rays = bare.primary_rays(&camera);
            let _ = bare.pass(&rays);
            let started = Instant::now();
            let hits = bare.pass(&rays);
            let pass_ns = started.elapsed().as_secs_f64() * 1e9 / rays.len() as f64;
            best[i] = (best[i].0.min(build_s), best[i].1.min(pass_ns), hits);
        }
    }
    println!(
        "{} triangles, {} rays, fastest of {rounds} rounds, {} rayon threads for the build",
        mesh.1.len(),
        128 * 128,
        rayon::current_num_threads()
    );
    println!("| preset | build (s) | primary ray, one thread (ns) | hits |");
    println!("| --- | ---: | ---: | ---: |");
    for ((name, _), (build_s, pass_ns, hits)) in presets.iter().zip(&best) {
        println!("| {name} | {build_s:.3} | {pass_ns:.0} | {hits} |");
    }
}
