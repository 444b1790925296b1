//! `--band`: a spectral band as a command line gives it ([`BandArg`]), and what each kind of
//! command takes of it ([`BandArgs`] over a [`BandForms`]): every form ([`Traced`]), every
//! form with the image's own band by default ([`Recorded`], [`ImageBandArgs`]), a band with
//! wavelengths ([`Wavelengths`]: a flat band or a response file) or a flat band alone
//! ([`Flat`]). A command refuses at parse time what it cannot take, and its help names only
//! what it takes; the flag, its value name and its type are the same everywhere.

use std::marker::PhantomData;
use std::str::FromStr;

use irsig_model::provenance::BandRecord;
use irsig_radiometry::{AnyBand, Band, SensorResponse, TotalRadiance};
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

/// What a command takes for `--band`: which forms of [`BandArg`] it accepts, refused at
/// parse time, and how its help says so.
pub trait BandForms: std::fmt::Debug + Clone + Default + Send + Sync + 'static {
    /// `--band`'s help: the forms taken and the default.
    const HELP: &'static str;

    /// Whether the command can take `band`.
    ///
    /// # Errors
    /// A form the command does not take, in words (clap names the flag and the value).
    fn accepts(band: &BandArg) -> Result<(), String>;
}

/// Every form: a flat band, a response file or `total` (the tracer).
#[derive(Debug, Clone, Copy, Default)]
pub struct Traced;

/// Every form, the image's own band by default: a tool that reads a traced image
/// ([`ImageBandArgs`]).
#[derive(Debug, Clone, Copy, Default)]
pub struct Recorded;

/// A band with wavelengths: a flat band or a response file, not `total` (calculators that
/// integrate over wavelength, a band-averaged emissivity).
#[derive(Debug, Clone, Copy, Default)]
pub struct Wavelengths;

/// A flat band alone, `MIN-MAX` (what a legacy table was integrated over, which names no
/// response).
#[derive(Debug, Clone, Copy, Default)]
pub struct Flat;

/// A flat band's limits as the band's own rule takes them (`0 < MIN < MAX`).
fn flat_limits(band: &BandArg) -> Result<(), String> {
    match *band {
        BandArg::Flat { min_um, max_um } => Band::new(min_um, max_um)
            .map(|_| ())
            .map_err(|_| format!("expected 0 < MIN < MAX in micrometres, found {min_um}-{max_um}")),
        BandArg::Response(_) | BandArg::Total => Ok(()),
    }
}

impl BandForms for Traced {
    const HELP: &'static str = "The band: MIN-MAX in micrometres (a flat response), a sensor \
        response file (formats/srf.md), or `total`, the whole spectrum (σT⁴/π), exact and for \
        checking by hand [default: 8-14]";

    fn accepts(band: &BandArg) -> Result<(), String> {
        flat_limits(band)
    }
}

impl BandForms for Recorded {
    const HELP: &'static str = "The band of the image's radiances: MIN-MAX in micrometres, a \
        sensor response file (formats/srf.md) or `total`. By default the band the image \
        records (irsig-trace writes it into its EXRs); given, it must be that band";

    fn accepts(band: &BandArg) -> Result<(), String> {
        flat_limits(band)
    }
}

impl BandForms for Wavelengths {
    const HELP: &'static str = "The band: MIN-MAX in micrometres (a flat response) or a sensor \
        response file (formats/srf.md), whose first and last wavelengths bound it \
        [default: 8-14]";

    fn accepts(band: &BandArg) -> Result<(), String> {
        match band {
            BandArg::Total => Err("`total` (the whole spectrum, σT⁴/π) has no wavelengths: \
                 expected MIN-MAX in micrometres or a sensor response file"
                .to_owned()),
            _ => flat_limits(band),
        }
    }
}

impl BandForms for Flat {
    const HELP: &'static str = "The band: MIN-MAX in micrometres, a flat response \
        [default: 8-14]";

    fn accepts(band: &BandArg) -> Result<(), String> {
        match band {
            BandArg::Flat { .. } => flat_limits(band),
            BandArg::Response(_) | BandArg::Total => Err(format!(
                "expected MIN-MAX in micrometres, such as 8-14: a flat band over a range of \
                 wavelengths, found `{band}`"
            )),
        }
    }
}

/// `--band` as [`BandForms`] `K` takes it: one definition of the flag for every command,
/// its value refused at parse time when `K` cannot take it.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct BandArgs<K: BandForms> {
    #[arg(long, value_name = "BAND", help = K::HELP, value_parser = parse::<K>)]
    band: Option<BandArg>,
    #[arg(skip)]
    forms: PhantomData<K>,
}

/// `--band`'s value parser for a command that takes `K`.
fn parse<K: BandForms>(s: &str) -> Result<BandArg, String> {
    let band: BandArg = s.parse()?;
    K::accepts(&band)?;
    Ok(band)
}

impl<K: BandForms> BandArgs<K> {
    /// `--band` as given, if it was.
    #[must_use]
    pub fn given(&self) -> Option<&BandArg> {
        self.band.as_ref()
    }

    /// `--band`'s value, or the default band (8–14 µm, flat) when it was not given.
    #[must_use]
    pub fn or_default(&self) -> BandArg {
        BandArg::or_default(self.band.as_ref())
    }

    /// The response file `--band` names, which the tool reads (`None` for a flat band or
    /// `total`).
    #[must_use]
    pub fn response_file(&self) -> Option<&str> {
        BandArg::response_file(self.band.as_ref())
    }

    /// `--band` as if given as `text`, for tests and for tools that build a command line
    /// themselves.
    ///
    /// # Errors
    /// A value `K` does not take.
    pub fn from_text(text: &str) -> Result<Self, String> {
        Ok(Self {
            band: Some(parse::<K>(text)?),
            forms: PhantomData,
        })
    }
}

impl BandArgs<Traced> {
    /// The band (the default when not given), and its record as an image traced in it
    /// keeps it.
    ///
    /// # Errors
    /// As [`BandArg::load_recorded`].
    pub fn load_recorded(&self) -> miette::Result<(AnyBand, BandRecord)> {
        self.or_default().load_recorded()
    }
}

impl BandArgs<Wavelengths> {
    /// The band (the default when not given): flat, or weighted by the response file read
    /// from disk.
    ///
    /// # Errors
    /// As [`BandArg::load`]: a response file that cannot be read or parsed.
    pub fn load(&self) -> miette::Result<Band> {
        self.or_default().load()
    }
}

impl BandArgs<Flat> {
    /// The flat band's limits `[min, max]`, µm (the default's when not given).
    ///
    /// # Errors
    /// None for a value parsed from a command line, which was checked there; as
    /// [`BandArg::flat_limits_um`] otherwise.
    pub fn limits_um(&self) -> miette::Result<[f64; 2]> {
        self.or_default().flat_limits_um()
    }
}

/// `--band` of a tool that reads a traced image (sensor, stats, report, merge): the band the
/// image records by default, since irsig-trace records it; a `--band` that is another band
/// is refused, naming both, unless `--override-band`, which warns.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct ImageBandArgs {
    /// The band the image's radiances are in.
    #[command(flatten)]
    pub band: BandArgs<Recorded>,
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
    /// [`resolve`](Self::resolve), its warning said on stderr as `tool`'s
    /// (`irsig-stats: warning: …`).
    ///
    /// # Errors
    /// As [`resolve`](Self::resolve).
    pub fn resolve_saying(
        &self,
        tool: &str,
        image: &str,
        recorded: Option<&BandRecord>,
    ) -> miette::Result<ResolvedBand> {
        let band = self.resolve(image, recorded)?;
        if let Some(w) = &band.warning {
            crate::note!("{tool}: warning: {w}");
        }
        Ok(band)
    }

    /// A truth EXR read with no radiance image beside it: its apparent temperatures are
    /// in the band it records, so a --band, when given, must be that band.
    ///
    /// # Errors
    /// As [`resolve`](Self::resolve), when --band is given.
    pub fn check_truth(
        &self,
        tool: &str,
        image: &str,
        recorded: Option<&BandRecord>,
    ) -> miette::Result<()> {
        if self.band.given().is_some() {
            self.resolve_saying(tool, image, recorded)?;
        }
        Ok(())
    }

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
        let given = self.band.given().map(BandArg::load_recorded).transpose()?;
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
                        .given()
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
                    .given()
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
    fn each_kind_of_command_refuses_at_parse_time_what_it_cannot_take() {
        let flat = |s| BandArgs::<Flat>::from_text(s).map(|b| b.limits_um().unwrap());
        let [lo, hi] = flat("3-5").unwrap();
        assert!((lo - 3.0).abs() < 1e-12 && (hi - 5.0).abs() < 1e-12);
        for bad in ["cam.srf", "total", "14-8", "0-14"] {
            assert!(flat(bad).is_err(), "{bad}");
        }
        let with_wavelengths = |s| BandArgs::<Wavelengths>::from_text(s).map(|_| ());
        assert!(with_wavelengths("cam.srf").is_ok() && with_wavelengths("8-14").is_ok());
        let e = with_wavelengths("total").unwrap_err();
        assert!(e.contains("no wavelengths"), "{e}");
        for s in ["total", "cam.srf", "3-5"] {
            assert!(BandArgs::<Traced>::from_text(s).is_ok(), "{s}");
            assert!(BandArgs::<Recorded>::from_text(s).is_ok(), "{s}");
        }
        assert!(BandArgs::<Traced>::from_text("5-3").is_err());
        // Not given: the thesis's band, 8-14 um, flat.
        let [lo, hi] = BandArgs::<Flat>::default().limits_um().unwrap();
        assert!((lo - 8.0).abs() < 1e-12 && (hi - 14.0).abs() < 1e-12);
        assert_eq!(
            BandArgs::<Traced>::default().or_default(),
            BandArg::default()
        );
    }

    #[test]
    fn each_kinds_help_names_only_what_it_takes() {
        assert!(Flat::HELP.contains("MIN-MAX") && !Flat::HELP.contains("file"));
        assert!(!Wavelengths::HELP.contains("total") && Wavelengths::HELP.contains("file"));
        assert!(Traced::HELP.contains("`total`") && Recorded::HELP.contains("`total`"));
    }
}
