//! What the PNG files cost: a 1024 × 1024 8-bit count image (the tracer's and the sensor's
//! `dc.png`) and its colour preview, encoded at the png crate's three compression levels
//! (through the image crate, which `irsig_raster`'s writers use at `Fast`). Smooth fields,
//! a few hard edges and a little deterministic noise, as a rendered thermal frame.
//! `cargo bench -p irsig-raster --bench png`; the sizes are printed first. BENCHMARKS.md
//! reports both.

use std::io::Cursor;

use image::ImageEncoder;
use image::codecs::png::{CompressionType, FilterType, PngEncoder};

const SIZE: usize = 1024;
const LEVELS: [(&str, CompressionType); 3] = [
    ("fast", CompressionType::Fast),
    ("default", CompressionType::Default),
    ("best", CompressionType::Best),
];

fn main() {
    let (gray, rgb) = (counts(), colour());
    for (name, level) in LEVELS {
        println!(
            "{name:>8}: counts {} bytes, colour {} bytes (raw {} and {})",
            encode(&gray, image::ExtendedColorType::L8, level).len(),
            encode(&rgb, image::ExtendedColorType::Rgb8, level).len(),
            gray.len(),
            rgb.len()
        );
    }
    divan::main();
}

/// Counts of a scene: a smooth 280–300 K ground at 4 counts per kelvin, a hot and a cold
/// block with hard edges, and ±1 count of noise.
fn counts() -> Vec<u8> {
    (0..SIZE * SIZE)
        .map(|i| {
            let (x, y) = ((i % SIZE) as f32, (i / SIZE) as f32);
            let mut h = (i as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15);
            h ^= h >> 31;
            let noise = (h & 3) as f32 - 1.5;
            let mut t = 290.0 + 10.0 * ((x * 0.01).sin() * (y * 0.013).cos());
            if (300.0..500.0).contains(&x) && (200.0..400.0).contains(&y) {
                t = 320.0;
            }
            if (600.0..900.0).contains(&x) && (700.0..800.0).contains(&y) {
                t = 265.0;
            }
            ((t - 260.0) * 4.0 + noise).clamp(0.0, 255.0) as u8
        })
        .collect()
}

/// The counts through a simple colour ramp, as the colour preview.
fn colour() -> Vec<u8> {
    counts()
        .into_iter()
        .flat_map(|c| [c, 255 - c, c / 2])
        .collect()
}

fn encode(data: &[u8], colour: image::ExtendedColorType, level: CompressionType) -> Vec<u8> {
    let mut out = Vec::new();
    PngEncoder::new_with_quality(Cursor::new(&mut out), level, FilterType::Adaptive)
        .write_image(data, SIZE as u32, SIZE as u32, colour)
        .unwrap();
    out
}

#[divan::bench(args = ["fast", "default", "best"], sample_count = 10)]
fn counts_1024(bencher: divan::Bencher, level: &str) {
    let data = counts();
    let level = LEVELS.iter().find(|(n, _)| *n == level).unwrap().1;
    bencher.bench(|| encode(divan::black_box(&data), image::ExtendedColorType::L8, level));
}

#[divan::bench(args = ["fast", "default", "best"], sample_count = 10)]
fn colour_1024(bencher: divan::Bencher, level: &str) {
    let data = colour();
    let level = LEVELS.iter().find(|(n, _)| *n == level).unwrap().1;
    bencher.bench(|| {
        encode(
            divan::black_box(&data),
            image::ExtendedColorType::Rgb8,
            level,
        )
    });
}
