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

/// A number as a person reads it: as written for ordinary magnitudes, in scientific notation
/// (`1.797e308`, `2.5e-12`) for very large or very small ones, never hundreds of digits.
struct Number(f64);

impl fmt::Display for Number {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let a = self.0.abs();
        if a != 0.0 && a.is_finite() && !(1e-6..1e15).contains(&a) {
            write!(f, "{:e}", self.0)
        } else {
            write!(f, "{}", self.0)
        }
    }
}

impl fmt::Display for ModelErrorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NotFinite => write!(f, "expected a finite number, found NaN or infinity"),
            Self::OutOfRange { value, min, max } => {
                let (value, min) = (Number(*value), Number(*min));
                if *max >= f64::MAX {
                    write!(f, "{value} is out of range: expected at least {min}")
                } else {
                    write!(
                        f,
                        "{value} is out of range: expected {min} to {}",
                        Number(*max)
                    )
                }
            }
            Self::NotIncreasing { previous, value } => {
                write!(
                    f,
                    "{} does not increase after {}",
                    Number(*value),
                    Number(*previous)
                )
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bounds_are_short_whatever_their_size() {
        // f64::MAX as an upper bound used to be written out in 309 digits.
        let e = ModelErrorKind::OutOfRange {
            value: -1.0,
            min: 1e-12,
            max: f64::MAX,
        };
        assert_eq!(e.to_string(), "-1 is out of range: expected at least 1e-12");
        let e = ModelErrorKind::OutOfRange {
            value: 1e300,
            min: 0.0,
            max: 1.0,
        };
        assert_eq!(e.to_string(), "1e300 is out of range: expected 0 to 1");
        let e = ModelErrorKind::NotIncreasing {
            previous: 40.0,
            value: 0.5,
        };
        assert_eq!(e.to_string(), "0.5 does not increase after 40");
    }
}
