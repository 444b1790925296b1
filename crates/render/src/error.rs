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
    /// A request error about `setting`, with no value to quote.
    #[must_use]
    pub fn new(setting: Setting, message: impl Into<String>) -> Self {
        Self {
            setting,
            value: None,
            message: message.into(),
        }
    }

    /// A request error about `setting`'s `value`.
    #[must_use]
    pub fn with_value(
        setting: Setting,
        value: impl std::fmt::Display,
        message: impl Into<String>,
    ) -> Self {
        Self {
            setting,
            value: Some(value.to_string()),
            message: message.into(),
        }
    }

    /// A report of a request error about `setting` (for a tool that checks a setting
    /// itself before it makes a request).
    #[must_use]
    pub fn report(setting: Setting, message: impl Into<String>) -> miette::Report {
        miette::Report::new(Self::new(setting, message))
    }

    /// A report of a request error about `setting`'s `value`.
    #[must_use]
    pub fn of_value(
        setting: Setting,
        value: impl std::fmt::Display,
        message: impl Into<String>,
    ) -> miette::Report {
        miette::Report::new(Self::with_value(setting, value, message))
    }
}

/// Why a frame's library work failed: the request, an input's content, the physics
/// libraries' refusals, the caller's own sink, or an invariant of the run. Each kind keeps
/// the error it wraps as its [`std::error::Error::source`] (and, where that is a
/// [`miette::Diagnostic`], as its diagnostic source), so that an input's file, line and
/// column and its underlined snippet reach the user as the parser said them.
#[derive(Debug, thiserror::Error)]
#[error(transparent)]
pub struct RenderError {
    /// What went wrong (boxed: a parse error and its context would make every
    /// `Result` of the crate large).
    pub kind: Box<RenderErrorKind>,
}

/// What went wrong in a frame's library work.
#[derive(Debug, thiserror::Error, miette::Diagnostic)]
#[non_exhaustive]
pub enum RenderErrorKind {
    /// A request that cannot be carried out as made: the tool names the flag.
    #[error(transparent)]
    #[diagnostic(transparent)]
    Request(RequestError),
    /// An input whose content is wrong, at its file, line and column.
    #[error("{context}")]
    #[diagnostic(code(irsig::render::input))]
    Input {
        /// Which input, and what was being done with it.
        context: String,
        /// The parser's error, with its place in the file.
        #[source]
        #[diagnostic_source]
        source: irsig_formats::ParseError,
    },
    /// The atmosphere cannot be modelled as asked (a model its tables do not allow, a band
    /// its spectra do not cover).
    #[error("{context}")]
    #[diagnostic(code(irsig::render::atmosphere))]
    Atmosphere {
        /// What was being built.
        context: String,
        /// The atmosphere library's error.
        #[source]
        source: irsig_atmosphere::AtmosphereError,
    },
    /// A material's image maps cannot be had (a missing or unusable image, a mapping that
    /// breaks a rule of its declaration).
    #[error("{context}")]
    #[diagnostic(code(irsig::render::maps))]
    Maps {
        /// Which material, in which library.
        context: String,
        /// The texture's error, naming the map and its image.
        #[source]
        source: irsig_texture::TextureError,
    },
    /// A band, a sub-band or a material's emissivity over one that the radiometry refuses.
    #[error("{context}")]
    #[diagnostic(code(irsig::render::band))]
    Band {
        /// Which band.
        context: String,
        /// The radiometry's error.
        #[source]
        source: irsig_radiometry::RadiometryError,
    },
    /// The tracer refuses the scene, the settings or a view, or fails tracing.
    #[error("{context}")]
    #[diagnostic(code(irsig::render::trace))]
    Trace {
        /// What was being traced or built.
        context: String,
        /// The tracer's error.
        #[source]
        source: irsig_tracer::TraceError,
    },
    /// The digital counts cannot be made (a calibration the quantiser refuses).
    #[error("{context}")]
    #[diagnostic(code(irsig::render::counts))]
    Counts {
        /// What was being made.
        context: String,
        /// The sensor model's error.
        #[source]
        source: irsig_sensor_model::SensorError,
    },
    /// A frame's file cannot be encoded (PNG, EXR, the provenance's RON).
    #[error("{context}")]
    #[diagnostic(code(irsig::render::encode))]
    Encode {
        /// Which file.
        context: String,
        /// The encoder's error.
        #[source]
        source: Box<dyn std::error::Error + Send + Sync>,
    },
    /// The caller's own error, from the sink it gave a frame's files to or the reader it
    /// gave the atmosphere's name to.
    #[error("{context}")]
    #[diagnostic(code(irsig::render::caller))]
    Caller {
        /// What the caller was asked to do.
        context: String,
        /// The caller's error, as it said it.
        #[source]
        #[diagnostic_source]
        source: CallerError,
    },
    /// A run the inputs, together, cannot make (a material id the interaction map cannot
    /// hold, a camera above a built-in atmosphere's data, a reference's stopping
    /// difference out of range).
    #[error("{0}")]
    #[diagnostic(code(irsig::render::refused))]
    Refused(String),
    /// An invariant of the run broken (a lock poisoned by a panic, the inputs read out of
    /// order): a bug of the caller or of this crate, never of the inputs.
    #[error("{0}")]
    #[diagnostic(code(irsig::render::internal))]
    Internal(String),
}

impl miette::Diagnostic for RenderError {
    fn code<'a>(&'a self) -> Option<Box<dyn std::fmt::Display + 'a>> {
        self.kind.code()
    }
    fn severity(&self) -> Option<miette::Severity> {
        self.kind.severity()
    }
    fn help<'a>(&'a self) -> Option<Box<dyn std::fmt::Display + 'a>> {
        self.kind.help()
    }
    fn url<'a>(&'a self) -> Option<Box<dyn std::fmt::Display + 'a>> {
        self.kind.url()
    }
    fn source_code(&self) -> Option<&dyn miette::SourceCode> {
        self.kind.source_code()
    }
    fn labels(&self) -> Option<Box<dyn Iterator<Item = miette::LabeledSpan> + '_>> {
        self.kind.labels()
    }
    fn related<'a>(&'a self) -> Option<Box<dyn Iterator<Item = &'a dyn miette::Diagnostic> + 'a>> {
        self.kind.related()
    }
    fn diagnostic_source(&self) -> Option<&dyn miette::Diagnostic> {
        self.kind.diagnostic_source()
    }
}

impl From<RenderErrorKind> for RenderError {
    fn from(kind: RenderErrorKind) -> Self {
        Self {
            kind: Box::new(kind),
        }
    }
}

impl From<RequestError> for RenderError {
    fn from(e: RequestError) -> Self {
        RenderErrorKind::Request(e).into()
    }
}

impl RenderError {
    /// The request error this is, if it is one: the tool reports it as bad usage of the
    /// flag of its setting.
    #[must_use]
    pub fn as_request(&self) -> Option<&RequestError> {
        match &*self.kind {
            RenderErrorKind::Request(e) => Some(e),
            _ => None,
        }
    }

    /// The caller's own error back, whole, if this is one (its sink's or its reader's): a
    /// tool's usage error or a broken pipe then reaches the tool's exit code as the tool
    /// made it, not as the render's.
    ///
    /// # Errors
    /// `self`, when it is not the caller's error.
    pub fn into_caller(self) -> Result<miette::Report, Self> {
        match *self.kind {
            RenderErrorKind::Caller { source, .. } => Ok(source.0),
            kind => Err(kind.into()),
        }
    }

    /// An input's content is wrong: `source` says where.
    pub(crate) fn input(context: impl Into<String>, source: irsig_formats::ParseError) -> Self {
        RenderErrorKind::Input {
            context: context.into(),
            source,
        }
        .into()
    }

    /// The atmosphere library refuses what `context` says was being built.
    pub(crate) fn atmosphere(
        context: impl Into<String>,
        source: irsig_atmosphere::AtmosphereError,
    ) -> Self {
        RenderErrorKind::Atmosphere {
            context: context.into(),
            source,
        }
        .into()
    }

    /// The radiometry refuses the band `context` names.
    pub(crate) fn band(
        context: impl Into<String>,
        source: irsig_radiometry::RadiometryError,
    ) -> Self {
        RenderErrorKind::Band {
            context: context.into(),
            source,
        }
        .into()
    }

    /// A material's maps cannot be had.
    pub(crate) fn maps(context: impl Into<String>, source: irsig_texture::TextureError) -> Self {
        RenderErrorKind::Maps {
            context: context.into(),
            source,
        }
        .into()
    }

    /// The tracer refuses what `context` says was being traced or built.
    pub(crate) fn trace(context: impl Into<String>, source: irsig_tracer::TraceError) -> Self {
        RenderErrorKind::Trace {
            context: context.into(),
            source,
        }
        .into()
    }

    /// The sensor model cannot make the counts `context` names.
    pub(crate) fn counts(
        context: impl Into<String>,
        source: irsig_sensor_model::SensorError,
    ) -> Self {
        RenderErrorKind::Counts {
            context: context.into(),
            source,
        }
        .into()
    }

    /// The file `context` names cannot be encoded.
    pub(crate) fn encode(
        context: impl Into<String>,
        source: impl std::error::Error + Send + Sync + 'static,
    ) -> Self {
        RenderErrorKind::Encode {
            context: context.into(),
            source: Box::new(source),
        }
        .into()
    }

    /// The caller's own error, when asked to do what `context` says.
    pub(crate) fn caller(context: impl Into<String>, report: miette::Report) -> Self {
        RenderErrorKind::Caller {
            context: context.into(),
            source: CallerError(report),
        }
        .into()
    }

    /// A run the inputs cannot make, and why.
    pub(crate) fn refused(message: impl Into<String>) -> Self {
        RenderErrorKind::Refused(message.into()).into()
    }

    /// A broken invariant of the run.
    pub(crate) fn internal(message: impl Into<String>) -> Self {
        RenderErrorKind::Internal(message.into()).into()
    }
}

/// The error a caller's sink or reader returned, kept whole: its message, its code, its
/// snippet and its own sources, as the caller made them.
pub struct CallerError(pub miette::Report);

impl std::fmt::Debug for CallerError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        std::fmt::Debug::fmt(&self.0, f)
    }
}

impl std::fmt::Display for CallerError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        std::fmt::Display::fmt(&self.0, f)
    }
}

impl std::error::Error for CallerError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        self.0.source()
    }
}

impl miette::Diagnostic for CallerError {
    fn code<'a>(&'a self) -> Option<Box<dyn std::fmt::Display + 'a>> {
        self.0.code()
    }
    fn severity(&self) -> Option<miette::Severity> {
        self.0.severity()
    }
    fn help<'a>(&'a self) -> Option<Box<dyn std::fmt::Display + 'a>> {
        self.0.help()
    }
    fn url<'a>(&'a self) -> Option<Box<dyn std::fmt::Display + 'a>> {
        self.0.url()
    }
    fn source_code(&self) -> Option<&dyn miette::SourceCode> {
        self.0.source_code()
    }
    fn labels(&self) -> Option<Box<dyn Iterator<Item = miette::LabeledSpan> + '_>> {
        self.0.labels()
    }
    fn related<'a>(&'a self) -> Option<Box<dyn Iterator<Item = &'a dyn miette::Diagnostic> + 'a>> {
        self.0.related()
    }
    fn diagnostic_source(&self) -> Option<&dyn miette::Diagnostic> {
        self.0.diagnostic_source()
    }
}

/// The whole chain of `e`'s messages, `: `-joined, as a log line shows it: what tests
/// match words against.
#[cfg(test)]
pub(crate) fn chain_text(e: &dyn std::error::Error) -> String {
    let mut text = e.to_string();
    let mut next = e.source();
    while let Some(s) = next {
        text.push_str(": ");
        text.push_str(&s.to_string());
        next = s.source();
    }
    text
}

#[cfg(test)]
mod tests {
    use std::error::Error as _;

    use miette::Diagnostic as _;

    use super::*;

    /// A parse error at the value of `b` in a two-line RON file: line 2, column 5 (` b: 2)`).
    fn parse_error() -> irsig_formats::ParseError {
        irsig_formats::canonical::error_at_path("d.ron", "(a: 1,\n b: 2)", "b", "b is wrong")
    }

    /// `e` rendered as a terminal without colours shows it.
    fn rendered(e: RenderError) -> String {
        let mut out = String::new();
        miette::GraphicalReportHandler::new_themed(miette::GraphicalTheme::unicode_nocolor())
            .render_report(&mut out, &e)
            .unwrap();
        out
    }

    #[test]
    fn an_input_error_keeps_its_parse_error_its_place_and_its_label() {
        let e = RenderError::input("reading the decision `d.ron`", parse_error());
        assert_eq!(e.to_string(), "reading the decision `d.ron`");
        assert_eq!(e.code().unwrap().to_string(), "irsig::render::input");
        let source = e.source().expect("the parse error is the source");
        let p = source
            .downcast_ref::<irsig_formats::ParseError>()
            .expect("a ParseError");
        assert_eq!((p.file.as_str(), p.line, p.column), ("d.ron", 2, 5));
        // Its diagnostic, with the snippet and the label, comes through whole.
        let inner = e.diagnostic_source().expect("a diagnostic source");
        assert!(inner.source_code().is_some());
        assert_eq!(inner.labels().map(Iterator::count), Some(1));
        let text = rendered(e);
        for part in [
            "irsig::render::input",
            "reading the decision",
            "d.ron:2:5: b is wrong",
        ] {
            assert!(text.contains(part), "{part} in {text}");
        }
        // The snippet: the offending line and the label under it.
        assert!(text.contains(" b: 2)") && text.contains("here"), "{text}");
    }

    #[test]
    fn a_request_error_is_the_request_error_and_says_only_it() {
        let e: RenderError = RequestError::with_value(Setting::SubBands, 9, "too many").into();
        assert_eq!(e.as_request().map(|r| r.setting), Some(Setting::SubBands));
        assert_eq!(e.to_string(), "9: too many");
        assert_eq!(e.code().unwrap().to_string(), "irsig::render::request");
        // A report of it is found by a tool that maps settings to flags.
        let report = miette::Report::new(e);
        let found = report
            .downcast_ref::<RenderError>()
            .and_then(RenderError::as_request);
        assert_eq!(found.map(|r| r.value.as_deref()), Some(Some("9")));
        // Any other kind is not a request error.
        assert!(RenderError::refused("no").as_request().is_none());
    }

    #[test]
    fn the_libraries_errors_are_kept_as_sources_with_a_code_each() {
        // A field of view of 0 deg sees nothing.
        let trace = irsig_tracer::Camera::from_view(&irsig_model::View::Legacy {
            position_m: [0.0, 0.0, 10.0],
            pixels: [4, 4],
            omega_phi_kappa_deg: [0.0; 3],
            fov_deg: [0.0, 0.0],
            gain_dc_per_k: None,
        });
        let cases: Vec<(RenderError, &str)> = vec![
            (
                RenderError::trace("the camera of view 1", trace.unwrap_err()),
                "irsig::render::trace",
            ),
            (
                RenderError::atmosphere(
                    "the built-in `nowhere`",
                    irsig_atmosphere::builtin("nowhere").unwrap_err(),
                ),
                "irsig::render::atmosphere",
            ),
            (
                RenderError::band(
                    "sub-band 14-8 um",
                    irsig_radiometry::Band::new(14.0, 8.0).unwrap_err(),
                ),
                "irsig::render::band",
            ),
            (
                RenderError::encode("the radiance EXR", std::io::Error::other("disk on fire")),
                "irsig::render::encode",
            ),
        ];
        for (e, code) in cases {
            assert_eq!(e.code().unwrap().to_string(), code, "{e}");
            let source = e.source().expect("a source");
            assert!(!source.to_string().is_empty());
            assert!(chain_text(&e).starts_with(&format!("{e}: ")), "{e}");
        }
    }

    #[test]
    fn a_callers_error_comes_back_whole() {
        let report = miette::Report::new(parse_error());
        let e = RenderError::caller("keeping the frame's radiance.exr", report);
        assert_eq!(e.code().unwrap().to_string(), "irsig::render::caller");
        assert_eq!(
            e.source().map(ToString::to_string).as_deref(),
            Some("d.ron:2:5: b is wrong")
        );
        let inner = e.diagnostic_source().expect("the caller's diagnostic");
        assert_eq!(inner.labels().map(Iterator::count), Some(1));
        // The io error under a caller's report stays in the chain.
        let io = miette::Report::new_boxed(Box::new(Wrapped(std::io::Error::from(
            std::io::ErrorKind::BrokenPipe,
        ))));
        let e = miette::Report::new(RenderError::caller("writing", io));
        assert!(e.chain().any(|c| {
            c.downcast_ref::<std::io::Error>()
                .is_some_and(|io| io.kind() == std::io::ErrorKind::BrokenPipe)
        }));
    }

    #[test]
    fn a_callers_error_is_given_back_as_it_was_made_and_no_other_is() {
        // A usage error or a bare broken pipe at the top of a caller's report is what the
        // tool's exit code is read from: it must come back as itself, not under a context.
        let pipe = miette::Report::new(Wrapped(std::io::Error::from(
            std::io::ErrorKind::BrokenPipe,
        )));
        let back = RenderError::caller("writing", pipe).into_caller().unwrap();
        let own = back
            .downcast_ref::<Wrapped>()
            .expect("the caller's error itself");
        assert_eq!(own.0.kind(), std::io::ErrorKind::BrokenPipe);
        let refused = RenderError::refused("no radiance layer")
            .into_caller()
            .unwrap_err();
        assert_eq!(refused.to_string(), "no radiance layer");
    }

    /// An error whose source is an io error, as a tool's file error is.
    #[derive(Debug, thiserror::Error, miette::Diagnostic)]
    #[error("cannot write")]
    struct Wrapped(#[source] std::io::Error);
}
