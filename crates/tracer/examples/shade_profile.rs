//! A profiling harness: builds the benchmark's sphere-over-ground scene once and renders
//! it repeatedly on one thread, so a sampling profiler sees shading and traversal rather
//! than the BVH build. `perf record -g target/release/examples/shade_profile 1 40`
//! (size index 0/1/2 = 1k/100k/1M triangles, then the number of renders; add `spec` or
//! `f16` for the specular or sky-view case, `radiance` for the diffuse case without the
//! truth terms).

use irsig_model::View;
use irsig_tracer::testing::{grey_materials, ground_quad, raw_scene, uv_sphere};
use irsig_tracer::{Camera, TotalRadiance, TraceOptions, Tracer, Vacuum};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let size: usize = args.get(1).and_then(|a| a.parse().ok()).unwrap_or(1);
    let renders: u32 = args.get(2).and_then(|a| a.parse().ok()).unwrap_or(20);
    let mode = args.get(3).map_or("diffuse", String::as_str);
    let (rings, segments) = [(17, 32), (224, 224), (708, 708)][size.min(2)];
    let sphere = uv_sphere([0.0, 0.0, 12.0], 10.0, rings, segments);
    let ground = ground_quad([-100.0, -100.0], [100.0, 100.0], 0.0);
    let scene = raw_scene(&[(&sphere, 1, 300.0), (&ground, 2, 290.0)]);
    let specular = if mode == "spec" { 1.0 } else { 0.0 };
    let materials = grey_materials(&[(1, 0.93, specular), (2, 0.95, 0.0)]);
    let sky = Vacuum {
        sky_radiance_w_m2_sr: 20.0,
    };
    let tracer = Tracer::new(&scene, &materials, TotalRadiance, sky).expect("valid scene");
    let camera = Camera::from_view(&View::LookAt {
        position_m: [30.0, -30.0, 25.0],
        target_m: [0.0, 0.0, 10.0],
        up: [0.0, 0.0, 1.0],
        pixels: [128, 128],
        fov_deg: [50.0, 50.0],
        gain_dc_per_k: None,
    })
    .expect("valid view");
    let options = TraceOptions {
        sky_view_rays: if mode == "f16" { 16 } else { 0 },
        truth: mode != "radiance",
        ..TraceOptions::default()
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("a thread pool");
    if mode == "bare" {
        bare(
            &tracer,
            &camera,
            &irsig_tracer::testing::triangles(&sphere_and_ground(&sphere, &ground)),
            renders,
        );
        return;
    }
    let start = std::time::Instant::now();
    let mut checksum = 0.0;
    for _ in 0..renders {
        let frame = pool
            .install(|| tracer.render(&camera, &options, &|_| {}))
            .expect("valid options");
        checksum += frame.radiance_w_m2_sr.iter().sum::<f64>();
    }
    let per = start.elapsed().as_secs_f64() / f64::from(renders) / 16384.0;
    println!(
        "{:.1} ns per primary sample (checksum {checksum:.6e})",
        per * 1e9
    );
}

fn sphere_and_ground(
    sphere: &irsig_tracer::testing::Mesh,
    ground: &irsig_tracer::testing::Mesh,
) -> irsig_tracer::testing::Mesh {
    let mut m = sphere.clone();
    let base = m.0.len() as u32;
    m.0.extend(&ground.0);
    m.1.extend(ground.1.iter().map(|f| f.map(|v| v + base)));
    m
}

/// The same primary rays through bare obvhs (its own triangle test, nothing else).
fn bare(
    tracer: &Tracer<TotalRadiance, Vacuum>,
    camera: &Camera,
    tris: &[[[f64; 3]; 3]],
    renders: u32,
) {
    use glam::Vec3A;
    use obvhs::{
        BvhBuildParams,
        cwbvh::builder::build_cwbvh_from_tris,
        ray::{Ray, RayHit},
        triangle::Triangle,
    };
    let c = tracer.geometry().centre_m();
    let v = |p: [f64; 3]| {
        Vec3A::new(
            (p[0] - c[0]) as f32,
            (p[1] - c[1]) as f32,
            (p[2] - c[2]) as f32,
        )
    };
    let tris: Vec<Triangle> = tris
        .iter()
        .map(|t| Triangle {
            v0: v(t[0]),
            v1: v(t[1]),
            v2: v(t[2]),
        })
        .collect();
    let bvh = build_cwbvh_from_tris(
        &tris,
        BvhBuildParams::medium_build(),
        &mut std::time::Duration::default(),
    );
    let o = v(camera.position_m);
    let dirs: Vec<Vec3A> = (0..128)
        .flat_map(|r| (0..128).map(move |c| (c, r)))
        .map(|(c, r)| {
            let d = camera.pixel_direction(c, r);
            Vec3A::new(d[0] as f32, d[1] as f32, d[2] as f32)
        })
        .collect();
    let start = std::time::Instant::now();
    let mut hits = 0u64;
    for _ in 0..renders {
        for d in &dirs {
            let mut hit = RayHit::none();
            if bvh.ray_traverse(Ray::new_inf(o, *d), &mut hit, |ray, id| {
                tris[bvh.primitive_indices[id] as usize].intersect(ray)
            }) {
                hits += 1;
            }
        }
    }
    let per = start.elapsed().as_secs_f64() / f64::from(renders) / 16384.0;
    println!("{:.1} ns per bare ray ({hits} hits)", per * 1e9);
}
