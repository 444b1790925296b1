//! The files one traced frame makes: the radiance EXR, the truth EXR, the 1990 interaction
//! map, the digital-count image and its LUT. `irsig-trace` makes them from a traced frame
//! and `irsig-merge` from a frame's merged tiles, through one library (`irsig-render`);
//! `irsig-cli` names them (`PREFIX.radiance.exr`, …) from one set of flags. This module is
//! what the three share: the kinds, the suffix each kind gets after a prefix, and a set of
//! them, one optional value per kind (a path, a wanted flag, encoded bytes).
//!
//! ```
//! use irsig_model::frame::{FrameFile, FrameFiles};
//! let mut files: FrameFiles<&str> = FrameFiles::default();
//! files.set(FrameFile::TruthExr, "f.truth.exr");
//! assert_eq!(FrameFile::TruthExr.suffix(), "truth.exr");
//! assert!(files.wants(FrameFile::TruthExr) && !files.wants(FrameFile::Lut));
//! ```

/// One kind of file a frame makes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum FrameFile {
    /// The radiance at the sensor, one f32 layer, W m⁻² sr⁻¹.
    RadianceExr,
    /// The truth layers ([`crate::truth::Layer::TRUTH`], and the error budget's).
    TruthExr,
    /// The 1990 interaction map: primary and reflected material id in two nibbles.
    MapPng,
    /// The digital-count image.
    DcPng,
    /// The digital-count LUT: count, radiance, kelvin, degrees Celsius.
    Lut,
}

impl FrameFile {
    /// Every kind, in the order a frame's files are listed.
    pub const ALL: [Self; 5] = [
        Self::RadianceExr,
        Self::TruthExr,
        Self::MapPng,
        Self::DcPng,
        Self::Lut,
    ];

    /// What follows `PREFIX.` in the file's name.
    #[must_use]
    pub fn suffix(self) -> &'static str {
        match self {
            Self::RadianceExr => "radiance.exr",
            Self::TruthExr => "truth.exr",
            Self::MapPng => "map.png",
            Self::DcPng => "dc.png",
            Self::Lut => "lut.txt",
        }
    }
}

/// One optional value per [`FrameFile`].
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FrameFiles<T> {
    /// The radiance EXR's.
    pub radiance_exr: Option<T>,
    /// The truth EXR's.
    pub truth_exr: Option<T>,
    /// The interaction map's.
    pub map_png: Option<T>,
    /// The digital-count image's.
    pub dc_png: Option<T>,
    /// The LUT's.
    pub lut: Option<T>,
}

impl<T> Default for FrameFiles<T> {
    fn default() -> Self {
        Self {
            radiance_exr: None,
            truth_exr: None,
            map_png: None,
            dc_png: None,
            lut: None,
        }
    }
}

impl<T> FrameFiles<T> {
    /// The value of `file`, if it has one.
    #[must_use]
    pub fn get(&self, file: FrameFile) -> Option<&T> {
        match file {
            FrameFile::RadianceExr => self.radiance_exr.as_ref(),
            FrameFile::TruthExr => self.truth_exr.as_ref(),
            FrameFile::MapPng => self.map_png.as_ref(),
            FrameFile::DcPng => self.dc_png.as_ref(),
            FrameFile::Lut => self.lut.as_ref(),
        }
    }

    /// Gives `file` a value.
    pub fn set(&mut self, file: FrameFile, value: T) {
        *self.slot(file) = Some(value);
    }

    /// Takes `file`'s value out.
    pub fn take(&mut self, file: FrameFile) -> Option<T> {
        self.slot(file).take()
    }

    fn slot(&mut self, file: FrameFile) -> &mut Option<T> {
        match file {
            FrameFile::RadianceExr => &mut self.radiance_exr,
            FrameFile::TruthExr => &mut self.truth_exr,
            FrameFile::MapPng => &mut self.map_png,
            FrameFile::DcPng => &mut self.dc_png,
            FrameFile::Lut => &mut self.lut,
        }
    }

    /// Whether `file` has a value.
    #[must_use]
    pub fn wants(&self, file: FrameFile) -> bool {
        self.get(file).is_some()
    }

    /// Whether any file has a value.
    #[must_use]
    pub fn any(&self) -> bool {
        FrameFile::ALL.into_iter().any(|f| self.wants(f))
    }

    /// The files with a value, in [`FrameFile::ALL`] order.
    pub fn iter(&self) -> impl Iterator<Item = (FrameFile, &T)> {
        FrameFile::ALL
            .into_iter()
            .filter_map(|f| self.get(f).map(|v| (f, v)))
    }

    /// Which files have a value.
    #[must_use]
    pub fn wanted(&self) -> FrameFiles<()> {
        FrameFiles {
            radiance_exr: self.radiance_exr.as_ref().map(|_| ()),
            truth_exr: self.truth_exr.as_ref().map(|_| ()),
            map_png: self.map_png.as_ref().map(|_| ()),
            dc_png: self.dc_png.as_ref().map(|_| ()),
            lut: self.lut.as_ref().map(|_| ()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_kind_has_its_own_slot_and_suffix() {
        let mut files = FrameFiles::default();
        for (i, f) in FrameFile::ALL.into_iter().enumerate() {
            files.set(f, i);
        }
        for (i, f) in FrameFile::ALL.into_iter().enumerate() {
            assert_eq!(files.get(f), Some(&i));
        }
        let suffixes: std::collections::HashSet<_> =
            FrameFile::ALL.into_iter().map(FrameFile::suffix).collect();
        assert_eq!(suffixes.len(), 5);
        assert_eq!(files.take(FrameFile::MapPng), Some(2));
        assert!(!files.wants(FrameFile::MapPng));
        assert_eq!(files.iter().count(), 4);
        assert!(files.wanted().wants(FrameFile::Lut));
    }
}
