//! What a statistical texture costs a hit: `TextureFields::sample` (a temperature field
//! and an emissivity field of `WAVES` plane waves each, as the tracer's `frame_1024` field
//! case draws them) at 4 096 points spread over 100 m, through the footprint filter, and
//! one field alone.
//!
//! `cargo bench --profile release --workspace --bench field`. Figures go to BENCHMARKS.md.

use divan::counter::ItemsCount;
use irsig_model::texture::FieldFilter;
use irsig_texture::{Field, Footprint, MaterialMaps, TextureFields, testing};

fn main() {
    divan::main();
}

const POINTS: usize = 4096;

/// Points on a spiral over a 100 m disc, 0 to 3 m high: no two alike, so nothing repeats
/// from one sample to the next.
fn points() -> Vec<[f64; 3]> {
    (0..POINTS)
        .map(|i| {
            let t = i as f64 / POINTS as f64;
            let a = t * 97.0;
            [50.0 * t * a.cos(), 50.0 * t * a.sin(), 3.0 * t]
        })
        .collect()
}

#[divan::bench(sample_count = 200)]
fn both_fields(bencher: divan::Bencher) {
    let fields = TextureFields::new(&testing::statistical(1)).unwrap();
    let points = points();
    bencher.counter(ItemsCount::new(POINTS)).bench(|| {
        points
            .iter()
            .map(|&p| {
                let t = fields.sample(divan::black_box(p));
                t.temperature_offset_k + t.emissivity_scale
            })
            .sum::<f64>()
    });
}

/// [`both_fields`] through the footprint filter (`FieldFilter::Footprint`), over a
/// horizontal cell `side_m` across at each point: a cell this small (1 µm) reads the point;
/// the others filter every wave.
#[divan::bench(args = [1e-6, 0.1, 1.0], sample_count = 200)]
fn both_fields_over(bencher: divan::Bencher, side_m: f64) {
    let mut texture = testing::statistical(1);
    texture.filter = FieldFilter::Footprint;
    let fields = TextureFields::new(&texture).unwrap();
    let cell = Footprint {
        edges_m: [[side_m, 0.0, 0.0], [0.0, side_m, 0.0]],
    };
    let points = points();
    bencher.counter(ItemsCount::new(POINTS)).bench(|| {
        points
            .iter()
            .map(|&p| {
                let t = fields.sample_over(divan::black_box(p), Some(&cell));
                t.temperature_offset_k + t.emissivity_scale
            })
            .sum::<f64>()
    });
}

#[divan::bench(sample_count = 200)]
fn one_field(bencher: divan::Bencher) {
    let spec = testing::statistical(1).temperature_offset_k.unwrap();
    let field = Field::new(&spec, 1);
    let points = points();
    bencher.counter(ItemsCount::new(POINTS)).bench(|| {
        points
            .iter()
            .map(|&p| field.at(divan::black_box(p)))
            .sum::<f64>()
    });
}

/// Both image maps of the tracer's `frame_1024` map cases (a temperature and an emissivity
/// map on one 256 × 256 image), read at the same points as texture coordinates (one
/// repetition per 4 m, as there) with a footprint of 0.7 texel (`false`: nearest and
/// bilinear) or 3 texels (`true`: both through the footprint filter).
#[divan::bench(args = [false, true], sample_count = 200)]
fn both_maps(bencher: divan::Bencher, footprint: bool) {
    let (declared, image) = testing::maps(footprint);
    let maps = MaterialMaps::new(&declared, |_, _| Ok(image.clone())).unwrap();
    let footprint_uv = if footprint { 3.0 } else { 0.7 } / testing::MAP_SIDE as f64;
    let uvs: Vec<[f64; 2]> = points().iter().map(|p| [p[0] / 4.0, p[1] / 4.0]).collect();
    bencher.counter(ItemsCount::new(POINTS)).bench(|| {
        uvs.iter()
            .map(|&uv| {
                let t = maps.sample_over(divan::black_box(uv), footprint_uv);
                t.temperature_offset_k + t.emissivity_scale
            })
            .sum::<f64>()
    });
}
