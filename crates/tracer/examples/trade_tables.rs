//! Prints the tables of docs/accuracy.md's tracer section: the sky-view factor's error
//! against its ray count (exact configuration factor, Howell B-3) and the supersampling's
//! edge-pixel error against N (exact pixel-area coverage), over several seeds.
//!
//! `cargo run --release -p irsig-tracer --example trade_tables`

use irsig_radiometry::{BandModel, TotalRadiance};
use irsig_tracer::testing::{EdgeExperiment, PitExperiment};

fn stats(errors: &[f64]) -> (f64, f64, f64) {
    let n = errors.len() as f64;
    let rms = (errors.iter().map(|e| e * e).sum::<f64>() / n).sqrt();
    let max = errors.iter().fold(0.0_f64, |m, e| m.max(e.abs()));
    let mean = errors.iter().sum::<f64>() / n;
    (rms, max, mean)
}

fn main() {
    let seeds = 0..8_u64;
    let pit = PitExperiment::new();
    println!(
        "Sky-view factor at the centre of a square pit (2 m wide, 1 m deep): exact F = {:.6}",
        pit.exact_sky_view_factor
    );
    println!("Apparent-temperature error: floor ε 0.9 at 300 K, walls 300 K, sky 250 K");
    println!(
        "| rays N | RMS F error | max F error | mean F error | RMS error (K) | max error (K) |"
    );
    println!("|---:|---:|---:|---:|---:|---:|");
    let t_exact = TotalRadiance.temperature(pit.exact_radiance_w_m2_sr);
    for rays in [4, 16, 64, 256, 1024] {
        let est: Vec<(f64, f64)> = seeds.clone().flat_map(|s| pit.estimates(rays, s)).collect();
        let f_err: Vec<f64> = est
            .iter()
            .map(|(f, _)| f - pit.exact_sky_view_factor)
            .collect();
        let k_err: Vec<f64> = est
            .iter()
            .map(|(_, l)| TotalRadiance.temperature(*l) - t_exact)
            .collect();
        let (rms, max, mean) = stats(&f_err);
        let (krms, kmax, _) = stats(&k_err);
        println!("| {rays} | {rms:.5} | {max:.5} | {mean:+.6} | {krms:.4} | {kmax:.4} |");
    }
    println!();
    let edge = EdgeExperiment::new();
    let [hot, cold] = EdgeExperiment::TEMPERATURES_K.map(|t| TotalRadiance.radiance(t));
    println!(
        "Edge pixels between 330 K and 300 K blackbody facets (contrast {:.3} W m-2 sr-1)",
        hot - cold
    );
    println!(
        "| N×N | edge pixels | RMS error (of contrast) | max error (of contrast) | RMS error (K) | max error (K) |"
    );
    println!("|---:|---:|---:|---:|---:|---:|");
    for n in [1, 2, 4, 8, 16] {
        let px: Vec<(f64, f64)> = seeds.clone().flat_map(|s| edge.edge_pixels(n, s)).collect();
        let c: Vec<f64> = px.iter().map(|(e, l)| (l - e) / (hot - cold)).collect();
        let k: Vec<f64> = px
            .iter()
            .map(|(e, l)| TotalRadiance.temperature(*l) - TotalRadiance.temperature(*e))
            .collect();
        let (rms, max, _) = stats(&c);
        let (krms, kmax, _) = stats(&k);
        println!(
            "| {n} | {} | {rms:.5} | {max:.5} | {krms:.4} | {kmax:.4} |",
            px.len() / 8
        );
    }
}
