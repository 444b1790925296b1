//! A frame's files (`irsig-trace`, `irsig-merge`): `-o PREFIX` for all of them, or one flag
//! per file ([`FrameOutputArgs`]).

use std::path::{Path, PathBuf};

use irsig_model::frame::{FrameFile, FrameFiles};

use super::outputs::{DcPng, Lut, Output};

/// Where a frame's files go (`irsig-trace`, `irsig-merge`): one prefix for all of them, or a
/// flag per file, so that `irsig-run` and Makefiles see every file a stage writes.
#[derive(Debug, Clone, Default, clap::Args)]
#[command(
    mut_arg("output", |a| a.help(
        "Output path prefix; files are PATH.radiance.exr, PATH.truth.exr, PATH.map.png, \
         PATH.dc.png and PATH.lut.txt (PATH.NNNN.* for several views)"
    )),
    mut_arg("dc_png", |a| a
        .help("Write the digital-count image (PNG, --dc-bits deep) to FILE")
        .conflicts_with_all(["output", "no_dc"])),
    mut_arg("lut", |a| a
        .help("Write the digital-count LUT (text: DC, radiance, K, degC) to FILE")
        .conflicts_with_all(["output", "no_dc"])),
)]
pub struct FrameOutputArgs {
    /// `-o PATH`, the prefix of every file.
    #[command(flatten)]
    pub prefix: Output,
    /// Write the radiance image (f32 EXR, W m^-2 sr^-1) to FILE. The per-output flags write
    /// only the files named, for one frame; any one of them may be `-`, standard output
    /// (e.g. piped into `irsig-sensor -`).
    #[arg(long, value_name = "FILE", conflicts_with = "output")]
    pub radiance_exr: Option<PathBuf>,
    /// Write the truth layers (multi-layer f32 EXR) to FILE.
    #[arg(long, value_name = "FILE", conflicts_with = "output")]
    pub truth_exr: Option<PathBuf>,
    /// Write the legacy interaction map (8-bit nibble bytes as a palette PNG, a colour
    /// per material) to FILE; an error when a material id does not fit in four bits.
    #[arg(long, value_name = "FILE", conflicts_with = "output")]
    pub map_png: Option<PathBuf>,
    /// `--dc-png FILE`.
    #[command(flatten)]
    pub dc_png: DcPng,
    /// `--lut FILE`.
    #[command(flatten)]
    pub lut: Lut,
    /// With -o, write no DC image or LUT.
    #[arg(long)]
    pub no_dc: bool,
}

impl FrameOutputArgs {
    /// The flag that names `kind`'s file.
    #[must_use]
    pub fn flag(kind: FrameFile) -> &'static str {
        match kind {
            FrameFile::RadianceExr => "--radiance-exr",
            FrameFile::TruthExr => "--truth-exr",
            FrameFile::MapPng => "--map-png",
            FrameFile::DcPng => "--dc-png",
            FrameFile::Lut => "--lut",
        }
    }

    /// The files the per-output flags name.
    #[must_use]
    pub fn named(&self) -> FrameFiles<PathBuf> {
        FrameFiles {
            radiance_exr: self.radiance_exr.clone(),
            truth_exr: self.truth_exr.clone(),
            map_png: self.map_png.clone(),
            dc_png: self.dc_png.path.clone(),
            lut: self.lut.path.clone(),
        }
    }

    /// Whether any per-output flag was given.
    #[must_use]
    pub fn has_files(&self) -> bool {
        self.named().any()
    }

    /// Where frame `index`'s decision goes without `--decision-out`: `PREFIX.decision.ron`
    /// with -o, else beside the first of `files` written to a file (`out.radiance.exr`
    /// gives `out.radiance.decision.ron`); `None` when every output goes to stdout.
    #[must_use]
    pub fn decision_file(
        &self,
        index: usize,
        frames: usize,
        files: &FrameFiles<PathBuf>,
    ) -> Option<PathBuf> {
        self.prefixed_file(index, frames, "decision.ron")
            .or_else(|| {
                let (_, first) = files.iter().find(|(_, p)| p.as_os_str() != "-")?;
                Some(first.with_extension("decision.ron"))
            })
    }

    /// `PREFIX.SUFFIX` of frame `index` (from 0) of `frames` (`PREFIX.NNNN.SUFFIX` for
    /// more than one); `None` without -o.
    #[must_use]
    pub fn prefixed_file(&self, index: usize, frames: usize, suffix: &str) -> Option<PathBuf> {
        let prefix = self.prefix.path.as_ref()?;
        let stem = if frames == 1 {
            prefix.clone()
        } else {
            let mut s = prefix.as_os_str().to_owned();
            s.push(format!(".{:04}", index + 1));
            PathBuf::from(s)
        };
        Some(with_suffix(&stem, suffix))
    }

    /// The files of frame `index` (from 0) of `frames` under the prefix, those of `kinds`
    /// (with `--no-dc`, no counts or LUT); `None` without -o.
    #[must_use]
    pub fn prefixed(
        &self,
        index: usize,
        frames: usize,
        kinds: &[FrameFile],
    ) -> Option<FrameFiles<PathBuf>> {
        self.prefix.path.as_ref()?;
        let mut files = FrameFiles::default();
        for &kind in kinds {
            let counts = matches!(kind, FrameFile::DcPng | FrameFile::Lut);
            if !(counts && self.no_dc) {
                files.set(kind, self.prefixed_file(index, frames, kind.suffix())?);
            }
        }
        Some(files)
    }

    /// The files of each of `frames` frames: under the prefix, those of `kinds`; else, for
    /// one frame, those the flags name.
    ///
    /// # Errors
    /// Per-output flags for more than one frame (bad usage).
    pub fn frames(
        &self,
        frames: usize,
        kinds: &[FrameFile],
    ) -> miette::Result<Vec<FrameFiles<PathBuf>>> {
        if self.prefix.path.is_none() && frames > 1 {
            return Err(crate::usage_error(format!(
                "the per-output flags name one file each, but {frames} views were given: \
                 give one view per run, or -o PREFIX for numbered outputs"
            )));
        }
        Ok((0..frames)
            .map(|i| {
                self.prefixed(i, frames, kinds)
                    .unwrap_or_else(|| self.named())
            })
            .collect())
    }

    /// At most one file goes to standard output (`-`).
    ///
    /// # Errors
    /// Two or more of them do (bad usage).
    pub fn check_stdout(&self) -> miette::Result<()> {
        let named = self.named();
        if named.iter().filter(|(_, p)| p.as_os_str() == "-").count() > 1 {
            return Err(crate::usage_error(
                "only one output can go to standard output (`-`)",
            ));
        }
        Ok(())
    }
}

/// `STEM.SUFFIX`.
#[must_use]
pub fn with_suffix(stem: &Path, suffix: &str) -> PathBuf {
    let mut s = stem.as_os_str().to_owned();
    s.push(".");
    s.push(suffix);
    PathBuf::from(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_outputs_are_a_prefix_or_one_flag_per_file() {
        let args = FrameOutputArgs {
            prefix: Output {
                path: Some(PathBuf::from("out/f")),
            },
            no_dc: true,
            ..FrameOutputArgs::default()
        };
        let files = args.prefixed(6, 12, &FrameFile::ALL).unwrap();
        assert_eq!(files.truth_exr, Some(PathBuf::from("out/f.0007.truth.exr")));
        assert!(files.dc_png.is_none() && files.lut.is_none());
        let one = args.prefixed(0, 1, &[FrameFile::MapPng]).unwrap();
        assert_eq!(one.iter().count(), 1);
        assert_eq!(one.map_png, Some(PathBuf::from("out/f.map.png")));
        let flags = FrameOutputArgs {
            radiance_exr: Some(PathBuf::from("-")),
            lut: Lut {
                path: Some(PathBuf::from("-")),
            },
            ..FrameOutputArgs::default()
        };
        assert!(flags.has_files() && flags.prefixed(0, 1, &FrameFile::ALL).is_none());
        assert!(flags.check_stdout().is_err());
    }
}
