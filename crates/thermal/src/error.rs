use std::fmt;

/// Why a wall could not be built or a step could not be taken, with the numbers involved.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{kind}: {message}")]
pub struct ThermalError {
    /// What kind of failure it is.
    pub kind: ThermalErrorKind,
    /// What was wrong, with the offending values (a facet's loads and temperatures where a
    /// step failed), in words.
    pub message: String,
}

/// The kinds of [`ThermalError`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum ThermalErrorKind {
    /// A number the solver was given is NaN, infinite or outside its range: a load, a
    /// surface property, a time step that is not positive, a temperature array of the
    /// wrong length.
    InvalidInput,
    /// A wall that cannot be discretised: its material record breaks a rule, the node
    /// spacing asked for is not usable, or it would need more than [`crate::MAX_NODES`]
    /// nodes.
    InvalidWall,
    /// The surface energy balance did not converge.
    NotConverged,
    /// A temperature left the physical range [`crate::MIN_TEMPERATURE_K`] to
    /// [`crate::MAX_TEMPERATURE_K`].
    OutOfRange,
}

impl fmt::Display for ThermalErrorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::InvalidInput => "invalid input",
            Self::InvalidWall => "wall cannot be discretised",
            Self::NotConverged => "surface energy balance did not converge",
            Self::OutOfRange => "temperature out of range",
        })
    }
}

impl ThermalError {
    pub(crate) fn new(kind: ThermalErrorKind, message: impl Into<String>) -> Self {
        Self {
            kind,
            message: message.into(),
        }
    }

    pub(crate) fn input(message: impl Into<String>) -> Self {
        Self::new(ThermalErrorKind::InvalidInput, message)
    }

    pub(crate) fn wall(message: impl Into<String>) -> Self {
        Self::new(ThermalErrorKind::InvalidWall, message)
    }
}
