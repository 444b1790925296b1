//! Cost of one `path()` call per atmosphere model, over a spread of geometries like a
//! tracer's (sensor 1 km up, targets at the ground and up to 30 m, nadir 0–88°).

use irsig_atmosphere::{AtmosphereModel, ModelKind, builtin};

fn main() {
    divan::main();
}

fn geometries() -> Vec<(f64, f64, f64)> {
    (0..256)
        .map(|i| {
            let angle = (f64::from(i) * 88.0 / 255.0).to_radians();
            let target = f64::from(i % 4) * 10.0;
            (1000.0, target, (1000.0 - target) / angle.cos())
        })
        .collect()
}

#[divan::bench(args = ["none", "thesis", "layered", "table"])]
fn path(bencher: divan::Bencher, kind: &str) {
    let atm = builtin("us-std-1976").unwrap();
    let model = AtmosphereModel::new(&atm, kind.parse::<ModelKind>().unwrap()).unwrap();
    let g = geometries();
    bencher
        .counter(divan::counter::ItemsCount::new(g.len()))
        .bench(|| {
            let mut acc = 0.0;
            for &(s, t, r) in &g {
                let p = model.path(divan::black_box(s), t, r);
                acc += p.transmission + p.path_radiance_w_m2_sr;
            }
            acc
        });
}

/// What each further sub-band pays for a path once it is located
/// ([`AtmosphereModel::path_along`]): a spectral rendering locates a path once and
/// evaluates it in every sub-band.
#[divan::bench(args = ["none", "thesis", "layered", "table"])]
fn path_along_located(bencher: divan::Bencher, kind: &str) {
    let atm = builtin("us-std-1976").unwrap();
    let model = AtmosphereModel::new(&atm, kind.parse::<ModelKind>().unwrap()).unwrap();
    let located: Vec<_> = geometries()
        .iter()
        .map(|&(s, t, r)| model.locate_path(s, t, r))
        .collect();
    bencher
        .counter(divan::counter::ItemsCount::new(located.len()))
        .bench(|| {
            let mut acc = 0.0;
            for g in &located {
                let p = model.path_along(divan::black_box(g));
                acc += p.transmission + p.path_radiance_w_m2_sr;
            }
            acc
        });
}

#[divan::bench(args = ["thesis", "layered", "table"])]
fn sky_view_lookup(bencher: divan::Bencher, kind: &str) {
    let atm = builtin("us-std-1976").unwrap();
    let model = AtmosphereModel::new(&atm, kind.parse::<ModelKind>().unwrap()).unwrap();
    let view = model.sky_view(1000.0);
    bencher
        .counter(divan::counter::ItemsCount::new(256usize))
        .bench(|| {
            (0..256)
                .map(|i| view.radiance(divan::black_box(f64::from(i) * 0.35)))
                .sum::<f64>()
        });
}
