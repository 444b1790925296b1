//! Writing a truth-sized EXR: 1024 × 1024 pixels, 11 `f32` layers (the tracer's truth EXR),
//! ZIP-compressed. Smooth fields with a little deterministic noise, as a rendered frame
//! compresses. `cargo bench -p irsig-raster --bench exr`; BENCHMARKS.md reports it.

use irsig_raster::{Raster, exr_bytes};

fn main() {
    divan::main();
}

fn truth_like(size: usize, layers: usize) -> Raster {
    let mut r = Raster::new(size, size);
    for l in 0..layers {
        let data: Vec<f32> = (0..size * size)
            .map(|i| {
                let (x, y) = ((i % size) as f32, (i / size) as f32);
                // A smooth field plus a small hash-noise term (splitmix-style bit mixing).
                let mut h = (i as u64 ^ (l as u64) << 40).wrapping_mul(0x9E37_79B9_7F4A_7C15);
                h ^= h >> 31;
                let noise = (h & 0xffff) as f32 / 65536.0;
                280.0 + 10.0 * ((x * 0.01 + l as f32).sin() * (y * 0.013).cos()) + 0.01 * noise
            })
            .collect();
        r.push_layer(format!("layer{l:02}"), "K", data).unwrap();
    }
    r
}

#[divan::bench(sample_count = 5)]
fn truth_1024(bencher: divan::Bencher) {
    let raster = truth_like(1024, 11);
    bencher.bench(|| exr_bytes(divan::black_box(&raster)).unwrap().len());
}
