//! Where a BVH build's time goes, stage by stage, for the shade profile's scene (a UV sphere
//! over a ground quad; SIZE 0/1/2 = 1k/100k/1M triangles): the f32 triangles obvhs builds
//! from, PLOC (obvhs's parallel builder), the reinsertion optimiser and the conversion to
//! the compressed wide BVH the tracer traverses, with the options each stage has.
//!
//! `cargo run --release -p irsig-tracer --example bvh_stages [SIZE] [ROUNDS]`
//!
//! Fastest of ROUNDS for each stage (interference only adds time). Each conversion's BVH is
//! also timed on the primary rays of a 512 × 512 view of the scene, one thread, warm (the
//! conversion's child ordering is for traversal), and its node count printed.

use std::time::Instant;

use irsig_tracer::testing::{bench_camera, bench_scene, primary_directions};
use obvhs::bvh2::reinsertion::ReinsertionOptimizer;
use obvhs::cwbvh::bvh2_to_cwbvh::bvh2_to_cwbvh;
use obvhs::ploc::{PlocBuilder, PlocSearchDistance, SortPrecision};
use obvhs::triangle::Triangle;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let size: usize = args.get(1).and_then(|a| a.parse().ok()).unwrap_or(2);
    let rounds: u32 = args.get(2).and_then(|a| a.parse().ok()).unwrap_or(3);
    let mesh = bench_scene(size);
    let camera = bench_camera(512);
    // Rays in the triangles' own (un-centred) frame, as the triangles below are.
    let rays: Vec<obvhs::ray::Ray> = primary_directions(&camera)
        .iter()
        .map(|d| {
            let o = camera.position_m;
            obvhs::ray::Ray::new_inf(
                glam::Vec3A::new(o[0] as f32, o[1] as f32, o[2] as f32),
                glam::Vec3A::new(d[0] as f32, d[1] as f32, d[2] as f32),
            )
        })
        .collect();
    let mut nodes = 0;
    let mut best = std::collections::BTreeMap::<&str, f64>::new();
    let mut time = |name: &'static str, seconds: f64| {
        let e = best.entry(name).or_insert(f64::INFINITY);
        *e = e.min(seconds);
    };
    for _ in 0..rounds {
        let t = Instant::now();
        let tris: Vec<Triangle> = mesh
            .1
            .iter()
            .map(|f| {
                let v = f.map(|i| {
                    let p = mesh.0[i as usize];
                    glam::Vec3A::new(p[0] as f32, p[1] as f32, p[2] as f32)
                });
                Triangle {
                    v0: v[0],
                    v1: v[1],
                    v2: v[2],
                }
            })
            .collect();
        time("1 f32 triangles", t.elapsed().as_secs_f64());
        for (name, precision) in [
            ("2 PLOC, 64-bit Morton sort", SortPrecision::U64),
            ("2 PLOC, 128-bit Morton sort", SortPrecision::U128),
        ] {
            let t = Instant::now();
            let bvh2 = PlocBuilder::with_capacity(tris.len()).build(
                PlocSearchDistance::Minimum,
                &tris,
                (0..tris.len() as u32).collect::<Vec<_>>(),
                precision,
                0,
            );
            time(name, t.elapsed().as_secs_f64());
            drop(bvh2);
        }
        let mut bvh2 = PlocBuilder::with_capacity(tris.len()).build(
            PlocSearchDistance::Minimum,
            &tris,
            (0..tris.len() as u32).collect::<Vec<_>>(),
            SortPrecision::U64,
            0,
        );
        let t = Instant::now();
        ReinsertionOptimizer::default().run(&mut bvh2, 0.01, None);
        time("3 reinsertion, 1 % of nodes", t.elapsed().as_secs_f64());
        for (name, ray_name, order) in [
            (
                "4 to CWBVH, children ordered",
                "5 rays through it, ns, children ordered",
                true,
            ),
            (
                "4 to CWBVH, children unordered",
                "5 rays through it, ns, children unordered",
                false,
            ),
        ] {
            let t = Instant::now();
            let cw = bvh2_to_cwbvh(&bvh2, 3, order, false);
            time(name, t.elapsed().as_secs_f64());
            let pass = || {
                let mut hits = 0u32;
                for ray in &rays {
                    let mut hit = obvhs::ray::RayHit::none();
                    if cw.ray_traverse(*ray, &mut hit, |r, id| {
                        tris[cw.primitive_indices[id] as usize].intersect(r)
                    }) {
                        hits += 1;
                    }
                }
                hits
            };
            let _ = pass();
            let t = Instant::now();
            std::hint::black_box(pass());
            time(
                ray_name,
                t.elapsed().as_secs_f64() * 1e9 / rays.len() as f64,
            );
            nodes = cw.nodes.len();
        }
    }
    println!(
        "{} triangles, {nodes} wide nodes, fastest of {rounds}, {} rayon threads",
        mesh.1.len(),
        rayon::current_num_threads()
    );
    for (name, v) in &best {
        if name.starts_with('5') {
            println!("| {name} | {v:.0} |");
        } else {
            println!("| {name} | {v:.3} s |");
        }
    }
}
