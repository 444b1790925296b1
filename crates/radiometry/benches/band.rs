//! Throughput of L(T) (flat band: series; with an SRF: quadrature), of the `.rtt`-style
//! table lookup that can replace it (`RadianceTable`, linear interpolation), of T(L) cold
//! and through the image's inverse table (`InverseTable`, table start and Newton polish),
//! and of the Fresnel generator.

use divan::{Bencher, black_box};
use irsig_radiometry::fresnel::{ComplexIndex, IndexTable, band_emissivity_table};
use irsig_radiometry::{Band, InverseTable, RadianceTable, SensorResponse};

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

/// A finely tabulated 8-14 um response of `rows` rows, jagged as a measured one.
fn fine_srf(rows: usize) -> (Vec<f64>, Vec<f64>) {
    let w = (0..rows)
        .map(|i| 7.9 + 6.2 * i as f64 / (rows - 1) as f64)
        .collect();
    let r = (0..rows)
        .map(|i| 0.5 + 0.4 * (i as f64 * 0.37).sin())
        .collect();
    (w, r)
}

/// Setting a band up from a response table of many rows, what `--band FILE` does once the
/// file is parsed: the table checked, the quadrature made (linear in the rows).
#[divan::bench(args = [10_000, 100_000])]
fn band_setup_from_rows(b: Bencher, rows: usize) {
    let (w, r) = fine_srf(rows);
    b.counter(divan::counter::ItemsCount::new(rows)).bench(|| {
        let srf = SensorResponse::new(w.clone(), r.clone()).unwrap();
        Band::new(7.9, 14.1).unwrap().with_response(&srf).unwrap()
    });
}

/// L(T) with a 100,000-row response: as cheap as with a coarse one.
#[divan::bench]
fn radiance_with_100k_row_srf(b: Bencher) {
    let (w, r) = fine_srf(100_000);
    let srf = SensorResponse::new(w, r).unwrap();
    let band = Band::new(7.9, 14.1).unwrap().with_response(&srf).unwrap();
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

/// T(L) through the inverse table an image's apparent-temperature layer uses (its
/// construction, 256 cold solves, included: what a 1000-pixel image would pay).
#[divan::bench]
fn temperature_flat_8_14_inverse_table(b: Bencher) {
    let band = Band::default();
    let l: Vec<f64> = temps().iter().map(|&t| band.radiance(t)).collect();
    b.counter(divan::counter::ItemsCount::new(l.len()))
        .bench(|| {
            let table = InverseTable::new(&band, &l);
            l.iter()
                .map(|&l| table.temperature(black_box(l)))
                .sum::<f64>()
        });
}

/// The same lookups with the table built once (a large image, where its construction is
/// amortised).
#[divan::bench]
fn temperature_flat_8_14_inverse_table_lookup(b: Bencher) {
    let band = Band::default();
    let l: Vec<f64> = temps().iter().map(|&t| band.radiance(t)).collect();
    let table = InverseTable::new(&band, &l);
    b.counter(divan::counter::ItemsCount::new(l.len()))
        .bench(|| {
            l.iter()
                .map(|&l| table.temperature(black_box(l)))
                .sum::<f64>()
        });
}

fn sample_srf() -> SensorResponse {
    SensorResponse::new(
        vec![7.5, 8.0, 8.5, 9.0, 10.0, 11.0, 11.5, 12.0, 12.5],
        vec![0.0, 0.35, 0.8, 0.95, 1.0, 0.97, 0.85, 0.4, 0.0],
    )
    .unwrap()
}

/// Off-grid temperatures for the table lookups (a lookup on a grid point is not typical).
fn off_grid_temps() -> Vec<f64> {
    (0..1000).map(|i| 250.037 + 0.1 * f64::from(i)).collect()
}

/// Linear interpolation in a 200–400 K table at the step given (K); its cost does not
/// depend on the band, only the table's construction does.
#[divan::bench(args = [0.1, 1.0, 5.0])]
fn rtt_table_lookup(b: Bencher, step_k: f64) {
    let band = Band::default().with_response(&sample_srf()).unwrap();
    let table = RadianceTable::new(&band, 200.0, 400.0, step_k).unwrap();
    let t = off_grid_temps();
    b.counter(divan::counter::ItemsCount::new(t.len()))
        .bench(|| t.iter().map(|&t| table.radiance(black_box(t))).sum::<f64>());
}

/// The exact L(T) at the same off-grid temperatures, for the comparison with the lookup.
#[divan::bench]
fn rtt_exact_flat(b: Bencher) {
    let band = Band::default();
    let t = off_grid_temps();
    b.counter(divan::counter::ItemsCount::new(t.len()))
        .bench(|| t.iter().map(|&t| band.radiance(black_box(t))).sum::<f64>());
}

/// The exact L(T) with the sample SRF (56 Gauss–Legendre nodes).
#[divan::bench]
fn rtt_exact_with_srf(b: Bencher) {
    let band = Band::default().with_response(&sample_srf()).unwrap();
    let t = off_grid_temps();
    b.counter(divan::counter::ItemsCount::new(t.len()))
        .bench(|| t.iter().map(|&t| band.radiance(black_box(t))).sum::<f64>());
}

/// One Fresnel evaluation (both polarisations) for water at 10.5 µm, 91 angles.
#[divan::bench]
fn fresnel_emissivity_91_angles(b: Bencher) {
    let water = ComplexIndex::new(1.185, 0.0662).unwrap();
    b.counter(divan::counter::ItemsCount::new(91_usize))
        .bench(|| {
            (0..=90)
                .map(|a| water.emissivity(black_box(f64::from(a))))
                .sum::<f64>()
        });
}

/// A whole band-averaged water table, 0:90:1, from a 19-row n, k table.
#[divan::bench]
fn fresnel_band_table_water(b: Bencher) {
    let w: Vec<f64> = (0..19).map(|i| 8.0 + f64::from(i) / 3.0).collect();
    let n: Vec<f64> = w.iter().map(|l| 1.3 - 0.01 * l).collect();
    let k: Vec<f64> = w.iter().map(|l| 0.01 * l * l / 10.0).collect();
    let table = IndexTable::new(w, &n, &k).unwrap();
    let angles: Vec<f64> = (0..=90).map(f64::from).collect();
    let band = Band::default();
    b.bench(|| band_emissivity_table(&table, &band, black_box(300.0), &angles).unwrap());
}
