//! The one error type of the sensor model.

/// Why a sensor-model operation refused its input.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{kind}")]
pub struct SensorError {
    kind: SensorErrorKind,
}

impl SensorError {
    /// What went wrong.
    #[must_use]
    pub fn kind(&self) -> &SensorErrorKind {
        &self.kind
    }

    pub(crate) fn parameter(name: &'static str, value: f64, expected: &'static str) -> Self {
        SensorErrorKind::InvalidParameter {
            name,
            value,
            expected,
        }
        .into()
    }
}

impl From<SensorErrorKind> for SensorError {
    fn from(kind: SensorErrorKind) -> Self {
        Self { kind }
    }
}

/// The kinds of [`SensorError`].
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SensorErrorKind {
    /// A model parameter is NaN, infinite or outside its physical range.
    #[error("parameter `{name}` = {value} is out of range: expected {expected}")]
    InvalidParameter {
        /// The parameter's name, with its unit.
        name: &'static str,
        /// The value given.
        value: f64,
        /// What the parameter must be.
        expected: &'static str,
    },
    /// An image has no pixels.
    #[error("the image is empty ({width} x {height} pixels)")]
    EmptyImage {
        /// Width in pixels.
        width: usize,
        /// Height in pixels.
        height: usize,
    },
    /// The data length does not match width × height.
    #[error("image data has {actual} values but {width} x {height} = {} were expected", width * height)]
    SizeMismatch {
        /// Width in pixels.
        width: usize,
        /// Height in pixels.
        height: usize,
        /// Number of values given.
        actual: usize,
    },
    /// A pixel holds NaN or an infinity where a radiance was expected.
    #[error("pixel (x {x}, y {y}) holds {value}: expected a finite radiance")]
    NonFinitePixel {
        /// Column, 0 at the left.
        x: usize,
        /// Row, 0 at the top.
        y: usize,
        /// The value found.
        value: f64,
    },
    /// The image cannot be divided into whole k × k blocks.
    #[error(
        "a {width} x {height} image cannot be reduced by {factor}: both sides must be multiples of it"
    )]
    NotDivisible {
        /// Width in pixels.
        width: usize,
        /// Height in pixels.
        height: usize,
        /// The reduction factor.
        factor: usize,
    },
    /// A convolution kernel is empty or its weights sum to zero.
    #[error("convolution kernel is invalid: {reason}")]
    InvalidKernel {
        /// What is wrong with it.
        reason: String,
    },
}

/// Result with a [`SensorError`].
pub type Result<T> = std::result::Result<T, SensorError>;

/// Checks that a parameter is finite and strictly positive.
pub(crate) fn positive(name: &'static str, value: f64) -> Result<f64> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(SensorError::parameter(
            name,
            value,
            "a finite number greater than 0",
        ))
    }
}

/// Checks that a parameter is finite and not negative.
pub(crate) fn non_negative(name: &'static str, value: f64) -> Result<f64> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(SensorError::parameter(
            name,
            value,
            "a finite number of at least 0",
        ))
    }
}

/// Checks that a parameter is finite.
pub(crate) fn finite(name: &'static str, value: f64) -> Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(SensorError::parameter(name, value, "a finite number"))
    }
}
