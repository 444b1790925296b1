//! Single-ray traversal on the same rays as another ray tracer: writes the scene's
//! triangles and the rays to files a peer's harness reads (`scripts/bench/embree_rays.cpp`
//! for Intel Embree), then times irsig's own traversal of them on one thread.
//!
//! `cargo run --release -p irsig-tracer --example traversal DIR [SIZE] [PIXELS] [ROUNDS]`
//!
//! The scene is the shade profile's (a UV sphere over a ground quad; SIZE 0/1/2 =
//! 1k/100k/1M triangles) seen by a PIXELS × PIXELS camera (default 1024). Written to DIR:
//! - `triangles.bin`: u32 count, then per triangle 9 f32 (three vertices, metres, re-centred
//!   as the tracer re-centres them);
//! - `rays-scanline.bin`, `rays-tiles.bin`: u32 count, then per ray 6 f32 (origin, unit
//!   direction) in the same frame, pixels row by row, or in 8 × 8 tiles (a coherence order).
//!
//! Prints, per ray order, the fastest of ROUNDS single-thread passes in ns per ray of:
//! obvhs's own traversal and triangle test on f32 rays (`bare`), the tracer's geometry
//! (`Geometry::closest_hit`: f64 clip, watertight test, f64 refinement), and bare obvhs with
//! the rays in packets of 64 consecutive ones (`BareObvhs::packet_pass`, a route measured,
//! not the tracer's), with the count of rays that hit.

use std::io::Write;
use std::time::Instant;

use irsig_tracer::geometry::Geometry;
use irsig_tracer::testing::{
    BareObvhs, PACKET, bench_camera, bench_scene, geometry_pass, triangles,
};

/// Live rays at or below which a packet's rays go on alone ([`BareObvhs::packet_pass`]):
/// on the sphere, 4 gave 122-131 ns a ray, 8 118-122, 16 114-121 and 32 115-124.
const PACKET_ALONE: u32 = 16;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let Some(dir) = args.get(1) else {
        eprintln!("usage: traversal DIR [SIZE] [PIXELS] [ROUNDS]");
        std::process::exit(2);
    };
    let size: usize = args.get(2).and_then(|a| a.parse().ok()).unwrap_or(2);
    let pixels: u32 = args.get(3).and_then(|a| a.parse().ok()).unwrap_or(1024);
    let rounds: u32 = args.get(4).and_then(|a| a.parse().ok()).unwrap_or(5);
    let mesh = bench_scene(size);
    let tris = triangles(&mesh);
    let geometry = Geometry::new(&tris);
    let centre = geometry.centre_m();
    let camera = bench_camera(pixels);
    let bare = BareObvhs::new(&mesh, centre);
    let scanline: Vec<(u32, u32)> = (0..pixels)
        .flat_map(|r| (0..pixels).map(move |c| (c, r)))
        .collect();
    let tiles: Vec<(u32, u32)> = {
        let t = 8;
        let n = pixels.div_ceil(t);
        let mut order = Vec::with_capacity(scanline.len());
        for tr in 0..n {
            for tc in 0..n {
                for r in tr * t..((tr + 1) * t).min(pixels) {
                    for c in tc * t..((tc + 1) * t).min(pixels) {
                        order.push((c, r));
                    }
                }
            }
        }
        order
    };
    let local = |p: glam::DVec3| (p - centre).to_array();
    let f32s = |v: &[f64]| v.iter().map(|&x| x as f32).collect::<Vec<f32>>();
    let dir = std::path::Path::new(dir);
    std::fs::create_dir_all(dir).expect("create DIR");
    let mut out = Vec::with_capacity(4 + tris.len() * 36);
    out.extend((tris.len() as u32).to_le_bytes());
    for t in &tris {
        for p in t {
            for x in f32s(&local(*p)) {
                out.extend(x.to_le_bytes());
            }
        }
    }
    std::fs::write(dir.join("triangles.bin"), &out).expect("write triangles.bin");
    let origin = local(camera.position_m);
    println!(
        "{} triangles, {} rays ({pixels}²), one thread, fastest of {rounds}",
        tris.len(),
        scanline.len()
    );
    println!(
        "| order | bare obvhs (ns/ray) | tracer geometry (ns/ray) | bare obvhs, packets of {PACKET} (ns/ray) | hits |"
    );
    println!("| --- | ---: | ---: | ---: | ---: |");
    for (name, order) in [("scanline", &scanline), ("tiles", &tiles)] {
        let directions: Vec<glam::DVec3> = order
            .iter()
            .map(|&(c, r)| camera.pixel_direction(c, r))
            .collect();
        let mut file = std::fs::File::create(dir.join(format!("rays-{name}.bin")))
            .expect("create the rays file");
        let mut bytes = Vec::with_capacity(4 + directions.len() * 24);
        bytes.extend((directions.len() as u32).to_le_bytes());
        for d in &directions {
            for x in f32s(&origin).into_iter().chain(f32s(&d.to_array())) {
                bytes.extend(x.to_le_bytes());
            }
        }
        file.write_all(&bytes).expect("write the rays file");
        let rays: Vec<obvhs::ray::Ray> = directions
            .iter()
            .map(|d| {
                let o = f32s(&origin);
                obvhs::ray::Ray::new_inf(
                    glam::Vec3A::new(o[0], o[1], o[2]),
                    glam::Vec3A::new(d[0] as f32, d[1] as f32, d[2] as f32),
                )
            })
            .collect();
        let (mut best_bare, mut best_geometry, mut hits) = (f64::INFINITY, f64::INFINITY, 0);
        let mut best_packets = f64::INFINITY;
        // Each pass runs once untimed first: at 1M triangles the bare BVH and the tracer's
        // are separate copies that evict each other from the caches.
        for _ in 0..rounds {
            let _ = bare.pass(&rays);
            let t = Instant::now();
            let h = bare.pass(&rays);
            best_bare = best_bare.min(t.elapsed().as_secs_f64() * 1e9 / rays.len() as f64);
            let _ = geometry_pass(&geometry, camera.position_m, &directions);
            let t = Instant::now();
            let g = geometry_pass(&geometry, camera.position_m, &directions);
            best_geometry = best_geometry.min(t.elapsed().as_secs_f64() * 1e9 / rays.len() as f64);
            hits = g;
            assert!(h.abs_diff(g) * 1000 <= g, "bare {h} and tracer {g} hits");
            let _ = bare.packet_pass(&rays, PACKET_ALONE);
            let t = Instant::now();
            let p = bare.packet_pass(&rays, PACKET_ALONE);
            best_packets = best_packets.min(t.elapsed().as_secs_f64() * 1e9 / rays.len() as f64);
            assert!(h.abs_diff(p) * 1000 <= h, "bare {h} and packets {p} hits");
        }
        println!("| {name} | {best_bare:.0} | {best_geometry:.0} | {best_packets:.0} | {hits} |");
    }
}
