use std::fmt;

/// A value in the model that breaks one of its rules (an emissivity above 1, a facet that
/// names a vertex that does not exist, altitudes that do not increase).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{path}: {kind}")]
pub struct ModelError {
    /// Where the value sits, as a path into the data: `materials[3].emissivity[2]`.
    pub path: String,
    /// What is wrong with it.
    pub kind: ModelErrorKind,
}

/// What is wrong with a value.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum ModelErrorKind {
    /// A number is NaN or infinite.
    NotFinite,
    /// A number lies outside the range it must lie in.
    OutOfRange {
        /// The offending value.
        value: f64,
        /// The inclusive lower bound.
        min: f64,
        /// The inclusive upper bound.
        max: f64,
    },
    /// A sequence that must increase strictly does not.
    NotIncreasing {
        /// The previous value.
        previous: f64,
        /// The value that does not exceed it.
        value: f64,
    },
    /// An index points past the end of what it indexes.
    IndexOutOfRange {
        /// The index.
        index: u64,
        /// The length of what it indexes.
        len: u64,
    },
    /// A table or list that must not be empty is.
    Empty,
    /// Two entries share a key that must be unique.
    Duplicate(String),
    /// A triangle whose three vertices are collinear or coincide.
    DegenerateTriangle,
    /// Anything else, in words.
    Other(String),
}

impl fmt::Display for ModelErrorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NotFinite => write!(f, "expected a finite number, found NaN or infinity"),
            Self::OutOfRange { value, min, max } => {
                write!(f, "{value} is out of range: expected {min} to {max}")
            }
            Self::NotIncreasing { previous, value } => {
                write!(f, "{value} does not increase after {previous}")
            }
            Self::IndexOutOfRange { index, len } => {
                write!(f, "index {index} is out of range for {len} entries")
            }
            Self::Empty => write!(f, "must not be empty"),
            Self::Duplicate(key) => write!(f, "duplicate `{key}`"),
            Self::DegenerateTriangle => write!(f, "degenerate triangle (zero area)"),
            Self::Other(text) => f.write_str(text),
        }
    }
}

impl ModelError {
    pub(crate) fn new(path: impl Into<String>, kind: ModelErrorKind) -> Self {
        Self {
            path: path.into(),
            kind,
        }
    }
}

/// Checks that `value` is finite and within `[min, max]`.
pub(crate) fn check_range(
    path: impl Fn() -> String,
    value: f64,
    min: f64,
    max: f64,
) -> Result<(), ModelError> {
    if !value.is_finite() {
        return Err(ModelError::new(path(), ModelErrorKind::NotFinite));
    }
    if value < min || value > max {
        return Err(ModelError::new(
            path(),
            ModelErrorKind::OutOfRange { value, min, max },
        ));
    }
    Ok(())
}

/// Checks that every value is finite.
pub(crate) fn check_finite(path: impl Fn() -> String, values: &[f64]) -> Result<(), ModelError> {
    if values.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(ModelError::new(path(), ModelErrorKind::NotFinite))
    }
}

/// Checks that a sequence increases strictly.
pub(crate) fn check_increasing(
    path: impl Fn(usize) -> String,
    values: impl IntoIterator<Item = f64>,
) -> Result<(), ModelError> {
    let mut previous: Option<f64> = None;
    for (i, v) in values.into_iter().enumerate() {
        if let Some(p) = previous {
            if v <= p {
                return Err(ModelError::new(
                    path(i),
                    ModelErrorKind::NotIncreasing {
                        previous: p,
                        value: v,
                    },
                ));
            }
        }
        previous = Some(v);
    }
    Ok(())
}
