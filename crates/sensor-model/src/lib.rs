//! The irsig sensor model: what a thermal imager does to the radiance field the tracer
//! computes (thesis §3.4, §4.2, §5.2). Pure image maths: no file syntax, no printing.
//!
//! - [`mtf`]: MTF models (box IFOV, Gaussian, Schott & Salvaggio, diffraction, detector
//!   footprint, motion, jitter, explicit kernels) and their cascade, eq. 12;
//! - [`blur`]: the cascade applied by FFT, with explicit edge handling, and direct
//!   convolution for small kernels;
//! - [`sample`]: reduction from the render grid to the sensor grid (block mean for
//!   continuous layers, majority for categorical ones);
//! - [`noise`]: NEΔT → radiance σ, seeded Gaussian noise;
//! - [`quantise`]: radiance → digital counts (fixed gain/offset, the thesis's DC/K
//!   auto-bias of Figure 14, or a fixed NEΔT-style calibration), the LUT, and apparent
//!   temperature.
//!
//! **Conventions.** Images are row-major, row 0 at the top, x to the right. Spatial
//! frequencies are in cycles per sensor pixel (Nyquist = 0.5). Radiance is band radiance in
//! W m⁻² sr⁻¹; temperatures in kelvin.
//!
//! ```
//! use irsig_sensor_model::{Plane, blur::{blur, EdgeMode}, mtf::{Mtf, MtfChain}};
//! use irsig_sensor_model::quantise::Quantiser;
//!
//! // A hot 1-pixel point on a 30 W m^-2 sr^-1 background, seen through the thesis's 5×5
//! // IFOV and a diffraction-limited f/2 optic with 25 µm pixels at 10 µm.
//! let mut radiance = vec![30.0; 32 * 32];
//! radiance[16 * 32 + 16] = 55.0;
//! let image = Plane::new(32, 32, radiance)?;
//! let chain = MtfChain::new(vec![
//!     Mtf::Box { width_px: 5, height_px: 5 },
//!     Mtf::Diffraction { wavelength_m: 10e-6, f_number: 2.0, pixel_pitch_m: 25e-6 },
//! ]);
//! let seen = blur(&image, &chain, EdgeMode::Reflect, 1)?;
//! // The blur spreads the point but keeps its energy.
//! let excess: f64 = seen.data.iter().map(|l| l - 30.0).sum();
//! assert!((excess - 25.0).abs() < 1e-9);
//!
//! // 8-bit counts, 10 counts per W m^-2 sr^-1, 30 W m^-2 sr^-1 at count 100.
//! let q = Quantiser::from_gain_offset(8, 10.0, -200.0)?;
//! assert_eq!(q.count(30.0), 100);
//! # Ok::<(), irsig_sensor_model::SensorError>(())
//! ```

#![deny(clippy::print_stdout, clippy::print_stderr)]

pub mod blur;
mod error;
pub mod mtf;
pub mod noise;
pub mod quantise;
pub mod sample;

pub use error::{Result, SensorError, SensorErrorKind};

/// One image plane of f64 values, row-major, row 0 at the top.
#[derive(Debug, Clone, PartialEq)]
pub struct Plane {
    /// Columns.
    pub width: usize,
    /// Rows.
    pub height: usize,
    /// `width × height` values, row-major.
    pub data: Vec<f64>,
}

impl Plane {
    /// A plane from its values.
    ///
    /// # Errors
    /// An empty size, or data whose length is not `width × height`.
    pub fn new(width: usize, height: usize, data: Vec<f64>) -> Result<Self> {
        let plane = Self {
            width,
            height,
            data,
        };
        plane.check()?;
        Ok(plane)
    }

    /// A plane from f32 values (as stored in EXR layers).
    ///
    /// # Errors
    /// As [`Plane::new`].
    pub fn from_f32(width: usize, height: usize, data: &[f32]) -> Result<Self> {
        Self::new(width, height, data.iter().map(|&v| f64::from(v)).collect())
    }

    /// The values rounded to f32.
    #[must_use]
    pub fn to_f32(&self) -> Vec<f32> {
        self.data.iter().map(|&v| v as f32).collect()
    }

    /// The first pixel that is NaN or infinite, as an error naming it.
    ///
    /// # Errors
    /// That pixel.
    pub fn check_finite(&self) -> Result<()> {
        match self.data.iter().position(|v| !v.is_finite()) {
            None => Ok(()),
            Some(i) => Err(SensorErrorKind::NonFinitePixel {
                x: i % self.width,
                y: i / self.width,
                value: self.data[i],
            }
            .into()),
        }
    }

    pub(crate) fn check(&self) -> Result<()> {
        if self.width == 0 || self.height == 0 {
            return Err(SensorErrorKind::EmptyImage {
                width: self.width,
                height: self.height,
            }
            .into());
        }
        if self.width.checked_mul(self.height) != Some(self.data.len()) {
            return Err(SensorErrorKind::SizeMismatch {
                width: self.width,
                height: self.height,
                actual: self.data.len(),
            }
            .into());
        }
        Ok(())
    }
}
