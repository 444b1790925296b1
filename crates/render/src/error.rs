//! A request that cannot be carried out as made: the tool that made it (from its flags)
//! reports it as bad usage, naming the flag of [`RequestError::setting`]. Errors of the
//! inputs' content are `irsig_formats::ParseError`s at their file, line and column, and
//! come through as they are.

/// The setting of a [`crate::Request`] an error is about: the tool names its flag.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Setting {
    /// The band (`Request::band`).
    Band,
    /// The atmosphere (`Request::atmosphere`).
    Atmosphere,
    /// The vacuum's sky radiance.
    SkyRadiance,
    /// The sub-band count.
    SubBands,
    /// The tolerance of the pilot.
    Tolerance,
    /// The percentile the tolerance applies to.
    TolerancePercentile,
    /// A pinned model of the pilot.
    Pin,
    /// The materials.
    Materials,
    /// A tile of the frame.
    Tile,
    /// The pixel probed.
    Probe,
    /// The outputs asked for.
    Outputs,
}

/// A request that cannot be carried out as made.
#[derive(Debug, Clone, PartialEq, thiserror::Error, miette::Diagnostic)]
#[error("{message}")]
#[diagnostic(code(irsig::render::request))]
pub struct RequestError {
    /// What the request got wrong.
    pub setting: Setting,
    /// Why, without the flag's name (the tool adds it).
    pub message: String,
}

impl RequestError {
    /// A report of a request error about `setting`.
    #[must_use]
    pub fn report(setting: Setting, message: impl Into<String>) -> miette::Report {
        miette::Report::new(Self {
            setting,
            message: message.into(),
        })
    }
}
