//! Statistical texture in the rendered image: a textured blackbody plate seen straight down
//! in a vacuum, whose apparent temperature is the facet's plus the field's offset at each
//! pixel's point, has the requested σ and correlation length (measured from the image over
//! several seeds); an emissivity field's σ likewise; a specular bounce samples the texture
//! where the reflected ray lands; same seed, same bytes, at any thread count; a texture
//! that varies nothing leaves the image as it was.

use irsig_model::texture::{
    CorrelationLength, FieldFilter, FieldSpectrum, RandomField, StatisticalTexture,
};
use irsig_model::{MaterialLibrary, RawScene, View};
use irsig_radiometry::{BandModel, TotalRadiance};
use irsig_texture::TextureFields;
use irsig_tracer::testing::{grey_materials, ground_quad, primary_directions, raw_scene};
use irsig_tracer::{Camera, TraceOptions, Tracer, Vacuum};

/// The sensor's height above the plate, m.
const HEIGHT_M: f64 = 100.0;
/// Pixels across the image.
const PIXELS: u32 = 256;
/// The full field of view, degrees.
const FOV_DEG: f64 = 20.0;

/// The plate's footprint of one pixel, m: a pinhole's image plane is parallel to the plate,
/// so the footprint is the same everywhere, `2·H·tan(fov/2)/N`.
fn footprint_m() -> f64 {
    pixel_side_m(PIXELS)
}

/// The footprint of one pixel of an image `pixels` across, m.
fn pixel_side_m(pixels: u32) -> f64 {
    2.0 * HEIGHT_M * (FOV_DEG / 2.0).to_radians().tan() / f64::from(pixels)
}

fn nadir_camera(pixels: u32, height_m: f64) -> Camera {
    Camera::from_view(&View::Legacy {
        position_m: [0.0, 0.0, height_m],
        pixels: [pixels, pixels],
        omega_phi_kappa_deg: [0.0, 0.0, 0.0],
        fov_deg: [FOV_DEG, FOV_DEG],
        gain_dc_per_k: None,
    })
    .unwrap()
}

/// A plate wider than the view at z = 0, material 1 at 300 K.
fn plate() -> RawScene {
    raw_scene(&[(&ground_quad([-30.0, -30.0], [30.0, 30.0], 0.0), 1, 300.0)])
}

fn library(emissivity: f64, texture: Option<StatisticalTexture>) -> MaterialLibrary {
    let mut lib = grey_materials(&[(1, emissivity, 0.0)]);
    lib.materials[0].texture = texture;
    lib
}

fn field(sigma: f64, spectrum: FieldSpectrum) -> Option<RandomField> {
    Some(RandomField { sigma, spectrum })
}

fn render(scene: &RawScene, lib: &MaterialLibrary, camera: &Camera) -> Vec<f64> {
    let tracer = Tracer::new(scene, lib, TotalRadiance, Vacuum::default()).unwrap();
    tracer
        .render(camera, &TraceOptions::default(), &|_| {})
        .unwrap()
        .radiance_w_m2_sr
}

/// The image's standard deviation and its correlation lengths along rows and along
/// columns, in pixels: the lag where the mean-removed autocorrelation falls to 1/e,
/// interpolated in ln C between the lags that bracket it.
fn sigma_and_lengths_px(image: &[f64], n: usize) -> (f64, f64, f64) {
    let mean = image.iter().sum::<f64>() / image.len() as f64;
    let d: Vec<f64> = image.iter().map(|v| v - mean).collect();
    let var = d.iter().map(|v| v * v).sum::<f64>() / d.len() as f64;
    let length = |step: (usize, usize)| {
        let c = |lag: usize| {
            let (mut sum, mut count) = (0.0, 0usize);
            for row in 0..n - lag * step.1 {
                for col in 0..n - lag * step.0 {
                    sum += d[row * n + col] * d[(row + lag * step.1) * n + col + lag * step.0];
                    count += 1;
                }
            }
            sum / count as f64 / var
        };
        let target = (-1.0f64).exp();
        let mut previous: f64 = 1.0;
        for lag in 1..n / 2 {
            let now = c(lag);
            if now <= target {
                let (a, b) = (previous.ln(), now.max(1e-12).ln());
                return (lag - 1) as f64 + (a - target.ln()) / (a - b);
            }
            previous = now;
        }
        f64::NAN
    };
    (var.sqrt(), length((1, 0)), length((0, 1)))
}

/// Mean and standard error of the mean.
fn mean_and_error(values: &[f64]) -> (f64, f64) {
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, (var / n).sqrt())
}

/// Renders the temperature field of `spectrum` (σ_T) for seeds 1..=8 and checks the
/// image's σ and its correlation lengths along x (rows) and y (columns) against the
/// requested ones: within three standard errors of the seeds' mean, plus 1 % for what a
/// finite image takes off any estimate of a variance (its mean removed, the correlation
/// over the image is missed: `πℓ²/L²` ≈ 0.2 % here).
fn check_temperature_field(spectrum: &FieldSpectrum, sigma_k: f64) {
    let scene = plate();
    let camera = nadir_camera(PIXELS, HEIGHT_M);
    let (mut sigmas, mut along_x, mut along_y) = (Vec::new(), Vec::new(), Vec::new());
    for seed in 1..=8 {
        let lib = library(
            1.0,
            Some(StatisticalTexture {
                seed,
                temperature_offset_k: field(sigma_k, spectrum.clone()),
                emissivity_scale: None,
                filter: FieldFilter::Point,
            }),
        );
        let radiance = render(&scene, &lib, &camera);
        // ε = 1 in a vacuum: the apparent temperature is the kinetic one.
        let t: Vec<f64> = radiance
            .iter()
            .map(|&l| TotalRadiance.temperature(l))
            .collect();
        let (s, lx, ly) = sigma_and_lengths_px(&t, PIXELS as usize);
        sigmas.push(s);
        along_x.push(lx * footprint_m());
        along_y.push(ly * footprint_m());
    }
    let expected_x = irsig_texture::correlation_length_m(spectrum, [1.0, 0.0, 0.0]);
    let expected_y = irsig_texture::correlation_length_m(spectrum, [0.0, 1.0, 0.0]);
    for (name, values, expected) in [
        ("sigma", &sigmas, sigma_k),
        ("length along x", &along_x, expected_x),
        ("length along y", &along_y, expected_y),
    ] {
        let (mean, error) = mean_and_error(values);
        assert!(
            (mean - expected).abs() <= 3.0 * error + 0.01 * expected,
            "{spectrum:?}: {name} {mean} ± {error}, expected {expected} ({values:?})"
        );
    }
}

#[test]
fn a_gaussian_field_has_the_requested_sigma_and_length() {
    // ℓ = 6 pixels.
    let spectrum = FieldSpectrum::Gaussian {
        correlation_length_m: CorrelationLength::Isotropic(6.0 * footprint_m()),
    };
    check_temperature_field(&spectrum, 1.5);
}

#[test]
fn an_exponential_field_stretched_along_x_has_its_two_lengths() {
    let spectrum = FieldSpectrum::Exponential {
        correlation_length_m: CorrelationLength::PerAxis(
            8.0 * footprint_m(),
            4.0 * footprint_m(),
            1.0,
        ),
    };
    check_temperature_field(&spectrum, 2.0);
}

#[test]
fn a_one_over_f_field_has_the_length_its_range_gives() {
    let spectrum = FieldSpectrum::OneOverF {
        shortest_m: 1.0 * footprint_m(),
        longest_m: 20.0 * footprint_m(),
    };
    check_temperature_field(&spectrum, 0.5);
}

#[test]
fn an_emissivity_field_scales_the_emitted_radiance() {
    // ε = 0.5 before the scale, a vacuum and a cold sky: L = ε·(1 + g)·L_T, so the image
    // divided by 0.5·L_T, less 1, is the field.
    let spectrum = FieldSpectrum::Gaussian {
        correlation_length_m: CorrelationLength::Isotropic(5.0 * footprint_m()),
    };
    let l_t = TotalRadiance.radiance(300.0);
    let mut sigmas = Vec::new();
    for seed in 1..=6 {
        let lib = library(
            0.5,
            Some(StatisticalTexture {
                seed,
                temperature_offset_k: None,
                emissivity_scale: field(0.1, spectrum.clone()),
                filter: FieldFilter::Point,
            }),
        );
        let radiance = render(&plate(), &lib, &nadir_camera(PIXELS, HEIGHT_M));
        let g: Vec<f64> = radiance.iter().map(|l| l / (0.5 * l_t) - 1.0).collect();
        sigmas.push(sigma_and_lengths_px(&g, PIXELS as usize).0);
    }
    let (mean, error) = mean_and_error(&sigmas);
    assert!(
        (mean - 0.1).abs() <= 3.0 * error + 0.001,
        "{mean} ± {error}"
    );
}

#[test]
fn a_mirror_shows_the_texture_where_its_reflection_lands() {
    // A horizontal mirror (ε = 0, specular) at z = 0 and a textured blackbody ceiling at
    // z = 10 m, facing it; the camera at z = 5 m looks down at the mirror. The ray along
    // d = (dx, dy, dz) meets the mirror at (5 dx/−dz, 5 dy/−dz, 0) and, reflected, the
    // ceiling 10 m higher, at 15/−dz along (dx, dy): there the pixel's temperature must be
    // 300 K plus the field's offset.
    let texture = StatisticalTexture {
        seed: 5,
        temperature_offset_k: field(
            2.0,
            FieldSpectrum::Gaussian {
                correlation_length_m: CorrelationLength::Isotropic(0.3),
            },
        ),
        emissivity_scale: None,
        filter: FieldFilter::Point,
    };
    let mirror = ground_quad([-20.0, -20.0], [20.0, 20.0], 0.0);
    let ceiling = ground_quad([-20.0, -20.0], [20.0, 20.0], 10.0);
    let scene = raw_scene(&[(&mirror, 1, 250.0), (&ceiling, 2, 300.0)]);
    let mut lib = grey_materials(&[(1, 0.0, 1.0), (2, 1.0, 0.0)]);
    lib.materials[1].texture = Some(texture.clone());
    let camera = nadir_camera(32, 5.0);
    let radiance = render(&scene, &lib, &camera);
    let fields = TextureFields::new(&texture).unwrap();
    let mut spread: f64 = 0.0;
    for (dir, l) in primary_directions(&camera).iter().zip(&radiance) {
        let t = 15.0 / -dir[2];
        let offset = fields
            .sample([dir[0] * t, dir[1] * t, 10.0])
            .temperature_offset_k;
        let apparent = TotalRadiance.temperature(*l);
        assert!(
            (apparent - (300.0 + offset)).abs() < 1e-6,
            "{apparent} K, expected {}",
            300.0 + offset
        );
        spread = spread.max(offset.abs());
    }
    // The check is not vacuous: the texture does vary over the image.
    assert!(spread > 1.0, "{spread}");
}

fn textured_library(seed: u64) -> MaterialLibrary {
    let spectrum = FieldSpectrum::Exponential {
        correlation_length_m: CorrelationLength::Isotropic(0.7),
    };
    library(
        0.9,
        Some(StatisticalTexture {
            seed,
            temperature_offset_k: field(1.0, spectrum.clone()),
            emissivity_scale: field(0.02, spectrum),
            filter: FieldFilter::Point,
        }),
    )
}

#[test]
fn the_same_seed_gives_the_same_bytes_at_any_thread_count() {
    let scene = plate();
    let camera = nadir_camera(64, HEIGHT_M);
    let a = render(&scene, &textured_library(3), &camera);
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let b = one.install(|| render(&scene, &textured_library(3), &camera));
    let c = render(&scene, &textured_library(4), &camera);
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&a), bits(&b));
    assert_ne!(bits(&a), bits(&c));
}

#[test]
fn a_texture_that_varies_nothing_leaves_the_image_as_it_was() {
    let scene = plate();
    let camera = nadir_camera(32, HEIGHT_M);
    let plain = render(&scene, &library(0.9, None), &camera);
    let flat = StatisticalTexture {
        seed: 9,
        temperature_offset_k: field(
            0.0,
            FieldSpectrum::Gaussian {
                correlation_length_m: CorrelationLength::Isotropic(1.0),
            },
        ),
        emissivity_scale: None,
        filter: FieldFilter::Point,
    };
    let zero = render(&scene, &library(0.9, Some(flat)), &camera);
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&plain), bits(&zero));
}

#[test]
fn a_texture_with_a_bad_sigma_is_refused() {
    let mut lib = textured_library(1);
    if let Some(t) = lib.materials[0].texture.as_mut() {
        t.temperature_offset_k = field(
            f64::NAN,
            FieldSpectrum::Gaussian {
                correlation_length_m: CorrelationLength::Isotropic(1.0),
            },
        );
    }
    let e = Tracer::new(&plate(), &lib, TotalRadiance, Vacuum::default()).unwrap_err();
    assert!(
        e.to_string().contains("texture.temperature_offset_k.sigma"),
        "{e}"
    );
}

/// A temperature field with the footprint filter, `length_m` long (Gaussian), σ 2 K.
fn filtered(seed: u64, length_m: f64, filter: FieldFilter) -> StatisticalTexture {
    StatisticalTexture {
        seed,
        temperature_offset_k: field(
            2.0,
            FieldSpectrum::Gaussian {
                correlation_length_m: CorrelationLength::Isotropic(length_m),
            },
        ),
        emissivity_scale: None,
        filter,
    }
}

#[test]
fn with_the_footprint_filter_a_pixel_shows_the_fields_mean_over_its_ground_cell() {
    // Straight down on the plate, a field five times finer than a pixel. A pinhole's image
    // plane is parallel to the plate, so each pixel's cell on it is a square
    // `pixel_side_m` across, centred where its centre ray lands: the field's mean over it,
    // by the midpoint rule on 200 × 200 points of the field itself, is what the pixel must
    // show (ε = 1, a vacuum: the apparent temperature is 300 K plus the offset).
    let side = pixel_side_m(64);
    let texture = filtered(21, side / 5.0, FieldFilter::Footprint);
    let camera = nadir_camera(64, HEIGHT_M);
    let radiance = render(&plate(), &library(1.0, Some(texture.clone())), &camera);
    let fields = TextureFields::new(&texture).unwrap();
    let n = 200;
    let (mut worst, mut aliased): (f64, f64) = (0.0, 0.0);
    let directions = primary_directions(&camera);
    for pixel in (0..directions.len()).step_by(97) {
        let dir = directions[pixel];
        let centre = [dir[0], dir[1]].map(|c| c * HEIGHT_M / -dir[2]);
        let mut sum = 0.0;
        for i in 0..n {
            for j in 0..n {
                let s = ((f64::from(i) + 0.5) / f64::from(n) - 0.5) * side;
                let t = ((f64::from(j) + 0.5) / f64::from(n) - 0.5) * side;
                let p = [centre[0] + s, centre[1] + t, 0.0];
                sum += fields.sample(p).temperature_offset_k;
            }
        }
        let mean = sum / f64::from(n * n);
        let apparent = TotalRadiance.temperature(radiance[pixel]);
        worst = worst.max((apparent - (300.0 + mean)).abs());
        let point = fields
            .sample([centre[0], centre[1], 0.0])
            .temperature_offset_k;
        aliased = aliased.max((point - mean).abs());
    }
    assert!(worst < 1e-3, "{worst} K");
    // Not vacuous: the point the ray hits is far from the pixel's mean.
    assert!(aliased > 1.0, "{aliased} K");
}

/// The standard deviation of a Gaussian field's (`C = exp(−r²/ℓ²)`) mean over squares `a`
/// across, as a fraction of the field's: `C` separates, so the variance is the square of
/// the mean of `exp(−(x − y)²/ℓ²)` over a segment `α = a/ℓ` long, `(2/α²)∫₀^α (α − u)
/// exp(−u²) du = (2/α²)(α·(√π/2)·erf α − (1 − exp(−α²))/2)`.
fn box_sigma_fraction(alpha: f64) -> f64 {
    2.0 / (alpha * alpha)
        * (alpha * std::f64::consts::PI.sqrt() / 2.0 * libm::erf(alpha)
            - (1.0 - (-alpha * alpha).exp()) / 2.0)
}

#[test]
fn a_field_finer_than_a_pixel_keeps_only_the_spread_of_pixel_means() {
    // ℓ a fifth of a pixel: with the footprint filter the image's σ is that of the field's
    // means over pixel squares, 0.31 σ (not the field's σ, which the point filter shows:
    // aliasing), over 8 seeds within three standard errors and 3 % (a 32-wave realisation
    // holds its spectrum only so closely).
    let camera = nadir_camera(128, HEIGHT_M);
    let expected = 2.0 * box_sigma_fraction(5.0);
    assert!((expected / 2.0 - 0.3145).abs() < 1e-3);
    for (filter, want) in [
        (FieldFilter::Footprint, expected),
        (FieldFilter::Point, 2.0),
    ] {
        let mut sigmas = Vec::new();
        for seed in 1..=8 {
            let lib = library(1.0, Some(filtered(seed, pixel_side_m(128) / 5.0, filter)));
            let t: Vec<f64> = render(&plate(), &lib, &camera)
                .iter()
                .map(|&l| TotalRadiance.temperature(l))
                .collect();
            sigmas.push(sigma_and_lengths_px(&t, 128).0);
        }
        let (mean, error) = mean_and_error(&sigmas);
        assert!(
            (mean - want).abs() <= 3.0 * error + 0.03 * want,
            "{filter:?}: {mean} ± {error} K, expected {want} K"
        );
    }
}
