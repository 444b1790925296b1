//! Detector noise: NEΔT converted to radiance, added as seeded Gaussian noise (§5.2).
//!
//! NEΔT is the change in blackbody temperature that gives a signal equal to the noise, so
//! the noise in radiance is σ_L = NEΔT · dL/dT at the reference temperature the NEΔT is
//! quoted for (300 K is the usual figure of merit).
//!
//! **The seed.** The noise field depends only on the seed and the image size: row `y` draws
//! its values from its own ChaCha8 stream (stream number `y`, key from `seed`), in order
//! along the row. The same seed gives bit-identical noise on every machine and at any
//! number of threads; a different seed gives an independent realisation (use it for
//! frame-to-frame temporal noise); the noise does not depend on the image content.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};
use rayon::prelude::*;

use crate::Plane;
use crate::error::{Result, non_negative, positive};
use irsig_radiometry::BandModel;

/// The radiance noise σ (W m⁻² sr⁻¹) of a sensor with the given NEΔT (K) quoted at
/// `reference_temperature_k`: NEΔT · dL/dT(T_ref).
///
/// # Errors
/// A negative or non-finite NEΔT, a non-positive reference temperature, or a band whose
/// dL/dT there is not positive.
pub fn nedt_radiance_sigma(
    nedt_k: f64,
    reference_temperature_k: f64,
    band: &impl BandModel,
) -> Result<f64> {
    non_negative("nedt_k", nedt_k)?;
    positive("reference_temperature_k", reference_temperature_k)?;
    let slope = positive(
        "dL/dT at the NEdT reference temperature (W m^-2 sr^-1 K^-1)",
        band.radiance_derivative(reference_temperature_k),
    )?;
    Ok(nedt_k * slope)
}

/// Adds zero-mean Gaussian noise of standard deviation `sigma_w_m2_sr` to every pixel,
/// reproducibly from `seed` (see the module documentation for the seed's role).
///
/// # Errors
/// A negative or non-finite σ.
pub fn add_gaussian_noise(image: &mut Plane, sigma_w_m2_sr: f64, seed: u64) -> Result<()> {
    non_negative("noise sigma_w_m2_sr", sigma_w_m2_sr)?;
    if sigma_w_m2_sr == 0.0 {
        return Ok(());
    }
    let w = image.width.max(1);
    image
        .data
        .par_chunks_mut(w)
        .enumerate()
        .for_each(|(y, row)| {
            let mut rng = ChaCha8Rng::seed_from_u64(seed);
            rng.set_stream(y as u64);
            for v in row {
                let z: f64 = StandardNormal.sample(&mut rng);
                *v += sigma_w_m2_sr * z;
            }
        });
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::quantise::tests::SimpsonBand;

    #[test]
    fn sigma_is_nedt_times_the_slope() {
        let band = SimpsonBand;
        let s = nedt_radiance_sigma(0.05, 300.0, &band).unwrap();
        let by_hand = 0.05 * (band.radiance(300.001) - band.radiance(299.999)) / 0.002;
        assert!((s - by_hand).abs() < 1e-6 * by_hand);
        assert!(nedt_radiance_sigma(-0.1, 300.0, &band).is_err());
        assert!(nedt_radiance_sigma(0.1, 0.0, &band).is_err());
    }

    #[test]
    fn noise_has_the_requested_statistics() {
        let mut image = Plane::new(256, 256, vec![30.0; 65536]).unwrap();
        add_gaussian_noise(&mut image, 0.025, 42).unwrap();
        let n = image.data.len() as f64;
        let mean = image.data.iter().sum::<f64>() / n;
        let var = image.data.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
        // Standard errors: σ/√n = 1e-4 for the mean, σ/√(2n) ≈ 7e-5 relative ~0.3 % for σ.
        assert!((mean - 30.0).abs() < 5e-4, "{mean}");
        assert!((var.sqrt() / 0.025 - 1.0).abs() < 0.015, "{}", var.sqrt());
        // Neighbouring pixels and rows are uncorrelated.
        let lag = |dx: usize, dy: usize| {
            let mut acc = 0.0;
            let mut count = 0.0;
            for y in 0..256 - dy {
                for x in 0..256 - dx {
                    acc += (image.data[y * 256 + x] - mean)
                        * (image.data[(y + dy) * 256 + x + dx] - mean);
                    count += 1.0;
                }
            }
            acc / count / var
        };
        assert!(lag(1, 0).abs() < 0.02 && lag(0, 1).abs() < 0.02);
    }

    #[test]
    fn same_seed_same_noise_other_seed_other_noise() {
        let base = Plane::new(33, 17, vec![1.0; 561]).unwrap();
        let noisy = |seed, threads| {
            let mut p = base.clone();
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| add_gaussian_noise(&mut p, 0.5, seed).unwrap());
            p.data
        };
        let a = noisy(7, 1);
        let b = noisy(7, 3);
        assert!(a.iter().zip(&b).all(|(x, y)| x.to_bits() == y.to_bits()));
        let c = noisy(8, 1);
        assert!(
            a.iter()
                .zip(&c)
                .filter(|(x, y)| x.to_bits() == y.to_bits())
                .count()
                < 3
        );
    }
}
