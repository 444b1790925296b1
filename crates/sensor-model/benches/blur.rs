//! FFT blur with a cascaded MTF (optics × detector × motion × jitter) at 512², 1024² and
//! 4096² (the floor: 4096² under 1 s), plus quantisation and noise at 1024².

use irsig_sensor_model::Plane;
use irsig_sensor_model::blur::{EdgeMode, Precision, blur, blur_with_precision};
use irsig_sensor_model::mtf::{Mtf, MtfChain};
use irsig_sensor_model::noise::add_gaussian_noise;
use irsig_sensor_model::quantise::Quantiser;

fn main() {
    divan::main();
}

fn cascade() -> MtfChain {
    MtfChain::new(vec![
        Mtf::Diffraction {
            wavelength_m: 10e-6,
            f_number: 1.0,
            pixel_pitch_m: 17e-6,
        },
        Mtf::Footprint {
            width_px: 1.0,
            height_px: 1.0,
        },
        Mtf::Motion {
            length_px: 1.5,
            angle_deg: 30.0,
        },
        Mtf::Jitter {
            sigma_x_px: 0.25,
            sigma_y_px: 0.25,
        },
    ])
}

fn scene(n: usize) -> Plane {
    // Stripes and a ramp: any content costs the same; this just is not constant.
    let data = (0..n * n)
        .map(|i| 30.0 + ((i % n) / 7 % 2) as f64 * 5.0 + (i / n) as f64 * 1e-3)
        .collect();
    Plane::new(n, n, data).unwrap()
}

#[divan::bench(args = [512, 1024, 4096], sample_count = 3, sample_size = 1)]
fn fft_blur_cascade_reflect(bencher: divan::Bencher, n: usize) {
    let image = scene(n);
    let chain = cascade();
    bencher.bench(|| blur(&image, &chain, EdgeMode::Reflect, 1).unwrap());
}

#[divan::bench(args = [512, 1024, 4096], sample_count = 3, sample_size = 1)]
fn fft_blur_cascade_reflect_single(bencher: divan::Bencher, n: usize) {
    let image = scene(n);
    let chain = cascade();
    bencher.bench(|| {
        blur_with_precision(&image, &chain, EdgeMode::Reflect, 1, Precision::Single).unwrap()
    });
}

#[divan::bench(args = [1024, 4096], sample_count = 3, sample_size = 1)]
fn fft_blur_thesis_box_wrap(bencher: divan::Bencher, n: usize) {
    let image = scene(n);
    let chain = MtfChain::new(vec![Mtf::Box {
        width_px: 5,
        height_px: 5,
    }]);
    bencher.bench(|| blur(&image, &chain, EdgeMode::Wrap, 1).unwrap());
}

#[divan::bench(sample_count = 5)]
fn noise_1024(bencher: divan::Bencher) {
    let image = scene(1024);
    bencher.bench(|| {
        let mut p = image.clone();
        add_gaussian_noise(&mut p, 0.05, 1).unwrap();
        p
    });
}

#[divan::bench(sample_count = 5)]
fn quantise_1024(bencher: divan::Bencher) {
    let image = scene(1024).to_f32();
    let q = Quantiser::from_gain_offset(14, 500.0, -10_000.0).unwrap();
    bencher.bench(|| q.quantise(&image, 1024).unwrap());
}
