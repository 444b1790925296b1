//! Declarative irsig pipelines: a RON file of stages, each run as its own tool
//! (`irsig-<tool>`), exactly as a user would type it.
//!
//! - [`Pipeline::load`] / [`Pipeline::parse`] read the file through
//!   `irsig_formats::ron_tree` (RON syntax checked by `ron`), keeping the position of every
//!   value, so later errors point at a line and column.
//! - [`Pipeline::plan`] expands frame sweeps into one step per frame, builds each step's
//!   command line, finds the tools, validates parameters with the tools' own command-line
//!   parsers ([`Tools::register`]), and checks for duplicate outputs, missing inputs and
//!   cycles, all before anything runs.
//! - [`Plan::run`] runs the steps in dependency order, independent ones in parallel, and
//!   skips a step whose outputs are up to date with its tool, command line and input
//!   contents (SHA-256, kept in `.irsig-run/` beside the pipeline file).
//! - [`Plan::dry_run`] lists every step and whether a run would start it;
//!   [`Plan::makefile`] writes the same steps as a Makefile; [`Plan::slurm`] writes them as
//!   Slurm batch scripts (a job array per frame sweep), whose tasks each run one step
//!   ([`Plan::run_step_named`]).
//!
//! The format is documented in `formats/pipeline.md`.
//!
//! ```
//! use irsig_pipeline::{Pipeline, Tools};
//! use std::path::{Path, PathBuf};
//!
//! let text = r#"Pipeline(
//!     sweeps: {"views": Frames([{"view": "a"}, {"view": "b"}])},
//!     stages: [
//!         Stage(tool: "echo", sweep: "views",
//!               params: {"label": "{view}"}, outputs: {"o": "out/{frame:02}.txt"}),
//!     ],
//! )"#;
//! let pipeline = Pipeline::parse("demo.ron", text, Path::new(".")).unwrap();
//! let tools = Tools::new(|tool| Some(PathBuf::from(format!("/bin/irsig-{tool}"))));
//! let plan = pipeline.plan(&tools).unwrap();
//! let commands: Vec<String> = plan.steps.iter().map(|s| s.command_line()).collect();
//! assert_eq!(commands, [
//!     "irsig-echo --label a -o out/01.txt",
//!     "irsig-echo --label b -o out/02.txt",
//! ]);
//! ```

// A closed stderr must not panic the tool: notes go through `irsig_cli::note!`.
#![deny(clippy::print_stdout, clippy::print_stderr)]

mod emit;
mod error;
mod plan;
mod run;
mod slurm;
mod spec;
mod step;
mod sun;
mod times;

pub use error::{ErrorKind, PipelineError};
pub use plan::{Pipeline, Plan, Tools, Validator};
pub use run::{Event, RunOptions, RunSummary};
pub use slurm::{
    Dependency, MEMORY_FLOOR_MIB, MEMORY_PER_INPUT_BYTE, NodeLimits, SlurmJob, SlurmOptions,
    SlurmScripts, estimate_memory_mib,
};
pub use step::{FileRef, Step};
pub use sun::SunFlags;
pub use times::TimeFlags;

/// `word` quoted for a POSIX shell when it needs quoting, as dry runs, Makefiles and Slurm
/// scripts print it: as it is when it holds only letters, digits and `+ - . / : @ ] _`,
/// else in single quotes (a backslash in double quotes), by shlex's rules. Never the raw
/// word: a word no quoting can carry is an error.
///
/// ```
/// assert_eq!(irsig_pipeline::shell_quote("8-14").unwrap(), "8-14");
/// assert_eq!(irsig_pipeline::shell_quote("scene: $(x)").unwrap(), "'scene: $(x)'");
/// assert!(irsig_pipeline::shell_quote("a\0b").is_err());
/// ```
///
/// # Errors
/// [`ErrorKind::ControlCharacter`] for a word holding a control character: a NUL has no
/// shell spelling, and the rest (a newline, a carriage return, a tab ...) would end or
/// split a line of a Makefile or a Slurm script; the pipeline file refuses them where it
/// is read.
pub fn shell_quote(word: &str) -> Result<String, PipelineError> {
    if let Some(c) = word.chars().find(|c| c.is_control()) {
        return Err(PipelineError::plain(
            ErrorKind::ControlCharacter,
            format!(
                "{word:?} holds the control character U+{:04X}, which no line of a shell, \
                 make or Slurm script may carry",
                u32::from(c)
            ),
        ));
    }
    shlex::try_quote(word)
        .map(std::borrow::Cow::into_owned)
        .map_err(|e| PipelineError::plain(ErrorKind::ControlCharacter, format!("{word:?}: {e}")))
}
