//! What every consumer of a band needs from it: blackbody radiance, its derivative and its
//! inverse. The tracer shades with it, the sensor stage quantises and adds noise with it,
//! and the apparent temperature everywhere comes from it, so it is defined once, here.

use rayon::prelude::*;

use crate::band::Band;
use crate::constants::{BOLTZMANN_J_K, PLANCK_J_S, SPEED_OF_LIGHT_M_S};
use crate::inverse::InverseTable;

/// Blackbody band radiance and its inverse for one spectral band.
///
/// [`Band`] is the project's real band (8–14 µm by default, optional sensor response);
/// [`TotalRadiance`] is the whole spectrum in closed form, for tests and hand checks.
pub trait BandModel: Sync {
    /// Band radiance of a blackbody at `temperature_k`, W m⁻² sr⁻¹.
    fn radiance(&self, temperature_k: f64) -> f64;
    /// dL/dT at `temperature_k`, W m⁻² sr⁻¹ K⁻¹.
    fn radiance_derivative(&self, temperature_k: f64) -> f64;
    /// The blackbody temperature in kelvin whose band radiance is `radiance_w_m2_sr` (the
    /// apparent temperature); 0 K for a radiance of 0 or less.
    fn temperature(&self, radiance_w_m2_sr: f64) -> f64;
    /// `(L(T), dL/dT)` together, for bands that share the work between the two.
    fn radiance_and_derivative(&self, temperature_k: f64) -> (f64, f64) {
        (
            self.radiance(temperature_k),
            self.radiance_derivative(temperature_k),
        )
    }
}

/// A band of wavelengths or the whole spectrum, chosen at run time: what a stage reads
/// from an image's record of its band.
#[derive(Debug, Clone, PartialEq)]
pub enum AnyBand {
    /// A band of wavelengths.
    Band(Band),
    /// The whole spectrum.
    Total(TotalRadiance),
}

impl BandModel for AnyBand {
    fn radiance(&self, temperature_k: f64) -> f64 {
        match self {
            Self::Band(b) => b.radiance(temperature_k),
            Self::Total(t) => t.radiance(temperature_k),
        }
    }
    fn radiance_derivative(&self, temperature_k: f64) -> f64 {
        match self {
            Self::Band(b) => b.radiance_derivative(temperature_k),
            Self::Total(t) => t.radiance_derivative(temperature_k),
        }
    }
    fn temperature(&self, radiance_w_m2_sr: f64) -> f64 {
        match self {
            Self::Band(b) => b.temperature(radiance_w_m2_sr),
            Self::Total(t) => t.temperature(radiance_w_m2_sr),
        }
    }
    fn radiance_and_derivative(&self, temperature_k: f64) -> (f64, f64) {
        match self {
            Self::Band(b) => b.radiance_and_derivative(temperature_k),
            Self::Total(t) => t.radiance_and_derivative(temperature_k),
        }
    }
}

/// The apparent temperature, K, of each radiance of an image layer (W m⁻² sr⁻¹, f32), in
/// `band`; NaN where the radiance is not finite. Each pixel gets the `f32` its exact solve
/// ([`BandModel::temperature`]) rounds to, bit for bit, found through an inverse table of
/// the layer's radiance range ([`InverseTable::temperature_f32`]): one or two Planck
/// evaluations a pixel rather than five or six. A run of equal radiances is looked up once.
/// The pixels are shared among every core; each pixel's answer is its own, so the result
/// is the same on any number of threads.
#[must_use]
pub fn apparent_temperatures<B: BandModel + ?Sized>(
    band: &B,
    radiance_w_m2_sr: &[f32],
) -> Vec<f32> {
    let (lo, hi) = radiance_w_m2_sr
        .iter()
        .filter(|l| l.is_finite() && **l > 0.0)
        .fold((f64::INFINITY, 0.0_f64), |(lo, hi), &l| {
            (lo.min(f64::from(l)), hi.max(f64::from(l)))
        });
    let table = InverseTable::new(band, &[lo, hi]);
    let table = &table;
    radiance_w_m2_sr
        .par_chunks(4096)
        .flat_map_iter(|run| {
            let mut last: Option<(u32, f32)> = None;
            run.iter().map(move |&l| match last {
                Some((bits, t)) if bits == l.to_bits() => t,
                _ => {
                    let t = if l.is_finite() {
                        table.temperature_f32(f64::from(l))
                    } else {
                        f32::NAN
                    };
                    last = Some((l.to_bits(), t));
                    t
                }
            })
        })
        .collect()
}

impl BandModel for Band {
    fn radiance(&self, temperature_k: f64) -> f64 {
        Band::radiance(self, temperature_k)
    }
    fn radiance_derivative(&self, temperature_k: f64) -> f64 {
        Band::radiance_derivative(self, temperature_k)
    }
    fn temperature(&self, radiance_w_m2_sr: f64) -> f64 {
        Band::temperature(self, radiance_w_m2_sr)
    }
    fn radiance_and_derivative(&self, temperature_k: f64) -> (f64, f64) {
        Band::radiance_and_derivative(self, temperature_k)
    }
}

/// The whole spectrum: `L(T) = σT⁴/π`, with its exact inverse. For tests and for comparing
/// with a hand computation.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct TotalRadiance;

/// Stefan–Boltzmann constant, W m⁻² K⁻⁴: `2π⁵k⁴ / (15h³c²)`, exact in the 2019 SI
/// (CODATA 2018 lists 5.670 374 419…e-8).
pub const STEFAN_BOLTZMANN_W_M2_K4: f64 = 2.0
    * std::f64::consts::PI
    * std::f64::consts::PI
    * std::f64::consts::PI
    * std::f64::consts::PI
    * std::f64::consts::PI
    * BOLTZMANN_J_K
    * BOLTZMANN_J_K
    * BOLTZMANN_J_K
    * BOLTZMANN_J_K
    / (15.0 * PLANCK_J_S * PLANCK_J_S * PLANCK_J_S * SPEED_OF_LIGHT_M_S * SPEED_OF_LIGHT_M_S);

impl BandModel for TotalRadiance {
    fn radiance(&self, temperature_k: f64) -> f64 {
        STEFAN_BOLTZMANN_W_M2_K4 * temperature_k.powi(4) / std::f64::consts::PI
    }
    fn radiance_derivative(&self, temperature_k: f64) -> f64 {
        4.0 * STEFAN_BOLTZMANN_W_M2_K4 * temperature_k.powi(3) / std::f64::consts::PI
    }
    fn temperature(&self, radiance_w_m2_sr: f64) -> f64 {
        if radiance_w_m2_sr <= 0.0 {
            0.0
        } else {
            (radiance_w_m2_sr * std::f64::consts::PI / STEFAN_BOLTZMANN_W_M2_K4).powf(0.25)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_images_apparent_temperatures_are_each_pixels_exact_solve_rounded() {
        // Runs, alternations, nothing positive, infinities and NaN, and radiances spread
        // over 150-400 K: every pixel the f32 of its own exact solve.
        let band = Band::default();
        let mut image: Vec<f32> = (0..5000)
            .map(|i| band.radiance(150.0 + 0.05 * f64::from(i)) as f32)
            .collect();
        image.extend([0.0, -0.0, -1.0, f32::NAN, f32::INFINITY, f32::NEG_INFINITY]);
        image.extend([image[7]; 9]);
        image.extend([image[3], image[4], image[3]]);
        let t = apparent_temperatures(&band, &image);
        assert_eq!(t.len(), image.len());
        for (l, t) in image.iter().zip(&t) {
            let exact = if l.is_finite() {
                band.temperature(f64::from(*l)) as f32
            } else {
                f32::NAN
            };
            assert_eq!(t.to_bits(), exact.to_bits(), "{l}: {t} against {exact}");
        }
        assert!(apparent_temperatures(&band, &[]).is_empty());
        let cold = apparent_temperatures(&band, &[0.0, f32::NAN]);
        assert_eq!(cold[0].to_bits(), 0.0_f32.to_bits());
        assert!(cold[1].is_nan());
    }

    #[test]
    fn stefan_boltzmann_matches_codata_2018() {
        // CODATA 2018: σ = 5.670 374 419… × 10⁻⁸ W m⁻² K⁻⁴.
        assert!((STEFAN_BOLTZMANN_W_M2_K4 / 5.670_374_419e-8 - 1.0).abs() < 1e-9);
    }

    #[test]
    fn total_radiance_round_trips() {
        for t in [3.0, 77.0, 300.0, 1500.0] {
            let l = TotalRadiance.radiance(t);
            assert!((TotalRadiance.temperature(l) - t).abs() < 1e-9 * t);
        }
        // σ·300⁴/π by hand: 5.670374419e-8 · 8.1e9 = 459.3003; / π = 146.1995.
        assert!((TotalRadiance.radiance(300.0) - 146.199_5).abs() < 1e-3);
        assert!(TotalRadiance.temperature(0.0).abs() < f64::MIN_POSITIVE);
    }

    #[test]
    fn the_band_is_a_band_model() {
        fn through_trait(b: &impl BandModel, t: f64) -> f64 {
            b.temperature(b.radiance(t))
        }
        assert!((through_trait(&Band::default(), 300.0) - 300.0).abs() < 1e-6);
    }
}
