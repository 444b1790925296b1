//! One planned run of one tool (a [`Step`]) and the files it reads and writes, each with
//! where the pipeline file names it, so that every later complaint points at its text.

use std::path::PathBuf;

use crate::error::PipelineError;

/// A byte range `(start, end)` in the pipeline file.
pub(crate) type Span = (usize, usize);

/// A file a step reads or writes, with where the pipeline file names it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FileRef {
    /// The path as written (after templates), relative to the pipeline's directory.
    pub path: PathBuf,
    /// The lexically normalised path, for matching outputs to inputs.
    pub(crate) key: PathBuf,
    pub(crate) start: usize,
    pub(crate) end: usize,
}

/// One run of one tool: a stage, or one frame of a swept stage.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Step {
    /// The stage's name, with `[frame]` for a frame of a sweep: `trace[3]`.
    pub name: String,
    /// The tool's name, such as `trace`.
    pub tool: String,
    /// The program found for the tool.
    pub program: PathBuf,
    /// The command line, program name (`irsig-<tool>`) first: exactly what a user would type.
    pub argv: Vec<String>,
    /// Files read: positional `args`, `inputs` and `reads`.
    pub inputs: Vec<FileRef>,
    /// Files written: `outputs`.
    pub outputs: Vec<FileRef>,
    /// Indices (in [`crate::Plan::steps`]) of the steps whose outputs this one reads.
    pub deps: Vec<usize>,
    /// The frame of the stage's sweep this step runs (from 1), or `None` for a stage without
    /// `sweep`.
    pub frame: Option<usize>,
    /// What the frame shows, for messages and scripts: a `Times` frame's time
    /// (`2001-08-07T14:00:00-06:00`); `None` for other steps.
    pub label: Option<String>,
    /// The index of the stage in the pipeline file's `stages`.
    pub(crate) stage: usize,
    pub(crate) start: usize,
    pub(crate) end: usize,
    /// (argv index, key span, value span) of each flag, to locate a validator's complaint.
    pub(crate) flags: Vec<(usize, Span, Span)>,
    pub(crate) tool_span: Span,
}

impl Step {
    /// The step's name with what its frame shows, for messages: `trace[15]
    /// (2001-08-07T14:00:00-06:00)`, or the name alone.
    #[must_use]
    pub fn described(&self) -> String {
        match &self.label {
            Some(label) => format!("{} ({label})", self.name),
            None => self.name.clone(),
        }
    }

    /// The command line for messages, shell-quoted so that it can be pasted into a shell.
    /// A planned step's words hold no control character (the pipeline file refuses them);
    /// should a word hold one, it is shown escaped (`\n`) inside quotes, inert, never raw.
    /// Scripts use [`Step::shell_line`], which refuses it.
    #[must_use]
    pub fn command_line(&self) -> String {
        self.argv
            .iter()
            .map(|w| {
                crate::shell_quote(w).unwrap_or_else(|_| {
                    let shown: String = w
                        .chars()
                        .flat_map(|c| {
                            let escaped: Vec<char> = if c.is_control() {
                                c.escape_debug().collect()
                            } else {
                                vec![c]
                            };
                            escaped
                        })
                        .collect();
                    crate::shell_quote(&shown).unwrap_or_default()
                })
            })
            .collect::<Vec<_>>()
            .join(" ")
    }

    /// The command line as one line of a shell script: every word quoted so that `sh` runs
    /// exactly [`Step::argv`].
    ///
    /// # Errors
    /// [`crate::ErrorKind::ControlCharacter`] for a word no shell line can carry.
    pub fn shell_line(&self) -> Result<String, PipelineError> {
        Ok(self
            .argv
            .iter()
            .map(|w| crate::shell_quote(w))
            .collect::<Result<Vec<_>, _>>()?
            .join(" "))
    }
}
