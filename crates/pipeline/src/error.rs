use std::fmt;

use irsig_formats::ParseError;
use miette::Diagnostic;

/// Everything that can go wrong with a pipeline: a malformed or inconsistent pipeline file
/// (located at its line and column), a stage that failed, or the run state that could not be
/// read or written.
#[derive(Debug)]
pub struct PipelineError {
    kind: ErrorKind,
    detail: Detail,
}

/// What kind of [`PipelineError`] this is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum ErrorKind {
    /// The file is not valid RON (reported with `ron`'s own message and position).
    Syntax,
    /// Valid RON, but not the pipeline shape: an unknown field, a value of the wrong type, a
    /// missing required field, a bad template or sweep.
    Structure,
    /// A stage names a tool for which no `irsig-<tool>` program is found.
    UnknownTool,
    /// A stage's parameters are rejected by its tool's command-line parser.
    BadParameter,
    /// Two stage instances write the same output file.
    DuplicateOutput,
    /// Stages depend on each other in a cycle.
    Cycle,
    /// An input file exists neither on disk nor as another stage's output.
    MissingInput,
    /// A stage's tool could not be started, exited with failure, or did not write an output.
    StageFailed,
    /// A path cannot be written into a Makefile (spaces, `:`, `$`, ...).
    NotMakeable,
    /// Reading or writing a file of the runner's own (the pipeline file, the run state).
    Io,
    /// A step asked for by name (`irsig-run --step`) that the plan does not have.
    UnknownStep,
    /// A stage asks Slurm for more CPUs or memory than any node of the cluster declares.
    ExceedsNode,
    /// Text holds a control character (newline, carriage return, NUL, tab, ...), which
    /// nothing the runner writes for a shell, make or Slurm may carry.
    ControlCharacter,
}

#[derive(Debug)]
enum Detail {
    Located(Box<ParseError>),
    Io {
        message: String,
        source: std::io::Error,
    },
    /// An error with no place in the pipeline file.
    Plain(String),
}

impl PipelineError {
    /// An error at `len` bytes from byte `offset` of the pipeline file `file` with text `source`.
    pub(crate) fn at(
        kind: ErrorKind,
        file: &str,
        source: &str,
        offset: usize,
        len: usize,
        message: impl Into<String>,
    ) -> Self {
        Self {
            kind,
            detail: Detail::Located(Box::new(ParseError::at_span(
                file,
                source,
                offset,
                len.max(1),
                message,
            ))),
        }
    }

    /// An error already located by the shared parser.
    pub(crate) fn located(kind: ErrorKind, error: ParseError) -> Self {
        Self {
            kind,
            detail: Detail::Located(Box::new(error)),
        }
    }

    pub(crate) fn io(message: impl Into<String>, source: std::io::Error) -> Self {
        Self {
            kind: ErrorKind::Io,
            detail: Detail::Io {
                message: message.into(),
                source,
            },
        }
    }

    /// An error about the command line's request rather than a place in the file.
    pub(crate) fn plain(kind: ErrorKind, message: String) -> Self {
        Self {
            kind,
            detail: Detail::Plain(message),
        }
    }

    pub(crate) fn with_help(mut self, help: impl Into<String>) -> Self {
        if let Detail::Located(e) = self.detail {
            self.detail = Detail::Located(Box::new(e.with_help(help)));
        }
        self
    }

    /// What kind of error this is.
    #[must_use]
    pub fn kind(&self) -> ErrorKind {
        self.kind
    }

    /// Where in the pipeline file the error is, as 1-based (line, column), when it has a place.
    #[must_use]
    pub fn line_column(&self) -> Option<(usize, usize)> {
        match &self.detail {
            Detail::Located(e) => Some((e.line, e.column)),
            Detail::Io { .. } | Detail::Plain(_) => None,
        }
    }
}

impl fmt::Display for PipelineError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.detail {
            Detail::Located(e) => e.fmt(f),
            Detail::Io { message, source } => write!(f, "{message}: {source}"),
            Detail::Plain(message) => f.write_str(message),
        }
    }
}

impl std::error::Error for PipelineError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match &self.detail {
            Detail::Located(_) | Detail::Plain(_) => None,
            Detail::Io { source, .. } => Some(source),
        }
    }
}

// The located form renders exactly as the shared `ParseError` does: the file, line and
// column, then the offending line of the pipeline file underlined.
impl Diagnostic for PipelineError {
    fn code<'a>(&'a self) -> Option<Box<dyn fmt::Display + 'a>> {
        Some(Box::new(match self.kind {
            ErrorKind::Syntax => "irsig::pipeline::syntax",
            ErrorKind::Structure => "irsig::pipeline::structure",
            ErrorKind::UnknownTool => "irsig::pipeline::unknown_tool",
            ErrorKind::BadParameter => "irsig::pipeline::bad_parameter",
            ErrorKind::DuplicateOutput => "irsig::pipeline::duplicate_output",
            ErrorKind::Cycle => "irsig::pipeline::cycle",
            ErrorKind::MissingInput => "irsig::pipeline::missing_input",
            ErrorKind::StageFailed => "irsig::pipeline::stage_failed",
            ErrorKind::NotMakeable => "irsig::pipeline::not_makeable",
            ErrorKind::Io => "irsig::pipeline::io",
            ErrorKind::UnknownStep => "irsig::pipeline::unknown_step",
            ErrorKind::ExceedsNode => "irsig::pipeline::exceeds_node",
            ErrorKind::ControlCharacter => "irsig::pipeline::control_character",
        }))
    }

    fn help<'a>(&'a self) -> Option<Box<dyn fmt::Display + 'a>> {
        match &self.detail {
            Detail::Located(e) => e.help(),
            Detail::Io { .. } | Detail::Plain(_) => None,
        }
    }

    fn source_code(&self) -> Option<&dyn miette::SourceCode> {
        match &self.detail {
            Detail::Located(e) => e.source_code(),
            Detail::Io { .. } | Detail::Plain(_) => None,
        }
    }

    fn labels(&self) -> Option<Box<dyn Iterator<Item = miette::LabeledSpan> + '_>> {
        match &self.detail {
            Detail::Located(e) => e.labels(),
            Detail::Io { .. } | Detail::Plain(_) => None,
        }
    }
}
