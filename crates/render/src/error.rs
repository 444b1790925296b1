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
    /// The sun's zenith angle (a sun given as a direction).
    SunZenith,
    /// The sun's azimuth (a sun given as a direction).
    SunAzimuth,
    /// The time the sun is seen at (a sun given by a time and a place).
    SunUtc,
    /// The latitude of the place the sun is seen from.
    Latitude,
    /// The longitude of the place the sun is seen from.
    Longitude,
    /// The altitude above sea level of the place the sun is seen from.
    SiteAltitude,
    /// The sun's shadow rays per hit.
    SunShadowRays,
}

impl Setting {
    /// The setting's name, as the tools spell it (kebab-case): `sub-bands`, `sky-radiance`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Band => "band",
            Self::Atmosphere => "atmosphere",
            Self::SkyRadiance => "sky-radiance",
            Self::SubBands => "sub-bands",
            Self::Tolerance => "tolerance",
            Self::TolerancePercentile => "tolerance-percentile",
            Self::Pin => "pin",
            Self::Materials => "materials",
            Self::Tile => "tile",
            Self::Probe => "probe",
            Self::Outputs => "outputs",
            Self::SunZenith => "sun-zenith-deg",
            Self::SunAzimuth => "sun-azimuth-deg",
            Self::SunUtc => "sun-utc",
            Self::Latitude => "latitude-deg",
            Self::Longitude => "longitude-deg",
            Self::SiteAltitude => "altitude-m",
            Self::SunShadowRays => "sun-shadow-rays",
        }
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
