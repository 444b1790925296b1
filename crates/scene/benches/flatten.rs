//! Flattening throughput on a generated 1M-triangle scene (four placed spheres).

use irsig_model::{MaterialId, Placement, Scene};

fn main() {
    divan::main();
}

#[divan::bench(sample_count = 5)]
fn flatten_1m_triangles(bencher: divan::Bencher) {
    // 4 × 2·500·250 = 998,000 triangles.
    let sphere = irsig_scene::uv_sphere(1.0, 500, 251, MaterialId(1));
    let scene = Scene {
        objects: (0..4)
            .map(|i| Placement {
                object: "s.ron".into(),
                rotation_deg: [10.0 * f64::from(i), 20.0, 30.0],
                translation_m: [5.0 * f64::from(i), 0.0, 0.0],
                scale: [1.0, 2.0, 3.0],
                temperature_k: Some(300.0),
                overrides: vec![],
            })
            .collect(),
        ..Scene::default()
    };
    let objects = [&sphere; 4];
    bencher
        .counter(divan::counter::ItemsCount::new(4 * sphere.facets.len()))
        .bench(|| irsig_scene::flatten(&scene, &objects).map(|r| r.facets.len()));
}
