//! Tracer throughput on one core: primary radiance samples per second on a tessellated
//! sphere (1k, 100k and 1M triangles) over a ground plate, diffuse, with one specular
//! bounce and with the sky-view factor on; the same primary rays through bare obvhs
//! (its own, non-watertight triangle test, no radiometry) for the ratio; the diffuse case
//! with a statistical texture on every facet, and with an image map on every facet (at 128²,
//! and as whole 1024² frames, `frame_1024`); BVH build time; and one call of the
//! rough-surface glint rule (`lobe_glint`).
//!
//! `cargo bench -p irsig-tracer` (a few seconds per case). Figures go to BENCHMARKS.md.

use std::sync::OnceLock;

use divan::counter::ItemsCount;
use irsig_model::{Material, MaterialId, MaterialLibrary, RawFacet, RawScene};
use irsig_radiometry::TotalRadiance;
use irsig_tracer::geometry::Geometry;
use irsig_tracer::testing::{
    BENCH_EMISSIVITY, BareObvhs, EdgeExperiment, LobeProbe, Mesh, PitExperiment, bench_camera,
    bench_scene, geometry_pass, primary_directions, triangles,
};
use irsig_tracer::{Camera, TraceOptions, Tracer, Vacuum};

fn main() {
    divan::main();
}

/// The sphere over the ground, `i` 0/1/2: 1 024, 99 904 and 1 001 112 sphere triangles.
fn mesh(i: usize) -> Mesh {
    bench_scene(i)
}

fn raw_scene(m: &Mesh) -> RawScene {
    let n = m.1.len();
    RawScene {
        objects: vec!["sphere".into()],
        positions_m: m.0.clone(),
        facets: m
            .1
            .iter()
            .enumerate()
            .map(|(i, f)| RawFacet {
                vertices: *f,
                // The ground plate (last two facets) is material 2.
                material: MaterialId(if i + 2 >= n { 2 } else { 1 }),
                temperature_k: 290.0 + (i % 17) as f64,
                object: 0,
                uv: None,
            })
            .collect(),
        ..RawScene::default()
    }
}

fn materials(sphere_specular: f64) -> MaterialLibrary {
    let m = |id: u16, s: f64| Material {
        id: MaterialId(id),
        name: format!("m{id}"),
        emissivity: BENCH_EMISSIVITY.to_vec(),
        specular_fraction: s,
        source: "bench".into(),
        band_um: None,
        spectral: None,
        rms_slope: None,
        thermal: None,
        texture: None,
        maps: None,
    };
    MaterialLibrary {
        materials: vec![m(1, sphere_specular), m(2, 0.0)],
    }
}

fn camera() -> Camera {
    bench_camera(128)
}

struct Prepared {
    diffuse: Tracer<TotalRadiance, Vacuum>,
    specular: Tracer<TotalRadiance, Vacuum>,
    bare: BareObvhs,
}

fn prepared(i: usize) -> &'static Prepared {
    static CACHE: [OnceLock<Prepared>; 3] = [const { OnceLock::new() }; 3];
    CACHE[i].get_or_init(|| {
        let m = mesh(i);
        let sc = raw_scene(&m);
        let sky = Vacuum {
            sky_radiance_w_m2_sr: 20.0,
        };
        let diffuse = Tracer::new(&sc, &materials(0.0), TotalRadiance, sky).unwrap();
        let specular = Tracer::new(&sc, &materials(1.0), TotalRadiance, sky).unwrap();
        let bare = BareObvhs::new(&m, diffuse.geometry().centre_m());
        Prepared {
            diffuse,
            specular,
            bare,
        }
    })
}

fn one_core<T: Send>(f: impl FnOnce() -> T + Send) -> T {
    rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap()
        .install(f)
}

const PIXELS: usize = 128 * 128;

#[divan::bench(args = [0, 1, 2], sample_count = 5, sample_size = 1)]
fn shaded_diffuse(bencher: divan::Bencher, i: usize) {
    let p = prepared(i);
    let cam = camera();
    bencher.counter(ItemsCount::new(PIXELS)).bench(|| {
        one_core(|| {
            p.diffuse
                .render(&cam, &TraceOptions::default(), &|_| {})
                .unwrap()
        })
    });
}

/// The diffuse scene with every facet textured: both materials vary their temperature
/// (σ 1.5 K, exponential, 0.5 m) and their emissivity (σ 2 %, Gaussian, 2 m), so every hit
/// evaluates two fields of `irsig_texture::WAVES` waves and reads the textured `L_T`
/// table. Against `shaded_diffuse`: what a texture on every facet costs a frame. With
/// `footprint`, both fields are read through the footprint filter (the mean over each
/// ray's pixel cell: every wave filtered, the cells being far above 10⁻³ of the shortest
/// wavelengths).
fn textured(i: usize, footprint: bool) -> &'static Tracer<TotalRadiance, Vacuum> {
    static CACHE: [OnceLock<Tracer<TotalRadiance, Vacuum>>; 6] = [const { OnceLock::new() }; 6];
    CACHE[i + 3 * usize::from(footprint)].get_or_init(|| {
        let mut lib = materials(0.0);
        for (k, m) in lib.materials.iter_mut().enumerate() {
            let mut texture = irsig_texture::testing::statistical(k as u64);
            if footprint {
                texture.filter = irsig_model::texture::FieldFilter::Footprint;
            }
            m.texture = Some(texture);
        }
        let sky = Vacuum {
            sky_radiance_w_m2_sr: 20.0,
        };
        Tracer::new(&raw_scene(&mesh(i)), &lib, TotalRadiance, sky).unwrap()
    })
}

#[divan::bench(args = [0, 1, 2], sample_count = 5, sample_size = 1)]
fn shaded_diffuse_textured(bencher: divan::Bencher, i: usize) {
    let tracer = textured(i, false);
    let cam = camera();
    bencher.counter(ItemsCount::new(PIXELS)).bench(|| {
        one_core(|| {
            tracer
                .render(&cam, &TraceOptions::default(), &|_| {})
                .unwrap()
        })
    });
}

/// The diffuse scene with an image map on every facet: each facet's corners get texture
/// coordinates from their x and y (one repetition of the image per 4 m), and both
/// materials a 256 × 256 temperature map (nearest) and emissivity map (bilinear), so every
/// hit interpolates its coordinates and reads two maps. Against `shaded_diffuse`: what an
/// image map on every facet costs a frame. With `footprint`, both maps are read with the
/// footprint filter instead (a mip pyramid, two levels read bilinearly at every hit).
fn mapped(i: usize, footprint: bool) -> &'static Tracer<TotalRadiance, Vacuum> {
    use irsig_texture::MaterialMaps;
    static CACHE: [OnceLock<Tracer<TotalRadiance, Vacuum>>; 6] = [const { OnceLock::new() }; 6];
    CACHE[i + 3 * usize::from(footprint)].get_or_init(|| {
        let mut scene = raw_scene(&mesh(i));
        let positions = scene.positions_m.clone();
        for f in &mut scene.facets {
            f.uv = Some(f.vertices.map(|v| {
                let p = positions[v as usize];
                [p[0] / 4.0, p[1] / 4.0]
            }));
        }
        let (maps, image) = irsig_texture::testing::maps(footprint);
        let mut lib = materials(0.0);
        let mut loaded = Vec::new();
        for m in &mut lib.materials {
            m.maps = Some(maps.clone());
            let maps = MaterialMaps::new(&maps, |_, _| Ok(image.clone())).unwrap();
            loaded.push((m.id, maps));
        }
        let sky = irsig_tracer::SubBand {
            band: TotalRadiance,
            atmosphere: Vacuum {
                sky_radiance_w_m2_sr: 20.0,
            },
            emissivity: None,
        };
        Tracer::with_sub_bands_and_maps(&scene, &lib, TotalRadiance, vec![sky], loaded).unwrap()
    })
}

#[divan::bench(args = [0, 1, 2], sample_count = 5, sample_size = 1)]
fn shaded_diffuse_mapped(bencher: divan::Bencher, i: usize) {
    let tracer = mapped(i, false);
    let cam = camera();
    bencher.counter(ItemsCount::new(PIXELS)).bench(|| {
        one_core(|| {
            tracer
                .render(&cam, &TraceOptions::default(), &|_| {})
                .unwrap()
        })
    });
}

/// `shaded_diffuse_mapped` with both maps read through the footprint filter.
#[divan::bench(args = [0, 1, 2], sample_count = 5, sample_size = 1)]
fn shaded_diffuse_mapped_footprint(bencher: divan::Bencher, i: usize) {
    let tracer = mapped(i, true);
    let cam = camera();
    bencher.counter(ItemsCount::new(PIXELS)).bench(|| {
        one_core(|| {
            tracer
                .render(&cam, &TraceOptions::default(), &|_| {})
                .unwrap()
        })
    });
}

/// The texture floor's own measurement: a whole 1024² frame of the diffuse scene on one
/// thread, `plain`, with a statistical texture on every facet (`field`; `field-footprint`
/// through the footprint filter), with image maps (`maps`, nearest and bilinear) and with
/// image maps through the footprint filter (`footprint`); the textured frames against
/// `plain`, scene by scene.
#[divan::bench(consts = [0, 1, 2], args = ["plain", "field", "field-footprint", "maps", "footprint"], sample_count = 5, sample_size = 1)]
fn frame_1024<const I: usize>(bencher: divan::Bencher, kind: &str) {
    let tracer = match kind {
        "field" => textured(I, false),
        "field-footprint" => textured(I, true),
        "maps" => mapped(I, false),
        "footprint" => mapped(I, true),
        _ => &prepared(I).diffuse,
    };
    let cam = bench_camera(1024);
    bencher
        .counter(ItemsCount::new(1024 * 1024_usize))
        .bench(|| {
            one_core(|| {
                tracer
                    .render(&cam, &TraceOptions::default(), &|_| {})
                    .unwrap()
            })
        });
}

#[divan::bench(args = [0, 1, 2], sample_count = 5, sample_size = 1)]
fn shaded_specular_bounce(bencher: divan::Bencher, i: usize) {
    let p = prepared(i);
    let cam = camera();
    bencher.counter(ItemsCount::new(PIXELS)).bench(|| {
        one_core(|| {
            p.specular
                .render(&cam, &TraceOptions::default(), &|_| {})
                .unwrap()
        })
    });
}

#[divan::bench(args = [0, 1, 2], sample_count = 3, sample_size = 1)]
fn shaded_sky_view_16_rays(bencher: divan::Bencher, i: usize) {
    let p = prepared(i);
    let cam = camera();
    let opts = TraceOptions {
        sky_view_rays: 16,
        ..TraceOptions::default()
    };
    bencher
        .counter(ItemsCount::new(PIXELS))
        .bench(|| one_core(|| p.diffuse.render(&cam, &opts, &|_| {}).unwrap()));
}

/// The same primary rays, closest hit with obvhs's own triangle test (triangles stored in
/// BVH order) and nothing else.
#[divan::bench(args = [0, 1, 2], sample_count = 5, sample_size = 1)]
fn bare_obvhs_primary(bencher: divan::Bencher, i: usize) {
    let p = prepared(i);
    let cam = camera();
    let rays = p.bare.primary_rays(&cam);
    bencher
        .counter(ItemsCount::new(PIXELS))
        .bench(|| divan::black_box(p.bare.pass(&rays)));
}

/// The same primary rays through the tracer's own geometry without shading: f64 clip,
/// watertight test, f64 refinement (what the tracer adds to obvhs before any radiometry).
#[divan::bench(args = [0, 1, 2], sample_count = 5, sample_size = 1)]
fn tracer_geometry_primary(bencher: divan::Bencher, i: usize) {
    let p = prepared(i);
    let cam = camera();
    let directions = primary_directions(&cam);
    bencher.counter(ItemsCount::new(PIXELS)).bench(|| {
        divan::black_box(geometry_pass(
            p.diffuse.geometry(),
            cam.position_m,
            &directions,
        ))
    });
}

/// Geometry only (re-centring, BVH build, BVH-order copies) from world triangles.
#[divan::bench(args = [0, 1, 2], sample_count = 3, sample_size = 1)]
fn bvh_build(bencher: divan::Bencher, i: usize) {
    let tris = triangles(&mesh(i));
    bencher.bench(|| Geometry::new(&tris));
}

/// The whole scene set-up a 1M-triangle trace pays before its first ray: validation,
/// L_T per facet, BVH.
#[divan::bench(sample_count = 3, sample_size = 1)]
fn scene_setup_1m(bencher: divan::Bencher) {
    let sc = raw_scene(&mesh(2));
    let mats = materials(0.0);
    bencher.bench(|| Tracer::new(&sc, &mats, TotalRadiance, Vacuum::default()).unwrap());
}

/// Time per diffuse hit with the sky-view factor on, N rays: the pit of the F-error table
/// (docs/accuracy.md), 256 pixels, every one a floor hit.
#[divan::bench(args = [4, 16, 64, 256, 1024], sample_count = 3, sample_size = 1)]
fn sky_view_pit(bencher: divan::Bencher, rays: u32) {
    static PIT: OnceLock<PitExperiment> = OnceLock::new();
    let pit = PIT.get_or_init(PitExperiment::new);
    bencher
        .counter(ItemsCount::new(256_usize))
        .bench(|| one_core(|| pit.estimates(rays, 1)));
}

/// Time per pixel with N × N supersampling: the slanted-edge image of the supersampling
/// table (docs/accuracy.md), 24 × 64 pixels.
#[divan::bench(args = [1, 2, 4, 8, 16], sample_count = 3, sample_size = 1)]
fn supersampling_edge(bencher: divan::Bencher, n: u32) {
    static EDGE: OnceLock<EdgeExperiment> = OnceLock::new();
    let edge = EDGE.get_or_init(EdgeExperiment::new);
    let options = TraceOptions {
        supersampling: n,
        ..TraceOptions::default()
    };
    bencher
        .counter(ItemsCount::new((24 * 64) as usize))
        .bench(|| one_core(|| edge.tracer.render(&edge.camera, &options, &|_| {}).unwrap()));
}

/// The 100k-triangle scene under the built-in US Standard atmosphere (table model, the
/// tool's default): path terms exact per hit, or tabulated per frame (the table's build
/// included in every render).
#[divan::bench(args = ["exact", "tabulated"], sample_count = 3, sample_size = 1)]
fn shaded_us_std_atmosphere_100k(bencher: divan::Bencher, mode: &str) {
    use irsig_atmosphere::{AtmosphereModel, ModelKind, PrecomputedAtmosphere, builtin};
    let sc = raw_scene(&mesh(1));
    let model = AtmosphereModel::new(&builtin("us-std-1976").unwrap(), ModelKind::Table).unwrap();
    // The sky precomputed up to the scene's top, as irsig-trace does.
    let air = PrecomputedAtmosphere::new(model, 25.0);
    let tracer = Tracer::new(&sc, &materials(0.0), TotalRadiance, air)
        .unwrap()
        .with_path_terms(if mode == "exact" {
            irsig_tracer::PathTermsMode::Exact
        } else {
            irsig_tracer::PathTermsMode::Tabulated
        });
    let cam = camera();
    bencher.counter(ItemsCount::new(PIXELS)).bench(|| {
        one_core(|| {
            tracer
                .render(&cam, &TraceOptions::default(), &|_| {})
                .unwrap()
        })
    });
}

/// The error budget's charges ([`irsig_tracer::charge`]): a frame of the 100k sphere, its
/// specular share mirroring the ground, with its truth kept, without and with the budget's
/// groups (one per material), centre rays alone and refined (edges and the horizon in 8
/// rounds of up to 16 × 16 rays). What the budget adds to a frame is the ratio of each
/// pair.
#[divan::bench(
    args = ["plain", "plain+budget", "refined", "refined+budget"],
    sample_count = 3,
    sample_size = 1
)]
fn budget_charges(bencher: divan::Bencher, case: &str) {
    let m = mesh(1);
    let sc = raw_scene(&m);
    let sky = Vacuum {
        sky_radiance_w_m2_sr: 20.0,
    };
    let refinement = case
        .starts_with("refined")
        .then_some(irsig_tracer::Refinement {
            target_k: 0.1,
            edge_k: 0.5,
            max_side: 16,
            thin_side: 8,
        });
    let groups = case
        .ends_with("+budget")
        .then(|| sc.facets.iter().map(|f| u32::from(f.material.0)).collect());
    let tracer = Tracer::new(&sc, &materials(0.5), TotalRadiance, sky)
        .unwrap()
        .with_refinement(refinement)
        .unwrap()
        .with_budget_groups(groups);
    let cam = camera();
    bencher.counter(ItemsCount::new(PIXELS)).bench(|| {
        one_core(|| {
            tracer
                .render(&cam, &TraceOptions::default(), &|_| {})
                .unwrap()
        })
    });
}

/// One call of the rough-surface glint rule, sun at 30°, for water (σ 0.105) and paint
/// (σ 0.15): views 20–40° from the zenith in the plane of incidence, within 10° of the
/// mirror direction ("near"), and 50–70° at azimuth 90°, across it ("across"). Each
/// sample is 1,000 calls over the range.
#[divan::bench(args = ["water near", "water across", "paint near", "paint across"], sample_count = 10)]
fn lobe_glint(bencher: divan::Bencher, case: &str) {
    let sigma = if case.starts_with("water") {
        0.105
    } else {
        0.15
    };
    let (from_deg, phi_deg) = if case.ends_with("near") {
        (20.0, 180.0)
    } else {
        (50.0, 90.0)
    };
    let probe = LobeProbe::new(sigma, 30.0);
    let n = 1000_u32;
    bencher.counter(ItemsCount::new(n)).bench(|| {
        (0..n)
            .map(|k| probe.glint_per_sr(from_deg + 20.0 * f64::from(k) / f64::from(n), phi_deg))
            .sum::<f64>()
    });
}
