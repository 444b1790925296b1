//! Cost of the spectral built-ins at start-up: decoding one (`builtin_spectral`; a 3–5 µm
//! one, quantised and deflated, `builtin_spectral_mwir`), one collapse over 8–14 µm, and
//! the 64 collapses a spectral tracer makes for 64 sub-bands.

use irsig_atmosphere::{builtin_spectral, builtin_spectral_mwir, collapse};

fn main() {
    divan::main();
}

#[divan::bench]
fn decode_builtin() -> irsig_model::SpectralAtmosphere {
    builtin_spectral(divan::black_box("us-std-1976")).unwrap()
}

#[divan::bench]
fn decode_builtin_mwir() -> irsig_model::SpectralAtmosphere {
    builtin_spectral_mwir(divan::black_box("us-std-1976")).unwrap()
}

#[divan::bench]
fn collapse_8_14(bencher: divan::Bencher) {
    let s = builtin_spectral("us-std-1976").unwrap();
    bencher.bench(|| collapse(divan::black_box(&s), 8.0, 14.0, |_| 1.0).unwrap());
}

#[divan::bench]
fn collapse_64_sub_bands(bencher: divan::Bencher) {
    let s = builtin_spectral("us-std-1976").unwrap();
    bencher.bench(|| {
        (0..64)
            .map(|k| {
                let lo = 8.0 + 6.0 * f64::from(k) / 64.0;
                let hi = 8.0 + 6.0 * f64::from(k + 1) / 64.0;
                collapse(divan::black_box(&s), lo, hi, |_| 1.0)
                    .unwrap()
                    .levels[6]
                    .transmission
            })
            .sum::<f64>()
    });
}
