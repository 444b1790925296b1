//! The files of a run's frames (`irsig-trace`, `irsig-merge`), named once and staged as
//! each frame's bytes arrive ([`StagedFrames`]): every destination checked before the long
//! work starts, all renamed into place together at the end, or none.

use std::path::{Path, PathBuf};

use irsig_model::frame::{FrameFile, FrameFiles};

use crate::Staged;

/// Each frame's files and what has been staged for them.
#[derive(Debug)]
pub struct StagedFrames {
    files: Vec<FrameFiles<PathBuf>>,
    staged: Staged,
}

impl StagedFrames {
    /// The frames' files, `files[i]` frame `i`'s, each destination checked (its folder
    /// exists and takes a new file) before anything is made, with `more` (a decision file,
    /// say).
    ///
    /// # Errors
    /// A destination that cannot be written.
    pub fn new(files: Vec<FrameFiles<PathBuf>>, more: &[&Path]) -> miette::Result<Self> {
        for path in files
            .iter()
            .flat_map(|f| f.iter().map(|(_, p)| p.as_path()))
            .chain(more.iter().copied())
        {
            crate::check_output(path)?;
        }
        Ok(Self {
            files,
            staged: Staged::new(),
        })
    }

    /// Which files frame `index` makes.
    #[must_use]
    pub fn wanted(&self, index: usize) -> FrameFiles<()> {
        self.files
            .get(index)
            .map(FrameFiles::wanted)
            .unwrap_or_default()
    }

    /// Frame `index`'s file of `kind`, if it makes one.
    #[must_use]
    pub fn path(&self, index: usize, kind: FrameFile) -> Option<&Path> {
        self.files.get(index)?.get(kind).map(PathBuf::as_path)
    }

    /// Stages `bytes` as frame `index`'s file of `kind` (nothing when it makes none).
    ///
    /// # Errors
    /// As [`Staged::stage`].
    pub fn stage(&mut self, index: usize, kind: FrameFile, bytes: &[u8]) -> miette::Result<()> {
        match self.files.get(index).and_then(|f| f.get(kind)) {
            Some(path) => self.staged.stage(path, bytes),
            None => Ok(()),
        }
    }

    /// Stages `bytes` for a file of the run beside the frames' (a decision).
    ///
    /// # Errors
    /// As [`Staged::stage`].
    pub fn stage_other(&mut self, path: &Path, bytes: &[u8]) -> miette::Result<()> {
        self.staged.stage(path, bytes)
    }

    /// Renames everything staged into place.
    ///
    /// # Errors
    /// As [`Staged::commit`].
    pub fn commit(self) -> miette::Result<()> {
        self.staged.commit()
    }
}
