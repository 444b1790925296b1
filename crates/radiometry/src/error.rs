use std::fmt;

/// A value the radiometry functions cannot work with, and why.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{kind}: {message}")]
pub struct RadiometryError {
    /// What kind of value was wrong.
    pub kind: RadiometryErrorKind,
    /// What was wrong with it, with the offending value.
    pub message: String,
}

/// The kinds of [`RadiometryError`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum RadiometryErrorKind {
    /// Band limits that are not finite, not positive, or not increasing.
    InvalidBand,
    /// A sensor response table that is too short, not increasing in wavelength, has a
    /// negative or non-finite response, or is zero over the whole band.
    InvalidResponse,
    /// An angular emissivity table with angles outside 0–90°, not increasing, or
    /// emissivities outside [0, 1].
    InvalidEmissivity,
    /// A complex refractive index with a non-finite or non-positive real part, a negative
    /// or non-finite imaginary part, or a wavelength table that is unusable.
    InvalidRefractiveIndex,
    /// A temperature that is negative, zero where a positive one is needed, or not finite.
    InvalidTemperature,
    /// A shape factor, emissivity or other fraction outside [0, 1], or a radiance that is
    /// negative or not finite.
    InvalidParameter,
}

impl fmt::Display for RadiometryErrorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::InvalidBand => "invalid band",
            Self::InvalidResponse => "invalid sensor response",
            Self::InvalidEmissivity => "invalid emissivity table",
            Self::InvalidRefractiveIndex => "invalid refractive index",
            Self::InvalidTemperature => "invalid temperature",
            Self::InvalidParameter => "invalid parameter",
        })
    }
}

impl RadiometryError {
    pub(crate) fn new(kind: RadiometryErrorKind, message: impl Into<String>) -> Self {
        Self {
            kind,
            message: message.into(),
        }
    }
}
