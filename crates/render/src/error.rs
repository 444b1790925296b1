//! A request that cannot be carried out as made: the tool that made it (from its flags)
//! reports it as bad usage, naming the flag of [`RequestError::setting`]. Errors of the
//! inputs' content are `irsig_formats::ParseError`s at their file, line and column, and
//! come through as they are.

use irsig_atmosphere::sun::SunField;

/// The setting of a [`crate::Request`] an error is about: the tool names its flag (each
/// tool maps every setting to the flag it spells it with, so the library knows none).
/// Exhaustive, so that a tool's mapping is checked by the compiler when a setting is added.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
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
    /// A tile of the frame.
    Tile,
    /// The pixel probed.
    Probe,
    /// A field of the sun's position (`SunRequest::spec`): its zenith angle or azimuth for a
    /// direction; its time, latitude, longitude or altitude for a time and a place.
    Sun(SunField),
    /// The sun's shadow rays per hit.
    SunShadowRays,
}

/// How the maker of a request spells each setting where the user reads it (`--sub-bands` on
/// a command line): the library names settings, never flags, and words what it says about
/// one (a warning, the advice in an error, a decision's reasons) in its caller's spelling.
#[derive(Clone, Copy)]
pub struct Spelling(pub fn(Setting) -> String);

impl Spelling {
    /// How `setting` is spelt.
    #[must_use]
    pub fn of(self, setting: Setting) -> String {
        (self.0)(setting)
    }
}

impl std::fmt::Debug for Spelling {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("Spelling(..)")
    }
}

impl PartialEq for Spelling {
    /// Two requests that differ only in how their settings are spelt render the same.
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

/// A request that cannot be carried out as made: `VALUE: MESSAGE`, or `MESSAGE` alone,
/// which the tool prefixes with the flag of [`RequestError::setting`].
#[derive(Debug, Clone, PartialEq, thiserror::Error, miette::Diagnostic)]
#[error("{}{message}", value.as_ref().map(|v| format!("{v}: ")).unwrap_or_default())]
#[diagnostic(code(irsig::render::request))]
pub struct RequestError {
    /// What the request got wrong.
    pub setting: Setting,
    /// The value at fault, as the user would write it, if one is.
    pub value: Option<String>,
    /// Why, without the flag's name (the tool adds it).
    pub message: String,
}

impl RequestError {
    /// A report of a request error about `setting`.
    #[must_use]
    pub fn report(setting: Setting, message: impl Into<String>) -> miette::Report {
        miette::Report::new(Self {
            setting,
            value: None,
            message: message.into(),
        })
    }

    /// A report of a request error about `setting`'s `value`.
    #[must_use]
    pub fn of_value(
        setting: Setting,
        value: impl std::fmt::Display,
        message: impl Into<String>,
    ) -> miette::Report {
        miette::Report::new(Self {
            setting,
            value: Some(value.to_string()),
            message: message.into(),
        })
    }
}
