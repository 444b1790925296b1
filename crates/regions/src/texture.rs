//! Texture estimation: the statistics of a region of a measured (or rendered) image that a
//! material's statistical texture reproduces.
//!
//! After the thesis's sources (Grumman and TACOM, §2), who textured their images with the
//! statistical characteristics of measured IR data: the region's standard deviation and
//! its autocorrelation along the image's rows and columns (the power spectrum's Fourier
//! transform, by the Wiener–Khinchin theorem), to which the named spectra of
//! `irsig-texture` are fitted by least squares. The result is a texture description
//! (`irsig_model::texture::StatisticalTexture`) a material can carry.
//!
//! The image's axes are taken as the world's: columns along x (east), rows down along −y
//! (north up), as a nadir view with north up gives them; `pixel_m` is the ground length of
//! a pixel along each.

use irsig_model::texture::{
    CorrelationLength, FieldFilter, FieldSpectrum, RandomField, StatisticalTexture,
};

pub use crate::stats::region_plane;

/// Lags of the autocorrelation are measured out to where it falls below this (the fit
/// uses the part of the curve that holds the length scale, not the noise of its tail).
const FIT_FLOOR: f64 = 0.05;

/// A region's texture statistics.
#[derive(Debug, Clone, PartialEq)]
pub struct TextureEstimate {
    /// Pixels used.
    pub pixels: usize,
    /// Their mean, in the values' unit.
    pub mean: f64,
    /// Their standard deviation about the mean.
    pub sigma: f64,
    /// The standard error of `sigma` for a Gaussian field of the fitted correlation
    /// lengths: `(σ/2)·√(π ℓx ℓy / A)` over the region's area `A` (the variance of a
    /// sample variance, `2σ⁴/N²·ΣΣC²`, with `∫C² dA = π ℓx ℓy / 2` for both the Gaussian
    /// and the exponential correlation).
    pub sigma_standard_error: f64,
    /// The autocorrelation at lags 0, 1, 2, … pixels along the rows (x) and the columns
    /// (y), out to where it falls below 0.05 (or half the region).
    pub autocorrelation: [Vec<f64>; 2],
    /// The correlation lengths along x and y, m, of the better-fitting spectrum.
    pub correlation_length_m: [f64; 2],
    /// That spectrum, `Gaussian` or `Exponential`, with its per-axis lengths (z takes the
    /// shorter of the two).
    pub spectrum: FieldSpectrum,
    /// The fit's root-mean-square residual in the correlation, of the chosen spectrum and
    /// of the other.
    pub residual: [f64; 2],
}

/// Why a region's texture cannot be estimated.
#[derive(Debug, Clone, PartialEq)]
pub enum TextureProblem {
    /// Fewer than 4 × 4 pixels, or no lag with a pair of pixels.
    TooSmall,
    /// The values do not vary: no texture to describe.
    Uniform,
    /// A pixel length that is not finite and above 0.
    BadPixelLength,
}

impl std::fmt::Display for TextureProblem {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Self::TooSmall => "expected a region of at least 4 x 4 pixels",
            Self::Uniform => "its values do not vary: there is no texture to estimate",
            Self::BadPixelLength => "expected a pixel length above 0 m",
        })
    }
}

/// The texture of the pixels of a `width × height` image whose `values` are finite (NaN
/// marks a pixel outside the region), each pixel `pixel_m` long along x and y.
///
/// # Errors
/// A region too small, uniform values or a bad pixel length.
pub fn estimate(
    values: &[f64],
    width: usize,
    pixel_m: [f64; 2],
) -> Result<TextureEstimate, TextureProblem> {
    if pixel_m.iter().any(|p| !p.is_finite() || *p <= 0.0) {
        return Err(TextureProblem::BadPixelLength);
    }
    let height = values.len().checked_div(width).unwrap_or(0);
    if width < 4 || height < 4 {
        return Err(TextureProblem::TooSmall);
    }
    let selected = values.iter().filter(|v| v.is_finite());
    let pixels = selected.clone().count();
    if pixels < 16 {
        return Err(TextureProblem::TooSmall);
    }
    let mean = selected.clone().sum::<f64>() / pixels as f64;
    let var = selected.map(|v| (v - mean).powi(2)).sum::<f64>() / pixels as f64;
    if var <= 0.0 || !var.is_finite() {
        return Err(TextureProblem::Uniform);
    }
    let d: Vec<f64> = values.iter().map(|v| v - mean).collect();
    let along = |dx: usize, dy: usize| {
        let max_lag = if dx > 0 { width / 2 } else { height / 2 };
        let mut c = vec![1.0];
        for lag in 1..max_lag {
            let (mut sum, mut n) = (0.0, 0usize);
            for row in 0..height - lag * dy {
                for col in 0..width - lag * dx {
                    let (a, b) = (
                        d[row * width + col],
                        d[(row + lag * dy) * width + col + lag * dx],
                    );
                    if a.is_finite() && b.is_finite() {
                        sum += a * b;
                        n += 1;
                    }
                }
            }
            if n == 0 {
                break;
            }
            let value = sum / n as f64 / var;
            c.push(value);
            if value < FIT_FLOOR {
                break;
            }
        }
        c
    };
    let autocorrelation = [along(1, 0), along(0, 1)];
    if autocorrelation.iter().any(|c| c.len() < 2) {
        return Err(TextureProblem::TooSmall);
    }
    let fit = |shape: Shape| {
        let lengths_px = [0, 1].map(|axis| fit_length_px(&autocorrelation[axis], shape));
        let residual = [0, 1]
            .iter()
            .map(|&axis| rms_residual(&autocorrelation[axis], shape, lengths_px[axis]))
            .fold(0.0, f64::max);
        (lengths_px, residual)
    };
    let (gaussian, exponential) = (fit(Shape::Gaussian), fit(Shape::Exponential));
    let (shape, (lengths_px, best), other) = if gaussian.1 <= exponential.1 {
        (Shape::Gaussian, gaussian, exponential.1)
    } else {
        (Shape::Exponential, exponential, gaussian.1)
    };
    let lengths_m = [lengths_px[0] * pixel_m[0], lengths_px[1] * pixel_m[1]];
    let correlation_length_m =
        CorrelationLength::PerAxis(lengths_m[0], lengths_m[1], lengths_m[0].min(lengths_m[1]));
    let spectrum = match shape {
        Shape::Gaussian => FieldSpectrum::Gaussian {
            correlation_length_m,
        },
        Shape::Exponential => FieldSpectrum::Exponential {
            correlation_length_m,
        },
    };
    let area_m2 = pixels as f64 * pixel_m[0] * pixel_m[1];
    let sigma = var.sqrt();
    Ok(TextureEstimate {
        pixels,
        mean,
        sigma,
        sigma_standard_error: 0.5
            * sigma
            * (std::f64::consts::PI * lengths_m[0] * lengths_m[1] / area_m2).sqrt(),
        autocorrelation,
        correlation_length_m: lengths_m,
        spectrum,
        residual: [best, other],
    })
}

impl TextureEstimate {
    /// The texture description of a temperature texture with these statistics (the values
    /// in kelvin), drawn from `seed`.
    #[must_use]
    pub fn temperature_texture(&self, seed: u64) -> StatisticalTexture {
        StatisticalTexture {
            seed,
            temperature_offset_k: Some(RandomField {
                sigma: self.sigma,
                spectrum: self.spectrum.clone(),
            }),
            emissivity_scale: None,
            filter: FieldFilter::Point,
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Shape {
    Gaussian,
    Exponential,
}

impl Shape {
    /// The shape's correlation at `lag_px` for a length of `length_px`: irsig-texture's,
    /// the one definition of each spectrum.
    fn at(self, lag_px: f64, length_px: f64) -> f64 {
        let correlation_length_m = CorrelationLength::Isotropic(length_px);
        let spectrum = match self {
            Self::Gaussian => FieldSpectrum::Gaussian {
                correlation_length_m,
            },
            Self::Exponential => FieldSpectrum::Exponential {
                correlation_length_m,
            },
        };
        irsig_texture::correlation(&spectrum, [lag_px, 0.0, 0.0])
    }
}

/// The RMS difference between the measured correlation at lags 1… and the shape at
/// `length_px`.
fn rms_residual(c: &[f64], shape: Shape, length_px: f64) -> f64 {
    let n = (c.len() - 1).max(1) as f64;
    let sum: f64 = c
        .iter()
        .enumerate()
        .skip(1)
        .map(|(lag, v)| (v - shape.at(lag as f64, length_px)).powi(2))
        .sum();
    (sum / n).sqrt()
}

/// The length, pixels, that fits `shape` to the correlation `c` by least squares: a
/// golden-section search in ln ℓ from 0.05 pixel to 100 times the lags measured (the
/// residual of one length scale is unimodal in it).
fn fit_length_px(c: &[f64], shape: Shape) -> f64 {
    let cost = |ln_l: f64| rms_residual(c, shape, ln_l.exp());
    let (mut a, mut b) = (0.05f64.ln(), (100.0 * c.len() as f64).ln());
    let g = (5f64.sqrt() - 1.0) / 2.0;
    let (mut x1, mut x2) = (b - g * (b - a), a + g * (b - a));
    let (mut f1, mut f2) = (cost(x1), cost(x2));
    for _ in 0..100 {
        if f1 < f2 {
            b = x2;
            x2 = x1;
            f2 = f1;
            x1 = b - g * (b - a);
            f1 = cost(x1);
        } else {
            a = x1;
            x1 = x2;
            f1 = f2;
            x2 = a + g * (b - a);
            f2 = cost(x2);
        }
    }
    (0.5 * (a + b)).exp()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A `n × n` image of `sigma`-scaled texture of `spectrum` from `seed`, pixels of
    /// `pixel_m`, its field made by irsig-texture at the pixel centres.
    fn image(spectrum: &FieldSpectrum, sigma: f64, seed: u64, n: usize, pixel_m: f64) -> Vec<f64> {
        let t = StatisticalTexture {
            seed,
            temperature_offset_k: Some(RandomField {
                sigma,
                spectrum: spectrum.clone(),
            }),
            emissivity_scale: None,
            filter: FieldFilter::Point,
        };
        let f = irsig_texture::TextureFields::new(&t).unwrap();
        (0..n * n)
            .map(|i| {
                let (col, row) = ((i % n) as f64, (i / n) as f64);
                300.0
                    + f.sample([col * pixel_m, -row * pixel_m, 0.0])
                        .temperature_offset_k
            })
            .collect()
    }

    /// Estimates eight seeds' images and checks the mean σ within three of the estimate's
    /// own stated standard errors (over √8) plus the finite region's bias, and the mean
    /// lengths within 5 % and three standard errors of the seeds' spread.
    fn recovers(spectrum: &FieldSpectrum, sigma: f64, lengths_m: [f64; 2], gaussian: bool) {
        let (n, pixel_m) = (200, 0.1);
        let estimates: Vec<TextureEstimate> = (1..=8)
            .map(|seed| {
                estimate(&image(spectrum, sigma, seed, n, pixel_m), n, [pixel_m; 2]).unwrap()
            })
            .collect();
        let count = estimates.len() as f64;
        let mean_sigma = estimates.iter().map(|e| e.sigma).sum::<f64>() / count;
        let stated = estimates
            .iter()
            .map(|e| e.sigma_standard_error)
            .sum::<f64>()
            / count;
        // The bias of a variance about the region's own mean: the correlation over pairs,
        // ~π ℓx ℓy / A.
        let bias = sigma * std::f64::consts::PI * lengths_m[0] * lengths_m[1]
            / (n as f64 * pixel_m).powi(2);
        assert!(
            (mean_sigma - sigma).abs() <= 3.0 * stated / count.sqrt() + bias,
            "σ {mean_sigma} (stated error {stated}), expected {sigma}"
        );
        for (axis, &expected) in lengths_m.iter().enumerate() {
            let values: Vec<f64> = estimates
                .iter()
                .map(|e| e.correlation_length_m[axis])
                .collect();
            let mean = values.iter().sum::<f64>() / count;
            let sd =
                (values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (count - 1.0)).sqrt();
            assert!(
                (mean - expected).abs() <= 3.0 * sd / count.sqrt() + 0.05 * expected,
                "axis {axis}: {mean} ± {sd}, expected {expected} ({values:?})"
            );
        }
        let chose_gaussian = estimates
            .iter()
            .filter(|e| matches!(e.spectrum, FieldSpectrum::Gaussian { .. }))
            .count();
        if gaussian {
            assert!(
                chose_gaussian >= 7,
                "{chose_gaussian} of 8 fitted as Gaussian"
            );
        } else {
            assert!(
                chose_gaussian <= 1,
                "{chose_gaussian} of 8 fitted as Gaussian"
            );
        }
    }

    #[test]
    fn a_gaussian_field_is_recovered() {
        let spectrum = FieldSpectrum::Gaussian {
            correlation_length_m: CorrelationLength::Isotropic(0.6),
        };
        recovers(&spectrum, 1.2, [0.6, 0.6], true);
    }

    #[test]
    fn a_stretched_exponential_field_is_recovered() {
        let spectrum = FieldSpectrum::Exponential {
            correlation_length_m: CorrelationLength::PerAxis(0.8, 0.4, 1.0),
        };
        recovers(&spectrum, 2.5, [0.8, 0.4], false);
    }

    #[test]
    fn what_cannot_be_estimated_is_refused() {
        assert_eq!(
            estimate(&[1.0; 9], 3, [0.1; 2]),
            Err(TextureProblem::TooSmall)
        );
        assert_eq!(
            estimate(&[1.0; 100], 10, [0.1; 2]),
            Err(TextureProblem::Uniform)
        );
        assert_eq!(
            estimate(&[1.0; 100], 10, [f64::NAN, 0.1]),
            Err(TextureProblem::BadPixelLength)
        );
        assert_eq!(
            estimate(&[f64::NAN; 100], 10, [0.1; 2]),
            Err(TextureProblem::TooSmall)
        );
    }

    #[test]
    fn the_description_round_trips_through_the_model_rules() {
        let spectrum = FieldSpectrum::Gaussian {
            correlation_length_m: CorrelationLength::Isotropic(0.5),
        };
        let e = estimate(&image(&spectrum, 1.0, 3, 64, 0.1), 64, [0.1; 2]).unwrap();
        let t = e.temperature_texture(42);
        assert!(t.validate("texture").is_ok());
        assert_eq!(t.seed, 42);
    }
}
