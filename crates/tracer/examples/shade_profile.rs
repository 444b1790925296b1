//! A profiling harness: builds the benchmark's sphere-over-ground scene once and renders
//! it repeatedly on one thread, so a sampling profiler sees shading and traversal rather
//! than the BVH build.
//!
//! `shade_profile SIZE RENDERS [MODE]`: SIZE 0/1/2 = 1k/100k/1M triangles; MODE `diffuse`
//! (default), `radiance` (diffuse without the truth terms), `spec`, `f16` (sky-view factor,
//! 16 rays) or `bare` (the same primary rays through bare obvhs). For a profiler:
//! `perf record -g target/profiling/examples/shade_profile 1 200 radiance`.
//!
//! A fourth argument `angular` gives both materials the benchmark's 4-point angular
//! emissivity table (0.95 at 0°, 0.93 at 45°, 0.85 at 70°, 0 at 90°) instead of grey ones,
//! so each hit pays the arc cosine the table is indexed by.
//!
//! MODE `compare` measures the shaded/bare ratio on a shared, noisy machine: it interleaves
//! one bare pass, one pass of the tracer's geometry alone (closest hits, no shading), one
//! diffuse pass with the truth terms and one without (each timed on its second run, with
//! warm caches), RENDERS times, and prints the fastest and the median pass of each. Interference only ever adds time, and
//! interleaving exposes the three to the same conditions, so the ratio of the fastest
//! passes is the stable figure.

use std::time::Instant;

use irsig_radiometry::TotalRadiance;
use irsig_tracer::testing::{
    BENCH_EMISSIVITY, BareObvhs, bench_camera, bench_ground, bench_scene, bench_sphere,
    geometry_pass, grey_materials, primary_directions, raw_scene,
};
use irsig_tracer::{TraceOptions, Tracer, Vacuum};

const PIXELS: f64 = 128.0 * 128.0;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let size: usize = args.get(1).and_then(|a| a.parse().ok()).unwrap_or(1);
    let renders: u32 = args.get(2).and_then(|a| a.parse().ok()).unwrap_or(20);
    let mode = args.get(3).map_or("diffuse", String::as_str);
    let (sphere, ground) = (bench_sphere(size), bench_ground());
    let scene = raw_scene(&[(&sphere, 1, 300.0), (&ground, 2, 290.0)]);
    let specular = if mode == "spec" { 1.0 } else { 0.0 };
    let mut materials = grey_materials(&[(1, 0.93, specular), (2, 0.95, 0.0)]);
    if args.get(4).is_some_and(|a| a == "angular") {
        for m in &mut materials.materials {
            m.emissivity = BENCH_EMISSIVITY.to_vec();
        }
    }
    let sky = Vacuum {
        sky_radiance_w_m2_sr: 20.0,
    };
    let tracer = Tracer::new(&scene, &materials, TotalRadiance, sky).expect("valid scene");
    let camera = bench_camera(128);
    let options = TraceOptions {
        sky_view_rays: if mode == "f16" { 16 } else { 0 },
        truth: mode != "radiance",
        ..TraceOptions::default()
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("a thread pool");
    let shaded = |options: &TraceOptions| {
        let frame = pool
            .install(|| tracer.render(&camera, options, &|_| {}))
            .expect("valid options");
        frame.radiance_w_m2_sr.iter().sum::<f64>()
    };
    if mode == "bare" || mode == "compare" {
        let bare = BareObvhs::new(&bench_scene(size), tracer.geometry().centre_m());
        let rays = bare.primary_rays(&camera);
        if mode == "bare" {
            let start = Instant::now();
            let hits: u64 = (0..renders).map(|_| bare.pass(&rays)).sum();
            let per = start.elapsed().as_secs_f64() / f64::from(renders) / PIXELS;
            println!("{:.1} ns per bare ray ({hits} hits)", per * 1e9);
            return;
        }
        let radiance_only = TraceOptions {
            truth: false,
            ..options
        };
        let directions = primary_directions(&camera);
        let mut times = [const { Vec::new() }; 4];
        // Each kind runs twice in a row and only the second pass is timed: the first warms
        // the caches with that kind's own data (the bare BVH and the tracer's are separate
        // copies; at 1M triangles each evicts the other), as a long render would.
        let time_warm = |f: &dyn Fn()| {
            f();
            let t = Instant::now();
            f();
            t.elapsed().as_secs_f64()
        };
        for _ in 0..renders {
            times[0].push(time_warm(&|| {
                std::hint::black_box(bare.pass(&rays));
            }));
            times[1].push(time_warm(&|| {
                std::hint::black_box(geometry_pass(
                    tracer.geometry(),
                    camera.position_m,
                    &directions,
                ));
            }));
            times[2].push(time_warm(&|| {
                std::hint::black_box(shaded(&options));
            }));
            times[3].push(time_warm(&|| {
                std::hint::black_box(shaded(&radiance_only));
            }));
        }
        let mut fastest = [0.0; 4];
        for (i, name) in [
            "bare obvhs",
            "tracer geometry only",
            "shaded, truth",
            "shaded, radiance only",
        ]
        .iter()
        .enumerate()
        {
            let t = &mut times[i];
            t.sort_by(f64::total_cmp);
            fastest[i] = t[0];
            println!(
                "{name:<22} fastest {:7.1} ns/ray, median {:7.1} ns/ray",
                t[0] / PIXELS * 1e9,
                t[t.len() / 2] / PIXELS * 1e9
            );
        }
        println!(
            "throughput of the fastest passes: shaded/bare: truth {:.3}, radiance only {:.3}; \
             geometry/bare {:.3}; shaded/geometry: truth {:.3}, radiance only {:.3}",
            fastest[0] / fastest[2],
            fastest[0] / fastest[3],
            fastest[0] / fastest[1],
            fastest[1] / fastest[2],
            fastest[1] / fastest[3]
        );
        return;
    }
    let start = Instant::now();
    let checksum: f64 = (0..renders).map(|_| shaded(&options)).sum();
    let per = start.elapsed().as_secs_f64() / f64::from(renders) / PIXELS;
    println!(
        "{:.1} ns per primary sample (checksum {checksum:.6e})",
        per * 1e9
    );
}
