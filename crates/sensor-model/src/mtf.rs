//! Modulation transfer function models and their cascade (thesis §3.4.2, eq. 12).
//!
//! Every model is stated by its optical transfer function (OTF): the complex gain applied
//! to a spatial frequency `(fx, fy)` in **cycles per sensor pixel** (x along a row to the
//! right, y down the rows). The MTF is its modulus. A chain of models is their product,
//! frequency by frequency, exactly as eq. 12 cascades optics, detector and electronics.
//!
//! Every model has OTF(0, 0) = 1, so every kernel sums to 1 and the blur preserves the
//! mean radiance of a scene.
//!
//! Models that are defined on a discrete grid of taps (the box IFOV and explicit kernels)
//! are evaluated as the discrete-time Fourier transform of those taps; the others are the
//! continuous optical formulas, sampled on the FFT grid.

use std::f64::consts::PI;

use irsig_fft::Complex64;
use serde::{Deserialize, Serialize};

use crate::error::{Result, SensorError, SensorErrorKind, non_negative, positive};

/// Energy left outside the margin the blur pads for the diffraction PSF (its Airy tails
/// fall off only as 1/r³, so a finite margin always leaves some).
const DIFFRACTION_TAIL_ENERGY: f64 = 1e-3;

/// Padding, in pixels, added to models whose sampled transfer function is cut at the
/// Nyquist frequency (sinc footprints, motion), whose discrete kernels ring as 1/n².
const SINC_RING_MARGIN_PX: f64 = 16.0;

/// One component of the system MTF. Lengths are in sensor pixels unless the field name
/// says otherwise; frequencies in cycles per sensor pixel.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Mtf {
    /// The 1990 model: a box of `width_px` × `height_px` equal weights, the detector's
    /// instantaneous field of view (the thesis used 5 × 5). On a grid rendered at `s`
    /// samples per pixel it has `width_px·s` × `height_px·s` taps. An even count has no
    /// centre tap; its taps run from −n/2 to n/2 − 1, which shifts the image by half a
    /// sample (the transfer function carries that phase).
    Box {
        /// Width of the IFOV in sensor pixels (≥ 1).
        width_px: u32,
        /// Height of the IFOV in sensor pixels (≥ 1).
        height_px: u32,
    },
    /// An isotropic Gaussian point-spread function of standard deviation `sigma_px`:
    /// MTF(f) = exp(−2π²σ²f²). See [`Mtf::gaussian_half_power`] for the other way of
    /// stating it.
    Gaussian {
        /// Standard deviation of the PSF in sensor pixels (> 0).
        sigma_px: f64,
    },
    /// Schott & Salvaggio (1987), as the thesis (§3.4.2) describes it: a 2-D kernel that is
    /// the convolution of an across-track 1-D kernel (along image rows, x) with an
    /// along-track 1-D kernel (down image columns, y), each specified by the half-power
    /// frequency of its 1-D power spectrum.
    ///
    /// Our reading (the paper's own shape is not in the thesis): each 1-D power spectrum is
    /// a Gaussian, P(f) = exp(−ln2·(f/f½)²), so the power is one half at f½ (the −3 dB
    /// point); the 1-D MTF is its square root, exp(−(ln2/2)(f/f½)²), which is 1/√2 at f½.
    /// The convolution of the two 1-D kernels is, in frequency, the product
    /// MTF(fx, fy) = MTF_across(fx) · MTF_along(fy), which is what is applied.
    SchottSalvaggio {
        /// Half-power frequency across track (x, along rows), cycles per pixel (> 0).
        across_track_half_power_cyc_px: f64,
        /// Half-power frequency along track (y, down columns), cycles per pixel (> 0).
        along_track_half_power_cyc_px: f64,
    },
    /// A diffraction-limited optic with a clear circular aperture, incoherent light:
    /// MTF(ν) = (2/π)(acos ν − ν√(1−ν²)) for ν = f/f_c < 1, else 0, with cut-off
    /// f_c = pitch / (λ·N) cycles per pixel.
    Diffraction {
        /// Wavelength in metres (e.g. 10e-6 for the middle of 8–14 µm).
        wavelength_m: f64,
        /// Working f-number N of the optic.
        f_number: f64,
        /// Detector pitch in metres.
        pixel_pitch_m: f64,
    },
    /// The detector footprint: a uniformly sensitive rectangle `width_px` × `height_px`
    /// pixel pitches (1 × 1 is a 100 % fill factor): MTF = sinc(w·fx)·sinc(h·fy). Do not
    /// also use it when the image is rendered at several samples per pixel and reduced by
    /// block averaging, which already integrates the footprint.
    Footprint {
        /// Active width in pixel pitches (> 0).
        width_px: f64,
        /// Active height in pixel pitches (> 0).
        height_px: f64,
    },
    /// Uniform linear motion during the integration time: the image moves `length_px`
    /// pixels along the direction `angle_deg` (0 = along +x, to the right; 90 = along +y,
    /// down the rows). MTF = sinc(L·(fx cos θ + fy sin θ)).
    Motion {
        /// Length of the smear in pixels (≥ 0).
        length_px: f64,
        /// Direction of the smear in degrees from +x towards +y.
        angle_deg: f64,
    },
    /// Random line-of-sight jitter, Gaussian with the given standard deviations:
    /// MTF = exp(−2π²(σx²fx² + σy²fy²)).
    Jitter {
        /// Standard deviation across x in pixels (≥ 0).
        sigma_x_px: f64,
        /// Standard deviation across y in pixels (≥ 0).
        sigma_y_px: f64,
    },
    /// An explicit kernel of taps on the grid the blur runs on (render samples). Weights
    /// are normalised to sum to 1 by [`Kernel::new`].
    Kernel(Kernel),
}

/// An explicit convolution kernel: `width` × `height` taps, row-major, row 0 at the top.
/// Tap (i, j) sits at offset (i − width/2, j − height/2) samples from the output pixel
/// (integer division, so an odd kernel is centred).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Kernel {
    /// Number of taps across.
    pub width: usize,
    /// Number of taps down.
    pub height: usize,
    /// The weights, row-major.
    pub taps: Vec<f64>,
}

impl Kernel {
    /// A kernel with its weights scaled to sum to 1.
    ///
    /// # Errors
    /// An empty kernel, a length that is not `width·height`, a non-finite weight, or
    /// weights that sum to zero.
    pub fn new(width: usize, height: usize, taps: Vec<f64>) -> Result<Self> {
        let mut kernel = Self {
            width,
            height,
            taps,
        };
        kernel.check()?;
        let sum: f64 = kernel.taps.iter().sum();
        for t in &mut kernel.taps {
            *t /= sum;
        }
        Ok(kernel)
    }

    /// A `width` × `height` box of equal weights.
    ///
    /// # Errors
    /// A zero size.
    pub fn uniform(width: usize, height: usize) -> Result<Self> {
        let n = width.checked_mul(height).unwrap_or(0);
        Self::new(width, height, vec![1.0; n])
    }

    fn check(&self) -> Result<()> {
        let invalid = |reason: String| SensorError::from(SensorErrorKind::InvalidKernel { reason });
        if self.width == 0 || self.height == 0 {
            return Err(invalid(format!(
                "it is {} x {} taps; both must be at least 1",
                self.width, self.height
            )));
        }
        if self.taps.len() != self.width * self.height {
            return Err(invalid(format!(
                "{} x {} taps need {} weights, found {}",
                self.width,
                self.height,
                self.width * self.height,
                self.taps.len()
            )));
        }
        if let Some(i) = self.taps.iter().position(|t| !t.is_finite()) {
            return Err(invalid(format!("weight {i} is {}", self.taps[i])));
        }
        let sum: f64 = self.taps.iter().sum();
        if sum.abs() < 1e-12 * self.taps.iter().map(|t| t.abs()).sum::<f64>() || sum == 0.0 {
            return Err(invalid(
                "its weights sum to zero, so it cannot preserve the mean".to_owned(),
            ));
        }
        Ok(())
    }

    /// Offset of tap column 0 from the output pixel, in samples.
    #[must_use]
    pub fn origin_x(&self) -> isize {
        -((self.width / 2) as isize)
    }

    /// Offset of tap row 0 from the output pixel, in samples.
    #[must_use]
    pub fn origin_y(&self) -> isize {
        -((self.height / 2) as isize)
    }

    /// The discrete-time Fourier transform of the taps at (fx, fy) in cycles per sample.
    #[must_use]
    pub fn transfer(&self, fx: f64, fy: f64) -> Complex64 {
        let mut acc = Complex64::new(0.0, 0.0);
        for j in 0..self.height {
            let dy = (j as isize + self.origin_y()) as f64;
            for i in 0..self.width {
                let dx = (i as isize + self.origin_x()) as f64;
                let w = self.taps[j * self.width + i];
                acc += Complex64::from_polar(w, -2.0 * PI * (fx * dx + fy * dy));
            }
        }
        acc
    }
}

impl Mtf {
    /// A Gaussian stated by its half-power frequency f½ (cycles per pixel): the frequency
    /// at which the power transfer |MTF|² falls to one half, i.e. MTF(f½) = 1/√2. Then
    /// σ = √(ln 2) / (2π f½).
    ///
    /// # Errors
    /// A frequency that is not finite and positive.
    pub fn gaussian_half_power(half_power_cyc_px: f64) -> Result<Self> {
        let f = positive("half_power_cyc_px", half_power_cyc_px)?;
        Ok(Self::Gaussian {
            sigma_px: half_power_sigma(f),
        })
    }

    /// Checks every parameter.
    ///
    /// # Errors
    /// The first parameter that is NaN, infinite or out of its range.
    pub fn validate(&self) -> Result<()> {
        match self {
            Self::Box {
                width_px,
                height_px,
            } => {
                if *width_px == 0 {
                    return Err(SensorError::parameter(
                        "box width_px",
                        0.0,
                        "at least 1 pixel",
                    ));
                }
                if *height_px == 0 {
                    return Err(SensorError::parameter(
                        "box height_px",
                        0.0,
                        "at least 1 pixel",
                    ));
                }
            }
            Self::Gaussian { sigma_px } => {
                positive("gaussian sigma_px", *sigma_px)?;
            }
            Self::SchottSalvaggio {
                across_track_half_power_cyc_px,
                along_track_half_power_cyc_px,
            } => {
                positive(
                    "across_track_half_power_cyc_px",
                    *across_track_half_power_cyc_px,
                )?;
                positive(
                    "along_track_half_power_cyc_px",
                    *along_track_half_power_cyc_px,
                )?;
            }
            Self::Diffraction {
                wavelength_m,
                f_number,
                pixel_pitch_m,
            } => {
                positive("wavelength_m", *wavelength_m)?;
                positive("f_number", *f_number)?;
                positive("pixel_pitch_m", *pixel_pitch_m)?;
            }
            Self::Footprint {
                width_px,
                height_px,
            } => {
                positive("footprint width_px", *width_px)?;
                positive("footprint height_px", *height_px)?;
            }
            Self::Motion {
                length_px,
                angle_deg,
            } => {
                non_negative("motion length_px", *length_px)?;
                crate::error::finite("motion angle_deg", *angle_deg)?;
            }
            Self::Jitter {
                sigma_x_px,
                sigma_y_px,
            } => {
                non_negative("jitter sigma_x_px", *sigma_x_px)?;
                non_negative("jitter sigma_y_px", *sigma_y_px)?;
            }
            Self::Kernel(k) => k.check()?,
        }
        Ok(())
    }

    /// The OTF at (fx, fy) cycles per sensor pixel, for an image sampled at
    /// `samples_per_pixel` samples per sensor pixel in each direction (which only the
    /// models defined by discrete taps need).
    #[must_use]
    pub fn otf(&self, fx: f64, fy: f64, samples_per_pixel: u32) -> Complex64 {
        let s = f64::from(samples_per_pixel.max(1));
        match self {
            Self::Box {
                width_px,
                height_px,
            } => {
                let nx = u64::from(*width_px) * u64::from(samples_per_pixel.max(1));
                let ny = u64::from(*height_px) * u64::from(samples_per_pixel.max(1));
                box_transfer(nx, fx / s) * box_transfer(ny, fy / s)
            }
            Self::Gaussian { sigma_px } => Complex64::new(
                (-2.0 * PI * PI * sigma_px * sigma_px * (fx * fx + fy * fy)).exp(),
                0.0,
            ),
            Self::SchottSalvaggio {
                across_track_half_power_cyc_px: fa,
                along_track_half_power_cyc_px: fl,
            } => {
                let half_ln2 = std::f64::consts::LN_2 / 2.0;
                let g = (-half_ln2 * ((fx / fa).powi(2) + (fy / fl).powi(2))).exp();
                Complex64::new(g, 0.0)
            }
            Self::Diffraction {
                wavelength_m,
                f_number,
                pixel_pitch_m,
            } => {
                let nu = fx.hypot(fy) * wavelength_m * f_number / pixel_pitch_m;
                Complex64::new(diffraction_mtf(nu), 0.0)
            }
            Self::Footprint {
                width_px,
                height_px,
            } => Complex64::new(sinc(width_px * fx) * sinc(height_px * fy), 0.0),
            Self::Motion {
                length_px,
                angle_deg,
            } => {
                let (sin, cos) = angle_deg.to_radians().sin_cos();
                Complex64::new(sinc(length_px * (fx * cos + fy * sin)), 0.0)
            }
            Self::Jitter {
                sigma_x_px,
                sigma_y_px,
            } => Complex64::new(
                (-2.0 * PI * PI * (sigma_x_px.powi(2) * fx * fx + sigma_y_px.powi(2) * fy * fy))
                    .exp(),
                0.0,
            ),
            Self::Kernel(k) => k.transfer(fx / s, fy / s),
        }
    }

    /// The OTF as a product `fx_part(fx) · fy_part(fy)` when the model is separable in x
    /// and y, so that the blur can tabulate it once per row and column of the spectrum.
    /// `None` for models that are not (diffraction, oblique motion, explicit kernels).
    #[must_use]
    pub fn separable_otf(&self, f: f64, axis: Axis, samples_per_pixel: u32) -> Option<Complex64> {
        let s = f64::from(samples_per_pixel.max(1));
        let pick = |x: f64, y: f64| match axis {
            Axis::X => x,
            Axis::Y => y,
        };
        let real = |v: f64| Some(Complex64::new(v, 0.0));
        match self {
            Self::Box {
                width_px,
                height_px,
            } => {
                let n = u64::from(match axis {
                    Axis::X => *width_px,
                    Axis::Y => *height_px,
                }) * u64::from(samples_per_pixel.max(1));
                Some(box_transfer(n, f / s))
            }
            Self::Gaussian { sigma_px } => {
                real((-2.0 * PI * PI * sigma_px * sigma_px * f * f).exp())
            }
            Self::SchottSalvaggio {
                across_track_half_power_cyc_px: fa,
                along_track_half_power_cyc_px: fl,
            } => real((-(std::f64::consts::LN_2 / 2.0) * (f / pick(*fa, *fl)).powi(2)).exp()),
            Self::Footprint {
                width_px,
                height_px,
            } => real(sinc(pick(*width_px, *height_px) * f)),
            Self::Jitter {
                sigma_x_px,
                sigma_y_px,
            } => real((-2.0 * PI * PI * pick(*sigma_x_px, *sigma_y_px).powi(2) * f * f).exp()),
            Self::Diffraction { .. } | Self::Motion { .. } | Self::Kernel(_) => None,
        }
    }

    /// How far (x, y) in sensor pixels the point-spread function reaches, for the padding
    /// the blur adds at the edges so that reflect and zero edges are exact.
    #[must_use]
    pub fn support_radius_px(&self, samples_per_pixel: u32) -> (f64, f64) {
        let s = f64::from(samples_per_pixel.max(1));
        match self {
            Self::Box {
                width_px,
                height_px,
            } => (
                f64::from(*width_px) / 2.0 + 1.0,
                f64::from(*height_px) / 2.0 + 1.0,
            ),
            Self::Gaussian { sigma_px } => (8.0 * sigma_px, 8.0 * sigma_px),
            Self::SchottSalvaggio {
                across_track_half_power_cyc_px,
                along_track_half_power_cyc_px,
            } => (
                8.0 * half_power_sigma(*across_track_half_power_cyc_px),
                8.0 * half_power_sigma(*along_track_half_power_cyc_px),
            ),
            Self::Diffraction {
                wavelength_m,
                f_number,
                pixel_pitch_m,
            } => {
                // Far from the centre the Airy pattern leaves 2/(π²·fc·r) of its energy
                // outside radius r (pixels, fc in cycles per pixel).
                let cutoff = pixel_pitch_m / (wavelength_m * f_number);
                let r = 2.0 / (PI * PI * cutoff * DIFFRACTION_TAIL_ENERGY);
                (r, r)
            }
            Self::Footprint {
                width_px,
                height_px,
            } => (
                width_px / 2.0 + SINC_RING_MARGIN_PX,
                height_px / 2.0 + SINC_RING_MARGIN_PX,
            ),
            Self::Motion {
                length_px,
                angle_deg,
            } => {
                let (sin, cos) = angle_deg.to_radians().sin_cos();
                (
                    (length_px * cos).abs() / 2.0 + SINC_RING_MARGIN_PX,
                    (length_px * sin).abs() / 2.0 + SINC_RING_MARGIN_PX,
                )
            }
            Self::Jitter {
                sigma_x_px,
                sigma_y_px,
            } => (8.0 * sigma_x_px, 8.0 * sigma_y_px),
            Self::Kernel(k) => (
                (k.width as f64 / 2.0 + 1.0) / s,
                (k.height as f64 / 2.0 + 1.0) / s,
            ),
        }
    }
}

/// One image axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Axis {
    /// Along a row, to the right.
    X,
    /// Down a column.
    Y,
}

/// σ of the Gaussian whose power transfer is one half at `half_power_cyc_px`.
fn half_power_sigma(half_power_cyc_px: f64) -> f64 {
    std::f64::consts::LN_2.sqrt() / (2.0 * PI * half_power_cyc_px)
}

/// The MTF of a clear circular aperture at ν = f/f_c: (2/π)(acos ν − ν√(1−ν²)), 0 from
/// the cut-off on.
#[must_use]
pub fn diffraction_mtf(nu: f64) -> f64 {
    if nu >= 1.0 {
        0.0
    } else {
        (2.0 / PI) * (nu.acos() - nu * (1.0 - nu * nu).sqrt())
    }
}

/// sin(πx)/(πx), 1 at 0.
#[must_use]
pub fn sinc(x: f64) -> f64 {
    if x.abs() < 1e-8 {
        // The series 1 − (πx)²/6 is exact to rounding here.
        1.0 - (PI * x).powi(2) / 6.0
    } else {
        (PI * x).sin() / (PI * x)
    }
}

/// DTFT of `n` equal taps at offsets −n/2 … n−1−n/2, at `f` cycles per sample: the
/// Dirichlet kernel sin(πnf)/(n sin πf), times the phase of the taps' centre.
fn box_transfer(n: u64, f: f64) -> Complex64 {
    let nf = n as f64;
    let centre = (nf - 1.0) / 2.0 - (n / 2) as f64;
    let s = (PI * f).sin();
    let magnitude = if s.abs() < 1e-12 {
        // f is a whole number of cycles per sample: every tap is in phase.
        1.0
    } else {
        (PI * nf * f).sin() / (nf * s)
    };
    Complex64::from_polar(magnitude, -2.0 * PI * f * centre)
}

/// A cascade of MTF components (eq. 12): the OTF is the product of theirs.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(transparent)]
pub struct MtfChain {
    /// The components, in any order (the product commutes).
    pub components: Vec<Mtf>,
}

impl MtfChain {
    /// A chain of the given components.
    #[must_use]
    pub fn new(components: Vec<Mtf>) -> Self {
        Self { components }
    }

    /// Checks every component.
    ///
    /// # Errors
    /// The first invalid parameter.
    pub fn validate(&self) -> Result<()> {
        self.components.iter().try_for_each(Mtf::validate)
    }

    /// The product of the components' OTFs at (fx, fy) cycles per sensor pixel.
    #[must_use]
    pub fn otf(&self, fx: f64, fy: f64, samples_per_pixel: u32) -> Complex64 {
        self.components
            .iter()
            .fold(Complex64::new(1.0, 0.0), |acc, m| {
                acc * m.otf(fx, fy, samples_per_pixel)
            })
    }

    /// The MTF (modulus of the OTF) at (fx, fy) cycles per sensor pixel.
    #[must_use]
    pub fn mtf(&self, fx: f64, fy: f64, samples_per_pixel: u32) -> f64 {
        self.otf(fx, fy, samples_per_pixel).norm()
    }

    /// How far the cascaded PSF reaches, in sensor pixels: supports add under convolution.
    #[must_use]
    pub fn support_radius_px(&self, samples_per_pixel: u32) -> (f64, f64) {
        self.components.iter().fold((0.0, 0.0), |(ax, ay), m| {
            let (x, y) = m.support_radius_px(samples_per_pixel);
            (ax + x, ay + y)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_abs_diff_eq;

    fn all_models() -> Vec<Mtf> {
        vec![
            Mtf::Box {
                width_px: 5,
                height_px: 5,
            },
            Mtf::Box {
                width_px: 4,
                height_px: 3,
            },
            Mtf::Gaussian { sigma_px: 0.7 },
            Mtf::SchottSalvaggio {
                across_track_half_power_cyc_px: 0.3,
                along_track_half_power_cyc_px: 0.2,
            },
            Mtf::Diffraction {
                wavelength_m: 10e-6,
                f_number: 2.0,
                pixel_pitch_m: 25e-6,
            },
            Mtf::Footprint {
                width_px: 1.0,
                height_px: 0.8,
            },
            Mtf::Motion {
                length_px: 3.0,
                angle_deg: 30.0,
            },
            Mtf::Jitter {
                sigma_x_px: 0.3,
                sigma_y_px: 0.5,
            },
            Mtf::Kernel(Kernel::new(3, 2, vec![1.0, 2.0, 1.0, 0.5, 3.0, 0.5]).unwrap()),
        ]
    }

    #[test]
    fn every_model_passes_zero_frequency_unchanged() {
        for m in all_models() {
            m.validate().unwrap();
            for s in [1, 2, 4] {
                let h = m.otf(0.0, 0.0, s);
                assert_abs_diff_eq!(h.re, 1.0, epsilon = 1e-15);
                assert_abs_diff_eq!(h.im, 0.0, epsilon = 1e-15);
            }
        }
    }

    #[test]
    fn box_of_five_matches_the_dirichlet_kernel_by_hand() {
        // Five taps of 1/5 at −2..2: H(f) = (1 + 2cos 2πf + 2cos 4πf)/5.
        let m = Mtf::Box {
            width_px: 5,
            height_px: 1,
        };
        for f in [0.05, 0.1, 0.2, 0.25, 0.4, 0.5] {
            let by_hand = (1.0 + 2.0 * (2.0 * PI * f).cos() + 2.0 * (4.0 * PI * f).cos()) / 5.0;
            let h = m.otf(f, 0.0, 1);
            assert_abs_diff_eq!(h.re, by_hand, epsilon = 1e-14);
            assert_abs_diff_eq!(h.im, 0.0, epsilon = 1e-14);
        }
        // Its first zero is at 1/5 cycle per pixel.
        assert_abs_diff_eq!(m.otf(0.2, 0.0, 1).norm(), 0.0, epsilon = 1e-14);
    }

    #[test]
    fn even_box_matches_its_taps() {
        let m = Mtf::Box {
            width_px: 4,
            height_px: 1,
        };
        let k = Kernel::uniform(4, 1).unwrap();
        for f in [0.07, 0.19, 0.33, 0.5] {
            let a = m.otf(f, 0.1, 1);
            let b = k.transfer(f, 0.1);
            assert_abs_diff_eq!(a.re, b.re, epsilon = 1e-14);
            assert_abs_diff_eq!(a.im, b.im, epsilon = 1e-14);
        }
    }

    #[test]
    fn half_power_frequencies_mean_power_one_half() {
        let g = Mtf::gaussian_half_power(0.25).unwrap();
        assert_abs_diff_eq!(g.otf(0.25, 0.0, 1).re.powi(2), 0.5, epsilon = 1e-14);
        assert_abs_diff_eq!(g.otf(0.0, 0.25, 1).re.powi(2), 0.5, epsilon = 1e-14);
        let ss = Mtf::SchottSalvaggio {
            across_track_half_power_cyc_px: 0.3,
            along_track_half_power_cyc_px: 0.15,
        };
        assert_abs_diff_eq!(ss.otf(0.3, 0.0, 1).re.powi(2), 0.5, epsilon = 1e-14);
        assert_abs_diff_eq!(ss.otf(0.0, 0.15, 1).re.powi(2), 0.5, epsilon = 1e-14);
        // Separable: the 2-D transfer is the product of the two 1-D ones.
        let p = ss.otf(0.3, 0.15, 1).re;
        assert_abs_diff_eq!(p, 0.5, epsilon = 1e-14);
    }

    #[test]
    fn diffraction_cuts_off_at_pitch_over_lambda_n() {
        // λ = 10 µm, N = 2, pitch 25 µm: f_c = 25/(10·2) = 1.25 cycles per pixel.
        let m = Mtf::Diffraction {
            wavelength_m: 10e-6,
            f_number: 2.0,
            pixel_pitch_m: 25e-6,
        };
        assert_abs_diff_eq!(m.otf(1.25, 0.0, 1).re, 0.0, epsilon = 1e-12);
        assert_abs_diff_eq!(m.otf(0.0, 2.0, 1).re, 0.0, epsilon = 1e-12);
        // At half the cut-off: (2/π)(acos ½ − ½·√¾) = 0.391 002 219 ...
        let by_hand = (2.0 / PI) * (PI / 3.0 - 0.5 * 0.75_f64.sqrt());
        assert_abs_diff_eq!(m.otf(0.625, 0.0, 1).re, by_hand, epsilon = 1e-14);
        assert_abs_diff_eq!(by_hand, 0.391_002_219, epsilon = 1e-9);
    }

    #[test]
    fn footprint_and_motion_are_sincs() {
        let f = Mtf::Footprint {
            width_px: 1.0,
            height_px: 1.0,
        };
        // sinc(½) = 2/π at Nyquist.
        assert_abs_diff_eq!(f.otf(0.5, 0.0, 1).re, 2.0 / PI, epsilon = 1e-15);
        let m = Mtf::Motion {
            length_px: 2.0,
            angle_deg: 90.0,
        };
        assert_abs_diff_eq!(m.otf(0.4, 0.0, 1).re, 1.0, epsilon = 1e-12);
        assert_abs_diff_eq!(m.otf(0.0, 0.5, 1).re, 0.0, epsilon = 1e-15);
    }

    #[test]
    fn separable_parts_multiply_to_the_otf() {
        for m in all_models() {
            for (fx, fy) in [(0.13, 0.0), (0.21, 0.37), (-0.45, 0.1)] {
                let Some(x) = m.separable_otf(fx, Axis::X, 2) else {
                    continue;
                };
                let y = m.separable_otf(fy, Axis::Y, 2).unwrap();
                let whole = m.otf(fx, fy, 2);
                assert_abs_diff_eq!((x * y).re, whole.re, epsilon = 1e-14);
                assert_abs_diff_eq!((x * y).im, whole.im, epsilon = 1e-14);
            }
        }
    }

    #[test]
    fn cascade_is_the_product() {
        let chain = MtfChain::new(all_models());
        for (fx, fy) in [(0.1, 0.0), (0.2, 0.3), (0.45, -0.1)] {
            let mut p = Complex64::new(1.0, 0.0);
            for m in &chain.components {
                p *= m.otf(fx, fy, 2);
            }
            let c = chain.otf(fx, fy, 2);
            assert_abs_diff_eq!(c.re, p.re, epsilon = 1e-15);
            assert_abs_diff_eq!(c.im, p.im, epsilon = 1e-15);
        }
    }

    #[test]
    fn bad_parameters_are_refused() {
        for bad in [
            Mtf::Box {
                width_px: 0,
                height_px: 5,
            },
            Mtf::Gaussian { sigma_px: f64::NAN },
            Mtf::Gaussian { sigma_px: -1.0 },
            Mtf::Diffraction {
                wavelength_m: 10e-6,
                f_number: 0.0,
                pixel_pitch_m: 1e-5,
            },
            Mtf::Motion {
                length_px: f64::INFINITY,
                angle_deg: 0.0,
            },
            Mtf::Kernel(Kernel {
                width: 2,
                height: 1,
                taps: vec![1.0, -1.0],
            }),
        ] {
            assert!(bad.validate().is_err(), "{bad:?} was accepted");
        }
        assert!(Mtf::gaussian_half_power(0.0).is_err());
        assert!(Kernel::new(2, 2, vec![1.0; 3]).is_err());
    }
}
