//! What a view path costs through the slab tables against the models they replace: the
//! path terms (`PrecomputedAtmosphere::path`, `table` model) and the scattered sunlight
//! (the difference of two paths, `ScatteredSunlight::path`, against
//! `SlabPaths::scattered`), ns per call, for paths from an observer of the file's slabs
//! to targets between its rows. docs/accuracy.md ("Slab tables") quotes it.
//!
//! `cargo run --release -p irsig-atmosphere --example slab_cost -- FILE.spa LO_UM HI_UM`

use std::hint::black_box;
use std::time::Instant;

use irsig_atmosphere::scattered::ScatteredSunlight;
use irsig_atmosphere::slab::SlabPaths;
use irsig_atmosphere::{AtmosphereModel, ModelKind, PrecomputedAtmosphere, collapse};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let [_, file, lo, hi] = args.as_slice() else {
        eprintln!("usage: slab_cost FILE.spa LO_UM HI_UM");
        std::process::exit(2);
    };
    let (lo, hi): (f64, f64) = (lo.parse().unwrap(), hi.parse().unwrap());
    let bytes = std::fs::read(file).unwrap();
    let spectral = irsig_formats::canonical::binary_spectral::decode(file, &bytes).unwrap();
    let slab = spectral
        .slabs
        .iter()
        .find(|s| s.down.is_some())
        .expect("an atmosphere with slabs down from an observer");
    let down = slab.down.as_ref().expect("slabs down");
    let o = slab.observer_m;
    let (t_lo, t_hi) = (down.target_m[0], o);
    let (a_lo, a_hi) = (down.angle_deg[0], down.angle_deg[down.angle_deg.len() - 1]);
    let band = collapse(&spectral, lo, hi, |_| 1.0).unwrap();
    let model = AtmosphereModel::new(&band, ModelKind::Table).unwrap();
    let plain = PrecomputedAtmosphere::new(model, 1000.0);
    let slabs = SlabPaths::new(&spectral, lo, hi, |_| 1.0).unwrap().unwrap();
    let with = plain.clone().with_slabs(slabs.clone());
    // Paths between the rows: targets and nadir angles on a 100 × 100 grid inside them.
    let n: u32 = 100;
    let paths: Vec<(f64, f64, [f64; 3])> = (0..n * n)
        .map(|k| {
            let t = t_lo + (t_hi - t_lo) * (f64::from(k / n) + 0.5) / f64::from(n);
            let a = (a_lo + (a_hi - a_lo) * (f64::from(k % n) + 0.5) / f64::from(n)).to_radians();
            let range = (o - t) / a.cos();
            (t, range, [a.sin(), 0.0, -a.cos()])
        })
        .collect();
    let time = |name: &str, f: &dyn Fn(f64, f64, [f64; 3]) -> f64| {
        let rounds = 20;
        let start = Instant::now();
        let mut sum = 0.0;
        for _ in 0..rounds {
            for &(t, r, d) in &paths {
                sum += f(black_box(t), black_box(r), black_box(d));
            }
        }
        let ns = start.elapsed().as_nanos() as f64 / (rounds * paths.len()) as f64;
        println!("{name}: {ns:.0} ns per path (sum {sum:.6e})");
    };
    time("path terms, table model", &|t, r, _| {
        plain.path(o, t, r).path_radiance_w_m2_sr
    });
    time("path terms, slab tables", &|t, r, _| {
        with.path(o, t, r).path_radiance_w_m2_sr
    });
    if spectral
        .solar
        .as_ref()
        .is_some_and(|s| !s.relative_azimuth_deg.is_empty())
    {
        let to_sun = [0.5_f64, 0.0, 0.75_f64.sqrt()];
        let scattered = ScatteredSunlight::new(&spectral, lo, hi, |_| 1.0, to_sun).unwrap();
        time("scattered, difference of two paths", &|t, _, d| {
            scattered.path(o, t, 0.9, d)
        });
        time("scattered, slab tables", &|t, _, d| {
            let c = slabs.covers_along(o, t, d[2]).unwrap();
            slabs
                .scattered(&c, scattered.relative_azimuth_deg(d))
                .unwrap()
        });
    }
}
