//! Prints the radiometry tables of `docs/accuracy.md` ("Speed and accuracy trades"):
//! quadrature nodes against error for the band radiance with a response and for the
//! hemispherical emissivity, the `.rtt` interpolation error, and the Fresnel generator
//! against the shared water reference and against a constant index.
//!
//! `cargo run --release -p irsig-radiometry --example radiometry_accuracy`
//!
//! Every reference here is computed independently of the code under test: the flat-band
//! Planck series against a response table that is flat, composite Simpson on a 1e-4 µm
//! grid with its own CODATA constants, Dunkle's closed-form hemispherical emissivity.

use irsig_radiometry::fresnel::{
    ComplexIndex, band_emissivity_table, band_mean_index, emissivity_table,
};
use irsig_radiometry::{Band, RadianceTable, SensorResponse};

#[path = "../tests/common/water.rs"]
mod water;
use water::{dunkle_hemispherical, water};

const H: f64 = 6.626_070_15e-34;
const C: f64 = 299_792_458.0;
const K: f64 = 1.380_649e-23;

/// Planck spectral radiance, W m^-2 sr^-1 µm^-1.
fn planck_um(lambda_um: f64, t_k: f64) -> f64 {
    let l = lambda_um * 1e-6;
    2.0 * H * C * C / l.powi(5) / (H * C / (l * K * t_k)).exp_m1() * 1e-6
}

/// Composite Simpson of `srf · B` on each linear piece of the response, 1e-4 µm steps.
fn simpson_band(srf: &SensorResponse, lo: f64, hi: f64, t_k: f64) -> f64 {
    let mut total = 0.0;
    for w in srf.wavelength_um().windows(2) {
        let (a, b) = (w[0].max(lo), w[1].min(hi));
        if b <= a {
            continue;
        }
        let n = (((b - a) / 1e-4).ceil() as usize).next_multiple_of(2);
        let h = (b - a) / n as f64;
        let f = |x: f64| srf.at(x) * planck_um(x, t_k);
        let mut s = f(a) + f(b);
        for i in 1..n {
            s += if i % 2 == 1 { 4.0 } else { 2.0 } * f(a + h * i as f64);
        }
        total += s * h / 3.0;
    }
    total
}

fn main() {
    quadrature_nodes();
    hemispherical_nodes();
    rtt_interpolation();
    fresnel_water();
}

fn quadrature_nodes() {
    let temps: Vec<f64> = [
        50.0, 100.0, 200.0, 250.0, 300.0, 350.0, 500.0, 1000.0, 3000.0,
    ]
    .to_vec();
    println!("## Band radiance with a response: Gauss-Legendre nodes against error");
    println!("max relative error over T = {temps:?} K");
    println!();
    println!(
        "| nodes per piece | max piece | nodes, flat 8-14 table | max rel. error vs series | nodes, sample 8-12 SRF | max rel. error vs Simpson |"
    );
    println!("| ---: | ---: | ---: | ---: | ---: | ---: |");
    let flat = SensorResponse::new(vec![8.0, 14.0], vec![1.0, 1.0]).unwrap();
    let sample = SensorResponse::new(
        vec![7.5, 8.0, 8.5, 9.0, 10.0, 11.0, 11.5, 12.0, 12.5],
        vec![0.0, 0.35, 0.8, 0.95, 1.0, 0.97, 0.85, 0.4, 0.0],
    )
    .unwrap();
    let series = Band::default();
    let sample_reference: Vec<f64> = temps
        .iter()
        .map(|&t| simpson_band(&sample, 8.0, 14.0, t))
        .collect();
    for (nodes, piece) in [
        (1, 1.0),
        (2, 1.0),
        (3, 1.0),
        (4, 1.0),
        (6, 1.0),
        (8, 1.0),
        (12, 1.0),
        (16, 1.0),
        (8, 0.5),
        (8, 0.25),
    ] {
        let a = Band::default()
            .with_response_quadrature(&flat, nodes, piece)
            .unwrap();
        let b = Band::default()
            .with_response_quadrature(&sample, nodes, piece)
            .unwrap();
        let ea = temps
            .iter()
            .map(|&t| (a.radiance(t) / series.radiance(t) - 1.0).abs())
            .fold(0.0, f64::max);
        let eb = temps
            .iter()
            .zip(&sample_reference)
            .map(|(&t, &r)| (b.radiance(t) / r - 1.0).abs())
            .fold(0.0, f64::max);
        let default = if nodes == 8 && (piece - 1.0_f64).abs() < 1e-12 {
            " (default)"
        } else {
            ""
        };
        println!(
            "| {nodes}{default} | {piece} um | {} | {ea:.1e} | {} | {eb:.1e} |",
            a.quadrature_nodes(),
            b.quadrature_nodes()
        );
    }
    // Where the default rule stands at low temperature.
    let b = Band::default().with_response(&flat).unwrap();
    let c = Band::default().with_response(&sample).unwrap();
    for t in [10.0, 20.0, 30.0, 50.0] {
        println!(
            "default rule at {t} K: relative error {:.1e} (flat table), {:.1e} (sample SRF)",
            (b.radiance(t) / series.radiance(t) - 1.0).abs(),
            (c.radiance(t) / simpson_band(&sample, 8.0, 14.0, t) - 1.0).abs()
        );
    }
    println!();
}

fn hemispherical_nodes() {
    println!("## Hemispherical emissivity (eq. 5 form) against the angular table's nodes");
    println!(
        "EmissivityTable::hemispherical integrates the linear interpolant exactly; the error is the table's"
    );
    println!();
    println!(
        "| angles | rows | n = 1.333: error | n = 4: error | water band table (vs 0.01 deg table) |"
    );
    println!("| --- | ---: | ---: | ---: | ---: |");
    let water = water();
    let fine: Vec<f64> = (0..=9000).map(|i| f64::from(i) * 0.01).collect();
    let water_fine = band_emissivity_table(&water, &Band::default(), 300.0, &fine)
        .unwrap()
        .hemispherical();
    let grids: Vec<(&str, Vec<f64>)> = vec![
        (
            "0:90:10 (the thesis's 10 angles)",
            (0..=9).map(|i| f64::from(i) * 10.0).collect(),
        ),
        ("0:90:5", (0..=18).map(|i| f64::from(i) * 5.0).collect()),
        ("0:89:1 (no 90 deg row)", (0..=89).map(f64::from).collect()),
        ("0:90:2", (0..=45).map(|i| f64::from(i) * 2.0).collect()),
        (
            "0:90:1 (the tool's default)",
            (0..=90).map(f64::from).collect(),
        ),
        ("0:90:0.5", (0..=180).map(|i| f64::from(i) * 0.5).collect()),
        ("0:90:0.1", (0..=900).map(|i| f64::from(i) * 0.1).collect()),
    ];
    for (label, angles) in grids {
        let err = |n: f64| {
            emissivity_table(ComplexIndex::new(n, 0.0).unwrap(), &angles)
                .unwrap()
                .hemispherical()
                - dunkle_hemispherical(n)
        };
        let w = band_emissivity_table(&water, &Band::default(), 300.0, &angles)
            .unwrap()
            .hemispherical()
            - water_fine;
        println!(
            "| {label} | {} | {:+.1e} | {:+.1e} | {w:+.1e} |",
            angles.len(),
            err(1.333),
            err(4.0)
        );
    }
    println!("water band hemispherical emissivity (0.01 deg table): {water_fine:.6}");
    println!();
}

fn rtt_interpolation() {
    println!("## RTT linear interpolation against exact L(T), error in K");
    println!();
    println!("| step | max error, 200-350 K | max error, 100-1000 K |");
    println!("| --- | ---: | ---: |");
    let band = Band::default();
    for step in [0.1, 1.0, 5.0] {
        let worst = |from: f64, to: f64| {
            let table = RadianceTable::new(&band, from, to, step).unwrap();
            let samples = 200_000;
            (0..samples)
                .map(|i| {
                    let t = from + (to - from) * (f64::from(i) + 0.5) / f64::from(samples);
                    let (l, dl) = band.radiance_and_derivative(t);
                    (table.radiance(t) - l) / dl
                })
                .fold(0.0, f64::max)
        };
        println!(
            "| {step} K | {:.1e} K | {:.1e} K |",
            worst(200.0, 350.0),
            worst(100.0, 1000.0)
        );
    }
    println!();
}

fn fresnel_water() {
    println!("## Fresnel: water (Hale & Querry 1973), 8-14 um, Planck weighting at 300 K");
    let reference_path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../formats/legacy/samples/water-hale-querry.ems"
    );
    let reference: Vec<(f64, f64)> = std::fs::read_to_string(reference_path)
        .unwrap()
        .lines()
        .map(|l| {
            let (a, e) = l.split_once(' ').unwrap();
            (a.parse().unwrap(), e.parse().unwrap())
        })
        .collect();
    let angles: Vec<f64> = reference.iter().map(|r| r.0).collect();
    let band = Band::default();
    let water = water();
    let ours = band_emissivity_table(&water, &band, 300.0, &angles).unwrap();
    let worst = ours
        .emissivity()
        .iter()
        .zip(&reference)
        .map(|(a, b)| (a - b.1).abs())
        .fold(0.0, f64::max);
    println!("max |generated - shared reference .ems| over 0-90 deg (5 deg): {worst:.1e}");
    let l300 = band.radiance(300.0);
    let kelvin = |e_const: f64, e_band: f64| {
        band.temperature(e_const * l300) - band.temperature(e_band * l300)
    };
    let mean = band_mean_index(&water, &band, 300.0).unwrap();
    println!(
        "Planck-weighted mean index: n = {:.4}, k = {:.4}",
        mean.n(),
        mean.k()
    );
    let fine: Vec<f64> = (0..=90).map(f64::from).collect();
    let banded = band_emissivity_table(&water, &band, 300.0, &fine).unwrap();
    println!();
    println!(
        "| constant index instead of the table | eps(0) | error at 0 deg | max error 0-60 deg | max error 0-85 deg | error at 0 deg, K (300 K, emitted) | hemispherical error |"
    );
    println!("| --- | ---: | ---: | ---: | ---: | ---: | ---: |");
    println!(
        "| (the band-averaged table) | {:.6} | | | | | ({:.5}) |",
        banded.emissivity()[0],
        banded.hemispherical()
    );
    let cases = [
        ("10.5 um point (1.185 + 0.0662i)", water.at(10.5)),
        ("band centre 11 um (1.153 + 0.0968i)", water.at(11.0)),
        ("Planck-weighted mean n, k", mean),
    ];
    for (label, index) in cases {
        let constant = emissivity_table(index, &fine).unwrap();
        let diff: Vec<f64> = constant
            .emissivity()
            .iter()
            .zip(banded.emissivity())
            .map(|(a, b)| a - b)
            .collect();
        let max_to = |deg: usize| {
            diff[..=deg]
                .iter()
                .fold(0.0_f64, |m, d| if d.abs() > m.abs() { *d } else { m })
        };
        println!(
            "| {label} | {:.6} | {:+.5} | {:+.5} | {:+.5} | {:+.2} K | {:+.5} |",
            constant.emissivity()[0],
            diff[0],
            max_to(60),
            max_to(85),
            kelvin(constant.emissivity()[0], banded.emissivity()[0]),
            constant.hemispherical() - banded.hemispherical()
        );
    }
}
