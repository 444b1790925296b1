//! Throughput of L(T) (flat band: series; with an SRF: quadrature) and of T(L).

use divan::{Bencher, black_box};
use irsig_radiometry::{Band, SensorResponse};

fn main() {
    divan::main();
}

fn temps() -> Vec<f64> {
    (0..1000).map(|i| 250.0 + 0.1 * f64::from(i)).collect()
}

#[divan::bench]
fn radiance_flat_8_14(b: Bencher) {
    let band = Band::default();
    let t = temps();
    b.counter(divan::counter::ItemsCount::new(t.len()))
        .bench(|| t.iter().map(|&t| band.radiance(black_box(t))).sum::<f64>());
}

#[divan::bench]
fn radiance_with_srf(b: Bencher) {
    let srf = SensorResponse::new(
        vec![7.5, 8.0, 8.5, 9.0, 10.0, 11.0, 11.5, 12.0, 12.5],
        vec![0.0, 0.35, 0.8, 0.95, 1.0, 0.97, 0.85, 0.4, 0.0],
    )
    .unwrap();
    let band = Band::default().with_response(&srf).unwrap();
    let t = temps();
    b.counter(divan::counter::ItemsCount::new(t.len()))
        .bench(|| t.iter().map(|&t| band.radiance(black_box(t))).sum::<f64>());
}

#[divan::bench]
fn temperature_flat_8_14(b: Bencher) {
    let band = Band::default();
    let l: Vec<f64> = temps().iter().map(|&t| band.radiance(t)).collect();
    b.counter(divan::counter::ItemsCount::new(l.len()))
        .bench(|| {
            l.iter()
                .map(|&l| band.temperature(black_box(l)))
                .sum::<f64>()
        });
}
