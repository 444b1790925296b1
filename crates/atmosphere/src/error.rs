use irsig_model::ModelError;

/// Why an atmosphere model could not be built, or a built-in atmosphere not found.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{kind}")]
pub struct AtmosphereError {
    /// What went wrong.
    pub kind: AtmosphereErrorKind,
}

/// What went wrong building an atmosphere model.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum AtmosphereErrorKind {
    /// The atmosphere breaks one of the canonical model's rules (see
    /// [`irsig_model::Atmosphere::validate`]).
    #[error("invalid atmosphere: {0}")]
    Invalid(#[from] ModelError),
    /// The chosen model needs a table the atmosphere does not have (the `thesis` model
    /// needs the `.cor` coefficients, the `table` model the slant tables).
    #[error(
        "the `{model}` atmosphere model needs `{table}`, which this atmosphere does not have; {instead}"
    )]
    MissingTable {
        /// The model asked for.
        model: &'static str,
        /// The missing field of the canonical atmosphere.
        table: &'static str,
        /// What to use instead.
        instead: &'static str,
    },
    /// The vertical transmission grows with altitude, which no atmosphere does; the layered
    /// model cannot turn such a table into layers.
    #[error(
        "levels[{level}].transmission = {value} exceeds the level below ({below}): the vertical transmission from the ground must not grow with altitude"
    )]
    TransmissionIncreases {
        /// Index of the offending level.
        level: usize,
        /// Its transmission.
        value: f64,
        /// The transmission of the level below it.
        below: f64,
    },
    /// An atmosphere model name that is not one of `thesis`, `layered`, `table`, `none`.
    #[error("unknown atmosphere model `{0}`: expected one of thesis, layered, table, none")]
    UnknownModel(String),
    /// A built-in atmosphere name that does not exist.
    #[error("unknown built-in atmosphere `{0}`: expected one of {names}", names = crate::BUILTIN_NAMES.join(", "))]
    UnknownBuiltin(String),
    /// A band a spectral atmosphere cannot be collapsed over: outside its grid, or with a
    /// response that is negative, not finite or zero everywhere in it.
    #[error("{0}")]
    Band(String),
    /// An atmosphere build's plan that cannot be made or assembled.
    #[error("{0}")]
    Plan(String),
    /// A plan of broadband loads that cannot be made or assembled, or a loads table asked
    /// for a sun it does not hold.
    #[error("{0}")]
    Loads(String),
    /// A sun's position that cannot be computed: a field out of its range or not a
    /// number, a time that does not parse or that SPA does not cover, no ΔT for its year.
    #[error("sun `{}`: {message}", field.path())]
    Sun {
        /// The field of [`crate::sun::SunSpec`] at fault; a file names it by its path
        /// (`refraction.pressure_hpa`), a command line by its flag.
        field: crate::sun::SunField,
        /// What is wrong, with the accepted range and the value found.
        message: String,
    },
    /// Direct sunlight asked for in a way the `solar` table cannot answer (a direction
    /// that is not one, a sun other than the table's).
    #[error("{0}")]
    Solar(String),
    /// A built-in atmosphere failed to decode (a bug in the shipped data).
    #[error("built-in atmosphere `{name}` is corrupt: {message}")]
    CorruptBuiltin {
        /// The built-in's name.
        name: String,
        /// The parser's message.
        message: String,
    },
}

impl From<AtmosphereErrorKind> for AtmosphereError {
    fn from(kind: AtmosphereErrorKind) -> Self {
        Self { kind }
    }
}

impl From<ModelError> for AtmosphereError {
    fn from(e: ModelError) -> Self {
        AtmosphereErrorKind::Invalid(e).into()
    }
}
