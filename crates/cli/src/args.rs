//! The command-line vocabulary the tools share, defined once so that every tool spells a
//! setting the same way: the band (`--band MIN-MAX`, `--band RESPONSE-FILE` or `--band
//! total`), lengths' units (`--view-unit km`), the digital-count calibration
//! (`--dc-per-kelvin`, `--reference-k`, `--dc-at-reference`, `--gain-dc-per-radiance`,
//! `--offset-dc`, `--dc-bits`), a frame's output files (`-o PREFIX` or one flag per file,
//! [`FrameOutputArgs`]), library enums offered by name, a table's `--format` and lists or
//! ranges of numbers (`--angles 0:90:5`). A flag of one name has one type and one default in
//! every tool (`tests/tests/architecture.rs` holds it).

use std::path::{Path, PathBuf};
use std::str::FromStr;

use clap::builder::{PossibleValuesParser, TypedValueParser};
use irsig_model::LengthUnit;
use irsig_model::frame::{FrameFile, FrameFiles};
use irsig_model::provenance::BandRecord;
use irsig_radiometry::{AnyBand, Band, SensorResponse, TotalRadiance};
use irsig_sensor_model::quantise::{Calibration, CountRequest};
use miette::miette;

/// A spectral band as given on a command line (`--band`, in every tool): `MIN-MAX` in
/// micrometres (a flat response), the path of a sensor response file (`formats/srf.md`),
/// whose first and last wavelengths bound the band, or `total`, the whole spectrum (σT⁴/π),
/// exact and for checking by hand. Resolve it with [`BandArg::load`].
#[derive(Debug, Clone, PartialEq)]
pub enum BandArg {
    /// A flat band between two wavelengths, µm.
    Flat {
        /// Short end, µm.
        min_um: f64,
        /// Long end, µm.
        max_um: f64,
    },
    /// A sensor response file.
    Response(String),
    /// `total`: the whole spectrum, σT⁴/π.
    Total,
}

impl Default for BandArg {
    /// The thesis's band, 8–14 µm, flat.
    fn default() -> Self {
        Self::Flat {
            min_um: 8.0,
            max_um: 14.0,
        }
    }
}

impl FromStr for BandArg {
    type Err = String;

    /// `MIN-MAX` (two positive numbers of µm joined by `-`), else a file name. `8:14`, the
    /// old spelling of some tools, is refused with the new one.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        if s == "total" {
            return Ok(Self::Total);
        }
        let number = |t: &str| t.trim().parse::<f64>().ok().filter(|v| v.is_finite());
        // The `-` that splits two numbers (an exponent such as `8e-1` holds one too).
        for (i, _) in s.match_indices('-') {
            if let (Some(min_um), Some(max_um)) = (number(&s[..i]), number(&s[i + 1..])) {
                return Ok(Self::Flat { min_um, max_um });
            }
        }
        if let Some((a, b)) = s.split_once(':')
            && number(a).is_some()
            && number(b).is_some()
        {
            return Err(format!(
                "expected MIN-MAX in micrometres, such as {a}-{b}, or a sensor response \
                 file; found `{s}`"
            ));
        }
        if s.is_empty() {
            return Err(
                "expected MIN-MAX in micrometres, such as 8-14, or a sensor response file"
                    .to_owned(),
            );
        }
        Ok(Self::Response(s.to_owned()))
    }
}

impl std::fmt::Display for BandArg {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Flat { min_um, max_um } => write!(f, "{min_um}-{max_um}"),
            Self::Response(path) => f.write_str(path),
            Self::Total => f.write_str("total"),
        }
    }
}

impl BandArg {
    /// The response file `--band` names, which the tool reads (`None` for a flat band or
    /// `total`).
    #[must_use]
    pub fn response_file(band: Option<&Self>) -> Option<&str> {
        match band {
            Some(Self::Response(path)) => Some(path),
            _ => None,
        }
    }

    /// `--band`'s value, or the default band (8–14 µm, flat) when it was not given.
    #[must_use]
    pub fn or_default(band: Option<&Self>) -> Self {
        band.cloned().unwrap_or_default()
    }

    /// The band: flat, or weighted by the response file read from disk.
    ///
    /// # Errors
    /// Limits that are not `0 < MIN < MAX` (bad usage), a response file that cannot be
    /// read or parsed (at its line and column), or `total`, which has no wavelengths.
    pub fn load(&self) -> miette::Result<Band> {
        match self.load_recorded()? {
            (AnyBand::Band(band), _) => Ok(band),
            (AnyBand::Total(_), _) => Err(crate::usage_error(
                "--band total (the whole spectrum, σT⁴/π) has no wavelengths: this needs \
                 MIN-MAX in micrometres or a sensor response file",
            )),
        }
    }

    /// The band, and its record as an image traced in it keeps it (a response file's
    /// table itself, with the file's name and SHA-256).
    ///
    /// # Errors
    /// As [`BandArg::load`], `total` excepted.
    pub fn load_recorded(&self) -> miette::Result<(AnyBand, BandRecord)> {
        match self {
            Self::Total => Ok((AnyBand::Total(TotalRadiance), BandRecord::Total)),
            Self::Flat { min_um, max_um } => {
                let record = BandRecord::Flat {
                    min_um: *min_um,
                    max_um: *max_um,
                };
                let band = band_of(&record)
                    .map_err(|e| crate::usage_error(format!("--band {self}: {e}")))?;
                Ok((band, record))
            }
            Self::Response(path) => {
                let input = crate::read_input(path)?;
                let text = irsig_formats::canonical::utf8(&input.name, &input.bytes)?;
                let table = irsig_formats::srf::parse(&input.name, text)?;
                let record = BandRecord::Response {
                    sha256: input.sha256(),
                    wavelength_um: table.wavelength_um,
                    response: table.response,
                };
                let band = band_of(&record).map_err(|e| miette!("{}: {e}", input.name))?;
                Ok((band, record))
            }
        }
    }
}

/// The band a record describes, built as from its file.
///
/// # Errors
/// Limits or a table the band cannot be made of, in words.
pub fn band_of(record: &BandRecord) -> Result<AnyBand, String> {
    match record {
        BandRecord::Total => Ok(AnyBand::Total(TotalRadiance)),
        BandRecord::Flat { min_um, max_um } => Band::new(*min_um, *max_um)
            .map(AnyBand::Band)
            .map_err(|e| e.to_string()),
        BandRecord::Response {
            wavelength_um,
            response,
            ..
        } => {
            let (Some(&lo), Some(&hi)) = (wavelength_um.first(), wavelength_um.last()) else {
                return Err("the response table is empty".to_owned());
            };
            let srf = SensorResponse::new(wavelength_um.clone(), response.clone())
                .map_err(|e| e.to_string())?;
            Band::new(lo, hi)
                .and_then(|b| b.with_response(&srf))
                .map(AnyBand::Band)
                .map_err(|e| e.to_string())
        }
    }
}

/// `--band` of a tool that reads a traced image (sensor, stats, report, merge): the band the
/// image records by default, since irsig-trace records it; a `--band` that is another band
/// is refused, naming both, unless `--override-band`, which warns.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct ImageBandArgs {
    /// The band of the image's radiances: `MIN-MAX` in micrometres, a sensor response file
    /// (formats/srf.md) or `total`. By default the band the image records (irsig-trace
    /// writes it into its EXRs); given, it must be that band.
    #[arg(long, value_name = "MIN-MAX|FILE|total")]
    pub band: Option<BandArg>,
    /// Use --band even where the image records another band (a warning says so).
    #[arg(long, requires = "band")]
    pub override_band: bool,
}

/// The band a stage converts an image's radiances with, and what it has to say about it.
#[derive(Debug, Clone)]
pub struct ResolvedBand {
    /// The band.
    pub band: AnyBand,
    /// Its record, for the stage's own outputs.
    pub record: BandRecord,
    /// A warning for stderr: a band assumed, or overridden.
    pub warning: Option<String>,
}

impl ImageBandArgs {
    /// The band of the image `image` (its name, for messages), which records `recorded`.
    ///
    /// # Errors
    /// A --band that is not the recorded band (bad usage, naming both) without
    /// --override-band, or a band that cannot be loaded.
    pub fn resolve(
        &self,
        image: &str,
        recorded: Option<&BandRecord>,
    ) -> miette::Result<ResolvedBand> {
        let given = self.band.as_ref().map(BandArg::load_recorded).transpose()?;
        match (given, recorded) {
            (None, Some(record)) => Ok(ResolvedBand {
                band: band_of(record)
                    .map_err(|e| miette!("{image}: its recorded band {record}: {e}"))?,
                record: record.clone(),
                warning: None,
            }),
            (Some((band, record)), Some(recorded)) if record.same_band(recorded) => {
                Ok(ResolvedBand {
                    band,
                    record,
                    warning: None,
                })
            }
            (Some((band, record)), Some(recorded)) if self.override_band => Ok(ResolvedBand {
                warning: Some(format!(
                    "--band {} ({record}) overrides the band `{image}` records, {recorded}: \
                     its apparent temperatures are not those of the radiance it was traced in",
                    self.band
                        .as_ref()
                        .map(ToString::to_string)
                        .unwrap_or_default()
                )),
                band,
                record,
            }),
            (Some((_, record)), Some(recorded)) => Err(crate::usage_error(format!(
                "--band {} ({record}) is not the band `{image}` records, {recorded}: leave \
                 --band out to use the recorded band, or add --override-band to convert with \
                 --band anyway",
                self.band
                    .as_ref()
                    .map(ToString::to_string)
                    .unwrap_or_default()
            ))),
            (Some((band, record)), None) => Ok(ResolvedBand {
                band,
                record,
                warning: None,
            }),
            (None, None) => {
                let (band, record) = BandArg::default().load_recorded()?;
                Ok(ResolvedBand {
                    warning: Some(format!(
                        "`{image}` records no band (not written by irsig-trace, or by an \
                         older one): its radiances are taken as {record}; give --band to say \
                         which band they are in"
                    )),
                    band,
                    record,
                })
            }
        }
    }
}

impl BandArg {
    /// A flat band's limits `[min, max]`, µm, for settings that cannot take a response
    /// file (the band a DIRTRAN table was integrated over).
    ///
    /// # Errors
    /// A response file or `total` (bad usage), or limits that are not `0 < MIN < MAX`.
    pub fn flat_limits_um(&self) -> miette::Result<[f64; 2]> {
        match *self {
            Self::Flat { min_um, max_um } if min_um > 0.0 && max_um > min_um => {
                Ok([min_um, max_um])
            }
            Self::Flat { min_um, max_um } => Err(crate::usage_error(format!(
                "--band {self}: expected 0 < MIN < MAX in micrometres, found {min_um}-{max_um}"
            ))),
            Self::Response(_) | Self::Total => Err(crate::usage_error(format!(
                "--band {self}: expected MIN-MAX in micrometres, such as 8-14 (these tables \
                 were integrated over a flat band)"
            ))),
        }
    }
}

/// `--view-unit` and `--unit`: a length unit by name (m, km, cm, mm, ft, in), as a clap value
/// parser.
///
/// # Errors
/// Any other word, naming the units.
pub fn length_unit(s: &str) -> Result<LengthUnit, String> {
    s.parse()
}

/// The unit of a 1990 viewing file's position when `--view-unit` is not given, in every
/// tool that reads one: km, the unit of the thesis's files.
pub const VIEW_UNIT_DEFAULT: &str = "km";

/// How a tool turns radiance into digital counts: one set of flags for every tool that
/// writes a DC image and its LUT.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct DcArgs {
    /// Gain in digital counts per kelvin. Alone: the thesis's auto-bias (Figure 14), the
    /// scene's mid radiance at mid-scale, so counts differ from scene to scene; with
    /// --reference-k: a fixed calibration, the same counts in every scene.
    #[arg(long, value_name = "DC_PER_K")]
    pub dc_per_kelvin: Option<f64>,
    /// Fixed calibration: the temperature (K) at which the gain is --dc-per-kelvin and
    /// whose blackbody radiance maps to --dc-at-reference.
    #[arg(long, value_name = "K", conflicts_with = "gain_dc_per_radiance")]
    pub reference_k: Option<f64>,
    /// Fixed calibration: the count of a blackbody at --reference-k (default mid-scale).
    #[arg(long, value_name = "DC", requires = "reference_k")]
    pub dc_at_reference: Option<f64>,
    /// A straight line instead: counts per W m^-2 sr^-1 (with --offset-dc).
    #[arg(long, value_name = "DC_PER_W_M2_SR", conflicts_with = "dc_per_kelvin")]
    pub gain_dc_per_radiance: Option<f64>,
    /// The count of zero radiance, with --gain-dc-per-radiance (default 0).
    #[arg(long, value_name = "DC", requires = "gain_dc_per_radiance")]
    pub offset_dc: Option<f64>,
    /// Bits per digital count (1-16): an 8-bit PNG up to 8, else a 16-bit one.
    #[arg(long, default_value_t = 8, value_name = "BITS",
          value_parser = clap::value_parser!(u8).range(1..=16))]
    pub dc_bits: u8,
}

impl DcArgs {
    /// The calibration the flags ask for, before a missing gain is filled in.
    #[must_use]
    pub fn request(&self) -> CountRequest {
        CountRequest {
            dc_per_kelvin: self.dc_per_kelvin,
            reference_k: self.reference_k,
            dc_at_reference: self.dc_at_reference,
            gain_dc_per_w_m2_sr: self.gain_dc_per_radiance,
            offset_dc: self.offset_dc,
            bits: self.dc_bits,
        }
    }

    /// The calibration the flags ask for; `default_dc_per_kelvin` stands in for a missing
    /// --dc-per-kelvin. `None` when no gain is known.
    #[must_use]
    pub fn calibration(&self, default_dc_per_kelvin: Option<f64>) -> Option<Calibration> {
        self.request().calibration(default_dc_per_kelvin)
    }
}

/// Where a frame's files go (`irsig-trace`, `irsig-merge`): one prefix for all of them, or a
/// flag per file, so that `irsig-run` and Makefiles see every file a stage writes.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct FrameOutputArgs {
    /// Output path prefix; files are PREFIX.radiance.exr, PREFIX.truth.exr, PREFIX.map.png,
    /// PREFIX.dc.png and PREFIX.lut.txt (PREFIX.NNNN.* for several views).
    #[arg(short = 'o', long, value_name = "PREFIX")]
    pub output: Option<PathBuf>,
    /// Write the radiance image (f32 EXR, W m^-2 sr^-1) to FILE. The per-output flags write
    /// only the files named, for one frame; any one of them may be `-`, standard output
    /// (e.g. piped into `irsig-sensor -`).
    #[arg(long, value_name = "FILE", conflicts_with = "output")]
    pub radiance_exr: Option<PathBuf>,
    /// Write the truth layers (multi-layer f32 EXR) to FILE.
    #[arg(long, value_name = "FILE", conflicts_with = "output")]
    pub truth_exr: Option<PathBuf>,
    /// Write the legacy interaction map (8-bit nibble PNG) to FILE; an error when a
    /// material id does not fit in four bits.
    #[arg(long, value_name = "FILE", conflicts_with = "output")]
    pub map_png: Option<PathBuf>,
    /// Write the digital-count image (PNG, --dc-bits deep) to FILE.
    #[arg(long, value_name = "FILE", conflicts_with_all = ["output", "no_dc"])]
    pub dc_png: Option<PathBuf>,
    /// Write the digital-count LUT (text: DC, radiance, K, degC) to FILE.
    #[arg(long, value_name = "FILE", conflicts_with_all = ["output", "no_dc"])]
    pub lut: Option<PathBuf>,
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
            dc_png: self.dc_png.clone(),
            lut: self.lut.clone(),
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
        let prefix = self.output.as_ref()?;
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
        self.output.as_ref()?;
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
        if self.output.is_none() && frames > 1 {
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

/// `--probe COLUMN,ROW`: a pixel, as a clap value parser.
///
/// # Errors
/// Anything but two whole numbers of 0 or more split by a comma.
pub fn pixel(s: &str) -> Result<(u32, u32), String> {
    let (a, b) = s
        .split_once(',')
        .ok_or_else(|| format!("expected COLUMN,ROW such as 128,64, found `{s}`"))?;
    let p = |t: &str| {
        t.trim()
            .parse::<u32>()
            .map_err(|_| format!("expected a pixel index (0 or more), found `{t}`"))
    };
    Ok((p(a)?, p(b)?))
}

/// A clap value parser for a library enum known by name: the names are listed in `--help`
/// and in the error for any other word, and the value is the enum's own `FromStr`. Only
/// `tools/*` use clap, so the libraries' enums carry names, not clap derives.
#[must_use]
pub fn named<T>(names: &'static [&'static str]) -> impl TypedValueParser<Value = T>
where
    T: FromStr + Clone + Send + Sync + 'static,
    T::Err: std::error::Error + Send + Sync + 'static,
{
    PossibleValuesParser::new(names).try_map(|s: String| s.parse::<T>())
}

/// The form in which a tool prints a table (`--format`): the atmosphere calculators' and
/// the region statistics' one spelling.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum TableFormat {
    /// Aligned columns for reading.
    #[default]
    Table,
    /// Comma-separated values with a header row, full precision.
    Csv,
    /// RON, full precision.
    Ron,
}

/// The numbers of an option such as `--angles`: a single value `a`, a list `a,b,c` or an
/// inclusive range `from:to:step` (at most a million values). `option` names the flag in
/// messages.
///
/// # Errors
/// A value that is not a finite number, a step that is not above 0, a range that ends
/// before it starts or holds more than a million values.
pub fn values(option: &str, text: &str) -> miette::Result<Vec<f64>> {
    let number = |s: &str| -> miette::Result<f64> {
        match s.trim().parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            _ => Err(miette!(
                "{option}: expected a finite number, found `{s}` in `{text}`"
            )),
        }
    };
    let parts: Vec<&str> = text.split(':').collect();
    match parts[..] {
        [single] => single.split(',').map(number).collect(),
        [from, to, step] => {
            let (from, to, step) = (number(from)?, number(to)?, number(step)?);
            if step <= 0.0 {
                return Err(miette!("{option}: range `{text}` needs a step > 0"));
            }
            if to < from {
                return Err(miette!("{option}: range `{text}` ends before it starts"));
            }
            let count = ((to - from) / step + 1e-9).floor() + 1.0;
            if count > 1e6 {
                return Err(miette!("{option}: range `{text}` has more than 1e6 values"));
            }
            Ok((0..count as usize)
                .map(|i| from + step * i as f64)
                .collect())
        }
        _ => Err(miette!(
            "{option}: expected a value, a list `a,b,c` or a range `from:to:step`, found `{text}`"
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_band_is_min_max_or_a_file() {
        assert_eq!(
            "8-14".parse::<BandArg>(),
            Ok(BandArg::Flat {
                min_um: 8.0,
                max_um: 14.0
            })
        );
        assert_eq!(
            "7.5e0-1.2e1".parse::<BandArg>(),
            Ok(BandArg::Flat {
                min_um: 7.5,
                max_um: 12.0
            })
        );
        assert_eq!(
            "cam-lwir.srf".parse::<BandArg>(),
            Ok(BandArg::Response("cam-lwir.srf".into()))
        );
        let e = "8:14".parse::<BandArg>().unwrap_err();
        assert!(e.contains("such as 8-14"), "{e}");
        assert!("".parse::<BandArg>().is_err());
        assert_eq!(BandArg::default().to_string(), "8-14");
    }

    #[test]
    fn a_flat_band_is_two_increasing_positive_numbers() {
        let limits = |s: &str| s.parse::<BandArg>().map(|b| b.flat_limits_um().ok());
        assert_eq!(limits("8-14"), Ok(Some([8.0, 14.0])));
        for bad in ["14-8", "0-14", "cam.srf", "total"] {
            assert_eq!(limits(bad), Ok(None), "{bad}");
        }
        assert!("8:14".parse::<BandArg>().is_err());
    }

    #[test]
    fn total_is_a_band_without_wavelengths() {
        assert_eq!("total".parse::<BandArg>(), Ok(BandArg::Total));
        assert_eq!(BandArg::Total.to_string(), "total");
        assert!(BandArg::Total.load().is_err());
        assert_eq!(BandArg::or_default(None), BandArg::default());
    }

    #[test]
    fn frame_outputs_are_a_prefix_or_one_flag_per_file() {
        let args = FrameOutputArgs {
            output: Some(PathBuf::from("out/f")),
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
            lut: Some(PathBuf::from("-")),
            ..FrameOutputArgs::default()
        };
        assert!(flags.has_files() && flags.prefixed(0, 1, &FrameFile::ALL).is_none());
        assert!(flags.check_stdout().is_err());
    }

    #[test]
    fn a_pixel_is_column_comma_row() {
        assert_eq!(pixel("128,64"), Ok((128, 64)));
        assert!(pixel("128").is_err());
        assert!(pixel("-1,3").is_err());
    }

    #[test]
    fn band_limits_are_checked_when_loaded() {
        for bad in ["14-8", "0-14"] {
            let b: BandArg = bad.parse().unwrap();
            assert!(b.load().is_err(), "{bad}");
        }
        let band = BandArg::default().load().unwrap();
        assert!((band.lambda_min_um() - 8.0).abs() < f64::EPSILON);
    }

    #[test]
    fn a_response_file_bounds_and_weights_the_band() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("cam.srf");
        std::fs::write(&path, "8.0 0.0\n10.0 1.0\n12.0 0.0\n").unwrap();
        let band = BandArg::Response(path.to_string_lossy().into_owned())
            .load()
            .unwrap();
        assert!((band.lambda_min_um() - 8.0).abs() < 1e-12);
        assert!((band.lambda_max_um() - 12.0).abs() < 1e-12);
        assert!(band.has_response());
        // A triangle response: less radiance than the flat 8-12 band.
        let flat = Band::new(8.0, 12.0).unwrap();
        assert!(band.radiance(300.0) < 0.6 * flat.radiance(300.0));
        let missing = BandArg::Response("no-such.srf".into()).load().unwrap_err();
        assert!(missing.to_string().contains("no-such.srf"), "{missing}");
    }

    #[test]
    fn dc_flags_give_one_calibration() {
        let fixed = DcArgs {
            dc_per_kelvin: Some(4.0),
            reference_k: Some(300.0),
            ..DcArgs::default()
        };
        assert_eq!(
            fixed.calibration(None),
            Some(Calibration::Fixed {
                dc_per_kelvin: 4.0,
                reference_k: 300.0,
                dc_at_reference: None
            })
        );
        let view_gain = DcArgs::default();
        assert_eq!(
            view_gain.calibration(Some(2.0)),
            Some(Calibration::AutoBias { dc_per_kelvin: 2.0 })
        );
        assert_eq!(DcArgs::default().calibration(None), None);
        let line = DcArgs {
            gain_dc_per_radiance: Some(3.0),
            ..DcArgs::default()
        };
        assert_eq!(
            line.calibration(Some(2.0)),
            Some(Calibration::GainOffset {
                gain_dc_per_w_m2_sr: 3.0,
                offset_dc: 0.0
            })
        );
    }

    #[test]
    fn table_formats_are_spelt_table_csv_ron() {
        use clap::ValueEnum;
        let names: Vec<String> = TableFormat::value_variants()
            .iter()
            .filter_map(|f| f.to_possible_value().map(|v| v.get_name().to_owned()))
            .collect();
        assert_eq!(names, ["table", "csv", "ron"]);
        assert_eq!(TableFormat::default(), TableFormat::Table);
    }

    #[test]
    fn values_are_one_a_list_or_a_range() {
        assert_eq!(values("--t", "300").unwrap(), [300.0]);
        assert_eq!(values("--t", "1, 2.5,-3").unwrap(), [1.0, 2.5, -3.0]);
        // 0 to 90 in steps of 30 includes both ends; a step that overshoots stops short.
        assert_eq!(values("--a", "0:90:30").unwrap(), [0.0, 30.0, 60.0, 90.0]);
        assert_eq!(values("--a", "0:1:0.4").unwrap(), [0.0, 0.4, 0.8]);
        for (bad, says) in [
            ("x", "expected a finite number, found `x`"),
            ("1,inf", "expected a finite number"),
            ("0:90:0", "needs a step > 0"),
            ("90:0:5", "ends before it starts"),
            ("0:1e7:1", "more than 1e6 values"),
            ("1:2", "a range `from:to:step`"),
        ] {
            let e = values("--a", bad).unwrap_err().to_string();
            assert!(e.starts_with("--a: ") && e.contains(says), "{bad}: {e}");
        }
    }
}
